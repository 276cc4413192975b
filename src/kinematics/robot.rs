//! The robot: a tree of joints (revolute, prismatic, fixed) with couplings and end-effectors.
//!
//! Every joint is lowered to one elementary sequence `pre * M(value) * post` (M a rotation about
//! or a translation along the joint axis), whether it came from a standard or modified DH row or
//! from a URDF origin and axis, so forward kinematics and Jacobians are shared by all sources
//! (the Robotics Toolbox's ETS idea). The DH rows are kept as the source of truth for editing and
//! calibration.

use super::dh::{Convention, DhRow};
use super::error::{Bound, ModelError};
use super::pose::{Pose, rot_x, rot_z, trans_x, trans_z};
use nalgebra::{Unit, Vector3};

/// Index of a joint in [`Robot::joints`].
pub type JointId = usize;

/// The kind of a joint.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JointKind {
    /// Rotation about the joint axis; its variable is an angle (rad).
    Revolute,
    /// Translation along the joint axis; its variable is a displacement (m).
    Prismatic,
    /// No motion: a constant transform.
    Fixed,
}

impl JointKind {
    /// Lower-case name, as in model files.
    pub fn as_str(self) -> &'static str {
        match self {
            JointKind::Revolute => "revolute",
            JointKind::Prismatic => "prismatic",
            JointKind::Fixed => "fixed",
        }
    }
}

/// Where a joint's geometry comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum JointGeometry {
    /// A DH row in the given convention; the motion is about/along the z axis of that row.
    Dh {
        /// The row's parameters.
        row: DhRow,
        /// Its convention.
        convention: Convention,
    },
    /// A URDF-style joint: `parent_from_joint` at zero, motion about/along `axis` (joint frame).
    Origin {
        /// The joint frame in its parent's frame at zero joint value.
        parent_from_joint: Pose,
        /// Unit axis in the joint frame.
        axis: Unit<Vector3<f64>>,
    },
}

/// How a joint's value is obtained from the joint vector q.
#[derive(Debug, Clone, PartialEq)]
pub enum Drive {
    /// The joint is driven by its own component `q[dof]`.
    Actuated(usize),
    /// The joint follows others: value = sum of `coef * value(joint)` over the terms, where each
    /// term names an actuated joint (e.g. theta4 = -theta2 - theta3 of the humanoid torso, Sect.
    /// 2.9, or a URDF mimic joint).
    Coupled(Vec<(JointId, f64)>),
    /// A passive joint of a closed chain: its value follows from actuated joints through the
    /// loop-closure equation of its mechanism, in closed form (Problem 2.11).
    Closure(crate::kinematics::closure::Closure),
    /// A fixed joint (no variable).
    None,
}

/// One joint of the tree.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// Human-readable name, unique in the robot.
    pub name: String,
    /// Revolute, prismatic or fixed.
    pub kind: JointKind,
    /// The joint whose frame this one is attached to; `None` = the robot base.
    pub parent: Option<JointId>,
    /// A constant transform applied before the joint's own geometry, in the parent frame (e.g.
    /// the torso-to-arm base `T_r^t` of (2.78)). Identity for an ordinary DH chain.
    pub pre: Pose,
    /// DH row or URDF origin.
    pub geometry: JointGeometry,
    /// Added to the joint value: theta = value + offset (revolute), d = value + offset
    /// (prismatic). rad or m.
    pub offset: f64,
    /// How the joint's value is obtained.
    pub drive: Drive,
    /// Joint-variable limits `[lower, upper]` (rad or m) of an actuated joint; an infinite bound
    /// means no limit on that side ([`UNBOUNDED`]: none at all).
    ///
    /// What limits do: closed-form IK returns every solution and flags those outside
    /// (`within_limits`), wrapping revolute angles by 2 pi into the limits where possible;
    /// numerical IK keeps every iterate inside (a revolute joint is first shifted by 2 pi into its
    /// range, then clamped) and draws its restarts from [`Robot::sampling_range`]; workspace
    /// sampling and the app's sliders use the same finite range.
    pub limits: [f64; 2],
}

/// An end-effector: a tool frame rigidly attached to a joint's frame.
#[derive(Debug, Clone, PartialEq)]
pub struct EndEffector {
    /// Name (e.g. "tool", "right hand").
    pub name: String,
    /// Joint whose output frame carries the tool.
    pub parent: JointId,
    /// `frame_from_tool`: the tool frame in the parent joint's output frame.
    pub tool: Pose,
}

/// A named joint configuration (e.g. "zero", "ready", the pose of a textbook figure).
#[derive(Debug, Clone, PartialEq)]
pub struct NamedConfig {
    /// Name.
    pub name: String,
    /// Joint vector (rad or m).
    pub q: Vec<f64>,
}

