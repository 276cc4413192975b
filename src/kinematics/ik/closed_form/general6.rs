//! Every six-revolute arm: all real solutions (at most 16) by Raghavan and Roth's elimination,
//! solved as an eigenvalue problem as Manocha and Canny do ("Efficient inverse kinematics for
//! general 6R manipulators", IEEE T-RA 10(5), 1994).
//!
//! The loop closure `A1 A2 A3 A4 A5 A6 = T` (2.52) is rearranged as
//! `A3 A4 A5 = A2^-1 A1^-1 T A6^-1`. The origin p and the z axis l of frame 5 (a point and the
//! direction of axis 6) do not depend on theta6. From p and l, both sides give the 14 quantities
//! p, l, p.p, p.l, p x l and (p.p) l - 2 (p.l) p, in frame 2. Raghavan and Roth showed that each
//! is, on the left, a trigonometric polynomial of degree 1 in each of theta3, theta4 and theta5
//! and, on the right, of degree 1 in each of theta1 and theta2. Their coefficients are found here
//! numerically, exactly: a trigonometric polynomial of degree 1 is fixed by its values at 0,
//! 2 pi/3 and 4 pi/3, so 27 evaluations of the left side and 9 of the right side give every
//! coefficient, and a check at other angles (when the arm is detected) proves the degree. Links
//! are general rigid transforms `A_i = Rz(theta_i) L_i` (a DH row, or a locked joint merged into
//! its neighbour), so the same code solves the 6R arms left when a 7R arm locks one joint.
//!
//! Then `P(theta3) v45 = Q v12`, with v45 the 9 products of (1, c4, s4) and (1, c5, s5) and v12
//! the 8 non-constant products of (1, c1, s1) and (1, c2, s2). The 6 combinations of rows that
//! annihilate Q (a Householder QR of Q) leave 6 equations in theta3, theta4, theta5 alone. With
//! half-angle tangents x3, x4, x5 and the 6 equations multiplied by x4, a 12 x 12 matrix
//! `M(x3) = M2 x3^2 + M1 x3 + M0` must be singular: its determinant (degree 24, 8 spurious roots
//! +-i) has every solution's x3 among its roots. They are the eigenvalues of a 24 x 24 companion
//! matrix. For each real one, the null vector of M(x3) gives theta4 and theta5, the top of the QR
//! gives theta1 and theta2, and the rest of the loop gives theta6. Each candidate is then polished
//! by Newton's method on the whole arm and kept only if forward kinematics meets the target to
//! [`FK_CHECK`]; duplicates go. A shift of theta3 by a fixed angle keeps x3 finite when a
//! solution has theta3 = pi. Where an order of the loop is degenerate for a special arm (Q loses
//! rank, the eliminant is singular, or a root's null vector is not unique), the loop is turned
//! by one joint (`A2 ... A6 G^-1 A1 = I`, the link after joint 6 becoming `L6 G^-1`) and solved
//! again, up to six orders; only when all fail does the solver say so.

use super::chain::Row;
use super::posture::Posture;
use crate::kinematics::pose::Pose;
use nalgebra::{Matrix3, Matrix6, SMatrix, Vector3, Vector6};

/// Number of Raghavan-Roth equations.
const NEQ: usize = 14;
/// sin(2 pi / 3).
const S120: f64 = 0.866_025_403_784_438_6;
/// The sample angles 0, 2 pi/3, 4 pi/3 as (cos, sin).
const SAMPLES: [(f64, f64); 3] = [(1.0, 0.0), (-0.5, S120), (-0.5, -S120)];
/// Most real solutions of a six-revolute arm.
pub(super) const MAX_BRANCHES: usize = 16;
/// A polished candidate is a solution when forward kinematics meets the target to this (m,
/// relative to the arm's size, and rad).
pub(super) const FK_CHECK: f64 = 1e-12;
/// Columns of the augmented matrix: Q (8), then P's coefficients of 1, c3, s3 (9 each).
const COLS: usize = 8 + 27;
/// Shifts of theta3 tried in turn when the leading matrix is singular (a solution at
/// theta3 = pi, or a special arm).
const SHIFTS: [f64; 4] = [0.0, 0.713, -1.931, 2.417];

/// One solution before offsets: the six theta.
pub(super) type Theta6 = [f64; 6];

/// The constant part of one link: `A_i = Rz(theta_i) L_i`, L a rotation and a translation. For
/// a DH row (2.52), `L = Tz(d) Tx(a) Rx(alpha)`; a locked joint merges its neighbours' into one.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Link {
    /// Rotation of L.
    pub r: Matrix3<f64>,
    /// Translation of L (m).
    pub t: Vector3<f64>,
}

impl Link {
    /// The link of a standard DH row: `Tz(d) Tx(a) Rx(alpha)`.
    pub(crate) fn dh(a: f64, d: f64, sa: f64, ca: f64) -> Self {
        Link {
            r: Matrix3::new(1.0, 0.0, 0.0, 0.0, ca, -sa, 0.0, sa, ca),
            t: Vector3::new(a, 0.0, d),
        }
    }

