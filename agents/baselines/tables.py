"""The baselines' markdown: every table of the report and of the docs' quoted blocks, with its caption.

Per-cell rates (:func:`matrix`, :func:`table`), probabilities of improvement (:func:`improvement`),
aggregates over the common task sets (:func:`aggregates`), rates by throw index (:func:`by_throw`),
the shipped models (:func:`shipped`), an env card's best learner (:func:`best_line`) and the
protocol as the result files record it (:func:`protocol`). The references (random, blind,
informed oracle) are one run each: their intervals are Wilson's over their throws.

Tables fit the docs' content column (about 700 px at a page width of 1280 px): at most
:data:`COLUMNS_A_TABLE` columns of intervals beside the key column, one line each, and ids that
never break at their hyphens (:func:`nowrap`).
"""

from __future__ import annotations

from collections import Counter, defaultdict
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from agents.baselines.analysis import Stats, clear_winners, is_clear, statistics
from agents.baselines.cells import (Cells, best_learners, bounds, cell_key, learners, set_name, table_ids,
                                    throw_rates, throw_tallies)
from agents.baselines.grid import ALGORITHMS, LEFT_OUT, REFERENCES, TABLE_IDS, TRAIN_SEED_STRIDE
from agents.baselines.stats import PROFILE_REPS, Estimate, normalise, wilson
from agents.hyperparams import TUNING, env_ids, yml
from netgym.bench.results import read_results

COLUMNS_A_TABLE = 3
"""Columns of intervals a table shows beside its key column: with an id there, about 650 px, within
the docs' content column (about 700 px at a page width of 1280 px)."""


def nowrap(text: str) -> str:
    """``text`` that a table never breaks (ids break at their hyphens otherwise); copied, it
    stays plain ASCII."""
    return f'<span style="white-space:nowrap">{text}</span>'


def _estimate(estimate: Estimate | list, scale: float = 100.0, digits: int = 1) -> str:
    """``point [low, high]`` (rates in percent to 0.1 by default); the point alone where there is
    no interval."""
    point, low, high = (None if value is None else scale * value for value in estimate)
    if low is None:
        return f"{point:.{digits}f}"
    return f"{point:.{digits}f} [{low:.{digits}f}, {high:.{digits}f}]"


def _seeds_text(seeds: list[int]) -> str:
    """``0-4`` for a run of consecutive seeds, else the seeds listed."""
    seeds = sorted(seeds)
    if len(seeds) > 2 and seeds == list(range(seeds[0], seeds[-1] + 1)):
        return f"{seeds[0]}-{seeds[-1]}"
    return ", ".join(map(str, seeds))


def _tables(corner: str, rows: list[tuple[str, Any]], columns: list[tuple[str, Callable[[Any], str | None]]]) -> str:
    """Markdown tables of ``rows`` (label, key) by ``columns`` (header, cell of a key or None),
    :data:`COLUMNS_A_TABLE` columns a table; a table has the rows that have a cell in it ('-'
    where a column has none)."""
    tables = []
    for start in range(0, len(columns), COLUMNS_A_TABLE):
        chunk = columns[start:start + COLUMNS_A_TABLE]
        lines = [f"| {corner} | " + " | ".join(header for header, _ in chunk) + " |", "|---|" + "---:|" * len(chunk)]
        for label, key in rows:
            texts = [cell(key) for _, cell in chunk]
            if any(text is not None for text in texts):
                lines.append(f"| {label} | " + " | ".join("-" if text is None else text for text in texts) + " |")
        tables.append("\n".join(lines))
    return "\n\n".join(tables)


def _final_wilson(final: dict[str, Any]) -> Estimate:
    """A final evaluation's capture rate and its Wilson interval over its throws."""
    return wilson(final["captured"], final["throws"])


def _usual(values: dict[Any, Any]) -> tuple[Any, dict[Any, list[Any]]]:
    """The most frequent of ``values`` (of equals, the first), and the keys of each other value."""
    usual = Counter(values.values()).most_common(1)[0][0]
    others: dict[Any, list[Any]] = defaultdict(list)
    for key, value in values.items():
        if value != usual:
            others[value].append(key)
    return usual, dict(others)


def _grouped(pairs: list[tuple[str, str]], joint: str) -> str:
    """``(name, place)`` pairs as ``a, b{joint}place``, one group a place, in order."""
    places: dict[str, list[str]] = defaultdict(list)
    for name, place in pairs:
        places[place].append(name)
    return "; ".join(f"{', '.join(names)}{joint}{place}" for place, names in places.items())


