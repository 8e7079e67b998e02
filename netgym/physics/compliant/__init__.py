"""The compliant contact model (``simulation.contact_model = "compliant"``): contacts as forces
inside the integrator, not impulses after it.

Every contact is a Hunt-Crossley spring-damper along its normal, ``k w delta max(0, 1 + d
delta')`` (:mod:`~netgym.physics.compliant.law`), with Coulomb friction regularised below a slip
speed, below which it grips an elastic tangential anchor (:mod:`~netgym.physics.compliant.grip`);
the balls meet the net's particles and, with a weight that vanishes at their ends, the
interiors of its structural segments (:mod:`~netgym.physics.compliant.contacts`,
:mod:`~netgym.physics.compliant.forces`). The forces are smooth between events (a contact's
onset, its separation, its damper's clamp, a pole contact's move between its caps and its
side, a grip or a break-away), which RK4 locates inside its steps, so that it converges at
its order through contact (:mod:`~netgym.physics.compliant.rk4`); IMEX Euler takes the
contacts' dampers and friction implicitly (:mod:`~netgym.physics.compliant.imex`); stiff
contacts split a substep into parts (:mod:`~netgym.physics.compliant.split`,
:mod:`~netgym.physics.compliant.step`).
"""
