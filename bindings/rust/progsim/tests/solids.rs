//! Solids (VPD, issue 32 §7): a tet hierarchy from tets, from a closed surface and from a file,
//! its levels' tets and boundary faces, prolongation of affine maps, a VPD animation falling
//! freely on two levels against the closed form of implicit Euler, a volumetric scene, and
//! misuse (bad tets, shell-only calls, effects a solid cannot have).

mod common;

use common::{repo_path, scratch_dir, GRID_FACES, GRID_VERTICES};
use progsim::{
    Effect, Hierarchy, HierarchyDef, Load, Mode, Simulation, SimulationDef, SimulationKind, Status,
};

const SPACING: f64 = 0.1;
const H: f64 = 0.01;
const G: f64 = 9.81;
const STEPS: usize = 5;

/// Signed volume (x1 − x0)·((x2 − x0) × (x3 − x0)) / 6 of `tet`, m³.
fn tet_volume(x: &[[f64; 3]], tet: [i32; 4]) -> f64 {
    let [a, b, c, d] = tet.map(|i| x[i as usize]);
    let e = |p: [f64; 3]| [p[0] - a[0], p[1] - a[1], p[2] - a[2]];
    let (u, v, w) = (e(b), e(c), e(d));
    (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0]))
        / 6.0
}

/// A cells³ grid of SPACING cubes, each split into the six tets of its main diagonal, all
/// positively oriented.
fn tet_box(cells: usize) -> (Vec<[f64; 3]>, Vec<[i32; 4]>) {
    let side = cells + 1;
    let index = |i: usize, j: usize, k: usize| ((k * side + j) * side + i) as i32;
    let mut vertices = Vec::new();
    for k in 0..side {
        for j in 0..side {
            for i in 0..side {
                vertices.push([i as f64 * SPACING, j as f64 * SPACING, k as f64 * SPACING]);
            }
        }
    }
    let paths = [(1, 2), (1, 4), (2, 1), (2, 4), (4, 1), (4, 2)]; // corner bits along x, y, z
    let mut tets = Vec::new();
    for k in 0..cells {
        for j in 0..cells {
            for i in 0..cells {
                let corner = |c: usize| index(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2 & 1));
                for (a, b) in paths {
                    let mut tet = [corner(0), corner(a), corner(a | b), corner(7)];
                    if tet_volume(&vertices, tet) < 0.0 {
                        tet.swap(1, 2);
                    }
                    tets.push(tet);
                }
            }
        }
    }
    (vertices, tets)
}

/// The 4³-cell box (125 vertices, 98 on the boundary, 384 tets) with one coarse level
/// decimated to 26 boundary vertices.
fn box_levels() -> Hierarchy {
    let (vertices, tets) = tet_box(4);
    let def = HierarchyDef { coarse_vertex_counts: vec![26], ..HierarchyDef::default() };
    Hierarchy::from_tets_with(&def, &vertices, &tets).expect("build the box's levels")
}

#[test]
fn levels_hold_tets_and_their_boundary_faces() {
    let (vertices, tets) = tet_box(4);
    let hierarchy = box_levels();
    assert!(hierarchy.is_solid());
    assert_eq!(hierarchy.num_levels(), 2);
    assert_eq!(hierarchy.level_size(1).unwrap(), (125, 2 * 6 * 4 * 4));
    assert_eq!(hierarchy.tets(1).unwrap(), tets); // the finest level is the input
    assert_eq!(hierarchy.rest_positions(1).unwrap(), vertices);
    let (coarse, _) = hierarchy.level_size(0).unwrap();
    assert!((26..125).contains(&coarse), "coarse level of {coarse} vertices");
    for level in 0..2 {
        let x = hierarchy.rest_positions(level).unwrap();
        let tets = hierarchy.tets(level).unwrap();
        let faces = hierarchy.faces(level).unwrap();
        assert!(!tets.is_empty() && faces.len() == hierarchy.level_size(level).unwrap().1);
        let in_range = |i: i32| i >= 0 && (i as usize) < x.len();
        assert!(tets.iter().flatten().all(|&i| in_range(i)));
        assert!(faces.iter().flatten().all(|&i| in_range(i)));
        assert!(tets.iter().all(|&tet| tet_volume(&x, tet) > 0.0), "level {level}");
    }
    let coarse_volume: f64 = hierarchy
        .tets(0)
        .unwrap()
        .iter()
        .map(|&t| tet_volume(&hierarchy.rest_positions(0).unwrap(), t))
        .sum();
    assert!(coarse_volume > 0.8 * 0.064 && coarse_volume <= 0.064 * (1.0 + 1e-9));
}

