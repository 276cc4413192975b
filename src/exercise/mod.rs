//! Exercises checked automatically (Sects. 2.8-2.12): per student, a question in Markdown with
//! what its figure must show, and an answer key; answers graded by equivalence, not by string,
//! with feedback that names the first wrong item in words. Pure compute: the CLI writes the
//! files and draws the figures.
//!
//! The kinds: `dh-table` (write the DH table of the arm drawn with its base and tool frames:
//! [`dh_table`]), `fk` (T at a given q), `ik` (every solution of a pose, with postures),
//! `workspace` (which points a two-link arm reaches and with how many postures; the area of its
//! workspace), `redundancy` (n, m, r for a stated task), `identifiability`; and the orientation
//! kinds `euler`, `compose`, `axis-angle` and `quaternion` ([`orientation`]), which draw no arm.

pub mod dh_table;
pub mod orientation;
pub mod sheet_file;

use crate::kinematics::ik::Target;
use crate::kinematics::ik::closed_form::{ClosedForm, Solutions, Verify};
use crate::kinematics::models::built_in;
use crate::kinematics::orientation::Step;
use crate::kinematics::pose::pose_to_rows;
use crate::kinematics::redundancy::{Redundancy, Task};
use crate::kinematics::{Convention, DhJoint, DhRow, JointKind, Pose, Robot};
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use thiserror::Error;

pub use dh_table::Tolerance;
pub use orientation::{EulerConvention, OrientationAnswer};
pub use sheet_file::{SHEET_FORMAT, SheetFile};

/// The format tag written into every key.
pub const KEY_FORMAT: &str = "armlab exercise key 1";

/// The kinds of exercise.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Kind {
    /// Write the DH table of the arm drawn with its base and tool frames only.
    DhTable,
    /// T at a given q.
    Fk,
    /// Every solution of a pose, with its posture.
    Ik,
    /// Which points a two-link planar arm reaches, with how many postures; its workspace area.
    Workspace,
    /// n, m and r for a stated task.
    Redundancy,
    /// Which DH parameters a stated measurement setup cannot identify (Sect. 2.11).
    Identifiability,
    /// The Euler angles (ZYZ, ZXZ or RPY) of a given matrix.
    Euler,
    /// The matrix of a described sequence of elementary rotations about current or fixed axes.
    Compose,
    /// The angle and axis of a given matrix.
    AxisAngle,
    /// The unit quaternion of a given matrix.
    Quaternion,
}

impl Kind {
    /// Every kind, in the CLI's order.
    pub const ALL: [Kind; 10] = [
        Kind::DhTable,
        Kind::Fk,
        Kind::Ik,
        Kind::Workspace,
        Kind::Redundancy,
        Kind::Identifiability,
        Kind::Euler,
        Kind::Compose,
        Kind::AxisAngle,
        Kind::Quaternion,
    ];

    /// The CLI name (`dh-table`).
    pub fn name(self) -> &'static str {
        match self {
            Kind::DhTable => "dh-table",
            Kind::Fk => "fk",
            Kind::Ik => "ik",
            Kind::Workspace => "workspace",
            Kind::Redundancy => "redundancy",
            Kind::Identifiability => "identifiability",
            Kind::Euler => "euler",
            Kind::Compose => "compose",
            Kind::AxisAngle => "axis-angle",
            Kind::Quaternion => "quaternion",
        }
    }

    /// Whether the kind is an orientation exercise ([`orientation`]): no arm, a given matrix or
    /// sequence.
    ///
    /// # Examples
    ///
    /// ```
    /// use armlab::exercise::Kind;
    ///
    /// assert!(Kind::AxisAngle.is_orientation() && !Kind::Fk.is_orientation());
    /// ```
    pub fn is_orientation(self) -> bool {
        matches!(
            self,
            Kind::Euler | Kind::Compose | Kind::AxisAngle | Kind::Quaternion
        )
    }
}

/// What goes wrong making or grading an exercise.
#[derive(Debug, Error, PartialEq)]
pub enum ExerciseError {
    /// The robot does not suit the kind.
    #[error("{kind} exercise: {reason}")]
    Unsuitable {
        /// The kind's name.
        kind: &'static str,
        /// Why.
        reason: String,
    },
    /// An answer of the wrong shape.
    #[error("answer: {reason}")]
    Answer {
        /// What is wrong.
        reason: String,
    },
    /// A field of an answer file that cannot be read: the file, the line (1-based) and the
    /// field (`None` where the whole line is at fault).
    #[error(
        "answer: {file}: line {line}{}: {problem}",
        .field.map(|f| format!(", field {f}")).unwrap_or_default()
    )]
    AnswerField {
        /// The file, as named to the reader.
        file: String,
        /// The line (1-based).
        line: usize,
        /// The field's name (`theta`, `r21`).
        field: Option<&'static str>,
        /// What is wrong with it.
        problem: orientation::FieldProblem,
    },
    /// An orientation key without the question its kind needs.
    #[error("{kind} key: no {field}")]
    KeyField {
        /// The kind's name.
        kind: &'static str,
        /// The missing field (`matrix`, `convention`, `sequence`).
        field: &'static str,
    },
}

/// The answer key of one sheet (written as JSON by the CLI). The arm kinds carry `robot`,
/// `model` and `q`; the orientation kinds carry their question instead: `matrix` (euler,
/// axis-angle, quaternion), `convention` (euler), `sequence` (compose).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Key {
    /// [`KEY_FORMAT`].
    #[serde(default = "key_format")]
    pub format: String,
    /// The kind.
    pub kind: Kind,
    /// The seed the class was made with.
    #[serde(default)]
    pub seed: u64,
    /// The student's number (1-based).
    #[serde(default)]
    pub student: usize,
    /// The arm's name (empty for the orientation kinds).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub robot: String,
    /// The arm as a TOML model file (DH rows, base and tool at its frames 0 and n; empty for
    /// the orientation kinds).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub model: String,
    /// The configuration drawn or asked about (rad, m; empty for the orientation kinds).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub q: Vec<f64>,
    /// The given rotation matrix, rows (euler, axis-angle, quaternion).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub matrix: Option<[[f64; 3]; 3]>,
    /// The Euler convention asked for (euler).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub convention: Option<EulerConvention>,
    /// The sequence of elementary rotations, in the order the sheet states it (compose; angles
    /// in rad).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sequence: Option<Vec<Step>>,
    /// What the sheet asks and its answer (an orientation key may leave it out: grading derives
    /// the answer from the question).
    #[serde(default = "KeyAnswer::from_question")]
    pub answer: KeyAnswer,
    /// Tolerances of the grading (the orientation kinds compare matrix entries within
    /// `angle`).
    #[serde(default)]
    pub tolerance: Tolerance,
    /// The sheet's question (Markdown), for the app's Exercise tab.
    #[serde(default)]
    pub question: String,
}

/// [`KEY_FORMAT`], for keys written without it.
fn key_format() -> String {
    KEY_FORMAT.into()
}

