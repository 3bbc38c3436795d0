"""Time-windowed refinement (Simulation.refine_window, progsim.windows): windows on two Dask
workers against the same windows refined serially, the first window against the whole
refinement, the seams' continuity against the interior's, and misuse."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import progsim
from progsim.windows import refine_in_windows, second_differences, window_bounds
from test_sweep import SCENE_TEXT

STEPS = 20

SERIAL_SCRIPT = """
import sys
import numpy as np
from progsim.sweep import _specs
from progsim.windows import refine_window_task, window_bounds
from test_sweep import SCENE_TEXT
spec = _specs(SCENE_TEXT, [{}], int(sys.argv[2]), None)[0]
windows = [refine_window_task(spec, a, b).positions for a, b in window_bounds(spec.steps, 2)]
np.savez(sys.argv[1], serial=refine_window_task(spec, 0, spec.steps).positions, *windows)
"""


def serial_windows(tmp_path: Path):
    """The two windows and the whole refinement, serially in a fresh one-thread process."""
    env = dict(os.environ, OMP_NUM_THREADS="1", PYTHONPATH=str(Path(__file__).parent))
    out = tmp_path / "serial.npz"
    subprocess.run([sys.executable, "-c", SERIAL_SCRIPT, str(out), str(STEPS)], env=env, check=True)
    with np.load(out) as saved:
        return [saved["arr_0"], saved["arr_1"]], saved["serial"]


def test_window_bounds():
    assert window_bounds(20, 2) == [(0, 10), (10, 20)]
    assert window_bounds(10, 3) == [(0, 3), (3, 7), (7, 10)]
    with pytest.raises(progsim.InvalidArgumentError, match="windows"):
        window_bounds(4, 5)


def test_windows_on_two_workers_match_serial_windows_and_report_their_seams(client, tmp_path):
    expected_windows, serial = serial_windows(tmp_path)
    joined = refine_in_windows(SCENE_TEXT, 2, client, steps=STEPS)
    assert [(w.first, w.last) for w in joined.windows] == [(0, 10), (10, 20)]
    for window, expected in zip(joined.windows, expected_windows):
        np.testing.assert_array_equal(window.positions, expected)  # bit for bit
    # The first window is the serial refinement's start; the joined animation has every frame.
    np.testing.assert_array_equal(joined.windows[0].positions, serial[:11])
    assert joined.positions.shape == serial.shape == (STEPS + 1, 81, 3)
    joined.serial = serial
    (seam,) = joined._seams()
    print("seam:", json.dumps(seam))
    # The window restarts from the refined coarse frame: a jump, but the discrete acceleration
    # at the seam stays within a small multiple of the interior's largest (measured when
    # written: see the README's "Time windows").
    assert seam["frame"] == 10 and seam["jump"] > 0.0
    assert seam["second_difference"] < 4.0 * seam["interior_max"]
    assert seam["serial_second_difference"] <= seam["interior_max"] * 4.0
    joined.write_csv(tmp_path / "seams.csv")
    assert (tmp_path / "seams.csv").read_text().startswith("frame,jump,second_difference")


def test_refine_window_misuse():
    with progsim.Simulation.from_scene(SCENE_TEXT) as sim:
        sim.step_preview(4)
        with pytest.raises(progsim.InvalidArgumentError, match="window of steps 3 to 2"):
            sim.refine_window(3, 2)
        sim.refine_window(1, 4)
        assert sim.dynamic_level_stats(1).first_step == 1
        assert sim.num_frames(1) == 4
        assert np.isfinite(second_differences(np.stack([f.positions for f in sim.frames(1)]))).all()
    with pytest.raises(progsim.InvalidArgumentError, match="two levels"):
        refine_in_windows(
            SCENE_TEXT.replace('"levels": [25]', '"levels": []'), 2, "serial", steps=4
        )
