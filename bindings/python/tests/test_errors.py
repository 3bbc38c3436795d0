"""Status codes become exceptions that carry the library's message, status and code."""

from __future__ import annotations

import numpy as np
import pytest

import progsim
from conftest import MESH, grid

ALL_ERRORS = {
    1: progsim.InvalidArgumentError,
    2: progsim.InvalidMeshError,
    3: progsim.InvalidSceneError,
    4: progsim.ProgsimIOError,
    5: progsim.NumericalError,
    6: progsim.WrongCallOrderError,
    7: progsim.OutOfRangeError,
    8: progsim.CancelledError,
    9: progsim.IntersectingError,
    10: progsim.InternalError,
    11: progsim.NullArgumentError,
    12: progsim.BufferTooSmallError,
    13: progsim.UninitializedDefError,
    14: progsim.VersionMismatchError,
    15: progsim.OutOfMemoryError,
    16: progsim.UnsupportedError,
}


@pytest.mark.parametrize("code,cls", sorted(ALL_ERRORS.items()))
def test_every_status_has_its_class(code, cls):
    from progsim._errors import make_error

    error = make_error(code, "the message")
    assert type(error) is cls and isinstance(error, progsim.ProgsimError)
    assert error.code == code and error.status == progsim.status_name(code)
    assert error.status.startswith("PS_ERROR_") and str(error) == "the message"


def test_python_families():
    assert issubclass(progsim.InvalidArgumentError, ValueError)
    assert issubclass(progsim.OutOfRangeError, IndexError)
    assert issubclass(progsim.ProgsimIOError, OSError)
    assert issubclass(progsim.UnsupportedError, NotImplementedError)
    error = progsim.ProgsimIOError("cannot read x")
    assert error.status == "PS_ERROR_IO" and error.code == 4 and str(error) == "cannot read x"


def test_nan_vertex_is_named():
    vertices, faces = grid()
    vertices[4, 1] = np.nan
    with pytest.raises(progsim.InvalidMeshError, match="vertex 4") as raised:
        progsim.Hierarchy(vertices, faces)
    assert raised.value.status == "PS_ERROR_INVALID_MESH" and raised.value.code == 2
    assert "non-finite" in str(raised.value)


def test_bad_face_index_is_named():
    vertices, faces = grid()
    faces[1, 2] = 9
    with pytest.raises(progsim.InvalidMeshError, match="9"):
        progsim.Hierarchy(vertices, faces)
    wide = faces.astype(np.int64)
    wide[1, 2] = 2**32 + 2  # would wrap around to 2 in int32: refused before the C call
    with pytest.raises(progsim.InvalidMeshError, match=str(2**32 + 2)):
        progsim.Hierarchy(vertices, wide)


def test_array_shapes_and_dtypes_are_checked():
    vertices, faces = grid()
    with pytest.raises(progsim.InvalidArgumentError, match=r"shape \(n, 3\)"):
        progsim.Hierarchy(vertices[:, :2], faces)
    with pytest.raises(progsim.InvalidArgumentError, match=r"shape \(m, 3\)"):
        progsim.Hierarchy(vertices, faces.ravel())
    with pytest.raises(progsim.InvalidArgumentError, match="integers"):
        progsim.Hierarchy(vertices, faces.astype(float))
    # Other layouts and dtypes are converted: int64 faces, Fortran-order float32 vertices.
    with progsim.Hierarchy(
        np.asfortranarray(vertices, dtype=np.float32), faces.astype(np.int64)
    ) as h:
        np.testing.assert_array_equal(h.rest_positions(), vertices)
        np.testing.assert_array_equal(h.faces(), faces)
    with progsim.Hierarchy(vertices.tolist(), faces.tolist()) as h:
        assert h.level_size() == (9, 8)


def _cloth_and_box_scene(material="{}", contact="{}"):
    """A 1 m cloth in the x-y plane cut through by a 0.5 m obstacle box."""
    return (
        '{"effects": ["membrane", "contact"], "contact": %s, '
        '"bodies": [{"mesh": {"generator": "grid", "width": 1, "height": 1, "nx": 2, "ny": 2},'
        ' "material": %s}], "obstacles": [{"mesh": {"generator": "box", "size": [0.5, 0.5, 0.5]},'
        ' "transform": {"translate": [0.5, 0.5, 0]}}]}' % (contact, material)
    )


def test_intersecting_start_and_bad_contact_parameters():
    with pytest.raises(progsim.IntersectingError, match="obstacle face"):
        progsim.Simulation.from_scene(_cloth_and_box_scene())
    with pytest.raises(progsim.InvalidSceneError, match="dhat"):
        progsim.Simulation.from_scene(_cloth_and_box_scene(contact='{"dhat": -1}'))
    with pytest.raises(progsim.InvalidSceneError, match="friction"):
        progsim.Simulation.from_scene(_cloth_and_box_scene(material='{"friction": -0.5}'))


