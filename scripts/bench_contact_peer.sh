#!/usr/bin/env bash
# Contact work against IPC Toolkit (bench/contact_peer.py): builds bench_contact_peer, puts
# IPC Toolkit's Python bindings in a venv of their own (build/peer-venv: a benchmark
# dependency only, never linked by the library), and runs the comparison.
# Usage: scripts/bench_contact_peer.sh [contact_peer.py options, e.g. --out CSV --sizes 100]
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x build/release/bench/bench_contact_peer ]; then
  scripts/build.sh release -DPROGSIM_BUILD_BENCH=ON
fi
venv=build/peer-venv
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
  "$venv/bin/python" -m pip install --quiet "ipctk==1.6.1" numpy scipy
fi
exec "$venv/bin/python" bench/contact_peer.py "$@"
