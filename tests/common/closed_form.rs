//! Helpers shared by the closed-form inverse-kinematics tests (`ik_closed_form*.rs`): the
//! built-ins with a closed form, comparisons modulo 2 pi, the reference data, and the names
//! those tests use (re-exported; each test file uses a part of them).
#![allow(unused_imports)]

pub use armlab::kinematics::dh::standard_to_modified;
pub use armlab::kinematics::ik::closed_form::{
    ArmKind, ClosedForm, Family, MAX_SOLUTIONS, RawSolutions, ReversedOf, wrap_into_limits,
};
pub use armlab::kinematics::ik::{IkError, IkResult, IkStatus, Target};
pub use armlab::kinematics::models::built_in;
pub use armlab::kinematics::orientation::{
    wrap_angle, zyz_from_rotation, zyz_from_rotation_negative,
};
pub use armlab::kinematics::pose::{matrix_from_rows, pose_from_matrix, rot_x, rot_y, rot_z};
pub use armlab::kinematics::{Convention, DhJoint, DhRow, JointKind, Pose, Robot};
pub use nalgebra::{Translation3, Vector3};
pub use proptest::prelude::*;
pub use serde_json::Value;
pub use std::f64::consts::{FRAC_PI_2, PI};

pub const CLOSED_FORM: [&str; 10] = [
    "planar2",
    "planar3",
    "spherical_arm",
    "anthropomorphic3r",
    "spherical_wrist",
    "stanford",
    "anthropomorphic_spherical_wrist",
    "scara",
    "cylindrical",
    "puma560",
];

pub fn robot(name: &str) -> Robot {
    built_in(name).unwrap_or_else(|| panic!("built-in {name}"))
}

pub fn cf(robot: &Robot) -> ClosedForm {
    ClosedForm::detect(robot).unwrap_or_else(|e| panic!("{}: no closed form: {e}", robot.name))
}

/// Same configuration modulo 2 pi for revolute joints.
pub fn same_q(robot: &Robot, a: &[f64], b: &[f64], tol: f64) -> bool {
    a.len() == b.len()
        && (0..a.len()).all(|j| {
            let d = a[j] - b[j];
            let d = if robot.dof_joint(j).kind == JointKind::Revolute {
                wrap_angle(d)
            } else {
                d
            };
            d.abs() < tol
        })
}

pub fn show(res: &IkResult) -> String {
    let mut s = format!("status {:?}\n", res.status);
    for x in &res.solutions {
        s += &format!(
            "  {:?} [{}] within={} pe={:.1e} oe={:.1e} free={:?}\n",
            x.q, x.posture, x.within_limits, x.position_error, x.orientation_error, x.free_joints
        );
    }
    s
}

pub fn solve(robot: &Robot, target: Target) -> IkResult {
    cf(robot).solve(robot, &target).expect("valid target")
}

/// Every solution reaches the target (position, and orientation when `orient`).
pub fn assert_verified(res: &IkResult, orient: bool, tol: f64) {
    for s in &res.solutions {
        assert!(
            s.position_error < tol && (!orient || s.orientation_error < tol),
            "not verified:\n{}",
            show(res)
        );
        assert!(s.q.iter().all(|v| v.is_finite()));
    }
}

pub fn q_in_limits(robot: &Robot, u: &[f64]) -> Vec<f64> {
    robot
        .limits()
        .iter()
        .zip(u)
        .map(|(l, &t)| l[0] + t * (l[1] - l[0]))
        .collect()
}

pub fn position_only(f: &Family) -> bool {
    matches!(
        f,
        Family::Planar2 | Family::Anthropomorphic | Family::SphericalArm | Family::Cylindrical
    )
}

/// A JSON array of numbers.
pub use super::vec_f64 as vecf;

/// Parsed JSON of a reference file.
pub use super::reference;

pub fn pose_of(v: &Value) -> Pose {
    let rows: Vec<Vec<f64>> = v.as_array().expect("rows").iter().map(vecf).collect();
    let mut m = [[0.0; 4]; 4];
    for (r, row) in rows.iter().enumerate() {
        for (c, x) in row.iter().enumerate() {
            m[r][c] = *x;
        }
    }
    pose_from_matrix(&matrix_from_rows(&m)).expect("rigid")
}

/// The reference solutions and ours are the same sets modulo 2 pi; returns, for each reference
/// solution, the index of ours.
pub fn match_sets(robot: &Robot, ours: &IkResult, refs: &[Vec<f64>], tol: f64) -> Vec<usize> {
    assert_eq!(
        ours.solutions.len(),
        refs.len(),
        "counts differ:\n{}",
        show(ours)
    );
    refs.iter()
        .map(|r| {
            ours.solutions
                .iter()
                .position(|s| same_q(robot, &s.q, r, tol))
                .unwrap_or_else(|| panic!("reference {r:?} not found in\n{}", show(ours)))
        })
        .collect()
}

// ---------------------------------------------------------------- detection

