"""The quoted figures of the README and the docs, generated from their result files.

Each quoted table sits between ``<!-- quote:NAME -->`` and ``<!-- /quote:NAME -->`` in a markdown
file; :data:`BLOCKS` says how NAME is made from the result files (``docs/results/*.json``, each
written by the script that measured it, and the files other scripts write: the training curve's
CSV, the report). ``python docs/_scripts/quotes.py`` rewrites every block; ``--check`` only says
which differ (the tests run it), so a quoted figure cannot drift from its source.

Usage::

    python docs/_scripts/quotes.py            # rewrite the quoted blocks
    python docs/_scripts/quotes.py --check    # exit 1 naming every block that is out of date
"""

from __future__ import annotations

import argparse
import csv
import re
import sys
from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

import netgym  # noqa: E402
from agents.baselines import tables as baselines  # noqa: E402
from agents.baselines.analysis import load_cells  # noqa: E402
from agents.bench.report import contact_convergence, model_agreement_quote  # noqa: E402
from agents.policies import SHIPPED_BASELINES  # noqa: E402
from netgym.bench.speed import roofline, speed_table  # noqa: E402
from netgym.bench.results import RESULTS, read_results  # noqa: E402

REPORT = "docs/BENCHMARKS.md"
TRAINING_CURVE = ROOT / "docs" / "figures" / "ppo_curve.csv"
SHIPPED_PPO = "PPO ppo_netcatch.zip"
BASELINES = RESULTS / "baselines"
"""The baselines' result files and the statistics stored beside them (``scripts/baselines.py --report --out
docs/results/baselines`` writes ``stats.json``; without it, or with records it was not computed from, the
baselines' blocks compute them anew: minutes)."""
BASELINES_LONG = RESULTS / "baselines_long"
"""Runs beyond the table's budget (``scripts/baselines.py --out docs/results/baselines_long --budget N``)."""


def _only_row(rows: list[dict], source: str, what: str, match: Callable[[dict], bool]) -> dict:
    """The one row of ``source``'s ``rows`` that ``match``es; a clear error naming ``what`` otherwise."""
    found = [row for row in rows if match(row)]
    if len(found) != 1:
        raise ValueError(f"docs/results/{source} has {len(found)} rows for {what}")
    return found[0]


def _rate(row: dict) -> str:
    return f"{100 * row['captured'] / row['throws']:.1f}%"


def _interval(row: dict) -> str:
    return f"{100 * row['low']:.1f}-{100 * row['high']:.1f}%"


def environments(cards: str = "docs/environments/") -> str:
    """One line per registered id, linked to its card in the folder ``cards``: what it tests, balls
    per episode, what the observation adds."""
    lines = ["| id | tests | balls | observation |", "|---|---|---:|---|"]
    lines += [f"| [`{env_id}`]({cards}{env_id}.md) | {entry.tests} | "
              f"{netgym.balls_per_episode(env_id)} | {entry.observation} |"
              for env_id, entry in netgym.ENVIRONMENTS.items()]
    return "\n".join(lines)


def capture_rates() -> str:
    """The capture rates of the shipped PPO model, the oracle and random actions on NetCatch-v0."""
    record = read_results(RESULTS / "agents.json")
    figures = record["figures"]
    lines = [f"| policy | capture rate | 95% CI | throws caught ({figures['episodes']} seeded episodes) |",
             "|---|---:|---:|---:|"]
    for label, row in figures["policies"].items():
        name = "shipped PPO model" if label == SHIPPED_PPO else label
        lines.append(f"| {name} | {_rate(row)} | {_interval(row)} | {row['captured']}/{row['throws']} |")
    lines.append(f"\nSource: `docs/results/agents.json`, written by `{record['command']}`.")
    return "\n".join(lines)


VARIANT_SOURCES = ("variants.json", "variants_randomized_v1.json")
"""The variants' result files, each written by ``scripts/variants_table.py`` (the second for the
variant added after the first was measured)."""


