//! Closed-form inverse kinematics (Sect. 2.12): every solution, labelled with its posture and
//! flagged inside or outside the joint limits.
//!
//! [`ClosedForm::detect`] recognises a family from the structure of the DH table (joint kinds,
//! twists, which lengths vanish), never from the robot's name, and extracts once the numbers the
//! formulas need; base and tool transforms and joint offsets are handled (the formulas work on
//! `base^-1 * T * tool^-1`, and `theta = q + offset`), and a modified (Craig) DH table is converted
//! exactly to the standard one first. The families:
//!
//! | family | structure | solutions for a generic target |
//! |---|---|---|
//! | [`Family::Planar2`] | R-R, all twists 0 or pi | 2 (elbow down: s2 > 0, elbow up) |
//! | [`Family::Planar3`] | R-R-R, all twists 0 or pi | 2 (same labels) |
//! | [`Family::Scara`] | three R and one P, all twists 0 or pi | 2 (same labels) |
//! | [`Family::Anthropomorphic`] | R-R-R, alpha1 = +-pi/2, alpha2 = 0 or pi | 4 (shoulder right/left x elbow up/down) |
//! | [`Family::SphericalArm`] | R-R-P, alpha1, alpha2 = +-pi/2 | 2 (shoulder right/left, d3 >= 0) |
//! | [`Family::Cylindrical`] | R-P-P, alpha1 = 0 or pi, alpha2 = +-pi/2 | 1 (d3 >= 0) |
//! | [`Family::SphericalWrist`] | R-R-R, a1 = a2 = d2 = 0, alpha1, alpha2 = +-pi/2 | 2 (wrist no flip/flip) |
//! | [`Family::Cartesian`] | P-P-P, the three prismatic axes not in one plane (a gantry) | 1 (a linear system) |
//! | [`Family::Decoupled6`] | one of the four arms + a spherical wrist | arm count x 2 (8 for the Puma 560, 2 for a gantry) |
//! | [`Family::Decoupled6`] with [`ArmKind::General3R`] | any other three revolute joints + a spherical wrist (Pieper's general case) | up to 8 (a quartic's real roots x 2: "branch k, wrist no flip/flip") |
//! | [`Family::ThreeParallel`] | R x 6, axes 2, 3, 4 parallel, a1 = a4 = a5 = a6 = 0, alpha1, alpha4, alpha5 = +-pi/2 (Universal Robots) | 8 (shoulder right/left x elbow up/down x wrist up/down) |
//! | [`Family::ThreeParallelGeneral`] | R x 6, axes 2, 3, 4 parallel, axes 1 and 5 not, any other lengths and twists (IK-Geo's `three_parallel`) | up to 8 (a quartic's real roots x 2 elbows: "elbow up, branch k") |
//! | [`Family::Reversed6`] | R x 6, one of the two six-joint families above when read from the tool back to the base (a spherical wrist at the base; axes 3-5 parallel) | those of the reversed chain ("tool shoulder right, elbow up, base wrist flip") |
//!
//! The spherical and cylindrical arms also have the mirror solution with the opposite extension
//! of the prismatic joint (d3 < 0 for the textbook arm); [`ClosedForm::solve`] returns it only when
//! it lies inside that joint's limits (never for the built-in models), the raw path always.
//!
//! Degenerate targets are reported, not hidden: where a joint is free (wrist point on the axis of
//! joint 1, wrist singularity sin(theta5) = 0, ...) or a posture pair merges (elbow stretched,
//! s3 = 0), one representative per family is returned, its [`IkSolution::free_joints`] say which
//! joints are free, and the status is [`IkStatus::Singular`]. A target outside the workspace gives
//! [`IkStatus::Unreachable`] with the distance to the workspace and no solutions. Cosines are
//! clamped only within [`COS_TOL`] of +-1; [`ClosedForm::solve`] never returns NaN and never panics.

mod arm;
mod arm_general;
mod chain;
mod eigen;
mod family;
mod general6;
mod locked;
mod parallel3;
mod parallel3_general;
mod planar;
mod posture;
mod reversed;
mod solutions;
mod why;
mod wrist;

pub use family::{ArmKind, Family, ReversedOf};
pub use locked::{EXACT_CHECK, LockedArm, MAX_LOCKED_SOLUTIONS};
pub use posture::{
    Elbow, Extension, FreeReason, Posture, SHORT_LEGEND, SHORT_LEGEND_UR, Shoulder, WristFlip,
};
pub use solutions::{Solution, SolutionErrors, Solutions, Verify};
pub use why::NoClosedForm;

use super::{IkError, IkResult, IkSolution, IkStatus, SolutionPosture, Target, check_target};
use crate::kinematics::fk::SharedPrefix;
use crate::kinematics::orientation::wrap_angle;
use crate::kinematics::pose::{Pose, rot_z};
use crate::kinematics::robot::Robot;
use arm::{ArmSol, SpatialArm};
use nalgebra::{Point3, Rotation3, Translation3, Vector3};
use planar::ParallelArm;
use std::f64::consts::TAU;
use wrist::Wrist;

/// A cosine within this distance of +-1 is clamped (the pair of postures merges); beyond it the
/// target is unreachable.
pub const COS_TOL: f64 = 1e-12;
/// How far (m) a target may lie off the plane of a planar arm.
pub const PLANE_TOL: f64 = 1e-9;
/// How far (rad) the z axis of a target may be tilted from z0 for planar arms and the SCARA.
pub const TILT_TOL: f64 = 1e-9;
/// Slack on the joint limits when flagging `within_limits` and wrapping angles into them.
pub const LIMIT_TOL: f64 = 1e-12;
/// Two solutions closer than this (modulo 2 pi for revolute joints) are the same.
pub const DUPLICATE_TOL: f64 = 1e-9;
/// Largest number of joints of a closed-form family.
pub const MAX_DOF: usize = 6;
/// Largest number of raw solutions (a general six-revolute arm: 16).
pub const MAX_SOLUTIONS: usize = 16;

