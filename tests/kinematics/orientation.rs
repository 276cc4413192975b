//! Round trips of every orientation representation (Sect. 2.4), singular cases included.

use armlab::kinematics::orientation::*;
use nalgebra::{Rotation3, Unit, UnitQuaternion, Vector3};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

fn close(a: &Rotation3<f64>, b: &Rotation3<f64>) -> f64 {
    (a.matrix() - b.matrix()).amax()
}

fn any_rotation() -> impl Strategy<Value = Rotation3<f64>> {
    (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64, 0.0..PI).prop_filter_map("axis", |(x, y, z, a)| {
        let v = Vector3::new(x, y, z);
        (v.norm() > 1e-3).then(|| Rotation3::from_axis_angle(&Unit::new_normalize(v), a))
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn zyz_round_trip(r in any_rotation()) {
        let o = zyz_from_rotation(&r);
        prop_assert!(o.angles[1] >= 0.0 && o.angles[1] <= PI);
        prop_assert!(close(&rotation_from_zyz(&o.angles), &r) < 1e-14);
        let n = zyz_from_rotation_negative(&r);
        prop_assert!(n.angles[1] <= 0.0 && n.angles[1] >= -PI);
        prop_assert!(close(&rotation_from_zyz(&n.angles), &r) < 1e-14);
    }

    #[test]
    fn zyz_angles_round_trip(phi in -3.1..3.1f64, theta in 1e-3..(PI - 1e-3), psi in -3.1..3.1f64) {
        let a = Vector3::new(phi, theta, psi);
        let o = zyz_from_rotation(&rotation_from_zyz(&a));
        prop_assert!((o.angles - a).amax() < 1e-10, "{:?} vs {:?}", o.angles, a);
    }

    #[test]
    fn rpy_round_trip(r in any_rotation()) {
        let o = rpy_from_rotation(&r);
        prop_assert!(o.angles[1].abs() <= FRAC_PI_2);
        prop_assert!(close(&rotation_from_rpy(&o.angles), &r) < 1e-14);
    }

    #[test]
    fn rpy_angles_round_trip(phi in -3.1..3.1f64, theta in -1.57..1.57f64, psi in -3.1..3.1f64) {
        let a = Vector3::new(phi, theta, psi);
        let o = rpy_from_rotation(&rotation_from_rpy(&a));
        prop_assert!((o.angles - a).amax() < 1e-9);
    }

    #[test]
    fn angle_axis_round_trip(r in any_rotation()) {
        let aa = angle_axis_from_rotation(&r);
        prop_assert!((0.0..=PI).contains(&aa.angle));
        prop_assert!((aa.axis.norm() - 1.0).abs() < 1e-14);
        prop_assert!(close(&rotation_from_angle_axis(aa.angle, &aa.axis), &r) < 1e-13);
    }

    #[test]
    fn quaternion_round_trip(r in any_rotation()) {
        let q = quaternion_from_rotation(&r);
        prop_assert!(q.w >= 0.0);
        prop_assert!(close(&rotation_from_quaternion(&q), &r) < 1e-14);
        // Each representation converts into each other one through the rotation matrix.
        let aa = angle_axis_from_rotation(&rotation_from_quaternion(&q));
        let back = quaternion_from_rotation(&rotation_from_angle_axis(aa.angle, &aa.axis));
        prop_assert!((back.coords - q.coords).amax() < 1e-13);
    }

    /// Near-singular rotations (theta a hair from 0 or pi) round-trip to within SINGULAR_EPS.
    #[test]
    fn near_singular_round_trips(phi in -3.1..3.1f64, eps in 0.0..1e-9f64, psi in -3.1..3.1f64, at_pi in any::<bool>()) {
        let theta = if at_pi { PI - eps } else { eps };
        let r = rotation_from_zyz(&Vector3::new(phi, theta, psi));
        prop_assert!(close(&rotation_from_zyz(&zyz_from_rotation(&r).angles), &r) < 2.0 * SINGULAR_EPS);
        let r = rotation_from_rpy(&Vector3::new(phi, if at_pi { FRAC_PI_2 - eps } else { eps - FRAC_PI_2 }, psi));
        prop_assert!(close(&rotation_from_rpy(&rpy_from_rotation(&r).angles), &r) < 2.0 * SINGULAR_EPS);
        let r = Rotation3::from_axis_angle(&Unit::new_normalize(Vector3::new(phi, psi, 1.0)), PI - eps);
        let aa = angle_axis_from_rotation(&r);
        prop_assert!(close(&rotation_from_angle_axis(aa.angle, &aa.axis), &r) < 1e-13);
    }
}

/// Problem 2.2: ZYZ with theta = 0 or pi determines only phi +- psi; phi = 0 is chosen.
#[test]
fn zyz_singular_cases() {
    let r = rotation_from_zyz(&Vector3::new(0.7, 0.0, 0.4));
    let o = zyz_from_rotation(&r);
    assert!(o.singular);
    assert_eq!(o.angles[0], 0.0);
    assert!((o.angles[2] - 1.1).abs() < 1e-15);
    let r = rotation_from_zyz(&Vector3::new(0.7, PI, 0.4));
    let o = zyz_from_rotation(&r);
    assert!(o.singular && o.angles.iter().all(|a| a.is_finite()));
    assert!((o.angles[1] - PI).abs() < 1e-15);
    assert!(close(&rotation_from_zyz(&o.angles), &r) < 1e-15);
    let o = zyz_from_rotation(&Rotation3::identity());
    assert_eq!(o.angles, Vector3::zeros());
}

/// Problem 2.3: RPY with theta = +-pi/2.
#[test]
fn rpy_singular_cases() {
    for theta in [FRAC_PI_2, -FRAC_PI_2] {
        let r = rotation_from_rpy(&Vector3::new(0.3, theta, -0.8));
        let o = rpy_from_rotation(&r);
        assert!(o.singular && o.angles[0] == 0.0);
        assert!(close(&rotation_from_rpy(&o.angles), &r) < 1e-15);
    }
}

/// Problem 2.5: angle-axis at theta = 0 (axis arbitrary) and theta = pi (sign ambiguous).
#[test]
fn angle_axis_singular_cases() {
    let aa = angle_axis_from_rotation(&Rotation3::identity());
    assert!(aa.singular && aa.angle == 0.0 && aa.axis.into_inner() == Vector3::z());
    for axis in [
        Vector3::x(),
        Vector3::y(),
        Vector3::z(),
        Vector3::new(1.0, -1.0, 1.0),
        Vector3::new(0.0, -3.0, 4.0),
    ] {
        let u = Unit::new_normalize(axis);
        let r = Rotation3::from_axis_angle(&u, PI);
        let aa = angle_axis_from_rotation(&r);
        assert!((aa.angle - PI).abs() < 1e-15);
        assert!(
            (aa.axis.into_inner() - u.into_inner()).amax() < 1e-15
                || (aa.axis.into_inner() + u.into_inner()).amax() < 1e-15
        );
        let k = (0..3)
            .max_by(|&a, &b| aa.axis[a].abs().total_cmp(&aa.axis[b].abs()))
            .unwrap();
        assert!(aa.axis[k] > 0.0, "largest component positive at pi");
        assert!(close(&rotation_from_angle_axis(aa.angle, &aa.axis), &r) < 1e-15);
    }
}

/// eta >= 0; a half turn has eta = 0 and the largest epsilon component positive.
#[test]
fn quaternion_sign_choices() {
    use nalgebra::Matrix3;
    let half_x = Rotation3::from_matrix_unchecked(Matrix3::new(
        1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, -1.0,
    ));
    let q = quaternion_from_rotation(&half_x);
    assert_eq!(q.w, 0.0);
    assert!(q.i > 0.0);
    let half_y = Rotation3::from_matrix_unchecked(Matrix3::new(
        -1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, -1.0,
    ));
    let q = quaternion_from_rotation(&half_y);
    assert!(q.w == 0.0 && q.j > 0.0);
    let q = quaternion_from_rotation(&Rotation3::identity());
    assert_eq!(q, UnitQuaternion::identity());
    let e = quaternion(0.5, Vector3::new(0.5, 0.5, 0.5));
    assert!(
        (rotation_from_quaternion(&e).matrix()
            - Rotation3::from_axis_angle(
                &Unit::new_normalize(Vector3::new(1.0, 1.0, 1.0)),
                2.0 * PI / 3.0
            )
            .matrix())
        .amax()
            < 1e-15
    );
}

#[test]
fn wrap_angle_range() {
    assert_eq!(wrap_angle(PI), PI);
    assert_eq!(wrap_angle(-PI), PI);
    assert!((wrap_angle(3.0 * PI / 2.0) + FRAC_PI_2).abs() < 1e-15);
    assert!((wrap_angle(-7.0) - (-7.0 + 2.0 * PI)).abs() < 1e-15);
}

// ---------------------------------------------------------------------------------------------
// Issue 47: every representation of the chapter, against matrices written out in this file.
// ---------------------------------------------------------------------------------------------

use nalgebra::{Matrix3, Matrix4};

/// A small xorshift generator, so that the 10,000 rotations are the same on every run.
struct XorShift(u64);

impl XorShift {
    fn next(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        self.0 = x;
        x
    }
    /// Uniform in [lo, hi).
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.next() >> 11) as f64 / (1u64 << 53) as f64)
    }
    /// A uniformly distributed rotation: Rz(a) Ry(acos(u)) Rz(c), all hand-written.
    fn rotation(&mut self) -> Matrix3<f64> {
        let (a, c) = (self.range(-PI, PI), self.range(-PI, PI));
        let b = self.range(-1.0, 1.0).acos();
        hz(a) * hy(b) * hz(c)
    }
    fn unit_vector(&mut self) -> Vector3<f64> {
        loop {
            let v = Vector3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            let n = v.norm();
            if n > 0.1 && n <= 1.0 {
                return v / n;
            }
        }
    }
}

