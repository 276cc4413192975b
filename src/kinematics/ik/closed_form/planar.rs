//! Arms whose joint axes are all parallel (twists 0 or pi): the two- and three-link planar arms
//! (Sect. 2.12.1) and the SCARA (Problem 2.20), and the two-link core they share with the
//! anthropomorphic arm (Sect. 2.12.4).

use super::chain::Chain;
use super::posture::{Elbow, FreeReason, Posture};
use super::{COS_TOL, Goal, PLANE_TOL, RawSolutions, TILT_TOL};
use crate::kinematics::ik::IkError;
use nalgebra::{Matrix3, Vector3};

/// The merged elbow of [`two_link`] may miss the target by at most this many `len_tol`.
const MERGE_TOL: f64 = 100.0;

/// One solution of the two-link problem `P = L1 e^{iA} + L2 e^{i(A + D)}`.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct TwoLinkSol {
    /// Angle A of the first link (rad).
    pub a: f64,
    /// Elbow angle D (rad).
    pub d: f64,
    /// Sign of sin D (+1, -1), or 0 when the elbow pair has merged (sin D = 0).
    pub sign: f64,
    /// cos D = +1 (stretched) or -1 (folded) when merged.
    pub merged_cos: f64,
    /// The first angle is free (target at the base with L1 = L2).
    pub free_first: bool,
}

/// Solves `(x, y) = L1 (cos A, sin A) + L2 (cos(A + D), sin(A + D))` as in Sect. 2.12.1 (after
/// (2.91)-(2.92)): c2 from the distance, s2 = +-sqrt(1 - c2^2), theta2 = Atan2(s2, c2), then A from
/// the s1, c1 formulas. Writes the s2 > 0
/// solution first. `Err(distance)` when the point is outside the annulus
/// `|L1 - L2| <= r <= L1 + L2` (distance to it, m); the cosine is clamped only within
/// [`COS_TOL`] of +-1 (then the pair merges into one solution).
pub(super) fn two_link(
    x: f64,
    y: f64,
    l1: f64,
    l2: f64,
    len_tol: f64,
    out: &mut [TwoLinkSol; 2],
) -> Result<usize, f64> {
    let r2 = x * x + y * y;
    let r = r2.sqrt();
    // c2 = (p_Wx^2 + p_Wy^2 - a1^2 - a2^2) / (2 a1 a2), kept as 1 + c2 and 1 - c2 in factored form
    // so that neither loses the target's distance to cancellation next to +-1 (a target 1e-8 m
    // from the base of an arm with L1 = L2 has 1 + c2 = 5e-17).
    let den = 2.0 * l1 * l2;
    let dm = (l1 - l2).abs();
    let one_plus = (r - dm) * (r + dm) / den;
    let one_minus = (l1 + l2 - r) * (l1 + l2 + r) / den;
    if one_minus < -COS_TOL {
        return Err(r - (l1 + l2));
    }
    if one_plus < -COS_TOL {
        return Err(dm - r);
    }
    let c = if one_plus < one_minus {
        one_plus - 1.0
    } else {
        1.0 - one_minus
    };
    // k = L1 + L2 c2 from the accurate side.
    let k = if c < 0.0 {
        (l1 - l2) + l2 * one_plus
    } else {
        l1 + l2 - l2 * one_minus
    };
    // theta1 = Atan2(s1, c1) with s1, c1 as in Sect. 2.12.1 (the common positive denominator
    // p_Wx^2 + p_Wy^2 dropped).
    let first = |s: f64, k: f64| (k * y - l2 * s * x).atan2(k * x + l2 * s * y);
    // Merge the pair only where the merged elbow (D = 0 or pi) still reaches the target: near the
    // folded elbow of an arm with L1 ~ L2 the two solutions are far apart in theta1 even though
    // c is within COS_TOL of -1.
    let near = one_plus.min(one_minus);
    let merged_miss = (r - (l1 + l2 * c.signum()).abs()).abs();
    if near <= 0.0 || (near <= COS_TOL && merged_miss <= MERGE_TOL * len_tol) {
        let c = c.signum();
        out[0] = TwoLinkSol {
            a: first(0.0, l1 + l2 * c),
            d: if c > 0.0 { 0.0 } else { std::f64::consts::PI },
            sign: 0.0,
            merged_cos: c,
            free_first: c < 0.0 && r <= len_tol,
        };
        return Ok(1);
    }
    // s2 = +-sqrt(1 - c2^2), theta2 = Atan2(s2, c2)
    let s = (one_minus * one_plus).sqrt();
    let d = s.atan2(c);
    out[0] = TwoLinkSol {
        a: first(s, k),
        d,
        sign: 1.0,
        merged_cos: 0.0,
        free_first: false,
    };
    out[1] = TwoLinkSol {
        a: first(-s, k),
        d: -d,
        sign: -1.0,
        merged_cos: 0.0,
        free_first: false,
    };
    Ok(2)
}

