"""The first step from an empty numba cache: what compiles, and what the user is told.

The cold run compiles in a subprocess with its own empty ``NUMBA_CACHE_DIR`` (about 15 s)."""

from __future__ import annotations

import io

import numpy as np
import pytest
from numba import njit
from numba.core import event
from numba.core.errors import TypingError

from netgym.bench.first_step import cold_and_warm
from netgym.config import load_scene
from netgym.physics import stepping
from netgym.physics.compile_notice import MESSAGE, SHOWN, CompileNotice
from netgym.physics.integrators import Scratch
from netgym.physics.kinds import Integrator
from netgym.physics.model import Settings
from netgym.physics.simulator import Simulator

INTEGRATOR_KERNELS = {
    Integrator.EXPLICIT_EULER: "step_euler",
    Integrator.SYMPLECTIC_EULER: "step_euler",
    Integrator.RK4: "step_rk4",
    Integrator.IMPLICIT_EULER: "step_implicit_euler",
    Integrator.IMEX_EULER: "step_imex_euler",
}


@pytest.mark.slow
def test_a_cold_first_step_compiles_only_the_scenes_integrator_and_says_so_once(monkeypatch) -> None:
    monkeypatch.delenv(SHOWN, raising=False)
    cold, warm = cold_and_warm("NetCatch-v0")
    used = INTEGRATOR_KERNELS[Integrator.IMEX_EULER]   # the basket's integrator and its pause's
    assert f"netgym.physics.integrators.{used}" in cold.kernels
    compiled = {name for name in INTEGRATOR_KERNELS.values() if f"netgym.physics.integrators.{name}" in cold.kernels}
    assert compiled == {used}
    assert cold.stderr.count(MESSAGE) == 1
    assert MESSAGE not in warm.stderr
    assert "netgym.physics.stepping._step" not in warm.kernels   # loaded inside relax, not compiled


def test_settings_are_of_their_integrators_class() -> None:
    for integrator in Integrator:
        settings = Settings.make(integrator, 1e-3, 0.25, 1e-8, 100, 1e3)
        assert settings.integrator == integrator and type(settings).INTEGRATOR == integrator
        assert type(settings).__name__.lower() == integrator.label.replace("_", "") + "settings"
    config = load_scene("basket").simulation
    settings = Settings.of(config, Integrator.RK4, 1e-3)
    assert type(settings).INTEGRATOR == Integrator.RK4
    assert settings == (Integrator.RK4, 1e-3, config.max_ball_travel, config.cg_tolerance, config.cg_max_iterations,
                        config.divergence_speed)


@pytest.mark.slow
def test_settings_that_name_no_integrator_are_a_clear_error(basket: Simulator) -> None:
    s, model = basket.state, basket.kernel_model
    plain = Settings(Integrator.IMEX_EULER, 1e-3, 0.25, 1e-8, 100, 1e3)
    with pytest.raises(TypingError, match="smooth_step takes settings of one integrator"):
        stepping.advance(s.x.copy(), s.v.copy(), s.inv_mass, s.entered, model, plain, 1,
                         Scratch.sized(len(s.x), len(model.springs.pairs)), stepping.new_counters())


def test_the_notice_is_written_once_at_the_first_compilation_of_the_package(monkeypatch) -> None:
    monkeypatch.delenv(SHOWN, raising=False)
    stream = io.StringIO()
    notice = CompileNotice(package=__name__, stream=stream)
    event.register("numba:compile", notice)
    try:
        square = njit(lambda x: x * x)
        square(2.0)
        assert stream.getvalue() == MESSAGE + "\n"
        square(np.arange(3))   # another compilation: no second line
        assert stream.getvalue() == MESSAGE + "\n"
    finally:
        event.unregister("numba:compile", notice)
    monkeypatch.delenv(SHOWN, raising=False)
    quiet = io.StringIO()
    elsewhere = CompileNotice(package="no_such_package", stream=quiet)
    event.register("numba:compile", elsewhere)
    try:
        njit(lambda x: x + 1)(1)
    finally:
        event.unregister("numba:compile", elsewhere)
    assert quiet.getvalue() == ""
