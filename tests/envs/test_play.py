"""Keyboard play (netgym.play), driven headless by synthetic pygame key events."""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest

pygame = pytest.importorskip("pygame")

from netgym.physics.simulator import Simulator  # noqa: E402
from netgym.play import STEP, Play  # noqa: E402
from netgym.view.render import Renderer  # noqa: E402

DISPLAY_VARIABLES = ("DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER")


def _key(key: int):
    return pygame.event.Event(pygame.KEYDOWN, key=key)


@pytest.mark.slow
def test_keys_aim_throw_score_and_quit() -> None:
    play = Play(balls=2, seed=0)
    play.env.metadata = dict(play.env.metadata, render_fps=1000)  # do not wait in tests
    for key in (pygame.K_UP, pygame.K_UP, pygame.K_w, pygame.K_LEFT):
        play.handle(_key(key))
    assert list(play.action) == pytest.approx([2 * STEP, STEP, STEP])
    assert "speed 10.6 m/s" in play.title()                   # 4..16 m/s, 0.1 of the way up from the middle
    play.handle(_key(pygame.K_SPACE))
    play.handle(_key(pygame.K_SPACE))
    play.handle(_key(pygame.K_SPACE))                         # the episode has ended: nothing happens
    assert play.throws == 2 and f"caught {play.caught}/2 of 2" in play.title()
    play.handle(_key(pygame.K_r))
    assert play.throws == 0 and play.caught == 0
    for _ in range(50):
        play.handle(_key(pygame.K_DOWN))
    assert play.action[0] == -1.0                             # clipped to the action space
    play.handle(_key(pygame.K_ESCAPE))
    assert not play.running
    play.env.close()


@pytest.mark.parametrize("setting", [{}, {"SDL_VIDEODRIVER": "x11"}], ids=["no display named", "SDL video fails"])
def test_play_without_a_display_says_so_and_exits(setting: dict[str, str]) -> None:
    env = {k: v for k, v in os.environ.items() if k not in DISPLAY_VARIABLES} | setting
    result = subprocess.run([sys.executable, "-m", "netgym.play"], env=env, capture_output=True, text=True, timeout=60)
    assert result.returncode != 0
    assert "netgym.play needs a display" in result.stderr and "ALSA" not in result.stdout + result.stderr


def test_the_window_starts_no_audio(basket: Simulator, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("SDL_AUDIODRIVER", "dummy")  # audio that would start anywhere, sound card or not
    renderer = Renderer(basket, 32, 24, human=True, supersample=1)
    renderer.show(np.zeros((24, 32, 3), dtype=np.uint8))
    assert pygame.display.get_init() and not pygame.mixer.get_init()
    renderer.close()
