//! Side and top views of arms with a closed-form positioning arm (anthropomorphic with or
//! without shoulder offset, spherical, cylindrical; alone or with a spherical wrist).
//!
//! Joint 1 turns the whole arm about the base z axis, so the position problem of the other
//! joints is planar in (r, z) (Sect. 2.12.3-2.12.4: theta1 from the azimuth, then a planar
//! problem): a point (r, z) of the side view is reached with a posture exactly when the closed
//! form at (r, 0, z) has a solution of that posture with joints 2 and 3 (and the wrist, for the
//! flange) within their limits; joint 1 then only decides the azimuths, `psi = s1 (q1 - q1_0)`
//! for q1 in its range, where q1_0 is the solution's joint 1 at azimuth 0. The top view is a
//! point (x, y) at radius r reached with a posture when some (r, z) is and q1 fits the azimuth;
//! the volume is Pappus's integral of r times the azimuth measure over the section.
//!
//! Tracked point: the wrist centre (exact, position of the arm alone) or the flange. With no
//! flange offset the flange is the wrist centre. The flange of an arm whose full-range spherical
//! wrist turns the tool in every direction, with joint 1 full-range and the arm in a plane through
//! its axis, is the wrist-centre workspace grown by a sphere, decided exactly on the section's
//! boundary arcs ([`super::arcs`]). Any other flange offset is decided over the 64 approach
//! directions of [`crate::workspace::approach_bin_centre`] (one roll each), which is not exact
//! and is said so.

use super::arcs::SectionArcs;
use super::raster;
use super::{CellValues, CurveRole, MapRequest, MapValues, MapView, TrackedPoint, WorkspaceMap};
use crate::kinematics::ik::closed_form::{
    ClosedForm, Family, LIMIT_TOL, MAX_DOF, RawSolutions, wrap_into_limits,
};
use crate::kinematics::{JointKind, Pose, Robot};
use crate::workspace::{
    Aabb, ClassMeasure, GridMethod, PostureClassifier, WorkspaceError, WorkspaceStats,
};
use nalgebra::{Point3, Rotation3, Translation3};
use std::f64::consts::{PI, TAU};

/// Approach directions of the flange scan.
const APPROACHES: usize = 64;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    /// The positioning arm alone (3-DOF arm, or the wrist centre of a 6-DOF arm).
    Position,
    /// The flange of a 6-DOF arm with a flange offset: approach directions scanned.
    FlangeScan,
    /// The flange of a 6-DOF arm whose full-range wrist turns the tool in every direction, joint
    /// 1 full-range and the arm in a plane through its axis: the wrist-centre workspace grown by
    /// the sphere of radius d (exact, [`SectionArcs::sphere_mask`]).
    FlangeSphere,
    /// A SCARA whose tool point lies on the last (roll) axis: the closed form at a vertical
    /// tool orientation; the roll joint does not move the point.
    Scara,
}

/// The section tester (see the module documentation).
#[derive(Debug, Clone)]
pub struct Section {
    cf: ClosedForm,
    classifier: PostureClassifier,
    mode: Mode,
    base: Pose,
    limits: Vec<[f64; 2]>,
    revolute: Vec<bool>,
    /// Sense of joint 1 about the base z axis (+1 or -1).
    s1: f64,
    /// Joint 1 covers a full turn.
    q1_full: bool,
    scale: f64,
    family: &'static str,
    point: TrackedPoint,
    /// The side view's extent, computed once.
    side_extent: std::sync::OnceLock<Aabb>,
    /// World rotation of the tool at q = 0 (SCARA targets).
    tool_rot0: Rotation3<f64>,
    /// The section's boundary arcs, for an arm in a plane through joint 1's axis.
    arcs: Option<SectionArcs>,
    /// Distance from the wrist centre to the flange (m), [`Mode::FlangeSphere`].
    sphere_radius: f64,
    /// Bits of every posture class.
    all_classes: u8,
    /// Joints the approach scan checks against their limits: all, or all but the last where
    /// turning it leaves the flange in place (a roll about the approach axis: the scan's
    /// approach directions fix the roll arbitrarily, and any value in its range serves).
    scan_dof: usize,
}

/// One posture reaching a side-view point: its class bits and q1 at azimuth 0 (rad).
#[derive(Debug, Clone, Copy, Default)]
struct Hit {
    mask: u8,
    q1: f64,
}

impl Section {
    /// The tester for a robot and tracked point, or `None` when the robot has no closed-form
    /// positioning arm whose joint 1 is a revolute joint about the base z axis.
    pub fn new(robot: &Robot, point: TrackedPoint) -> Option<Self> {
        if robot.end_effectors().len() != 1 || robot.dof() < 3 {
            return None;
        }
        let cf = ClosedForm::detect(robot).ok()?;
        let mut mode = match (cf.family(), point) {
            (Family::Anthropomorphic | Family::SphericalArm | Family::Cylindrical, _) => {
                Mode::Position
            }
            (Family::Decoupled6 { .. }, TrackedPoint::WristCentre) => Mode::Position,
            (Family::Scara, _) if roll_keeps_position(robot) => Mode::Scara,
            (Family::Decoupled6 { .. }, TrackedPoint::Flange) => {
                if flange_is_wrist_centre(robot, &cf) {
                    Mode::Position
                } else {
                    Mode::FlangeScan
                }
            }
            _ => return None,
        };
        if robot.dof_joint(0).kind != JointKind::Revolute {
            return None;
        }
        let s1 = joint1_sense(robot)?;
        let limits = robot.limits();
        let q1_full = !(limits[0][0].is_finite() && limits[0][1].is_finite())
            || limits[0][1] - limits[0][0] >= TAU - 1e-12;
        let classifier = PostureClassifier::new(robot);
        let wrist_centre = cf.wrist_centre_in_tool();
        let arcs = match cf.family() {
            Family::Anthropomorphic | Family::Decoupled6 { .. } => SectionArcs::new(
                robot,
                &cf,
                &classifier,
                wrist_centre.unwrap_or_else(nalgebra::Vector3::zeros),
            ),
            _ => None,
        };
        if mode == Mode::FlangeScan && q1_full && arcs.is_some() && wrist_is_full(robot) {
            mode = Mode::FlangeSphere;
        }
        let all_classes = ((1u16 << classifier.class_names().len().min(8)) - 1) as u8;
        let n = robot.dof();
        let rolls = robot.dof_joint(n - 1).kind == JointKind::Revolute
            && limits[n - 1][0] <= limits[n - 1][1]
            && roll_keeps_position(robot);
        Some(Self {
            scan_dof: n - usize::from(rolls),
            arcs,
            sphere_radius: wrist_centre.map_or(0.0, |c| c.norm()),
            all_classes,
            classifier,
            mode,
            base: robot.base,
            revolute: (0..robot.dof())
                .map(|k| robot.dof_joint(k).kind == JointKind::Revolute)
                .collect(),
            limits,
            s1,
            q1_full,
            scale: robot.characteristic_length(),
            family: cf.name(),
            point,
            side_extent: std::sync::OnceLock::new(),
            tool_rot0: robot.fk(&vec![0.0; robot.dof()]).ok()?.rotation,
            cf,
        })
    }