/// One joint of a serial DH table for [`Robot::from_dh`]: its kind, its row, the joint offset and
/// the limits, read like a row of the textbook's tables.
///
/// ```
/// use armlab::kinematics::{DhJoint, DhRow};
/// let elbow = DhJoint::revolute(DhRow { a: 0.4318, alpha: 0.0, d: 0.0, theta: 0.0 })
///     .limits(-0.785, 3.927);
/// let slide = DhJoint::prismatic(DhRow { a: 0.0, alpha: 0.0, d: 0.0, theta: 0.0 })
///     .limits(0.0, 0.5);
/// assert!(DhJoint::revolute(DhRow::default()).is_unbounded());
/// # let _ = (elbow, slide);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct DhJoint {
    /// Revolute (theta = q + offset), prismatic (d = q + offset) or fixed.
    pub kind: JointKind,
    /// The row; its theta (revolute) or d (prismatic) is replaced by the joint variable.
    pub row: DhRow,
    /// Joint offset (rad or m), added to q.
    pub offset: f64,
    /// `[lower, upper]` (rad or m); infinite bounds mean no limit. Default: unbounded.
    pub limits: [f64; 2],
    /// Joint name; `None` = `q1`, `q2`, ...
    pub name: Option<String>,
}

impl DhJoint {
    /// A joint of the given kind with this row, no offset, no limits.
    pub fn new(kind: JointKind, row: DhRow) -> Self {
        Self {
            kind,
            row,
            offset: 0.0,
            limits: UNBOUNDED,
            name: None,
        }
    }

    /// A revolute joint (theta = q + offset).
    pub fn revolute(row: DhRow) -> Self {
        Self::new(JointKind::Revolute, row)
    }

    /// A prismatic joint (d = q + offset).
    pub fn prismatic(row: DhRow) -> Self {
        Self::new(JointKind::Prismatic, row)
    }

    /// A fixed row (no variable).
    pub fn fixed(row: DhRow) -> Self {
        Self::new(JointKind::Fixed, row)
    }

    /// Sets the joint offset (rad or m).
    pub fn offset(mut self, offset: f64) -> Self {
        self.offset = offset;
        self
    }

    /// Sets the limits `lower <= q <= upper` (rad or m; `f64::INFINITY` for an open side).
    pub fn limits(mut self, lower: f64, upper: f64) -> Self {
        self.limits = [lower, upper];
        self
    }

    /// Removes the limits.
    pub fn unbounded(mut self) -> Self {
        self.limits = UNBOUNDED;
        self
    }

    /// Sets the joint's name.
    pub fn name(mut self, name: impl Into<String>) -> Self {
        self.name = Some(name.into());
        self
    }

    /// Whether both bounds are infinite.
    pub fn is_unbounded(&self) -> bool {
        self.limits == UNBOUNDED
    }
}

/// The limits of a joint without limits: `[-inf, +inf]`.
pub const UNBOUNDED: [f64; 2] = [f64::NEG_INFINITY, f64::INFINITY];

/// The joint motion after lowering.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Motion {
    /// Rotation about local z.
    RotZ,
    /// Translation along local z.
    TransZ,
    /// Rotation about an arbitrary unit axis.
    Rot(Unit<Vector3<f64>>),
    /// Translation along an arbitrary unit axis.
    Trans(Unit<Vector3<f64>>),
    /// No motion.
    Fixed,
}

/// A joint lowered to `pre * M(value + offset) * post`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Lowered {
    pub(crate) parent: Option<JointId>,
    pub(crate) pre: Pose,
    pub(crate) pre_is_identity: bool,
    pub(crate) motion: Motion,
    pub(crate) post: Pose,
    pub(crate) offset: f64,
    /// `Some(k)` when the joint is driven by `q[k]` alone (the FK fast path).
    pub(crate) dof: Option<usize>,
    /// A revolute DH row with no extra `pre`, evaluated by the specialised product.
    pub(crate) fast: Option<FastDh>,
}

/// The constants of a revolute DH row: `cos alpha`, `sin alpha`, `a`, `d`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum FastDh {
    /// Standard: `T * Rz(theta) * Tz(d) * Tx(a) * Rx(alpha)`.
    Standard([f64; 4]),
    /// Modified: `T * Rx(alpha) * Tx(a) * Rz(theta) * Tz(d)`.
    Modified([f64; 4]),
}

/// A serial DH table: convention and, per joint, kind, row and offset.
pub type DhTable = (Convention, Vec<(JointKind, DhRow, f64)>);

/// A link's mass, lumped at its centre of mass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointMass {
    /// The joint whose frame carries it (its child link); `None` for the base.
    pub joint: Option<JointId>,
    /// The centre of mass in that frame (m).
    pub com: Vector3<f64>,
    /// The mass (kg).
    pub mass: f64,
}

/// One link pair never checked for collision (the stored allowed-collision matrix).
#[derive(Debug, Clone, PartialEq)]
pub struct DisabledPair {
    /// The first link's name.
    pub link1: String,
    /// The second link's name.
    pub link2: String,
    /// Why, as an SRDF says it ("Adjacent", "Always", "Never", "Default", or the user's word).
    pub reason: String,
}

