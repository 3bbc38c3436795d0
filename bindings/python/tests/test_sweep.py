"""Design sweeps (progsim.sweep): grids, Dask runs against serial ones, faults, the table,
the contact sheet, refinement of a chosen run, the command line, and the GIL."""

from __future__ import annotations

import csv
import json
import os
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import progsim
from progsim.__main__ import main as cli_main, parse_param
from progsim.scene_text import load_scene, override
from progsim.sweep import Range, grid, sampled, sweep

#: A small swinging cloth: 9 x 9 vertices pinned at two corners, two levels (25 and 81
#: vertices), dynamic. Comments as in the bundled scene files.
SCENE_TEXT = """// a cloth swinging from two corners
{
  "name": "sweep_test",
  "simulation": { "mode": "dynamic", "time_step": 0.02, "duration": 0.2 },
  "gravity": [0, -9.81, 0],
  "effects": ["membrane", "bending", "gravity"],
  "solver": { "newton_tolerance": 1e-6, "max_newton_iterations": 50 },
  "bodies": [ { "name": "cloth",
    "mesh": { "generator": "grid", "width": 1.0, "height": 1.0, "nx": 8, "ny": 8 },
    "material": { "youngs_modulus": 5e5, "poisson_ratio": 0.3, "thickness": 5e-4,
                  "density": 400 } } ],
  /* both top corners */
  "handles": [
    { "body": "cloth", "box": { "min": [-0.01, 0.99, -0.01], "max": [0.01, 1.01, 0.01] } },
    { "body": "cloth", "box": { "min": [0.99, 0.99, -0.01], "max": [1.01, 1.01, 0.01] } } ],
  "progressive": { "levels": [25] }
}
"""

#: Four runs: two stiffnesses × two initial velocities out of the cloth's plane.
PARAMETERS = {
    "material.youngs_modulus": Range(2e5, 8e5, 2),
    "initial_velocity": [[0.0, 0.0, 0.5], [0.0, 0.0, -1.0]],
}

#: Columns that depend on the machine, not on the simulation.
TIMING = ("seconds", "bytes_in", "bytes_out")

SERIAL_SCRIPT = """
import json, sys
import numpy as np
from progsim.sweep import Range, sweep
from test_sweep import PARAMETERS, SCENE_TEXT
runs = sweep(SCENE_TEXT, PARAMETERS, "serial", steps=int(sys.argv[2]), progress=False)
np.savez(sys.argv[1] + ".npz", *[r.positions for r in runs.results])
json.dump(runs.rows(), open(sys.argv[1] + ".json", "w"))
"""


def outcome(rows):
    """The rows without their timing columns."""
    return [{k: v for k, v in row.items() if k not in TIMING} for row in rows]


def serial_reference(tmp_path: Path, steps: int):
    """The sweep run serially in a fresh process with one OpenMP thread: (rows, positions)."""
    env = dict(os.environ, OMP_NUM_THREADS="1", PYTHONPATH=str(Path(__file__).parent))
    stem = tmp_path / f"serial_{steps}"
    subprocess.run(
        [sys.executable, "-c", SERIAL_SCRIPT, str(stem), str(steps)],
        env=env,
        check=True,
    )
    rows = json.loads(stem.with_suffix(".json").read_text())
    with np.load(stem.with_suffix(".npz")) as saved:
        positions = [saved[f"arr_{i}"] for i in range(len(saved.files))]
    return rows, positions


def test_grid_and_samples():
    runs = grid({"a": [1, 2], "b": Range(0.0, 1.0, 3)})
    assert runs == [{"a": a, "b": b} for a in (1, 2) for b in (0.0, 0.5, 1.0)]
    drawn = sampled({"a": Range(2.0, 3.0, 1), "b": ["x", "y"]}, samples=50, seed=4)
    assert len(drawn) == 50 and drawn == sampled({"a": Range(2.0, 3.0, 1), "b": ["x", "y"]}, 50, 4)
    assert all(2.0 <= run["a"] <= 3.0 and run["b"] in ("x", "y") for run in drawn)
    assert {run["b"] for run in drawn} == {"x", "y"}
    with pytest.raises(progsim.InvalidArgumentError, match="no values"):
        grid({"a": []})


def test_unknown_parameter_is_refused_before_any_run():
    with pytest.raises(progsim.InvalidArgumentError, match="unknown sweep parameter 'stifness'"):
        sweep(SCENE_TEXT, {"stifness": [1.0]}, "serial", progress=False)


def test_scene_overrides_and_comments():
    scene = load_scene(SCENE_TEXT)
    assert scene["handles"][1]["box"]["min"] == [0.99, 0.99, -0.01]
    changed = override(scene, "bodies.0.material.thickness", 1e-3)
    assert changed["bodies"][0]["material"]["thickness"] == 1e-3
    assert scene["bodies"][0]["material"]["thickness"] == 5e-4  # the original is kept
    assert override(scene, "wind.velocity", [1, 0, 0])["wind"] == {"velocity": [1, 0, 0]}
    with pytest.raises(progsim.InvalidSceneError, match="no entry bodies.3"):
        override(scene, "bodies.3.name", "x")
    with pytest.raises(progsim.InvalidSceneError, match="not JSON"):
        load_scene("{ // no end")


