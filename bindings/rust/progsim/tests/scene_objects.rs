//! Handles, obstacles and the ground from Rust: a scene built in code steps bit for bit like
//! the same scene read from JSON; bad objects are refused naming the problem, nothing changed.

mod common;

use progsim::{
    Effect, Effects, Ground, HandleMotion, Hierarchy, Interpolation, Keyframe, Obstacle,
    Simulation, SimulationDef, Status,
};

/// A 0.4 m sheet (vertex (i, j) at 5 j + i) falling in −z onto a plate (tests/data/plate.obj)
/// rising 1 cm in 0.1 s; two corners lifted by smooth keys, a third rising at 0.1 m/s; a
/// frictional ground below.
const SCENE: &str = r#"{
  "simulation": { "time_step": 0.01 }, "gravity": [0, 0, -9.81],
  "effects": ["membrane", "bending", "gravity", "contact", "friction"],
  "bodies": [ { "mesh": { "generator": "grid", "width": 0.4, "height": 0.4, "nx": 4, "ny": 4 } } ],
  "handles": [
    { "body": 0, "vertices": [0, 4], "motion": { "interpolation": "smooth",
      "keyframes": [ { "time": 0 }, { "time": 0.1, "translation": [0, 0, 0.02] } ] } },
    { "body": 0, "vertices": [24], "motion": { "velocity": [0, 0, 0.1] } } ],
  "obstacles": [ { "mesh": { "file": "plate.obj" }, "friction": 0.2,
    "motion": { "keyframes": [ { "time": 0 }, { "time": 0.1, "translation": [0, 0, 0.01] } ] } } ],
  "ground": { "normal": [0, 0, 2], "height": -0.1, "friction": 0.3 }
}"#;

fn plate() -> Obstacle {
    Obstacle {
        vertices: vec![[0.1, 0.1, -0.03], [0.3, 0.1, -0.03], [0.3, 0.3, -0.03], [0.1, 0.3, -0.03]],
        faces: vec![[0, 1, 2], [0, 2, 3]],
        friction: 0.2,
        progressive: false,
    }
}

fn effects() -> Effects {
    Effect::Membrane | Effect::Bending | Effect::Gravity | Effect::Contact | Effect::Friction
}

/// The scene's mesh as a hierarchy of its own.
fn sheet_hierarchy(scene: &Simulation) -> Hierarchy {
    let own = scene.hierarchy().expect("a scene owns its hierarchy");
    let (vertices, faces) = (own.rest_positions(0).unwrap(), own.faces(0).unwrap());
    Hierarchy::from_mesh(&vertices, &faces).expect("the scene's valid mesh")
}

fn bare_sheet(hierarchy: &Hierarchy) -> Simulation<'_> {
    let def = SimulationDef {
        effects: effects(),
        gravity: [0.0, 0.0, -9.81],
        ..SimulationDef::default()
    };
    Simulation::new(hierarchy, &def).expect("valid def")
}

fn rise(to: f64) -> [Keyframe; 2] {
    [
        Keyframe::default(),
        Keyframe { time: 0.1, translation: [0.0, 0.0, to], ..Keyframe::default() },
    ]
}

#[test]
fn code_equals_json_step_by_step() {
    let mut from_json =
        Simulation::from_scene(SCENE, Some(&common::repo_path("tests/data"))).expect("valid scene");
    let hierarchy = sheet_hierarchy(&from_json);
    let mut sim = bare_sheet(&hierarchy);
    assert_eq!(sim.add_handle(0, &[0, 4]).expect("corners"), 0);
    sim.set_handle_keyframes(0, &rise(0.02), Interpolation::Smooth).expect("valid keys");
    assert_eq!(sim.add_handle(0, &[24]).expect("a corner"), 1);
    let up = HandleMotion { velocity: [0.0, 0.0, 0.1], ..HandleMotion::default() };
    sim.set_handle_motion(1, &up).expect("valid motion");
    assert_eq!(sim.add_obstacle(&plate()).expect("a plate below"), 0);
    sim.set_obstacle_keyframes(0, &rise(0.01), Interpolation::Linear).expect("valid keys");
    let ground = Ground { normal: [0.0, 0.0, 2.0], height: -0.1, friction: 0.3 };
    sim.set_ground(Some(&ground)).expect("the sheet is above it");
    assert_eq!((sim.num_handles(), sim.num_obstacles()), (2, 1));
    assert_eq!((from_json.num_handles(), from_json.num_obstacles()), (2, 1));
    for step in 0..15 {
        from_json.step_preview(1).unwrap();
        sim.step_preview(1).unwrap();
        assert_eq!(sim.positions(0).unwrap(), from_json.positions(0).unwrap(), "step {step}");
    }
    let x = sim.positions(0).unwrap();
    assert_eq!((x[0][2], x[4][2]), (0.02, 0.02)); // held at the last key
    assert!((x[24][2] - 0.015).abs() < 1e-12);
    assert!(x[12][2] > -0.02 && x[12][2] < 0.0, "the centre rests on the plate: {}", x[12][2]);
}

