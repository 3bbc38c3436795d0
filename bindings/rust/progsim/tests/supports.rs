//! Partial supports and handle reactions through the safe wrapper: a propped stiff strip whose
//! roller carries the beam-theory share of the weight and no horizontal load.

use progsim::{Axes, Simulation, Status, Support};

const LENGTH: f64 = 0.5;
const WIDTH: f64 = 0.05;
const THICKNESS: f64 = 5e-3;
const DENSITY: f64 = 1000.0;
const G: f64 = 9.81;

/// A stiff strip along x clamped over x ≤ 1.5 Δx, its far end on a roller held in height.
fn propped_strip() -> String {
    let dx = LENGTH / 40.0;
    format!(
        r#"{{
          "simulation": {{"mode": "quasistatic", "time_step": 1.0}},
          "gravity": [0, 0, -{G}],
          "effects": ["membrane", "bending", "gravity"],
          "solver": {{"newton_tolerance": 1e-8}},
          "bodies": [{{
            "mesh": {{"generator": "grid", "width": {LENGTH}, "height": {WIDTH}, "nx": 40, "ny": 2}},
            "material": {{"youngs_modulus": 1e10, "poisson_ratio": 0.0,
                          "thickness": {THICKNESS}, "density": {DENSITY}}}
          }}],
          "handles": [
            {{"body": 0, "box": {{"min": [-1, -1, -1], "max": [{clamp}, 1, 1]}}}},
            {{"body": 0, "box": {{"min": [{end}, -1, -1], "max": [1, 1, 1]}}, "axes": "z"}}
          ]
        }}"#,
        clamp = 1.5 * dx,
        end = LENGTH - 1e-9,
    )
}

#[test]
fn a_roller_carries_the_prop_share_and_no_horizontal_load() {
    let weight = DENSITY * THICKNESS * LENGTH * WIDTH * G;
    let mut sim = Simulation::from_scene(&propped_strip(), None).expect("valid scene");
    assert_eq!(sim.handle_reaction(0, 0).unwrap_err().code, Status::WrongCallOrder);
    sim.step_preview(1).expect("one load step");
    let clamp = sim.handle_reaction(0, 0).expect("clamp reaction");
    let roller = sim.handle_reaction(0, 1).expect("roller reaction");
    assert!((clamp.force[2] + roller.force[2] - weight).abs() < 1e-6 * weight);
    assert_eq!(roller.force[0], 0.0);
    assert!(clamp.force[0].abs() < 1e-6 * weight);
    // Propped cantilever under uniform load (beam theory): the prop carries 3/8 of the span.
    let dx = LENGTH / 40.0;
    let prop = 3.0 / 8.0 * weight / LENGTH * (LENGTH - dx) + weight / LENGTH * dx / 2.0;
    assert!((roller.force[2] - prop).abs() < 0.03 * prop, "{} vs {prop}", roller.force[2]);

    sim.set_handle_axes(1, Axes::ALL).expect("a pin instead");
    sim.settle(10).expect("settle");
    assert!(sim.handle_reaction(0, 0).expect("clamp").force[0].abs() > 0.1 * weight);
    let none = Axes { x: false, y: false, z: false };
    assert_eq!(sim.set_handle_axes(1, none).unwrap_err().code, Status::InvalidScene);
    assert_eq!(sim.set_handle_axes(7, Axes::ALL).unwrap_err().code, Status::OutOfRange);
}

#[test]
fn a_rotation_support_free_to_translate_leaves_the_weight_to_the_clamp() {
    // The roller (one column) switched to a rotation support free to translate: it keeps the
    // column straight but supplies no force, so the clamp carries the whole weight.
    let weight = DENSITY * THICKNESS * LENGTH * WIDTH * G;
    let mut sim = Simulation::from_scene(&propped_strip(), None).expect("valid scene");
    sim.set_handle_support(1, Support::Rotation, Axes::NONE).expect("a guided end");
    sim.step_preview(1).expect("one load step");
    let clamp = sim.handle_reaction(0, 0).expect("clamp reaction");
    let guided = sim.handle_reaction(0, 1).expect("guided reaction");
    assert!((clamp.force[2] - weight).abs() < 1e-6 * weight, "{}", clamp.force[2]);
    assert!(guided.force.iter().all(|f| f.abs() < 1e-4 * weight), "{:?}", guided.force);
    // The same support from the scene key steps bit for bit alike.
    let keyed_scene =
        propped_strip().replace(r#""axes": "z""#, r#""support": "rotation", "axes": """#);
    let mut keyed = Simulation::from_scene(&keyed_scene, None).expect("valid scene");
    keyed.step_preview(1).expect("one load step");
    assert_eq!(keyed.positions(0).unwrap(), sim.positions(0).unwrap());
    assert_eq!(
        sim.set_handle_support(1, Support::Position, Axes::NONE).unwrap_err().code,
        Status::InvalidScene
    );
    assert_eq!(
        sim.set_handle_support(9, Support::Rotation, Axes::NONE).unwrap_err().code,
        Status::OutOfRange
    );
}
