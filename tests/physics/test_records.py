"""The named records the kernels take instead of arrays whose slots meant things by position."""

from __future__ import annotations

import numpy as np

from netgym.config import load_scene
from netgym.physics.model.contact_tables import Materials
from netgym.physics.integration import RestTest
from netgym.kinds import Contact
from netgym.physics.model.model import Model


def test_each_contact_kind_has_its_material_by_name() -> None:
    table = np.arange(2.0 * len(Contact)).reshape(len(Contact), 2)
    materials = Materials.of_table(table)
    for kind in Contact:
        assert getattr(materials, kind.label) == (table[kind, 0], table[kind, 1])


def test_the_kernel_model_names_the_scenes_poles_opening_and_materials() -> None:
    config = load_scene("goal")
    model = Model.from_config(config)
    k = model.kernel
    assert np.array_equal(np.hstack([k.poles.start, k.poles.end]), model.geometry.poles)
    assert np.all(k.poles.radius == config.net.pole_radius)
    o = model.opening
    assert (k.opening.axis, k.opening.sign, k.opening.plane) == (o.axis, o.sign, o.plane)
    assert (k.opening.u, k.opening.w) == o.tangent_axes
    assert (k.opening.u_lo, k.opening.w_lo, k.opening.u_hi, k.opening.w_hi) == (*o.tangent_lower, *o.tangent_upper)
    assert k.materials.ball_net == (config.contact.ball_net.restitution, config.contact.ball_net.friction)
    assert k.materials.net_ground == (config.contact.net_ground.restitution, config.contact.net_ground.friction)


def test_a_new_rest_test_has_recorded_nothing_and_is_not_at_rest() -> None:
    rest = RestTest((4, 3), window=5, displacement=1e-3, damped=False)
    memory = rest.record.memory[0]
    assert (memory["recorded"], memory["kinetic"], memory["steps"]) == (0, np.inf, 0)
    assert rest.steps == 0 and not rest.at_rest and rest.record.history.shape == (5, 4, 3)
    assert rest.record.damped is False and rest.record.displacement == 1e-3
