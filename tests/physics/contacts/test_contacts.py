"""The contact kernels (``netgym/physics/kernels/impulse_contacts.py``) against analytic cases: a head-on pair
of balls with restitution e, a ball at rest on a particle, the friction cone's boundary and a
ball pressing on a spring segment. Each case is a handful of bodies handed to the kernels
directly, so the expectation is a formula of momentum, restitution and Coulomb's law."""

from __future__ import annotations

import numpy as np
import pytest

from netgym.physics.kernels import impulse_contacts as contacts
from netgym.physics.model import contact_tables
from netgym.kinds import Contact
from netgym.physics.model.model import KernelModel, index_segments
from netgym.physics.model.opening import Opening
from netgym.physics.kernels.springs import Springs

RADIUS = 0.3           # m, ball radius
THRESHOLD = 0.2        # m/s, restitution threshold: slower approaches do not bounce
NET_MASS = 0.2         # kg, a net particle


def coefficients(restitution: float, friction: float) -> np.ndarray:
    """A contact table with every kind at (restitution, friction)."""
    return np.tile([restitution, friction], (len(Contact), 1)).astype(np.float64)


def resolve(x: np.ndarray, v: np.ndarray, inv_mass: np.ndarray, n_net: int, segments: np.ndarray,
            coef: np.ndarray) -> None:
    """One pass of :func:`contacts.resolve_ball_contacts` and :func:`contacts.resolve_ground` over
    bodies ``x``, ``v`` (net particles first, then balls of radius RADIUS), no poles, the substep
    having started at ``x``."""
    ordered, segment_start = index_segments(np.asarray(segments, dtype=np.int64).reshape(-1, 2), n_net)
    net = x[:n_net]
    box = np.concatenate([net.min(axis=0), net.max(axis=0)]) if n_net else np.array([np.inf] * 3 + [-np.inf] * 3)
    nowhere = Opening(2, 1, 100.0, (0, 1), (-1.0, -1.0), (1.0, 1.0))
    model = KernelModel(n_net=n_net, springs=Springs.of(np.zeros((0, 2)), np.zeros((0, 3)), n_net),
                        segments=ordered, segment_start=segment_start, poles=contact_tables.Poles.none(),
                        materials=contact_tables.Materials.of_table(coef), restitution_threshold=THRESHOLD, gravity=0.0,
                        drag=0.0, ball_radius=RADIUS, opening=nowhere.kernel_record(), ball_drag=0.0, wind=np.zeros(3))
    bodies = contacts.Bodies(x, v, inv_mass, x.copy())
    contacts.resolve_ball_contacts(bodies, model, box, np.zeros(n_net, dtype=np.int64))
    contacts.resolve_ground(bodies, model)


@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
def test_a_head_on_pair_leaves_with_momentum_kept_and_its_closing_speed_times_e(e: float) -> None:
    """Balls of 1 and 3 kg meeting head-on at 4 and -2 m/s, 1 cm overlapped: afterwards
    v1 = (m1 u1 + m2 u2 + m2 e (u2 - u1)) / (m1 + m2) and v2 = (... + m1 e (u1 - u2)) / (m1 + m2),
    and the overlap is gone, split by inverse mass (the heavier ball moves a quarter)."""
    m1, m2, u1, u2, overlap = 1.0, 3.0, 4.0, -2.0, 0.01
    x = np.array([[0.0, 0.0, 5.0], [2 * RADIUS - overlap, 0.0, 5.0]])
    v = np.array([[u1, 0.0, 0.0], [u2, 0.0, 0.0]])
    resolve(x, v, np.array([1 / m1, 1 / m2]), 0, np.zeros((0, 2)), coefficients(e, 0.3))
    total = m1 + m2
    assert v[0, 0] == pytest.approx((m1 * u1 + m2 * u2 + m2 * e * (u2 - u1)) / total, rel=1e-12, abs=1e-12)
    assert v[1, 0] == pytest.approx((m1 * u1 + m2 * u2 + m1 * e * (u1 - u2)) / total, rel=1e-12, abs=1e-12)
    assert m1 * v[0, 0] + m2 * v[1, 0] == pytest.approx(m1 * u1 + m2 * u2, abs=1e-12)
    assert v[1, 0] - v[0, 0] == pytest.approx(-e * (u2 - u1), abs=1e-12)
    assert not v[:, 1:].any()  # nothing off the line of centres
    assert x[0, 0] == pytest.approx(-overlap * m2 / total, abs=1e-15)
    assert x[1, 0] - x[0, 0] == pytest.approx(2 * RADIUS, abs=1e-15)