    /// `Rz(theta)` for (cos, sin) of theta.
    pub(crate) fn rz(c: f64, s: f64) -> Self {
        Link {
            r: Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0),
            t: Vector3::zeros(),
        }
    }

    const IDENTITY: Link = Link {
        r: Matrix3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0),
        t: Vector3::new(0.0, 0.0, 0.0),
    };

    /// The inverse transform.
    pub(crate) fn inverse(&self) -> Link {
        Link {
            r: self.r.transpose(),
            t: -self.r.tr_mul(&self.t),
        }
    }

    /// `self * other`.
    pub(crate) fn then(&self, other: &Link) -> Link {
        Link {
            r: self.r * other.r,
            t: self.t + self.r * other.t,
        }
    }

    fn scaled(&self, k: f64) -> Link {
        Link {
            r: self.r,
            t: self.t * k,
        }
    }

    /// `A = Rz(theta) L` for (cos, sin) of theta: rotation and translation.
    #[inline]
    fn at(&self, c: f64, s: f64) -> (Matrix3<f64>, Vector3<f64>) {
        let rz = Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0);
        (rz * self.r, rz * self.t)
    }
}

/// The elimination of one arm: its links, found once.
#[derive(Debug, Clone)]
pub(super) struct General6 {
    /// The links as given (m).
    links: [Link; 6],
    /// Length unit inside the elimination (m).
    scale: f64,
    /// The order of the loop solved first (0 to 5, see [`Problem::rotated`]).
    first: usize,
}

/// Why the elimination cannot solve a pose (a special arm or pose: the solver says so rather
/// than return a partial set).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Degenerate {
    /// In every order of the loop, theta1 and theta2 cannot be eliminated, or the eliminant is
    /// singular, or its null vectors are not unique.
    Special,
}

impl Degenerate {
    /// A sentence saying why.
    pub(super) fn text(self) -> &'static str {
        match self {
            Degenerate::Special => {
                "in every order of the loop the eliminant is singular or its roots ambiguous (a \
                 special arm this method does not cover)"
            }
        }
    }
}

/// One order of the loop `Rz(t1) L1 ... Rz(t6) L6 = G`, lengths in the elimination's unit:
/// `perm[i]` is the joint whose angle is t(i+1).
#[derive(Debug, Clone, Copy)]
struct Problem {
    links: [Link; 6],
    goal: Link,
    perm: [usize; 6],
}

impl Problem {
    /// The loop turned by one joint: `A2 ... A6 G^-1 Rz(t1) = L1^-1`.
    fn rotated(&self) -> Problem {
        let l = &self.links;
        Problem {
            links: [
                l[1],
                l[2],
                l[3],
                l[4],
                l[5].then(&self.goal.inverse()),
                Link::IDENTITY,
            ],
            goal: l[0].inverse(),
            perm: [
                self.perm[1],
                self.perm[2],
                self.perm[3],
                self.perm[4],
                self.perm[5],
                self.perm[0],
            ],
        }
    }
}

/// The 14 quantities of Raghavan and Roth for the point p and direction l.
#[inline]
fn equations(p: &Vector3<f64>, l: &Vector3<f64>) -> [f64; NEQ] {
    let pp = p.dot(p);
    let pl = p.dot(l);
    let c = p.cross(l);
    let v = l * pp - p * (2.0 * pl);
    [
        p.x, p.y, p.z, l.x, l.y, l.z, pp, pl, c.x, c.y, c.z, v.x, v.y, v.z,
    ]
}

/// The coefficients (1, cos, sin) of `f = a + b cos + c sin` from its values at the
/// [`SAMPLES`].
#[inline]
fn fit3(f0: f64, f1: f64, f2: f64) -> [f64; 3] {
    [
        (f0 + f1 + f2) / 3.0,
        (2.0 * f0 - f1 - f2) / 3.0,
        (f1 - f2) * S120 * (2.0 / 3.0),
    ]
}

/// (1, cos, sin) of an angle.
#[inline]
fn basis(theta: f64) -> [f64; 3] {
    let (s, c) = theta.sin_cos();
    [1.0, c, s]
}

/// The left side's coefficients: `lhs[i3][k][m45]` multiplies `b(t3)[i3] * v45[m45]` in
/// equation k, with b = (1, cos, sin) and `v45[3 i + j] = b(t4)[i] b(t5)[j]`.
type Lhs = [[[f64; 9]; NEQ]; 3];