/// The answer part of a key.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case")]
pub enum KeyAnswer {
    /// Any DH table describing the model (graded by [`dh_table::check`]).
    DhTable,
    /// `T` (rows) at `q`.
    Fk {
        /// Rows of T (m).
        t: [[f64; 4]; 4],
    },
    /// Every solution of `target`, with its posture.
    Ik {
        /// Rows of the target pose (m).
        target: [[f64; 4]; 4],
        /// The solutions (rad, m) and their postures.
        solutions: Vec<(Vec<f64>, String)>,
    },
    /// Points (m, in the arm's plane), the number of postures reaching each, the area (m^2).
    Workspace {
        /// The points asked about.
        points: Vec<[f64; 2]>,
        /// How many postures reach each (0, 1 on the boundary, 2).
        postures: Vec<usize>,
        /// The workspace's area, 4 pi a1 a2 (m^2).
        area: f64,
    },
    /// The parameters a setup cannot identify on their own, and why, in words.
    Identifiability {
        /// The setup's name (`pose`, `position`, `distance`).
        setup: String,
        /// The parameters' names (`d2`, `theta6`).
        parameters: Vec<String>,
        /// The combinations the data sees instead, in words.
        combinations: Vec<String>,
    },
    /// n, m, r for `task`.
    Redundancy {
        /// The task's CLI name.
        task: String,
        /// Joints.
        n: usize,
        /// Operational space dimension.
        m: usize,
        /// Components the task constrains.
        r: usize,
    },
    /// The Euler angles of the key's matrix (graded from `matrix` and `convention`).
    Euler(orientation::EulerReference),
    /// The product of the key's sequence (graded from `sequence`).
    Compose(orientation::ComposeReference),
    /// The angle and axis of the key's matrix (graded from `matrix`).
    AxisAngle(orientation::AxisAngleReference),
    /// The quaternion of the key's matrix (graded from `matrix`).
    Quaternion(orientation::QuaternionReference),
    /// An orientation key written without its reference answer: grading derives it from the
    /// key's question.
    FromQuestion,
}

impl KeyAnswer {
    /// [`KeyAnswer::FromQuestion`]: what a key without an `answer` holds.
    fn from_question() -> Self {
        KeyAnswer::FromQuestion
    }
}

/// One sheet: the question (Markdown), the key, and the arm and configuration its figure
/// draws.
#[derive(Debug, Clone)]
pub struct Sheet {
    /// The question in Markdown (the figure is `figure.png` next to it).
    pub markdown: String,
    /// The answer key.
    pub key: Key,
    /// The arm drawn (`None` for the orientation kinds).
    pub robot: Option<Robot>,
    /// Its configuration in the figure.
    pub q: Vec<f64>,
    /// Draw the DH frames of every joint (false: the base and tool frames only).
    pub frames: bool,
    /// A target frame to draw (ik; for euler, axis-angle and quaternion the given frame).
    pub target: Option<Pose>,
    /// Points to mark (workspace), world frame (m).
    pub points: Vec<[f64; 3]>,
}

/// The question of an `fk` sheet: the arm, its DH table, q (`shown`), what to hand in.
fn fk_question(arm: &Robot, shown: &str) -> String {
    format!(
        "# Direct kinematics\n\n{}\n\nThe figure shows the arm with its DH frames; its table:\n\n{}\n\
         Compute the end-effector pose T = T_n^0(q) (2.50) at\n\n    q = {shown}\n\n\
         Answer with a text file of four rows of four numbers (the rows of T, metres), \
         hand it in: the app's Exercise tab saves it under your sheet's name (`student-NN.txt`).\n",
        arm.name,
        dh_table_markdown(arm)
    )
}

/// The arms `--random` draws from (the textbook's, with their lengths varied).
pub const POOL: [&str; 7] = [
    "planar3",
    "anthropomorphic3r",
    "spherical_arm",
    "stanford",
    "anthropomorphic_spherical_wrist",
    "scara",
    "puma560",
];

/// A small deterministic generator (xorshift), seeded per student.
pub struct Rng(u64);

impl Rng {
    /// A generator for `seed` and `student`.
    pub fn new(seed: u64, student: usize) -> Self {
        Rng((seed ^ 0x9E37_79B9_7F4A_7C15).wrapping_mul(student as u64 * 2 + 1) | 1)
    }

    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [lo, hi), rounded to `step`.
    pub fn stepped(&mut self, lo: f64, hi: f64, step: f64) -> f64 {
        ((lo + (hi - lo) * self.uniform()) / step).round() * step
    }
}

/// The arm of a sheet: the serial DH chain of end-effector 0 with base and tool at its frames
/// 0 and n (what the figure draws), optionally with its nonzero lengths varied (`--random`).
pub fn sheet_arm(robot: &Robot, rng: Option<&mut Rng>) -> Result<Robot, ExerciseError> {
    let unsuitable = |reason: &str| ExerciseError::Unsuitable {
        kind: "this",
        reason: reason.into(),
    };
    let (conv, table) = robot
        .dh_table()
        .ok_or_else(|| unsuitable("the arm needs a serial DH table"))?;
    let mut rows: Vec<DhJoint> = table
        .iter()
        .map(|(k, r, o)| DhJoint::new(*k, *r).offset(*o))
        .collect();
    for (row, j) in rows.iter_mut().zip(robot.joints()) {
        row.limits = j.limits;
        row.name = Some(j.name.clone());
    }
    if let Some(rng) = rng {
        for r in &mut rows {
            for v in [&mut r.row.a, &mut r.row.d] {
                if *v != 0.0 {
                    *v = v.signum() * rng.stepped(0.2, 0.8, 0.05);
                }
            }
        }
    }
    Robot::from_dh(&robot.name, conv, &rows, Pose::identity(), Pose::identity())
        .map_err(|e| unsuitable(&e.to_string()))
}

/// A configuration inside the limits, away from them, on a 15-degree (5 cm) grid.
fn random_q(robot: &Robot, rng: &mut Rng) -> Vec<f64> {
    (0..robot.dof())
        .map(|k| {
            let [lo, hi] = robot.sampling_range(k);
            let (lo, hi) = (lo + 0.15 * (hi - lo), hi - 0.15 * (hi - lo));
            if robot.dof_joint(k).kind == JointKind::Prismatic {
                rng.stepped(lo, hi, 0.05)
            } else {
                rng.stepped(lo, hi, PI / 12.0)
            }
        })
        .collect()
}