def _seed_caption(cells: Cells) -> str:
    """How many seeds the learners' cells have: the usual seeds, and the cells with others."""
    usual, others = _usual({(algo, nowrap(env_id)): tuple(r["seed"] for r in cells[algo, env_id])
                            for env_id in table_ids(cells) for algo in learners(cells) if (algo, env_id) in cells})
    return (f"{len(usual)} seeds a cell ({_seeds_text(list(usual))})"
            + "".join(f"; {len(s)} ({_seeds_text(list(s))}): {_grouped(keys, ' on ')}" for s, keys in others.items()))


def _references(cells: Cells) -> str:
    """The references' table: tasks by reference, each run's rate with its Wilson interval."""
    runs = {key: records[0]["final"] for key, records in cells.items() if key[0] in REFERENCES}
    columns = [(f"*{name}*", lambda env_id, name=name: _estimate(_final_wilson(runs[name, env_id]))
                if (name, env_id) in runs else None) for name in REFERENCES if any(n == name for n, _ in runs)]
    return _tables("task (rate in %)", [(nowrap(env_id), env_id) for env_id in table_ids(cells)], columns)


def matrix(cells: Cells, stats: Stats | None = None) -> str:
    """The tables a reader looks at first: tasks by learner, each cell the IQM capture rate over
    the cell's seeds with its 95% interval, a task's leader in bold where it is clear of the
    runner-up (:func:`~agents.baselines.analysis.clear_winners`); then the references' rates with
    their Wilson intervals."""
    stats = stats or statistics(cells)
    winners = clear_winners(stats)

    def cell(algo: str) -> Callable[[str], str | None]:
        def text(env_id: str) -> str | None:
            estimate = stats["cells"].get(cell_key(algo, env_id))
            if estimate is None:
                return None
            return f"**{_estimate(estimate)}**" if winners.get(env_id) == algo else _estimate(estimate)
        return text

    episodes = sorted({r["final"]["episodes"] for records in cells.values() for r in records})
    caption = (f"Capture rate (%) on {' / '.join(map(str, episodes))} held-out episodes, IQM over seeds "
               f"[95% stratified bootstrap CI], {_seed_caption(cells)}. Bold: the task's leader, where the "
               "95% interval of the probability that it beats the runner-up lies above 0.5.")
    learner_tables = _tables("task (rate in %)", [(nowrap(env_id), env_id) for env_id in table_ids(cells)],
                             [(algo, cell(algo)) for algo in learners(cells)])
    reference_caption = ("References, one run each (they do not learn) on the same episodes; "
                         "95% Wilson interval over the run's throws:")
    return f"{caption}\n\n{learner_tables}\n\n{reference_caption}\n\n{_references(cells)}"


def improvement(cells: Cells, stats: Stats | None = None) -> str:
    """The table of the probabilities of improvement: per task its leader against the runner-up
    and every learner whose interval overlaps the leader's, bold where the interval lies above
    one half."""
    stats = stats or statistics(cells)
    lines = ["| task | leader | against | P(leader > other) [95% CI] |", "|---|---|---|---:|"]
    for env_id, pairs in stats["improvement"].items():
        for pair in pairs:
            text = _estimate(pair["p"], 1.0, 2)
            lines.append(f"| {nowrap(env_id)} | {pair['leader']} | {pair['other']} | "
                         f"{f'**{text}**' if is_clear(pair['p']) else text} |")
    alone = [nowrap(env_id) for env_id in table_ids(cells) if env_id not in stats["improvement"]]
    caption = (f"rliable's probability of improvement from the seeds' capture rates (every seed of both cells), "
               f"95% interval over {stats['improvement_reps']:,} bootstrap resamples of each cell's seeds.")
    return caption + "\n\n" + "\n".join(lines) + (f"\n\nOne learner only: {', '.join(alone)}." if alone else "")


