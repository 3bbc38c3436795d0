#!/usr/bin/env bash
# Installs everything progsim needs on a Debian machine, idempotently: the Debian packages of
# the C++ build, then (as later parts of the product arrive) Python and Rust pieces.
set -euo pipefail

APT_PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libsuitesparse-dev libopenblas-openmp-dev libcgal-dev
  nlohmann-json3-dev libcli11-dev libgtest-dev
  clang-format
)

missing=()
for pkg in "${APT_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "ok installed" || missing+=("$pkg")
done
if ((${#missing[@]})); then
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  echo "install_deps: installing ${missing[*]}"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "install_deps: all Debian packages present"
fi
