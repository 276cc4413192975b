//! Issue 27, the Universal Robots family (axes 2, 3, 4 parallel, no spherical wrist) in closed
//! form. "All solutions" is checked against computations written here, not against the solver:
//!
//! - the UR5 and UR10 DH tables from the vendor's documentation; every solution meets the target
//!   to 1e-12 by a forward kinematics written in this file, no two are the same (angles modulo
//!   2 pi), at most 8, exactly 8 for generic poses, and the joint vector that made the pose is
//!   among them;
//! - a brute-force multi-start Newton search (written here, with a finite-difference Jacobian
//!   of this file's forward kinematics) finds no solution the closed form missed;
//! - the UR5 URDF of the real-robot corpus gives the same solution set as the vendor's table.

use armlab::kinematics::ik::solver::{SolverChoice, solve};
use armlab::kinematics::ik::{ClosedForm, Target, numerical::NumericalOptions};
use armlab::kinematics::{Convention, DhJoint, DhRow, Pose, Robot};
use nalgebra::{Matrix4, Vector6};
use std::f64::consts::{FRAC_PI_2, PI};

/// The vendor's DH parameters (d1, a2, a3, d4, d5, d6), alpha = (pi/2, 0, 0, pi/2, -pi/2, 0).
const UR5: [f64; 6] = [0.089159, -0.425, -0.39225, 0.10915, 0.09465, 0.0823];
const UR10: [f64; 6] = [0.1273, -0.612, -0.5723, 0.163941, 0.1157, 0.0922];
const ALPHA: [f64; 6] = [FRAC_PI_2, 0.0, 0.0, FRAC_PI_2, -FRAC_PI_2, 0.0];

fn rows(p: &[f64; 6]) -> [(f64, f64, f64); 6] {
    // (a, alpha, d) per joint.
    [
        (0.0, ALPHA[0], p[0]),
        (p[1], ALPHA[1], 0.0),
        (p[2], ALPHA[2], 0.0),
        (0.0, ALPHA[3], p[3]),
        (0.0, ALPHA[4], p[4]),
        (0.0, ALPHA[5], p[5]),
    ]
}

fn robot(name: &str, p: &[f64; 6]) -> Robot {
    let joints: Vec<DhJoint> = rows(p)
        .iter()
        .map(|&(a, alpha, d)| {
            DhJoint::revolute(DhRow {
                a,
                alpha,
                d,
                theta: 0.0,
            })
            .limits(-2.0 * PI, 2.0 * PI)
        })
        .collect();
    Robot::from_dh(
        name,
        Convention::Standard,
        &joints,
        Pose::identity(),
        Pose::identity(),
    )
    .unwrap()
}

/// The forward kinematics written here: the product of (2.52) `Rz(q) Tz(d) Tx(a) Rx(alpha)`.
fn fk(p: &[f64; 6], q: &[f64]) -> Matrix4<f64> {
    fk_prefix(p, q, 6)
}

fn wrap(a: f64) -> f64 {
    (a + PI).rem_euclid(2.0 * PI) - PI
}

fn same(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.iter().zip(b).all(|(x, y)| wrap(x - y).abs() < tol)
}

/// A small deterministic generator (no test-only dependency).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn angles(&mut self) -> Vec<f64> {
        (0..6).map(|_| (self.next() * 2.0 - 1.0) * PI).collect()
    }
}

fn closed_form(r: &Robot, t: &Matrix4<f64>) -> Vec<Vec<f64>> {
    let pose = armlab::kinematics::pose::pose_from_matrix(t).unwrap();
    let (res, used) = solve(
        r,
        0,
        &Target::Pose(pose),
        None,
        SolverChoice::ClosedForm,
        &NumericalOptions::default(),
    )
    .unwrap();
    assert!(used.to_string().contains("three parallel"), "{used}");
    res.solutions.into_iter().map(|s| s.q).collect()
}

#[test]
fn every_solution_of_ur5_and_ur10_is_valid_distinct_and_the_original_is_found() {
    for (name, p) in [("UR5", UR5), ("UR10", UR10)] {
        let r = robot(name, &p);
        let cf = ClosedForm::detect(&r).unwrap();
        assert_eq!(cf.name(), "three parallel axes (Universal Robots type)");
        let mut rng = Lcg(7);
        let mut eights = 0;
        for _ in 0..300 {
            let q0 = rng.angles();
            let t = fk(&p, &q0);
            let sols = closed_form(&r, &t);
            // The formulas alone, before any Newton polish, are right to rounding.
            let pose = armlab::kinematics::pose::pose_from_matrix(&t).unwrap();
            let raw = cf.solve(&r, &Target::Pose(pose)).unwrap();
            for s in &raw.solutions {
                let e = (fk(&p, &s.q) - t).amax();
                assert!(e < 1e-9, "{name}: unpolished {} misses by {e:e}", s.posture);
            }
            assert!(sols.len() <= 8, "{name}: {} solutions", sols.len());
            eights += usize::from(sols.len() == 8);
            for (i, q) in sols.iter().enumerate() {
                let e = (fk(&p, q) - t).amax();
                assert!(e < 1e-12, "{name}: solution {i} misses by {e:e}");
                for other in &sols[..i] {
                    assert!(!same(q, other, 1e-9), "{name}: duplicate {q:?}");
                }
            }
            assert!(
                sols.iter().any(|q| same(q, &q0, 1e-7)),
                "{name}: {q0:?} not among {sols:?}"
            );
        }
        // Not every pose has all 8 (a branch can be out of reach); the brute-force search
        // below shows that none is missed.
        assert!(
            eights > 150,
            "{name}: 8 solutions for {eights} of 300 random poses"
        );
    }
}

