//! The exact self-motion of offset-elbow 7R arms (the Franka Panda) parameterised by the last
//! joint's angle q7: three intersecting shoulder axes at S, an elbow axis 4 that misses S and
//! the wrist point, axes 5 and 6 meeting at the wrist point W, and an axis 7 that misses W (so
//! the arm is not SRS and has no arm angle of its own).
//!
//! Read from the joint axes at q = 0 (product of exponentials), like [`super::srs`]: with g_i
//! the rigid motion of joint i, the target fixes `G = g_1 ... g_6 = T_target T(0)^-1 g_7(q7)^-1`
//! once q7 is chosen. Then
//! - W is on axes 5 and 6, so `g_1 ... g_4 W_0 = G W_0 = W_t`, and S is on axes 1-3, so
//!   |W_t - S| depends on q4 alone: two elbow solutions (law of cosines about axis 4);
//! - the shoulder rotation `R_sh = R_1 R_2 R_3` takes `v_4 = g_4 W_0 - S` to `W_t - S`: a
//!   rotation `Rot(u, psi) R_ref` about the shoulder-wrist direction u, one angle psi left;
//! - the wrist `R_5 R_6 = (R_sh R_4)^T M` (M the rotation of G) exists if and only if
//!   `(R_sh R_4 w_5) . (M w_6) = w_5 . w_6`, a trigonometric equation `a sin psi + b cos psi +
//!   c = 0` in psi: two wrist solutions (the two roots);
//! - the shoulder's three angles from `R_sh` (subproblem 2 for axis 3's direction, two
//!   solutions), then q5 and q6 by subproblem 1.
//!
//! Eight branches in all, labelled by the three signs like the SRS arm's.

use super::geometry::{meet, rot, rotv, rotv_sc, sub1, sub2_sc, trig_roots, wrap_into};
use crate::kinematics::{Pose, Robot};
use nalgebra::{Matrix3, Point3, Rotation3, Vector3};
use std::f64::consts::{PI, TAU};

/// Steps of q7 over [0, 2 pi) on which the limit crossings of the joints without a closed form
/// (1-3, 5, 6) are bracketed before bisection.
pub const BRACKET_STEPS: usize = 2048;

/// An offset-elbow 7R arm read from its axes (see the module documentation).
#[derive(Debug, Clone)]
pub struct OffsetElbowArm {
    /// Joint axes at q = 0 (world, unit).
    w: [Vector3<f64>; 7],
    /// A point on each axis at q = 0 (world, m).
    o: [Vector3<f64>; 7],
    /// Shoulder centre and wrist point at q = 0 (world, m).
    s: Vector3<f64>,
    w0: Vector3<f64>,
    /// Tool pose at q = 0.
    t0: Pose,
    /// A unit vector perpendicular to each axis (for subproblem 1 on that axis).
    probe: [Vector3<f64>; 7],
    limits: Vec<[f64; 2]>,
}

impl OffsetElbowArm {
    /// The offset-elbow structure of a 7R robot (one end-effector), or `None` without it.
    pub fn detect(robot: &Robot) -> Option<Self> {
        let (w, o, t0) = super::geometry::axes_7r(robot)?;
        let tol = 1e-9 * robot.characteristic_length();
        let (s, g01) = meet(&o[0], &w[0], &o[1], &w[1]);
        let (s2, g12) = meet(&o[1], &w[1], &o[2], &w[2]);
        let (w0, g45) = meet(&o[4], &w[4], &o[5], &w[5]);
        let line_gap = |k: usize, p: &Vector3<f64>| (p - o[k]).cross(&w[k]).norm();
        let ok = g01 < tol
            && g12 < tol
            && (s - s2).norm() < tol
            && g45 < tol
            && line_gap(3, &s) > tol
            && line_gap(3, &w0) > tol
            && line_gap(6, &w0) > tol
            && w[4].cross(&w[5]).norm() > 1e-9;
        if !ok {
            return None;
        }
        let probe = super::geometry::probes(&w);
        Some(Self {
            w,
            o,
            s,
            w0,
            t0,
            probe,
            limits: robot.limits(),
        })
    }

