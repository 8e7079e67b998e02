"""An episode as one self-contained 3D web page (plotly, its JavaScript embedded: no network).

The net's strings, the poles, the ground, the balls and the thrower, frame by frame, with
orbit and zoom (plotly's 3D scene), play/pause buttons, a time slider and each frame's caption
(which throw, and its outcome once decided) as the title. To keep the file small, frames are
thinned to at most ``MAX_FPS`` a simulated second (every caption change kept) and coordinates
rounded to the centimetre; the net's springs are drawn as a few long polylines, not segment by
segment. The embedded plotly.js is most of a short episode's file.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from netgym.errors import InvalidArgumentError
from netgym.view.framing import side_view, thrower_figure
from netgym.view.replay import Scenery, Snapshot

MAX_FPS = 15             # frames a simulated second the page keeps at most
DECIMALS = 2             # coordinates rounded to the centimetre
NET_COLOUR = "rgb(45, 45, 45)"
POLE_COLOUR = "rgb(200, 40, 40)"
BALL_COLOUR = "rgb(240, 140, 30)"
THROWER_COLOUR = "rgb(40, 60, 170)"
GROUND_COLOUR = "rgb(96, 150, 88)"
SKY_COLOUR = "rgb(215, 230, 245)"
EYE_DISTANCE = 0.9      # of the scene box's longest side, from its centre
MOVING_TRACES = [2, 3, 4, 5]   # net, balls, thrower's limbs, thrower's head; 0 and 1 (ground, poles) stay
SLIDER_PAD = 50          # px from the scene's bottom to the time slider's row (its "t = ..." label, its rail)
BUTTONS_PAD = 10         # px from the scene's bottom to the Play/Pause row, above the slider's
PAGE = """<!doctype html>
<html>
<head>
<meta charset="utf-8">
<title>netgym episode replay</title>
<style>html, body {{height: 100%; margin: 0;}}</style>
</head>
<body>
{figure}
</body>
</html>
"""
"""The page around the figure: the figure fills the window, which never scrolls."""


def net_strings(segments: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """The net's ``segments`` (s, 2) as polylines: particle indices, -1 between two lines.
    Each segment is in exactly one line; a line goes on as straight as it can (by ``positions``)."""
    neighbours: dict[int, list[tuple[int, int]]] = {}
    for edge, (a, b) in enumerate(segments.tolist()):
        neighbours.setdefault(a, []).append((b, edge))
        neighbours.setdefault(b, []).append((a, edge))
    used = np.zeros(len(segments), dtype=bool)
    left = {v: len(n) for v, n in neighbours.items()}
    starts = sorted(neighbours, key=lambda v: (len(neighbours[v]) % 2 == 0, v))  # odd degree first
    order: list[int] = []
    for start in starts:
        while left[start] > 0:
            line, here, heading = [start], start, None
            while left[here] > 0:
                free = [(v, e) for v, e in neighbours[here] if not used[e]]
                if heading is None:
                    there, edge = free[0]
                else:
                    there, edge = max(free, key=lambda ve: float(np.dot(positions[ve[0]] - positions[here], heading)))
                used[edge] = True
                left[here] -= 1
                left[there] -= 1
                step = positions[there] - positions[here]
                heading = step / max(float(np.linalg.norm(step)), 1e-12)
                line.append(there)
                here = there
            order += line + [-1]
    return np.array(order[:-1], dtype=np.int64)


def _sphere() -> tuple[np.ndarray, np.ndarray]:
    """A unit icosphere (one subdivision): vertices (42, 3) and triangles (80, 3)."""
    p = (1 + 5 ** 0.5) / 2
    vertices = [(-1, p, 0), (1, p, 0), (-1, -p, 0), (1, -p, 0), (0, -1, p), (0, 1, p), (0, -1, -p), (0, 1, -p),
                (p, 0, -1), (p, 0, 1), (-p, 0, -1), (-p, 0, 1)]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
             (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11),
             (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    points = [np.array(v, dtype=float) for v in vertices]
    middle: dict[tuple[int, int], int] = {}

    def halfway(a: int, b: int) -> int:
        key = (min(a, b), max(a, b))
        if key not in middle:
            middle[key] = len(points)
            points.append(0.5 * (points[a] + points[b]))
        return middle[key]

    finer = []
    for a, b, c in faces:
        ab, bc, ca = halfway(a, b), halfway(b, c), halfway(c, a)
        finer += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
    unit = np.array(points)
    return unit / np.linalg.norm(unit, axis=1, keepdims=True), np.array(finer)


SPHERE = _sphere()


def _coordinates(points: np.ndarray) -> dict[str, list]:
    """x, y, z lists of ``points`` (k, 3), rounded; NaN rows become gaps (None)."""
    rounded = np.round(points.astype(np.float64), DECIMALS)
    return {axis: [None if math.isnan(v) else v for v in rounded[:, i].tolist()] for i, axis in enumerate("xyz")}


def _lines(starts: np.ndarray, ends: np.ndarray) -> np.ndarray:
    """Separate segments as one polyline array with NaN gaps, (3k, 3)."""
    gaps = np.full_like(starts, np.nan)
    return np.stack([starts, ends, gaps], axis=1).reshape(-1, 3)


def _balls(centres: np.ndarray, radius: float) -> dict:
    vertices, faces = SPHERE
    points = (centres[:, None, :] + radius * vertices[None]).reshape(-1, 3)
    triangles = (faces[None] + len(vertices) * np.arange(len(centres))[:, None, None]).reshape(-1, 3)
    return {"type": "mesh3d", **_coordinates(points), "i": triangles[:, 0].tolist(), "j": triangles[:, 1].tolist(),
            "k": triangles[:, 2].tolist(), "color": BALL_COLOUR, "flatshading": False, "name": "balls",
            "lighting": {"ambient": 0.5, "diffuse": 0.8, "specular": 0.3}, "hoverinfo": "skip"}


def _moving(snapshot: Snapshot, strings: np.ndarray) -> list[dict]:
    """The traces that change from frame to frame (:data:`MOVING_TRACES`)."""
    net = np.where((strings < 0)[:, None], np.nan, snapshot.net[np.maximum(strings, 0)])
    line = {"type": "scatter3d", "mode": "lines", "hoverinfo": "skip"}
    if snapshot.thrower is None:
        limbs, head = np.empty((0, 3)), np.empty((0, 3))
    else:
        figure = thrower_figure(snapshot.thrower, snapshot.scenery.centre)
        limbs, head = _lines(figure.segments[:, 0], figure.segments[:, 1]), figure.head[None]
    return [{**line, **_coordinates(net), "line": {"color": NET_COLOUR, "width": 2}, "name": "net"},
            _balls(snapshot.balls, snapshot.scenery.ball_radius),
            {**line, **_coordinates(limbs), "line": {"color": THROWER_COLOUR, "width": 6}, "name": "thrower"},
            {"type": "scatter3d", "mode": "markers", **_coordinates(head), "hoverinfo": "skip", "name": "head",
             "marker": {"color": THROWER_COLOUR, "size": 9}}]


def _kept(snapshots: Sequence[Snapshot], captions: Sequence[str], fps: int) -> list[int]:
    """Indices of the frames the page keeps: one in ``ceil(fps / MAX_FPS)``, every caption change, the last."""
    every = max(1, math.ceil(fps / MAX_FPS))
    return [i for i in range(len(snapshots))
            if i % every == 0 or i == len(snapshots) - 1 or captions[i] != captions[i - 1]]


def _bounds(snapshots: Sequence[Snapshot]) -> tuple[np.ndarray, np.ndarray]:
    """The box (low, high) that holds the whole episode, the ground under it."""
    parts = [s.net for s in snapshots] + [s.balls for s in snapshots if len(s.balls)]
    parts += [thrower_figure(s.thrower, s.scenery.centre).points for s in snapshots if s.thrower is not None]
    points = np.vstack(parts)
    radius = snapshots[0].scenery.ball_radius
    low, high = points.min(axis=0) - radius - 1.0, points.max(axis=0) + radius + 0.5
    low[2] = 0.0
    return low, high


def _static(scenery: Scenery, low: np.ndarray, high: np.ndarray) -> list[dict]:
    """The ground (a green rectangle at z = 0) and the poles."""
    ground = {"type": "mesh3d", "x": [low[0], high[0], high[0], low[0]], "y": [low[1], low[1], high[1], high[1]],
              "z": [0.0] * 4, "i": [0, 0], "j": [1, 2], "k": [2, 3], "color": GROUND_COLOUR, "hoverinfo": "skip",
              "name": "ground"}
    poles = {"type": "scatter3d", "mode": "lines", **_coordinates(_lines(scenery.poles[:, 0], scenery.poles[:, 1])),
             "line": {"color": POLE_COLOUR, "width": 8}, "hoverinfo": "skip", "name": "poles"}
    return [ground, poles]


def _controls(names: list[str], times: list[float], duration: float) -> tuple[list[dict], list[dict]]:
    """Play/pause buttons and the time slider, on rows of their own (the buttons first, the slider
    under them across the page's width), so that they never overlap however narrow the page."""
    still = {"mode": "immediate", "frame": {"duration": 0, "redraw": True}, "transition": {"duration": 0}}
    buttons = [{"type": "buttons", "direction": "left", "x": 0.0, "y": 0.0, "xanchor": "left", "yanchor": "top",
                "pad": {"t": BUTTONS_PAD, "l": 10}, "showactive": False,
                "buttons": [{"label": "Play", "method": "animate",
                             "args": [None, {"frame": {"duration": duration, "redraw": True}, "fromcurrent": True,
                                             "transition": {"duration": 0}}]},
                            {"label": "Pause", "method": "animate", "args": [[None], still]}]}]
    slider = [{"active": 0, "x": 0.0, "y": 0.0, "len": 1.0, "yanchor": "top",
               "pad": {"t": SLIDER_PAD, "l": 10, "r": 10}, "ticklen": 3,
               "font": {"color": "rgba(0, 0, 0, 0)"},   # one step a frame: too many labels to show
               "currentvalue": {"prefix": "t = ", "suffix": " s", "font": {"color": "rgb(40, 40, 40)"}},
               "steps": [{"label": f"{t:.2f}", "method": "animate", "args": [[name], still]}
                         for name, t in zip(names, times)]}]
    return buttons, slider


def write_replay_page(snapshots: Sequence[Snapshot], path: str | Path, fps: int,
                      captions: Sequence[str] | None = None) -> Path:
    """Write the episode of ``snapshots`` (``fps`` a simulated second; one caption each, shown as
    the title) to ``path`` as a self-contained HTML page; returns the path."""
    import plotly.io

    if not snapshots:
        raise InvalidArgumentError("no snapshots to write (render_mode='replay_list' collects them)")
    captions = list(captions) if captions is not None else [""] * len(snapshots)
    scenery = snapshots[0].scenery
    strings = net_strings(scenery.segments, snapshots[0].net)
    kept = _kept(snapshots, captions, fps)
    low, high = _bounds([snapshots[i] for i in kept])
    names = [str(i) for i in kept]
    frames = [{"name": str(i), "data": _moving(snapshots[i], strings), "traces": MOVING_TRACES,
               "layout": {"title": {"text": captions[i]}}} for i in kept]
    first = snapshots[kept[0]]
    view = side_view(first.thrower, scenery.centre) if first.thrower is not None else np.array([0.7, -1.0, -0.6])
    extent = high - low
    ratio = extent / extent.max()
    buttons, slider = _controls(names, [snapshots[i].time - snapshots[kept[0]].time for i in kept],
                                1000.0 * len(snapshots) / fps / len(kept))
    axis = {"visible": False}
    layout = {"title": {"text": captions[kept[0]], "x": 0.02, "font": {"size": 18}},
              "margin": {"l": 0, "r": 0, "t": 50, "b": 0},  # plotly widens "b" to fit the buttons and the slider
              "showlegend": False, "uirevision": "replay",
              "scene": {"xaxis": {**axis, "range": [low[0], high[0]]}, "yaxis": {**axis, "range": [low[1], high[1]]},
                        "zaxis": {**axis, "range": [low[2], high[2]]}, "bgcolor": SKY_COLOUR,
                        "aspectmode": "manual", "aspectratio": dict(zip("xyz", ratio.tolist())),
                        "camera": {"eye": dict(zip("xyz", (-EYE_DISTANCE * view).tolist()))},
                        "uirevision": "replay"},
              "updatemenus": buttons, "sliders": slider}
    figure = {"data": _static(scenery, low, high) + frames[0]["data"], "layout": layout, "frames": frames}
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    html = plotly.io.to_html(figure, include_plotlyjs=True, auto_play=False, validate=False,
                             config={"displaylogo": False}, full_html=False, default_height="100%")
    path.write_text(PAGE.format(figure=html), encoding="utf-8")
    return path
