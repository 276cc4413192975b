//! The boundary arcs of the section of an arm whose positioning arm moves in a plane through joint
//! 1's axis (anthropomorphic arm without shoulder offset, alone or with a spherical wrist), and
//! the exact flange workspace they give when a full-range spherical wrist turns the tool in every
//! direction.
//!
//! **Section arcs.** With joint 1 full-range the workspace W of the tracked point (the wrist
//! centre) is the solid of revolution of its section Sigma in the half-plane (r >= 0, z); the
//! part Sigma_c reached with posture class c likewise. The boundary of Sigma_c lies on the images
//! of the edges of the (q2, q3) box and of the elbow's stretched and folded lines, on each of which
//! one joint moves: circular arcs in the arm plane (signed radius rho, z). Each arc is split where
//! it crosses the axis (the shoulder class flips there) and carries the classes of its
//! configurations. From them, in closed form: the radii and heights the section spans, and the
//! smallest and largest distance from the base origin (the reach).
//!
//! **The flange as a Minkowski sum** (the tool point at distance d from the wrist centre, Sect.
//! 2.12.2). A wrist whose joints are full-range and whose consecutive axes are orthogonal reaches
//! every orientation, so the flange reaches p with class c exactly when the sphere S(p, d) meets
//! W_c. A wrist centre at (r, z) turned about the axis lies at every distance from p = (r_p, z_p)
//! in [|(r - r_p, z - z_p)|, |(r + r_p, z - z_p)|], so S(p, d) meets W_c exactly when Sigma_c meets
//! the crescent K(p) = {x : |x - P| <= d <= |x - P'|}, P = (r_p, z_p), P' = (-r_p, z_p). K(p) is
//! connected (for each z its points form one interval of r), so that happens exactly when an arc
//! of class c meets K(p) or K(p) lies inside Sigma_c, which one point of K(p), (r_p + d, z_p),
//! tells. Along an arc the squared distances to P and P' minus d^2 are each
//! A + B cos(theta) + C sin(theta), with closed-form roots, and the arc meets K(p) where their
//! product is <= 0. The radii reached with class c are those of Sigma_c widened by d on both
//! sides (the top view), the heights likewise.

use crate::kinematics::ik::closed_form::{ClosedForm, RawSolutions};
use crate::kinematics::{JointKind, Robot};
use crate::workspace::PostureClassifier;
use nalgebra::{Point3, Vector3};
use std::f64::consts::{PI, TAU};

/// One boundary arc of the section in the arm plane (rho, z) (m): the points
/// `c + r (cos theta, sin theta)` for theta in `th`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Piece {
    c: [f64; 2],
    r: f64,
    /// Angle range about `c` (rad), `th[0] <= th[1] <= th[0] + 2 pi`.
    th: [f64; 2],
    /// Range of |rho| along the arc (m).
    rr: [f64; 2],
    /// Range of z along the arc (m).
    zz: [f64; 2],
    /// Posture classes of the arc's configurations (bits).
    mask: u8,
}

/// The section's boundary arcs (see the module documentation).
#[derive(Debug, Clone)]
pub(super) struct SectionArcs {
    pieces: Vec<Piece>,
}

/// One sweep of a joint with the other fixed: which joint moves (1 or 2, 0-based), the fixed
/// value, the range swept, and whether the fixed value is an elbow fold.
#[derive(Debug, Clone, Copy)]
struct Sweep {
    joint: usize,
    fixed: f64,
    range: [f64; 2],
    fold: bool,
}

/// A joint's range for the sweeps: its limits, or one turn when it covers a full turn.
fn sweep_range(l: [f64; 2]) -> ([f64; 2], bool) {
    if !(l[0].is_finite() && l[1].is_finite()) || l[1] - l[0] >= TAU - 1e-12 {
        ([-PI, PI], true)
    } else {
        (l, false)
    }
}

/// The angle difference a - b wrapped into (-pi, pi].
fn wrapped(a: f64) -> f64 {
    let w = a.rem_euclid(TAU);
    if w > PI { w - TAU } else { w }
}

/// Centre and radius of the circle through three points (`None` when they are collinear, or
/// within `tol` (m) of one point: a joint that does not move the point).
fn circumcircle(a: [f64; 2], b: [f64; 2], c: [f64; 2], tol: f64) -> Option<([f64; 2], f64)> {
    let (bx, by) = (b[0] - a[0], b[1] - a[1]);
    let (cx, cy) = (c[0] - a[0], c[1] - a[1]);
    let det = 2.0 * (bx * cy - by * cx);
    let scale = (bx * bx + by * by).max(cx * cx + cy * cy);
    if scale <= tol * tol || det.abs() <= 1e-12 * scale {
        return None;
    }
    let (b2, c2) = (bx * bx + by * by, cx * cx + cy * cy);
    let ux = (cy * b2 - by * c2) / det;
    let uy = (bx * c2 - cx * b2) / det;
    Some(([a[0] + ux, a[1] + uy], ux.hypot(uy)))
}