    /// Branch names in branch order (8), as the SRS arm's.
    pub fn branch_names() -> [String; 8] {
        super::srs::SrsArm::branch_names()
    }

    /// The shoulder centre S (world, m).
    pub fn shoulder(&self) -> Vector3<f64> {
        self.s
    }

    /// `G = T_target T(0)^-1 g_7(q7)^-1`, the motion of joints 1-6 (see the module docs).
    fn six(&self, target: &Pose, q7: f64) -> Pose {
        let r7 = rot(&self.w[6], -q7);
        let g7_inv = Pose::from_parts(nalgebra::Translation3::from(self.o[6] - r7 * self.o[6]), r7);
        target * self.t0.inverse() * g7_inv
    }

    /// The wrist point W (world, m) for `target` and `q7`.
    pub fn wrist_of(&self, target: &Pose, q7: f64) -> Vector3<f64> {
        (self.six(target, q7) * Point3::from(self.w0)).coords
    }

    /// The elbow angle q4 (rad, branch `sign`) putting W at distance `l` (m) from S.
    fn elbow(&self, l: f64, sign: f64) -> Option<f64> {
        super::geometry::elbow_angle(
            &(self.o[3] - self.s),
            &(self.w0 - self.o[3]),
            &self.w[3],
            l,
            sign,
        )
    }

    /// The shoulder-wrist vector after joint 4 alone (world, m).
    fn v4(&self, q4: f64) -> Vector3<f64> {
        self.o[3] - self.s + rot(&self.w[3], q4) * (self.w0 - self.o[3])
    }

    /// Every branch reaching `target` with last joint angle `q7` (rad), allocation-free: branch
    /// k is written to `out[k]` when bit k of the returned mask is set (angles not wrapped).
    /// Bit 8 of the result is set where the wrist equation is degenerate (every psi solves it, or
    /// none can be told apart): a singular q7, reported instead of a NaN.
    pub fn solve_raw(&self, target: &Pose, q7: f64, out: &mut [[f64; 7]; 8]) -> u16 {
        let g = self.six(target, q7);
        let wt = (g * Point3::from(self.w0)).coords;
        let sw = wt - self.s;
        let l = sw.norm();
        if l < 1e-12 {
            return 1 << 8;
        }
        let u = sw / l;
        let m = g.rotation.into_inner();
        let y = m * self.w[5];
        let c56 = self.w[4].dot(&self.w[5]);
        let mut mask = 0u16;
        let mut roots = Vec::with_capacity(2);
        for (ie, se) in [1.0, -1.0].into_iter().enumerate() {
            let Some(q4) = self.elbow(l, se) else {
                continue;
            };
            let r4 = rot(&self.w[3], q4);
            let r_ref = rotation_between(&self.v4(q4), &sw);
            let x = r_ref * (r4 * self.w[4]);
            let x_par = u * u.dot(&x);
            let (a, b, c) = (
                u.cross(&x).dot(&y),
                (x - x_par).dot(&y),
                x_par.dot(&y) - c56,
            );
            if a.hypot(b) < 1e-12 {
                mask |= 1 << 8;
                continue;
            }
            roots.clear();
            trig_roots(a, b, c, &mut roots);
            for (iw, psi) in roots.iter().enumerate() {
                let r_sh = rot(&u, *psi).into_inner() * r_ref;
                let n = (r_sh * r4.into_inner()).transpose() * m;
                let q5 = sub1(&self.w[4], &self.w[5], &(n * self.w[5]));
                let v = rotv(&self.w[4], -q5, &(n * self.probe[5]));
                let q6 = sub1(&self.w[5], &self.probe[5], &v);
                for (is, ss) in [1.0, -1.0].into_iter().enumerate() {
                    let Some([q1, q2, q3]) = self.shoulder_angles(&r_sh, ss) else {
                        continue;
                    };
                    let k = is << 2 | ie << 1 | iw;
                    out[k] = [q1, q2, q3, q4, q5, q6, q7];
                    mask |= 1 << k;
                }
            }
        }
        mask
    }

