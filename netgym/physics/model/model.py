"""Model (static arrays of a scene) and State (what changes while it runs).

Bodies are rows of one position/velocity array: rows ``0 .. n_net-1`` are net particles,
the rows after them are balls, in launch order. Kernels work on these flat float64 arrays.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from netgym.config import SceneConfig, SimulationConfig
from netgym.physics.compliant.contacts import possible_contacts
from netgym.physics.compliant.grip import ANCHOR_COLUMNS, relaid
from netgym.physics.model.contact_tables import Materials, Poles
from netgym.kinds import Contact, ContactModel, Integrator, SpringKind
from netgym.physics.model.net import NetGeometry, build_net
from netgym.physics.model.opening import Opening, OpeningRecord
from netgym.physics.kernels.springs import SpringLayout, Springs, kernel_indices


def ball_drag_constant(config: SceneConfig) -> float:
    """``k`` (1/m) of a ball's drag acceleration ``-k |v - wind| (v - wind)``:
    ``0.5 * density * drag_coefficient * pi * radius**2 / mass``."""
    air, ball = config.air, config.ball
    return 0.5 * air.density * air.drag_coefficient * math.pi * ball.radius ** 2 / ball.mass


def index_segments(segments: np.ndarray, n_net: int) -> tuple[np.ndarray, np.ndarray]:
    """``segments`` in order of their first particle (a stable sort: rows already in that order
    keep it) and where each particle's rows begin: particle k's are rows ``start[k]`` to
    ``start[k + 1]``, which the contacts' broad phase reads."""
    ordered = np.ascontiguousarray(segments[np.argsort(segments[:, 0], kind="stable")])
    return ordered, np.searchsorted(ordered[:, 0], np.arange(n_net + 1)).astype(np.int64)


class KernelModel(NamedTuple):
    """The static arrays and constants of a scene in the form the numba kernels take (one
    typed record instead of a dozen arguments). Built once per :class:`Model`."""

    n_net: int
    springs: Springs
    segments: np.ndarray
    segment_start: np.ndarray
    poles: Poles
    materials: Materials
    restitution_threshold: float
    gravity: float
    drag: float
    ball_radius: float
    opening: OpeningRecord
    ball_drag: float
    wind: np.ndarray


class Settings(NamedTuple):
    """How to integrate: the method and step, and the safeguards (see :class:`SimulationConfig`).

    Made by :meth:`make` or :meth:`of`, settings are an instance of their integrator's own
    subclass (:data:`SETTINGS_CLASSES`): the kernels take the integrator from that type, so
    numba compiles a kernel once per integrator it meets, and only those.
    """

    integrator: int
    dt: float
    max_travel: float
    cg_tolerance: float
    cg_max_iterations: int
    divergence_speed: float
    contact_stiffness: float = 0.0

    @staticmethod
    def make(integrator: int, dt: float, max_travel: float, cg_tolerance: float, cg_max_iterations: int,
             divergence_speed: float, contact_model: int = ContactModel.IMPULSE,
             contact_stiffness: float = 0.0) -> "Settings":
        """Settings of ``integrator`` (an :class:`Integrator` code) and ``contact_model`` (a
        :class:`ContactModel` code, its springs of ``contact_stiffness`` N/m), of their class in
        :data:`SETTINGS_CLASSES`."""
        kind = SETTINGS_CLASSES[Integrator(integrator), ContactModel(contact_model)]
        return kind(int(integrator), float(dt), float(max_travel), float(cg_tolerance), int(cg_max_iterations),
                    float(divergence_speed), float(contact_stiffness))

    @classmethod
    def of(cls, config: SimulationConfig, integrator: int, dt: float) -> "Settings":
        """The settings of a scene's simulation section with this integrator and ``dt``."""
        return cls.make(integrator, dt, config.max_ball_travel, config.cg_tolerance, config.cg_max_iterations,
                        config.divergence_speed, ContactModel.parse(config.contact_model), config.contact_stiffness)


