//! Base placement (issue 49), checked against computations written here:
//! - every posture bit set at sampled placements of the UR5 and the Puma 560: the forward
//!   kinematics of the reported joint vector, on the robot moved by a shift composed here,
//!   lands on the task to 1e-9 and lies within the limits;
//! - entries with no bit set next to entries with some (the edge of what reaches): a
//!   brute-force search written here (projected damped least squares from 64 random starts
//!   within the limits, on the moved robot) finds no solution within 1e-6 m and 1e-6 rad;
//! - hand-checkable arms: the two-link planar arm's heat map is the count of tasks within
//!   2 m; three tasks 1.98 m around a point are reached together only there; a two-link arm with
//!   q1 in [0, 20] degrees reaches a task at 1.5 m only at the yaws its geometry allows;
//! - a wall in a scene: no base on its near side reaches a task behind it, a base whose
//!   pedestal (attached to the base) is inside it is blocked, the floor under the pedestal is
//!   its mounting;
//! - the task file: both layouts, the header, the degrees, and errors naming line and field;
//! - bad options are errors before any work; a raised cancel flag stops it.

use armlab::collision::{CellScene, CollisionWorld};
use armlab::kinematics::arm::arm_of;
use armlab::kinematics::models::built_in;
use armlab::kinematics::{Pose, Robot};
use armlab::reachability::{
    PlacementError, PlacementGrid, PlacementMap, PlacementOptions, PlacementSolver, PlacementTask,
    Placer, TaskFileError, TaskMatch, parse_tasks, place,
};
use nalgebra::{DMatrix, DVector, Matrix3, Rotation3, Translation3, Vector3};
use std::f64::consts::PI;
use std::path::Path;
use std::sync::atomic::AtomicBool;

fn ur5() -> Robot {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/urdf_corpus/ur5_robot.urdf");
    let robot = armlab::model_file::load_model(path.to_str().unwrap()).unwrap();
    arm_of(&robot, 0, &robot.ready_or_zero()).unwrap().robot
}

/// The robot with its base moved to `Trans(x, y, 0) Rz(yaw) base`, composed here.
fn moved(robot: &Robot, x: f64, y: f64, yaw: f64) -> Robot {
    let mut m = robot.clone();
    let shift = Pose::from_parts(
        Translation3::new(x, y, 0.0),
        Rotation3::from_axis_angle(&Vector3::z_axis(), yaw),
    );
    m.base = shift * robot.base;
    m
}

/// Twelve tasks: the tool at twelve spread configurations, seen from base (0.3, -0.2) at 40
/// degrees.
fn tasks_of(robot: &Robot) -> Vec<PlacementTask> {
    let from = moved(robot, 0.3, -0.2, 40f64.to_radians());
    (0..12)
        .map(|k| {
            let t = k as f64;
            let q = [
                0.5 * (t * 0.7).sin(),
                -0.9 + 0.3 * (t * 1.3).cos(),
                1.2 + 0.4 * (t * 0.9).sin(),
                -1.5 + 0.5 * (t * 1.7).cos(),
                -1.4 + 0.6 * (t * 0.5).sin(),
                0.8 * t,
            ];
            PlacementTask::new(format!("t{k}"), from.fk(&q).unwrap())
        })
        .collect()
}

fn run(
    robot: &Robot,
    tasks: &[PlacementTask],
    world: Option<&CollisionWorld>,
    options: &PlacementOptions,
) -> PlacementMap {
    place(
        robot,
        tasks,
        world,
        options,
        &AtomicBool::new(false),
        &|_| {},
    )
    .unwrap()
}

/// Position error (m) and orientation error (rad, the angle of `R_d R^T`).
fn pose_gap(a: &Pose, b: &Pose) -> (f64, f64) {
    let dp = (a.translation.vector - b.translation.vector).norm();
    let r = a.rotation.matrix() * b.rotation.matrix().transpose();
    let c = ((r.trace() - 1.0) / 2.0).clamp(-1.0, 1.0);
    let s = Vector3::new(
        r[(2, 1)] - r[(1, 2)],
        r[(0, 2)] - r[(2, 0)],
        r[(1, 0)] - r[(0, 1)],
    )
    .norm()
        / 2.0;
    (dp, s.atan2(c))
}

