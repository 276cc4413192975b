//! The exact workspace boundary of two- and three-link planar arms (Sect. 2.10.1, Example 2.6,
//! Figs 2.29-2.30), in plane coordinates ([`PlanarFrame`], m).
//!
//! The boundary of the image of the joint-limit box lies on the images of (i) the edges of the
//! box (a loss of mobility at a joint limit) and (ii) the configurations where the position map
//! restricted to the interior or to a face of the box loses rank (a kinematic singularity, e.g.
//! the aligned links q2 = 0 of segment ad in Fig. 2.29). On every such curve exactly one joint
//! moves, so each image is an arc of a circle about that joint's axis. For a planar chain the rank
//! test of two columns i < j of the position Jacobian, `(p - p_i) x (p - p_j)` (z component),
//! does not depend on the joints up to i, which is why the singular values can be found by a
//! one-dimensional root search ([`planar_boundary`]).
//!
//! For the two-link arm the joint-space rectangle is split at the singular values of q2 into
//! bands of constant posture; the image of a band's perimeter is a closed curve (ABCDA for the
//! elbow-down band q2 in [0, q2M] of Fig. 2.30, EADFE for the elbow-up band) that bounds the
//! region reached with that posture, because the map is one-to-one on a band whose q1 span is at
//! most 2 pi.

use super::posture::PostureClassifier;
use super::rectangle::{JointRectangle, joint_rectangle};
use super::{Aabb, PlanarFrame, WorkspaceError, planar_frame};
use crate::kinematics::ik::closed_form::{ClosedForm, Family};
use crate::kinematics::{Pose, Robot};
use nalgebra::{Matrix6xX, Rotation3, Vector3};
use std::f64::consts::{PI, TAU};

/// Polyline resolution of [`planar_boundary`].
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BoundaryOptions {
    /// Largest change of the moving joint between polyline vertices (rad). The chord error of an
    /// arc of radius r is about `r * step^2 / 8`.
    pub step: f64,
}

impl Default for BoundaryOptions {
    /// 0.25 degree (chord error 4.8e-6 m at a radius of 2 m).
    fn default() -> Self {
        Self {
            step: 0.25_f64.to_radians(),
        }
    }
}

/// Why the arm loses mobility along a boundary curve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum CurveKind {
    /// Every fixed joint is at one of its limits.
    JointLimit,
    /// A fixed joint sits at a singular value (aligned or folded links), e.g. q2 = 0 (segment ad
    /// of Fig. 2.29, arc DA of Fig. 2.30).
    Singular,
}

/// One boundary candidate: the image of a joint-space segment along which one joint moves.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundaryCurve {
    /// Short label: Fig. 2.30's arc names ("AB", "BC", ...) for a two-link arm, "E1", "F1", "S1"
    /// (edge, face fold, interior singularity) for a three-link arm.
    pub label: String,
    /// What the curve is, in words, with the fixed joint values.
    pub description: String,
    /// Joint limit or singularity.
    pub kind: CurveKind,
    /// Index of the joint that moves along the curve.
    pub moving_joint: usize,
    /// Joint vector at the start (rad).
    pub q_start: Vec<f64>,
    /// Joint vector at the end (rad).
    pub q_end: Vec<f64>,
    /// The image in plane coordinates (m), from `q_start` to `q_end`.
    pub points: Vec<[f64; 2]>,
}

/// The closed image of the perimeter of one posture band of a two-link arm (plane coordinates,
/// m): the region inside is reached with that posture.
#[derive(Debug, Clone, PartialEq)]
pub struct PostureLoop {
    /// Posture class (index into [`PlanarBoundary::class_names`]).
    pub class: u8,
    /// The corners in order, e.g. "ABCDA" (elbow down in Fig. 2.30).
    pub label: String,
    /// The q2 range of the band (rad).
    pub q2: [f64; 2],
    /// Vertices; the polygon closes from the last back to the first.
    pub points: Vec<[f64; 2]>,
}

/// The exact boundary data of a planar arm.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanarBoundary {
    /// The arm's plane.
    pub frame: PlanarFrame,
    /// Names of the posture classes.
    pub class_names: Vec<String>,
    /// Every boundary candidate (the workspace boundary is a subset of their union).
    pub curves: Vec<BoundaryCurve>,
    /// Closed loops per posture band (two-link arms only; empty for three links).
    pub loops: Vec<PostureLoop>,
    /// The joint-space rectangle (two-link arms only).
    pub rectangle: Option<JointRectangle>,
}

