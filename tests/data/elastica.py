#!/usr/bin/env python3
"""Reference tip displacements of a cantilever under an end load (the inextensible elastica),
for tests/sim/test_bending_convergence.cpp (a dead end shear, Sze, Liu & Lo 2004 section 3.1)
and tests/sim/test_follower_loads.cpp (a follower load that stays normal to the free end).

Moment balance about s with the end force F = P n(theta_L), n normal to the end's tangent:
E I theta'(s) = (r(L) - r(s)) x F, so theta'' = -k cos(theta - theta_L) on s in [0, 1],
theta(0) = 0 (clamped), theta'(1) = 0 (free end), k = P L^2 / (E I); x' = cos(theta),
z' = sin(theta). A dead shear (always along z) is the same equation with theta_L = 0
(Mattiasson 1981's problem). For a given end angle the slope theta'(0) is found by bisection on
theta'(1) = 0; a follower's theta_L by bisection on theta(1) = theta_L. Classical RK4, 20 000
steps. Independent of progsim: numpy only. Prints -u/L, w/L (and theta_L) at k = 2, 4 (dead)
and 1, 2, 4 (follower), in about 3.5 minutes. Output at the time of writing:
dead     k = 2: -u/L = 0.16064, w/L = 0.49346
dead     k = 4: -u/L = 0.32894, w/L = 0.66996
follower k = 1: -u/L = 0.06435, w/L = 0.32064, theta_L = 0.49588
follower k = 2: -u/L = 0.23264, w/L = 0.57384, theta_L = 0.96824
follower k = 4: -u/L = 0.65725, w/L = 0.78617, theta_L = 1.77644
"""
import numpy as np


def integrate(k, end_angle, slope, steps):
    """(theta, theta', x, z) at s = 1 from theta(0) = 0, theta'(0) = slope."""
    h = 1.0 / steps
    y = np.array([0.0, slope, 0.0, 0.0])

    def f(y):
        return np.array([y[1], -k * np.cos(y[0] - end_angle), np.cos(y[0]), np.sin(y[0])])

    for _ in range(steps):
        k1 = f(y)
        k2 = f(y + 0.5 * h * k1)
        k3 = f(y + 0.5 * h * k2)
        k4 = f(y + h * k3)
        y = y + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
    return y


def free_end(k, end_angle, steps):
    """The state at s = 1 whose slope there is 0, for a given end angle."""
    lo, hi = 0.0, 2.0 * k  # theta'(1) < 0 at slope 0 and > 0 at slope 2k
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if integrate(k, end_angle, mid, steps)[1] > 0.0:
            hi = mid
        else:
            lo = mid
    return integrate(k, end_angle, 0.5 * (lo + hi), steps)


def dead_tip(k, steps=20000):
    y = free_end(k, 0.0, steps)
    return 1.0 - y[2], y[3]


def follower_tip(k, steps=20000):
    lo, hi = 0.0, min(k, 3.0)  # theta(1) - theta_L > 0 at theta_L = 0, < 0 at the top
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        if free_end(k, mid, steps // 10)[0] > mid:
            lo = mid
        else:
            hi = mid
    angle = 0.5 * (lo + hi)
    y = free_end(k, angle, steps)
    return 1.0 - y[2], y[3], angle


if __name__ == "__main__":
    for k in (2.0, 4.0):
        u, w = dead_tip(k)
        print(f"dead     k = {k:g}: -u/L = {u:.5f}, w/L = {w:.5f}")
    for k in (1.0, 2.0, 4.0):
        u, w, angle = follower_tip(k)
        print(f"follower k = {k:g}: -u/L = {u:.5f}, w/L = {w:.5f}, theta_L = {angle:.5f}")
