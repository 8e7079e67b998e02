"""What long starts say while they last: worker processes' progress lines do not overwrite each
other (training's environment workers say when each is ready: tests/agents/test_agents.py)."""

from __future__ import annotations

import io
import multiprocessing
import os
from types import SimpleNamespace

from netgym.physics.progress import Progress


def _advance(progress: Progress, simulated: list[float]) -> None:
    """Report ``simulated`` times to ``progress`` as a simulation's observer would see them."""
    for t in simulated:
        progress(SimpleNamespace(state=SimpleNamespace(time=t)))
    progress.close()


def test_a_worker_writes_whole_lines_named_by_its_process_and_the_main_process_one_line_in_place() -> None:
    worker, main = io.StringIO(), io.StringIO()
    _advance(Progress("settling the net", 60.0, quiet=0.0, every=0.0, stream=worker, worker=True), [0.0, 1.0, 2.0])
    _advance(Progress("settling the net", 60.0, quiet=0.0, every=0.0, stream=main, worker=False), [0.0, 1.0, 2.0])
    lines = worker.getvalue().splitlines(keepends=True)
    assert len(lines) == 1   # a worker reports at most every WORKER_EVERY s
    assert lines[0].startswith(f"process {os.getpid()}, settling the net: 1.00 of at most 60 s") and "\r" not in lines[0]
    assert main.getvalue().startswith("\rsettling the net: 1.00") and main.getvalue().count("\r") == 2
    assert main.getvalue().endswith("\n") and main.getvalue().count("\n") == 1


def _is_worker(answer: multiprocessing.Queue) -> None:
    answer.put(Progress("x", 1.0).worker)


def test_progress_knows_a_multiprocessing_worker_from_the_main_process() -> None:
    assert not Progress("x", 1.0).worker
    context = multiprocessing.get_context("fork")
    answer = context.Queue()
    child = context.Process(target=_is_worker, args=(answer,))
    child.start()
    child.join(timeout=60)
    assert answer.get(timeout=10) is True
