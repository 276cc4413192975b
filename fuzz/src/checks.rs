//! What must hold for every input of armlab's parsers of outside text: more than "no panic".
//! Shared by the cargo-fuzz targets (`fuzz/fuzz_targets/`) and by the stable test suite, which
//! replays every input kept under `tests/data/fuzz/<target>/` (`tests/kinematics/fuzz_regressions.rs`).
//!
//! - A file that parses yields a robot whose forward kinematics and Jacobian are finite for
//!   finite q (inside its limits), whose written form (TOML or URDF) reads back to the same
//!   kinematics; otherwise the error names the file and, for a model file, a line in it.
//! - Rows and measurements that parse have exactly the numbers asked for, all finite, at
//!   increasing lines; otherwise the error names `file:line` with a line of the file.
//! - An angle that parses is finite.
#![allow(dead_code)]

use armlab::kinematics::Robot;
use std::path::Path;

/// Joint vectors to evaluate a parsed robot at: zero, and points spread inside the limits.
fn probe_qs(robot: &Robot) -> Vec<Vec<f64>> {
    let ranges = robot.sampling_ranges();
    let mut qs = vec![vec![0.0; robot.dof()]];
    for t in [0.1, 0.5, 0.93] {
        qs.push(ranges.iter().map(|[lo, hi]| lo + t * (hi - lo)).collect());
    }
    qs
}

/// Forward kinematics and the Jacobian of every end-effector at every probe: finite.
fn check_robot(robot: &Robot) {
    for q in probe_qs(robot) {
        assert!(q.iter().all(|v| v.is_finite()), "probe q not finite: {q:?}");
        for ee in 0..robot.end_effectors().len() {
            let pose = robot.fk_ee(&q, ee).expect("FK of a parsed robot");
            let m = pose.to_homogeneous();
            assert!(m.iter().all(|v| v.is_finite()), "FK not finite at {q:?}");
            let j = robot.jacobian(&q, ee).expect("Jacobian of a parsed robot");
            assert!(j.iter().all(|v| v.is_finite()), "Jacobian not finite");
        }
    }
    // Neither of these may panic; either answer is fine.
    let _ = armlab::kinematics::ik::closed_form::ClosedForm::detect(robot);
    let _ = armlab::kinematics::dh_derive::derive_dh(
        robot,
        0,
        armlab::kinematics::Convention::Standard,
    );
}

/// Two robots with the same forward kinematics (every end-effector, every probe of `a`).
fn check_same_kinematics(a: &Robot, b: &Robot, how: &str) {
    assert_eq!(a.dof(), b.dof(), "{how}: DOF changed");
    assert_eq!(
        a.end_effectors().len(),
        b.end_effectors().len(),
        "{how}: end-effectors changed"
    );
    let scale = a.characteristic_length().max(1.0);
    for q in probe_qs(a) {
        for ee in 0..a.end_effectors().len() {
            let ma = a.fk_ee(&q, ee).unwrap().to_homogeneous();
            let mb = b.fk_ee(&q, ee).unwrap().to_homogeneous();
            let d = (ma - mb).amax();
            assert!(d <= 1e-9 * scale, "{how}: FK differs by {d} at {q:?}");
        }
    }
}

/// The 1-based line an error names must exist in the text (or be one past its end).
fn check_line(text: &str, line: usize, what: &str) {
    let lines = text.lines().count();
    assert!(
        line >= 1 && line <= lines + 1,
        "{what}: line {line} of a {lines}-line text"
    );
}

/// A TOML model file.
pub fn model_toml(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let path = Path::new("fuzz.toml");
    match armlab::model_file::parse_model(text, path) {
        Ok(robot) => {
            check_robot(&robot);
            if let Some(written) = armlab::model_file::to_toml(&robot) {
                let again = armlab::model_file::parse_model(&written, path)
                    .unwrap_or_else(|e| panic!("written TOML does not read back: {e}\n{written}"));
                check_same_kinematics(&robot, &again, "TOML round trip");
            }
        }
        Err(e) => {
            let message = e.to_string();
            assert!(message.contains("fuzz.toml"), "no file named: {message}");
            let at = e.location().expect("a parse error has a location");
            check_line(text, at.line, &message);
        }
    }
}

/// A URDF file (through urdf-rs into armlab's robot).
pub fn urdf(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let path = Path::new("fuzz.urdf");
    match armlab::urdf::parse_urdf(text, path) {
        Ok(robot) => {
            check_robot(&robot);
            if let Ok(written) = armlab::urdf::to_urdf(&robot) {
                let again = armlab::urdf::parse_urdf(&written, path)
                    .unwrap_or_else(|e| panic!("written URDF does not read back: {e}\n{written}"));
                check_same_kinematics(&robot, &again, "URDF round trip");
            }
        }
        Err(e) => {
            let message = e.to_string();
            assert!(message.contains("fuzz.urdf"), "no file named: {message}");
        }
    }
}

