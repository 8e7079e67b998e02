"""Rendering in every mode: shapes, dtypes, that the picture shows the scene, the GIF script."""

from __future__ import annotations

import math
import sys

import gymnasium as gym
import numpy as np
import pytest

import netgym  # noqa: F401
from netgym.aim import BallisticAim
from netgym.config import load_scene
from netgym.errors import InvalidArgumentError
from netgym.envs import NetCatchEnv
from netgym.envs.observation import aim_at_centre
from netgym.physics.film import Film, FrameClock
from netgym.physics.simulator import Simulator
from netgym.physics.throw import throw


@pytest.mark.parametrize("scene", ["basket", "goal"])
def test_rgb_array_frame(scene: str) -> None:
    env = gym.make("NetCatch-v0", scene=scene, render_mode="rgb_array")
    env.reset(seed=0)
    frame = env.render()
    h, w = frame.shape[:2]
    assert frame.shape == (360, 480, 3) and frame.dtype == np.uint8
    # the net is drawn in light grey (no blue cast, unlike the sky) and the poles in red over the
    # sky/ground background (anti-aliased: colours blend at the edges)
    rgb = frame.astype(int)
    grey = (rgb.min(axis=-1) > 150) & (np.ptp(rgb, axis=-1) < 20)
    assert np.sum(grey) > 500
    assert np.sum((rgb[..., 0] > 150) & (rgb[..., 1] < 90) & (rgb[..., 2] < 90)) > 100
    thrower = (rgb[..., 2] > 120) & (rgb[..., 0] < 90) & (rgb[..., 1] < 110)
    assert np.sum(thrower) > 50  # the thrower's figure, in blue
    empty = frame.copy()
    sim = env.unwrapped.sim
    centre = sim.model.geometry.positions.mean(axis=0)
    sim.launch_ball(centre, [0.0, 0.0, 0.0])
    with_ball = env.render()
    camera = env.unwrapped._renderer.camera
    _, depth = camera.project(centre[None])
    disc = math.pi * (camera.focal * sim.model.ball_radius / depth[0]) ** 2 / env.unwrapped._renderer.supersample ** 2
    assert np.sum(np.any(with_ball != empty, axis=-1)) > 0.5 * disc  # the ball shows (behind the net's strings)
    assert (h, w) == (360, 480)
    env.close()


def test_rgb_array_list_holds_the_frames_of_a_throw() -> None:
    env = gym.make("NetCatch-v0", render_mode="rgb_array_list").unwrapped
    obs, _ = env.reset(seed=1)
    aim = BallisticAim(env.scene)
    _, _, _, _, info = env.step(aim_at_centre(aim, obs))
    frames = env.render()
    expected = info["sim_time"] * env.metadata["render_fps"]
    assert len(frames) >= 0.8 * expected
    assert all(f.shape == (360, 480, 3) and f.dtype == np.uint8 for f in frames)
    assert env.render() == []  # frames are handed out once


@pytest.mark.parametrize("scene", ["basket", "goal"])
def test_the_camera_follows_a_high_throw_to_the_net(scene: str) -> None:
    """The frames of a throw frame its whole flight up to the net: a lob at the top speed and
    elevation of the scene's ranges from the farthest thrower stays in the picture (with the
    thrower) until it is past the net."""
    from netgym.view.framing import thrower_figure
    from netgym.view.render import throw_camera

    env = gym.make("NetCatch-v0", scene=scene, render_mode="replay_list").unwrapped
    t = env.scene.throw
    env.reset(seed=0, options={"thrower": {"distance": t.distance[1]}})
    launch = env.thrower.position
    _, _, _, _, info = env.step(np.array([1.0, 1.0, 0.0], dtype=np.float32))
    snapshots = env.render()
    camera = throw_camera(env.sim, launch, info["launch_velocity"], 480, 360)
    centre = env.sim.opening.centre
    past = float(np.linalg.norm((centre - launch)[:2])) + 0.5 * float(np.linalg.norm(
        np.subtract(env.scene.net.upper, env.scene.net.lower)[:2]))
    flight = np.array([s.balls[-1] for s in snapshots if len(s.balls)])
    flight = flight[np.linalg.norm((flight - launch)[:, :2], axis=1) <= past]
    assert len(flight) > 10 and flight[:, 2].max() > 5.0  # a high throw, filmed
    points = np.vstack([flight, thrower_figure(launch, centre).points])
    pixels, depth = camera.project(points)
    assert np.all(depth > 0) and np.all((pixels >= 0) & (pixels <= [480, 360]))
    env.close()


