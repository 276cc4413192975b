//! Kinematic redundancy (Sect. 2.10.2): the excerpt's n, m, r examples, tool-frame task masks, and
//! the exact self-motion of the three-link planar arm against computations written here.

use armlab::kinematics::ik::Target;
use armlab::kinematics::ik::numerical::{self, NumericalOptions, TaskMask};
use armlab::kinematics::models::built_in;
use armlab::kinematics::pose::rot_z;
use armlab::kinematics::redundancy::{Redundancy, Task};
use armlab::kinematics::{DhJoint, DhRow, Pose, Robot};
use armlab::redundancy::PlanarSelfMotion;
use std::f64::consts::{PI, TAU};

fn robot(name: &str) -> Robot {
    built_in(name).unwrap()
}

#[test]
fn the_excerpts_examples_of_redundancy() {
    let cases = [
        ("planar3", Task::Planar, (3, 3, 2), "functionally redundant"),
        ("planar3", Task::PlanarPhi, (3, 3, 3), "not redundant"),
        (
            "planar4",
            Task::PlanarPhi,
            (4, 3, 3),
            "intrinsically redundant",
        ),
        ("dlr", Task::Pose, (7, 6, 6), "intrinsically redundant"),
        (
            "puma560",
            Task::PositionAxis,
            (6, 6, 5),
            "functionally redundant",
        ),
        ("puma560", Task::Pose, (6, 6, 6), "not redundant"),
        ("planar2", Task::Planar, (2, 3, 2), "not redundant"),
    ];
    for (name, task, (n, m, r), words) in cases {
        let red = Redundancy::of(&robot(name), task);
        assert_eq!((red.n, red.m, red.r), (n, m, r), "{name} {task:?}");
        assert_eq!(red.words(), words, "{name} {task:?}");
    }
    assert_eq!(Redundancy::of(&robot("dlr"), Task::Pose).degree(), 1);
    for t in Task::ALL {
        assert_eq!(Task::from_name(t.name()), Some(t));
    }
}

/// Laser cutting (r = 5): a solution of the position + approach-axis task stays a solution when
/// the target turns about its approach axis, which a world-frame mask cannot express.
#[test]
fn a_tool_frame_task_leaves_the_rotation_about_the_tool_axis_free() {
    let r = robot("puma560");
    let q0 = [0.3, -0.5, 0.4, 0.6, -0.7, 0.2];
    let target = r.fk(&q0).unwrap();
    let opts = NumericalOptions {
        mask: TaskMask::of_task(Task::PositionAxis),
        ..NumericalOptions::default()
    };
    let seed = [0.2, -0.4, 0.3, 0.5, -0.6, 0.1];
    let rep = numerical::solve(&r, 0, &Target::Pose(target), &seed, &opts).unwrap();
    assert!(rep.converged, "{rep:?}");
    for angle in [0.4, 1.3, -2.0] {
        let turned = target * rot_z(angle);
        let again = numerical::solve(&r, 0, &Target::Pose(turned), &rep.q, &opts).unwrap();
        // Still a solution: the solver does not need to move the joints (beyond polishing the
        // last digits of the first solve).
        assert!(again.converged, "{angle}: {again:?}");
        let moved = again
            .q
            .iter()
            .zip(&rep.q)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(moved < 1e-8, "{angle}: moved {moved}");
        // The hand's position and approach axis are the target's.
        let t = r.fk(&again.q).unwrap();
        let (a, b) = (
            t.rotation * nalgebra::Vector3::z(),
            turned.rotation * nalgebra::Vector3::z(),
        );
        assert!(
            (a - b).norm() < 1e-9
                && (t.translation.vector - turned.translation.vector).norm() < 1e-9
        );
        // A full-pose task does see the turn.
        let full = numerical::solve(
            &r,
            0,
            &Target::Pose(turned),
            &rep.q,
            &NumericalOptions {
                max_iterations: 0,
                restarts: 0,
                ..NumericalOptions::default()
            },
        )
        .unwrap();
        assert!(!full.converged);
    }
}

