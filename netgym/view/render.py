"""Rendering: frames of the net, poles, balls and ground from a fixed perspective camera.

A small NumPy rasteriser with a depth buffer (no GPU, no extra dependency): net strings as
lines shaded by depth (nearer strings brighter, so the box reads in 3D), poles as thick lines,
balls as shaded discs, the ground as a checkerboard, the thrower as a stick figure when one is
filmed (:meth:`Renderer.film`, which also frames the camera on the throw); anti-aliased by
supersampling (the frame is drawn at ``supersample`` times the size and averaged down: the
default 2 draws four times the pixels of 1). ``human`` mode shows the frames in a
pygame window (optional extra ``render``; headless with ``SDL_VIDEODRIVER=dummy``).
:func:`caption_frame` writes a line of text on a frame (Pillow, extra ``render``).
"""

from __future__ import annotations

import math
import os
import sys

import numpy as np

from netgym.errors import InvalidArgumentError
from netgym.view.framing import Figure, flight_points, frame_points, side_view, thrower_figure
from netgym.physics.simulator import Simulator

SKY_TOP = np.array([150, 190, 235], dtype=np.float64)
SKY_LOW = np.array([215, 230, 245], dtype=np.float64)
GROUND_A = np.array([96, 150, 88], dtype=np.float64)
GROUND_B = np.array([86, 138, 80], dtype=np.float64)
NET = np.array([245, 245, 245], dtype=np.float64)
NET_FAR_SHADE = 0.55          # brightness of the farthest net string relative to the nearest
POLE = np.array([200, 40, 40], dtype=np.float64)
BALL = np.array([240, 140, 30], dtype=np.float64)
THROWER = np.array([40, 60, 170], dtype=np.float64)
FOV = 50.0                    # degrees, vertical field of view of the scene cameras
CAPTION_BOX = (20, 20, 20)
CAPTION_TEXT = (255, 255, 255)


