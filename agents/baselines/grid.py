"""The grid of baseline runs: algorithms x env ids x seeds, and the budget of each id.

An algorithm runs on the ids its hyperparameter file (``agents/hyperparams/NAME.yml``, rl_zoo3's
format) has settings for; the file's ``n_timesteps`` is ignored, every algorithm gets the id's
:data:`BUDGETS`. Besides the learners, each id has three reference runs, :data:`REFERENCES`: the
random policy and the informed oracle (the 0 and 1 of the normalised score), and the blind oracle
between them.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import netgym
from agents.hyperparams import env_ids, yml
from netgym.errors import InvalidArgumentError

ALGORITHMS: dict[str, tuple[str, str]] = {
    "ppo": ("stable_baselines3", "PPO"),
    "sac": ("stable_baselines3", "SAC"),
    "td3": ("stable_baselines3", "TD3"),
    "tqc": ("sb3_contrib", "TQC"),
    "rppo": ("sb3_contrib", "RecurrentPPO"),
    "ppo_cnn": ("stable_baselines3", "PPO"),
    "sac_asym": ("agents.asymmetric", "AsymmetricSAC"),
}
"""Algorithm name (its yml's name) -> (module, class) of its implementation."""
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
"""Environment steps (throws) of every learning run on the id. Multiples of 512, so that PPO's
rollouts (8 envs x 64 steps; x 128 on pixels) end on the budget. On NetCatch-v0 PPO passed 95% at 12,288-16,384
steps (docs/AGENTS.md), SAC, TD3 and TQC at 2,000-4,000; on the windy id PPO needed ~40,000 for
95%. Measured on one core (2026-12-03, 4096 steps from scratch, training only): NetCatch-v0 PPO
273 steps/s, TD3 150, SAC 103, TQC 89; NetCatchWindy-v0 PPO 166, SAC 91; NetCatchPixels-v0
PPO-CNN 47. Taking a catching policy's later steps at 60% of those rates, the table of 5 seeds
is ~27,000 CPU seconds, ~3.8 hours on 2 cores (the limit: 6). NetCatchLongEpisode-v0 asks the
same aim as NetCatch-v0 into a fuller net, so it gets NetCatch-v0's budget; NetCatchRandomized-v1,
5 throws with feedback like the windy id, gets the windy id's. Pixels get NetCatch-v0's: the
asymmetric SAC (sac_asym.yml) caught every throw from 8,192 steps; PPO-CNN, which climbed only
slowly (ppo_cnn.yml), would need ~115 minutes a seed for 24x that, beyond the table's hours."""
TABLE_IDS = ("NetCatch-v0", "NetCatchGoal-v0", "NetCatchNoisy-v0", "NetCatchWindy-v0", "NetCatchPixels-v0",
             "NetCatchLongEpisode-v0", "NetCatchRandomized-v1")
"""The ids of the table (the default)."""
SEEDS = (0, 1, 2, 3, 4)
FINAL_EPISODES, FINAL_SEED = 100, 10_000
"""The final evaluation: episodes seeded 10000, 10001, ..., the same for every run of an id."""
CURVE_POINTS, CURVE_EPISODES, CURVE_SEED = 20, 10, 20_000
"""The learning curve: evaluated at step 0 and every budget / CURVE_POINTS steps on
CURVE_EPISODES episodes seeded from CURVE_SEED (not the final evaluation's)."""
QUICK_IDS, QUICK_SEEDS, QUICK_BUDGET = ("NetCatch-v0", "NetCatchGoal-v0"), (0,), 512
QUICK_ALGORITHMS = ("ppo", "sac", "td3", "tqc")
QUICK_EPISODES = 4


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
        """The arguments of ``python`` that run this run alone (if its result file is missing)."""
        longer = self.budget not in (0, table_budget(self.env_id, self.quick))
        return ["scripts/baselines.py", "--out", str(out), "--algos", self.algorithm, "--ids", self.env_id,
                "--seeds", str(self.seed), *(["--quick"] if self.quick else []),
                *(["--budget", str(self.budget)] if longer else [])]

    @property
    def cost(self) -> int:
        """Throws the run simulates, training and final evaluation (for progress estimates)."""
        return self.budget + self.final_episodes * netgym.balls_per_episode(self.env_id)


def table_budget(env_id: str, quick: bool = False) -> int:
    """The learners' steps on ``env_id`` under the table's protocol (its :data:`BUDGETS`, or
    :data:`QUICK_BUDGET` in quick mode)."""
    return QUICK_BUDGET if quick else BUDGETS[env_id]


def grid(algorithms: list[str] | None = None, ids: list[str] | None = None, seeds: list[int] | None = None,
         quick: bool = False, budget: int | None = None) -> list[Run]:
    """The runs of ``algorithms`` (default: all) on ``ids`` (default: :data:`TABLE_IDS`, in
    quick mode :data:`QUICK_IDS`) that each algorithm has settings for, one per seed (default:
    :data:`SEEDS`, quick :data:`QUICK_SEEDS`), and the reference runs of those ids (one each:
    their policies do not learn). ``quick``: :data:`QUICK_BUDGET` steps and
    :data:`QUICK_EPISODES` episodes, for smoke tests. ``budget``: the learners' steps instead of
    the ids' :data:`BUDGETS` (runs beyond the table's protocol, kept in a folder of their own)."""
    if budget is not None and (not isinstance(budget, int) or budget < 1):
        raise InvalidArgumentError(f"budget = {budget!r}; allowed: a positive number of environment steps")
    algorithms = list(algorithms or (QUICK_ALGORITHMS if quick else ALGORITHMS))
    ids = list(ids or (QUICK_IDS if quick else TABLE_IDS))
    for name, known, what in ((algorithms, ALGORITHMS, "algorithm"), (ids, BUDGETS, "env id")):
        if unknown := sorted(set(name) - set(known)):
            raise InvalidArgumentError(f"unknown {what}(s) {unknown}; one of {list(known)}")
    seeds = list(seeds if seeds is not None else (QUICK_SEEDS if quick else SEEDS))
    episodes = dict(final_episodes=QUICK_EPISODES, curve_episodes=2, quick=True) if quick else {}
    runs = [Run(reference, env_id, 0, 0, **episodes) for env_id in ids for reference in REFERENCES]
    for algorithm in algorithms:
        for env_id in (i for i in ids if i in env_ids(yml(algorithm))):
            steps = budget or table_budget(env_id, quick)
            runs += [Run(algorithm, env_id, seed, steps, **episodes) for seed in seeds]
    return runs
