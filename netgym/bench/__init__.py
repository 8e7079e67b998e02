"""Benchmarks of the simulator alone: the library behind ``scripts/bench_sim.py``,
``scripts/roofline.py``, ``scripts/contact_convergence.py`` and the simulator sections of the
benchmark report (``agents.bench.report``, which also runs the benchmarks that need policies).

- :mod:`netgym.bench.speed`: substeps/s per integrator and scene, the force pass's roofline, the
  same net in NumPy and MuJoCo, the speed table;
- :mod:`netgym.bench.accuracy`: work-precision on a strike, convergence through contact, the pause
  against a fine relaxation, creep of balls at rest, stability limits, the fast path against the
  full simulation;
- :mod:`netgym.bench.throws`: seeded test throws, random and noisy aimed
  (:class:`~netgym.aim.BallisticAim`);
- :mod:`netgym.bench.settings`: the integrator settings the report compares;
- :mod:`netgym.bench.results`: the result files under ``docs/results``;
- :mod:`netgym.bench.plots`: the report's figures.

Nothing here imports ``agents``: benchmarks that throw with a policy live in :mod:`agents.bench`.
"""