/// Makes one sheet. `robot`: the arm of every sheet (`--robot`), or `None` to draw one per
/// student from [`POOL`] with varied lengths (`--random`); the orientation kinds take none.
pub fn generate(
    kind: Kind,
    robot: Option<&Robot>,
    seed: u64,
    student: usize,
) -> Result<Sheet, ExerciseError> {
    if kind.is_orientation() {
        if robot.is_some() {
            return Err(unsuitable(
                kind,
                "an orientation exercise has no arm".into(),
            ));
        }
        return orientation::generate(kind, seed, student);
    }
    let mut rng = Rng::new(seed, student);
    if kind == Kind::Workspace {
        return workspace_sheet(robot, seed, student, &mut rng);
    }
    let arm = match robot {
        Some(r) => sheet_arm(r, None)?,
        None => {
            let name = POOL[(rng.uniform() * POOL.len() as f64) as usize % POOL.len()];
            let base = built_in(name).expect("pool names are built-ins");
            sheet_arm(&base, Some(&mut rng))?
        }
    };
    let q = random_q(&arm, &mut rng);
    let model = crate::model_file::to_toml(&arm).unwrap_or_default();
    let key = |answer: KeyAnswer| Key {
        format: KEY_FORMAT.into(),
        kind,
        seed,
        student,
        robot: arm.name.clone(),
        model: model.clone(),
        q: q.clone(),
        matrix: None,
        convention: None,
        sequence: None,
        answer,
        tolerance: Tolerance::default(),
        question: String::new(),
    };
    let shown = q_text(&arm, &q);
    let mut sheet = Sheet {
        markdown: String::new(),
        key: key(KeyAnswer::DhTable),
        robot: Some(arm.clone()),
        q: q.clone(),
        frames: false,
        target: None,
        points: Vec::new(),
    };
    match kind {
        Kind::DhTable => {
            sheet.markdown = dh_question(&arm, &q, &shown);
        }
        Kind::Fk => {
            let t = arm.fk(&q).map_err(|e| unsuitable(kind, e.to_string()))?;
            sheet.key = key(KeyAnswer::Fk {
                t: pose_to_rows(&t),
            });
            sheet.frames = true;
            sheet.markdown = fk_question(&arm, &shown);
        }
        Kind::Ik => ik_sheet(&mut sheet, &arm, &mut rng, key(KeyAnswer::DhTable))?,
        Kind::Redundancy => redundancy_sheet(&mut sheet, &arm, &mut rng, key(KeyAnswer::DhTable)),
        Kind::Identifiability => {
            identifiability_sheet(&mut sheet, &arm, &mut rng, key(KeyAnswer::DhTable))?
        }
        Kind::Workspace | Kind::Euler | Kind::Compose | Kind::AxisAngle | Kind::Quaternion => {
            unreachable!("handled above")
        }
    }
    sheet.key.question = sheet.markdown.clone();
    Ok(sheet)
}

fn unsuitable(kind: Kind, reason: String) -> ExerciseError {
    ExerciseError::Unsuitable {
        kind: kind.name(),
        reason,
    }
}

/// q as the sheet prints it: degrees for revolute joints, metres for prismatic ones.
fn q_text(robot: &Robot, q: &[f64]) -> String {
    let parts: Vec<String> = q
        .iter()
        .enumerate()
        .map(|(k, v)| match robot.dof_joint(k).kind {
            JointKind::Prismatic => format!("{v:.3} m"),
            _ => format!("{:.0} deg", v.to_degrees()),
        })
        .collect();
    format!("({})", parts.join(", "))
}

/// The arm's DH table as a Markdown table (for the kinds that give it).
fn dh_table_markdown(robot: &Robot) -> String {
    let Some((conv, table)) = robot.dh_table() else {
        return String::new();
    };
    let mut s = format!(
        "{} convention:\n\n| row | joint | a (m) | alpha (deg) | d (m) | theta (deg) |\n|---|---|---|---|---|---|\n",
        conv.as_str()
    );
    for (i, (kind, row, _)) in table.iter().enumerate() {
        let (d, theta) = match kind {
            JointKind::Prismatic => ("q".to_string(), format!("{:.0}", row.theta.to_degrees())),
            _ => (format!("{}", row.d), "q".to_string()),
        };
        s.push_str(&format!(
            "| {} | {} | {} | {:.0} | {d} | {theta} |\n",
            i + 1,
            kind.as_str(),
            row.a,
            row.alpha.to_degrees()
        ));
    }
    s
}

/// Each actuated joint's axis at `q` in the base frame: a point on it and its direction (z of
/// the frame before the joint; for the modified convention z of the joint's own frame). (m)
pub(crate) fn joint_axes(arm: &Robot, q: &[f64]) -> Vec<(Vector3<f64>, Vector3<f64>)> {
    let frames = arm.fk_frames(q).unwrap_or_default();
    (0..arm.dof())
        .map(|k| {
            let j = arm.dof_joint(k);
            let parent = j.parent.map_or(Pose::identity(), |p| frames[p]);
            let axis_frame = parent * j.pre;
            let (f, axis) = match j.geometry {
                crate::kinematics::JointGeometry::Dh {
                    convention: Convention::Modified,
                    row,
                } => (
                    axis_frame
                        * crate::kinematics::pose::rot_x(row.alpha)
                        * crate::kinematics::pose::trans_x(row.a),
                    Vector3::z(),
                ),
                crate::kinematics::JointGeometry::Dh { .. } => (axis_frame, Vector3::z()),
                // A URDF joint: its origin, and its own axis in that frame.
                crate::kinematics::JointGeometry::Origin {
                    parent_from_joint,
                    axis,
                } => (axis_frame * parent_from_joint, axis.into_inner()),
            };
            (f.translation.vector, f.rotation * axis)
        })
        .collect()
}

/// The dh-table question: the arm's joint axes in the base frame at the drawn q (so that the
/// lengths can be read off), the tool frame, and what to hand in.
fn dh_question(arm: &Robot, q: &[f64], shown: &str) -> String {
    let mut s = format!(
        "# The DH table of an arm\n\nThe figure shows an arm with {} joints at q = {shown}, with \
         only its base frame (frame 0) and its tool frame (frame {}). Revolute joints are drawn \
         as cylinders along their axes, prismatic joints as boxes.\n\nIts joint axes at this q, \
         in the base frame (m):\n\n| joint | type | a point on the axis | direction |\n|---|---|---|---|\n",
        arm.dof(),
        arm.dof()
    );
    for (k, (p, z)) in joint_axes(arm, q).iter().enumerate() {
        s.push_str(&format!(
            "| {} | {} | ({:.3}, {:.3}, {:.3}) | ({:.3}, {:.3}, {:.3}) |\n",
            k + 1,
            arm.dof_joint(k).kind.as_str(),
            p.x,
            p.y,
            p.z,
            z.x,
            z.y,
            z.z
        ));
    }
    let tool = arm.fk(q).unwrap_or_default();
    let r = pose_to_rows(&tool);
    s.push_str(&format!(
        "\nThe tool frame in the base frame (rows of T, m):\n\n    {}\n\n",
        r.iter()
            .map(|row| row
                .iter()
                .map(|v| format!("{v:7.3}"))
                .collect::<Vec<_>>()
                .join(" "))
            .collect::<Vec<_>>()
            .join("\n    ")
    ));
    s.push_str(
        "Write the arm's DH table (standard or modified convention) as an armlab model file \
         (`name`, `convention`, one `[[joints]]` per row with `type`, `a`, `alpha`, `d`, and \
         `offset` where your q differs from the figure's), with frame 0 the base frame and frame \
         n the tool frame. Any valid choice of the z axes' directions and of the x axes is \
         accepted. Hand it in as `student-NN.toml` (the app's Exercise tab writes it from the grid).\n",
    );
    s
}

