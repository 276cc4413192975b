//! Jacobians against central finite differences of the direct kinematics, for every built-in
//! model and every end-effector (couplings included).

use armlab::kinematics::models::BUILT_INS;
use armlab::kinematics::{EulerKind, Robot};
use nalgebra::{Matrix6xX, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const H: f64 = 1e-6;

fn random_q(r: &Robot, rng: &mut ChaCha8Rng) -> Vec<f64> {
    r.limits()
        .iter()
        .map(|l| rng.random_range(l[0]..=l[1]))
        .collect()
}

/// Geometric Jacobian by central differences: linear part from p, angular part from
/// vee(R_dot R^T).
fn fd_geometric(r: &Robot, q: &[f64], ee: usize) -> Matrix6xX<f64> {
    let mut j = Matrix6xX::zeros(r.dof());
    for k in 0..r.dof() {
        let (mut qp, mut qm) = (q.to_vec(), q.to_vec());
        qp[k] += H;
        qm[k] -= H;
        let (tp, tm) = (r.fk_ee(&qp, ee).unwrap(), r.fk_ee(&qm, ee).unwrap());
        let dp = (tp.translation.vector - tm.translation.vector) / (2.0 * H);
        let rdot = (tp.rotation.matrix() - tm.rotation.matrix()) / (2.0 * H);
        let s = rdot * r.fk_ee(q, ee).unwrap().rotation.matrix().transpose();
        let w = Vector3::new(
            s[(2, 1)] - s[(1, 2)],
            s[(0, 2)] - s[(2, 0)],
            s[(1, 0)] - s[(0, 1)],
        ) * 0.5;
        j.fixed_view_mut::<3, 1>(0, k).copy_from(&dp);
        j.fixed_view_mut::<3, 1>(3, k).copy_from(&w);
    }
    j
}

#[test]
fn geometric_jacobian_matches_finite_differences() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for b in BUILT_INS {
        let r = (b.build)();
        for _ in 0..50 {
            let q = random_q(&r, &mut rng);
            for ee in 0..r.end_effectors().len() {
                let j = r.jacobian(&q, ee).unwrap();
                let fd = fd_geometric(&r, &q, ee);
                let err = (j - &fd).amax();
                assert!(err < 1e-7, "{}: ee {ee} q {q:?} error {err:e}", b.name);
            }
        }
    }
}

#[test]
fn analytical_jacobian_matches_finite_differences() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for name in [
        "anthropomorphic_spherical_wrist",
        "puma560",
        "stanford",
        "panda",
    ] {
        let r = armlab::kinematics::models::built_in(name).unwrap();
        for kind in EulerKind::ALL {
            let mut checked = 0;
            while checked < 50 {
                let q = random_q(&r, &mut rng);
                let Ok(ja) = r.analytical_jacobian(&q, 0, kind) else {
                    continue;
                };
                let x0 = r.operational(&q, 0, kind).unwrap();
                // Stay away from the representation's singularity and the +-pi cut of atan2.
                if x0[3].abs() > 3.0
                    || x0[5].abs() > 3.0
                    || (x0[4].sin().abs() < 0.1 && kind != EulerKind::Rpy)
                    || (x0[4].cos().abs() < 0.1 && kind == EulerKind::Rpy)
                {
                    continue;
                }
                for k in 0..r.dof() {
                    let (mut qp, mut qm) = (q.clone(), q.clone());
                    qp[k] += H;
                    qm[k] -= H;
                    let d = (r.operational(&qp, 0, kind).unwrap()
                        - r.operational(&qm, 0, kind).unwrap())
                        / (2.0 * H);
                    let err = (ja.column(k) - d).amax();
                    assert!(err < 1e-6, "{name} {kind:?} column {k}: {err:e}");
                }
                checked += 1;
            }
        }
    }
}

#[test]
fn analytical_jacobian_reports_representation_singularity() {
    let r = armlab::kinematics::models::built_in("anthropomorphic_spherical_wrist").unwrap();
    // theta5 = 0 with the arm at zero: R = Rz(...) about z0 only, ZYZ theta = 0.
    let err = r
        .analytical_jacobian(&[0.0; 6], 0, EulerKind::Zyz)
        .unwrap_err();
    assert!(err.to_string().contains("ZYZ"), "{err}");
}

#[test]
fn rank_and_manipulability() {
    let r = armlab::kinematics::models::built_in("anthropomorphic_spherical_wrist").unwrap();
    // Generic pose: full rank.
    let a = r
        .analyze_jacobian(&[0.1, 0.7, 0.4, 0.3, 0.9, 0.2], 0)
        .unwrap();
    assert_eq!(a.rank, 6);
    assert!(a.manipulability > 0.0);
    // Wrist singularity theta5 = 0: rank 5, manipulability 0.
    let a = r
        .analyze_jacobian(&[0.1, 0.7, 0.4, 0.3, 0.0, 0.2], 0)
        .unwrap();
    assert_eq!(a.rank, 5);
    assert!(a.min_singular_value() < 1e-12 && a.manipulability < 1e-12);
    // Two-link arm: manipulability of the position rows is a1 a2 |s2| (Sect. 3.9).
    let p2 = armlab::kinematics::models::built_in("planar2").unwrap();
    let j = p2.jacobian(&[0.3, 0.8], 0).unwrap();
    let jp = nalgebra::DMatrix::from_fn(2, 2, |i, k| j[(i, k)]);
    let m = armlab::kinematics::jacobian::analyze(&jp).manipulability;
    assert!((m - 0.8f64.sin()).abs() < 1e-14);
}
