"""Point and line loads and the gravity ramp from Python: a simulation built in code steps bit
for bit like the same scene read from JSON, and bad loads are refused naming the problem."""

from __future__ import annotations

import numpy as np
import pytest

import progsim

# A 0.4 m × 0.1 m strip of 8 × 2 quads (27 vertices) clamped on its first two columns, a tip
# force and a follower (normal) force spread by area and a couple about y on its last two
# columns, ramped over two steps.
LOADED_STRIP = {
    "simulation": {"mode": "quasistatic"},
    "effects": ["membrane", "bending"],
    "bodies": [
        {
            "name": "strip",
            "mesh": {"generator": "grid", "width": 0.4, "height": 0.1, "nx": 8, "ny": 2},
            "material": {"youngs_modulus": 1e9},
        }
    ],
    "handles": [{"body": 0, "vertices": [0, 1, 9, 10, 18, 19]}],
    "loads": [
        {
            "body": 0,
            "vertices": [8, 17, 26],
            "force": [0, 0, -0.002],
            "normal_force": -0.001,
            "distribution": "area",
        },
        {
            "body": 0,
            "vertices": [7, 8, 16, 17, 25, 26],
            "distribution": "per_vertex",
            "moment": {"axis": [0, 1, 0], "magnitude": 1e-4},
            "ramp": 0.02,
        },
    ],
}
TIP = np.array([8, 17, 26], dtype=np.int32)
END = np.array([7, 8, 16, 17, 25, 26])


def strip_in_code(hierarchy):
    sim = progsim.Simulation(
        hierarchy,
        mode="quasistatic",
        effects={"membrane", "bending"},
        youngs_modulus=1e9,
        pinned=[0, 1, 9, 10, 18, 19],
    )
    assert sim.add_load(TIP, force=(0, 0, -0.002), normal_force=-0.001, distribution="area") == 0
    index = sim.add_load(
        END, moment=1e-4, moment_axis=(0, 1, 0), distribution="per_vertex", ramp=0.02
    )
    assert index == 1
    return sim


def test_code_equals_json_step_by_step():
    with progsim.Simulation.from_scene(LOADED_STRIP) as from_json:
        with strip_in_code(from_json.hierarchy) as from_code:
            assert from_json.num_loads == from_code.num_loads == 2
            for _ in range(3):
                from_json.step_preview(1)
                from_code.step_preview(1)
                assert np.array_equal(from_json.positions(), from_code.positions())
            assert from_code.positions()[26, 2] < -1e-4  # the tip force pulls the tip down


def test_bad_loads_are_refused_and_change_nothing():
    with progsim.Simulation.from_scene(LOADED_STRIP) as sim:
        with pytest.raises(progsim.InvalidSceneError, match=r"loads\[2\].force"):
            sim.add_load(TIP, force=(0, float("nan"), 0))
        with pytest.raises(progsim.InvalidSceneError, match="vertex 27 is out of range"):
            sim.add_load([27], force=(0, 0, 1))
        with pytest.raises(progsim.InvalidSceneError, match="selects no vertices"):
            sim.add_load([], force=(0, 0, 1))
        with pytest.raises(progsim.InvalidSceneError, match=r"loads\[2\].ramp"):
            sim.add_load(TIP, force=(0, 0, 1), ramp=-1.0)
        with pytest.raises(progsim.InvalidSceneError, match=r"loads\[2\].moment"):
            sim.add_load(TIP, moment=1.0, moment_axis=(0, 1, 0))  # the tip edge lies along y
        with pytest.raises(progsim.InvalidArgumentError, match="distribution"):
            sim.add_load(TIP, force=(0, 0, 1), distribution="volume")
        with pytest.raises(progsim.InvalidArgumentError, match="integers"):
            sim.add_load([8.5], force=(0, 0, 1))
        assert sim.num_loads == 2
        sim.step_preview(1)


def test_gravity_ramp_keyword_and_parameter():
    with progsim.Simulation.from_scene(LOADED_STRIP) as scene:
        with progsim.Simulation(scene.hierarchy, gravity_ramp=0.5) as sim:
            assert sim.get_param("gravity_ramp") == 0.5
            sim.set_param("simulation.gravity_ramp", 0.25)
            assert sim.get_param("simulation.gravity_ramp") == 0.25
            with pytest.raises(progsim.InvalidArgumentError, match="gravity_ramp"):
                sim.set_param("gravity_ramp", -1.0)
