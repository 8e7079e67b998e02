"""Scene files: TOML text -> validated, frozen dataclasses (and back).

A scene file is data only: it is parsed with :mod:`tomllib` and every value is checked against
the type and range declared on its dataclass field (:mod:`netgym.config_fields`). A wrong field
raises :class:`~netgym.errors.ConfigError` naming the field (``simulation.dt``) and its allowed
range.
"""

from __future__ import annotations

import dataclasses
import tomllib
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any, Mapping

from netgym.config_fields import build, choice, number, replaced
from netgym.errors import ConfigError
from netgym.kinds import ContactModel, Integrator

INTEGRATORS = Integrator.labels()
CONTACT_MODELS = ContactModel.labels()
FACES = ("+x", "-x", "+y", "-y", "+z", "-z")
BUILTIN_SCENES = ("basket", "goal")
CAPTURE_RULES = ("held", "line")
MAX_NET_PARTICLES = 20_000     # beyond this a scene is slow to build and settle
MAX_SPRING_RATE = 2e9          # spring evaluations per simulated second beyond which a scene crawls
SPRINGS_PER_PARTICLE = 6       # structural, shear and bending: at most two of each per particle


@dataclass(frozen=True)
class NetConfig:
    """Geometry and mass of the net: an axis-aligned box of net faces with one face open.

    ``particles`` counts particles along x, y and z (shared edges included). The open face's
    border is fixed (the rim or the goal frame); with ``fix_side_edges`` the four box edges
    parallel to the open face's normal are fixed too (the basket's corner poles, the goal's
    depth bars). Fixed edges above the ground are solid capsules of ``pole_radius`` for balls.
    ``drag`` (1/s) is the air drag on net particles, a force ``-drag * mass * velocity``: the
    dampers along the springs do not damp a membrane's transverse swinging, air does.
    """

    lower: tuple[float, float, float] = number(-100.0, 100.0)
    upper: tuple[float, float, float] = number(-100.0, 100.0)
    particles: tuple[int, int, int] = number(3, 200)
    open_face: str = choice(*FACES)
    fix_side_edges: bool = field()
    particle_mass: float = number(0.0, 100.0, lo_open=True)
    drag: float = number(0.0, 100.0)
    pole_radius: float = number(0.0, 1.0, lo_open=True)


@dataclass(frozen=True)
class SpringConfig:
    """Stiffness ``ks`` (N/m) and damping ``kd`` (N s/m) of one spring type."""

    ks: float = number(0.0, 1e8, lo_open=True)
    kd: float = number(0.0, 1e6)


@dataclass(frozen=True)
class SpringsConfig:
    """Structural (grid neighbours), shear (diagonals) and bending (second neighbours) springs."""

    structural: SpringConfig
    shear: SpringConfig
    bending: SpringConfig


@dataclass(frozen=True)
class BallConfig:
    """A ball: a rigid sphere without spin."""

    radius: float = number(0.01, 2.0)
    mass: float = number(0.0, 100.0, lo_open=True)


@dataclass(frozen=True)
class ContactPairConfig:
    """Restitution (0..1) and Coulomb friction coefficient of one kind of contact."""

    restitution: float = number(0.0, 1.0)
    friction: float = number(0.0, 5.0)


@dataclass(frozen=True)
class ContactConfig:
    """Contact coefficients per pair; approach speeds below ``restitution_threshold`` (m/s)
    do not bounce, which keeps resting contacts still (no ground jitter)."""

    ball_net: ContactPairConfig
    ball_pole: ContactPairConfig
    ball_ball: ContactPairConfig
    ball_ground: ContactPairConfig
    net_ground: ContactPairConfig
    restitution_threshold: float = number(0.0, 10.0)


