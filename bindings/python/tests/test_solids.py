"""Solids through the C ABI (VPD, issue 32 §7): tet hierarchies from tets, closed surfaces and
files, their levels' tets and boundary faces, prolongation of affine maps, calls that apply to
shells only, bad tet meshes, and a VPD animation falling freely against implicit Euler's closed
form on both levels."""

from __future__ import annotations

import numpy as np
import pytest

import progsim

from conftest import REPO

JELLY = REPO / "scenes" / "vpd_jelly_drop.json"
CLOTH_ON_JELLY = REPO / "scenes" / "cloth_on_jelly.json"
SPACING = 0.1  # m, the edge of one box cell
STEP, GRAVITY = 0.01, 9.81  # s, m/s²

#: The unit cube's 12 triangles, counter-clockwise seen from outside.
CUBE_VERTICES = np.array(
    [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]],
    dtype=float,
)
CUBE_FACES = np.array(
    [[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],
     [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]],
    dtype=np.int32,
)  # fmt: skip


def tet_volumes(vertices: np.ndarray, tets: np.ndarray) -> np.ndarray:
    """Signed volumes (x1 − x0)·((x2 − x0) × (x3 − x0)) / 6 of `tets`, m³."""
    edges = vertices[tets[:, 1:]] - vertices[tets[:, :1]]
    return np.einsum("ij,ij->i", edges[:, 0], np.cross(edges[:, 1], edges[:, 2])) / 6.0