fn within(robot: &Robot, q: &[f64], tol: f64) -> bool {
    robot
        .limits()
        .iter()
        .zip(q)
        .all(|(&[lo, hi], &v)| v >= lo - tol && v <= hi + tol)
}

/// Every bit set at a sample of placements: a solution of that bit, whose forward kinematics on
/// the moved robot lands on the task; the detail's masks are the map's.
fn check_bits(robot: &Robot, tasks: &[PlacementTask], map: &PlacementMap, every: usize) -> usize {
    let placer = Placer::new(robot, tasks, None, 8).unwrap();
    let mut checked = 0;
    for p in (0..map.grid.placements()).step_by(every) {
        let [i, j, k] = map.grid.ijk(p);
        let (x, y, yaw) = (map.grid.x[i], map.grid.y[j], map.grid.yaw[k]);
        let detail = placer.evaluate(x, y, yaw);
        let m = moved(robot, x, y, yaw);
        for (t, reach) in detail.tasks.iter().enumerate() {
            assert_eq!(
                reach.mask,
                map.mask(i, j, k, t),
                "({x}, {y}, {yaw}) task {t}"
            );
            let mut bits = 0u16;
            for s in &reach.solutions {
                let (dp, da) = pose_gap(&m.fk(&s.q).unwrap(), &tasks[t].world_from_tool);
                assert!(
                    dp < 1e-9 && da < 1e-9,
                    "{dp:e} m, {da:e} rad at {x} {y} {yaw}"
                );
                assert!(within(robot, &s.q, 1e-12), "{:?}", s.q);
                bits |= s.classes;
                checked += 1;
            }
            assert_eq!(bits, reach.mask);
        }
    }
    checked
}

/// Pose error `[p_d - p; 0.5 (n x n_d + s x s_d + a x a_d)]` (3.85) of the moved robot at q.
fn error6(robot: &Robot, q: &[f64], goal: &Pose) -> DVector<f64> {
    let t = robot.fk(q).unwrap();
    let dp = goal.translation.vector - t.translation.vector;
    let (r, rd): (Matrix3<f64>, Matrix3<f64>) = (*t.rotation.matrix(), *goal.rotation.matrix());
    let mut eo = Vector3::zeros();
    for c in 0..3 {
        eo += r.column(c).cross(&rd.column(c)) * 0.5;
    }
    DVector::from_row_slice(&[dp.x, dp.y, dp.z, eo.x, eo.y, eo.z])
}

/// Brute force: damped least squares with a finite-difference Jacobian, each step projected
/// into the limits, from `starts` random configurations within them. The best errors found.
fn brute_force(robot: &Robot, goal: &Pose, starts: usize, seed: u64) -> (f64, f64) {
    let limits = robot.limits();
    let mut state = seed;
    let mut uniform = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut best = (f64::INFINITY, f64::INFINITY);
    for _ in 0..starts {
        let mut q: Vec<f64> = limits
            .iter()
            .map(|&[lo, hi]| {
                let (lo, hi) = (lo.max(-2.0 * PI), hi.min(2.0 * PI));
                lo + (hi - lo) * uniform()
            })
            .collect();
        for _ in 0..200 {
            let e = error6(robot, &q, goal);
            if e.norm() < 1e-12 {
                break;
            }
            let mut jac = DMatrix::zeros(6, q.len());
            for c in 0..q.len() {
                let mut qh = q.clone();
                qh[c] += 1e-7;
                let col = (&e - error6(robot, &qh, goal)) / 1e-7;
                jac.set_column(c, &col);
            }
            let lambda2 = 1e-4;
            let jjt = &jac * jac.transpose() + DMatrix::identity(6, 6) * lambda2;
            let Some(step) = jjt.lu().solve(&e) else {
                break;
            };
            let dq = jac.transpose() * step;
            for (c, v) in q.iter_mut().enumerate() {
                *v = (*v + dq[c].clamp(-0.5, 0.5)).clamp(limits[c][0], limits[c][1]);
            }
        }
        let (dp, da) = pose_gap(&robot.fk(&q).unwrap(), goal);
        if dp.max(da) < best.0.max(best.1) {
            best = (dp, da);
        }
    }
    best
}

