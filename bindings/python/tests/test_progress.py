"""Progress reports: tqdm bars, user callables, cancellation and callback exceptions."""

from __future__ import annotations

import pytest

import progsim
from conftest import grid


@pytest.fixture
def sim():
    with progsim.Hierarchy(*grid()) as hierarchy, progsim.Simulation(
        hierarchy, pinned=[6, 8]
    ) as simulation:
        yield simulation


def test_callable_sees_every_step(sim):
    calls = []
    sim.step_preview(4, progress=lambda done, total, phase: calls.append((done, total, phase)))
    assert calls == [(1, 4, "preview"), (2, 4, "preview"), (3, 4, "preview"), (4, 4, "preview")]
    assert sim.level_stats().steps == 4


def test_cancelling_callable_raises_cancelled(sim):
    calls = []

    def cancel_after_two(done, total, phase):
        calls.append(done)
        return done >= 2

    with pytest.raises(progsim.CancelledError, match="after 2 of 10") as raised:
        sim.step_preview(10, progress=cancel_after_two)
    assert raised.value.status == "PS_ERROR_CANCELLED" and raised.value.code == 8
    assert calls == [1, 2]
    assert sim.level_stats().steps == 2  # the state of the last completed step
    sim.step_preview(1)  # the callback is gone: later calls run normally
    assert sim.level_stats().steps == 3


def test_exception_in_callback_is_reraised_after_the_call(sim):
    class Boom(Exception):
        pass

    def explode(done, total, phase):
        if done == 3:
            raise Boom("from the callback")

    with pytest.raises(Boom, match="from the callback"):
        sim.step_preview(10, progress=explode)
    assert sim.level_stats().steps == 3  # cancelled right after the failing report


def test_keyboard_interrupt_in_callback_cancels_cleanly(sim):
    def interrupt(done, total, phase):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        sim.step_preview(5, progress=interrupt)
    assert sim.level_stats().steps == 1
    sim.step_preview(1)
    assert sim.level_stats().steps == 2


def test_calling_progsim_from_a_callback_is_refused(sim):
    def reenter(done, total, phase):
        sim.positions()

    with pytest.raises(progsim.WrongCallOrderError, match="progress callback"):
        sim.step_preview(3, progress=reenter)
    with pytest.raises(progsim.WrongCallOrderError):
        sim.step_preview(3, progress=lambda *report: sim.close())
    assert not sim.closed
    assert sim.positions().shape == (9, 3)  # usable again after the call


def test_tqdm_bar(sim, capsys):
    sim.step_preview(3, progress=True)
    err = capsys.readouterr().err
    assert "preview" in err and "3/3" in err
    sim.step_preview(2, progress=False)
    assert capsys.readouterr().err == ""
    assert sim.level_stats().steps == 5


def test_bad_progress_argument(sim):
    with pytest.raises(progsim.InvalidArgumentError, match="progress"):
        sim.step_preview(1, progress="yes")
    assert sim.level_stats().steps == 0


def test_refine_takes_progress_too(sim):
    with pytest.raises(progsim.OutOfRangeError):
        sim.refine(progress=True)


def test_ctrl_c_stops_a_long_preview():
    import signal
    import subprocess
    import sys
    import textwrap

    from conftest import MESH

    script = textwrap.dedent(f"""
        import sys
        import progsim
        h = progsim.Hierarchy.from_file({str(MESH)!r})
        sim = progsim.Simulation(h, pinned=[420, 440])

        def report(done, total, phase):
            if done == 1:
                print("started", flush=True)

        try:
            sim.step_preview(10000, progress=report)
        except KeyboardInterrupt:
            print("interrupted after", sim.level_stats().steps, flush=True)
        """)
    child = subprocess.Popen(
        [sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    try:
        assert child.stdout.readline().strip() == "started"
        child.send_signal(signal.SIGINT)
        out, err = child.communicate(timeout=120)
    finally:
        child.kill()
    assert child.returncode == 0, err
    steps = int(out.split()[-1])
    assert 1 <= steps < 10000