/// The positioning arm's tracked point in the arm plane, and the classes of a configuration.
struct Arm<'a> {
    robot: &'a Robot,
    cf: &'a ClosedForm,
    classifier: &'a PostureClassifier,
    /// The tracked point in the tool frame (m).
    point_in_tool: Vector3<f64>,
    /// Horizontal unit direction of the arm plane at q1 = 0 (base frame).
    u: [f64; 2],
}

impl Arm<'_> {
    /// The tracked point in the base frame at q1 = 0 and (q2, q3), the other joints 0.
    fn base_point(&self, q2: f64, q3: f64) -> Option<Vector3<f64>> {
        let mut q = vec![0.0; self.robot.dof()];
        q[1] = q2;
        q[2] = q3;
        let world_from_tool = self.robot.fk(&q).ok()?;
        let p = world_from_tool * Point3::from(self.point_in_tool);
        Some(self.robot.base.inverse_transform_point(&p).coords)
    }

    /// (rho, z) in the arm plane (m).
    fn plane(&self, q2: f64, q3: f64) -> Option<[f64; 2]> {
        let p = self.base_point(q2, q3)?;
        Some([p.x * self.u[0] + p.y * self.u[1], p.z])
    }

    /// Classes of the configuration (0, q2, q3): the posture of the closed-form solution equal
    /// to it.
    fn classes(&self, q2: f64, q3: f64) -> u8 {
        let Some(p) = self.base_point(q2, q3) else {
            return 0;
        };
        let world = self.robot.base * Point3::from(p);
        let mut raw = RawSolutions::default();
        if self.cf.solve_position_raw(&world.coords, &mut raw).is_err() {
            return 0;
        }
        let same = |a: f64, b: f64| wrapped(a - b).abs() < 1e-7;
        (0..raw.len)
            .filter(|&k| same(raw.q[k][0], 0.0) && same(raw.q[k][1], q2) && same(raw.q[k][2], q3))
            .fold(0, |m, k| m | self.classifier.posture_mask(&raw.postures[k]))
    }
}

impl SectionArcs {
    /// The arcs of the section of `robot`'s tracked point (`point_in_tool`, in the tool frame:
    /// the wrist centre of a six-joint arm, the origin of a three-joint one), or `None` when the
    /// positioning arm does not move in a plane through joint 1's axis with revolute joints 2 and 3
    /// and an elbow (then the section's boundary is not made of arcs).
    pub(super) fn new(
        robot: &Robot,
        cf: &ClosedForm,
        classifier: &PostureClassifier,
        point_in_tool: Vector3<f64>,
    ) -> Option<Self> {
        if robot.dof() < 3 || (0..3).any(|k| robot.dof_joint(k).kind != JointKind::Revolute) {
            return None;
        }
        let scale = robot.characteristic_length();
        let mut arm = Arm {
            robot,
            cf,
            classifier,
            point_in_tool,
            u: [1.0, 0.0],
        };
        // The arm plane: every sample's horizontal part along one direction.
        let samples = [
            (0.3, 0.7),
            (1.1, -0.4),
            (-2.0, 2.5),
            (2.9, 1.3),
            (-0.8, -2.2),
        ];
        let pts: Vec<Vector3<f64>> = samples
            .iter()
            .map(|&(a, b)| arm.base_point(a, b))
            .collect::<Option<_>>()?;
        let far = pts
            .iter()
            .max_by(|a, b| a.xy().norm().total_cmp(&b.xy().norm()))?;
        let h = far.xy().norm();
        if h < 1e-9 * scale {
            return None;
        }
        arm.u = [far.x / h, far.y / h];
        if pts
            .iter()
            .any(|p| (p.x * arm.u[1] - p.y * arm.u[0]).abs() > 1e-9 * scale)
        {
            return None;
        }
        let pieces = Self::pieces(&arm, scale)?;
        Some(Self { pieces })
    }

