#!/usr/bin/env python3
"""Benchmark of progsim on Dask: a sweep of flag previews and the flag's finest level refined
in time windows, each on local clusters of 1 and 2 single-threaded workers.

Prints a table and writes CSV (one row per measurement): wall time, speed-up against one
worker, per-run time, bytes sent to and returned from each task, and the scaling the
measured figures predict on N machines (runs of the 1-worker median cost, with its per-task
overhead; each machine receives the spec and returns the result once per run over a network
of --bandwidth bytes/s). "run s" is the median wall time of one run in that sweep.

Usage: python3 bench/dask_sweep.py [--scene scenes/pd_flag.json] [--steps 60] [--out CSV]
Needs the progsim package (scripts/test_python.sh installs it) with Dask.
"""

from __future__ import annotations

import argparse
import csv
import math
import pickle
import statistics
import time
from pathlib import Path

from progsim.sweep import Range, local_client, sweep
from progsim.windows import refine_in_windows

ROOT = Path(__file__).resolve().parent.parent

#: 16 runs: four stiffnesses × four drag coefficients of the wind.
PARAMETERS = {
    "material.youngs_modulus": Range(5e5, 2e6, 4),
    "scene.wind.drag": [0.8, 1.0, 1.2, 1.4],
}


def timed_sweep(scene: Path, steps: int, workers: int):
    """(seconds of the sweep alone, its Sweep) on a fresh cluster of `workers` workers."""
    with local_client(workers) as client:
        start = time.perf_counter()
        runs = sweep(scene, PARAMETERS, client, steps=steps, progress=False)
        seconds = time.perf_counter() - start
        client.cluster.close()
    failed = [row for row in runs.rows() if row["status"] != "PS_OK"]
    if failed:
        raise SystemExit(f"bench: {len(failed)} runs failed: {failed[0]['error']}")
    return seconds, runs


def timed_windows(scene: Path, steps: int, workers: int):
    """(seconds, WindowedRefinement) of the finest level in `workers` windows on as many."""
    with local_client(workers) as client:
        start = time.perf_counter()
        joined = refine_in_windows(scene, workers, client, steps=steps)
        seconds = time.perf_counter() - start
        client.cluster.close()
    return seconds, joined


def predicted_speedup(
    runs: int,
    run_seconds: float,
    overhead: float,
    nbytes: float,
    bandwidth: float,
    machines: int,
) -> float:
    """Speed-up on `machines` machines of one single-threaded worker each: runs in
    ceil(runs / machines) rounds, each paying the run, the task overhead and the transfer.
    """
    per_run = run_seconds + overhead + nbytes / bandwidth
    return runs * per_run / (math.ceil(runs / machines) * per_run)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", type=Path, default=ROOT / "scenes" / "pd_flag.json")
    parser.add_argument(
        "--steps", type=int, default=60, help="preview steps (10 ms each)"
    )
    parser.add_argument(
        "--bandwidth", type=float, default=1.25e8, help="bytes/s (1 Gbit/s)"
    )
    parser.add_argument(
        "--out", type=Path, default=ROOT / "bench" / "results" / "dask_sweep.csv"
    )
    args = parser.parse_args()

    rows = []
    sweeps = {w: timed_sweep(args.scene, args.steps, w) for w in (1, 2)}
    one_seconds, one_runs = sweeps[1]
    run_seconds = statistics.median(r["seconds"] for r in one_runs.rows())
    bytes_in = statistics.mean(r["bytes_in"] for r in one_runs.rows())
    bytes_out = statistics.mean(r["bytes_out"] for r in one_runs.rows())
    overhead = max(0.0, one_seconds / len(one_runs) - run_seconds)
    for workers, (seconds, runs) in sweeps.items():
        rows.append(
            {
                "job": "sweep 16 flag previews",
                "workers": workers,
                "seconds": seconds,
                "speedup": one_seconds / seconds,
                # each run's own time: above the 1-worker median where the workers compete
                "run_seconds": statistics.median(r["seconds"] for r in runs.rows()),
                "bytes_in_per_run": bytes_in,
                "bytes_out_per_run": bytes_out,
            }
        )
    for machines in (4, 8, 16):
        rows.append(
            {
                "job": "sweep, predicted",
                "workers": machines,
                "speedup": predicted_speedup(
                    16,
                    run_seconds,
                    overhead,
                    bytes_in + bytes_out,
                    args.bandwidth,
                    machines,
                ),
                "run_seconds": run_seconds,
                "bytes_in_per_run": bytes_in,
                "bytes_out_per_run": bytes_out,
            }
        )

    windows = {w: timed_windows(args.scene, args.steps, w) for w in (1, 2)}
    serial_seconds = windows[1][0]
    for workers, (seconds, joined) in windows.items():
        seams = joined.seams
        window_bytes = statistics.mean(len(pickle.dumps(w)) for w in joined.windows)
        rows.append(
            {
                "job": f"finest level in {workers} window(s)",
                "workers": workers,
                "seconds": seconds,
                "speedup": serial_seconds / seconds,
                "run_seconds": max(w.total_seconds for w in joined.windows),
                "window_seconds": " ".join(f"{w.seconds:.1f}" for w in joined.windows),
                "coarser_levels_seconds": " ".join(
                    f"{w.total_seconds - w.seconds:.1f}" for w in joined.windows
                ),
                "bytes_out_per_run": window_bytes,
                "seam_jump_m": seams[0]["jump"] if seams else "",
                "seam_second_difference_m": (
                    seams[0]["second_difference"] if seams else ""
                ),
                "interior_max_second_difference_m": (
                    seams[0]["interior_max"] if seams else ""
                ),
            }
        )

    names = [
        "job",
        "workers",
        "seconds",
        "speedup",
        "run_seconds",
        "window_seconds",
        "coarser_levels_seconds",
        "bytes_in_per_run",
        "bytes_out_per_run",
        "seam_jump_m",
        "seam_second_difference_m",
        "interior_max_second_difference_m",
    ]
    args.out.parent.mkdir(parents=True, exist_ok=True)
    with open(args.out, "w", newline="") as out:
        writer = csv.DictWriter(out, fieldnames=names)
        writer.writeheader()
        writer.writerows(rows)
    print(
        f"{'job':34} {'workers':>7} {'seconds':>8} {'speedup':>7} {'run s':>7} "
        f"{'bytes in':>9} {'bytes out':>9}"
    )
    for row in rows:
        seconds = f"{row['seconds']:8.2f}" if "seconds" in row else f"{'-':>8}"
        print(
            f"{row['job']:34} {row['workers']:7d} {seconds} {row['speedup']:7.2f} "
            f"{row['run_seconds']:7.2f} {row.get('bytes_in_per_run', 0):9.0f} "
            f"{row.get('bytes_out_per_run', 0):9.0f}"
        )
    for workers, (_, joined) in windows.items():
        for w in joined.windows:
            print(
                f"{workers} window(s): steps {w.first}-{w.last}: finest level {w.seconds:.1f} s, "
                f"preview and coarser levels {w.total_seconds - w.seconds:.1f} s"
            )
        for seam in joined.seams:
            print(
                f"seam at frame {seam['frame']}: jump {seam['jump']:.3g} m, second difference "
                f"{seam['second_difference']:.3g} m (interior median "
                f"{seam['interior_median']:.3g}, max {seam['interior_max']:.3g})"
            )
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
