"""Partial supports (rollers) and the reaction forces of handles, through the C ABI."""

import numpy as np
import pytest

import progsim

LENGTH, WIDTH, THICKNESS, DENSITY, G = 0.5, 0.05, 5e-3, 1000.0, 9.81


def _propped_strip(roller_axes: str) -> dict:
    """A stiff strip along x, clamped over x <= 1.5 dx, its far end on a second handle."""
    dx = LENGTH / 40
    return {
        "simulation": {"mode": "quasistatic", "time_step": 1.0, "duration": 1.0},
        "gravity": [0, 0, -G],
        "effects": ["membrane", "bending", "gravity"],
        "solver": {"newton_tolerance": 1e-8},
        "bodies": [
            {
                "mesh": {"generator": "grid", "width": LENGTH, "height": WIDTH, "nx": 40, "ny": 2},
                "material": {
                    "youngs_modulus": 1e10,
                    "poisson_ratio": 0.0,
                    "thickness": THICKNESS,
                    "density": DENSITY,
                },
            }
        ],
        "handles": [
            {"body": 0, "box": {"min": [-1, -1, -1], "max": [1.5 * dx, 1, 1]}},
            {
                "body": 0,
                "box": {"min": [LENGTH - 1e-9, -1, -1], "max": [1, 1, 1]},
                "axes": roller_axes,
            },
        ],
    }


def test_reactions_carry_the_weight_and_a_roller_no_horizontal_load():
    weight = DENSITY * THICKNESS * LENGTH * WIDTH * G
    with progsim.Simulation.from_scene(_propped_strip("z")) as sim:
        sim.step_preview(1)
        clamp, roller = sim.handle_reaction(0), sim.handle_reaction(1)
        np.testing.assert_allclose(clamp.force + roller.force, [0, 0, weight], atol=1e-6 * weight)
        assert roller.force[0] == 0.0 and roller.force[1] == 0.0
        assert abs(clamp.force[0]) < 1e-6 * weight
        # propped cantilever (beam theory): the prop carries 3/8 of the span's load
        dx = LENGTH / 40
        prop = 3 / 8 * weight / LENGTH * (LENGTH - dx) + weight / LENGTH * dx / 2
        assert roller.force[2] == pytest.approx(prop, rel=0.03)
        # the same scene with the roller switched to a pin through the ABI pulls horizontally
        sim.set_handle_axes(1, "xyz")
        sim.settle()
        assert abs(sim.handle_reaction(0).force[0]) > 0.1 * weight


def test_bad_axes_and_handles_are_refused():
    with progsim.Simulation.from_scene(_propped_strip("z")) as sim:
        for bad in ("", "xx", "w", 3):
            with pytest.raises(progsim.InvalidArgumentError):
                sim.set_handle_axes(1, bad)
        with pytest.raises(progsim.OutOfRangeError):
            sim.set_handle_axes(2, "x")
        with pytest.raises(progsim.WrongCallOrderError):
            sim.handle_reaction(0)  # no solve yet
        with pytest.raises(progsim.OutOfRangeError):
            sim.handle_reaction(5)


def _guided_strip(support_in_scene: bool) -> dict:
    """The propped strip with its last two columns on a rotation support (free translation)."""
    scene = _propped_strip("z")
    dx = LENGTH / 40
    end = {"body": 0, "box": {"min": [LENGTH - dx - 1e-9, -1, -1], "max": [1, 1, 1]}}
    if support_in_scene:
        end.update({"support": "rotation", "axes": ""})
    scene["handles"][1] = end
    return scene


def test_a_rotation_support_set_in_code_equals_the_scene_key():
    weight = DENSITY * THICKNESS * LENGTH * WIDTH * G
    with progsim.Simulation.from_scene(_guided_strip(True)) as keyed, progsim.Simulation.from_scene(
        _guided_strip(False)
    ) as coded:
        coded.set_handle_support(1, "rotation")
        keyed.step_preview(1)
        coded.step_preview(1)
        np.testing.assert_array_equal(keyed.positions(), coded.positions())
        clamp, guided = coded.handle_reaction(0), coded.handle_reaction(1)
        # the guided end translates freely: the clamp carries the whole weight
        assert clamp.force[2] == pytest.approx(weight, rel=1e-6)
        assert np.linalg.norm(guided.force) < 1e-4 * weight  # to the solve's tolerance
        assert abs(guided.moment[1]) > 0.01 * weight * LENGTH  # it holds the end's slope
        end = coded.positions()[-2:]  # the last two columns' corner vertices, flat at rest
        assert end[0, 2] < -1e-4  # the end sank ...
        assert end[0, 2] == pytest.approx(end[1, 2], abs=1e-12)  # ... keeping its slope


def test_bad_supports_are_refused():
    with progsim.Simulation.from_scene(_propped_strip("z")) as sim:
        with pytest.raises(progsim.InvalidArgumentError, match="support"):
            sim.set_handle_support(1, "hinge")
        with pytest.raises(progsim.InvalidSceneError, match="axes"):
            sim.set_handle_support(1, "position", "")
        with pytest.raises(progsim.OutOfRangeError):
            sim.set_handle_support(4, "rotation")
