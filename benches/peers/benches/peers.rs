//! armlab's closed-form IK side by side with its peers in one run (issue 27):
//!
//! - the UR5 (the corpus URDF): armlab's three-parallel family against ik-geo's
//!   `three_parallel_two_intersecting` (the solver of its `ur5()`);
//! - the general six-revolute arm of `tests/kinematics/ik_general6.rs`: armlab's elimination against
//!   ik-geo's `gen_six_dof`;
//! - the ABB IRB 2400/10 (OPW parameters of rs-opw-kinematics): armlab's spherical-wrist family
//!   (the labelled `solve_into`, and the raw `solve_raw`) against `OPWKinematics::inverse`.
//!
//! Every solver gets the same poses (FK of random joint vectors), each in its own frames: the arm
//! is taken to a product of exponentials (axis and point of each joint at q = 0, read off the
//! arm's own forward kinematics) and rebuilt as a URDF for armlab or as `h`, `p` for ik-geo, and
//! the bench checks that the forward kinematics agree before timing. Before the timings it prints,
//! per solver, the mean number of returned vectors per pose and of valid ones: distinct (1e-6 rad)
//! and FK-checked to 1e-9 (m and rad) by armlab's forward kinematics of the same arm.

use armlab::kinematics::ik::closed_form::{RawSolutions, Solutions, Verify};
use armlab::kinematics::ik::{ClosedForm, Target};
use armlab::kinematics::{Pose, Robot};
use criterion::{Criterion, criterion_group, criterion_main};
use ik_geo::robot::IKSolver;
use nalgebra::{Matrix3, Rotation3, Translation3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rs_opw_kinematics::kinematic_traits::Kinematics;
use std::hint::black_box;

/// An arm as a product of exponentials: joint axes `h` and points on them `o` (base frame,
/// q = 0), and the tool's pose at q = 0.
struct Poe {
    h: [Vector3<f64>; 6],
    o: [Vector3<f64>; 6],
    home: Pose,
}

/// The product of exponentials of an arm with forward kinematics `fk` (six revolute joints):
/// `fk(e_i) fk(0)^-1` is a rotation by 1 rad about joint i's axis, whose axis is `h_i` and
/// whose fixed points give `o_i` (the one nearest the base origin).
fn poe_of(fk: impl Fn(&[f64; 6]) -> Pose) -> Poe {
    let home = fk(&[0.0; 6]);
    let mut h = [Vector3::zeros(); 6];
    let mut o = [Vector3::zeros(); 6];
    for i in 0..6 {
        let mut q = [0.0; 6];
        q[i] = 1.0;
        let d = fk(&q) * home.inverse();
        let (axis, angle) = d.rotation.axis_angle().expect("a joint turns the tool");
        assert!(
            (angle - 1.0).abs() < 1e-9,
            "joint {i} is not a unit-rate revolute joint"
        );
        h[i] = axis.into_inner();
        // (I - R) o = t has a line of solutions; the least-norm one via the pseudo-inverse.
        let a = Matrix3::identity() - d.rotation.matrix();
        let svd = a.svd(true, true);
        o[i] = svd.solve(&d.translation.vector, 1e-12).expect("svd");
    }
    // IK-Geo's convention: where consecutive axes meet, both points are the meeting point (its
    // solvers for such families take the vector between them to be zero).
    for i in 0..5 {
        if let Some(m) = meeting(h[i], o[i], h[i + 1], o[i + 1]) {
            o[i] = m;
            o[i + 1] = m;
        }
    }
    Poe { h, o, home }
}

/// The point where the lines `o1 + s h1` and `o2 + t h2` meet (closer than 1e-9 m, not
/// parallel), if they do.
fn meeting(
    h1: Vector3<f64>,
    o1: Vector3<f64>,
    h2: Vector3<f64>,
    o2: Vector3<f64>,
) -> Option<Vector3<f64>> {
    let n = h1.cross(&h2);
    if n.norm() < 1e-9 {
        return None;
    }
    let w = o2 - o1;
    if (w.dot(&n) / n.norm()).abs() > 1e-9 {
        return None;
    }
    // o1 + s h1 = o2 + t h2: s = ((o2 - o1) x h2) . n / |n|^2.
    let s = w.cross(&h2).dot(&n) / n.norm_squared();
    Some(o1 + h1 * s)
}

/// The arm of `poe` as a URDF whose link frames are all parallel to the base at q = 0, the tool
/// frame at the home position with the base's orientation (poses for it are `T R_home^-1`).
fn urdf_of(poe: &Poe) -> String {
    let mut s = String::from("<robot name=\"poe\"><link name=\"l0\"/>\n");
    let mut prev = Vector3::zeros();
    for i in 0..6 {
        let (x, a) = (poe.o[i] - prev, poe.h[i]);
        s += &format!(
            "<joint name=\"j{}\" type=\"revolute\"><parent link=\"l{i}\"/><child link=\"l{}\"/>\
             <origin xyz=\"{} {} {}\"/><axis xyz=\"{} {} {}\"/>\
             <limit lower=\"-6.2832\" upper=\"6.2832\" effort=\"1\" velocity=\"1\"/></joint>\
             <link name=\"l{}\"/>\n",
            i + 1,
            i + 1,
            x.x,
            x.y,
            x.z,
            a.x,
            a.y,
            a.z,
            i + 1
        );
        prev = poe.o[i];
    }
    let t = poe.home.translation.vector - prev;
    s += &format!(
        "<joint name=\"tool\" type=\"fixed\"><parent link=\"l6\"/><child link=\"tool\"/>\
         <origin xyz=\"{} {} {}\"/></joint><link name=\"tool\"/></robot>\n",
        t.x, t.y, t.z
    );
    s
}

/// `pose` for the URDF of [`urdf_of`] (its tool keeps the base's orientation).
fn stripped(poe: &Poe, pose: &Pose) -> Pose {
    Pose::from_parts(
        pose.translation,
        pose.rotation * poe.home.rotation.inverse(),
    )
}

/// ik-geo's kinematics of `poe`: `h` the axes, `p` the vectors from joint to joint (base frame,
/// q = 0), its `p_6T` the tool point (ik-geo's tool has the base's orientation).
fn ik_geo_kin(
    poe: &Poe,
) -> (
    nalgebra_ikgeo::Matrix3x6<f64>,
    nalgebra_ikgeo::SMatrix<f64, 3, 7>,
) {
    let mut h = nalgebra_ikgeo::Matrix3x6::zeros();
    let mut p = nalgebra_ikgeo::SMatrix::<f64, 3, 7>::zeros();
    let mut prev = Vector3::zeros();
    for i in 0..6 {
        for r in 0..3 {
            h[(r, i)] = poe.h[i][r];
            p[(r, i)] = poe.o[i][r] - prev[r];
        }
        prev = poe.o[i];
    }
    for r in 0..3 {
        p[(r, 6)] = poe.home.translation.vector[r] - prev[r];
    }
    (h, p)
}

/// `(rotation, translation)` of a pose in ik-geo's nalgebra.
fn ik_geo_pose(p: &Pose) -> (nalgebra_ikgeo::Matrix3<f64>, nalgebra_ikgeo::Vector3<f64>) {
    let m = p.rotation.matrix();
    let r = nalgebra_ikgeo::Matrix3::from_fn(|i, j| m[(i, j)]);
    let t = p.translation.vector;
    (r, nalgebra_ikgeo::Vector3::new(t.x, t.y, t.z))
}

/// Angle difference wrapped to (-pi, pi].
fn wrap(a: f64) -> f64 {
    let t = a.rem_euclid(std::f64::consts::TAU);
    if t > std::f64::consts::PI {
        t - std::f64::consts::TAU
    } else {
        t
    }
}

/// Distinct joint vectors among `sols` that reach `target` to 1e-9 (m and rad) by `robot`'s FK.
fn valid(robot: &Robot, target: &Pose, sols: &[[f64; 6]]) -> usize {
    let mut kept: Vec<[f64; 6]> = Vec::new();
    for q in sols {
        if q.iter().any(|v| !v.is_finite()) {
            continue;
        }
        let Ok(p) = robot.fk(q) else { continue };
        let dp = (p.translation.vector - target.translation.vector).norm();
        // Frobenius norm of the rotation difference (~ the angle; `angle()` is NaN near 0).
        let dr = (p.rotation.matrix() - target.rotation.matrix()).norm();
        let dup = kept
            .iter()
            .any(|k| k.iter().zip(q).all(|(a, b)| wrap(a - b).abs() < 1e-6));
        if dp < 1e-9 && dr < 1e-9 && !dup {
            kept.push(*q);
        }
    }
    kept.len()
}

/// `n` poses of `robot` at random joint vectors in (-pi, pi) (seeded).
fn poses(robot: &Robot, n: usize) -> Vec<Pose> {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    (0..n)
        .map(|_| {
            let q: Vec<f64> = (0..6).map(|_| rng.random_range(-3.1..3.1)).collect();
            robot.fk(&q).expect("fk")
        })
        .collect()
}

/// Mean returned and valid solutions per pose of a solver.
fn report(name: &str, counts: &[(usize, usize)]) {
    let n = counts.len() as f64;
    let ret: usize = counts.iter().map(|c| c.0).sum();
    let ok: usize = counts.iter().map(|c| c.1).sum();
    println!(
        "{name}: {:.2} vectors per pose, {:.2} valid (distinct, FK to 1e-9), over {} poses",
        ret as f64 / n,
        ok as f64 / n,
        counts.len()
    );
}

/// armlab's robot from the URDF of a product of exponentials, checked against `fk` at random q.
fn rebuilt(poe: &Poe, fk: impl Fn(&[f64; 6]) -> Pose) -> Robot {
    let robot = armlab::model_file::parse_model_text("poe.urdf", &urdf_of(poe)).expect("URDF");
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    for _ in 0..20 {
        let q: [f64; 6] = std::array::from_fn(|_| rng.random_range(-3.0..3.0));
        let a = robot.fk(&q).expect("fk");
        let b = stripped(poe, &fk(&q));
        assert!(
            (a.translation.vector - b.translation.vector).norm() < 1e-12
                && (a.rotation.matrix() - b.rotation.matrix()).norm() < 1e-12,
            "the rebuilt arm's FK differs at {q:?}: {} m, {} rad\n{a}\n{b}",
            (a.translation.vector - b.translation.vector).norm(),
            (a.rotation.matrix() - b.rotation.matrix()).norm()
        );
    }
    robot
}

/// armlab against ik-geo on one arm (its FK `fk`), ik-geo's solver `make`.
fn against_ik_geo(
    c: &mut Criterion,
    name: &str,
    arm: &Robot,
    make: fn(
        nalgebra_ikgeo::Matrix3x6<f64>,
        nalgebra_ikgeo::SMatrix<f64, 3, 7>,
    ) -> ik_geo::robot::Robot,
    ik_geo_name: &str,
) {
    let fk = |q: &[f64; 6]| arm.fk(q).expect("fk");
    let poe = poe_of(fk);
    let robot = rebuilt(&poe, fk);
    let (h, p) = ik_geo_kin(&poe);
    let geo = make(h, p);
    // ik-geo's own forward kinematics agrees with the rebuilt arm's.
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for _ in 0..20 {
        let q: [f64; 6] = std::array::from_fn(|_| rng.random_range(-3.0..3.0));
        let (r, x) = geo.fk(&q);
        let (r0, x0) = ik_geo_pose(&robot.fk(&q).expect("fk"));
        assert!(
            (r - r0).norm() < 1e-12 && (x - x0).norm() < 1e-12,
            "{name}: ik-geo's FK of the converted arm differs"
        );
    }
    let cf = ClosedForm::detect(&robot).expect("armlab's closed form");
    let targets: Vec<Pose> = poses(&robot, 200);
    let geo_targets: Vec<_> = targets.iter().map(ik_geo_pose).collect();
    // Solution counts, on the same poses.
    let mut raw = RawSolutions::default();
    let ours: Vec<(usize, usize)> = targets
        .iter()
        .map(|t| {
            cf.solve_raw(t, &mut raw).expect("pose");
            let q: Vec<[f64; 6]> = raw.q[..raw.len]
                .iter()
                .map(|v| std::array::from_fn(|k| v[k]))
                .collect();
            (q.len(), valid(&robot, t, &q))
        })
        .collect();
    report(&format!("{name}: armlab"), &ours);
    let theirs: Vec<(usize, usize)> = targets
        .iter()
        .zip(&geo_targets)
        .map(|(t, (r, x))| {
            let q: Vec<[f64; 6]> = geo
                .ik(*r, *x)
                .iter()
                .map(|(v, _)| std::array::from_fn(|k| v[k]))
                .collect();
            (q.len(), valid(&robot, t, &q))
        })
        .collect();
    report(&format!("{name}: ik-geo {ik_geo_name}"), &theirs);
    // Valid ik-geo solutions that armlab did not return (1e-6 rad apart from all of its).
    let mut missed = 0;
    for (t, (r, x)) in targets.iter().zip(&geo_targets) {
        cf.solve_raw(t, &mut raw).expect("pose");
        for (v, _) in geo.ik(*r, *x) {
            let q: [f64; 6] = std::array::from_fn(|k| v[k]);
            let ours = raw.q[..raw.len]
                .iter()
                .any(|o| q.iter().zip(o).all(|(a, b)| wrap(a - b).abs() < 1e-6));
            if valid(&robot, t, &[q]) == 1 && !ours {
                missed += 1;
            }
        }
    }
    println!("{name}: valid ik-geo solutions armlab did not return: {missed}");
    let mut i = 0;
    c.bench_function(&format!("peers/{name}/armlab_solve_raw"), |b| {
        b.iter(|| {
            i = (i + 1) % targets.len();
            cf.solve_raw(black_box(&targets[i]), &mut raw)
                .expect("pose");
            raw.len
        })
    });
    let mut sols = Solutions::default();
    let tt: Vec<Target> = targets.iter().map(|p| Target::Pose(*p)).collect();
    let mut i = 0;
    c.bench_function(&format!("peers/{name}/armlab_solve_into"), |b| {
        b.iter(|| {
            i = (i + 1) % tt.len();
            cf.solve_into(&robot, black_box(&tt[i]), Verify::Limits, &mut sols)
                .expect("pose");
            sols.len()
        })
    });
    let mut i = 0;
    c.bench_function(&format!("peers/{name}/ik_geo_{ik_geo_name}"), |b| {
        b.iter(|| {
            i = (i + 1) % geo_targets.len();
            let (r, x) = geo_targets[i];
            geo.ik(black_box(r), black_box(x)).len()
        })
    });
}

/// The UR5 from the real-robot corpus, its tool at `tool0`.
fn ur5() -> Robot {
    armlab::model_file::load_model("../../tests/data/urdf_corpus/ur5_robot.urdf").expect("UR5")
}

/// The general arm of `tests/kinematics/ik_general6.rs` (no two axes parallel or meeting).
fn general6() -> Robot {
    use armlab::kinematics::{Convention, DhJoint, DhRow};
    let arm = [
        (-0.16783737474333676, 1.0052561698243567, 0.2659782754010333),
        (
            -0.20021619228968035,
            -2.0083552205516653,
            0.5956370685537575,
        ),
        (0.2936438967887273, -1.0416631758468398, 0.5822396042478765),
        (-0.5561143422303767, 3.1085585463184633, 0.2553345078792291),
        (0.30384208036121435, -0.9355901363914724, 0.5776510034128405),
        (
            0.00958484907078212,
            1.9354200442639786,
            -0.13873531864068797,
        ),
    ];
    let joints: Vec<DhJoint> = arm
        .iter()
        .map(|&(a, alpha, d)| {
            let row = DhRow {
                a,
                alpha,
                d,
                theta: 0.0,
            };
            DhJoint::revolute(row).limits(-std::f64::consts::PI, std::f64::consts::PI)
        })
        .collect();
    Robot::from_dh(
        "general6",
        Convention::Standard,
        &joints,
        Pose::identity(),
        Pose::identity(),
    )
    .expect("general arm")
}

fn ur5_and_general(c: &mut Criterion) {
    against_ik_geo(
        c,
        "ur5",
        &ur5(),
        ik_geo::robot::three_parallel_two_intersecting,
        "three_parallel_two_intersecting",
    );
    against_ik_geo(
        c,
        "general6",
        &general6(),
        ik_geo::robot::gen_six_dof,
        "gen_six_dof",
    );
}

/// armlab's pose of an OPW pose (glam) and back.
fn from_opw(p: &rs_opw_kinematics::kinematic_traits::Pose) -> Pose {
    let q = p.rotation;
    let r =
        nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q.w, q.x, q.y, q.z));
    Pose::from_parts(
        Translation3::new(p.translation.x, p.translation.y, p.translation.z),
        Rotation3::from(r),
    )
}

