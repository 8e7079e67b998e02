"""An episode's trajectory for replays: the 3D positions of the net and the balls at each frame
instant, instead of pixels.

``NetCatchEnv(render_mode="replay_list")`` takes a :class:`Snapshot` wherever
``rgb_array_list`` would draw a frame (the same instants, ``1 / render_fps`` simulated seconds
apart), and ``render()`` hands them out as it does frames. What does not move in an episode
(the springs drawn, the poles, the ball radius) is the snapshots' shared :class:`Scenery`.
:func:`netgym.view.video.write_video` turns them into a 3D page (``.html``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from netgym.physics.simulator import Simulator


@dataclass(frozen=True, eq=False)
class Scenery:
    """What stays put through an episode: ``segments`` (s, 2) net particle pairs drawn as
    strings, ``poles`` (p, 2, 3) end points, the ``ball_radius`` and the opening's ``centre``."""

    segments: np.ndarray
    poles: np.ndarray
    ball_radius: float
    centre: np.ndarray

    @classmethod
    def of(cls, sim: Simulator) -> "Scenery":
        """The scenery of ``sim``'s scene."""
        m = sim.model
        return cls(m.segments.copy(), np.stack([m.poles.start, m.poles.end], axis=1), float(m.ball_radius),
                   np.array(sim.opening.centre, dtype=float))


@dataclass(frozen=True, eq=False)
class Snapshot:
    """The scene at simulated ``time``: ``net`` (n, 3) particle and ``balls`` (k, 3) centre
    positions (float32), the release point of the ``thrower`` (None: none yet), and ``scenery``."""

    time: float
    net: np.ndarray
    balls: np.ndarray
    thrower: np.ndarray | None
    scenery: Scenery

    @classmethod
    def of(cls, sim: Simulator, scenery: Scenery, thrower: np.ndarray | None) -> "Snapshot":
        """The snapshot of ``sim`` now (``scenery``: :meth:`Scenery.of` the same simulator)."""
        x, n = sim.state.x, sim.model.n_net
        return cls(float(sim.state.time), x[:n].astype(np.float32), x[n:].astype(np.float32),
                   None if thrower is None else np.array(thrower, dtype=float), scenery)
