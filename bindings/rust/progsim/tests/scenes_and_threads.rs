//! Scene simulations (which own their hierarchy) and moving simulations between threads.

mod common;

use std::thread;

use common::{repo_path, square_cloth, TOP_CORNERS};
use progsim::{Hierarchy, HierarchyDef, LevelStats, Simulation, SimulationDef};

/// On a two-level scene: preview steps, equilibrium on the coarse level, refinement,
/// equilibrium on the finest; the two levels' statistics.
fn preview_then_refine_once(sim: &mut Simulation<'_>, steps: u32) -> (LevelStats, LevelStats) {
    sim.step_preview(steps).unwrap();
    assert!(sim.settle(300).unwrap());
    sim.refine().unwrap();
    assert!(sim.settle(300).unwrap());
    (sim.level_stats(0).unwrap(), sim.level_stats(1).unwrap())
}

#[test]
fn progressive_obstacle_is_decimated_then_refined_with_the_cloth() {
    // PSQ §4.6: the coarse level meets a decimated copy of the sphere, the finest the sphere.
    let mut sim =
        Simulation::from_scene_file(repo_path("tests/data/progressive_obstacle.json")).unwrap();
    let (coarse, fine) = preview_then_refine_once(&mut sim, 1);
    assert_eq!(fine.obstacle_vertices, 162); // the sphere's own vertices
    assert!(coarse.obstacle_vertices > 0 && coarse.obstacle_vertices < fine.obstacle_vertices);
    assert_eq!(coarse.obstacle_refinement.splits, 0);
    assert_eq!(fine.obstacle_refinement.splits, fine.obstacle_vertices - coarse.obstacle_vertices);
    assert!(fine.obstacle_refinement.reached > 0.0 && fine.obstacle_refinement.reached <= 1.0);
}

