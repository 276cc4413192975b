//! The parameter vector zeta of (2.84), the pose it predicts, and the calibration matrix Phi of
//! (2.86) in closed form.

use super::CalibrationError;
use crate::kinematics::dh::{Convention, DhRow};
use crate::kinematics::orientation::angle_axis_from_rotation;
use crate::kinematics::pose::Pose;
use crate::kinematics::robot::{Drive, JointKind, Robot};
use nalgebra::{DMatrix, Rotation3, Translation3, Vector3};

/// Which DH parameter of a row.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Link length a (m).
    A,
    /// Link twist alpha (rad).
    Alpha,
    /// Link offset d (m); the joint offset of a prismatic joint.
    D,
    /// Joint angle theta (rad); the joint offset of a revolute joint.
    Theta,
    /// Hayati's beta (rad) of a row whose joint axes are parallel: a rotation about the row's
    /// y axis after `Rx(alpha)`, replacing that row's d (then fixed).
    Beta,
    /// A translation of the base along world axis 0, 1, 2 (m): `world_from_base` becomes
    /// `Trans(t) Rot(r) world_from_base`.
    BaseTranslation(usize),
    /// A rotation of the base about world axis 0, 1, 2 (rad; the rotation vector r).
    BaseRotation(usize),
    /// A translation of the tool along its own axis 0, 1, 2 (m): `flange_from_tool` becomes
    /// `flange_from_tool Trans(t) Rot(r)`.
    ToolTranslation(usize),
    /// A rotation of the tool about its own axis 0, 1, 2 (rad; the rotation vector r).
    ToolRotation(usize),
    /// A revolute joint's compliance (rad per N m): gravity's torque tau on the joint turns it
    /// by `c tau` beyond its reading.
    Compliance,
}

impl Kind {
    /// The name used in reports and JSON: "a", "alpha", "d", "theta".
    pub fn as_str(self) -> &'static str {
        match self {
            Kind::A => "a",
            Kind::Alpha => "alpha",
            Kind::D => "d",
            Kind::Theta => "theta",
            Kind::Beta => "beta",
            Kind::BaseTranslation(k) => ["base_x", "base_y", "base_z"][k.min(2)],
            Kind::BaseRotation(k) => ["base_rx", "base_ry", "base_rz"][k.min(2)],
            Kind::ToolTranslation(k) => ["tool_x", "tool_y", "tool_z"][k.min(2)],
            Kind::ToolRotation(k) => ["tool_rx", "tool_ry", "tool_rz"][k.min(2)],
            Kind::Compliance => "c",
        }
    }

    /// How reports show a value: the factor from SI and the unit (degrees, millimetres, or
    /// microradians per N m for a compliance).
    pub fn display(self) -> (f64, &'static str) {
        match self {
            Kind::Compliance => (1e6, "urad/Nm"),
            k if k.is_angle() => (180.0 / std::f64::consts::PI, "deg"),
            _ => (1e3, "mm"),
        }
    }

    /// Whether the parameter is an angle (rad) rather than a length (m).
    pub fn is_angle(self) -> bool {
        matches!(
            self,
            Kind::Alpha | Kind::Theta | Kind::Beta | Kind::BaseRotation(_) | Kind::ToolRotation(_)
        )
    }
}

/// One component of zeta.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    /// Name, e.g. "d2" (kind and 1-based row).
    pub name: String,
    /// 1-based DH row.
    pub joint: usize,
    /// Which parameter.
    pub kind: Kind,
    /// Nominal value (m or rad).
    pub nominal: f64,
    /// Kept at its nominal value (not estimated).
    pub fixed: bool,
}

