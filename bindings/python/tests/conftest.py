"""Shared fixtures: the repository's bundled data and a small grid mesh."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import progsim

REPO = Path(__file__).resolve().parents[3]
MESH = REPO / "scenes" / "meshes" / "square_cloth.obj"
SCENE = REPO / "scenes" / "hanging_cloth.json"
HEADER = REPO / "capi" / "include" / "progsim.h"
CORNERS = [420, 440]  # (0, 1, 0) and (1, 1, 0) in square_cloth.obj


def grid(nx: int = 2, ny: int = 2):
    """An nx × ny grid of unit squares in the x-y plane: (vertices (n, 3), faces (m, 3))."""
    xs, ys = np.meshgrid(np.arange(nx + 1, dtype=float), np.arange(ny + 1, dtype=float))
    vertices = np.column_stack([xs.ravel(), ys.ravel(), np.zeros(xs.size)])
    faces = []
    for j in range(ny):
        for i in range(nx):
            a = j * (nx + 1) + i
            b, c, d = a + 1, a + nx + 2, a + nx + 1
            faces += [(a, b, c), (a, c, d)]
    return vertices, np.array(faces, dtype=np.int32)


@pytest.fixture
def cloth():
    """The bundled 441-vertex cloth as a Hierarchy (closed after the test)."""
    with progsim.Hierarchy.from_file(MESH) as hierarchy:
        yield hierarchy


@pytest.fixture
def small():
    """A 9-vertex grid Hierarchy (closed after the test)."""
    vertices, faces = grid()
    with progsim.Hierarchy(vertices, faces) as hierarchy:
        yield hierarchy


@pytest.fixture(scope="session")
def client():
    """A Dask LocalCluster of two single-threaded worker processes (as progsim.sweep makes),
    shared by the sweep and window tests."""
    from progsim.sweep import local_client

    with local_client(workers=2) as dask_client:
        yield dask_client
        dask_client.cluster.close()
