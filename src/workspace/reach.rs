//! Point queries with the closed-form IK (Sect. 2.12): which posture classes reach a position
//! within the joint limits, and how many quantised orientations they reach it with.
//!
//! Orientation bins ([`ORIENTATION_BINS`] = 64): for planar arms the angle phi of the tool x axis
//! in the plane (2.83), 64 sectors of 5.625 degrees; for spatial arms the approach direction
//! a_e (tool z axis, world frame) in 64 equal-area cells of the sphere (8 bands of equal height in
//! z times 8 sectors of longitude).

use super::posture::PostureClassifier;
use super::{PlanarFrame, TrackedPoint, planar_frame};
use crate::kinematics::ik::closed_form::{
    ClosedForm, Family, LIMIT_TOL, MAX_DOF, RawSolutions, wrap_into_limits,
};
use crate::kinematics::{JointKind, Pose, Robot};
use nalgebra::{Matrix3, Rotation3, Translation3, Vector3};
use std::f64::consts::{PI, TAU};

/// Number of orientation bins (see the module documentation).
pub const ORIENTATION_BINS: usize = 64;

/// Bin of an approach direction `a` (unit vector, world frame): band `floor((a_z + 1) / 2 * 8)`
/// (equal areas, Archimedes), sector `floor((atan2(a_y, a_x) + pi) / (2 pi) * 8)`.
pub fn approach_bin(a: [f64; 3]) -> usize {
    let band = (((a[2] + 1.0) * 4.0).floor() as isize).clamp(0, 7) as usize;
    let sector = (((a[1].atan2(a[0]) + PI) / TAU * 8.0).floor() as isize).clamp(0, 7) as usize;
    band * 8 + sector
}

/// The centre of approach bin `k` (unit vector, world frame).
pub fn approach_bin_centre(k: usize) -> [f64; 3] {
    let (band, sector) = (k / 8, k % 8);
    let z = (band as f64 + 0.5) / 4.0 - 1.0;
    let lon = (sector as f64 + 0.5) / 8.0 * TAU - PI;
    let r = (1.0 - z * z).sqrt();
    [r * lon.cos(), r * lon.sin(), z]
}

/// The rotation whose approach (z axis) is the centre of approach bin `k`, its x axis
/// perpendicular to it (world x projected, or y when the approach is near x).
pub(crate) fn approach_rotation(k: usize) -> Rotation3<f64> {
    let a = Vector3::from(approach_bin_centre(k));
    let helper = if a.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let x = (helper - a * a.dot(&helper)).normalize();
    Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[x, a.cross(&x), a]))
}

/// Bin of an in-plane angle phi (rad): `floor((phi + pi) / (2 pi) * 64)` modulo 64.
pub fn phi_bin(phi: f64) -> usize {
    let b = ((phi + PI) / TAU * ORIENTATION_BINS as f64).floor() as isize;
    b.rem_euclid(ORIENTATION_BINS as isize) as usize
}

/// Result of testing one point with [`ReachTester`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Reach {
    /// Bit k set when posture class k reaches the point within the limits.
    pub mask: u8,
    /// Orientations reached (scanned orientations with a solution, or distinct orientation bins
    /// of the solutions of a position-only arm).
    pub reached: u32,
    /// Orientations tried (the scan size, or [`ORIENTATION_BINS`]).
    pub tried: u32,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Mode {
    /// Position-only closed form (two-link planar, 3-DOF spatial arms).
    Position,
    /// Three-link planar arm: phi scanned.
    PlanarScan(usize),
    /// Six-DOF arm with spherical wrist: the 64 approach-bin centres, one roll each.
    ApproachScan,
    /// The wrist centre of a six-DOF arm with a spherical wrist: the positioning arm's
    /// closed form, the wrist joints at [`ReachTester::wrist_reference`].
    WristCentre,
}

