//! The wind effect set through code: a free grid blown downwind as implicit Euler of the drag
//! equation predicts, gusts as keyframes, bad wind settings refused naming the field.

mod common;

use common::{GRID_FACES, GRID_VERTICES};
use progsim::{Effect, Hierarchy, Mode, Simulation, SimulationDef, Status};

/// A free 2 m × 2 m grid in a wind, gravity off, stepped at h = 0.05 s.
fn grid_in_wind(wind: SimulationDef) -> SimulationDef {
    SimulationDef {
        time_step: 0.05,
        newton_tolerance: 1e-9,
        effects: Effect::Membrane | Effect::Wind,
        gravity: [0.0; 3],
        ..wind
    }
}

#[test]
fn grid_is_blown_downwind_as_implicit_euler_predicts() {
    let (speed, h, steps) = (10.0, 0.05, 20);
    let hierarchy = Hierarchy::from_mesh(&GRID_VERTICES, &GRID_FACES).expect("valid grid");
    let def = grid_in_wind(SimulationDef {
        wind_velocity: [0.0, 0.0, speed],
        wind_drag: 1.5,
        ..SimulationDef::default()
    });
    let mut sim = Simulation::new(&hierarchy, &def).expect("a dynamic scene with wind");
    assert!(sim.effects().contains(Effect::Wind));
    sim.step_preview(steps).expect("steps");
    // m (v' − v)/h = ½ρC_dA (w − v')² per unit area (areal density 200 kg/m³ × 1 mm), solved
    // for the lag d' = w − v' each step.
    let a = 0.5 * def.wind_density * def.wind_drag / (def.density * def.thickness) * h;
    let (mut lag, mut travelled) = (speed, 0.0);
    for _ in 0..steps {
        lag = ((1.0 + 4.0 * a * lag).sqrt() - 1.0) / (2.0 * a);
        travelled += h * (speed - lag);
    }
    for (now, rest) in sim.positions(0).expect("positions").iter().zip(GRID_VERTICES.iter()) {
        assert!((now[2] - rest[2] - travelled).abs() < 1e-6 * travelled, "{now:?} vs {travelled}");
        assert!((now[0] - rest[0]).abs() < 1e-9 && (now[1] - rest[1]).abs() < 1e-9);
    }
}

#[test]
fn gusts_follow_their_keyframes() {
    let hierarchy = Hierarchy::from_mesh(&GRID_VERTICES, &GRID_FACES).expect("valid grid");
    let def = grid_in_wind(SimulationDef {
        wind_keyframes: vec![[0.5, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 8.0]],
        ..SimulationDef::default()
    });
    let mut sim = Simulation::new(&hierarchy, &def).expect("gusts");
    sim.step_preview(10).expect("still air until 0.5 s");
    assert_eq!(sim.positions(0).expect("positions"), GRID_VERTICES.to_vec());
    sim.step_preview(10).expect("the gust");
    assert!(sim.positions(0).expect("positions").iter().all(|p| p[2] > 0.0));
}

#[test]
fn bad_wind_is_refused_naming_the_field() {
    let hierarchy = Hierarchy::from_mesh(&GRID_VERTICES, &GRID_FACES).expect("valid grid");
    let refused = |def: SimulationDef, code: Status, needle: &str| {
        let error = Simulation::new(&hierarchy, &grid_in_wind(def)).expect_err("refused");
        assert_eq!(error.code, code, "{error}");
        assert!(error.message.contains(needle), "{error:?} does not mention {needle:?}");
    };
    refused(
        SimulationDef { wind_density: -1.0, ..SimulationDef::default() },
        Status::InvalidArgument,
        "wind.density",
    );
    refused(
        SimulationDef {
            wind_keyframes: vec![[1.0, 0.0, 0.0, 1.0], [0.5, 0.0, 0.0, 2.0]],
            ..SimulationDef::default()
        },
        Status::InvalidScene,
        "wind.keyframes[1].time",
    );
    refused(
        SimulationDef {
            mode: Mode::Quasistatic,
            pinned_vertices: vec![0],
            ..SimulationDef::default()
        },
        Status::InvalidScene,
        "needs a dynamic scene",
    );
}