/// (placement, task) entries with no bit set whose grid neighbour in x or y has one.
fn edge_entries(map: &PlacementMap, most: usize) -> Vec<([usize; 3], usize)> {
    let g = &map.grid;
    let mut out = Vec::new();
    for p in 0..g.placements() {
        let [i, j, k] = g.ijk(p);
        for t in 0..map.tasks.len() {
            if map.mask(i, j, k, t) != 0 {
                continue;
            }
            let near = [(1, 0), (0, 1)].iter().any(|&(di, dj)| {
                let (a, b) = (i + di, j + dj);
                a < g.x.len() && b < g.y.len() && map.mask(a, b, k, t) != 0
            });
            if near && p % 7 == t % 7 {
                out.push(([i, j, k], t));
            }
        }
    }
    out.truncate(most);
    out
}

fn check_unset(robot: &Robot, map: &PlacementMap, most: usize) {
    let entries = edge_entries(map, most);
    assert!(
        entries.len() >= most / 2,
        "too few edge entries: {}",
        entries.len()
    );
    for ([i, j, k], t) in entries {
        let (x, y, yaw) = (map.grid.x[i], map.grid.y[j], map.grid.yaw[k]);
        let m = moved(robot, x, y, yaw);
        let (dp, da) = brute_force(&m, &map.tasks[t].world_from_tool, 64, (i * 131 + j) as u64);
        assert!(
            dp > 1e-6 || da > 1e-6,
            "({x}, {y}, {:.0} deg) task {t}: the search found a solution ({dp:e} m, {da:e} rad)",
            yaw.to_degrees()
        );
    }
}

fn coarse() -> PlacementOptions {
    PlacementOptions {
        area: [-1.0, 1.0, -1.0, 1.0],
        step: 0.25,
        yaws: 8,
        ..PlacementOptions::default()
    }
}

#[test]
fn ur5_every_bit_set_is_a_solution_on_the_moved_robot() {
    let robot = ur5();
    let tasks = tasks_of(&robot);
    let map = run(&robot, &tasks, None, &coarse());
    assert!(matches!(map.solver, PlacementSolver::ClosedForm { .. }));
    assert_eq!(map.task_match, TaskMatch::Pose);
    assert_eq!(map.posture_names.len(), 8, "{:?}", map.posture_names);
    let checked = check_bits(&robot, &tasks, &map, 5);
    assert!(checked > 200, "only {checked} solutions checked");
}

#[test]
fn ur5_entries_without_bits_have_no_solution_by_brute_force() {
    let robot = ur5();
    let tasks = tasks_of(&robot);
    let map = run(&robot, &tasks, None, &coarse());
    check_unset(&robot, &map, 8);
}

#[test]
fn puma_bits_and_edges_within_its_joint_limits() {
    let robot = built_in("puma560").unwrap();
    let tasks = tasks_of(&robot);
    let map = run(&robot, &tasks, None, &coarse());
    assert_eq!(map.posture_names.len(), 8, "{:?}", map.posture_names);
    // Its limits cut postures off: some reached tasks are reached by fewer than eight.
    let partial = map
        .masks
        .iter()
        .filter(|&&m| m != 0 && m.count_ones() < 8)
        .count();
    assert!(partial > 0);
    assert!(check_bits(&robot, &tasks, &map, 3) > 100);
    check_unset(&robot, &map, 8);
}