impl General6 {
    /// The elimination for six revolute rows; `None` if a row is prismatic or the left side is
    /// not of degree 1 (which the theory excludes; checked, not assumed).
    pub(super) fn detect(rows: &[Row]) -> Option<Self> {
        if rows.len() != 6 || rows.iter().any(|r| !r.revolute) {
            return None;
        }
        let links = std::array::from_fn(|i| Link::dh(rows[i].a, rows[i].d, rows[i].sa, rows[i].ca));
        let g = Self::from_links(links);
        let p = g.problem(&Link::IDENTITY);
        let lhs = fit_left(&p);
        degree_one(&p, &lhs).then_some(g)
    }

    /// The elimination for six links `A_i = Rz(theta_i) L_i` (m).
    pub(crate) fn from_links(links: [Link; 6]) -> Self {
        let scale = links.iter().map(|l| l.t.norm()).sum::<f64>().max(1e-9) / 6.0;
        General6 {
            links,
            scale,
            first: 0,
        }
    }

    /// The same elimination, solving order `first` of the loop first (the others follow where
    /// it is degenerate or not sound): [`Self::sound_order`] found once for an arm solved many
    /// times skips the orders its structure makes degenerate (on the Kinova Gen3 with q3 locked,
    /// orders 0, 2, 3 and 4 at every pose: 10 us each to find out).
    pub(crate) fn starting_at(self, first: usize) -> Self {
        General6 {
            first: first % 6,
            ..self
        }
    }

    /// The first order of the loop that is sound for the goal `A1 ... A6 = goal`, if any.
    pub(crate) fn sound_order(&self, goal: &Link) -> Option<usize> {
        let mut p = self.problem(goal);
        let mut out = [[0.0; 6]; MAX_BRANCHES];
        (0..6).find(|_| {
            let mut n = 0;
            let sound = self.solve_order(&p, goal, &mut out, &mut n) == Some(true);
            p = p.rotated();
            sound
        })
    }

    fn problem(&self, goal: &Link) -> Problem {
        let k = 1.0 / self.scale;
        Problem {
            links: self.links.map(|l| l.scaled(k)),
            goal: goal.scaled(k),
            perm: [0, 1, 2, 3, 4, 5],
        }
    }

    /// Every real solution for the pose `t` of frame 6 in frame 0 (theta values, offsets
    /// included), polished and checked, without duplicates, sorted by (theta1, ..., theta6)
    /// wrapped into (-pi, pi]; the count.
    pub(super) fn solve(
        &self,
        t: &Pose,
        out: &mut [Theta6; MAX_BRANCHES],
    ) -> Result<usize, Degenerate> {
        let goal = Link {
            r: *t.rotation.matrix(),
            t: t.translation.vector,
        };
        self.solve_goal(&goal, out)
    }