/// Solutions of the allocation-free core ([`ClosedForm::solve_raw`]).
///
/// `q[k][..dof]` is solution k (offsets removed, so it is the joint vector; angles straight from
/// atan2, not wrapped into the limits; no duplicates removal, no limit filtering, mirror
/// extensions included).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RawSolutions {
    /// Joint vectors; entries beyond the robot's dof are 0.
    pub q: [[f64; MAX_DOF]; MAX_SOLUTIONS],
    /// Posture of each solution.
    pub postures: [Posture; MAX_SOLUTIONS],
    /// Number of solutions written.
    pub len: usize,
    /// `Some(distance)` when the target is outside the workspace (then `len` = 0).
    pub unreachable: Option<f64>,
}

impl Default for RawSolutions {
    fn default() -> Self {
        Self {
            q: [[0.0; MAX_DOF]; MAX_SOLUTIONS],
            postures: [Posture::default(); MAX_SOLUTIONS],
            len: 0,
            unreachable: None,
        }
    }
}

impl RawSolutions {
    /// Solutions written, as slices of length `dof`.
    pub fn iter(&self, dof: usize) -> impl Iterator<Item = (&[f64], &Posture)> {
        self.q[..self.len]
            .iter()
            .map(move |q| &q[..dof])
            .zip(&self.postures[..self.len])
    }
}

/// What the core solves for, in the normalised base frame.
enum Goal {
    /// Pose of DH frame n (tool removed).
    Frame(Pose),
    /// Position of the tool point.
    Point(Vector3<f64>),
}

/// The world target, for the honest errors.
enum World {
    Pose(Pose),
    Point(Vector3<f64>),
}

impl World {
    /// The FK check of this target for a robot whose first end-effector holds `tool`.
    fn check(&self, tool: Pose) -> solutions::Check {
        match self {
            World::Pose(t) => solutions::Check::new(tool, Some(t), t.translation.vector),
            World::Point(p) => solutions::Check::new(tool, None, *p),
        }
    }
}

#[derive(Debug, Clone)]
enum Geometry {
    Parallel(ParallelArm),
    Parallel3(parallel3::Parallel3),
    General(Box<general6::General6>),
    Arm(SpatialArm),
    Wrist(Wrist),
    Decoupled {
        arm: SpatialArm,
        wrist: Wrist,
        /// The wrist centre in frame 6: `A_6^-1` applied to the origin of frame 5.
        w6: Vector3<f64>,
    },
    Reversed(Box<reversed::Reversed>),
    Parallel3General(Box<parallel3_general::Parallel3General>),
}

/// A closed-form solver for one robot: the family and the numbers its formulas need, extracted
/// once from the DH table.
#[derive(Debug, Clone)]
pub struct ClosedForm {
    family: Family,
    dof: usize,
    base: Pose,
    base_inv: Pose,
    tool_inv: Pose,
    base_is_identity: bool,
    tool_is_identity: bool,
    offsets: [f64; MAX_DOF],
    revolute: [bool; MAX_DOF],
    /// q index of the prismatic joint whose mirror extension is filtered by the limits.
    mirror_joint: Option<usize>,
    geometry: Geometry,
    /// How far the robot is from the ideal structure solved (`None`: exactly on it).
    near_miss: Option<crate::kinematics::dh_derive::Deviation>,
    /// For [`Family::General6`], why no named family applies.
    not_named: Option<String>,
}

/// Angle tolerance (rad) of a near miss: axes within it of parallel or perpendicular count as
/// such for the closed forms (then polished on the exact model).
pub const NEAR_MISS_ANGLE: f64 = 1e-5;
/// Length tolerance of a near miss, relative to the arm's size: axes whose common normal is
/// shorter meet, lengths below it vanish.
pub const NEAR_MISS_LENGTH: f64 = 1e-5;

impl ClosedForm {
    /// Detects the family from the structure of the DH table (`robot.dh_table()`, joint kinds,
    /// twists, vanishing lengths; base and tool are allowed), never from the robot's name.
    ///
    /// When no family matches (parallelogram, DLR, humanoid, LWR, Panda, most URDF trees) the
    /// error says why in words, e.g. "axes 4-6 do not intersect in one point: a5 = 0.1 m, not 0:
    /// no spherical wrist, so position and orientation do not decouple".
    ///
    /// A chain that misses a family's structure only by CAD rounding or calibration (axes
    /// parallel, perpendicular or meeting to within [`NEAR_MISS_ANGLE`] rad and
    /// [`NEAR_MISS_LENGTH`] times the arm's size) gets the family of its ideal structure
    /// ([`ClosedForm::near_miss`] says by how much): its branches are solved on the ideal
    /// structure and [`crate::kinematics::ik::solver::solve`] polishes each by Newton on the
    /// exact model, keeping only those that forward kinematics confirms to 1e-12.
    ///
    /// Any other six-revolute chain gets [`Family::General6`]: every real solution by
    /// elimination.
    ///
    /// # Examples
    ///
    /// ```
    /// use armlab::kinematics::ik::closed_form::{ArmKind, ClosedForm, Family, NoClosedForm};
    /// use armlab::kinematics::models::built_in;
    ///
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// let puma = built_in("puma560").expect("a built-in model");
    /// let cf = ClosedForm::detect(&puma)?;
    /// assert!(matches!(cf.family(), Family::Decoupled6 { arm: ArmKind::Anthropomorphic }));
    /// assert!(cf.near_miss().is_none());
    /// println!("{}", cf.describe()); // "anthropomorphic arm with spherical wrist"
    ///
    /// // Of the four-joint arms only the SCARA has a closed form: the error says why, in words.
    /// let planar4 = built_in("planar4").expect("a built-in model");
    /// let why = ClosedForm::detect(&planar4).unwrap_err();
    /// assert!(matches!(why, NoClosedForm::Geometry { .. }));
    /// assert!(why.to_string().starts_with("4 joints: only the SCARA"));
    /// println!("{why}");
    /// # Ok(())
    /// # }
    /// ```
    pub fn detect(robot: &Robot) -> Result<ClosedForm, NoClosedForm> {
        if let Some(cf) = Self::detect_family(robot, false) {
            return Ok(cf);
        }
        match Self::detect_near_miss(robot) {
            Ok(cf) => Ok(cf),
            Err(why) => match Self::detect_family(robot, true) {
                Some(mut cf) => {
                    cf.not_named = Some(why.to_string());
                    Ok(cf)
                }
                None => Self::general_near_miss(robot)
                    .ok_or(why.clone())
                    .map(|mut cf| {
                        cf.not_named = Some(why.to_string());
                        cf
                    }),
            },
        }
    }