    /// Names of the posture classes.
    pub fn class_names(&self) -> &[String] {
        self.classifier.class_names()
    }

    /// Whether the side view is exact (the positioning arm, or the flange of a full-range wrist
    /// as a Minkowski sum), not an approach scan.
    pub fn exact(&self) -> bool {
        self.mode != Mode::FlangeScan
    }

    /// Joints `from..to` of a raw solution within their limits (revolute ones modulo 2 pi).
    #[inline]
    fn within(&self, q: &[f64; MAX_DOF], from: usize, to: usize) -> bool {
        (from..to).all(|k| {
            let v = if self.revolute[k] {
                wrap_into_limits(q[k], self.limits[k])
            } else {
                q[k]
            };
            v >= self.limits[k][0] - LIMIT_TOL && v <= self.limits[k][1] + LIMIT_TOL
        })
    }

    /// The postures reaching the base-frame point (r, 0, z) with joint 1 free; writes up to 8
    /// hits and returns the count. Allocation-free.
    fn hits(&self, r: f64, z: f64, out: &mut [Hit; 8]) -> usize {
        let w = self.base * Point3::new(r, 0.0, z);
        let mut raw = RawSolutions::default();
        let mut n = 0;
        match self.mode {
            Mode::FlangeSphere => {
                let Some(arcs) = &self.arcs else { return 0 };
                let d = self.sphere_radius;
                let inside = self.position_mask(r + d, z);
                let mask = arcs.sphere_mask(r, z, d, inside, self.all_classes);
                if mask != 0 {
                    // Joint 1 is full-range: its value does not matter.
                    out[0] = Hit { mask, q1: 0.0 };
                    n = 1;
                }
            }
            Mode::Position | Mode::Scara => {
                let solved = if self.mode == Mode::Scara {
                    let pose = Pose::from_parts(Translation3::from(w.coords), self.tool_rot0);
                    self.cf.solve_raw(&pose, &mut raw)
                } else {
                    self.cf.solve_position_raw(&w.coords, &mut raw)
                };
                if solved.is_err() {
                    return 0;
                }
                for k in 0..raw.len {
                    if n < 8 && self.within(&raw.q[k], 1, 3) {
                        out[n] = Hit {
                            mask: self.classifier.posture_mask(&raw.postures[k]),
                            q1: raw.q[k][0],
                        };
                        n += 1;
                    }
                }
            }
            Mode::FlangeScan => {
                let dof = self.scan_dof;
                for b in 0..APPROACHES {
                    let pose = Pose::from_parts(Translation3::from(w.coords), approach(b));
                    if self.solve_arm_within(&pose, &mut raw).is_err() {
                        continue;
                    }
                    for k in 0..raw.len {
                        if !self.within(&raw.q[k], 1, dof) {
                            continue;
                        }
                        let mask = self.classifier.posture_mask(&raw.postures[k]);
                        let q1 = raw.q[k][0];
                        if let Some(h) = out[..n]
                            .iter_mut()
                            .find(|h| h.mask == mask && (h.q1 - q1).abs() < 1e-9)
                        {
                            h.mask |= mask;
                        } else if n < 8 {
                            out[n] = Hit { mask, q1 };
                            n += 1;
                        }
                    }
                    // Full: a later hit could only OR a mask into the same (mask, q1), a no-op.
                    if n == 8 {
                        break;
                    }
                }
            }
        }
        n
    }

    /// Class mask of the positioning arm's tracked point (the wrist centre) at the side-view
    /// point (r >= 0, z), base frame (m), joint 1 free.
    fn position_mask(&self, r: f64, z: f64) -> u8 {
        let w = self.base * Point3::new(r, 0.0, z);
        let mut raw = RawSolutions::default();
        if self.cf.solve_position_raw(&w.coords, &mut raw).is_err() {
            return 0;
        }
        (0..raw.len)
            .filter(|&k| self.within(&raw.q[k], 1, 3))
            .fold(0, |m, k| m | self.classifier.posture_mask(&raw.postures[k]))
    }

    /// Class mask of a side-view point (r >= 0, z), base frame (m).
    pub fn side_mask(&self, r: f64, z: f64) -> u8 {
        if self.mode == Mode::FlangeScan {
            return self.scan_mask(r, z);
        }
        let mut h = [Hit::default(); 8];
        let n = self.hits(r, z, &mut h);
        h[..n].iter().fold(0, |m, x| m | x.mask)
    }

    /// [`Self::side_mask`] of the approach scan: the classes over the approach directions, which
    /// stops as soon as every class is found (joint 1's values do not matter here).
    fn scan_mask(&self, r: f64, z: f64) -> u8 {
        self.scan_classes(self.base * Point3::new(r, 0.0, z), None, 1)
    }