    /// [`Self::solve`] for the goal `A1 ... A6 = goal` given as a link.
    pub(super) fn solve_goal(
        &self,
        goal: &Link,
        out: &mut [Theta6; MAX_BRANCHES],
    ) -> Result<usize, Degenerate> {
        let mut p = self.problem(goal);
        for _ in 0..self.first {
            p = p.rotated();
        }
        let (mut n, mut solved) = (0, false);
        // A sound order has every solution; where the eliminant is not sound (a special arm),
        // the solutions of every order that solves are joined.
        for _ in 0..6 {
            match self.solve_order(&p, goal, out, &mut n) {
                Some(true) => {
                    solved = true;
                    break;
                }
                Some(false) => solved = true,
                None => {}
            }
            p = p.rotated();
        }
        if !solved {
            return Err(Degenerate::Special);
        }
        out[..n].sort_by(|a, b| {
            let key = |q: &Theta6| q.map(crate::kinematics::orientation::wrap_angle);
            key(a)
                .partial_cmp(&key(b))
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        Ok(n)
    }

    /// The solutions in one order of the loop, added to `out[..n]` (duplicates skipped); whether
    /// the eliminant was sound, or `None` where this order is degenerate.
    fn solve_order(
        &self,
        p: &Problem,
        goal: &Link,
        out: &mut [Theta6; MAX_BRANCHES],
        n: &mut usize,
    ) -> Option<bool> {
        let lhs = fit_left(p);
        let aug = eliminate(p, &lhs)?;
        for &shift in &SHIFTS {
            let Some((roots, healthy, pen)) = roots(&aug, shift) else {
                continue;
            };
            let mut found = [[0.0; 6]; MAX_BRANCHES];
            let (mut m, mut sound) = (0, healthy);
            for &(x, clear) in roots.iter().flatten() {
                let polished = candidate(p, &aug, &pen, x, shift).and_then(|c| {
                    let mut q = [0.0; 6];
                    for (i, j) in p.perm.iter().enumerate() {
                        q[*j] = c[i];
                    }
                    self.polish(q, goal)
                });
                match polished {
                    Some(q) if !found[..m].iter().any(|o| same(o, &q)) && m < MAX_BRANCHES => {
                        found[m] = q;
                        m += 1;
                    }
                    // A clearly real root that gives no new solution: this order cannot be
                    // trusted to have them all (an ill-conditioned eliminant).
                    _ if clear => sound = false,
                    _ => {}
                }
            }
            for q in &found[..m] {
                if !out[..*n].iter().any(|o| same(o, q)) && *n < MAX_BRANCHES {
                    out[*n] = *q;
                    *n += 1;
                }
            }
            return Some(sound);
        }
        None
    }

    /// Newton's method on the whole arm from `q` (a few steps; the candidates are already
    /// close); the polished q if forward kinematics then meets `goal` to [`FK_CHECK`].
    fn polish(&self, mut q: Theta6, goal: &Link) -> Option<Theta6> {
        let tol = FK_CHECK * self.scale.max(1.0);
        for _ in 0..20 {
            let (e, j, aligned) = self.error_and_jacobian(&q, goal);
            if e.fixed_rows::<3>(0).norm() <= tol * 0.1
                && e.fixed_rows::<3>(3).norm() <= 1e-13
                && aligned
            {
                return Some(q);
            }
            let step = j.lu().solve(&e)?;
            // A candidate from an ill-conditioned root may start far: steps are clamped.
            let k = (0.5 / step.amax()).min(1.0);
            for (v, d) in q.iter_mut().zip(step.iter()) {
                *v += d * k;
            }
        }
        let (e, _, aligned) = self.error_and_jacobian(&q, goal);
        (e.fixed_rows::<3>(0).norm() <= tol && e.fixed_rows::<3>(3).norm() <= FK_CHECK && aligned)
            .then_some(q)
    }

    /// The pose error (position, then orientation as in (3.84): half the sum of the cross
    /// products of the axes), the geometric Jacobian (3.30) in frame 0, lengths in m, and whether
    /// the axes point within 90 degrees of the goal's (the orientation error also vanishes at a
    /// half turn).
    fn error_and_jacobian(&self, q: &Theta6, goal: &Link) -> (Vector6<f64>, Matrix6<f64>, bool) {
        let mut r = Matrix3::identity();
        let mut p = Vector3::zeros();
        let mut z = [Vector3::zeros(); 6];
        let mut o = [Vector3::zeros(); 6];
        for (i, link) in self.links.iter().enumerate() {
            z[i] = r.column(2).into_owned();
            o[i] = p;
            let (s, c) = q[i].sin_cos();
            let (ri, pi) = link.at(c, s);
            p += r * pi;
            r *= ri;
        }
        let mut j = Matrix6::zeros();
        for i in 0..6 {
            let lin = z[i].cross(&(p - o[i]));
            j.fixed_view_mut::<3, 1>(0, i).copy_from(&lin);
            j.fixed_view_mut::<3, 1>(3, i).copy_from(&z[i]);
        }
        let ep = goal.t - p;
        let mut eo = Vector3::zeros();
        let mut aligned = true;
        for c in 0..3 {
            eo += r.column(c).cross(&goal.r.column(c));
            aligned &= r.column(c).dot(&goal.r.column(c)) > 0.0;
        }
        let mut e = Vector6::zeros();
        e.fixed_rows_mut::<3>(0).copy_from(&ep);
        e.fixed_rows_mut::<3>(3).copy_from(&(eo * 0.5));
        (e, j, aligned)
    }
}

/// The left side `A3 A4 A5` applied to the origin and z axis of frame 5: the 14 quantities at
/// (t3, t4, t5) = (cos, sin) pairs.
#[inline]
fn left(p: &Problem, a: (f64, f64), b: (f64, f64), c: (f64, f64)) -> [f64; NEQ] {
    let (r3, p3) = p.links[2].at(a.0, a.1);
    let (r4, p4) = p.links[3].at(b.0, b.1);
    let (r5, p5) = p.links[4].at(c.0, c.1);
    let r34 = r3 * r4;
    let pos = p3 + r3 * p4 + r34 * p5;
    let z = r34 * r5.column(2);
    equations(&pos, &z)
}

/// The left side's coefficients from its values at the 27 sample triples.
fn fit_left(p: &Problem) -> Lhs {
    let mut vals = [[[[0.0; NEQ]; 3]; 3]; 3];
    for (i3, a) in vals.iter_mut().enumerate() {
        for (i4, b) in a.iter_mut().enumerate() {
            for (i5, c) in b.iter_mut().enumerate() {
                *c = left(p, SAMPLES[i3], SAMPLES[i4], SAMPLES[i5]);
            }
        }
    }
    let mut lhs = [[[0.0; 9]; NEQ]; 3];
    for k in 0..NEQ {
        // Fit along t5, then t4, then t3.
        let mut c5 = [[[0.0; 3]; 3]; 3];
        for i3 in 0..3 {
            for i4 in 0..3 {
                let v = &vals[i3][i4];
                c5[i3][i4] = fit3(v[0][k], v[1][k], v[2][k]);
            }
        }
        for j4 in 0..3 {
            for j5 in 0..3 {
                let mut c4 = [[0.0; 3]; 3];
                for i3 in 0..3 {
                    c4[i3] = fit3(c5[i3][0][j5], c5[i3][1][j5], c5[i3][2][j5]);
                }
                let f = fit3(c4[0][j4], c4[1][j4], c4[2][j4]);
                for (j3, v) in f.iter().enumerate() {
                    lhs[j3][k][3 * j4 + j5] = *v;
                }
            }
        }
    }
    lhs
}

/// Whether the fitted left side equals the direct one at angles off the samples.
fn degree_one(p: &Problem, lhs: &Lhs) -> bool {
    [[0.3, -1.2, 2.2], [2.9, 0.4, -0.8], [-2.0, 1.7, 0.1]]
        .iter()
        .all(|t: &[f64; 3]| {
            let cs = |a: f64| (a.cos(), a.sin());
            let direct = left(p, cs(t[0]), cs(t[1]), cs(t[2]));
            let (b3, b4, b5) = (basis(t[0]), basis(t[1]), basis(t[2]));
            direct.iter().enumerate().all(|(k, d)| {
                let mut f = 0.0;
                for (i3, b) in b3.iter().enumerate() {
                    for i4 in 0..3 {
                        for i5 in 0..3 {
                            f += b * b4[i4] * b5[i5] * lhs[i3][k][3 * i4 + i5];
                        }
                    }
                }
                (f - d).abs() <= 1e-9 * (1.0 + d.abs())
            })
        })
}

/// The right side's coefficients: `g[k][3 j1 + j2]` multiplies `b(t1)[j1] b(t2)[j2]`, from
/// `A2^-1 A1^-1 G` applied to frame 5's origin and z axis (which do not depend on t6).
fn fit_right(p: &Problem) -> [[f64; 9]; NEQ] {
    let l6 = &p.links[5];
    let o5_in_6 = -l6.r.tr_mul(&l6.t);
    let z5_in_6: Vector3<f64> = l6.r.row(2).transpose();
    let pt = p.goal.t + p.goal.r * o5_in_6;
    let lt = p.goal.r * z5_in_6;
    let mut vals = [[[0.0; NEQ]; 3]; 3];
    for (i1, row) in vals.iter_mut().enumerate() {
        let (r1, p1) = p.links[0].at(SAMPLES[i1].0, SAMPLES[i1].1);
        let u1 = r1.tr_mul(&(pt - p1));
        let w1 = r1.tr_mul(&lt);
        for (i2, v) in row.iter_mut().enumerate() {
            let (r2, p2) = p.links[1].at(SAMPLES[i2].0, SAMPLES[i2].1);
            *v = equations(&r2.tr_mul(&(u1 - p2)), &r2.tr_mul(&w1));
        }
    }
    let mut g = [[0.0; 9]; NEQ];
    for (k, gk) in g.iter_mut().enumerate() {
        let mut c2 = [[0.0; 3]; 3];
        for i1 in 0..3 {
            c2[i1] = fit3(vals[i1][0][k], vals[i1][1][k], vals[i1][2][k]);
        }
        for j2 in 0..3 {
            let f = fit3(c2[0][j2], c2[1][j2], c2[2][j2]);
            for j1 in 0..3 {
                gk[3 * j1 + j2] = f[j1];
            }
        }
    }
    g
}

/// The augmented matrix `[Q | P0 Pc Ps]` after the Householder QR of Q: rows 0..8 hold R and
/// the top of `H P`, rows 8..14 the six equations free of t1 and t2; `None` if Q's columns are
/// dependent.
// The Householder steps index rows and columns of one fixed-size array: plain ranges read best.
#[allow(clippy::needless_range_loop)]
fn eliminate(p: &Problem, lhs: &Lhs) -> Option<[[f64; COLS]; NEQ]> {
    let g = fit_right(p);
    let mut m = [[0.0; COLS]; NEQ];
    for k in 0..NEQ {
        m[k][..8].copy_from_slice(&g[k][1..]);
        for i3 in 0..3 {
            m[k][8 + 9 * i3..17 + 9 * i3].copy_from_slice(&lhs[i3][k]);
        }
        // The right side's constant moves to the left: P v45 = Q v12 with Q v12 its
        // non-constant part.
        m[k][8] -= g[k][0];
    }
    let mut biggest: f64 = 0.0;
    for j in 0..8 {
        let norm = (j..NEQ).map(|i| m[i][j] * m[i][j]).sum::<f64>().sqrt();
        biggest = biggest.max(norm);
        if norm <= 1e-8 * biggest.max(1.0) {
            return None;
        }
        let alpha = if m[j][j] > 0.0 { -norm } else { norm };
        let mut v = [0.0; NEQ];
        v[j] = m[j][j] - alpha;
        v[j + 1..].copy_from_slice(&m_col(&m, j)[j + 1..]);
        let vv = (j..NEQ).map(|i| v[i] * v[i]).sum::<f64>();
        for c in j..COLS {
            let s = (j..NEQ).map(|i| v[i] * m[i][c]).sum::<f64>() * 2.0 / vv;
            for i in j..NEQ {
                m[i][c] -= s * v[i];
            }
        }
    }
    Some(m)
}

fn m_col(m: &[[f64; COLS]; NEQ], j: usize) -> [f64; NEQ] {
    std::array::from_fn(|i| m[i][j])
}

/// The real roots x of `det M(x) = 0` for t3 = 2 atan(x) + shift, the pencil, and whether the eliminant is
/// sound (its 8 roots at +-i are there); `None` when the leading matrix is singular for this
/// shift.
/// A root's real part and whether it is clearly real.
type Root = Option<(f64, bool)>;

fn roots(aug: &[[f64; COLS]; NEQ], shift: f64) -> Option<([Root; 24], bool, Pencil)> {
    let [mm0, mm1, mm2] = pencil(aug, shift);
    let lu = mm2.lu();
    let u = lu.u();
    let (lo, hi) = u
        .diagonal()
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), d| {
            (lo.min(d.abs()), hi.max(d.abs()))
        });
    if lo.is_nan() || lo <= 1e-9 * hi {
        return None;
    }
    let k1 = lu.solve(&mm1)?;
    let k0 = lu.solve(&mm0)?;
    // The companion matrix, row-major as the eigenvalue routine wants it.
    let mut c = [[0.0; 24]; 24];
    for i in 0..12 {
        c[i][12 + i] = 1.0;
        for j in 0..12 {
            c[12 + i][j] = -k0[(i, j)];
            c[12 + i][12 + j] = -k1[(i, j)];
        }
    }
    // Schur's iteration has no cap: never hand it a NaN.
    if c.iter().flatten().any(|v| !v.is_finite()) {
        return None;
    }
    balance(&mut c);
    // Eigenvalues only (no Schur vectors), with a capped iteration: one that cycles on a special
    // arm's companion matrix sends the solver to the next shift or order.
    let eig = super::eigen::eigenvalues(&mut c)?;
    let healthy = healthy(&eig);
    let mut roots = [None; 24];
    for (r, &(re, im)) in roots.iter_mut().zip(eig.iter()) {
        // Loose: a near-double root, or a root of an ill-conditioned eliminant (a nearly special
        // arm), may come out as a complex pair; Newton and the FK check decide.
        let spurious = re.abs() < 1e-3 && (im.abs() - 1.0).abs() < 1e-3;
        if !spurious && im.abs() <= 0.1 * (1.0 + re.abs()) {
            *r = Some((re, im.abs() <= 1e-7 * (1.0 + re.abs())));
        }
    }
    Some((roots, healthy, [mm0, mm1, mm2]))
}