/// The redundancy sheet: a task drawn at random among pose, position, position + axis.
fn redundancy_sheet(sheet: &mut Sheet, arm: &Robot, rng: &mut Rng, key: Key) {
    let tasks = [Task::Pose, Task::Position, Task::PositionAxis];
    let task = tasks[(rng.uniform() * 3.0) as usize % 3];
    let red = Redundancy::of(arm, task);
    sheet.key = Key {
        answer: KeyAnswer::Redundancy {
            task: task.name().into(),
            n: red.n,
            m: red.m,
            r: red.r,
        },
        ..key
    };
    sheet.markdown = format!(
        "# Redundancy\n\n{} ({} joints, figure). The task: {} ({}).\n\n\
         Give n (joint-space dimension), m (operational-space dimension) and r (the \
         components the task prescribes), Sect. 2.10.2, as one row `n m r`; then \
         hand it in: the app's Exercise tab saves it under your sheet's name (`student-NN.txt`).\n",
        arm.name,
        arm.dof(),
        task.name(),
        task.description()
    );
}

/// The identifiability sheet: plain DH parameters (no Hayati), a setup drawn among full poses,
/// tool points and a distance artefact, the rank analysis (2.87) of noise-free measurements at
/// the nominal parameters.
fn identifiability_sheet(
    sheet: &mut Sheet,
    arm: &Robot,
    rng: &mut Rng,
    key: Key,
) -> Result<(), ExerciseError> {
    use crate::calibration::{
        CalibrationOptions, ParameterModel, Setup, SetupScene, identifiability, nominal_examples,
    };
    let fail =
        |e: crate::calibration::CalibrationError| unsuitable(Kind::Identifiability, e.to_string());
    let setups = [Setup::Pose, Setup::Position, Setup::Distance];
    let setup = setups[(rng.uniform() * 3.0) as usize % 3];
    let model = ParameterModel::new(arm).map_err(fail)?;
    let scene = SetupScene {
        setup,
        ..SetupScene::default()
    };
    let seed = (rng.uniform() * 1e9) as u64;
    let ms = nominal_examples(&model, &scene, 60, seed).map_err(fail)?;
    let id = identifiability(
        &model,
        &model.nominal(),
        &ms,
        &CalibrationOptions::default(),
    )
    .map_err(fail)?;
    let names: Vec<String> = model.parameters().iter().map(|p| p.name.clone()).collect();
    let parameters: Vec<String> = id
        .unidentifiable
        .iter()
        .filter(|n| names.contains(n))
        .cloned()
        .collect();
    sheet.key = Key {
        answer: KeyAnswer::Identifiability {
            setup: setup.name().into(),
            parameters,
            combinations: id.combinations.clone(),
        },
        ..key
    };
    let what = match setup {
        Setup::Pose => "the full pose of the tool (a tracker measuring position and orientation)",
        Setup::Position => "the position of the tool point only",
        _ => "pairs of tool points a known distance apart (a ball bar)",
    };
    sheet.frames = true;
    sheet.markdown = format!(
        "# Identifiability\n\n{}; its DH table (standard convention, parameters a_i, alpha_i, \
         d_i, theta_i as offsets):\n\n{}\nThe arm is calibrated (Sect. 2.11) from measurements \
         of {what}, at many well spread joint vectors, with every DH parameter free. Which \
         parameters can the measurements not identify on their own? Answer with their names \
         (`d2`, `theta6`, ...), one per line or separated by commas (nothing for none); then \
         hand it in: the app's Exercise tab saves it under your sheet's name (`student-NN.txt`).\n",
        arm.name,
        dh_table_markdown(arm)
    );
    Ok(())
}

/// The ik sheet: a target reached at a random q; every closed-form solution with its posture.
fn ik_sheet(sheet: &mut Sheet, arm: &Robot, rng: &mut Rng, key: Key) -> Result<(), ExerciseError> {
    let solver = ClosedForm::detect(arm).map_err(|e| unsuitable(Kind::Ik, e.to_string()))?;
    let q0 = random_q(arm, rng);
    let target_pose = arm
        .fk(&q0)
        .map_err(|e| unsuitable(Kind::Ik, e.to_string()))?;
    let mut sols = Solutions::default();
    solver
        .solve_into(arm, &Target::Pose(target_pose), Verify::Fk, &mut sols)
        .map_err(|e| unsuitable(Kind::Ik, e.to_string()))?;
    let solutions: Vec<(Vec<f64>, String)> = sols
        .iter()
        .map(|s| (s.q().to_vec(), s.posture.to_string()))
        .collect();
    let target = pose_to_rows(&target_pose);
    sheet.key = Key {
        answer: KeyAnswer::Ik { target, solutions },
        q: q0,
        ..key
    };
    sheet.frames = true;
    sheet.target = Some(target_pose);
    sheet.markdown = format!(
        "# Inverse kinematics\n\n{}; its DH table:\n\n{}\nFind every joint vector q that puts the \
         end-effector at the pose (rows of T, m; the frame drawn in the figure)\n\n    {}\n\n\
         Answer with one row per solution (radians; a first line `# deg` for degrees), in any \
         order; hand it in: the app's Exercise tab saves it under your sheet's name (`student-NN.txt`).\n",
        arm.name,
        dh_table_markdown(arm),
        target
            .iter()
            .map(|row| row
                .iter()
                .map(|v| format!("{v:7.4}"))
                .collect::<Vec<_>>()
                .join(" "))
            .collect::<Vec<_>>()
            .join("\n    ")
    );
    Ok(())
}

/// The workspace sheet: a two-link planar arm (the one given, or random lengths), six points.
fn workspace_sheet(
    robot: Option<&Robot>,
    seed: u64,
    student: usize,
    rng: &mut Rng,
) -> Result<Sheet, ExerciseError> {
    let (a1, a2) = match robot {
        Some(r) => two_link_lengths(r)?,
        None => (rng.stepped(0.4, 1.0, 0.05), rng.stepped(0.2, 0.8, 0.05)),
    };
    let row = |a| {
        DhJoint::revolute(DhRow {
            a,
            alpha: 0.0,
            d: 0.0,
            theta: 0.0,
        })
        .unbounded()
    };
    let arm = Robot::from_dh(
        "Two-link planar arm",
        Convention::Standard,
        &[row(a1), row(a2)],
        Pose::identity(),
        Pose::identity(),
    )
    .map_err(|e| unsuitable(Kind::Workspace, e.to_string()))?;
    let (points, postures) = workspace_points(a1, a2, rng);
    let area = 4.0 * PI * a1 * a2;
    let q = vec![0.0, 0.0];
    let key = Key {
        format: KEY_FORMAT.into(),
        kind: Kind::Workspace,
        seed,
        student,
        robot: arm.name.clone(),
        model: crate::model_file::to_toml(&arm).unwrap_or_default(),
        q: q.clone(),
        matrix: None,
        convention: None,
        sequence: None,
        answer: KeyAnswer::Workspace {
            points: points.clone(),
            postures,
            area,
        },
        tolerance: Tolerance::default(),
        question: String::new(),
    };
    let list: Vec<String> = points
        .iter()
        .enumerate()
        .map(|(i, p)| format!("{}. ({:.4}, {:.4}) m", i + 1, p[0], p[1]))
        .collect();
    let markdown = format!(
        "# Workspace of a two-link planar arm\n\nThe arm has a1 = {a1} m, a2 = {a2} m and joints \
             that turn fully (Sect. 2.10.1). For each point of the plane below, how many postures \
             reach it (0, 1 or 2)? And what is the area of the workspace (m^2)?\n\n{}\n\n\
             Answer with six rows of one number (the counts, in order) and a seventh row with \
             the area; hand it in: the app's Exercise tab saves it under your sheet's name (`student-NN.txt`).\n",
        list.join("\n")
    );
    Ok(Sheet {
        key: Key {
            question: markdown.clone(),
            ..key
        },
        markdown,
        robot: Some(arm),
        q,
        frames: false,
        target: None,
        points: points.iter().map(|p| [p[0], p[1], 0.0]).collect(),
    })
}

