//! Every documented misuse gives the right `Status` and a message naming the problem; a
//! cancelling or panicking progress closure leaves a usable simulation.

mod common;

use std::panic::{self, AssertUnwindSafe};
use std::path::Path;

use common::{square_cloth, GRID_FACES, GRID_VERTICES, TOP_CORNERS};
use progsim::{Error, HandleMotion, Hierarchy, HierarchyDef, Simulation, SimulationDef, Status};

/// Asserts `result` failed with `code` and a message containing `needle`.
#[track_caller]
fn assert_error<T: std::fmt::Debug>(
    result: progsim::Result<T>,
    code: Status,
    needle: &str,
) -> Error {
    let error = result.expect_err("the call should have failed");
    assert_eq!(error.code, code, "{error}");
    assert!(error.message.contains(needle), "{error:?} does not mention {needle:?}");
    error
}

fn grid() -> Hierarchy {
    Hierarchy::from_mesh(&GRID_VERTICES, &GRID_FACES).expect("the grid is valid")
}

#[test]
fn nan_vertex_is_an_invalid_mesh_naming_the_vertex() {
    let mut vertices = GRID_VERTICES;
    vertices[4][1] = f64::NAN;
    let error =
        assert_error(Hierarchy::from_mesh(&vertices, &GRID_FACES), Status::InvalidMesh, "vertex 4");
    assert!(error.to_string().starts_with("PS_ERROR_INVALID_MESH: "), "{error}");
}

#[test]
fn bad_meshes_and_files_are_rejected() {
    let mut faces = GRID_FACES;
    faces[1][2] = 9;
    assert_error(Hierarchy::from_mesh(&GRID_VERTICES, &faces), Status::InvalidMesh, "9");
    assert_error(Hierarchy::from_mesh(&[], &[]), Status::InvalidMesh, "0 vertices");
    assert_error(
        Hierarchy::from_flat(&[0.0; 4], &[0, 1, 2]),
        Status::InvalidArgument,
        "multiple of 3",
    );
    assert_error(
        Hierarchy::from_file("/nonexistent/mesh.obj"),
        Status::Io,
        "/nonexistent/mesh.obj",
    );
    let def = HierarchyDef { coarse_vertex_counts: vec![9], ..Default::default() };
    assert_error(
        Hierarchy::from_mesh_with(&def, &GRID_VERTICES, &GRID_FACES),
        Status::InvalidArgument,
        "below the mesh's 9 vertices",
    );
    assert_error(Hierarchy::load("/nonexistent/h.bin"), Status::Io, "/nonexistent/h.bin");
}

#[test]
fn scene_with_a_typo_key_is_an_invalid_scene_naming_it() {
    let json = r#"{"bodies": [], "efects": ["gravity"]}"#;
    assert_error(Simulation::from_scene(json, None), Status::InvalidScene, "efects");
    assert_error(Simulation::from_scene("{ not json", None), Status::InvalidScene, "");
    assert_error(Simulation::from_scene("{}\0", None), Status::InvalidArgument, "NUL");
    assert_error(
        Simulation::from_scene_file("/nonexistent/scene.json"),
        Status::Io,
        "/nonexistent/scene.json",
    );
}

#[test]
fn unknown_or_out_of_range_parameters_are_invalid_arguments() {
    let hierarchy = grid();
    let mut sim = Simulation::new(&hierarchy, &SimulationDef::default()).unwrap();
    assert_error(
        sim.set_param("material.thicknes", 1e-3),
        Status::InvalidArgument,
        "unknown parameter 'material.thicknes'",
    );
    assert_error(sim.param("no.such.parameter"), Status::InvalidArgument, "no.such.parameter");
    assert_error(
        sim.set_param("material.thickness", f64::NAN),
        Status::InvalidArgument,
        "material.thickness",
    );
    assert_error(
        sim.set_param("simulation.time_step", -1.0),
        Status::InvalidArgument,
        "simulation.time_step",
    );
    assert_error(sim.set_param("bad\0name", 1.0), Status::InvalidArgument, "NUL");
    // Failed calls left the simulation unchanged.
    assert_eq!(sim.param("simulation.time_step"), Ok(0.01));
    assert_eq!(sim.param("material.thickness"), Ok(1e-3));
    assert_error(sim.step_preview(0), Status::InvalidArgument, "steps = 0");
    assert_error(
        sim.set_handle_motion(0, &HandleMotion::default()),
        Status::OutOfRange,
        "handle 0 does not exist",
    );
    assert_error(
        sim.write_mesh(0, "/nonexistent/dir/out.obj"),
        Status::Io,
        "/nonexistent/dir/out.obj",
    );
    // Success after failures works and clears nothing it should not.
    sim.step_preview(1).unwrap();
    assert_eq!(sim.level_stats(0).unwrap().steps, 1);
}

#[test]
fn bad_defs_are_rejected_at_creation() {
    let hierarchy = grid();
    let def = SimulationDef { poisson_ratio: 0.5, ..SimulationDef::default() };
    assert_error(
        Simulation::new(&hierarchy, &def),
        Status::InvalidArgument,
        "material.poisson_ratio",
    );
    let def = SimulationDef { pinned_vertices: vec![99], ..SimulationDef::default() };
    assert_error(Simulation::new(&hierarchy, &def), Status::InvalidScene, "vertex 99");
    let def = SimulationDef {
        effects: progsim::Effects::from_bits_retain(1 << 9),
        ..SimulationDef::default()
    };
    assert_error(Simulation::new(&hierarchy, &def), Status::InvalidArgument, "unknown bits");
}