/// Health check: the determinant of a sound eliminant has the factor (1 + x^2)^4 (the
/// half-angle of t3), so 4 eigenvalues at +i and 4 at -i; they come out to 1e-12 and better. A
/// special arm's eliminant may lose them (and real roots with them): then the other orders of
/// the loop are solved too. A nearly special arm (the Kinova Gen3 with a joint locked: offsets
/// of millimetres from an SRS arm) has further complex roots near +-i, a millimetre away: the
/// roots of the special arm's missing solutions, moved off +-i. They are not counted against
/// it, so that check asks for at least 4 at each within 1e-6 (an earlier check, exactly 8 within
/// 1e-3, called these arms unsound at 63 % of poses and solved a second order for nothing).
fn healthy(eig: &[(f64, f64)]) -> bool {
    [1.0, -1.0].iter().all(|&side| {
        eig.iter()
            .filter(|&&(re, im)| re.hypot(im - side) < 1e-6)
            .count()
            >= 4
    })
}

/// Parlett and Reinsch's balancing (powers of 2, so exact): a similarity that makes each row
/// and column of similar size, for accurate eigenvalues of a badly scaled companion matrix.
fn balance(c: &mut [[f64; 24]; 24]) {
    for _ in 0..20 {
        let mut done = true;
        for i in 0..24 {
            let (mut col, mut row) = (0.0, 0.0);
            for (j, r) in c.iter().enumerate() {
                if j != i {
                    col += r[i].abs();
                    row += c[i][j].abs();
                }
            }
            if col == 0.0 || row == 0.0 {
                continue;
            }
            // Column i times f, row i over f: the new sum is col f + row / f.
            let s = col + row;
            let (mut f, mut cc) = (1.0, col);
            while cc < row / 2.0 {
                f *= 2.0;
                cc *= 4.0;
            }
            while cc > row * 2.0 {
                f /= 2.0;
                cc /= 4.0;
            }
            if (cc + row) / f < 0.95 * s {
                done = false;
                for v in c[i].iter_mut() {
                    *v /= f;
                }
                for r in c.iter_mut() {
                    r[i] *= f;
                }
            }
        }
        if done {
            return;
        }
    }
}

