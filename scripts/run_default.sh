#!/usr/bin/env bash
# The main job: install what is needed, build, simulate the bundled default scene (a cloth
# hanging from two corners), write frames, logs and a summary to results/hanging_cloth.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
scripts/build.sh release -DPROGSIM_BUILD_TESTS=OFF -DPROGSIM_BUILD_BENCH=OFF
scene=${1:-scenes/hanging_cloth.json}
out=${2:-results/$(basename "$scene" .json)}
build/release/core/progsim run "$scene" --out "$out"
echo "summary: $out/summary.json"