/// A DH row as `Robot::from_dh` takes it.
pub type Row = DhJoint;

/// A DH joint from kind, row, offset (rad or m) and limits.
pub fn dj(kind: JointKind, row: DhRow, offset: f64, [lo, hi]: [f64; 2]) -> Row {
    DhJoint::new(kind, row).offset(offset).limits(lo, hi)
}
/// Short names for the joint kinds.
pub const R: JointKind = JointKind::Revolute;
/// Short names for the joint kinds.
pub const P: JointKind = JointKind::Prismatic;
/// A revolute joint's full turn.
pub const FULL: [f64; 2] = [-PI, PI];

/// A revolute row with full limits.
pub fn rv(a: f64, alpha: f64, d: f64, offset: f64) -> Row {
    dj(
        R,
        DhRow {
            a,
            alpha,
            d,
            theta: 0.0,
        },
        offset,
        FULL,
    )
}

/// A two-link planar arm with offsets 0.2 and -0.5 rad, on `base`, holding `tool`.
pub fn planar2_custom(a1: f64, a2: f64, base: Pose, tool: Pose) -> Robot {
    Robot::from_dh(
        "my planar",
        Convention::Standard,
        &[rv(a1, 0.0, 0.0, 0.2), rv(a2, 0.0, 0.0, -0.5)],
        base,
        tool,
    )
    .expect("valid")
}

/// The standard DH matrix `Rz(theta) Tz(d) Tx(a) Rx(alpha)`, written out (2.52).
pub fn dh_matrix(a: f64, alpha: f64, d: f64, theta: f64) -> nalgebra::Matrix4<f64> {
    let (st, ct) = theta.sin_cos();
    let (sa, ca) = alpha.sin_cos();
    #[rustfmt::skip]
    let m = nalgebra::Matrix4::new(
        ct, -st * ca, st * sa, a * ct,
        st, ct * ca, -ct * sa, a * st,
        0.0, sa, ca, d,
        0.0, 0.0, 0.0, 1.0,
    );
    m
}

/// Newton's method over six joints on a forward kinematics `fk` given by the test (finite
/// differences), from `q`: the joint vector if it meets `t` to 1e-10 in position (m) and in the
/// rotation matrix (so a half turn, where the residual below also vanishes, is no solution).
pub fn newton_on(
    fk: impl Fn(&[f64]) -> nalgebra::Matrix4<f64>,
    t: &Pose,
    mut q: Vec<f64>,
) -> Option<Vec<f64>> {
    let want = t.to_homogeneous();
    let resid = |q: &[f64]| -> nalgebra::Vector6<f64> {
        let m = fk(q);
        let dp = want.fixed_view::<3, 1>(0, 3) - m.fixed_view::<3, 1>(0, 3);
        // Half the sum of the axes' cross products (3.84).
        let mut eo = Vector3::zeros();
        for c in 0..3 {
            let a: Vector3<f64> = m.fixed_view::<3, 1>(0, c).into();
            let b: Vector3<f64> = want.fixed_view::<3, 1>(0, c).into();
            eo += a.cross(&b) * 0.5;
        }
        nalgebra::Vector6::new(dp.x, dp.y, dp.z, eo.x, eo.y, eo.z)
    };
    for _ in 0..60 {
        let e = resid(&q);
        if e.norm() < 1e-13 {
            let m = fk(&q);
            let dp = (m.fixed_view::<3, 1>(0, 3) - want.fixed_view::<3, 1>(0, 3)).norm();
            let dr = (m.fixed_view::<3, 3>(0, 0) - want.fixed_view::<3, 3>(0, 0)).norm();
            return (dp < 1e-10 && dr < 1e-10).then_some(q);
        }
        let mut j = nalgebra::Matrix6::zeros();
        for k in 0..6 {
            let mut qk = q.clone();
            qk[k] += 1e-7;
            j.set_column(k, &((e - resid(&qk)) / 1e-7));
        }
        let dq = j.lu().solve(&e)?;
        let scale = (0.4 / dq.amax()).min(1.0);
        for k in 0..6 {
            q[k] += dq[k] * scale;
        }
    }
    None
}

/// Whether `ARMLAB_EVIDENCE=full` asks for the long evidence runs.
pub fn full_evidence() -> bool {
    std::env::var("ARMLAB_EVIDENCE").is_ok_and(|v| v == "full")
}

/// Totals of [`all_solutions_evidence`].
#[derive(Debug, Default)]
pub struct Evidence {
    /// Solutions returned over all poses.
    pub solutions: usize,
    /// Newton starts that converged (each to a returned solution).
    pub converged: usize,
    /// The largest count for one pose.
    pub most: usize,
}

