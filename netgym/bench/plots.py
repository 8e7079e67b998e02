"""The benchmark report's figures (matplotlib, imported on call)."""

from __future__ import annotations

from pathlib import Path

from netgym.bench.settings import DEFAULT, REFERENCE, SWEEPS


def plot_work_precision(rows: list[dict], path: Path) -> None:
    """Log-log error against wall time per simulated second, one line per integrator."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for integrator in SWEEPS:
        runs = [r for r in rows if r["integrator"] == integrator and not r["diverged"]]
        for ax, key in zip(axes, ("ball_error", "net_error")):
            ax.loglog([r["wall_per_sim_s"] for r in runs], [r[key] for r in runs], marker="o", label=integrator)
            for r in runs:
                ax.annotate(f"{r['dt'] * 1e3:g} ms", (r["wall_per_sim_s"], r[key]), fontsize=7,
                            textcoords="offset points", xytext=(3, 3))
    for ax, title in zip(axes, ("RMS ball position error over the strike", "RMS net position error at the end")):
        ax.set_xlabel("wall seconds per simulated second (one core)")
        ax.set_ylabel("error (m)")
        ax.set_title(title, fontsize=10)
        ax.grid(alpha=0.3, which="both")
    axes[0].legend(fontsize=8)
    fig.suptitle(f"Work-precision, basket scene, ball striking the net; reference {REFERENCE[0]} at dt = {REFERENCE[1]:g} s",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_outcomes(rows: list[dict], path: Path) -> None:
    """Outcome agreement against throws per second, default marked."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for integrator in SWEEPS:
        runs = [r for r in rows if r["integrator"] == integrator]
        ax.semilogx([r["throws_per_s"] for r in runs], [100 * r["agreement"] for r in runs], marker="o", label=integrator)
        for r in runs:
            ax.annotate(f"{r['dt'] * 1e3:g} ms", (r["throws_per_s"], 100 * r["agreement"]), fontsize=7,
                        textcoords="offset points", xytext=(3, -9))
    default = next(r for r in rows if (r["integrator"], r["dt"]) == DEFAULT)
    ax.scatter([default["throws_per_s"]], [100 * default["agreement"]], s=160, facecolors="none", edgecolors="red",
               label="default")
    ax.set_xlabel("throws per second (one core, fast path)")
    ax.set_ylabel("outcome agreement with the reference (%)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