/// Elbow label of a two-link solution: "elbow down" when `sin D * orientation_sign > 0`
/// (`orientation_sign` = +1 for planar arms, Siciliano's naming s2 > 0 = elbow down).
pub(super) fn elbow_of(s: &TwoLinkSol, orientation_sign: f64) -> Elbow {
    if s.sign == 0.0 {
        if s.merged_cos > 0.0 {
            Elbow::Stretched
        } else {
            Elbow::Folded
        }
    } else if s.sign * orientation_sign > 0.0 {
        Elbow::Down
    } else {
        Elbow::Up
    }
}

/// A chain of parallel axes with two or three revolute joints and at most one prismatic joint.
///
/// With every twist 0 or pi, `A_i` keeps z parallel to z0; in the base frame the x axis of frame i
/// makes the angle `psi_i = sum_{j<=i} s_j theta_j` with x0 (s_j = -1 after an odd number of
/// twists pi), the origins add up as `sum a_i e^{i psi_i}` in the plane and `sum s_i d_i` along z0.
/// Grouping the links between consecutive revolute joints gives constant vectors `V_k`, so the
/// plane problem is the two-link problem of Sect. 2.12.1 for `V_1`, `V_2`, after subtracting
/// `V_3 e^{i Psi_3}` with `Psi_3` known from the orientation (the wrist point of (2.91)-(2.92)).
#[derive(Debug, Clone)]
pub(super) struct ParallelArm {
    /// Number of revolute joints (2 or 3).
    pub m: usize,
    rev: [usize; 3],
    sign: [f64; 3],
    gamma: [f64; 3],
    c0: [f64; 2],
    len: [f64; 3],
    beta: [f64; 3],
    v: [[f64; 2]; 3],
    len_tool: f64,
    beta_tool: f64,
    kappa: f64,
    /// The prismatic joint (row index) and the sign of its motion along z0.
    pub prismatic: Option<(usize, f64)>,
    z_frame: f64,
    /// z (base frame) of the tool point when there is no prismatic joint.
    pub z_tool: f64,
    end_flip: f64,
    /// Rotation of the tool in the base frame at psi_n = 0.
    pub tool_rot0: Matrix3<f64>,
    len_tol: f64,
}

impl ParallelArm {
    /// Recognises the structure: every twist 0 or pi, 2 or 3 revolute joints, at most one
    /// prismatic joint, non-zero links between the first two revolute axes and after the second.
    pub(super) fn detect(chain: &Chain, len_tol: f64) -> Option<Self> {
        let mut s = 1.0;
        let mut acc = 0.0;
        let mut k = 0usize;
        let mut me = ParallelArm {
            m: 0,
            rev: [0; 3],
            sign: [1.0; 3],
            gamma: [0.0; 3],
            c0: [0.0; 2],
            len: [0.0; 3],
            beta: [0.0; 3],
            v: [[0.0; 2]; 3],
            len_tool: 0.0,
            beta_tool: 0.0,
            kappa: 0.0,
            prismatic: None,
            z_frame: 0.0,
            z_tool: 0.0,
            end_flip: 1.0,
            tool_rot0: Matrix3::identity(),
            len_tol,
        };
        for (i, row) in chain.rows.iter().enumerate() {
            let flip = row.twist.parallel_sign()?;
            if row.revolute {
                if k == 3 {
                    return None;
                }
                me.rev[k] = i;
                me.sign[k] = s;
                me.gamma[k] = acc;
                acc = 0.0;
                k += 1;
                me.z_frame += s * row.d;
            } else {
                if me.prismatic.is_some() {
                    return None;
                }
                me.prismatic = Some((i, s));
                acc += s * row.theta;
            }
            let (sn, cs) = acc.sin_cos();
            let target = if k == 0 { &mut me.c0 } else { &mut me.v[k - 1] };
            target[0] += row.a * cs;
            target[1] += row.a * sn;
            s *= flip;
        }
        if k < 2 || (k == 2 && me.prismatic.is_some()) {
            return None;
        }
        me.m = k;
        me.kappa = acc;
        me.end_flip = s;
        for j in 0..3 {
            me.len[j] = me.v[j][0].hypot(me.v[j][1]);
            me.beta[j] = me.v[j][1].atan2(me.v[j][0]);
        }
        // V_m with the tool translation: R_n t = Rz(psi_n) (t_x, s t_y, s t_z).
        let t = chain.tool.translation.vector;
        let (sk, ck) = me.kappa.sin_cos();
        let (tx, ty) = (t.x, s * t.y);
        let vt = [
            me.v[k - 1][0] + ck * tx - sk * ty,
            me.v[k - 1][1] + sk * tx + ck * ty,
        ];
        me.len_tool = vt[0].hypot(vt[1]);
        me.beta_tool = vt[1].atan2(vt[0]);
        me.z_tool = me.z_frame + s * t.z;
        let flip = Matrix3::from_diagonal(&Vector3::new(1.0, s, s));
        me.tool_rot0 = flip * chain.tool.rotation.matrix();
        let last_len = if k == 2 { me.len_tool } else { me.len[1] };
        if me.len[0] <= len_tol || last_len <= len_tol {
            return None;
        }
        Some(me)
    }