    /// Every arc: the sweeps of the (q2, q3) box's edges and of the elbow folds, split at the
    /// axis and at the folds, each with its classes.
    fn pieces(arm: &Arm, scale: f64) -> Option<Vec<Piece>> {
        let limits = arm.robot.limits();
        let (r2, full2) = sweep_range(limits[1]);
        let (r3, full3) = sweep_range(limits[2]);
        // The elbow folds: q3 where the tracked point is farthest from and nearest to the
        // shoulder (the centre of its circle as q2 turns), |w - S|^2 = A + B cos q3 + C sin q3.
        let shoulder = |q3: f64| -> Option<[f64; 2]> {
            let p = |q2: f64| arm.plane(q2, q3);
            circumcircle(p(0.0)?, p(TAU / 3.0)?, p(2.0 * TAU / 3.0)?, 1e-9 * scale).map(|(c, _)| c)
        };
        // (At a q3 that puts the tracked point on joint 2's axis the circle is a point: the
        // next q3 is tried.)
        let s = [0.0, 1.0, 2.0].into_iter().find_map(shoulder)?;
        let dist2 = |q3: f64| -> Option<f64> {
            let w = arm.plane(0.0, q3)?;
            Some((w[0] - s[0]).powi(2) + (w[1] - s[1]).powi(2))
        };
        let (f0, f1, f2) = (dist2(0.0)?, dist2(0.5 * PI)?, dist2(PI)?);
        let (a, b) = (0.5 * (f0 + f2), 0.5 * (f0 - f2));
        let c = f1 - a;
        if b.hypot(c) < 1e-9 * scale * scale {
            return None;
        }
        let folds: Vec<f64> = [c.atan2(b), c.atan2(b) + PI]
            .into_iter()
            .filter_map(|v| {
                let v = if full3 {
                    wrapped(v)
                } else {
                    r3[0] + (v - r3[0]).rem_euclid(TAU)
                };
                (v >= r3[0] && v <= r3[1]).then_some(v)
            })
            .collect();
        let mut sweeps = Vec::new();
        let mut q3_fixed: Vec<(f64, bool)> = folds.iter().map(|&v| (v, true)).collect();
        if !full3 {
            q3_fixed.extend([(r3[0], false), (r3[1], false)]);
        }
        for (v, fold) in q3_fixed {
            sweeps.push(Sweep {
                joint: 1,
                fixed: v,
                range: r2,
                fold,
            });
        }
        if !full2 {
            for v in r2 {
                sweeps.push(Sweep {
                    joint: 2,
                    fixed: v,
                    range: r3,
                    fold: false,
                });
            }
        }
        let mut out = Vec::new();
        for sw in sweeps {
            let splits = if sw.joint == 2 { folds.as_slice() } else { &[] };
            Self::split(arm, sw, splits, r3, scale, &mut out)?;
        }
        (!out.is_empty() && out.iter().any(|p| p.mask != 0)).then_some(out)
    }

    /// The arcs of one sweep, split where rho changes sign and at `splits` (joint values).
    fn split(
        arm: &Arm,
        sw: Sweep,
        splits: &[f64],
        r3: [f64; 2],
        scale: f64,
        out: &mut Vec<Piece>,
    ) -> Option<()> {
        let at = |q: f64| {
            if sw.joint == 1 {
                arm.plane(q, sw.fixed)
            } else {
                arm.plane(sw.fixed, q)
            }
        };
        let (p0, p1, p2) = (at(0.0)?, at(TAU / 3.0)?, at(2.0 * TAU / 3.0)?);
        // theta(q) = th0 + sense * q about the centre; a point when the joint does not move it.
        let (c, r, th0, sense) = match circumcircle(p0, p1, p2, 1e-9 * scale) {
            Some((c, r)) => {
                let th = |p: [f64; 2]| (p[1] - c[1]).atan2(p[0] - c[0]);
                let sense = wrapped(th(p1) - th(p0)).signum();
                (c, r, th(p0), sense)
            }
            None => (p0, 0.0, 0.0, 1.0),
        };
        let check = at(1.234)?;
        let e = [
            c[0] + r * (th0 + sense * 1.234).cos(),
            c[1] + r * (th0 + sense * 1.234).sin(),
        ];
        if (e[0] - check[0]).hypot(e[1] - check[1]) > 1e-9 * scale {
            return None;
        }
        let [lo, hi] = sw.range;
        let mut cuts = vec![lo, hi];
        cuts.extend(splits.iter().copied().filter(|&v| v > lo && v < hi));
        if r > 0.0 && (c[0] / r).abs() <= 1.0 {
            let alpha = (-c[0] / r).acos();
            for t in [alpha, -alpha] {
                // q = (t - th0) / sense + 2 pi k within (lo, hi)
                let q0 = (t - th0) * sense;
                let k0 = ((lo - q0) / TAU).ceil();
                let mut q = q0 + k0 * TAU;
                while q < hi {
                    if q > lo {
                        cuts.push(q);
                    }
                    q += TAU;
                }
            }
        }
        cuts.sort_by(f64::total_cmp);
        cuts.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
        for w in cuts.windows(2) {
            let (a, b) = (w[0], w[1]);
            if b - a < 1e-12 {
                continue;
            }
            let (ta, tb) = (th0 + sense * a, th0 + sense * b);
            let th = if ta <= tb { [ta, tb] } else { [tb, ta] };
            out.push(Piece::new(
                c,
                r,
                th,
                Self::sweep_classes(arm, sw, [a, b], r3),
            ));
        }
        Some(())
    }