/// A manipulator: base transform, joint tree, end-effectors and named configurations.
///
/// # Examples
///
/// A built-in model of the textbook ([`crate::kinematics::models::built_in`]) and what it holds:
///
/// ```
/// use armlab::kinematics::models::built_in;
///
/// let puma = built_in("puma560").expect("a built-in model");
/// assert_eq!(puma.dof(), 6);
/// assert_eq!(puma.end_effectors().len(), 1);
/// // Every built-in model has the configurations "zero" and "ready".
/// assert_eq!(puma.config("zero"), Some(&[0.0; 6][..]));
/// let ready = puma.config("ready").expect("a ready configuration");
/// assert!(puma.within_limits(ready, 0.0));
/// // Joints are named q1, q2, ... unless the table names them.
/// println!("{}: {} joints, first {:?}", puma.name, puma.joints().len(), puma.joints()[0].name);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Robot {
    /// Display name.
    pub name: String,
    /// One-paragraph description with the textbook section and where numbers were chosen.
    pub description: String,
    /// `world_from_base`: the base frame in world coordinates.
    pub base: Pose,
    joints: Vec<Joint>,
    end_effectors: Vec<EndEffector>,
    /// Named configurations; every one has `dof()` entries.
    pub configurations: Vec<NamedConfig>,
    /// What the links look like (a URDF's `<visual>` elements); empty for a DH model, which is
    /// drawn from its joints.
    pub visuals: Vec<super::visual::Visual>,
    /// What collision checks use for the links (a URDF's `<collision>` elements, or a link's
    /// `<visual>` where it has no `<collision>`); empty for a DH model, whose links are checked
    /// as they are drawn (see `crate::collision`).
    pub collisions: Vec<super::visual::Visual>,
    /// What reading the collision geometry skipped or replaced, in words naming the link (a link
    /// without `<collision>` checked with its `<visual>`, a collision mesh not found); said when
    /// collisions are checked, not on every load.
    pub collision_warnings: Vec<String>,
    /// The link pairs never checked for collision (a model file's `[[disable_collisions]]`, as
    /// an SRDF's `<disable_collisions>`): the stored allowed-collision matrix; empty when none
    /// is stored.
    pub disabled_collisions: Vec<DisabledPair>,
    /// The name of the root link (a URDF's), the base's body in collision reports; `None` for a
    /// DH model ("base").
    pub root_link: Option<String>,
    /// What loading the model skipped, in words naming the file (a mesh that could not be read
    /// and was replaced by the joint's body); empty when nothing was.
    pub load_warnings: Vec<String>,
    /// The links' masses as points (a URDF's `<inertial>`, a model file's `mass` and `com`):
    /// what gravity pulls on, for the joints' compliance in calibration; empty when unknown.
    pub masses: Vec<PointMass>,
    /// Every link of a robot description with the joint whose output frame is the link's frame
    /// (a URDF joint's child link), in file order: any of them can be made an end-effector by
    /// name ([`Robot::end_effector_at`]). Empty for a DH model.
    pub link_frames: Vec<(String, JointId)>,
    pub(crate) lowered: Vec<Lowered>,
    /// `dof_joint[k]` = joint driven by `q[k]`.
    pub(crate) dof_joint: Vec<JointId>,
    /// For every joint, the chain of ancestors from the base to it (inclusive).
    pub(crate) chains: Vec<Vec<JointId>>,
}

impl Robot {
    /// Builds a robot, validating the tree, couplings, parameters and transforms.
    ///
    /// `joints` must be in topological order (a parent before its children). If
    /// `end_effectors` is empty one end-effector named "tool" is placed on the last joint.
    pub fn new(
        name: impl Into<String>,
        base: Pose,
        joints: Vec<Joint>,
        mut end_effectors: Vec<EndEffector>,
    ) -> Result<Self, ModelError> {
        check_size(&joints, &base, &end_effectors)?;
        let mut dof_joint = Vec::new();
        for (i, j) in joints.iter().enumerate() {
            validate_joint(i, j, &joints)?;
            if let Drive::Actuated(k) = j.drive {
                if k != dof_joint.len() {
                    return Err(ModelError::Structure(
                        "actuated joints must take q components in order 0, 1, 2, ...",
                    ));
                }
                dof_joint.push(i);
            }
        }
        if dof_joint.is_empty() {
            return Err(ModelError::Structure(
                "a robot needs at least one actuated joint",
            ));
        }
        if end_effectors.is_empty() {
            end_effectors.push(EndEffector {
                name: "tool".into(),
                parent: joints.len() - 1,
                tool: Pose::identity(),
            });
        }
        for ee in &end_effectors {
            if ee.parent >= joints.len() {
                return Err(ModelError::Structure(
                    "an end-effector names a joint that does not exist",
                ));
            }
        }
        let lowered = joints.iter().map(lower).collect();
        let chains = (0..joints.len())
            .map(|i| {
                let mut c = vec![i];
                let mut p = joints[i].parent;
                while let Some(k) = p {
                    c.push(k);
                    p = joints[k].parent;
                }
                c.reverse();
                c
            })
            .collect();
        let n = dof_joint.len();
        Ok(Self {
            name: name.into(),
            description: String::new(),
            base,
            joints,
            end_effectors,
            configurations: vec![NamedConfig {
                name: "zero".into(),
                q: vec![0.0; n],
            }],
            visuals: Vec::new(),
            collisions: Vec::new(),
            collision_warnings: Vec::new(),
            root_link: None,
            disabled_collisions: Vec::new(),
            load_warnings: Vec::new(),
            masses: Vec::new(),
            link_frames: Vec::new(),
            lowered,
            dof_joint,
            chains,
        })
    }

