"""The numba kernels beneath the rest of the physics: their decorators and row updates, the
spring law and the springs as the kernels take them, the smooth forces and their integrators,
impulse contacts (:mod:`~netgym.physics.kernels.impulse_contacts`), air on a ball, and the
distances around a ball (:mod:`~netgym.physics.kernels.surroundings`). Nothing here imports
the physics outside this folder."""
