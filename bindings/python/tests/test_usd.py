"""USD export (progsim.usd_export): a refined level's frames reopen with pxr.Usd as time
samples of the right count and values."""

from __future__ import annotations

import numpy as np
import pytest
from pxr import Usd, UsdGeom

import progsim
from progsim.usd_export import write_usd
from test_sweep import SCENE_TEXT


def test_a_refined_animation_reopens_with_every_frame(tmp_path):
    with progsim.Simulation.from_scene(SCENE_TEXT) as sim:
        sim.step_preview(5)
        sim.refine()
        path = tmp_path / "cloth.usda"
        assert write_usd(sim, path, level=1) == 6
        frames = list(sim.frames(1))
        faces = sim.hierarchy.faces(1)
        time_step = sim.get_param("simulation.time_step")

    stage = Usd.Stage.Open(str(path))
    assert UsdGeom.GetStageUpAxis(stage) == UsdGeom.Tokens.y
    assert (stage.GetStartTimeCode(), stage.GetEndTimeCode()) == (0, 5)
    assert stage.GetTimeCodesPerSecond() == pytest.approx(1.0 / time_step)
    mesh = UsdGeom.Mesh(stage.GetPrimAtPath("/progsim/level_1"))
    points = mesh.GetPointsAttr()
    assert points.GetTimeSamples() == [0.0, 1.0, 2.0, 3.0, 4.0, 5.0]
    for frame in frames:
        stored = np.array(points.Get(frame.index))
        assert stored.shape == (81, 3)
        np.testing.assert_array_equal(stored, frame.positions.astype(np.float32))
    assert np.array(mesh.GetFaceVertexIndicesAttr().Get()).reshape(-1, 3).tolist() == faces.tolist()
    assert not np.array_equal(np.array(points.Get(0)), np.array(points.Get(5)))  # it moved


def test_bad_up_axis(tmp_path):
    with progsim.Simulation.from_scene(SCENE_TEXT) as sim:
        sim.step_preview(1)
        with pytest.raises(progsim.InvalidArgumentError, match="up_axis"):
            write_usd(sim, tmp_path / "x.usda", up_axis="X")
