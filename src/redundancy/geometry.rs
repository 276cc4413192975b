//! Geometry shared by the exact self-motion solvers: rotations about axes, Paden-Kahan
//! subproblems 1 and 2, closest points of lines, and angle bookkeeping.

use nalgebra::{Matrix3, Rotation3, Unit, Vector3};
use std::f64::consts::{PI, TAU};

/// Rotation about unit axis `w` by `t` (rad).
pub(crate) fn rot(w: &Vector3<f64>, t: f64) -> Rotation3<f64> {
    Rotation3::from_axis_angle(&Unit::new_unchecked(*w), t)
}

/// `Rot(w, t) v` by Rodrigues' formula (no matrix).
#[inline(always)]
pub(crate) fn rotv(w: &Vector3<f64>, t: f64, v: &Vector3<f64>) -> Vector3<f64> {
    let (st, ct) = crate::kinematics::trig::sin_cos(t);
    v * ct + w.cross(v) * st + w * (w.dot(v) * (1.0 - ct))
}

/// `Rot(w, t) v` from the sine and cosine of t (no trigonometric call).
#[inline(always)]
pub(crate) fn rotv_sc(w: &Vector3<f64>, st: f64, ct: f64, v: &Vector3<f64>) -> Vector3<f64> {
    v * ct + w.cross(v) * st + w * (w.dot(v) * (1.0 - ct))
}

/// An angle with its sine and cosine.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Angle {
    /// The angle (rad).
    pub t: f64,
    /// sin t.
    pub s: f64,
    /// cos t.
    pub c: f64,
}

/// [`sub1`] with the sine and cosine of the angle, read off the atan2 arguments.
#[inline(always)]
pub(crate) fn sub1_sc(w: &Vector3<f64>, p: &Vector3<f64>, q: &Vector3<f64>) -> Angle {
    let pp = p - w * w.dot(p);
    let qq = q - w * w.dot(q);
    let (y, x) = (w.dot(&pp.cross(&qq)), pp.dot(&qq));
    // Not `hypot`: x and y are products of bounded vectors (no overflow), and hypot's care costs
    // more than the rest of the subproblem.
    let r = (x * x + y * y).sqrt();
    let (s, c) = if r > 0.0 { (y / r, x / r) } else { (0.0, 1.0) };
    Angle {
        t: y.atan2(x),
        s,
        c,
    }
}

/// Subproblem 1: the angle t with Rot(w, t) p = q (p, q of equal components along w).
pub(crate) fn sub1(w: &Vector3<f64>, p: &Vector3<f64>, q: &Vector3<f64>) -> f64 {
    let pp = p - w * w.dot(p);
    let qq = q - w * w.dot(q);
    w.dot(&pp.cross(&qq)).atan2(pp.dot(&qq))
}

/// Both solutions of [`sub2_sc`] (sign +1, then -1), sharing the work they have in common.
#[inline(always)]
pub(crate) fn sub2_pair_sc(
    w1: &Vector3<f64>,
    w2: &Vector3<f64>,
    p: &Vector3<f64>,
    q: &Vector3<f64>,
) -> Option<[(Angle, Angle); 2]> {
    let c12 = w1.dot(w2);
    let den = c12 * c12 - 1.0;
    if den.abs() < 1e-12 {
        return None;
    }
    let (w2p, w1q) = (w2.dot(p), w1.dot(q));
    let alpha = (c12 * w2p - w1q) / den;
    let beta = (c12 * w1q - w2p) / den;
    let x = w1.cross(w2);
    let g2 = (p.norm_squared() - alpha * alpha - beta * beta - 2.0 * alpha * beta * c12)
        / x.norm_squared();
    if g2 < -1e-10 * p.norm_squared().max(1e-30) {
        return None;
    }
    let base = w1 * alpha + w2 * beta;
    let off = x * g2.max(0.0).sqrt();
    Some([base + off, base - off].map(|c| (sub1_sc(w1, &c, q), sub1_sc(w2, p, &c))))
}

/// Subproblem 2: the angles (t1, t2) with Rot(w1, t1) Rot(w2, t2) p = q, for `sign` = +1 or -1
/// (the two solutions), with their sines and cosines; `None` when there is none (beyond
/// rounding).
pub(crate) fn sub2_sc(
    w1: &Vector3<f64>,
    w2: &Vector3<f64>,
    p: &Vector3<f64>,
    q: &Vector3<f64>,
    sign: f64,
) -> Option<(Angle, Angle)> {
    let c12 = w1.dot(w2);
    let den = c12 * c12 - 1.0;
    if den.abs() < 1e-12 {
        return None;
    }
    let alpha = (c12 * w2.dot(p) - w1.dot(q)) / den;
    let beta = (c12 * w1.dot(q) - w2.dot(p)) / den;
    let x = w1.cross(w2);
    let g2 = (p.norm_squared() - alpha * alpha - beta * beta - 2.0 * alpha * beta * c12)
        / x.norm_squared();
    if g2 < -1e-10 * p.norm_squared().max(1e-30) {
        return None;
    }
    let c = w1 * alpha + w2 * beta + x * (sign * g2.max(0.0).sqrt());
    Some((sub1_sc(w1, &c, q), sub1_sc(w2, p, &c)))
}