/// A rows file (joint vectors, targets, points): the first byte picks how many numbers a row
/// has (1 to 16); rows of 16 are also read as poses, as `armlab ik --target pose` does.
pub fn rows(data: &[u8]) {
    let Some((&first, rest)) = data.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    let expected = 1 + usize::from(first % 16);
    match armlab::input::parse_rows(text, "fuzz.txt", expected, "numbers") {
        Ok(rows) => {
            let mut last = 0;
            for (line, row) in rows {
                assert!(line > last, "lines out of order");
                check_line(text, line, "row");
                last = line;
                assert_eq!(row.len(), expected);
                assert!(row.iter().all(|v| v.is_finite()));
                if expected == 16 {
                    let m = nalgebra::Matrix4::from_row_slice(&row);
                    if let Ok(p) = armlab::kinematics::pose::pose_from_matrix(&m) {
                        assert!(p.to_homogeneous().iter().all(|v| v.is_finite()));
                    }
                }
            }
        }
        Err(e) => {
            let message = e.to_string();
            let line = message
                .strip_prefix("fuzz.txt:")
                .and_then(|m| m.split(':').next())
                .and_then(|n| n.parse::<usize>().ok())
                .unwrap_or_else(|| panic!("no file:line in {message:?}"));
            check_line(text, line, &message);
        }
    }
}

/// A measurement file for a robot of 1 to 8 joints and one of the setups (the first byte),
/// plain or headered.
pub fn measurements(data: &[u8]) {
    use armlab::calibration::{JointColumns, Measurement, Setup, parse_setup};
    let Some((&first, rest)) = data.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    let dof = 1 + usize::from(first % 8);
    let setup = Setup::ALL[usize::from(first / 8) % Setup::ALL.len()];
    let joints = JointColumns::numbered(dof);
    match parse_setup(text, "fuzz.txt", &joints, setup, Some(0.02)) {
        Ok(file) => {
            let ms = &file.measurements;
            assert!(!ms.is_empty(), "an empty file parsed");
            for m in ms {
                for q in m.joint_vectors() {
                    assert_eq!(q.len(), dof);
                    assert!(q.iter().all(|v| v.is_finite()));
                }
                let finite = match m {
                    Measurement::Pose {
                        world_from_tool, ..
                    } => world_from_tool
                        .to_homogeneous()
                        .iter()
                        .all(|v| v.is_finite()),
                    Measurement::Position { p, .. } => p.iter().all(|v| v.is_finite()),
                    Measurement::Distance { distance: v, .. }
                    | Measurement::Sphere { radius: v, .. } => v.is_finite() && *v > 0.0,
                    Measurement::Pivot { .. } | Measurement::Plane { .. } => true,
                };
                assert!(finite, "a measurement with a non-finite value");
                assert_eq!(m.kind(), ms[0].kind(), "mixed kinds parsed");
            }
        }
        Err(e) => {
            assert_eq!(e.source_name, "fuzz.txt");
            if e.line > 0 {
                check_line(text, e.line, &e.to_string());
            }
        }
    }
}

/// An angle expression ("pi/2", "-90deg", "1.2rad").
pub fn angle(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Some(v) = armlab::model_file::parse_angle(text) {
        assert!(v.is_finite(), "{text:?} gave {v}");
    }
}

/// A mesh file (STL, OBJ or COLLADA: the first byte picks the extension) read as a URDF visual
/// is: every index in range, every vertex finite, at most `MAX_TRIANGLES` triangles.
pub fn mesh(data: &[u8]) {
    let Some((&first, rest)) = data.split_first() else {
        return;
    };
    let ext = ["stl", "obj", "dae"][usize::from(first % 3)];
    // armlab catches a panic of the mesh loader (a third-party crate) and reports the file as
    // unreadable; libfuzzer's panic hook would abort on the caught panic, so the default hook is
    // put back. A panic armlab does not catch still aborts (libfuzzer-sys catches the unwind).
    static DEFAULT_HOOK: std::sync::Once = std::sync::Once::new();
    DEFAULT_HOOK.call_once(|| drop(std::panic::take_hook()));
    let path = std::env::temp_dir().join(format!("armlab-fuzz-mesh.{ext}"));
    if let Ok(mesh) = armlab::urdf::parse_mesh(rest, &path) {
        let n = mesh.positions.len() as u32;
        assert!(!mesh.triangles.is_empty(), "a mesh without triangles");
        assert!(mesh.triangles.len() <= armlab::urdf::MAX_TRIANGLES);
        assert!(
            mesh.triangles.iter().flatten().all(|&v| v < n),
            "index out of range"
        );
        assert!(mesh.positions.iter().flatten().all(|v| v.is_finite()));
    }
}
