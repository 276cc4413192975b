//! The exact self-motion of SRS 7R arms (three intersecting shoulder axes, an elbow, three
//! intersecting wrist axes: the DLR arm, the KUKA LWR4) parameterised by the **arm angle** psi
//! (Shimizu et al., IEEE T-RO 2008): the rotation of the elbow about the shoulder-to-wrist axis,
//! measured from the reference plane that the arm's elbow spans with joint 3 at zero, positive by
//! the right-hand rule about the axis pointing from shoulder S to wrist W.
//!
//! The structure is read from the joint axes at q = 0 (product of exponentials), not from the
//! robot's name or DH convention: with spatial rotations R_i = Rot(omega_i, q_i) about the zero-
//! configuration axes, `R(q) = R_1 ... R_7 R(0)`, the wrist centre `W = S + R_1 R_2 R_3 (E_0 - S +
//! R_4 (W_0 - E_0))` and the elbow `E = S + R_1 R_2 R_3 (E_0 - S)`. Then
//! - |W - S| depends on q4 only: two elbow solutions (law of cosines about axis 4);
//! - the reference elbow E° comes from q3 = 0: R_1 R_2 takes W_4 - S to W - S (Paden-Kahan's
//!   subproblem 2; of its two solutions the one with the larger q2 component sign, see
//!   [`SrsArm::reference`]);
//! - for a psi, E = S + Rot(u, psi)(E° - S), and R_1 R_2 R_3 is the rotation taking (E_0 - S,
//!   W_4 - S) to (E - S, W - S): two shoulder solutions (subproblem 2 for axis 3's direction, then
//!   subproblem 1 for q3);
//! - the wrist R_5 R_6 R_7 = (R_1 ... R_4)^T R_e R(0)^T: two wrist solutions.
//!
//! Eight branches in all, labelled by the three signs.

use crate::kinematics::{JointKind, Pose, Robot};
use nalgebra::{Matrix3, Point3, Rotation3, Unit, Vector3};
use std::f64::consts::{PI, TAU};

/// Rotation about unit axis `w` by `t` (rad).
fn rot(w: &Vector3<f64>, t: f64) -> Rotation3<f64> {
    Rotation3::from_axis_angle(&Unit::new_unchecked(*w), t)
}

/// Subproblem 1: the angle t with Rot(w, t) p = q (p, q of equal components along w).
fn sub1(w: &Vector3<f64>, p: &Vector3<f64>, q: &Vector3<f64>) -> f64 {
    let pp = p - w * w.dot(p);
    let qq = q - w * w.dot(q);
    w.dot(&pp.cross(&qq)).atan2(pp.dot(&qq))
}

/// Subproblem 2: the angles (t1, t2) with Rot(w1, t1) Rot(w2, t2) p = q, for `sign` = +1 or -1
/// (the two solutions); `None` when there is none (beyond rounding).
fn sub2(
    w1: &Vector3<f64>,
    w2: &Vector3<f64>,
    p: &Vector3<f64>,
    q: &Vector3<f64>,
    sign: f64,
) -> Option<(f64, f64)> {
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
    Some((sub1(w1, &c, q), sub1(w2, p, &c)))
}

/// Closest point of line (a, u) to line (b, v) (points, unit directions), and the gap between
/// the lines (m).
fn meet(
    a: &Vector3<f64>,
    u: &Vector3<f64>,
    b: &Vector3<f64>,
    v: &Vector3<f64>,
) -> (Vector3<f64>, f64) {
    let w0 = a - b;
    let (uu, uv, vv) = (u.dot(u), u.dot(v), v.dot(v));
    let (du, dv) = (u.dot(&w0), v.dot(&w0));
    let den = uu * vv - uv * uv;
    if den.abs() < 1e-12 {
        return (*a, f64::INFINITY);
    }
    let s = (uv * dv - vv * du) / den;
    let t = (uu * dv - uv * du) / den;
    let pa = a + u * s;
    let pb = b + v * t;
    (0.5 * (pa + pb), (pa - pb).norm())
}

/// The orthonormal frame of `a` and the part of `b` perpendicular to it, as columns.
fn triad(a: &Vector3<f64>, b: &Vector3<f64>) -> Matrix3<f64> {
    let x = a.normalize();
    let y = (b - x * x.dot(b)).normalize();
    Matrix3::from_columns(&[x, y, x.cross(&y)])
}

/// One branch at one arm angle.
#[derive(Debug, Clone, PartialEq)]
pub struct SrsSolution {
    /// Name from the three signs, e.g. "shoulder +, elbow -, wrist +".
    pub name: String,
    /// Joint vector (rad), each value shifted by 2 pi into its limits where it fits.
    pub q: [f64; 7],
    /// Every joint within its limits.
    pub within_limits: bool,
}

