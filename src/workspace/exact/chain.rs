//! A planar chain of two or three revolute joints as plane geometry (Sect. 2.9.1, Fig. 2.20):
//! the axis of joint 1, the link vectors at q = 0 and the sense of each joint, read from the
//! robot's forward kinematics and Jacobian (so DH offsets, base and tool transforms, twists of pi
//! and URDF models are all covered), and the exact point test of Sect. 2.12.1 with the orientation
//! left free.
//!
//! With `theta_k = sum_{j<=k} s_j q_j` (s_j = +-1, the sense of axis j along the plane normal) the
//! end-effector position is `p = c_1 + sum_k R(theta_k) u_k`, which is (2.63) with the link
//! vectors `u_k` in place of `a_k (1, 0)`. Angles of the link vectors: `alpha_k = theta_k + beta_k`
//! (absolute), `gamma_k = alpha_k - alpha_{k-1}` (relative, `gamma_k = s_k q_k + beta_k -
//! beta_{k-1}`).

use super::super::{PlanarFrame, WorkspaceError, planar_frame};
use crate::kinematics::ik::closed_form::{ClosedForm, Family};
use crate::kinematics::{JointKind, Pose, Robot};
use nalgebra::{Matrix6xX, Vector3};
use std::f64::consts::{PI, TAU};

/// Slack of the joint-limit test (rad), as the closed-form IK's.
pub(crate) const LIMIT_SLACK: f64 = 1e-12;

/// The range of one joint: `[lo, hi]` (rad), or the whole circle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Range {
    pub lo: f64,
    pub hi: f64,
    /// The range covers 2 pi or more: every angle is allowed.
    pub full: bool,
}

impl Range {
    pub(crate) fn of(l: [f64; 2]) -> Self {
        let full = !(l[0].is_finite() && l[1].is_finite()) || l[1] - l[0] >= TAU - 1e-12;
        let (lo, hi) = if full { (-PI, PI) } else { (l[0], l[1]) };
        Self { lo, hi, full }
    }

    /// Whether angle `q` (any representative) is inside the range.
    #[inline]
    pub fn contains(&self, q: f64) -> bool {
        if self.full {
            return true;
        }
        // The representative of q just above lo - slack.
        let k = ((self.lo - LIMIT_SLACK - q) / TAU).ceil();
        let v = q + k * TAU;
        v <= self.hi + LIMIT_SLACK
    }

    /// The representative of `q` inside the range, if any.
    pub fn representative(&self, q: f64) -> Option<f64> {
        if self.full {
            return Some(crate::kinematics::orientation::wrap_angle(q));
        }
        let k = ((self.lo - LIMIT_SLACK - q) / TAU).ceil();
        let v = q + k * TAU;
        (v <= self.hi + LIMIT_SLACK).then_some(v.clamp(self.lo, self.hi))
    }

    /// The limits as values (none for a full range).
    pub fn ends(&self) -> Vec<f64> {
        if self.full {
            Vec::new()
        } else {
            vec![self.lo, self.hi]
        }
    }
}

/// A two- or three-link planar revolute chain in plane coordinates (m, rad).
#[derive(Debug, Clone)]
pub(crate) struct PlanarChain {
    /// Number of joints (2 or 3).
    pub n: usize,
    /// Axis of joint 1 in plane coordinates (m).
    pub c1: [f64; 2],
    /// Link lengths |u_k| (m).
    pub len: [f64; 3],
    /// Angles of the link vectors at q = 0 (rad).
    pub beta: [f64; 3],
    /// Sense of each joint along the plane normal (+1 or -1).
    pub sign: [f64; 3],
    /// Joint ranges.
    pub range: [Range; 3],
    /// Class index of the branch with sin(gamma_2) > 0 and of the one with sin(gamma_2) < 0.
    pub branch_class: [u8; 2],
    /// Size of the arm (sum of the lengths, m).
    pub scale: f64,
}

/// Membership of one point: the posture classes that reach it, and (three links) the measure of
/// the orientations phi it is reached with.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Membership {
    /// Bit k set when posture class k reaches the point within the limits.
    pub mask: u8,
    /// Measure (rad) of the end-effector orientations phi with which some posture reaches the
    /// point: 0 to 2 pi for a three-link arm, 0 for a two-link arm (its orientation is not free).
    pub orientations: f64,
}

