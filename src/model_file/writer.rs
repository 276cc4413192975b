//! Writes a serial DH robot back as a TOML model file.

use super::angle::exact_angle_string;
use crate::kinematics::pose::{Pose, pose_to_rows};
use crate::kinematics::{Drive, JointKind, Robot};
use std::fmt::Write;

/// The TOML model file of a serial DH robot, or `None` if the robot is not one.
///
/// A serial DH robot has only DH joints in one convention, each the child of the previous one,
/// and no couplings (see [`Robot::dh_table_with_pre`]; constant `pre` transforms, such as a
/// calibrated Hayati rotation, are written as `pre`); its end-effectors may sit on
/// any joint. Angles that are exact multiples of pi or whole degrees are written as strings such
/// as `"pi/2"` or `"-160deg"`, everything else with the shortest decimal that reads back to the
/// same `f64`, so parsing the result gives a robot with the same forward kinematics, joint
/// names, limits, named configurations and stored allowed-collision matrix
/// (`[[disable_collisions]]`). The base and tool go through
/// [`crate::kinematics::pose::pose_from_matrix`] again on reading, which may change them in the
/// last bit.
///
/// # Examples
///
/// A round trip: the Puma 560 written out and read back has the same forward kinematics.
///
/// ```
/// use armlab::kinematics::models::built_in;
/// use armlab::model_file::{parse_model, to_toml};
/// use std::path::Path;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let puma = built_in("puma560").expect("a built-in model");
/// let text = to_toml(&puma).expect("a serial DH robot");
/// let back = parse_model(&text, Path::new("puma560.toml"))?;
/// let q = [0.3, -0.5, 0.2, 0.4, 0.9, -0.1];
/// assert!((back.fk(&q)?.to_homogeneous() - puma.fk(&q)?.to_homogeneous()).amax() < 1e-15);
/// assert_eq!(back.limits(), puma.limits());
/// // A closed chain has no DH table to write.
/// assert!(to_toml(&built_in("parallelogram").expect("a built-in model")).is_none());
/// # Ok(())
/// # }
/// ```
// Over 80 lines: the file's sections written in their order (joints, end-effectors,
// configurations, masses, the collision matrix); each is a short loop, read top to bottom.
pub fn to_toml(robot: &Robot) -> Option<String> {
    let ((convention, rows), pres) = robot.dh_table_with_pre()?;
    let follows =
        |j: &crate::kinematics::Joint| matches!(j.drive, Drive::Coupled(_) | Drive::Closure(_));
    if robot.joints().iter().any(follows) {
        return None;
    }
    let joints = robot.joints();
    let ees = robot.end_effectors();
    let default_ee = ees.len() == 1 && ees[0].name == "tool" && ees[0].parent + 1 == joints.len();
    let mut s = String::new();
    // Writing into a String cannot fail; the results are ignored.
    let _ = writeln!(s, "# Serial DH model written by armlab.");
    let _ = writeln!(s, "name = {}", quote(&robot.name));
    if !robot.description.is_empty() {
        let _ = writeln!(s, "description = {}", quote(&robot.description));
    }
    let _ = writeln!(s, "convention = \"{}\"", convention.as_str());
    if robot.base != Pose::identity() {
        let _ = writeln!(s, "base = {}", matrix(&robot.base));
    }
    if default_ee && ees[0].tool != Pose::identity() {
        let _ = writeln!(s, "tool = {}", matrix(&ees[0].tool));
    }
    for (i, ((j, (kind, row, offset)), pre)) in joints.iter().zip(rows).zip(&pres).enumerate() {
        let revolute = kind == JointKind::Revolute;
        let _ = writeln!(s, "\n[[joints]]\ntype = \"{}\"", kind.as_str());
        let _ = writeln!(s, "name = {}", quote(&j.name));
        if *pre != Pose::identity() {
            let _ = writeln!(s, "pre = {}", matrix(pre));
        }
        let _ = writeln!(s, "a = {}", num(row.a));
        let _ = writeln!(s, "alpha = {}", angle(row.alpha));
        if kind != JointKind::Prismatic {
            let _ = writeln!(s, "d = {}", num(row.d));
        }
        if kind != JointKind::Revolute && row.theta != 0.0 {
            let _ = writeln!(s, "theta = {}", angle(row.theta));
        }
        if kind != JointKind::Fixed {
            if offset != 0.0 {
                let _ = writeln!(s, "offset = {}", scalar(offset, revolute));
            }
            let [lo, hi] = j.limits;
            if lo.is_infinite() && hi.is_infinite() {
                let _ = writeln!(s, "limits = \"none\"");
            } else {
                let _ = writeln!(
                    s,
                    "limits = [{}, {}]",
                    scalar(lo, revolute),
                    scalar(hi, revolute)
                );
            }
        }
        write_mass(&mut s, robot, i);
    }
    if !default_ee {
        for e in ees {
            let _ = writeln!(s, "\n[[end_effectors]]\nname = {}", quote(&e.name));
            let _ = writeln!(s, "parent = {}", quote(&joints[e.parent].name));
            if e.tool != Pose::identity() {
                let _ = writeln!(s, "tool = {}", matrix(&e.tool));
            }
        }
    }
    for c in &robot.configurations {
        if c.name == "zero" && c.q.iter().all(|&v| v == 0.0) {
            continue;
        }
        let q: Vec<String> =
            c.q.iter()
                .enumerate()
                .map(|(k, &v)| scalar(v, robot.dof_joint(k).kind == JointKind::Revolute))
                .collect();
        let _ = writeln!(s, "\n[[configurations]]\nname = {}", quote(&c.name));
        let _ = writeln!(s, "q = [{}]", q.join(", "));
    }
    for d in &robot.disabled_collisions {
        let _ = writeln!(s, "\n[[disable_collisions]]");
        let _ = writeln!(s, "link1 = {}", quote(&d.link1));
        let _ = writeln!(s, "link2 = {}", quote(&d.link2));
        let _ = writeln!(s, "reason = {}", quote(&d.reason));
    }
    Some(s)
}

