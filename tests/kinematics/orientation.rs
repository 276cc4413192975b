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