#[test]
fn prolongation_carries_affine_maps_to_the_finest_level() {
    let hierarchy = box_levels();
    let a = [[1.1, 0.2, 0.0], [-0.1, 0.9, 0.3], [0.05, 0.0, 1.2]];
    let b = [0.5, -0.2, 1.0];
    let map =
        |p: &[f64; 3]| [0, 1, 2].map(|i| b[i] + a[i][0] * p[0] + a[i][1] * p[1] + a[i][2] * p[2]);
    let coarse: Vec<[f64; 3]> = hierarchy.rest_positions(0).unwrap().iter().map(map).collect();
    let fine = hierarchy.prolong(0, &coarse).unwrap();
    let (vertices, _) = tet_box(4);
    assert_eq!(fine.len(), vertices.len());
    for (x, p) in fine.iter().zip(&vertices) {
        let exact = map(p);
        assert!((0..3).all(|i| (x[i] - exact[i]).abs() < 1e-9), "{x:?} vs {exact:?}");
    }
}

#[test]
fn shells_are_not_solids() {
    let shell = Hierarchy::from_mesh(&GRID_VERTICES, &GRID_FACES).unwrap();
    assert!(!shell.is_solid());
    assert!(shell.tets(0).unwrap().is_empty());
}

#[test]
fn closed_surfaces_and_files_give_solids() {
    let cube = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
        [0.0, 1.0, 1.0],
    ];
    let faces = [
        [0, 2, 1],
        [0, 3, 2],
        [4, 5, 6],
        [4, 6, 7],
        [0, 1, 5],
        [0, 5, 4],
        [1, 2, 6],
        [1, 6, 5],
        [2, 3, 7],
        [2, 7, 6],
        [3, 0, 4],
        [3, 4, 7],
    ];
    let def = HierarchyDef { tet_cell_size: 0.4, ..HierarchyDef::default() };
    let filled = Hierarchy::from_closed_surface_with(&def, &cube, &faces).unwrap();
    assert!(filled.is_solid());
    let x = filled.rest_positions(0).unwrap();
    let volume: f64 = filled.tets(0).unwrap().iter().map(|&t| tet_volume(&x, t)).sum();
    assert!((volume - 1.0).abs() < 1e-12, "volume {volume}");
    let open = Hierarchy::from_closed_surface_with(&def, &cube, &faces[..11]).unwrap_err();
    assert_eq!(open.code, Status::InvalidMesh);
    assert!(open.message.contains("not closed"), "{}", open.message);
    let bad = HierarchyDef { tet_cell_size: -1.0, ..HierarchyDef::default() };
    let error = Hierarchy::from_closed_surface_with(&bad, &cube, &faces).unwrap_err();
    assert_eq!(error.code, Status::InvalidArgument);
    assert!(error.message.contains("tet_cell_size"), "{}", error.message);

    // The box as a Medit file (1-based indices, reference 0).
    let (vertices, tets) = tet_box(2);
    let mut text = format!("MeshVersionFormatted 2\nDimension 3\nVertices\n{}\n", vertices.len());
    for [x, y, z] in &vertices {
        text += &format!("{x:?} {y:?} {z:?} 0\n");
    }
    text += &format!("Tetrahedra\n{}\n", tets.len());
    for [a, b, c, d] in &tets {
        text += &format!("{} {} {} {} 0\n", a + 1, b + 1, c + 1, d + 1);
    }
    text += "End\n";
    let dir = scratch_dir("solids");
    let path = dir.join("box.mesh");
    std::fs::write(&path, text).unwrap();
    let from_file = Hierarchy::solid_from_file(&path).unwrap();
    assert!(from_file.is_solid());
    assert_eq!(from_file.tets(0).unwrap(), tets);
    assert_eq!(from_file.rest_positions(0).unwrap(), vertices);
    let missing = Hierarchy::solid_from_file(dir.join("missing.mesh")).unwrap_err();
    assert_eq!(missing.code, Status::Io);
    assert!(missing.message.contains("missing.mesh"), "{}", missing.message);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn bad_tets_and_shell_only_calls_fail_clearly() {
    let (vertices, tets) = tet_box(4);
    let mut bad = tets.clone();
    bad[3][2] = 125;
    let error = Hierarchy::from_tets(&vertices, &bad).unwrap_err();
    assert_eq!(error.code, Status::InvalidMesh);
    assert!(error.message.contains("tet 3 references vertex 125"), "{}", error.message);
    let mut inverted = tets.clone();
    inverted[7].swap(1, 2);
    let error = Hierarchy::from_tets(&vertices, &inverted).unwrap_err();
    assert_eq!(error.code, Status::InvalidMesh);
    assert!(error.message.contains("tet 7") && error.message.contains("inverted"), "{error}");
    let error = Hierarchy::from_tets(&vertices, &[]).unwrap_err();
    assert_eq!(error.code, Status::InvalidMesh);
    let def = HierarchyDef {
        coarse_vertex_counts: vec![26],
        tet_size_factor: -1.0,
        ..HierarchyDef::default()
    };
    let error = Hierarchy::from_tets_with(&def, &vertices, &tets).unwrap_err();
    assert_eq!(error.code, Status::InvalidArgument);
    assert!(error.message.contains("size_factor"), "{}", error.message);

    let hierarchy = box_levels();
    let dir = scratch_dir("solids-save");
    let error = hierarchy.save(dir.join("box.hierarchy")).unwrap_err();
    assert_eq!(error.code, Status::Unsupported);
    assert!(error.message.contains("solid"), "{}", error.message);
    assert!(!dir.join("box.hierarchy").exists());
    let _ = std::fs::remove_dir_all(dir);
    assert_eq!(hierarchy.num_expansion_batches(0).unwrap_err().code, Status::Unsupported);
    assert_eq!(hierarchy.tets(2).unwrap_err().code, Status::OutOfRange);

    // A cloth's effects (the default) on a solid, and a quasistatic solid on several levels.
    let error = Simulation::new(&hierarchy, &SimulationDef::default()).unwrap_err();
    assert_eq!(error.code, Status::InvalidScene);
    assert!(error.message.contains("membrane"), "{}", error.message);
    let def = SimulationDef {
        effects: Effect::Elasticity.into(),
        mode: Mode::Quasistatic,
        ..SimulationDef::default()
    };
    let error = Simulation::new(&hierarchy, &def).unwrap_err();
    assert_eq!(error.code, Status::Unsupported);
    assert!(error.message.contains("quasistatic"), "{}", error.message);
}