#[inline]
fn cis(a: f64) -> [f64; 2] {
    let (s, c) = a.sin_cos();
    [c, s]
}

impl PlanarChain {
    /// Reads the chain of a two- or three-link planar arm (closed-form family `Planar2` or
    /// `Planar3`, every joint revolute, one end-effector).
    pub fn from_robot(robot: &Robot) -> Result<(Self, PlanarFrame), WorkspaceError> {
        let not = |why: &str| WorkspaceError::NotPlanar {
            robot: robot.name.clone(),
            reason: format!("has no exact planar workspace: {why}"),
        };
        let cf = ClosedForm::detect(robot).map_err(|e| not(&e.to_string()))?;
        let n = match cf.family() {
            Family::Planar2 => 2,
            Family::Planar3 => 3,
            _ => return Err(not("it is not a two- or three-link planar arm")),
        };
        if robot.end_effectors().len() != 1
            || (0..n).any(|k| robot.dof_joint(k).kind != JointKind::Revolute)
        {
            return Err(not("the joints must be revolute with one end-effector"));
        }
        let frame =
            planar_frame(robot, 0).ok_or_else(|| not("its end-effector leaves the plane"))?;
        let q0 = vec![0.0; n];
        let mut frames = vec![Pose::identity(); robot.joints().len()];
        let mut jac = Matrix6xX::zeros(n);
        let tool = robot.jacobian_into(&q0, 0, &mut frames, &mut jac)?;
        let rot = frame.world_from_base.rotation.inverse();
        let tp = tool.translation.vector;
        let p0 = frame.to_plane([tp.x, tp.y, tp.z]);
        let mut centres = [[0.0; 2]; 3];
        let mut sign = [1.0; 3];
        for k in 0..n {
            let c = jac.column(k);
            let v = rot * Vector3::new(c[0], c[1], c[2]);
            let z = rot * Vector3::new(c[3], c[4], c[5]);
            sign[k] = z.z.signum();
            // v = s (-(p - c)_y, (p - c)_x)
            centres[k] = [p0[0] - v.y / sign[k], p0[1] + v.x / sign[k]];
        }
        let mut len = [0.0; 3];
        let mut beta = [0.0; 3];
        for k in 0..n {
            let next = if k + 1 < n { centres[k + 1] } else { p0 };
            let u = [next[0] - centres[k][0], next[1] - centres[k][1]];
            len[k] = u[0].hypot(u[1]);
            beta[k] = u[1].atan2(u[0]);
        }
        let scale: f64 = len.iter().sum();
        if len[..n].iter().any(|&l| l <= 1e-9 * scale.max(1e-9)) {
            return Err(not(
                "a link of zero length (two axes coincide, or the tool point lies on the last axis)",
            ));
        }
        let limits = robot.limits();
        let mut range = [Range::of([-PI, PI]); 3];
        for k in 0..n {
            range[k] = Range::of(limits[k]);
        }
        let mut chain = Self {
            n,
            c1: centres[0],
            len,
            beta,
            sign,
            range,
            branch_class: [0, 1],
            scale,
        };
        chain.check_against_fk(robot, &frame)?;
        chain.branch_class = chain.classes_of_branches(robot);
        Ok((chain, frame))
    }

    /// Joint vector of absolute link angles alpha (rad).
    pub fn q_of_alpha(&self, alpha: &[f64; 3]) -> [f64; 3] {
        let mut q = [0.0; 3];
        let mut prev = 0.0;
        let mut prev_beta = 0.0;
        for k in 0..self.n {
            q[k] = self.sign[k] * (alpha[k] - prev - self.beta[k] + prev_beta);
            prev = alpha[k];
            prev_beta = self.beta[k];
        }
        q
    }

    /// Absolute link angles of a joint vector (rad).
    pub fn alpha_of_q(&self, q: &[f64]) -> [f64; 3] {
        let mut a = [0.0; 3];
        let mut theta = 0.0;
        for k in 0..self.n {
            theta += self.sign[k] * q[k];
            a[k] = theta + self.beta[k];
        }
        a
    }

    /// Position of the axis of joint `k` (k = n: the end-effector) at link angles `alpha`.
    pub fn point(&self, alpha: &[f64; 3], k: usize) -> [f64; 2] {
        let mut p = self.c1;
        for (a, l) in alpha.iter().zip(&self.len).take(k) {
            let e = cis(*a);
            p[0] += l * e[0];
            p[1] += l * e[1];
        }
        p
    }

