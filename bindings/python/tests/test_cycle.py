"""The full cycle on the bundled cloth: hierarchy → simulation → steps → results → close."""

from __future__ import annotations

import math

import numpy as np
import pytest

import progsim
from conftest import CORNERS, MESH, SCENE


def test_hierarchy_from_file_reports_the_mesh(cloth):
    assert cloth.num_levels == 1
    assert cloth.level_size(0) == (441, 800)
    rest = cloth.rest_positions(0)
    faces = cloth.faces(0)
    assert rest.shape == (441, 3) and rest.dtype == np.float64 and rest.flags.c_contiguous
    assert faces.shape == (800, 3) and faces.dtype == np.int32
    np.testing.assert_array_equal(rest[CORNERS], [[0.0, 1.0, 0.0], [1.0, 1.0, 0.0]])
    assert rest[:, 2].max() == 0.0 and rest[:, 2].min() == 0.0  # flat in the x-y plane
    assert faces.min() == 0 and faces.max() == 440
    np.testing.assert_array_equal(cloth.rest_positions(-1), rest)  # -1 = finest


def test_full_cycle(cloth, tmp_path):
    rest = cloth.rest_positions()
    sim = progsim.Simulation(cloth, pinned=CORNERS, thickness=1e-3)
    assert sim.hierarchy is cloth
    assert sim.current_level == 0 and sim.num_handles == 1
    assert sim.effects == {"membrane", "bending", "gravity"}

    sim.set_param("material.thickness", 5e-4)
    assert sim.get_param("material.thickness") == 5e-4
    assert sim.get_param("thickness") == 5e-4  # short alias
    sim.gravity = (0.0, 0.0, -9.81)  # fall out of the cloth's plane
    assert sim.gravity == (0.0, 0.0, -9.81)
    assert sim.get_param("gravity.z") == -9.81
    sim.set_param("simulation.time_step", 0.01)
    assert sim.get_param("solver.max_newton_iterations") == 100
    assert isinstance(sim.get_param("solver.max_newton_iterations"), int)

    sim.step_preview(10)
    with pytest.raises(progsim.OutOfRangeError, match="finest level 0") as raised:
        sim.refine()
    assert raised.value.status == "PS_ERROR_OUT_OF_RANGE" and raised.value.code == 7
    assert sim.current_level == 0

    x = sim.positions()
    assert x.shape == (441, 3) and x.dtype == np.float64
    # Started flat at z = 0; free fall alone gives 0.049 m in 0.1 s.
    assert x[:, 2].min() < -0.03
    np.testing.assert_array_equal(x[CORNERS], rest[CORNERS])  # pinned: unchanged
    assert np.all(np.isfinite(x))
    np.testing.assert_array_equal(sim.positions(0), x)

    out = np.zeros((441, 3))
    assert sim.positions(out=out) is out
    np.testing.assert_array_equal(out, x)

    stats = sim.level_stats()
    assert stats.level == 0 and stats.steps == 10
    assert stats.newton_iterations >= 10 and 0 <= stats.converged_steps <= 10
    assert stats.seconds > 0 and math.isfinite(stats.energy)
    assert stats.simulated_time == pytest.approx(0.1)
    assert math.isnan(stats.error_rms) and math.isnan(stats.error_max)

    path = tmp_path / "out.obj"
    sim.write_mesh(0, path)
    lines = path.read_text().splitlines()
    vertices = np.array(
        [[float(v) for v in line.split()[1:4]] for line in lines if line.startswith("v ")]
    )
    assert vertices.shape == (441, 3)
    np.testing.assert_allclose(vertices, x, atol=1e-5)

    sim.close()
    assert sim.closed


def test_handle_motion_drags_the_pinned_corners(cloth):
    with progsim.Simulation(cloth, pinned=CORNERS, gravity=(0, 0, -9.81)) as sim:
        sim.set_handle_motion(0, offset=(0.1, 0.0, 0.0))
        sim.step_preview(1)
        x = sim.positions()
        np.testing.assert_allclose(x[CORNERS], [[0.1, 1.0, 0.0], [1.1, 1.0, 0.0]], atol=1e-12)
        with pytest.raises(progsim.OutOfRangeError, match="handle 1 does not exist"):
            sim.set_handle_motion(1, velocity=(0, 0, 1))
        with pytest.raises(progsim.InvalidArgumentError, match="axis"):
            sim.set_handle_motion(0, axis=(0, 0, 0), angular_velocity=1.0)
        with pytest.raises(progsim.InvalidArgumentError, match="3 components"):
            sim.set_handle_motion(0, velocity=(1, 2))


