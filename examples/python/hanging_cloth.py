#!/usr/bin/env python3
"""progsim from Python: a cloth hanging from its two top corners.

Loads the bundled mesh, pins the corners nearest to (0, 1, 0) and (1, 1, 0), previews with a
progress bar, refines to the finest level, steps there, writes the final mesh and prints
the statistics.

    python examples/python/hanging_cloth.py [--mesh MESH] [--out OUT] [--steps N]

Needs the progsim package (``pip install ./bindings/python``, see bindings/python/README.md).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

import progsim

REPO = Path(__file__).resolve().parents[2]


def nearest_vertex(positions: np.ndarray, point: tuple) -> int:
    """Index of the row of the (n, 3) array ``positions`` nearest to ``point``."""
    return int(np.argmin(np.linalg.norm(positions - np.asarray(point), axis=1)))


def main(argv: list | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--mesh", type=Path, default=REPO / "scenes" / "meshes" / "square_cloth.obj"
    )
    parser.add_argument("--out", type=Path, default=Path("hanging_cloth_final.obj"))
    parser.add_argument("--steps", type=int, default=25, help="steps before and after refining")
    parser.add_argument("--no-progress", action="store_true", help="no progress bars")
    args = parser.parse_args(argv)
    progress = not args.no_progress

    print(f"progsim {progsim.library_version()}")
    with progsim.Hierarchy.from_file(args.mesh) as hierarchy:
        rest = hierarchy.rest_positions()  # finest level, (n, 3) m
        corners = [nearest_vertex(rest, (0, 1, 0)), nearest_vertex(rest, (1, 1, 0))]
        # The cloth lies in the x-y plane and swings down along -z.
        with progsim.Simulation(
            hierarchy,
            pinned=corners,
            thickness=5e-4,
            time_step=0.02,
            gravity=(0.0, 0.0, -9.81),
        ) as sim:
            sim.set_param("material.youngs_modulus", 2e5)

            sim.step_preview(args.steps, progress=progress)
            while sim.current_level < hierarchy.num_levels - 1:
                sim.refine(progress=progress)
            sim.step_preview(args.steps, progress=progress)

            finest = hierarchy.num_levels - 1
            positions = sim.positions(finest)
            stats = sim.level_stats(finest)
            print(
                f"level {stats.level}: {stats.steps} steps, {stats.newton_iterations} Newton "
                f"iterations ({stats.converged_steps} converged steps), {stats.seconds:.3f} s, "
                f"t = {stats.simulated_time:.3f} s"
            )
            print(f"lowest point z = {positions[:, 2].min():.3f} m")
            print(f"pinned corners {corners} at {positions[corners].tolist()}")
            sim.write_mesh(finest, args.out)
            print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except progsim.ProgsimError as error:
        print(f"error: {error.status}: {error}", file=sys.stderr)
        sys.exit(1)