    /// The model reproduces the forward kinematics at a few configurations (1e-9 of the size).
    fn check_against_fk(&self, robot: &Robot, frame: &PlanarFrame) -> Result<(), WorkspaceError> {
        let tests = [[0.3, -0.7, 1.1], [-1.2, 0.4, -0.3], [2.0, 1.5, -2.5]];
        for t in tests {
            let q = &t[..self.n];
            let p = robot.fk(q)?.translation.vector;
            let want = frame.to_plane([p.x, p.y, p.z]);
            let got = self.point(&self.alpha_of_q(q), self.n);
            if (got[0] - want[0]).hypot(got[1] - want[1]) > 1e-9 * self.scale {
                return Err(WorkspaceError::NotPlanar {
                    robot: robot.name.clone(),
                    reason: "has no exact planar workspace: the plane model of the chain does \
                             not reproduce its forward kinematics"
                        .into(),
                });
            }
        }
        Ok(())
    }

    /// The posture class of each elbow branch, from the robot's own classifier.
    fn classes_of_branches(&self, robot: &Robot) -> [u8; 2] {
        let classifier = super::super::PostureClassifier::new(robot);
        if classifier.class_count() < 2 {
            return [0, 0];
        }
        let mut out = [0u8, 1u8];
        for (b, g) in [0.5 * PI, -0.5 * PI].into_iter().enumerate() {
            let alpha = [self.beta[0], self.beta[0] + g, self.beta[0] + g];
            let q = self.q_of_alpha(&alpha);
            let Ok(t) = robot.fk(&q[..self.n]) else {
                continue;
            };
            let c = classifier.classify(&q[..self.n], &t);
            if (c as usize) < classifier.class_count() {
                out[b] = c;
            }
        }
        out
    }

    /// Two-link solution for the point `w` relative to joint 1's axis: link angles (alpha1,
    /// gamma2) of branch `b` (0: sin gamma2 >= 0, 1: <= 0), or `None` when out of reach.
    #[inline]
    fn two_link(&self, w: [f64; 2], b: usize) -> Option<(f64, f64)> {
        let (l1, l2) = (self.len[0], self.len[1]);
        let r2 = w[0] * w[0] + w[1] * w[1];
        // c2 = (p_Wx^2 + p_Wy^2 - a1^2 - a2^2) / (2 a1 a2)   (Sect. 2.12.1)
        let c = (r2 - l1 * l1 - l2 * l2) / (2.0 * l1 * l2);
        if !(-1.0 - 1e-12..=1.0 + 1e-12).contains(&c) {
            return None;
        }
        let c = c.clamp(-1.0, 1.0);
        let s = ((1.0 - c) * (1.0 + c)).sqrt() * if b == 0 { 1.0 } else { -1.0 };
        let k = l1 + l2 * c;
        let a1 = (k * w[1] - l2 * s * w[0]).atan2(k * w[0] + l2 * s * w[1]);
        Some((a1, s.atan2(c)))
    }

    /// The wrist point `p - a_3 (cos phi, sin phi)` (three links) solved as a two-link arm:
    /// (alpha1, gamma2) of branch `b`, limits not checked.
    #[inline]
    fn arm_angles(&self, p: [f64; 2], phi: f64, b: usize) -> Option<(f64, f64)> {
        let mut w = [p[0] - self.c1[0], p[1] - self.c1[1]];
        if self.n == 3 {
            let e = cis(phi);
            w[0] -= self.len[2] * e[0];
            w[1] -= self.len[2] * e[1];
        }
        self.two_link(w, b)
    }

    /// Whether branch `b` reaches `p` within the limits with the last link at absolute angle
    /// `phi` (three links) or at all (two links, `phi` unused).
    #[inline]
    pub fn feasible(&self, p: [f64; 2], phi: f64, b: usize) -> bool {
        self.solve(p, phi, b).is_some()
    }

