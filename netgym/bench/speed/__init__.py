"""How fast the simulator alone runs: substeps/s per integrator, the roofline of the force
pass, the same net in NumPy and MuJoCo, and the speed table of the report."""
