//! Keyframed handle motion set through code: each key's pose at its time, the same steps bit
//! for bit as the scene's "keyframes", and bad keys refused naming the key.

use std::f64::consts::FRAC_PI_2;

use progsim::{Interpolation, Keyframe, Simulation, Status};

/// A quasistatic 1 m sheet (4 × 4 quads) whose handle 0 holds its left edge with `motion`.
fn sheet(motion: &str) -> Simulation<'static> {
    let scene = format!(
        r#"{{"simulation": {{"mode": "quasistatic", "time_step": 0.1}},
            "effects": ["membrane", "bending"],
            "bodies": [{{"mesh": {{"generator": "grid", "width": 1, "height": 1, "nx": 4, "ny": 4}}}}],
            "handles": [{{"body": 0, "vertices": [0, 5, 10, 15, 20], "motion": {motion}}}]}}"#
    );
    Simulation::from_scene(&scene, None).expect("a valid scene")
}

/// Lifted by 0.1 m at 0.2 s, then turned a quarter about z through the centre by 0.4 s.
fn keys() -> Vec<Keyframe> {
    let lifted = [0.0, 0.0, 0.1];
    vec![
        Keyframe::default(),
        Keyframe { time: 0.2, translation: lifted, ..Keyframe::default() },
        Keyframe { time: 0.4, translation: lifted, angle: FRAC_PI_2, ..Keyframe::default() },
    ]
}

fn near(a: [f64; 3], b: [f64; 3]) -> bool {
    a.iter().zip(b.iter()).all(|(x, y)| (x - y).abs() < 1e-12)
}

#[test]
fn keys_are_reached_at_their_times_and_match_the_scene_bit_for_bit() {
    let mut coded = sheet(r#"{"center": [0, 0.5, 0]}"#);
    let mut read = sheet(
        r#"{"center": [0, 0.5, 0], "interpolation": "smooth", "keyframes": [{"time": 0},
            {"time": 0.2, "translation": [0, 0, 0.1]},
            {"time": 0.4, "translation": [0, 0, 0.1], "angle": 1.5707963267948966}]}"#,
    );
    coded.set_handle_keyframes(0, &keys(), Interpolation::Smooth).expect("valid keys");
    for step in 1..=5 {
        coded.step_preview(1).expect("step");
        read.step_preview(1).expect("step");
        let x = coded.positions(0).expect("positions");
        assert_eq!(x, read.positions(0).expect("positions"), "step {step}");
        if step == 2 {
            assert!(near(x[20], [0.0, 1.0, 0.1]), "key 1 at step 2: {:?}", x[20]);
        }
        if step >= 4 {
            assert!(near(x[20], [-0.5, 0.5, 0.1]), "key 2 at step {step}: {:?}", x[20]);
        }
    }
}

#[test]
fn bad_keys_are_refused_naming_the_key() {
    let mut sim = sheet("{}");
    let mut late = keys();
    late[2].time = 0.1;
    let error = sim.set_handle_keyframes(0, &late, Interpolation::Linear).unwrap_err();
    assert_eq!(error.code, Status::InvalidArgument);
    assert!(error.message.contains("handles[0].motion.keyframes[2].time"), "{}", error.message);
    let zero_axis = [Keyframe { axis: [0.0; 3], ..Keyframe::default() }];
    let error = sim.set_handle_keyframes(0, &zero_axis, Interpolation::Hold).unwrap_err();
    assert!(error.message.contains("keyframes[0].axis"), "{}", error.message);
    let error = sim.set_handle_keyframes(0, &[], Interpolation::Hold).unwrap_err();
    assert_eq!(error.code, Status::InvalidArgument);
    let error = sim.set_handle_keyframes(1, &keys(), Interpolation::Hold).unwrap_err();
    assert_eq!(error.code, Status::OutOfRange);
}