/// One measured pose of the end-effector, with the joint readings it was taken at.
#[derive(Debug, Clone, PartialEq)]
pub enum Measurement {
    /// The whole `world_from_tool`.
    Pose {
        /// Joint values (rad or m).
        q: Vec<f64>,
        /// Measured `world_from_tool`.
        world_from_tool: Pose,
    },
    /// The tool point only (a laser tracker without orientation).
    Position {
        /// Joint values (rad or m).
        q: Vec<f64>,
        /// Measured tool point, world frame (m).
        p: Vector3<f64>,
    },
    /// Two joint vectors whose tool points are a known distance apart (a rigid artefact with
    /// two sockets, a ball bar): one equation, `|p(qa) - p(qb)| = distance`.
    Distance {
        /// Joint values at the first socket (rad or m).
        qa: Vec<f64>,
        /// Joint values at the second socket.
        qb: Vec<f64>,
        /// The known distance (m).
        distance: f64,
    },
    /// The tool point held on a fixed, unknown point (pivoting): three equations,
    /// `p(q) = c_point`, with the point estimated too.
    Pivot {
        /// Joint values (rad or m).
        q: Vec<f64>,
        /// Which point (0-based group).
        point: usize,
    },
    /// The tool point touching a plane of unknown pose: one equation, `n . p(q) = h`, with the
    /// plane estimated too.
    Plane {
        /// Joint values (rad or m).
        q: Vec<f64>,
        /// Which plane (0-based group).
        plane: usize,
    },
    /// The tool point (a probe ball's centre) touching a sphere of known radius and unknown
    /// centre: one equation, `|p(q) - c_sphere| = radius`, with the centre estimated too.
    Sphere {
        /// Joint values (rad or m).
        q: Vec<f64>,
        /// Which sphere (0-based group).
        sphere: usize,
        /// Distance from the sphere's centre to the tool point at contact (m): the sphere's
        /// radius plus the probe ball's.
        radius: f64,
    },
}

impl Measurement {
    /// The joint values (the first joint vector of a distance).
    pub fn q(&self) -> &[f64] {
        match self {
            Measurement::Pose { q, .. }
            | Measurement::Position { q, .. }
            | Measurement::Pivot { q, .. }
            | Measurement::Plane { q, .. }
            | Measurement::Sphere { q, .. } => q,
            Measurement::Distance { qa, .. } => qa,
        }
    }

    /// Every joint vector of the measurement (two for a distance).
    pub fn joint_vectors(&self) -> Vec<&[f64]> {
        match self {
            Measurement::Distance { qa, qb, .. } => vec![qa, qb],
            _ => vec![self.q()],
        }
    }

    /// Rows this measurement adds to the stacked system: 6 (pose), 3 (position, pivot) or 1.
    pub fn rows(&self) -> usize {
        match self {
            Measurement::Pose { .. } => 6,
            Measurement::Position { .. } | Measurement::Pivot { .. } => 3,
            Measurement::Distance { .. }
            | Measurement::Plane { .. }
            | Measurement::Sphere { .. } => 1,
        }
    }

    /// "pose", "position", "distance", "pivot", "plane" or "sphere".
    pub fn kind(&self) -> &'static str {
        match self {
            Measurement::Pose { .. } => "pose",
            Measurement::Position { .. } => "position",
            Measurement::Distance { .. } => "distance",
            Measurement::Pivot { .. } => "pivot",
            Measurement::Plane { .. } => "plane",
            Measurement::Sphere { .. } => "sphere",
        }
    }
}

/// The left Jacobian of SO(3) at the rotation vector r: `Exp(r + dr) = Exp(J_l(r) dr) Exp(r)`
/// to first order.
fn left_jacobian(r: &Vector3<f64>) -> nalgebra::Matrix3<f64> {
    let th = r.norm();
    let k = r.cross_matrix();
    if th < 1e-8 {
        return nalgebra::Matrix3::identity() + k * 0.5;
    }
    nalgebra::Matrix3::identity()
        + k * ((1.0 - th.cos()) / (th * th))
        + k * k * ((th - th.sin()) / (th * th * th))
}

/// One DH row as the model evaluates it.
#[derive(Debug, Clone, Copy)]
struct RowInfo {
    kind: JointKind,
    /// The q index of an actuated row.
    dof: Option<usize>,
    /// The stored row (for the constant theta of a prismatic row, d of a revolute one).
    row: DhRow,
}

/// A compliance's index in zeta, its joint's axis times gravity's torque (world), and a point
/// on the axis.
type ComplianceAxis = (usize, Vector3<f64>, Vector3<f64>);