/// An SRS arm read from its axes (see the module documentation).
#[derive(Debug, Clone)]
pub struct SrsArm {
    /// Joint axes at q = 0 (world, unit).
    w: [Vector3<f64>; 7],
    /// Shoulder, elbow and wrist centres at q = 0 (world, m).
    s: Vector3<f64>,
    e0: Vector3<f64>,
    w0: Vector3<f64>,
    /// The wrist centre in the tool frame (m).
    w_tool: Vector3<f64>,
    /// Tool rotation at q = 0.
    r0: Rotation3<f64>,
    /// A unit vector perpendicular to each axis (for subproblem 1 on that axis).
    probe: [Vector3<f64>; 7],
    limits: Vec<[f64; 2]>,
}

/// The elbow and wrist signs of branch index `k` (0..8): shoulder bit 2, elbow bit 1, wrist bit 0.
fn signs(k: usize) -> [f64; 3] {
    [k >> 2 & 1, k >> 1 & 1, k & 1].map(|b| if b == 0 { 1.0 } else { -1.0 })
}

impl SrsArm {
    /// The SRS structure of a 7R robot (one end-effector), or `None` with no such structure
    /// (axes 1-3 or 5-7 not meeting in a point, axes 3-5 not meeting at an elbow point) .
    pub fn detect(robot: &Robot) -> Option<Self> {
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
            let v = Vector3::new(c[0], c[1], c[2]);
            o[k] = pe + w[k].cross(&v);
        }
        let tol = 1e-9 * robot.characteristic_length();
        let point3 = |i: usize, j: usize, k: usize| -> Option<Vector3<f64>> {
            let (p, g) = meet(&o[i], &w[i], &o[j], &w[j]);
            let (p2, g2) = meet(&o[j], &w[j], &o[k], &w[k]);
            (g < tol && g2 < tol && (p - p2).norm() < tol).then_some(p)
        };
        let s = point3(0, 1, 2)?;
        let w0 = point3(4, 5, 6)?;
        let e0 = point3(2, 3, 4)?;
        if (e0 - s).norm() < tol || (w0 - e0).norm() < tol {
            return None;
        }
        let w_tool = t0.inverse_transform_point(&Point3::from(w0)).coords;
        let probe = w.map(|a| {
            let h = if a.x.abs() < 0.9 {
                Vector3::x()
            } else {
                Vector3::y()
            };
            (h - a * a.dot(&h)).normalize()
        });
        Some(Self {
            probe,
            w,
            s,
            e0,
            w0,
            w_tool,
            r0: t0.rotation,
            limits: robot.limits(),
        })
    }

    /// The shoulder centre S (world, m).
    pub fn shoulder(&self) -> Vector3<f64> {
        self.s
    }

    /// The wrist centre of a target pose (world, m).
    pub fn wrist_of(&self, target: &Pose) -> Vector3<f64> {
        (target * Point3::from(self.w_tool)).coords
    }

    /// Branch names in branch order (8).
    pub fn branch_names() -> [String; 8] {
        std::array::from_fn(|k| {
            let [s, e, w] = signs(k).map(|x| if x > 0.0 { '+' } else { '-' });
            format!("shoulder {s}, elbow {e}, wrist {w}")
        })
    }

    /// The two elbow angles q4 (rad) putting the wrist at distance `l` (m) from the shoulder;
    /// `None` out of reach.
    fn elbow(&self, l: f64, sign: f64) -> Option<f64> {
        let a = self.e0 - self.s;
        let b = self.w0 - self.e0;
        let w4 = self.w[3];
        // |a + R4 b|^2 = |a|^2 + |b|^2 + 2 (a.b_par + cos q4 a.b_perp + sin q4 a.(w4 x b))
        let b_par = w4 * w4.dot(&b);
        let b_perp = b - b_par;
        let k = 0.5 * (l * l - a.norm_squared() - b.norm_squared()) - a.dot(&b_par);
        let (c, s) = (a.dot(&b_perp), a.dot(&w4.cross(&b)));
        let r = c.hypot(s);
        if r < 1e-15 || k.abs() > r * (1.0 + 1e-12) {
            return None;
        }
        let phase = s.atan2(c);
        Some(phase + sign * (k / r).clamp(-1.0, 1.0).acos())
    }

    /// The wrist centre relative to the shoulder after joint 4 alone (world, m).
    fn w4(&self, q4: f64) -> Vector3<f64> {
        self.e0 - self.s + rot(&self.w[3], q4) * (self.w0 - self.e0)
    }

    /// The reference elbow direction E° - S for wrist centre `wc` with elbow angle q4: joint 3 at
    /// zero, and of the two shoulder solutions the one with sign +1 of subproblem 2. `None` at
    /// the algorithmic singularity (S-W line along axis 1) or out of reach.
    pub fn reference(&self, wc: &Vector3<f64>, q4: f64) -> Option<Vector3<f64>> {
        let sw = wc - self.s;
        if sw.normalize().cross(&self.w[0]).norm() < 1e-9 {
            return None;
        }
        let (t1, t2) = sub2(&self.w[0], &self.w[1], &self.w4(q4), &sw, 1.0)?;
        Some(rot(&self.w[0], t1) * rot(&self.w[1], t2) * (self.e0 - self.s))
    }

    /// Whether a target's shoulder-wrist line lies along axis 1 (the arm angle's algorithmic
    /// singularity: the reference plane is undefined).
    pub fn singular(&self, target: &Pose) -> bool {
        let sw = self.wrist_of(target) - self.s;
        sw.norm() < 1e-12 || sw.normalize().cross(&self.w[0]).norm() < 1e-9
    }

    /// Every branch reaching `target` with arm angle `psi` (rad), allocation-free: branch k
    /// (see [`Self::branch_names`]) is written to `out[k]` when bit k of the returned mask is
    /// set (angles not wrapped into the limits). Mask 0 when the wrist centre is out of reach or
    /// at the algorithmic singularity.
    pub fn solve_raw(&self, target: &Pose, psi: f64, out: &mut [[f64; 7]; 8]) -> u8 {
        let wc = self.wrist_of(target);
        let sw = wc - self.s;
        let u = sw.normalize();
        let rot_psi = rot(&u, psi);
        let mut mask = 0u8;
        // Shared work: the elbow (2), then the shoulder (2 per elbow), then the wrist (2 each).
        for (ie, se) in [1.0, -1.0].into_iter().enumerate() {
            let Some(q4) = self.elbow(sw.norm(), se) else {
                continue;
            };
            let Some(reference) = self.reference(&wc, q4) else {
                continue;
            };
            let e = rot_psi * reference;
            let w4 = self.w4(q4);
            let r_sh = triad(&e, &sw) * triad(&(self.e0 - self.s), &w4).transpose();
            for (is, ss) in [1.0, -1.0].into_iter().enumerate() {
                let Some((q1, q2)) =
                    sub2(&self.w[0], &self.w[1], &self.w[2], &(r_sh * self.w[2]), ss)
                else {
                    continue;
                };
                let r12 = rot(&self.w[0], q1) * rot(&self.w[1], q2);
                let x = self.probe[2];
                let q3 = sub1(&self.w[2], &x, &(r12.inverse() * (r_sh * x)));
                let r14 = r12 * rot(&self.w[2], q3) * rot(&self.w[3], q4);
                let r_w = (r14.inverse() * target.rotation * self.r0.inverse()).into_inner();
                for (iw, sws) in [1.0, -1.0].into_iter().enumerate() {
                    let Some((q5, q6)) =
                        sub2(&self.w[4], &self.w[5], &self.w[6], &(r_w * self.w[6]), sws)
                    else {
                        continue;
                    };
                    let r56 = rot(&self.w[4], q5) * rot(&self.w[5], q6);
                    let y = self.probe[6];
                    let q7 = sub1(&self.w[6], &y, &(r56.inverse() * (r_w * y)));
                    let k = is << 2 | ie << 1 | iw;
                    out[k] = [q1, q2, q3, q4, q5, q6, q7];
                    mask |= 1 << k;
                }
            }
        }
        mask
    }

    /// Every branch (up to 8) reaching `target` with arm angle `psi` (rad), named, wrapped into
    /// the limits where they fit and flagged. Empty when the wrist centre is out of reach or at
    /// the algorithmic singularity.
    pub fn solve(&self, target: &Pose, psi: f64) -> Vec<SrsSolution> {
        let names = Self::branch_names();
        let mut raw = [[0.0; 7]; 8];
        let mask = self.solve_raw(target, psi, &mut raw);
        let mut out = Vec::with_capacity(8);
        for (k, q) in raw.into_iter().enumerate() {
            if mask >> k & 1 == 1 {
                let q = self.wrapped(q);
                out.push(SrsSolution {
                    name: names[k].clone(),
                    within_limits: q
                        .iter()
                        .zip(&self.limits)
                        .all(|(v, l)| *v >= l[0] - 1e-12 && *v <= l[1] + 1e-12),
                    q,
                });
            }
        }
        out
    }

    /// Each angle shifted by a multiple of 2 pi into its limits where one fits, else wrapped to
    /// (-pi, pi].
    fn wrapped(&self, q: [f64; 7]) -> [f64; 7] {
        std::array::from_fn(|k| {
            let [lo, hi] = self.limits[k];
            let base = q[k] - TAU * ((q[k] + PI) / TAU).floor();
            [base, base - TAU, base + TAU]
                .into_iter()
                .find(|v| *v >= lo - 1e-12 && *v <= hi + 1e-12)
                .unwrap_or(base)
        })
    }

    /// The arm angle (rad) of a configuration: the signed angle about S->W from the reference
    /// elbow to the elbow. `None` at the algorithmic singularity.
    pub fn arm_angle(&self, q: &[f64]) -> Option<f64> {
        let r13 = rot(&self.w[0], q[0]) * rot(&self.w[1], q[1]) * rot(&self.w[2], q[2]);
        let e = r13 * (self.e0 - self.s);
        let sw = r13 * self.w4(q[3]);
        let reference = self.reference(&(self.s + sw), q[3])?;
        let u = sw.normalize();
        let a = reference - u * u.dot(&reference);
        let b = e - u * u.dot(&e);
        Some(u.dot(&a.cross(&b)).atan2(a.dot(&b)))
    }
}