def enclosed_volume(vertices: np.ndarray, faces: np.ndarray) -> float:
    """Signed volume a closed triangle surface encloses (> 0 for outward faces), m³."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def tet_box(cells: int):
    """A cells³ grid of SPACING cubes, each split into the six tets of its main diagonal, all
    positively oriented: (vertices (n, 3), tets (k, 4) int32)."""
    side = cells + 1
    k, j, i = np.meshgrid(*(np.arange(side),) * 3, indexing="ij")
    vertices = np.column_stack([i.ravel(), j.ravel(), k.ravel()]) * SPACING
    paths = [(1, 2), (1, 4), (2, 1), (2, 4), (4, 1), (4, 2)]  # corner bits along x, y, z
    tets = []
    for k0, j0, i0 in np.ndindex(cells, cells, cells):
        corner = [((k0 + (c >> 2 & 1)) * side + j0 + (c >> 1 & 1)) * side + i0 + (c & 1)
                  for c in range(8)]  # fmt: skip
        tets += [[corner[0], corner[a], corner[a | b], corner[7]] for a, b in paths]
    tets = np.array(tets, dtype=np.int32)
    flip = tet_volumes(vertices, tets) < 0
    tets[flip, 1], tets[flip, 2] = tets[flip, 2].copy(), tets[flip, 1].copy()
    assert (tet_volumes(vertices, tets) > 0).all()
    return vertices, tets


BOX_VERTICES, BOX_TETS = tet_box(4)  # 125 vertices (98 on the boundary), 384 tets


@pytest.fixture(scope="module")
def box():
    """The 4³-cell box with one coarse level (26 boundary vertices before tetrahedralization)."""
    with progsim.Hierarchy.from_tets(BOX_VERTICES, BOX_TETS, coarse_vertex_counts=[26]) as h:
        yield h


def test_levels_hold_tets_and_their_boundary(box):
    assert box.is_solid and box.num_levels == 2
    assert box.level_size(-1) == (125, 2 * 6 * 4 * 4)  # two triangles per boundary square
    assert np.array_equal(box.tets(), BOX_TETS)  # the finest level is the input
    assert np.array_equal(box.rest_positions(), BOX_VERTICES)
    coarse_vertices, coarse_faces = box.level_size(0)
    assert 26 <= coarse_vertices < 125
    for level in range(2):
        vertices, faces, tets = box.rest_positions(level), box.faces(level), box.tets(level)
        assert tets.dtype == np.int32 and tets.ndim == 2 and tets.shape[1] == 4
        assert len(tets) > 0 and len(faces) == box.level_size(level)[1]
        assert tets.min() >= 0 and tets.max() < len(vertices)
        assert np.array_equal(np.unique(tets), np.arange(len(vertices)))  # all referenced
        assert faces.min() >= 0 and faces.max() < len(vertices)
        assert (tet_volumes(vertices, tets) > 0).all()
        # the boundary faces enclose exactly the tets, facing outward
        volume = tet_volumes(vertices, tets).sum()
        assert enclosed_volume(vertices, faces) == pytest.approx(volume, rel=1e-12)
    # the decimated, re-tetrahedralized box keeps its volume (0.064 m³) within 20 %
    volume = tet_volumes(box.rest_positions(0), box.tets(0)).sum()
    assert 0.8 * 0.064 < volume <= 0.064 * (1 + 1e-9)


def test_tets_fill_a_caller_buffer(box):
    out = np.empty((len(BOX_TETS), 4), dtype=np.int32)
    assert box.tets(1, out=out) is out and np.array_equal(out, BOX_TETS)
    with pytest.raises(progsim.InvalidArgumentError, match=r"shape \(384, 4\)"):
        box.tets(1, out=np.empty((384, 3), dtype=np.int32))
    with pytest.raises(progsim.OutOfRangeError, match="level 2"):
        box.tets(2)


def test_shells_are_not_solids(small):
    assert not small.is_solid
    tets = small.tets()
    assert tets.shape == (0, 4) and tets.dtype == np.int32


def test_prolongation_carries_affine_maps_to_the_finest_level(box):
    a = np.array([[1.1, 0.2, 0.0], [-0.1, 0.9, 0.3], [0.05, 0.0, 1.2]])
    b = np.array([0.5, -0.2, 1.0])
    coarse = box.rest_positions(0) @ a.T + b
    prolonged = box.prolong(coarse, 0)
    assert prolonged.shape == (125, 3)
    assert np.abs(prolonged - (BOX_VERTICES @ a.T + b)).max() < 1e-9
    # the coarse rest shape gives the finest rest shape; a translation carries over
    assert np.abs(box.prolong(box.rest_positions(0), 0) - BOX_VERTICES).max() < 1e-9
    moved = box.prolong(box.rest_positions(0) + [0, 0, 1], 0) - BOX_VERTICES
    assert np.abs(moved - [0, 0, 1]).max() < 1e-9


def test_shell_only_calls_are_unsupported(box, tmp_path):
    path = tmp_path / "box.hierarchy"
    with pytest.raises(progsim.UnsupportedError, match="ps_hierarchy_save.*solid") as error:
        box.save(path)
    assert error.value.status == "PS_ERROR_UNSUPPORTED"
    assert not path.exists()
    with pytest.raises(progsim.UnsupportedError, match="solid"):
        box.num_expansion_batches(0)


def test_bad_tet_meshes_name_the_problem():
    bad = BOX_TETS.copy()
    bad[3, 2] = 125
    with pytest.raises(progsim.InvalidMeshError, match="tet 3 references vertex 125"):
        progsim.Hierarchy.from_tets(BOX_VERTICES, bad)
    bad = BOX_TETS.copy()
    bad[7, [1, 2]] = bad[7, [2, 1]]
    with pytest.raises(progsim.InvalidMeshError, match=r"tet 7 .* is inverted"):
        progsim.Hierarchy.from_tets(BOX_VERTICES, bad)
    with pytest.raises(progsim.InvalidMeshError, match="duplicates"):
        progsim.Hierarchy.from_tets(BOX_VERTICES, np.vstack([BOX_TETS, BOX_TETS[:1]]))
    nan = BOX_VERTICES.copy()
    nan[5, 1] = np.nan
    with pytest.raises(progsim.InvalidMeshError, match="vertex 5"):
        progsim.Hierarchy.from_tets(nan, BOX_TETS)
    with pytest.raises(progsim.InvalidMeshError, match="0 tets"):
        progsim.Hierarchy.from_tets(BOX_VERTICES, BOX_TETS[:0])
    with pytest.raises(progsim.InvalidArgumentError, match=r"tets must have shape \(k, 4\)"):
        progsim.Hierarchy.from_tets(BOX_VERTICES, BOX_TETS[:, :3])
    with pytest.raises(progsim.InvalidMeshError, match="32-bit"):
        progsim.Hierarchy.from_tets(BOX_VERTICES, BOX_TETS.astype(np.int64) + 2**32)


def test_bad_level_options_are_rejected():
    with pytest.raises(progsim.InvalidArgumentError, match="size_factor"):
        progsim.Hierarchy.from_tets(
            BOX_VERTICES, BOX_TETS, coarse_vertex_counts=[26], tet_size_factor=-1.0
        )
    with pytest.raises(progsim.InvalidArgumentError):  # not below the boundary's 98 vertices
        progsim.Hierarchy.from_tets(BOX_VERTICES, BOX_TETS, coarse_vertex_counts=[98])
    with pytest.raises(progsim.InvalidArgumentError, match="tet_size_factor must be a real"):
        progsim.Hierarchy.from_tets(BOX_VERTICES, BOX_TETS, tet_size_factor="big")


def test_a_closed_surface_is_filled_with_tets():
    with progsim.Hierarchy.from_closed_surface(
        CUBE_VERTICES, CUBE_FACES, tet_cell_size=0.4
    ) as cube:
        assert cube.is_solid and cube.num_levels == 1
        vertices, faces, tets = cube.rest_positions(), cube.faces(), cube.tets()
        assert tet_volumes(vertices, tets).sum() == pytest.approx(1.0, abs=1e-12)
        boundary = vertices[np.unique(faces)]  # resampled onto the cube's faces
        assert np.minimum(np.abs(boundary), np.abs(boundary - 1)).min(axis=1).max() < 1e-12
    with progsim.Hierarchy.from_closed_surface(
        CUBE_VERTICES, CUBE_FACES, tet_cell_size=0.3, coarse_vertex_counts=[10]
    ) as levels:
        assert levels.num_levels == 2
        assert levels.level_size(0)[0] < levels.level_size(1)[0]
    with pytest.raises(progsim.InvalidMeshError, match="not closed"):
        progsim.Hierarchy.from_closed_surface(CUBE_VERTICES, CUBE_FACES[:11])
    with pytest.raises(progsim.InvalidArgumentError, match="tet_cell_size"):
        progsim.Hierarchy.from_closed_surface(CUBE_VERTICES, CUBE_FACES, tet_cell_size=-1.0)


def write_medit(path, vertices, tets):
    """A Medit .mesh file of a tet mesh (1-based indices, reference 0)."""
    lines = ["MeshVersionFormatted 2", "Dimension 3", "Vertices", str(len(vertices))]
    lines += [f"{x!r} {y!r} {z!r} 0" for x, y, z in vertices.tolist()]
    lines += ["Tetrahedra", str(len(tets))]
    lines += [" ".join(str(i + 1) for i in tet) + " 0" for tet in tets.tolist()]
    path.write_text("\n".join(lines + ["End", ""]))


def test_solids_from_files(tmp_path):
    mesh = tmp_path / "box.mesh"
    write_medit(mesh, BOX_VERTICES, BOX_TETS)
    with progsim.Hierarchy.solid_from_file(mesh, coarse_vertex_counts=[26]) as box:
        assert box.is_solid and box.num_levels == 2
        assert np.array_equal(box.tets(), BOX_TETS)
        assert np.array_equal(box.rest_positions(), BOX_VERTICES)
    surface = tmp_path / "cube.obj"
    surface.write_text(
        "".join(f"v {x} {y} {z}\n" for x, y, z in CUBE_VERTICES)
        + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in CUBE_FACES)
    )
    with progsim.Hierarchy.solid_from_file(surface, tet_cell_size=0.4) as cube:
        assert cube.is_solid
        assert tet_volumes(cube.rest_positions(), cube.tets()).sum() == pytest.approx(1.0)
    missing = tmp_path / "missing.mesh"
    with pytest.raises(progsim.ProgsimIOError, match="missing.mesh"):
        progsim.Hierarchy.solid_from_file(missing)


def test_progress_reports_the_phases_and_cancels():
    phases = []
    progsim.Hierarchy.from_tets(
        BOX_VERTICES,
        BOX_TETS,
        coarse_vertex_counts=[26],
        progress=lambda done, total, phase: phases.append(phase),
    ).close()
    assert {"decimation", "tetrahedralization", "binding"} <= set(phases)
    with pytest.raises(progsim.CancelledError, match="cancelled"):
        progsim.Hierarchy.from_tets(
            BOX_VERTICES, BOX_TETS, coarse_vertex_counts=[26], progress=lambda *report: True
        )


def fallen(frames: np.ndarray, velocity: float = 0.0) -> np.ndarray:
    """Implicit Euler from x_0 with initial velocity v_0 under gravity g: after n steps
    x_n − x_0 = n h v_0 + g h² n(n+1)/2 (the displacement of every vertex of a free solid)."""
    return frames * STEP * velocity - GRAVITY * STEP**2 * frames * (frames + 1) / 2.0


def frames_of(sim, level):
    return np.stack([frame.positions for frame in sim.frames(level)])


def test_vpd_animates_a_free_fall_on_both_levels(box):
    steps = 5
    with progsim.Simulation(box, gravity=(0, 0, -GRAVITY), newton_tolerance=1e-12) as sim:
        assert sim.kind == "volumetric_dynamics"
        assert sim.effects == {"elasticity", "gravity"}  # the library's default for solids
        sim.step_preview(steps)
        sim.refine()
        assert sim.current_level == 1
        n = np.arange(steps + 1)
        for level in range(2):
            assert sim.num_frames(level) == steps + 1
            x = frames_of(sim, level)  # (frames, vertices, 3)
            assert x.shape == (steps + 1, box.level_size(level)[0], 3)
            assert np.isfinite(x).all()
            assert np.array_equal(x[0], box.rest_positions(level))
            moved = x - x[0]
            assert np.abs(moved[..., :2]).max() < 1e-9  # no sideways drift
            assert np.abs(moved[..., 2] - fallen(n)[:, None]).max() < 1e-8
            stats = sim.step_stats(level)
            assert len(stats) == steps and (stats["converged"] == 1).all()
            drop = stats["center_of_mass"][:, 2] - stats["center_of_mass"][0, 2]
            assert drop == pytest.approx(fallen(n[1:]) - fallen(1), abs=1e-9)
            # ≈ g t²/2: implicit Euler's n(n+1)/2 h² lies (n+1)/n above t²/2 after n steps
            t = steps * STEP
            assert -moved[-1, :, 2].mean() == pytest.approx(
                GRAVITY * t**2 / 2 * (steps + 1) / steps, rel=1e-6
            )
            assert sim.dynamic_level_stats(level).vertices == box.level_size(level)[0]
        with pytest.raises(progsim.OutOfRangeError, match="finest"):
            sim.refine()
        sim.restart()
        assert sim.current_level == 0 and sim.num_frames(0) == 1
        # initial velocities: the preview (and so the finer level) keeps them
        sim.set_preview_velocities(np.tile([0.5, 0.0, 0.0], (box.level_size(0)[0], 1)))
        sim.step_preview(3)
        sim.refine()
        for level in range(2):
            moved = frames_of(sim, level) - box.rest_positions(level)
            n = np.arange(4)[:, None]
            assert np.abs(moved[..., 0] - n * STEP * 0.5).max() < 1e-8
            assert np.abs(moved[..., 2] - fallen(n)).max() < 1e-8


def test_solid_simulations_refuse_what_vpd_cannot_do(box):
    with pytest.raises(progsim.InvalidSceneError, match="membrane"):
        progsim.Simulation(box, effects=["membrane", "gravity"])
    with pytest.raises(progsim.UnsupportedError, match="quasistatic"):
        progsim.Simulation(box, mode="quasistatic")
    with pytest.raises(progsim.UnsupportedError):
        progsim.Simulation(box, pinned=[0, 1])


def test_a_volumetric_scene_animates_with_vpd():
    with progsim.Simulation.from_scene_file(JELLY) as sim:
        assert sim.kind == "volumetric_dynamics"
        hierarchy = sim.hierarchy
        assert hierarchy.is_solid and hierarchy.num_levels == 3
        assert hierarchy.level_size(-1)[0] == 729 and hierarchy.tets(-1).shape == (3072, 4)
        sim.step_preview(2)
        assert sim.num_frames(0) == 3
        assert np.isfinite(sim.frame_positions(0, 2)).all()
        assert sim.frame_positions(0, 2)[:, 1].mean() < sim.frame_positions(0, 0)[:, 1].mean()
        assert "progressive animation" in repr(sim)


def test_a_scene_mixing_a_cloth_and_a_jelly_runs_directly():
    with progsim.Simulation.from_scene_file(CLOTH_ON_JELLY) as sim:
        assert sim.kind == "direct"
        start = sim.positions(0)
        assert start.shape == (216 + 441, 3)  # the jelly's tet vertices, then the cloth's
        sim.step_preview(3)
        moved = sim.positions(0)
        assert np.isfinite(moved).all()
        assert moved[216:, 1].mean() < start[216:, 1].mean()  # the cloth falls along −y
        assert moved[:216, 1].min() > 0.0  # the jelly stays on the ground


def test_one_level_is_a_direct_simulation_of_the_solid():
    vertices, tets = tet_box(2)
    with progsim.Hierarchy.from_tets(vertices, tets) as h:
        assert h.num_levels == 1
        with progsim.Simulation(h, gravity=(0, 0, -GRAVITY), newton_tolerance=1e-12) as sim:
            assert sim.kind == "direct"
            sim.step_preview(3)
            moved = sim.positions(0) - vertices
            assert np.abs(moved[:, :2]).max() < 1e-9
            assert np.abs(moved[:, 2] - fallen(np.array(3))).max() < 1e-8


def test_a_handle_box_holds_each_levels_own_vertices(box):
    with progsim.Simulation(box, gravity=(0, 0, -GRAVITY)) as sim:
        with pytest.raises(progsim.InvalidArgumentError, match="box_min.x"):
            sim.add_handle_box((1.0, -1, -1), (0.5, 1, 1))
        with pytest.raises(progsim.InvalidSceneError, match="holds no vertex"):
            sim.add_handle_box((5, 5, 5), (6, 6, 6))
        low = BOX_VERTICES[:, 0].min()
        assert sim.add_handle_box((low - 0.01, -1, -1), (low + 0.01, 1, 1)) == 0
        sim.step_preview(3)
        sim.refine()
        for level in range(2):
            rest = box.rest_positions(level)
            moved = sim.positions(level) - rest
            held = np.abs(rest[:, 0] - low) <= 0.01
            assert held.sum() >= 4
            assert np.abs(moved[held]).max() == 0.0
            assert moved[~held, 2].min() < 0.0  # the rest sags


def test_a_load_box_pushes_each_levels_own_vertices(box):
    # Without gravity, a box around the whole solid with a total force F spread by mass
    # accelerates every vertex of level l at a_l = F / (ρ V_l), V_l the level's own tet volume.
    # The refined level's steps take the preview's velocity (VPD's velocity-only prediction,
    # x̂ = xᵗ + h U v₀ᵗ): z_n − z_0 = −h² (a₀ n(n−1)/2 + a₁ n).
    steps, force, density = 4, 3.0, 200.0
    with progsim.Simulation(
        box, effects=["elasticity"], density=density, newton_tolerance=1e-12
    ) as sim:
        with pytest.raises(progsim.InvalidArgumentError, match="not both"):
            sim.add_load([0], box=((-1, -1, -1), (1, 1, 1)), force=(0, 0, -force))
        with pytest.raises(progsim.InvalidArgumentError, match="not both"):
            sim.add_load(force=(0, 0, -force))
        with pytest.raises(progsim.InvalidSceneError, match="holds no vertex"):
            sim.add_load(box=((5, 5, 5), (6, 6, 6)), force=(0, 0, -force))
        assert sim.add_load(box=((-1, -1, -1), (1, 1, 1)), force=(0, 0, -force)) == 0
        sim.step_preview(steps)
        sim.refine()
        n = np.arange(steps + 1)[:, None]
        a = [
            force / (density * tet_volumes(box.rest_positions(level), box.tets(level)).sum())
            for level in range(2)
        ]
        assert abs(a[1] / a[0] - 1) > 1e-3  # else the prediction rule goes untested
        for level in range(2):
            moved = frames_of(sim, level) - box.rest_positions(level)
            assert np.abs(moved[..., :2]).max() < 1e-9
            expected = -(STEP**2) * (a[0] * n * (n - 1) / 2 + a[level] * n)
            assert np.abs(moved[..., 2] - expected).max() < 1e-8