    /// The shoulder's three angles with `R_1 R_2 R_3 = r`, branch `sign` of subproblem 2.
    fn shoulder_angles(&self, r: &Matrix3<f64>, sign: f64) -> Option<[f64; 3]> {
        let (w1, w2, w3) = (&self.w[0], &self.w[1], &self.w[2]);
        let (a1, a2) = sub2_sc(w1, w2, w3, &(r * w3), sign)?;
        let x = self.probe[2];
        let v = rotv_sc(w2, -a2.s, a2.c, &rotv_sc(w1, -a1.s, a1.c, &(r * x)));
        Some([a1.t, a2.t, sub1(w3, &x, &v)])
    }

    /// Every branch (up to 8) at `q7`, named, wrapped into the limits where they fit and
    /// FK-checked against `target`.
    pub fn branch_solutions(
        &self,
        robot: &Robot,
        target: &Pose,
        q7: f64,
    ) -> Vec<super::BranchSolution> {
        let names = Self::branch_names();
        let mut raw = [[0.0; 7]; 8];
        let mask = self.solve_raw(target, q7, &mut raw);
        (0..8)
            .filter(|k| mask >> k & 1 == 1)
            .map(|k| {
                super::checked(
                    robot,
                    target,
                    names[k].clone(),
                    &wrap_into(raw[k], &self.limits),
                    &self.limits,
                )
            })
            .collect()
    }

    /// Whether `q7` is singular for `target` (the wrist equation degenerate).
    pub fn singular(&self, target: &Pose, q7: f64) -> bool {
        self.solve_raw(target, q7, &mut [[0.0; 7]; 8]) >> 8 & 1 == 1
    }
}

/// The rotation taking direction `a` to direction `b` (the half-turn about a perpendicular when
/// they are opposite).
fn rotation_between(a: &Vector3<f64>, b: &Vector3<f64>) -> Matrix3<f64> {
    Rotation3::rotation_between(a, b)
        .unwrap_or_else(|| {
            let h = if a.x.abs() < 0.9 {
                Vector3::x()
            } else {
                Vector3::y()
            };
            rot(&a.cross(&h).normalize(), PI)
        })
        .into_inner()
}

impl OffsetElbowArm {
    /// The signed distance (rad) of joint `k`'s angle inside its limits (negative outside, and
    /// +inf for a joint without limits): its roots are the limit crossings.
    fn margin(&self, k: usize, q: f64) -> f64 {
        let [lo, hi] = self.limits[k];
        if !(lo.is_finite() && hi.is_finite()) || hi - lo >= TAU - 1e-12 {
            return f64::INFINITY;
        }
        let mid = 0.5 * (lo + hi);
        0.5 * (hi - lo) - super::wrap(q - mid).abs()
    }

    /// Every q7 (rad, in [0, 2 pi)) where the joint-limit feasibility of a branch can change:
    /// q7's own limits; a joint at a limit or a branch appearing or vanishing, bracketed on
    /// [`BRACKET_STEPS`] steps of q7 and bisected to 1e-14 rad.
    pub fn breakpoints(&self, target: &Pose) -> Vec<f64> {
        let mut out: Vec<f64> = self.limits[6]
            .iter()
            .filter(|v| v.is_finite() && self.limits[6][1] - self.limits[6][0] < TAU - 1e-12)
            .map(|v| v.rem_euclid(TAU))
            .collect();
        let h = TAU / BRACKET_STEPS as f64;
        let mut raw = [[0.0; 7]; 8];
        // A sample: the mask and, per branch, the margins of joints 1-6.
        let sample = |t: f64, raw: &mut [[f64; 7]; 8]| -> (u16, [[f64; 6]; 8]) {
            let mask = self.solve_raw(target, t, raw);
            let mut g = [[0.0; 6]; 8];
            for k in 0..8 {
                for j in 0..6 {
                    g[k][j] = self.margin(j, raw[k][j]);
                }
            }
            (mask, g)
        };
        let mut prev = sample(0.0, &mut raw);
        for i in 1..=BRACKET_STEPS {
            let t1 = h * i as f64;
            let next = sample(t1, &mut raw);
            let t0 = t1 - h;
            for k in 0..8 {
                let (a, b) = (prev.0 >> k & 1, next.0 >> k & 1);
                if a != b {
                    out.push(self.bisect(target, t0, t1, &|m, _| m >> k & 1 == a));
                } else if a == 1 {
                    for j in 0..6 {
                        let (ga, gb) = (prev.1[k][j], next.1[k][j]);
                        if (ga >= 0.0) != (gb >= 0.0) {
                            let inside = ga >= 0.0;
                            out.push(self.bisect(target, t0, t1, &|m, r: &[[f64; 7]; 8]| {
                                m >> k & 1 == 1 && (self.margin(j, r[k][j]) >= 0.0) == inside
                            }));
                        }
                    }
                }
            }
            prev = next;
        }
        let mut out: Vec<f64> = out.into_iter().map(|p| p.rem_euclid(TAU)).collect();
        out.sort_by(f64::total_cmp);
        out.dedup_by(|a, b| (*a - *b).abs() < 1e-13);
        out
    }