def test_captions_name_the_throw_and_its_outcome_once_decided() -> None:
    """EpisodeFilm captions every frame of a throw with its number, and with its outcome from
    the frame of its decision on; it holds the last frame; caption_frame writes the text."""
    from netgym.view.render import caption_frame
    from netgym.view.video import HOLD, EpisodeFilm

    fps = NetCatchEnv.metadata["render_fps"]
    film = EpisodeFilm(2, fps)
    film.start(["reset"])
    film.add_throw([f"a{i}" for i in range(30)], {"captured": True, "reason": "at_rest_in_net", "sim_time": 0.5})
    film.add_throw([f"b{i}" for i in range(10)], {"captured": False, "reason": "flies_away", "sim_time": 0.0})
    held = round(HOLD * fps)
    assert film.frames == ["reset"] + [f"a{i}" for i in range(30)] + ["a29"] * held + \
        [f"b{i}" for i in range(10)] + ["b9"] * held
    assert film.captions[:16] == ["throw 1/2"] * 16                  # the reset and 0.5 s of flight
    assert set(film.captions[16:31 + held]) == {"throw 1/2: caught (at rest in net)"}
    assert set(film.captions[31 + held:]) == {"throw 2/2: missed (flies away)"}
    frame = np.full((360, 480, 3), 128, dtype=np.uint8)
    captioned = caption_frame(frame, film.captions[-1])
    assert captioned.shape == frame.shape and np.any(captioned[:30, :200] != 128)
    assert np.array_equal(captioned[60:], frame[60:]) and caption_frame(frame, "") is frame


@pytest.mark.slow
def test_human_mode_runs_headless() -> None:
    pytest.importorskip("pygame")
    env = gym.make("NetCatch-v0", render_mode="human")
    env.unwrapped.metadata = dict(env.unwrapped.metadata, render_fps=1000)  # do not wait in tests
    env.reset(seed=0)
    assert env.render() is None
    env.step(np.zeros(3, dtype=np.float32))
    env.close()
    env.close()


def _episode(render_mode: str | None, render_settling: bool = False, scene: str = "basket") -> tuple[list, list]:
    """Steps of one seeded 4-ball episode (aimed, noisy aimed, random actions) and the frames of each."""
    env = gym.make("NetCatch-v0", scene=scene, balls_per_episode=4, render_mode=render_mode,
                   render_settling=render_settling).unwrapped
    obs, _ = env.reset(seed=5)
    aim, rng = BallisticAim(env.scene), np.random.default_rng(2)
    steps, frames = [], []
    for k in range(4):
        action = aim_at_centre(aim, obs) if k % 2 == 0 else rng.uniform(-1, 1, 3).astype(np.float32)
        obs, reward, _, _, info = env.step(action)
        s = env.sim.state
        steps.append((obs.tobytes(), reward, info["reason"], info["sim_time"], info["substeps"],
                      info["final_position"].tobytes(), s.x.tobytes(), s.v.tobytes(), s.time))
        frames.append(env.render() if render_mode == "rgb_array_list" else None)
    env.close()
    return steps, frames


@pytest.mark.slow
@pytest.mark.parametrize("scene", ["basket", "goal"])
def test_rendering_changes_nothing(scene: str) -> None:
    """Filming throws (and the settling) stops integration at frame instants, yet every outcome,
    substep count and the whole state stay bitwise those of the unrendered episode."""
    plain, _ = _episode(None, scene=scene)
    assert _episode("rgb_array_list", scene=scene)[0] == plain
    assert _episode("rgb_array_list", render_settling=True, scene=scene)[0] == plain