def variants() -> str:
    """The capture rates of the reference agents on the variants, with their intervals and speed."""
    records = [read_results(RESULTS / name) for name in VARIANT_SOURCES]
    episodes = {record["figures"]["episodes"] for record in records}
    if len(episodes) != 1:
        raise ValueError(f"docs/results/{VARIANT_SOURCES} count different episodes {sorted(episodes)}")
    lines = [f"| variant | agent | capture rate | 95% CI | throws caught ({episodes.pop()} episodes) | "
             "throws/s (one process) |", "|---|---|---:|---:|---:|---:|"]
    lines += [f"| {row['variant']} | {row['agent']} | {_rate(row)} | {_interval(row)} | "
              f"{row['captured']}/{row['throws']} | {row['throws_per_s']:.1f} |"
              for record in records for row in record["figures"]["rows"]]
    lines += [f"\nSource: `docs/results/{name}`, written by `{record['command']}` "
              f"({record['written']}, {record['machine']})." for name, record in zip(VARIANT_SOURCES, records)]
    return "\n".join(lines)


def learning_curve(name: str, checkpoints: tuple[int, ...] = (0, 4096, 8192, 12288, 16384, 24576)) -> str:
    """The evaluated capture rate of every seed of a training curve (``docs/figures/NAME.csv``, as
    ``scripts/train_ppo.py`` writes it) at ``checkpoints`` environment steps and at the end."""
    curves: dict[str, list[tuple[int, float, float]]] = {}
    with (ROOT / "docs" / "figures" / f"{name}.csv").open() as f:
        for row in csv.DictReader(f):
            curves.setdefault(row["seed"], []).append((int(row["env_steps"]), float(row["capture_rate"]),
                                                       float(row["wall_seconds"])))
    seeds = sorted(curves, key=int)
    lines = ["| environment steps | " + " | ".join(f"seed {seed}" for seed in seeds) + " | mean | minutes of training |",
             "|---:|" + "---:|" * (len(seeds) + 2)]

    def row(label: str, points: list[tuple[int, float, float]]) -> str:
        minutes = sorted(f"{p[2] / 60:.1f}" for p in points)
        span = minutes[0] if minutes[0] == minutes[-1] else f"{minutes[0]}-{minutes[-1]}"
        rates = " | ".join(f"{100 * p[1]:.1f}%" for p in points)
        return f"| {label} | {rates} | {100 * sum(p[1] for p in points) / len(points):.1f}% | {span} |"

    for step in checkpoints:
        points = [next((p for p in curves[seed] if p[0] == step), None) for seed in seeds]
        if all(points):
            lines.append(row(f"{step:,}", points))
    ends = [curves[seed][-1] for seed in seeds]
    low, high = min(p[0] for p in ends), max(p[0] for p in ends)
    lines.append(row(f"end ({low:,})" if low == high else f"end ({low:,}-{high:,})", ends))
    lines.append(f"\nSource: `docs/figures/{name}.csv`, written by `scripts/train_ppo.py`.")
    return "\n".join(lines)


def variants_summary() -> str:
    """What the variants' table says, in points of capture rate: the gap learning must close on the
    windy variant and how much of it each learner closes, and what the noise costs the oracle."""
    rows = [row for name in VARIANT_SOURCES for row in read_results(RESULTS / name)["figures"]["rows"]]

    def rate(variant: str, agent: str) -> float:
        row = _only_row(rows, "variants.json", f"{variant}, {agent}",
                        lambda r: r["variant"] == variant and r["agent"].startswith(agent))
        return 100 * row["captured"] / row["throws"]

    windy, noisy, randomized = "NetCatchWindy-v0", "NetCatchNoisy-v0", "NetCatchRandomized-v1"
    blind, informed = rate(windy, "ballistic oracle"), rate(windy, "informed oracle")
    adaptive, mlp, stacked = rate(windy, "adaptive oracle"), rate(windy, "PPO, MLP with"), rate(windy, "PPO, MLP on")
    oracle = read_results(RESULTS / "agents.json")["figures"]["policies"]["oracle"]
    clean = 100 * oracle["captured"] / oracle["throws"]
    return "\n".join([
        f"- The gap between the blind and the informed oracle on {windy}, {informed - blind:.1f} points, is what "
        f"learning must close. PPO closes {mlp - blind:+.1f} points of it with the feedback in the observation, "
        f"{stacked - blind:+.1f} on the last five observations stacked; the hand-written adaptive oracle "
        f"{adaptive - blind:+.1f}.",
        f"- {noisy}: the launch noise costs the ballistic oracle {clean - rate(noisy, 'ballistic oracle'):.1f} "
        "points against NetCatch-v0 without noise. No policy can undo noise drawn after its action; one "
        "can only aim where the noise costs least ([baselines](baselines.md): what learners reach).",
        f"- NetCatchRandomized-v0: the ballistic oracle catches {rate('NetCatchRandomized-v0', 'ballistic oracle'):.1f}%: "
        "ball mass, restitution, friction and the net's stiffness and damping change how the net answers, not the "
        "flight, so the variant tests robustness of what happens at the net (rim hits, loaded nets), not aim. "
        "Each reset settles a new net, hence its lower throughput.",
        f"- NetCatchRandomized-v1 draws the ball's drag coefficient and mass too, hidden: blind to the draws the "
        f"ballistic oracle catches {rate(randomized, 'ballistic oracle'):.1f}%, told them "
        f"{rate(randomized, 'informed oracle'):.1f}%; the adaptive oracle, whose correction of a steady drift fits "
        f"the wind, {rate(randomized, 'adaptive oracle'):.1f}%: a wrong drag misses by an amount that depends on "
        "the throw, so the feedback must be used to identify the ball, not to shift the aim."])