/// The calibration model of a serial DH robot: its 4n parameters zeta = [a; alpha; d; theta]
/// (2.84) in that order, each row's joint offset included (theta of a revolute row, d of a
/// prismatic one), and which of them are fixed.
#[derive(Debug, Clone)]
pub struct ParameterModel {
    nominal: Robot,
    convention: Convention,
    rows: Vec<RowInfo>,
    params: Vec<Parameter>,
    /// Index in zeta of the 6 base parameters (translation, rotation), if estimated.
    base_at: Option<usize>,
    /// Index in zeta of the 6 tool parameters, if estimated.
    tool_at: Option<usize>,
    /// Rows (0-based) with Hayati's beta, and the index of beta in zeta.
    betas: Vec<(usize, usize)>,
    /// Rows (0-based) with a compliance, and the index of the compliance in zeta.
    compliances: Vec<(usize, usize)>,
}

impl ParameterModel {
    /// The model of `robot`, every parameter free. The robot must be a serial DH chain (one
    /// convention, each joint the child of the previous, no couplings) with its first
    /// end-effector on the last row.
    pub fn new(robot: &Robot) -> Result<Self, CalibrationError> {
        let (convention, table) = robot.dh_table().ok_or(CalibrationError::NotSerialDh(
            "not one chain of DH rows in one convention",
        ))?;
        if robot
            .joints()
            .iter()
            .any(|j| matches!(j.drive, Drive::Coupled(_) | Drive::Closure(_)))
        {
            return Err(CalibrationError::NotSerialDh(
                "a joint is coupled to others",
            ));
        }
        if robot.end_effectors()[0].parent + 1 != robot.joints().len() {
            return Err(CalibrationError::NotSerialDh(
                "the first end-effector is not on the last row",
            ));
        }
        let rows: Vec<RowInfo> = robot
            .joints()
            .iter()
            .zip(&table)
            .map(|(j, &(kind, row, _))| RowInfo {
                kind,
                dof: match j.drive {
                    Drive::Actuated(k) => Some(k),
                    _ => None,
                },
                row,
            })
            .collect();
        let n = rows.len();
        let mut params = Vec::with_capacity(4 * n);
        for kind in [Kind::A, Kind::Alpha, Kind::D, Kind::Theta] {
            for (i, &(jk, row, offset)) in table.iter().enumerate() {
                let nominal = match kind {
                    Kind::A => row.a,
                    Kind::Alpha => row.alpha,
                    Kind::D if jk == JointKind::Prismatic => offset,
                    Kind::D => row.d,
                    Kind::Theta if jk == JointKind::Revolute => offset,
                    Kind::Theta => row.theta,
                    Kind::Beta
                    | Kind::BaseTranslation(_)
                    | Kind::BaseRotation(_)
                    | Kind::ToolTranslation(_)
                    | Kind::ToolRotation(_)
                    | Kind::Compliance => 0.0,
                };
                params.push(Parameter {
                    name: format!("{}{}", kind.as_str(), i + 1),
                    joint: i + 1,
                    kind,
                    nominal,
                    fixed: false,
                });
            }
        }
        Ok(Self {
            nominal: robot.clone(),
            convention,
            rows,
            params,
            base_at: None,
            tool_at: None,
            betas: Vec::new(),
            compliances: Vec::new(),
        })
    }

    /// The rows (1-based) whose joint axes i and i + 1 are parallel in the nominal table
    /// (standard DH, |sin alpha_i| < 1e-6), where plain DH cannot place the common normal and
    /// Hayati's beta should replace d_i.
    pub fn parallel_rows(&self) -> Vec<usize> {
        if self.convention != Convention::Standard {
            return Vec::new();
        }
        let n = self.rows.len();
        (0..n.saturating_sub(1))
            .filter(|&i| self.params[n + i].nominal.sin().abs() < 1e-6)
            .filter(|&i| self.rows[i].kind == JointKind::Revolute)
            .map(|i| i + 1)
            .collect()
    }

