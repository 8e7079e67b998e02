"""The first step from an empty numba cache: what compiles, and what the user is told.

The cold run compiles in a subprocess with its own empty ``NUMBA_CACHE_DIR``."""

from __future__ import annotations

import io
import json

import numpy as np
import pytest
from numba import njit
from numba.core import event
from numba.core.errors import TypingError

from agents.bench import first_step_text
from agents.bench.first_step import FirstStep, add_runs, cold_and_warm, latest_runs, run_figures
from netgym.config import load_scene
from netgym.errors import InvalidArgumentError
from netgym.physics import stepping
from netgym.physics.compile_notice import MESSAGE, SHOWN, CompileNotice
from netgym.physics.kernels.integrators import Scratch
from netgym.kinds import ContactModel, Integrator
from netgym.physics.model.model import Settings
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
    assert f"netgym.physics.kernels.integrators.{used}" in cold.kernels
    compiled = {name for name in INTEGRATOR_KERNELS.values() if f"netgym.physics.kernels.integrators.{name}" in cold.kernels}
    assert compiled == {used}
    # the new net settles without balls: the balls' contacts wait for the first throw that reaches the net
    assert "netgym.physics.kernels.impulse_contacts.resolve_ground" in cold.kernels
    assert "netgym.physics.kernels.impulse_contacts.resolve_ball_contacts" not in cold.kernels
    assert cold.stderr.count(MESSAGE) == 1 and " kernels compiled in " in cold.stderr
    assert MESSAGE not in warm.stderr and " kernels compiled in " not in warm.stderr
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
                        config.divergence_speed, config.contact_stiffness)
    assert type(settings).CONTACT_MODEL == ContactModel.IMPULSE
    compliant = Settings.make(Integrator.RK4, 1e-3, 0.25, 1e-8, 100, 1e3, ContactModel.COMPLIANT, 2e4)
    assert type(compliant).__name__ == "Rk4CompliantSettings" and type(compliant).CONTACT_MODEL == ContactModel.COMPLIANT


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
    notice = CompileNotice(package=__name__, stream=stream, clock=lambda: 0.0)  # every compilation quick: no progress
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


def _listening(notice: CompileNotice, work) -> None:
    """Run ``work()`` with ``notice`` registered for numba's compile events."""
    event.register("numba:compile", notice)
    try:
        work()
    finally:
        event.unregister("numba:compile", notice)


def test_a_long_compilation_shows_the_kernels_compiled_and_the_one_compiling_now(monkeypatch) -> None:
    monkeypatch.delenv(SHOWN, raising=False)
    ticks = iter(range(100))
    stream = io.StringIO()
    notice = CompileNotice(package=__name__, stream=stream, quiet=1.0, clock=lambda: float(next(ticks)))
    inner = njit(lambda x: x + 1.0)
    outer = njit(lambda x: inner(x) * 2.0)
    _listening(notice, lambda: outer(1.0))
    header, progress = stream.getvalue().split("\n", 1)
    assert header == MESSAGE
    shown = progress.split("\r")[1:]   # one line rewritten in place, ended once the outermost kernel is
    assert [line.split(" in ")[0] for line in shown] == ["netgym: 1 kernels compiled", "netgym: 2 kernels compiled"]
    assert shown[0] == f"netgym: 1 kernels compiled in 1 s, compiling {__name__}.<lambda>"
    assert shown[1] == "netgym: 2 kernels compiled in 2 s".ljust(len(shown[0])) + "\n"
    assert notice.spent == 2.0


def test_a_process_whose_parent_wrote_the_notice_writes_nothing(monkeypatch) -> None:
    monkeypatch.setenv(SHOWN, "1")
    stream = io.StringIO()
    ticks = iter(range(100))
    notice = CompileNotice(package=__name__, stream=stream, quiet=0.0, clock=lambda: float(next(ticks)))
    _listening(notice, lambda: njit(lambda x: x - 1.0)(1.0))
    assert stream.getvalue() == "" and notice.compiled == 1


def _run(label: str, cold_seconds: float, load: float = 1.0) -> dict:
    cold = FirstStep(cold_seconds, cold_seconds / 2, 5.0, 2.5, {"a": 1, "b": 2}, "")
    warm = FirstStep(1.25, 1.0, 0.5, 0.25, {}, "")
    return run_figures(label, load, cold, warm)


def test_runs_replace_those_of_their_label_and_the_quote_reads_the_label_written_last(tmp_path) -> None:
    path = tmp_path / "first_step.json"
    add_runs(path, "NetCatch-v0", [_run("before", 30.0), _run("before", 31.0)])
    add_runs(path, "NetCatch-v0", [_run("after", 12.0, load=2.0), _run("after", 14.04, load=3.0)])
    add_runs(path, "NetCatch-v0", [_run("before", 29.0)])   # measured again: replaces both earlier runs
    figures = json.loads(path.read_text())["figures"]
    assert [run["label"] for run in figures["runs"]] == ["after", "after", "before"]
    assert figures["runs"][0]["cold"] == {"seconds": 12.0, "cpu_seconds": 6.0, "aimed_seconds": 5.0,
                                          "aimed_cpu_seconds": 2.5}
    assert figures["runs"][0]["cold_kernels"] == 2
    assert [run["cold"]["seconds"] for run in latest_runs(figures)] == [29.0]
    add_runs(path, "NetCatch-v0", [_run("after", 12.0, load=2.0), _run("after", 14.04, load=3.0)])
    text = first_step_text.block(path)
    assert "took 12.0-14.0 s, and the first throw to reach the net 5.0 s more" in text
    assert "numba's cache: 1.2 s to the first step" in text and "2 runs at load 2.0-3.0 on" in text
    with pytest.raises(InvalidArgumentError, match="NetCatch-v0, not NetCatchGoal-v0"):
        add_runs(path, "NetCatchGoal-v0", [_run("after", 12.0)])