    /// The elimination on the ideal structure of a six-revolute chain whose exact axes have no
    /// DH table (axes 7e-6 rad from parallel put the common normal 38 km away: the Kinova Gen3
    /// lite's URDF), its solutions polished on the exact model as for any near miss.
    fn general_near_miss(robot: &Robot) -> Option<ClosedForm> {
        let (ideal, dev) = Self::ideal_robot(robot)?;
        if dev.length == 0.0 && dev.angle == 0.0 {
            return None;
        }
        let mut cf = Self::detect_family(&ideal, true)?;
        cf.near_miss = Some(dev);
        Some(cf)
    }

    /// The family of the robot's ideal structure, for a chain that misses it by rounding; the
    /// reason it has none otherwise.
    fn detect_near_miss(robot: &Robot) -> Result<ClosedForm, NoClosedForm> {
        let why = why::diagnose(robot);
        let Some(ideal) = Self::ideal_robot(robot) else {
            return Err(why);
        };
        // Only a chain that was rounded is a near miss (an ideal equal to the chain is the
        // chain, and its refusal stands).
        let rounded = ideal.1.length > 0.0 || ideal.1.angle > 0.0;
        match Self::detect_family(&ideal.0, false) {
            Some(mut cf) if rounded => {
                cf.near_miss = Some(ideal.1);
                Ok(cf)
            }
            // An exact chain too ill-conditioned for a DH table: say what its ideal
            // structure lacks.
            None if matches!(why, NoClosedForm::NoDhTable(_)) => Err(why::diagnose(&ideal.0)),
            _ => Err(why),
        }
    }

    /// The robot of `robot`'s ideal structure (a near miss rounded, see [`Self::detect`]) and
    /// how far it is; `None` for a robot with several end-effectors or beyond the tolerance.
    fn ideal_robot(robot: &Robot) -> Option<(Robot, crate::kinematics::dh_derive::Deviation)> {
        if robot.end_effectors().len() != 1 {
            return None;
        }
        let length_tol = NEAR_MISS_LENGTH * robot.characteristic_length();
        let (ideal, dev) =
            crate::kinematics::dh_derive::derive_ideal_dh(robot, 0, NEAR_MISS_ANGLE, length_tol)
                .ok()?;
        Some((ideal.robot(&robot.name).ok()?, dev))
    }

    /// How far the robot is from the ideal structure its family was detected on (`None` when
    /// it has that structure exactly).
    pub fn near_miss(&self) -> Option<&crate::kinematics::dh_derive::Deviation> {
        self.near_miss.as_ref()
    }

    /// For a general six-revolute arm, why none of the named families applies, e.g. "axes 4-6
    /// do not intersect in one point: a5 = 0.1 m, ...".
    pub fn not_named(&self) -> Option<&str> {
        self.not_named.as_deref()
    }

    /// The family's name, and for a near miss how near, e.g. "anthropomorphic arm with
    /// spherical wrist (ideal structure: axes meet within 3.0e-7 m, twists within 2.8e-10 rad;
    /// solutions polished on the exact model)".
    pub fn describe(&self) -> String {
        match &self.near_miss {
            None => self.name().to_string(),
            Some(d) => format!(
                "{} (ideal structure: axes meet within {:.1e} m, twists within {:.1e} rad, \
                 pose within {:.1e} m; solutions polished on the exact model)",
                self.name(),
                d.length,
                d.angle,
                d.pose
            ),
        }
    }

    /// The family of the exact chain, read from the base to the tool only (no
    /// [`Family::Reversed6`], no elimination): the reversed chain's own detection.
    fn detect_forward(robot: &Robot) -> Option<ClosedForm> {
        Self::detect_chain(robot, false, false)
    }

    /// The family of the exact chain; the general six-revolute elimination only if `general`.
    fn detect_family(robot: &Robot, general: bool) -> Option<ClosedForm> {
        Self::detect_chain(robot, general, true)
    }

    /// [`Self::detect_family`], the chain also read from the tool back to the base if `reverse`.
    fn detect_chain(robot: &Robot, general: bool, reverse: bool) -> Option<ClosedForm> {
        let chain = chain::normalize(robot)?;
        let rows = &chain.rows;
        let n = rows.len();
        let tol = 1e-12 * chain.scale();
        let (family, geometry) = match n {
            2..=4 => {
                if let Some(p) = ParallelArm::detect(&chain, tol) {
                    let family = match (p.m, p.prismatic.is_some(), n) {
                        (2, false, 2) => Family::Planar2,
                        (3, false, 3) => Family::Planar3,
                        (3, true, 4) => Family::Scara,
                        _ => return None,
                    };
                    (family, Geometry::Parallel(p))
                } else if n != 3 {
                    return None;
                } else if let Some(a) =
                    SpatialArm::detect(rows, &chain.tool.translation.vector, tol)
                {
                    let family = match a.kind {
                        ArmKind::Anthropomorphic => Family::Anthropomorphic,
                        ArmKind::Spherical => Family::SphericalArm,
                        ArmKind::Cylindrical => Family::Cylindrical,
                        ArmKind::Cartesian => Family::Cartesian,
                        // detect() finds only the named arms.
                        ArmKind::General3R => return None,
                    };
                    (family, Geometry::Arm(a))
                } else {
                    let w = Wrist::detect(rows, tol)?;
                    (Family::SphericalWrist, Geometry::Wrist(w))
                }
            }
            6 => Self::six_revolute(rows, tol, general, reverse)?,
            _ => return None,
        };
        let mirror_joint = match &geometry {
            Geometry::Arm(a) | Geometry::Decoupled { arm: a, .. }
                if matches!(a.kind, ArmKind::Spherical | ArmKind::Cylindrical) =>
            {
                Some(2)
            }
            _ => None,
        };
        let mut offsets = [0.0; MAX_DOF];
        let mut revolute = [false; MAX_DOF];
        for (i, r) in rows.iter().enumerate() {
            offsets[i] = r.offset;
            revolute[i] = r.revolute;
        }
        Some(ClosedForm {
            family,
            dof: n,
            base: chain.base,
            base_inv: chain.base.inverse(),
            tool_inv: chain.tool.inverse(),
            base_is_identity: chain.base == Pose::identity(),
            tool_is_identity: chain.tool == Pose::identity(),
            offsets,
            revolute,
            mirror_joint,
            geometry,
            near_miss: None,
            not_named: None,
        })
    }