class Camera:
    """A pinhole camera looking from ``eye`` at ``target`` with vertical field of view ``fov``."""

    def __init__(self, eye: np.ndarray, target: np.ndarray, width: int, height: int, fov: float = 50.0) -> None:
        self.eye, self.width, self.height = np.asarray(eye, dtype=float), width, height
        forward = np.asarray(target, dtype=float) - self.eye
        forward /= np.linalg.norm(forward)
        right = np.cross(forward, [0.0, 0.0, 1.0])
        right /= np.linalg.norm(right)
        up = np.cross(right, forward)
        self.rotation = np.stack([right, -up, forward])  # rows: camera x (right), y (down), z (forward)
        self.focal = 0.5 * height / math.tan(math.radians(fov) / 2)

    def project(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Pixel coordinates (k, 2) and depths (k,) of world points (k, 3)."""
        cam = (points - self.eye) @ self.rotation.T
        depth = cam[:, 2]
        safe = np.where(depth > 1e-6, depth, np.nan)
        pixels = np.stack([self.focal * cam[:, 0] / safe + 0.5 * self.width,
                           self.focal * cam[:, 1] / safe + 0.5 * self.height], axis=1)
        return pixels, depth

    def rays(self) -> np.ndarray:
        """World-space direction of every pixel's ray, (height, width, 3)."""
        u, v = np.meshgrid(np.arange(self.width) + 0.5, np.arange(self.height) + 0.5)
        cam = np.stack([(u - 0.5 * self.width) / self.focal, (v - 0.5 * self.height) / self.focal,
                        np.ones_like(u)], axis=-1)
        return cam @ self.rotation


def scene_camera(sim: Simulator, width: int, height: int) -> Camera:
    """A camera that frames the scene's net, looking into its opening."""
    lower, upper = np.array(sim.config.net.lower), np.array(sim.config.net.upper)
    target = 0.5 * (lower + upper)
    opening = sim.opening
    if opening.axis == 2:
        direction = np.array([0.7, -1.0, 0.9])
    else:
        normal = np.zeros(3)
        normal[opening.axis] = opening.sign
        direction = 1.2 * normal + np.array([0.3, -0.6, 0.5])
    direction /= np.linalg.norm(direction)
    distance = 1.7 * float(np.linalg.norm(upper - lower))
    return Camera(target + distance * direction, target, width, height, FOV)


def throw_camera(sim: Simulator, release: np.ndarray, velocity: np.ndarray | None, width: int,
                 height: int) -> Camera:
    """A camera that sees the throw from ``release`` side-on: the net, the thrower's figure and
    the ball's flight (``velocity``: its launch velocity; None: no flight yet) up to the far
    side of the net, the apex included."""
    lower, upper = np.array(sim.config.net.lower), np.array(sim.config.net.upper)
    corners = np.array([[x, y, z] for x in (lower[0], upper[0]) for y in (lower[1], upper[1])
                        for z in (0.0, upper[2])])
    centre = sim.opening.centre
    points = [corners, thrower_figure(release, centre).points]
    if velocity is not None:
        reach = float(np.linalg.norm((centre - release)[:2])) + 0.5 * float(np.linalg.norm((upper - lower)[:2]))
        points.append(flight_points(release, velocity, sim.model.gravity, reach, sim.model.ball_radius))
    eye, target = frame_points(np.vstack(points), side_view(release, centre), width / height, FOV)
    return Camera(eye, target, width, height, FOV)


def caption_frame(frame: np.ndarray, text: str) -> np.ndarray:
    """A copy of ``frame`` with ``text`` written at its top left on a dark box (unchanged if empty)."""
    if not text:
        return frame
    from PIL import Image, ImageDraw, ImageFont

    image = Image.fromarray(frame)
    draw = ImageDraw.Draw(image)
    font = ImageFont.load_default(size=max(10, frame.shape[0] // 24))
    left, top, right, bottom = draw.textbbox((8, 6), text, font=font)
    draw.rectangle((left - 5, top - 4, right + 5, bottom + 4), fill=CAPTION_BOX)
    draw.text((8, 6), text, fill=CAPTION_TEXT, font=font)
    return np.asarray(image)


def _background(camera: Camera) -> np.ndarray:
    rays = camera.rays()
    image = np.empty(rays.shape, dtype=np.float64)
    sky = np.clip(rays[..., 2] / np.linalg.norm(rays, axis=-1), 0.0, 1.0)[..., None]
    image[:] = SKY_LOW + (SKY_TOP - SKY_LOW) * np.sqrt(sky)
    down = rays[..., 2] < -1e-9
    t = np.where(down, -camera.eye[2] / np.where(down, rays[..., 2], -1.0), 0.0)
    hit = camera.eye[:2] + t[..., None] * rays[..., :2]
    checker = (np.floor(hit[..., 0]) + np.floor(hit[..., 1])) % 2 == 0
    ground = np.where(checker[..., None], GROUND_A, GROUND_B)
    fog = np.clip(t / 60.0, 0.0, 1.0)[..., None]
    image[down] = (ground * (1 - fog) + SKY_LOW * fog)[down]
    return image.astype(np.uint8)


class Renderer:
    """Draws frames of a simulator's scene; optionally shows them in a pygame window."""

    def __init__(self, sim: Simulator, width: int = 480, height: int = 360, human: bool = False, fps: int = 30,
                 supersample: int = 2) -> None:
        if not isinstance(supersample, int) or not 1 <= supersample <= 4:
            raise InvalidArgumentError(f"supersample = {supersample!r}; allowed: an integer in [1, 4]")
        self.supersample = supersample
        self.size = (width, height)
        self.look(scene_camera(sim, width * supersample, height * supersample))
        self.human, self.fps = human, fps
        self.figure: Figure | None = None
        self._filmed: tuple | None = None
        self._window = None
        self._clock = None

    def look(self, camera: Camera) -> None:
        """Draw through ``camera`` from now on (its size: ``supersample`` times the frame's)."""
        self.camera = camera
        self.background = _background(camera)

    def look_from(self, eye: np.ndarray, target: np.ndarray, fov: float = FOV) -> None:
        """Draw from ``eye`` towards ``target`` from now on."""
        width, height = self.size
        self.look(Camera(eye, target, width * self.supersample, height * self.supersample, fov))

    def film(self, sim: Simulator, release: np.ndarray, velocity: np.ndarray | None = None) -> None:
        """Film the throw from ``release`` from now on: draw the thrower there, facing the
        opening, and frame the camera on it (:func:`throw_camera`; ``velocity``: the launch
        velocity, None before the launch). Filming the same throw again changes nothing."""
        key = (tuple(release), None if velocity is None else tuple(velocity))
        if key == self._filmed:
            return
        width, height = self.size
        self.look(throw_camera(sim, release, velocity, width * self.supersample, height * self.supersample))
        self.figure = thrower_figure(release, sim.opening.centre)
        self._filmed = key

    def _line_fragments(self, a: np.ndarray, b: np.ndarray, colour: np.ndarray, thickness: int):
        pa, da = self.camera.project(a)
        pb, db = self.camera.project(b)
        ok = (da > 0.05) & (db > 0.05) & np.all(np.isfinite(pa), axis=1) & np.all(np.isfinite(pb), axis=1)
        pa, pb, da, db = pa[ok], pb[ok], da[ok], db[ok]
        if len(pa) == 0:
            return None
        length = np.clip(np.ceil(np.abs(pb - pa).max(axis=1)).astype(int), 1, 2 * max(self.camera.width, self.camera.height))
        samples = int(length.max()) + 1
        t = np.linspace(0.0, 1.0, samples)[None, :]
        keep = (t * length[:, None] <= length[:, None] + 0.5)
        px = (pa[:, 0:1] + t * (pb[:, 0:1] - pa[:, 0:1]))[keep]
        py = (pa[:, 1:2] + t * (pb[:, 1:2] - pa[:, 1:2]))[keep]
        depth = (da[:, None] + t * (db - da)[:, None])[keep]
        xs, ys, ds = [], [], []
        for ox in range(thickness):
            for oy in range(thickness):
                xs.append(px + ox - thickness // 2)
                ys.append(py + oy - thickness // 2)
                ds.append(depth)
        return (np.concatenate(xs), np.concatenate(ys), np.concatenate(ds),
                np.broadcast_to(colour, (sum(len(x) for x in xs), 3)))

    def _ball_fragments(self, centres: np.ndarray, radius: float, colour: np.ndarray = BALL):
        pixels, depth = self.camera.project(centres)
        out = []
        for (cx, cy), d in zip(pixels, depth):
            if not (d > radius and np.isfinite(cx)):
                continue
            rp = self.camera.focal * radius / d
            span = int(math.ceil(rp))
            gx, gy = np.meshgrid(np.arange(-span, span + 1), np.arange(-span, span + 1))
            inside = gx * gx + gy * gy <= rp * rp
            nx, ny = gx[inside] / rp, gy[inside] / rp
            nz = np.sqrt(np.clip(1 - nx * nx - ny * ny, 0.0, 1.0))
            shade = np.clip(0.35 + 0.65 * (-0.4 * nx - 0.5 * ny + 0.77 * nz), 0.0, 1.0)
            out.append((cx + gx[inside], cy + gy[inside], d - radius * nz, colour * shade[:, None]))
        if not out:
            return None
        return tuple(np.concatenate(parts) for parts in zip(*out))

    def draw(self, sim: Simulator) -> np.ndarray:
        """An (H, W, 3) uint8 frame of the simulator's current state."""
        x, m, k = sim.state.x, sim.model, self.supersample
        net = self._line_fragments(x[m.segments[:, 0]], x[m.segments[:, 1]], NET, 1)
        if net is not None:
            depth = net[2]
            far = (depth - depth.min()) / max(float(np.ptp(depth)), 1e-9)
            net = (*net[:3], NET * (1.0 - (1.0 - NET_FAR_SHADE) * far)[:, None])
        fragments = [net, self._line_fragments(m.poles.start, m.poles.end, POLE, 2 * k),
                     self._ball_fragments(x[m.n_net:], m.ball_radius)]
        if self.figure is not None:
            limbs = self.figure.segments
            fragments += [self._line_fragments(limbs[:, 0], limbs[:, 1], THROWER, 2 * k),
                          self._ball_fragments(self.figure.head[None], self.figure.head_radius, THROWER)]
        image = self.background.copy()
        parts = [f for f in fragments if f is not None]
        if parts:
            px, py, depth, colour = (np.concatenate(p) for p in zip(*parts))
            ix, iy = np.round(px).astype(int), np.round(py).astype(int)
            visible = (ix >= 0) & (ix < self.camera.width) & (iy >= 0) & (iy < self.camera.height)
            order = np.argsort(-depth[visible], kind="stable")  # far first: nearer fragments overwrite
            image[iy[visible][order], ix[visible][order]] = colour[visible][order].astype(np.uint8)
        if k == 1:
            return image
        total = sum(image[i::k, j::k].astype(np.uint16) for i in range(k) for j in range(k))
        return ((total + k * k // 2) // (k * k)).astype(np.uint8)

    def show(self, frame: np.ndarray) -> None:
        """Show a frame in the pygame window (human mode), at most ``fps`` frames per second."""
        import pygame

        if self._window is None:
            problem = display_problem()
            if problem is not None:
                raise InvalidArgumentError(
                    f'render_mode="human" needs a display for its window: {problem}. Use render_mode="rgb_array" '
                    f'(frames as arrays) or "rgb_array_list" with netgym.wrappers.RecordEpisodeVideo, or set '
                    f'SDL_VIDEODRIVER=dummy to draw without a window (gymnasium\'s check_env makes every declared mode: '
                    f'set it there too, or pass skip_render_check=True)')
            pygame.display.init()  # the window only: no audio, whose drivers warn where there is no sound card
            pygame.display.set_caption("NetCatch-v0")
            self._window = pygame.display.set_mode((frame.shape[1], frame.shape[0]))
            self._clock = pygame.time.Clock()
        pygame.event.pump()
        self._window.blit(pygame.surfarray.make_surface(frame.swapaxes(0, 1)), (0, 0))
        pygame.display.flip()
        self._clock.tick(self.fps)

    def close(self) -> None:
        """Close the window if one is open."""
        if self._window is not None:
            import pygame

            pygame.display.quit()
            pygame.quit()
            self._window = None


def display_problem() -> str | None:
    """Why no window can open here, or None: on Linux no display named in the environment, or
    else SDL's video failing to start."""
    named = ("DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER")
    if sys.platform.startswith("linux") and not any(os.environ.get(name) for name in named):
        return "neither DISPLAY nor WAYLAND_DISPLAY is set"
    import pygame

    try:
        pygame.display.init()
    except pygame.error as error:
        return f"SDL's video did not start ({error})"
    return None
