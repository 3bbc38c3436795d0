"""The compiled bindings match the header they were generated from."""

from __future__ import annotations

import re

import progsim
from progsim._progsim_cffi import ffi, lib
from conftest import HEADER


def test_every_header_function_is_bound():
    names = re.findall(r"PS_API\s+[\w\s\*]+?\b(ps_\w+)\s*\(", HEADER.read_text())
    assert len(names) >= 30
    missing = [name for name in names if not hasattr(lib, name)]
    assert not missing


def test_status_enum_matches_the_header():
    header = HEADER.read_text()
    for name, value in re.findall(r"\b(PS_(?:OK|ERROR_\w+))\s*=\s*(\d+)", header):
        assert getattr(lib, name) == int(value)
        assert progsim.status_name(int(value)) == name


def test_version_macros_come_from_the_header():
    header = HEADER.read_text()
    major, minor, patch = (
        int(re.search(rf"#define PS_VERSION_{part} (\d+)", header).group(1))
        for part in ("MAJOR", "MINOR", "PATCH")
    )
    assert progsim.HEADER_VERSION == major * 10000 + minor * 100 + patch


def test_parameters_follow_the_def_struct():
    # The library's parameter list and the def-struct come from one table: every listed
    # table parameter is a def field, and every numeric def field is listed.
    fields = {name for name, _ in ffi.typeof("ps_sim_def").fields}
    for name in progsim.PARAMETERS:
        if "." in name and not name.startswith("gravity."):
            assert name.replace(".", "_", 1) in fields
    for field in fields:
        if field.startswith(("simulation_", "material_", "solver_")):
            assert field.replace("_", ".", 1) in progsim.PARAMETERS
    assert "material.thickness" in progsim.PARAMETERS and "gravity.z" in progsim.PARAMETERS
    assert "pressure" in progsim.PARAMETERS


def test_arrays_in_the_right_layout_are_not_copied():
    import numpy as np

    from progsim._native import as_faces, as_vertices

    vertices = np.zeros((4, 3))
    faces = np.zeros((2, 3), dtype=np.int32)
    assert as_vertices(vertices) is vertices
    assert as_faces(faces) is faces
    assert as_vertices(vertices.T.copy().T) is not vertices  # Fortran order: converted
    assert as_vertices(vertices.T.copy().T).flags.c_contiguous
