//! `armlab robots` and `armlab info`: what the models are, and one configuration evaluated.

use super::fk::{fmt_vec, write_pose};
use super::{CliError, Format, JointInput, joint_vectors};
use crate::kinematics::ik::ClosedForm;
use crate::kinematics::models::{BUILT_INS, DEFAULT_MODEL};
use crate::kinematics::pose::pose_to_rows;
use crate::kinematics::{EulerKind, JointGeometry, JointKind, Robot};
use serde_json::json;
use std::io::Write;

/// `armlab robots`.
pub(super) fn robots(format: Format, out: &mut dyn Write) -> Result<(), CliError> {
    let list: Vec<(&str, Robot, &str)> = BUILT_INS
        .iter()
        .map(|b| (b.name, (b.build)(), b.summary))
        .collect();
    match format {
        Format::Json => {
            let v: Vec<_> = list
                .iter()
                .map(|(name, r, summary)| {
                    json!({
                        "name": name,
                        "title": r.name,
                        "dof": r.dof(),
                        "joints": r.joints().len(),
                        "end_effectors": r.end_effectors().iter().map(|e| e.name.clone()).collect::<Vec<_>>(),
                        "summary": summary,
                        "description": r.description,
                        "configurations": r.configurations.iter().map(|c| c.name.clone()).collect::<Vec<_>>(),
                    })
                })
                .collect();
            serde_json::to_writer_pretty(&mut *out, &v).map_err(std::io::Error::from)?;
            writeln!(out)?;
        }
        Format::Text => {
            writeln!(out, "{:<32} {:>3}  description", "name", "dof")?;
            for (name, r, summary) in &list {
                writeln!(out, "{name:<32} {:>3}  {summary}", r.dof())?;
            }
        }
    }
    Ok(())
}

/// `armlab info [MODEL]` (also what `armlab` alone runs).
pub(super) fn run(
    model: Option<&str>,
    joints: &JointInput,
    format: Format,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let spec = model.unwrap_or(DEFAULT_MODEL);
    let robot = crate::model_file::load_model(spec)?;
    let fallback = if robot.config("ready").is_some() {
        "ready"
    } else {
        "zero"
    };
    let rows = joint_vectors(&robot, spec, joints, Some(fallback))?;
    let Some(q) = rows.first() else {
        return Err(CliError::Usage("no joint vector given"));
    };
    let poses = robot.fk_all_ee(q)?;
    let analyses: Vec<_> = (0..poses.len())
        .map(|e| robot.analyze_jacobian(q, e))
        .collect::<Result<_, _>>()?;
    if format == Format::Json {
        let ees: Vec<_> = robot
            .end_effectors()
            .iter()
            .zip(&poses)
            .zip(&analyses)
            .map(|((e, t), a)| {
                json!({
                    "name": e.name,
                    "T": pose_to_rows(t),
                    "phi_zyz": EulerKind::Zyz.from_rotation(&t.rotation).angles.as_slice(),
                    "phi_rpy": EulerKind::Rpy.from_rotation(&t.rotation).angles.as_slice(),
                    "jacobian_rank": a.rank,
                    "singular_values": a.singular_values.as_slice(),
                    "manipulability": a.manipulability,
                })
            })
            .collect();
        let (family, why_not) = match ClosedForm::detect(&robot) {
            Ok(cf) => (Some(cf.name()), None),
            Err(e) => (None, Some(e.to_string())),
        };
        let v = json!({
            "name": robot.name,
            "description": robot.description,
            "dof": robot.dof(),
            "limits": robot.limits(),
            "q": q,
            "end_effectors": ees,
            "closed_form": family,
            "no_closed_form": why_not,
        });
        serde_json::to_writer_pretty(&mut *out, &v).map_err(std::io::Error::from)?;
        writeln!(out)?;
        return Ok(());
    }
    writeln!(out, "{} ({} DOF)", robot.name, robot.dof())?;
    writeln!(out, "{}", robot.description)?;
    writeln!(out)?;
    write_table(&robot, out)?;
    writeln!(out)?;
    for c in &robot.configurations {
        writeln!(out, "configuration {:<8} q = {}", c.name, fmt_vec(&c.q))?;
    }
    writeln!(out)?;
    match ClosedForm::detect(&robot) {
        Ok(cf) => writeln!(out, "inverse kinematics: closed form ({})", cf.name())?,
        Err(e) => writeln!(
            out,
            "inverse kinematics: numerical only; no closed form: {e}"
        )?,
    }
    writeln!(out)?;
    writeln!(out, "at q = {}", fmt_vec(q))?;
    for ((e, t), a) in robot.end_effectors().iter().zip(&poses).zip(&analyses) {
        writeln!(out, "T ({}) =", e.name)?;
        write_pose(out, t)?;
        writeln!(out, "p = {} m", fmt_vec(t.translation.vector.as_slice()))?;
        for kind in [EulerKind::Zyz, EulerKind::Rpy] {
            let phi = kind.from_rotation(&t.rotation);
            let deg: Vec<f64> = phi.angles.iter().map(|a| a.to_degrees()).collect();
            let note = if phi.singular {
                " (singular representation)"
            } else {
                ""
            };
            writeln!(out, "phi {} = {} deg{note}", kind.as_str(), fmt_vec(&deg))?;
        }
        writeln!(
            out,
            "Jacobian rank {} of {}, manipulability {:.6}, smallest singular value {:.3e}{}",
            a.rank,
            robot.dof().min(6),
            a.manipulability,
            a.min_singular_value(),
            if a.rank < robot.dof().min(6) {
                "  <- singular configuration"
            } else {
                ""
            }
        )?;
    }
    Ok(())
}

