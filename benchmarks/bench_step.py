"""The simulator's step, every integrator: the settled basket net alone, and with a ball resting
in it (every contact live); the spring pass; the compliant contacts' step."""

from __future__ import annotations

from benchmarks.compat import INTEGRATOR_DT, STEPS


class NetStep:
    """``STEPS`` steps of the basket with each integrator at its benchmark dt."""

    params = (list(INTEGRATOR_DT), ["net alone", "ball resting"])
    param_names = ["integrator", "load"]

    def setup(self, integrator: str, load: str) -> None:
        from netgym.physics.simulator import Simulator

        self.sim = Simulator("basket", {"simulation.integrator": integrator,
                                        "simulation.dt": INTEGRATOR_DT[integrator]})
        if load == "ball resting":
            self.sim.launch_ball([0.0, 0.0, 1.5], [0.0, 0.0, 0.0])
            self.sim.relax()
        self.sim.step(2)  # compiled (or loaded from numba's cache) outside the timed calls

    def time_steps(self, integrator: str, load: str) -> None:
        self.sim.step(STEPS)


class CompliantStep:
    """``STEPS`` steps of the basket with a ball resting in it under compliant contacts."""

    params = ["imex_euler", "symplectic_euler", "rk4"]
    param_names = ["integrator"]

    def setup(self, integrator: str) -> None:
        from netgym.physics.simulator import Simulator

        try:
            self.sim = Simulator("basket", {"simulation.contact_model": "compliant", "simulation.integrator": integrator,
                                            "simulation.dt": min(INTEGRATOR_DT[integrator], 1e-3)})
        except Exception as error:  # trees before the compliant model reject the field
            raise NotImplementedError(f"no compliant contacts here: {error}")
        self.sim.launch_ball([0.0, 0.0, 1.5], [0.0, 0.0, 0.0])
        self.sim.step(200)  # into the net: the contacts are live from here
        self.sim.step(2)

    def time_steps(self, integrator: str) -> None:
        self.sim.step(STEPS)


class SpringPass:
    """One pass of every spring of the basket net (3250 springs), called from compiled code as
    the integrators call it: ns a spring, the best of 20 timings of 100 passes (the roofline's
    figure, docs/BENCHMARKS.md)."""

    unit = "ns"

    def setup(self) -> None:
        try:
            from netgym.bench.speed.roofline import spring_pass_arguments, spring_pass_seconds
        except ImportError as missing:
            raise NotImplementedError(f"this tree has no spring pass to time alone: {missing}")
        self.arguments, self.seconds = spring_pass_arguments("basket"), spring_pass_seconds
        self.seconds(self.arguments, repeats=1)

    def track_spring_pass_ns_per_spring(self) -> float:
        return 1e9 * self.seconds(self.arguments) / self.arguments[2].pairs.shape[0]
