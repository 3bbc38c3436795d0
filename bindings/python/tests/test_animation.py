"""A progressive animation (Progressive Dynamics) from Python: a cloth falling freely on three
levels against the closed form of implicit Euler, frames as numpy arrays, initial velocities,
restart, per-step statistics, progress and cancellation, and misuse."""

from __future__ import annotations

import numpy as np
import pytest

import progsim
from conftest import grid

H, G, STEPS = 0.01, 9.81, 5


def fallen(n: int) -> float:
    """Implicit Euler from rest under gravity g: z_n − z_0 = −g h² n(n+1)/2."""
    return -G * H * H * n * (n + 1) / 2


@pytest.fixture(scope="module")
def levels():
    """An 8 × 8 grid of 0.1 m squares (81 vertices) with 16- and 36-vertex coarse levels."""
    vertices, faces = grid(8, 8)
    with progsim.Hierarchy(0.1 * vertices, faces, coarse_vertex_counts=[16, 36]) as hierarchy:
        yield hierarchy


@pytest.fixture
def falling(levels):
    """The defaults (a progressive animation) falling along −z, solved to 1e-12."""
    with progsim.Simulation(levels, gravity=(0, 0, -G), newton_tolerance=1e-12) as sim:
        yield sim


def check_free_fall(sim, level, vx=0.0):
    assert sim.num_frames(level) == STEPS + 1
    frames = list(sim.frames(level))
    rest = frames[0].positions
    for frame in frames:
        n = frame.index
        assert frame.positions.shape == rest.shape and frame.velocities.shape == rest.shape
        expected = rest + np.array([vx * H * n, 0.0, fallen(n)])
        np.testing.assert_allclose(frame.positions, expected, rtol=0, atol=1e-9)
        expected_v = np.broadcast_to([vx, 0.0, -G * H * n], rest.shape)
        np.testing.assert_allclose(frame.velocities, expected_v, rtol=0, atol=1e-7)
    stats = sim.step_stats(level)
    assert stats.dtype == progsim.STEP_STATS_DTYPE and len(stats) == STEPS
    assert list(stats["step"]) == list(range(1, STEPS + 1))
    np.testing.assert_allclose(stats["time"], H * np.arange(1, STEPS + 1), atol=1e-12)
    expected_z = [fallen(n) for n in range(1, STEPS + 1)]
    np.testing.assert_allclose(stats["center_of_mass"][:, 2], expected_z, rtol=0, atol=1e-9)
    assert np.all(stats["converged"] == 1) and np.all(stats["com_deviation"] < 1e-9)
    level_stats = sim.dynamic_level_stats(level)
    assert level_stats.vertices == sim.hierarchy.level_size(level)[0]
    assert level_stats.steps == STEPS and level_stats.converged_steps == STEPS


def test_free_fall_matches_implicit_euler_on_every_level(falling):
    assert falling.kind == "progressive_dynamics" and falling.prediction == "velocity_only"
    assert falling.get_param("consistency_weight") == 0.0
    assert falling.get_param("galerkin_refresh") == 0.5
    falling.step_preview(STEPS)
    falling.refine()
    falling.refine()
    assert falling.current_level == 2
    for level in range(3):
        check_free_fall(falling, level)
    np.testing.assert_array_equal(falling.positions(-1), falling.frame_positions(-1, STEPS))
    with pytest.raises(progsim.OutOfRangeError, match="finest"):
        falling.refine()


def test_initial_velocities_carry_to_finer_levels_and_restart_forgets_them(falling):
    falling.set_preview_velocities(np.tile([1.0, 0.0, 0.0], (16, 1)))
    falling.step_preview(STEPS)
    falling.refine()
    check_free_fall(falling, 0, vx=1.0)
    check_free_fall(falling, 1, vx=1.0)
    falling.restart()
    assert falling.current_level == 0 and falling.num_frames(0) == 1
    falling.step_preview(STEPS)
    check_free_fall(falling, 0)


