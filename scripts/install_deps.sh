#!/usr/bin/env bash
# Installs everything progsim needs on a Debian machine, idempotently: the Debian packages of
# the C++ build and the sanitizer/fuzzer build (clang), the Python packages of the cffi
# bindings and their tests, and a Rust toolchain for the bindgen crates.
set -euo pipefail

# Both OpenBLAS builds: Debian's libblas.so.3 alternative picks the pthreads one when present
# (as on most machines with OpenBLAS), and the tests run the factorization under each
# (tests/blas/blas_variants.cpp).
APT_PACKAGES=(
  build-essential cmake ninja-build pkg-config ccache
  libeigen3-dev libsuitesparse-dev libopenblas-openmp-dev libopenblas0-pthread libcgal-dev
  nlohmann-json3-dev libcli11-dev libgtest-dev libcairo2-dev fonts-dejavu-core
  clang-format clang-14 libclang-rt-14-dev libomp-14-dev libclang-dev
  python3-pip python3-venv
)

sudo_cmd=""
[ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
missing=()
for pkg in "${APT_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "ok installed" || missing+=("$pkg")
done
if ((${#missing[@]})); then
  echo "install_deps: installing ${missing[*]}"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "install_deps: all Debian packages present"
fi

PYTHON=${PYTHON:-python3}
# The package's build backend, the sweeps' engine (Dask) and contact sheets (matplotlib), and
# the USD export's usd-core.
PYTHON_PACKAGES=(cffi numpy tqdm pytest scikit-build-core "dask[distributed]" matplotlib usd-core)
if ! "$PYTHON" -c "import cffi, numpy, tqdm, pytest, scikit_build_core, distributed, matplotlib, pxr" \
  2>/dev/null; then
  echo "install_deps: installing Python packages"
  "$PYTHON" -m pip install -q --disable-pip-version-check "${PYTHON_PACKAGES[@]}"
fi

if ! command -v cargo >/dev/null 2>&1; then
  echo "install_deps: installing Rust (Debian's cargo)"
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends cargo
fi
