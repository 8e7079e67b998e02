"""netgym's asv suite: the speed guard every change to the hot path is timed with.

Run ``asv continuous -f 1.05 main HEAD`` (see docs/CONTRIBUTING.md). The benchmarks use the
public API that trees back to 1858e2a share (:mod:`benchmarks.compat` bridges the few names that
moved), so that a change can be timed against the tree before it; a benchmark whose subject a
tree lacks is skipped there (NotImplementedError in its setup, asv's convention).
"""