/// Six points of the plane and how many postures of the two-link arm reach each: two inside
/// the ring, one on its outer circle, one outside, one in the hole (or inside where there is
/// none), one more inside.
fn workspace_points(a1: f64, a2: f64, rng: &mut Rng) -> (Vec<[f64; 2]>, Vec<usize>) {
    let (inner, outer) = ((a1 - a2).abs(), a1 + a2);
    let mut points = Vec::new();
    let mut postures = Vec::new();
    for i in 0..6 {
        // radii: two inside, one on the outer circle, one outside, one inside the hole (if
        // any), one more inside
        let r = match i {
            0 | 5 => inner + (outer - inner) * (0.2 + 0.6 * rng.uniform()),
            1 => inner + (outer - inner) * 0.5,
            2 => outer,
            3 => outer * (1.1 + 0.3 * rng.uniform()),
            // inside the hole; with a1 = a2 there is none (and the base point is reached with
            // every q1), so one more point inside
            _ if inner > 0.05 => inner * 0.5,
            _ => inner + (outer - inner) * 0.3,
        };
        let phi = rng.stepped(-PI, PI, PI / 36.0);
        let p = [r * phi.cos(), r * phi.sin()];
        // by the law of cosines: two elbow postures strictly inside, one on either circle
        let count = if r > outer + 1e-12 || r < inner - 1e-12 {
            0
        } else if (r - outer).abs() <= 1e-12 || (r - inner).abs() <= 1e-12 {
            1
        } else {
            2
        };
        points.push([(p[0] * 1e4).round() / 1e4, (p[1] * 1e4).round() / 1e4]);
        postures.push(count);
    }
    (points, postures)
}

/// a1, a2 of a two-link planar arm.
fn two_link_lengths(r: &Robot) -> Result<(f64, f64), ExerciseError> {
    match r.dh_table() {
        Some((_, t))
            if t.len() == 2
                && t.iter().all(|(k, row, _)| {
                    *k == JointKind::Revolute && row.alpha == 0.0 && row.d == 0.0
                }) =>
        {
            Ok((t[0].1.a, t[1].1.a))
        }
        _ => Err(unsuitable(
            Kind::Workspace,
            "the workspace exercise needs a two-link planar arm (planar2)".into(),
        )),
    }
}

/// Rows of numbers from an answer's text: one row per line, separated by commas or spaces,
/// `#` comments; a first line `# deg` makes every number an angle in degrees (turned into
/// radians). Errors name `file` and the line.
pub fn parse_rows(text: &str, file: &str) -> Result<Vec<Vec<f64>>, ExerciseError> {
    let degrees = text.lines().next().is_some_and(|l| {
        l.trim()
            .trim_start_matches('#')
            .trim()
            .eq_ignore_ascii_case("deg")
    });
    let mut rows = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let body = line.split('#').next().unwrap_or("").trim();
        if body.is_empty() {
            continue;
        }
        let mut row = Vec::new();
        for field in body
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|f| !f.is_empty())
        {
            let v: f64 = field.parse().map_err(|_| ExerciseError::Answer {
                reason: format!("{file}: line {}: {field:?} is not a number", i + 1),
            })?;
            if !v.is_finite() {
                return Err(ExerciseError::Answer {
                    reason: format!("{file}: line {}: {field:?} is not a finite number", i + 1),
                });
            }
            row.push(if degrees { v.to_radians() } else { v });
        }
        rows.push(row);
    }
    Ok(rows)
}

/// An answer as the CLI read it.
#[derive(Debug, Clone)]
pub enum Answer {
    /// A model file (dh-table).
    Model(Box<Robot>),
    /// Rows of numbers (fk, ik, workspace, redundancy); ik rows in radians.
    Rows(Vec<Vec<f64>>),
    /// Names (identifiability).
    Words(Vec<String>),
    /// An orientation answer ([`orientation::parse_answer`]).
    Orientation(OrientationAnswer),
}

/// A mistake, named: what a class summary counts (`armlab exercise grade`). Its JSON name is
/// the variant in snake_case ("alpha_sign"); `Display` says it in a teacher's words.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Mistake {
    /// A DH table with another number of joint variables than the arm's.
    JointCount,
    /// A model that is not a serial DH table.
    NotDhTable,
    /// A revolute joint written as prismatic, or the other way.
    JointKind,
    /// alpha with the wrong sign: z turned the other way.
    AlphaSign,
    /// a with the wrong sign.
    ASign,
    /// d with the wrong sign.
    DSign,
    /// a and d swapped.
    ASwappedWithD,
    /// alpha wrong by a right angle or a half turn.
    AlphaWrong,
    /// a wrong (not the common normal's length).
    AWrong,
    /// d wrong (not the distance along z).
    DWrong,
    /// A row whose frame no single change explains.
    Unplaced,
    /// An entry of T with the wrong sign.
    TSign,
    /// A position entry of T wrong.
    TPosition,
    /// A rotation entry of T wrong.
    TRotation,
    /// An IK solution missing.
    MissingSolution,
    /// An IK row that does not reach the target.
    ExtraSolution,
    /// A workspace point's number of postures wrong.
    PostureCount,
    /// The workspace's area wrong.
    Area,
    /// n (joints) wrong.
    JointNumber,
    /// m (operational space) wrong.
    OperationalSpace,
    /// r (task components) wrong.
    TaskComponents,
    /// An unidentifiable parameter missed.
    MissedUnidentifiable,
    /// An identifiable parameter named as unidentifiable.
    NamedIdentifiable,
    /// Steps about the current axes composed as about the fixed ones (pre-multiplied).
    FixedForCurrent,
    /// Steps about the fixed axes composed as about the current ones (post-multiplied).
    CurrentForFixed,
    /// The transpose (the rotation back) answered.
    Transpose,
    /// Degrees read as radians.
    DegreesAsRadians,
    /// Radians read as degrees.
    RadiansAsDegrees,
    /// The angles of another Euler convention.
    OtherConvention,
    /// The angles, or the steps, in the reversed order.
    ReversedOrder,
    /// One angle with the wrong sign.
    AngleSign,
    /// A quaternion that is not unit.
    NonUnitQuaternion,
    /// An axis that is not a unit vector.
    NonUnitAxis,
    /// epsilon written before eta.
    EpsilonFirst,
    /// The half angle given for the angle of angle and axis.
    HalfAngle,
    /// The whole angle where the quaternion takes half of it.
    FullAngle,
}