impl PlanarBoundary {
    /// Bounding box of the curves in plane coordinates (m; z = 0).
    pub fn bounds(&self) -> Aabb {
        let mut b = Aabb::EMPTY;
        for p in self.curves.iter().flat_map(|c| &c.points) {
            b.extend([p[0], p[1], 0.0]);
        }
        b
    }

    /// Smallest and largest distance (m) from the base origin over the curves' points (3D, the
    /// plane's z included). The largest is the maximum reach; the smallest is the minimum reach
    /// unless the base origin itself is reachable.
    pub fn curve_reach(&self) -> [f64; 2] {
        let z2 = self.frame.z * self.frame.z;
        self.curves
            .iter()
            .flat_map(|c| &c.points)
            .fold([f64::INFINITY, 0.0], |[lo, hi], p| {
                let d = (p[0] * p[0] + p[1] * p[1] + z2).sqrt();
                [lo.min(d), hi.max(d)]
            })
    }

    /// Whether a point (plane coordinates, m) is reachable: inside a posture loop, or within
    /// `tol` (m) of a boundary curve. `None` for three-link arms (no loops; use
    /// [`super::ReachTester`]).
    pub fn contains(&self, p: [f64; 2], tol: f64) -> Option<bool> {
        if self.loops.is_empty() {
            return None;
        }
        Some(
            self.loops.iter().any(|l| inside(p, &l.points))
                || self
                    .curves
                    .iter()
                    .any(|c| polyline_distance(p, &c.points, false) <= tol),
        )
    }

    /// Where the arcs labelled `a` and `b` cross away from their ends (plane coordinates, m):
    /// point H of Fig. 2.30, where arc FD (joint 1 at its upper limit) cuts arc BC (joint 2 at
    /// its upper limit) when the limits of joint 2 are not symmetric; `None` when they do not
    /// cross or meet only at an end (with symmetric limits H falls on F). Each arc lies on a
    /// circle about the joint that moves along it; the circles are intersected in closed form
    /// and a point is kept when it lies on both polylines to within their chord error.
    pub fn crossing(&self, a: &str, b: &str) -> Option<[f64; 2]> {
        let arc = |name: &str| self.curves.iter().find(|c| c.label == name);
        let (ca, cb) = (arc(a)?, arc(b)?);
        let (ka, kb) = (circle_through(&ca.points)?, circle_through(&cb.points)?);
        let scale = ka.1.max(kb.1);
        let ends = [
            ca.points[0],
            *ca.points.last()?,
            cb.points[0],
            *cb.points.last()?,
        ];
        circle_intersections(ka, kb)
            .into_iter()
            .flatten()
            .find(|&p| {
                let on = |c: &BoundaryCurve| polyline_distance(p, &c.points, false) <= 1e-5 * scale;
                let away = ends
                    .iter()
                    .all(|e| (e[0] - p[0]).hypot(e[1] - p[1]) > 1e-7 * scale);
                on(ca) && on(cb) && away
            })
    }

    /// Whether a point is reachable with posture `class`: inside one of its loops or within
    /// `tol` of one. `None` for three-link arms.
    pub fn class_contains(&self, class: u8, p: [f64; 2], tol: f64) -> Option<bool> {
        if self.loops.is_empty() {
            return None;
        }
        Some(
            self.loops
                .iter()
                .filter(|l| l.class == class)
                .any(|l| inside(p, &l.points) || polyline_distance(p, &l.points, true) <= tol),
        )
    }

    /// Area (m^2) reached with posture `class`: the summed shoelace areas of its loops (exact up
    /// to the chord error of the polylines). `None` for three-link arms.
    pub fn loop_area(&self, class: u8) -> Option<f64> {
        if self.loops.is_empty() {
            return None;
        }
        Some(
            self.loops
                .iter()
                .filter(|l| l.class == class)
                .map(|l| shoelace(&l.points).abs())
                .sum(),
        )
    }
}

/// Even-odd test of a point against a closed polygon.
fn inside(p: [f64; 2], poly: &[[f64; 2]]) -> bool {
    let mut c = false;
    let n = poly.len();
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if p[0] < x {
                c = !c;
            }
        }
    }
    c
}