// The elementary rotations, written out here from the textbook's figures, not the library.
fn hx(a: f64) -> Matrix3<f64> {
    let (c, s) = (a.cos(), a.sin());
    Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c)
}
fn hy(a: f64) -> Matrix3<f64> {
    let (c, s) = (a.cos(), a.sin());
    Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c)
}
fn hz(a: f64) -> Matrix3<f64> {
    let (c, s) = (a.cos(), a.sin());
    Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}
fn hand(axis: Axis, a: f64) -> Matrix3<f64> {
    match axis {
        Axis::X => hx(a),
        Axis::Y => hy(a),
        Axis::Z => hz(a),
    }
}
/// The matrix of a set of angles, multiplied out here from the elementary rotations.
fn hand_euler(kind: EulerKind, a: &Vector3<f64>) -> Matrix3<f64> {
    match kind {
        EulerKind::Zyz => hz(a[0]) * hy(a[1]) * hz(a[2]),
        EulerKind::Zxz => hz(a[0]) * hx(a[1]) * hz(a[2]),
        EulerKind::Rpy => hz(a[0]) * hy(a[1]) * hx(a[2]),
    }
}
/// Rodrigues' formula, written here as the sum of the three terms.
fn hand_angle_axis(theta: f64, r: &Vector3<f64>) -> Matrix3<f64> {
    let s = Matrix3::new(0.0, -r.z, r.y, r.z, 0.0, -r.x, -r.y, r.x, 0.0);
    Matrix3::identity() * theta.cos() + r * r.transpose() * (1.0 - theta.cos()) + s * theta.sin()
}
/// The rotation of a unit quaternion, from the rotation of a vector by q v q*, column by
/// column, with the quaternion product written here.
fn hand_quaternion(eta: f64, eps: &Vector3<f64>) -> Matrix3<f64> {
    let rotate = |v: Vector3<f64>| {
        // q v = {-eps.v, eta v + eps x v}; (q v) q* with q* = {eta, -eps}.
        let (w1, v1) = (-eps.dot(&v), v * eta + eps.cross(&v));
        v1 * eta - eps * w1 - v1.cross(eps)
    };
    Matrix3::from_columns(&[
        rotate(Vector3::x()),
        rotate(Vector3::y()),
        rotate(Vector3::z()),
    ])
}
fn rot(m: Matrix3<f64>) -> Rotation3<f64> {
    Rotation3::from_matrix_unchecked(m)
}

