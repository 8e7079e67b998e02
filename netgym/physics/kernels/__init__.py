"""The numba kernels: forces, the spring law, integrators, contacts, stepping, the balls'
flight through air, and the checks a throw runs between chunks."""
