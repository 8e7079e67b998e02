"""The benchmark report's figures (matplotlib, imported on call)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from netgym.bench.settings import DEFAULT, REFERENCE, SWEEPS

OUTCOME_TARGET = 0.995   # outcome agreement a setting must reach to be drawn green


def plot_work_precision(rows: list[dict], path: Path) -> None:
    """Log-log error against wall time per simulated second, one line per integrator."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.6))
    for integrator in SWEEPS:
        runs = [r for r in rows if r["integrator"] == integrator and not r["diverged"]]
        for ax, key in zip(axes, ("ball_error", "net_error")):
            line, = ax.loglog([r["wall_per_sim_s"] for r in runs], [r[key] for r in runs], marker="o", label=integrator)
            for k, r in enumerate(runs):  # labels alternate above and below the line, in its colour
                ax.annotate(f"{r['dt'] * 1e3:g}", (r["wall_per_sim_s"], r[key]), fontsize=7, color=line.get_color(),
                            textcoords="offset points", xytext=(4, 4) if k % 2 == 0 else (4, -10))
            default = [r for r in runs if (r["integrator"], r["dt"]) == DEFAULT]
            ax.scatter([r["wall_per_sim_s"] for r in default], [r[key] for r in default], s=180, facecolors="none",
                       edgecolors="red", linewidths=1.5, label="default" if default else None, zorder=3)
    for ax, title in zip(axes, ("RMS ball position error over the strike", "RMS net position error at the end")):
        ax.set_xlabel("wall seconds per simulated second (one core); labels: dt in ms")
        ax.set_ylabel("error (m)")
        ax.set_title(title, fontsize=10)
        ax.grid(alpha=0.3, which="both")
    axes[0].legend(fontsize=8)
    fig.suptitle(f"Work-precision, basket scene, ball striking the net; reference {REFERENCE[0]} at dt = {REFERENCE[1]:g} s",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


LABEL_OFFSETS = (7, -15, 17, -25)
"""Vertical offsets (points) of the label levels of :func:`plot_outcomes`: above, below, further
above, further below."""
LABEL_HALF_WIDTH = 0.15
"""Half the width of a point's label in decades of throws per second (a label spans about a quarter decade)."""


def _label_levels(speeds: list[float]) -> list[int]:
    """A level (index into :data:`LABEL_OFFSETS`) for each point's label, so that no two labels on
    one level overlap: each point, slowest first, takes the first level whose last label ends
    before its own begins."""
    ends = [-math.inf] * len(LABEL_OFFSETS)
    levels = [0] * len(speeds)
    for k in sorted(range(len(speeds)), key=lambda k: speeds[k]):
        x = math.log10(speeds[k])
        level = next((n for n, end in enumerate(ends) if end <= x - LABEL_HALF_WIDTH), int(np.argmin(ends)))
        ends[level] = x + LABEL_HALF_WIDTH
        levels[k] = level
    return levels


def plot_outcomes(rows: list[dict], path: Path) -> None:
    """Outcome agreement and throws per second: one row per integrator (so that settings of equal
    speed do not overprint), each point labelled with its dt and agreement, default ringed."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(len(SWEEPS), 1, figsize=(7.5, 1.0 + 1.3 * len(SWEEPS)), sharex=True)
    for ax, integrator in zip(axes, SWEEPS):
        runs = [r for r in rows if r["integrator"] == integrator]
        speeds = [r["throws_per_s"] for r in runs]
        colours = ["tab:green" if r["agreement"] >= OUTCOME_TARGET else "tab:red" for r in runs]
        ax.scatter(speeds, [0.0] * len(runs), c=colours, s=36, zorder=3)
        ax.plot(speeds, [0.0] * len(runs), color="gray", linewidth=0.8)
        for r, level in zip(runs, _label_levels(speeds)):
            ax.annotate(f"{r['dt'] * 1e3:g} ms: {100 * r['agreement']:.1f}%", (r["throws_per_s"], 0.0), fontsize=7,
                        ha="center", textcoords="offset points", xytext=(0, LABEL_OFFSETS[level]))
            if (r["integrator"], r["dt"]) == DEFAULT:
                ax.scatter([r["throws_per_s"]], [0.0], s=200, facecolors="none", edgecolors="red", linewidths=1.5,
                           zorder=4)
        ax.set_xscale("log")
        ax.set_ylim(-1.0, 1.0)
        ax.set_yticks([])
        ax.set_ylabel(integrator, rotation=0, ha="right", va="center", fontsize=9)
        ax.grid(alpha=0.3, which="both", axis="x")
    speeds = [r["throws_per_s"] for r in rows]
    axes[-1].set_xlim(min(speeds) / 1.6, max(speeds) * 1.6)  # room for the end points' labels
    axes[-1].set_xlabel("throws per second (one core, fast path)")
    axes[0].set_title(f"Outcome agreement with the reference per setting (green: >= {100 * OUTCOME_TARGET:g}%, "
                      "red ring: the default)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_contact_convergence(many: dict, path: Path) -> None:
    """Log-log ensemble error against dt, one panel per phase after the first contact (median
    lines, 90th-percentile bands), one line per integrator, with the reference's median
    self-difference and a first-order slope to read the others against; ``many``: a
    :func:`~netgym.bench.accuracy.contact_convergence.summary`."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from netgym.bench.accuracy.contact_convergence import PHASES

    phases = PHASES[1:]  # before the contact every method is at round-off
    fig, axes = plt.subplots(1, len(phases), figsize=(11, 4.6), sharey=True)
    for ax, phase in zip(axes, phases):
        for integrator in dict.fromkeys(row["integrator"] for row in many["rows"]):
            rows = [r for r in many["rows"] if r["integrator"] == integrator and r[phase] is not None]
            dts = [1e3 * r["dt"] for r in rows]
            line, = ax.loglog(dts, [r[phase]["median"] for r in rows], marker="o", label=integrator)
            ax.fill_between(dts, [r[phase]["median"] for r in rows], [r[phase]["p90"] for r in rows],
                            color=line.get_color(), alpha=0.12)
        floor = many["self_difference"][phase]["median"]
        ax.axhline(10 * floor, color="grey", linestyle=":", label="10x the reference's self-difference")
        dts = np.array([0.0156, 2.0])
        ax.loglog(dts, 2e-3 * dts, color="black", linestyle="--", linewidth=1, label="first order")
        ax.set_title(f"{phase}: median, band to p90", fontsize=10)
        ax.set_xlabel("dt (ms)")
        ax.grid(alpha=0.3, which="both")
    axes[0].set_ylabel("largest ball error in the phase (m)")
    axes[0].legend(fontsize=8)
    fig.suptitle(f"Convergence through contact: {many['strikes']} strikes into the basket, every integrator", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