    /// A serial DH chain: joint i's parent is joint i-1, one end-effector `tool`
    /// (`flange_from_tool`) on the last joint, `base` = `world_from_base`. Joints are named
    /// `q1`, `q2`, ... unless [`DhJoint::name`] is given.
    ///
    /// # Examples
    ///
    /// The two-link planar arm of Sect. 2.12.1 with a1 = 0.5 m, a2 = 0.3 m, mounted 1 m above
    /// the world origin. Stretched out along x0 (q = 0) its tool is at x = a1 + a2:
    ///
    /// ```
    /// use armlab::kinematics::{Convention, DhJoint, DhRow, Pose, Robot};
    ///
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// let (a1, a2) = (0.5, 0.3);
    /// let arm = Robot::from_dh(
    ///     "two-link arm",
    ///     Convention::Standard,
    ///     &[
    ///         DhJoint::revolute(DhRow { a: a1, alpha: 0.0, d: 0.0, theta: 0.0 }).name("shoulder"),
    ///         DhJoint::revolute(DhRow { a: a2, alpha: 0.0, d: 0.0, theta: 0.0 }).name("elbow"),
    ///     ],
    ///     Pose::translation(0.0, 0.0, 1.0), // world_from_base
    ///     Pose::identity(),                 // flange_from_tool
    /// )?;
    /// assert_eq!(arm.dof(), 2);
    /// assert_eq!(arm.dof_joint(1).name, "elbow");
    /// let p = arm.fk(&[0.0, 0.0])?.translation.vector;
    /// assert!((p.x - (a1 + a2)).abs() < 1e-15 && p.y.abs() < 1e-15 && (p.z - 1.0).abs() < 1e-15);
    /// # Ok(())
    /// # }
    /// ```
    ///
    /// A table that is not a robot is a typed [`ModelError`], here limits that are not an
    /// interval:
    ///
    /// ```
    /// use armlab::kinematics::{Convention, DhJoint, DhRow, ModelError, Pose, Robot};
    ///
    /// let bad = Robot::from_dh(
    ///     "bad",
    ///     Convention::Standard,
    ///     &[DhJoint::revolute(DhRow { a: 1.0, ..DhRow::default() }).limits(1.0, -1.0)],
    ///     Pose::identity(),
    ///     Pose::identity(),
    /// );
    /// assert!(matches!(bad, Err(ModelError::BadLimits { joint: 0, .. })));
    /// println!("{}", bad.unwrap_err()); // "joint 0: limits [1, -1] are not an interval (...)"
    /// ```
    pub fn from_dh(
        name: impl Into<String>,
        convention: Convention,
        rows: &[DhJoint],
        base: Pose,
        tool: Pose,
    ) -> Result<Self, ModelError> {
        let mut dof = 0;
        let joints: Vec<Joint> = rows
            .iter()
            .enumerate()
            .map(|(i, r)| {
                let drive = if r.kind == JointKind::Fixed {
                    Drive::None
                } else {
                    dof += 1;
                    Drive::Actuated(dof - 1)
                };
                Joint {
                    name: r.name.clone().unwrap_or_else(|| format!("q{}", i + 1)),
                    kind: r.kind,
                    parent: i.checked_sub(1),
                    pre: Pose::identity(),
                    geometry: JointGeometry::Dh {
                        row: r.row,
                        convention,
                    },
                    offset: r.offset,
                    drive,
                    limits: r.limits,
                }
            })
            .collect();
        let last = joints.len().saturating_sub(1);
        Self::new(
            name,
            base,
            joints,
            vec![EndEffector {
                name: "tool".into(),
                parent: last,
                tool,
            }],
        )
    }

    /// Sets the description (builder style).
    pub fn with_description(mut self, d: impl Into<String>) -> Self {
        self.description = d.into();
        self
    }

    /// Adds a named configuration (builder style). Panics in debug builds on a wrong length.
    pub fn with_config(mut self, name: &str, q: Vec<f64>) -> Self {
        debug_assert_eq!(q.len(), self.dof(), "configuration {name}");
        self.configurations.retain(|c| c.name != name);
        self.configurations.push(NamedConfig {
            name: name.into(),
            q,
        });
        self
    }

    /// Number of degrees of freedom (length of q).
    pub fn dof(&self) -> usize {
        self.dof_joint.len()
    }

    /// All joints, actuated, coupled and fixed, in topological order.
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// The end-effectors.
    pub fn end_effectors(&self) -> &[EndEffector] {
        &self.end_effectors
    }

    /// The joint driven by `q[k]`.
    pub fn dof_joint(&self, k: usize) -> &Joint {
        &self.joints[self.dof_joint[k]]
    }

    /// Joint ids of the actuated joints, in q order.
    pub fn actuated_joints(&self) -> &[JointId] {
        &self.dof_joint
    }

    /// The ancestors of joint `j` from the base to `j` inclusive.
    pub fn chain_to(&self, j: JointId) -> &[JointId] {
        &self.chains[j]
    }

    /// Limits of every component of q, `[lower, upper]` (rad or m).
    pub fn limits(&self) -> Vec<[f64; 2]> {
        self.dof_joint
            .iter()
            .map(|&j| self.joints[j].limits)
            .collect()
    }

