//! A corpus of public robot descriptions as their makers publish them (`tests/data/urdf_corpus/`,
//! 22 files: arms, a dual-arm robot, a mobile manipulator, a humanoid, grippers with mimic
//! joints; source, commit and licence of each in `SOURCES.toml`, meshes left out). Every file
//! loads (missing meshes are warnings naming the link), and the chain from the root to each
//! robot's tool frame has the number of moving joints (mimic joints included) recorded in the
//! manifest, which was counted from the files by hand-checked script, not by armlab.
//!
//! Each robot's default end-effector is on the arm of its tool frame, and that arm's analysis
//! (closed-form family or the reason for none, degree of redundancy, self-motion parameter)
//! matches the manifest's per-arm columns; a claimed spherical wrist is checked independently
//! (axes 4-6 from finite differences of the tool pose meet in one point).

use armlab::kinematics::end_effectors::catalog;
use armlab::kinematics::{JointKind, Robot};
use armlab::redundancy::report::arm_report;

use std::path::Path;

#[derive(serde::Deserialize)]
struct Manifest {
    robot: Vec<Entry>,
}

#[derive(serde::Deserialize)]
struct Entry {
    name: String,
    file: String,
    licence: String,
    commit: String,
    tool_frame: String,
    dof: usize,
    mimic_joints: usize,
    closed_form: String,
    closed_form_reason_contains: String,
    redundancy_degree: usize,
    self_motion: String,
}

fn manifest() -> Manifest {
    let text = std::fs::read_to_string("tests/data/urdf_corpus/SOURCES.toml").unwrap();
    toml::from_str(&text).unwrap()
}

fn load(file: &str) -> Robot {
    let path = Path::new("tests/data/urdf_corpus").join(file);
    armlab::model_file::load_model(path.to_str().unwrap()).unwrap_or_else(|e| panic!("{file}: {e}"))
}

#[test]
fn the_manifest_names_source_licence_and_commit_of_every_file() {
    let m = manifest();
    assert!(m.robot.len() >= 15, "{} robots", m.robot.len());
    for e in &m.robot {
        assert!(!e.licence.is_empty() && e.commit.len() == 40, "{}", e.name);
        assert!(
            Path::new("tests/data/urdf_corpus").join(&e.file).is_file(),
            "{}",
            e.file
        );
    }
    // Grippers with mimic joints are in it.
    assert!(m.robot.iter().filter(|e| e.mimic_joints > 0).count() >= 2);
}