def aggregates(cells: Cells, stats: Stats | None = None) -> str:
    """Each learner's normalised IQM and optimality gap over each common task set, with 95%
    intervals (every learner with a normalised score appears); which tasks and seeds a set has."""
    stats = stats or statistics(cells)
    sets = stats["sets"]
    rows = [(algo, algo) for algo in learners(cells) if any(algo in s["learners"] for s in sets)]

    def columns(metric: str) -> list[tuple[str, Callable[[str], str | None]]]:
        return [(nowrap(set_name(s["tasks"])), lambda algo, s=s: _estimate(s["learners"][algo][metric], 1.0, 2)
                 if algo in s["learners"] else None) for s in sets]

    legend = "".join(f"{set_name(s['tasks'])}: {', '.join(map(nowrap, s['tasks']))}. " for s in sets
                     if len(s["tasks"]) > 1)
    return (f"Normalised score (random 0, informed oracle 1 on each task), IQM over the runs of every task of a "
            f"set [95% stratified bootstrap CI]; a learner appears in a set's column when it ran every task of it. "
            f"{legend}{_set_seeds_caption(stats)}\n\n{_tables('learner', rows, columns('iqm'))}\n\n"
            f"Optimality gap (γ = 1: how far the mean normalised score, each capped at 1, falls short of 1; "
            f"lower is better) [95% CI]:\n\n{_tables('learner', rows, columns('gap'))}")


def _set_seeds_caption(stats: Stats) -> str:
    """Which seeds the sets take: the usual ones, and the learners of a set with others."""
    usual, others = _usual({(algo, nowrap(set_name(s["tasks"]))): tuple(member["seeds"])
                            for s in stats["sets"] for algo, member in s["learners"].items()})
    return (f"Each set takes the seeds all its tasks have: {_seeds_text(list(usual))}"
            + "".join(f"; {_seeds_text(list(found))} of {_grouped(keys, ' on ')}" for found, keys in others.items())
            + " (a cell with more seeds than the set's other tasks gives the set only the seeds they share).")


def table(cells: Cells, stats: Stats | None = None) -> str:
    """The table of every cell: per task and learner its seeds, IQM capture rate and normalised
    IQM with 95% intervals and the median minutes a run; then the references (one run, Wilson)."""
    stats = stats or statistics(cells)
    lines = ["| task | learner (seeds) | capture rate (%), IQM [95% CI] | normalised IQM [95% CI] | "
             "minutes a run (median) |", "|---|---|---:|---:|---:|"]
    rows = [(env_id, algo) for env_id in table_ids(cells) for algo in [*learners(cells), *REFERENCES]
            if (algo, env_id) in cells]
    for env_id, algo in rows:
        records = cells[algo, env_id]
        wall = np.median([record["wall_s"] for record in records]) / 60
        if algo in REFERENCES:
            name, rate, scaled = f"*{algo}* (1 run)", _estimate(_final_wilson(records[0]["final"])), "-"
        else:
            estimate, scale = stats["cells"][cell_key(algo, env_id)], bounds(cells, env_id)
            name, rate = f"{algo} ({len(records)})", _estimate(estimate)
            scaled = "-" if scale is None else _estimate(
                [None if value is None else float(normalise(value, *scale)) for value in estimate], 1.0, 2)
        lines.append(f"| {nowrap(env_id)} | {name} | {rate} | {scaled} | {wall:.1f} |")
    return "\n".join(lines)


def by_throw(cells: Cells, env_id: str, stats: Stats | None = None) -> str:
    """``env_id``'s capture rate by throw index: per learner (``n``: its runs that counted them)
    the IQM over its runs of each throw's rate and of the later throws' rate, with 95% intervals;
    the references' with Wilson intervals over their episodes."""
    stats = stats or statistics(cells)
    counted = stats["by_throw"].get(env_id, {})
    references = {name: tallies for name in REFERENCES if (name, env_id) in cells
                  and (tallies := throw_tallies(cells[name, env_id][0]["final"])) is not None}
    if not counted and not references:
        return f"No run on {env_id} counted its captures by throw yet."
    throws = len(next(iter(counted.values()))["rates"] if counted else next(iter(references.values()))) - 1
    rows = [(f"throw {k + 1}", k) for k in range(throws)] + [(f"throws 2-{throws}", throws)]
    learner_columns = [(f"{algo} (n={found['runs']})", lambda k, found=found: _estimate(found["rates"][k]))
                       for algo, found in counted.items()]
    reference_columns = [(f"*{name}*", lambda k, tallies=tallies: _estimate(wilson(*tallies[k])))
                         for name, tallies in references.items()]
    missing = [algo for algo in learners(cells) if (algo, env_id) in cells and algo not in counted]
    caption = (f"Capture rate (%) by throw index, IQM over the runs [95% CI] (n: runs that counted their throws; "
               f"throws 2-{throws}: each run's rate over those throws); references: Wilson 95% interval over the "
               "episodes." + (f" Not counted (runs from before the count was recorded): {', '.join(missing)}."
                              if missing else ""))
    return "\n\n".join(part for part in (caption, _tables("rate in %", rows, learner_columns) if counted else "",
                                         _tables("rate in %", rows, reference_columns) if references else "") if part)