#[test]
fn elementary_rotations_are_the_hand_written_ones() {
    let mut rng = XorShift(0x5eed_0047);
    for _ in 0..1000 {
        let a = rng.range(-2.0 * PI, 2.0 * PI);
        for axis in [Axis::X, Axis::Y, Axis::Z] {
            assert!((elementary(axis, a).matrix() - hand(axis, a)).amax() < 1e-15);
        }
    }
    // Tiny angles are not rounded to the identity.
    assert_eq!(elementary(Axis::X, 1e-20).matrix()[(2, 1)], 1e-20);
}

/// ZYZ (2.18), ZXZ (Problem 2.1) and RPY (2.21) against the products of elementary matrices
/// written in this file, and the ZXZ entries of Problem 2.1 written out.
#[test]
fn euler_matrices_are_the_products_of_elementary_rotations() {
    let mut rng = XorShift(47);
    for _ in 0..10_000 {
        let a = Vector3::new(rng.range(-PI, PI), rng.range(-PI, PI), rng.range(-PI, PI));
        for kind in EulerKind::ALL {
            let err = (kind.to_rotation(&a).matrix() - hand_euler(kind, &a)).amax();
            assert!(err < 1e-15, "{kind:?} {a:?}: {err:e}");
        }
        let (cp, sp, ct, st, cs, ss) = (
            a[0].cos(),
            a[0].sin(),
            a[1].cos(),
            a[1].sin(),
            a[2].cos(),
            a[2].sin(),
        );
        let m = rotation_from_zxz(&a);
        assert!((m[(0, 0)] - (cp * cs - sp * ct * ss)).abs() < 1e-15);
        assert!((m[(0, 2)] - sp * st).abs() < 1e-15 && (m[(1, 2)] + cp * st).abs() < 1e-15);
        assert!((m[(2, 0)] - st * ss).abs() < 1e-15 && (m[(2, 1)] - st * cs).abs() < 1e-15);
    }
}