def test_refine_reports_each_step_and_cancelling_changes_nothing(falling):
    falling.step_preview(STEPS)
    calls = []

    def cancel_at_two(done, total, phase):
        calls.append((done, total, phase))
        return done >= 2

    with pytest.raises(progsim.CancelledError, match="cancelled"):
        falling.refine(progress=cancel_at_two)
    assert calls == [(1, STEPS, "refine"), (2, STEPS, "refine")]
    assert falling.current_level == 0
    with pytest.raises(progsim.OutOfRangeError, match="not been computed"):
        falling.num_frames(1)
    falling.refine(progress=True)  # a tqdm bar counting the steps
    check_free_fall(falling, 1)


def test_options_from_keywords_and_scenes(levels):
    with progsim.Simulation(
        levels, prediction="per_frame", consistency_weight=0.5, galerkin_refresh=0
    ) as sim:
        assert sim.prediction == "per_frame" and sim.get_param("consistency_weight") == 0.5
        assert sim.get_param("galerkin_refresh") == 0.0
        sim.prediction = "prolonged_positions"
        assert sim.prediction == "prolonged_positions"
        with pytest.raises(progsim.InvalidArgumentError, match="the predictions are"):
            sim.prediction = "linear"
    scene = {
        "simulation": {"mode": "dynamic", "time_step": 0.01},
        "effects": ["membrane", "bending", "gravity"],
        "progressive": {"levels": [12, 30], "prediction": "prolonged_positions"},
        "bodies": [{"mesh": {"generator": "grid", "width": 1, "height": 1, "nx": 8, "ny": 8}}],
    }
    with progsim.Simulation.from_scene(scene) as sim:
        assert sim.kind == "progressive_dynamics" and sim.prediction == "prolonged_positions"
        sim.step_preview(2)
        sim.refine()
        assert sim.num_frames(1) == 3 and "progressive animation" in repr(sim)


def test_misuse_is_refused_clearly(falling, levels):
    with pytest.raises(progsim.WrongCallOrderError, match="preview at least one step"):
        falling.refine()
    with pytest.raises(progsim.OutOfRangeError, match="frame 1"):
        falling.frame_positions(0, 1)
    with pytest.raises(progsim.OutOfRangeError, match="level 2 has not been computed"):
        falling.frame_velocities(2, 0)
    with pytest.raises(progsim.InvalidArgumentError, match=r"shape \(n, 3\)"):
        falling.set_preview_velocities(np.zeros(48))
    with pytest.raises(progsim.InvalidArgumentError, match="45 values given"):
        falling.set_preview_velocities(np.zeros((15, 3)))
    with pytest.raises(progsim.InvalidArgumentError, match="non-finite"):
        falling.set_preview_velocities(np.full((16, 3), np.nan))
    with pytest.raises(progsim.InvalidArgumentError, match="progressive animation"):
        falling.settle()
    with pytest.raises(progsim.InvalidArgumentError, match="progressive animation"):
        falling.level_stats()
    with pytest.raises(progsim.InvalidArgumentError, match="consistency_weight"):
        falling.set_param("consistency_weight", -1)
    falling.step_preview(1)
    with pytest.raises(progsim.WrongCallOrderError, match="restart"):
        falling.set_preview_velocities(np.zeros((16, 3)))
    falling.refine()
    with pytest.raises(progsim.WrongCallOrderError, match="restart"):
        falling.step_preview(1)
    with pytest.raises(progsim.WrongCallOrderError, match="restart"):
        falling.prediction = "per_frame"
    assert falling.num_frames(0) == 2  # nothing above changed the animation
    with progsim.Simulation(levels, mode="quasistatic", effects=["membrane"]) as psq:
        assert psq.kind == "psq"
        with pytest.raises(progsim.InvalidArgumentError, match="PSQ"):
            psq.num_frames(0)
        with pytest.raises(progsim.InvalidArgumentError, match="progressive animation"):
            psq.restart()
