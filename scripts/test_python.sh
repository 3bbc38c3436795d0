#!/usr/bin/env bash
# Installs the Python package (bindings/python) with its test needs, then runs its tests.
# Idempotent: every run rebuilds and reinstalls progsim from the work tree.
# Needs build/release (scripts/build.sh release). Usage: scripts/test_python.sh [pytest args]
# Environment: PYTHON (default python3); PROGSIM_LIB_DIR / PROGSIM_INCLUDE_DIR as in
# bindings/python/progsim_build.py.
set -euo pipefail
cd "$(dirname "$0")/.."
python=${PYTHON:-python3}
lib_dir=${PROGSIM_LIB_DIR:-$PWD/build/release/core}
if ! ls "$lib_dir"/libprogsim.* >/dev/null 2>&1; then
  echo "test_python.sh: no libprogsim in $lib_dir; run scripts/build.sh release first" >&2
  exit 1
fi
export PIP_ROOT_USER_ACTION=ignore PIP_DISABLE_PIP_VERSION_CHECK=1

echo "== installing the progsim Python package =="
"$python" -m pip install --quiet "numpy>=1.20" "tqdm>=4.0" "cffi>=1.15" "pytest>=7"
# Build isolation fetches setuptools/cffi from the index; offline, build with what is here.
if ! "$python" -m pip install --quiet --force-reinstall --no-deps ./bindings/python; then
  echo "isolated build failed; retrying with --no-build-isolation" >&2
  "$python" -m pip install --quiet "setuptools>=61" wheel "cffi>=1.15" ||
    echo "could not install the build tools; building with those already installed" >&2
  "$python" -m pip install --quiet --force-reinstall --no-deps --no-build-isolation ./bindings/python
fi

echo "== Python tests =="
# From a neutral folder's point of view the package is the installed one, not src/.
"$python" -m pytest bindings/python/tests -q "$@"