impl std::fmt::Display for Mistake {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Mistake::JointCount => "wrong number of joints",
            Mistake::NotDhTable => "not a DH table",
            Mistake::JointKind => "joint type (revolute or prismatic) wrong",
            Mistake::AlphaSign => "alpha with the wrong sign (z turned the other way)",
            Mistake::ASign => "a with the wrong sign",
            Mistake::DSign => "d with the wrong sign",
            Mistake::ASwappedWithD => "a and d swapped",
            Mistake::AlphaWrong => "alpha wrong (the angle between the z axes)",
            Mistake::AWrong => "a wrong (the length of the common normal)",
            Mistake::DWrong => "d wrong (the distance along z)",
            Mistake::Unplaced => "a frame no single change explains",
            Mistake::TSign => "an entry of T with the wrong sign",
            Mistake::TPosition => "a position entry of T wrong",
            Mistake::TRotation => "a rotation entry of T wrong",
            Mistake::MissingSolution => "an IK solution missing",
            Mistake::ExtraSolution => "an IK row that does not reach the target",
            Mistake::PostureCount => "a point's number of postures wrong",
            Mistake::Area => "the workspace area wrong",
            Mistake::JointNumber => "n (the number of joints) wrong",
            Mistake::OperationalSpace => "m (the operational space) wrong",
            Mistake::TaskComponents => "r (the task's components) wrong",
            Mistake::MissedUnidentifiable => "an unidentifiable parameter missed",
            Mistake::NamedIdentifiable => "an identifiable parameter named",
            Mistake::FixedForCurrent => {
                "you composed about the fixed axes; the sequence turns about the current ones"
            }
            Mistake::CurrentForFixed => {
                "you composed about the current axes; the sequence turns about the fixed ones"
            }
            Mistake::Transpose => "this is the transpose",
            Mistake::DegreesAsRadians => "degrees read as radians",
            Mistake::RadiansAsDegrees => "radians read as degrees",
            Mistake::OtherConvention => "the other convention",
            Mistake::ReversedOrder => "the reversed order",
            Mistake::AngleSign => "an angle with the wrong sign",
            Mistake::NonUnitQuaternion => "a quaternion that is not unit",
            Mistake::NonUnitAxis => "an axis that is not a unit vector",
            Mistake::EpsilonFirst => "eta and epsilon in the wrong order (epsilon first)",
            Mistake::HalfAngle => "the half angle",
            Mistake::FullAngle => "the whole angle in the quaternion",
        })
    }
}

/// One graded item.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Item {
    /// What it is ("row 3", "T\[2\]\[4\]", "solution 2").
    pub item: String,
    /// Right or not.
    pub correct: bool,
    /// In words.
    pub feedback: String,
    /// The mistake, named (None where the item is right or was not graded).
    pub mistake: Option<Mistake>,
}

/// A grade: `score` of `max` and the items.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Grade {
    /// Items right.
    pub score: usize,
    /// Items.
    pub max: usize,
    /// Each item.
    pub items: Vec<Item>,
}

impl Grade {
    fn of(items: Vec<Item>) -> Self {
        Grade {
            score: items.iter().filter(|i| i.correct).count(),
            max: items.len(),
            items,
        }
    }
}

/// The key's arm.
pub fn key_robot(key: &Key) -> Result<Robot, ExerciseError> {
    crate::model_file::parse_model(&key.model, std::path::Path::new("key.model.toml")).map_err(
        |e| ExerciseError::Answer {
            reason: format!("the key's model: {e}"),
        },
    )
}

/// Grades `answer` against `key`.
pub fn grade(key: &Key, answer: &Answer) -> Result<Grade, ExerciseError> {
    if key.kind.is_orientation() {
        return orientation::grade(key, answer);
    }
    let bad = |reason: String| ExerciseError::Answer { reason };
    match (&key.answer, answer) {
        (KeyAnswer::DhTable, Answer::Model(a)) => Ok(grade_dh(&key_robot(key)?, a, key.tolerance)),
        (KeyAnswer::Fk { t }, Answer::Rows(rows)) => grade_fk(t, rows, key.tolerance),
        (KeyAnswer::Ik { solutions, .. }, Answer::Rows(rows)) => {
            grade_ik(&key_robot(key)?, solutions, rows, key.tolerance)
        }
        (KeyAnswer::Workspace { postures, area, .. }, Answer::Rows(rows)) => {
            grade_workspace(postures, *area, rows)
        }
        (KeyAnswer::Redundancy { n, m, r, .. }, Answer::Rows(rows)) => {
            grade_redundancy([*n, *m, *r], rows)
        }
        (
            KeyAnswer::Identifiability {
                parameters,
                combinations,
                ..
            },
            Answer::Words(words),
        ) => Ok(grade_identifiability(parameters, combinations, words)),
        (KeyAnswer::Identifiability { .. }, _) => {
            Err(bad("an identifiability answer is parameter names".into()))
        }
        (_, Answer::Words(_)) => Err(bad("this answer is not a list of names".into())),
        (KeyAnswer::DhTable, Answer::Rows(_)) => {
            Err(bad("a dh-table answer is a TOML model file".into()))
        }
        (_, Answer::Model(_)) => Err(bad(
            "this answer is rows of numbers, not a model file".into()
        )),
        (_, Answer::Orientation(_)) => Err(bad("this answer is not an orientation".into())),
        (
            KeyAnswer::Euler(_)
            | KeyAnswer::Compose(_)
            | KeyAnswer::AxisAngle(_)
            | KeyAnswer::Quaternion(_)
            | KeyAnswer::FromQuestion,
            _,
        ) => Err(bad(format!(
            "a {} key holds no orientation question",
            key.kind.name()
        ))),
    }
}

/// n, m and r (Sect. 2.10) against the key's: an item each, the mistake named.
fn grade_redundancy([n, m, r]: [usize; 3], rows: &[Vec<f64>]) -> Result<Grade, ExerciseError> {
    let bad = |reason: String| ExerciseError::Answer { reason };
    let got: Vec<f64> = rows.iter().flatten().copied().collect();
    if got.len() != 3 {
        return Err(bad(format!(
            "give n, m, r: three numbers, not {}",
            got.len()
        )));
    }
    let items = [
        ("n", n, "the number of joints", Mistake::JointNumber),
        (
            "m",
            m,
            "the dimension of the operational space of the task's kind",
            Mistake::OperationalSpace,
        ),
        (
            "r",
            r,
            "the number of components the task prescribes",
            Mistake::TaskComponents,
        ),
    ]
    .iter()
    .zip(&got)
    .map(|((name, want, what, mistake), g)| {
        let ok = (*g - *want as f64).abs() < 1e-9;
        Item {
            item: name.to_string(),
            correct: ok,
            feedback: if ok {
                "right".into()
            } else {
                format!("{name} is wrong: it is {what}")
            },
            mistake: (!ok).then_some(*mistake),
        }
    })
    .collect();
    Ok(Grade::of(items))
}

