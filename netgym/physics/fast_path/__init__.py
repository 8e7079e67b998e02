"""The fast path's numba kernels: what a throw watches while its scene is integrated
(:mod:`~netgym.physics.fast_path.watch`), the energy bound on reaching the opening
(:mod:`~netgym.physics.fast_path.reach`), and a lone ball's flight in closed form
(:mod:`~netgym.physics.fast_path.flight`) and towards the sleeping scene
(:mod:`~netgym.physics.fast_path.approach`). The plan that runs them is :mod:`netgym.physics.throw`."""
