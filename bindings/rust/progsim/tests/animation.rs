//! A progressive animation (Progressive Dynamics): a cloth falling freely on three levels
//! against the closed form of implicit Euler, frames and velocities, initial velocities,
//! restart, per-step statistics, progress and cancellation, and misuse.

use progsim::{
    Hierarchy, HierarchyDef, Mode, Prediction, Simulation, SimulationDef, SimulationKind, Status,
};

const H: f64 = 0.01;
const G: f64 = 9.81;
const STEPS: usize = 5;

/// Implicit Euler from rest under gravity: z_n − z_0 = −g h² n(n+1)/2.
fn fallen(n: usize) -> f64 {
    -G * H * H * (n * (n + 1)) as f64 / 2.0
}

/// An 8 × 8 grid of 0.1 m squares (81 vertices) with 16- and 36-vertex coarse levels.
fn grid_levels() -> Hierarchy {
    let side = 9;
    let vertices: Vec<[f64; 3]> =
        (0..side * side).map(|k| [0.1 * (k % side) as f64, 0.1 * (k / side) as f64, 0.0]).collect();
    let mut faces = Vec::new();
    for j in 0..side - 1 {
        for i in 0..side - 1 {
            let a = (j * side + i) as i32;
            let (b, c, d) = (a + 1, a + side as i32 + 1, a + side as i32);
            faces.extend([[a, b, c], [a, c, d]]);
        }
    }
    let def = HierarchyDef { coarse_vertex_counts: vec![16, 36], ..Default::default() };
    Hierarchy::from_mesh_with(&def, &vertices, &faces).expect("decimate the grid")
}

/// The defaults (a progressive animation) falling along −z, each step solved to 1e-12.
fn falling(hierarchy: &Hierarchy) -> Simulation<'_> {
    let def = SimulationDef {
        gravity: [0.0, 0.0, -G],
        newton_tolerance: 1e-12,
        ..SimulationDef::default()
    };
    Simulation::new(hierarchy, &def).expect("create the animation")
}

/// Every frame of `level` follows the closed form, moving along x at `vx` m/s.
fn check_free_fall(sim: &Simulation<'_>, level: usize, vx: f64) {
    assert_eq!(sim.num_frames(level).unwrap(), STEPS + 1);
    let rest = sim.frame_positions(level, 0).unwrap();
    for frame in sim.frames(level).unwrap() {
        let frame = frame.unwrap();
        let n = frame.index;
        assert_eq!(frame.positions.len(), rest.len());
        for ((x, v), x0) in frame.positions.iter().zip(&frame.velocities).zip(&rest) {
            assert!((x[0] - x0[0] - vx * H * n as f64).abs() < 1e-9, "level {level} frame {n}");
            assert!((x[2] - x0[2] - fallen(n)).abs() < 1e-9, "level {level} frame {n}");
            assert!((v[0] - vx).abs() < 1e-7 && v[1].abs() < 1e-7);
            assert!((v[2] + G * H * n as f64).abs() < 1e-7);
        }
    }
    let stats = sim.step_stats(level).unwrap();
    assert_eq!(stats.len(), STEPS);
    for (k, step) in stats.iter().enumerate() {
        assert_eq!(step.step, k + 1);
        assert!(step.converged && (step.time - H * (k + 1) as f64).abs() < 1e-12);
        assert!((step.center_of_mass[2] - fallen(k + 1)).abs() < 1e-9);
        assert!(step.com_deviation < 1e-9 && step.kinetic_energy > 0.0);
    }
    let level_stats = sim.dynamic_level_stats(level).unwrap();
    assert_eq!((level_stats.level, level_stats.vertices), (level, rest.len()));
    assert_eq!((level_stats.steps, level_stats.converged_steps), (STEPS, STEPS));
}

#[test]
fn free_fall_matches_implicit_euler_on_every_level() {
    let hierarchy = grid_levels();
    let mut sim = falling(&hierarchy);
    assert_eq!(sim.kind().unwrap(), SimulationKind::ProgressiveDynamics);
    assert_eq!(sim.prediction().unwrap(), Prediction::VelocityOnly);
    sim.step_preview(STEPS as u32).unwrap();
    sim.refine().unwrap();
    sim.refine().unwrap();
    assert_eq!(sim.current_level(), 2);
    for level in 0..3 {
        check_free_fall(&sim, level, 0.0);
    }
    assert_eq!(sim.positions(2).unwrap(), sim.frame_positions(2, STEPS).unwrap());
    assert_eq!(sim.refine().unwrap_err().code, Status::OutOfRange);
}

#[test]
fn cancelling_a_refinement_changes_nothing() {
    let hierarchy = grid_levels();
    let mut sim = falling(&hierarchy);
    sim.step_preview(STEPS as u32).unwrap();
    let mut calls = Vec::new();
    let error = sim
        .refine_with_progress(|done, total, phase| {
            calls.push((done, total, phase.to_owned()));
            done >= 2
        })
        .unwrap_err();
    assert_eq!(error.code, Status::Cancelled);
    assert_eq!(calls, [(1, 5, "refine".to_owned()), (2, 5, "refine".to_owned())]);
    assert_eq!(sim.current_level(), 0);
    assert_eq!(sim.num_frames(1).unwrap_err().code, Status::OutOfRange);
    let mut reports = 0;
    sim.refine_with_progress(|_, _, _| {
        reports += 1;
        false
    })
    .unwrap();
    assert_eq!(reports, STEPS);
    check_free_fall(&sim, 1, 0.0);
}