#[test]
fn the_two_link_heat_map_counts_the_tasks_within_two_metres() {
    let arm = built_in("planar2").unwrap();
    let points = [[1.2, 0.4], [-0.7, 1.5], [0.1, -1.9], [2.5, 2.5]];
    let tasks: Vec<PlacementTask> = points
        .iter()
        .map(|p| PlacementTask::new("p", Pose::translation(p[0], p[1], 0.0)))
        .collect();
    let options = PlacementOptions {
        area: [-1.5, 1.5, -1.5, 1.5],
        step: 0.1,
        yaws: 3,
        ..PlacementOptions::default()
    };
    let map = run(&arm, &tasks, None, &options);
    assert_eq!(map.task_match, TaskMatch::Position);
    assert_eq!((map.grid.x.len(), map.grid.y.len()), (31, 31));
    let heat = map.heat();
    let mut compared = 0;
    for (i, x) in map.grid.x.iter().enumerate() {
        for (j, y) in map.grid.y.iter().enumerate() {
            let d: Vec<f64> = points.iter().map(|p| (p[0] - x).hypot(p[1] - y)).collect();
            if d.iter().any(|d| (d - 2.0).abs() < 1e-6) {
                continue;
            }
            let inside = d.iter().filter(|&&d| d < 2.0).count();
            assert_eq!(heat[i * 31 + j], inside as f64 / 4.0, "({x}, {y})");
            // Yaw does not matter to a position: every yaw reaches as many.
            for k in 0..3 {
                assert_eq!(map.fraction(i, j, k), heat[i * 31 + j]);
            }
            compared += 1;
        }
    }
    assert!(compared > 900);
}

#[test]
fn three_tasks_around_a_point_are_reached_together_only_there() {
    let arm = built_in("planar2").unwrap();
    let c = [0.3, -0.2];
    let tasks: Vec<PlacementTask> = [90.0f64, 210.0, 330.0]
        .iter()
        .map(|a| {
            let (s, co) = a.to_radians().sin_cos();
            PlacementTask::new(
                "p",
                Pose::translation(c[0] + 1.98 * co, c[1] + 1.98 * s, 0.0),
            )
        })
        .collect();
    let map = run(&arm, &tasks, None, &PlacementOptions::default());
    let best = &map.best[0];
    assert_eq!(best.reached, 3);
    assert!((best.detail.x - c[0]).abs() < 1e-9 && (best.detail.y - c[1]).abs() < 1e-9);
    assert_eq!(map.heat().iter().filter(|&&f| f == 1.0).count(), 1);
    // The others reach two tasks at most, and are ranked so.
    assert!(map.best[1..].iter().all(|b| b.reached <= 2));
    assert_eq!(map.best.len(), 5);
}

#[test]
fn a_limited_shoulder_reaches_a_task_only_at_the_yaws_its_geometry_allows() {
    // a1 = a2 = 1 m, q1 in [0, 20] deg (0.349 rad). A task 1.5 m ahead (world bearing 0): the elbow angle
    // has c2 = (1.5^2 - 2) / 2, and q1 = phi -+ atan2(s2, 1 + c2) = phi -+ 41.41 deg, phi the
    // task's bearing in the base frame, -yaw. So yaw in [21.4, 41.4] (s2 < 0: "elbow up") or
    // [-61.4, -41.4] (s2 > 0: "elbow down"): of 36 yaws, 30, 40, 300 and 310 degrees.
    let text = "name = \"limited\"\nconvention = \"standard\"\n\
                [[joints]]\ntype = \"revolute\"\na = 1.0\nalpha = 0.0\nd = 0.0\n\
                limits = [0.0, 0.3490658503988659]\n\
                [[joints]]\ntype = \"revolute\"\na = 1.0\nalpha = 0.0\nd = 0.0\n\
                limits = [\"-pi\", \"pi\"]\n";
    let arm = armlab::model_file::parse_model_text("limited.toml", text).unwrap();
    let c2 = (1.5f64 * 1.5 - 2.0) / 2.0;
    let beta = (1.0 - c2 * c2).sqrt().atan2(1.0 + c2);
    assert!((beta.to_degrees() - 41.41).abs() < 0.01);
    let tasks = [PlacementTask::new(
        "ahead",
        Pose::translation(1.5, 0.0, 0.0),
    )];
    let options = PlacementOptions {
        area: [0.0, 0.01, 0.0, 0.01],
        step: 0.05,
        yaws: 36,
        ..PlacementOptions::default()
    };
    let map = run(&arm, &tasks, None, &options);
    assert_eq!(map.grid.positions(), 1);
    let reached: Vec<usize> = (0..36).filter(|&k| map.mask(0, 0, k, 0) != 0).collect();
    assert_eq!(reached, [3, 4, 30, 31]);
    assert_eq!(map.names_of(map.mask(0, 0, 3, 0)), ["elbow up"]);
    assert_eq!(map.names_of(map.mask(0, 0, 31, 0)), ["elbow down"]);
}