pub(crate) use crate::construction::meet;

/// The orthonormal frame of `a` and the part of `b` perpendicular to it, as columns.
pub(crate) fn triad(a: &Vector3<f64>, b: &Vector3<f64>) -> Matrix3<f64> {
    let x = a.normalize();
    let y = (b - x * x.dot(b)).normalize();
    Matrix3::from_columns(&[x, y, x.cross(&y)])
}

/// The roots psi (rad) of `a sin psi + b cos psi + c = 0`.
pub(crate) fn trig_roots(a: f64, b: f64, c: f64, out: &mut Vec<f64>) {
    // Not `hypot` (slow): a and b are products of bounded vectors.
    let r = (a * a + b * b).sqrt();
    if r < 1e-14 || c.abs() > r {
        return;
    }
    let phase = a.atan2(b);
    let d = (-c / r).clamp(-1.0, 1.0).acos();
    out.push(phase + d);
    out.push(phase - d);
}

/// Each angle shifted by a multiple of 2 pi into its limits where one fits, else wrapped to
/// (-pi, pi].
pub(crate) fn wrap_into<const N: usize>(q: [f64; N], limits: &[[f64; 2]]) -> [f64; N] {
    std::array::from_fn(|k| {
        let [lo, hi] = limits[k];
        let base = q[k] - TAU * ((q[k] + PI) / TAU).floor();
        [base, base - TAU, base + TAU]
            .into_iter()
            .find(|v| *v >= lo - 1e-12 && *v <= hi + 1e-12)
            .unwrap_or(base)
    })
}

/// Whether every angle lies within its limits (slack 1e-12 rad).
pub(crate) fn within(q: &[f64], limits: &[[f64; 2]]) -> bool {
    q.iter()
        .zip(limits)
        .all(|(v, l)| *v >= l[0] - 1e-12 && *v <= l[1] + 1e-12)
}

/// Directions and points of the 7 axes (world), and the tool pose, at q = 0.
pub(crate) type Axes7 = (
    [Vector3<f64>; 7],
    [Vector3<f64>; 7],
    crate::kinematics::Pose,
);

/// The joint axes of a 7R robot with one end-effector at q = 0 (unit directions, a point on
/// each, world) and its tool pose there; `None` for any other robot.
pub(crate) fn axes_7r(robot: &crate::kinematics::Robot) -> Option<Axes7> {
    use crate::kinematics::JointKind;
    if robot.dof() != 7
        || robot.end_effectors().len() != 1
        || (0..7).any(|k| robot.dof_joint(k).kind != JointKind::Revolute)
    {
        return None;
    }
    let q0 = [0.0; 7];
    let jac = robot.jacobian(&q0, 0).ok()?;
    let t0 = robot.fk(&q0).ok()?;
    let pe = t0.translation.vector;
    let mut w = [Vector3::zeros(); 7];
    let mut o = [Vector3::zeros(); 7];
    for k in 0..7 {
        let c = jac.column(k);
        w[k] = Vector3::new(c[3], c[4], c[5]).normalize();
        o[k] = pe + w[k].cross(&Vector3::new(c[0], c[1], c[2]));
    }
    Some((w, o, t0))
}

/// A unit vector perpendicular to each axis (for subproblem 1 about it).
pub(crate) fn probes(w: &[Vector3<f64>; 7]) -> [Vector3<f64>; 7] {
    w.map(|a| {
        let h = if a.x.abs() < 0.9 {
            Vector3::x()
        } else {
            Vector3::y()
        };
        (h - a * a.dot(&h)).normalize()
    })
}

/// The angle q4 (rad) about the unit axis `w4` with `|a + Rot(w4, q4) b| = l` (m), branch `sign`
/// (+1 or -1) of the law of cosines; `None` out of reach.
pub(crate) fn elbow_angle(
    a: &Vector3<f64>,
    b: &Vector3<f64>,
    w4: &Vector3<f64>,
    l: f64,
    sign: f64,
) -> Option<f64> {
    // |a + R4 b|^2 = |a|^2 + |b|^2 + 2 (a.b_par + cos q4 a.b_perp + sin q4 a.(w4 x b))
    let b_par = w4 * w4.dot(b);
    let b_perp = b - b_par;
    let k = 0.5 * (l * l - a.norm_squared() - b.norm_squared()) - a.dot(&b_par);
    let (c, s) = (a.dot(&b_perp), a.dot(&w4.cross(b)));
    let r = c.hypot(s);
    if r < 1e-15 || k.abs() > r * (1.0 + 1e-12) {
        return None;
    }
    Some(s.atan2(c) + sign * (k / r).clamp(-1.0, 1.0).acos())
}
