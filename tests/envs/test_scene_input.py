"""Scene files and command-line overrides as they are read: text that is not UTF-8, overrides
parsed as JSON, numpy numbers, and scenes that would run for hours, refused at once."""

from __future__ import annotations

import numpy as np
import pytest

from netgym.config import load_scene
from netgym.envs import NetCatchEnv
from netgym.errors import ConfigError


def test_scene_file_that_is_not_text_gets_a_config_error(tmp_path) -> None:
    path = tmp_path / "scene.toml"
    path.write_bytes(bytes(range(256)))
    with pytest.raises(ConfigError, match="is not UTF-8 text"):
        load_scene(path)


def test_command_line_overrides_are_read_as_json_where_they_parse() -> None:
    from netgym.arguments import parse_overrides

    assert parse_overrides("simulation.dt=0.001,capture_rule=line,simulation.cg_max_iterations=50") == {
        "simulation.dt": 0.001, "capture_rule": "line", "simulation.cg_max_iterations": 50}


def test_numpy_numbers_are_accepted_in_overrides() -> None:
    cfg = load_scene("basket", {"simulation.time_limit": np.float32(4.0), "simulation.cg_max_iterations": np.int64(50)})
    assert cfg.simulation.time_limit == 4.0 and cfg.simulation.cg_max_iterations == 50


@pytest.mark.parametrize(("overrides", "message"), [
    ({"simulation.dt": 1e-9}, r"simulation\.dt = 1e-09 s .* use simulation\.dt >= 2e-06 s"),
    ({"net.particles": [200, 200, 200]}, r"net\.particles = \[200, 200, 200\] makes up to 237,608 net particles"),
])
def test_scenes_that_would_run_for_hours_are_refused_at_once(overrides: dict, message: str) -> None:
    with pytest.raises(ConfigError, match=message):
        load_scene("basket", overrides)
    with pytest.raises(ConfigError, match=message):
        NetCatchEnv(overrides=overrides)