/// Signed area of a closed polygon (m^2).
fn shoelace(poly: &[[f64; 2]]) -> f64 {
    let n = poly.len();
    0.5 * (0..n)
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
}

/// Distance from `p` to a polyline (closed if `closed`).
/// The circle through the first, middle and last points of an arc's polyline: centre and radius
/// (m); `None` for fewer than three points or collinear ones.
fn circle_through(pts: &[[f64; 2]]) -> Option<([f64; 2], f64)> {
    let (a, b, c) = (pts.first()?, pts.get(pts.len() / 2)?, pts.last()?);
    let d = 2.0 * (a[0] * (b[1] - c[1]) + b[0] * (c[1] - a[1]) + c[0] * (a[1] - b[1]));
    let n = |p: &[f64; 2]| p[0] * p[0] + p[1] * p[1];
    let scale = (b[0] - a[0])
        .hypot(b[1] - a[1])
        .max((c[0] - b[0]).hypot(c[1] - b[1]));
    if pts.len() < 3 || d.abs() <= 1e-12 * scale * scale {
        return None;
    }
    let x = (n(a) * (b[1] - c[1]) + n(b) * (c[1] - a[1]) + n(c) * (a[1] - b[1])) / d;
    let y = (n(a) * (c[0] - b[0]) + n(b) * (a[0] - c[0]) + n(c) * (b[0] - a[0])) / d;
    Some(([x, y], (a[0] - x).hypot(a[1] - y)))
}

/// The (up to two) intersections of two circles (centre, radius; m).
fn circle_intersections(
    (c0, r0): ([f64; 2], f64),
    (c1, r1): ([f64; 2], f64),
) -> [Option<[f64; 2]>; 2] {
    let (dx, dy) = (c1[0] - c0[0], c1[1] - c0[1]);
    let d = dx.hypot(dy);
    if d == 0.0 || d > r0 + r1 || d < (r0 - r1).abs() {
        return [None, None];
    }
    let a = (r0 * r0 - r1 * r1 + d * d) / (2.0 * d);
    let h = (r0 * r0 - a * a).max(0.0).sqrt();
    let (mx, my) = (c0[0] + a * dx / d, c0[1] + a * dy / d);
    [
        Some([mx + h * dy / d, my - h * dx / d]),
        Some([mx - h * dy / d, my + h * dx / d]),
    ]
}