def test_sweep_on_two_workers_matches_serial_runs_bit_for_bit(client, tmp_path):
    rows, positions = serial_reference(tmp_path, steps=10)
    runs = sweep(SCENE_TEXT, PARAMETERS, client, steps=10, progress=False)
    assert outcome(runs.rows()) == outcome(rows)
    assert [r["status"] for r in rows] == ["PS_OK"] * 4
    for result, expected in zip(runs.results, positions):
        np.testing.assert_array_equal(result.positions, expected)
    # The runs differ from each other: the parameters reached the simulation.
    assert len({row["center_of_mass_z"] for row in rows}) == 4


def test_a_killed_worker_does_not_change_the_table(client, tmp_path):
    rows, _ = serial_reference(tmp_path, steps=40)
    killed = {}

    def kill_a_busy_worker():
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and not killed:
            busy = [w for w, tasks in client.processing().items() if tasks]
            if busy:
                killed["worker"], killed["tasks"] = (
                    busy[0],
                    client.processing()[busy[0]],
                )
                try:
                    client.run(os._exit, 1, workers=[busy[0]], wait=False)
                except Exception:  # noqa: BLE001 - the worker dies under the call
                    pass
            time.sleep(0.005)

    killer = threading.Thread(target=kill_a_busy_worker)
    killer.start()
    runs = sweep(SCENE_TEXT, PARAMETERS, client, steps=40, progress=False)
    killer.join()
    assert killed and killed["tasks"], "no worker was killed while it ran a task"
    assert outcome(runs.rows()) == outcome(rows)
    client.wait_for_workers(2, timeout=60)  # the nanny restarts it for the next test


def test_a_failing_run_is_a_row_and_the_others_complete(client):
    runs = sweep(
        SCENE_TEXT,
        {"material.youngs_modulus": [5e5, -1.0, 3e5]},
        client,
        steps=3,
        progress=False,
    )
    rows = runs.rows()
    assert [row["status"] for row in rows] == [
        "PS_OK",
        "PS_ERROR_INVALID_ARGUMENT",
        "PS_OK",
    ]
    assert "youngs_modulus" in rows[1]["error"]
    assert rows[1]["steps"] == "" and rows[0]["steps"] == 3


def test_table_contact_sheet_and_refinement(tmp_path):
    runs = sweep(
        SCENE_TEXT,
        {"scene.bodies.0.material.thickness": [4e-4, 8e-4]},
        "serial",
        steps=5,
        progress=False,
    )
    directory = runs.write(tmp_path / "out")
    with open(directory / "runs.csv", newline="") as table:
        written = list(csv.DictReader(table))
    assert [row["scene.bodies.0.material.thickness"] for row in written] == [
        "0.0004",
        "0.0008",
    ]
    assert float(written[1]["center_of_mass_y"]) == runs.rows()[1]["center_of_mass_y"]
    image = (directory / "contact_sheet.png").read_bytes()
    assert image[:8] == b"\x89PNG\r\n\x1a\n"
    width, height = int.from_bytes(image[16:20], "big"), int.from_bytes(image[20:24], "big")
    assert (width, height) == (600, 300)  # two 3-inch panels side by side at 100 dpi

    with runs.refine(1) as sim:
        assert sim.num_frames(1) == 6  # frame 0 and five refined steps at the finest level
        np.testing.assert_array_equal(sim.positions(0), runs.results[1].positions)
        assert np.isfinite(sim.positions(1)).all()
    with pytest.raises(progsim.InvalidArgumentError, match="no run 2"):
        runs.refine(2)


def test_command_line(tmp_path, capsys):
    assert parse_param("a=1:2:3") == ("a", Range(1.0, 2.0, 3))
    assert parse_param("a=1,x") == ("a", [1.0, "x"])
    assert parse_param("a=[[0,0,1]]") == ("a", [[0, 0, 1]])
    scene = tmp_path / "scene.json"
    scene.write_text(SCENE_TEXT)
    out = tmp_path / "cli"
    status = cli_main(
        [
            "sweep",
            str(scene),
            "--param",
            "material.youngs_modulus=3e5:6e5:2",
            "--serial",
            "--steps",
            "2",
            "--out",
            str(out),
        ]
    )
    assert status == 0, capsys.readouterr().err
    assert len((out / "runs.csv").read_text().splitlines()) == 3
    assert cli_main(["sweep", str(scene), "--param", "nope=1", "--serial", "--out", str(out)]) == 2
    assert "unknown sweep parameter 'nope'" in capsys.readouterr().err


def test_calls_release_the_gil():
    """Python keeps running in another thread while a simulation steps inside the library."""
    sim = progsim.Simulation.from_scene(SCENE_TEXT)
    window = {}

    def step():
        window["start"] = time.perf_counter()
        sim.step_preview(100)
        window["end"] = time.perf_counter()

    stepper = threading.Thread(target=step)
    ticks = []
    stepper.start()
    while stepper.is_alive():
        ticks.append(time.perf_counter())
    stepper.join()
    sim.close()
    inside = [t for t in ticks if window["start"] < t < window["end"]]
    assert window["end"] - window["start"] > 0.01
    assert len(inside) > 1000, f"{len(inside)} ticks of the main thread during the C call"