/// The pencil `[M0, M1, M2]`.
type Pencil = [SMatrix<f64, 12, 12>; 3];

/// `[M0, M1, M2]` of `M(x) = M2 x^2 + M1 x + M0` for t3 = 2 atan(x) + shift: the six equations
/// and the six multiplied by x4, in the monomials `x4^i x5^j` (column 3 i + j, i < 4, j < 3).
fn pencil(aug: &[[f64; COLS]; NEQ], shift: f64) -> [SMatrix<f64, 12, 12>; 3] {
    let (sf, cf) = shift.sin_cos();
    // (1, cos, sin) of a half-angle tangent, times (1 + x^2): coefficients of x^0, x^1, x^2.
    const HALF: [[f64; 3]; 3] = [[1.0, 0.0, 1.0], [1.0, 0.0, -1.0], [0.0, 2.0, 0.0]];
    let mut mats = [SMatrix::<f64, 12, 12>::zeros(); 3];
    for r in 0..6 {
        let row = &aug[8 + r];
        let mut e = [[0.0; 9]; 3];
        for m in 0..9 {
            let (e0, ec, es) = (row[8 + m], row[17 + m], row[26 + m]);
            // t3 = psi + shift, then (1 + x^2) times: x^2 (E0 - Ec') + x 2 Es' + E0 + Ec'.
            let ec2 = ec * cf + es * sf;
            let es2 = -ec * sf + es * cf;
            e[2][m] = e0 - ec2;
            e[1][m] = 2.0 * es2;
            e[0][m] = e0 + ec2;
        }
        for (mat, ep) in mats.iter_mut().zip(&e) {
            for b4 in 0..3 {
                for b5 in 0..3 {
                    let v = ep[3 * b4 + b5];
                    if v == 0.0 {
                        continue;
                    }
                    for i in 0..3 {
                        for j in 0..3 {
                            let w = v * HALF[b4][i] * HALF[b5][j];
                            mat[(r, 3 * i + j)] += w;
                            mat[(6 + r, 3 * (i + 1) + j)] += w;
                        }
                    }
                }
            }
        }
    }
    mats
}

