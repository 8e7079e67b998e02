"""What users pay: a single throw, 3-ball episodes with the ballistic oracle and with the shipped
PPO model, an episode of every id with its shipped model, and a reset of each id. Each timed
call is the same seeded episode, policy included (as an evaluation pays it)."""

from __future__ import annotations

from benchmarks.compat import IDS, oracle_for, run_episode, shipped_policy

SEED = 7


def _make(env_id: str, **kwargs):
    import gymnasium as gym

    import netgym  # noqa: F401  (registers the ids)

    try:
        return gym.make(env_id, disable_env_checker=True, **kwargs)
    except gym.error.Error as missing:
        raise NotImplementedError(f"this tree has no {env_id}: {missing}")


class OracleThrow:
    """A reset of NetCatch-v0 and one oracle throw into its empty basket."""

    def setup(self) -> None:
        self.env = _make("NetCatch-v0")
        obs, _ = self.env.reset(seed=SEED)
        self.action = oracle_for(self.env).predict(obs)[0]
        self.time_oracle_throw_into_empty_basket()

    def time_oracle_throw_into_empty_basket(self) -> None:
        self.env.reset(seed=SEED)
        self.env.step(self.action)


class BasketEpisodes:
    """A 3-ball NetCatch-v0 episode: every ball caught, the loaded net settling between throws."""

    params = ["oracle", "shipped PPO"]
    param_names = ["policy"]

    def setup(self, policy: str) -> None:
        if policy == "oracle":
            self.env = _make("NetCatch-v0")
            self.policy = oracle_for(self.env)
        else:
            env_id, self.policy = shipped_policy("NetCatch-v0")
            self.env = _make(env_id)
        run_episode(self.env, self.policy, SEED)

    def time_episode(self, policy: str) -> None:
        run_episode(self.env, self.policy, SEED)


class EveryIdEpisode:
    """An episode of every id with the model shipped for it."""

    params = list(IDS)
    param_names = ["env_id"]
    timeout = 300

    def setup(self, env_id: str) -> None:
        acting_id, self.policy = shipped_policy(env_id)
        self.env = _make(acting_id)
        run_episode(self.env, self.policy, SEED)

    def time_episode(self, env_id: str) -> None:
        run_episode(self.env, self.policy, SEED)


class Reset:
    """A seeded reset of every id (a new episode's scene: draws, net family, first thrower)."""

    params = list(IDS)
    param_names = ["env_id"]

    def setup(self, env_id: str) -> None:
        self.env = _make(env_id)
        self.env.reset(seed=SEED)

    def time_reset(self, env_id: str) -> None:
        self.env.reset(seed=SEED)
