//! Issue 48: the exact self-motion in a cell. The collision-free intervals of an SRS arm (the
//! LWR-IV's arm angle), the Panda (q7) and a locked joint (the Panda's q3) beside a box placed
//! at the elbow, checked against a brute-force search written here: every branch on a grid of
//! the parameter 1e-3 rad apart (2e-3 for the locked joint, whose elimination is slower), each
//! grid value checked with `CollisionWorld::in_collision` and the joint limits directly.
//!
//! - every grid value inside a returned interval is free and within the limits;
//! - every free grid value is inside one, and one whose neighbours are free is a grid step or
//!   more away from its ends;
//! - each end that is not a limit's is right to 1e-6 rad: 1e-6 inside the branch is free,
//!   1e-6 outside it hits something;
//! - each colliding stretch hits at its middle, and the pair it names is in contact there or
//!   at one of its grid values.

use armlab::collision::{CellScene, CollisionWorld, Obstacle};
use armlab::kinematics::Robot;
use armlab::kinematics::models::built_in;
use armlab::redundancy::collision::{CellScanOptions, CollidingStretch, CollisionFreeMotion};
use armlab::redundancy::motion::ExactSelfMotion;
use std::f64::consts::{PI, TAU};

/// The branch `b` at `t`: within the limits (1e-9) and hitting nothing; `None` without a
/// solution.
fn good(
    robot: &Robot,
    motion: &ExactSelfMotion,
    world: &CollisionWorld,
    b: usize,
    t: f64,
) -> Option<bool> {
    let name = &motion.names()[b];
    let s = motion
        .solutions(robot, t)
        .into_iter()
        .find(|s| &s.name == name)?;
    let within =
        s.q.iter()
            .zip(robot.limits())
            .all(|(v, l)| *v >= l[0] - 1e-9 && *v <= l[1] + 1e-9);
    let hit = world
        .in_collision(robot, &s.q)
        .expect("a configuration of the robot");
    Some(within && !hit)
}

/// Whether the branch `b` at `t` hits something (a solution within the limits that collides).
fn hits(robot: &Robot, motion: &ExactSelfMotion, world: &CollisionWorld, b: usize, t: f64) -> bool {
    let name = &motion.names()[b];
    motion
        .solutions(robot, t)
        .into_iter()
        .find(|s| &s.name == name)
        .is_some_and(|s| world.in_collision(robot, &s.q).expect("a configuration"))
}

/// The self-motion of `robot` through `q0` (with joint `lock` locked), a box of side 0.1 m
/// centred on the elbow at a parameter 0.5 to 1.6 rad from `q0`'s, and the world.
fn case(robot: &Robot, q0: &[f64], lock: Option<usize>) -> (ExactSelfMotion, CollisionWorld) {
    let pose = robot.fk(q0).expect("fk");
    let motion = ExactSelfMotion::with_lock(robot, &pose, lock).expect("an exact self-motion");
    let (b0, v0) = motion.locate(robot, q0).expect("q0 on its self-motion");
    let name = motion.names()[b0].clone();
    let elbow = [1.2, -1.2, 1.6, -1.6, 0.9, -0.9, 0.7, -0.7, 0.5, -0.5]
        .iter()
        .find_map(|dv| {
            let v = (v0 + dv + PI).rem_euclid(TAU) - PI;
            let s = motion
                .solutions(robot, v)
                .into_iter()
                .find(|s| s.name == name && s.within_limits)?;
            motion.traced_point(robot, &s.q)
        })
        .expect("the branch moves 0.5 rad or more within its limits");
    let cell = CellScene {
        obstacles: vec![Obstacle::cuboid("box", [0.1, 0.1, 0.1], elbow.into())],
        ..CellScene::default()
    };
    let world = CollisionWorld::new(robot, &cell).expect("a world");
    (motion, world)
}

/// Checks the intervals against the brute force on a grid `h` apart; returns (colliding
/// stretches, free intervals, ends checked to 1e-6).
fn check(robot: &Robot, motion: &ExactSelfMotion, world: &CollisionWorld, h: f64) -> [usize; 3] {
    let result: CollisionFreeMotion =
        motion.collision_free(robot, world, CellScanOptions::default());
    let n = (TAU / h).round() as usize;
    let grid: Vec<f64> = (0..n).map(|k| -PI + TAU / n as f64 * k as f64).collect();
    let mut ends_checked = 0;
    for b in 0..motion.names().len() {
        check_grid(robot, motion, world, b, &result.free[b], &grid);
        ends_checked += check_ends(robot, motion, world, b, &result.free[b]);
    }
    for s in &result.colliding {
        check_stretch(robot, motion, world, s, &grid);
    }
    let intervals = result.free.iter().map(Vec::len).sum();
    [result.colliding.len(), intervals, ends_checked]
}

/// Branch `b`'s free intervals against the brute force on `grid` (evenly spaced).
fn check_grid(
    robot: &Robot,
    motion: &ExactSelfMotion,
    world: &CollisionWorld,
    b: usize,
    free: &[[f64; 2]],
    grid: &[f64],
) {
    let (name, n, h) = (&motion.names()[b], grid.len(), grid[1] - grid[0]);
    let truth: Vec<Option<bool>> = grid
        .iter()
        .map(|&t| good(robot, motion, world, b, t))
        .collect();
    let is_good = |k: usize| truth[k] == Some(true);
    for (k, &t) in grid.iter().enumerate() {
        let inside = free.iter().find(|iv| iv[0] <= t && t <= iv[1]);
        if inside.is_some() {
            assert!(
                is_good(k),
                "{name}: {t} is in a free interval {inside:?} but not free"
            );
        }
        if !is_good(k) {
            continue;
        }
        let iv = free
            .iter()
            .find(|iv| iv[0] - 1e-6 <= t && t <= iv[1] + 1e-6)
            .unwrap_or_else(|| panic!("{name}: {t} is free but in no interval {free:?}"));
        if k > 0 && k + 1 < n && is_good(k - 1) && is_good(k + 1) {
            assert!(
                t - iv[0] >= h - 1e-6 && iv[1] - t >= h - 1e-6,
                "{name}: {t} and its neighbours are free, but it is within a grid step of an \
                 end of {iv:?}"
            );
        }
    }
}

