//! Robots into URDF text: `armlab export MODEL --urdf OUT.urdf` and the app's "Save as URDF".
//!
//! Every joint is lowered as `pre * M(value + offset) * post` (see [`crate::kinematics::robot`]).
//! URDF puts a joint's motion at its child link's frame, so the child link of joint j is
//! `F_parent * pre_j * M_j(value)`, and the joint's `<origin>` is `post_parent * pre_j *
//! M_j(offset)` (a joint's offset turns or slides along its own axis, so it folds into the
//! origin). The root link `world` carries the robot's base through a fixed joint to
//! `base_link`; each end-effector becomes a fixed joint to a link of its name at
//! `post_parent * tool`. A coupled joint with one term becomes a `<mimic>`; one that follows
//! several joints, or a closed chain's loop, has no URDF form and is refused. Each link gets
//! simple visuals: a cylinder along a revolute axis, a box on a prismatic one, and a thin
//! cylinder to each child joint. Numbers are written with Rust's shortest round-trip format, so
//! reading the file back gives the same forward kinematics to rounding (1e-15 m).

use crate::kinematics::robot::{Lowered, Motion};
use crate::kinematics::{Drive, JointKind, Pose, Robot};
use nalgebra::{Unit, Vector3};
use std::fmt::Write as _;
use thiserror::Error;

/// Why a robot cannot be written as URDF.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum UrdfExportError {
    /// A joint that follows several joints or a closed chain's loop.
    #[error(
        "joint \"{joint}\" {why}: URDF's <mimic> follows exactly one joint, so the robot has no \
         URDF form"
    )]
    NotExpressible {
        /// The joint.
        joint: String,
        /// What it follows.
        why: &'static str,
    },
}

