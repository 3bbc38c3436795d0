//! Point and line loads and the gravity ramp from Rust: a simulation built in code steps bit
//! for bit like the same scene read from JSON; bad loads are refused naming the problem.

use progsim::{Effect, Hierarchy, Load, LoadDistribution, Mode, Simulation, SimulationDef, Status};

/// A 0.4 m × 0.1 m strip of 8 × 2 quads (27 vertices) clamped on its first two columns, a tip
/// force and a follower (normal) force spread by area and a couple about y on its last two
/// columns, ramped over two steps.
const LOADED_STRIP: &str = r#"{
  "simulation": { "mode": "quasistatic" },
  "effects": ["membrane", "bending"],
  "bodies": [ { "name": "strip",
                "mesh": { "generator": "grid", "width": 0.4, "height": 0.1, "nx": 8, "ny": 2 },
                "material": { "youngs_modulus": 1e9 } } ],
  "handles": [ { "body": 0, "vertices": [0, 1, 9, 10, 18, 19] } ],
  "loads": [
    { "body": 0, "vertices": [8, 17, 26], "force": [0, 0, -0.002], "normal_force": -0.001,
      "distribution": "area" },
    { "body": 0, "vertices": [7, 8, 16, 17, 25, 26], "distribution": "per_vertex",
      "moment": { "axis": [0, 1, 0], "magnitude": 1e-4 }, "ramp": 0.02 } ]
}"#;

/// The scene's mesh as a hierarchy of its own (the scene simulation's is borrowed from it).
fn strip_hierarchy(scene: &Simulation) -> Hierarchy {
    let own = scene.hierarchy().expect("a scene owns its hierarchy");
    let (vertices, faces) = (own.rest_positions(0).unwrap(), own.faces(0).unwrap());
    Hierarchy::from_mesh(&vertices, &faces).expect("the scene's valid mesh")
}

fn tip_force() -> Load {
    Load {
        vertices: vec![8, 17, 26],
        force: [0.0, 0.0, -0.002],
        normal_force: -0.001,
        distribution: LoadDistribution::Area,
        ..Load::default()
    }
}

#[test]
fn code_equals_json_step_by_step() {
    let mut from_json = Simulation::from_scene(LOADED_STRIP, None).expect("valid scene");
    let hierarchy = strip_hierarchy(&from_json);
    let def = SimulationDef {
        mode: Mode::Quasistatic,
        effects: Effect::Membrane | Effect::Bending,
        youngs_modulus: 1e9,
        pinned_vertices: vec![0, 1, 9, 10, 18, 19],
        ..SimulationDef::default()
    };
    let mut from_code = Simulation::new(&hierarchy, &def).expect("valid def");
    assert_eq!(from_code.add_load(&tip_force()).expect("a tip force"), 0);
    let couple = Load {
        vertices: vec![7, 8, 16, 17, 25, 26],
        distribution: LoadDistribution::PerVertex,
        moment_axis: [0.0, 1.0, 0.0],
        moment: 1e-4,
        ramp: 0.02,
        ..Load::default()
    };
    assert_eq!(from_code.add_load(&couple).expect("an end couple"), 1);
    assert_eq!((from_json.num_loads(), from_code.num_loads()), (2, 2));
    for step in 0..3 {
        from_json.step_preview(1).expect("step");
        from_code.step_preview(1).expect("step");
        let (a, b) = (from_json.positions(0).unwrap(), from_code.positions(0).unwrap());
        assert_eq!(a, b, "step {step}: not bit for bit");
    }
    assert!(from_code.positions(0).unwrap()[26][2] < -1e-4, "the tip force pulls the tip down");
}

#[test]
fn bad_loads_are_refused_and_change_nothing() {
    let mut sim = Simulation::from_scene(LOADED_STRIP, None).expect("valid scene");
    let refused = |sim: &mut Simulation, load: Load, needle: &str| {
        let error = sim.add_load(&load).expect_err(needle);
        assert_eq!(error.code, Status::InvalidScene, "{}", error.message);
        assert!(error.message.contains(needle), "{} lacks {needle}", error.message);
    };
    refused(&mut sim, Load { force: [0.0, f64::NAN, 0.0], ..tip_force() }, "loads[2].force");
    refused(&mut sim, Load { vertices: vec![27], ..tip_force() }, "vertex 27 is out of range");
    refused(&mut sim, Load { vertices: vec![], ..tip_force() }, "selects no vertices");
    refused(&mut sim, Load { ramp: -1.0, ..tip_force() }, "loads[2].ramp");
    refused(&mut sim, Load { body: 3, ..tip_force() }, "loads[2]: body index 3");
    let twist = Load { moment: 1.0, moment_axis: [0.0, 1.0, 0.0], ..tip_force() };
    refused(&mut sim, twist, "loads[2].moment"); // the tip edge lies along y
    assert_eq!(sim.num_loads(), 2);
    sim.step_preview(1).expect("still steps");
}

#[test]
fn gravity_ramp_is_a_def_field_and_a_parameter() {
    let scene = Simulation::from_scene(LOADED_STRIP, None).expect("valid scene");
    let def = SimulationDef { gravity_ramp: 0.5, ..SimulationDef::default() };
    let hierarchy = strip_hierarchy(&scene);
    let mut sim = Simulation::new(&hierarchy, &def).expect("valid def");
    assert_eq!(sim.param("simulation.gravity_ramp").unwrap(), 0.5);
    sim.set_param("simulation.gravity_ramp", 0.25).unwrap();
    assert_eq!(sim.param("simulation.gravity_ramp").unwrap(), 0.25);
    let error = sim.set_param("simulation.gravity_ramp", -1.0).unwrap_err();
    assert_eq!(error.code, Status::InvalidArgument);
}