    /// A finite range for drawing values of `q[k]` (numerical-IK restarts, workspace sampling,
    /// sliders): the limits where both are finite; for a revolute joint an open side is closed
    /// one turn (2 pi) from the other bound, or [-pi, pi] with no limits at all; for a prismatic
    /// joint an open side lies [`Robot::characteristic_length`] from the other bound (or from 0).
    pub fn sampling_range(&self, k: usize) -> [f64; 2] {
        let j = &self.joints[self.dof_joint[k]];
        let [lo, hi] = j.limits;
        if lo.is_finite() && hi.is_finite() {
            return [lo, hi];
        }
        let span = match j.kind {
            JointKind::Revolute => std::f64::consts::TAU,
            _ => 2.0 * self.characteristic_length(),
        };
        match (lo.is_finite(), hi.is_finite()) {
            (true, false) => [lo, lo + span],
            (false, true) => [hi - span, hi],
            _ => [-0.5 * span, 0.5 * span],
        }
    }

    /// [`Robot::sampling_range`] of every component of q.
    pub fn sampling_ranges(&self) -> Vec<[f64; 2]> {
        (0..self.dof()).map(|k| self.sampling_range(k)).collect()
    }

    /// A length that sets the robot's scale (m): the sum of every |a| and |d| of its DH rows, the
    /// lengths of its URDF origins and the finite prismatic strokes, at least 1 m when there is
    /// none. Used to bound open prismatic ranges.
    pub fn characteristic_length(&self) -> f64 {
        let mut sum = 0.0;
        for j in &self.joints {
            sum += j.pre.translation.vector.norm();
            match &j.geometry {
                JointGeometry::Dh { row, .. } => sum += row.a.abs() + row.d.abs(),
                JointGeometry::Origin {
                    parent_from_joint, ..
                } => sum += parent_from_joint.translation.vector.norm(),
            }
            if j.kind == JointKind::Prismatic && j.limits.iter().all(|v| v.is_finite()) {
                sum += j.limits[1] - j.limits[0];
            }
        }
        if sum > 0.0 && sum.is_finite() {
            sum
        } else {
            1.0
        }
    }

    /// The length of the longest chain (m): the longest sum of DH lengths and offsets (and
    /// prismatic strokes) along a chain from the base to an end-effector, at least 0.2 m. Sizes
    /// joint bodies, triads and the grid of drawings, and makes Jacobians dimensionless.
    pub fn longest_chain_length(&self) -> f64 {
        let len = |j: &Joint| match &j.geometry {
            JointGeometry::Dh { row, .. } => {
                row.a.abs()
                    + row.d.abs()
                    + if j.kind == JointKind::Prismatic && j.limits[1].is_finite() {
                        j.limits[1].abs()
                    } else {
                        0.0
                    }
            }
            JointGeometry::Origin {
                parent_from_joint, ..
            } => parent_from_joint.translation.vector.norm(),
        };
        let longest = self
            .end_effectors()
            .iter()
            .map(|e| {
                let chain: f64 = self
                    .chain_to(e.parent)
                    .iter()
                    .map(|&j| {
                        len(&self.joints()[j]) + self.joints()[j].pre.translation.vector.norm()
                    })
                    .sum();
                chain + e.tool.translation.vector.norm()
            })
            .fold(0.0, f64::max);
        longest.max(0.2)
    }

    /// Whether `q` lies inside the limits (inclusive, with `tol` slack).
    pub fn within_limits(&self, q: &[f64], tol: f64) -> bool {
        q.len() == self.dof()
            && self.dof_joint.iter().zip(q).all(|(&j, &v)| {
                v >= self.joints[j].limits[0] - tol && v <= self.joints[j].limits[1] + tol
            })
    }

    /// Whether the components of `q` that move end-effector `ee` (the joints on its chain) lie
    /// inside their limits; the joints off that chain (another arm, a gripper's fingers) are
    /// not asked. An unknown `ee` asks every joint.
    pub fn within_limits_for(&self, ee: usize, q: &[f64], tol: f64) -> bool {
        let Some(e) = self.end_effectors.get(ee) else {
            return self.within_limits(q, tol);
        };
        let chain = self.chain_to(e.parent);
        q.len() == self.dof()
            && self.dof_joint.iter().zip(q).all(|(&j, &v)| {
                let [lo, hi] = self.joints[j].limits;
                !chain.contains(&j) || (v >= lo - tol && v <= hi + tol)
            })
    }

    /// The "ready" configuration, or else zero moved into each joint's limits (rad or m): where
    /// the app opens, tools start, seeds come from, and joints off an arm's chain stay. A
    /// gripper's fingers limited to [0.015, 0.037] m start at 0.015 m, not at 0.
    pub fn ready_or_zero(&self) -> Vec<f64> {
        self.config("ready")
            .filter(|c| c.len() == self.dof())
            .map_or_else(
                || {
                    self.dof_joint
                        .iter()
                        .map(|&j| {
                            let [lo, hi] = self.joints[j].limits;
                            if lo <= hi { 0.0f64.clamp(lo, hi) } else { 0.0 }
                        })
                        .collect()
                },
                <[f64]>::to_vec,
            )
    }

