//! The full cycle on the bundled cloth: hierarchy, simulation, parameters, preview steps,
//! results, refinement at the finest level, statistics, output file.

mod common;

use common::{square_cloth, TOP_CORNERS};
use progsim::{Effect, HandleMotion, Hierarchy, Simulation, SimulationDef, Status};

fn lowest_z(positions: &[[f64; 3]]) -> f64 {
    positions.iter().map(|p| p[2]).fold(f64::INFINITY, f64::min)
}

#[test]
fn hanging_cloth_full_cycle() {
    let hierarchy = Hierarchy::from_file(square_cloth()).expect("load the bundled mesh");
    assert_eq!(hierarchy.num_levels(), 1);
    assert_eq!(hierarchy.level_size(0), Ok((441, 800)));
    let rest = hierarchy.rest_positions(0).unwrap();
    assert_eq!(rest.len(), 441);
    assert_eq!(rest[420], [0.0, 1.0, 0.0]);
    assert_eq!(rest[440], [1.0, 1.0, 0.0]);
    assert!(rest.iter().all(|p| p[2] == 0.0), "the cloth starts flat");
    let faces = hierarchy.faces(0).unwrap();
    assert_eq!(faces.len(), 800);
    assert!(faces.iter().flatten().all(|&i| (0..441).contains(&i)));

    let def = SimulationDef {
        time_step: 0.01,
        gravity: [0.0, 0.0, -9.81],
        pinned_vertices: TOP_CORNERS.to_vec(),
        ..SimulationDef::default()
    };
    let mut sim = Simulation::new(&hierarchy, &def).expect("create the simulation");
    assert!(sim.hierarchy().is_none(), "a borrowed hierarchy is not handed out again");
    assert_eq!(sim.current_level(), 0);
    assert_eq!(sim.num_handles(), 1);
    assert_eq!(sim.param("simulation.time_step"), Ok(0.01));
    assert_eq!(sim.param("gravity.z"), Ok(-9.81));

    sim.set_param("material.thickness", 5e-4).unwrap();
    assert_eq!(sim.param("material.thickness"), Ok(5e-4));
    sim.set_param("material.youngs_modulus", 2e5).unwrap();
    assert_eq!(sim.param("material.youngs_modulus"), Ok(2e5));
    sim.set_param("material.bending_youngs_modulus", 3e6).unwrap();
    assert_eq!(sim.param("material.bending_youngs_modulus"), Ok(3e6));
    sim.set_effect(Effect::Bending, false).unwrap();
    assert_eq!(sim.effects(), Effect::Membrane | Effect::Gravity);
    sim.set_effect(Effect::Bending, true).unwrap();
    assert!(sim.effects().contains(Effect::Bending));

    sim.step_preview(10).expect("10 preview steps");
    let x = sim.positions(0).unwrap();
    assert_eq!(x.len(), 441);
    // Free fall gives 0.049 m in 0.1 s; the cloth started flat at z = 0.
    let lowest = lowest_z(&x);
    assert!(lowest < -0.03, "lowest z = {lowest}");
    for corner in TOP_CORNERS {
        assert_eq!(
            x[corner as usize][2], 0.0,
            "pinned vertex {corner} moved: {:?}",
            x[corner as usize]
        );
    }

    let refine = sim.refine().expect_err("a single-level hierarchy cannot be refined");
    assert_eq!(refine.code, Status::OutOfRange);
    assert!(refine.message.contains("finest level 0"), "{refine}");
    assert_eq!(sim.current_level(), 0);

    let stats = sim.level_stats(0).unwrap();
    assert_eq!(stats.level, 0);
    assert_eq!(stats.steps, 10);
    assert!(stats.newton_iterations >= 10, "{stats:?}");
    assert!(stats.converged_steps <= 10);
    assert!(stats.seconds > 0.0 && stats.energy.is_finite() && stats.gradient_norm.is_finite());
    assert!((stats.simulated_time - 0.1).abs() < 1e-9, "{stats:?}");
    assert_eq!(stats.error_rms, None);
    assert_eq!(stats.error_max, None);

    // Dragging handle 0 moves the pinned corners with it.
    let drag = HandleMotion { offset: [0.1, 0.0, 0.0], ..HandleMotion::default() };
    sim.set_handle_motion(0, &drag).unwrap();
    sim.step_preview(1).unwrap();
    let dragged = sim.positions(0).unwrap();
    assert!((dragged[420][0] - 0.1).abs() < 1e-12, "{:?}", dragged[420]);
    assert_eq!(sim.level_stats(0).unwrap().steps, 11);

    let out_dir = common::scratch_dir("full_cycle");
    let out = out_dir.join("final.obj");
    sim.write_mesh(0, &out).unwrap();
    let text = std::fs::read_to_string(&out).unwrap();
    assert_eq!(text.lines().filter(|l| l.starts_with("v ")).count(), 441);
    assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 800);
    // The written mesh loads again, with the simulated shape.
    let reloaded = Hierarchy::from_file(&out).unwrap();
    assert!((lowest_z(&reloaded.rest_positions(0).unwrap()) - lowest_z(&dragged)).abs() < 1e-6);

    drop(sim);
    drop(hierarchy);
    std::fs::remove_dir_all(out_dir).unwrap();
}

#[test]
fn mesh_from_slices_matches_the_file() {
    let from_file = Hierarchy::from_file(square_cloth()).unwrap();
    let vertices = from_file.rest_positions(0).unwrap();
    let faces = from_file.faces(0).unwrap();
    let from_arrays = Hierarchy::from_mesh(&vertices, &faces).unwrap();
    assert_eq!(from_arrays.rest_positions(0).unwrap(), vertices);
    assert_eq!(from_arrays.faces(0).unwrap(), faces);

    let flat_vertices: Vec<f64> = vertices.iter().flatten().copied().collect();
    let flat_faces: Vec<i32> = faces.iter().flatten().copied().collect();
    let from_flat = Hierarchy::from_flat(&flat_vertices, &flat_faces).unwrap();
    assert_eq!(from_flat.level_size(0), Ok((441, 800)));
}

#[test]
fn quasistatic_default_gravity_sags_in_y() {
    // Defaults: gravity (0, −9.81, 0) pulls the cloth within its own plane.
    let hierarchy = Hierarchy::from_file(square_cloth()).unwrap();
    let def = SimulationDef {
        mode: progsim::Mode::Quasistatic,
        pinned_vertices: TOP_CORNERS.to_vec(),
        ..SimulationDef::default()
    };
    let mut sim = Simulation::new(&hierarchy, &def).unwrap();
    assert_eq!(sim.mode(), progsim::Mode::Quasistatic);
    sim.step_preview(1).unwrap();
    let x = sim.positions(0).unwrap();
    let rest = hierarchy.rest_positions(0).unwrap();
    assert!(x[0][1] < rest[0][1], "the bottom corner hangs lower: {:?}", x[0]);
    assert_eq!(x[420], rest[420]);
    sim.set_mode(progsim::Mode::Dynamic).unwrap();
    assert_eq!(sim.mode(), progsim::Mode::Dynamic);
    sim.step_preview(1).unwrap();
}
