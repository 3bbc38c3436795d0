//! Multi-level hierarchies: level sizes, exact rest recovery through `prolong`, save/load and
//! errors, on the bundled 441-vertex cloth.

mod common;

use common::square_cloth;
use progsim::{
    HandleMotion, Hierarchy, HierarchyDef, Mode, Simulation, SimulationDef, SimulationKind, Status,
};

fn cloth_levels() -> Hierarchy {
    let def = HierarchyDef { coarse_vertex_counts: vec![30, 110], ..Default::default() };
    Hierarchy::from_file_with(&def, square_cloth()).expect("decimate the bundled cloth")
}

fn max_distance(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| {
            ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
        })
        .fold(0.0, f64::max)
}

#[test]
fn levels_prolong_to_the_fine_rest_shape() {
    let hierarchy = cloth_levels();
    assert_eq!(hierarchy.num_levels(), 3);
    assert_eq!(hierarchy.level_size(0).unwrap().0, 30);
    assert_eq!(hierarchy.level_size(1).unwrap().0, 110);
    let fine = hierarchy.rest_positions(2).unwrap();
    for level in 0..2 {
        let coarse = hierarchy.rest_positions(level).unwrap();
        let prolonged = hierarchy.prolong(level, &coarse).unwrap();
        assert!(max_distance(&prolonged, &fine) < 1e-9, "level {level}");
        assert!(hierarchy.num_expansion_batches(level).unwrap() >= 1);
    }
    // A translation of the coarse shape translates the fine one.
    let moved: Vec<[f64; 3]> = hierarchy
        .rest_positions(0)
        .unwrap()
        .iter()
        .map(|p| [p[0] + 1.0, p[1], p[2] - 2.0])
        .collect();
    let expected: Vec<[f64; 3]> = fine.iter().map(|p| [p[0] + 1.0, p[1], p[2] - 2.0]).collect();
    assert!(max_distance(&hierarchy.prolong(0, &moved).unwrap(), &expected) < 1e-9);
}

#[test]
fn saved_hierarchy_loads_the_same() {
    let hierarchy = cloth_levels();
    let path = std::env::temp_dir().join(format!("progsim_rust_{}.hierarchy", std::process::id()));
    hierarchy.save(&path).unwrap();
    let loaded = Hierarchy::load(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    for level in 0..3 {
        assert_eq!(loaded.faces(level).unwrap(), hierarchy.faces(level).unwrap());
        assert_eq!(loaded.rest_positions(level).unwrap(), hierarchy.rest_positions(level).unwrap());
    }
}

#[test]
fn bad_requests_are_errors() {
    let hierarchy = cloth_levels();
    let error = hierarchy.prolong(0, &[[0.0; 3]; 29]).unwrap_err();
    assert_eq!(error.code, Status::InvalidArgument);
    assert!(error.message.contains("needs 90"), "{}", error.message);
    assert_eq!(hierarchy.prolong(5, &[[0.0; 3]; 30]).unwrap_err().code, Status::OutOfRange);
    assert_eq!(hierarchy.num_expansion_batches(2).unwrap_err().code, Status::OutOfRange);
    let def = HierarchyDef { coarse_vertex_counts: vec![50, 50], ..Default::default() };
    let error = Hierarchy::from_file_with(&def, square_cloth()).unwrap_err();
    assert_eq!(error.code, Status::InvalidArgument);
    // The default mode is dynamic: on several levels, a progressive animation.
    let mut sim = Simulation::new(&hierarchy, &SimulationDef::default()).unwrap();
    assert_eq!(sim.kind().unwrap(), SimulationKind::ProgressiveDynamics);
    let error = sim.refine().unwrap_err();
    assert_eq!(error.code, Status::WrongCallOrder);
    assert!(error.message.contains("preview at least one step"), "{}", error.message);
}

#[test]
fn progressive_preview_refines_to_the_converged_finest() {
    let top_row: Vec<i32> = (420..441).collect(); // y = 1 in the bundled square cloth
    let def = HierarchyDef {
        coarse_vertex_counts: vec![40, 120],
        pinned_vertices: top_row.clone(),
        ..Default::default()
    };
    let hierarchy = Hierarchy::from_file_with(&def, square_cloth()).unwrap();
    let mut sim_def = SimulationDef::default();
    sim_def.mode = Mode::Quasistatic;
    sim_def.time_step = 1.0;
    sim_def.pinned_vertices = top_row;
    let mut sim = Simulation::new(&hierarchy, &sim_def).unwrap();
    sim.step_preview(1).unwrap();
    assert!(sim.settle(300).unwrap());
    assert_eq!(sim.positions(2).unwrap().len(), 441); // the preview prolonged
    sim.refine().unwrap();
    assert!(sim.settle(300).unwrap());
    sim.refine().unwrap();
    assert!(sim.settle(50).unwrap());
    let coarse = sim.level_stats(0).unwrap();
    let error = coarse.error_max.expect("measured once the finest level converged");
    assert!(error > 0.0 && error < 0.05, "{error}");
    assert_eq!(sim.level_stats(2).unwrap().error_max, Some(0.0));
    let refined = sim.level_stats(1).unwrap();
    assert!(refined.refine_seconds > 0.0);
    // No contact: the prolonged state is the start, no safe expansion ran.
    assert_eq!((refined.refinement.splits, refined.reduced_offsets), (0, 0));
    assert_eq!(sim.refine().unwrap_err().code, Status::OutOfRange);
    assert_eq!(sim.settle(0).unwrap_err().code, Status::InvalidArgument);
}

#[test]
fn two_vertex_groups_become_two_handles_on_every_level() {
    // The cloth's top corners (the top row is y = 1: vertices 420 ..= 440) as groups 0 and 1:
    // a PSQ simulation holds the first by its pinned vertices, adds the second as handle 1 and
    // drags it sideways; the coarse level and the finest both carry the corner there.
    let mut ids = vec![-1; 441];
    ids[420] = 0;
    ids[421] = 0;
    ids[439] = 1;
    ids[440] = 1;
    let def = HierarchyDef {
        coarse_vertex_counts: vec![60],
        vertex_group_ids: ids,
        ..Default::default()
    };
    let hierarchy = Hierarchy::from_file_with(&def, square_cloth()).expect("two groups");
    let sim_def = SimulationDef {
        mode: Mode::Quasistatic,
        pinned_vertices: vec![420, 421],
        ..SimulationDef::default()
    };
    let mut sim = Simulation::new(&hierarchy, &sim_def).expect("group 0 pinned");
    assert_eq!(sim.add_handle(0, &[0]).unwrap_err().code, Status::InvalidArgument);
    assert_eq!(sim.add_handle(0, &[439, 440]).expect("group 1"), 1);
    sim.set_handle_motion(1, &HandleMotion { offset: [0.05, 0.0, 0.0], ..Default::default() })
        .expect("drag it");
    sim.step_preview(2).expect("preview");
    let coarse = sim.positions(0).unwrap();
    let at_corner = |p: &[f64; 3]| (p[0] - 1.05).abs() < 1e-12 && (p[1] - 1.0).abs() < 1e-12;
    assert_eq!(coarse.iter().filter(|p| at_corner(p)).count(), 1);
    sim.refine().expect("refine");
    let fine = sim.positions(1).unwrap();
    assert!(at_corner(&fine[440]), "{:?}", fine[440]);
    assert!(fine[420][0].abs() < 1e-12 && (fine[420][1] - 1.0).abs() < 1e-12);
}