    /// The absolute link angles (rad) of branch `b` reaching `p` (with the last link at `phi`
    /// for three links) when that configuration is within the limits.
    #[inline]
    pub fn solve(&self, p: [f64; 2], phi: f64, b: usize) -> Option<[f64; 3]> {
        let (a1, g2) = self.arm_angles(p, phi, b)?;
        let q1 = self.sign[0] * (a1 - self.beta[0]);
        let q2 = self.sign[1] * (g2 - self.beta[1] + self.beta[0]);
        if !(self.range[0].contains(q1) && self.range[1].contains(q2)) {
            return None;
        }
        if self.n == 3 {
            let q3 = self.sign[2] * (phi - a1 - g2 - self.beta[2] + self.beta[1]);
            if !self.range[2].contains(q3) {
                return None;
            }
        }
        Some([a1, a1 + g2, phi])
    }

    /// Branch `b`'s joint vector (rad) reaching `p` with the last link at absolute angle `phi`
    /// (three links) whether or not it is within the limits, and whether it is; `None` when the
    /// wrist point is out of the two-link reach.
    pub fn solve_unlimited(&self, p: [f64; 2], phi: f64, b: usize) -> Option<([f64; 3], bool)> {
        let (a1, g2) = self.arm_angles(p, phi, b)?;
        let q = self.q_of_alpha(&[a1, a1 + g2, phi]);
        let within = (0..self.n).all(|k| self.range[k].contains(q[k]));
        let wrapped = std::array::from_fn(|k| {
            if k < self.n {
                self.range[k]
                    .representative(q[k])
                    .unwrap_or_else(|| crate::kinematics::orientation::wrap_angle(q[k]))
            } else {
                0.0
            }
        });
        Some((wrapped, within))
    }

    /// The last link's absolute angles (rad, [0, 2 pi)) at which the two elbow branches merge
    /// for the point `p`: the wrist point on the two-link arm's outer or inner circle.
    pub fn merge_angles(&self, p: [f64; 2]) -> Vec<f64> {
        let mut bp = [0.0; 16];
        let mut me = self.clone();
        // Only the two reach circles: no limits.
        me.range = [Range::of([f64::NEG_INFINITY, f64::INFINITY]); 3];
        let n = me.breakpoints(p, &mut bp);
        bp[..n].to_vec()
    }

    /// Position manipulability sqrt(det(J_P J_P^T)) (m^2) at link angles `alpha`: by the
    /// Cauchy-Binet formula the root of the sum of the squared cross products of the columns,
    /// `(p - c_i) x (p - c_j)` for i < j.
    pub fn manipulability(&self, alpha: &[f64; 3]) -> f64 {
        let p = self.point(alpha, self.n);
        let r: Vec<[f64; 2]> = (0..self.n)
            .map(|k| {
                let c = self.point(alpha, k);
                [p[0] - c[0], p[1] - c[1]]
            })
            .collect();
        let mut sum = 0.0;
        for i in 0..self.n {
            for j in i + 1..self.n {
                let c = r[i][0] * r[j][1] - r[i][1] * r[j][0];
                sum += c * c;
            }
        }
        sum.sqrt()
    }

    /// Largest position manipulability (m^2) over the configurations reaching `p`: both branches
    /// (two links); both branches at 96 orientations and at each breakpoint interval's midpoint
    /// (three links). `None` when `p` is not reached.
    pub fn max_manipulability(&self, p: [f64; 2]) -> Option<f64> {
        let mut best: Option<f64> = None;
        let mut try_phi = |phi: f64| {
            for b in 0..2 {
                if let Some(a) = self.solve(p, phi, b) {
                    let m = self.manipulability(&a);
                    best = Some(best.map_or(m, |x: f64| x.max(m)));
                }
            }
        };
        if self.n == 2 {
            try_phi(0.0);
            return best;
        }
        for k in 0..96 {
            try_phi(k as f64 * TAU / 96.0);
        }
        let mut bp = [0.0; 16];
        let n = self.breakpoints(p, &mut bp);
        let bp = &mut bp[..n];
        bp.sort_unstable_by(f64::total_cmp);
        for i in 0..n {
            let hi = if i + 1 < n { bp[i + 1] } else { bp[0] + TAU };
            try_phi(0.5 * (bp[i] + hi));
        }
        best
    }