    /// Writes the joint values (theta or d, offsets included) of every solution into `out`.
    pub(super) fn solve(&self, goal: &Goal, out: &mut RawSolutions) -> Result<(), IkError> {
        let (w, l2, b2, psi3, z, zref) = match goal {
            Goal::Frame(t) => {
                let r = t.rotation.matrix();
                // The z axis of frame n must be +-z0.
                let tilt = r[(0, 2)].hypot(r[(1, 2)]).atan2(self.end_flip * r[(2, 2)]);
                if tilt > TILT_TOL {
                    if self.prismatic.is_none() {
                        return Err(IkError::TiltedOutOfPlane { tilt });
                    }
                    out.unreachable = Some(tilt);
                    return Ok(());
                }
                // phi = theta1 + theta2 + theta3 (2.90), generalised: psi_n from the x axis.
                let psi3 = r[(1, 0)].atan2(r[(0, 0)]) - self.kappa;
                let (s, c) = crate::kinematics::trig::sin_cos(psi3);
                let p = t.translation.vector;
                let v = self.v[2];
                // p_W = p - a3 (cos phi, sin phi), (2.91)-(2.92)
                let w = [
                    p.x - self.c0[0] - (c * v[0] - s * v[1]),
                    p.y - self.c0[1] - (s * v[0] + c * v[1]),
                ];
                (w, self.len[1], self.beta[1], Some(psi3), p.z, self.z_frame)
            }
            Goal::Point(p) => {
                let w = [p.x - self.c0[0], p.y - self.c0[1]];
                (w, self.len_tool, self.beta_tool, None, p.z, self.z_tool)
            }
        };
        let prism = match self.prismatic {
            Some((i, sp)) => Some((i, sp * (z - zref))),
            None => {
                if (z - zref).abs() > PLANE_TOL {
                    return Err(IkError::OffPlane {
                        offset: z - zref,
                        plane_z: zref,
                    });
                }
                None
            }
        };
        let mut tl = [TwoLinkSol::default(); 2];
        let n = match two_link(w[0], w[1], self.len[0], l2, self.len_tol, &mut tl) {
            Ok(n) => n,
            Err(d) => {
                out.unreachable = Some(d);
                return Ok(());
            }
        };
        for s in &tl[..n] {
            let k = out.len;
            let q = &mut out.q[k];
            let psi1 = s.a - self.beta[0];
            let psi2 = s.a + s.d - b2;
            q[self.rev[0]] = self.sign[0] * (psi1 - self.gamma[0]);
            q[self.rev[1]] = self.sign[1] * (psi2 - psi1 - self.gamma[1]);
            if let Some(psi3) = psi3 {
                // theta3 = phi - theta1 - theta2 (2.90)
                q[self.rev[2]] = self.sign[2] * (psi3 - psi2 - self.gamma[2]);
            }
            if let Some((i, d)) = prism {
                q[i] = d;
            }
            let mut posture = Posture {
                elbow: Some(elbow_of(s, 1.0)),
                ..Posture::default()
            };
            if s.free_first {
                posture.free[self.rev[0]] = Some(FreeReason::PlanarOrigin);
            }
            out.postures[k] = posture;
            out.len += 1;
        }
        Ok(())
    }
}
