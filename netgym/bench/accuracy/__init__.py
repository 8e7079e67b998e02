"""How accurate the simulator alone is: work-precision on a strike, convergence through
contact, the pause against a fine relaxation, creep of balls at rest, stability limits, and
the fast path against the full simulation."""
