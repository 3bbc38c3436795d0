//! Gives this crate's tests and examples an rpath to the `libprogsim` that `progsim-sys`
//! linked, so they run without `LD_LIBRARY_PATH`. (A `rustc-link-arg` of `progsim-sys` only
//! reaches that crate's own targets; the folder arrives here as `links` metadata.)
//! Crates depending on `progsim` need the same line in their build script, or the library
//! installed where the dynamic loader looks.

fn main() {
    println!("cargo::rerun-if-env-changed=DEP_PROGSIM_LIB_DIR");
    let lib_dir = std::env::var("DEP_PROGSIM_LIB_DIR")
        .expect("progsim-sys (links = \"progsim\") hands over DEP_PROGSIM_LIB_DIR");
    if std::env::var("CARGO_CFG_TARGET_FAMILY").as_deref() == Ok("unix") {
        println!("cargo::rustc-link-arg=-Wl,-rpath,{lib_dir}");
    }
}