fn polyline_distance(p: [f64; 2], pts: &[[f64; 2]], closed: bool) -> f64 {
    let n = pts.len();
    let seg = |a: [f64; 2], b: [f64; 2]| {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let l2 = dx * dx + dy * dy;
        let t = if l2 > 0.0 {
            (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
    };
    let mut d = pts.first().map_or(f64::INFINITY, |&a| seg(a, a));
    for i in 1..n {
        d = d.min(seg(pts[i - 1], pts[i]));
    }
    if closed && n > 1 {
        d = d.min(seg(pts[n - 1], pts[0]));
    }
    d
}

/// The planar arm's frame and number of joints, or why it is not a two-/three-link planar arm.
pub(super) fn planar_arm(robot: &Robot) -> Result<(PlanarFrame, usize), WorkspaceError> {
    let not = || WorkspaceError::NotPlanar {
        robot: robot.name.clone(),
        reason: "is not a two- or three-link planar arm (revolute joints with parallel axes)"
            .into(),
    };
    let cf = ClosedForm::detect(robot).map_err(|e| WorkspaceError::NotPlanar {
        robot: robot.name.clone(),
        reason: format!("has no planar closed form: {e}"),
    })?;
    let n = match cf.family() {
        Family::Planar2 => 2,
        Family::Planar3 => 3,
        _ => return Err(not()),
    };
    let frame = planar_frame(robot, 0).ok_or_else(not)?;
    Ok((frame, n))
}

/// Evaluates the plane position and the rank tests of a planar arm.
pub(super) struct Eval<'a> {
    robot: &'a Robot,
    frame: PlanarFrame,
    base_from_world: Rotation3<f64>,
    frames: Vec<Pose>,
    jac: Matrix6xX<f64>,
}

impl<'a> Eval<'a> {
    pub(super) fn new(robot: &'a Robot, frame: PlanarFrame) -> Self {
        Self {
            robot,
            frame,
            base_from_world: robot.base.rotation.inverse(),
            frames: vec![Pose::identity(); robot.joints().len()],
            jac: Matrix6xX::zeros(robot.dof()),
        }
    }

    /// Plane coordinates of the end-effector at q.
    fn point(&self, q: &[f64]) -> Result<[f64; 2], WorkspaceError> {
        let p = self.robot.fk(q)?.translation.vector;
        Ok(self.frame.to_plane([p.x, p.y, p.z]))
    }

    /// z of the cross product of position-Jacobian columns i and j in the base frame: zero where
    /// the two columns are parallel.
    pub(super) fn cross(&mut self, q: &[f64], i: usize, j: usize) -> f64 {
        if self
            .robot
            .jacobian_into(q, 0, &mut self.frames, &mut self.jac)
            .is_err()
        {
            return f64::NAN;
        }
        let col = |k: usize| {
            let c = self.jac.column(k);
            self.base_from_world * Vector3::new(c[0], c[1], c[2])
        };
        let (a, b) = (col(i), col(j));
        a.x * b.y - a.y * b.x
    }

    /// The image of the joint-space segment from `q0` to `q1` (one joint moving).
    fn polyline(&self, q0: &[f64], q1: &[f64], step: f64) -> Result<Vec<[f64; 2]>, WorkspaceError> {
        let span = q0
            .iter()
            .zip(q1)
            .map(|(a, b)| (b - a).abs())
            .fold(0.0, f64::max);
        let n = ((span / step).ceil() as usize).max(1);
        let mut q = q0.to_vec();
        (0..=n)
            .map(|k| {
                let t = k as f64 / n as f64;
                for (v, (a, b)) in q.iter_mut().zip(q0.iter().zip(q1)) {
                    *v = a + t * (b - a);
                }
                self.point(&q)
            })
            .collect()
    }
}

/// Roots of `f` strictly inside (lo, hi): a scan every 0.005 rad (at least 256 intervals) for sign
/// changes, refined by bisection; roots within 1e-10 of a multiple of pi/2 are snapped to it.
/// Double roots without a sign change are missed.
pub(super) fn roots(mut f: impl FnMut(f64) -> f64, lo: f64, hi: f64) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::new();
    if hi - lo <= 1e-9 {
        return out;
    }
    let n = (((hi - lo) / 0.005).ceil() as usize).max(256);
    let x_at = |k: usize| lo + (hi - lo) * k as f64 / n as f64;
    let (mut x0, mut f0) = (lo, f(lo));
    for k in 1..=n {
        let x1 = x_at(k);
        let f1 = f(x1);
        if f1 == 0.0 {
            out.push(x1);
        } else if f0 != 0.0 && f0.is_finite() && f1.is_finite() && (f0 < 0.0) != (f1 < 0.0) {
            let (mut a, mut b, fa) = (x0, x1, f0);
            for _ in 0..80 {
                let m = 0.5 * (a + b);
                let fm = f(m);
                if fm == 0.0 {
                    a = m;
                    b = m;
                    break;
                }
                if (fm < 0.0) == (fa < 0.0) {
                    a = m;
                } else {
                    b = m;
                }
            }
            out.push(0.5 * (a + b));
        }
        (x0, f0) = (x1, f1);
    }
    let quarter = PI / 2.0;
    let mut clean: Vec<f64> = Vec::new();
    for r in out {
        let snapped = (r / quarter).round() * quarter;
        let r = if (r - snapped).abs() < 1e-10 {
            snapped
        } else {
            r
        };
        if r > lo + 1e-9 && r < hi - 1e-9 && clean.last().is_none_or(|&l| r - l > 1e-9) {
            clean.push(r);
        }
    }
    clean
}

