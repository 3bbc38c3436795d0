"""Keyframed handle motion set through code: each key's pose at its time, the same steps bit
for bit as the scene's "keyframes", and bad keys refused naming the key."""

from __future__ import annotations

import math

import numpy as np
import pytest

import progsim

LEFT_EDGE = [0, 5, 10, 15, 20]  # x = 0 of a 4 × 4-quad grid


def sheet(motion: dict) -> progsim.Simulation:
    """A quasistatic 1 m sheet whose handle 0 holds its left edge with ``motion``."""
    return progsim.Simulation.from_scene(
        {
            "simulation": {"mode": "quasistatic", "time_step": 0.1},
            "effects": ["membrane", "bending"],
            "bodies": [{"mesh": {"generator": "grid", "width": 1, "height": 1, "nx": 4, "ny": 4}}],
            "handles": [{"body": 0, "vertices": LEFT_EDGE, "motion": motion}],
        }
    )


def test_keys_are_reached_at_their_times_and_match_the_scene_bit_for_bit():
    times = [0.0, 0.2, 0.4]
    translations = [[0, 0, 0], [0, 0, 0.1], [0, 0, 0.1]]
    angles = [0.0, 0.0, math.pi / 2]
    keys = [
        {"time": t, "translation": T, "angle": a} for t, T, a in zip(times, translations, angles)
    ]
    center = {"center": [0, 0.5, 0]}
    scene_keys = {**center, "interpolation": "smooth", "keyframes": keys}
    with sheet(center) as coded, sheet(scene_keys) as read:
        coded.set_handle_keyframes(0, times, translations, angles=angles, interpolation="smooth")
        for step in range(1, 6):
            coded.step_preview(1)
            read.step_preview(1)
            x = coded.positions()
            assert np.array_equal(x, read.positions()), f"step {step}"
            if step == 2:  # key 1: lifted by 0.1
                np.testing.assert_allclose(x[20], [0.0, 1.0, 0.1], atol=1e-12)
            if step >= 4:  # key 2 and held: a quarter turn about z through (0, 0.5, 0)
                np.testing.assert_allclose(x[20], [-0.5, 0.5, 0.1], atol=1e-12)


def test_axes_default_to_z_and_hold_keeps_the_earlier_pose():
    with sheet({}) as sim:
        sim.set_handle_keyframes(
            0, [0.0, 0.25], [[0, 0, 0], [0, 0, 0.2]], angles=[0, 0], interpolation="hold"
        )
        sim.step_preview(2)  # t = 0.2: still the first key's pose
        np.testing.assert_allclose(sim.positions()[LEFT_EDGE, 2], 0.0, atol=1e-15)
        sim.step_preview(1)  # t = 0.3: the second key's
        np.testing.assert_allclose(sim.positions()[LEFT_EDGE, 2], 0.2, atol=1e-15)


def test_bad_keys_are_refused_naming_the_key():
    with sheet({}) as sim:
        with pytest.raises(progsim.InvalidArgumentError, match=r"keyframes\[2\]\.time"):
            sim.set_handle_keyframes(0, [0, 1, 0.5], np.zeros((3, 3)))
        with pytest.raises(progsim.InvalidArgumentError, match=r"keyframes\[0\]\.axis"):
            sim.set_handle_keyframes(0, [0], [[0, 0, 0]], axes=[[0, 0, 0]])
        with pytest.raises(progsim.InvalidArgumentError, match=r"keyframes\[1\]\.angle"):
            sim.set_handle_keyframes(0, [0, 1], np.zeros((2, 3)), angles=[0, math.nan])
        with pytest.raises(progsim.InvalidArgumentError, match="translations has 1 keys"):
            sim.set_handle_keyframes(0, [0, 1], [[0, 0, 0]])
        with pytest.raises(progsim.InvalidArgumentError, match=r"shape \(k, 3\)"):
            sim.set_handle_keyframes(0, [0], [0, 0])
        with pytest.raises(progsim.InvalidArgumentError, match="unknown interpolation 'cubic'"):
            sim.set_handle_keyframes(0, [0], [[0, 0, 0]], interpolation="cubic")
        with pytest.raises(progsim.OutOfRangeError):
            sim.set_handle_keyframes(3, [0], [[0, 0, 0]])
        assert set(progsim.INTERPOLATIONS) == {"hold", "linear", "smooth"}