@dataclass(frozen=True)
class SimulationConfig:
    """Integrator, time step and the numerical safeguards of the simulator.

    ``max_ball_travel`` is the largest distance, as a fraction of the ball radius, that a ball
    may move relative to the net in one substep; longer steps are split (no tunnelling).
    ``rest_speed`` (m/s): a ball whose outcome waits on it is at rest when it and what is near
    it stay slower than this for 0.1 s. ``settle_speed`` (m/s): the pause between two throws
    ends when no body has moved faster than this over 0.1 s (the scene is then stopped).
    The pause seeks an equilibrium, not a trajectory: it steps with ``settle_integrator`` at
    ``settle_dt`` (s), or at 90% of that integrator's linear stability limit on the net if
    that is smaller, and falls back to ``integrator`` at ``dt`` should it diverge. Meanwhile the
    net's inertia is ``settle_inertia`` times its mass, its weight unchanged (dynamic relaxation
    with a fictitious mass: the same equilibrium, frequencies sqrt(settle_inertia) lower, so the
    stability limit, and with it the pause's step, that much longer).

    ``contact_model``: ``"impulse"`` (the default: contacts resolved by projections and impulses
    after each substep) or ``"compliant"`` (Hunt-Crossley forces of stiffness
    ``contact_stiffness`` (N/m) inside the integrator, which converge at its order through
    contact; :mod:`netgym.physics.compliant`). The compliant model steps the scene
    (``Simulator.step``) with every integrator but implicit Euler; throws do not take it yet.
    """

    integrator: str = choice(*INTEGRATORS)
    dt: float = number(0.0, 0.05, lo_open=True)
    gravity: float = number(-100.0, 0.0)
    time_limit: float = number(0.0, 120.0, lo_open=True)
    max_ball_travel: float = number(0.01, 0.9)
    cg_tolerance: float = number(1e-14, 1e-2)
    cg_max_iterations: int = number(1, 10_000)
    divergence_speed: float = number(1.0, 1e8, lo_open=True)
    rest_speed: float = number(0.0, 1.0, lo_open=True)
    settle_speed: float = number(0.0, 1.0, lo_open=True)
    settle_integrator: str = choice(*INTEGRATORS)
    settle_dt: float = number(0.0, 0.05, lo_open=True)
    settle_inertia: float = number(1.0, 100.0, default=1.0)
    contact_model: str = choice(*CONTACT_MODELS, default="impulse")
    contact_stiffness: float = number(1.0, 1e8, default=2e4)


@dataclass(frozen=True)
class ThrowConfig:
    """Where throwers stand and which launches an action can ask for.

    Throwers stand at a horizontal ``distance`` from the centre of the opening, at a
    ``bearing`` (degrees, counter-clockwise from +x) and release ``height`` above the ground.
    An action maps to launch ``speed`` (m/s), ``elevation`` above the horizon and ``azimuth``
    offset from the direction towards the opening's centre (degrees).
    """

    distance: tuple[float, float] = number(0.0, 100.0)
    bearing: tuple[float, float] = number(-360.0, 360.0)
    height: tuple[float, float] = number(0.0, 20.0)
    speed: tuple[float, float] = number(0.0, 40.0)
    elevation: tuple[float, float] = number(-89.0, 89.0)
    azimuth: tuple[float, float] = number(-180.0, 180.0)


@dataclass(frozen=True)
class AirConfig:
    """Air acting on balls (optional table ``[air]``; by default there is none): quadratic drag
    ``0.5 * density * drag_coefficient * pi * radius**2 * |v - wind| (v - wind)`` towards the
    ``wind`` velocity. Air at sea level has a density of 1.2 kg/m^3; a smooth sphere a drag
    coefficient of about 0.47. The net's own air drag is ``net.drag``."""

    density: float = number(0.0, 10.0, default=0.0)
    drag_coefficient: float = number(0.0, 5.0, default=0.47)
    wind: tuple[float, float, float] = number(-100.0, 100.0, default=(0.0, 0.0, 0.0))


@dataclass(frozen=True)
class SceneConfig:
    """A whole scene: the net, its springs, the ball, contacts, simulation and throws.

    ``capture_rule`` says when a throw counts as caught: ``"held"``, the ball came in through
    the opening and is inside the net when it comes to rest or the time limit ends; ``"line"``
    (the sport's rule), the whole ball has crossed the opening's plane inside the frame,
    decided that instant; a ball launched in front of that plane that is wholly past it beside
    the frame (over the bar, wide of a post) is out of play, a miss decided that instant.
    """

    name: str
    net: NetConfig
    springs: SpringsConfig
    ball: BallConfig
    contact: ContactConfig
    simulation: SimulationConfig
    throw: ThrowConfig
    capture_rule: str = choice(*CAPTURE_RULES, default="held")
    air: AirConfig = AirConfig()

    def replace(self, overrides: Mapping[str, Any]) -> "SceneConfig":
        """Return a validated copy with dotted fields replaced, e.g. ``{"simulation.dt": 5e-4}``.

        Each new value is validated as :func:`from_dict` would, the untouched fields are shared,
        and the whole scene is checked for consistency again."""
        cfg = self
        for dotted, value in overrides.items():
            cfg = replaced(cfg, dotted.split("."), value, dotted)
        _check_consistency(cfg)
        return cfg