    /// The values of phi (absolute angle of the last link, rad, in [0, 2 pi)) where the set of
    /// feasible orientations of some branch can change: a joint at a limit, or the wrist point
    /// on the inner or outer circle of the two-link arm (branches merge). Each is a root of
    /// `|A - B e^{i phi}| = R`. Returns the count written into `out` (at most 16).
    pub(crate) fn breakpoints(&self, p: [f64; 2], out: &mut [f64; 16]) -> usize {
        let (l1, l2, l3) = (self.len[0], self.len[1], self.len[2]);
        let a = [p[0] - self.c1[0], p[1] - self.c1[1]];
        let mut n = 0;
        let mut push = |av: [f64; 2], bv: [f64; 2], r: f64| {
            // Re(conj(A) B e^{i phi}) = (|A|^2 + |B|^2 - R^2) / 2
            let z = [av[0] * bv[0] + av[1] * bv[1], av[0] * bv[1] - av[1] * bv[0]];
            let zn = z[0].hypot(z[1]);
            let k = 0.5 * (av[0] * av[0] + av[1] * av[1] + bv[0] * bv[0] + bv[1] * bv[1] - r * r);
            if zn <= 1e-300 || k.abs() > zn {
                return;
            }
            let zeta = z[1].atan2(z[0]);
            let d = (k / zn).acos();
            for phi in [-zeta + d, -zeta - d] {
                if n < out.len() {
                    out[n] = phi.rem_euclid(TAU);
                    n += 1;
                }
            }
        };
        let b3 = [l3, 0.0];
        push(a, b3, l1 + l2);
        push(a, b3, (l1 - l2).abs());
        for lam in self.range[1].ends() {
            let g = self.sign[1] * lam + self.beta[1] - self.beta[0];
            let e = cis(g);
            push(a, b3, (l1 + l2 * e[0]).hypot(l2 * e[1]));
        }
        for lam in self.range[0].ends() {
            let e = cis(self.sign[0] * lam + self.beta[0]);
            push([a[0] - l1 * e[0], a[1] - l1 * e[1]], b3, l2);
        }
        for lam in self.range[2].ends() {
            let e = cis(-(self.sign[2] * lam + self.beta[2] - self.beta[1]));
            push(a, [l3 + l2 * e[0], l2 * e[1]], l1);
        }
        n
    }

    /// Exact membership of a point in plane coordinates (m): the classes reaching it, and the
    /// measure of the orientations reaching it. Allocation-free.
    ///
    /// Three links: the orientation phi is free; between consecutive [`Self::breakpoints`] the
    /// feasibility of each branch is constant (the solution is continuous and no joint crosses a
    /// limit), so one test at each interval's midpoint and one at each breakpoint decide it.
    pub fn membership(&self, p: [f64; 2]) -> Membership {
        self.decide(p, false)
    }

    /// The class mask of [`Self::membership`] alone (stops as soon as every class is found).
    #[inline]
    pub fn mask(&self, p: [f64; 2]) -> u8 {
        self.decide(p, true).mask
    }

    fn decide(&self, p: [f64; 2], mask_only: bool) -> Membership {
        let mut m = Membership::default();
        let all = (1u8 << self.branch_class[0]) | (1u8 << self.branch_class[1]);
        if self.n == 2 {
            for b in 0..2 {
                if self.feasible(p, 0.0, b) {
                    m.mask |= 1 << self.branch_class[b];
                }
            }
            return m;
        }
        let mut bp = [0.0; 16];
        let k = self.breakpoints(p, &mut bp);
        let bp = &mut bp[..k];
        bp.sort_unstable_by(f64::total_cmp);
        if bp.is_empty() {
            for b in 0..2 {
                if self.feasible(p, 0.0, b) {
                    m.mask |= 1 << self.branch_class[b];
                    m.orientations = TAU;
                }
            }
            return m;
        }
        // Interval midpoints decide every point off the boundary; a branch feasible at a single
        // breakpoint only (a boundary point) is found by testing the breakpoints afterwards.
        for i in 0..bp.len() {
            let (lo, hi) = (
                bp[i],
                if i + 1 < bp.len() {
                    bp[i + 1]
                } else {
                    bp[0] + TAU
                },
            );
            let mid = lo + 0.5 * (hi - lo);
            let mut any = false;
            for b in 0..2 {
                let bit = 1 << self.branch_class[b];
                if (mask_only && m.mask & bit != 0) || !self.feasible(p, mid, b) {
                    continue;
                }
                m.mask |= bit;
                any = true;
            }
            if any {
                m.orientations += hi - lo;
            }
            if mask_only && m.mask == all {
                return m;
            }
        }
        for &lo in bp.iter() {
            for b in 0..2 {
                let bit = 1 << self.branch_class[b];
                if m.mask & bit == 0 && self.feasible(p, lo, b) {
                    m.mask |= bit;
                }
            }
        }
        m
    }
}