#[test]
fn bad_objects_are_refused_and_change_nothing() {
    let from_json =
        Simulation::from_scene(SCENE, Some(&common::repo_path("tests/data"))).expect("valid scene");
    let hierarchy = sheet_hierarchy(&from_json);
    let mut sim = bare_sheet(&hierarchy);
    let spike = Obstacle {
        vertices: vec![[0.15, 0.2, -0.05], [0.25, 0.2, -0.05], [0.2, 0.2, 0.05]],
        faces: vec![[0, 1, 2]],
        ..Obstacle::default()
    };
    let error = sim.add_obstacle(&spike).unwrap_err();
    assert_eq!(error.code(), Status::Intersecting);
    assert!(error.message().contains("obstacle face 0 cross"), "{error}");
    let outside = Obstacle { faces: vec![[0, 1, 2], [0, 2, 4]], ..plate() };
    assert_eq!(sim.add_obstacle(&outside).unwrap_err().code(), Status::InvalidMesh);
    let error = sim.add_handle(0, &[25]).unwrap_err();
    assert_eq!(error.code(), Status::InvalidScene);
    assert!(error.message().contains("vertex 25 is out of range"), "{error}");
    assert_eq!(
        sim.set_obstacle_motion(0, &HandleMotion::default()).unwrap_err().code(),
        Status::OutOfRange
    );
    let above = Ground { normal: [0.0, 0.0, 1.0], height: 0.1, friction: 0.0 };
    assert_eq!(sim.set_ground(Some(&above)).unwrap_err().code(), Status::Intersecting);
    assert_eq!((sim.num_handles(), sim.num_obstacles()), (0, 0));
    sim.add_obstacle(&plate()).expect("the plate is clear of the sheet");
    let unordered = [
        Keyframe { time: 0.1, ..Keyframe::default() },
        Keyframe { time: 0.05, ..Keyframe::default() },
    ];
    let error = sim.set_obstacle_keyframes(0, &unordered, Interpolation::Linear).unwrap_err();
    assert!(error.message().contains("obstacles[0].motion.keyframes[1].time"), "{error}");
    sim.step_preview(1).unwrap();
    assert_eq!(sim.add_handle(0, &[24]).unwrap_err().code(), Status::WrongCallOrder);
    sim.set_ground(None).expect("removing the ground between steps");
    sim.step_preview(1).unwrap();
}

#[test]
fn named_options_set_in_code_equal_the_scene_file() {
    const OPTIONS: &str = r#"{
      "simulation": { "mode": "quasistatic" }, "gravity": [0, 0, -9.81],
      "effects": ["membrane", "bending", "gravity"],
      "bodies": [ { "mesh": { "generator": "grid", "width": 0.4, "height": 0.4, "nx": 4, "ny": 4 },
                    "material": { "bending_model": "midedge" } } ],
      "handles": [ { "body": 0, "vertices": [0, 1, 2, 3, 4, 5, 6, 7, 8, 9] } ],
      "progressive": { "levels": [12], "proxy_hessian": "galerkin", "prolongation": "direct" }
    }"#;
    let table = progsim::choices();
    let hessian = table.iter().find(|c| c.name == "progressive.proxy_hessian").unwrap();
    assert_eq!(hessian.options, ["auto", "level", "galerkin"]);
    let mut from_json = Simulation::from_scene(OPTIONS, None).expect("valid scene");
    from_json.step_preview(1).unwrap();
    from_json.refine().unwrap();
    from_json.step_preview(1).unwrap();
    let own = from_json.hierarchy().unwrap();
    let def = SimulationDef {
        mode: progsim::Mode::Quasistatic,
        gravity: [0.0, 0.0, -9.81],
        pinned_vertices: (0..10).collect(),
        ..SimulationDef::default()
    };
    let mut sim = Simulation::new(own, &def).expect("valid def");
    sim.set_choice("material.bending_model", "midedge").unwrap();
    sim.set_choice("progressive.proxy_hessian", "galerkin").unwrap();
    sim.set_choice("progressive.prolongation", "direct").unwrap();
    assert_eq!(sim.choice("progressive.prolongation"), Ok("direct"));
    let error = sim.set_choice("progressive.proxy_hessian", "exact").unwrap_err();
    assert_eq!(error.code(), Status::InvalidArgument);
    assert!(error.message().contains("known: auto, level, galerkin"), "{error}");
    sim.step_preview(1).unwrap();
    sim.refine().unwrap();
    sim.step_preview(1).unwrap();
    assert_eq!(sim.positions(1).unwrap(), from_json.positions(1).unwrap());
}
