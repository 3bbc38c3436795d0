#!/usr/bin/env bash
# Fetches real meshes nobody here wrote (DESIGN.md §4) for tests/mesh/test_real_meshes.cpp:
# CGAL's data set from Debian's libcgal-demo package, without installing the package.
# Result: ${PROGSIM_MESH_CACHE:-$HOME/.cache/progsim/meshes}/meshes/*.off (about 30 MB).
# Idempotent: does nothing when the meshes are already there.
# Licence: files without their own notice are CC0 per CGAL; some models come from the
# Stanford 3D scanning repository.
set -euo pipefail

cache=${PROGSIM_MESH_CACHE:-$HOME/.cache/progsim/meshes}
marker="$cache/meshes/sphere.off"
if [ -f "$marker" ]; then
  echo "fetch_test_meshes: meshes present in $cache/meshes"
  exit 0
fi

mkdir -p "$cache"
work=$(mktemp -d "$cache/.fetch.XXXXXX")
trap 'rm -rf "$work"' EXIT
cd "$work"

if ! apt-get download libcgal-demo >/dev/null 2>&1; then
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  echo "fetch_test_meshes: apt-get download failed; updating the package lists and retrying"
  $sudo_cmd apt-get update -qq
  apt-get download libcgal-demo
fi

dpkg -x libcgal-demo_*.deb package
data=package/usr/share/doc/libcgal-dev/data.tar.gz
if [ ! -f "$data" ]; then
  echo "fetch_test_meshes: $data not found in libcgal-demo; its layout changed" >&2
  exit 1
fi
# The archive holds data/meshes/...; keep only that folder, moved into place in one step so
# that an interrupted run never leaves a half-filled meshes/ behind.
tar -xzf "$data" --strip-components=1 data/meshes
rm -rf "$cache/meshes"
mv meshes "$cache/meshes"
echo "fetch_test_meshes: $(ls "$cache/meshes" | wc -l) files in $cache/meshes"
