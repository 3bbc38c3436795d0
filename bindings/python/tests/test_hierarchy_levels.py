"""Multi-level hierarchies through the C ABI: level sizes, exact rest recovery and rigid
motions through ``prolong``, save/load, progress and cancellation, and clear errors."""

from __future__ import annotations

import numpy as np
import pytest

import progsim

from conftest import MESH


@pytest.fixture(scope="module")
def levels():
    """The bundled 441-vertex cloth decimated to 30 and 110 vertices."""
    with progsim.Hierarchy.from_file(MESH, coarse_vertex_counts=[30, 110]) as hierarchy:
        yield hierarchy


def random_rotation(rng):
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q *= np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


def test_levels_have_the_requested_sizes(levels):
    assert levels.num_levels == 3
    assert [levels.level_size(level)[0] for level in range(3)] == [30, 110, 441]
    for level in range(2):
        assert 1 <= levels.num_expansion_batches(level) < 110
    with pytest.raises(progsim.OutOfRangeError, match="finest"):
        levels.num_expansion_batches(2)


def test_prolonging_the_rest_shape_gives_the_fine_rest_shape(levels):
    fine = levels.rest_positions()
    diagonal = np.linalg.norm(fine.max(axis=0) - fine.min(axis=0))
    for level in range(2):
        prolonged = levels.prolong(levels.rest_positions(level), level)
        assert np.abs(prolonged - fine).max() < 1e-9 * diagonal
    assert np.array_equal(levels.prolong(fine, -1), fine)


def test_prolongation_commutes_with_rigid_motions(levels):
    rng = np.random.default_rng(3)
    coarse = levels.rest_positions(0) + rng.normal(scale=0.01, size=(30, 3))
    q, c = random_rotation(rng), rng.normal(size=3)
    expected = levels.prolong(coarse, 0) @ q.T + c
    assert np.abs(levels.prolong(coarse @ q.T + c, 0) - expected).max() < 1e-9


def test_save_and_load_round_trip(levels, tmp_path):
    path = tmp_path / "cloth.hierarchy"
    levels.save(path)
    with progsim.Hierarchy.load(path) as loaded:
        assert loaded.num_levels == 3
        for level in range(3):
            assert np.array_equal(loaded.faces(level), levels.faces(level))
            assert np.array_equal(loaded.rest_positions(level), levels.rest_positions(level))
        coarse = levels.rest_positions(0) * 1.5
        assert np.array_equal(loaded.prolong(coarse, 0), levels.prolong(coarse, 0))
    path.write_bytes(path.read_bytes()[:100])
    with pytest.raises(progsim.ProgsimIOError, match="cloth.hierarchy"):
        progsim.Hierarchy.load(path)
    with pytest.raises(progsim.ProgsimIOError):
        progsim.Hierarchy.load(tmp_path / "missing.hierarchy")


def test_progress_reports_and_cancels():
    seen = []

    def record(done, total, phase):
        seen.append((done, total, phase))
        return False

    progsim.Hierarchy.from_file(MESH, coarse_vertex_counts=[50], progress=record).close()
    assert seen and seen[-1][0] == seen[-1][1] == 100
    assert {phase for _, _, phase in seen} <= {"decimation", "expansion coloring"}
    with pytest.raises(progsim.CancelledError):
        progsim.Hierarchy.from_file(
            MESH, coarse_vertex_counts=[50], progress=lambda done, total, phase: done >= 50
        )


def test_bad_requests_are_clear_errors(levels):
    with pytest.raises(progsim.InvalidArgumentError, match="distinct"):
        progsim.Hierarchy.from_file(MESH, coarse_vertex_counts=[50, 50])
    with pytest.raises(progsim.InvalidArgumentError, match="at least 4"):
        progsim.Hierarchy.from_file(MESH, coarse_vertex_counts=[2])
    with pytest.raises(progsim.InvalidArgumentError, match="needs 90"):
        levels.prolong(np.zeros((29, 3)), 0)
    with pytest.raises(progsim.InvalidArgumentError, match="NaN"):
        levels.prolong(np.full((30, 3), np.nan), 0)
    with pytest.raises(progsim.OutOfRangeError):
        levels.prolong(np.zeros((30, 3)), 7)
    # The default mode is dynamic: on several levels, a progressive animation.
    with progsim.Simulation(levels) as sim:
        assert sim.kind == "progressive_dynamics"
        with pytest.raises(progsim.WrongCallOrderError, match="preview at least one step"):
            sim.refine()


def test_two_vertex_groups_become_two_handles_on_every_level():
    """The cloth's top corners (top row y = 1: vertices 420..440) as groups 0 and 1: a PSQ
    simulation pins the first, adds the second as handle 1 and drags it on every level."""
    ids = np.full(441, -1, dtype=np.int32)
    ids[[420, 421]] = 0
    ids[[439, 440]] = 1
    cloth = MESH
    with progsim.Hierarchy.from_file(
        cloth, coarse_vertex_counts=[60], vertex_group_ids=ids
    ) as hierarchy, progsim.Simulation(hierarchy, mode="quasistatic", pinned=[420, 421]) as sim:
        with pytest.raises(progsim.InvalidArgumentError, match="group -1 of the hierarchy"):
            sim.add_handle([0])
        assert sim.add_handle([439, 440]) == 1
        sim.set_handle_motion(1, offset=(0.05, 0, 0))
        sim.step_preview(2)
        coarse = sim.positions(0)
        at_corner = (np.abs(coarse[:, 0] - 1.05) < 1e-12) & (np.abs(coarse[:, 1] - 1.0) < 1e-12)
        assert at_corner.sum() == 1
        sim.refine()
        fine = sim.positions(1)
        np.testing.assert_allclose(fine[440, :2], [1.05, 1.0], atol=1e-12)
        np.testing.assert_allclose(fine[420, :2], [0.0, 1.0], atol=1e-12)
    with pytest.raises(progsim.InvalidArgumentError, match="not both"):
        progsim.Hierarchy.from_file(cloth, pinned=[420], vertex_group_ids=ids)
