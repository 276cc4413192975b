//! Issue 27, every family that decomposes: a six-revolute arm whose last three axes meet (a
//! spherical wrist) but whose first three joints are none of the named arms (any lengths and
//! twists) is Pieper's general case: the wrist centre fixes theta3 by a quartic, then theta1 and
//! theta2, then the wrist its two postures (up to 8 solutions). Checked against computations
//! written here: a forward kinematics of the DH rows multiplied out in the test, and a
//! brute-force Newton search over all six joints that finds no solution the solver missed.
//! `ARMLAB_EVIDENCE=full` runs 1000 poses per arm with 1000 starts each.

mod common;

use common::closed_form::*;
use nalgebra::Matrix4;
use rand::{Rng, SeedableRng};

/// (a, alpha, d) of the first three rows; the wrist is the textbook's (d4, d6 below).
type Rows3 = [(f64, f64, f64); 3];

/// Twists of 1.1 and 0.7 rad: no named arm.
const GENERIC: Rows3 = [(0.15, 1.1, 0.3), (0.4, 0.7, 0.1), (0.05, -1.2, 0.08)];
/// a1 = 0 (the quartic would be a square): G = 0 is solved apart.
const NO_A1: Rows3 = [(0.0, 0.9, 0.3), (0.45, -0.5, 0.05), (0.1, 1.3, 0.0)];
/// Axes 1 and 2 parallel (alpha1 = 0), axis 3 skew to them: q_z is fixed by the height.
const PARALLEL12: Rows3 = [(0.3, 0.0, 0.25), (0.35, 1.0, 0.06), (0.04, -0.8, 0.1)];
/// The wrist: d4 along axis 4 to the wrist centre, d6 to the flange.
const D4: f64 = 0.35;
const D6: f64 = 0.1;
/// Base and tool transforms (nothing axis-aligned).
fn base() -> Pose {
    Pose::translation(0.1, -0.2, 0.05) * rot_z(0.3)
}
fn tool() -> Pose {
    Pose::translation(0.01, 0.02, 0.04) * rot_y(0.25)
}

/// Joint offsets, so that theta = q + offset is exercised.
const OFFSETS: [f64; 6] = [0.2, -0.4, 0.1, 0.0, 0.3, -0.1];

fn arm(rows: &Rows3) -> Robot {
    let mut r: Vec<Row> = rows
        .iter()
        .zip(OFFSETS)
        .map(|(&(a, alpha, d), off)| rv(a, alpha, d, off))
        .collect();
    r.push(rv(0.0, -FRAC_PI_2, D4, OFFSETS[3]));
    r.push(rv(0.0, FRAC_PI_2, 0.0, OFFSETS[4]));
    r.push(rv(0.0, 0.0, D6, OFFSETS[5]));
    Robot::from_dh("pieper", Convention::Standard, &r, base(), tool()).unwrap()
}

/// The standard DH matrix `Rz(theta) Tz(d) Tx(a) Rx(alpha)`, written out (2.52).
fn dh(a: f64, alpha: f64, d: f64, theta: f64) -> Matrix4<f64> {
    let (st, ct) = theta.sin_cos();
    let (sa, ca) = alpha.sin_cos();
    #[rustfmt::skip]
    let m = Matrix4::new(
        ct, -st * ca, st * sa, a * ct,
        st, ct * ca, -ct * sa, a * st,
        0.0, sa, ca, d,
        0.0, 0.0, 0.0, 1.0,
    );
    m
}

/// The arm's forward kinematics multiplied out here, base and tool included.
fn fk_here(rows: &Rows3, q: &[f64]) -> Matrix4<f64> {
    let mut t = base().to_homogeneous();
    for (i, &(a, alpha, d)) in rows.iter().enumerate() {
        t *= dh(a, alpha, d, q[i] + OFFSETS[i]);
    }
    t *= dh(0.0, -FRAC_PI_2, D4, q[3] + OFFSETS[3]);
    t *= dh(0.0, FRAC_PI_2, 0.0, q[4] + OFFSETS[4]);
    t *= dh(0.0, 0.0, D6, q[5] + OFFSETS[5]);
    t * tool().to_homogeneous()
}

/// Position (m) and rotation (Frobenius norm of the difference) errors by [`fk_here`].
fn errors_here(rows: &Rows3, q: &[f64], t: &Pose) -> (f64, f64) {
    let m = fk_here(rows, q);
    let want = t.to_homogeneous();
    let dp = (m.fixed_view::<3, 1>(0, 3) - want.fixed_view::<3, 1>(0, 3)).norm();
    let dr = (m.fixed_view::<3, 3>(0, 0) - want.fixed_view::<3, 3>(0, 0)).norm();
    (dp, dr)
}

/// Newton over all six joints on [`fk_here`], from `q` (see `common::closed_form::newton_on`).
fn newton_here(rows: &Rows3, t: &Pose, q: Vec<f64>) -> Option<Vec<f64>> {
    newton_on(|q: &[f64]| fk_here(rows, q), t, q)
}