/// 10,000 uniformly random rotations through every representation and back; every solution
/// reproduces the matrix through the hand-written products.
#[test]
fn every_conversion_round_trips_on_10000_random_rotations() {
    let mut rng = XorShift(0xa11_0047);
    for _ in 0..10_000 {
        let m = rng.rotation();
        let r = rot(m);
        for kind in EulerKind::ALL {
            let s = euler_solutions(kind, &r);
            assert!(!s.singular() && s.solutions.len() == 2, "{kind:?} {m}");
            for a in &s.solutions {
                let err = (hand_euler(kind, a) - m).amax();
                assert!(err < 1e-14, "{kind:?} {a:?}: {err:e}");
                assert!(a.iter().all(|x| (-PI..=PI).contains(x)));
            }
            let (t1, t2) = (s.solutions[0][1], s.solutions[1][1]);
            match kind {
                EulerKind::Rpy => assert!(t1.abs() <= FRAC_PI_2 && t2.abs() >= FRAC_PI_2),
                _ => assert!(t1 >= 0.0 && t2 <= 0.0),
            }
            // The fast path gives the first solution.
            assert_eq!(kind.from_rotation(&r).angles, s.solutions[0]);
        }
        let aa = angle_axis_from_rotation(&r);
        assert!((0.0..=PI).contains(&aa.angle));
        assert!((hand_angle_axis(aa.angle, &aa.axis) - m).amax() < 1e-14);
        assert!((rotation_from_angle_axis(aa.angle, &aa.axis).matrix() - m).amax() < 1e-14);
        let q = quaternion_from_rotation(&r);
        assert!(q.w >= 0.0 && (q.coords.norm() - 1.0).abs() < 1e-15);
        assert!((hand_quaternion(q.w, &q.imag()) - m).amax() < 1e-14);
        assert!((rotation_from_quaternion(&q).matrix() - m).amax() < 1e-14);
        // eta = cos(theta/2), epsilon = sin(theta/2) r (2.30)-(2.31).
        assert!((q.w - (aa.angle / 2.0).cos()).abs() < 1e-12);
        assert!((q.imag() - aa.axis.into_inner() * (aa.angle / 2.0).sin()).amax() < 1e-12);
    }
}

