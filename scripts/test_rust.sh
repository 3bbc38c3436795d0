#!/usr/bin/env bash
# Tests the Rust bindings (bindings/rust: progsim-sys and progsim) against the C library in
# build/release (or PROGSIM_LIB_DIR), runs the hanging_cloth example into a temporary folder,
# then builds and runs it again against an installed copy found by pkg-config (progsim.pc),
# as a user without this build tree would. Needs cargo and libclang for bindgen (Debian:
# libclang-dev).
# Usage: scripts/test_rust.sh [extra cargo test args...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)

lib_dir=${PROGSIM_LIB_DIR:-$root/build/release/core}
if [ ! -e "$lib_dir/libprogsim.so" ]; then
  echo "test_rust: $lib_dir/libprogsim.so not found; build it first (scripts/build.sh release)" >&2
  exit 1
fi

export PROGSIM_LIB_DIR=$lib_dir
cd "$root/bindings/rust"
export CARGO_TARGET_DIR="$root/bindings/rust/target"
cargo_flags=()
[ -f Cargo.lock ] && cargo_flags+=(--locked)

cargo test "${cargo_flags[@]}" "$@"

out_dir=$(mktemp -d)
trap 'rm -rf "$out_dir"' EXIT

# Runs the hanging_cloth example and checks the mesh it writes.
run_example() {
  rm -f "$out_dir/out.obj"
  cargo run "${cargo_flags[@]}" --example hanging_cloth -- "$out_dir/out.obj"
  vertices=$(grep -c '^v ' "$out_dir/out.obj" || true)
  if [ "$vertices" -ne 441 ]; then
    echo "test_rust: the example wrote $vertices vertices to out.obj, expected 441" >&2
    exit 1
  fi
  echo "test_rust: example wrote $out_dir/out.obj ($vertices vertices)"
}
run_example

echo "== Rust bindings against an installed copy (pkg-config) =="
prefix="$out_dir/prefix"
cmake --install "$root/build/release" --prefix "$prefix" >/dev/null
pc_dir=$(dirname "$(find "$prefix" -name progsim.pc | head -n 1)")
(
  unset PROGSIM_LIB_DIR PROGSIM_INCLUDE_DIR
  export PKG_CONFIG_PATH=$pc_dir PROGSIM_NO_SOURCE_BUILD=1
  run_example
)
linked=$(ldd "$CARGO_TARGET_DIR/debug/examples/hanging_cloth" | sed -n 's/.*libprogsim.so => \([^ ]*\).*/\1/p')
case "$linked" in
  "$prefix"/*) echo "test_rust: the example linked the installed $linked" ;;
  *)
    echo "test_rust: the example linked '$linked', not the copy installed in $prefix" >&2
    exit 1
    ;;
esac
