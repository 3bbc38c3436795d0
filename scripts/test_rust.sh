#!/usr/bin/env bash
# Tests the Rust bindings (bindings/rust: progsim-sys and progsim) against the C library in
# build/release (or PROGSIM_LIB_DIR), then runs the hanging_cloth example into a temporary
# folder. Needs cargo and libclang for bindgen (Debian: libclang-dev).
# Usage: scripts/test_rust.sh [extra cargo test args...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)

lib_dir=${PROGSIM_LIB_DIR:-$root/build/release/core}
if [ ! -e "$lib_dir/libprogsim.so" ]; then
  echo "test_rust: $lib_dir/libprogsim.so not found; build it first (scripts/build.sh release)" >&2
  exit 1
fi

cd "$root/bindings/rust"
export CARGO_TARGET_DIR="$root/bindings/rust/target"
cargo_flags=()
[ -f Cargo.lock ] && cargo_flags+=(--locked)

cargo test "${cargo_flags[@]}" "$@"

out_dir=$(mktemp -d)
trap 'rm -rf "$out_dir"' EXIT
cargo run "${cargo_flags[@]}" --example hanging_cloth -- "$out_dir/out.obj"
vertices=$(grep -c '^v ' "$out_dir/out.obj" || true)
if [ "$vertices" -ne 441 ]; then
  echo "test_rust: the example wrote $vertices vertices to out.obj, expected 441" >&2
  exit 1
fi
echo "test_rust: example wrote $out_dir/out.obj ($vertices vertices)"
