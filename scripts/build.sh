#!/usr/bin/env bash
# Configures and builds progsim into build/<name>. Usage: scripts/build.sh NAME [cmake args...]
set -euo pipefail
cd "$(dirname "$0")/.."
name=${1:-release}
shift || true
source scripts/ccache_env.sh
cmake -S . -B "build/$name" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "build/$name" -j "$(nproc)"
