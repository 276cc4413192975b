//! `armlab robots` and `armlab info`: what the models are, and one configuration evaluated.

use super::fk::{fmt_vec, write_pose};
use super::{CliError, Format, JointInput, joint_vectors};
use crate::kinematics::dh_derive::DerivedDh;
use crate::kinematics::end_effectors::catalog;
use crate::kinematics::models::{BUILT_INS, DEFAULT_MODEL};
use crate::kinematics::pose::pose_to_rows;
use crate::kinematics::{EulerKind, JacobianAnalysis, JointGeometry, JointKind, Pose, Robot};
use crate::redundancy::report::{ArmReport, Role, arm_report};
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

/// `armlab info [MODEL]` (also what `armlab` alone runs); `ee` restricts the per-end-effector
/// part to one end-effector (a name or an index).
pub(super) fn run(
    model: Option<&str>,
    joints: &JointInput,
    ee: Option<&str>,
    format: Format,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let spec = model.unwrap_or(DEFAULT_MODEL);
    let mut robot = super::load_model(spec)?;
    let only = match ee {
        Some(_) => Some(super::ik::end_effector(&mut robot, ee)?),
        None => None,
    };
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
    let cat = catalog(&robot);
    let reports: Vec<ArmReport> = (0..poses.len())
        .map(|e| arm_report(&robot, &cat, e, q))
        .collect();
    let shown: Vec<usize> = match only {
        Some(e) => vec![e],
        None => (0..poses.len()).collect(),
    };
    let info = Info {
        robot: &robot,
        q,
        poses: &poses,
        analyses: &analyses,
        reports: &reports,
        shown: &shown,
        default_ee: only.unwrap_or(cat.default_ee()),
    };
    if format == Format::Json {
        return write_info_json(&info, out);
    }
    write_info_text(&info, out)
}

/// What `armlab info` says, computed once for both formats.
struct Info<'a> {
    robot: &'a Robot,
    q: &'a [f64],
    poses: &'a [Pose],
    analyses: &'a [JacobianAnalysis],
    reports: &'a [ArmReport],
    /// The end-effectors to show (all, or the one `--ee` names).
    shown: &'a [usize],
    /// The end-effector whose arm the model-level lines describe.
    default_ee: usize,
}

/// A derived DH table as JSON rows (m, rad).
fn dh_json(d: &DerivedDh) -> serde_json::Value {
    json!({
        "convention": d.convention.as_str(),
        "rows": d.joints.iter().map(|j| json!({
            "name": j.name,
            "type": j.kind.as_str(),
            "a": j.row.a,
            "alpha": j.row.alpha,
            "d": j.row.d,
            "theta": j.row.theta,
            "offset": j.offset,
            "limits": j.limits,
        })).collect::<Vec<_>>(),
        "world_from_base": pose_to_rows(&d.world_from_base),
        "flange_from_tool": pose_to_rows(&d.flange_from_tool),
    })
}

/// `armlab info --format json`: the model, q and, per end-effector, its pose, Euler angles and
/// Jacobian analysis, and its arm: the chain to it, DH table, closed form, degree of redundancy
/// and self-motion parameter (each with the reason when there is none).
fn write_info_json(info: &Info, out: &mut dyn Write) -> Result<(), CliError> {
    let robot = info.robot;
    let ees: Vec<_> = info
        .shown
        .iter()
        .map(|&k| {
            let (e, t, a, r) = (
                &robot.end_effectors()[k],
                &info.poses[k],
                &info.analyses[k],
                &info.reports[k],
            );
            json!({
                "name": e.name,
                "role": r.role.as_str(),
                "arm": r.arm_index,
                "chain": r.chain,
                "dof": r.dof,
                "variables": r.variables,
                "dh": r.dh.as_ref().map(dh_json),
                "dh_reason": r.dh_reason,
                "closed_form": r.closed_form,
                "closed_form_reason": r.closed_form_reason,
                "closed_form_near_miss": r.closed_form_near_miss,
                "redundancy_degree": r.redundancy_degree,
                "redundancy": r.redundancy,
                "self_motion": r.self_motion,
                "self_motion_reason": r.self_motion_reason,
                "T": pose_to_rows(t),
                "phi_zyz": EulerKind::Zyz.from_rotation(&t.rotation).angles.as_slice(),
                "phi_rpy": EulerKind::Rpy.from_rotation(&t.rotation).angles.as_slice(),
                "jacobian_rank": a.rank,
                "singular_values": a.singular_values.as_slice(),
                "manipulability": a.manipulability,
            })
        })
        .collect();
    let main = &info.reports[info.default_ee];
    let v = json!({
        "name": robot.name,
        "description": robot.description,
        "dof": robot.dof(),
        "limits": robot.limits(),
        "q": info.q,
        "default_end_effector": robot.end_effectors()[info.default_ee].name,
        "end_effectors": ees,
        "closed_form": main.closed_form,
        "no_closed_form": main.closed_form_reason,
        "warnings": robot.load_warnings,
    });
    serde_json::to_writer_pretty(&mut *out, &v).map_err(std::io::Error::from)?;
    writeln!(out)?;
    Ok(())
}

