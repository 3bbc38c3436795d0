//! The accuracy-vs-time report through Rust, on the bundled plate-buckling scene.

mod common;

use common::repo_path;
use progsim::{Accuracy, AccuracyDef, Method, Status};

#[test]
fn plate_rows_errors_and_files() {
    let accuracy = Accuracy::run(repo_path("scenes/psq_plate_buckling.json")).unwrap();
    let rows = accuracy.rows();
    let kinds: Vec<(Method, usize)> = rows.iter().map(|r| (r.method, r.level)).collect();
    assert_eq!(
        kinds,
        vec![
            (Method::Progressive, 0),
            (Method::Progressive, 1),
            (Method::Progressive, 2),
            (Method::Direct, 0),
            (Method::Direct, 1),
            (Method::Direct, 2),
        ]
    );
    assert_eq!(rows[2].error_max, 0.0); // the converged finest result itself
    assert!(rows[0].error_max > 0.0 && rows[0].error_max < 0.1);
    assert!(rows[0].seconds < rows[2].seconds);
    assert_eq!(rows[5].vertices, 625);
    assert!(rows.iter().all(|row| row.intersecting_pairs == 0 && row.converged));
    assert!(rows.iter().all(|row| row.load_steps == 10 && row.finished));
    let dir = std::env::temp_dir().join(format!("progsim_rust_accuracy_{}", std::process::id()));
    accuracy.write(&dir).unwrap();
    assert!(dir.join("accuracy.csv").is_file());
    assert!(dir.join("error_vs_time.png").is_file());
    assert!(dir.join("time_by_level.png").is_file());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn scenes_without_levels_are_refused() {
    let error = Accuracy::run(repo_path("scenes/hanging_cloth.json")).unwrap_err();
    assert_eq!(error.code, Status::InvalidScene);
    assert!(error.message.contains("coarse levels"), "{}", error.message);
}

#[test]
fn only_the_levels_asked_for_are_solved_directly_within_the_time_ratio() {
    let def = AccuracyDef { direct_levels: vec![2], direct_time_ratio: 1e-9, ..Default::default() };
    let accuracy = Accuracy::run_with(repo_path("scenes/psq_plate_buckling.json"), &def).unwrap();
    let rows = accuracy.rows();
    assert_eq!(rows.len(), 4);
    assert_eq!((rows[3].method, rows[3].level), (Method::Direct, 2));
    assert!(!rows[3].finished && !rows[3].converged && rows[3].load_steps < 10);
    assert!(rows[..3].iter().all(|row| row.finished));
    // The limit is the ratio times the progressive time to the converged finest level.
    assert_eq!(accuracy.direct_time_limit(), 1e-9 * rows[2].seconds);
}

#[test]
fn a_time_ratio_of_the_preview_gives_the_direct_solve_that_many_previews() {
    let def = AccuracyDef {
        direct_levels: vec![2],
        direct_time_ratio: 2.0,
        direct_time_of_preview: true,
    };
    let accuracy = Accuracy::run_with(repo_path("scenes/psq_plate_buckling.json"), &def).unwrap();
    let preview = &accuracy.rows()[0];
    assert_eq!((preview.method, preview.level), (Method::Progressive, 0));
    assert_eq!(accuracy.direct_time_limit(), 2.0 * preview.seconds);
}

#[test]
fn direct_levels_that_do_not_exist_and_negative_ratios_are_refused() {
    let plate = repo_path("scenes/psq_plate_buckling.json");
    for (def, needle) in [
        (AccuracyDef { direct_levels: vec![3], ..Default::default() }, "does not exist"),
        (AccuracyDef { direct_time_ratio: -1.0, ..Default::default() }, "time ratio"),
    ] {
        let error = Accuracy::run_with(&plate, &def).unwrap_err();
        assert_eq!(error.code, Status::InvalidArgument);
        assert!(error.message.contains(needle), "{}", error.message);
    }
}