/// Angles -> matrix -> angles gives the same angles back where they lie in the first
/// solution's range, and the other solution's formula otherwise.
#[test]
fn angles_round_trip_through_the_matrix() {
    let mut rng = XorShift(2_0047);
    for _ in 0..10_000 {
        let a = Vector3::new(
            rng.range(-3.1, 3.1),
            rng.range(0.01, PI - 0.01),
            rng.range(-3.1, 3.1),
        );
        for kind in [EulerKind::Zyz, EulerKind::Zxz] {
            let s = euler_solutions(kind, &rot(hand_euler(kind, &a)));
            assert!((s.solutions[0] - a).amax() < 1e-12, "{kind:?} {a:?} {s:?}");
            let other = Vector3::new(wrap_angle(a[0] + PI), -a[1], wrap_angle(a[2] + PI));
            let d = s.solutions[1] - other;
            assert!(
                d.iter().all(|x| wrap_angle(*x).abs() < 1e-12),
                "{kind:?} {d:?}"
            );
        }
        let b = Vector3::new(a[0], a[1] - FRAC_PI_2, a[2]); // theta in (-pi/2, pi/2)
        let s = euler_solutions(EulerKind::Rpy, &rot(hand_euler(EulerKind::Rpy, &b)));
        assert!((s.solutions[0] - b).amax() < 1e-12, "{b:?} {s:?}");
        let other = Vector3::new(b[0] + PI, PI - b[1], b[2] + PI);
        let d = s.solutions[1] - other;
        assert!(d.iter().all(|x| wrap_angle(*x).abs() < 1e-12), "{d:?}");
    }
}

/// The singular sets: ZYZ and ZXZ at theta = 0 and pi, RPY at theta = +-pi/2. The family's
/// combination and value are those of the angles the matrix was made from, and every member of
/// the family multiplies out to the same matrix.
#[test]
fn singular_families_are_named_and_every_member_reproduces_the_matrix() {
    let mut rng = XorShift(3_0047);
    let cases = [
        (EulerKind::Zyz, 0.0, Combination::PhiPlusPsi),
        (EulerKind::Zyz, PI, Combination::PhiMinusPsi),
        (EulerKind::Zxz, 0.0, Combination::PhiPlusPsi),
        (EulerKind::Zxz, PI, Combination::PhiMinusPsi),
        (EulerKind::Rpy, FRAC_PI_2, Combination::PhiMinusPsi),
        (EulerKind::Rpy, -FRAC_PI_2, Combination::PhiPlusPsi),
        // As the CLI makes them, from degrees.
        (
            EulerKind::Zyz,
            180f64.to_radians(),
            Combination::PhiMinusPsi,
        ),
        (EulerKind::Rpy, 90f64.to_radians(), Combination::PhiMinusPsi),
        (
            EulerKind::Rpy,
            (-90f64).to_radians(),
            Combination::PhiPlusPsi,
        ),
    ];
    for (kind, theta, combination) in cases {
        for _ in 0..1000 {
            let (phi, psi) = (rng.range(-PI, PI), rng.range(-PI, PI));
            let m = hand_euler(kind, &Vector3::new(phi, theta, psi));
            let s = euler_solutions(kind, &rot(m));
            let family = s.family.expect("singular");
            assert_eq!(family.combination, combination, "{kind:?} theta {theta}");
            let expected = match combination {
                Combination::PhiPlusPsi => phi + psi,
                Combination::PhiMinusPsi => phi - psi,
            };
            assert!(wrap_angle(family.value - expected).abs() < 1e-12);
            assert_eq!(s.solutions.len(), 1);
            assert_eq!(s.solutions[0][0], 0.0);
            assert!((hand_euler(kind, &s.solutions[0]) - m).amax() < 1e-14);
            // Any other member: choose phi freely, psi from the constraint.
            let t = rng.range(-PI, PI);
            let psi_t = match combination {
                Combination::PhiPlusPsi => family.value - t,
                Combination::PhiMinusPsi => t - family.value,
            };
            let member = Vector3::new(t, s.solutions[0][1], psi_t);
            assert!((hand_euler(kind, &member) - m).amax() < 1e-14);
            // The other representations of the same singular matrices.
            let aa = angle_axis_from_rotation(&rot(m));
            assert!((hand_angle_axis(aa.angle, &aa.axis) - m).amax() < 1e-14);
            let q = quaternion_from_rotation(&rot(m));
            assert!(q.w >= 0.0 && (hand_quaternion(q.w, &q.imag()) - m).amax() < 1e-14);
        }
    }
}