/// Damped Newton on this file's forward kinematics (finite-difference Jacobian of the 12
/// numbers of the rotation and position), from `q`: the joint vector, if it converges.
fn newton(p: &[f64; 6], t: &Matrix4<f64>, mut q: Vec<f64>) -> Option<Vec<f64>> {
    let resid = |q: &[f64]| -> Vec<f64> {
        let m = fk(p, q) - t;
        (0..3)
            .flat_map(|r| (0..4).map(move |c| (r, c)))
            .map(|(r, c)| m[(r, c)])
            .collect()
    };
    for _ in 0..60 {
        let f = resid(&q);
        let norm = f.iter().map(|v| v * v).sum::<f64>().sqrt();
        if norm < 1e-13 {
            return Some(q);
        }
        let mut jac = nalgebra::DMatrix::zeros(12, 6);
        for k in 0..6 {
            let mut qk = q.clone();
            qk[k] += 1e-7;
            let fk2 = resid(&qk);
            for r in 0..12 {
                jac[(r, k)] = (fk2[r] - f[r]) / 1e-7;
            }
        }
        let jt = jac.transpose();
        let a = &jt * &jac + nalgebra::DMatrix::identity(6, 6) * 1e-9;
        let b = &jt * nalgebra::DVector::from_vec(f);
        let dq: Vector6<f64> = Vector6::from_iterator(a.lu().solve(&b)?.iter().copied());
        for k in 0..6 {
            q[k] -= dq[k].clamp(-0.5, 0.5);
        }
    }
    None
}

#[test]
fn a_brute_force_newton_search_finds_no_missed_solution() {
    let r = robot("UR5", &UR5);
    let mut rng = Lcg(11);
    let mut found = 0;
    for _ in 0..40 {
        let t = fk(&UR5, &rng.angles());
        let sols = closed_form(&r, &t);
        for _ in 0..300 {
            if let Some(q) = newton(&UR5, &t, rng.angles()) {
                // Converged to the pose: it must be one of the closed form's (to the Newton's
                // accuracy).
                assert!(
                    sols.iter().any(|s| same(s, &q, 1e-6)),
                    "Newton found {q:?}, not among {sols:?}"
                );
                found += 1;
            }
        }
    }
    assert!(
        found > 1000,
        "only {found} of 12000 starts converged: the search is too weak"
    );
}

#[test]
fn the_ur5_urdf_and_the_vendors_table_give_the_same_solutions() {
    let urdf = armlab::model_file::load_model("tests/data/urdf_corpus/ur5_robot.urdf").unwrap();
    let dh = robot("UR5", &UR5);
    let mut rng = Lcg(3);
    for _ in 0..50 {
        let q0 = rng.angles();
        // The same joint values: each model's own pose.
        let t_urdf = urdf.fk(&q0).unwrap();
        let a = closed_form(&urdf, &t_urdf.to_homogeneous());
        let b = closed_form(&dh, &fk(&UR5, &q0));
        assert_eq!(a.len(), b.len(), "{q0:?}");
        for q in &a {
            assert!(
                b.iter().any(|s| same(s, q, 1e-7)),
                "{q:?} only from the URDF"
            );
        }
    }
}

/// The elbow labels against the geometry, computed here: "elbow up" when the elbow (origin of
/// DH frame 2, on axis 3) lies above the line from the shoulder (frame 1) to the wrist (frame 3,
/// on axis 4) along the base z axis; shoulder right/left and wrist up/down come in pairs.
#[test]
fn the_labels_say_what_the_geometry_shows() {
    let r = robot("UR5", &UR5);
    let mut rng = Lcg(5);
    let origin = |q: &[f64], k: usize| {
        let m = fk_prefix(&UR5, q, k);
        nalgebra::Vector3::new(m[(0, 3)], m[(1, 3)], m[(2, 3)])
    };
    for _ in 0..100 {
        let t = fk(&UR5, &rng.angles());
        let pose = armlab::kinematics::pose::pose_from_matrix(&t).unwrap();
        let cf = ClosedForm::detect(&r).unwrap();
        let res = cf.solve(&r, &Target::Pose(pose)).unwrap();
        for s in &res.solutions {
            let (o1, o2, o3) = (origin(&s.q, 1), origin(&s.q, 2), origin(&s.q, 3));
            let u = (o3 - o1).normalize();
            let foot = o1 + u * u.dot(&(o2 - o1));
            let above = o2.z > foot.z;
            if s.posture.to_string().contains("elbow up") {
                assert!(above, "{}: the elbow is below", s.posture);
            } else if s.posture.to_string().contains("elbow down") {
                assert!(!above, "{}: the elbow is above", s.posture);
            }
        }
        let count = |w: &str| {
            res.solutions
                .iter()
                .filter(|s| s.posture.to_string().contains(w))
                .count()
        };
        if res.solutions.len() == 8 {
            for w in [
                "shoulder right",
                "shoulder left",
                "wrist up",
                "wrist down",
                "elbow up",
            ] {
                assert_eq!(count(w), 4, "{w}");
            }
        }
    }
}

/// Frame k in frame 0: the product of the first `k` rows (2.52).
fn fk_prefix(p: &[f64; 6], q: &[f64], k: usize) -> Matrix4<f64> {
    let mut t = Matrix4::identity();
    for (&(a, alpha, d), &th) in rows(p).iter().zip(q).take(k) {
        let (st, ct) = th.sin_cos();
        let (sa, ca) = alpha.sin_cos();
        t *= Matrix4::new(
            ct,
            -st * ca,
            st * sa,
            a * ct,
            st,
            ct * ca,
            -ct * sa,
            a * st,
            0.0,
            sa,
            ca,
            d,
            0.0,
            0.0,
            0.0,
            1.0,
        );
    }
    t
}