/// Decides with the closed-form IK which postures reach a position within the joint limits.
///
/// Supported: two- and three-link planar arms, the anthropomorphic, spherical and cylindrical
/// arms (position), and six-DOF arms with a spherical wrist (a position counts as reached when some
/// approach direction of the 64 bin centres, with the x axis of the tool chosen perpendicular to
/// it, has a solution; the roll about the approach is not scanned, which matters only when the
/// last joint's range is under 2 pi).
///
/// # Examples
///
/// The three-link planar arm (Problem 2.17) at a point: which elbows reach it within the limits,
/// and with how many of 64 orientations phi (the dexterous workspace counts these):
///
/// ```
/// use armlab::kinematics::models::built_in;
/// use armlab::workspace::ReachTester;
///
/// let arm = built_in("planar3").expect("a built-in model");
/// let tester = ReachTester::new(&arm, 64).expect("a closed form");
/// assert_eq!(tester.family(), "three-link planar arm");
/// let near = tester.test_plane([0.6, 0.2]);
/// assert!(near.mask != 0 && near.reached > 0 && near.reached < near.tried);
/// assert_eq!(near.tried, 64);
/// // Beyond a1 + a2 + a3 = 1 m nothing reaches.
/// let far = tester.test_plane([1.1, 0.0]);
/// assert_eq!((far.mask, far.reached), (0, 0));
/// for (k, name) in tester.class_names().iter().enumerate() {
///     println!("{name}: {}", near.mask >> k & 1 == 1);
/// }
/// ```
#[derive(Debug, Clone)]
pub struct ReachTester<'a> {
    robot: &'a Robot,
    cf: ClosedForm,
    classifier: PostureClassifier,
    mode: Mode,
    frame: Option<PlanarFrame>,
    limits: Vec<[f64; 2]>,
    revolute: Vec<bool>,
    /// Tool rotation at the zero configuration, in the base frame (planar scan).
    r0: Matrix3<f64>,
    /// The wrist joints' values of [`Mode::WristCentre`] (rad).
    wrist: [f64; 3],
}

impl<'a> ReachTester<'a> {
    /// A tester for end-effector 0, or `None` when the robot has no supported closed form.
    /// `orientations` is the number of angles phi scanned for a three-link planar arm.
    pub fn new(robot: &'a Robot, orientations: usize) -> Option<Self> {
        if robot.end_effectors().len() != 1 {
            return None;
        }
        let cf = ClosedForm::detect(robot).ok()?;
        let frame = planar_frame(robot, 0);
        let mode = match cf.family() {
            Family::Planar2 => Mode::Position,
            Family::Planar3 => Mode::PlanarScan(orientations.max(1)),
            Family::Anthropomorphic | Family::SphericalArm | Family::Cylindrical => Mode::Position,
            Family::Decoupled6 { .. } => Mode::ApproachScan,
            _ => return None,
        };
        if matches!(cf.family(), Family::Planar2 | Family::Planar3) && frame.is_none() {
            return None;
        }
        let zero: Vec<f64> = vec![0.0; robot.dof()];
        let t0 = robot.fk(&zero).ok()?;
        Some(Self {
            robot,
            classifier: PostureClassifier::new(robot),
            mode,
            frame,
            limits: robot.limits(),
            revolute: (0..robot.dof())
                .map(|k| robot.dof_joint(k).kind == JointKind::Revolute)
                .collect(),
            r0: (robot.base.rotation.inverse() * t0.rotation).into_inner(),
            wrist: [3, 4, 5].map(|k| match robot.limits().get(k) {
                Some(&[lo, hi]) if lo > 0.0 || hi < 0.0 => 0.5 * (lo + hi),
                _ => 0.0,
            }),
            cf,
        })
    }

    /// A tester of `point` for end-effector 0: [`Self::new`] for the flange, and for the wrist
    /// centre of a six-DOF arm with a spherical wrist the positioning arm's closed form (the
    /// wrist joints, which do not move the wrist centre, at [`Self::wrist_reference`]).
    pub fn tracking(robot: &'a Robot, orientations: usize, point: TrackedPoint) -> Option<Self> {
        let mut tester = Self::new(robot, orientations)?;
        if point == TrackedPoint::WristCentre && tester.mode == Mode::ApproachScan {
            tester.mode = Mode::WristCentre;
        }
        Some(tester)
    }