    /// The point in [t0, t1] where `same(mask, solutions)` stops holding (true at t0).
    fn bisect(
        &self,
        target: &Pose,
        mut t0: f64,
        mut t1: f64,
        same: &dyn Fn(u16, &[[f64; 7]; 8]) -> bool,
    ) -> f64 {
        let mut raw = [[0.0; 7]; 8];
        while t1 - t0 > 1e-14 {
            let t = 0.5 * (t0 + t1);
            if same(self.solve_raw(target, t, &mut raw), &raw) {
                t0 = t;
            } else {
                t1 = t;
            }
        }
        0.5 * (t0 + t1)
    }

    /// The feasible values of q7 of every branch inside the joint limits: between consecutive
    /// [`Self::breakpoints`] no joint crosses a limit, so one test at each interval's midpoint
    /// decides it. Pieces of [-pi, pi] (one across +-pi given as two), in branch order.
    pub fn feasible_intervals(&self, target: &Pose) -> [Vec<[f64; 2]>; 8] {
        self.intervals_from(target, self.breakpoints(target))
    }

    /// [`Self::feasible_intervals`] from breakpoints already found.
    fn intervals_from(&self, target: &Pose, cuts: Vec<f64>) -> [Vec<[f64; 2]>; 8] {
        let mut raw = [[0.0; 7]; 8];
        super::srs::midpoint_intervals(cuts, |t, ok: &mut [bool; 8]| {
            let mask = self.solve_raw(target, t, &mut raw);
            for (k, v) in ok.iter_mut().enumerate() {
                *v = mask >> k & 1 == 1
                    && super::geometry::within(&wrap_into(raw[k], &self.limits), &self.limits);
            }
        })
    }

    /// The number of disjoint self-motion manifolds inside the limits: the feasible intervals
    /// of the 8 branches, joined where two branches' solutions coincide.
    pub fn manifolds(&self, target: &Pose) -> usize {
        self.feasible_and_manifolds(target).1
    }

    /// [`Self::feasible_intervals`] and [`Self::manifolds`] together, the breakpoints found
    /// once.
    pub fn feasible_and_manifolds(&self, target: &Pose) -> ([Vec<[f64; 2]>; 8], usize) {
        let cuts = self.breakpoints(target);
        let points: Vec<f64> = cuts
            .iter()
            .map(|&p| if p > PI { p - TAU } else { p })
            .collect();
        let pieces = self.intervals_from(target, cuts);
        let same = |a: usize, b: usize, t: f64| {
            let mut raw = [[0.0; 7]; 8];
            let mask = self.solve_raw(target, t, &mut raw);
            mask >> a & 1 == 1 && mask >> b & 1 == 1 && super::same_angles(&raw[a], &raw[b])
        };
        let count = super::count_manifolds(&pieces, &points, &same);
        (pieces, count)
    }
}
