"""The wind effect set through code: a free plate blown downwind as implicit Euler of the drag
equation predicts, gusts as keyframes, and bad wind settings refused naming the field."""

from __future__ import annotations

import math

import numpy as np
import pytest

import progsim

SQUARE = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]])
TRIANGLES = np.array([[0, 1, 2], [0, 2, 3]], dtype=np.int32)
AREAL_DENSITY = 200.0 * 1e-3  # kg/m², the default material density times thickness


def plate_in_wind(hierarchy, **wind):
    return progsim.Simulation(
        hierarchy,
        time_step=0.05,
        newton_tolerance=1e-9,
        effects={"membrane", "wind"},
        gravity=(0.0, 0.0, 0.0),
        **wind,
    )


def test_plate_is_blown_downwind_as_implicit_euler_predicts():
    speed, h, steps = 10.0, 0.05, 20
    with progsim.Hierarchy(SQUARE, TRIANGLES) as hierarchy:
        with plate_in_wind(hierarchy, wind=(0.0, 0.0, speed), wind_drag=1.5) as sim:
            assert "wind" in sim.effects
            sim.step_preview(steps)
            moved = sim.positions() - SQUARE
    # m (v' - v)/h = ½ρC_dA (w - v')² per unit area, solved for the lag d' = w - v' each step.
    a = 0.5 * 1.2 * 1.5 / AREAL_DENSITY * h
    lag, travelled = speed, 0.0
    for _ in range(steps):
        lag = (math.sqrt(1.0 + 4.0 * a * lag) - 1.0) / (2.0 * a)
        travelled += h * (speed - lag)
    assert np.allclose(moved[:, 2], travelled, rtol=1e-6)
    assert np.allclose(moved[:, :2], 0.0, atol=1e-9)


def test_gusts_follow_their_keyframes():
    still_then_gust = [[0.0, 0.0, 0.0, 0.0], [0.5, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 8.0]]
    with progsim.Hierarchy(SQUARE, TRIANGLES) as hierarchy:
        with plate_in_wind(hierarchy, wind_keyframes=still_then_gust) as sim:
            sim.step_preview(10)  # to t = 0.5 s: still air
            assert np.array_equal(sim.positions(), SQUARE)
            sim.step_preview(10)  # the gust rises
            assert sim.positions()[:, 2].min() > 0.0


def test_bad_wind_is_refused_naming_the_field():
    with progsim.Hierarchy(SQUARE, TRIANGLES) as hierarchy:
        with pytest.raises(progsim.InvalidArgumentError, match="wind.density"):
            plate_in_wind(hierarchy, wind_density=-1.0)
        with pytest.raises(progsim.InvalidSceneError, match=r"wind.keyframes\[1\].time"):
            plate_in_wind(hierarchy, wind_keyframes=[[1.0, 0, 0, 1], [0.5, 0, 0, 2]])
        with pytest.raises(progsim.InvalidArgumentError, match=r"shape \(k, 4\)"):
            plate_in_wind(hierarchy, wind_keyframes=[[1.0, 0, 0]])
        with pytest.raises(progsim.InvalidSceneError, match="needs a dynamic scene"):
            progsim.Simulation(
                hierarchy, mode="quasistatic", effects={"membrane", "wind"}, pinned=[0]
            )