    /// The family of six rows, in order: the UR structure, a spherical wrist, three parallel
    /// axes 2-4, the chain read from the tool (if `reverse`), the elimination (if `general`).
    fn six_revolute(
        rows: &[chain::Row],
        tol: f64,
        general: bool,
        reverse: bool,
    ) -> Option<(Family, Geometry)> {
        if let Some(g) = parallel3::Parallel3::detect(rows, tol) {
            return Some((Family::ThreeParallel, Geometry::Parallel3(g)));
        }
        if let Some(d) = Self::decoupled(rows, tol) {
            return Some(d);
        }
        if let Some(g) = parallel3_general::Parallel3General::detect(rows, tol) {
            return Some((
                Family::ThreeParallelGeneral,
                Geometry::Parallel3General(Box::new(g)),
            ));
        }
        if let Some(r) = reverse.then(|| reversed::Reversed::detect(rows)).flatten() {
            let of = match r.inner.family {
                Family::Decoupled6 { arm } => ReversedOf::Decoupled(arm),
                Family::ThreeParallelGeneral => ReversedOf::ThreeParallelGeneral,
                _ => ReversedOf::ThreeParallel,
            };
            return Some((Family::Reversed6 { of }, Geometry::Reversed(Box::new(r))));
        }
        if general {
            let g = general6::General6::detect(rows)?;
            return Some((Family::General6, Geometry::General(Box::new(g))));
        }
        None
    }

    /// A six-DOF arm with a spherical wrist (Sect. 2.12.2).
    fn decoupled(rows: &[chain::Row], tol: f64) -> Option<(Family, Geometry)> {
        let wrist = Wrist::detect(&rows[3..], tol)?;
        // Wrist centre W = origin of frame 4 = (0, 0, d4) in frame 3 (a4 = 0).
        let w3 = Vector3::new(0.0, 0.0, rows[3].d);
        let arm = SpatialArm::detect_any(&rows[..3], &w3, tol)?;
        let r6 = rows[5];
        let w6 = Vector3::new(-r6.a, -r6.sa * r6.d, -r6.ca * r6.d);
        Some((
            Family::Decoupled6 { arm: arm.kind },
            Geometry::Decoupled { arm, wrist, w6 },
        ))
    }

    /// The family.
    pub fn family(&self) -> &Family {
        &self.family
    }