/// Problems 2.2 and 2.3 in words, from the typed family.
#[test]
fn singular_families_in_words() {
    let deg = f64::to_radians;
    let r = rot(hz(deg(30.0)) * hz(deg(45.0)));
    let s = euler_solutions(EulerKind::Zyz, &r);
    assert_eq!(
        s.family.unwrap().to_string(),
        "only phi + psi is determined: 75°"
    );
    assert_eq!(
        s.to_string(),
        "singular (theta = 0°): only phi + psi is determined: 75°; with phi = 0: (0°, 0°, 75°)"
    );
    let r = rot(hand_euler(
        EulerKind::Rpy,
        &Vector3::new(deg(50.0), deg(90.0), deg(20.0)),
    ));
    let s = euler_solutions(EulerKind::Rpy, &r);
    assert_eq!(
        s.family.unwrap().to_string(),
        "only phi - psi is determined: 30°"
    );
    assert_eq!(s.family.unwrap().combination.as_str(), "phi-psi");
    let s = euler_solutions(
        EulerKind::Zyz,
        &rot(hand_euler(
            EulerKind::Zyz,
            &Vector3::new(deg(30.0), deg(45.0), deg(60.0)),
        )),
    );
    assert_eq!(
        s.to_string(),
        "(phi, theta, psi) = (30°, 45°, 60°) or (-150°, -45°, -120°)"
    );
}

/// sin(theta) = 0 for angle and axis (Problem 2.5): theta = 0 any axis, theta = pi r and -r.
#[test]
fn angle_axis_cases_of_problem_2_5() {
    let none = angle_axis_solutions(&Rotation3::identity());
    assert_eq!(none.case, AngleAxisCase::AnyAxis);
    assert!(none.axes.is_empty() && none.angle == 0.0);
    assert!(none.to_string().contains("any axis"));
    let mut rng = XorShift(5_0047);
    for _ in 0..1000 {
        let r = rng.unit_vector();
        let m = hand_angle_axis(PI, &r);
        let s = angle_axis_solutions(&rot(m));
        assert_eq!(s.case, AngleAxisCase::HalfTurn, "{r:?}");
        assert_eq!(s.axes.len(), 2);
        assert!((s.angle - PI).abs() < 1e-15);
        let (a, b) = (s.axes[0].into_inner(), s.axes[1].into_inner());
        assert!((a + b).amax() == 0.0);
        assert!((a - r).amax() < 1e-14 || (a + r).amax() < 1e-14);
        assert_eq!(a.max(), a.amax(), "r has its largest component positive");
        for axis in [a, b] {
            assert!((hand_angle_axis(PI, &axis) - m).amax() < 1e-14);
        }
        // The quaternion of a half turn: eta = 0 (to rounding), epsilon = +-r.
        let q = quaternion_from_rotation(&rot(m));
        assert!(q.w >= 0.0 && q.w < 1e-15);
        assert!((q.imag() - r).amax() < 1e-14 || (q.imag() + r).amax() < 1e-14);
        assert!((hand_quaternion(q.w, &q.imag()) - m).amax() < 1e-14);
        // Regular: one axis, and (-theta, -r) is the same rotation.
        let theta = rng.range(1e-6, PI - 1e-6);
        let m = hand_angle_axis(theta, &r);
        let s = angle_axis_solutions(&rot(m));
        assert_eq!(s.case, AngleAxisCase::Regular);
        assert!((s.angle - theta).abs() < 1e-9 && (s.axes[0].into_inner() - r).amax() < 1e-9);
        assert!((hand_angle_axis(-s.angle, &-s.axes[0].into_inner()) - m).amax() < 1e-14);
    }
}

/// The product (2.37) is the matrix product, and the inverse (2.36) the transpose.
#[test]
fn quaternion_product_is_the_matrix_product() {
    let mut rng = XorShift(6_0047);
    for _ in 0..10_000 {
        let (m1, m2) = (rng.rotation(), rng.rotation());
        let (q1, q2) = (
            quaternion_from_rotation(&rot(m1)),
            quaternion_from_rotation(&rot(m2)),
        );
        let q = quaternion_product(&q1, &q2);
        assert!((hand_quaternion(q.w, &q.imag()) - m1 * m2).amax() < 1e-14);
        let inv = quaternion_inverse(&q1);
        assert!((hand_quaternion(inv.w, &inv.imag()) - m1.transpose()).amax() < 1e-14);
        // The product written out against Hamilton's product of the components.
        let (a, b) = (q1.coords, q2.coords); // (x, y, z, w)
        let w = a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2];
        let x = a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1];
        assert!((q.w - w).abs() < 1e-15 && (q.i - x).abs() < 1e-15);
    }
}