fn full() -> bool {
    std::env::var("ARMLAB_EVIDENCE").is_ok_and(|v| v == "full")
}

/// Per arm: every solution FK-valid to 1e-12 by [`fk_here`], the pose's own q among them, no
/// duplicates, at most 8, in wrist pairs with distinct labels; a brute-force Newton search finds
/// nothing else. Returns (solutions, starts converged).
fn check(rows: &Rows3, seed: u64) -> (usize, usize) {
    let r = arm(rows);
    let c = cf(&r);
    assert_eq!(
        *c.family(),
        Family::Decoupled6 {
            arm: ArmKind::General3R
        },
        "{}",
        c.name()
    );
    let (poses, starts) = if full() { (1000, 1000) } else { (60, 150) };
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let (mut total, mut converged) = (0, 0);
    for _ in 0..poses {
        let q: Vec<f64> = (0..6).map(|_| rng.random_range(-PI..PI)).collect();
        let t = pose_from_matrix(&fk_here(rows, &q)).unwrap();
        let res = c.solve(&r, &Target::Pose(t)).unwrap();
        assert_eq!(res.status, IkStatus::Ok, "{}", show(&res));
        let n = res.solutions.len();
        assert!(
            n <= 8 && n.is_multiple_of(2),
            "{n} solutions\n{}",
            show(&res)
        );
        total += n;
        for s in &res.solutions {
            let (dp, dr) = errors_here(rows, &s.q, &t);
            assert!(dp < 1e-12 && dr < 1e-12, "{dp:e} {dr:e}\n{}", show(&res));
        }
        assert!(
            res.solutions.iter().any(|s| same_q(&r, &s.q, &q, 1e-9)),
            "{q:?} missing from\n{}",
            show(&res)
        );
        for (i, a) in res.solutions.iter().enumerate() {
            for b in &res.solutions[..i] {
                assert!(!same_q(&r, &a.q, &b.q, 1e-9), "duplicate\n{}", show(&res));
                assert_ne!(a.posture, b.posture, "labels\n{}", show(&res));
            }
            assert!(a.posture.contains("branch") && a.posture.contains("wrist"));
        }
        for _ in 0..starts {
            let start: Vec<f64> = (0..6).map(|_| rng.random_range(-PI..PI)).collect();
            if let Some(found) = newton_here(rows, &t, start) {
                converged += 1;
                assert!(
                    res.solutions.iter().any(|s| same_q(&r, &s.q, &found, 1e-6)),
                    "Newton found {found:?}, not among\n{}",
                    show(&res)
                );
            }
        }
    }
    (total, converged)
}

#[test]
fn a_general_three_revolute_arm_with_a_spherical_wrist_has_every_solution() {
    let (n, conv) = check(&GENERIC, 1);
    eprintln!("generic: {n} solutions, {conv} starts converged");
    // Poses with 8 solutions occur: the quartic has 4 real roots there.
    assert!(conv > 0 && n > 0);
}

#[test]
fn with_no_first_link_length_the_wrist_centre_fixes_theta3_directly() {
    let (n, conv) = check(&NO_A1, 2);
    eprintln!("a1 = 0: {n} solutions, {conv} starts converged");
    assert!(conv > 0 && n > 0);
}

#[test]
fn with_parallel_first_axes_the_height_fixes_theta3() {
    let (n, conv) = check(&PARALLEL12, 3);
    eprintln!("alpha1 = 0: {n} solutions, {conv} starts converged");
    assert!(conv > 0 && n > 0);
}

/// Eight solutions do occur for the generic arm: the quartic's four real roots are found, not
/// only two (a test of the count, against the brute force above that would miss nothing).
#[test]
fn the_generic_arm_reaches_eight_solutions() {
    let r = arm(&GENERIC);
    let c = cf(&r);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(9);
    let mut counts = [0usize; 9];
    for _ in 0..400 {
        let q: Vec<f64> = (0..6).map(|_| rng.random_range(-PI..PI)).collect();
        let t = pose_from_matrix(&fk_here(&GENERIC, &q)).unwrap();
        let res = c.solve(&r, &Target::Pose(t)).unwrap();
        counts[res.solutions.len()] += 1;
    }
    assert!(counts[8] > 0 && counts[4] > 0, "counts by size {counts:?}");
}

/// A point out of reach is unreachable, with a positive lower bound on the gap.
#[test]
fn a_pose_out_of_reach_is_unreachable() {
    let r = arm(&GENERIC);
    let c = cf(&r);
    let t = Pose::translation(3.0, 1.0, 0.5);
    let res = c.solve(&r, &Target::Pose(t)).unwrap();
    match res.status {
        IkStatus::Unreachable { distance } => assert!(distance > 1.0, "{distance}"),
        s => panic!("{s:?}"),
    }
}
