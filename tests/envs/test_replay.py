"""Episode replays: the ``replay_list`` snapshots, the self-contained 3D page, and the page in a
real browser (headless Chromium: it must show the net)."""

from __future__ import annotations

import re
import shutil
import subprocess
import tempfile
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

import netgym  # noqa: F401
from netgym.aim import BallisticAim
from netgym.envs.observation import aim_at_centre
from netgym.view.replay import Snapshot
from netgym.view.video import write_video
from netgym.wrappers import RecordEpisodeVideo

pytest.importorskip("plotly")


def _steps(render_mode: str, throws: int = 2) -> list[list]:
    """What ``render()`` hands out after the reset and after each aimed throw of a seeded episode."""
    env = gym.make("NetCatch-v0", balls_per_episode=throws, render_mode=render_mode, render_settling=True).unwrapped
    obs, _ = env.reset(seed=3)
    start = env.sim.state.x.copy()
    out = [env.render()]
    aim = BallisticAim(env.scene)
    for _ in range(throws):
        obs, *_ = env.step(aim_at_centre(aim, obs))
        out.append(env.render())
    out.append(start)
    env.close()
    return out


@pytest.mark.slow
def test_snapshots_are_taken_at_the_frame_instants() -> None:
    """replay_list takes a snapshot wherever rgb_array_list draws a frame, 1 / render_fps
    simulated seconds apart; the reset's is the state the episode starts from."""
    *snapshots, start = _steps("replay_list")
    *frames, _ = _steps("rgb_array_list")
    assert [len(s) for s in snapshots] == [len(f) for f in frames]
    assert all(isinstance(s, Snapshot) for step in snapshots for s in step)
    first = snapshots[0][0]
    assert len(first.balls) == 0 and np.allclose(first.net, start, atol=1e-6)
    times = [s.time for s in snapshots[1]]
    assert np.allclose(np.diff(times)[:10], 1.0 / 30.0, atol=0.01)


def _page(tmp_path: Path) -> Path:
    env = RecordEpisodeVideo(gym.make("NetCatch-v0", balls_per_episode=2, render_mode="replay_list",
                                      render_settling=True), tmp_path, video_format="html")
    aim = BallisticAim(env.unwrapped.scene)
    obs, _ = env.reset(seed=3)
    done = False
    while not done:
        obs, _, terminated, truncated, _ = env.step(aim_at_centre(aim, obs))
        done = terminated or truncated
    env.close()
    assert [p.name for p in env.written] == ["netcatch-episode-0.html"]
    return env.written[0]


