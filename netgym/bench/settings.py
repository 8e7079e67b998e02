"""The integrator settings the benchmark report compares: the fine reference, the dt sweep of
each integrator, the scenes' default setting and the setting the peers run."""

from __future__ import annotations

REFERENCE = ("rk4", 1e-5)
QUICK_REFERENCE = ("rk4", 1e-4)  # --quick: settling the net at 0.01 ms alone takes a minute
SWEEPS = {
    "explicit_euler": [1e-4, 2e-4, 2.5e-4, 5e-4],
    "symplectic_euler": [1e-4, 2e-4, 2.5e-4, 5e-4],
    "rk4": [1e-4, 2e-4, 5e-4, 1e-3],
    "implicit_euler": [5e-4, 1e-3, 2e-3, 5e-3, 1e-2],
    "imex_euler": [5e-4, 1e-3, 2e-3, 2.5e-3, 5e-3],
}
DEFAULT = ("imex_euler", 2e-3)
PEER_SETTING = ("symplectic_euler", 5e-4)  # the peers run the same explicit method at the same dt


def outcome_sweeps(quick: bool) -> dict[str, list[float]]:
    """The dt of each integrator the outcome-accuracy section runs: :data:`SWEEPS`, or with
    ``quick`` one each, :data:`DEFAULT`'s or :data:`PEER_SETTING`'s where it is its integrator's,
    else its largest."""
    if not quick:
        return SWEEPS
    chosen = dict([PEER_SETTING, DEFAULT])
    return {integrator: [chosen.get(integrator, dts[-1])] for integrator, dts in SWEEPS.items()}