#[test]
fn an_arm_without_a_closed_form_uses_the_numerical_solver() {
    // The four-link planar arm (0.35 + 0.3 + 0.2 + 0.15 = 1 m of reach): positions.
    let arm = built_in("planar4").unwrap();
    let points = [[0.5, 0.2], [-0.4, -0.3]];
    let tasks: Vec<PlacementTask> = points
        .iter()
        .map(|p| PlacementTask::new("p", Pose::translation(p[0], p[1], 0.0)))
        .collect();
    let options = PlacementOptions {
        area: [-0.6, 0.6, -0.6, 0.6],
        step: 0.2,
        yaws: 1,
        ..PlacementOptions::default()
    };
    let map = run(&arm, &tasks, None, &options);
    assert!(matches!(
        map.solver,
        PlacementSolver::Numerical { seeds: 8, .. }
    ));
    assert_eq!(map.task_match, TaskMatch::Position);
    for (i, x) in map.grid.x.iter().enumerate() {
        for (j, y) in map.grid.y.iter().enumerate() {
            for (t, p) in points.iter().enumerate() {
                let d = (p[0] - x).hypot(p[1] - y);
                let m = map.mask(i, j, 0, t);
                if d > 1.0 + 1e-9 {
                    assert_eq!(m, 0, "({x}, {y}) reaches {d} m");
                } else if d < 0.95 {
                    assert_ne!(m, 0, "({x}, {y}) misses {d} m");
                }
            }
        }
    }
    let best = &map.best[0];
    assert_eq!(best.reached, 2);
    let m = moved(&arm, best.detail.x, best.detail.y, best.detail.yaw);
    for (t, reach) in best.detail.tasks.iter().enumerate() {
        for s in &reach.solutions {
            let p = m.fk(&s.q).unwrap().translation.vector;
            let want = tasks[t].world_from_tool.translation.vector;
            assert!((p - want).norm() < 1e-9);
        }
    }
}

/// A wall from x = 0.6 to 0.8 m (6 m wide, z from -1 to 2 m), a pedestal under the base
/// (attached to it: it moves with the base) and the floor the pedestal stands on.
fn wall_scene() -> CellScene {
    let text = "[[obstacle]]\nname = \"pedestal\"\nshape = \"box\"\nsize = [0.3, 0.3, 0.5]\n\
                xyz = [0, 0, -0.35]\nframe = \"base\"\n\n\
                [[obstacle]]\nname = \"wall\"\nshape = \"box\"\nsize = [0.2, 6.0, 3.0]\n\
                xyz = [0.7, 0, 0.5]\n\n\
                [[obstacle]]\nname = \"floor\"\nshape = \"plane\"\nxyz = [0, 0, -0.6]\n";
    CellScene::parse(text, Path::new("wall.toml")).unwrap()
}