def _settings_class(integrator: Integrator, contact_model: ContactModel) -> type[Settings]:
    """The subclass of :class:`Settings` of one integrator and contact model, named after them
    (``ImexEulerSettings``, ``Rk4CompliantSettings``), with them as its ``INTEGRATOR`` and
    ``CONTACT_MODEL``."""
    model = "" if contact_model == ContactModel.IMPULSE else contact_model.label.title()
    name = "".join(word.title() for word in integrator.label.split("_")) + model + "Settings"
    return type(name, (Settings,), {"__slots__": (), "__module__": __name__, "__qualname__": name,
                                    "__doc__": f":class:`Settings` of {integrator.label}, {contact_model.label} contacts.",
                                    "INTEGRATOR": integrator, "CONTACT_MODEL": contact_model})


SETTINGS_CLASSES: dict[tuple[Integrator, ContactModel], type[Settings]] = {
    (integrator, contact_model): _settings_class(integrator, contact_model)
    for integrator in Integrator for contact_model in ContactModel}
"""Each integrator and contact model's class of :class:`Settings`."""
globals().update({cls.__name__: cls for cls in SETTINGS_CLASSES.values()})  # numba's cache pickles them by name


@dataclass(frozen=True)
class Model:
    """Static description of a scene, as arrays ready for the kernels.

    ``springs`` holds particle index pairs, ``spring_params`` the columns (rest length, ks, kd).
    ``segments`` are the structural springs, against which balls collide (not only the
    particles: springs never sink into a ball), in order of their first particle, and
    ``segment_start`` where each particle's begin (:func:`index_segments`). ``poles`` are the
    capsules (:class:`~netgym.physics.model.contact_tables.Poles`). ``contact`` rows are (restitution, friction) per
    :class:`Contact` kind. ``kernel`` is the same in the form the kernels take.
    """

    config: SceneConfig
    geometry: NetGeometry
    n_net: int
    net_inv_mass: np.ndarray
    springs: np.ndarray
    spring_params: np.ndarray
    spring_kind: np.ndarray
    segments: np.ndarray
    segment_start: np.ndarray
    poles: Poles
    contact: np.ndarray
    restitution_threshold: float
    gravity: float
    drag: float
    ball_radius: float
    ball_mass: float
    opening: Opening
    integrator: Integrator
    ball_drag: float
    wind: np.ndarray
    layout_hint: SpringLayout | None = dataclasses.field(default=None, compare=False, repr=False)

    @classmethod
    def from_config(cls, config: SceneConfig, like: "Model | None" = None) -> "Model":
        """Build the model of a scene (the net's geometry, and the layout of its springs for the
        kernels, taken from ``like``, a model of a scene with the same net section, if given)."""
        same_net = like is not None and like.config.net == config.net
        geo = like.geometry if same_net else build_net(config.net)
        rest = np.linalg.norm(geo.positions[geo.springs[:, 0]] - geo.positions[geo.springs[:, 1]], axis=1)
        per_kind = np.array([[getattr(config.springs, k).ks, getattr(config.springs, k).kd] for k in SpringKind.labels()])
        params = np.column_stack([rest, per_kind[geo.spring_kind]])
        inv_mass = np.where(geo.fixed, 0.0, 1.0 / config.net.particle_mass)
        poles = Poles(np.ascontiguousarray(geo.poles[:, :3], dtype=np.float64),
                      np.ascontiguousarray(geo.poles[:, 3:6], dtype=np.float64),
                      np.full(len(geo.poles), float(config.net.pole_radius)))
        contact = np.array([[getattr(config.contact, p).restitution, getattr(config.contact, p).friction]
                            for p in Contact.labels()])
        structural = geo.springs[geo.spring_kind == SpringKind.STRUCTURAL]
        segments, segment_start = index_segments(structural, len(geo.positions))
        return cls(
            config=config,
            geometry=geo,
            n_net=len(geo.positions),
            net_inv_mass=inv_mass,
            springs=np.ascontiguousarray(geo.springs),
            spring_params=np.ascontiguousarray(params),
            spring_kind=geo.spring_kind,
            segments=segments,
            segment_start=segment_start,
            poles=poles,
            contact=contact,
            restitution_threshold=config.contact.restitution_threshold,
            gravity=config.simulation.gravity,
            drag=config.net.drag,
            ball_radius=config.ball.radius,
            ball_mass=config.ball.mass,
            opening=geo.opening,
            integrator=Integrator.parse(config.simulation.integrator),
            ball_drag=ball_drag_constant(config),
            wind=np.array(config.air.wind, dtype=np.float64),
            layout_hint=like.spring_layout[1] if same_net else None,
        )

    def with_air(self, config: SceneConfig) -> "Model":
        """This model under ``config``, a scene that differs from this one's at most in its air
        (a wind drawn per episode): the net, its springs and the kernel's arrays are shared."""
        if dataclasses.replace(self.config, air=config.air) != config:
            raise ValueError("Model.with_air: the scenes differ in more than their air")
        model = dataclasses.replace(self, config=config, ball_drag=ball_drag_constant(config),
                                    wind=np.array(config.air.wind, dtype=np.float64))
        model.__dict__["kernel"] = self.kernel._replace(ball_drag=model.ball_drag, wind=model.wind)  # cached_property's slot
        return model

    @functools.cached_property
    def spring_layout(self) -> tuple[Springs, SpringLayout]:
        """The springs as the kernels take them, and their layout (refilled from the
        ``layout_hint`` of a model of the same net where that serves)."""
        if self.layout_hint is not None:
            springs = self.layout_hint.refill(self.spring_params)
            if springs is not None:
                return springs, self.layout_hint
        return Springs.laid_out(self.springs, self.spring_params, self.n_net)

    @functools.cached_property
    def kernel(self) -> KernelModel:
        """The arrays and constants the kernels need, as one record; its springs a
        :class:`~netgym.physics.kernels.springs.Springs`."""
        springs = self.spring_layout[0]
        return KernelModel(self.n_net, springs, kernel_indices(self.segments), self.segment_start, self.poles,
                           Materials.of_table(self.contact), self.restitution_threshold, self.gravity, self.drag,
                           self.ball_radius, self.opening.kernel_record(), self.ball_drag, self.wind)

    @property
    def n_springs(self) -> int:
        """Number of springs of all kinds."""
        return len(self.springs)

    @property
    def anchor_sizes(self) -> tuple[int, int, int] | None:
        """The net's particles, segments and poles, which size the state's compliant contact
        anchors (:mod:`~netgym.physics.compliant.grip`); None with impulse contacts, which keep none."""
        if ContactModel.parse(self.config.simulation.contact_model) != ContactModel.COMPLIANT:
            return None
        return self.n_net, len(self.segments), len(self.poles.radius)