/// Implicit Euler from rest under gravity along −z: z_n − z_0 = −g h² n(n+1)/2.
fn fallen(n: usize) -> f64 {
    -G * H * H * (n * (n + 1)) as f64 / 2.0
}

#[test]
fn vpd_animates_a_free_fall_on_both_levels() {
    let hierarchy = box_levels();
    let def = SimulationDef {
        effects: Effect::Elasticity | Effect::Gravity,
        gravity: [0.0, 0.0, -G],
        newton_tolerance: 1e-12,
        ..SimulationDef::default()
    };
    let mut sim = Simulation::new(&hierarchy, &def).unwrap();
    assert_eq!(sim.kind().unwrap(), SimulationKind::VolumetricDynamics);
    sim.step_preview(STEPS as u32).unwrap();
    sim.refine().unwrap();
    assert_eq!(sim.current_level(), 1);
    for level in 0..2 {
        assert_eq!(sim.num_frames(level).unwrap(), STEPS + 1);
        let rest = hierarchy.rest_positions(level).unwrap();
        for frame in sim.frames(level).unwrap() {
            let frame = frame.unwrap();
            let n = frame.index;
            assert_eq!(frame.positions.len(), rest.len());
            for (x, x0) in frame.positions.iter().zip(&rest) {
                assert!(x.iter().all(|c| c.is_finite()));
                assert!((x[0] - x0[0]).abs() < 1e-9 && (x[1] - x0[1]).abs() < 1e-9);
                assert!((x[2] - x0[2] - fallen(n)).abs() < 1e-8, "level {level} frame {n}");
            }
        }
        let stats = sim.step_stats(level).unwrap();
        assert_eq!(stats.len(), STEPS);
        let start = stats[0].center_of_mass[2] - fallen(1);
        for (k, step) in stats.iter().enumerate() {
            assert!(step.converged);
            assert!((step.center_of_mass[2] - start - fallen(k + 1)).abs() < 1e-9);
        }
        // ≈ g t²/2: implicit Euler's drop is (n + 1)/n times it after n steps
        let t = STEPS as f64 * H;
        let drop = start - stats[STEPS - 1].center_of_mass[2];
        let expected = G * t * t / 2.0 * (STEPS + 1) as f64 / STEPS as f64;
        assert!((drop - expected).abs() < 1e-9, "level {level}: fell {drop} m");
        assert_eq!(sim.dynamic_level_stats(level).unwrap().vertices, rest.len());
    }
    assert_eq!(sim.refine().unwrap_err().code, Status::OutOfRange);
    sim.restart().unwrap();
    assert_eq!(sim.current_level(), 0);
    assert_eq!(sim.num_frames(0).unwrap(), 1);
}

