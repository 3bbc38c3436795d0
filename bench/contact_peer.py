#!/usr/bin/env python3
"""Contact work side by side with IPC Toolkit (issue 33): broad phase, barrier value, gradient
and Hessian, and CCD of one step, timed on the same frames by our `bench_contact_peer` and by
`ipctk` (IPC Toolkit's Python bindings, a benchmark dependency only), with 1 and 2 threads.

The frames are a cloth folded on itself (a U fold whose upper layer comes down to 0.4–0.9 mm
above the lower one, so most of it is within d̂ = 1 mm), and the step moves the upper layer
0.6 mm down and 1 cm sideways, so CCD has to cut it. On a small fold, both libraries' candidate
counts are checked against a brute-force count of overlapping boxes (numpy).

usage: scripts/bench_contact_peer.sh (a venv with IPC Toolkit, then this script), or
       python3 bench/contact_peer.py [--sizes 100 200] [--repeats 5] [--out CSV]
        [--bench-exe build/release/bench/bench_contact_peer]
needs: pip install ipctk==1.6.1 numpy scipy (in a venv: the library never links IPC Toolkit)
"""

import argparse
import csv
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

try:
    import ipctk
except ImportError:
    sys.exit("contact_peer.py needs IPC Toolkit's bindings: python3 -m pip install ipctk==1.6.1")

DHAT = 1e-3  # m, the activation gap of both barriers
GAP = 4e-4  # m, the upper layer's lowest height above the lower one
WRINKLE = 2.5e-4  # m, amplitude of the upper layer's wrinkles (gaps GAP .. GAP + 2 WRINKLE)
DROP, SLIDE = 6e-4, 1e-2  # m, the step: the upper layer moves down and sideways


def fold_frames(n):
    """A 1 m square cloth of (n + 1)² vertices folded in a U (bend radius 3 edges) at the start
    of the step and at its end: (V0, V1, F)."""
    h = 1.0 / n
    radius, descent = 3 * h, 0.15
    flat = (1.0 - math.pi * radius) / 2
    s, v = np.meshgrid(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1), indexing="ij")
    s, v = s.ravel(), v.ravel()
    angle = np.clip((s - flat) / radius, 0, math.pi)
    u = np.clip(s - flat - math.pi * radius, 0, None)  # distance along the upper layer
    upper = s > flat + math.pi * radius
    lowered = GAP + (2 * radius - GAP) * np.clip(1 - u / descent, 0, 1) ** 2
    wrinkle = WRINKLE * (1 + np.sin(2 * math.pi * v / (4 * h)) * np.sin(2 * math.pi * u / (4 * h)))
    x = np.where(s < flat, s, np.where(upper, flat - u, flat + radius * np.sin(angle)))
    y = np.where(s < flat, 0.0, np.where(upper, lowered + wrinkle, radius * (1 - np.cos(angle))))
    start = np.column_stack([x, y, v])
    weight = np.where(upper, np.clip(u / descent, 0, 1), 0.0)
    end = start + np.outer(weight, [0.0, -DROP, SLIDE])
    i = np.arange(n)[:, None] * (n + 1) + np.arange(n)[None, :]
    i = i.ravel()
    faces = np.concatenate(
        [np.column_stack([i, i + n + 1, i + 1]), np.column_stack([i + 1, i + n + 1, i + n + 2])]
    ).astype(np.int32)
    return start, end, faces


def write_frames(path, start, end, faces):
    with open(path, "wb") as f:
        np.array([len(start), len(faces)], dtype=np.int64).tofile(f)
        start.astype(np.float64).tofile(f)
        end.astype(np.float64).tofile(f)
        faces.astype(np.int32).tofile(f)


def boxes(points_start, points_end, elements, grow):
    """Per element (rows of vertex indices) the box of its vertices at both ends, ± grow."""
    corners = np.concatenate([points_start[elements], points_end[elements]], axis=1)
    return corners.min(axis=1) - grow, corners.max(axis=1) + grow