/// Parameter names from an answer's text: separated by commas, spaces or lines; `#` comments.
pub fn parse_words(text: &str) -> Vec<String> {
    text.lines()
        .map(|l| l.split('#').next().unwrap_or(""))
        .flat_map(|l| l.split(|c: char| c == ',' || c.is_whitespace()))
        .filter(|w| !w.is_empty())
        .map(|w| w.to_ascii_lowercase())
        .collect()
}

/// Grades a list of unidentifiable parameters: one item per parameter of the key (named or
/// missed, with the combination the data sees), one per name given that is identifiable.
fn grade_identifiability(
    parameters: &[String],
    combinations: &[String],
    words: &[String],
) -> Grade {
    let why = |p: &str| {
        combinations
            .iter()
            .find(|c| c.split(|ch: char| !ch.is_alphanumeric()).any(|w| w == p))
            .cloned()
            .unwrap_or_default()
    };
    let mut items: Vec<Item> = parameters
        .iter()
        .map(|p| {
            let named = words.iter().any(|w| w == p);
            Item {
                item: p.clone(),
                correct: named,
                feedback: if named {
                    "right".into()
                } else {
                    format!("missed: {}", why(p))
                },
                mistake: (!named).then_some(Mistake::MissedUnidentifiable),
            }
        })
        .collect();
    for w in words {
        if !parameters.contains(w) {
            items.push(Item {
                item: w.clone(),
                correct: false,
                feedback: format!("{w} can be identified with this setup"),
                mistake: Some(Mistake::NamedIdentifiable),
            });
        }
    }
    if items.is_empty() {
        items.push(Item {
            item: "none".into(),
            correct: true,
            feedback: "right: every parameter is identifiable".into(),
            mistake: None,
        });
    }
    Grade::of(items)
}

/// Grades a DH table: one item per row.
pub fn grade_dh(reference: &Robot, answer: &Robot, tol: Tolerance) -> Grade {
    let v = dh_table::check(reference, answer, tol);
    Grade::of(
        v.rows
            .into_iter()
            .map(|r| Item {
                item: format!("row {}", r.row),
                correct: r.correct,
                feedback: r.feedback,
                mistake: r.mistake,
            })
            .collect(),
    )
}

/// Grades T: one item per entry of the top three rows.
fn grade_fk(t: &[[f64; 4]; 4], rows: &[Vec<f64>], tol: Tolerance) -> Result<Grade, ExerciseError> {
    let got: Vec<f64> = rows.iter().flatten().copied().collect();
    if got.len() != 16 && got.len() != 12 {
        return Err(ExerciseError::Answer {
            reason: format!(
                "T has 16 numbers (or 12: its top three rows), the answer has {}",
                got.len()
            ),
        });
    }
    let names = [
        ["n_x", "s_x", "a_x", "p_x"],
        ["n_y", "s_y", "a_y", "p_y"],
        ["n_z", "s_z", "a_z", "p_z"],
    ];
    let mut items = Vec::new();
    for i in 0..3 {
        for j in 0..4 {
            let (want, g) = (t[i][j], got[4 * i + j]);
            let tol = if j == 3 { tol.length } else { tol.angle };
            let ok = (want - g).abs() <= tol;
            let sign = (want + g).abs() <= tol;
            items.push(Item {
                item: format!("T[{}][{}] ({})", i + 1, j + 1, names[i][j]),
                correct: ok,
                feedback: if ok {
                    "right".into()
                } else if sign {
                    format!("{} has the wrong sign", names[i][j])
                } else if j == 3 {
                    format!(
                        "{} is wrong: it is the tool origin's coordinate in the base frame",
                        names[i][j]
                    )
                } else {
                    format!(
                        "{} is wrong: it is a component of a unit vector of the tool frame",
                        names[i][j]
                    )
                },
                mistake: match (ok, sign, j == 3) {
                    (true, _, _) => None,
                    (false, true, _) => Some(Mistake::TSign),
                    (false, false, true) => Some(Mistake::TPosition),
                    (false, false, false) => Some(Mistake::TRotation),
                },
            });
        }
    }
    Ok(Grade::of(items))
}

/// Two joint vectors equal modulo 2 pi (revolute) within the tolerances.
fn same_q(robot: &Robot, a: &[f64], b: &[f64], tol: Tolerance) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).enumerate().all(|(k, (x, y))| {
            let d = x - y;
            match robot.dof_joint(k).kind {
                JointKind::Prismatic => d.abs() <= tol.length,
                _ => (d - (d / (2.0 * PI)).round() * 2.0 * PI).abs() <= tol.angle * 5.0,
            }
        })
}

/// Grades a solution set: one item per key solution (found or not), wrong extra rows named.
fn grade_ik(
    robot: &Robot,
    solutions: &[(Vec<f64>, String)],
    rows: &[Vec<f64>],
    tol: Tolerance,
) -> Result<Grade, ExerciseError> {
    if let Some(r) = rows.iter().find(|r| r.len() != robot.dof()) {
        return Err(ExerciseError::Answer {
            reason: format!(
                "each row is one q of {} numbers; a row has {}",
                robot.dof(),
                r.len()
            ),
        });
    }
    let mut items: Vec<Item> = solutions
        .iter()
        .enumerate()
        .map(|(i, (q, posture))| {
            let found = rows.iter().any(|r| same_q(robot, r, q, tol));
            Item {
                item: format!("solution {} ({posture})", i + 1),
                correct: found,
                feedback: if found {
                    "found".into()
                } else {
                    format!("missing: the {posture} posture")
                },
                mistake: (!found).then_some(Mistake::MissingSolution),
            }
        })
        .collect();
    for (i, r) in rows.iter().enumerate() {
        if !solutions.iter().any(|(q, _)| same_q(robot, r, q, tol)) {
            items.push(Item {
                item: format!("answer row {}", i + 1),
                correct: false,
                feedback: format!("row {} does not reach the target", i + 1),
                mistake: Some(Mistake::ExtraSolution),
            });
        }
    }
    Ok(Grade::of(items))
}

/// Grades the workspace answer: six counts and the area (1 % tolerance).
fn grade_workspace(
    postures: &[usize],
    area: f64,
    rows: &[Vec<f64>],
) -> Result<Grade, ExerciseError> {
    let got: Vec<f64> = rows.iter().flatten().copied().collect();
    if got.len() != postures.len() + 1 {
        return Err(ExerciseError::Answer {
            reason: format!(
                "give {} counts and the area: {} numbers, not {}",
                postures.len(),
                postures.len() + 1,
                got.len()
            ),
        });
    }
    let mut items: Vec<Item> = postures
        .iter()
        .zip(&got)
        .enumerate()
        .map(|(i, (want, g))| {
            let ok = (*g - *want as f64).abs() < 1e-9;
            Item {
                item: format!("point {}", i + 1),
                correct: ok,
                feedback: if ok {
                    "right".into()
                } else {
                    "wrong: compare its distance from the base with |a1 - a2| and a1 + a2".into()
                },
                mistake: (!ok).then_some(Mistake::PostureCount),
            }
        })
        .collect();
    let g = got[postures.len()];
    let ok = (g - area).abs() <= 0.01 * area;
    items.push(Item {
        item: "area".into(),
        correct: ok,
        feedback: if ok {
            "right".into()
        } else {
            "wrong: the workspace is the ring between the circles of radius |a1 - a2| and a1 + a2"
                .into()
        },
        mistake: (!ok).then_some(Mistake::Area),
    });
    Ok(Grade::of(items))
}