    /// The classes reaching the world point `w` over the approach directions (each turned by
    /// `turn`, a world rotation, if given) with joints `from..` within their limits (the roll
    /// joint aside, see `scan_dof`); stops as soon as every class is found.
    fn scan_classes(&self, w: Point3<f64>, turn: Option<Rotation3<f64>>, from: usize) -> u8 {
        let dof = self.scan_dof;
        let mut raw = RawSolutions::default();
        let mut mask = 0;
        for b in 0..APPROACHES {
            let rot = turn.map_or_else(|| approach(b), |t| t * approach(b));
            let pose = Pose::from_parts(Translation3::from(w.coords), rot);
            let kept = self.cf.solve_raw_where(&pose, &mut raw, |a| {
                let mut q = [0.0; MAX_DOF];
                q[..3].copy_from_slice(a);
                self.within(&q, from, 3)
            });
            if kept.is_err() {
                continue;
            }
            for k in 0..raw.len {
                if self.within(&raw.q[k], from, dof) {
                    mask |= self.classifier.posture_mask(&raw.postures[k]);
                }
            }
            if mask == self.all_classes {
                break;
            }
        }
        mask
    }

    /// The solutions at a world pose whose positioning joints 2 and 3 are within their limits
    /// (the wrist is solved only for those: the others would be dropped anyway).
    #[inline]
    fn solve_arm_within(
        &self,
        pose: &Pose,
        raw: &mut RawSolutions,
    ) -> Result<usize, crate::kinematics::ik::IkError> {
        self.cf.solve_raw_where(pose, raw, |a| {
            let mut q = [0.0; MAX_DOF];
            q[..3].copy_from_slice(a);
            self.within(&q, 1, 3)
        })
    }

    /// The approach scan's class mask at radius r, height z and azimuth psi (base frame; m,
    /// rad), every joint within its limits (joint 1 included); the approach directions turned
    /// with the azimuth about the base z axis, as the side view's are at azimuth 0. Stops once
    /// every class is found.
    fn scan_mask_3d(&self, r: f64, z: f64, psi: f64) -> u8 {
        let w = self.base * Point3::new(r * psi.cos(), r * psi.sin(), z);
        let turn = self.base.rotation
            * Rotation3::from_axis_angle(&nalgebra::Vector3::z_axis(), psi)
            * self.base.rotation.inverse();
        self.scan_classes(w, Some(turn), 0)
    }

    /// Base-frame coordinates of a world point (m).
    pub(super) fn base_from_world(&self, p: [f64; 3]) -> [f64; 3] {
        let l = self
            .base
            .inverse_transform_point(&Point3::new(p[0], p[1], p[2]));
        [l.x, l.y, l.z]
    }

    /// Class mask at radius r, height z and azimuth psi (base frame; m, rad).
    pub(super) fn mask_at(&self, r: f64, z: f64, psi: f64) -> u8 {
        if self.mode == Mode::FlangeScan {
            // The scan at the point itself (the hits keep only eight (class, q1) pairs).
            return self.scan_mask_3d(r, z, psi);
        }
        let mut h = [Hit::default(); 8];
        let n = self.hits(r, z, &mut h);
        h[..n]
            .iter()
            .filter(|x| self.q1_fits(x.q1, psi))
            .fold(0, |m, x| m | x.mask)
    }

    /// Whether q1 = q1_0 + psi / s1 fits joint 1's range (azimuth psi, rad).
    #[inline]
    fn q1_fits(&self, q1_0: f64, psi: f64) -> bool {
        if self.q1_full {
            return true;
        }
        let q = wrap_into_limits(q1_0 + psi * self.s1, self.limits[0]);
        q >= self.limits[0][0] - LIMIT_TOL && q <= self.limits[0][1] + LIMIT_TOL
    }

    /// Measures (rad) of the azimuths reached at a side-view point: by any posture, by each
    /// class, and by each class alone (no other class at that azimuth).
    fn azimuths(&self, hits: &[Hit], classes: usize) -> (f64, [f64; 4], [f64; 4]) {
        if hits.is_empty() {
            return (0.0, [0.0; 4], [0.0; 4]);
        }
        // Each hit covers psi in s1 (range - q1_0): cut the circle at every end.
        let mut cuts: Vec<f64> = vec![0.0];
        if !self.q1_full {
            for h in hits {
                for l in self.limits[0] {
                    cuts.push((self.s1 * (l - h.q1)).rem_euclid(TAU));
                }
            }
        }
        cuts.sort_by(f64::total_cmp);
        let (mut any, mut with, mut only) = (0.0, [0.0; 4], [0.0; 4]);
        for i in 0..cuts.len() {
            let hi = if i + 1 < cuts.len() { cuts[i + 1] } else { TAU };
            let width = hi - cuts[i];
            if width <= 0.0 {
                continue;
            }
            let mid = 0.5 * (cuts[i] + hi);
            let mask = hits
                .iter()
                .filter(|h| self.q1_fits(h.q1, mid))
                .fold(0u8, |m, h| m | h.mask);
            if mask != 0 {
                any += width;
            }
            for c in 0..classes.min(4) {
                if mask >> c & 1 == 1 {
                    with[c] += width;
                    if mask == 1 << c {
                        only[c] += width;
                    }
                }
            }
        }
        (any, with, only)
    }

