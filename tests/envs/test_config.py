"""Scene files: defaults, named errors for bad fields, round trips."""

from __future__ import annotations

import pytest

from netgym.config import BUILTIN_SCENES, SceneConfig, load_scene, loads, to_toml
from netgym.errors import ConfigError


@pytest.mark.parametrize("name", BUILTIN_SCENES)
def test_builtin_scenes_load(name: str) -> None:
    cfg = load_scene(name)
    assert isinstance(cfg, SceneConfig)
    assert cfg.name == name
    assert cfg.simulation.dt > 0 and cfg.ball.radius > 0


def test_basket_has_the_seed_parameters() -> None:
    cfg = load_scene("basket")
    assert cfg.net.particles == (10, 10, 15)
    assert cfg.net.particle_mass == 0.2
    for kind in ("structural", "shear", "bending"):
        spring = getattr(cfg.springs, kind)
        assert (spring.ks, spring.kd) == (1500.0, 50.0)
    assert (cfg.ball.radius, cfg.ball.mass) == (0.3, 1.0)
    assert cfg.net.open_face == "+z" and cfg.net.upper[2] == 3.0


@pytest.mark.parametrize(
    ("field", "value", "message"),
    [
        ("simulation.dt", 0.0, "simulation.dt = 0.0 is out of range; allowed: (0, 0.05]"),
        ("simulation.dt", 1.0, "simulation.dt = 1.0 is out of range"),
        ("simulation.dt", float("nan"), "simulation.dt = nan is out of range"),
        ("simulation.integrator", "verlet", "simulation.integrator = 'verlet' is not allowed"),
        ("simulation.cg_max_iterations", 2.5, "simulation.cg_max_iterations must be an integer"),
        ("net.particles", [10, 2, 15], "net.particles[1] = 2 is out of range; allowed: [3, 200]"),
        ("net.particles", [10, 10], "net.particles must be a list of 3 numbers"),
        ("net.open_face", "top", "net.open_face = 'top' is not allowed"),
        ("net.fix_side_edges", 1, "net.fix_side_edges must be true or false"),
        ("net.particle_mass", -0.2, "net.particle_mass = -0.2 is out of range"),
        ("ball.radius", "big", "ball.radius must be a number"),
        ("springs.shear.ks", 0.0, "springs.shear.ks = 0.0 is out of range"),
        ("contact.ball_net.restitution", 1.5, "contact.ball_net.restitution = 1.5 is out of range; allowed: [0, 1]"),
        ("net.lower", [1.0, -1.0, 0.5], "net.lower[0] = 1.0 must be below net.upper[0] = 1.0"),
        ("net.lower", [-1.0, -1.0, -0.5], "net.lower[2] = -0.5 is below the ground"),
        ("throw.speed", [20.0, 5.0], "throw.speed = [20.0, 5.0] must be an increasing [min, max] pair"),
        ("ball", 3, "ball must be a table"),
    ],
)
def test_bad_field_names_the_field_and_range(field: str, value: object, message: str) -> None:
    with pytest.raises(ConfigError) as info:
        load_scene("basket", {field: value})
    assert message in str(info.value)


def test_unknown_and_missing_fields_are_named() -> None:
    text = to_toml(load_scene("basket"))
    with pytest.raises(ConfigError, match=r"unknown field simulation\.speedup"):
        loads(text.replace("[simulation]\n", "[simulation]\nspeedup = 2\n"))
    with pytest.raises(ConfigError, match=r"missing field ball\.mass"):
        loads("\n".join(line for line in text.splitlines() if not line.startswith("mass =")))
    with pytest.raises(ConfigError, match="unknown field 'simulation.nope'"):
        load_scene("basket", {"simulation.nope": 1})


def test_invalid_toml_and_missing_file() -> None:
    with pytest.raises(ConfigError, match="not valid TOML"):
        loads("name = ")
    with pytest.raises(ConfigError, match="neither a built-in scene"):
        load_scene("no/such/scene.toml")


def test_a_value_is_data_never_code() -> None:
    scene = load_scene("basket")
    text = to_toml(scene).replace(f"dt = {scene.simulation.dt!r}", 'dt = "__import__(\'os\').getcwd()"')
    assert "__import__" in text
    with pytest.raises(ConfigError, match="simulation.dt must be a number"):
        loads(text)


@pytest.mark.parametrize("name", BUILTIN_SCENES)
def test_round_trip_through_toml_text_and_file(name: str, tmp_path) -> None:
    cfg = load_scene(name)
    assert loads(to_toml(cfg)) == cfg
    path = tmp_path / "scene.toml"
    path.write_text(to_toml(cfg))
    assert load_scene(path) == cfg
    changed = cfg.replace({"simulation.dt": 2.5e-4, "net.particles": [5, 6, 7]})
    assert loads(to_toml(changed)) == changed
    assert changed.simulation.dt == 2.5e-4 and changed.net.particles == (5, 6, 7)


def test_configs_are_frozen() -> None:
    cfg = load_scene("basket")
    with pytest.raises(AttributeError):
        cfg.simulation.dt = 1.0  # type: ignore[misc]