fn write_table(robot: &Robot, out: &mut dyn Write) -> std::io::Result<()> {
    writeln!(
        out,
        "{:<3} {:<8} {:<9} {:>9} {:>10} {:>9} {:>10} {:>9}  {:<22} drive",
        "#", "name", "type", "a [m]", "alpha[deg]", "d [m]", "theta[deg]", "offset", "limits"
    )?;
    for (i, j) in robot.joints().iter().enumerate() {
        let (a, al, d, th, conv) = match &j.geometry {
            JointGeometry::Dh { row, convention } => (
                row.a,
                row.alpha.to_degrees(),
                row.d,
                row.theta.to_degrees(),
                convention.as_str(),
            ),
            JointGeometry::Origin { .. } => (f64::NAN, f64::NAN, f64::NAN, f64::NAN, "urdf"),
        };
        let lim = match j.kind {
            _ if j.limits.iter().all(|v| v.is_infinite()) && j.kind != JointKind::Fixed => {
                "none".into()
            }
            JointKind::Revolute => format!(
                "[{:.1}, {:.1}] deg",
                j.limits[0].to_degrees(),
                j.limits[1].to_degrees()
            ),
            JointKind::Prismatic => format!("[{:.3}, {:.3}] m", j.limits[0], j.limits[1]),
            JointKind::Fixed => "-".into(),
        };
        let drive = match &j.drive {
            crate::kinematics::Drive::Actuated(k) => format!("q{}", k + 1),
            crate::kinematics::Drive::Coupled(t) => t
                .iter()
                .map(|(s, c)| format!("{c:+} * {}", robot.joints()[*s].name))
                .collect::<Vec<_>>()
                .join(" "),
            crate::kinematics::Drive::Closure(c) => format!(
                "closure of {} and {}",
                robot.joints()[c.mechanism.crank].name,
                robot.joints()[c.mechanism.arm].name
            ),
            crate::kinematics::Drive::None => "fixed".into(),
        };
        let _ = conv;
        writeln!(
            out,
            "{:<3} {:<8} {:<9} {:>9.4} {:>10.1} {:>9.4} {:>10.1} {:>9.4}  {:<22} {drive}",
            i + 1,
            j.name,
            j.kind.as_str(),
            a,
            al,
            d,
            th,
            j.offset,
            lim
        )?;
    }
    Ok(())
}