def test_balls_that_separate_keep_their_velocities_and_only_lose_the_overlap() -> None:
    x = np.array([[0.0, 0.0, 5.0], [2 * RADIUS - 0.01, 0.0, 5.0]])
    v = np.array([[-1.0, 0.5, 0.0], [1.0, 0.0, 0.0]])
    before = v.copy()
    resolve(x, v, np.array([1.0, 1.0]), 0, np.zeros((0, 2)), coefficients(0.5, 0.3))
    assert np.array_equal(v, before)
    assert x[1, 0] - x[0, 0] == pytest.approx(2 * RADIUS, abs=1e-15)


def test_a_ball_overlapping_a_free_particle_at_rest_gains_no_velocity() -> None:
    """Projection alone: the overlap is removed, split by inverse mass, and neither body moves
    afterwards."""
    overlap = 0.004
    x = np.array([[0.0, 0.0, 1.0], [0.0, 0.0, 1.0 + RADIUS - overlap]])
    v = np.zeros((2, 3))
    inv_mass = np.array([1 / NET_MASS, 1.0])
    resolve(x, v, inv_mass, 1, np.zeros((0, 2)), coefficients(0.5, 0.3))
    assert not v.any()
    assert x[1, 2] - x[0, 2] == pytest.approx(RADIUS, abs=1e-15)
    assert x[1, 2] == pytest.approx(1.0 + RADIUS - overlap + overlap * 1.0 / (1.0 + 1 / NET_MASS), abs=1e-15)
    assert not x[:, :2].any()


def test_a_ball_resting_on_a_fixed_particle_under_gravity_neither_sinks_nor_gains_speed() -> None:
    """1000 substeps of 2 ms: gravity pulls the ball 9.81 h^2 into the particle each substep and
    the contact (approaching at 9.81 h, below the restitution threshold: no bounce) puts it back
    at one radius, at rest. No sinking accumulates over the substeps."""
    h, g = 0.002, -9.81
    x = np.array([[0.0, 0.0, 1.0], [0.0, 0.0, 1.0 + RADIUS]])
    v = np.zeros((2, 3))
    inv_mass = np.array([0.0, 1.0])
    for _ in range(1000):
        v[1, 2] += g * h
        x[1, 2] += h * v[1, 2]
        resolve(x, v, inv_mass, 1, np.zeros((0, 2)), coefficients(0.5, 0.3))
        assert abs(v[1, 2]) < 1e-15
    assert x[1, 2] == pytest.approx(1.0 + RADIUS, abs=1e-12)
    assert not x[1, :2].any() and not v[1, :2].any()


@pytest.mark.parametrize(("share", "sticks"), [(0.99, True), (1.01, False)])
def test_the_friction_cone_holds_a_slip_within_mu_times_the_normal_impulse(share: float, sticks: bool) -> None:
    """A ball (1 kg) landing on a fixed particle at vn = 1 m/s with tangential speed vt: the
    normal impulse is (1 + e) m vn and friction takes at most mu times that. Just inside the
    cone (vt = 0.99 mu (1 + e) vn) the ball sticks (no tangential speed left); just outside
    (1.01) it slides on at vt - mu (1 + e) vn. Either way it leaves at e vn."""
    e, mu, vn, overlap = 0.5, 0.3, 1.0, 0.002
    bound = mu * (1 + e) * vn
    vt = share * bound
    x = np.array([[0.0, 0.0, 1.0 + RADIUS - overlap], [0.0, 0.0, 1.0]])  # the ball first, as ``a``
    v = np.array([[vt, 0.0, -vn], [0.0, 0.0, 0.0]])
    start = x.copy()
    contacts._pair_response(contacts.Bodies(x, v, np.array([1.0, 0.0]), start), 0, 1, 1, 0.0,
                            contacts.Touch(0.0, 0.0, -1.0, overlap), contact_tables.Material(e, mu), THRESHOLD)
    assert v[0, 2] == pytest.approx(e * vn, abs=1e-12)
    assert v[0, 0] == pytest.approx(0.0 if sticks else vt - bound, abs=1e-12)
    assert (v[0, 0] > 1e-6) == (not sticks)
    assert not v[1].any() and v[0, 1] == 0.0
    assert x[0, 2] == pytest.approx(1.0 + RADIUS, abs=1e-15) and np.array_equal(x[1], start[1])


