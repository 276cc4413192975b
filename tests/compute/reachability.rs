//! Reachability maps (issue 49) against computations written here: the sample poses from the
//! issue's formulas, a forward-kinematics check of every posture bit set on sampled entries, and
//! a brute-force Newton search from many random starts (the test's own finite differences) on
//! sampled entries that are not reached; bad input refused before any work.

use crate::common::closed_form::newton_on;
use armlab::kinematics::models::built_in;
use armlab::kinematics::{Pose, Robot};
use armlab::reachability::{
    MapControl, MapOptions, MapSolver, ReachabilityError, ReachabilityMap, compute_reachability,
    fibonacci_directions, plan_grid, roll_angles, sample_rotation, solutions_at,
};
use nalgebra::{Matrix3, Rotation3, Translation3, Unit, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

#[test]
fn the_sample_poses_follow_the_issues_formulas() {
    for n in [1usize, 7, 200] {
        let d = fibonacci_directions(n);
        for (i, v) in d.iter().enumerate() {
            let z = 1.0 - (2.0 * i as f64 + 1.0) / n as f64;
            let rho = (1.0 - z * z).sqrt();
            let phi = i as f64 * PI * (3.0 - 5f64.sqrt());
            let want = [rho * phi.cos(), rho * phi.sin(), z];
            for a in 0..3 {
                assert!(
                    (v[a] - want[a]).abs() < 1e-14,
                    "n {n} i {i}: {v:?} vs {want:?}"
                );
            }
        }
    }
    let rolls = roll_angles(8);
    assert_eq!(rolls.len(), 8);
    for (j, r) in rolls.iter().enumerate() {
        assert!((r - 2.0 * PI * j as f64 / 8.0).abs() < 1e-15);
    }
    // The tool frame: z = d, x = e - (e.d) d normalised and turned by r about d.
    for d in fibonacci_directions(50)
        .into_iter()
        .chain([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])
    {
        let dv = Vector3::from(d);
        let e = if dv.x.abs() > 0.9 {
            Vector3::y()
        } else {
            Vector3::x()
        };
        let x0 = (e - dv * e.dot(&dv)).normalize();
        for r in roll_angles(8) {
            let turn = Rotation3::from_axis_angle(&Unit::new_normalize(dv), r);
            let x = turn * x0;
            let want = Matrix3::from_columns(&[x, dv.cross(&x), dv]);
            let got = sample_rotation(d, r);
            assert!((got.matrix() - want).amax() < 1e-12, "d {d:?} r {r}");
            assert!((got.matrix().determinant() - 1.0).abs() < 1e-12);
        }
    }
}

/// A small map of the Puma 560.
fn puma_map(robot: &Robot) -> (ReachabilityMap, MapOptions) {
    let opts = MapOptions {
        voxel_m: 0.2,
        directions: 24,
        rolls: 3,
        ..MapOptions::default()
    };
    let map = compute_reachability(robot, &opts, None, MapControl::default()).expect("a map");
    (map, opts)
}

/// The test's own forward kinematics of `robot` as a 4x4 matrix.
fn fk4(robot: &Robot) -> impl Fn(&[f64]) -> nalgebra::Matrix4<f64> + '_ {
    move |q: &[f64]| robot.fk(q).expect("fk").to_homogeneous()
}

/// The sample pose of flat sample `s`, from the grid and the formulas (not the map's helper).
fn pose_of(map: &ReachabilityMap, s: usize) -> Pose {
    let (n, r) = (map.directions.len(), map.rolls.len());
    let (v, d, j) = (s / (n * r), s / r % n, s % r);
    let [nx, ny, nz] = map.grid.dims;
    assert!(v < nx * ny * nz);
    let (i, jj, k) = (v / (ny * nz), v / nz % ny, v % nz);
    let c = [
        map.grid.origin[0] + map.grid.voxel_m * i as f64,
        map.grid.origin[1] + map.grid.voxel_m * jj as f64,
        map.grid.origin[2] + map.grid.voxel_m * k as f64,
    ];
    let rot = sample_rotation(fibonacci_directions(n)[d], 2.0 * PI * j as f64 / r as f64);
    Pose::from_parts(Translation3::new(c[0], c[1], c[2]), rot)
}