#[test]
fn a_wall_keeps_every_base_on_its_near_side_from_the_tasks_behind_it() {
    let robot = built_in("puma560").unwrap();
    let tasks: Vec<PlacementTask> = [0.3f64, 0.5, 0.7]
        .iter()
        .map(|z| PlacementTask::new("behind", Pose::translation(1.15, 0.1, *z) * rot_y_down()))
        .collect();
    let options = PlacementOptions {
        area: [0.0, 1.6, -0.3, 0.3],
        step: 0.1,
        yaws: 8,
        ..PlacementOptions::default()
    };
    let free = run(&robot, &tasks, None, &options);
    let world = CollisionWorld::new(&robot, &wall_scene()).unwrap();
    let walled = run(&robot, &tasks, Some(&world), &options);
    assert!(walled.collisions);
    let g = &walled.grid;
    let (mut near_reached_freely, mut far_reached) = (0, 0);
    for p in 0..g.placements() {
        let [i, _, k] = g.ijk(p);
        let x = g.x[i];
        assert!(walled.reached[p] <= free.reached[p]);
        // The pedestal's square (0.3 m) turned by the yaw spans x +- half in x; its gap to the
        // wall's [0.6, 0.8] (negative: they overlap).
        let (s, c) = g.yaw[k].sin_cos();
        let half = 0.15 * (s.abs() + c.abs());
        let gap = (0.6 - (x + half)).max(x - half - 0.8);
        if gap > 1e-3 {
            assert!(
                !walled.blocked[p],
                "x = {x}: the floor under the pedestal is its mounting"
            );
        } else if gap < -1e-3 {
            assert!(
                walled.blocked[p],
                "x = {x}, yaw {k}: the pedestal is in the wall"
            );
        }
        if x < 0.45 {
            assert_eq!(
                walled.reached[p], 0,
                "base at x = {x} reaches through the wall"
            );
            near_reached_freely += usize::from(free.reached[p] > 0);
        } else if (x - 0.7).abs() < 0.05 {
            assert!(walled.blocked[p], "base at x = {x} inside the wall");
            assert_eq!(walled.reached[p], 0);
        } else if x > 0.95 {
            far_reached += usize::from(walled.reached[p] > 0);
        }
    }
    assert!(
        near_reached_freely > 0,
        "the tasks are within reach without the wall"
    );
    assert!(far_reached > 0, "bases behind the wall reach the tasks");
    let inside = Placer::new(&robot, &tasks, Some(&world), 1)
        .unwrap()
        .evaluate(0.7, 0.0, 0.0);
    assert!(
        inside
            .base_contacts
            .contains(&("pedestal".into(), "wall".into())),
        "{:?}",
        inside.base_contacts
    );
    assert_eq!(inside.reached(), 0);
}

/// The tool pointing down (a half turn about y).
fn rot_y_down() -> Pose {
    Pose::from_parts(
        Translation3::identity(),
        Rotation3::from_axis_angle(&Vector3::y_axis(), PI),
    )
}

#[test]
fn the_grid_includes_both_ends_and_even_yaws() {
    let g = PlacementGrid::new(&PlacementOptions::default(), 12).unwrap();
    assert_eq!((g.x.len(), g.y.len(), g.yaw.len()), (41, 41, 36));
    assert_eq!((g.x[0], g.y[0]), (-1.0, -1.0));
    assert!((g.x[40] - 1.0).abs() < 1e-12);
    assert!((g.yaw[1] - 10f64.to_radians()).abs() < 1e-15);
    let opts = PlacementOptions {
        area: [0.0, 1.03, 0.0, 0.5],
        ..PlacementOptions::default()
    };
    let g = PlacementGrid::new(&opts, 1).unwrap();
    assert_eq!(g.x.len(), 21, "stops at 1.0, the last step before 1.03");
    assert_eq!(g.y.len(), 11);
    assert_eq!(g.ijk(g.index(3, 7, 5)), [3, 7, 5]);
}