def test_effects_and_modes(small):
    # Quasistatic, the unpinned sheet under gravity has no equilibrium: refused, naming it.
    with pytest.raises(progsim.InvalidSceneError, match="is free in a quasistatic scene"):
        progsim.Simulation(small, effects={"membrane", "gravity"}, mode="quasistatic")
    with progsim.Simulation(small, effects={"membrane"}, mode="quasistatic") as sim:
        assert sim.effects == {"membrane"}
        sim.set_effect("bending", True)
        assert sim.effects == {"membrane", "bending"}
        with pytest.raises(progsim.InvalidSceneError, match="is free"):
            sim.set_effect("gravity", True)
        assert sim.effects == {"membrane", "bending"}
        sim.effects = ["membrane", "pressure"]
        assert sim.effects == {"membrane", "pressure"}
        with pytest.raises(progsim.InvalidArgumentError, match="unknown effect 'gravty'"):
            sim.set_effect("gravty")
        assert sim.mode == "quasistatic"
        sim.mode = "dynamic"
        assert sim.mode == "dynamic"
        with pytest.raises(progsim.InvalidArgumentError, match="unknown mode"):
            sim.mode = "static"
        assert sim.mode == "dynamic"
    with pytest.raises(progsim.InvalidArgumentError, match="unknown mode"):
        progsim.Simulation(small, mode="static")


def test_constructor_parameters_reach_the_simulation(small):
    with progsim.Simulation(
        small,
        time_step=0.005,
        youngs_modulus=2e5,
        bending_youngs_modulus=3e6,
        poisson_ratio=0.25,
        thickness=2e-3,
        density=300,
        newton_tolerance=1e-4,
        max_newton_iterations=20,
        gravity=(1.0, 2.0, 3.0),
        pressure=5.0,
    ) as sim:
        assert sim.get_param("simulation.time_step") == 0.005
        assert sim.get_param("material.youngs_modulus") == 2e5
        assert sim.get_param("material.bending_youngs_modulus") == 3e6
        assert sim.get_param("material.poisson_ratio") == 0.25
        assert sim.get_param("material.thickness") == 2e-3
        assert sim.get_param("material.density") == 300
        assert sim.get_param("solver.newton_tolerance") == 1e-4
        assert sim.get_param("solver.max_newton_iterations") == 20
        assert sim.gravity == (1.0, 2.0, 3.0)
        assert sim.get_param("pressure") == 5.0
        assert sim.num_handles == 0


def test_scene_file_owns_its_hierarchy():
    with progsim.Simulation.from_scene_file(SCENE) as sim:
        assert sim.num_handles == 2
        assert sim.get_param("material.thickness") == 5e-4
        hierarchy = sim.hierarchy
        assert hierarchy.level_size(0) == (41 * 41, 2 * 40 * 40)
        sim.step_preview(1)
        assert sim.level_stats().steps == 1
        assert sim.positions().shape == (41 * 41, 3)
    assert hierarchy.closed  # a view of the simulation's hierarchy closes with it
    with pytest.raises(progsim.ClosedError):
        hierarchy.faces()


def test_scene_text_with_base_dir_and_dict():
    scene = {
        "effects": ["membrane", "gravity"],
        "bodies": [{"mesh": {"file": "meshes/square_cloth.obj"}}],
        "handles": [{"body": 0, "vertices": CORNERS}],
    }
    with progsim.Simulation.from_scene(scene, base_dir=SCENE.parent) as sim:
        assert sim.hierarchy.level_size() == (441, 800)
        assert sim.effects == {"membrane", "gravity"}
    with pytest.raises(progsim.ProgsimIOError, match="square_cloth.obj"):
        progsim.Simulation.from_scene(scene, base_dir=MESH.parent)  # meshes/meshes/...


def test_library_version():
    assert progsim.library_version() == "0.20.0"
    assert progsim.library_version_number() == progsim.HEADER_VERSION
    assert progsim.status_name(2) == "PS_ERROR_INVALID_MESH"