#[test]
fn a_scene_mixing_a_cloth_and_a_jelly_runs_directly() {
    let mut sim = Simulation::from_scene_file(repo_path("scenes/cloth_on_jelly.json")).unwrap();
    assert_eq!(sim.kind().unwrap(), SimulationKind::Direct);
    let start = sim.positions(0).unwrap();
    assert_eq!(start.len(), 216 + 441, "the jelly's tet vertices, then the cloth's");
    sim.step_preview(3).unwrap();
    let moved = sim.positions(0).unwrap();
    assert!(moved.iter().flatten().all(|c| c.is_finite()));
    let mean_y = |x: &[[f64; 3]]| x.iter().map(|p| p[1]).sum::<f64>() / x.len() as f64;
    assert!(mean_y(&moved[216..]) < mean_y(&start[216..]), "the cloth falls along −y");
    assert!(moved[..216].iter().all(|p| p[1] > 0.0), "the jelly stays on the ground");
}

#[test]
fn a_volumetric_scene_animates_with_vpd() {
    let mut sim = Simulation::from_scene_file(repo_path("scenes/vpd_jelly_drop.json")).unwrap();
    assert_eq!(sim.kind().unwrap(), SimulationKind::VolumetricDynamics);
    let hierarchy = sim.hierarchy().expect("a scene owns its hierarchy");
    assert!(hierarchy.is_solid());
    assert_eq!(hierarchy.num_levels(), 3);
    assert_eq!(hierarchy.level_size(2).unwrap().0, 729);
    assert_eq!(hierarchy.tets(2).unwrap().len(), 3072);
    sim.step_preview(2).unwrap();
    let first = sim.frame_positions(0, 0).unwrap();
    let last = sim.frame_positions(0, 2).unwrap();
    assert!(last.iter().flatten().all(|c| c.is_finite()));
    let mean_y = |x: &[[f64; 3]]| x.iter().map(|p| p[1]).sum::<f64>() / x.len() as f64;
    assert!(mean_y(&last) < mean_y(&first), "the jelly falls along −y");
}