@pytest.mark.slow
def test_every_throw_is_filmed_at_render_fps() -> None:
    """Each step returns the frames of its throw from the launch, misses decided at launch too
    (their closed-form flight is drawn to the landing); settling frames only on request."""
    steps, frames = _episode("rgb_array_list")
    fps = NetCatchEnv.metadata["render_fps"]
    for (_, _, reason, sim_time, *_), throw_frames in zip(steps, frames):
        assert len(throw_frames) >= math.floor(sim_time * fps) + 1
        if reason == "flies_away":
            assert len(throw_frames) >= 10  # the flight to the ground, though decided early
    _, with_settling = _episode("rgb_array_list", render_settling=True)
    assert sum(map(len, with_settling)) > sum(map(len, frames))


def test_frames_are_one_period_apart() -> None:
    """Frame instants are exactly 1/fps apart: integration stops at the substep nearest each
    (within dt/2), closed-form flight at the instant itself; none is skipped or taken twice."""
    sim = Simulator(load_scene("basket"))
    clock = FrameClock(1.0 / 30.0)
    taken: list[float] = []

    film = Film(clock, lambda s: taken.append(s.state.time))
    for velocity in ([5.0, 0.0, 6.1], [2.0, 0.0, 3.0]):  # into the opening (caught); short of the net
        taken.clear()
        result = throw(sim, [-5.0, 0.0, 1.8], velocity, film=film)
        times = np.array(taken) - clock.anchor
        k = np.round(times * 30.0)
        assert np.array_equal(k, np.arange(len(k)))                    # every instant once, from the launch
        assert np.abs(times - k / 30.0).max() <= 0.5 * sim.dt + 1e-9
        assert len(k) >= math.floor(result.time * 30.0)


@pytest.mark.slow
def test_recorded_episode_video_holds_every_throw_at_render_fps(tmp_path) -> None:
    """RecordEpisodeVideo writes an MP4 per episode with every frame of every throw (and each
    throw's last frame held): its length is at least the simulated time of the throws at
    render_fps, played at render_fps."""
    imageio = pytest.importorskip("imageio.v2")
    from netgym.wrappers import RecordEpisodeVideo

    env = RecordEpisodeVideo(gym.make("NetCatch-v0", render_mode="rgb_array_list"), tmp_path,
                             episode_trigger=lambda episode: episode == 1)
    aim = BallisticAim(env.unwrapped.scene)
    simulated = []
    for episode in range(2):
        obs, _ = env.reset(seed=episode)
        done = False
        while not done:
            obs, _, terminated, truncated, info = env.step(aim_at_centre(aim, obs))
            if episode == 1:
                simulated.append(info["sim_time"])
            done = terminated or truncated
    assert [p.name for p in env.written] == ["netcatch-episode-1.mp4"]   # the trigger picked episode 1 only
    reader = imageio.get_reader(env.written[0])
    frames = [frame for frame in reader]
    fps = NetCatchEnv.metadata["render_fps"]
    assert reader.get_meta_data()["fps"] == fps
    assert len(frames) >= 1 + sum(math.floor(t * fps) + 1 for t in simulated)
    assert frames[0].shape == (360, 480, 3)
    env.close()


def test_human_mode_without_a_display_says_so_at_the_first_render(monkeypatch: pytest.MonkeyPatch) -> None:
    """No display named (and no SDL driver chosen): the first render (human mode renders from
    reset on) names what is missing and what to use instead, rather than drawing into SDL's
    silent off-screen fallback."""
    pytest.importorskip("pygame")
    for name in ("DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER"):
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setattr(sys, "platform", "linux")
    env = gym.make("NetCatch-v0", render_mode="human")
    with pytest.raises(InvalidArgumentError, match=r'render_mode="human" needs a display.*DISPLAY.*"rgb_array"'):
        env.reset(seed=0)  # human mode renders from reset on
    env.close()
