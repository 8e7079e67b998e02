"""Peers: the same net (no contacts) in a NumPy vectorised implementation and in MuJoCo, at the
same dt as netgym, each against the same fine reference."""

from __future__ import annotations

import time

import numpy as np

from netgym.bench.settings import PEER_SETTING, REFERENCE
from netgym.physics.simulator import Simulator


def numpy_peer(dt: float, seconds: float) -> tuple[float, np.ndarray]:
    """The same net (springs, dampers, drag, gravity; no contacts) in vectorised NumPy with
    symplectic Euler, released from its built shape: (steps per second, final positions)."""
    sim = Simulator("basket")
    m = sim.model
    x = m.geometry.positions.copy()
    v = np.zeros_like(x)
    i, j = m.springs[:, 0], m.springs[:, 1]
    rest, ks, kd = m.spring_params.T
    w = m.net_inv_mass[:, None]
    free = (m.net_inv_mass > 0)[:, None]
    g = np.array([0.0, 0.0, m.gravity])
    steps = round(seconds / dt)
    start = time.perf_counter()
    for _ in range(steps):
        d = x[i] - x[j]
        length = np.linalg.norm(d, axis=1)
        u = d / length[:, None]
        mag = -ks * (length - rest) - kd * np.sum((v[i] - v[j]) * u, axis=1)
        f = np.zeros_like(x)
        np.add.at(f, i, mag[:, None] * u)
        np.add.at(f, j, -mag[:, None] * u)
        v += dt * (w * f - m.drag * v + g) * free
        x += dt * v
    return steps / (time.perf_counter() - start), x


def mujoco_peer(dt: float, seconds: float) -> tuple[float, np.ndarray] | None:
    """The same net in MuJoCo (``bench`` extra): one body with three slide joints per free
    particle (joint damping = air drag), a site per particle, one spatial tendon per spring
    (stiffness ks, damping kd, spring length = rest length), contacts off, MuJoCo's Euler
    integrator (damping implicit) at the same dt. Returns (steps per second, final positions),
    or None when MuJoCo is not installed."""
    try:
        import mujoco
    except ImportError:
        return None
    sim = Simulator("basket")
    m = sim.model
    pos, fixed, mass = m.geometry.positions, m.geometry.fixed, sim.config.net.particle_mass
    damping = m.drag * mass
    xml = [f'<mujoco><option timestep="{dt}" integrator="Euler" gravity="0 0 {m.gravity}">'
           '<flag contact="disable"/></option><worldbody>']
    for k, p in enumerate(pos):
        if fixed[k]:
            xml.append(f'<site name="s{k}" pos="{p[0]} {p[1]} {p[2]}"/>')
            continue
        joints = "".join(f'<joint type="slide" axis="{a}" damping="{damping}"/>' for a in ("1 0 0", "0 1 0", "0 0 1"))
        xml.append(f'<body pos="{p[0]} {p[1]} {p[2]}">{joints}'
                   f'<inertial pos="0 0 0" mass="{mass}" diaginertia="1e-6 1e-6 1e-6"/><site name="s{k}"/></body>')
    xml.append("</worldbody><tendon>")
    for (i, j), (rest, ks, kd) in zip(m.springs, m.spring_params):
        xml.append(f'<spatial stiffness="{ks}" damping="{kd}" springlength="{rest}">'
                   f'<site site="s{i}"/><site site="s{j}"/></spatial>')
    xml.append("</tendon></mujoco>")
    model = mujoco.MjModel.from_xml_string("".join(xml))
    data = mujoco.MjData(model)
    mujoco.mj_step(model, data)  # warm-up
    mujoco.mj_resetData(model, data)
    steps = round(seconds / dt)
    start = time.perf_counter()
    for _ in range(steps):
        mujoco.mj_step(model, data)
    rate = steps / (time.perf_counter() - start)
    x = pos.copy()
    x[~fixed] += data.qpos.reshape(-1, 3)
    return rate, x


def peers(quick: bool, reference_setting: tuple[str, float] = REFERENCE) -> list[dict]:
    """netgym and the NumPy peer on the same released net at the same dt, against the same
    reference (integrator, dt)."""
    seconds = 0.05 if quick else 0.2
    dt = PEER_SETTING[1]

    def released(integrator: str, step: float) -> tuple[float, np.ndarray]:
        sim = Simulator("basket", {"simulation.integrator": integrator, "simulation.dt": step}, check_stability=False)
        sim.step(1)
        sim.state.x[:] = sim.model.geometry.positions
        sim.state.v[:] = 0.0
        start = time.perf_counter()
        sim.step(round(seconds / step))
        return round(seconds / step) / (time.perf_counter() - start), sim.state.x.copy()

    _, reference = released(*reference_setting)
    ours_rate, ours = released(*PEER_SETTING)
    peer_rate, peer = numpy_peer(dt, seconds)

    def rms(x: np.ndarray) -> float:
        return float(np.sqrt(np.mean(np.sum((x - reference) ** 2, axis=1))))

    rows = [{"system": "netgym (numba kernels), symplectic Euler", "steps_per_s": ours_rate, "error": rms(ours)},
            {"system": "NumPy vectorised, symplectic Euler", "steps_per_s": peer_rate, "error": rms(peer)}]
    mujoco_result = mujoco_peer(dt, seconds)
    if mujoco_result is not None:
        rows.append({"system": "MuJoCo (slide joints + spatial spring tendons), Euler", "steps_per_s": mujoco_result[0],
                     "error": rms(mujoco_result[1])})
    return rows