/// A three-link planar arm without joint limits (a = 0.5, 0.3, 0.2 m).
fn free_planar3() -> Robot {
    let rows: Vec<DhJoint> = [0.5, 0.3, 0.2]
        .iter()
        .map(|&a| {
            DhJoint::revolute(DhRow {
                a,
                alpha: 0.0,
                d: 0.0,
                theta: 0.0,
            })
            .unbounded()
        })
        .collect();
    Robot::from_dh(
        "free three-link arm",
        armlab::kinematics::Convention::Standard,
        &rows,
        Pose::identity(),
        Pose::identity(),
    )
    .unwrap()
}

fn lcg(s: &mut u64) -> f64 {
    *s = s
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (*s >> 11) as f64 / (1u64 << 53) as f64
}

#[test]
fn planar_self_motion_keeps_the_hand_exactly_still() {
    let r = robot("planar3");
    let mut s = 3u64;
    let mut checked = 0;
    while checked < 2000 {
        let p = [-0.2 + 1.2 * lcg(&mut s), -1.0 + 2.0 * lcg(&mut s)];
        let Ok(m) = PlanarSelfMotion::new(&r, p) else {
            continue;
        };
        let phi = -PI + TAU * lcg(&mut s);
        for b in m.solutions(&r, phi) {
            // FK written out, (2.63) with the data of Problem 2.17.
            let (q1, q2, q3) = (b.q[0], b.q[1], b.q[2]);
            let x = 0.5 * q1.cos() + 0.3 * (q1 + q2).cos() + 0.2 * (q1 + q2 + q3).cos();
            let y = 0.5 * q1.sin() + 0.3 * (q1 + q2).sin() + 0.2 * (q1 + q2 + q3).sin();
            assert!((x - p[0]).hypot(y - p[1]) < 1e-12, "{p:?} {phi}: {b:?}");
            let d = (q1 + q2 + q3 - phi).rem_euclid(TAU);
            assert!(d.min(TAU - d) < 1e-12, "orientation {b:?}");
            assert!(b.position_error < 1e-12 && b.orientation_error < 1e-12);
            checked += 1;
        }
    }
}

/// Feasible intervals against 10^5 samples of phi, with the limits of Problem 2.17 checked in
/// the test on the solutions' joint values.
#[test]
fn planar_feasible_intervals_match_dense_sampling() {
    let r = robot("planar3");
    let lim = [PI / 3.0, 2.0 * PI / 3.0, PI / 2.0];
    for p in [
        [0.6, 0.1],
        [0.3, 0.5],
        [0.75, -0.2],
        [0.1, -0.6],
        [0.45, 0.0],
    ] {
        let m = PlanarSelfMotion::new(&r, p).unwrap();
        let (feasible, _) = m.feasible();
        let names = m.branch_names();
        for (b, name) in names.iter().enumerate() {
            let n = 100_000;
            let mut hits = 0;
            for k in 0..n {
                let phi = -PI + TAU * (k as f64 + 0.5) / n as f64;
                let sol = m.solutions(&r, phi).into_iter().find(|x| &x.name == name);
                let ok = sol.is_some_and(|x| (0..3).all(|j| x.q[j].abs() <= lim[j] + 1e-12));
                let inside = feasible[b].iter().any(|iv| phi >= iv[0] && phi <= iv[1]);
                let near_end = feasible[b]
                    .iter()
                    .any(|iv| (phi - iv[0]).abs() < 1e-4 || (phi - iv[1]).abs() < 1e-4);
                if !near_end {
                    assert_eq!(ok, inside, "{p:?} {name} phi {phi}");
                }
                hits += usize::from(ok);
            }
            let measure: f64 = feasible[b].iter().map(|iv| iv[1] - iv[0]).sum();
            let sampled = hits as f64 / n as f64 * TAU;
            assert!(
                (measure - sampled).abs() < 1e-3,
                "{p:?} {name}: {measure} vs {sampled}"
            );
            for iv in &feasible[b] {
                assert!(-PI <= iv[0] && iv[0] <= iv[1] && iv[1] <= PI, "{iv:?}");
            }
        }
    }
}

