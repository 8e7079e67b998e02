"""One episode filmed under a policy: the frames (or 3D snapshots) of every throw, captioned,
for ``scripts/render_throw.py``."""

from __future__ import annotations

import gymnasium as gym

import netgym  # noqa: F401  (registers NetCatch-v0)
from agents.policies import load_policy
from netgym.view.video import EpisodeFilm


def record(scene: str, seed: int, throws: int, policy: str, algorithm: str | None = None, settling: bool = True,
           render_mode: str = "rgb_array_list") -> EpisodeFilm:
    """The film of one episode of ``throws`` throws by ``policy`` (``oracle``, ``random`` or a
    saved model): images (``render_mode="rgb_array_list"``) or 3D snapshots (``"replay_list"``)."""
    env = gym.make("NetCatch-v0", scene=scene, balls_per_episode=throws, render_mode=render_mode,
                   render_settling=settling)
    agent = load_policy(policy, scene, algorithm)
    film = EpisodeFilm(throws, env.metadata["render_fps"])
    obs, _ = env.reset(seed=seed)
    film.start(env.render())
    for _ in range(throws):
        obs, reward, terminated, _, info = env.step(agent.predict(obs, deterministic=True)[0])
        throw_frames = env.render()
        film.add_throw(throw_frames, info)
        print(f"throw {film.done}/{throws}: {'captured' if info['captured'] else 'missed'} ({info['reason']}, "
              f"{info['sim_time']:.2f} s simulated, {info['substeps']} substeps, {len(throw_frames)} frames)")
    env.close()
    return film