@pytest.fixture(scope="module")
def page(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return _page(tmp_path_factory.mktemp("replay"))


def test_page_is_self_contained_with_frames_and_outcomes(page: Path) -> None:
    """The page loads nothing from the network, embeds plotly.js, and holds the frames, the
    time slider, play/pause and each throw's caption with its outcome."""
    html = page.read_text().replace("\\u002f", "/")  # JSON in a script escapes "/"
    assert not re.search(r"<(script|link)[^>]+(src|href)=[\"']?(https?:)?//", html)
    assert "Plotly.newPlot" in html and "plotly.js v" in html     # the library itself, inline
    assert html.count('"traces":[2,3,4,5]') > 30                  # the animation's frames
    for text in ('"label":"Play"', '"label":"Pause"', '"sliders"', "throw 1/2", "throw 2/2: caught ("):
        assert text in html
    assert page.stat().st_size < 10e6


def test_a_page_needs_snapshots_and_the_wrapper_the_matching_mode(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="replay_list"):
        write_video([np.zeros((4, 4, 3), np.uint8)], tmp_path / "a.html", 30)
    with pytest.raises(ValueError, match="render_mode='replay_list'"):
        RecordEpisodeVideo(gym.make("NetCatch-v0", render_mode="rgb_array_list"), tmp_path, video_format="html")
    with pytest.raises(ValueError, match="video_format"):
        RecordEpisodeVideo(gym.make("NetCatch-v0", render_mode="rgb_array_list"), tmp_path, video_format="webm")


def _chromium(page: Path, *args: str, width: int = 1000) -> str:
    """Open ``page`` in headless Chromium, ``width`` x 800 pixels, with ``args``; its stdout."""
    with tempfile.TemporaryDirectory() as profile:
        return subprocess.run(["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader",
                               "--disable-quic", "--no-first-run", "--disable-background-networking",
                               "--disable-component-update", "--disable-sync", f"--user-data-dir={profile}", *args,
                               f"--window-size={width},800", "--virtual-time-budget=15000", page.resolve().as_uri()],
                              check=True, capture_output=True, text=True, timeout=120).stdout


def screenshot(page: Path, png: Path) -> np.ndarray:
    """A 1000 x 800 screenshot of ``page`` in headless Chromium, as an (H, W, 3) array."""
    from PIL import Image

    _chromium(page, f"--screenshot={png}")
    with Image.open(png) as image:
        return np.asarray(image.convert("RGB")).astype(int)


def near(colour: str, region: np.ndarray, tolerance: int = 30) -> int:
    """How many pixels of ``region`` are within ``tolerance`` of ``colour`` ("rgb(r, g, b)")."""
    rgb = np.array([int(v) for v in re.findall(r"\d+", colour)])
    return int(np.sum(np.abs(region - rgb).max(axis=-1) <= tolerance))


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("chromium") is None, reason="chromium is not on PATH (apt-get install chromium)")
def test_page_shows_the_net_in_a_browser(page: Path, tmp_path: Path) -> None:
    """Opened from a file:// URL with no network, the page draws the 3D scene: the sky-coloured
    scene, the dark net strings in its middle, the red poles, the green ground; the scene fills
    the window to its edge (no margin, no scrollbar)."""
    from netgym.view.replay_page import GROUND_COLOUR, NET_COLOUR, POLE_COLOUR, SKY_COLOUR

    image = screenshot(page, tmp_path / "replay.png")
    scene = image[80:540, 20:980]
    assert len(np.unique(scene.reshape(-1, 3), axis=0)) > 50            # not blank
    assert near(SKY_COLOUR, scene, 5) > 0.3 * scene.shape[0] * scene.shape[1]
    assert near(GROUND_COLOUR, scene) > 5000
    assert near(POLE_COLOUR, scene, 40) > 500
    middle = image[200:500, 300:700]
    assert near(NET_COLOUR, middle) > 1500                              # the net's strings
    edge = image[80:200, -3:]
    assert near(SKY_COLOUR, edge, 5) == edge.shape[0] * edge.shape[1]


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("chromium") is None, reason="chromium is not on PATH (apt-get install chromium)")
def test_the_controls_keep_apart_on_a_narrow_page(page: Path) -> None:
    """On a page 480 pixels wide, the Play/Pause buttons and the time slider (its "t = ..."
    label, its rail) do not overlap, as plotly lays them out."""
    dom = _chromium(page, "--dump-dom", width=480)
    number = r"([\d.]+)"
    buttons = [(float(x), float(y), float(x) + float(w), float(y) + float(h)) for x, y, w, h in re.findall(
        rf'class="updatemenu-button" transform="translate\({number},{number}\)"><rect[^>]* width="{number}" '
        rf'height="{number}"', dom)]
    x, y = map(float, re.search(rf'class="slider-group" transform="translate\({number},{number}\)"', dom).groups())
    width, height, top = map(float, re.search(rf'class="slider-rail-touch-rect" width="{number}" height="{number}" '
                                              rf'opacity="0" transform="translate\(0,{number}\)"', dom).groups())
    slider = (x, y, x + width, y + top + height)
    assert len(buttons) == 2
    for left, upper, right, lower in buttons:
        assert right <= slider[0] or left >= slider[2] or lower <= slider[1] or upper >= slider[3]
