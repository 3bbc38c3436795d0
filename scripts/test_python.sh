#!/usr/bin/env bash
# Installs the Python package (bindings/python) with its test needs, then runs its tests.
# pip builds the package with CMake (scikit-build-core): the C++ core and the cffi extension,
# in bindings/python/build/<tag> (kept, so a reinstall recompiles only what changed; with
# ccache the objects of build/release are reused). Usage: scripts/test_python.sh [pytest args]
# Environment: PYTHON (default python3).
set -euo pipefail
cd "$(dirname "$0")/.."
python=${PYTHON:-python3}
source scripts/ccache_env.sh
export PIP_ROOT_USER_ACTION=ignore PIP_DISABLE_PIP_VERSION_CHECK=1

echo "== installing the progsim Python package =="
"$python" -m pip install --quiet "numpy>=1.20" "tqdm>=4.0" "cffi>=1.15" "pytest>=7" \
  "dask[distributed]" matplotlib usd-core
# Build isolation fetches scikit-build-core and cffi from the index; offline, build with what
# is here.
if ! "$python" -m pip install --quiet --force-reinstall --no-deps ./bindings/python; then
  echo "isolated build failed; retrying with --no-build-isolation" >&2
  "$python" -m pip install --quiet "scikit-build-core>=0.10" "cffi>=1.15" ||
    echo "could not install the build tools; building with those already installed" >&2
  "$python" -m pip install --quiet --force-reinstall --no-deps --no-build-isolation ./bindings/python
fi

echo "== Python tests =="
# From a neutral folder's point of view the package is the installed one, not src/.
"$python" -m pytest bindings/python/tests -q "$@"