/// "All solutions" checked against the test's own forward kinematics `fk` (base and tool
/// included): for `poses` random configurations q in [-pi, pi]^6, the closed form of `robot` at
/// the pose fk(q) gives status Ok, at most `max` solutions, each meeting the pose to 1e-12 in
/// position (m) and rotation matrix, q itself among them, no duplicates, distinct labels (and
/// whatever `extra` asserts); a brute-force Newton search from `starts` random starts finds
/// nothing else.
pub fn all_solutions_evidence(
    robot: &Robot,
    fk: impl Fn(&[f64]) -> nalgebra::Matrix4<f64>,
    (poses, starts): (usize, usize),
    max: usize,
    seed: u64,
    extra: impl Fn(&IkResult),
) -> Evidence {
    use rand::{Rng, SeedableRng};
    let c = cf(robot);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut ev = Evidence::default();
    let random_q = |rng: &mut rand_chacha::ChaCha8Rng| -> Vec<f64> {
        (0..6).map(|_| rng.random_range(-PI..PI)).collect()
    };
    for _ in 0..poses {
        let q = random_q(&mut rng);
        let t = pose_from_matrix(&fk(&q)).unwrap();
        let want = t.to_homogeneous();
        let res = c.solve(robot, &Target::Pose(t)).unwrap();
        assert_eq!(res.status, IkStatus::Ok, "{}", show(&res));
        let n = res.solutions.len();
        assert!(n <= max, "{n} solutions\n{}", show(&res));
        extra(&res);
        ev.solutions += n;
        ev.most = ev.most.max(n);
        for s in &res.solutions {
            let m = fk(&s.q);
            let dp = (m.fixed_view::<3, 1>(0, 3) - want.fixed_view::<3, 1>(0, 3)).norm();
            let dr = (m.fixed_view::<3, 3>(0, 0) - want.fixed_view::<3, 3>(0, 0)).norm();
            assert!(dp < 1e-12 && dr < 1e-12, "{dp:e} {dr:e}\n{}", show(&res));
        }
        assert!(
            res.solutions.iter().any(|s| same_q(robot, &s.q, &q, 1e-9)),
            "{q:?} missing from\n{}",
            show(&res)
        );
        for (i, a) in res.solutions.iter().enumerate() {
            for b in &res.solutions[..i] {
                assert!(
                    !same_q(robot, &a.q, &b.q, 1e-9),
                    "duplicate\n{}",
                    show(&res)
                );
                assert_ne!(a.posture, b.posture, "labels\n{}", show(&res));
            }
        }
        for _ in 0..starts {
            if let Some(found) = newton_on(&fk, &t, random_q(&mut rng)) {
                ev.converged += 1;
                assert!(
                    res.solutions
                        .iter()
                        .any(|s| same_q(robot, &s.q, &found, 1e-6)),
                    "Newton found {found:?}, not among\n{}",
                    show(&res)
                );
            }
        }
    }
    ev
}

/// How many poses (of `poses` random configurations, fk(q) by the test) have 0, 1, ..., 16
/// solutions.
pub fn solution_counts(
    robot: &Robot,
    fk: impl Fn(&[f64]) -> nalgebra::Matrix4<f64>,
    poses: usize,
    seed: u64,
) -> [usize; 17] {
    use rand::{Rng, SeedableRng};
    let c = cf(robot);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut counts = [0usize; 17];
    for _ in 0..poses {
        let q: Vec<f64> = (0..6).map(|_| rng.random_range(-PI..PI)).collect();
        let t = pose_from_matrix(&fk(&q)).unwrap();
        counts[c.solve(robot, &Target::Pose(t)).unwrap().solutions.len()] += 1;
    }
    counts
}

/// (a, alpha, d) of six revolute DH rows (standard convention).
pub type Rows6 = [(f64, f64, f64); 6];

/// Base transform of the test arms built by [`arm6`] (nothing axis-aligned).
pub fn base6() -> Pose {
    Pose::translation(0.1, -0.2, 0.05) * rot_z(0.3)
}

/// Tool transform of the test arms built by [`arm6`].
pub fn tool6() -> Pose {
    Pose::translation(0.01, 0.02, 0.04) * rot_y(0.25)
}

/// Joint offsets of the test arms built by [`arm6`], so that theta = q + offset is exercised.
pub const OFFSETS6: [f64; 6] = [0.2, -0.4, 0.1, 0.0, 0.3, -0.1];

/// A six-revolute test arm: the rows with [`OFFSETS6`], [`base6`] and [`tool6`].
pub fn arm6(name: &str, rows: &Rows6) -> Robot {
    let r: Vec<Row> = rows
        .iter()
        .zip(OFFSETS6)
        .map(|(&(a, alpha, d), off)| rv(a, alpha, d, off))
        .collect();
    Robot::from_dh(name, Convention::Standard, &r, base6(), tool6()).unwrap()
}

/// The forward kinematics of [`arm6`] multiplied out here (2.52), base and tool included.
pub fn fk6(rows: &Rows6, q: &[f64]) -> nalgebra::Matrix4<f64> {
    let mut t = base6().to_homogeneous();
    for (i, &(a, alpha, d)) in rows.iter().enumerate() {
        t *= dh_matrix(a, alpha, d, q[i] + OFFSETS6[i]);
    }
    t * tool6().to_homogeneous()
}
