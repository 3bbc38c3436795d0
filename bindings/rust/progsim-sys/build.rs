//! Generates the raw bindings from `progsim.h` and links the prebuilt `libprogsim`.
//!
//! Nothing is downloaded or built here: the header comes from the repository (or
//! `PROGSIM_INCLUDE_DIR`) and the library from the CMake build (or `PROGSIM_LIB_DIR`).
//!
//! Environment:
//! - `PROGSIM_INCLUDE_DIR`: folder holding `progsim.h` (default `<repo>/capi/include`).
//! - `PROGSIM_LIB_DIR`: folder holding `libprogsim.so` (default `<repo>/build/release/core`).
//!
//! Dependents see the two folders as `DEP_PROGSIM_INCLUDE` and `DEP_PROGSIM_LIB_DIR` in
//! their own build scripts (the `links = "progsim"` metadata); the safe `progsim` crate uses
//! the latter to give its tests and examples an rpath.

use std::env;
use std::path::{Path, PathBuf};

/// The repository root: this crate lives in `<repo>/bindings/rust/progsim-sys`.
fn repo_root() -> PathBuf {
    let manifest_dir = PathBuf::from(env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    manifest_dir.join("../../..")
}

/// The folder named by environment variable `var`, else `default`; relative values start
/// from this crate's folder. Made absolute so that the rpath works from anywhere.
fn folder(var: &str, default: PathBuf) -> PathBuf {
    println!("cargo::rerun-if-env-changed={var}");
    let dir = env::var_os(var).map(PathBuf::from).unwrap_or(default);
    dir.canonicalize().unwrap_or(dir)
}

/// Where the shared library is, or a panic telling how to get one.
fn check_library(lib_dir: &Path) {
    let names = ["libprogsim.so", "libprogsim.dylib", "progsim.lib"];
    if !names.iter().any(|name| lib_dir.join(name).exists()) {
        panic!(
            "progsim-sys: no libprogsim in {}. Build it first (scripts/build.sh release) or set \
             PROGSIM_LIB_DIR to the folder holding libprogsim.so.",
            lib_dir.display()
        );
    }
}

fn main() {
    let root = repo_root();
    let include_dir = folder("PROGSIM_INCLUDE_DIR", root.join("capi/include"));
    let lib_dir = folder("PROGSIM_LIB_DIR", root.join("build/release/core"));
    let header = include_dir.join("progsim.h");
    if !header.exists() {
        panic!(
            "progsim-sys: {} does not exist; set PROGSIM_INCLUDE_DIR to the folder holding \
             progsim.h",
            header.display()
        );
    }
    check_library(&lib_dir);

    // Regenerate when the header changes. (A rebuilt library needs no rebuild here: it is
    // linked dynamically, and the tests compare its run-time version with the header.)
    println!("cargo::rerun-if-changed={}", header.display());
    println!("cargo::rerun-if-changed=build.rs");

    println!("cargo::rustc-link-search=native={}", lib_dir.display());
    println!("cargo::rustc-link-lib=dylib=progsim");
    // Only this crate's own tests get this rpath; `links` metadata hands the folder on to
    // dependents (DEP_PROGSIM_LIB_DIR) so they can add the same to theirs.
    if env::var("CARGO_CFG_TARGET_FAMILY").as_deref() == Ok("unix") {
        println!("cargo::rustc-link-arg=-Wl,-rpath,{}", lib_dir.display());
    }
    println!("cargo::metadata=lib_dir={}", lib_dir.display());
    println!("cargo::metadata=include={}", include_dir.display());

    let bindings = bindgen::Builder::default()
        .header(header.to_string_lossy())
        .clang_arg(format!("-I{}", include_dir.display()))
        .allowlist_function("ps_.*")
        .allowlist_type("ps_.*")
        .allowlist_var("PS_.*")
        // C-style constants (PS_OK, PS_EFFECT_GRAVITY, ...) rather than Rust enums: the
        // library may return values a Rust enum would not have, which would be UB.
        .default_enum_style(bindgen::EnumVariation::Consts)
        .prepend_enum_name(false)
        // PS_VERSION_HEADER and friends as i32, the type ps_version() returns.
        .default_macro_constant_type(bindgen::MacroTypeVariation::Signed)
        .derive_default(false)
        .derive_debug(true)
        .layout_tests(true)
        .parse_callbacks(Box::new(bindgen::CargoCallbacks::new()))
        .generate()
        .expect("progsim-sys: bindgen could not parse progsim.h (is libclang installed?)");
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets it")).join("bindings.rs");
    bindings.write_to_file(&out).expect("progsim-sys: cannot write bindings.rs");
}
