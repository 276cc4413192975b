//! `armlab robots` and `armlab info`: what the models are, and one configuration evaluated.

use super::fk::{fmt_vec, write_pose};
use super::{CliError, Format, JointInput, joint_vectors};
use crate::kinematics::dh_derive::derive_dh;
use crate::kinematics::ik::ClosedForm;
use crate::kinematics::models::{BUILT_INS, DEFAULT_MODEL};
use crate::kinematics::pose::pose_to_rows;
use crate::kinematics::{
    Convention, EulerKind, JacobianAnalysis, JointGeometry, JointKind, Pose, Robot,
};
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
    let robot = super::load_model(spec)?;
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
        return write_info_json(&robot, q, &poses, &analyses, out);
    }
    write_info_text(&robot, q, &poses, &analyses, out)
}

/// `armlab info --format json`: the model, q and, per end-effector, its pose, Euler angles and
/// Jacobian analysis.
fn write_info_json(
    robot: &Robot,
    q: &[f64],
    poses: &[Pose],
    analyses: &[JacobianAnalysis],
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let ees: Vec<_> = robot
        .end_effectors()
        .iter()
        .zip(poses)
        .zip(analyses)
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
    let (family, why_not) = match ClosedForm::detect(robot) {
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
    Ok(())
}

/// `armlab info` as text: the model, its joint table, configurations, closed form, then each
/// end-effector at q.
fn write_info_text(
    robot: &Robot,
    q: &[f64],
    poses: &[Pose],
    analyses: &[JacobianAnalysis],
    out: &mut dyn Write,
) -> Result<(), CliError> {
    writeln!(out, "{} ({} DOF)", robot.name, robot.dof())?;
    writeln!(out, "{}", robot.description)?;
    writeln!(out)?;
    write_table(robot, out)?;
    writeln!(out)?;
    for c in &robot.configurations {
        writeln!(out, "configuration {:<8} q = {}", c.name, fmt_vec(&c.q))?;
    }
    writeln!(out)?;
    match ClosedForm::detect(robot) {
        Ok(cf) => writeln!(out, "inverse kinematics: closed form ({})", cf.name())?,
        Err(e) => writeln!(
            out,
            "inverse kinematics: numerical only; no closed form: {e}"
        )?,
    }
    writeln!(out)?;
    writeln!(out, "at q = {}", fmt_vec(q))?;
    for ((e, t), a) in robot.end_effectors().iter().zip(poses).zip(analyses) {
        writeln!(out, "T ({}) =", e.name)?;
        write_pose(out, t)?;
        write_ee_analysis(robot, t, a, out)?;
    }
    Ok(())
}

/// One end-effector's position, ZYZ and RPY angles (flagging a singular representation) and
/// Jacobian rank, manipulability and smallest singular value.
fn write_ee_analysis(
    robot: &Robot,
    t: &Pose,
    a: &JacobianAnalysis,
    out: &mut dyn Write,
) -> std::io::Result<()> {
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
    )
}

/// The joint table: DH rows as given, or, for a chain given by URDF origins and axes, the
/// origins and the DH table derived from the axes (or why there is none); never NaN.
fn write_table(robot: &Robot, out: &mut dyn Write) -> std::io::Result<()> {
    let dh = robot
        .joints()
        .iter()
        .all(|j| matches!(j.geometry, JointGeometry::Dh { .. }));
    if dh {
        return write_dh_rows(robot, out);
    }
    writeln!(
        out,
        "{:<3} {:<14} {:<9} {:<28} {:<28} {:<22} {:<22} drive",
        "#", "name", "type", "origin xyz [m]", "origin rpy [deg]", "axis", "limits"
    )?;
    for (i, j) in robot.joints().iter().enumerate() {
        let (xyz, rpy, axis) = match &j.geometry {
            JointGeometry::Origin {
                parent_from_joint,
                axis,
            } => {
                let (r, p, y) = parent_from_joint.rotation.euler_angles();
                (
                    fmt_vec(parent_from_joint.translation.vector.as_slice()),
                    fmt_deg(&[r, p, y]),
                    fmt_vec(axis.as_slice()),
                )
            }
            JointGeometry::Dh { row, convention } => (
                format!("DH ({}) a {:.4} d {:.4}", convention.as_str(), row.a, row.d),
                fmt_deg(&[row.alpha, row.theta]),
                "z".into(),
            ),
        };
        writeln!(
            out,
            "{:<3} {:<14} {:<9} {xyz:<28} {rpy:<28} {axis:<22} {:<22} {}",
            i + 1,
            j.name,
            j.kind.as_str(),
            limits_text(j),
            drive_text(robot, j)
        )?;
    }
    writeln!(out)?;
    match derive_dh(robot, 0, Convention::Standard).map(|d| (d.robot(&robot.name), d)) {
        Ok((Ok(table), d)) => {
            writeln!(
                out,
                "DH table derived from the joint axes (standard convention, forward kinematics \
                 equal to the chain's; theta of a revolute joint and d of a prismatic one are \
                 q plus the offset):"
            )?;
            write_dh_rows(&table, out)?;
            writeln!(out, "base (world from frame 0) =")?;
            write_pose(out, &d.world_from_base)?;
            writeln!(out, "tool (frame {} to the tool) =", d.joints.len())?;
            write_pose(out, &d.flange_from_tool)?;
        }
        Ok((Err(e), _)) => writeln!(out, "DH table: none ({e})")?,
        Err(e) => writeln!(out, "DH table: {e}")?,
    }
    Ok(())
}

/// Angles in degrees, as `fmt_vec` writes numbers.
fn fmt_deg(v: &[f64]) -> String {
    fmt_vec(&v.iter().map(|a| a.to_degrees()).collect::<Vec<_>>())
}

/// A joint's limits in words.
fn limits_text(j: &crate::kinematics::Joint) -> String {
    match j.kind {
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
    }
}

/// What drives a joint, in words.
fn drive_text(robot: &Robot, j: &crate::kinematics::Joint) -> String {
    match &j.drive {
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
    }
}

/// The DH rows of a robot all of whose joints are DH rows.
fn write_dh_rows(robot: &Robot, out: &mut dyn Write) -> std::io::Result<()> {
    writeln!(
        out,
        "{:<3} {:<8} {:<9} {:>9} {:>10} {:>9} {:>10} {:>9}  {:<22} drive",
        "#", "name", "type", "a [m]", "alpha[deg]", "d [m]", "theta[deg]", "offset", "limits"
    )?;
    for (i, j) in robot.joints().iter().enumerate() {
        let JointGeometry::Dh { row, .. } = &j.geometry else {
            continue;
        };
        writeln!(
            out,
            "{:<3} {:<8} {:<9} {:>9.4} {:>10.1} {:>9.4} {:>10.1} {:>9.4}  {:<22} {}",
            i + 1,
            j.name,
            j.kind.as_str(),
            row.a,
            row.alpha.to_degrees(),
            row.d,
            row.theta.to_degrees(),
            j.offset,
            limits_text(j),
            drive_text(robot, j)
        )?;
    }
    Ok(())
}
