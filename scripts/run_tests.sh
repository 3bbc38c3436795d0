#!/usr/bin/env bash
# Runs every test: installs what is needed, builds, and runs the C++ and C tests (normal build),
# an installed-copy find_package check, the Python (cffi) binding tests, the CLI sweep, a
# self-contained Python wheel, the Rust (bindgen) binding tests (also against pkg-config),
# then the C++/C tests again under AddressSanitizer + UBSan (clang) and 30 000 libFuzzer inputs
# over the scene parser and mesh loaders. CI runs exactly this, with CI=true: the main job
# (scripts/run_default.sh) then runs first on the same clone.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
scripts/fetch_test_meshes.sh
export OMP_WAIT_POLICY=passive  # tests share the cores; idle OpenMP threads must sleep

# The fewest tests the release build may run: a build that lost a test directory (or every
# test, as a reused build/release configured by the main job once did) fails here loudly.
min_release_tests=300

# Runs ctest on build/release with the given arguments (its output also in
# build/release/ctest.log), then fails unless it ran every test it lists for that build and at
# least $min_release_tests of them. A skipped test (GTEST_SKIP) counts as run; one with the
# DISABLED property does not, so it fails the check too.
release_ctest() {
  local listed ran
  ctest --test-dir build/release --output-on-failure --no-tests=error "$@" |
    tee build/release/ctest.log
  listed=$(ctest --test-dir build/release -N | sed -n 's/^Total Tests: \([0-9][0-9]*\)$/\1/p')
  ran=$(sed -n 's/.* tests failed out of \([0-9][0-9]*\)$/\1/p' build/release/ctest.log)
  if [ -z "$listed" ] || [ -z "$ran" ] || [ "$ran" -ne "$listed" ] ||
    [ "$ran" -lt "$min_release_tests" ]; then
    echo "run_tests: ctest ran ${ran:-no} tests of the ${listed:-no} build/release lists;" \
      "expected all of them and at least $min_release_tests" >&2
    return 1
  fi
  echo "run_tests: ctest ran all $ran tests build/release lists"
}

if [ "${CI:-}" = true ]; then
  echo "== main job (scripts/run_default.sh), then the tests on the same clone =="
  # It configures build/release without tests; the release build below must still run them
  # all. The library and the CLI it builds are reused there (nothing of them is rebuilt), so
  # this costs the scene's run: 31 s on 2 cores.
  scripts/run_default.sh
fi

echo "== release build: C++ and C tests =="
# Tests and benchmarks on explicitly: the main job (run_default.sh) configures build/release
# without them, and a reused cache would otherwise build and run no test at all.
scripts/build.sh release -DPROGSIM_BUILD_TESTS=ON -DPROGSIM_BUILD_BENCH=ON
release_ctest -j "$(nproc)"

echo "== installed copy: find_package(progsim) =="
rm -rf build/install build/consumer
cmake --install build/release --prefix "$PWD/build/install" >/dev/null
cmake -S tests/consumer -B build/consumer -G Ninja -DCMAKE_PREFIX_PATH="$PWD/build/install" >/dev/null
cmake --build build/consumer >/dev/null
build/consumer/progsim_consumer

echo "== Python bindings (cffi) =="
scripts/test_python.sh

echo "== the CLI's sweep command, through the installed package =="
sweep_out=$(mktemp -d)
build/release/core/progsim sweep scenes/hanging_cloth.json --serial --steps 2 \
  --param material.youngs_modulus=3e5,6e5 --out "$sweep_out"
if [ "$(wc -l <"$sweep_out/runs.csv")" -ne 3 ] || [ ! -s "$sweep_out/contact_sheet.png" ]; then
  echo "run_tests: progsim sweep did not write 2 runs and a contact sheet" >&2
  exit 1
fi
rm -rf "$sweep_out"

echo "== a self-contained wheel (installed elsewhere, build trees moved aside) =="
scripts/test_wheel.sh

echo "== Rust bindings (bindgen) =="
scripts/test_rust.sh

echo "== AddressSanitizer + UBSan build (clang): C++ and C tests, then libFuzzer =="
# -O1 with line tables only (reports keep file:line), Eigen's headers uninstrumented
# (cmake/sanitizer_ignorelist.txt) and without NDEBUG, so Eigen checks every index itself.
# Measured on 2 cores: the tests below ran in 180 s against 489 s with Eigen instrumented.
sanitizer_flags="-O1 -gline-tables-only"
CC=clang-14 CXX=clang++-14 scripts/build.sh asan -DPROGSIM_SANITIZE=ON -DPROGSIM_FUZZ=ON \
  -DPROGSIM_BUILD_BENCH=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$sanitizer_flags" -DCMAKE_C_FLAGS_RELWITHDEBINFO="$sanitizer_flags"
# The long contact scenes (90-step drapes, the two-turn twist, the spinning sphere, one step of
# every bundled scene, the PSQ scenes' full progressive and direct runs) took 1-7 min each
# under the sanitizers with Eigen instrumented, and the real-mesh drape takes 18 s in release;
# they run in the release build above. Under the sanitizers the same contact code runs
# through its unit tests (barrier, friction, CCD, broad phase, distances, safe refinement) and
# the short scenes (incline, strain limit, bad input). The decimation guard's real-mesh levels
# at three scales (CrossingFreeLevels, 15 s in release) took 500 s of CPU under the sanitizers;
# its unit tests (CollapseGuard) and the hierarchy tests run there. The PD bouncing ball (three
# levels and two direct runs of a cube on a sheet, 95 s in release) took 502 s under the
# sanitizers on CI's clean clone, a third of that run; the other PD tests run there. The PD
# continuity test under contact (three predictions of a cloth onto a sphere, per_frame refining
# every frame safely, every frame checked by CGAL; 17-23 s in release) took 240 s there; the
# swinging-cloth continuity test and safe refinement's unit tests run there.
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  LSAN_OPTIONS="suppressions=$PWD/tests/lsan_suppressions.txt" \
  ctest --test-dir build/asan --output-on-failure --no-tests=error -j "$(nproc)" \
  -E '^(ContactScenes[.](ClothDrapes|FastImpact|ClothTwisted|SpinningSphere)|BundledScenes[.]|PsqScenes[.]|RealMeshDrape[.]|Scales/CrossingFreeLevels[.]|ProgressiveDynamics[.](LevelsBounceTheBall|VelocityOnlyPredictionIsTheMostContinuousUnderContact))'

