"""Benchmarks of the simulator and the environment: the library behind ``scripts/bench_sim.py``,
``scripts/bench_env.py`` and ``scripts/report.py`` (which only parse options and print).

Modules, one job each:

- :mod:`netgym.bench.throws`: seeded test throws (random and noisy-oracle actions);
- :mod:`netgym.bench.fast_path`: every throw simulated with and without the fast path;
- :mod:`netgym.bench.env_throughput`: throws/s of a Gymnasium SyncVectorEnv and of the SB3 training env;
- :mod:`netgym.bench.sim_throughput`: substeps/s per integrator and scene;
- :mod:`netgym.bench.settings`: the integrator settings the report compares;
- :mod:`netgym.bench.work_precision`: error against wall time on a strike into the net;
- :mod:`netgym.bench.outcomes`: capture outcomes per setting against a fine reference;
- :mod:`netgym.bench.stability_limits`: largest stable dt, bisected and estimated;
- :mod:`netgym.bench.peers`: the same net in NumPy and MuJoCo;
- :mod:`netgym.bench.plots`: the report's figures;
- :mod:`netgym.bench.episodes`: whole episodes as a user trains on them, the pauses booked;
- :mod:`netgym.bench.episode_agreement`: seeded episodes against a fine reference pipeline;
- :mod:`netgym.bench.pause_accuracy`: the pause between throws against a fine relaxation;
- :mod:`netgym.bench.creep`: how far balls at rest in piles still move;
- :mod:`netgym.bench.report`: every section measured, and the report's markdown;
- :mod:`netgym.bench.report_text`: the report's fixed prose, its dated findings included.

The noisy-oracle throws use the ballistic oracle of the sibling package ``agents`` (same
distribution). It is imported inside the functions that need it
(:func:`netgym.bench.throws.ballistic_oracle`), so importing ``netgym`` or ``netgym.bench``
never imports ``agents``; the SB3 figure also needs the ``train`` extra.
"""