    /// Uses Hayati's parameter on every row of [`Self::parallel_rows`]: the row becomes
    /// `Rz(theta) Tz(d) Tx(a) Rx(alpha) Ry(beta)` with d fixed at its nominal value and beta
    /// (nominal 0) estimated. Standard DH tables only.
    pub fn with_hayati(mut self) -> Result<Self, CalibrationError> {
        if self.convention != Convention::Standard {
            return Err(CalibrationError::InvalidOption(
                "Hayati's parameter is implemented for standard DH tables".into(),
            ));
        }
        let n = self.rows.len();
        for row in self.parallel_rows() {
            let i = row - 1;
            if self.betas.iter().any(|&(r, _)| r == i) {
                continue;
            }
            self.params[2 * n + i].fixed = true;
            self.betas.push((i, self.params.len()));
            self.params.push(Parameter {
                name: format!("beta{row}"),
                joint: row,
                kind: Kind::Beta,
                nominal: 0.0,
                fixed: false,
            });
        }
        Ok(self)
    }

    /// The DH convention of the table.
    pub fn convention(&self) -> Convention {
        self.convention
    }

    /// Also estimates one compliance per revolute joint (`c1` .. , rad per N m, nominal 0):
    /// joint i turns by `c_i tau_i(q)` beyond its reading, `tau_i` the torque of gravity (world
    /// -z, 9.80665 m/s^2) on the links after it, from the robot's masses (a URDF's inertials, a
    /// model file's `mass` and `com`) on the nominal geometry. An error when the robot has none.
    pub fn with_compliance(mut self) -> Result<Self, CalibrationError> {
        if self.nominal.masses.iter().all(|m| m.joint.is_none()) {
            return Err(CalibrationError::InvalidOption(
                "joint compliance needs the links' masses: a URDF with <inertial> elements, or \
                 `mass` and `com` on the joints of the model file"
                    .into(),
            ));
        }
        for i in 0..self.rows.len() {
            if self.rows[i].kind != JointKind::Revolute || self.rows[i].dof.is_none() {
                continue;
            }
            if self.compliances.iter().any(|&(r, _)| r == i) {
                continue;
            }
            self.compliances.push((i, self.params.len()));
            self.params.push(Parameter {
                name: format!("c{}", i + 1),
                joint: i + 1,
                kind: Kind::Compliance,
                nominal: 0.0,
                fixed: false,
            });
        }
        Ok(self)
    }

    /// The torque of gravity on each row's joint at `q` (N m, about the joint's axis; 0 for a
    /// row without a compliance), from the nominal robot's masses and geometry.
    fn gravity_torques(&self, q: &[f64]) -> Result<Vec<f64>, CalibrationError> {
        let mut tau = vec![0.0; self.rows.len()];
        if self.compliances.is_empty() {
            return Ok(tau);
        }
        let robot = &self.nominal;
        let frames = robot.fk_frames(q)?;
        let g = Vector3::new(0.0, 0.0, -9.80665);
        for &(i, _) in &self.compliances {
            // Joint i's axis: z of the frame before it (with its constant pre), standard DH.
            let j = &robot.joints()[i];
            let before = j.parent.map_or(robot.base, |p| frames[p]) * j.pre;
            let (u, o) = match self.convention {
                Convention::Standard => (before.rotation * Vector3::z(), before.translation.vector),
                Convention::Modified => (
                    frames[i].rotation * Vector3::z(),
                    frames[i].translation.vector,
                ),
            };
            tau[i] = robot
                .masses
                .iter()
                .filter(|m| m.joint.is_some_and(|a| a >= i))
                .map(|m| {
                    let p = frames[m.joint.unwrap_or(0)] * nalgebra::Point3::from(m.com);
                    u.dot(&(p.coords - o).cross(&(g * m.mass)))
                })
                .sum();
        }
        Ok(tau)
    }

    /// Per compliance: its index in zeta, the joint's axis (world) times gravity's torque on it
    /// at `q`, and a point on the axis; `frames` are [`Self::frames`]'s.
    fn compliance_axes(
        &self,
        frames: &[Pose],
        q: &[f64],
    ) -> Result<Vec<ComplianceAxis>, CalibrationError> {
        if self.compliances.is_empty() {
            return Ok(Vec::new());
        }
        let tau = self.gravity_torques(q)?;
        Ok(self
            .compliances
            .iter()
            .map(|&(i, k)| {
                let f = match self.convention {
                    Convention::Standard => &frames[i],
                    Convention::Modified => &frames[i + 1],
                };
                (k, f.rotation * Vector3::z() * tau[i], f.translation.vector)
            })
            .collect())
    }