/// (2.45): the inverse of a homogeneous transform times the transform is the identity.
#[test]
fn inverse_homogeneous_times_the_transform_is_the_identity() {
    let mut rng = XorShift(7_0047);
    for _ in 0..1000 {
        let mut t = Matrix4::identity();
        t.fixed_view_mut::<3, 3>(0, 0).copy_from(&rng.rotation());
        for k in 0..3 {
            t[(k, 3)] = rng.range(-2.0, 2.0);
        }
        let inv = inverse_homogeneous(&t);
        assert!((inv * t - Matrix4::identity()).amax() < 1e-14);
        assert!((t * inv - Matrix4::identity()).amax() < 1e-14);
        assert_eq!(inv.row(3), Matrix4::<f64>::identity().row(3));
    }
}

/// Problem 2.16: the commutator of two finite elementary rotations over the angle squared tends
/// to sqrt(2) (= |S(a x b)|); the first-order matrices commute but for a second-order term.
#[test]
fn commutator_shrinks_as_the_angle_squared() {
    let pairs = [(Axis::X, Axis::Y), (Axis::Y, Axis::Z), (Axis::Z, Axis::X)];
    for (a, b) in pairs {
        let mut last = f64::INFINITY;
        // Down to 1e-4: below, rounding of the O(1) entries (1e-16) swamps the a^2 commutator.
        for k in 1..=4 {
            let angle = 10f64.powi(-k);
            let (ma, mb) = (hand(a, angle), hand(b, angle));
            let hand_norm = (ma * mb - mb * ma).norm();
            let n = commutator_norm(a, b, angle);
            assert!((n - hand_norm).abs() < 1e-15 + 1e-12 * n);
            let gap = (n / (angle * angle) - 2f64.sqrt()).abs();
            assert!(gap < last, "{a:?} {b:?}: the ratio does not settle");
            assert!(gap < 0.5 * angle, "{a:?} {b:?} at {angle}: {gap}");
            last = gap;
            let first_order = infinitesimal_commutator_norm(a, b, angle);
            assert!((first_order - 2f64.sqrt() * angle * angle).abs() < 1e-15 * angle);
        }
        assert_eq!(commutator_norm(a, a, 0.3), 0.0);
        assert_eq!(infinitesimal_commutator_norm(b, b, 0.3), 0.0);
    }
    // R(dphi) = I + S(dphi) is Rx Ry Rz of the small angles to first order.
    let d = Vector3::new(1e-5, -2e-5, 3e-5);
    let product = hx(d.x) * hy(d.y) * hz(d.z);
    assert!((infinitesimal(&d) - product).amax() < 1e-9);
}

/// Problem 2.15: the sum defined by composition does not commute.
#[test]
fn the_sum_of_minimal_representations_does_not_commute() {
    let mut rng = XorShift(8_0047);
    for kind in EulerKind::ALL {
        for _ in 0..200 {
            let a = Vector3::new(
                rng.range(-3.0, 3.0),
                rng.range(0.1, 1.4),
                rng.range(-3.0, 3.0),
            );
            let b = Vector3::new(
                rng.range(-3.0, 3.0),
                rng.range(0.1, 1.4),
                rng.range(-3.0, 3.0),
            );
            let c = sum_comparison(kind, &a, &b);
            let (ab, ba) = (
                hand_euler(kind, &a) * hand_euler(kind, &b),
                hand_euler(kind, &b) * hand_euler(kind, &a),
            );
            assert!((hand_euler(kind, &c.sum) - ab).amax() < 1e-13);
            assert!((hand_euler(kind, &c.reversed) - ba).amax() < 1e-13);
            let cos = ((ab.transpose() * ba).trace() - 1.0) / 2.0;
            assert!((c.order_angle.cos() - cos).abs() < 1e-12);
            let naive = hand_euler(kind, &(a + b));
            let cos = ((naive.transpose() * ab).trace() - 1.0) / 2.0;
            assert!((c.naive_angle.cos() - cos).abs() < 1e-12);
        }
    }
}