@dataclass
class State:
    """Positions ``x`` and velocities ``v`` of all bodies, their inverse masses, each ball's
    ``entered`` flag (1 once it came in through the opening, 0 again if it left through it),
    the simulated ``time`` and the compliant contacts' ``anchors`` (their grips, kept between
    steps: :mod:`~netgym.physics.compliant.grip`; no rows with impulse contacts)."""

    x: np.ndarray
    v: np.ndarray
    inv_mass: np.ndarray
    entered: np.ndarray
    time: float = 0.0
    anchors: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros((0, ANCHOR_COLUMNS)))

    @classmethod
    def at_rest(cls, model: Model, positions: np.ndarray | None = None) -> "State":
        """The net at ``positions`` (default: its built geometry), still, with no balls."""
        x = np.array(model.geometry.positions if positions is None else positions, dtype=np.float64)
        sizes = model.anchor_sizes
        anchors = np.zeros((0 if sizes is None else possible_contacts(*sizes, 0), ANCHOR_COLUMNS))
        return cls(x=x, v=np.zeros_like(x), inv_mass=model.net_inv_mass.copy(),
                   entered=np.zeros(0, dtype=np.int8), anchors=anchors)

    def copy(self) -> "State":
        """An independent copy."""
        return State(self.x.copy(), self.v.copy(), self.inv_mass.copy(), self.entered.copy(), self.time,
                     self.anchors.copy())

    def restore(self, other: "State") -> None:
        """Overwrite this state in place with ``other``'s values."""
        self.x, self.v = other.x.copy(), other.v.copy()
        self.inv_mass, self.entered, self.time = other.inv_mass.copy(), other.entered.copy(), other.time
        self.anchors = other.anchors.copy()

    def relay_anchors(self, model: Model, old_balls: int, kept: list[int]) -> None:
        """Lay the anchors of ``old_balls`` balls out for the balls ``kept`` (old indices in
        their new order, -1 for a new one), after balls were added or taken out."""
        sizes = model.anchor_sizes
        if sizes is not None:
            self.anchors = relaid(self.anchors, sizes, old_balls, kept)