/// Without limits the position task's self-motion is one curve or two (Lenarcic): two where the
/// wrist circle stays inside the two-link annulus, one where it crosses its edge (the branches
/// meet).
#[test]
fn self_motion_curves_are_counted() {
    let r = free_planar3();
    // |p| = 0.5: the wrist circle (radius 0.2) spans 0.3..0.7, inside the annulus 0.2..0.8.
    assert_eq!(
        PlanarSelfMotion::new(&r, [0.5, 0.0]).unwrap().manifolds(&r),
        2
    );
    // |p| = 0.9: the circle 0.7..1.1 crosses the outer edge 0.8, the branches meet.
    assert_eq!(
        PlanarSelfMotion::new(&r, [0.0, 0.9]).unwrap().manifolds(&r),
        1
    );
    // With the limits of Problem 2.17 the count is between 1 and 2 where reachable.
    let p3 = robot("planar3");
    for p in [[0.6, 0.1], [0.3, 0.5], [0.45, 0.0]] {
        let k = PlanarSelfMotion::new(&p3, p).unwrap().manifolds(&p3);
        assert!((1..=3).contains(&k), "{p:?}: {k}");
    }
    // Out of reach, and a non-redundant arm, are errors.
    assert!(PlanarSelfMotion::new(&r, [1.5, 0.0]).is_err());
    assert!(PlanarSelfMotion::new(&robot("planar2"), [1.0, 0.0]).is_err());
}

/// Numerical self-motion of the humanoid's arm with its torso (10 joints move the hand): after
/// 10,000 steps the hand is still where it was to 1e-12 m and 1e-12 rad, and the arm has moved.
#[test]
fn numerical_self_motion_does_not_drift() {
    let r = robot("humanoid");
    let q0 = r
        .config("ready")
        .map_or_else(|| vec![0.1; r.dof()], <[f64]>::to_vec);
    let mut m = armlab::redundancy::numerical::NullSpaceMotion::new(&r, 0, &q0, None).unwrap();
    let start = m.q().to_vec();
    let gap = |q: &[f64]| {
        q.iter()
            .zip(&start)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    };
    let mut widest: f64 = 0.0;
    for k in 0..10_000 {
        // Back and forth, as a slider is dragged: out 2500 steps, back, out, back.
        let ds = if (k / 2500) % 2 == 0 { 4e-4 } else { -4e-4 };
        m.step(ds).unwrap();
        widest = widest.max(gap(m.q()));
        let (pe, oe) = m.errors().unwrap();
        assert!(pe < 1e-12 && oe < 1e-12, "step {k}: drift {pe} m, {oe} rad");
    }
    // The arm swung, and dragging back returns near the start (the null space is 4-dimensional
    // here, so the transported tangent need not retrace the path exactly).
    assert!(widest > 0.2, "widest excursion {widest} rad");
    assert!(gap(m.q()) < 1e-3, "back at {}", gap(m.q()));
    // Degree 1 (the DLR arm, a full pose): the null space is a line, so going back retraces
    // the path exactly.
    let dlr = robot("dlr");
    let q0 = dlr.config("ready").unwrap().to_vec();
    let mut m = armlab::redundancy::numerical::NullSpaceMotion::new(&dlr, 0, &q0, None).unwrap();
    for k in 0..2000 {
        m.step(if k < 1000 { 1e-3 } else { -1e-3 }).unwrap();
    }
    let back = m
        .q()
        .iter()
        .zip(&q0)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(back < 1e-9, "DLR back at {back}");
    let (pe, oe) = m.errors().unwrap();
    assert!(pe < 1e-12 && oe < 1e-12);
    // A non-redundant arm has no self-motion.
    assert!(
        armlab::redundancy::numerical::NullSpaceMotion::new(
            &robot("puma560"),
            0,
            &[0.1, -0.4, 0.3, 0.5, -0.6, 0.2],
            None
        )
        .is_err()
    );
}

