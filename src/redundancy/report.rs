//! The chapter's treatment of each arm of a robot, in one report per end-effector: the chain to
//! it, its DH table (or why none), its closed-form family (or why none), its degree of
//! redundancy for a full pose and its self-motion parameter. Joints off the chain (fingers, a
//! head, the other arm) do not count ([`crate::kinematics::arm`]).

use crate::kinematics::arm::{Arm, arm_of};
use crate::kinematics::dh_derive::{DerivedDh, derive_dh, derive_ideal_dh};
use crate::kinematics::end_effectors::{EndEffectorCatalog, catalog};
use crate::kinematics::ik::ClosedForm;
use crate::kinematics::ik::closed_form::{NEAR_MISS_ANGLE, NEAR_MISS_LENGTH};
use crate::kinematics::redundancy::{Redundancy, Task};
use crate::kinematics::{Convention, Robot};

/// What a frame is to a user.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// An arm's tool: its IK target.
    Tool,
    /// Another frame of an arm (a flange, a finger).
    ArmFrame,
    /// Fixed to the base, or a collision, visual, sensor or head frame.
    Other,
}

impl Role {
    /// "tool", "arm frame" or "other".
    pub fn as_str(self) -> &'static str {
        match self {
            Role::Tool => "tool",
            Role::ArmFrame => "arm frame",
            Role::Other => "other",
        }
    }
}

/// One end-effector's arm, analysed.
#[derive(Debug, Clone)]
pub struct ArmReport {
    /// The end-effector's index in the robot.
    pub ee: usize,
    /// Its name.
    pub name: String,
    /// Tool, arm frame or other frame.
    pub role: Role,
    /// The arm it belongs to (index in the catalog's arms), if any.
    pub arm_index: Option<usize>,
    /// The moving joints from the root to it (mimic joints included), names root to tip.
    pub chain: Vec<String>,
    /// The moving joints on its chain (mimic joints included).
    pub dof: usize,
    /// The arm's joint variables n (a mimic joint follows another's).
    pub variables: usize,
    /// The DH table derived for the chain (standard convention).
    pub dh: Option<DerivedDh>,
    /// Why there is no DH table.
    pub dh_reason: Option<String>,
    /// The closed-form family's name.
    pub closed_form: Option<&'static str>,
    /// The closed-form family.
    pub family: Option<crate::kinematics::ik::Family>,
    /// Why there is no closed form; for a general six-revolute arm (solved by elimination),
    /// why none of the named families applies.
    pub closed_form_reason: Option<String>,
    /// For a closed form found on the ideal structure of a near miss, how near, in words.
    pub closed_form_near_miss: Option<String>,
    /// n - r for the full task (the pose; (x, y, phi) for a planar arm), 0 when not redundant.
    pub redundancy_degree: usize,
    /// n, m, r in words.
    pub redundancy: String,
    /// The exact self-motion's parameter ("arm angle", "q7", "phi").
    pub self_motion: Option<&'static str>,
    /// Why there is no exact self-motion parameter (not redundant, or the numerical walk).
    pub self_motion_reason: Option<String>,
}

/// The exact self-motion parameter of a serial arm, if it has one: "arm angle" (SRS 7R),
/// "q7" (offset-elbow 7R), "phi_3" (four-link planar arm holding position and phi; the
/// three-link arm's "phi" is a self-motion of the position task only, not of its full task).
pub fn self_motion_parameter(arm: &Robot) -> Option<&'static str> {
    if super::srs::SrsArm::detect(arm).is_some() {
        Some("arm angle")
    } else if super::offset_elbow::OffsetElbowArm::detect(arm).is_some() {
        Some("q7")
    } else if crate::workspace::planar_frame(arm, 0).is_some() && arm.dof() == 4 {
        Some("phi_3")
    } else if arm.dof() == 7 {
        super::locked::LockedSelfMotion::pick(arm).map(|(k, _)| super::locked::parameter_name(k))
    } else {
        None
    }
}