#[test]
fn initial_velocities_and_restart() {
    let hierarchy = grid_levels();
    let mut sim = falling(&hierarchy);
    let error = sim.set_preview_velocities(&[[1.0, 0.0, 0.0]; 15]).unwrap_err();
    assert_eq!(error.code, Status::InvalidArgument);
    assert!(error.message.contains("45 values given"), "{}", error.message);
    let mut bad = [[1.0, 0.0, 0.0]; 16];
    bad[3][1] = f64::NAN;
    assert_eq!(sim.set_preview_velocities(&bad).unwrap_err().code, Status::InvalidArgument);
    sim.set_preview_velocities(&[[1.0, 0.0, 0.0]; 16]).unwrap();
    sim.step_preview(STEPS as u32).unwrap();
    let error = sim.set_preview_velocities(&[[1.0, 0.0, 0.0]; 16]).unwrap_err();
    assert_eq!(error.code, Status::WrongCallOrder);
    sim.refine().unwrap();
    check_free_fall(&sim, 0, 1.0);
    check_free_fall(&sim, 1, 1.0);
    let error = sim.step_preview(1).unwrap_err();
    assert_eq!(error.code, Status::WrongCallOrder);
    assert!(error.message.contains("restart"), "{}", error.message);
    assert_eq!(sim.set_prediction(Prediction::PerFrame).unwrap_err().code, Status::WrongCallOrder);
    sim.restart().unwrap();
    assert_eq!((sim.current_level(), sim.num_frames(0).unwrap()), (0, 1));
    sim.set_prediction(Prediction::ProlongedPositions).unwrap();
    sim.set_param("progressive.consistency_weight", 0.5).unwrap();
    sim.set_param("progressive.galerkin_refresh", 0.0).unwrap(); // assembled every iteration
    sim.step_preview(STEPS as u32).unwrap();
    sim.refine().unwrap();
    check_free_fall(&sim, 1, 0.0); // a rigid fall: every prediction and penalty agree
}

#[test]
fn misuse_is_refused_clearly() {
    let hierarchy = grid_levels();
    let mut sim = falling(&hierarchy);
    let error = sim.refine().unwrap_err();
    assert_eq!(error.code, Status::WrongCallOrder);
    assert!(error.message.contains("preview at least one step"), "{}", error.message);
    assert_eq!(sim.frame_positions(0, 1).unwrap_err().code, Status::OutOfRange);
    let error = sim.frame_velocities(1, 0).unwrap_err();
    assert_eq!(error.code, Status::OutOfRange);
    assert!(error.message.contains("level 1 has not been computed"), "{}", error.message);
    let error = sim.settle(5).unwrap_err();
    assert_eq!(error.code, Status::InvalidArgument);
    assert!(error.message.contains("progressive animation"), "{}", error.message);
    assert_eq!(sim.level_stats(0).unwrap_err().code, Status::InvalidArgument);
    assert_eq!(sim.num_frames(0).unwrap(), 1); // nothing above changed the animation

    let def = SimulationDef {
        mode: Mode::Quasistatic,
        effects: progsim::Effect::Membrane.into(),
        consistency_weight: 0.25,
        ..SimulationDef::default()
    };
    let mut psq = Simulation::new(&hierarchy, &def).unwrap();
    assert_eq!(psq.kind().unwrap(), SimulationKind::Psq);
    assert_eq!(psq.param("progressive.consistency_weight").unwrap(), 0.25);
    let error = psq.num_frames(0).unwrap_err();
    assert_eq!(error.code, Status::InvalidArgument);
    assert!(error.message.contains("PSQ"), "{}", error.message);
    assert_eq!(psq.restart().unwrap_err().code, Status::InvalidArgument);
}

#[test]
fn a_window_continues_the_free_fall_from_its_first_frame() {
    let hierarchy = grid_levels();
    let mut sim = falling(&hierarchy);
    sim.step_preview(STEPS as u32).unwrap();
    let error = sim.refine_window(3, 2).unwrap_err();
    assert_eq!(error.code, Status::InvalidArgument);
    assert!(error.message.contains("window of steps 3 to 2"), "{}", error.message);
    sim.refine_window(2, STEPS as u32).unwrap();
    let stats = sim.dynamic_level_stats(1).unwrap();
    assert_eq!((stats.first_step, stats.steps), (2, STEPS - 2));
    let rest = hierarchy.rest_positions(1).unwrap();
    for frame in sim.frames(1).unwrap() {
        let frame = frame.unwrap();
        let n = frame.index + 2; // the animation's frame
        for ((x, v), x0) in frame.positions.iter().zip(&frame.velocities).zip(&rest) {
            assert!((x[2] - x0[2] - fallen(n)).abs() < 1e-9, "frame {n}");
            assert!((v[2] + G * H * n as f64).abs() < 1e-7, "frame {n}");
        }
    }
    let error = sim.refine().unwrap_err();
    assert_eq!(error.code, Status::WrongCallOrder);
    assert!(error.message.contains("window"), "{}", error.message);
}