    /// Human-readable name of the family.
    pub fn name(&self) -> &'static str {
        self.family.name()
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.dof
    }

    /// The wrist centre in the tool frame (m) of a six-DOF arm with a spherical wrist (`None`
    /// for other families): the point the wrist turns the tool about, so that the tool point
    /// lies on a sphere of radius `|c|` about the wrist centre whatever the wrist joints.
    pub fn wrist_centre_in_tool(&self) -> Option<Vector3<f64>> {
        match &self.geometry {
            Geometry::Decoupled { w6, .. } => Some((self.tool_inv * Point3::from(*w6)).coords),
            _ => None,
        }
    }

    /// Every solution for the target, each labelled with its posture, revolute angles wrapped
    /// modulo 2 pi into the limits where possible (otherwise into (-pi, pi]), with
    /// `within_limits`, `position_error` and `orientation_error` computed by forward kinematics
    /// of `robot` (so they are honest), duplicates (modulo 2 pi, [`DUPLICATE_TOL`]) removed.
    ///
    /// Targets: planar arms take a [`Target::Planar`] (x, y and phi in the base frame's x-y
    /// plane), a [`Target::Pose`] whose z axis is along z0 or a [`Target::Position`] (two-link
    /// arm only) in the arm's plane (otherwise [`IkError::TargetKind`]); the three-DOF spatial arms
    /// take a position, or the position of a pose; the SCARA, the wrist and the six-DOF arms a
    /// pose. Where a target asks more than the family controls (phi for a two-link arm, the
    /// orientation of a pose for a positioning arm, the position for the wrist alone), the
    /// controlled part is solved and the error of the rest is reported honestly in
    /// `position_error` / `orientation_error`.
    ///
    /// Unreachable targets give [`IkStatus::Unreachable`] with no solutions; the distance is the
    /// gap to the workspace in the plane of the arm (|p_W| - (a2 + a3) for the anthropomorphic
    /// arm, the gap to the annulus for planar arms, the gap to the cylinder of the lateral offset
    /// for a Puma-like shoulder), or the tilt angle (rad) of a pose a SCARA cannot orient.
    ///
    /// # Examples
    ///
    /// The two-link planar arm (a1 = a2 = 1 m) reaching (1, 1) m: the elbow at (1, 0) with
    /// q = (0, pi/2), or at (0, 1) with q = (pi/2, -pi/2) (Sect. 2.12.1).
    ///
    /// ```
    /// use armlab::kinematics::ik::{ClosedForm, IkStatus, Target};
    /// use armlab::kinematics::models::built_in;
    /// use armlab::nalgebra::Vector3;
    /// use std::f64::consts::FRAC_PI_2;
    ///
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// let arm = built_in("planar2").expect("a built-in model");
    /// let cf = ClosedForm::detect(&arm)?;
    /// let result = cf.solve(&arm, &Target::Position(Vector3::new(1.0, 1.0, 0.0)))?;
    /// assert_eq!(result.status, IkStatus::Ok);
    /// assert_eq!(result.solutions.len(), 2);
    /// for s in &result.solutions {
    ///     let label = s.posture.to_string();
    ///     let expected = if label == "elbow down" { [0.0, FRAC_PI_2] } else { [FRAC_PI_2, -FRAC_PI_2] };
    ///     assert!((s.q[0] - expected[0]).abs() < 1e-12 && (s.q[1] - expected[1]).abs() < 1e-12);
    ///     assert!(s.within_limits && s.position_error < 1e-12);
    /// }
    /// # Ok(())
    /// # }
    /// ```
    ///
    /// A point out of reach is not an error: the status says by how much it misses.
    ///
    /// ```
    /// use armlab::kinematics::ik::{ClosedForm, IkStatus, Target};
    /// use armlab::kinematics::models::built_in;
    /// use armlab::nalgebra::Vector3;
    ///
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// let arm = built_in("planar2").expect("a built-in model");
    /// let cf = ClosedForm::detect(&arm)?;
    /// let far = cf.solve(&arm, &Target::Position(Vector3::new(3.0, 0.0, 0.0)))?;
    /// let IkStatus::Unreachable { distance } = far.status else { panic!("reachable?") };
    /// assert!((distance - 1.0).abs() < 1e-12); // 3 m from the base, the arm reaches 2 m
    /// assert!(far.solutions.is_empty());
    /// # Ok(())
    /// # }
    /// ```
    pub fn solve(&self, robot: &Robot, target: &Target) -> Result<IkResult, IkError> {
        let mut out = Solutions::default();
        self.solve_into(robot, target, Verify::Fk, &mut out)?;
        let solutions = out
            .iter()
            .map(|s| {
                let e = s.errors.unwrap_or_default();
                IkSolution {
                    q: s.q().to_vec(),
                    posture: SolutionPosture::ClosedForm(s.posture),
                    within_limits: s.within_limits,
                    position_error: e.position,
                    orientation_error: e.orientation,
                    free_joints: s.posture.free_joints(),
                }
            })
            .collect();
        Ok(IkResult {
            status: out.status,
            solutions,
        })
    }

    /// Every solution for the target into `out`, labelled and flagged as [`Self::solve`] does,
    /// without allocating: postures stay [`Posture`] values (their `Display` is the label),
    /// revolute angles are wrapped into the limits, `within_limits` is set and duplicates are
    /// removed in the same pass; with [`Verify::Fk`] each solution is also checked by the
    /// robot's forward kinematics. `out` is cleared first; its `status` is set as in
    /// [`IkResult::status`].
    ///
    /// # Examples
    ///
    /// The anthropomorphic arm (Sect. 2.12.4) has four postures for a point; one buffer serves
    /// a whole trajectory, with no allocation per point:
    ///
    /// ```
    /// use armlab::kinematics::ik::Target;
    /// use armlab::kinematics::ik::closed_form::{ClosedForm, Solutions, Verify};
    /// use armlab::kinematics::models::built_in;
    ///
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// let arm = built_in("anthropomorphic3r").expect("a built-in model");
    /// let cf = ClosedForm::detect(&arm)?;
    /// let mut out = Solutions::default();
    /// for k in 0..10 {
    ///     let q = [0.1 * k as f64, 0.3, -0.8];
    ///     let p = arm.fk(&q)?.translation.vector;
    ///     cf.solve_into(&arm, &Target::Position(p), Verify::Limits, &mut out)?;
    ///     assert_eq!(out.len(), 4);
    ///     // Verify::Limits skips the forward-kinematics check: errors stay None.
    ///     assert!(out.iter().all(|s| s.errors.is_none()));
    ///     // The configuration the point came from is one of the four.
    ///     assert!(out.iter().any(|s| s.q().iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-9)));
    /// }
    /// # Ok(())
    /// # }
    /// ```
    pub fn solve_into(
        &self,
        robot: &Robot,
        target: &Target,
        verify: Verify,
        out: &mut Solutions,
    ) -> Result<(), IkError> {
        out.clear();
        check_target(target)?;
        if robot.dof() != self.dof {
            return Err(IkError::OtherRobot {
                dof: self.dof,
                family: self.name(),
                robot_dof: robot.dof(),
            });
        }
        let (goal, world) = self.prepare(target)?;
        let mut raw = RawSolutions::default();
        self.core(&goal, &mut raw)?;
        if let Some(d) = raw.unreachable {
            let distance = if d.is_nan() {
                f64::INFINITY
            } else {
                d.max(0.0)
            };
            out.status = IkStatus::Unreachable { distance };
            return Ok(());
        }
        let dof = self.dof;
        let mut limits = [[0.0; 2]; MAX_DOF];
        for (k, l) in limits[..dof].iter_mut().enumerate() {
            *l = robot.dof_joint(k).limits;
        }
        let mut singular = false;
        // The two wrist solutions of an arm branch share joints 1-3: their frame is reused.
        let mut shared = SharedPrefix::new(if self.dof == 6 { 3 } else { 0 });
        let check = (verify == Verify::Fk).then(|| world.check(robot.end_effectors()[0].tool));
        for (q_raw, posture) in raw.q[..raw.len].iter().zip(&raw.postures) {
            let Some((q, within)) = self.wrap_solution(q_raw, &limits) else {
                continue;
            };
            if posture.extension == Some(Extension::Reversed)
                && let Some(j) = self.mirror_joint
                && !(q[j] >= limits[j][0] - LIMIT_TOL && q[j] <= limits[j][1] + LIMIT_TOL)
            {
                continue;
            }
            // Two solutions of different branches can coincide only where a pair of postures
            // merges or a joint is free (the flags are set within COS_TOL, i.e. ~1e-6 rad, far
            // above DUPLICATE_TOL), so only then are they compared.
            let degenerate = posture.is_degenerate();
            if (degenerate || singular)
                && out
                    .iter()
                    .any(|s| same_configuration_fast(s.q(), &q[..dof], &self.revolute[..dof]))
            {
                continue;
            }
            let mut s = Solution::new(q, dof, *posture);
            s.within_limits = within;
            if let Some(check) = &check {
                s.errors = Some(check.errors(&robot.fk_ee_shared(&q[..dof], 0, &mut shared)?));
            }
            singular |= degenerate;
            out.push(s);
        }
        out.status = if out.is_empty() {
            IkStatus::Unreachable {
                distance: f64::INFINITY,
            }
        } else if singular {
            IkStatus::Singular
        } else {
            IkStatus::Ok
        };
        Ok(())
    }

    /// A raw solution with its revolute angles wrapped into the limits, and whether it lies
    /// inside them; `None` if it has a non-finite entry.
    #[inline]
    fn wrap_solution(
        &self,
        q_raw: &[f64; MAX_DOF],
        limits: &[[f64; 2]; MAX_DOF],
    ) -> Option<([f64; MAX_DOF], bool)> {
        let mut q = [0.0; MAX_DOF];
        let mut within = true;
        for i in 0..self.dof {
            let v = q_raw[i];
            if !v.is_finite() {
                return None;
            }
            let [lo, hi] = limits[i];
            let w = if self.revolute[i] {
                wrap_into_limits(v, [lo, hi])
            } else {
                v
            };
            within &= w >= lo - LIMIT_TOL && w <= hi + LIMIT_TOL;
            q[i] = w;
        }
        Some((q, within))
    }

    /// The allocation-free core for a pose target `world_from_tool`: every solution (up to 8)
    /// with its posture into `out`, returning the count. No wrapping into the limits, no
    /// duplicate removal, no FK check (see [`RawSolutions`]). For position-only families the
    /// position of the pose is used.
    ///
    /// # Examples
    ///
    /// The eight raw solutions of the Puma 560, each checked here by forward kinematics:
    ///
    /// ```
    /// use armlab::kinematics::ik::closed_form::{ClosedForm, RawSolutions};
    /// use armlab::kinematics::models::built_in;
    ///
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// let puma = built_in("puma560").expect("a built-in model");
    /// let cf = ClosedForm::detect(&puma)?;
    /// let target = puma.fk(&[0.3, -0.5, 0.2, 0.4, 0.9, -0.1])?;
    /// let mut raw = RawSolutions::default();
    /// let n = cf.solve_raw(&target, &mut raw)?;
    /// assert_eq!(n, 8);
    /// for (q, posture) in raw.iter(puma.dof()) {
    ///     let t = puma.fk(q)?;
    ///     let gap = (t.to_homogeneous() - target.to_homogeneous()).amax();
    ///     assert!(gap < 1e-12, "{posture}: {gap}");
    /// }
    /// # Ok(())
    /// # }
    /// ```
    pub fn solve_raw(
        &self,
        world_from_tool: &Pose,
        out: &mut RawSolutions,
    ) -> Result<usize, IkError> {
        let goal = self.goal_of_pose(world_from_tool);
        self.core(&goal, out)?;
        Ok(out.len)
    }

    /// [`Self::solve_raw`] that goes on to the wrist only for the positioning solutions `keep`
    /// accepts (q1..q3 in rad or m, joint offsets removed, as in `out`): a workspace scan skips
    /// the wrist's trigonometry where the arm is already outside its limits. Families without a
    /// separate positioning arm give every solution and do not call `keep`.
    pub fn solve_raw_where(
        &self,
        world_from_tool: &Pose,
        out: &mut RawSolutions,
        keep: impl Fn(&[f64; 3]) -> bool,
    ) -> Result<usize, IkError> {
        let goal = self.goal_of_pose(world_from_tool);
        self.core_where(&goal, out, keep)?;
        Ok(out.len)
    }

    /// Solves the positioning arm alone for a world position: the tool point of a 3-DOF
    /// position family (anthropomorphic, spherical, cylindrical arm), or the **wrist centre** of a
    /// six-DOF arm with a spherical wrist (Sect. 2.12.2: the wrist centre depends on the first
    /// three joints only). Writes q1..q3 (rad or m, joint offsets removed, not wrapped, the other
    /// entries 0) and their postures into `out`; allocation-free. Other families: `TargetKind`.
    ///
    /// # Examples
    ///
    /// Kinematic decoupling (Sect. 2.12.2): the Puma's wrist centre depends on q1..q3 alone, and
    /// every one of the four arm solutions puts it in place.
    ///
    /// ```
    /// use armlab::kinematics::ik::closed_form::{ClosedForm, RawSolutions};
    /// use armlab::kinematics::models::built_in;
    /// use armlab::nalgebra::Point3;
    ///
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// let puma = built_in("puma560").expect("a built-in model");
    /// let cf = ClosedForm::detect(&puma)?;
    /// let centre_in_tool = cf.wrist_centre_in_tool().expect("a spherical wrist");
    /// let q = [0.3, -0.5, 0.2, 0.4, 0.9, -0.1];
    /// let centre = (puma.fk(&q)? * Point3::from(centre_in_tool)).coords;
    /// let mut raw = RawSolutions::default();
    /// assert_eq!(cf.solve_position_raw(&centre, &mut raw)?, 4);
    /// for (arm_q, _) in raw.iter(6) {
    ///     // Any wrist angles: the centre stays put.
    ///     let q_any = [arm_q[0], arm_q[1], arm_q[2], 1.0, -0.5, 2.0];
    ///     let c = (puma.fk(&q_any)? * Point3::from(centre_in_tool)).coords;
    ///     assert!((c - centre).norm() < 1e-12);
    /// }
    /// # Ok(())
    /// # }
    /// ```
    pub fn solve_position_raw(
        &self,
        world_point: &Vector3<f64>,
        out: &mut RawSolutions,
    ) -> Result<usize, IkError> {
        let arm = match &self.geometry {
            Geometry::Arm(a) | Geometry::Decoupled { arm: a, .. } => a,
            _ => {
                return Err(IkError::TargetKind {
                    target: "position",
                    solver: self.name(),
                    hint: "it has no positioning arm solved apart",
                });
            }
        };
        out.len = 0;
        out.unreachable = None;
        let local = (self.base_inv * Point3::from(*world_point)).coords;
        let mut sols = [ArmSol::default(); 4];
        match arm.solve(&local, &mut sols) {
            Ok(n) => {
                for (k, s) in sols[..n].iter().enumerate() {
                    out.q[k] = [
                        s.v[0] - self.offsets[0],
                        s.v[1] - self.offsets[1],
                        s.v[2] - self.offsets[2],
                        0.0,
                        0.0,
                        0.0,
                    ];
                    out.postures[k] = s.posture;
                }
                out.len = n;
            }
            Err(d) => out.unreachable = Some(d),
        }
        Ok(out.len)
    }

    fn goal_of_pose(&self, t: &Pose) -> Goal {
        if self.family.uses_frame() {
            let mut f = *t;
            if !self.base_is_identity {
                f = self.base_inv * f;
            }
            if !self.tool_is_identity {
                f *= self.tool_inv;
            }
            Goal::Frame(f)
        } else {
            Goal::Point((self.base_inv * Point3::from(t.translation.vector)).coords)
        }
    }

    fn prepare(&self, target: &Target) -> Result<(Goal, World), IkError> {
        match *target {
            Target::Pose(t) => Ok((self.goal_of_pose(&t), World::Pose(t))),
            Target::Position(p) => {
                if self.family.uses_frame() {
                    return Err(IkError::TargetKind {
                        target: "position",
                        solver: self.name(),
                        hint: match self.family {
                            Family::Planar3 => {
                                "the three-link planar arm is redundant for a position; give a \
                                 planar target (px, py, phi) or a pose whose z axis is along z0"
                            }
                            Family::SphericalWrist => "the wrist needs an orientation: give a pose",
                            _ => "a position does not determine it: give a pose target",
                        },
                    });
                }
                let local = self.base_inv * Point3::from(p);
                Ok((Goal::Point(local.coords), World::Point(p)))
            }
            Target::Planar { px, py, phi } => {
                let Geometry::Parallel(arm) = &self.geometry else {
                    return Err(IkError::TargetKind {
                        target: "planar (px, py, phi)",
                        solver: self.name(),
                        hint: "a planar target needs a planar arm",
                    });
                };
                if arm.prismatic.is_some() {
                    return Err(IkError::TargetKind {
                        target: "planar (px, py, phi)",
                        solver: self.name(),
                        hint: "a planar target has no z: give a pose target",
                    });
                }
                // The tool pose in the base frame with psi_n = phi - phi0.
                let r0 = arm.tool_rot0;
                let (cx, cy) = (r0[(0, 0)], r0[(1, 0)]);
                if cx.hypot(cy) < 1e-9 {
                    return Err(IkError::TargetKind {
                        target: "planar (px, py, phi)",
                        solver: self.name(),
                        hint: "the tool x axis is perpendicular to the arm plane, so phi is \
                               undefined: give a pose target",
                    });
                }
                let rot = rot_z(phi - cy.atan2(cx)).rotation.matrix() * r0;
                let local = Pose::from_parts(
                    Translation3::new(px, py, arm.z_tool),
                    Rotation3::from_matrix_unchecked(rot),
                );
                let t = self.base * local;
                Ok((self.goal_of_pose(&t), World::Pose(t)))
            }
        }
    }

    fn core(&self, goal: &Goal, out: &mut RawSolutions) -> Result<(), IkError> {
        self.core_where(goal, out, |_| true)
    }

    /// [`Self::core`], the wrist solved only for the positioning solutions `keep` accepts (see
    /// [`Self::solve_raw_where`]).
    fn core_where(
        &self,
        goal: &Goal,
        out: &mut RawSolutions,
        keep: impl Fn(&[f64; 3]) -> bool,
    ) -> Result<(), IkError> {
        out.len = 0;
        out.unreachable = None;
        match (&self.geometry, goal) {
            (Geometry::Parallel(p), g) => p.solve(g, out)?,
            (Geometry::Arm(a), Goal::Point(p)) => {
                let mut sols = [ArmSol::default(); 4];
                match a.solve(p, &mut sols) {
                    Ok(n) => {
                        for (k, s) in sols[..n].iter().enumerate() {
                            out.q[k] = [s.v[0], s.v[1], s.v[2], 0.0, 0.0, 0.0];
                            out.postures[k] = s.posture;
                        }
                        out.len = n;
                    }
                    Err(d) => out.unreachable = Some(d),
                }
            }
            (Geometry::Wrist(w), Goal::Frame(t)) => wrist_raw(w, t, out),
            (Geometry::Parallel3(g), Goal::Frame(t)) => g.solve_raw(t, out),
            (Geometry::General(g), Goal::Frame(t)) => general_raw(g, t, out)?,
            (Geometry::Reversed(r), Goal::Frame(t)) => r.solve(t, out)?,
            (Geometry::Parallel3General(g), Goal::Frame(t)) => g.solve_raw(t, out),
            (Geometry::Decoupled { arm, wrist, w6 }, Goal::Frame(t)) => {
                let r6 = t.rotation.matrix();
                // p_W = p_e - d6 a_e (2.93), generalised to a6, alpha6.
                let pw = t.translation.vector + r6 * w6;
                let mut arms = [ArmSol::default(); 4];
                let na = match arm.solve(&pw, &mut arms) {
                    Ok(n) => n,
                    Err(d) => {
                        out.unreachable = Some(d);
                        return Ok(());
                    }
                };
                for a in &arms[..na] {
                    let o = &self.offsets;
                    if !keep(&[a.v[0] - o[0], a.v[1] - o[1], a.v[2] - o[2]]) {
                        continue;
                    }
                    // R_6^3 = (R_3^0)^T R_e
                    let r36 = arm.rotation(&a.v).transpose() * r6;
                    let mut ws = [[0.0; 3]; 2];
                    let (nw, singular) = wrist.solve(&r36, &mut ws);
                    for (i, w) in ws[..nw].iter().enumerate() {
                        let k = out.len;
                        out.q[k] = [a.v[0], a.v[1], a.v[2], w[0], w[1], w[2]];
                        let mut posture = a.posture;
                        posture.wrist = Some(wrist_posture(singular, i));
                        if singular {
                            posture.free[3] = Some(FreeReason::WristAligned);
                        }
                        out.postures[k] = posture;
                        out.len += 1;
                    }
                }
            }
            _ => {
                return Err(IkError::TargetKind {
                    target: "position",
                    solver: self.name(),
                    hint: "give a pose target",
                });
            }
        }
        for q in &mut out.q[..out.len] {
            for (v, off) in q.iter_mut().zip(&self.offsets) {
                *v -= off;
            }
        }
        Ok(())
    }
}

