"""Play NetCatch-v0 yourself: aim, throw, watch the net.

``python -m netgym.play [--scene goal] [--balls 5] [--seed 0]`` opens a window (``render``
extra); without a display it says so and exits. Keys:

| key | does |
|---|---|
| Up / Down | launch speed up / down |
| W / S | elevation up / down |
| Left / Right | aim left / right (azimuth offset) |
| Space | throw |
| R | new episode |
| Esc or closing the window | quit |

The window title shows the aim (speed, elevation, azimuth) and the score. Each throw is shown
as it is simulated, frames ``1 / render_fps`` simulated seconds apart.
"""

from __future__ import annotations

import argparse
import os
import sys
from typing import Any

import numpy as np

from netgym.envs import NetCatchEnv
from netgym.launch import action_to_launch
from netgym.view.render import display_problem

STEP = 0.05   # change of an action component per key press (the action spans [-1, 1])


class Play:
    """Keyboard play of one env in ``human`` render mode: :meth:`handle` takes pygame events."""

    def __init__(self, scene: str = "basket", balls: int = 3, seed: int | None = None) -> None:
        self.env = NetCatchEnv(scene=scene, balls_per_episode=balls, render_mode="human")
        self.action = np.zeros(3, dtype=np.float32)
        self.caught = self.throws = 0
        self.running = True
        self._seed = seed
        self.new_episode()

    def new_episode(self) -> None:
        """Reset the env and the score."""
        self.env.reset(seed=self._seed)
        self._seed = None  # later episodes draw new throwers
        self.caught = self.throws = 0
        self.env.render()

    def title(self) -> str:
        """The aim and the score, for the window title."""
        speed, elevation, azimuth = action_to_launch(self.action, self.env.scene.throw)
        return (f"NetCatch: speed {speed:.1f} m/s, elevation {elevation:.0f} deg, aim {azimuth:+.0f} deg | "
                f"caught {self.caught}/{self.throws} of {self.env.balls_per_episode} | space: throw, R: new, Esc: quit")

    def handle(self, event: Any) -> None:
        """Act on one pygame event."""
        import pygame

        if event.type == pygame.QUIT or (event.type == pygame.KEYDOWN and event.key == pygame.K_ESCAPE):
            self.running = False
            return
        if event.type != pygame.KEYDOWN:
            return
        changes = {pygame.K_UP: (0, STEP), pygame.K_DOWN: (0, -STEP), pygame.K_w: (1, STEP), pygame.K_s: (1, -STEP),
                   pygame.K_LEFT: (2, STEP), pygame.K_RIGHT: (2, -STEP)}
        if event.key in changes:
            index, delta = changes[event.key]
            self.action[index] = np.clip(self.action[index] + delta, -1.0, 1.0)
        elif event.key == pygame.K_SPACE and self.throws < self.env.balls_per_episode:
            _, _, _, _, info = self.env.step(self.action)
            self.throws += 1
            self.caught += int(info["captured"])
        elif event.key == pygame.K_r:
            self.new_episode()
        pygame.display.set_caption(self.title())

    def run(self) -> None:
        """The event loop, until Esc or the window closes."""
        import pygame

        pygame.display.set_caption(self.title())
        clock = pygame.time.Clock()
        while self.running:
            for event in pygame.event.get():
                self.handle(event)
            clock.tick(self.env.metadata["render_fps"])
        self.env.close()


def main() -> None:
    """Parse arguments and play."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scene", default="basket")
    parser.add_argument("--balls", type=int, default=3)
    parser.add_argument("--seed", type=int, default=None)
    args = parser.parse_args()
    os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
    problem = display_problem()
    if problem is not None:
        sys.exit(f"python -m netgym.play needs a display for its window: {problem}. "
                 "Run it on a desktop session (or over ssh -X).")
    Play(args.scene, args.balls, args.seed).run()


if __name__ == "__main__":
    main()
