"""The grid of baseline runs: algorithms x env ids x seeds, and the budget of each id.

An algorithm runs on the ids its hyperparameter file (``agents/hyperparams/NAME.yml``, rl_zoo3's
format) has settings for; the file's ``n_timesteps`` is ignored, every algorithm gets the id's
:data:`BUDGETS`. Besides the learners, each id has three
reference runs, :data:`REFERENCES`: the random policy and the informed oracle (the 0 and 1 of the
normalised score), and the blind oracle between them.

The shipped models, declared before the runs: for each id, the learner with the highest IQM
capture rate over its seeds (ties: more seeds, then the higher mean), and of its seeds the model
that catches the most throws of 400 fresh episodes seeded from 50000, neither training's nor the
table's (``scripts/ship_model.py``); besides, on NetCatchPixels-v0, the same choice among the
learners from pixels alone (no critic reads the state: sac_drq).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

from agents.hyperparams import env_ids, load, yml
from netgym.errors import InvalidArgumentError

ROOT = Path(__file__).resolve().parents[2]
"""The repository's root: commands are written relative to it."""

ALGORITHMS: dict[str, tuple[str, str]] = {
    "ppo": ("stable_baselines3", "PPO"),
    "sac": ("stable_baselines3", "SAC"),
    "td3": ("stable_baselines3", "TD3"),
    "tqc": ("sb3_contrib", "TQC"),
    "rppo": ("sb3_contrib", "RecurrentPPO"),
    "ppo_cnn": ("stable_baselines3", "PPO"),
    "sac_asym": ("agents.asymmetric", "AsymmetricSAC"),
    "sac_sym": ("agents.asymmetric", "AsymmetricSAC"),
    "sac_drq": ("agents.drq", "DrQSAC"),
}
"""Algorithm name (its yml's name) -> (module, class) of its implementation. Two are controls:
``sac_sym`` is sac_asym's windy settings with critics that read what the actor reads (not the
wind), ``sac_drq`` learns from pixels alone (no critic reads the state)."""
REFERENCES = ("random", "blind", "oracle")
"""The runs that learn nothing: uniform random actions, the ballistic oracle blind to what an
episode hides (its wind, its ball), and the informed oracle (told them); on pixels they act on the
same episodes' vector observations. The gap from blind to informed is what learning within an
episode can close."""
BUDGETS: dict[str, int] = {
    "NetCatch-v0": 20_480,
    "NetCatchGoal-v0": 20_480,
    "NetCatchNoisy-v0": 20_480,
    "NetCatchWindy-v0": 30_720,
    "NetCatchPixels-v0": 20_480,
    "NetCatchLongEpisode-v0": 20_480,
    "NetCatchRandomized-v0": 20_480,
    "NetCatchRandomized-v1": 30_720,
}
"""Environment steps (throws) of every learning run on the id. Multiples of 512, so that PPO's rollouts (8 envs x 64 steps; x 128 on
pixels) end on the budget. The ids with feedback across 5 throws (NetCatchWindy-v0,
NetCatchRandomized-v1) get half as many again; NetCatchLongEpisode-v0 asks the same aim as
NetCatch-v0 into a fuller net and gets its budget; the learning curves on docs/baselines.md show
where each learner levels off within them."""
TABLE_IDS = ("NetCatch-v0", "NetCatchGoal-v0", "NetCatchNoisy-v0", "NetCatchWindy-v0", "NetCatchPixels-v0",
             "NetCatchLongEpisode-v0", "NetCatchRandomized-v1")
"""The ids of the table (the default)."""
SEEDS = (0, 1, 2, 3, 4)
CONTROL_SEEDS = tuple(range(10))
CONTROLLED = {("sac", "NetCatchWindy-v0"), ("sac_asym", "NetCatchWindy-v0"), ("sac_sym", "NetCatchWindy-v0")}
"""The cells that get :data:`CONTROL_SEEDS`: the windy id's control (sac_asym against sac_sym, its
settings without the wind in its critics, and sac), whose rates sit within a point of each other.
The other cells get :data:`SEEDS`; aggregates over ids take seeds 0-4 of every cell."""
TRAIN_SEED_STRIDE = 1000
"""Run seed ``k``'s training envs are seeded ``1000 k + i`` (worker ``i``; a resumed run's next
workers ``1000 k + 8 r + i`` after its ``r``-th resumption): no two runs share an episode stream."""
FINAL_EPISODES, FINAL_SEED = 1000, 1_000_000
"""The final evaluation: episodes seeded 1000000, 1000001, ..., the same for every run of an id,
beyond every training seed (run seeds stay below 1000)."""
CURVE_POINTS, CURVE_EPISODES, CURVE_SEED = 20, 10, 2_000_000
"""The learning curve: evaluated at step 0 and every budget / CURVE_POINTS steps on
CURVE_EPISODES episodes seeded from CURVE_SEED (neither the final evaluation's nor training's)."""
MODELS = "models"
"""The folder under the output folder where each learner's final model is saved
(``models/ALGORITHM/ENV_ID/seed_K.zip``; not committed with the result files)."""
QUICK_IDS, QUICK_SEEDS, QUICK_BUDGET = ("NetCatch-v0", "NetCatchGoal-v0"), (0,), 512
QUICK_ALGORITHMS = ("ppo", "sac", "td3", "tqc")
QUICK_EPISODES = 4