@pytest.mark.parametrize("t", [0.5, 0.25])
def test_a_ball_pressing_on_a_spring_segment_is_pushed_out_along_its_normal(t: float) -> None:
    """A ball falling at 2 m/s onto the interior of a 1 m structural segment between two free
    0.2 kg particles, at the fraction ``t`` along it, 1 cm overlapped (the particles out of its
    reach). The impulse J is along the segment's normal (+z here): the ball takes +J, the end
    particles -(1 - t) J and -t J (barycentric shares), so momentum is kept and the point of the
    segment under the ball separates at e times the closing speed; the overlap is removed the
    same way, leaving the ball one radius from the segment."""
    e, fall, overlap = 0.5, 2.0, 0.01
    x = np.array([[-0.5, 0.0, 1.0], [0.5, 0.0, 1.0], [-0.5 + t, 0.0, 1.0 + RADIUS - overlap]])
    v = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, -fall]])
    masses = np.array([NET_MASS, NET_MASS, 1.0])
    assert np.linalg.norm(x[:2] - x[2], axis=1).min() > RADIUS  # only the segment's interior touches
    resolve(x, v, 1 / masses, 2, np.array([[0, 1]]), coefficients(e, 0.3))
    assert not v[:, :2].any()  # along the normal only
    assert x[2, 0] == pytest.approx(-0.5 + t, abs=1e-15) and not x[:, 1].any()
    impulse = masses[2] * (v[2, 2] + fall)
    assert impulse > 0.0
    assert masses[0] * v[0, 2] == pytest.approx(-(1 - t) * impulse, rel=1e-12)
    assert masses[1] * v[1, 2] == pytest.approx(-t * impulse, rel=1e-12)
    assert masses @ v[:, 2] == pytest.approx(-fall, abs=1e-12)  # momentum kept
    point = (1 - t) * v[0, 2] + t * v[1, 2]
    assert v[2, 2] - point == pytest.approx(e * fall, rel=1e-12)
    segment_z = (1 - t) * x[0, 2] + t * x[1, 2]
    assert x[2, 2] - segment_z == pytest.approx(RADIUS, abs=1e-15)
    assert x[0, 2] < 1.0 and x[1, 2] < 1.0  # the end particles took the reaction


def test_a_ball_beyond_a_segments_end_is_pushed_away_from_the_end_particle() -> None:
    """Beyond a segment's ends only the particle answers: a ball overlapping the end particle
    from outside the segment is pushed straight away from that particle."""
    x = np.array([[-0.5, 0.0, 1.0], [0.5, 0.0, 1.0], [0.5 + 0.2, 0.0, 1.0 + 0.2]])
    v = np.zeros((3, 3))
    depth = RADIUS - np.hypot(0.2, 0.2)
    resolve(x, v, np.array([0.0, 0.0, 1.0]), 2, np.array([[0, 1]]), coefficients(0.5, 0.3))
    assert x[2, 0] - 0.5 == pytest.approx(x[2, 2] - 1.0, abs=1e-15)  # along the diagonal from the particle
    assert np.hypot(x[2, 0] - 0.5, x[2, 2] - 1.0) == pytest.approx(RADIUS, abs=1e-15)
    assert depth > 0.0 and not v.any()