    /// Class mask of a top-view point (base-frame x, y) for a radial table (see [`Radial`]).
    fn top_mask(&self, radial: &Radial, x: f64, y: f64) -> u8 {
        let r = x.hypot(y);
        let psi = y.atan2(x);
        let mut out = 0u8;
        let mut h = [Hit::default(); 8];
        // Heights of this radius bin and of its neighbours, each tested at the point's own
        // radius: a true point of the section whenever it is reached.
        let mut tried = [f64::NAN; 12];
        for (k, z) in radial.near(r).enumerate() {
            if !z.is_finite() || tried.contains(&z) {
                continue;
            }
            tried[k.min(11)] = z;
            if self.mode == Mode::FlangeScan {
                // The scan solves at the point itself, joint 1 checked with the others: the
                // side view's hits keep only the first eight (class, q1) pairs and so miss
                // azimuths that other approach directions reach.
                out |= self.scan_mask_3d(r, z, psi);
                if out == self.all_classes {
                    return out;
                }
                continue;
            }
            let n = self.hits(r, z, &mut h);
            for hit in &h[..n] {
                if self.q1_fits(hit.q1, psi) {
                    out |= hit.mask;
                }
            }
        }
        if self.mode == Mode::FlangeScan && out != 0 {
            // A class missing at the bins' heights may reach this azimuth at another height
            // (joint 1's limit cuts each height differently): eight more across the side view.
            let [lo, hi] = radial.z_span;
            for j in 0..8 {
                out |= self.scan_mask_3d(r, lo + (j as f64 + 0.5) / 8.0 * (hi - lo), psi);
                if out == self.all_classes {
                    break;
                }
            }
        }
        out
    }

    /// Bounding box of a view (m): the side view's reached cells on a 256 x 256 scan of
    /// `[0, L] x [-L, L]` (L the arm's characteristic length) grown by a cell, or the disk of
    /// the largest radius for the top view.
    pub fn extent(&self, view: MapView) -> Aabb {
        let b = *self
            .side_extent
            .get_or_init(|| match (self.mode, &self.arcs) {
                (Mode::FlangeSphere, Some(arcs)) => {
                    // Exact: the section's radii and heights widened by the sphere.
                    let ([r, lo, hi], d) = (arcs.extent(), self.sphere_radius);
                    Aabb {
                        min: [0.0, lo - d, 0.0],
                        max: [r + d, hi + d, 0.0],
                    }
                }
                _ => self.scan_extent(),
            });
        match view {
            MapView::Side | MapView::Plane => b,
            MapView::Top => Aabb {
                min: [-b.max[0], -b.max[0], 0.0],
                max: [b.max[0], b.max[0], 0.0],
            },
        }
    }
}

impl Section {
    /// Cells per side of the scans behind the statistics: fewer for the approach scan, which
    /// costs 64 solves per point.
    fn scan_cells(&self, exact: usize) -> usize {
        if self.exact() { exact } else { exact / 4 }
    }

    /// The side view's reached cells on a scan of `[0, L] x [-L, L]`, grown by a cell.
    fn scan_extent(&self) -> Aabb {
        let l = self.scale;
        let n = self.scan_cells(256);
        let bounds = [0.0, l, -l, l];
        let masks = raster::fill(bounds, [n, n], &|p| self.side_mask(p[0], p[1]));
        let mut b = Aabb::EMPTY;
        let cell = [l / n as f64, 2.0 * l / n as f64];
        for (k, &m) in masks.iter().enumerate() {
            if m != 0 {
                let c = raster::centre(bounds, [n, n], k % n, k / n);
                b.extend([(c[0] - cell[0]).max(0.0), c[1] - cell[1], 0.0]);
                b.extend([c[0] + cell[0], c[1] + cell[1], 0.0]);
            }
        }
        b
    }
}

/// Does the last joint (a SCARA's roll) leave the tool position unchanged?
fn roll_keeps_position(robot: &Robot) -> bool {
    let n = robot.dof();
    let mut q = vec![0.3; n];
    let Ok(a) = robot.fk(&q) else { return false };
    q[n - 1] += 1.0;
    let Ok(b) = robot.fk(&q) else { return false };
    (a.translation.vector - b.translation.vector).norm() < 1e-12 * robot.characteristic_length()
}

/// Is the flange at the wrist centre (no flange offset, no tool offset)?
fn flange_is_wrist_centre(robot: &Robot, cf: &ClosedForm) -> bool {
    let q = [0.3, -0.4, 0.5, 0.7, -0.6, 0.2];
    let Ok(t) = robot.fk(&q[..robot.dof().min(6)]) else {
        return false;
    };
    let mut raw = RawSolutions::default();
    let p = t.translation.vector;
    if cf.solve_position_raw(&p, &mut raw).is_err() {
        return false;
    }
    (0..raw.len).any(|k| {
        (0..3).all(|j| {
            let d = (raw.q[k][j] - q[j]).rem_euclid(TAU);
            d.min(TAU - d) < 1e-9
        })
    })
}

/// The sense of joint 1 about the base z axis, if its axis is that axis.
fn joint1_sense(robot: &Robot) -> Option<f64> {
    let mut q = vec![0.0; robot.dof()];
    q[1] = 0.3;
    q[2] = 0.2;
    let p0 = robot.base.inverse() * robot.fk(&q).ok()?;
    q[0] = 0.5;
    let p1 = robot.base.inverse() * robot.fk(&q).ok()?;
    let (a, b) = (p0.translation.vector, p1.translation.vector);
    let (ra, rb) = (a.x.hypot(a.y), b.x.hypot(b.y));
    if (a.z - b.z).abs() > 1e-9 || (ra - rb).abs() > 1e-9 || ra < 1e-6 {
        return None;
    }
    let turn = (a.x * b.y - a.y * b.x).atan2(a.x * b.x + a.y * b.y);
    if (turn.abs() - 0.5).abs() > 1e-9 {
        return None;
    }
    Some(turn.signum())
}

/// The rotation with approach (z axis) along approach bin `k`, x axis perpendicular to it.
fn approach(k: usize) -> Rotation3<f64> {
    crate::workspace::reach::approach_rotation(k)
}

/// Per radius bin and class, a height z at which the class reaches (r, z) with joint 1 free
/// (NaN if none): the radial extent of the section, for the top view.
/// A map's point test: view coordinates (m) to class mask.
type PointTest<'a> = Box<dyn Fn([f64; 2]) -> u8 + Sync + 'a>;