/// A four-link planar arm with limits on every joint (a = 0.35, 0.3, 0.2, 0.15 m).
fn limited_planar4() -> Robot {
    let lim = [[-2.0, 2.0], [-2.5, 2.5], [-1.5, 1.5], [-1.0, 1.2]];
    let rows: Vec<DhJoint> = [0.35, 0.3, 0.2, 0.15]
        .iter()
        .zip(lim)
        .map(|(&a, l)| {
            DhJoint::revolute(DhRow {
                a,
                alpha: 0.0,
                d: 0.0,
                theta: 0.0,
            })
            .limits(l[0], l[1])
        })
        .collect();
    Robot::from_dh(
        "limited four-link arm",
        armlab::kinematics::Convention::Standard,
        &rows,
        Pose::identity(),
        Pose::identity(),
    )
    .unwrap()
}

/// The four-link arm holding (x, y, phi): every branch at every phi_3 reproduces the hand by
/// the forward kinematics (2.63) extended to four links, written out here; the configuration a
/// hand pose came from is among the branches at its own phi_3 = q1 + q2 + q3.
#[test]
fn four_link_self_motion_keeps_the_hand_exactly_still() {
    use armlab::redundancy::four_link::FourLinkSelfMotion;
    let a = [0.35, 0.3, 0.2, 0.15];
    let fk = |q: &[f64]| {
        let (mut x, mut y, mut t) = (0.0, 0.0, 0.0);
        for k in 0..4 {
            t += q[k];
            x += a[k] * t.cos();
            y += a[k] * t.sin();
        }
        (x, y, t)
    };
    for r in [robot("planar4"), limited_planar4()] {
        let lim = r.limits();
        let mut s = 17u64;
        let mut checked = 0;
        for _ in 0..2000 {
            let q: Vec<f64> = lim
                .iter()
                .map(|l| l[0] + (l[1] - l[0]) * lcg(&mut s))
                .collect();
            let (x, y, phi) = fk(&q);
            let target = r.fk(&q).unwrap();
            let m = FourLinkSelfMotion::new(&r, &target).unwrap();
            let own = m.solutions(&r, q[0] + q[1] + q[2]);
            assert!(own.iter().any(|b| b.q.iter().zip(&q).all(|(u, v)| {
                (u - v).rem_euclid(TAU).min(TAU - (u - v).rem_euclid(TAU)) < 1e-9
            })));
            let phi3 = -PI + TAU * lcg(&mut s);
            for b in m.solutions(&r, phi3) {
                let (bx, by, bt) = fk(&b.q);
                assert!((bx - x).hypot(by - y) < 1e-12, "{b:?}");
                let d = (bt - phi).rem_euclid(TAU);
                assert!(d.min(TAU - d) < 1e-12);
                let d3 = (b.q[0] + b.q[1] + b.q[2] - phi3).rem_euclid(TAU);
                assert!(d3.min(TAU - d3) < 1e-12);
                assert!(b.position_error < 1e-12 && b.orientation_error < 1e-12);
                checked += 1;
            }
        }
        assert!(checked > 1000, "{checked}");
    }
}