/// The solution in this order for one root t3: t4, t5 from the null vector of M, t1, t2 from
/// the top of the QR, t6 from the rest of the loop; `None` if the null vector is not unique
/// (then this order of the loop cannot tell the branches apart).
fn candidate(
    p: &Problem,
    aug: &[[f64; COLS]; NEQ],
    [mm0, mm1, mm2]: &Pencil,
    x: f64,
    shift: f64,
) -> Option<Theta6> {
    let t3 = 2.0 * x.atan() + shift;
    // M(x), scaled by 1 / x^2 for a large root (the null vector does not care).
    let m = if x.abs() <= 1.0 {
        mm2 * (x * x) + mm1 * x + mm0
    } else {
        mm2 + mm1 * (1.0 / x) + mm0 * (1.0 / (x * x))
    };
    let v = null_vector(m)?;
    let at = |i: usize, j: usize| v[3 * i + j];
    let mut best = (0.0, 0, 0);
    for i in 0..3 {
        for j in 0..3 {
            let w = at(i, j).powi(2) + at(i + 1, j).powi(2);
            if w > best.0 {
                best = (w, i, j);
            }
        }
    }
    let t4 = 2.0 * at(best.1 + 1, best.2).atan2(at(best.1, best.2));
    let mut best = (0.0, 0, 0);
    for i in 0..4 {
        for j in 0..2 {
            let w = at(i, j).powi(2) + at(i, j + 1).powi(2);
            if w > best.0 {
                best = (w, i, j);
            }
        }
    }
    let t5 = 2.0 * at(best.1, best.2 + 1).atan2(at(best.1, best.2));
    let (b3, b4, b5) = (basis(t3), basis(t4), basis(t5));
    let mut rhs = [0.0; 8];
    for (r, x) in rhs.iter_mut().enumerate() {
        for (i3, b) in b3.iter().enumerate() {
            for i4 in 0..3 {
                for i5 in 0..3 {
                    *x += b * b4[i4] * b5[i5] * aug[r][8 + 9 * i3 + 3 * i4 + i5];
                }
            }
        }
    }
    // R v12 = rhs, R upper triangular; v12[m - 1] is the product number m = 3 j1 + j2.
    let mut v12 = [0.0; 8];
    for r in (0..8).rev() {
        let s = (r + 1..8).map(|c| aug[r][c] * v12[c]).sum::<f64>();
        v12[r] = (rhs[r] - s) / aug[r][r];
    }
    let t1 = v12[5].atan2(v12[2]);
    let t2 = v12[1].atan2(v12[0]);
    // A6 = A5^-1 ... A1^-1 G = Rz(t6) L6: Rz(t6) = (rotation) L6_r^T.
    let mut r = p.goal.r;
    for (link, th) in p.links[..5].iter().zip([t1, t2, t3, t4, t5]) {
        let (s, c) = th.sin_cos();
        let (ri, _) = link.at(c, s);
        r = ri.tr_mul(&r);
    }
    let rz = r * p.links[5].r.transpose();
    let t6 = rz[(1, 0)].atan2(rz[(0, 0)]);
    let q = [t1, t2, t3, t4, t5, t6];
    q.iter().all(|v| v.is_finite()).then_some(q)
}