/// What a map's point test needs computed first ([`Section::prepare`]).
pub(super) struct Prepared {
    radial: Option<Radial>,
}

pub(super) struct Radial {
    r_max: f64,
    /// The side view's heights (m), lowest and highest.
    z_span: [f64; 2],
    bins: usize,
    z: Vec<[f64; 4]>,
}

impl Radial {
    fn new(s: &Section, side: [f64; 4], bins: usize, heights: usize) -> Self {
        use rayon::prelude::*;
        let r_max = side[1];
        let z = (0..bins)
            .into_par_iter()
            .map(|i| {
                let r = (i as f64 + 0.5) / bins as f64 * r_max;
                // Per class the middle of the longest run of heights reached: the most interior
                // height, robust to the radius varying across a bin.
                let mut best = [(0usize, f64::NAN); 4];
                let mut run = [(0usize, 0usize); 4];
                for j in 0..=heights {
                    let m = if j < heights {
                        let z = side[2] + (j as f64 + 0.5) / heights as f64 * (side[3] - side[2]);
                        s.side_mask(r, z)
                    } else {
                        0
                    };
                    for c in 0..4 {
                        if m >> c & 1 == 1 {
                            if run[c].1 == 0 {
                                run[c].0 = j;
                            }
                            run[c].1 += 1;
                        } else if run[c].1 > 0 {
                            if run[c].1 > best[c].0 {
                                let mid = run[c].0 as f64 + 0.5 * run[c].1 as f64;
                                best[c] = (
                                    run[c].1,
                                    side[2] + mid / heights as f64 * (side[3] - side[2]),
                                );
                            }
                            run[c].1 = 0;
                        }
                    }
                }
                best.map(|b| b.1)
            })
            .collect();
        Self {
            r_max,
            z_span: [side[2], side[3]],
            bins,
            z,
        }
    }

    /// The heights of the bin of radius `r` and of the two bins beside it.
    fn near(&self, r: f64) -> impl Iterator<Item = f64> + '_ {
        let i = (r / self.r_max * self.bins as f64).floor();
        let i = if i.is_finite() { i as isize } else { -10 };
        (i - 1..=i + 1)
            .filter(|&k| k >= 0 && (k as usize) < self.bins)
            .flat_map(move |k| self.z[k as usize].into_iter())
    }
}

impl Section {
    /// The map of a side or top view over `bounds`.
    pub(super) fn map(
        &self,
        robot: &Robot,
        req: &MapRequest,
        bounds: [f64; 4],
        forming: &mut dyn super::MapForming,
    ) -> Result<WorkspaceMap, WorkspaceError> {
        if req.values == MapValues::Manipulability {
            return super::sampled::map(robot, req, bounds, forming);
        }
        let prepared = self.prepare(req, bounds);
        let (test, how) = self.test(req, &prepared);
        let masks = raster::fill_tiled(bounds, req.cells, &test, how, &mut |masks, rows| {
            if rows < req.cells[1] && forming.wants() {
                forming.partial(&self.bare_map(req, bounds, masks.to_vec()), rows);
            }
        });
        self.finish(req, bounds, &prepared, masks)
    }

    /// What a map's point test needs computed first: for a top view decided through the side
    /// view, the side view's heights per radius.
    pub(super) fn prepare(&self, req: &MapRequest, bounds: [f64; 4]) -> Prepared {
        let radial = match (req.view, &self.arcs) {
            (MapView::Top, Some(_)) if self.mode == Mode::FlangeSphere => None,
            (MapView::Top, _) => {
                let side = self.extent(MapView::Side);
                let side = [0.0, side.max[0], side.min[1], side.max[1]];
                let cell = (bounds[1] - bounds[0]) / req.cells[0] as f64;
                // The approach scan costs 64 solves per test: a quarter of the radii and of the
                // heights (it is not exact anyway; each top cell is still tested at its own
                // radius), which keeps its figure within seconds.
                let (per_cell, heights) = if self.exact() {
                    (2.0, 1024)
                } else {
                    (0.5, 256)
                };
                let bins = ((side[1] / cell * per_cell).ceil() as usize).clamp(64, 8192);
                Some(Radial::new(self, side, bins, heights))
            }
            _ => None,
        };
        Prepared { radial }
    }