def rllib_throughput() -> str:
    """Training env steps/s on 2 cores: SB3 with ``SubprocVecEnv``, RLlib on one and on two Ray
    nodes of one machine."""
    record = read_results(RESULTS / "rllib.json")
    figures = record["figures"]
    labels = {"sb3_subproc_2_envs": "SB3 PPO, 2 `SubprocVecEnv` envs",
              "rllib_2_env_runners_1_node": "RLlib PPO, 2 env runners, one Ray node",
              "rllib_2_env_runners_2_nodes_one_machine": "RLlib PPO, 2 env runners, two Ray nodes on one machine"}
    lines = ["| training on 2 cores | env steps/s, each run | median |", "|---|---:|---:|"]
    for key, label in labels.items():
        runs = ", ".join(f"{run['env_steps_per_s']:.1f}" for run in figures["runs"][key])
        lines.append(f"| {label} | {runs} | {figures['median_env_steps_per_s'][key]:.1f} |")
    lines.append(f"\nSource: `docs/results/rllib.json`, written by `{record['command']}` ({record['written']}).")
    return "\n".join(lines)


def first_step() -> str:
    """How long a first run waits for the kernels to compile, and a later one for the cache."""
    from agents.bench import first_step_text

    return first_step_text.block(RESULTS / "first_step.json")


def _episode_row(rows: list[dict], scene: str, policy: str, balls: int) -> dict:
    return _only_row(rows, "episodes.json", f"{scene}, {policy}, {balls} balls",
                     lambda r: (r["scene"], r["policy"], r["balls"]) == (scene, policy, balls))


def _training_rate() -> tuple[float, float]:
    """The slowest and fastest seed's environment steps per second of training (evaluations
    excluded), from the learning curve's CSV that ``scripts/train_ppo.py`` writes."""
    last: dict[str, tuple[float, float]] = {}
    with TRAINING_CURVE.open() as f:
        for row in csv.DictReader(f):
            last[row["seed"]] = (float(row["env_steps"]), float(row["wall_seconds"]))
    rates = [steps / seconds for steps, seconds in last.values()]
    return min(rates), max(rates)


def _report_agreement(integrator: str, dt_ms: str) -> str:
    """The outcome agreement of one setting in the report's section 2 (written by scripts/report.py)."""
    text = (ROOT / REPORT).read_text()
    section = text[text.index("## 2. Outcome accuracy"):text.index("## 3.")]
    for line in section.splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if cells[0].split(" ")[0] == integrator and cells[1:2] == [dt_ms]:
            return cells[2]
    raise ValueError(f"{REPORT} section 2 has no row for {integrator} at {dt_ms} ms")