#[test]
fn bad_options_are_errors_before_any_work() {
    let arm = built_in("planar2").unwrap();
    let tasks = [PlacementTask::new("p", Pose::translation(1.0, 0.0, 0.0))];
    let cancel = AtomicBool::new(false);
    let with = |f: &dyn Fn(&mut PlacementOptions)| {
        let mut o = PlacementOptions::default();
        f(&mut o);
        place(&arm, &tasks, None, &o, &cancel, &|_| panic!("work started")).unwrap_err()
    };
    assert!(matches!(
        with(&|o| o.area = [1.0, 1.0, 0.0, 1.0]),
        PlacementError::EmptyArea { axis: "x", .. }
    ));
    assert!(matches!(
        with(&|o| o.area = [0.0, 1.0, 0.5, -0.5]),
        PlacementError::EmptyArea { axis: "y", .. }
    ));
    assert!(matches!(
        with(&|o| o.area[1] = f64::NAN),
        PlacementError::NonFiniteArea { .. }
    ));
    for step in [0.0, -0.1, f64::INFINITY, f64::NAN] {
        assert!(matches!(
            with(&|o| o.step = step),
            PlacementError::BadStep { .. }
        ));
    }
    assert_eq!(with(&|o| o.yaws = 0), PlacementError::NoYaws);
    let e = with(&|o| o.step = 1e-4);
    assert!(
        matches!(e, PlacementError::TooManyEvaluations { .. }),
        "{e}"
    );
    assert!(e.to_string().contains("over the limit"), "{e}");
    let none: [PlacementTask; 0] = [];
    let err = place(
        &arm,
        &none,
        None,
        &PlacementOptions::default(),
        &cancel,
        &|_| {},
    );
    assert_eq!(err.unwrap_err(), PlacementError::NoTasks);
    // Forced, the grid is made (nothing computed here).
    let forced = PlacementOptions {
        step: 1e-4,
        force: true,
        ..PlacementOptions::default()
    };
    assert_eq!(PlacementGrid::new(&forced, 1).unwrap().x.len(), 20001);
    // Several end-effectors: place one arm.
    let humanoid = built_in("humanoid").unwrap();
    let err = place(
        &humanoid,
        &tasks,
        None,
        &PlacementOptions::default(),
        &cancel,
        &|_| {},
    );
    assert!(matches!(
        err,
        Err(PlacementError::SeveralEndEffectors { .. })
    ));
}

#[test]
fn a_raised_cancel_flag_stops_the_placement() {
    let arm = built_in("planar2").unwrap();
    let tasks = [PlacementTask::new("p", Pose::translation(1.0, 0.0, 0.0))];
    let cancel = AtomicBool::new(true);
    let err = place(
        &arm,
        &tasks,
        None,
        &PlacementOptions::default(),
        &cancel,
        &|_| {},
    );
    assert_eq!(
        err.unwrap_err(),
        PlacementError::Cancelled {
            done: 0,
            total: 41 * 41
        }
    );
}

#[test]
fn the_best_placements_are_ranked_one_per_position() {
    let robot = ur5();
    let tasks = tasks_of(&robot);
    let map = run(&robot, &tasks, None, &coarse());
    let key = |b: &armlab::reachability::BestPlacement| (b.reached, b.solutions, b.steady);
    assert_eq!(map.best.len(), 5);
    for w in map.best.windows(2) {
        assert!(key(&w[0]) >= key(&w[1]));
        assert_ne!(w[0].index[..2], w[1].index[..2]);
    }
    let top = &map.best[0];
    // Nothing in the grid reaches more tasks, or as many with more solutions.
    let most = (map.reached.iter().zip(&map.solutions))
        .map(|(&r, &s)| (r as usize, s))
        .max()
        .unwrap();
    assert_eq!((top.reached, top.solutions), most);
    let detail_solutions: usize = top.detail.tasks.iter().map(|t| t.solutions.len()).sum();
    assert_eq!(detail_solutions, top.solutions as usize);
    assert_eq!(top.detail.reached(), top.reached);
}