    /// The end-effector named `name`: one the robot has, or else a link of its description
    /// (see [`Robot::link_frames`]) made one, with an identity tool, and appended. `None` when
    /// neither has that name.
    ///
    /// ```
    /// use armlab::model_file::parse_model_text;
    ///
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// let urdf = r#"<robot name="arm">
    ///   <link name="base"/> <link name="forearm"/> <link name="hand"/>
    ///   <joint name="j1" type="continuous"><parent link="base"/><child link="forearm"/>
    ///     <axis xyz="0 0 1"/></joint>
    ///   <joint name="j2" type="continuous"><parent link="forearm"/><child link="hand"/>
    ///     <origin xyz="0.5 0 0"/><axis xyz="0 0 1"/></joint>
    /// </robot>"#;
    /// let mut robot = parse_model_text("arm.urdf", urdf)?;
    /// assert_eq!(robot.end_effectors().len(), 1); // the leaf, "hand"
    /// let ee = robot.end_effector_at("forearm").expect("a link");
    /// assert_eq!(robot.end_effectors()[ee].name, "forearm");
    /// assert!(robot.end_effector_at("elbow").is_none());
    /// # Ok(())
    /// # }
    /// ```
    pub fn end_effector_at(&mut self, name: &str) -> Option<usize> {
        if let Some(i) = self.end_effectors.iter().position(|e| e.name == name) {
            return Some(i);
        }
        let &(_, joint) = self.link_frames.iter().find(|(l, _)| l == name)?;
        self.end_effectors.push(EndEffector {
            name: name.to_string(),
            parent: joint,
            tool: Pose::identity(),
        });
        Some(self.end_effectors.len() - 1)
    }

    /// A named configuration, if the robot has one by that name.
    pub fn config(&self, name: &str) -> Option<&[f64]> {
        self.configurations
            .iter()
            .find(|c| c.name == name)
            .map(|c| c.q.as_slice())
    }

    /// The DH rows of a serial chain with one convention, if the robot is one (all joints DH,
    /// each the child of the previous, no `pre` transforms).
    pub fn dh_table(&self) -> Option<DhTable> {
        let mut conv = None;
        let mut out = Vec::new();
        for (i, j) in self.joints.iter().enumerate() {
            let JointGeometry::Dh { row, convention } = j.geometry else {
                return None;
            };
            if j.parent != i.checked_sub(1) || j.pre != Pose::identity() {
                return None;
            }
            if *conv.get_or_insert(convention) != convention {
                return None;
            }
            out.push((j.kind, row, j.offset));
        }
        conv.map(|c| (c, out))
    }

    /// The robot with point masses `(joint, mass kg, centre of mass m in the joint's frame)`.
    pub fn with_masses(mut self, masses: &[(JointId, f64, [f64; 3])]) -> Self {
        self.masses = masses
            .iter()
            .map(|&(j, mass, com)| PointMass {
                joint: Some(j),
                com: Vector3::from(com),
                mass,
            })
            .collect();
        self
    }

    /// Replaces joint `j`'s DH row (live editing, calibration); the robot is re-lowered.
    pub fn set_dh_row(&mut self, j: JointId, row: DhRow) -> Result<(), ModelError> {
        let mut joint = self.joints[j].clone();
        let JointGeometry::Dh { convention, .. } = joint.geometry else {
            return Err(ModelError::Structure(
                "this joint is not described by a DH row",
            ));
        };
        joint.geometry = JointGeometry::Dh { row, convention };
        validate_joint(j, &joint, &self.joints)?;
        self.lowered[j] = lower(&joint);
        self.joints[j] = joint;
        Ok(())
    }

    /// Replaces joint `j`'s constant `pre` transform (Hayati's extra rotation after a
    /// calibrated row goes into the next joint's `pre`); validated, re-lowered.
    pub fn set_pre(&mut self, j: JointId, pre: Pose) -> Result<(), ModelError> {
        let mut joint = self.joints[j].clone();
        joint.pre = pre;
        validate_joint(j, &joint, &self.joints)?;
        self.lowered[j] = lower(&joint);
        self.joints[j] = joint;
        Ok(())
    }

    /// The rows of a serial chain of DH joints in one convention like [`Self::dh_table`], also
    /// when joints carry constant `pre` transforms (returned alongside, identity where none).
    pub fn dh_table_with_pre(&self) -> Option<(DhTable, Vec<Pose>)> {
        let mut conv = None;
        let mut out = Vec::new();
        let mut pres = Vec::new();
        for (i, j) in self.joints.iter().enumerate() {
            let JointGeometry::Dh { row, convention } = j.geometry else {
                return None;
            };
            if j.parent != i.checked_sub(1) || *conv.get_or_insert(convention) != convention {
                return None;
            }
            out.push((j.kind, row, j.offset));
            pres.push(j.pre);
        }
        conv.map(|c| ((c, out), pres))
    }

    /// Replaces the tool (`frame_from_tool`) of end-effector `ee` (calibration); validated.
    pub fn set_tool(&mut self, ee: usize, tool: Pose) -> Result<(), ModelError> {
        if ee >= self.end_effectors.len() {
            return Err(ModelError::Structure("no such end-effector"));
        }
        if !tool.to_homogeneous().iter().all(|v| v.is_finite()) {
            return Err(ModelError::NotRigid {
                what: format!("end-effector {ee} tool"),
                reason: "non-finite element".into(),
            });
        }
        self.end_effectors[ee].tool = tool;
        Ok(())
    }