/// Escapes text for an XML attribute.
fn xml(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// `xyz="..." rpy="..."` of a pose (URDF's rpy: R = Rz(yaw) Ry(pitch) Rx(roll)).
fn origin(p: &Pose) -> String {
    let t = p.translation.vector;
    let (r, pi, y) = p.rotation.euler_angles();
    format!(
        "<origin xyz=\"{} {} {}\" rpy=\"{} {} {}\"/>",
        t.x + 0.0,
        t.y + 0.0,
        t.z + 0.0,
        r + 0.0,
        pi + 0.0,
        y + 0.0
    )
}

/// The joint's motion axis (local) and URDF kind, or `None` for a fixed joint.
fn motion(l: &Lowered) -> Option<(Unit<Vector3<f64>>, &'static str)> {
    match l.motion {
        Motion::RotZ => Some((Vector3::z_axis(), "revolute")),
        Motion::TransZ => Some((Vector3::z_axis(), "prismatic")),
        Motion::Rot(a) => Some((a, "revolute")),
        Motion::Trans(a) => Some((a, "prismatic")),
        Motion::Fixed => None,
    }
}

/// The pose of the motion `M(v)` about or along `axis`.
fn moved(axis: &Unit<Vector3<f64>>, kind: &str, v: f64) -> Pose {
    if kind == "revolute" {
        Pose::from_parts(
            nalgebra::Translation3::identity(),
            nalgebra::Rotation3::from_axis_angle(axis, v),
        )
    } else {
        Pose::from_parts(
            nalgebra::Translation3::from(axis.into_inner() * v),
            nalgebra::Rotation3::identity(),
        )
    }
}

/// The transform from joint j's child link (as written) to its armlab frame F_j: `post`, or
/// the identity for a fixed joint (whose whole transform is in its origin).
fn link_post(robot: &Robot, j: usize) -> Pose {
    if robot.joints()[j].kind == JointKind::Fixed {
        Pose::identity()
    } else {
        robot.lowered[j].post
    }
}

/// The names written: URDF wants joint names unique and link names unique, and a robot's
/// joint or end-effector may be called like a name the writer adds ("base", "world",
/// "link_q1"), so each is made unique with a `_2`, `_3`, ... suffix where it would repeat.
struct Names {
    /// Per joint: its `<joint>` name.
    joint: Vec<String>,
    /// Per joint: its child link.
    link: Vec<String>,
    /// The fixed joint from `world` to `base_link`.
    base_joint: String,
    /// Per end-effector: its link and its fixed joint.
    ee: Vec<(String, String)>,
}

/// `want`, or `want_2`, `want_3`, ... : the first not in `taken` (then taken).
fn unique(taken: &mut std::collections::HashSet<String>, want: String) -> String {
    let mut name = want.clone();
    let mut k = 2;
    while taken.contains(&name) {
        name = format!("{want}_{k}");
        k += 1;
    }
    taken.insert(name.clone());
    name
}

impl Names {
    fn of(robot: &Robot) -> Names {
        let mut joints = std::collections::HashSet::new();
        let mut links: std::collections::HashSet<String> =
            ["world", "base_link"].map(String::from).into();
        let joint: Vec<String> = robot
            .joints()
            .iter()
            .map(|j| unique(&mut joints, j.name.clone()))
            .collect();
        let link = joint
            .iter()
            .map(|n| unique(&mut links, format!("link_{n}")))
            .collect();
        let base_joint = unique(&mut joints, "base".into());
        let ee = robot
            .end_effectors()
            .iter()
            .map(|e| {
                let l = unique(&mut links, e.name.clone());
                (l, unique(&mut joints, format!("{}_fixed", e.name)))
            })
            .collect();
        Names {
            joint,
            link,
            base_joint,
            ee,
        }
    }
}

/// Writes `robot` as a URDF document, or says why it has no URDF form.
pub fn to_urdf(robot: &Robot) -> Result<String, UrdfExportError> {
    let joints = robot.joints();
    let scale = robot.characteristic_length();
    let mut s = String::new();
    let _ = writeln!(s, "<?xml version=\"1.0\"?>");
    let _ = writeln!(
        s,
        "<!-- Written by armlab from \"{}\"; joint values are the model's q. -->",
        xml(&robot.name).replace("--", "- -")
    );
    let _ = writeln!(s, "<robot name=\"{}\">", xml(&robot.name));
    let _ = writeln!(s, "  <link name=\"world\"/>");
    let _ = writeln!(s, "  <link name=\"base_link\">");
    write_visuals(&mut s, robot, None, scale);
    let _ = writeln!(s, "  </link>");
    let names = Names::of(robot);
    fixed_joint(&mut s, &names.base_joint, "world", "base_link", &robot.base);
    for j in 0..joints.len() {
        write_joint(&mut s, robot, &names, j, scale)?;
    }
    for (e, (link, joint)) in robot.end_effectors().iter().zip(&names.ee) {
        let _ = writeln!(s, "  <link name=\"{}\"/>", xml(link));
        let o = link_post(robot, e.parent) * e.tool;
        fixed_joint(&mut s, joint, &names.link[e.parent], link, &o);
    }
    let _ = writeln!(s, "</robot>");
    Ok(s)
}

/// Joint j's child link (with its visuals) and the joint itself.
fn write_joint(
    s: &mut String,
    robot: &Robot,
    names: &Names,
    j: usize,
    scale: f64,
) -> Result<(), UrdfExportError> {
    let joints = robot.joints();
    let joint = &joints[j];
    let l = &robot.lowered[j];
    let parent_link = l.parent.map_or("base_link", |p| names.link[p].as_str());
    let parent_post = l.parent.map_or(Pose::identity(), |p| link_post(robot, p));
    let child = &names.link[j];
    let _ = writeln!(s, "  <link name=\"{}\">", xml(child));
    write_visuals(s, robot, Some(j), scale);
    let _ = writeln!(s, "  </link>");
    let Some((axis, kind)) = motion(l).filter(|_| joint.kind != JointKind::Fixed) else {
        let o = parent_post * l.pre * l.post;
        // A fixed joint: its whole transform is the origin; its child's frame is F_j.
        fixed_joint(s, &names.joint[j], parent_link, child, &o);
        return Ok(());
    };
    let o = parent_post * l.pre * moved(&axis, kind, joint.offset);
    let mimic = match &joint.drive {
        Drive::Coupled(terms) if terms.len() == 1 => Some(format!(
            "    <mimic joint=\"{}\" multiplier=\"{}\" offset=\"0\"/>",
            xml(&names.joint[terms[0].0]),
            terms[0].1
        )),
        Drive::Coupled(_) => {
            return Err(UrdfExportError::NotExpressible {
                joint: joint.name.clone(),
                why: "follows several joints",
            });
        }
        Drive::Closure(_) => {
            return Err(UrdfExportError::NotExpressible {
                joint: joint.name.clone(),
                why: "follows a closed chain's loop",
            });
        }
        _ => None,
    };
    let range = match &joint.drive {
        Drive::Actuated(k) => robot.sampling_range(*k),
        _ => [-1e3, 1e3],
    };
    let bounded = joint.limits.iter().all(|v| v.is_finite());
    let urdf_kind = if kind == "revolute" && !bounded {
        "continuous"
    } else {
        kind
    };
    let _ = writeln!(
        s,
        "  <joint name=\"{}\" type=\"{urdf_kind}\">\n    <parent link=\"{}\"/>\n    <child \
         link=\"{}\"/>\n    {}\n    <axis xyz=\"{} {} {}\"/>",
        xml(&names.joint[j]),
        xml(parent_link),
        xml(child),
        origin(&o),
        axis.x + 0.0,
        axis.y + 0.0,
        axis.z + 0.0
    );
    let [lo, hi] = if bounded { joint.limits } else { range };
    let _ = writeln!(
        s,
        "    <limit lower=\"{lo}\" upper=\"{hi}\" effort=\"100\" velocity=\"1\"/>"
    );
    if let Some(m) = mimic {
        let _ = writeln!(s, "{m}");
    }
    let _ = writeln!(s, "  </joint>");
    Ok(())
}

/// A fixed joint from `parent` to `child` at `o`.
fn fixed_joint(s: &mut String, name: &str, parent: &str, child: &str, o: &Pose) {
    let _ = writeln!(
        s,
        "  <joint name=\"{}\" type=\"fixed\">\n    <parent link=\"{}\"/>\n    <child \
         link=\"{}\"/>\n    {}\n  </joint>",
        xml(name),
        xml(parent),
        xml(child),
        origin(o)
    );
}

/// The visuals of joint j's child link (or of `base_link` for `None`): the joint's body at the
/// link origin and a thin cylinder to each child joint's origin.
fn write_visuals(s: &mut String, robot: &Robot, j: Option<usize>, scale: f64) {
    let r = 0.03 * scale.max(0.1);
    let grey = "<material name=\"grey\"><color rgba=\"0.6 0.6 0.65 1\"/></material>";
    if let Some(j) = j {
        let body = match motion(&robot.lowered[j]) {
            Some((axis, "revolute")) => {
                let rot = nalgebra::Rotation3::rotation_between(&Vector3::z(), &axis)
                    .unwrap_or_else(|| {
                        nalgebra::Rotation3::from_axis_angle(
                            &Vector3::x_axis(),
                            std::f64::consts::PI,
                        )
                    });
                Some((
                    Pose::from_parts(nalgebra::Translation3::identity(), rot),
                    format!("<cylinder radius=\"{}\" length=\"{}\"/>", 1.5 * r, 4.0 * r),
                ))
            }
            Some((_, _)) => Some((
                Pose::identity(),
                format!("<box size=\"{0} {0} {0}\"/>", 3.0 * r),
            )),
            None => None,
        };
        if let Some((o, geometry)) = body {
            let _ = writeln!(
                s,
                "    <visual>{}<geometry>{geometry}</geometry>\
                 <material name=\"blue\"><color rgba=\"0.3 0.45 0.8 1\"/></material></visual>",
                origin(&o)
            );
        }
    }
    let post = j.map_or(Pose::identity(), |j| link_post(robot, j));
    for (k, l) in robot.lowered.iter().enumerate() {
        if l.parent != j || k == j.unwrap_or(usize::MAX) {
            continue;
        }
        let tip = (post * l.pre).translation.vector;
        let len = tip.norm();
        if len <= 1e-9 * scale {
            continue;
        }
        let rot = nalgebra::Rotation3::rotation_between(&Vector3::z(), &tip).unwrap_or_else(|| {
            nalgebra::Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)
        });
        let o = Pose::from_parts(nalgebra::Translation3::from(tip * 0.5), rot);
        let _ = writeln!(
            s,
            "    <visual>{}<geometry><cylinder radius=\"{r}\" length=\"{len}\"/></geometry>\
             {grey}</visual>",
            origin(&o)
        );
    }
}