    /// Classes of the configurations of a sweep's joint values `[a, b]` (constant between the
    /// cuts): those at three inner points; a fold borders the classes on either side of it that
    /// the limits of joint 3 allow.
    fn sweep_classes(arm: &Arm, sw: Sweep, [a, b]: [f64; 2], r3: [f64; 2]) -> u8 {
        let mut mask = 0;
        for f in [0.25, 0.5, 0.75] {
            let q = a + f * (b - a);
            let (q2, q3) = if sw.joint == 1 {
                (q, sw.fixed)
            } else {
                (sw.fixed, q)
            };
            if sw.fold {
                for dv in [-1e-4, 1e-4] {
                    let v = q3 + dv;
                    if (r3[1] - r3[0] >= TAU - 1e-9) || (v >= r3[0] && v <= r3[1]) {
                        mask |= arm.classes(q2, v);
                    }
                }
            } else {
                mask |= arm.classes(q2, q3);
            }
        }
        mask
    }

    /// The largest |rho| of the section and the range of its heights (m).
    pub(super) fn extent(&self) -> [f64; 3] {
        self.pieces
            .iter()
            .fold([0.0, f64::INFINITY, f64::NEG_INFINITY], |[r, lo, hi], p| {
                [r.max(p.rr[1]), lo.min(p.zz[0]), hi.max(p.zz[1])]
            })
    }

    /// Smallest and largest distance (m) from the point (rho, z) = `o` to the arcs.
    pub(super) fn distance_range(&self, o: [f64; 2]) -> [f64; 2] {
        self.pieces
            .iter()
            .fold([f64::INFINITY, 0.0], |[lo, hi], p| {
                let [a, b] = p.distance_range(o);
                [lo.min(a), hi.max(b)]
            })
    }

    /// Classes reaching radius `r` (m) when the section is widened by `d` (m) on both sides: the
    /// top view of the section turned about the axis, grown by the sphere of radius d.
    pub(super) fn radius_mask(&self, r: f64, d: f64) -> u8 {
        self.pieces
            .iter()
            .filter(|p| r >= (p.rr[0] - d).max(0.0) && r <= p.rr[1] + d)
            .fold(0, |m, p| m | p.mask)
    }

    /// Classes c whose section Sigma_c meets the crescent K(p) of the point (r_p, z_p) and
    /// radius `d` (see the module documentation), given `inside`, the classes of the section at
    /// (r_p + d, z_p). Allocation-free.
    pub(super) fn sphere_mask(&self, rp: f64, zp: f64, d: f64, inside: u8, all: u8) -> u8 {
        let mut m = inside;
        let d2 = d * d;
        for p in &self.pieces {
            if m & p.mask == p.mask {
                if m == all {
                    break;
                }
                continue;
            }
            if p.zz[0] > zp + d || p.zz[1] < zp - d || p.rr[0] > rp + d {
                continue;
            }
            if p.meets(rp, zp, d2) {
                m |= p.mask;
            }
        }
        m
    }
}

impl Piece {
    fn new(c: [f64; 2], r: f64, th: [f64; 2], mask: u8) -> Self {
        let mut rho = [c[0] + r * th[0].cos(), c[0] + r * th[1].cos()];
        let mut z = [c[1] + r * th[0].sin(), c[1] + r * th[1].sin()];
        let inside = |t: f64| angle_in(t, th);
        let (mut rlo, mut rhi) = (rho[0].min(rho[1]), rho[0].max(rho[1]));
        if inside(0.0) {
            rhi = rhi.max(c[0] + r);
        }
        if inside(PI) {
            rlo = rlo.min(c[0] - r);
        }
        rho = if rlo >= 0.0 {
            [rlo, rhi]
        } else if rhi <= 0.0 {
            [-rhi, -rlo]
        } else {
            [0.0, rhi.max(-rlo)]
        };
        let (mut zlo, mut zhi) = (z[0].min(z[1]), z[0].max(z[1]));
        if inside(0.5 * PI) {
            zhi = zhi.max(c[1] + r);
        }
        if inside(-0.5 * PI) {
            zlo = zlo.min(c[1] - r);
        }
        z = [zlo, zhi];
        Self {
            c,
            r,
            th,
            rr: rho,
            zz: z,
            mask,
        }
    }