/// The spherical wrist alone (Sect. 2.12.5) into the raw solutions.
fn wrist_raw(w: &Wrist, t: &Pose, out: &mut RawSolutions) {
    let mut ws = [[0.0; 3]; 2];
    let (n, singular) = w.solve(t.rotation.matrix(), &mut ws);
    for (k, v) in ws[..n].iter().enumerate() {
        out.q[k] = [v[0], v[1], v[2], 0.0, 0.0, 0.0];
        let mut posture = Posture {
            wrist: Some(wrist_posture(singular, k)),
            ..Posture::default()
        };
        if singular {
            posture.free[0] = Some(FreeReason::WristAligned);
        }
        out.postures[k] = posture;
    }
    out.len = n;
}

/// The general six-revolute elimination into the raw solutions ("branch k" in its order); an
/// unreachable pose has no distance to report (NaN).
fn general_raw(g: &general6::General6, t: &Pose, out: &mut RawSolutions) -> Result<(), IkError> {
    let mut sols = [[0.0; 6]; general6::MAX_BRANCHES];
    match g.solve(t, &mut sols) {
        Ok(0) => out.unreachable = Some(f64::NAN),
        Ok(n) => {
            for (k, q) in sols[..n].iter().enumerate() {
                out.q[k] = *q;
                out.postures[k] = general6::branch_posture(k);
            }
            out.len = n;
        }
        Err(why) => {
            return Err(IkError::Degenerate { reason: why.text() });
        }
    }
    Ok(())
}