def overlapping_pairs(a, b, a_elements, b_elements, same):
    """Brute force: pairs (i, j) whose boxes overlap and that share no vertex (i < j if same)."""
    lo = np.all(a[0][:, None, :] <= b[1][None, :, :], axis=2)
    hit = lo & np.all(b[0][None, :, :] <= a[1][:, None, :], axis=2)
    shared = (a_elements[:, None, :, None] == b_elements[None, :, None, :]).any(axis=(2, 3))
    hit &= ~shared
    if same:
        hit = np.triu(hit, 1)
    return int(hit.sum())


def brute_force_counts(start, end, faces, edges):
    """(vertex–face, edge–edge) pairs whose boxes, each grown by d̂/2, overlap over the step."""
    vertices = np.arange(len(start))[:, None]
    vf = overlapping_pairs(
        boxes(start, end, vertices, DHAT / 2),
        boxes(start, end, faces, DHAT / 2),
        vertices,
        faces,
        False,
    )
    e = boxes(start, end, edges, DHAT / 2)
    return vf, overlapping_pairs(e, e, edges, edges, True)


def median_seconds(repeats, work):
    times = []
    for _ in range(repeats):
        begin = time.perf_counter()
        work()
        times.append(time.perf_counter() - begin)
    return statistics.median(times)


BROAD_PHASES = {
    "HashGrid": ipctk.HashGrid,
    "LBVH": ipctk.LBVH,
    "SweepAndPrune": ipctk.SweepAndPrune,
}


def peer_broad_phase(mesh, start, end, repeats):
    """Their fastest broad phase (static and swept boxes grown by d̂/2): times and counts."""
    best = {}
    for name, make in BROAD_PHASES.items():
        for kind, ends in (("broad_static", (start,)), ("broad_swept", (start, end))):
            cands = ipctk.Candidates()
            seconds = median_seconds(
                repeats,
                lambda: cands.build(mesh, *ends, inflation_radius=DHAT / 2, broad_phase=make()),
            )
            counts = (len(cands.fv_candidates), len(cands.ee_candidates))
            if kind not in best or seconds < best[kind][0]:
                best[kind] = (seconds, name, counts)
    return best


def peer_times(start, end, faces, threads, repeats):
    """IPC Toolkit on the same frames: {phase: (seconds, method, counts)}."""
    ipctk.set_num_threads(threads)
    edges = ipctk.edges(faces)
    mesh = ipctk.CollisionMesh(start, edges, faces)
    out = peer_broad_phase(mesh, start, end, repeats)
    static = ipctk.Candidates()
    static.build(mesh, start, inflation_radius=DHAT / 2, broad_phase=ipctk.HashGrid())
    collisions = ipctk.NormalCollisions()
    out["active_set"] = (
        median_seconds(repeats, lambda: collisions.build(static, mesh, start, DHAT)),
        "NormalCollisions.build",
        (len(collisions),),
    )
    barrier = ipctk.BarrierPotential(DHAT, 1.0)
    clamp = ipctk.PSDProjectionMethod.CLAMP
    out["value"] = (median_seconds(repeats, lambda: barrier(collisions, mesh, start)), "", ())
    out["gradient"] = (
        median_seconds(repeats, lambda: barrier.gradient(collisions, mesh, start)),
        "",
        (),
    )
    hessian = [None]

    def assemble():
        hessian[0] = barrier.hessian(collisions, mesh, start, clamp)

    out["hessian"] = (median_seconds(repeats, assemble), "PSD clamp", (hessian[0].nnz,))
    swept = ipctk.Candidates()
    swept.build(mesh, start, end, inflation_radius=DHAT / 2, broad_phase=ipctk.HashGrid())
    alpha = [0.0]

    def ccd():  # the same algorithm as ours (C-IPC's ACCD, rescaling 0.9)
        alpha[0] = swept.compute_collision_free_stepsize(mesh, start, end, 0.0, ipctk.AdditiveCCD())

    out["ccd_narrow"] = (median_seconds(repeats, ccd), "AdditiveCCD", (alpha[0],))
    return out


def our_times(exe, frames_path, threads, repeats):
    result = subprocess.run(
        [exe, frames_path, repr(DHAT), str(threads), str(repeats)],
        check=True,
        capture_output=True,
        text=True,
    )
    return json.loads(result.stdout)


