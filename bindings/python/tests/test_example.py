"""The Python example runs and writes its mesh."""

from __future__ import annotations

import re
import subprocess
import sys

import numpy as np

from conftest import REPO


def test_hanging_cloth_example(tmp_path):
    out = tmp_path / "final.obj"
    result = subprocess.run(
        [
            sys.executable,
            str(REPO / "examples" / "python" / "hanging_cloth.py"),
            "--out",
            str(out),
            "--steps",
            "5",
        ],
        capture_output=True,
        text=True,
        timeout=600,
        cwd=tmp_path,
    )
    assert result.returncode == 0, result.stderr
    assert "preview" in result.stderr  # the progress bar
    assert "level 0: 10 steps" in result.stdout
    lowest = float(re.search(r"lowest point z = (-?[0-9.]+) m", result.stdout).group(1))
    assert lowest < -0.05  # 0.2 s of falling
    assert "pinned corners [420, 440] at [[0.0, 1.0, 0.0], [1.0, 1.0, 0.0]]" in result.stdout
    lines = out.read_text().splitlines()
    vertices = np.array(
        [[float(v) for v in line.split()[1:4]] for line in lines if line.startswith("v ")]
    )
    assert vertices.shape == (441, 3)
    assert sum(line.startswith("f ") for line in lines) == 800
    assert abs(vertices[:, 2].min() - lowest) <= 5e-4  # printed with 3 decimals


def test_progressive_animation_example(tmp_path):
    result = subprocess.run(
        [
            sys.executable,
            str(REPO / "examples" / "python" / "progressive_animation.py"),
            "--cells",
            "10",
            "--steps",
            "4",
            "--levels",
            "16,40",
        ],
        capture_output=True,
        text=True,
        timeout=600,
        cwd=tmp_path,
    )
    assert result.returncode == 0, result.stderr
    assert "refine" in result.stderr  # the progress bar of each refinement
    assert "progressive_dynamics, 3 levels, prediction velocity_only" in result.stdout
    rows = re.findall(
        r"level (\d): (\d+) vertices, 4 steps in [0-9.]+ s, max centre-of-mass deviation "
        r"from the preview ([0-9.e+-]+) m",
        result.stdout,
    )
    assert [(int(level), int(n)) for level, n, _ in rows] == [(0, 16), (1, 40), (2, 121)]
    assert float(rows[0][2]) == 0.0