    /// The rows (1-based) that use Hayati's beta.
    pub fn hayati_rows(&self) -> Vec<usize> {
        self.betas.iter().map(|&(i, _)| i + 1).collect()
    }

    fn beta_of(&self, zeta: &[f64], i: usize) -> Option<f64> {
        self.betas
            .iter()
            .find(|&&(r, _)| r == i)
            .map(|&(_, k)| zeta[k])
    }

    /// Also estimates the base transform: 6 parameters (`base_x` .. `base_rz`, nominal 0) after
    /// the DH ones, `world_from_base = Trans(t) Rot(r) world_from_base_nominal`.
    pub fn with_base(mut self) -> Self {
        if self.base_at.is_none() {
            self.base_at = Some(self.params.len());
            self.push_six(0, Kind::BaseTranslation, Kind::BaseRotation);
        }
        self
    }

    /// Also estimates the tool transform: 6 parameters (`tool_x` .. `tool_rz`, nominal 0),
    /// `flange_from_tool = flange_from_tool_nominal Trans(t) Rot(r)`.
    pub fn with_tool(mut self) -> Self {
        if self.tool_at.is_none() {
            self.tool_at = Some(self.params.len());
            let joint = self.rows.len() + 1;
            self.push_six(joint, Kind::ToolTranslation, Kind::ToolRotation);
        }
        self
    }

    fn push_six(&mut self, joint: usize, t: fn(usize) -> Kind, r: fn(usize) -> Kind) {
        for kind in (0..3).map(t).chain((0..3).map(r)) {
            self.params.push(Parameter {
                name: kind.as_str().into(),
                joint,
                kind,
                nominal: 0.0,
                fixed: false,
            });
        }
    }

    /// `Trans(t) Rot(r)` of the six parameters starting at `at` (identity when not estimated).
    fn six(zeta: &[f64], at: Option<usize>) -> Pose {
        at.map_or_else(Pose::identity, |k| {
            Pose::from_parts(
                Translation3::new(zeta[k], zeta[k + 1], zeta[k + 2]),
                Rotation3::new(Vector3::new(zeta[k + 3], zeta[k + 4], zeta[k + 5])),
            )
        })
    }

    /// Fixes the named parameters ("d2", "theta1", ...); unknown names are an error.
    pub fn fix(&mut self, names: &[&str]) -> Result<(), CalibrationError> {
        for name in names {
            let p = self
                .params
                .iter_mut()
                .find(|p| p.name == *name)
                .ok_or_else(|| {
                    CalibrationError::InvalidOption(format!("no parameter named {name:?}"))
                })?;
            p.fixed = true;
        }
        Ok(())
    }

    /// Every parameter, in the order of zeta.
    pub fn parameters(&self) -> &[Parameter] {
        &self.params
    }

    /// Indices (into zeta) of the free parameters.
    pub fn free(&self) -> Vec<usize> {
        (0..self.params.len())
            .filter(|&k| !self.params[k].fixed)
            .collect()
    }

    /// The nominal zeta.
    pub fn nominal(&self) -> Vec<f64> {
        self.params.iter().map(|p| p.nominal).collect()
    }

    /// The nominal robot.
    pub fn nominal_robot(&self) -> &Robot {
        &self.nominal
    }

    /// Number of DH rows n (zeta has 4n entries).
    pub fn rows(&self) -> usize {
        self.rows.len()
    }

    /// The parameters of row i (0-based) as (a, alpha, d, theta) of zeta.
    fn row_values(&self, zeta: &[f64], i: usize) -> [f64; 4] {
        let n = self.rows.len();
        [zeta[i], zeta[n + i], zeta[2 * n + i], zeta[3 * n + i]]
    }