def test_scene_typo_names_the_key():
    with pytest.raises(progsim.InvalidSceneError, match="efects") as raised:
        progsim.Simulation.from_scene('{"bodies": [], "efects": []}')
    assert raised.value.status == "PS_ERROR_INVALID_SCENE"
    text = (MESH.parents[1] / "hanging_cloth.json").read_text().replace('"thickness"', '"thicknes"')
    with pytest.raises(progsim.InvalidSceneError, match="thicknes"):
        progsim.Simulation.from_scene(text, base_dir=MESH.parents[1])
    with pytest.raises(progsim.InvalidSceneError):
        progsim.Simulation.from_scene("{ not json")


def test_unknown_parameter(small):
    with progsim.Simulation(small) as sim:
        with pytest.raises(
            progsim.InvalidArgumentError, match="unknown parameter 'material.thicknes'"
        ) as raised:
            sim.set_param("material.thicknes", 1e-3)
        assert "material.thickness" in str(raised.value)  # the message lists the known names
        with pytest.raises(progsim.InvalidArgumentError):
            sim.get_param("gravity.w")
        with pytest.raises(progsim.InvalidArgumentError, match="material.thickness"):
            sim.set_param("material.thickness", float("nan"))
        with pytest.raises(progsim.InvalidArgumentError, match="simulation.time_step"):
            sim.set_param("simulation.time_step", -1)
        assert sim.get_param("simulation.time_step") == 0.01  # unchanged by the failures
        with pytest.raises(progsim.InvalidArgumentError, match="steps = 0"):
            sim.step_preview(0)


def test_out_of_range_levels(small):
    with pytest.raises(progsim.OutOfRangeError, match="level 1 does not exist"):
        small.level_size(1)
    with pytest.raises(progsim.OutOfRangeError, match="level 1 does not exist"):
        small.rest_positions(1)
    with pytest.raises(progsim.OutOfRangeError, match="level 1"):
        small.faces(1)
    with pytest.raises(progsim.OutOfRangeError):
        small.level_size(-2)
    with progsim.Simulation(small) as sim:
        with pytest.raises(progsim.OutOfRangeError, match="level 1 does not exist") as raised:
            sim.positions(1)
        assert raised.value.code == 7
        with pytest.raises(progsim.OutOfRangeError):
            sim.level_stats(1)
        with pytest.raises(progsim.OutOfRangeError):
            sim.write_mesh(1, "never.obj")
        with pytest.raises(progsim.OutOfRangeError, match="handle 0 does not exist"):
            sim.set_handle_motion(0, offset=(1, 0, 0))


def test_create_errors(small, tmp_path):
    with pytest.raises(progsim.InvalidArgumentError, match="material.poisson_ratio"):
        progsim.Simulation(small, poisson_ratio=0.5)
    with pytest.raises(progsim.InvalidSceneError, match="vertex 99"):
        progsim.Simulation(small, pinned=[99])
    with pytest.raises(progsim.InvalidArgumentError, match="below the mesh's 9 vertices"):
        progsim.Hierarchy(*grid(), coarse_vertex_counts=[9])
    with pytest.raises(progsim.ProgsimIOError, match="nonexistent"):
        progsim.Hierarchy.from_file(tmp_path / "nonexistent.obj")
    with pytest.raises(progsim.ProgsimIOError):
        progsim.Simulation.from_scene_file(tmp_path / "nonexistent.json")
    with pytest.raises(progsim.InvalidArgumentError):
        progsim.Simulation("not a hierarchy")
    with progsim.Simulation(small) as sim:
        with pytest.raises(progsim.ProgsimIOError, match="out.obj"):
            sim.write_mesh(0, tmp_path / "no" / "such" / "dir" / "out.obj")


def test_output_buffers_are_checked(small):
    with progsim.Simulation(small) as sim:
        with pytest.raises(progsim.InvalidArgumentError, match=r"shape \(9, 3\)"):
            sim.positions(out=np.zeros((8, 3)))
        with pytest.raises(progsim.InvalidArgumentError, match="float64"):
            sim.positions(out=np.zeros((9, 3), dtype=np.float32))
        with pytest.raises(progsim.InvalidArgumentError, match="C-contiguous"):
            sim.positions(out=np.zeros((9, 3), order="F"))


def test_python_side_argument_checks(small, tmp_path):
    with progsim.Simulation(small) as sim:
        with pytest.raises(progsim.InvalidArgumentError, match="real number"):
            sim.set_param("thickness", "thin")
        with pytest.raises(progsim.InvalidArgumentError, match="3 real numbers"):
            sim.gravity = ("down", 0, 0)
        with pytest.raises(progsim.InvalidArgumentError, match="integer"):
            sim.step_preview(1.5)
        with pytest.raises(progsim.InvalidArgumentError, match="32-bit"):
            sim.positions(2**40)
    with pytest.raises(progsim.InvalidArgumentError, match="from_scene_file"):
        progsim.Simulation.from_scene(tmp_path / "scene.json")
    with pytest.raises(progsim.InvalidArgumentError, match="NUL"):
        progsim.Simulation.from_scene('{"bodies": []}\0')


def test_errors_pickle():
    import pickle

    error = pickle.loads(pickle.dumps(progsim.InvalidMeshError("vertex 4 is bad")))
    assert type(error) is progsim.InvalidMeshError
    assert (str(error), error.status, error.code) == ("vertex 4 is bad", "PS_ERROR_INVALID_MESH", 2)