fn wrist_posture(singular: bool, k: usize) -> WristFlip {
    if singular {
        WristFlip::Singular
    } else if k == 0 {
        WristFlip::NoFlip
    } else {
        WristFlip::Flip
    }
}

/// `q + 2 pi k` inside `[lo, hi]` (with [`LIMIT_TOL`] slack), the one nearest to 0 if several;
/// `q` wrapped into (-pi, pi] when no shift fits.
///
/// # Examples
///
/// ```
/// use armlab::kinematics::ik::closed_form::wrap_into_limits;
/// use std::f64::consts::{PI, TAU};
///
/// // -0.5 rad is not inside [0, 2 pi], -0.5 + 2 pi is.
/// assert!((wrap_into_limits(-0.5, [0.0, TAU]) - (TAU - 0.5)).abs() < 1e-15);
/// // No shift fits: wrapped into (-pi, pi].
/// assert!((wrap_into_limits(3.0 * PI - 0.1, [-0.2, 0.2]) - (PI - 0.1)).abs() < 1e-14);
/// ```
///
/// The shifts are tried outwards from the wrapped angle (which is the nearest to 0), so no
/// floating-point rounding call is needed in the common case of limits within a few turns.
#[inline]
pub fn wrap_into_limits(q: f64, [lo, hi]: [f64; 2]) -> f64 {
    let w = wrap_angle(q);
    let (lo, hi) = (lo - LIMIT_TOL, hi + LIMIT_TOL);
    if w >= lo && w <= hi {
        return w;
    }
    if !(lo.is_finite() && hi.is_finite()) || hi - lo > 64.0 * TAU {
        return wrap_into_limits_far(w, lo, hi);
    }
    // |w + k 2pi| grows with |k| on each side; alternate sides, nearer first.
    let reach = lo.abs().max(hi.abs()) + TAU;
    let mut k = 1.0;
    while k * TAU - std::f64::consts::PI <= reach {
        let (near, far) = if w > 0.0 {
            (w - k * TAU, w + k * TAU)
        } else {
            (w + k * TAU, w - k * TAU)
        };
        if near >= lo && near <= hi {
            return near;
        }
        if far >= lo && far <= hi {
            return far;
        }
        k += 1.0;
    }
    w
}

