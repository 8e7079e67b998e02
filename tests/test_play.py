"""Keyboard play (netgym.play), driven headless by synthetic pygame key events."""

from __future__ import annotations

import os

import pytest

pygame = pytest.importorskip("pygame")
os.environ.setdefault("SDL_VIDEODRIVER", "dummy")

from netgym.play import STEP, Play  # noqa: E402


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