/// One student's line of a class's grades: the answer's stem, and its grade or why it could
/// not be graded (no answer, an unreadable file).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StudentGrade {
    /// The stem shared by the key and the answer (`student-07`).
    pub student: String,
    /// The answer's file name, if there is one.
    pub answer: Option<String>,
    /// The grade; for an answer that could not be graded, score 0 of the key's items.
    pub grade: Grade,
    /// Why the answer could not be graded (none given, or what is wrong with the file).
    pub error: Option<String>,
}

/// A class's grades (`armlab exercise grade`): one line per key, the answers that match no
/// key, and how many made each named mistake.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ClassGrades {
    /// Per student, in the order of the stems.
    pub students: Vec<StudentGrade>,
    /// Answer files whose stem matches no key.
    pub unmatched_answers: Vec<String>,
    /// Each named mistake and how many students made it (at least once), most made first.
    pub mistakes: Vec<(Mistake, usize)>,
}

/// How many items grading `key` gives (the maximum score): a missing answer scores 0 of it.
pub fn item_count(key: &Key) -> usize {
    if key.kind.is_orientation() {
        return 1;
    }
    match &key.answer {
        KeyAnswer::DhTable => key_robot(key).map_or(1, |r| r.dof()),
        KeyAnswer::Fk { .. } => 12,
        KeyAnswer::Ik { solutions, .. } => solutions.len(),
        KeyAnswer::Workspace { postures, .. } => postures.len() + 1,
        KeyAnswer::Redundancy { .. } => 3,
        KeyAnswer::Identifiability { parameters, .. } => parameters.len().max(1),
        KeyAnswer::Euler(_)
        | KeyAnswer::Compose(_)
        | KeyAnswer::AxisAngle(_)
        | KeyAnswer::Quaternion(_)
        | KeyAnswer::FromQuestion => 1,
    }
}

impl ClassGrades {
    /// The class's grades from each student's line and the answers without a key; counts the
    /// mistakes (a student who made one twice counts once).
    pub fn new(mut students: Vec<StudentGrade>, unmatched_answers: Vec<String>) -> Self {
        students.sort_by(|a, b| a.student.cmp(&b.student));
        let mut counts = std::collections::BTreeMap::<Mistake, usize>::new();
        for s in &students {
            let mut made: Vec<Mistake> = s.grade.items.iter().filter_map(|i| i.mistake).collect();
            made.sort();
            made.dedup();
            for m in made {
                *counts.entry(m).or_default() += 1;
            }
        }
        let mut mistakes: Vec<(Mistake, usize)> = counts.into_iter().collect();
        mistakes.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
        Self {
            students,
            unmatched_answers,
            mistakes,
        }
    }

    /// The grades as CSV: a header, then one row per student: student, answer, score, max,
    /// error, the named mistakes (`;`-separated JSON names), then one column per item
    /// ("row 2: WRONG: row 2: alpha2 has the wrong sign ..."), as many as the longest sheet.
    pub fn csv(&self) -> String {
        let items = self
            .students
            .iter()
            .map(|s| s.grade.items.len())
            .max()
            .unwrap_or(0);
        let mut header = vec![
            "student".to_string(),
            "answer".into(),
            "score".into(),
            "max".into(),
            "error".into(),
            "mistakes".into(),
        ];
        header.extend((1..=items).map(|k| format!("item {k}")));
        let mut out = csv_line(&header);
        for s in &self.students {
            let mut made: Vec<String> = s
                .grade
                .items
                .iter()
                .filter_map(|i| i.mistake)
                .map(|m| mistake_name(m).to_string())
                .collect();
            made.sort();
            made.dedup();
            let mut row = vec![
                s.student.clone(),
                s.answer.clone().unwrap_or_default(),
                s.grade.score.to_string(),
                s.grade.max.to_string(),
                s.error.clone().unwrap_or_default(),
                made.join(";"),
            ];
            row.extend(s.grade.items.iter().map(|i| {
                let mark = if i.correct { "ok" } else { "WRONG" };
                format!("{}: {mark}: {}", i.item, i.feedback)
            }));
            out.push_str(&csv_line(&row));
        }
        out
    }
}

/// The JSON name of a mistake ("alpha_sign").
pub fn mistake_name(m: Mistake) -> &'static str {
    match m {
        Mistake::JointCount => "joint_count",
        Mistake::NotDhTable => "not_dh_table",
        Mistake::JointKind => "joint_kind",
        Mistake::AlphaSign => "alpha_sign",
        Mistake::ASign => "a_sign",
        Mistake::DSign => "d_sign",
        Mistake::ASwappedWithD => "a_swapped_with_d",
        Mistake::AlphaWrong => "alpha_wrong",
        Mistake::AWrong => "a_wrong",
        Mistake::DWrong => "d_wrong",
        Mistake::Unplaced => "unplaced",
        Mistake::TSign => "t_sign",
        Mistake::TPosition => "t_position",
        Mistake::TRotation => "t_rotation",
        Mistake::MissingSolution => "missing_solution",
        Mistake::ExtraSolution => "extra_solution",
        Mistake::PostureCount => "posture_count",
        Mistake::Area => "area",
        Mistake::JointNumber => "joint_number",
        Mistake::OperationalSpace => "operational_space",
        Mistake::TaskComponents => "task_components",
        Mistake::MissedUnidentifiable => "missed_unidentifiable",
        Mistake::NamedIdentifiable => "named_identifiable",
        Mistake::FixedForCurrent => "fixed_for_current",
        Mistake::CurrentForFixed => "current_for_fixed",
        Mistake::Transpose => "transpose",
        Mistake::DegreesAsRadians => "degrees_as_radians",
        Mistake::RadiansAsDegrees => "radians_as_degrees",
        Mistake::OtherConvention => "other_convention",
        Mistake::ReversedOrder => "reversed_order",
        Mistake::AngleSign => "angle_sign",
        Mistake::NonUnitQuaternion => "non_unit_quaternion",
        Mistake::NonUnitAxis => "non_unit_axis",
        Mistake::EpsilonFirst => "epsilon_first",
        Mistake::HalfAngle => "half_angle",
        Mistake::FullAngle => "full_angle",
    }
}

/// One CSV line (RFC 4180): fields with a comma, quote or line break quoted, quotes doubled.
fn csv_line(fields: &[String]) -> String {
    let quoted: Vec<String> = fields
        .iter()
        .map(|f| {
            if f.contains([',', '"', '\n', '\r']) {
                format!("\"{}\"", f.replace('"', "\"\""))
            } else {
                f.clone()
            }
        })
        .collect();
    quoted.join(",") + "\n"
}