    /// Whether the tester follows the wrist centre of an arm with a spherical wrist (its
    /// configurations hold the wrist joints at [`Self::wrist_reference`]).
    pub fn wrist_centre(&self) -> bool {
        self.mode == Mode::WristCentre
    }

    /// The wrist joints' values (rad) in the configurations of a wrist-centre tester: 0, or
    /// the middle of a joint's range that excludes 0.
    pub fn wrist_reference(&self) -> [f64; 3] {
        self.wrist
    }

    /// Calls `visit(class_mask, q)` for every configuration within the joint limits that puts
    /// the tracked point at world point `p` (m): one per closed-form solution (of each scanned
    /// orientation, for the scanning arms), `q` wrapped into the limits. Stops when `visit`
    /// returns true.
    pub fn visit_world(&self, p: [f64; 3], visit: &mut dyn FnMut(u8, &[f64]) -> bool) {
        let t = Translation3::new(p[0], p[1], p[2]);
        let mut raw = RawSolutions::default();
        let mut q = [0.0; MAX_DOF];
        let mut each = |raw: &RawSolutions, q: &mut [f64; MAX_DOF]| -> bool {
            (0..raw.len).any(|k| {
                self.valid(&raw.q[k], q)
                    && visit(
                        self.classifier.posture_mask(&raw.postures[k]),
                        &q[..self.limits.len()],
                    )
            })
        };
        match self.mode {
            Mode::Position => {
                let pose = Pose::from_parts(t, Rotation3::identity());
                if self.cf.solve_raw(&pose, &mut raw).is_ok() {
                    each(&raw, &mut q);
                }
            }
            Mode::WristCentre => {
                if self
                    .cf
                    .solve_position_raw(&Vector3::new(p[0], p[1], p[2]), &mut raw)
                    .is_ok()
                {
                    for k in 0..raw.len {
                        raw.q[k][3..6].copy_from_slice(&self.wrist);
                    }
                    each(&raw, &mut q);
                }
            }
            Mode::PlanarScan(n) => {
                let base = self.robot.base.rotation.into_inner();
                for k in 0..n {
                    let (s, c) = (k as f64 * TAU / n as f64).sin_cos();
                    let rz = Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0);
                    let r = Rotation3::from_matrix_unchecked(base * rz * self.r0);
                    if self.cf.solve_raw(&Pose::from_parts(t, r), &mut raw).is_ok()
                        && each(&raw, &mut q)
                    {
                        return;
                    }
                }
            }
            Mode::ApproachScan => {
                for k in 0..ORIENTATION_BINS {
                    let pose = Pose::from_parts(t, approach_rotation(k));
                    if self.cf.solve_raw(&pose, &mut raw).is_ok() && each(&raw, &mut q) {
                        return;
                    }
                }
            }
        }
    }

    /// Names of the posture classes (bits of [`Reach::mask`]).
    pub fn class_names(&self) -> &[String] {
        self.classifier.class_names()
    }

    /// The plane of a planar arm.
    pub fn frame(&self) -> Option<&PlanarFrame> {
        self.frame.as_ref()
    }

    /// Name of the closed-form family.
    pub fn family(&self) -> &'static str {
        self.cf.name()
    }

    /// Orientations tried per point (1 for position-only arms).
    pub fn orientations(&self) -> usize {
        match self.mode {
            Mode::Position => 1,
            Mode::PlanarScan(n) => n,
            Mode::ApproachScan => ORIENTATION_BINS,
            Mode::WristCentre => 1,
        }
    }

    /// Tests a point given in plane coordinates (m); planar arms only (else nothing reaches).
    pub fn test_plane(&self, xy: [f64; 2]) -> Reach {
        match self.frame {
            Some(f) => self.test_world(f.to_world(xy)),
            None => Reach::default(),
        }
    }

    /// Tests a world point (m). Allocation-free.
    pub fn test_world(&self, p: [f64; 3]) -> Reach {
        let t = Translation3::new(p[0], p[1], p[2]);
        let mut raw = RawSolutions::default();
        let mut q = [0.0; MAX_DOF];
        let mut out = Reach::default();
        match self.mode {
            Mode::Position => {
                let pose = Pose::from_parts(t, Rotation3::identity());
                let mut bins = 0u64;
                if self.cf.solve_raw(&pose, &mut raw).is_ok() {
                    for k in 0..raw.len {
                        if self.valid(&raw.q[k], &mut q) {
                            out.mask |= self.classifier.posture_mask(&raw.postures[k]);
                            bins |= 1 << self.orientation_bin(&q);
                        }
                    }
                }
                out.reached = bins.count_ones();
                out.tried = ORIENTATION_BINS as u32;
            }
            Mode::PlanarScan(n) => {
                let base = self.robot.base.rotation.into_inner();
                for k in 0..n {
                    let phi = k as f64 * TAU / n as f64;
                    let (s, c) = phi.sin_cos();
                    let rz = Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0);
                    let r = Rotation3::from_matrix_unchecked(base * rz * self.r0);
                    out.reached +=
                        self.scan_one(&Pose::from_parts(t, r), &mut raw, &mut q, &mut out.mask);
                }
                out.tried = n as u32;
            }
            Mode::ApproachScan => {
                for k in 0..ORIENTATION_BINS {
                    let r = approach_rotation(k);
                    out.reached +=
                        self.scan_one(&Pose::from_parts(t, r), &mut raw, &mut q, &mut out.mask);
                }
                out.tried = ORIENTATION_BINS as u32;
            }
            Mode::WristCentre => {
                let mut mask = 0;
                self.visit_world(p, &mut |m, _| {
                    mask |= m;
                    false
                });
                out.mask = mask;
                out.reached = u32::from(mask != 0);
                out.tried = 1;
            }
        }
        out
    }

    /// Solves one pose; 1 if some solution is within the limits (its posture bits into `mask`).
    fn scan_one(
        &self,
        pose: &Pose,
        raw: &mut RawSolutions,
        q: &mut [f64; MAX_DOF],
        mask: &mut u8,
    ) -> u32 {
        if self.cf.solve_raw(pose, raw).is_err() {
            return 0;
        }
        let mut hit = 0;
        for k in 0..raw.len {
            if self.valid(&raw.q[k], q) {
                *mask |= self.classifier.posture_mask(&raw.postures[k]);
                hit = 1;
            }
        }
        hit
    }

    /// Wraps a raw solution into the limits (revolute joints, modulo 2 pi) and checks them.
    #[inline]
    fn valid(&self, raw: &[f64; MAX_DOF], q: &mut [f64; MAX_DOF]) -> bool {
        let n = self.limits.len();
        for k in 0..n {
            q[k] = if self.revolute[k] {
                wrap_into_limits(raw[k], self.limits[k])
            } else {
                raw[k]
            };
        }
        self.robot.within_limits(&q[..n], LIMIT_TOL)
    }

    /// Orientation bin of configuration q: phi in the plane, or the approach direction.
    fn orientation_bin(&self, q: &[f64; MAX_DOF]) -> usize {
        let Ok(t) = self.robot.fk(&q[..self.limits.len()]) else {
            return 0;
        };
        orientation_bin_of(&t, self.frame.as_ref())
    }
}

/// Orientation bin of a tool pose: phi of the tool x axis in the plane (planar) or the approach.
pub(crate) fn orientation_bin_of(t: &Pose, frame: Option<&PlanarFrame>) -> usize {
    let r = t.rotation.matrix();
    match frame {
        Some(f) => {
            let x = f.world_from_base.rotation.inverse()
                * Vector3::new(r[(0, 0)], r[(1, 0)], r[(2, 0)]);
            phi_bin(x.y.atan2(x.x))
        }
        None => approach_bin([r[(0, 2)], r[(1, 2)], r[(2, 2)]]),
    }
}