    /// `world_from_frame_i` for i = 0 (the base) .. n with the parameters `zeta`, and the tool
    /// pose: `k(zeta, q)` of (2.84) with the robot's base and tool.
    pub fn frames(&self, zeta: &[f64], q: &[f64]) -> Result<(Vec<Pose>, Pose), CalibrationError> {
        self.nominal.check_q(q)?;
        let tau = self.gravity_torques(q)?;
        let mut frames = Vec::with_capacity(self.rows.len() + 1);
        let mut t = Self::six(zeta, self.base_at) * self.nominal.base;
        frames.push(t);
        for (i, r) in self.rows.iter().enumerate() {
            let [a, alpha, d, theta] = self.row_values(zeta, i);
            let bend = self
                .compliances
                .iter()
                .find(|&&(row, _)| row == i)
                .map_or(0.0, |&(_, k)| zeta[k] * tau[i]);
            let v = r.dof.map_or(0.0, |k| q[k]) + bend;
            let (theta, d) = match r.kind {
                JointKind::Revolute => (v + theta, d),
                JointKind::Prismatic => (theta, v + d),
                JointKind::Fixed => (theta, d),
            };
            let row = DhRow { a, alpha, d, theta };
            t *= row.transform(self.convention, theta, d);
            if let Some(beta) = self.beta_of(zeta, i) {
                t *= crate::kinematics::pose::rot_y(beta);
            }
            frames.push(t);
        }
        let tool = t * self.nominal.end_effectors()[0].tool * Self::six(zeta, self.tool_at);
        Ok((frames, tool))
    }

    /// The robot with the parameters `zeta` (its DH rows and joint offsets replaced): what
    /// `--write-model` saves. Its FK equals [`Self::frames`]'s tool pose.
    pub fn robot_with(&self, zeta: &[f64]) -> Result<Robot, CalibrationError> {
        let mut r = self.nominal.clone();
        r.base = Self::six(zeta, self.base_at) * self.nominal.base;
        r.set_tool(
            0,
            self.nominal.end_effectors()[0].tool * Self::six(zeta, self.tool_at),
        )?;
        for (i, info) in self.rows.iter().enumerate() {
            let [a, alpha, d, theta] = self.row_values(zeta, i);
            let (row, offset) = match info.kind {
                JointKind::Revolute => (
                    DhRow {
                        a,
                        alpha,
                        d,
                        theta: info.row.theta,
                    },
                    theta,
                ),
                JointKind::Prismatic => (
                    DhRow {
                        a,
                        alpha,
                        d: info.row.d,
                        theta,
                    },
                    d,
                ),
                JointKind::Fixed => (DhRow { a, alpha, d, theta }, 0.0),
            };
            r.set_dh_row(i, row)?;
            if let Some(beta) = self.beta_of(zeta, i) {
                // Ry(beta) after row i: the constant transform before row i + 1.
                let pre = crate::kinematics::pose::rot_y(beta) * r.joints()[i + 1].pre;
                r.set_pre(i + 1, pre)?;
            }
            if info.kind != JointKind::Fixed {
                let limits = r.joints()[i].limits;
                r.set_offset_limits(i, offset, limits)?;
            }
        }
        Ok(r)
    }

    /// The error `[p_measured - p_model; delta phi]` (6 rows, or 3 for a position) of one
    /// pose or position measurement against the model with `zeta`, written into `out` (the
    /// other kinds are an error here: their residual needs the setup's unknowns).
    pub fn residual(
        &self,
        zeta: &[f64],
        m: &Measurement,
        out: &mut [f64],
    ) -> Result<(), CalibrationError> {
        let (_, t) = self.frames(zeta, m.q())?;
        match m {
            Measurement::Pose {
                world_from_tool, ..
            } => {
                let dp = world_from_tool.translation.vector - t.translation.vector;
                let aa =
                    angle_axis_from_rotation(&(world_from_tool.rotation * t.rotation.inverse()));
                let dphi = aa.axis.into_inner() * aa.angle;
                out[..3].copy_from_slice(dp.as_slice());
                out[3..6].copy_from_slice(dphi.as_slice());
            }
            Measurement::Position { p, .. } => {
                out[..3].copy_from_slice((p - t.translation.vector).as_slice());
            }
            _ => {
                return Err(CalibrationError::InvalidOption(format!(
                    "a {} measurement's residual needs the setup's unknowns",
                    m.kind()
                )));
            }
        }
        Ok(())
    }