#[test]
fn every_posture_bit_set_is_a_solution_within_the_limits() {
    let puma = built_in("puma560").expect("puma");
    let (map, opts) = puma_map(&puma);
    assert!(matches!(map.solver, MapSolver::ClosedForm { .. }));
    assert_eq!(map.posture_names.len(), 8, "{:?}", map.posture_names);
    let reached: Vec<usize> = (0..map.reachable.len())
        .filter(|&s| map.reachable[s])
        .collect();
    assert!(reached.len() > 1000, "{} reached", reached.len());
    let mut rng = ChaCha8Rng::seed_from_u64(49);
    for _ in 0..300 {
        let s = reached[rng.random_range(0..reached.len())];
        let pose = pose_of(&map, s);
        let sols = solutions_at(&puma, &map, &opts, None, &pose);
        let mut bits = 0u16;
        for sol in &sols {
            let t = puma.fk(&sol.q).expect("fk");
            let gap = (t.to_homogeneous() - pose.to_homogeneous()).amax();
            assert!(gap < 1e-9, "sample {s}: {} misses by {gap}", sol.label);
            assert!(puma.within_limits(&sol.q, 1e-12), "{:?}", sol.q);
            // A non-degenerate solution sets exactly the bit of its own label.
            if sol.mask.count_ones() == 1 {
                let b = sol.mask.trailing_zeros() as usize;
                assert_eq!(map.posture_names[b], sol.label);
            }
            bits |= sol.mask;
        }
        assert_eq!(bits, map.postures[s], "sample {s}");
        assert_ne!(bits, 0);
    }
    // Index: the fraction of each voxel's samples reached.
    let per = map.per_voxel();
    for (v, &x) in map.index().iter().enumerate() {
        let count = map.reachable[v * per..(v + 1) * per]
            .iter()
            .filter(|&&b| b)
            .count();
        assert!((x - count as f64 / per as f64).abs() < 1e-15);
    }
}

#[test]
fn nothing_reachable_is_missed_by_a_brute_force_search() {
    let puma = built_in("puma560").expect("puma");
    let (map, _) = puma_map(&puma);
    let limits = puma.limits();
    let fk = fk4(&puma);
    let mut rng = ChaCha8Rng::seed_from_u64(4949);
    // Unreached samples near reached ones are the hard cases: take samples of voxels whose
    // index is strictly between 0 and 1, and some from empty voxels inside the grid.
    let per = map.per_voxel();
    let index = map.index();
    let partial: Vec<usize> = (0..index.len())
        .filter(|&v| index[v] > 0.0 && index[v] < 1.0)
        .collect();
    assert!(!partial.is_empty());
    let mut checked = 0;
    while checked < 40 {
        let v = partial[rng.random_range(0..partial.len())];
        let s = v * per + rng.random_range(0..per);
        if map.reachable[s] {
            continue;
        }
        checked += 1;
        let pose = pose_of(&map, s);
        for _ in 0..150 {
            let q0: Vec<f64> = (0..6).map(|_| rng.random_range(-PI..PI)).collect();
            if let Some(q) = newton_on(&fk, &pose, q0) {
                // A solution: every joint, turned by whole turns, must fall outside its limits
                // for the map to be right.
                let inside = q.iter().zip(&limits).all(|(&x, &[lo, hi])| {
                    (-3..=3).any(|k| {
                        let y = x + 2.0 * PI * k as f64;
                        y >= lo - 1e-9 && y <= hi + 1e-9
                    })
                });
                assert!(!inside, "sample {s}: {q:?} reaches it within the limits");
            }
        }
    }
}