/// An OPW pose (glam) of armlab's.
fn to_opw(p: &Pose) -> rs_opw_kinematics::kinematic_traits::Pose {
    let q = nalgebra::UnitQuaternion::from_rotation_matrix(&p.rotation);
    let t = p.translation.vector;
    rs_opw_kinematics::kinematic_traits::Pose {
        translation: glam::DVec3::new(t.x, t.y, t.z),
        rotation: glam::DQuat::from_xyzw(q.i, q.j, q.k, q.w),
    }
}

/// The ABB IRB 2400/10: armlab's spherical-wrist family against rs-opw-kinematics.
fn spherical_wrist(c: &mut Criterion) {
    use rs_opw_kinematics::kinematics_impl::OPWKinematics;
    use rs_opw_kinematics::parameters::opw_kinematics::Parameters;
    let opw = OPWKinematics::new(Parameters::irb2400_10());
    let fk = |q: &[f64; 6]| from_opw(&opw.forward(q));
    let poe = poe_of(fk);
    let robot = rebuilt(&poe, fk);
    let cf = ClosedForm::detect(&robot).expect("armlab's closed form");
    let full: Vec<Pose> = {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        (0..200)
            .map(|_| {
                let q: [f64; 6] = std::array::from_fn(|_| rng.random_range(-3.1..3.1));
                fk(&q)
            })
            .collect()
    };
    let ours_t: Vec<Target> = full
        .iter()
        .map(|p| Target::Pose(stripped(&poe, p)))
        .collect();
    let theirs_t: Vec<_> = full.iter().map(to_opw).collect();
    let mut sols = Solutions::default();
    let ours: Vec<(usize, usize)> = ours_t
        .iter()
        .map(|t| {
            cf.solve_into(&robot, t, Verify::Limits, &mut sols)
                .expect("pose");
            let q: Vec<[f64; 6]> = sols
                .iter()
                .map(|s| std::array::from_fn(|k| s.q()[k]))
                .collect();
            let Target::Pose(p) = t else { unreachable!() };
            (q.len(), valid(&robot, p, &q))
        })
        .collect();
    report("irb2400: armlab solve_into", &ours);
    let theirs: Vec<(usize, usize)> = theirs_t
        .iter()
        .zip(&ours_t)
        .map(|(t, o)| {
            let q = opw.inverse(t);
            let Target::Pose(p) = o else { unreachable!() };
            (q.len(), valid(&robot, p, &q))
        })
        .collect();
    report("irb2400: rs-opw-kinematics inverse", &theirs);
    let mut i = 0;
    c.bench_function("peers/irb2400/armlab_solve_into", |b| {
        b.iter(|| {
            i = (i + 1) % ours_t.len();
            cf.solve_into(&robot, black_box(&ours_t[i]), Verify::Limits, &mut sols)
                .expect("pose");
            sols.len()
        })
    });
    let mut raw = RawSolutions::default();
    let mut i = 0;
    c.bench_function("peers/irb2400/armlab_solve_raw", |b| {
        b.iter(|| {
            i = (i + 1) % ours_t.len();
            let Target::Pose(p) = &ours_t[i] else {
                unreachable!()
            };
            cf.solve_raw(black_box(p), &mut raw).expect("pose");
            raw.len
        })
    });
    let mut i = 0;
    c.bench_function("peers/irb2400/opw_inverse", |b| {
        b.iter(|| {
            i = (i + 1) % theirs_t.len();
            opw.inverse(black_box(&theirs_t[i])).len()
        })
    });
}

criterion_group!(benches, spherical_wrist, ur5_and_general);
criterion_main!(benches);