/// `armlab info` as text: the model, its joint table, configurations, closed form, then each
/// end-effector at q.
fn write_info_text(info: &Info, out: &mut dyn Write) -> Result<(), CliError> {
    let robot = info.robot;
    writeln!(out, "{} ({} DOF)", robot.name, robot.dof())?;
    writeln!(out, "{}", robot.description)?;
    writeln!(out)?;
    write_table(robot, &info.reports[info.default_ee], out)?;
    writeln!(out)?;
    for c in &robot.configurations {
        writeln!(out, "configuration {:<8} q = {}", c.name, fmt_vec(&c.q))?;
    }
    writeln!(out)?;
    let main = &info.reports[info.default_ee];
    let whose = if robot.end_effectors().len() > 1 {
        format!(" of \"{}\"", main.name)
    } else {
        String::new()
    };
    match (main.closed_form, &main.closed_form_reason) {
        (Some(f), _) => writeln!(
            out,
            "inverse kinematics{whose}: closed form ({})",
            main.closed_form_near_miss.as_deref().unwrap_or(f)
        )?,
        (None, why) => writeln!(
            out,
            "inverse kinematics{whose}: numerical only; no closed form: {}",
            why.as_deref().unwrap_or("")
        )?,
    }
    if robot.end_effectors().len() > 1 {
        writeln!(out)?;
        write_arms(info, out)?;
    }
    writeln!(out)?;
    writeln!(out, "at q = {}", fmt_vec(info.q))?;
    for &k in info.shown {
        let (e, t, a) = (&robot.end_effectors()[k], &info.poses[k], &info.analyses[k]);
        writeln!(out, "T ({}) =", e.name)?;
        write_pose(out, t)?;
        write_ee_analysis(robot, t, a, out)?;
    }
    Ok(())
}

/// The end-effectors of a robot with several, each with its arm in words.
fn write_arms(info: &Info, out: &mut dyn Write) -> std::io::Result<()> {
    writeln!(
        out,
        "end-effectors (the arm of each is the chain from the root to it):"
    )?;
    for &k in info.shown {
        let r = &info.reports[k];
        let role = match (r.role, r.arm_index) {
            (Role::Tool, Some(a)) => format!("tool of arm {}", a + 1),
            (Role::ArmFrame, Some(a)) => format!("a frame of arm {}", a + 1),
            _ => "other frame".into(),
        };
        let default = if k == info.default_ee {
            ", the default"
        } else {
            ""
        };
        writeln!(
            out,
            "  {} ({role}{default}): {} joints: {}",
            r.name,
            r.dof,
            r.chain.join(", ")
        )?;
        let dh = match (&r.dh, &r.dh_reason) {
            (Some(_), _) => "DH table derived".to_string(),
            (None, why) => why.clone().unwrap_or_default(),
        };
        let cf = match (r.closed_form, &r.closed_form_reason) {
            (Some(_), _) if r.closed_form_near_miss.is_some() => format!(
                "closed form: {}",
                r.closed_form_near_miss.as_deref().unwrap_or("")
            ),
            (Some(f), _) => format!("closed form: {f}"),
            (None, why) => format!("no closed form: {}", why.as_deref().unwrap_or("")),
        };
        writeln!(out, "    {dh}; {cf}")?;
        let sm = match (r.self_motion, &r.self_motion_reason) {
            (Some(p), _) => format!("exact self-motion parameter: {p}"),
            (None, why) => why.clone().unwrap_or_default(),
        };
        writeln!(out, "    {}; {sm}", r.redundancy)?;
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
fn write_table(robot: &Robot, main: &ArmReport, out: &mut dyn Write) -> std::io::Result<()> {
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
    let of = if robot.end_effectors().len() > 1 {
        format!(" of the chain to \"{}\"", main.name)
    } else {
        String::new()
    };
    let derived = match (&main.dh, &main.dh_reason) {
        (Some(d), _) => Ok(d.clone()),
        (None, why) => Err(why.clone().unwrap_or_default()),
    };
    match derived.map(|d| (d.robot(&robot.name), d)) {
        Ok((Ok(table), d)) => {
            writeln!(
                out,
                "DH table{of} derived from the joint axes (standard convention, forward \
                 kinematics equal to the chain's; theta of a revolute joint and d of a \
                 prismatic one are q plus the offset):"
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