CPU_MS_A_STEP: dict[tuple[str, str], float] = {
    ("ppo", "NetCatch-v0"): 5.4, ("ppo", "NetCatchGoal-v0"): 1.9, ("ppo", "NetCatchLongEpisode-v0"): 9.8,
    ("ppo", "NetCatchNoisy-v0"): 4.6, ("ppo", "NetCatchRandomized-v1"): 8.6, ("ppo", "NetCatchWindy-v0"): 13.0,
    ("ppo_cnn", "NetCatchPixels-v0"): 8.7, ("rppo", "NetCatchRandomized-v1"): 5.7, ("rppo", "NetCatchWindy-v0"): 6.2,
    ("sac", "NetCatch-v0"): 12.4, ("sac", "NetCatchGoal-v0"): 3.4, ("sac", "NetCatchLongEpisode-v0"): 15.2,
    ("sac", "NetCatchNoisy-v0"): 13.4, ("sac", "NetCatchRandomized-v1"): 12.9, ("sac", "NetCatchWindy-v0"): 19.0,
    ("sac_asym", "NetCatchPixels-v0"): 43.9, ("sac_asym", "NetCatchWindy-v0"): 9.8,
    ("td3", "NetCatch-v0"): 8.5, ("td3", "NetCatchGoal-v0"): 3.4, ("td3", "NetCatchLongEpisode-v0"): 10.9,
    ("td3", "NetCatchNoisy-v0"): 8.4, ("td3", "NetCatchRandomized-v1"): 8.4, ("td3", "NetCatchWindy-v0"): 14.0,
    ("tqc", "NetCatch-v0"): 18.2, ("tqc", "NetCatchGoal-v0"): 7.7, ("tqc", "NetCatchLongEpisode-v0"): 17.2,
    ("tqc", "NetCatchNoisy-v0"): 19.3, ("tqc", "NetCatchRandomized-v1"): 13.2, ("tqc", "NetCatchWindy-v0"): 19.0,
    ("sac_sym", "NetCatchWindy-v0"): 9.8, ("sac_drq", "NetCatchPixels-v0"): 68.0,
}
"""CPU milliseconds a training step (curve evaluations included) of each learner on each id: the
median over the seeds of the table of 2026-12-07 (docs/results/baselines at 3b6cb38, runs on
2-core AMD EPYC machines); sac_sym as sac_asym (the same networks), sac_drq from its tuning run.
For the runner's estimates only."""
CPU_MS_AN_EPISODE: dict[str, float] = {
    "NetCatch-v0": 15.0, "NetCatchGoal-v0": 7.0, "NetCatchLongEpisode-v0": 85.0, "NetCatchNoisy-v0": 32.0,
    "NetCatchPixels-v0": 45.0, "NetCatchRandomized-v1": 62.0, "NetCatchWindy-v0": 62.0,
}
"""CPU milliseconds of one evaluation episode on each id: the informed oracle's in the same
table, plus a millisecond a throw for a learner's forward pass (pixels: plus the images drawn).
For the runner's estimates only."""

PPO_CNN_STEPS = int(load(yml("ppo_cnn"), "NetCatchPixels-v0")["n_timesteps"])
LEFT_OUT = {"ppo_cnn": f"the budget its settings ask for (agents/hyperparams/ppo_cnn.yml: {PPO_CNN_STEPS:,} steps, "
                       f"{PPO_CNN_STEPS / BUDGETS['NetCatchPixels-v0']:.0f} times the pixel budget) would cost about "
                       f"{PPO_CNN_STEPS * CPU_MS_A_STEP['ppo_cnn', 'NetCatchPixels-v0'] * len(SEEDS) / 3.6e6:.0f} CPU "
                       f"hours for {len(SEEDS)} seeds at its measured cost a step; "
                       f"sac_drq is the table's learner from pixels alone"}
"""Algorithms with settings that the table leaves out, and why (the page says so)."""