#[test]
fn refined_start_is_brought_under_its_strain_limit() {
    // The bundled drape at 21 × 21 vertices: refinement stretches faces far beyond the cloth's
    // strain limit of 1.06; the strain correction (PSQ §4.4.5) brings every one back under it.
    let scenes = repo_path("scenes");
    let json = std::fs::read_to_string(scenes.join("psq_cloth_on_sphere.json")).unwrap();
    assert!(json.contains(r#""nx": 40, "ny": 40"#));
    let json = json.replace(r#""nx": 40, "ny": 40"#, r#""nx": 20, "ny": 20"#);
    let mut sim = Simulation::from_scene(&json, Some(&scenes)).unwrap();
    sim.step_preview(4).unwrap();
    assert!(sim.settle(300).unwrap());
    sim.refine().unwrap();
    let coarse = sim.level_stats(0).unwrap().strain_correction;
    let fine = sim.level_stats(1).unwrap().strain_correction;
    assert_eq!(coarse.strained_faces, 0);
    assert_eq!(coarse.stretch_before, 0.0);
    assert!(fine.strained_faces > 0 && fine.over_limit_faces == 0);
    assert!(fine.stretch_before > 1.06 && fine.stretch_after < 1.06);
    assert!(fine.newton_iterations > 0);
}

#[test]
fn cg_refinement_counts_only_on_the_finest_level() {
    // solver.max_cg_iterations from the scene: the coarse proxy never refines, the wrung
    // finest level does.
    let mut sim =
        Simulation::from_scene_file(repo_path("tests/data/twist_cg_refined.json")).unwrap();
    assert_eq!(sim.param("solver.max_cg_iterations").unwrap(), 50.0);
    let (coarse, fine) = preview_then_refine_once(&mut sim, 6);
    assert!(coarse.newton_iterations > 0 && coarse.cg_iterations == 0);
    assert!(fine.newton_iterations > 0 && fine.cg_iterations > 0);
}

/// Newton steps the line search lengthened on the twist's coarse level over 6 preview steps,
/// with `solver.line_search_extrapolation` set to `on`.
fn extrapolated_preview_steps(on: f64) -> usize {
    let mut sim =
        Simulation::from_scene_file(repo_path("tests/data/twist_cg_refined.json")).unwrap();
    assert_eq!(sim.param("solver.line_search_extrapolation").unwrap(), 1.0); // on by default
    sim.set_param("solver.line_search_extrapolation", on).unwrap();
    sim.step_preview(6).unwrap();
    sim.level_stats(0).unwrap().extrapolated_steps
}

#[test]
fn line_search_extrapolation_can_be_switched_off() {
    assert!(extrapolated_preview_steps(1.0) > 0);
    assert_eq!(extrapolated_preview_steps(0.0), 0);
    let hierarchy = Hierarchy::from_file(square_cloth()).unwrap();
    let def = SimulationDef { line_search_extrapolation: false, ..SimulationDef::default() };
    let sim = Simulation::new(&hierarchy, &def).unwrap();
    assert_eq!(sim.param("solver.line_search_extrapolation"), Ok(0.0));
}

#[test]
fn scene_file_simulation_owns_its_hierarchy() {
    let mut sim = Simulation::from_scene_file(repo_path("scenes/hanging_cloth.json")).unwrap();
    let hierarchy = sim.hierarchy().expect("a scene simulation owns its hierarchy");
    assert_eq!(hierarchy.num_levels(), 1);
    let (vertices, faces) = hierarchy.level_size(0).unwrap();
    assert_eq!((vertices, faces), (41 * 41, 2 * 40 * 40));
    assert_eq!(sim.num_handles(), 2);
    assert_eq!(sim.param("simulation.time_step"), Ok(0.02));
    assert_eq!(sim.param("material.density"), Ok(400.0));
    sim.step_preview(2).unwrap();
    assert_eq!(sim.positions(0).unwrap().len(), vertices);
    assert_eq!(sim.level_stats(0).unwrap().steps, 2);
}

#[test]
fn scene_text_resolves_mesh_paths_from_base_dir() {
    let json = r#"
        // the bundled cloth file, pinned at its top corners
        {
          "effects": ["membrane", "gravity"],
          "gravity": [0, 0, -9.81],
          "bodies": [{ "name": "cloth", "mesh": { "file": "meshes/square_cloth.obj" } }],
          "handles": [{ "body": "cloth", "vertices": [420, 440] }]
        }"#;
    let base = repo_path("scenes");
    let mut sim = Simulation::from_scene(json, Some(&base)).unwrap();
    assert_eq!(sim.hierarchy().unwrap().level_size(0), Ok((441, 800)));
    sim.step_preview(3).unwrap();
    let x = sim.positions(0).unwrap();
    assert!(x.iter().any(|p| p[2] < 0.0));
    assert_eq!(x[420][2], 0.0);
    // Without the base folder the relative path does not resolve from here.
    let error =
        Simulation::from_scene(json, Some(std::path::Path::new("/nonexistent"))).unwrap_err();
    assert_eq!(error.code, progsim::Status::Io, "{error}");
}

/// The z of the lowest vertex after `steps` steps of the hanging cloth on this thread.
fn lowest_after(sim: &mut Simulation<'_>, steps: u32) -> f64 {
    sim.step_preview(steps).unwrap();
    sim.positions(0).unwrap().iter().map(|p| p[2]).fold(f64::INFINITY, f64::min)
}

#[test]
fn scene_simulation_moves_to_another_thread() {
    let mut sim = Simulation::from_scene_file(repo_path("scenes/hanging_cloth.json")).unwrap();
    sim.set_param("gravity.y", 0.0).unwrap();
    sim.set_param("gravity.z", -9.81).unwrap();
    let creator = thread::current().id();
    let worker = thread::spawn(move || {
        assert_ne!(thread::current().id(), creator);
        let lowest = lowest_after(&mut sim, 5);
        let calls = {
            let mut calls = 0;
            sim.step_preview_with_progress(2, |_, _, _| {
                calls += 1;
                false
            })
            .unwrap();
            calls
        };
        (sim, lowest, calls)
    });
    let (sim, lowest, calls) = worker.join().expect("stepping on the worker thread");
    assert!(lowest < -0.01, "lowest z = {lowest}");
    assert_eq!(calls, 2);
    // And back: the simulation is usable on this thread again.
    assert_eq!(sim.level_stats(0).unwrap().steps, 7);
}

#[test]
fn borrowing_simulations_step_on_several_threads() {
    let hierarchy = Hierarchy::from_file(square_cloth()).unwrap();
    let def = SimulationDef {
        gravity: [0.0, 0.0, -9.81],
        pinned_vertices: TOP_CORNERS.to_vec(),
        ..SimulationDef::default()
    };
    let mut sims: Vec<Simulation<'_>> =
        (0..2).map(|_| Simulation::new(&hierarchy, &def).unwrap()).collect();
    let lowest: Vec<f64> = thread::scope(|scope| {
        let workers: Vec<_> =
            sims.iter_mut().map(|sim| scope.spawn(move || lowest_after(sim, 10))).collect();
        // The hierarchy stays usable on this thread while the simulations read it.
        assert_eq!(hierarchy.level_size(0), Ok((441, 800)));
        workers.into_iter().map(|w| w.join().unwrap()).collect()
    });
    assert!(lowest[0] < -0.03, "{lowest:?}");
    assert_eq!(lowest[0], lowest[1], "same inputs, same result on any thread");
    drop(sims);
    drop(hierarchy);
}

#[test]
fn hierarchy_moves_to_another_thread() {
    let hierarchy = Hierarchy::from_file(square_cloth()).unwrap();
    let levels = thread::spawn(move || {
        let def =
            SimulationDef { pinned_vertices: TOP_CORNERS.to_vec(), ..SimulationDef::default() };
        let mut sim = Simulation::new(&hierarchy, &def).unwrap();
        sim.step_preview(1).unwrap();
        hierarchy.num_levels()
    })
    .join()
    .unwrap();
    assert_eq!(levels, 1);
}

#[test]
fn a_crossing_input_is_refused_unless_the_scene_opts_in() {
    // Issue 28's one rule: a finest mesh that crosses itself, with contact on, is refused naming
    // a crossing pair of the input, from a scene file and from code; crossing_start lets it run.
    let err = Simulation::from_scene_file(repo_path("tests/data/crossing_flap.json")).unwrap_err();
    assert_eq!(err.code, progsim::Status::Intersecting);
    assert!(err.message.contains("the input mesh: shell face"), "{}", err.message);
    let def = HierarchyDef { coarse_vertex_counts: vec![40, 100], ..Default::default() };
    let hierarchy =
        Hierarchy::from_file_with(&def, repo_path("tests/data/crossing_flap.obj")).unwrap();
    let mut sim_def = SimulationDef {
        mode: progsim::Mode::Quasistatic,
        time_step: 1.0,
        effects: progsim::Effect::Membrane | progsim::Effect::Contact,
        ..SimulationDef::default()
    };
    let err = Simulation::new(&hierarchy, &sim_def).unwrap_err();
    assert_eq!(err.code, progsim::Status::Intersecting);
    sim_def.contact_crossing_start = true;
    let sim = Simulation::new(&hierarchy, &sim_def).unwrap();
    assert_eq!(sim.param("contact.crossing_start"), Ok(1.0));
}

#[test]
fn hierarchy_contact_offset_is_checked() {
    // ps_hierarchy_def.contact_offset: a length >= 0 (the levels keep it; C++ tests measure).
    let mesh = repo_path("tests/data/crossing_flap.obj");
    let bad = HierarchyDef {
        coarse_vertex_counts: vec![40],
        contact_offset: -1e-3,
        ..Default::default()
    };
    let err = Hierarchy::from_file_with(&bad, &mesh).unwrap_err();
    assert_eq!(err.code, progsim::Status::InvalidArgument);
    assert!(err.message.contains("contact_offset"), "{}", err.message);
    let good = HierarchyDef { contact_offset: 2.5e-4, ..bad };
    assert_eq!(Hierarchy::from_file_with(&good, &mesh).unwrap().num_levels(), 2);
}