#[test]
fn task_files_read_both_layouts_in_degrees() {
    let text = "# picks\n\n0.5, 0.1, 0.4, 90, 0, 0  # roll a quarter turn\n\
                1 0 0 0.2  0 1 0 0.3  0 0 1 0.4  0 0 0 1\n";
    let tasks = parse_tasks(text, "poses.csv").unwrap();
    assert_eq!(tasks.len(), 2);
    assert_eq!((tasks[0].name.as_str(), tasks[0].line), ("1", 3));
    assert_eq!((tasks[1].name.as_str(), tasks[1].line), ("2", 4));
    // Roll 90 degrees about x: y goes to z.
    let r = tasks[0].world_from_tool.rotation.matrix();
    assert!((r.column(1) - Vector3::new(0.0, 0.0, 1.0)).norm() < 1e-15);
    assert_eq!(tasks[1].world_from_tool.translation.vector.z, 0.4);
    // Fixed-axis roll, pitch, yaw: R = Rz(yaw) Ry(pitch) Rx(roll), composed here.
    let named = "name x y z roll_deg pitch_deg yaw_deg\npick 1 2 3 10 20 30\n";
    let t = &parse_tasks(named, "n.txt").unwrap()[0];
    let (a, b, c) = (10f64.to_radians(), 20f64.to_radians(), 30f64.to_radians());
    let want = Rotation3::from_axis_angle(&Vector3::z_axis(), c)
        * Rotation3::from_axis_angle(&Vector3::y_axis(), b)
        * Rotation3::from_axis_angle(&Vector3::x_axis(), a);
    assert!((t.world_from_tool.rotation.matrix() - want.matrix()).amax() < 1e-15);
    assert_eq!(t.name, "pick");
    let sixteen = "name, t00, t01, t02, t03, t10, t11, t12, t13, t20, t21, t22, t23, t30, t31, \
                   t32, t33\nbox, 1, 0, 0, 0.5, 0, 1, 0, 0, 0, 0, 1, 0.2, 0, 0, 0, 1\n";
    let t = &parse_tasks(sixteen, "m.csv").unwrap()[0];
    assert_eq!(
        (t.name.as_str(), t.world_from_tool.translation.vector.x),
        ("box", 0.5)
    );
}

#[test]
fn task_file_errors_name_the_line_and_the_field() {
    let err = |text: &str| parse_tasks(text, "poses.csv").unwrap_err();
    let e = err("0.5, 0.1, 0.4, 0, 0, 0\n0.5, 0.1, x, 0, 0, 0\n");
    assert!(matches!(e, TaskFileError::Number(_)));
    assert_eq!(
        e.to_string(),
        "poses.csv:2: value 3 (\"x\") is not a finite number"
    );
    let e = err("# nothing\n\n");
    assert_eq!(
        e.to_string(),
        "poses.csv: no task poses (blank lines, # comments and a header only)"
    );
    let e = err("x, y, z, roll, pitch, yaw\n1, 2, 3, 0, 0, 0\n");
    assert!(
        e.to_string().starts_with("poses.csv:1: read as a header"),
        "{e}"
    );
    assert!(e.to_string().contains("column 4 is \"roll\""), "{e}");
    assert!(e.to_string().contains("degrees"), "{e}");
    let e = err("1, 2, 3\n");
    assert_eq!(
        e.to_string(),
        "poses.csv:1: expected 6 numbers (x, y, z in m, roll_deg, pitch_deg, yaw_deg) or 16 (a \
         row-major 4x4 pose), got 3 field(s)"
    );
    // A 4x4 that is not a rotation.
    let e = err("1 0 0 0  0 2 0 0  0 0 1 0  0 0 0 1\n");
    assert!(matches!(e, TaskFileError::NotRigid { .. }));
    assert!(
        e.to_string()
            .starts_with("poses.csv:1: the 4x4 pose is not rigid"),
        "{e}"
    );
    let e = err("name, x, y, z, roll_deg, pitch_deg, yaw_deg\n, 1, 2, 3, 0, 0, 0\n");
    assert_eq!(e.to_string(), "poses.csv:2: field 1 (the name) is empty");
    let e = err("name, x, y, z, roll_deg, pitch_deg, yaw_deg\na, 1, 2, 3, 0, 0\n");
    assert!(
        e.to_string()
            .starts_with("poses.csv:2: expected a name and 6 numbers"),
        "{e}"
    );
    let e = err("name, x, y\n");
    assert!(
        matches!(e, TaskFileError::HeaderCount { got: 3, .. }),
        "{e}"
    );
}