    /// The map's point test (view coordinates to class mask) and how its cells are filled.
    fn test<'a>(
        &'a self,
        req: &MapRequest,
        prepared: &'a Prepared,
    ) -> (PointTest<'a>, raster::Fill<'a>) {
        let test: PointTest<'a> = match (req.view, &self.arcs) {
            (MapView::Top, Some(arcs)) if self.mode == Mode::FlangeSphere => {
                let d = self.sphere_radius;
                Box::new(move |p: [f64; 2]| arcs.radius_mask(p[0].hypot(p[1]), d))
            }
            (MapView::Top, _) => match &prepared.radial {
                Some(radial) => Box::new(move |p: [f64; 2]| self.top_mask(radial, p[0], p[1])),
                None => Box::new(|_| 0),
            },
            _ => Box::new(|p: [f64; 2]| {
                if p[0] < 0.0 {
                    0
                } else {
                    self.side_mask(p[0], p[1])
                }
            }),
        };
        let how = if self.mode == Mode::FlangeScan {
            raster::Fill::Blocks(None)
        } else {
            raster::Fill::Cells
        };
        (test, how)
    }

    /// The masks of rows `rows` (from the top; the first a multiple of [`super::TILE_ROWS`]) of
    /// the map: the cells [`Self::map`] decides there, the same way.
    pub(super) fn rows(
        &self,
        req: &MapRequest,
        bounds: [f64; 4],
        prepared: &Prepared,
        rows: std::ops::Range<usize>,
    ) -> Vec<u8> {
        let (test, how) = self.test(req, prepared);
        raster::fill_rows(bounds, req.cells, &test, how, rows)
    }

    /// The map from all its masks: the edge cells, the curves and the values.
    pub(super) fn finish(
        &self,
        req: &MapRequest,
        bounds: [f64; 4],
        prepared: &Prepared,
        masks: Vec<u8>,
    ) -> Result<WorkspaceMap, WorkspaceError> {
        let (test, _) = self.test(req, prepared);
        let dims = req.cells;
        let edges = self.edges(&masks, bounds, dims, &test);
        let curves = self.curves(&masks, bounds, dims, &test);
        let values = match req.values {
            MapValues::Dexterity => Some(self.dexterity(req.view, bounds, dims)?),
            _ => None,
        };
        Ok(WorkspaceMap {
            edges,
            values,
            curves,
            ..self.bare_map(req, bounds, masks)
        })
    }

    /// A map with these masks and nothing else computed (no edge cells, curves or values).
    fn bare_map(&self, req: &MapRequest, bounds: [f64; 4], masks: Vec<u8>) -> WorkspaceMap {
        WorkspaceMap {
            view: req.view,
            bounds,
            width: req.cells[0],
            height: req.cells[1],
            masks,
            edges: Vec::new(),
            class_names: self.class_names().to_vec(),
            values: None,
            fills: Vec::new(),
            curves: Vec::new(),
            method: self.method(),
            exact: self.exact(),
            collision: None,
        }
    }

    /// How the map's classes were decided, in words.
    fn method(&self) -> String {
        let point = match (self.mode, self.point) {
            (Mode::FlangeScan | Mode::FlangeSphere, _) => "flange",
            (_, TrackedPoint::WristCentre) => "wrist centre",
            _ => "end-effector",
        };
        match self.mode {
            Mode::Position | Mode::Scara => format!(
                "exact: closed-form IK of the {} for the {point} at each cell, joint 1 \
                 from the azimuth",
                self.family
            ),
            Mode::FlangeScan => format!(
                "closed-form IK of the {} for the flange over {APPROACHES} approach \
                 directions at each cell (not exact: orientations between them are not tried)",
                self.family
            ),
            Mode::FlangeSphere => format!(
                "exact: the wrist-centre workspace of the {} grown by the sphere of radius \
                 {:.4} m that its full-range wrist sweeps the flange over (a Minkowski sum, \
                 decided at each cell on the section's boundary arcs in closed form)",
                self.family, self.sphere_radius
            ),
        }
    }

    /// The edge cells, supersampled 4 x 4 on the exact test; none for the approach scan (64
    /// solves per sub-sample for an edge that is not exact anyway: its cells keep their centre's
    /// classes).
    fn edges(
        &self,
        masks: &[u8],
        bounds: [f64; 4],
        dims: [usize; 2],
        test: &(dyn Fn([f64; 2]) -> u8 + Sync),
    ) -> Vec<raster::EdgeCell> {
        if self.exact() {
            raster::edges(masks, bounds, dims, test)
        } else {
            Vec::new()
        }
    }

    /// The reachable boundary and the posture boundaries traced on the exact test (exact
    /// modes only; the approach scan would need 64 solves per bisection step).
    fn curves(
        &self,
        masks: &[u8],
        bounds: [f64; 4],
        dims: [usize; 2],
        test: &(dyn Fn([f64; 2]) -> u8 + Sync),
    ) -> Vec<super::MapCurve> {
        if !self.exact() {
            return Vec::new();
        }
        let mut out = super::contour::contours(masks, bounds, dims, test, CurveRole::Boundary);
        if self.class_names().len() > 1 {
            out.extend(super::contour::contours(
                masks,
                bounds,
                dims,
                test,
                CurveRole::PostureBoundary,
            ));
        }
        out
    }

    /// Volume (m^3) by Pappus: the integral of r times the azimuth measure over the (r, z)
    /// section, on `n` x `n` cells (edge cells supersampled 4 x 4), with per-class measures.
    fn pappus(&self, n: usize) -> (f64, [f64; 4], [f64; 4]) {
        use rayon::prelude::*;
        let e = self.extent(MapView::Side);
        let bounds = [0.0, e.max[0], e.min[1], e.max[1]];
        let dims = [n, n];
        let test = |p: [f64; 2]| self.side_mask(p[0], p[1]);
        let masks = raster::fill(bounds, dims, &test);
        let edges = raster::edges(&masks, bounds, dims, &test);
        let classes = self.class_names().len();
        let da = (bounds[1] - bounds[0]) * (bounds[3] - bounds[2]) / (n * n) as f64;
        let at = |p: [f64; 2], w: f64| {
            let mut h = [Hit::default(); 8];
            let k = self.hits(p[0], p[1], &mut h);
            let (any, with, only) = self.azimuths(&h[..k], classes);
            let f = p[0] * da * w;
            (any * f, with.map(|x| x * f), only.map(|x| x * f))
        };
        let add = |a: (f64, [f64; 4], [f64; 4]), b: (f64, [f64; 4], [f64; 4])| {
            (
                a.0 + b.0,
                std::array::from_fn(|c| a.1[c] + b.1[c]),
                std::array::from_fn(|c| a.2[c] + b.2[c]),
            )
        };
        let zero = (0.0, [0.0; 4], [0.0; 4]);
        let edge_set: std::collections::HashSet<u32> = edges.iter().map(|e| e.index).collect();
        // Sums per row in parallel, then in order: the same sum every run (a parallel reduce
        // adds in the order the threads happen to finish).
        let inner = (0..n)
            .into_par_iter()
            .map(|j| {
                (j * n..(j + 1) * n)
                    .filter(|k| masks[*k] != 0 && !edge_set.contains(&(*k as u32)))
                    .map(|k| at(raster::centre(bounds, dims, k % n, k / n), 1.0))
                    .fold(zero, add)
            })
            .collect::<Vec<_>>()
            .into_iter()
            .fold(zero, add);
        let rim = edges
            .par_iter()
            .map(|e| {
                let (i, j) = (e.index as usize % n, e.index as usize / n);
                let c = raster::centre(bounds, dims, i, j);
                let (dx, dy) = (
                    (bounds[1] - bounds[0]) / n as f64,
                    (bounds[3] - bounds[2]) / n as f64,
                );
                (0..16)
                    .map(|s| {
                        let p = [
                            c[0] + ((s % 4) as f64 * 0.25 - 0.375) * dx,
                            c[1] - ((s / 4) as f64 * 0.25 - 0.375) * dy,
                        ];
                        at(p, 1.0 / 16.0)
                    })
                    .fold(zero, add)
            })
            .collect::<Vec<_>>()
            .into_iter()
            .fold(zero, add);
        add(inner, rim)
    }

    /// Statistics: the volume by Pappus (512 cells, the error from the 256-cell result), per
    /// class volumes, bounds and reach of the section.
    pub fn statistics(&self) -> WorkspaceStats {
        let n = self.scan_cells(512);
        let (v, with, only) = self.pappus(n);
        let (v_half, _, _) = self.pappus(n / 2);
        let e = self.extent(MapView::Side);
        let names = self.class_names();
        let classes = names
            .iter()
            .enumerate()
            .map(|(k, name)| ClassMeasure {
                name: name.clone(),
                with: if names.len() > 1 { with[k] } else { v },
                only: if names.len() > 1 { only[k] } else { v },
            })
            .collect();
        let exact_reach = self.exact_reach();
        let reach = exact_reach.unwrap_or_else(|| self.reach_range(&e));
        let r = e.max[0];
        let base = self.base.translation.vector;
        let bounds = Aabb {
            min: [base.x - r, base.y - r, base.z + e.min[1]],
            max: [base.x + r, base.y + r, base.z + e.max[1]],
        };
        WorkspaceStats {
            planar: false,
            area: None,
            area_both_postures: None,
            volume: Some(v),
            measure_all_classes: 0.0,
            classes,
            dexterous_measure: self.dexterous_volume(&e),
            bounds,
            min_reach: reach[0],
            max_reach: reach[1],
            reach_exact: exact_reach.is_some(),
            cell_size: [0.0; 3],
            resolution: n,
            samples: 0,
            method: GridMethod::ClosedForm {
                family: self.family.into(),
                orientations: if self.exact() { 1 } else { APPROACHES },
            },
            measure_method: format!(
                "Pappus: r times the azimuths joint 1 allows, integrated over the {} (r, z) \
                 section on {n} x {n} cells (edge cells 4 x 4); error from the {}-cell result",
                if self.exact() { "exact" } else { "scanned" },
                n / 2
            ),
            measure_error: Some((v - v_half).abs()),
        }
    }

    /// Smallest and largest distance (m) from the base origin to the workspace, exact from the
    /// section's arcs: the wrist centre's distances fill [m, M] (the workspace is connected, the
    /// image of a connected joint box), M the largest distance to an arc, m 0 when the origin is
    /// reached and otherwise the smallest distance to an arc; the flange's fill the union over
    /// s in [m, M] of [|s - d|, s + d]. `None` without arcs or for the approach scan.
    fn exact_reach(&self) -> Option<[f64; 2]> {
        let arcs = self.arcs.as_ref()?;
        let d = match self.mode {
            Mode::FlangeSphere => self.sphere_radius,
            Mode::Position => 0.0,
            _ => return None,
        };
        let [lo, hi] = arcs.distance_range([0.0, 0.0]);
        let m = if self.position_mask(1e-12 * self.scale, 0.0) != 0 {
            0.0
        } else {
            lo
        };
        let min = if d < m {
            m - d
        } else if d > hi {
            d - hi
        } else {
            0.0
        };
        Some([min, hi + d])
    }

    /// Smallest and largest distance (m) from the base origin over the reached points of a
    /// 256 x 256 scan of the section (cell centres; within a cell of the true values).
    fn reach_range(&self, e: &Aabb) -> [f64; 2] {
        let bounds = [0.0, e.max[0], e.min[1], e.max[1]];
        let n = self.scan_cells(256);
        let dims = [n, n];
        let masks = raster::fill(bounds, dims, &|p| self.side_mask(p[0], p[1]));
        masks
            .iter()
            .enumerate()
            .filter(|(_, m)| **m != 0)
            .map(|(k, _)| {
                let c = raster::centre(bounds, dims, k % n, k / n);
                c[0].hypot(c[1])
            })
            .fold([f64::INFINITY, 0.0], |[lo, hi], d| [lo.min(d), hi.max(d)])
    }

    /// Fraction of the 64 approach directions reached (dexterity), per side-view cell, or per
    /// top-view cell the largest over the heights with joint 1 fitting the azimuth.
    fn dexterity(
        &self,
        view: MapView,
        bounds: [f64; 4],
        dims: [usize; 2],
    ) -> Result<CellValues, WorkspaceError> {
        if !matches!(self.cf.family(), Family::Decoupled6 { .. }) {
            return Err(WorkspaceError::PositionOnly {
                family: self.family.to_string(),
            });
        }
        // At most 256 cells across: the values are smooth, the classes carry the edges.
        let k = (dims[0].max(dims[1]) as f64 / 256.0).max(1.0);
        let dims = [
            ((dims[0] as f64 / k).round() as usize).max(1),
            ((dims[1] as f64 / k).round() as usize).max(1),
        ];
        let d = Dexterity::new(self, bounds, dims, view);
        Ok(CellValues {
            dims,
            data: d.data,
            name: "fraction of the approach directions reached".into(),
            unit: String::new(),
            range: [0.0, 1.0],
            method: format!(
                "closed-form IK over {APPROACHES} approach directions (one roll each) per \
                 (r, z) cell, the wrist decoupled from the arm (Sect. 2.12.2){}",
                if view == MapView::Top {
                    "; top view: largest over 128 heights with joint 1 fitting the azimuth"
                } else {
                    ""
                }
            ),
        })
    }
}

