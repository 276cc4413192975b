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

use super::geometry::{
    meet, rot, rotv, rotv_sc, sub1, sub2_pair_sc, sub2_sc, triad, trig_roots, within, wrap_into,
};
use crate::kinematics::{Pose, Robot};
use nalgebra::{Matrix3, Point3, Rotation3, Vector3};
use std::f64::consts::{PI, TAU};

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

/// A target as [`SrsArm::prepare`] leaves it: what does not depend on psi.
#[derive(Debug, Clone, Copy)]
pub struct SrsPose {
    sw: Vector3<f64>,
    u: Vector3<f64>,
    m: Matrix3<f64>,
    /// `m w_7` and `m x_7` (x_7 the probe of axis 7): the wrist triple needs only
    /// `R_w w_7` and `R_w x_7`, and `R_w = (R_sh R_4)^T m`.
    m_wrist: [Vector3<f64>; 2],
    elbows: [Option<ElbowPart>; 2],
}

/// Both branches of the shoulder triple and of the wrist triple at one arm angle.
type TriplePairs = ([Option<[f64; 3]>; 2], [Option<[f64; 3]>; 2]);

/// One elbow branch of a prepared target.
#[derive(Debug, Clone, Copy)]
struct ElbowPart {
    q4: f64,
    reference: Vector3<f64>,
    r4: Matrix3<f64>,
    /// `triad(E_0 - S, W_4 - S)^T`: the shoulder's rotation at psi = 0 is `triad(E°, SW)` times it.
    zero: Matrix3<f64>,
    /// `zero w_3` and `zero x_3`: the shoulder triple needs only `R_sh w_3` and `R_sh x_3`, and
    /// `R_sh = triad(E, SW) zero`.
    zero_shoulder: [Vector3<f64>; 2],
    /// `(zero R_4)^T`: `R_w v = (zero R_4)^T triad(E, SW)^T (m v)`.
    wrist_from_triad: Matrix3<f64>,
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
    /// What the limit crossings of the shoulder triple (0) and the wrist triple (1) need that
    /// does not depend on the target.
    crossings: [TripleCrossings; 2],
}

/// For a spherical triple of axes w1, w2, w3 (rotation R = R1 R2 R3), the equations
/// `x . R y = v` that hold where a joint is at one of its finite limits or the two branches
/// of subproblem 2 meet: one (x, y, v) each, from the axes and limits alone.
#[derive(Debug, Clone, Default)]
struct TripleCrossings {
    equations: Vec<(Vector3<f64>, Vector3<f64>, f64)>,
}

impl TripleCrossings {
    fn new(w: [Vector3<f64>; 3], limits: &[[f64; 2]]) -> Self {
        let [w1, w2, w3] = w;
        let finite = |k: usize| {
            let [lo, hi] = limits[k];
            (lo.is_finite() && hi.is_finite() && hi - lo < TAU - 1e-12)
                .then_some([lo, hi])
                .into_iter()
                .flatten()
        };
        let mut equations = Vec::new();
        // Middle joint: w1 . R w3 = w1 . R_mid(t) w3.
        for t in finite(1) {
            equations.push((w1, w3, w1.dot(&(rot(&w2, t) * w3))));
        }
        // First joint: (R_first(t) w2) . R w3 = w2 . w3.
        for t in finite(0) {
            equations.push((rot(&w1, t) * w2, w3, w2.dot(&w3)));
        }
        // Last joint: w1 . R (R_last(t)^T w2) = w1 . w2.
        for t in finite(2) {
            equations.push((w1, rot(&w3, -t) * w2, w1.dot(&w2)));
        }
        // Singular: gamma^2 = 0 in subproblem 2, a quadratic in s = w1 . R w3.
        let c12 = w1.dot(&w2);
        let den = c12 * c12 - 1.0;
        if den.abs() > 1e-12 {
            let k = w2.dot(&w3);
            // alpha = (c12 k - s) / den, beta = (c12 s - k) / den.
            let (a1, a0) = (-1.0 / den, c12 * k / den);
            let (b1, b0) = (c12 / den, -k / den);
            // 1 - (a1 s + a0)^2 - (b1 s + b0)^2 - 2 c12 (a1 s + a0)(b1 s + b0) = 0
            let qa = -(a1 * a1 + b1 * b1 + 2.0 * c12 * a1 * b1);
            let qb = -(2.0 * a1 * a0 + 2.0 * b1 * b0 + 2.0 * c12 * (a1 * b0 + a0 * b1));
            let qc = 1.0 - a0 * a0 - b0 * b0 - 2.0 * c12 * a0 * b0;
            let disc = qb * qb - 4.0 * qa * qc;
            if disc >= 0.0 && qa.abs() > 1e-14 {
                for sgn in [1.0, -1.0] {
                    equations.push((w1, w3, (-qb + sgn * disc.sqrt()) / (2.0 * qa)));
                }
            }
        }
        Self { equations }
    }
}