#[test]
fn a_handle_box_holds_each_levels_own_vertices() {
    let hierarchy = box_levels();
    let def = SimulationDef {
        effects: Effect::Elasticity | Effect::Gravity,
        gravity: [0.0, 0.0, -G],
        ..SimulationDef::default()
    };
    let mut sim = Simulation::new(&hierarchy, &def).unwrap();
    let error = sim.add_handle_box(0, [0.02, -1.0, -1.0], [0.01, 1.0, 1.0]).unwrap_err();
    assert_eq!(error.code, Status::InvalidArgument);
    let error = sim.add_handle_box(0, [5.0; 3], [6.0; 3]).unwrap_err();
    assert_eq!(error.code, Status::InvalidScene);
    assert!(error.message.contains("holds no vertex"), "{}", error.message);
    assert_eq!(sim.add_handle_box(0, [-0.01, -1.0, -1.0], [0.01, 1.0, 1.0]).unwrap(), 0);
    sim.step_preview(3).unwrap();
    sim.refine().unwrap();
    for level in 0..2 {
        let rest = hierarchy.rest_positions(level).unwrap();
        let x = sim.positions(level).unwrap();
        let held: Vec<usize> = (0..rest.len()).filter(|&v| rest[v][0].abs() <= 0.01).collect();
        assert!(held.len() >= 4, "level {level}: {} held", held.len());
        assert!(held.iter().all(|&v| x[v] == rest[v]), "level {level}: a held vertex moved");
        assert!((0..rest.len()).any(|v| x[v][2] < rest[v][2]), "level {level}: nothing sags");
    }
}

#[test]
fn a_load_box_pushes_each_levels_own_vertices() {
    // Without gravity, a box around the whole solid with a total force F spread by mass
    // accelerates every vertex of level l at a_l = F / (ρ V_l), V_l the level's own tet volume.
    // The refined level's steps take the preview's velocity (VPD's velocity-only prediction,
    // x̂ = xᵗ + h U v₀ᵗ): z_n − z_0 = −h² (a₀ n(n−1)/2 + a₁ n).
    let hierarchy = box_levels();
    let def = SimulationDef {
        effects: Effect::Elasticity.into(),
        density: 200.0,
        newton_tolerance: 1e-12,
        ..SimulationDef::default()
    };
    let mut sim = Simulation::new(&hierarchy, &def).unwrap();
    let force = 3.0;
    let whole =
        Load { force: [0.0, 0.0, -force], region: Some([[-1.0; 3], [1.0; 3]]), ..Load::default() };
    let both = Load { vertices: vec![0], ..whole.clone() };
    let error = sim.add_load(&both).unwrap_err();
    assert_eq!(error.code, Status::InvalidArgument);
    assert!(error.message.contains("not both"), "{}", error.message);
    let empty = Load { region: Some([[5.0; 3], [6.0; 3]]), ..whole.clone() };
    let error = sim.add_load(&empty).unwrap_err();
    assert_eq!(error.code, Status::InvalidScene);
    assert!(error.message.contains("holds no vertex"), "{}", error.message);
    assert_eq!(sim.add_load(&whole).unwrap(), 0);
    sim.step_preview(4).unwrap();
    sim.refine().unwrap();
    let acceleration = |level: usize| {
        let rest = hierarchy.rest_positions(level).unwrap();
        let tets = hierarchy.tets(level).unwrap();
        force / (def.density * tets.iter().map(|&t| tet_volume(&rest, t)).sum::<f64>())
    };
    let a = [acceleration(0), acceleration(1)];
    assert!((a[1] / a[0] - 1.0).abs() > 1e-3, "else the prediction rule goes untested");
    for level in 0..2 {
        let rest = hierarchy.rest_positions(level).unwrap();
        for frame in sim.frames(level).unwrap() {
            let frame = frame.unwrap();
            let n = frame.index as f64;
            for (x, x0) in frame.positions.iter().zip(&rest) {
                assert!((x[0] - x0[0]).abs() < 1e-9 && (x[1] - x0[1]).abs() < 1e-9);
                let expected = -H * H * (a[0] * n * (n - 1.0) / 2.0 + a[level] * n);
                assert!((x[2] - x0[2] - expected).abs() < 1e-8, "level {level} frame {n}");
            }
        }
    }
}
