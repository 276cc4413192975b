//! The files engineers have (issue 28), through the CLI: a headered CSV typed as a cell logs it
//! (degrees, millimetres, quaternions, extra columns), every setup's plain file written and read
//! back, the annotated template, and the calibrated robot written as TOML and as URDF with the
//! same FK.

use armlab::model_file::load_model;
use std::path::PathBuf;
use std::process::{Command, Output};

fn armlab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args(args)
        .output()
        .expect("run armlab")
}

fn json(o: &Output) -> serde_json::Value {
    assert!(
        o.status.success(),
        "stderr: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).expect("JSON on stdout")
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("armlab-calfiles-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn data(name: &str) -> String {
    format!(
        "{}/tests/data/calibration/{name}",
        env!("CARGO_MANIFEST_DIR")
    )
}

#[test]
fn a_headered_csv_from_a_cell_calibrates_to_the_noise_floor() {
    // tests/data/calibration/cell_puma_*.csv: joint angles in degrees (J1..J6), tracker
    // positions in millimetres, the probe's orientation as a quaternion, a timestamp and a note
    // column, comments and a blank line: 40 poses to fit, 40 held out; 0.02 mm and 0.05 mrad of
    // noise on a Puma 560 whose every parameter is off by up to 1 mm / 0.5 degree.
    let v = json(&armlab(&[
        "calibrate",
        "puma560",
        "--measurements",
        &data("cell_puma_fit.csv"),
        "--validate",
        &data("cell_puma_check.csv"),
        "--noise-mm",
        "0.02",
        "--noise-mrad",
        "0.05",
        "--format",
        "json",
    ]));
    let warnings: Vec<&str> = v["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w.as_str().unwrap())
        .collect();
    assert!(
        warnings.iter().any(|w| w.contains("\"timestamp\""))
            && warnings.iter().any(|w| w.contains("\"note\"")),
        "{warnings:?}"
    );
    assert_eq!(v["converged"], true);
    let before = v["validation"]["before"]["position_rms"].as_f64().unwrap();
    let after = v["validation"]["after"]["position_rms"].as_f64().unwrap();
    // Floor sqrt(3) x 0.02 mm; 40 poses for 24 parameters add about 30 % on held-out data.
    let floor = 3f64.sqrt() * 0.02e-3;
    assert!(before > 100.0 * floor, "{before}");
    assert!(after < 1.4 * floor, "{after} vs floor {floor}");
    // The same file in radians and metres with the columns in another order reads the same.
    let text = std::fs::read_to_string(data("cell_puma_fit.csv")).unwrap();
    let mut lines = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty());
    let header: Vec<&str> = lines.next().unwrap().split(',').map(str::trim).collect();
    let rows: Vec<Vec<String>> = lines
        .map(|l| l.split(',').map(|f| f.trim().to_string()).collect())
        .collect();
    let mut si = String::from(
        "note, qx, qy, qz, qw, x_m, y_m, z_m, q1 (rad), q2 (rad), q3 (rad), q4 (rad), q5 (rad), q6 (rad)\n",
    );
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    for r in &rows {
        let num = |name: &str| r[col(name)].parse::<f64>().unwrap();
        let mut f = vec![r[col("note")].clone()];
        for c in ["qx", "qy", "qz", "qw"] {
            f.push(r[col(c)].clone());
        }
        for c in ["X [mm]", "Y [mm]", "Z [mm]"] {
            f.push(format!("{:?}", num(c) * 1e-3));
        }
        for k in 1..=6 {
            f.push(format!("{:?}", num(&format!("J{k} [deg]")).to_radians()));
        }
        si.push_str(&f.join(", "));
        si.push('\n');
    }
    let d = dir("si");
    let path = d.join("si.csv");
    std::fs::write(&path, si).unwrap();
    let w = json(&armlab(&[
        "calibrate",
        "puma560",
        "--measurements",
        path.to_str().unwrap(),
        "--noise-mm",
        "0.02",
        "--noise-mrad",
        "0.05",
        "--format",
        "json",
    ]));
    for (a, b) in v["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .zip(w["parameters"].as_array().unwrap())
    {
        let (ea, eb) = (
            a["estimate"].as_f64().unwrap(),
            b["estimate"].as_f64().unwrap(),
        );
        assert!((ea - eb).abs() < 1e-9, "{}: {ea} vs {eb}", a["name"]);
    }
}

#[test]
fn headered_files_say_what_is_wrong_with_file_line_and_column() {
    let d = dir("bad");
    let path = d.join("bad.csv");
    let run = |text: &str| {
        std::fs::write(&path, text).unwrap();
        let o = armlab(&[
            "calibrate",
            "puma560",
            "--measurements",
            path.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(2));
        String::from_utf8_lossy(&o.stderr).to_string()
    };
    let e = run("J1 [deg], J2 [deg], J3 [deg], J4 [deg], J5 [deg], x, y, z\n1,2,3,4,5,6,7,8\n");
    assert!(
        e.contains("bad.csv") && e.contains("line 1") && e.contains("joint 6"),
        "{e}"
    );
    let e = run("J1 [mm], J2, J3, J4, J5, J6, x, y, z\n");
    assert!(e.contains("line 1") && e.contains("\"J1 [mm]\""), "{e}");
    let e = run("J1, J2, J3, J4, J5, J6, x, y, z\n1,2,3,4,5,6,7,8,oops\n");
    assert!(e.contains("line 2") && e.contains("column 9"), "{e}");
    let e = run("J1, J2, J3, J4, J5, J6, x, y, z, qw, qx\n1,2,3,4,5,6,7,8,9,1,0\n");
    assert!(e.contains("line 2") && e.contains("quaternion"), "{e}");
}

#[test]
fn every_setup_writes_its_plain_file_and_calibrates_from_it() {
    let d = dir("setups");
    for (setup, extra) in [
        ("distance", &[][..]),
        ("pivot", &["--groups", "3"][..]),
        ("plane", &["--groups", "2"][..]),
        ("sphere", &["--groups", "2", "--sphere-radius-mm", "25"][..]),
        ("tracker", &[][..]),
        ("position", &[][..]),
    ] {
        let file = d.join(format!("{setup}.csv"));
        let mut args = vec![
            "calibrate",
            "puma560",
            "--simulate",
            "--setup",
            setup,
            "--poses",
            "80",
            "--noise-mm",
            "0.02",
            "--write-measurements",
            file.to_str().unwrap(),
            "--format",
            "json",
        ];
        args.extend(extra);
        let sim = json(&armlab(&args));
        assert_eq!(sim["setup"], setup);
        assert_eq!(sim["converged"], true, "{setup}");
        assert!(sim["setup_cannot_see"].as_str().unwrap().len() > 20);
        // Read back: the same estimate.
        let mut again = vec![
            "calibrate",
            "puma560",
            "--setup",
            setup,
            "--measurements",
            file.to_str().unwrap(),
            "--noise-mm",
            "0.02",
            "--format",
            "json",
        ];
        if setup == "sphere" {
            // The radius travels in the file (`# radius_m`): no flag needed.
            assert!(
                std::fs::read_to_string(&file)
                    .unwrap()
                    .contains("# radius_m 0.025")
            );
        }
        again.truncate(10);
        let read = json(&armlab(&again));
        let a = sim["parameters"].as_array().unwrap();
        let b = read["parameters"].as_array().unwrap();
        for (pa, pb) in a.iter().zip(b) {
            let (ea, eb) = (
                pa["estimate"].as_f64().unwrap(),
                pb["estimate"].as_f64().unwrap(),
            );
            assert!(
                (ea - eb).abs() < 1e-9,
                "{setup}: {}: {ea} vs {eb}",
                pa["name"]
            );
        }
    }
}

#[test]
fn the_template_is_an_annotated_file_that_reads_back() {
    let d = dir("template");
    for setup in ["pose", "distance", "pivot", "plane", "sphere", "tracker"] {
        let t = d.join(format!("{setup}.csv"));
        let o = armlab(&[
            "calibrate",
            "puma560",
            "--setup",
            setup,
            "--template",
            t.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let text = std::fs::read_to_string(&t).unwrap();
        assert!(text.starts_with("# armlab calibration measurements"));
        assert!(text.contains("[deg]") && text.contains("What this setup cannot see"));
        // Its example rows parse. Four full poses are enough equations to run, and the nominal
        // model fits its own examples to their rounding (1e-4 degree and mm); the other setups
        // stop at the equation count, not at the file.
        let o = armlab(&[
            "calibrate",
            "puma560",
            "--setup",
            setup,
            "--measurements",
            t.to_str().unwrap(),
            "--format",
            "json",
        ]);
        if setup == "pose" {
            let v = json(&o);
            assert!(v["fit"]["before"]["position_max"].as_f64().unwrap() < 1e-5);
        } else {
            let err = String::from_utf8_lossy(&o.stderr);
            assert!(err.contains("equations from"), "{setup}: {err}");
        }
    }
}

#[test]
fn the_calibrated_robot_is_written_as_toml_and_urdf_with_the_same_fk() {
    let d = dir("urdf");
    let (toml, urdf) = (d.join("cal.toml"), d.join("cal.urdf"));
    let o = armlab(&[
        "calibrate",
        "puma560",
        "--simulate",
        "--with-tool",
        "--write-model",
        toml.to_str().unwrap(),
        "--write-urdf",
        urdf.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let a = load_model(toml.to_str().unwrap()).unwrap();
    let b = load_model(urdf.to_str().unwrap()).unwrap();
    assert_eq!(a.dof(), b.dof());
    let nominal = armlab::kinematics::models::built_in("puma560").unwrap();
    let mut worst = 0.0f64;
    for k in 0..50 {
        let q: Vec<f64> = (0..6)
            .map(|j| ((k * 7 + j * 3) as f64 * 0.37).sin() * 2.0)
            .collect();
        let (ta, tb) = (a.fk(&q).unwrap(), b.fk(&q).unwrap());
        let d = (ta.to_homogeneous() - tb.to_homogeneous()).abs().max();
        worst = worst.max(d);
        // And the calibration moved the arm (it is not the nominal one).
        let tn = nominal.fk(&q).unwrap();
        assert!((ta.to_homogeneous() - tn.to_homogeneous()).abs().max() > 1e-5);
    }
    assert!(worst < 1e-12, "URDF vs TOML FK: {worst:e}");
}

#[test]
fn correct_targets_writes_a_row_per_pose_and_posture() {
    let d = dir("targets");
    let targets = d.join("targets.csv");
    std::fs::write(
        &targets,
        "# desired poses\nx [mm], y [mm], z [mm], roll [deg], pitch [deg], yaw [deg]\n\
         450, 150, 400, 180, 0, 0\n500, -200, 300, 180, 20, 30\n",
    )
    .unwrap();
    let q = d.join("q.csv");
    let v = json(&armlab(&[
        "calibrate",
        "puma560",
        "--measurements",
        &data("cell_puma_fit.csv"),
        "--noise-mm",
        "0.02",
        "--noise-mrad",
        "0.05",
        "--correct-targets",
        targets.to_str().unwrap(),
        "--out",
        q.to_str().unwrap(),
        "--format",
        "json",
    ]));
    let tc = &v["target_correction"];
    assert_eq!(tc["poses"], 2);
    assert!(tc["worst_error"].as_f64().unwrap() <= 1e-12);
    let rows = tc["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 16, "two poses, eight Puma postures each");
    for r in rows {
        for key in [
            "pose",
            "posture",
            "q",
            "within_limits",
            "send",
            "position_error",
            "uncorrected_error",
        ] {
            assert!(r.get(key).is_some(), "{key}");
        }
        // The posture as fields too, the label rebuilt from them (the Puma's three parts).
        let parts = &r["posture_parts"];
        assert_eq!(parts["solver"], "closed_form", "{parts}");
        let word = |k: &str| parts[k].as_str().unwrap_or("?").replace('_', " ");
        let rebuilt = format!(
            "shoulder {}, elbow {}, wrist {}",
            word("shoulder"),
            word("elbow"),
            word("wrist")
        );
        assert_eq!(r["posture"].as_str(), Some(rebuilt.as_str()), "{parts}");
        // The uncorrected nominal solution misses by millimetres on this arm.
        assert!(r["uncorrected_error"].as_f64().unwrap() > 1e-3);
    }
    let text = std::fs::read_to_string(&q).unwrap();
    let lines: Vec<&str> = text.lines().filter(|l| !l.starts_with('#')).collect();
    assert_eq!(lines.len(), 17);
    assert!(lines[0].starts_with("pose, posture, within_limits, q1 [rad]"));
    assert!(lines[0].contains("send_qw"));
    // Bad targets: a position without orientation.
    std::fs::write(&targets, "x, y, z\n0.4, 0.1, 0.5\n").unwrap();
    let o = armlab(&[
        "calibrate",
        "puma560",
        "--simulate",
        "--correct-targets",
        targets.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("needs an orientation"));
}

/// Simulated full poses of a perturbed Puma 560 (0.02 mm, 0.05 mrad), seen from a camera 2 m
/// away and turned 90 degrees: (joint vectors, camera_from_tool).
fn camera_poses(count: usize, seed: u64) -> Vec<(Vec<f64>, armlab::kinematics::pose::Pose)> {
    use armlab::calibration::{ParameterModel, SimulationOptions, simulate};
    use armlab::kinematics::pose::Pose;
    use nalgebra::{Rotation3, Translation3, Vector3};
    let model = ParameterModel::new(&armlab::kinematics::models::built_in("puma560").unwrap())
        .unwrap()
        .with_hayati()
        .unwrap();
    let sim = simulate(
        &model,
        &SimulationOptions {
            poses: count,
            validation_poses: 0,
            noise_mm: 0.02,
            noise_mrad: 0.05,
            seed,
            ..SimulationOptions::default()
        },
    )
    .unwrap();
    let world_from_camera = Pose::from_parts(
        Translation3::new(2.2, 0.7, 1.075),
        Rotation3::from_axis_angle(&Vector3::z_axis(), std::f64::consts::FRAC_PI_2),
    );
    sim.measurements
        .iter()
        .map(|m| match m {
            armlab::calibration::Measurement::Pose {
                q, world_from_tool, ..
            } => (q.clone(), world_from_camera.inverse() * world_from_tool),
            _ => unreachable!(),
        })
        .collect()
}

#[test]
fn robot_cal_tools_yaml_calibrates_with_the_camera_pose_estimated() {
    // The layout of robot_cal_tools' kinematic measurements (rct_examples/data/
    // positioner_kinematic_measurements.yaml): a map from a timestamp to target_joints,
    // camera_joints (empty: a fixed camera) and pose (x y z qw qx qy qz, the target in the
    // camera's frame).
    let mut yaml = String::from("# written like robot_cal_tools' measurement files\n");
    for (k, (q, t)) in camera_poses(60, 31).iter().enumerate() {
        let u = nalgebra::UnitQuaternion::from_rotation_matrix(&t.rotation);
        let p = t.translation.vector;
        yaml.push_str(&format!(
            "'{}':\n  camera_joints: []\n  pose:\n",
            1_593_701_755 + 7 * k
        ));
        for (name, v) in [
            ("qw", u.w),
            ("qx", u.i),
            ("qy", u.j),
            ("qz", u.k),
            ("x", p.x),
            ("y", p.y),
            ("z", p.z),
        ] {
            yaml.push_str(&format!("    {name}: {v:?}\n"));
        }
        yaml.push_str("  target_joints:\n");
        for v in q {
            yaml.push_str(&format!("  - {v:?}\n"));
        }
    }
    let d = dir("yaml");
    let path = d.join("measurements.yaml");
    std::fs::write(&path, &yaml).unwrap();
    let v = json(&armlab(&[
        "calibrate",
        "puma560",
        "--setup",
        "tracker",
        "--measurements",
        path.to_str().unwrap(),
        "--noise-mm",
        "0.02",
        "--noise-mrad",
        "0.05",
        "--format",
        "json",
    ]));
    assert_eq!(v["converged"], true);
    let after = v["fit"]["after"]["position_rms"].as_f64().unwrap();
    assert!(after < 1.3 * 3f64.sqrt() * 0.02e-3, "{after}");
    // The camera found where it is: 2.2 m, 0.7 m, 1.075 m, turned 90 degrees (the base in the
    // camera's frame is the inverse).
    let t: Vec<f64> = v["tracker_from_base"]["translation"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let expect = [-0.7, 2.2, -1.075];
    for (a, b) in t.iter().zip(expect) {
        assert!((a - b).abs() < 0.01, "{t:?}");
    }
    // A camera on a moving chain is refused with the observation's name and line.
    let bad = yaml.replacen("camera_joints: []", "camera_joints: [0.1]", 1);
    std::fs::write(&path, bad).unwrap();
    let o = armlab(&[
        "calibrate",
        "puma560",
        "--setup",
        "tracker",
        "--measurements",
        path.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(
        e.contains("1593701755") && e.contains("line 2") && e.contains("camera_joints"),
        "{e}"
    );
}

#[test]
fn figaroh_csv_calibrates() {
    // FIGAROH's layout (figaroh-examples, examples/ur10/data/calibration.csv): marker columns
    // x1, y1, z1, phix1, phiy1, phiz1 (roll-pitch-yaw, rad), then the joints by name; a time
    // column `t` as in the Talos files; SI units, no unit in the header.
    let puma = armlab::kinematics::models::built_in("puma560").unwrap();
    let names = armlab::calibration::JointColumns::of(&puma).names;
    let mut csv = format!("t,x1,y1,z1,phix1,phiy1,phiz1,{}\n", names.join(","));
    for (k, (q, t)) in camera_poses(60, 32).iter().enumerate() {
        // The camera is the world here: undo the camera pose of camera_poses.
        let world_from_camera = armlab::kinematics::pose::Pose::from_parts(
            nalgebra::Translation3::new(2.2, 0.7, 1.075),
            nalgebra::Rotation3::from_axis_angle(
                &nalgebra::Vector3::z_axis(),
                std::f64::consts::FRAC_PI_2,
            ),
        );
        let w = world_from_camera * t;
        let rpy = armlab::kinematics::orientation::rpy_from_rotation(&w.rotation).angles;
        let p = w.translation.vector;
        let mut f = vec![
            format!("{}", k as f64 * 0.5),
            format!("{:?}", p.x),
            format!("{:?}", p.y),
            format!("{:?}", p.z),
        ];
        // rpy_from_rotation gives (phi, theta, psi) of Rz(phi) Ry(theta) Rx(psi): phiz, phiy, phix.
        f.extend([rpy[2], rpy[1], rpy[0]].iter().map(|v| format!("{v:?}")));
        f.extend(q.iter().map(|v| format!("{v:?}")));
        csv.push_str(&f.join(","));
        csv.push('\n');
    }
    let d = dir("figaroh");
    let path = d.join("calibration.csv");
    std::fs::write(&path, csv).unwrap();
    let v = json(&armlab(&[
        "calibrate",
        "puma560",
        "--measurements",
        path.to_str().unwrap(),
        "--noise-mm",
        "0.02",
        "--noise-mrad",
        "0.05",
        "--format",
        "json",
    ]));
    assert_eq!(v["setup"], "pose");
    assert_eq!(v["converged"], true);
    let after = v["fit"]["after"]["position_rms"].as_f64().unwrap();
    assert!(after < 1.3 * 3f64.sqrt() * 0.02e-3, "{after}");
    let warnings = v["warnings"].to_string();
    assert!(warnings.contains("\\\"t\\\""), "{warnings}");
}

#[test]
fn a_urdf_arm_calibrates_through_its_dh_form_and_keeps_its_joints_in_the_written_urdf() {
    // The UR5 URDF (tests/data/urdf_corpus): not a DH table. It is calibrated through its
    // derived standard DH table (Hayati's beta on the parallel axes 2-3-4), and the URDF written
    // keeps the chain's joints, their origins moved, with the FK of the calibrated table.
    let d = dir("ur5");
    let (toml, urdf) = (d.join("cal.toml"), d.join("cal.urdf"));
    let src = format!(
        "{}/tests/data/urdf_corpus/ur5_robot.urdf",
        env!("CARGO_MANIFEST_DIR")
    );
    let v = json(&armlab(&[
        "calibrate",
        &src,
        "--simulate",
        "--poses",
        "60",
        "--noise-mm",
        "0.02",
        "--write-model",
        toml.to_str().unwrap(),
        "--write-urdf",
        urdf.to_str().unwrap(),
        "--format",
        "json",
    ]));
    assert!(
        v["warnings"]
            .to_string()
            .contains("derived standard DH table")
    );
    assert_eq!(v["hayati_rows"], serde_json::json!([2, 3]));
    assert_eq!(v["converged"], true);
    let after = v["validation"]["after"]["position_rms"].as_f64().unwrap();
    assert!(after < 1.3 * 3f64.sqrt() * 0.02e-3, "{after}");
    let original = load_model(&src).unwrap();
    let a = load_model(toml.to_str().unwrap()).unwrap();
    let b = load_model(urdf.to_str().unwrap()).unwrap();
    let names = |r: &armlab::kinematics::Robot| armlab::calibration::JointColumns::of(r).names;
    assert_eq!(
        names(&b),
        names(&original),
        "the URDF keeps the chain's joint names"
    );
    let (mut worst, mut moved) = (0.0f64, 0.0f64);
    for k in 0..40 {
        let q: Vec<f64> = (0..6)
            .map(|j| ((k * 5 + j * 2) as f64 * 0.41).sin() * 2.5)
            .collect();
        let (ta, tb) = (a.fk(&q).unwrap(), b.fk(&q).unwrap());
        worst = worst.max((ta.to_homogeneous() - tb.to_homogeneous()).abs().max());
        let to = original.fk(&q).unwrap();
        moved = moved.max((tb.translation.vector - to.translation.vector).norm());
    }
    assert!(worst < 1e-12, "URDF vs TOML FK: {worst:e}");
    assert!(
        moved > 1e-3,
        "the calibration moved the tool by {moved} m at most"
    );
}

#[test]
fn with_compliance_uses_the_urdf_inertials_and_says_when_there_are_none() {
    let src = format!(
        "{}/tests/data/urdf_corpus/ur5_robot.urdf",
        env!("CARGO_MANIFEST_DIR")
    );
    let v = json(&armlab(&[
        "calibrate",
        &src,
        "--simulate",
        "--with-compliance",
        "--poses",
        "100",
        "--noise-mm",
        "0.005",
        "--noise-mrad",
        "0.01",
        "--format",
        "json",
    ]));
    assert_eq!(v["converged"], true);
    let cs: Vec<&serde_json::Value> = v["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["kind"] == "c")
        .collect();
    assert_eq!(cs.len(), 6, "a compliance per revolute joint");
    // The UR5's shoulder and elbow carry the arm: their compliances are identified.
    for p in &cs[1..3] {
        assert_eq!(p["identifiable"], true, "{}", p["name"]);
        let (e, t, s) = (
            p["estimate"].as_f64().unwrap(),
            p["true"].as_f64().unwrap(),
            p["std"].as_f64().unwrap(),
        );
        assert!(
            (e - t).abs() < 4.0 * s,
            "{}: {e} vs {t} (std {s})",
            p["name"]
        );
    }
    let o = armlab(&["calibrate", "stanford", "--simulate", "--with-compliance"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("needs the links' masses"));
}

#[test]
fn ik_on_a_calibrated_model_keeps_the_nominal_postures() {
    // A calibrated Puma (Hayati's beta on axes 2-3: no longer exactly the Puma's structure):
    // `armlab ik CAL --nominal puma560` gives the Puma's eight labelled postures, each on the
    // calibrated arm to 1e-12.
    let d = dir("ik");
    let cal = d.join("cal.toml");
    let o = armlab(&[
        "calibrate",
        "puma560",
        "--simulate",
        "--write-model",
        cal.to_str().unwrap(),
    ]);
    assert!(o.status.success());
    let puma = armlab::kinematics::models::built_in("puma560").unwrap();
    let t = puma
        .fk(&[0.3, -0.5, 0.4, 0.6, -0.7, 0.2])
        .unwrap()
        .to_homogeneous();
    let pose: Vec<String> = (0..4)
        .flat_map(|r| (0..4).map(move |c| (r, c)))
        .map(|(r, c)| format!("{:?}", t[(r, c)]))
        .collect();
    let pose = pose.join(",");
    let v = json(&armlab(&[
        "ik",
        cal.to_str().unwrap(),
        "--nominal",
        "puma560",
        "--pose",
        &pose,
        "--all",
        "--format",
        "json",
    ]));
    let sols = v[0]["solutions"].as_array().unwrap();
    assert_eq!(sols.len(), 8);
    let calibrated = load_model(cal.to_str().unwrap()).unwrap();
    // Without --nominal: the general 6R elimination, 8 branches, each polished to 1e-12 on the
    // model (they were left at 3e-12 m when the polish refused an orientation error rising from
    // 1e-16 to 1e-14).
    let general = json(&armlab(&[
        "ik",
        cal.to_str().unwrap(),
        "--pose",
        &pose,
        "--all",
        "--format",
        "json",
    ]));
    let branches = general[0]["solutions"].as_array().unwrap();
    assert_eq!(branches.len(), 8);
    for s in branches {
        let q: Vec<f64> = s["q"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        let e = calibrated.fk(&q).unwrap().to_homogeneous();
        assert!(
            (e - t).abs().max() < 1e-12,
            "{}: {:e}",
            s["posture"],
            (e - t).abs().max()
        );
    }
    for s in sols {
        assert!(
            s["posture"].as_str().unwrap().starts_with("shoulder "),
            "{s}"
        );
        let q: Vec<f64> = s["q"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        // FK-checked here, on the calibrated model.
        let e = calibrated.fk(&q).unwrap().to_homogeneous();
        assert!((e - t).abs().max() < 1e-12, "{}", s["posture"]);
    }
}