/// Whether two solutions are the same configuration (every angle within 1e-9 modulo 2 pi).
fn same(a: &Theta6, b: &Theta6) -> bool {
    a.iter()
        .zip(b)
        .all(|(x, y)| crate::kinematics::orientation::wrap_angle(x - y).abs() < 1e-9)
}

/// A null vector of a 12 x 12 matrix of rank 11: by Gaussian elimination with row pivoting
/// where the first 11 columns are clearly independent (the generic case: the elimination runs
/// down contiguous columns), else with complete pivoting.
fn null_vector(m: SMatrix<f64, 12, 12>) -> Option<[f64; 12]> {
    null_vector_rows(&m).or_else(|| null_vector_complete(m))
}

/// [`null_vector`] by row pivoting, the last column left for the null direction; `None` where
/// a pivot of the first 11 columns is below 1e-9 of the largest (then complete pivoting
/// decides).
// Row k of column j is `a[j][k]`: plain index ranges over the fixed-size columns read best.
#[allow(clippy::needless_range_loop)]
fn null_vector_rows(m: &SMatrix<f64, 12, 12>) -> Option<[f64; 12]> {
    let mut a = [[0.0; 12]; 12];
    for (j, col) in a.iter_mut().enumerate() {
        col.copy_from_slice(m.column(j).as_slice());
    }
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for k in 0..11 {
        let mut p = k;
        for i in k + 1..12 {
            if a[k][i].abs() > a[k][p].abs() {
                p = i;
            }
        }
        let pivot = a[k][p];
        lo = lo.min(pivot.abs());
        hi = hi.max(pivot.abs());
        // A NaN pivot fails too.
        if pivot.abs().is_nan() || pivot.abs() <= 1e-9 * hi {
            return None;
        }
        for col in a[k..].iter_mut() {
            col.swap(k, p);
        }
        let mut f = [0.0; 12];
        for i in k + 1..12 {
            f[i] = a[k][i] / pivot;
        }
        let (_, right) = a.split_at_mut(k + 1);
        for col in right.iter_mut() {
            let akj = col[k];
            if akj != 0.0 {
                for i in k + 1..12 {
                    col[i] -= f[i] * akj;
                }
            }
        }
    }
    if lo <= 1e-9 * hi {
        return None;
    }
    // U z = 0 with z[11] = 1: column j of U is a[j], rows 0..11.
    let mut z = [0.0; 12];
    z[11] = 1.0;
    for k in (0..11).rev() {
        let s = (k + 1..12).map(|j| a[j][k] * z[j]).sum::<f64>();
        z[k] = -s / a[k][k];
    }
    z.iter().all(|x| x.is_finite()).then_some(z)
}

/// [`null_vector`] by complete pivoting; `None` where the null space is not one line.
fn null_vector_complete(mut m: SMatrix<f64, 12, 12>) -> Option<[f64; 12]> {
    let mut cols: [usize; 12] = std::array::from_fn(|i| i);
    for k in 0..11 {
        let (mut pi, mut pj, mut best) = (k, k, 0.0);
        for i in k..12 {
            for j in k..12 {
                if m[(i, j)].abs() > best {
                    (pi, pj, best) = (i, j, m[(i, j)].abs());
                }
            }
        }
        if best == 0.0 {
            return None;
        }
        m.swap_rows(k, pi);
        m.swap_columns(k, pj);
        cols.swap(k, pj);
        for i in k + 1..12 {
            let f = m[(i, k)] / m[(k, k)];
            if f != 0.0 {
                for j in k..12 {
                    m[(i, j)] -= f * m[(k, j)];
                }
            }
        }
    }
    // A second tiny pivot: the null space is not one line, this order cannot tell.
    if m[(10, 10)].abs() <= 1e-9 * m[(0, 0)].abs() {
        return None;
    }
    let mut z = [0.0; 12];
    z[11] = 1.0;
    for k in (0..11).rev() {
        let s = (k + 1..12).map(|j| m[(k, j)] * z[j]).sum::<f64>();
        z[k] = -s / m[(k, k)];
    }
    let mut v = [0.0; 12];
    for (k, c) in cols.iter().enumerate() {
        v[*c] = z[k];
    }
    v.iter().all(|x| x.is_finite()).then_some(v)
}

/// The posture of branch `k` (0-based) of a general arm.
pub(super) fn branch_posture(k: usize) -> Posture {
    Posture {
        branch: Some(k as u8 + 1),
        ..Posture::default()
    }
}