    /// Replaces joint `j`'s offset and limits (live editing); validated.
    pub fn set_offset_limits(
        &mut self,
        j: JointId,
        offset: f64,
        limits: [f64; 2],
    ) -> Result<(), ModelError> {
        let mut joint = self.joints[j].clone();
        joint.offset = offset;
        joint.limits = limits;
        validate_joint(j, &joint, &self.joints)?;
        self.lowered[j] = lower(&joint);
        self.joints[j] = joint;
        Ok(())
    }
}

/// Most joints (actuated, coupled or fixed) a robot may have.
pub const MAX_JOINTS: usize = 256;
/// Largest length a robot's parameter may have (m): 10 km.
pub const MAX_LENGTH: f64 = 1e4;
/// Largest angle a robot's parameter or finite limit may have (rad): about 159 turns.
pub const MAX_ANGLE: f64 = 1e3;

fn check_finite(joint: usize, field: &'static str, value: f64) -> Result<(), ModelError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(ModelError::NonFiniteParameter {
            joint,
            field,
            value,
        })
    }
}

/// Finite and within `bound`.
fn check_range(
    joint: usize,
    field: &'static str,
    value: f64,
    bound: Bound,
) -> Result<(), ModelError> {
    check_finite(joint, field, value)?;
    let max = match bound {
        Bound::Length => MAX_LENGTH,
        Bound::Angle => MAX_ANGLE,
    };
    if value.abs() > max {
        return Err(ModelError::OutOfRange {
            joint,
            field,
            value,
            bound,
        });
    }
    Ok(())
}

/// The bound of a joint variable's kind.
fn variable_range(kind: JointKind) -> Bound {
    match kind {
        JointKind::Prismatic => Bound::Length,
        _ => Bound::Angle,
    }
}

/// At least one and at most [`MAX_JOINTS`] joints; base and tools finite and within
/// [`MAX_LENGTH`].
fn check_size(
    joints: &[Joint],
    base: &Pose,
    end_effectors: &[EndEffector],
) -> Result<(), ModelError> {
    if joints.is_empty() {
        return Err(ModelError::Structure("a robot needs at least one joint"));
    }
    if joints.len() > MAX_JOINTS {
        return Err(ModelError::TooManyJoints {
            count: joints.len(),
            max: MAX_JOINTS,
        });
    }
    check_placement("base", base)?;
    for (k, ee) in end_effectors.iter().enumerate() {
        check_placement(&format!("tool of end-effector {k}"), &ee.tool)?;
    }
    Ok(())
}

/// A base or tool: finite, translation within [`MAX_LENGTH`].
fn check_placement(what: &str, p: &Pose) -> Result<(), ModelError> {
    let t = p.translation.vector.norm();
    let finite = p.to_homogeneous().iter().all(|v| v.is_finite());
    if finite && t <= MAX_LENGTH {
        return Ok(());
    }
    Err(ModelError::NotRigid {
        what: what.to_string(),
        reason: if finite {
            format!("translation {t:e} m is beyond {MAX_LENGTH:e} m")
        } else {
            "non-finite element".into()
        },
    })
}

fn check_pose(joint: usize, what: &'static str, p: &Pose) -> Result<(), ModelError> {
    let m = p.to_homogeneous();
    if !m.iter().all(|v| v.is_finite()) {
        return Err(ModelError::NotRigid {
            what: format!("joint {joint} {what}"),
            reason: "non-finite element".into(),
        });
    }
    check_range(joint, what, p.translation.vector.norm(), Bound::Length)
}

fn validate_joint(i: usize, j: &Joint, all: &[Joint]) -> Result<(), ModelError> {
    if let Some(p) = j.parent
        && p >= i
    {
        return Err(ModelError::BadParent {
            joint: i,
            parent: p,
        });
    }
    let var_bound = variable_range(j.kind);
    check_range(i, "offset", j.offset, var_bound)?;
    check_pose(i, "pre", &j.pre)?;
    match &j.geometry {
        JointGeometry::Dh { row, .. } => {
            check_range(i, "a", row.a, Bound::Length)?;
            check_range(i, "alpha", row.alpha, Bound::Angle)?;
            check_range(i, "d", row.d, Bound::Length)?;
            check_range(i, "theta", row.theta, Bound::Angle)?;
        }
        JointGeometry::Origin {
            parent_from_joint,
            axis,
        } => {
            check_pose(i, "origin", parent_from_joint)?;
            if !axis.iter().all(|v| v.is_finite()) || axis.norm() < 0.5 {
                return Err(ModelError::ZeroAxis { joint: i });
            }
        }
    }
    if j.kind != JointKind::Fixed && matches!(j.drive, Drive::Actuated(_)) {
        let [lo, hi] = j.limits;
        if lo.is_nan() || hi.is_nan() || lo > hi || lo == f64::INFINITY || hi == f64::NEG_INFINITY {
            return Err(ModelError::BadLimits {
                joint: i,
                lower: lo,
                upper: hi,
            });
        }
        for bound in [lo, hi].into_iter().filter(|b| b.is_finite()) {
            check_range(i, "limits", bound, var_bound)?;
        }
    }
    match &j.drive {
        Drive::None if j.kind != JointKind::Fixed => {
            return Err(ModelError::Structure(
                "a revolute or prismatic joint needs a drive",
            ));
        }
        Drive::Actuated(_) | Drive::Coupled(_) | Drive::Closure(_)
            if j.kind == JointKind::Fixed =>
        {
            return Err(ModelError::Structure(
                "a fixed joint cannot be actuated or coupled",
            ));
        }
        Drive::Closure(c) => check_closure(i, c, all)?,
        Drive::Coupled(terms) => check_coupling(i, terms, all)?,
        _ => {}
    }
    Ok(())
}