#[test]
fn every_robot_loads_and_its_tool_chain_has_the_manifests_dof() {
    let mut bad = Vec::new();
    for e in manifest().robot {
        let robot = load(&e.file);
        // Forward kinematics is finite at zero for every end-effector.
        for k in 0..robot.end_effectors().len() {
            let tool = robot.fk_ee(&vec![0.0; robot.dof()], k).unwrap();
            assert!(
                tool.translation.vector.iter().all(|v| v.is_finite()),
                "{}",
                e.file
            );
        }
        let Some(ee) = robot
            .end_effectors()
            .iter()
            .find(|t| t.name == e.tool_frame)
        else {
            let names: Vec<&str> = robot
                .end_effectors()
                .iter()
                .map(|t| t.name.as_str())
                .collect();
            bad.push(format!(
                "{}: no end-effector {} among {names:?}",
                e.file, e.tool_frame
            ));
            continue;
        };
        let moving = robot
            .chain_to(ee.parent)
            .iter()
            .filter(|&&j| robot.joints()[j].kind != JointKind::Fixed)
            .count();
        if moving != e.dof {
            bad.push(format!(
                "{}: {moving} moving joints to {}, the manifest says {}",
                e.file, e.tool_frame, e.dof
            ));
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// The manifest's tool frame and armlab's default end-effector are on one arm (the same moving
/// joints), and that arm's analysis is the manifest's.
#[test]
fn the_default_end_effector_is_the_tool_of_an_arm_and_its_analysis_holds() {
    let mut bad = Vec::new();
    for e in manifest().robot {
        let robot = load(&e.file);
        let cat = catalog(&robot);
        assert_eq!(
            cat.default_ee(),
            0,
            "{}: end-effector 0 is the default",
            e.file
        );
        let q = vec![0.0; robot.dof()];
        let default = arm_report(&robot, &cat, 0, &q);
        let tool = robot
            .end_effectors()
            .iter()
            .position(|t| t.name == e.tool_frame)
            .unwrap();
        let expected = arm_report(&robot, &cat, tool, &q);
        // A robot with two like arms (Baxter) may default to either: the other must then be an
        // arm of its own with the manifest's tool as its tool.
        let twin = default.dof == expected.dof && cat.tools().contains(&tool);
        if default.chain != expected.chain && !twin {
            bad.push(format!(
                "{}: the default {} ({:?}) is not on the arm of {} ({:?})",
                e.file, default.name, default.chain, e.tool_frame, expected.chain
            ));
            continue;
        }
        let r = expected;
        match (e.closed_form.as_str(), r.closed_form) {
            ("none", None) => {
                let why = r.closed_form_reason.clone().unwrap_or_default();
                if !why.contains(&e.closed_form_reason_contains) {
                    bad.push(format!(
                        "{}: no closed form as expected, but the reason \"{why}\" does not say \"{}\"",
                        e.file, e.closed_form_reason_contains
                    ));
                }
            }
            (want, Some(got)) if want == got => {
                let why = r.closed_form_reason.clone().unwrap_or_default();
                if !why.contains(&e.closed_form_reason_contains) {
                    bad.push(format!(
                        "{}: {got}, but the reason no named family applies (\"{why}\") does \
                         not say \"{}\"",
                        e.file, e.closed_form_reason_contains
                    ));
                }
                if got.contains("spherical wrist") {
                    let gap = wrist_gap(&robot, r.ee);
                    if gap > 1e-5 {
                        bad.push(format!("{}: wrist axes miss by {gap:e} m", e.file));
                    }
                }
            }
            (want, got) => bad.push(format!(
                "{}: closed form {got:?} ({:?}), the manifest says {want}",
                e.file, r.closed_form_reason
            )),
        }
        if r.redundancy_degree != e.redundancy_degree {
            bad.push(format!(
                "{}: degree of redundancy {}, the manifest says {}",
                e.file, r.redundancy_degree, e.redundancy_degree
            ));
        }
        let sm = r.self_motion.unwrap_or("none");
        if sm != e.self_motion {
            bad.push(format!(
                "{}: self-motion parameter {sm}, the manifest says {} ({:?})",
                e.file, e.self_motion, r.self_motion_reason
            ));
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// How far the axes of the last three joints of end-effector `ee`'s arm are from meeting in one
/// point (m), at a spread configuration: each axis is read from finite differences of the tool
/// pose (the rotation axis and a point of it), not from the DH or closed-form code.
fn wrist_gap(robot: &Robot, ee: usize) -> f64 {
    let arm = armlab::kinematics::arm::arm_of(robot, ee, &vec![0.0; robot.dof()]).unwrap();
    let r = &arm.robot;
    let n = r.dof();
    let q: Vec<f64> = (0..n).map(|k| 0.3 + 0.2 * k as f64).collect();
    let t0 = r.fk(&q).unwrap();
    let h = 1e-6;
    let mut axes = Vec::new();
    for k in n - 3..n {
        let mut q1 = q.clone();
        q1[k] += h;
        let t1 = r.fk(&q1).unwrap();
        // omega = axis (world), v = d p / d q = omega x (p - c).
        let dr = (t1.rotation * t0.rotation.inverse()).scaled_axis() / h;
        let w = dr.normalize();
        let v = (t1.translation.vector - t0.translation.vector) / h;
        // A point c on the axis: c = p + (w x v) (unit w).
        let c = t0.translation.vector + w.cross(&v);
        axes.push((c, w));
    }
    // Distance between axis pairs (lines) and whether their closest points coincide.
    let closest = |(c1, w1): (nalgebra::Vector3<f64>, nalgebra::Vector3<f64>),
                   (c2, w2): (nalgebra::Vector3<f64>, nalgebra::Vector3<f64>)| {
        let n = w1.cross(&w2);
        let d = c2 - c1;
        let s = d.cross(&w2).dot(&n) / n.norm_squared();
        c1 + w1 * s
    };
    let p45 = closest(axes[0], axes[1]);
    let p56 = closest(axes[1], axes[2]);
    let on = |p: nalgebra::Vector3<f64>,
              (c, w): (nalgebra::Vector3<f64>, nalgebra::Vector3<f64>)| {
        (p - c).cross(&w).norm()
    };
    (p45 - p56)
        .norm()
        .max(on(p45, axes[0]))
        .max(on(p45, axes[1]))
        .max(on(p56, axes[2]))
}