/// The full task of a robot: (x, y, phi) for a planar arm with one end-effector ((x, y) for a
/// two-link one), the whole pose otherwise.
pub fn full_task(robot: &Robot) -> Task {
    let planar =
        robot.end_effectors().len() == 1 && crate::workspace::planar_frame(robot, 0).is_some();
    match (planar, robot.dof()) {
        (true, 3..) => Task::PlanarPhi,
        (true, _) => Task::Planar,
        (false, _) => Task::Pose,
    }
}

/// A serial arm's DH table (standard convention), or for a CAD-rounded chain whose exact table
/// is ill-conditioned the table of its ideal structure with the deviation; else why none.
fn dh_of(arm: &Robot) -> (Option<DerivedDh>, Option<String>) {
    let e = match derive_dh(arm, 0, Convention::Standard) {
        Ok(d) => return (Some(d), None),
        Err(e) => e,
    };
    let tol = NEAR_MISS_LENGTH * arm.characteristic_length();
    match derive_ideal_dh(arm, 0, NEAR_MISS_ANGLE, tol) {
        Ok((d, dev)) => (
            Some(d),
            Some(format!(
                "the table of the ideal structure (axes rounded to parallel, perpendicular or \
                 meeting within {:.1e} rad and {:.1e} m; it follows the chain to {:.1e} m); the \
                 exact chain has {e}",
                dev.angle, dev.length, dev.pose
            )),
        ),
        Err(_) => (None, Some(e.to_string())),
    }
}

/// The report of end-effector `ee` at the whole robot's `q` (see the module docs).
pub fn arm_report(robot: &Robot, cat: &EndEffectorCatalog, ee: usize, q: &[f64]) -> ArmReport {
    let name = robot
        .end_effectors()
        .get(ee)
        .map_or_else(String::new, |e| e.name.clone());
    let arm_index = cat.arm_of(ee);
    let role = match arm_index {
        Some(a) if cat.arms[a].tool == ee => Role::Tool,
        Some(_) => Role::ArmFrame,
        None => Role::Other,
    };
    let mut r = ArmReport {
        ee,
        name,
        role,
        arm_index,
        chain: Vec::new(),
        dof: 0,
        variables: 0,
        dh: None,
        dh_reason: None,
        closed_form: None,
        family: None,
        closed_form_reason: None,
        closed_form_near_miss: None,
        redundancy_degree: 0,
        redundancy: String::new(),
        self_motion: None,
        self_motion_reason: None,
    };
    let arm: Arm = match arm_of(robot, ee, q) {
        Ok(a) => a,
        Err(e) => {
            let why = e.to_string();
            r.dh_reason = Some(format!("no DH table: {why}"));
            r.closed_form_reason = Some(why.clone());
            r.self_motion_reason = Some(why);
            return r;
        }
    };
    r.chain = arm.chain_names();
    r.dof = r.chain.len();
    r.variables = arm.robot.dof();
    (r.dh, r.dh_reason) = dh_of(&arm.robot);
    match ClosedForm::detect(&arm.robot) {
        Ok(cf) => {
            r.closed_form = Some(cf.name());
            r.family = Some(*cf.family());
            r.closed_form_near_miss = cf.near_miss().map(|_| cf.describe());
            r.closed_form_reason = cf.not_named().map(str::to_string);
        }
        Err(e) => r.closed_form_reason = Some(e.to_string()),
    }
    let red = Redundancy::of(&arm.robot, full_task(&arm.robot));
    r.redundancy_degree = red.degree().max(0) as usize;
    r.redundancy = red.to_string();
    (r.self_motion, r.self_motion_reason) = if r.redundancy_degree == 0 {
        (
            None,
            Some(format!("not redundant for its full task ({red})")),
        )
    } else {
        match self_motion_parameter(&arm.robot) {
            Some(p) => (Some(p), None),
            None => (
                None,
                Some(
                    "no exact parameter for this structure: the self-motion is the numerical \
                     null-space walk, parametrised by arc length"
                        .into(),
                ),
            ),
        }
    };
    r
}

/// The reports of every end-effector of `robot` at `q`, in the catalog's order (each arm's tool
/// then its frames, then the other frames).
pub fn arm_reports(robot: &Robot, q: &[f64]) -> Vec<ArmReport> {
    let cat = catalog(robot);
    cat.order()
        .into_iter()
        .map(|ee| arm_report(robot, &cat, ee, q))
        .collect()
}
