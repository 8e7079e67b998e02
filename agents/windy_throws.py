"""Capture rates by throw index on NetCatchWindy-v0, and the best fixed first throw.

An episode of NetCatchWindy-v0 blows one hidden wind (0-3 m/s, any direction) on its 5 throws;
from throw 2 on, the observation carries the previous throw's feedback, so a policy can learn
the wind within the episode. Throw 1 can know the thrower only. :func:`per_throw_rates`
evaluates the oracles and the shipped PPO models by throw index; :func:`search_first_throw`
searches the blind aim (:class:`FirstThrowAim`: the elevation by the thrower's distance, and the
aim point moved along and across the throw) that catches the most first throws over the wind
prior, on training episodes, and :func:`measure` reports it on the held-out ones: what a policy
that knows the thrower but not the wind reaches on throw 1 with this family of aims.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from tqdm import tqdm

from agents.baselines.grid import FINAL_SEED
from agents.evaluation import CaptureRate, Policy, evaluate
from agents.oracle import AdaptiveOracle, BallisticOracle, InformedOracle
from agents.policies import PRETRAINED, PRETRAINED_WINDY, PRETRAINED_WINDY_STACKED, SHIPPED_BASELINES, policy_in_env
from netgym.bench.results import RESULTS, read_results
from netgym.config import SceneConfig
from netgym.envs import NetCatchEnv

WINDY = "NetCatchWindy-v0"
FIRST_THROW = {"balls_per_episode": 1}
"""The fast path to the first throws: an episode of one throw draws the same wind and thrower
from its seed, and no settling pause follows its throw."""


@dataclass(frozen=True)
class FirstThrowAim:
    """A blind aim: the steepest elevation tried (degrees; the blind oracle's is 75), linear in
    the thrower's distance from ``near`` at the scene's nearest to ``far`` at its farthest, and
    the aim point moved from the opening's centre ``along`` the throw (m, away from the
    thrower) and ``across`` it (m, to the thrower's left)."""

    near: float
    far: float
    along: float = 0.0
    across: float = 0.0

    def moved(self, coordinate: int, step: float) -> "FirstThrowAim":
        """This aim with its ``coordinate``-th field (near, far, along, across) moved by ``step``."""
        values = list(dataclasses.astuple(self))
        values[coordinate] = round(values[coordinate] + step, 6)
        return FirstThrowAim(*values)

    def __str__(self) -> str:
        return (f"elevation {self.near:g}-{self.far:g} deg from the nearest to the farthest thrower, aim point "
                f"{self.along:+.3f} m along, {self.across:+.3f} m left")


BLIND_AIM = FirstThrowAim(75.0, 75.0)
"""The blind oracle's aim (:class:`~agents.oracle.BallisticOracle`'s defaults)."""


class AimedOracle(BallisticOracle):
    """The blind oracle (knows the drag, not the wind) aiming as a :class:`FirstThrowAim` says."""

    def __init__(self, scene: SceneConfig, aim: FirstThrowAim) -> None:
        super().__init__(scene)
        self.aim_of_throw = aim

    def act(self, row: np.ndarray) -> np.ndarray:
        """Aim through the air, without wind, at the moved aim point, no steeper than the aim's
        elevation at the thrower's distance."""
        thrower, aim = self.thrower_of(row), self.aim_of_throw
        nearest, farthest = self.scene.throw.distance
        self.max_elevation = float(np.interp(thrower.distance, (nearest, farthest), (aim.near, aim.far)))
        cos, sin = math.cos(thrower.facing), math.sin(thrower.facing)
        target = self.opening.centre + aim.along * np.array([cos, sin, 0.0]) + aim.across * np.array([-sin, cos, 0.0])
        return self.aim(thrower, target)


@dataclass(frozen=True)
class SearchPlan:
    """How the best fixed first throw is searched: on ``episodes`` training episodes seeded
    ``seed, seed + 1, ...``, the grid of ``elevations`` for the nearest x ``elevations`` for
    the farthest thrower (the aim point at the centre), then ``rounds`` rounds of local
    refinement around the best, each trying every field of the aim moved by +- its step
    (``steps``: near, far, along, across), the steps halved after each round."""

    episodes: int = 1000
    seed: int = 0
    elevations: tuple[float, ...] = (25.0, 30.0, 35.0, 40.0, 45.0, 50.0, 55.0, 60.0, 65.0, 70.0, 75.0)
    rounds: int = 4
    steps: tuple[float, float, float, float] = (2.5, 2.5, 0.125, 0.125)

    @property
    def trials(self) -> int:
        """How many aims the search evaluates at the most (fewer when the refinement meets aims
        already tried)."""
        return len(self.elevations) ** 2 + 2 * len(self.steps) * self.rounds


QUICK_PLAN = SearchPlan(episodes=3, elevations=(50.0, 75.0), rounds=1)
"""A search of seconds, for smoke tests."""


@dataclass(frozen=True)
class FirstThrowSearch:
    """What :func:`search_first_throw` found: the ``best`` aim and the first throws each aim
    tried caught (``tried``) out of the plan's episodes."""

    plan: SearchPlan
    best: FirstThrowAim
    tried: dict[FirstThrowAim, int]

    def record(self) -> dict[str, Any]:
        """JSON-ready: the plan, the best aim and its captures, the blind oracle's, every aim tried."""
        return {"plan": dataclasses.asdict(self.plan), "best": dataclasses.asdict(self.best),
                "best_captured": self.tried[self.best], "blind_captured": self.tried.get(BLIND_AIM),
                "tried": [{**dataclasses.asdict(aim), "captured": n} for aim, n in self.tried.items()]}


def first_throw_rate(aim: FirstThrowAim, episodes: int, seed: int) -> CaptureRate:
    """The first throws of ``episodes`` seeded episodes of NetCatchWindy-v0 that ``aim`` catches."""
    return evaluate(lambda env: AimedOracle(env.scene, aim), episodes, seed=seed, env_id=WINDY, **FIRST_THROW)


def search_first_throw(plan: SearchPlan = SearchPlan(), progress: bool = True) -> FirstThrowSearch:
    """The aim that catches the most first throws of the plan's training episodes: the best of
    the grid (which holds the blind oracle's aim when it holds 75 degrees), refined
    locally; a tie keeps the aim found first. With ``progress``, a bar with ETA on stderr."""
    tried: dict[FirstThrowAim, int] = {}
    bar = tqdm(total=plan.trials, desc="first-throw search", unit="aim", disable=not progress)

    def captures(aim: FirstThrowAim) -> int:
        if aim not in tried:
            tried[aim] = first_throw_rate(aim, plan.episodes, plan.seed).captured
            bar.update()
        return tried[aim]

    best = max((FirstThrowAim(near, far) for near in plan.elevations for far in plan.elevations), key=captures)
    steps = plan.steps
    for _ in range(plan.rounds):
        around = [best.moved(k, sign * step) for k, step in enumerate(steps) for sign in (-1, 1)]
        best = max([best, *around], key=captures)
        steps = tuple(step / 2 for step in steps)
    bar.close()
    return FirstThrowSearch(plan, best, tried)


def windy_policies() -> dict[str, Policy | Callable[[NetCatchEnv], Policy]]:
    """The policies evaluated by throw index, by label (loading the shipped PPO models and the
    shipped baselines of the windy task)."""
    baselines = {}
    for name, run in SHIPPED_BASELINES.items():
        record = read_results(RESULTS / f"{run}.json")["figures"]
        if record["env_id"] == WINDY:
            label = f"{record['algorithm']} {name} (baseline, {record['budget']:,} steps)"
            baselines[label] = policy_in_env(PRETRAINED.parent / name, WINDY)[1]
    return {"informed oracle (knows the wind)": InformedOracle,
            "blind oracle (ignores the wind)": lambda env: BallisticOracle(env.scene),
            "adaptive oracle (uses the feedback)": lambda env: AdaptiveOracle(env.scene),
            "PPO ppo_windy.zip (the feedback)": policy_in_env(PRETRAINED_WINDY, WINDY)[1],
            "PPO ppo_windy_stack5.zip (5 stacked observations)": policy_in_env(PRETRAINED_WINDY_STACKED, WINDY)[1],
            **baselines}


def per_throw_rates(episodes: int, seed: int = FINAL_SEED, progress: bool = True) -> dict[str, CaptureRate]:
    """Each of :func:`windy_policies` evaluated on ``episodes`` seeded episodes of
    NetCatchWindy-v0, captures counted by throw index."""
    return {label: evaluate(policy, episodes, seed=seed, progress=label if progress else None, env_id=WINDY)
            for label, policy in windy_policies().items()}


def measure(episodes: int, plan: SearchPlan = SearchPlan(), progress: bool = True) -> dict[str, Any]:
    """The result file's figures: every policy's captures by throw index on ``episodes``
    held-out episodes (seeded from :data:`~agents.baselines.grid.FINAL_SEED`, the baselines'),
    and the best fixed first throw, searched on ``plan``'s training episodes and evaluated on
    the held-out ones; with the seconds each part took."""
    clock = time.perf_counter()
    rates = per_throw_rates(episodes, progress=progress)
    evaluated = time.perf_counter()
    search = search_first_throw(plan, progress=progress)
    searched = time.perf_counter()
    first = first_throw_rate(search.best, episodes, FINAL_SEED)
    rates[f"best fixed first throw ({search.best})"] = first
    return {"env_id": WINDY, "episodes": episodes, "seed": FINAL_SEED,
            "rows": [{"policy": label, **dataclasses.asdict(rate)} for label, rate in rates.items()],
            "first_throw_search": search.record(),
            "wall_s": {"policies": evaluated - clock, "search": searched - evaluated,
                       "total": time.perf_counter() - clock}}


def _percent(rate: float | None) -> str:
    return "-" if rate is None else f"{100 * rate:.1f}%"


def table(figures: dict[str, Any]) -> str:
    """Markdown: each row's capture rate at throw 1, 2, ..., over throws 2 on and over all
    throws (``-`` where the row has no such throws: the best fixed first throw's)."""
    rates = [CaptureRate(row["captured"], row["throws"], row["low"], row["high"], tuple(row["by_throw"]),
                         row["episodes"]) for row in figures["rows"]]
    throws = max(len(rate.by_throw) for rate in rates)
    lines = ["| policy | " + " | ".join(f"throw {k + 1}" for k in range(throws)) + f" | throws 2-{throws} | all |",
             "|---|" + "---:|" * (throws + 2)]
    for row, rate in zip(figures["rows"], rates):
        whole = len(rate.by_throw) == throws
        cells = [*rate.rate_by_throw, *[None] * (throws - len(rate.by_throw)),
                 sum(rate.by_throw[1:]) / (rate.episodes * (throws - 1)) if whole else None,
                 rate.rate if whole else None]
        lines.append(f"| {row['policy']} | " + " | ".join(_percent(cell) for cell in cells) + " |")
    return "\n".join(lines)


def search_summary(figures: dict[str, Any]) -> str:
    """One paragraph: how the best fixed first throw was searched and what it caught on the
    training episodes, beside the blind oracle's aim."""
    search = figures["first_throw_search"]
    plan, episodes = search["plan"], figures["episodes"]
    grid = len(plan["elevations"])
    return (f"The best fixed first throw is the blind aim, of {len(search['tried'])} tried ({grid} x {grid} "
            f"elevations for the nearest and the farthest thrower, {plan['elevations'][0]:g}-"
            f"{plan['elevations'][-1]:g} degrees, then {plan['rounds']} rounds of local refinement that also move "
            f"the aim point), that caught the most first throws of {plan['episodes']} training episodes (seeds "
            f"{plan['seed']}-{plan['seed'] + plan['episodes'] - 1}): {search['best_captured']} of them, the blind "
            f"oracle's aim {search['blind_captured']}. Its row is its first throws of the held-out episodes: "
            f"{episodes} for every row, seeds {figures['seed']}-{figures['seed'] + episodes - 1}.")
