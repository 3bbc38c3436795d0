#!/usr/bin/env python3
"""Reference tip displacements of a cantilever under a dead end shear (the inextensible
elastica), used by tests/sim/test_bending_convergence.cpp for Sze, Liu & Lo (2004) §3.1.

theta'' = -k cos(theta) on s in [0, 1], theta(0) = 0 (clamped), theta'(1) = 0 (free end),
k = P L^2 / (E I); x' = cos(theta), z' = sin(theta). Shooting on theta'(0) by bisection,
classical RK4 with 20 000 steps. Prints -u/L and w/L at k = 2 and 4 (Sze's P/P_max = 0.5, 1).
Independent of progsim: numpy only. Output at the time of writing:
k = 2: -u/L = 0.16064, w/L = 0.49346; k = 4: -u/L = 0.32894, w/L = 0.66996.
"""
import numpy as np


def integrate(k, slope, steps):
    """(theta, theta', x, z) at s = 1 from theta(0) = 0, theta'(0) = slope."""
    h = 1.0 / steps
    y = np.array([0.0, slope, 0.0, 0.0])

    def f(y):
        return np.array([y[1], -k * np.cos(y[0]), np.cos(y[0]), np.sin(y[0])])

    for _ in range(steps):
        k1 = f(y)
        k2 = f(y + 0.5 * h * k1)
        k3 = f(y + 0.5 * h * k2)
        k4 = f(y + h * k3)
        y = y + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
    return y


def tip(k, steps=20000):
    lo, hi = 0.0, k  # theta'(1) < 0 at slope 0 and > 0 at slope k
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if integrate(k, mid, steps // 5)[1] > 0.0:
            hi = mid
        else:
            lo = mid
    y = integrate(k, 0.5 * (lo + hi), steps)
    return 1.0 - y[2], y[3]


if __name__ == "__main__":
    for k in (2.0, 4.0):
        u, w = tip(k)
        print(f"k = {k:g}: -u/L = {u:.5f}, w/L = {w:.5f}")
