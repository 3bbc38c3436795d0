//! Generates the raw bindings from `progsim.h` and links `libprogsim`, found in this order
//! (as zstd-sys and libgit2-sys find theirs):
//!
//! 1. `PROGSIM_LIB_DIR`: a folder holding a built `libprogsim.so` (e.g. `<repo>/build/release/core`
//!    from `scripts/build.sh release`); the header from `PROGSIM_INCLUDE_DIR` (default
//!    `<repo>/capi/include`).
//! 2. An installed copy that pkg-config knows (`progsim.pc`, installed by `cmake --install`;
//!    `PKG_CONFIG_PATH` for a non-standard prefix), header included.
//! 3. Otherwise the library is built from this repository's sources with CMake (the `cmake`
//!    crate; the Debian packages of `scripts/install_deps.sh` must be present), into `OUT_DIR`.
//!    `PROGSIM_NO_SOURCE_BUILD=1` turns this off, so a missing library fails at once.
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

/// Where the header and the library come from.
struct Library {
    include_dir: PathBuf,
    lib_dir: PathBuf,
}

/// Whether `lib_dir` holds a shared libprogsim.
fn has_library(lib_dir: &Path) -> bool {
    ["libprogsim.so", "libprogsim.dylib", "progsim.lib"]
        .iter()
        .any(|name| lib_dir.join(name).exists())
}

/// Source 1: `PROGSIM_LIB_DIR`, if set (it must then hold the library).
fn prebuilt(root: &Path) -> Option<Library> {
    println!("cargo::rerun-if-env-changed=PROGSIM_LIB_DIR");
    env::var_os("PROGSIM_LIB_DIR")?;
    let lib_dir = folder("PROGSIM_LIB_DIR", PathBuf::new());
    if !has_library(&lib_dir) {
        panic!("progsim-sys: PROGSIM_LIB_DIR={} holds no libprogsim", lib_dir.display());
    }
    Some(Library { include_dir: folder("PROGSIM_INCLUDE_DIR", root.join("capi/include")), lib_dir })
}

/// Source 2: an installed copy described by `progsim.pc`.
fn installed() -> Option<Library> {
    println!("cargo::rerun-if-env-changed=PKG_CONFIG_PATH");
    let found = pkg_config::Config::new().cargo_metadata(false).probe("progsim").ok()?;
    // Canonical: progsim.pc names its prefix relative to its own folder.
    let lib_dir = found.link_paths.first()?.canonicalize().ok()?;
    let include_dir = found.include_paths.first()?.canonicalize().ok()?;
    has_library(&lib_dir).then_some(Library { include_dir, lib_dir })
}

/// Source 3: the repository's CMake build of the library alone (no CLI, tests or benchmarks).
fn built_from_source(root: &Path) -> Library {
    println!("cargo::rerun-if-env-changed=PROGSIM_NO_SOURCE_BUILD");
    if env::var_os("PROGSIM_NO_SOURCE_BUILD").is_some_and(|v| v != "0") {
        panic!(
            "progsim-sys: no libprogsim: set PROGSIM_LIB_DIR to the folder holding libprogsim.so, \
             install progsim where pkg-config finds it, or unset PROGSIM_NO_SOURCE_BUILD to \
             build it from source"
        );
    }
    let out = cmake::Config::new(root)
        .define("PROGSIM_BUILD_TESTS", "OFF")
        .define("PROGSIM_BUILD_BENCH", "OFF")
        .profile("Release")
        .build_target("progsim")
        .build();
    for area in ["core", "capi"] {
        println!("cargo::rerun-if-changed={}", root.join(area).display());
    }
    Library { include_dir: root.join("capi/include"), lib_dir: out.join("build/core") }
}

fn main() {
    let root = repo_root();
    let Library { include_dir, lib_dir } =
        prebuilt(&root).or_else(installed).unwrap_or_else(|| built_from_source(&root));
    let header = include_dir.join("progsim.h");
    if !header.exists() {
        panic!(
            "progsim-sys: {} does not exist; set PROGSIM_INCLUDE_DIR to the folder holding \
             progsim.h",
            header.display()
        );
    }

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
