//! progsim from Rust: load the bundled cloth, pin its two top corners, preview under
//! gravity with a progress printout, refine to the finest level, write the final mesh and
//! print the statistics.
//!
//! ```text
//! cargo run --example hanging_cloth -- [OUT.obj] [MESH]
//! ```
//!
//! Defaults: `hanging_cloth_final.obj` in the current folder, and the repository's
//! `scenes/meshes/square_cloth.obj`.

use std::error::Error;
use std::io::Write;
use std::path::PathBuf;

use progsim::{Hierarchy, Simulation, SimulationDef};

/// Index of the vertex nearest to `target`.
fn nearest_vertex(positions: &[[f64; 3]], target: [f64; 3]) -> i32 {
    let distance2 = |p: &[f64; 3]| (0..3).map(|i| (p[i] - target[i]).powi(2)).sum::<f64>();
    let (index, _) = positions
        .iter()
        .enumerate()
        .min_by(|(_, a), (_, b)| distance2(a).total_cmp(&distance2(b)))
        .expect("a mesh has vertices");
    i32::try_from(index).expect("vertex indices fit in i32")
}

/// The repository's `scenes/meshes/square_cloth.obj` (this example lives in
/// `<repo>/bindings/rust/progsim/examples`).
fn bundled_mesh() -> PathBuf {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../scenes/meshes/square_cloth.obj");
    path.canonicalize().unwrap_or(path)
}

/// A one-line progress bar on stderr; never cancels.
fn print_progress(done: u32, total: u32, phase: &str) -> bool {
    eprint!("\r{phase:<8} {done:>3}/{total}");
    if done == total {
        eprintln!();
    }
    let _ = std::io::stderr().flush();
    false
}

fn main() -> Result<(), Box<dyn Error>> {
    let mut args = std::env::args_os().skip(1);
    let out_path =
        args.next().map_or_else(|| PathBuf::from("hanging_cloth_final.obj"), PathBuf::from);
    let mesh_path = args.next().map_or_else(bundled_mesh, PathBuf::from);

    progsim::check_version()?;
    println!(
        "progsim {} (Rust bindings {})",
        progsim::library_version_string(),
        env!("CARGO_PKG_VERSION")
    );

    let hierarchy = Hierarchy::from_file(&mesh_path)?;
    let finest = hierarchy.num_levels() - 1;
    let rest = hierarchy.rest_positions(finest)?;
    let (num_vertices, num_faces) = hierarchy.level_size(finest)?;
    println!(
        "{}: {num_vertices} vertices, {num_faces} faces, {} level(s)",
        mesh_path.display(),
        finest + 1
    );

    let def = SimulationDef {
        // The cloth lies in the x-y plane with its top edge at y = 1; it swings down along −z.
        pinned_vertices: vec![
            nearest_vertex(&rest, [0.0, 1.0, 0.0]),
            nearest_vertex(&rest, [1.0, 1.0, 0.0]),
        ],
        thickness: 5e-4,
        time_step: 0.02,
        gravity: [0.0, 0.0, -9.81],
        ..SimulationDef::default()
    };
    let mut sim = Simulation::new(&hierarchy, &def)?;
    sim.set_param("material.youngs_modulus", 2e5)?;

    sim.step_preview_with_progress(25, print_progress)?;
    while sim.current_level() < finest {
        sim.refine_with_progress(print_progress)?;
    }
    sim.step_preview_with_progress(25, print_progress)?;

    let x = sim.positions(finest)?;
    let lowest = x.iter().map(|p| p[2]).fold(f64::INFINITY, f64::min);
    let stats = sim.level_stats(finest)?;
    println!(
        "level {}: {} steps ({} converged), {} Newton iterations, {:.3} s wall, {:.2} s simulated, \
         energy {:.4e} J, lowest point z = {lowest:.3} m",
        stats.level,
        stats.steps,
        stats.converged_steps,
        stats.newton_iterations,
        stats.seconds,
        stats.simulated_time,
        stats.energy,
    );
    sim.write_mesh(finest, &out_path)?;
    println!("wrote {}", out_path.display());
    Ok(())
}
