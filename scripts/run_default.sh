#!/usr/bin/env bash
# The main job: install what is needed, build, animate the bundled default scene with
# Progressive Dynamics (a cloth dropped onto a sphere: a coarse preview, then every finer level),
# write frames, logs, plots and a summary to results/pd_drape.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
scripts/build.sh release -DPROGSIM_BUILD_TESTS=OFF -DPROGSIM_BUILD_BENCH=OFF
scene=${1:-scenes/pd_drape.json}
out=${2:-results/$(basename "$scene" .json)}
build/release/core/progsim run "$scene" --out "$out"
echo "summary: $out/summary.json"
