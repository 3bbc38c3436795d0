#!/usr/bin/env bash
# Runs every test: installs what is needed, builds, runs the C++ tests in a normal build and
# under AddressSanitizer + UBSan, and checks that an installed copy works with find_package.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
scripts/fetch_test_meshes.sh

echo "== release build and tests =="
scripts/build.sh release
ctest --test-dir build/release --output-on-failure -j "$(nproc)"

echo "== installed copy: find_package(progsim) =="
rm -rf build/install build/consumer
cmake --install build/release --prefix "$PWD/build/install" >/dev/null
cmake -S tests/consumer -B build/consumer -G Ninja -DCMAKE_PREFIX_PATH="$PWD/build/install" >/dev/null
cmake --build build/consumer >/dev/null
build/consumer/progsim_consumer

echo "== AddressSanitizer + UBSan build and tests =="
scripts/build.sh asan -DPROGSIM_SANITIZE=ON -DPROGSIM_BUILD_BENCH=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build/asan --output-on-failure -j "$(nproc)"
