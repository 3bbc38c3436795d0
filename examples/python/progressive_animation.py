#!/usr/bin/env python3
"""progsim from Python: a progressive animation (Progressive Dynamics) of a swinging cloth.

Makes a square cloth in code, pins its two top corners on every level, previews its swing on
the coarsest level with a progress bar, refines level by level over the same span, and prints
per level its vertices, the wall time of its steps and the largest distance of its centre of
mass from the preview's at the same time.

    python examples/python/progressive_animation.py [--cells N] [--steps N] [--levels A,B]

Needs the progsim package (``pip install ./bindings/python``, see bindings/python/README.md).
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

import progsim


def square_cloth(cells: int):
    """A 1 m square of cells × cells quads in the x-y plane: (vertices (n, 3), faces (m, 3))
    and the indices of its top corners (0, 1, 0) and (1, 1, 0)."""
    side = cells + 1
    xs, ys = np.meshgrid(np.linspace(0, 1, side), np.linspace(0, 1, side))
    vertices = np.column_stack([xs.ravel(), ys.ravel(), np.zeros(side * side)])
    a = (np.arange(cells)[None, :] + side * np.arange(cells)[:, None]).ravel()
    faces = np.concatenate([np.column_stack([a, a + 1, a + side + 1]),
                            np.column_stack([a, a + side + 1, a + side])])
    return vertices, faces.astype(np.int32), [side * cells, side * side - 1]


def main(argv: list | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cells", type=int, default=20, help="quads per side of the cloth")
    parser.add_argument("--steps", type=int, default=30, help="preview steps of 10 ms")
    parser.add_argument("--levels", default="40,120", help="coarse levels' vertex counts")
    parser.add_argument("--no-progress", action="store_true", help="no progress bars")
    args = parser.parse_args(argv)
    progress = not args.no_progress
    coarse = [int(n) for n in args.levels.split(",")]

    vertices, faces, corners = square_cloth(args.cells)
    print(f"progsim {progsim.library_version()}")
    with progsim.Hierarchy(vertices, faces, coarse_vertex_counts=coarse, pinned=corners) as h:
        # The defaults give a progressive animation; the cloth swings down along -z.
        with progsim.Simulation(
            h, pinned=corners, thickness=5e-4, density=400, gravity=(0, 0, -9.81)
        ) as sim:
            print(f"{sim.kind}, {h.num_levels} levels, prediction {sim.prediction}")
            sim.step_preview(args.steps, progress=progress)
            for _ in range(1, h.num_levels):
                sim.refine(progress=progress)
            for level in range(h.num_levels):
                level_stats = sim.dynamic_level_stats(level)
                steps = sim.step_stats(level)
                print(
                    f"level {level}: {level_stats.vertices} vertices, {level_stats.steps} steps "
                    f"in {level_stats.seconds:.3f} s, max centre-of-mass deviation from the "
                    f"preview {steps['com_deviation'].max():.2e} m, lowest point "
                    f"z = {sim.frame_positions(level, args.steps)[:, 2].min():.3f} m"
                )
    return 0


if __name__ == "__main__":
    sys.exit(main())