/// The exact boundary candidates of a two- or three-link planar arm, in plane coordinates (m).
///
/// Two links: the images of the segments of [`joint_rectangle`] (arcs AB, BC, CD, DA, AE, EF,
/// FD of Fig. 2.30 when q2 = 0 is inside the limits) and the closed loops of the posture bands.
/// Three links: the images of the 12 edges of the joint-limit box ("E"), of the fold curves of
/// its faces ("F": on the face q_k = limit, the two free columns of the position Jacobian are
/// parallel) and of the interior singular lines ("S": all links aligned or folded); no loops.
pub fn planar_boundary(
    robot: &Robot,
    opts: &BoundaryOptions,
) -> Result<PlanarBoundary, WorkspaceError> {
    if !(opts.step > 0.0 && opts.step.is_finite()) {
        return Err(WorkspaceError::InvalidOption {
            option: "polyline step",
            value: opts.step.to_string(),
            expected: "must be positive",
        });
    }
    let (frame, n) = planar_arm(robot)?;
    let mut ev = Eval::new(robot, frame);
    let classifier = PostureClassifier::new(robot);
    let class_names = classifier.class_names().to_vec();
    if n == 2 {
        let rect = joint_rectangle(robot)?;
        let curves = rectangle_curves(&rect, &ev, opts.step)?;
        let loops = posture_loops(&rect, &ev, opts.step)?;
        return Ok(PlanarBoundary {
            frame,
            class_names,
            curves,
            loops,
            rectangle: Some(rect),
        });
    }
    // Three links: each curve is (moving joint, fixed values of the other two).
    let lim = robot.sampling_ranges();
    let mut specs = edge_specs(&lim);
    face_fold_specs(&mut ev, &lim, &mut specs);
    interior_specs(&mut ev, &lim, &mut specs);
    let curves = three_link_curves(specs, &lim, &ev, opts.step)?;
    Ok(PlanarBoundary {
        frame,
        class_names,
        curves,
        loops: Vec::new(),
        rectangle: None,
    })
}

/// Two links: the image of every segment of the joint-space rectangle (arcs AB, BC, ... of
/// Fig. 2.30), labelled by the segment's label in capitals.
fn rectangle_curves(
    rect: &JointRectangle,
    ev: &Eval,
    step: f64,
) -> Result<Vec<BoundaryCurve>, WorkspaceError> {
    let mut curves = Vec::new();
    for s in &rect.segments {
        let (a, b) = (rect.points[s.from].q, rect.points[s.to].q);
        let moving = if a[0] == b[0] { 1 } else { 0 };
        curves.push(BoundaryCurve {
            label: s.label.to_uppercase(),
            description: format!(
                "image of segment {}: q{} from {:.6} to {:.6} rad, q{} = {:.6} rad ({})",
                s.label,
                moving + 1,
                a[moving],
                b[moving],
                2 - moving,
                a[1 - moving],
                match s.kind {
                    CurveKind::JointLimit => "joint limit",
                    CurveKind::Singular => "aligned links, a singularity",
                }
            ),
            kind: s.kind,
            moving_joint: moving,
            q_start: a.to_vec(),
            q_end: b.to_vec(),
            points: ev.polyline(&a, &b, step)?,
        });
    }
    Ok(curves)
}

/// Two links: the closed image of the perimeter of each posture band (ABCDA, EADFE, ... of
/// Fig. 2.30), its q1 span cut at 2 pi so that the map is one-to-one on the band.
fn posture_loops(
    rect: &JointRectangle,
    ev: &Eval,
    step: f64,
) -> Result<Vec<PostureLoop>, WorkspaceError> {
    let l1 = rect.q1;
    let q1_hi = l1[1].min(l1[0] + TAU);
    let mut loops = Vec::new();
    for (i, &(q2, class)) in rect.bands.iter().enumerate() {
        let corner = |k: usize| rect.points[k].label.to_uppercase();
        let label = format!(
            "{}{}{}{}{}",
            corner(2 * i),
            corner(2 * i + 2),
            corner(2 * i + 3),
            corner(2 * i + 1),
            corner(2 * i)
        );
        let path = [
            [l1[0], q2[0]],
            [l1[0], q2[1]],
            [q1_hi, q2[1]],
            [q1_hi, q2[0]],
            [l1[0], q2[0]],
        ];
        let mut points = Vec::new();
        for w in path.windows(2) {
            let mut p = ev.polyline(&w[0], &w[1], step)?;
            p.pop();
            points.extend(p);
        }
        loops.push(PostureLoop {
            class,
            label,
            q2,
            points,
        });
    }
    Ok(loops)
}

/// A three-link boundary curve before it is traced: tag ('E' edge, 'F' face fold, 'S' interior
/// singularity), moving joint, joint vector with the fixed values set, description of the fixed
/// values.
type CurveSpec = (char, usize, [f64; 3], String);