def shipped(results: Path, models: dict[str, str]) -> str:
    """The markdown table of the shipped models ``models`` (file name -> run, as
    :data:`agents.policies.SHIPPED_BASELINES`), each with its run and final evaluation from its
    result file under ``results``: the capture rate with its Wilson interval over the evaluation's
    throws and, where the run counted them, throw 1 and the later throws."""
    lines = ["| agents/pretrained/ | run | capture rate (%) [95% CI] | throw 1 (%) | later throws (%) |",
             "|---|---|---:|---:|---:|"]
    records = {name: read_results(results / f"{run}.json")["figures"] for name, run in models.items()}
    for name, record in records.items():
        final, rates = record["final"], throw_rates(record["final"])
        first, later = ("-", "-") if rates is None else (f"{100 * rates[0]:.1f}", f"{100 * rates[-1]:.1f}")
        lines.append(f"| `{name}` | {nowrap(record['env_id'])}, {record['algorithm']} seed {record['seed']}, "
                     f"{record['budget']:,} steps | {_estimate(_final_wilson(final))} | {first} | {later} |")
    episodes = sorted({record["final"]["episodes"] for record in records.values()})
    return ("\n".join(lines) + f"\n\nOn {' / '.join(map(str, episodes))} held-out episodes; 95% Wilson interval over "
            "the evaluation's throws.")


def best_line(cells: Cells, env_id: str) -> str:
    """One sentence naming ``env_id``'s best learner(s): the IQM capture rate, interval, seeds and
    budget; or that no learner has run on it."""
    best = best_learners(cells).get(env_id)
    if best is None:
        return "none trained yet"
    records = cells[best[0], env_id]
    point, low, high = statistics(cells)["cells"][cell_key(best[0], env_id)]
    interval = "" if low is None else f" [{100 * low:.1f}, {100 * high:.1f}]"
    return (f"{', '.join(best)}{' (tied)' if len(best) > 1 else ''}: {100 * point:.1f}%{interval} IQM over "
            f"{len(records)} seeds at {records[0]['budget']:,} steps")


def _distinct(values: list[Any]) -> str:
    """The distinct values, most frequent first; each with its count where there are several."""
    counted = Counter(values).most_common()
    return str(counted[0][0]) if len(counted) == 1 else ", ".join(f"{value} ({n})" for value, n in counted)


def _protocol_rows(cells: Cells) -> list[str]:
    """Per task: the learners' budget(s), seeds, final evaluation and learning curve."""
    lines = ["| task | budget (env steps) | seeds | final evaluation (deterministic) | learning curve |",
             "|---|---:|---|---|---|"]
    for env_id in table_ids(cells):
        runs = {algo: cells[algo, env_id] for algo in learners(cells) if (algo, env_id) in cells}
        usual, others = _usual({algo: records[0]["budget"] for algo, records in runs.items()})
        budget = f"{usual:,}" + "".join(f"; {', '.join(algos)}: {b:,}" for b, algos in others.items())
        usual, others = _usual({algo: tuple(r["seed"] for r in records) for algo, records in runs.items()})
        seed_text = _seeds_text(list(usual)) + "".join(f"; {', '.join(algos)}: {_seeds_text(list(found))}"
                                                       for found, algos in others.items())
        finals = [r["final"] for records in cells.values() for r in records if r["env_id"] == env_id]
        evaluation = _distinct([f"{f['episodes']} episodes seeded from {f['seed']:,}" for f in finals])
        curves = [r["curve"] for records in runs.values() for r in records]
        curve = _distinct([f"{len(c['points'])} points of {c['episodes']} episodes"
                           + (f" seeded from {c['seed']:,}" if "seed" in c else "") for c in curves])
        lines.append(f"| {nowrap(env_id)} | {budget} | {seed_text} | {evaluation} | {curve} |")
    return lines