    /// Phi(zeta) of (2.86) for one configuration: 6 x 4n (or 3 x 4n with `position_only`), the
    /// first-order change of `[p; phi]` of the tool per unit change of each parameter.
    ///
    /// Every parameter moves the tool like a joint would: a length (a or d) translates along a
    /// DH axis, an angle (theta or alpha) rotates about one; so a column is `[u; 0]` or
    /// `[u x (p_e - o); u]` with u the axis and o a point on it. Standard rows
    /// `Rz(theta) Tz(d) Tx(a) Rx(alpha)`: theta and d along z_{i-1} through o_{i-1}, a and alpha
    /// along x_i through o_i. Modified rows `Rx(alpha) Tx(a) Rz(theta) Tz(d)`: alpha and a along
    /// x_{i-1} through o_{i-1}, theta and d along z_i through o_i.
    pub fn calibration_matrix(
        &self,
        zeta: &[f64],
        q: &[f64],
        position_only: bool,
    ) -> Result<DMatrix<f64>, CalibrationError> {
        let (frames, tool) = self.frames(zeta, q)?;
        let pe = tool.translation.vector;
        let n = self.rows.len();
        let rows = if position_only { 3 } else { 6 };
        let mut phi = DMatrix::zeros(rows, self.params.len());
        let mut put = |col: usize, u: Vector3<f64>, o: Option<Vector3<f64>>| {
            let (lin, ang) = match o {
                Some(o) => (u.cross(&(pe - o)), u),
                None => (u, Vector3::zeros()),
            };
            for k in 0..3 {
                phi[(k, col)] = lin[k];
                if !position_only {
                    phi[(3 + k, col)] = ang[k];
                }
            }
        };
        for i in 0..n {
            let prev = &frames[i];
            let this = &frames[i + 1];
            let axis = |p: &Pose, c: usize| p.rotation.matrix().column(c).into_owned();
            let origin = |p: &Pose| p.translation.vector;
            // With Hayati's beta, frame i ends with Ry(beta): a and alpha act along the x axis
            // before it (Ry turns x), through the same origin.
            let x_before_beta = match self.beta_of(zeta, i) {
                Some(beta) => this.rotation.matrix() * Vector3::new(beta.cos(), 0.0, beta.sin()),
                None => axis(this, 0),
            };
            let (a_axis, a_point, t_axis, t_point) = match self.convention {
                // a, alpha along x_i through o_i; theta, d along z_{i-1} through o_{i-1}.
                Convention::Standard => (x_before_beta, origin(this), axis(prev, 2), origin(prev)),
                // a, alpha along x_{i-1} through o_{i-1}; theta, d along z_i through o_i.
                Convention::Modified => (axis(prev, 0), origin(prev), axis(this, 2), origin(this)),
            };
            put(i, a_axis, None);
            put(n + i, a_axis, Some(a_point));
            put(2 * n + i, t_axis, None);
            put(3 * n + i, t_axis, Some(t_point));
        }
        // A compliance turns joint i by tau_i: the joint's own column times tau_i.
        for (k, u, o) in self.compliance_axes(&frames, q)? {
            put(k, u, Some(o));
        }
        for &(i, k) in &self.betas {
            // Ry(beta) at the end of row i: a rotation about y_i through o_i.
            let f = &frames[i + 1];
            put(k, f.rotation * Vector3::y(), Some(f.translation.vector));
        }
        if let Some(k) = self.base_at {
            // world_from_tool = Trans(t) Rot(r) B X: a translation e_j moves everything by e_j;
            // a change of r rotates by omega = J_l(r) e_j about the base origin t.
            let t = Vector3::new(zeta[k], zeta[k + 1], zeta[k + 2]);
            let jl = left_jacobian(&Vector3::new(zeta[k + 3], zeta[k + 4], zeta[k + 5]));
            for j in 0..3 {
                put(k + j, Vector3::ith(j, 1.0), None);
                put(k + 3 + j, jl.column(j).into_owned(), Some(t));
            }
        }
        if let Some(k) = self.tool_at {
            // world_from_tool = A Trans(t) Rot(r): t moves the tool point along A's axes; r turns
            // the tool about its own point by omega = R_A J_l(r) e_j.
            let a = frames[n] * self.nominal.end_effectors()[0].tool;
            let ra = a.rotation.matrix();
            let jl = left_jacobian(&Vector3::new(zeta[k + 3], zeta[k + 4], zeta[k + 5]));
            for j in 0..3 {
                put(k + j, ra.column(j).into_owned(), None);
                put(k + 3 + j, ra * jl.column(j), Some(pe));
            }
        }
        Ok(phi)
    }
}
