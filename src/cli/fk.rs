//! `armlab fk`: direct kinematics of one or many joint vectors.

use super::{CliError, Format, JointInput, joint_vectors};
use crate::kinematics::pose::pose_to_rows;
use crate::kinematics::{EulerKind, Pose, Robot};
use serde_json::{Value, json};
use std::io::Write;

/// Runs `fk`. Every row is parsed and checked before anything is printed.
pub(super) fn run(
    model: &str,
    joints: &JointInput,
    frames: bool,
    ee: Option<&str>,
    euler: Option<EulerKind>,
    format: Format,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let mut robot = super::load_model(model)?;
    let ee = super::ik::end_effector(&mut robot, ee)?;
    let rows = joint_vectors(&robot, model, joints, None)?;
    let mut results = Vec::with_capacity(rows.len());
    for q in &rows {
        let all = robot.fk_frames(q)?;
        let ees: Vec<Pose> = robot
            .end_effectors()
            .iter()
            .map(|e| all[e.parent] * e.tool)
            .collect();
        results.push((q, all, ees));
    }
    match format {
        Format::Json => {
            let arr: Vec<Value> = results
                .iter()
                .map(|(q, all, ees)| fk_json(&robot, q, all, ees, ee, frames, euler))
                .collect();
            serde_json::to_writer_pretty(&mut *out, &arr).map_err(std::io::Error::from)?;
            writeln!(out)?;
        }
        Format::Text => {
            for (i, (q, all, ees)) in results.iter().enumerate() {
                if i > 0 {
                    writeln!(out)?;
                }
                write_fk_text(&robot, q, all, ees, frames, euler, out)?;
            }
        }
    }
    Ok(())
}

/// One joint vector's JSON object: q, the first end-effector's pose (and Euler angles when
/// asked), every end-effector's pose when there are several, and the joint frames if `frames`.
fn fk_json(
    robot: &Robot,
    q: &[f64],
    all: &[Pose],
    ees: &[Pose],
    ee: usize,
    frames: bool,
    euler: Option<EulerKind>,
) -> Value {
    let mut o =
        json!({ "q": q, "T": pose_to_rows(&ees[ee]), "p": ees[ee].translation.vector.as_slice() });
    if let Some(kind) = euler {
        let phi = kind.from_rotation(&ees[ee].rotation);
        o["euler"] = json!(kind.as_str());
        o["phi"] = json!(phi.angles.as_slice());
        o["phi_singular"] = json!(phi.singular);
    }
    if ees.len() > 1 {
        o["end_effectors"] = robot
            .end_effectors()
            .iter()
            .zip(ees)
            .map(|(e, t)| json!({ "name": e.name, "T": pose_to_rows(t) }))
            .collect();
    }
    if frames {
        o["frames"] = robot
            .joints()
            .iter()
            .zip(all)
            .map(|(j, t)| json!({ "name": j.name, "T": pose_to_rows(t) }))
            .collect();
    }
    o
}

/// One joint vector as text: q, each end-effector's pose (and Euler angles when asked), then the
/// joint frames if `frames`.
fn write_fk_text(
    robot: &Robot,
    q: &[f64],
    all: &[Pose],
    ees: &[Pose],
    frames: bool,
    euler: Option<EulerKind>,
    out: &mut dyn Write,
) -> std::io::Result<()> {
    writeln!(out, "q = {}", fmt_vec(q))?;
    for (e, t) in robot.end_effectors().iter().zip(ees) {
        writeln!(out, "T ({}) =", e.name)?;
        write_pose(out, t)?;
        if let Some(kind) = euler {
            let phi = kind.from_rotation(&t.rotation);
            let note = if phi.singular {
                "  (representation singular: phi set to 0)"
            } else {
                ""
            };
            writeln!(
                out,
                "phi ({}) = {} rad{note}",
                kind.as_str(),
                fmt_vec(phi.angles.as_slice())
            )?;
        }
    }
    if frames {
        for (j, t) in robot.joints().iter().zip(all) {
            writeln!(out, "frame {} =", j.name)?;
            write_pose(out, t)?;
        }
    }
    Ok(())
}

/// `[a, b, c]` with 6 decimals.
pub(super) fn fmt_vec(v: &[f64]) -> String {
    let parts: Vec<String> = v.iter().map(|&x| format!("{:.6}", tidy(x))).collect();
    format!("[{}]", parts.join(", "))
}

/// Rounds |x| < 5e-7 to +0 so six-decimal text never shows "-0.000000".
pub(super) fn tidy(x: f64) -> f64 {
    if x.abs() < 5e-7 { 0.0 } else { x }
}

/// A 4x4 pose as four indented rows.
pub(super) fn write_pose(out: &mut dyn Write, t: &Pose) -> std::io::Result<()> {
    for row in pose_to_rows(t) {
        let [a, b, c, d] = row.map(tidy);
        writeln!(out, "  {a:>10.6} {b:>10.6} {c:>10.6} {d:>10.6}")?;
    }
    Ok(())
}
