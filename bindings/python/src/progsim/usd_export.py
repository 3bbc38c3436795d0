"""Frames of a level as a USD stage with time samples (``usd-core``, the ``usd`` extra).

Blender (File > Import > Universal Scene Description) and usdview open the stage: one
``UsdGeom.Mesh`` whose ``points`` carry a time sample per frame, at one time code per frame
and ``timeCodesPerSecond`` frames per simulated second, in metres and Y- or Z-up as the scene.
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional, Union

import numpy as np

from ._errors import InvalidArgumentError
from .simulation import Simulation

__all__ = ["write_usd"]


def _pxr():
    """The pxr modules, or a clear error naming the extra that provides them."""
    try:
        from pxr import Usd, UsdGeom, Vt
    except ImportError as error:
        raise ImportError(
            "USD export needs usd-core: pip install 'progsim[usd]' (or pip install usd-core)"
        ) from error
    return Usd, UsdGeom, Vt


def write_usd(
    sim: Simulation,
    path: Union[str, Path],
    level: int = 0,
    up_axis: str = "Y",
    frames_per_second: Optional[float] = None,
) -> int:
    """Writes every frame of ``level`` of a progressive animation to a USD stage
    (``.usda`` text or ``.usdc`` binary, by the file name), returning the number of frames.

    Args:
        sim: a progressive animation (:meth:`Simulation.frames` works on it).
        path: the stage's file.
        level: which level's frames.
        up_axis: ``"Y"`` or ``"Z"``, the stage's up axis (the scene's gravity direction).
        frames_per_second: time codes per second (default: one per time step, so that the
            stage plays in simulated time).

    Raises:
        ImportError: usd-core is not installed.
        OutOfRangeError: the level has no frames.
        InvalidArgumentError: an up axis other than Y or Z.
    """
    if up_axis not in ("Y", "Z"):
        raise InvalidArgumentError(f"up_axis must be 'Y' or 'Z', got {up_axis!r}")
    Usd, UsdGeom, Vt = _pxr()
    count = sim.num_frames(level)
    faces = np.asarray(sim.hierarchy.faces(level), dtype=np.int32)
    if frames_per_second is None:
        frames_per_second = 1.0 / sim.get_param("simulation.time_step")
    stage = Usd.Stage.CreateNew(str(path))
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.y if up_axis == "Y" else UsdGeom.Tokens.z)
    UsdGeom.SetStageMetersPerUnit(stage, 1.0)
    stage.SetTimeCodesPerSecond(frames_per_second)
    stage.SetStartTimeCode(0)
    stage.SetEndTimeCode(count - 1)
    mesh = UsdGeom.Mesh.Define(stage, f"/progsim/level_{level}")
    stage.SetDefaultPrim(stage.GetPrimAtPath("/progsim"))
    mesh.CreateFaceVertexCountsAttr(Vt.IntArray([3] * len(faces)))
    mesh.CreateFaceVertexIndicesAttr(Vt.IntArray(faces.ravel().tolist()))
    mesh.CreateSubdivisionSchemeAttr(UsdGeom.Tokens.none)
    points = mesh.CreatePointsAttr()
    for frame in sim.frames(level):  # one at a time: long animations do not fill memory
        positions = np.asarray(frame.positions, dtype=np.float32)
        points.Set(Vt.Vec3fArray.FromNumpy(positions), frame.index)
    stage.GetRootLayer().Save()
    return count