def _check_consistency(cfg: SceneConfig) -> None:
    net = cfg.net
    for axis, (lo, hi) in enumerate(zip(net.lower, net.upper)):
        if not lo < hi:
            raise ConfigError(f"net.lower[{axis}] = {lo} must be below net.upper[{axis}] = {hi}")
    if min(net.lower[2], net.upper[2]) < 0.0:
        raise ConfigError(f"net.lower[2] = {net.lower[2]} is below the ground; allowed: >= 0")
    for key in ("distance", "bearing", "height", "speed", "elevation", "azimuth"):
        lo, hi = getattr(cfg.throw, key)
        if lo > hi:
            raise ConfigError(f"throw.{key} = [{lo}, {hi}] must be an increasing [min, max] pair")
    sim = cfg.simulation
    if sim.contact_model == "compliant" and "implicit_euler" in (sim.integrator, sim.settle_integrator):
        raise ConfigError("simulation.contact_model = 'compliant' has no step for implicit_euler: choose another "
                          "simulation.integrator and simulation.settle_integrator")
    _check_cost(cfg)


def _check_cost(cfg: SceneConfig) -> None:
    """Refuse scenes whose simulation would run for hours: too many particles, or a dt so small
    that a simulated second costs more than MAX_SPRING_RATE spring evaluations."""
    a, b, c = cfg.net.particles
    particles = a * b * c - (a - 2) * (b - 2) * (c - 2)  # the box's surface lattice, an upper bound
    if particles > MAX_NET_PARTICLES:
        raise ConfigError(f"net.particles = {list(cfg.net.particles)} makes up to {particles:,} net particles; "
                          f"allowed: at most {MAX_NET_PARTICLES:,} (building and settling a larger net "
                          f"takes minutes to hours)")
    springs = SPRINGS_PER_PARTICLE * particles
    rate = springs / cfg.simulation.dt
    if rate > MAX_SPRING_RATE:
        raise ConfigError(f"simulation.dt = {cfg.simulation.dt:g} s on a net of up to {particles:,} particles costs "
                          f"about {rate:.2g} spring evaluations per simulated second (settling the net alone takes "
                          f"seconds of simulated time); allowed: at most {MAX_SPRING_RATE:.0e}: use "
                          f"simulation.dt >= {springs / MAX_SPRING_RATE:.2g} s or fewer net.particles")


def from_dict(table: Mapping[str, Any]) -> SceneConfig:
    """Validate a parsed scene table into a :class:`SceneConfig`."""
    cfg = build(SceneConfig, table, "")
    _check_consistency(cfg)
    return cfg


def to_dict(cfg: Any) -> dict[str, Any]:
    """The plain-data form of a config (tuples become lists), the inverse of :func:`from_dict`."""
    out: dict[str, Any] = {}
    for f in dataclasses.fields(cfg):
        value = getattr(cfg, f.name)
        if dataclasses.is_dataclass(value):
            value = to_dict(value)
        elif isinstance(value, tuple):
            value = list(value)
        out[f.name] = value
    return out


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    return repr(value)


def to_toml(cfg: SceneConfig) -> str:
    """Serialise a config to TOML text that :func:`loads` reads back to an equal config."""
    lines: list[str] = []

    def emit(table: dict[str, Any], path: str) -> None:
        scalars = {k: v for k, v in table.items() if not isinstance(v, dict)}
        if path:
            lines.append(f"\n[{path}]")
        lines.extend(f"{k} = {_toml_value(v)}" for k, v in scalars.items())
        for key, sub in table.items():
            if isinstance(sub, dict):
                emit(sub, f"{path}.{key}" if path else key)

    emit(to_dict(cfg), "")
    return "\n".join(lines).lstrip("\n") + "\n"


def loads(text: str) -> SceneConfig:
    """Parse and validate scene TOML text."""
    try:
        table = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"scene file is not valid TOML: {exc}") from exc
    return from_dict(table)


def load_scene(scene: str | Path = "basket", overrides: Mapping[str, Any] | None = None) -> SceneConfig:
    """Load a built-in scene by name (``"basket"``, ``"goal"``) or a TOML file by path.

    :param scene: a built-in scene name or the path of a ``.toml`` scene file.
    :param overrides: dotted fields to replace, e.g. ``{"simulation.integrator": "rk4"}``.
    """
    if isinstance(scene, str) and scene in BUILTIN_SCENES:
        text = resources.files("netgym.scenes").joinpath(f"{scene}.toml").read_text()
    else:
        path = Path(scene)
        if not path.is_file():
            raise ConfigError(f"scene {str(scene)!r} is neither a built-in scene "
                              f"{list(BUILTIN_SCENES)} nor an existing TOML file")
        try:
            text = path.read_text(encoding="utf-8")
        except UnicodeDecodeError as exc:
            raise ConfigError(f"scene file {str(path)!r} is not UTF-8 text (a TOML file is): {exc}") from exc
    cfg = loads(text)
    return cfg.replace(overrides) if overrides else cfg