def at_a_glance() -> str:
    """The README's speed and accuracy table: whole episodes as users pay them, next to the best case."""
    record = read_results(RESULTS / "episodes.json")
    rows = record["figures"]["rows"]
    episodes = "docs/BENCHMARKS.md#7-episodes"
    table = [("basket, **shipped PPO**, 3-ball episodes (every ball caught; the loaded net settles between throws)",
              _episode_row(rows, "basket", "shipped PPO", 3), episodes),
             ("basket, ballistic oracle, 3-ball episodes", _episode_row(rows, "basket", "oracle", 3), episodes),
             ("basket, oracle, 10-ball episodes", _episode_row(rows, "basket", "oracle", 10), episodes),
             ("basket, random actions, 3-ball episodes", _episode_row(rows, "basket", "random", 3), episodes),
             ("goal (`line` rule), oracle, 3-ball episodes", _episode_row(rows, "goal", "oracle", 3), episodes),
             ("best case: single oracle throws into the empty basket", _episode_row(rows, "basket", "oracle", 1),
              "docs/BENCHMARKS.md#4-throughput")]
    lines = ["| workload | throws/s | step p50 / p99 / max (ms) |", "|---|---:|---|"]
    for label, row, link in table:
        p50, p99, peak = row["step_ms"]
        lines.append(f"| [{label}]({link}) | {row['throws_per_s']:.1f} | {p50:.1f} / {p99:.1f} / {peak:.1f} |")
    low, high = _training_rate()
    rllib = read_results(RESULTS / "rllib.json")["figures"]["median_env_steps_per_s"]["rllib_2_env_runners_1_node"]
    lines.append(f"| [PPO training on 2 cores: SB3, 8 envs in `SubprocVecEnv`](docs/AGENTS.md#learning-curve) / "
                 f"[RLlib, 2 env runners](docs/AGENTS.md#scaling-out-ray-rllib) | "
                 f"{low:.0f}-{high:.0f} / {rllib:.0f} env steps/s | |")
    lines.append(f"| [outcomes of the default (IMEX Euler, 2 ms) against RK4 at 0.1 ms, 1000 throws]"
                 f"(docs/BENCHMARKS.md#2-outcome-accuracy) | {_report_agreement('imex_euler', '2')} agree | |")
    lines.append(f"\nOne process, one numba thread. Sources: `docs/results/episodes.json` (`{record['command']}`), "
                 "`docs/figures/ppo_curve.csv` (`python scripts/train_ppo.py --minutes 6 --seeds 0 1 2`), "
                 "`docs/results/rllib.json` (`python scripts/bench_rllib.py`), "
                 "`docs/BENCHMARKS.md` (`python scripts/report.py`).")
    return "\n".join(lines)


def windy_per_throw() -> str:
    """The capture rates by throw index on NetCatchWindy-v0, and how the best fixed first throw was found."""
    from agents.windy_throws import search_summary, table

    record = read_results(RESULTS / "windy_per_throw.json")
    figures = record["figures"]
    return "\n".join([table(figures), f"\n{search_summary(figures)}",
                      f"\nSource: `docs/results/windy_per_throw.json`, written by `{record['command']}` "
                      f"({record['written']}, {record['machine']})."])


def windy_long_seeds() -> str:
    """Every long windy run's model by throw on the held-out episodes, beside the best fixed
    first throw on the same episodes (from ``windy_per_throw.json``)."""
    from agents.windy_throws import table

    seeds, bound = read_results(RESULTS / "windy_long_seeds.json"), read_results(RESULTS / "windy_per_throw.json")
    figures, fixed = seeds["figures"], bound["figures"]
    if (figures["episodes"], figures["seed"]) != (fixed["episodes"], fixed["seed"]):
        raise ValueError("windy_long_seeds.json and windy_per_throw.json evaluate different episodes")
    rows = [*figures["rows"], *(row for row in fixed["rows"] if row["policy"].startswith("best fixed first throw"))]
    return "\n".join([table({**figures, "rows": rows}),
                      f"\n{figures['episodes']} held-out episodes a row (seeds {figures['seed']}-"
                      f"{figures['seed'] + figures['episodes'] - 1}). Sources: `docs/results/windy_long_seeds.json`, "
                      f"written by `{seeds['command']}` ({seeds['written']}); the last row "
                      "`docs/results/windy_per_throw.json`."])