@dataclass(frozen=True)
class Run:
    """One cell's seed: an algorithm (or a reference) trained on ``env_id`` for ``budget``
    steps and evaluated on ``final_episodes`` episodes."""

    algorithm: str
    env_id: str
    seed: int
    budget: int
    final_episodes: int = FINAL_EPISODES
    curve_episodes: int = CURVE_EPISODES
    quick: bool = False

    @property
    def name(self) -> str:
        """``algorithm/env_id/seed_k``: the result file's path under the output folder, less ``.json``."""
        return f"{self.algorithm}/{self.env_id}/seed_{self.seed}"

    def path(self, out: Path) -> Path:
        """The run's result file under ``out``."""
        return out / f"{self.name}.json"

    def command(self, out: Path) -> list[str]:
        """The arguments of ``python`` that run this run alone (if its result file is missing),
        from the repository's root: ``out`` relative to it."""
        longer = self.budget not in (0, table_budget(self.env_id, self.quick))
        return ["scripts/baselines.py", "--out", os.path.relpath(out.resolve(), ROOT), "--algos", self.algorithm, "--ids", self.env_id,
                "--seeds", str(self.seed), *(["--quick"] if self.quick else []),
                *(["--budget", str(self.budget)] if longer else [])]

    @property
    def cost(self) -> float:
        """Estimated CPU seconds of the run, training and final evaluation (:data:`CPU_MS_A_STEP`,
        :data:`CPU_MS_AN_EPISODE`; for planning and progress)."""
        step = CPU_MS_A_STEP.get((self.algorithm, self.env_id), 0.0) if self.budget else 0.0
        return (self.budget * step + self.final_episodes * CPU_MS_AN_EPISODE[self.env_id]) / 1000.0


def table_budget(env_id: str, quick: bool = False) -> int:
    """The learners' steps on ``env_id`` under the table's protocol (its :data:`BUDGETS`, or
    :data:`QUICK_BUDGET` in quick mode)."""
    return QUICK_BUDGET if quick else BUDGETS[env_id]


def table_seeds(algorithm: str, env_id: str) -> tuple[int, ...]:
    """The seeds of ``algorithm`` on ``env_id`` under the table's protocol."""
    return CONTROL_SEEDS if (algorithm, env_id) in CONTROLLED else SEEDS


def grid(algorithms: list[str] | None = None, ids: list[str] | None = None, seeds: list[int] | None = None,
         quick: bool = False, budget: int | None = None) -> list[Run]:
    """The runs of ``algorithms`` (default: all) on ``ids`` (default: :data:`TABLE_IDS`, in
    quick mode :data:`QUICK_IDS`) that each algorithm has settings for, one per seed (default:
    :func:`table_seeds`, quick :data:`QUICK_SEEDS`), and the reference runs of those ids (one each:
    their policies do not learn; the table leaves out :data:`LEFT_OUT`). ``quick``: :data:`QUICK_BUDGET` steps and
    :data:`QUICK_EPISODES` episodes, for smoke tests. ``budget``: the learners' steps instead of
    the ids' :data:`BUDGETS` (runs beyond the table's protocol, kept in a folder of their own)."""
    if budget is not None and (not isinstance(budget, int) or budget < 1):
        raise InvalidArgumentError(f"budget = {budget!r}; allowed: a positive number of environment steps")
    algorithms = list(algorithms or (QUICK_ALGORITHMS if quick else [a for a in ALGORITHMS if a not in LEFT_OUT]))
    ids = list(ids or (QUICK_IDS if quick else TABLE_IDS))
    for name, known, what in ((algorithms, ALGORITHMS, "algorithm"), (ids, BUDGETS, "env id")):
        if unknown := sorted(set(name) - set(known)):
            raise InvalidArgumentError(f"unknown {what}(s) {unknown}; one of {list(known)}")
    if seeds is not None and (bad := [seed for seed in seeds if not 0 <= seed < TRAIN_SEED_STRIDE]):
        raise InvalidArgumentError(f"seeds {bad}; allowed: 0 to {TRAIN_SEED_STRIDE - 1} (training streams stay "
                                   f"below the evaluations' seeds)")
    episodes = dict(final_episodes=QUICK_EPISODES, curve_episodes=2, quick=True) if quick else {}
    runs = [Run(reference, env_id, 0, 0, **episodes) for env_id in ids for reference in REFERENCES]
    for algorithm in algorithms:
        for env_id in (i for i in ids if i in env_ids(yml(algorithm))):
            steps = budget or table_budget(env_id, quick)
            chosen = seeds if seeds is not None else (QUICK_SEEDS if quick else table_seeds(algorithm, env_id))
            runs += [Run(algorithm, env_id, seed, steps, **episodes) for seed in chosen]
    return runs