/// A coupled joint's terms name earlier actuated joints with finite factors.
fn check_coupling(i: usize, terms: &[(JointId, f64)], all: &[Joint]) -> Result<(), ModelError> {
    if terms.is_empty() {
        return Err(ModelError::Structure(
            "a coupled joint needs at least one term",
        ));
    }
    for &(src, coef) in terms {
        let reason = if src >= i {
            Some("it must name an earlier joint")
        } else if !matches!(all[src].drive, Drive::Actuated(_)) {
            Some("it must name an actuated joint")
        } else if !coef.is_finite() {
            Some("the factor is not finite")
        } else {
            None
        };
        if let Some(reason) = reason {
            return Err(ModelError::BadCoupling {
                joint: i,
                source_joint: src,
                reason,
            });
        }
    }
    Ok(())
}

/// A closure-driven joint reads two earlier actuated revolute joints at the base, and its loop
/// closes for every value of theirs.
fn check_closure(
    i: usize,
    c: &crate::kinematics::closure::Closure,
    all: &[Joint],
) -> Result<(), ModelError> {
    let m = &c.mechanism;
    for (src, length) in [(m.crank, m.a_crank), (m.arm, m.a_arm)] {
        let planar_row = |j: &Joint| match j.geometry {
            JointGeometry::Dh {
                row,
                convention: Convention::Standard,
            } => row.a == length && row.alpha == 0.0 && row.d == 0.0 && j.pre == Pose::identity(),
            _ => false,
        };
        let reason = if src >= i {
            Some("it must name an earlier joint")
        } else if !planar_row(&all[src]) {
            Some(
                "its DH row must be the loop's link: standard, a equal to the loop's length, \
                 alpha = d = 0",
            )
        } else if !matches!(all[src].drive, Drive::Actuated(_))
            || all[src].kind != JointKind::Revolute
            || all[src].parent.is_some()
        {
            Some("it must name an actuated revolute joint at the base")
        } else if !m.always_closes() {
            Some("the loop does not close for every crank angle (|a_arm - a_crank| <= |offset|)")
        } else {
            None
        };
        if let Some(reason) = reason {
            return Err(ModelError::BadCoupling {
                joint: i,
                source_joint: src,
                reason,
            });
        }
    }
    Ok(())
}

fn lower(j: &Joint) -> Lowered {
    let (geo_pre, motion, post) = match (&j.geometry, j.kind) {
        (JointGeometry::Dh { row, convention }, kind) => match (convention, kind) {
            // A_i = Rz(theta) Tz(d) Tx(a) Rx(alpha), (2.52)
            (Convention::Standard, JointKind::Revolute) => (
                Pose::identity(),
                Motion::RotZ,
                trans_z(row.d) * trans_x(row.a) * rot_x(row.alpha),
            ),
            (Convention::Standard, JointKind::Prismatic) => (
                rot_z(row.theta),
                Motion::TransZ,
                trans_x(row.a) * rot_x(row.alpha),
            ),
            (Convention::Standard, JointKind::Fixed) => (
                Pose::identity(),
                Motion::Fixed,
                rot_z(row.theta) * trans_z(row.d) * trans_x(row.a) * rot_x(row.alpha),
            ),
            // A_i = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i) Tz(d_i)
            (Convention::Modified, JointKind::Revolute) => (
                rot_x(row.alpha) * trans_x(row.a),
                Motion::RotZ,
                trans_z(row.d),
            ),
            (Convention::Modified, JointKind::Prismatic) => (
                rot_x(row.alpha) * trans_x(row.a) * rot_z(row.theta),
                Motion::TransZ,
                Pose::identity(),
            ),
            (Convention::Modified, JointKind::Fixed) => (
                Pose::identity(),
                Motion::Fixed,
                rot_x(row.alpha) * trans_x(row.a) * rot_z(row.theta) * trans_z(row.d),
            ),
        },
        (
            JointGeometry::Origin {
                parent_from_joint,
                axis,
            },
            kind,
        ) => {
            let m = match kind {
                JointKind::Revolute => Motion::Rot(*axis),
                JointKind::Prismatic => Motion::Trans(*axis),
                JointKind::Fixed => Motion::Fixed,
            };
            (*parent_from_joint, m, Pose::identity())
        }
    };
    let pre = j.pre * geo_pre;
    Lowered {
        parent: j.parent,
        pre_is_identity: pre == Pose::identity(),
        pre,
        motion,
        post,
        offset: j.offset,
        dof: match j.drive {
            Drive::Actuated(k) => Some(k),
            _ => None,
        },
        fast: match (&j.geometry, j.kind) {
            (JointGeometry::Dh { row, convention }, JointKind::Revolute)
                if j.pre == Pose::identity() =>
            {
                let (sa, ca) = super::trig::sin_cos(row.alpha);
                let k = [ca, sa, row.a, row.d];
                Some(match convention {
                    Convention::Standard => FastDh::Standard(k),
                    Convention::Modified => FastDh::Modified(k),
                })
            }
            _ => None,
        },
    }
}