/// Each end of branch `b`'s free intervals that is not a feasible interval's (the limits' or
/// the +-pi cut's): 1e-6 inside free, 1e-6 outside hitting. Returns how many were checked.
fn check_ends(
    robot: &Robot,
    motion: &ExactSelfMotion,
    world: &CollisionWorld,
    b: usize,
    free: &[[f64; 2]],
) -> usize {
    let name = &motion.names()[b];
    let limit_end = |e: f64| {
        motion.feasible()[b]
            .iter()
            .any(|f| (f[0] - e).abs() < 1e-9 || (f[1] - e).abs() < 1e-9)
    };
    let mut checked = 0;
    for iv in free {
        for (e, inward) in [(iv[0], 1.0), (iv[1], -1.0)] {
            if limit_end(e) {
                continue;
            }
            assert_eq!(
                good(robot, motion, world, b, e + inward * 1e-6),
                Some(true),
                "{name}: 1e-6 inside the end {e} of {iv:?} is not free"
            );
            assert!(
                hits(robot, motion, world, b, e - inward * 1e-6),
                "{name}: 1e-6 outside the end {e} of {iv:?} hits nothing"
            );
            checked += 1;
        }
    }
    checked
}

/// A colliding stretch hits at its middle, and the pair it names is in contact there or at
/// one of the grid values inside it.
fn check_stretch(
    robot: &Robot,
    motion: &ExactSelfMotion,
    world: &CollisionWorld,
    s: &CollidingStretch,
    grid: &[f64],
) {
    let name = &motion.names()[s.branch];
    let middle = 0.5 * (s.from + s.to);
    assert!(
        hits(robot, motion, world, s.branch, middle),
        "{name}: {s:?} is free at its middle"
    );
    let pairs_at = |t: f64| {
        motion
            .solutions(robot, t)
            .into_iter()
            .find(|x| &x.name == name)
            .map(|x| world.check(robot, &x.q).expect("a configuration").pairs)
            .unwrap_or_default()
    };
    let named = std::iter::once(middle)
        .chain(grid.iter().copied().filter(|t| *t >= s.from && *t <= s.to))
        .any(|t| pairs_at(t).iter().any(|c| c.a == s.a && c.b == s.b));
    assert!(
        named,
        "{name}: {s:?} names a pair that is not in contact on the stretch"
    );
}

#[test]
fn srs_arm_angle_intervals_leave_out_the_box_as_a_brute_force_finds() {
    let lwr = built_in("lwr4").expect("lwr4");
    let (motion, world) = case(&lwr, &[0.2, 0.6, -0.3, -1.4, 0.2, 0.7, 0.1], None);
    let [stretches, intervals, ends] = check(&lwr, &motion, &world, 1e-3);
    assert!(
        stretches >= 1 && intervals >= 1 && ends >= 2,
        "{stretches} {intervals} {ends}"
    );
}

#[test]
fn panda_q7_intervals_leave_out_the_box_as_a_brute_force_finds() {
    let panda = built_in("panda").expect("panda");
    let (motion, world) = case(&panda, &[0.3, -0.4, 0.2, -2.0, 0.1, 1.6, 0.5], None);
    assert_eq!(motion.parameter(), "q7");
    let [stretches, intervals, ends] = check(&panda, &motion, &world, 1e-3);
    assert!(
        stretches >= 1 && intervals >= 1 && ends >= 2,
        "{stretches} {intervals} {ends}"
    );
}

#[test]
fn locked_joint_intervals_leave_out_the_box_as_a_brute_force_finds() {
    let panda = built_in("panda").expect("panda");
    let (motion, world) = case(&panda, &[0.3, -0.4, 0.2, -2.0, 0.1, 1.6, 0.5], Some(2));
    assert_eq!(motion.locked_joint(), Some(2));
    let [stretches, intervals, ends] = check(&panda, &motion, &world, 2e-3);
    assert!(
        stretches >= 1 && intervals >= 1 && ends >= 2,
        "{stretches} {intervals} {ends}"
    );
}

#[test]
fn without_obstacles_the_free_intervals_are_the_feasible_ones_where_nothing_self_collides() {
    // The LWR-IV alone: a branch whose brute force finds no self-collision keeps its feasible
    // intervals exactly.
    let lwr = built_in("lwr4").expect("lwr4");
    let pose = lwr.fk(&[0.2, 0.6, -0.3, -1.4, 0.2, 0.7, 0.1]).expect("fk");
    let motion = ExactSelfMotion::new(&lwr, &pose).expect("an SRS self-motion");
    let world = CollisionWorld::new(&lwr, &CellScene::default()).expect("a world");
    let result = motion.collision_free(&lwr, &world, CellScanOptions::default());
    let mut kept = 0;
    for (b, feasible) in motion.feasible().iter().enumerate() {
        let clean = feasible.iter().all(|iv| {
            (0..=200).all(|k| {
                let t = iv[0] + (iv[1] - iv[0]) * k as f64 / 200.0;
                !hits(&lwr, &motion, &world, b, t)
            })
        });
        if clean {
            assert_eq!(&result.free[b], feasible, "{}", motion.names()[b]);
            kept += 1;
        }
    }
    assert!(
        kept >= 1,
        "no branch of the LWR-IV is free of self-collision here"
    );
}