#[test]
fn the_grid_covers_every_point_the_arm_reaches() {
    let puma = built_in("puma560").expect("puma");
    let (map, _) = puma_map(&puma);
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let limits = puma.limits();
    let centre = Vector3::from(map.reach_centre);
    for _ in 0..5000 {
        let q: Vec<f64> = limits
            .iter()
            .map(|&[lo, hi]| rng.random_range(lo..hi))
            .collect();
        let p = puma.fk(&q).expect("fk").translation.vector;
        let v = map.grid.voxel_at(p.into());
        assert!(v.is_some(), "{p:?} outside the grid {:?}", map.grid);
        assert!((p - centre).norm() < map.reach_m - map.grid.voxel_m);
    }
}

#[test]
fn bad_input_is_refused_before_any_work() {
    let puma = built_in("puma560").expect("puma");
    let calls = AtomicUsize::new(0);
    let progress = |_: usize, _: usize| {
        calls.fetch_add(1, Ordering::Relaxed);
    };
    let control = MapControl {
        cancel: None,
        progress: Some(&progress),
    };
    let run = |opts: MapOptions| compute_reachability(&puma, &opts, None, control).unwrap_err();
    for v in [0.0, -0.1, f64::NAN, f64::INFINITY] {
        let e = run(MapOptions {
            voxel_m: v,
            ..MapOptions::default()
        });
        assert!(matches!(e, ReachabilityError::BadVoxel { .. }), "{e}");
    }
    let e = run(MapOptions {
        directions: 0,
        ..MapOptions::default()
    });
    assert!(e.to_string().contains("directions"), "{e}");
    let e = run(MapOptions {
        rolls: 0,
        ..MapOptions::default()
    });
    assert!(e.to_string().contains("rolls"), "{e}");
    let big = MapOptions {
        voxel_m: 0.005,
        ..MapOptions::default()
    };
    let e = run(big);
    assert!(
        matches!(e, ReachabilityError::TooManySamples { samples, .. } if samples > 1_000_000_000),
        "{e}"
    );
    assert!(e.to_string().contains("over the limit"), "{e}");
    assert_eq!(calls.load(Ordering::Relaxed), 0, "work started");
    // plan_grid says the same without computing.
    assert!(plan_grid(&puma, &big).is_err());
    let ok = plan_grid(&puma, &MapOptions::default()).expect("a grid");
    assert!(ok.len() > 1000);
}

#[test]
fn a_cancelled_map_stops_with_an_error() {
    let puma = built_in("puma560").expect("puma");
    let stop = AtomicBool::new(false);
    let progress = |done: usize, _: usize| {
        if done >= 10 {
            stop.store(true, Ordering::Relaxed);
        }
    };
    let control = MapControl {
        cancel: Some(&stop),
        progress: Some(&progress),
    };
    let opts = MapOptions {
        voxel_m: 0.1,
        directions: 50,
        rolls: 2,
        ..MapOptions::default()
    };
    match compute_reachability(&puma, &opts, None, control) {
        Err(ReachabilityError::Cancelled { done, total }) => assert!(done < total),
        other => panic!("{other:?}"),
    }
}

#[test]
fn arms_without_a_closed_form_use_the_numerical_solver_and_say_so() {
    let panda = built_in("panda").expect("panda");
    let opts = MapOptions {
        voxel_m: 0.35,
        directions: 6,
        rolls: 1,
        seeds: 3,
        ..MapOptions::default()
    };
    let map = compute_reachability(&panda, &opts, None, MapControl::default()).expect("a map");
    assert!(matches!(map.solver, MapSolver::Numerical { seeds: 3, .. }));
    assert!(map.solver.describe().contains("numerical"));
    let reached: Vec<usize> = (0..map.reachable.len())
        .filter(|&s| map.reachable[s])
        .collect();
    assert!(!reached.is_empty());
    for &s in reached.iter().take(10) {
        let pose = pose_of(&map, s);
        let sols = solutions_at(&panda, &map, &opts, None, &pose);
        assert!(!sols.is_empty());
        for sol in sols {
            let gap =
                (panda.fk(&sol.q).expect("fk").to_homogeneous() - pose.to_homogeneous()).amax();
            assert!(gap < 1e-8, "{gap}");
            assert!(panda.within_limits(&sol.q, 1e-12));
        }
    }
}