impl Section {
    /// Per branch of joint 1 (its value q1_0 at azimuth 0, NaN for an unused slot) the bit set
    /// of the approach directions with which the flange reaches (r, 0, z) within the limits of
    /// joints 2 to 6.
    fn approach_bits(&self, r: f64, z: f64) -> [(f64, u64); 4] {
        let w = self.base * Point3::new(r, 0.0, z);
        let mut raw = RawSolutions::default();
        let mut out = [(f64::NAN, 0u64); 4];
        for b in 0..APPROACHES {
            let pose = Pose::from_parts(Translation3::from(w.coords), approach(b));
            if self.solve_arm_within(&pose, &mut raw).is_err() {
                continue;
            }
            for k in 0..raw.len {
                if !self.within(&raw.q[k], 1, self.scan_dof) {
                    continue;
                }
                let q1 = raw.q[k][0];
                let same = |o: f64| {
                    let d = (o - q1).rem_euclid(TAU);
                    d.min(TAU - d) < 1e-6
                };
                let slot = out
                    .iter()
                    .position(|o| o.0.is_nan() || same(o.0))
                    .unwrap_or(3);
                out[slot].0 = q1;
                out[slot].1 |= 1 << b;
            }
        }
        out
    }

    /// Volume (m^3) of the dexterous workspace: where at least half of the approach directions
    /// are reached, Pappus over a 48 x 48 section (an estimate; 0 for arms without a wrist).
    fn dexterous_volume(&self, e: &Aabb) -> f64 {
        use rayon::prelude::*;
        if !matches!(self.cf.family(), Family::Decoupled6 { .. }) {
            return 0.0;
        }
        let n = 48;
        let bounds = [0.0, e.max[0], e.min[1], e.max[1]];
        let da = (bounds[1] - bounds[0]) * (bounds[3] - bounds[2]) / (n * n) as f64;
        (0..n * n)
            .into_par_iter()
            .map(|k| {
                let c = raster::centre(bounds, [n, n], k % n, k / n);
                let bits = self.approach_bits(c[0], c[1]);
                let all = bits.iter().fold(0u64, |m, b| m | b.1);
                if (all.count_ones() as usize) * 2 < APPROACHES {
                    return 0.0;
                }
                let hits: Vec<Hit> = bits
                    .iter()
                    .filter(|b| b.0.is_finite())
                    .map(|b| Hit { mask: 1, q1: b.0 })
                    .collect();
                self.azimuths(&hits, 1).0 * c[0] * da
            })
            .collect::<Vec<f64>>()
            .iter()
            .sum()
    }
}