/// Shortest decimal that reads back to the same f64 (valid TOML for finite values).
/// Joint `i`'s link masses as one (the same pull of gravity): their total mass at their centre.
fn write_mass(s: &mut String, robot: &Robot, i: usize) {
    let on: Vec<_> = robot.masses.iter().filter(|m| m.joint == Some(i)).collect();
    let total: f64 = on.iter().map(|m| m.mass).sum();
    if total > 0.0 {
        let com = on
            .iter()
            .map(|m| m.com * m.mass)
            .sum::<nalgebra::Vector3<f64>>()
            / total;
        let _ = writeln!(s, "mass = {}", num(total));
        let _ = writeln!(s, "com = [{}, {}, {}]", num(com.x), num(com.y), num(com.z));
    }
}

fn num(v: f64) -> String {
    format!("{v:?}")
}

/// An angle: `"pi/2"`- or `"-160deg"`-style string when exact, else the number of radians.
fn angle(v: f64) -> String {
    exact_angle_string(v).map_or_else(|| num(v), |p| format!("\"{p}\""))
}

fn scalar(v: f64, angular: bool) -> String {
    if angular { angle(v) } else { num(v) }
}

fn matrix(p: &Pose) -> String {
    let rows: Vec<String> = pose_to_rows(p)
        .iter()
        .map(|r| {
            let cols: Vec<String> = r.iter().map(|&v| num(v)).collect();
            format!("[{}]", cols.join(", "))
        })
        .collect();
    format!("[{}]", rows.join(", "))
}

/// A TOML basic string.
fn quote(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 2);
    out.push('"');
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            '\r' => out.push_str("\\r"),
            c if c.is_control() => {
                let _ = write!(out, "\\u{:04X}", u32::from(c));
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}