/// The elbow and wrist signs of branch index `k` (0..8): shoulder bit 2, elbow bit 1, wrist bit 0.
fn signs(k: usize) -> [f64; 3] {
    [k >> 2 & 1, k >> 1 & 1, k & 1].map(|b| if b == 0 { 1.0 } else { -1.0 })
}

impl SrsArm {
    /// The SRS structure of a 7R robot (one end-effector), or `None` with no such structure
    /// (axes 1-3 or 5-7 not meeting in a point, axes 3-5 not meeting at an elbow point) .
    pub fn detect(robot: &Robot) -> Option<Self> {
        let (w, o, t0) = super::geometry::axes_7r(robot)?;
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
        let probe = super::geometry::probes(&w);
        let limits = robot.limits();
        let crossings =
            [0, 4].map(|i| TripleCrossings::new([w[i], w[i + 1], w[i + 2]], &limits[i..i + 3]));
        Some(Self {
            crossings,
            probe,
            w,
            s,
            e0,
            w0,
            w_tool,
            r0: t0.rotation,
            limits,
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
        super::geometry::elbow_angle(
            &(self.e0 - self.s),
            &(self.w0 - self.e0),
            &self.w[3],
            l,
            sign,
        )
    }

    /// The wrist centre relative to the shoulder after joint 4 alone (world, m).
    fn w4(&self, q4: f64) -> Vector3<f64> {
        self.e0 - self.s + rot(&self.w[3], q4) * (self.w0 - self.e0)
    }

    /// The reference elbow direction E° - S for wrist centre `wc` with elbow angle q4: joint 3 at
    /// zero, and of the two shoulder solutions the one with sign +1 of subproblem 2. `None` at
    /// the algorithmic singularity (S-W line along axis 1) or out of reach.
    pub fn reference(&self, wc: &Vector3<f64>, q4: f64) -> Option<Vector3<f64>> {
        self.reference_of(&(wc - self.s), &self.w4(q4))
    }

    /// [`Self::reference`] from S->W (`sw`) and the wrist after joint 4 alone (`w4`, see
    /// [`Self::w4`]): R_1 R_2 (E_0 - S) with R_1 R_2 w4 = sw, rotating the vector only.
    #[inline(always)]
    fn reference_of(&self, sw: &Vector3<f64>, w4: &Vector3<f64>) -> Option<Vector3<f64>> {
        if sw.normalize().cross(&self.w[0]).norm() < 1e-9 {
            return None;
        }
        let (a1, a2) = sub2_sc(&self.w[0], &self.w[1], w4, sw, 1.0)?;
        let e = rotv_sc(&self.w[1], a2.s, a2.c, &(self.e0 - self.s));
        Some(rotv_sc(&self.w[0], a1.s, a1.c, &e))
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
        self.solve_prepared(&self.prepare(target), psi, out)
    }

    /// What a target fixes before psi is chosen (the wrist centre, both elbow angles, their
    /// reference elbows): [`Self::solve_prepared`] then costs only the psi-dependent part, for
    /// a slider or a sampled manifold of one pose.
    pub fn prepare(&self, target: &Pose) -> SrsPose {
        let wc = self.wrist_of(target);
        let sw = wc - self.s;
        let m = target.rotation.into_inner() * self.r0.inverse().into_inner();
        let elbows = [1.0, -1.0].map(|se| {
            let q4 = self.elbow(sw.norm(), se)?;
            let r4 = rot(&self.w[3], q4).into_inner();
            let w4 = self.e0 - self.s + r4 * (self.w0 - self.e0);
            let reference = self.reference_of(&sw, &w4)?;
            let zero = triad(&(self.e0 - self.s), &w4).transpose();
            Some(ElbowPart {
                q4,
                reference,
                r4,
                zero,
                zero_shoulder: [zero * self.w[2], zero * self.probe[2]],
                wrist_from_triad: (zero * r4).transpose(),
            })
        });
        SrsPose {
            sw,
            u: sw.normalize(),
            m,
            m_wrist: [m * self.w[6], m * self.probe[6]],
            elbows,
        }
    }

    /// [`Self::solve_raw`] for a prepared target.
    pub fn solve_prepared(&self, p: &SrsPose, psi: f64, out: &mut [[f64; 7]; 8]) -> u8 {
        let mut mask = 0u8;
        for (ie, part) in p.elbows.iter().enumerate() {
            let Some(part) = part else {
                continue;
            };
            let (shoulders, wrists) = self.sides(p, part, psi);
            for (is, shoulder) in shoulders.into_iter().enumerate() {
                let Some([q1, q2, q3]) = shoulder else {
                    continue;
                };
                for (iw, w) in wrists.iter().enumerate() {
                    if let Some([q5, q6, q7]) = *w {
                        let k = is << 2 | ie << 1 | iw;
                        out[k] = [q1, q2, q3, part.q4, q5, q6, q7];
                        mask |= 1 << k;
                    }
                }
            }
        }
        mask
    }

    /// The shoulder triples and the wrist triples (both branches each) at arm angle `psi`.
    /// R_1 R_2 R_3 = R_sh whichever the shoulder branch, so the wrist sees the same rotation
    /// from both: R_5 R_6 R_7 = R_w = (R_sh R_4)^T R_e R(0)^T. Only `R w_3` and `R x_3` of each
    /// triple's rotation are needed, so no 3x3 product is formed (see [`ElbowPart`]).
    #[inline(always)]
    fn sides(&self, p: &SrsPose, part: &ElbowPart, psi: f64) -> TriplePairs {
        let t = Self::triad_at(p, part, psi);
        (self.shoulders(part, &t), self.wrists(p, part, &t))
    }

    /// `triad(E, SW)` at arm angle `psi`: R_sh is this times `part.zero`.
    #[inline(always)]
    fn triad_at(p: &SrsPose, part: &ElbowPart, psi: f64) -> Matrix3<f64> {
        triad(&rotv(&p.u, psi, &part.reference), &p.sw)
    }

    /// Both shoulder triples for `t = triad_at(psi)`.
    #[inline(always)]
    fn shoulders(&self, part: &ElbowPart, t: &Matrix3<f64>) -> [Option<[f64; 3]>; 2] {
        let [zw, zx] = &part.zero_shoulder;
        self.triples(0, &(t * zw), &(t * zx))
    }

    /// Both wrist triples for `t = triad_at(psi)`.
    #[inline(always)]
    fn wrists(&self, p: &SrsPose, part: &ElbowPart, t: &Matrix3<f64>) -> [Option<[f64; 3]>; 2] {
        let ww = part.wrist_from_triad * t.tr_mul(&p.m_wrist[0]);
        let wx = part.wrist_from_triad * t.tr_mul(&p.m_wrist[1]);
        self.triples(4, &ww, &wx)
    }

    /// The angles of the spherical triple of axes `i`, `i + 1`, `i + 2` whose product of
    /// rotations R has `R w_{i+2}` = `rw` and `R x_{i+2}` = `rx` (x the axis's probe): both
    /// branches of subproblem 2 (sign +1, then -1), `None` where there is no solution.
    #[inline(always)]
    fn triples(&self, i: usize, rw: &Vector3<f64>, rx: &Vector3<f64>) -> [Option<[f64; 3]>; 2] {
        let (w1, w2, w3) = (&self.w[i], &self.w[i + 1], &self.w[i + 2]);
        let Some(pair) = sub2_pair_sc(w1, w2, w3, rw) else {
            return [None, None];
        };
        let x = self.probe[i + 2];
        // R_2^T R_1^T (r x), rotating the vector only, with the sines and cosines subproblem 2
        // already has.
        pair.map(|(a1, a2)| {
            let v = rotv_sc(w2, -a2.s, a2.c, &rotv_sc(w1, -a1.s, a1.c, rx));
            Some([a1.t, a2.t, sub1(w3, &x, &v)])
        })
    }

    /// Every branch (up to 8) reaching `target` with arm angle `psi` (rad), named, wrapped into
    /// the limits where they fit and flagged. Empty when the wrist centre is out of reach or at
    /// the algorithmic singularity.
    ///
    /// # Examples
    ///
    /// The DLR arm of Fig. 2.27 is an SRS arm; each branch at an arm angle has that arm angle
    /// and puts the tool at the target:
    ///
    /// ```
    /// use armlab::kinematics::models::built_in;
    /// use armlab::redundancy::srs::SrsArm;
    ///
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// let dlr = built_in("dlr").expect("a built-in model");
    /// let arm = SrsArm::detect(&dlr).expect("an SRS arm");
    /// let target = dlr.fk(&[0.3, 0.7, -0.2, 1.2, 0.4, -0.6, 0.2])?;
    /// let branches = arm.solve(&target, 0.8);
    /// assert_eq!(branches.len(), 8);
    /// for b in &branches {
    ///     let gap = (dlr.fk(&b.q)?.to_homogeneous() - target.to_homogeneous()).amax();
    ///     assert!(gap < 1e-12, "{}", b.name);
    ///     let psi = arm.arm_angle(&b.q).expect("not at the singularity");
    ///     assert!((psi - 0.8).abs() < 1e-9);
    /// }
    /// # Ok(())
    /// # }
    /// ```
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
                    within_limits: within(&q, &self.limits),
                    q,
                });
            }
        }
        out
    }

    /// Each angle shifted by a multiple of 2 pi into its limits where one fits, else wrapped to
    /// (-pi, pi].
    fn wrapped(&self, q: [f64; 7]) -> [f64; 7] {
        wrap_into(q, &self.limits)
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

/// A rotation that depends on psi as `C + sin(psi) A + cos(psi) B`.
struct TrigRotation {
    c: Matrix3<f64>,
    a: Matrix3<f64>,
    b: Matrix3<f64>,
}

impl TrigRotation {
    /// The psi where `x . R(psi) y = v`.
    fn roots(&self, x: &Vector3<f64>, y: &Vector3<f64>, v: f64, out: &mut Vec<f64>) {
        let f = |m: &Matrix3<f64>| x.dot(&(m * y));
        trig_roots(f(&self.a), f(&self.b), f(&self.c) - v, out);
    }
}

impl SrsArm {
    /// The psi where a joint of a spherical triple (the shoulder `side` 0 or the wrist 1, with
    /// rotation `m(psi)`) meets one of its limits or the triple is singular (its two branches
    /// meet).
    fn triple_roots(&self, side: usize, m: &TrigRotation, out: &mut Vec<f64>) {
        for (x, y, v) in &self.crossings[side].equations {
            m.roots(x, y, *v, out);
        }
    }

    /// Every psi (rad, in [0, 2 pi)) where the joint-limit feasibility of a branch can change
    /// for `target`: a joint at a limit, a branch merge of the shoulder or the wrist (joint 4
    /// does not move with psi). Each is a root of `a sin psi + b cos psi + c = 0`: the shoulder's
    /// rotation is `Rot(u, psi) R_sh(0)` and the wrist's `R_4^T R_sh^T R_e R(0)^T`, both of the
    /// form `C + sin(psi) A + cos(psi) B`.
    pub fn breakpoints(&self, target: &Pose) -> Vec<f64> {
        let mut out: Vec<f64> = self
            .breakpoint_parts(&self.prepare(target))
            .into_iter()
            .flatten()
            .flatten()
            .collect();
        out.sort_by(f64::total_cmp);
        out.dedup_by(|a, b| (*a - *b).abs() < 1e-13);
        out
    }

    /// [`Self::breakpoints`] apart: for each elbow branch, those of the shoulder triple and
    /// those of the wrist triple (each in [0, 2 pi), sorted), empty for an elbow that does not
    /// reach.
    fn breakpoint_parts(&self, p: &SrsPose) -> [[Vec<f64>; 2]; 2] {
        let k = p.u.cross_matrix();
        let k2 = k * k;
        let mut parts: [[Vec<f64>; 2]; 2] = Default::default();
        for (ie, part) in p.elbows.iter().enumerate() {
            // No elbow: out of reach, or the algorithmic singularity (no reference plane).
            let Some(part) = part else {
                continue;
            };
            let r0 = triad(&part.reference, &p.sw) * part.zero;
            let sh = TrigRotation {
                c: (Matrix3::identity() + k2) * r0,
                a: k * r0,
                b: -k2 * r0,
            };
            let [shoulder, wrist] = &mut parts[ie];
            self.triple_roots(0, &sh, shoulder);
            let r4t = part.r4.transpose();
            let wr = TrigRotation {
                c: r4t * sh.c.transpose() * p.m,
                a: r4t * sh.a.transpose() * p.m,
                b: r4t * sh.b.transpose() * p.m,
            };
            self.triple_roots(1, &wr, wrist);
            for list in [shoulder, wrist] {
                for p in list.iter_mut() {
                    *p = p.rem_euclid(TAU);
                }
                list.sort_by(f64::total_cmp);
                list.dedup_by(|a, b| (*a - *b).abs() < 1e-13);
            }
        }
        parts
    }

    /// The feasible arm angles of every branch inside the joint limits, exactly. A branch is
    /// feasible where its elbow angle q4 (constant in psi) is within its limits, its shoulder
    /// triple is and its wrist triple is; the shoulder's feasibility changes only at the
    /// shoulder's breakpoints and the wrist's only at the wrist's, so each is decided by one
    /// test of that triple alone at the midpoint between consecutive breakpoints of its own, and
    /// a branch's intervals are the intersection. Pieces of [-pi, pi] (one across +-pi given as
    /// two), in branch order ([`Self::branch_names`]).
    pub fn feasible_intervals(&self, target: &Pose) -> [Vec<[f64; 2]>; 8] {
        let p = self.prepare(target);
        let parts = self.breakpoint_parts(&p);
        let mut out: [Vec<[f64; 2]>; 8] = Default::default();
        for (ie, part) in p.elbows.iter().enumerate() {
            let Some(part) = part else {
                continue;
            };
            let [lo4, hi4] = self.limits[3];
            let q4 = wrap_into([part.q4], &self.limits[3..4])[0];
            if q4 < lo4 - 1e-12 || q4 > hi4 + 1e-12 {
                continue;
            }
            let shoulder = side_intervals(&parts[ie][0], |psi, ok: &mut [bool; 2]| {
                let t = Self::triad_at(&p, part, psi);
                for (is, t) in self.shoulders(part, &t).into_iter().enumerate() {
                    ok[is] = t.is_some_and(|t| {
                        within(&wrap_into(t, &self.limits[0..3]), &self.limits[0..3])
                    });
                }
            });
            let wrist = side_intervals(&parts[ie][1], |psi, ok: &mut [bool; 2]| {
                let t = Self::triad_at(&p, part, psi);
                for (iw, t) in self.wrists(&p, part, &t).into_iter().enumerate() {
                    ok[iw] = t.is_some_and(|t| {
                        within(&wrap_into(t, &self.limits[4..7]), &self.limits[4..7])
                    });
                }
            });
            for (is, sh) in shoulder.iter().enumerate() {
                for (iw, wr) in wrist.iter().enumerate() {
                    out[is << 2 | ie << 1 | iw] = to_signed(&intersect(sh, wr));
                }
            }
        }
        out
    }
}

/// The feasible intervals in [0, 2 pi] of N branches from the `cuts` (in [0, 2 pi)) between
/// which no branch's feasibility changes: `test(t, ok)` decides every branch at one interval's
/// midpoint t.
fn side_intervals<const N: usize>(
    cuts: &[f64],
    mut test: impl FnMut(f64, &mut [bool; N]),
) -> [Vec<[f64; 2]>; N] {
    let mut bounds = Vec::with_capacity(cuts.len() + 2);
    bounds.push(0.0);
    bounds.extend(cuts.iter().copied().filter(|c| *c > 0.0 && *c < TAU));
    bounds.push(TAU);
    bounds.dedup_by(|a, b| (*a - *b).abs() < 1e-13);
    let mut out: [Vec<[f64; 2]>; N] = std::array::from_fn(|_| Vec::new());
    let mut ok = [false; N];
    for w in bounds.windows(2) {
        let (lo, hi) = (w[0], w[1]);
        if hi <= lo {
            continue;
        }
        test(0.5 * (lo + hi), &mut ok);
        for (list, _) in out.iter_mut().zip(ok).filter(|(_, v)| *v) {
            match list.last_mut() {
                Some(l) if l[1] == lo => l[1] = hi,
                _ => list.push([lo, hi]),
            }
        }
    }
    out
}

/// The intersection of two sorted lists of disjoint intervals.
fn intersect(a: &[[f64; 2]], b: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let (mut i, mut j, mut out) = (0, 0, Vec::new());
    while i < a.len() && j < b.len() {
        let (lo, hi) = (a[i][0].max(b[j][0]), a[i][1].min(b[j][1]));
        if hi > lo {
            out.push([lo, hi]);
        }
        if a[i][1] < b[j][1] {
            i += 1;
        } else {
            j += 1;
        }
    }
    out
}

/// The feasible intervals of 8 branches from the `cuts` (in [0, 2 pi)) between which no branch's
/// feasibility changes: `test(t, ok)` decides each branch at one interval's midpoint t. Pieces
/// of [-pi, pi] in branch order.
pub(super) fn midpoint_intervals(
    mut cuts: Vec<f64>,
    test: impl FnMut(f64, &mut [bool; 8]),
) -> [Vec<[f64; 2]>; 8] {
    cuts.sort_by(f64::total_cmp);
    side_intervals(&cuts, test).map(|list| to_signed(&list))
}

/// Intervals of [0, 2 pi] as pieces of [-pi, pi]: an interval across pi is split in two, and
/// the pieces touching at +-pi stay two.
pub(super) fn to_signed(list: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut out = Vec::new();
    for &[lo, hi] in list {
        if hi <= PI {
            out.push([lo, hi]);
        } else if lo >= PI {
            out.push([lo - TAU, hi - TAU]);
        } else {
            out.push([lo, PI]);
            out.push([-PI, hi - TAU]);
        }
    }
    out.sort_by(|a, b| a[0].total_cmp(&b[0]));
    // Pieces that meet at 0 (the cut added there) join again.
    let mut merged: Vec<[f64; 2]> = Vec::new();
    for iv in out {
        match merged.last_mut() {
            Some(l) if (l[1] - iv[0]).abs() < 1e-13 => l[1] = iv[1],
            _ => merged.push(iv),
        }
    }
    merged
}

impl SrsArm {
    /// The number of disjoint self-motion manifolds inside the limits for `target`: the feasible
    /// intervals of the 8 branches, joined where two branches' solutions coincide (a shoulder or
    /// wrist branch merge).
    pub fn manifolds(&self, target: &Pose) -> usize {
        let pieces = self.feasible_intervals(target);
        let points: Vec<f64> = self
            .breakpoints(target)
            .into_iter()
            .map(|p| if p > PI { p - TAU } else { p })
            .collect();
        let same = |a: usize, b: usize, psi: f64| {
            let mut raw = [[0.0; 7]; 8];
            let mask = self.solve_raw(target, psi, &mut raw);
            mask >> a & 1 == 1 && mask >> b & 1 == 1 && super::same_angles(&raw[a], &raw[b])
        };
        super::count_manifolds(&pieces, &points, &same)
    }
}

impl SrsArm {
    /// [`Self::solve`] with each branch FK-checked against `target`: position error (m) and
    /// rotation angle of `R^T R_target` (rad).
    pub fn branch_solutions(
        &self,
        robot: &Robot,
        target: &Pose,
        psi: f64,
    ) -> Vec<super::BranchSolution> {
        self.solve(target, psi)
            .into_iter()
            .map(|s| super::checked(robot, target, s.name, &s.q, &self.limits))
            .collect()
    }
}