BLOCKS: dict[str, Callable[[], str]] = {
    "environments": environments,
    "environments-docs": lambda: environments(cards="environments/"),
    "capture-rates": capture_rates,
    "variants": variants,
    "at-a-glance": at_a_glance,
    "rllib-throughput": rllib_throughput,
    "roofline": lambda: roofline.to_markdown(read_results(RESULTS / "roofline.json")),
    "first-step": first_step,
    "variant-speed": lambda: speed_table.block(RESULTS / "variant_speed.json"),
    "contact-convergence": lambda: contact_convergence("impulse"),
    "compliant-convergence": lambda: contact_convergence("compliant"),
    "model-agreement": model_agreement_quote,
    "variants-summary": variants_summary,
    "baselines-matrix": lambda: baselines.matrix(load_cells(BASELINES)),
    "baselines-improvement": lambda: baselines.improvement(load_cells(BASELINES)),
    "baselines-aggregates": lambda: baselines.aggregates(load_cells(BASELINES)),
    "baselines-table": lambda: baselines.table(load_cells(BASELINES)),
    "baselines-protocol": lambda: baselines.protocol(load_cells(BASELINES)),
    "baselines-tuning": baselines.tuning,
    "baselines-shipped": lambda: baselines.shipped(RESULTS, SHIPPED_BASELINES),
    "baselines-by-throw-windy": lambda: baselines.by_throw(load_cells(BASELINES), "NetCatchWindy-v0"),
    "baselines-by-throw-randomized": lambda: baselines.by_throw(load_cells(BASELINES),
                                                                "NetCatchRandomized-v1"),
    "baselines-long-table": lambda: baselines.table(load_cells(BASELINES_LONG)),
    "baselines-long-by-throw-windy": lambda: baselines.by_throw(load_cells(BASELINES_LONG),
                                                                "NetCatchWindy-v0"),
    "baselines-long-protocol": lambda: baselines.protocol(load_cells(BASELINES_LONG)),
    "learning-curve": lambda: learning_curve("ppo_curve"),
    "learning-curve-windy": lambda: learning_curve("ppo_windy_curve", (0, 8192, 16384, 24576, 32768, 40960)),
    "learning-curve-windy-stack5": lambda: learning_curve("ppo_windy_stack5_curve",
                                                          (0, 8192, 16384, 24576, 32768, 40960)),
    "windy-per-throw": windy_per_throw,
    "windy-long-seeds": windy_long_seeds,
}
"""How each quoted block is made."""

FILES = ("README.md", "docs/AGENTS.md", "docs/index.md", "docs/getting-started.md", "docs/BENCHMARKS.md",
         "docs/baselines.md")
"""The files whose quoted blocks are generated."""

_BLOCK = re.compile(r"(<!-- quote:([\w-]+) -->\n)(.*?)(<!-- /quote:\2 -->)", re.S)


def render(text: str) -> str:
    """``text`` with every quoted block made anew from its sources."""
    return _BLOCK.sub(lambda m: f"{m.group(1)}{BLOCKS[m.group(2)]()}\n{m.group(4)}", text)


def stale_blocks(root: Path = ROOT) -> list[str]:
    """``FILE: NAME`` of every quoted block that differs from what its sources make."""
    stale = []
    for name in FILES:
        path = root / name
        if not path.is_file():
            continue
        text = path.read_text()
        fresh = render(text)
        stale += [f"{name}: {m.group(2)}" for m, n in zip(_BLOCK.finditer(text), _BLOCK.finditer(fresh))
                  if m.group(0) != n.group(0)]
    return stale


def main() -> None:
    """Rewrite every quoted block, or (``--check``) name those out of date."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--check", action="store_true", help="change nothing; exit 1 if a block is out of date")
    args = parser.parse_args()
    if args.check:
        stale = stale_blocks()
        print("\n".join(f"out of date: {block}" for block in stale) or "every quoted block matches its source")
        raise SystemExit(1 if stale else 0)
    for name in FILES:
        path = ROOT / name
        if path.is_file():
            path.write_text(render(path.read_text()))
    print(f"rewrote the quoted blocks of {', '.join(FILES)}")


if __name__ == "__main__":
    main()