/// [`wrap_into_limits`] for limits of many turns or with an open side.
fn wrap_into_limits_far(w: f64, lo: f64, hi: f64) -> f64 {
    let k_lo = ((lo - w) / TAU).ceil();
    let k_hi = ((hi - w) / TAU).floor();
    if k_lo > k_hi || k_lo.is_nan() || k_hi.is_nan() {
        return w;
    }
    // The shift nearest to 0 in [k_lo, k_hi] (an open side is infinite and never chosen).
    let k = 0f64.clamp(k_lo, k_hi);
    let c = w + k * TAU;
    if c >= lo && c <= hi { c } else { w }
}

/// [`same_configuration`] without the floating-point remainder: a difference is compared with
/// the nearest multiple of 2 pi found by a truncating conversion (the remainder is a library
/// call that made duplicate removal the largest part of the labelled solve).
#[inline]
fn same_configuration_fast(a: &[f64], b: &[f64], revolute: &[bool]) -> bool {
    a.iter().zip(b).zip(revolute).all(|((&x, &y), &rev)| {
        let d = (x - y).abs();
        if d < DUPLICATE_TOL {
            return true;
        }
        if !rev || d > 1e6 {
            return false;
        }
        let turns = (d / TAU + 0.5) as u64 as f64;
        (d - turns * TAU).abs() < DUPLICATE_TOL
    })
}

/// Whether two joint vectors are the same configuration: every revolute joint equal modulo
/// 2 pi, every prismatic joint equal, within [`DUPLICATE_TOL`].
///
/// # Examples
///
/// ```
/// use armlab::kinematics::ik::closed_form::same_configuration;
/// use std::f64::consts::TAU;
///
/// let revolute = [true, true, false]; // R-R-P
/// assert!(same_configuration(&[0.1, 0.2, 0.3], &[0.1 + TAU, 0.2, 0.3], &revolute));
/// // A prismatic joint has no turns.
/// assert!(!same_configuration(&[0.1, 0.2, 0.3], &[0.1, 0.2, 0.3 + TAU], &revolute));
/// ```
pub fn same_configuration(a: &[f64], b: &[f64], revolute: &[bool]) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).zip(revolute).all(|((&x, &y), &rev)| {
            let d = if rev { wrap_angle(x - y) } else { x - y };
            d.abs() < DUPLICATE_TOL
        })
}