/// Composition about current axes post-multiplies, about fixed axes pre-multiplies; a list
/// about the current axes ends where the reversed list about the fixed axes does.
#[test]
fn composition_about_current_and_fixed_axes() {
    let mut rng = XorShift(9_0047);
    for _ in 0..2000 {
        let n = (rng.next() % 6) as usize;
        let steps: Vec<Step> = (0..n)
            .map(|_| Step {
                frame: if rng.next().is_multiple_of(2) {
                    StepFrame::Current
                } else {
                    StepFrame::Fixed
                },
                axis: [Axis::X, Axis::Y, Axis::Z][(rng.next() % 3) as usize],
                angle: rng.range(-PI, PI),
            })
            .collect();
        let partial = partial_products(&steps);
        assert_eq!(partial.len(), n);
        let mut m = Matrix3::identity();
        for (s, p) in steps.iter().zip(&partial) {
            m = match s.frame {
                StepFrame::Current => m * hand(s.axis, s.angle),
                StepFrame::Fixed => hand(s.axis, s.angle) * m,
            };
            assert!((p.matrix() - m).amax() < 1e-14);
        }
        assert!((compose(&steps).matrix() - m).amax() < 1e-14);
        // All about the current axes, against the list reversed with all about the fixed axes.
        let with = |frame, list: &mut dyn Iterator<Item = &Step>| -> Vec<Step> {
            list.map(|s| Step { frame, ..*s }).collect()
        };
        let current = compose(&with(StepFrame::Current, &mut steps.iter()));
        let reversed_fixed = compose(&with(StepFrame::Fixed, &mut steps.iter().rev()));
        assert!((current.matrix() - reversed_fixed.matrix()).amax() < 1e-14);
        let m_current = steps
            .iter()
            .fold(Matrix3::identity(), |m, s| m * hand(s.axis, s.angle));
        assert!((current.matrix() - m_current).amax() < 1e-14);
    }
    let s = Step {
        frame: StepFrame::Current,
        axis: Axis::Z,
        angle: 30f64.to_radians(),
    };
    assert_eq!(s.to_string(), "current Rz(30°)");
    assert_eq!(
        serde_json::to_value(s).unwrap(),
        serde_json::json!({"frame": "current", "axis": "z", "angle": 30f64.to_radians()})
    );
}

/// T(phi) of every representation against finite differences of the hand-written matrices:
/// `S(omega) dt = R(phi + phi_dot dt) R(phi)^T - I` to first order.
#[test]
fn angular_velocity_maps_match_finite_differences() {
    let mut rng = XorShift(10_0047);
    let h = 1e-6;
    for kind in EulerKind::ALL {
        for _ in 0..200 {
            let a = Vector3::new(
                rng.range(-3.0, 3.0),
                rng.range(0.2, 1.3),
                rng.range(-3.0, 3.0),
            );
            let rate = Vector3::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            );
            let plus = hand_euler(kind, &(a + rate * h));
            let minus = hand_euler(kind, &(a - rate * h));
            let w = (plus - minus) / (2.0 * h) * hand_euler(kind, &a).transpose();
            let omega = Vector3::new(w[(2, 1)], w[(0, 2)], w[(1, 0)]);
            let mapped = angular_velocity_map(kind, &a) * rate;
            assert!((mapped - omega).amax() < 1e-8, "{kind:?} {a:?}");
        }
    }
}

/// Every representation of one rotation at once.
#[test]
fn representations_of_one_rotation() {
    let deg = f64::to_radians;
    let m = hand_euler(
        EulerKind::Zyz,
        &Vector3::new(deg(30.0), deg(45.0), deg(60.0)),
    );
    let all = Representations::of(&rot(m));
    assert_eq!(all.matrix.matrix(), &m);
    for kind in EulerKind::ALL {
        let s = all.euler(kind);
        assert_eq!(s.kind, kind);
        for a in &s.solutions {
            assert!((hand_euler(kind, a) - m).amax() < 1e-14);
        }
    }
    assert!((all.zyz.solutions[0] - Vector3::new(deg(30.0), deg(45.0), deg(60.0))).amax() < 1e-14);
    let aa = &all.axis_angle;
    assert!((hand_angle_axis(aa.angle, &aa.axes[0]) - m).amax() < 1e-14);
    let q = all.quaternion;
    assert!(q.w >= 0.0 && (hand_quaternion(q.w, &q.imag()) - m).amax() < 1e-14);
    assert_eq!(degrees(deg(-120.0)), "-120");
}