    /// Whether the arc meets the crescent of (rp, zp) and squared radius d2: some theta with
    /// (|x - P|^2 - d^2) (|x - P'|^2 - d^2) <= 0.
    #[inline]
    fn meets(&self, rp: f64, zp: f64, d2: f64) -> bool {
        let g = |qx: f64| {
            let (dx, dz) = (self.c[0] - qx, self.c[1] - zp);
            (
                dx * dx + dz * dz + self.r * self.r - d2,
                2.0 * self.r * dx,
                2.0 * self.r * dz,
            )
        };
        let (g1, g2) = (g(rp), g(-rp));
        if self.r == 0.0 {
            return g1.0 * g2.0 <= 0.0;
        }
        if root_in(g1, self.th) || root_in(g2, self.th) {
            return true;
        }
        let t = 0.5 * (self.th[0] + self.th[1]);
        let (s, c) = t.sin_cos();
        (g1.0 + g1.1 * c + g1.2 * s) * (g2.0 + g2.1 * c + g2.2 * s) <= 0.0
    }

    /// Smallest and largest distance (m) from `o` to the arc.
    fn distance_range(&self, o: [f64; 2]) -> [f64; 2] {
        let at = |t: f64| {
            let (s, c) = t.sin_cos();
            (self.c[0] + self.r * c - o[0]).hypot(self.c[1] + self.r * s - o[1])
        };
        let ends = [at(self.th[0]), at(self.th[1])];
        let (mut lo, mut hi) = (ends[0].min(ends[1]), ends[0].max(ends[1]));
        if self.r > 0.0 {
            let toward = (o[1] - self.c[1]).atan2(o[0] - self.c[0]);
            if angle_in(toward, self.th) {
                lo = lo.min(at(toward));
            }
            if angle_in(toward + PI, self.th) {
                hi = hi.max(at(toward + PI));
            }
        }
        [lo, hi]
    }
}

/// Whether the angle t (rad, modulo 2 pi) lies in `th`.
#[inline]
fn angle_in(t: f64, th: [f64; 2]) -> bool {
    let t = t + ((th[0] - t) / TAU).ceil() * TAU;
    t <= th[1] + 1e-12
}

/// Whether A + B cos(theta) + C sin(theta) has a root with theta in `th`.
#[inline]
fn root_in((a, b, c): (f64, f64, f64), th: [f64; 2]) -> bool {
    let m = b.hypot(c);
    if a.abs() > m {
        return false;
    }
    if m == 0.0 {
        return true;
    }
    let phi = c.atan2(b);
    let alpha = (-a / m).acos();
    angle_in(phi + alpha, th) || angle_in(phi - alpha, th)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roots_and_angles() {
        // cos(theta) - 0.5 = 0 at +-60 degrees
        assert!(root_in((-0.5, 1.0, 0.0), [0.0, 1.1]));
        assert!(!root_in((-0.5, 1.0, 0.0), [1.1, 5.0]));
        assert!(root_in((-0.5, 1.0, 0.0), [5.0, 5.5]));
        assert!(angle_in(-0.1, [6.0, 6.3]));
        assert!(!angle_in(0.1, [6.0, 6.3]));
        let (c, r) = circumcircle([1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], 1e-9).unwrap();
        assert!(circumcircle([1e-17, 0.0], [0.0, 2e-17], [-1e-17, 0.0], 1e-9).is_none());
        assert!(c[0].abs() < 1e-15 && c[1].abs() < 1e-15 && (r - 1.0).abs() < 1e-15);
    }

    #[test]
    fn crescent_of_a_point_arc() {
        // A point arc at (1, 0): the crescent of p = (1, 0.5) with d = 0.5 holds it (|x - P| =
        // 0.5 = d <= |x - P'|); with d = 0.4 it does not.
        let p = Piece::new([1.0, 0.0], 0.0, [0.0, 0.0], 1);
        assert!(p.meets(1.0, 0.5, 0.25));
        assert!(!p.meets(1.0, 0.5, 0.16));
    }
}