impl PlanarChain {
    /// Representatives inside joint `k`'s range of `q = s_k (gamma - beta_k + beta_{k-1})` for
    /// the given relative link angles `gamma` (rad).
    fn q_of_gamma(&self, k: usize, gammas: &[f64]) -> Vec<f64> {
        let prev = if k == 0 { 0.0 } else { self.beta[k - 1] };
        let mut v: Vec<f64> = gammas
            .iter()
            .filter_map(|g| self.range[k].representative(self.sign[k] * (g - self.beta[k] + prev)))
            .collect();
        v.sort_by(f64::total_cmp);
        v.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
        v
    }

    /// Relative angle gamma_k (rad) of joint value q_k.
    fn gamma_of(&self, k: usize, q: f64) -> f64 {
        let prev = if k == 0 { 0.0 } else { self.beta[k - 1] };
        self.sign[k] * q + self.beta[k] - prev
    }

    /// The arc traced when joint `m` sweeps its range and the others stay at `q` (rad).
    fn sweep(&self, m: usize, mut q: [f64; 3]) -> super::Arc {
        let r = self.range[m];
        q[m] = if r.full { 0.0 } else { r.lo };
        let alpha = self.alpha_of_q(&q[..self.n]);
        let c = self.point(&alpha, m);
        let p = self.point(&alpha, self.n);
        let d = [p[0] - c[0], p[1] - c[1]];
        super::Arc {
            centre: c,
            radius: d[0].hypot(d[1]),
            start: d[1].atan2(d[0]),
            sweep: self.sign[m] * if r.full { TAU } else { r.hi - r.lo },
        }
    }

    /// Every boundary candidate of the reachable set and of each posture region: the images of
    /// the edges of the joint-limit box (and of the boxes split at the elbow's singular values,
    /// which bound the posture regions), of the fold curves of their faces, and of the interior
    /// singular lines (links aligned or folded). On each, one joint moves, so each is an arc about
    /// that joint's axis.
    pub fn candidates(&self) -> Vec<super::Arc> {
        let lim = |k: usize| self.range[k].ends();
        let split = |k: usize| self.q_of_gamma(k, &[0.0, PI]);
        let cat = |a: Vec<f64>, b: Vec<f64>| a.into_iter().chain(b).collect::<Vec<f64>>();
        let mut out = Vec::new();
        if self.n == 2 {
            for v in cat(lim(1), split(1)) {
                out.push(self.sweep(0, [0.0, v, 0.0]));
            }
            for v in lim(0) {
                out.push(self.sweep(1, [v, 0.0, 0.0]));
            }
            return out;
        }
        let (l1, l2, l3) = (self.len[0], self.len[1], self.len[2]);
        let q2s = cat(lim(1), split(1));
        // Folds of the faces q3 = const (columns 1, 2 parallel) and q2 = const (columns 1, 3).
        let fold2 = |v3: f64| {
            let g3 = self.gamma_of(2, v3);
            let g = (-l3 * g3.sin()).atan2(l2 + l3 * g3.cos());
            self.q_of_gamma(1, &[g, g + PI])
        };
        let fold3 = |v2: f64| {
            let g2 = self.gamma_of(1, v2);
            let g = (-l1 * g2.sin()).atan2(l2 + l1 * g2.cos());
            self.q_of_gamma(2, &[g, g + PI])
        };
        let mut pairs: Vec<[f64; 2]> = Vec::new();
        for &v2 in &q2s {
            pairs.extend(lim(2).into_iter().map(|v3| [v2, v3]));
            pairs.extend(fold3(v2).into_iter().map(|v3| [v2, v3]));
        }
        for v3 in lim(2) {
            pairs.extend(fold2(v3).into_iter().map(|v2| [v2, v3]));
        }
        for v2 in split(1) {
            pairs.extend(split(2).into_iter().map(|v3| [v2, v3]));
        }
        for [v2, v3] in pairs {
            out.push(self.sweep(0, [0.0, v2, v3]));
        }
        for v1 in lim(0) {
            for v3 in cat(lim(2), split(2)) {
                out.push(self.sweep(1, [v1, 0.0, v3]));
            }
            for &v2 in &q2s {
                out.push(self.sweep(2, [v1, v2, 0.0]));
            }
        }
        out
    }
}