/// "q{k+1} = v rad (why)": one fixed joint value of a three-link curve's description.
fn fixed_value(k: usize, v: f64, why: &str) -> String {
    format!("q{} = {v:.6} rad ({why})", k + 1)
}

/// Three links: the 12 edges of the joint-limit box, two fixed joints at a limit each.
fn edge_specs(lim: &[[f64; 2]]) -> Vec<CurveSpec> {
    let mut specs = Vec::new();
    for mv in 0..3 {
        let others: Vec<usize> = (0..3).filter(|&k| k != mv).collect();
        for &va in &lim[others[0]] {
            for &vb in &lim[others[1]] {
                let mut q = [0.0; 3];
                q[others[0]] = va;
                q[others[1]] = vb;
                let d = format!(
                    "{}, {}",
                    fixed_value(others[0], va, "limit"),
                    fixed_value(others[1], vb, "limit")
                );
                specs.push(('E', mv, q, d));
            }
        }
    }
    specs
}

/// Three links: the fold curves of the faces of the joint-limit box, appended to `specs`.
fn face_fold_specs(ev: &mut Eval, lim: &[[f64; 2]], specs: &mut Vec<CurveSpec>) {
    // Face folds: free joints i < j, fixed k; the rank test depends on q_j (and q_k), so its roots
    // are values of q_j and joint i moves.
    for k in 0..3 {
        let free: Vec<usize> = (0..3).filter(|&x| x != k).collect();
        let (i, j) = (free[0], free[1]);
        for &vk in &lim[k] {
            let mut q = [lim[0][0], lim[1][0], lim[2][0]];
            q[k] = vk;
            let rs = roots(
                |x| {
                    let mut qq = q;
                    qq[j] = x;
                    ev.cross(&qq, i, j)
                },
                lim[j][0],
                lim[j][1],
            );
            for r in rs {
                let mut qq = q;
                qq[j] = r;
                let d = format!(
                    "{}, {}",
                    fixed_value(k, vk, "limit"),
                    fixed_value(j, r, "fold of the face")
                );
                specs.push(('F', i, qq, d));
            }
        }
    }
}

/// Three links: the interior singular lines (all links aligned or folded; joint 1 moves),
/// appended to `specs`.
fn interior_specs(ev: &mut Eval, lim: &[[f64; 2]], specs: &mut Vec<CurveSpec>) {
    // Interior: columns 2 and 3 parallel (a value of q3), then columns 1 and 2 (a value of q2).
    let mut q = [lim[0][0], 0.0, 0.0];
    q[1] = lim[1][0];
    for r3 in roots(|x| ev.cross(&[q[0], q[1], x], 1, 2), lim[2][0], lim[2][1]) {
        for r2 in roots(|x| ev.cross(&[q[0], x, r3], 0, 1), lim[1][0], lim[1][1]) {
            let d = format!(
                "{}, {}",
                fixed_value(1, r2, "aligned"),
                fixed_value(2, r3, "aligned")
            );
            specs.push(('S', 0, [0.0, r2, r3], d));
        }
    }
}

/// Three links: traces each spec (its moving joint sweeping its limits), labelled by tag and a
/// count per tag ("E1", "F1", "S1", ...).
fn three_link_curves(
    specs: Vec<CurveSpec>,
    lim: &[[f64; 2]],
    ev: &Eval,
    step: f64,
) -> Result<Vec<BoundaryCurve>, WorkspaceError> {
    let mut counts = [0usize; 3];
    let mut curves = Vec::new();
    for (tag, mv, q, desc) in specs {
        let slot = match tag {
            'E' => 0,
            'F' => 1,
            _ => 2,
        };
        counts[slot] += 1;
        let (mut a, mut b) = (q, q);
        a[mv] = lim[mv][0];
        b[mv] = lim[mv][1];
        curves.push(BoundaryCurve {
            label: format!("{tag}{}", counts[slot]),
            description: format!("q{} sweeps its limits; {desc}", mv + 1),
            kind: if tag == 'E' {
                CurveKind::JointLimit
            } else {
                CurveKind::Singular
            },
            moving_joint: mv,
            q_start: a.to_vec(),
            q_end: b.to_vec(),
            points: ev.polyline(&a, &b, step)?,
        });
    }
    Ok(curves)
}