#[test]
fn level_one_is_out_of_range() {
    let hierarchy = grid();
    assert_error(hierarchy.level_size(1), Status::OutOfRange, "level 1 does not exist");
    assert_error(hierarchy.rest_positions(1), Status::OutOfRange, "level 1 does not exist");
    assert_error(hierarchy.faces(1), Status::OutOfRange, "level 1 does not exist");
    let sim = Simulation::new(&hierarchy, &SimulationDef::default()).unwrap();
    assert_error(sim.positions(1), Status::OutOfRange, "level 1 does not exist");
    assert_error(sim.level_stats(1), Status::OutOfRange, "level 1 does not exist");
    assert_error(
        sim.write_mesh(1, Path::new("unused.obj")),
        Status::OutOfRange,
        "level 1 does not exist",
    );
    assert_error(sim.positions(usize::MAX), Status::OutOfRange, "does not exist");
}

fn hanging_cloth(hierarchy: &Hierarchy) -> Simulation<'_> {
    let def = SimulationDef {
        gravity: [0.0, 0.0, -9.81],
        pinned_vertices: TOP_CORNERS.to_vec(),
        ..SimulationDef::default()
    };
    Simulation::new(hierarchy, &def).unwrap()
}

#[test]
fn progress_closure_can_cancel() {
    let hierarchy = Hierarchy::from_file(square_cloth()).unwrap();
    let mut sim = hanging_cloth(&hierarchy);
    let mut calls = Vec::new();
    let result = sim.step_preview_with_progress(10, |done, total, phase| {
        calls.push((done, total, phase.to_owned()));
        done >= 2
    });
    assert_error(result, Status::Cancelled, "after 2 of 10");
    assert_eq!(calls, [(1, 10, "preview".to_owned()), (2, 10, "preview".to_owned())]);
    assert_eq!(sim.level_stats(0).unwrap().steps, 2, "the state of the last completed step");

    // The closure is gone after the call: plain steps run without it.
    sim.step_preview(1).unwrap();
    let mut seen = 0;
    sim.step_preview_with_progress(3, |_, _, _| {
        seen += 1;
        false
    })
    .unwrap();
    assert_eq!(seen, 3);
    assert_eq!(sim.level_stats(0).unwrap().steps, 6);
}

#[test]
fn panicking_progress_closure_does_not_unwind_into_c() {
    let hierarchy = Hierarchy::from_file(square_cloth()).unwrap();
    let mut sim = hanging_cloth(&hierarchy);
    let mut calls = 0;
    let outcome = panic::catch_unwind(AssertUnwindSafe(|| {
        sim.step_preview_with_progress(5, |_, _, _| {
            calls += 1;
            panic!("progress closure exploded");
        })
    }));
    // Reaching this line at all means the panic did not cross the C frames (which would
    // abort the process); it resumed in Rust once the C call had returned.
    let payload = outcome.expect_err("the closure's panic resumes after the C call");
    assert_eq!(payload.downcast_ref::<&str>(), Some(&"progress closure exploded"));
    assert_eq!(calls, 1, "the C call was cancelled at the first callback");
    assert_eq!(sim.level_stats(0).unwrap().steps, 1);
    // The simulation stays usable, and the panicking closure is no longer installed.
    sim.step_preview(2).unwrap();
    assert_eq!(sim.level_stats(0).unwrap().steps, 3);
    assert!(sim.positions(0).unwrap().iter().flatten().all(|v| v.is_finite()));
}

#[test]
fn refine_with_progress_reports_out_of_range() {
    let hierarchy = grid();
    let mut sim = Simulation::new(&hierarchy, &SimulationDef::default()).unwrap();
    assert_error(sim.refine_with_progress(|_, _, _| false), Status::OutOfRange, "finest level 0");
}

#[test]
fn progress_closure_cannot_call_progsim() {
    let hierarchy = Hierarchy::from_file(square_cloth()).unwrap();
    let mut sim = hanging_cloth(&hierarchy);
    let other = grid();
    let mut inside = Vec::new();
    sim.step_preview_with_progress(2, |_, _, _| {
        inside.push(hierarchy.level_size(0).map(|_| ()));
        inside.push(other.faces(0).map(|_| ()));
        inside.push(Hierarchy::from_mesh(&GRID_VERTICES, &GRID_FACES).map(|_| ()));
        false
    })
    .unwrap();
    assert_eq!(inside.len(), 6);
    for result in inside {
        assert_error(result, Status::WrongCallOrder, "inside a progress callback");
    }
    // A plain-value getter panics instead; the panic cancels and resumes as usual.
    let outcome = panic::catch_unwind(AssertUnwindSafe(|| {
        sim.step_preview_with_progress(3, |_, _, _| hierarchy.num_levels() > 1)
    }));
    let payload = outcome.expect_err("num_levels() inside the closure panics");
    let message = payload.downcast_ref::<String>().expect("a formatted panic message");
    assert!(message.contains("PS_ERROR_WRONG_CALL_ORDER"), "{message}");
    // Outside the closure everything works again.
    assert_eq!(hierarchy.num_levels(), 1);
    assert_eq!(sim.level_stats(0).unwrap().steps, 3);
}
