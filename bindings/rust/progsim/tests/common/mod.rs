//! Paths and small meshes shared by the integration tests.
#![allow(dead_code)]

use std::path::PathBuf;

/// A path inside the repository (this crate is `<repo>/bindings/rust/progsim`).
pub fn repo_path(relative: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../..").join(relative)
}

/// The bundled 1 m square cloth: 441 vertices, 800 faces in the x-y plane.
pub fn square_cloth() -> PathBuf {
    repo_path("scenes/meshes/square_cloth.obj")
}

/// The cloth's top corners (0, 1, 0) and (1, 1, 0).
pub const TOP_CORNERS: [i32; 2] = [420, 440];

/// A fresh, empty folder for one test's output files.
pub fn scratch_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("progsim-rust-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create scratch folder");
    dir
}

/// A 2 × 2 grid of unit squares (9 vertices, 8 faces) in the x-y plane.
pub const GRID_VERTICES: [[f64; 3]; 9] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [2.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [1.0, 1.0, 0.0],
    [2.0, 1.0, 0.0],
    [0.0, 2.0, 0.0],
    [1.0, 2.0, 0.0],
    [2.0, 2.0, 0.0],
];
/// The grid's faces, counter-clockwise seen from +z.
pub const GRID_FACES: [[i32; 3]; 8] =
    [[0, 1, 4], [0, 4, 3], [1, 2, 4], [2, 5, 4], [3, 4, 6], [4, 7, 6], [4, 5, 8], [4, 8, 7]];