def check_counts(exe, directory):
    """Brute force against both libraries' candidate counts on a small fold (441 vertices)."""
    start, end, faces = fold_frames(20)
    path = os.path.join(directory, "small.bin")
    write_frames(path, start, end, faces)
    ours = our_times(exe, path, 1, 1)
    brute = brute_force_counts(start, end, faces, ipctk.edges(faces))
    mesh = ipctk.CollisionMesh(start, ipctk.edges(faces), faces)
    theirs = peer_broad_phase(mesh, start, end, 1)["broad_swept"][2]
    print(
        f"small fold, swept boxes: brute force {brute[0]} vertex-face + {brute[1]} edge-edge; "
        f"ours {ours['swept_vf']} + {ours['swept_ee']}; IPC Toolkit {theirs[0]} + {theirs[1]}"
    )
    if (ours["swept_vf"], ours["swept_ee"]) != brute:
        sys.exit("our candidate counts differ from the brute-force count")
    return brute, (ours["swept_vf"], ours["swept_ee"]), theirs


PHASES = [  # (label, our key(s), their key)
    ("broad phase, static boxes", ("broad_static",), "broad_static"),
    ("broad phase, swept boxes", ("broad_swept",), "broad_swept"),
    ("barrier value", ("value",), "value"),
    ("barrier gradient, after the value at that x (ours: + active set)", ("gradient",), "gradient"),
    ("barrier Hessian, PSD, assembled (ditto)", ("hessian",), "hessian"),
    ("  the same, first assembly (new pattern)", ("hessian_new_pattern",), "hessian"),
    ("CCD narrow phase", ("ccd_narrow",), "ccd_narrow"),
]


def compare(exe, directory, n, threads, repeats):
    start, end, faces = fold_frames(n)
    path = os.path.join(directory, f"fold_{n}.bin")
    write_frames(path, start, end, faces)
    ours = our_times(exe, path, threads, repeats)
    theirs = peer_times(start, end, faces, threads, repeats)
    print(
        f"\n{len(start)} vertices, {threads} thread(s): active pairs ours {ours['active']}, "
        f"theirs {theirs['active_set'][2][0]}; step ours {ours['alpha']:.4f}, "
        f"theirs {theirs['ccd_narrow'][2][0]:.4f}"
    )
    print(
        f"ours: Hessian triplets {ours['hessian_triplets']:.4f} s of the assembled Hessian; "
        f"the first assembly, which builds the pattern, {ours['hessian_new_pattern']:.4f} s"
    )
    print(f"{'phase':40s} {'ours s':>10s} {'theirs s':>10s} {'ours/theirs':>12s}  their method")
    rows = []
    for label, keys, key in PHASES:
        mine = sum(ours[k] for k in keys)
        seconds, method, _ = theirs[key]
        # Ours finds the active pairs among the candidates on every call; theirs once, before
        # (NormalCollisions.build), which is added to their value, the first call of the three.
        if key == "value":
            seconds += theirs["active_set"][0]
            method = "NormalCollisions.build + value"
        ratio = mine / seconds if seconds > 0 else float("inf")
        print(f"{label:40s} {mine:10.4f} {seconds:10.4f} {ratio:12.2f}  {method}")
        rows.append([len(start), threads, label, mine, seconds, ratio, method])
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[100, 200])
    parser.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--out", default="contact_peer.csv")
    parser.add_argument("--bench-exe", default="build/release/bench/bench_contact_peer")
    args = parser.parse_args()
    if not os.access(args.bench_exe, os.X_OK):
        sys.exit(f"{args.bench_exe} not found: build with -DPROGSIM_BUILD_BENCH=ON")
    print(f"IPC Toolkit {ipctk.__version__}, d̂ = {DHAT} m, median of {args.repeats} runs")
    with tempfile.TemporaryDirectory() as directory:
        brute, ours, theirs = check_counts(args.bench_exe, directory)
        rows = [
            row
            for n in args.sizes
            for threads in args.threads
            for row in compare(args.bench_exe, directory, n, threads, args.repeats)
        ]
    with open(args.out, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["vertices", "threads", "phase", "ours_s", "theirs_s", "ratio", "their_method"])
        w.writerows(rows)
        f.write(
            f"# small fold swept candidates (vertex-face, edge-edge): brute force {brute}, "
            f"ours {ours}, IPC Toolkit {theirs}\n"
        )
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