/// Dexterity maps: per (r, z) point and shoulder branch (q1_0), the bit set of approach
/// directions reached.
struct Dexterity {
    data: Vec<f32>,
}

impl Dexterity {
    fn new(s: &Section, bounds: [f64; 4], dims: [usize; 2], view: MapView) -> Self {
        let bits = |r: f64, z: f64| s.approach_bits(r, z);
        let frac = |m: u64| m.count_ones() as f32 / APPROACHES as f32;
        let data = match view {
            MapView::Top => {
                let e = s.extent(MapView::Side);
                let nr = dims[0].max(dims[1]).min(256);
                let nz = 128;
                let table: Vec<Vec<[(f64, u64); 4]>> = {
                    use rayon::prelude::*;
                    (0..nr)
                        .into_par_iter()
                        .map(|i| {
                            let r = (i as f64 + 0.5) / nr as f64 * e.max[0];
                            (0..nz)
                                .map(|j| {
                                    let z = e.min[1]
                                        + (j as f64 + 0.5) / nz as f64 * (e.max[1] - e.min[1]);
                                    bits(r, z)
                                })
                                .collect()
                        })
                        .collect()
                };
                let f = |p: [f64; 2]| {
                    let r = p[0].hypot(p[1]);
                    let psi = p[1].atan2(p[0]);
                    let i = (r / e.max[0] * nr as f64) as usize;
                    let col = table.get(i)?;
                    let best = col
                        .iter()
                        .map(|b| {
                            b.iter()
                                .filter(|(q1, _)| q1.is_finite() && s.q1_fits(*q1, psi))
                                .fold(0u64, |m, (_, x)| m | x)
                        })
                        .max_by_key(|m| m.count_ones())?;
                    (best != 0).then(|| frac(best))
                };
                raster::values(bounds, dims, &f)
            }
            _ => {
                let f = |p: [f64; 2]| {
                    if p[0] < 0.0 {
                        return None;
                    }
                    let m = bits(p[0], p[1]).iter().fold(0u64, |m, (_, x)| m | x);
                    (m != 0).then(|| frac(m))
                };
                raster::values(bounds, dims, &f)
            }
        };
        let _ = PI;
        Self { data }
    }
}

/// Whether the spherical wrist (joints 4 to 6) reaches every orientation: three full-range
/// revolute joints with consecutive axes orthogonal (then they are ZYZ Euler angles, Sect.
/// 2.4.1, which cover every rotation).
fn wrist_is_full(robot: &Robot) -> bool {
    if robot.dof() != 6 {
        return false;
    }
    let limits = robot.limits();
    let full = |k: usize| {
        robot.dof_joint(k).kind == JointKind::Revolute
            && (!(limits[k][0].is_finite() && limits[k][1].is_finite())
                || limits[k][1] - limits[k][0] >= TAU - 1e-12)
    };
    if !(3..6).all(full) {
        return false;
    }
    let Ok(j) = robot.jacobian(&[0.3, -0.4, 0.5, 0.7, -0.6, 0.2], 0) else {
        return false;
    };
    let axis = |k: usize| j.fixed_view::<3, 1>(3, k).into_owned();
    axis(3).dot(&axis(4)).abs() < 1e-9 && axis(4).dot(&axis(5)).abs() < 1e-9
}