def _provenance(cells: Cells) -> list[str]:
    """The runs' training seeds, commits (with a warning line where there are several, or a tree
    with changes), machines, dates, compute and package versions."""
    records = [record for runs in cells.values() for record in runs]
    learning = [r for r in records if r["algorithm"] not in REFERENCES]
    seeded = [r for r in learning if "env_seeds" in r]
    stride = TRAIN_SEED_STRIDE
    as_planned = [r for r in seeded if all(stride * r["seed"] <= s < stride * (r["seed"] + 1) for s in r["env_seeds"])
                  and r["env_seeds"][:r["hyperparams"].get("n_envs", 1)]
                  == [stride * r["seed"] + i for i in range(r["hyperparams"].get("n_envs", 1))]]
    lines = ["Training env seeds: not recorded by these runs." if not seeded else
             f"Training envs: worker i of run seed k seeded {stride} k + i (a resumed run's next workers the next "
             f"ones of its block of {stride}) in {len(as_planned)} of the {len(seeded)} learner runs that record them"
             + ("" if len(seeded) == len(learning) else f" ({len(learning)} learner runs)")
             + ("." if len(as_planned) == len(seeded) else "; **Warning:** the others were seeded otherwise.")]
    commits = Counter(str(r["versions"].get("commit"))[:10] for r in records)
    if len(commits) == 1:
        lines.append(f"Commit: `{next(iter(commits))}` (every run).")
    else:
        shown = commits.most_common(3)
        lines.append(f"**Warning:** the runs come from {len(commits)} commits, not one: "
                     + ", ".join(f"`{commit}` ({n} runs)" for commit, n in shown)
                     + (f" and {len(commits) - len(shown)} more." if len(commits) > len(shown) else "."))
    dirty = sum(r["versions"].get("tree_clean") is False for r in records)
    unknown = sum(r["versions"].get("tree_clean") is None for r in records)
    if dirty:
        lines.append(f"**Warning:** {dirty} runs ran on a tree with uncommitted changes: their commit does not say "
                     f"what ran.")
    if unknown:
        lines.append(f"{unknown} runs did not record whether their tree had uncommitted changes.")
    started = sorted(r["started"] for r in records)
    cpu_hours, wall_hours = (sum(r[key] for r in records) / 3600 for key in ("cpu_s", "wall_s"))
    lines.append(f"{len(records)} runs ({len(learning)} learning), one process and one torch thread each, CPU only, on "
                 f"{_distinct([r['machine'] for r in records])}; started {started[0][:16].replace('T', ' ')} to "
                 f"{started[-1][:16].replace('T', ' ')} UTC. Compute: {cpu_hours:.1f} CPU hours, {wall_hours:.1f} "
                 "hours of runs' wall-clock.")
    names = dict.fromkeys(name for r in records for name in r["versions"] if name not in ("commit", "tree_clean"))
    lines.append("Versions: " + ", ".join(
        f"{name} {_distinct([str(r['versions'][name]) for r in records if r['versions'].get(name)])}"
        for name in names) + ".")
    return lines


def protocol(cells: Cells, stats: Stats | None = None) -> str:
    """The protocol as the result files record it: per task the budgets, seeds, held-out
    evaluation and learning curve; the runs' training seeds, commits, machines, compute and
    versions; the statistics' resamples."""
    stats = stats or statistics(cells)
    return "\n".join(_protocol_rows(cells)) + "\n\n" + "\n\n".join([*_provenance(cells), (
        f"Statistics: rliable {stats['rliable']}, stratified bootstrap 95% percentile intervals from "
        f"{stats['reps']:,} resamples (probabilities of improvement: {stats['improvement_reps']:,}; the figures' "
        f"bands: {min(stats['reps'], PROFILE_REPS):,}), numpy's global generator seeded {stats['seed']} for each.")])


def tuning() -> str:
    """The markdown table of where each algorithm of the grid was tuned and the table's ids it runs
    on (:data:`agents.hyperparams.TUNING`, the yml files), with the reason of any the table leaves out."""
    lines = ["| learner | settings | ids | tuned |", "|---|---|---|---|"]
    for algorithm in ALGORITHMS:
        ids = ", ".join(nowrap(env_id) for env_id in env_ids(yml(algorithm)) if env_id in TABLE_IDS)
        left_out = f"; left out of the table: {LEFT_OUT[algorithm]}" if algorithm in LEFT_OUT else ""
        lines.append(f"| {algorithm} | `agents/hyperparams/{algorithm}.yml` | {ids} | {TUNING[algorithm]}{left_out} |")
    return "\n".join(lines)
