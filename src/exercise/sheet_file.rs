//! The student's sheet file (`student-NN/sheet.json`, written by `armlab exercise new` beside
//! the question): the question, the arm and the drawn q, and nothing of the answer. The app's
//! Exercise tab opens it in exam mode; the key stays with the teacher (`keys/`).
//!
//! The arm is written as a URDF whose link frames are all parallel to the base frame, at the
//! model's zero configuration: every joint is a point on its axis and the axis' direction, the
//! same geometry the question's table of axes gives. No DH row, offset or convention is in the
//! file, so a dh-table sheet carries its question and not its answer.
//!
//! An orientation sheet has no arm: it carries its question as data instead, the given
//! `matrix` (and the `convention` asked for) or the `sequence` of turns, never their answer.

use super::{EulerConvention, ExerciseError, Kind, Sheet, joint_axes};
use crate::kinematics::orientation::Step;
use crate::kinematics::{JointKind, Robot};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;

/// The format tag written into every sheet file.
pub const SHEET_FORMAT: &str = "armlab exercise sheet 1";

/// One student's sheet, as the student receives it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SheetFile {
    /// [`SHEET_FORMAT`].
    pub format: String,
    /// The kind.
    pub kind: Kind,
    /// The seed the class was made with.
    pub seed: u64,
    /// The student's number (1-based): the answer file is `student-NN` (see
    /// [`SheetFile::answer_file_name`]).
    pub student: usize,
    /// The question (Markdown), as in `sheet.md`.
    pub question: String,
    /// The arm as URDF text: link frames parallel to the base frame, joints as axes (m); empty
    /// for the orientation kinds.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub arm: String,
    /// The configuration drawn (rad, m); empty for the orientation kinds.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub q: Vec<f64>,
    /// The given rotation matrix, rows (euler, axis-angle, quaternion).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub matrix: Option<[[f64; 3]; 3]>,
    /// The Euler convention asked for (euler).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub convention: Option<EulerConvention>,
    /// The sequence of elementary rotations, as the question states it (compose; rad).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sequence: Option<Vec<Step>>,
}

impl SheetFile {
    /// The sheet file of `sheet` (the student's part of it: no key).
    pub fn of(sheet: &Sheet) -> Result<Self, ExerciseError> {
        let key = &sheet.key;
        Ok(Self {
            format: SHEET_FORMAT.into(),
            kind: key.kind,
            seed: key.seed,
            student: key.student,
            question: sheet.markdown.clone(),
            arm: match &sheet.robot {
                Some(robot) => axes_urdf(robot)?,
                None => String::new(),
            },
            q: sheet.q.clone(),
            matrix: key.matrix,
            convention: key.convention,
            sequence: key.sequence.clone(),
        })
    }

    /// Reads a sheet file; `name` (the file) for messages.
    pub fn parse(name: &str, text: &str) -> Result<Self, ExerciseError> {
        let sheet: Self = serde_json::from_str(text).map_err(|e| ExerciseError::Answer {
            reason: format!("{name}: not an armlab exercise sheet: {e}"),
        })?;
        if sheet.format != SHEET_FORMAT {
            return Err(ExerciseError::Answer {
                reason: format!(
                    "{name}: format {:?}, expected {SHEET_FORMAT:?}",
                    sheet.format
                ),
            });
        }
        Ok(sheet)
    }

    /// The sheet's arm, read from its URDF (an orientation sheet has none: an error).
    pub fn robot(&self) -> Result<Robot, ExerciseError> {
        if self.arm.is_empty() {
            return Err(ExerciseError::Unsuitable {
                kind: self.kind.name(),
                reason: "the sheet has no arm (sheet.urdf)".into(),
            });
        }
        crate::urdf::parse_urdf(&self.arm, std::path::Path::new("sheet.urdf")).map_err(|e| {
            ExerciseError::Answer {
                reason: format!("the sheet's arm: {e}"),
            }
        })
    }

    /// The name the answer is handed in under, matched to the key by its stem
    /// (`student-07.toml` for a DH table, `student-07.txt` otherwise).
    pub fn answer_file_name(&self) -> String {
        let ext = if self.kind == Kind::DhTable {
            "toml"
        } else {
            "txt"
        };
        format!("student-{:02}.{ext}", self.student)
    }
}

/// `arm` (a serial chain) as a URDF with every link frame parallel to the base frame, at the
/// arm's zero configuration: a joint is its axis (a point and a direction, in the base frame),
/// the tool a fixed frame at the end. The base frame is the URDF's root link.
pub fn axes_urdf(arm: &Robot) -> Result<String, ExerciseError> {
    let n = arm.dof();
    let serial =
        arm.joints().len() == n && (0..n).all(|k| arm.dof_joint(k).parent == k.checked_sub(1));
    if !serial {
        return Err(ExerciseError::Unsuitable {
            kind: "this",
            reason: "the sheet's arm must be a serial chain of actuated joints".into(),
        });
    }
    let zero = vec![0.0; n];
    let axes = joint_axes(arm, &zero);
    let base_from_tool = arm.fk(&zero).map_err(|e| ExerciseError::Unsuitable {
        kind: "this",
        reason: e.to_string(),
    })?;
    let mut s = String::new();
    let _ = writeln!(s, "<?xml version=\"1.0\"?>");
    let _ = writeln!(s, "<robot name=\"sheet_arm\">");
    let _ = writeln!(s, "  <link name=\"base\"/>");
    let mut parent = ("base".to_string(), nalgebra::Vector3::zeros());
    for (k, (p, z)) in axes.iter().enumerate() {
        let j = arm.dof_joint(k);
        let link = format!("link{}", k + 1);
        let d = p - parent.1;
        let kind = match (j.kind, j.limits[0].is_finite() && j.limits[1].is_finite()) {
            (JointKind::Prismatic, _) => "prismatic",
            (_, true) => "revolute",
            (_, false) => "continuous",
        };
        let _ = writeln!(s, "  <link name=\"{link}\"/>");
        let _ = writeln!(s, "  <joint name=\"joint{}\" type=\"{kind}\">", k + 1);
        let _ = writeln!(
            s,
            "    <parent link=\"{}\"/> <child link=\"{link}\"/>",
            parent.0
        );
        let _ = writeln!(
            s,
            "    <origin xyz=\"{} {} {}\" rpy=\"0 0 0\"/>",
            d.x, d.y, d.z
        );
        let _ = writeln!(s, "    <axis xyz=\"{} {} {}\"/>", z.x, z.y, z.z);
        if kind != "continuous" {
            let [lo, hi] = j.limits;
            let _ = writeln!(
                s,
                "    <limit lower=\"{lo}\" upper=\"{hi}\" effort=\"1\" velocity=\"1\"/>"
            );
        }
        let _ = writeln!(s, "  </joint>");
        parent = (link, *p);
    }
    let d = base_from_tool.translation.vector - parent.1;
    let (roll, pitch, yaw) = base_from_tool.rotation.euler_angles();
    let _ = writeln!(s, "  <link name=\"tool\"/>");
    let _ = writeln!(s, "  <joint name=\"tool_fixed\" type=\"fixed\">");
    let _ = writeln!(
        s,
        "    <parent link=\"{}\"/> <child link=\"tool\"/>",
        parent.0
    );
    let _ = writeln!(
        s,
        "    <origin xyz=\"{} {} {}\" rpy=\"{roll} {pitch} {yaw}\"/>",
        d.x, d.y, d.z
    );
    let _ = writeln!(s, "  </joint>");
    let _ = writeln!(s, "</robot>");
    Ok(s)
}