/// Feasible phi_3 intervals of the limited four-link arm against 10^5 samples, limits checked
/// on the joint values in the test.
#[test]
fn four_link_feasible_intervals_match_dense_sampling() {
    use armlab::redundancy::four_link::FourLinkSelfMotion;
    let r = limited_planar4();
    let lim = r.limits();
    for q in [
        [0.3, 0.8, 0.5, -0.4],
        [-1.2, 1.9, -0.7, 0.9],
        [1.5, -2.0, 1.2, 0.1],
    ] {
        let target = r.fk(&q).unwrap();
        let m = FourLinkSelfMotion::new(&r, &target).unwrap();
        let (feasible, _) = m.feasible();
        for (b, name) in m.branch_names().iter().enumerate() {
            let n = 100_000;
            let mut hits = 0;
            for k in 0..n {
                let phi = -PI + TAU * (k as f64 + 0.5) / n as f64;
                let sol = m.solutions(&r, phi).into_iter().find(|x| &x.name == name);
                let ok = sol.is_some_and(|x| {
                    (0..4).all(|j| x.q[j] >= lim[j][0] - 1e-12 && x.q[j] <= lim[j][1] + 1e-12)
                });
                let inside = feasible[b].iter().any(|iv| phi >= iv[0] && phi <= iv[1]);
                let near_end = feasible[b]
                    .iter()
                    .any(|iv| (phi - iv[0]).abs() < 1e-4 || (phi - iv[1]).abs() < 1e-4);
                if !near_end {
                    assert_eq!(ok, inside, "{q:?} {name} phi {phi}");
                }
                hits += usize::from(ok);
            }
            let measure: f64 = feasible[b].iter().map(|iv| iv[1] - iv[0]).sum();
            let sampled = hits as f64 / n as f64 * TAU;
            assert!(
                (measure - sampled).abs() < 1e-3,
                "{q:?} {name}: {measure} vs {sampled}"
            );
            // The limits bite: neither nothing nor the whole circle.
            assert!(
                measure > 0.01 && measure < TAU - 0.01,
                "{q:?} {name}: {measure}"
            );
        }
        assert!(m.manifolds(&r) >= 1);
    }
}

/// The laser-cutting task on the Puma (position and approach axis, r = 5 of n = 6): the
/// numerical self-motion holding only the task turns the hand about its approach axis while the
/// tool point and the axis stay put, checked with FK and an axis angle computed here, over
/// 10,000 steps back and forth; with the position alone (degree 3) the point stays put.
#[test]
fn numerical_self_motion_holds_a_partial_task_without_drift() {
    use armlab::redundancy::numerical::NullSpaceMotion;
    let puma = robot("puma560");
    let q0 = [0.3, -0.5, 0.4, 0.6, -0.7, 0.2];
    let start = puma.fk(&q0).unwrap();
    let axis_angle = |a: &Pose, b: &Pose| {
        let (za, zb) = (
            a.rotation * nalgebra::Vector3::z(),
            b.rotation * nalgebra::Vector3::z(),
        );
        za.cross(&zb).norm().atan2(za.dot(&zb))
    };
    let about_axis = |a: &Pose, b: &Pose| {
        // The rotation from a to b about a's z (they share it): atan2 of b's x in a's frame.
        let x = a.rotation.inverse() * (b.rotation * nalgebra::Vector3::x());
        x.y.atan2(x.x)
    };
    let mask = TaskMask::of_task(Task::PositionAxis);
    let mut m = NullSpaceMotion::for_task(&puma, 0, &q0, None, mask).unwrap();
    let mut turned: f64 = 0.0;
    for k in 0..10_000 {
        let ds = if (k / 500) % 2 == 0 { 0.004 } else { -0.003 };
        m.step(ds).unwrap();
        let t = puma.fk(m.q()).unwrap();
        let dp = (t.translation.vector - start.translation.vector).norm();
        assert!(dp < 1e-12, "step {k}: the tool point moved {dp} m");
        assert!(
            axis_angle(&t, &start) < 1e-12,
            "step {k}: the approach axis turned"
        );
        turned = turned.max(about_axis(&start, &t).abs());
        let (pe, oe) = m.errors().unwrap();
        assert!(pe < 1e-12 && oe < 1e-12);
    }
    assert!(
        turned > 0.3,
        "the hand hardly turned about its axis: {turned} rad"
    );
    let mask = TaskMask::of_task(Task::Position);
    let mut m = NullSpaceMotion::for_task(&puma, 0, &q0, None, mask).unwrap();
    let mut moved: f64 = 0.0;
    for k in 0..2000 {
        m.step(if k < 1000 { 0.005 } else { -0.005 }).unwrap();
        let t = puma.fk(m.q()).unwrap();
        assert!((t.translation.vector - start.translation.vector).norm() < 1e-12);
        moved = moved.max(axis_angle(&t, &start));
    }
    assert!(moved > 0.1, "the hand's axis hardly moved: {moved} rad");
}
