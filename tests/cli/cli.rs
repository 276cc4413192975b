//! The command line as a script uses it: outputs, JSON shape, and bad input exiting with code 2
//! and one clear line on stderr (never a panic, never a partial result).

use std::io::Write;
use std::process::{Command, Output, Stdio};

fn armlab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args(args)
        .output()
        .expect("run armlab")
}

fn armlab_stdin(args: &[&str], input: &str) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn");
    // armlab may stop reading early (a refused line): a broken pipe is its answer, not ours.
    let written = child.stdin.take().unwrap().write_all(input.as_bytes());
    if let Err(e) = written {
        assert_eq!(e.kind(), std::io::ErrorKind::BrokenPipe, "{e}");
    }
    child.wait_with_output().unwrap()
}

fn json(o: &Output) -> serde_json::Value {
    assert!(
        o.status.success(),
        "stderr: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).expect("JSON on stdout")
}

/// Exit code 2, nothing on stdout, one line on stderr containing `needle`.
fn bad(o: &Output, needle: &str) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert!(
        o.stdout.is_empty(),
        "partial output: {}",
        String::from_utf8_lossy(&o.stdout)
    );
    assert_eq!(
        err.trim_end().lines().count(),
        1,
        "one line expected: {err}"
    );
    assert!(err.contains(needle), "{needle:?} not in {err:?}");
    assert!(!err.contains("panicked"));
}

#[test]
fn the_app_without_a_display_says_what_to_do() {
    let o = Command::new(env!("CARGO_BIN_EXE_armlab"))
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .output()
        .unwrap();
    bad(&o, "--screenshot");
}

#[test]
fn robots_lists_every_built_in() {
    let v = json(&armlab(&["robots", "--format", "json"]));
    let list = v.as_array().unwrap();
    assert_eq!(list.len(), armlab::kinematics::models::BUILT_INS.len());
    let puma = list.iter().find(|r| r["name"] == "puma560").unwrap();
    assert_eq!(puma["dof"], 6);
    let text = String::from_utf8(armlab(&["robots"]).stdout).unwrap();
    assert!(text.contains("humanoid") && text.contains("17"));
}

#[test]
fn fk_json_is_exact_and_shaped() {
    let v = json(&armlab(&[
        "fk",
        "puma560",
        "--q",
        "0.1,0.2,0.3,0.4,0.5,0.6",
        "--format",
        "json",
        "--euler",
        "zyz",
        "--frames",
    ]));
    let row = &v.as_array().unwrap()[0];
    assert_eq!(row["q"], serde_json::json!([0.1, 0.2, 0.3, 0.4, 0.5, 0.6]));
    let robot = armlab::kinematics::models::built_in("puma560").unwrap();
    let t = robot
        .fk(&[0.1, 0.2, 0.3, 0.4, 0.5, 0.6])
        .unwrap()
        .to_homogeneous();
    for r in 0..4 {
        for c in 0..4 {
            // Shortest round-trip doubles: the printed number parses to the same double.
            assert_eq!(row["T"][r][c].as_f64().unwrap(), t[(r, c)]);
        }
    }
    assert_eq!(row["phi"].as_array().unwrap().len(), 3);
    assert_eq!(row["frames"].as_array().unwrap().len(), 6);
}

#[test]
fn fk_many_rows_from_a_file_and_stdin() {
    let dir = std::env::temp_dir().join(format!("armlab-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("q.txt");
    std::fs::write(&f, "# two-link arm\n0, 0\n\n0.5,-0.25  # elbow\n").unwrap();
    let v = json(&armlab(&[
        "fk",
        "planar2",
        "--input",
        f.to_str().unwrap(),
        "--format",
        "json",
    ]));
    assert_eq!(v.as_array().unwrap().len(), 2);
    assert_eq!(v[0]["T"][0][3], 2.0);
    let v = json(&armlab_stdin(
        &["fk", "planar2", "--input", "-", "--format", "json"],
        "0,0\n",
    ));
    assert_eq!(v.as_array().unwrap().len(), 1);
    // The humanoid reports both hands.
    let v = json(&armlab(&[
        "fk", "humanoid", "--config", "ready", "--format", "json",
    ]));
    assert_eq!(v[0]["end_effectors"].as_array().unwrap().len(), 2);
    // Degrees only in flags named *_deg.
    let a = json(&armlab(&[
        "fk", "planar2", "--q-deg", "90,0", "--format", "json",
    ]));
    let b = json(&armlab(&[
        "fk",
        "planar2",
        "--q",
        &format!("{},0", std::f64::consts::FRAC_PI_2),
        "--format",
        "json",
    ]));
    assert_eq!(a[0]["T"], b[0]["T"]);
}

#[test]
fn bad_input_exits_2_with_one_clear_line() {
    bad(
        &armlab(&["fk", "nosuch", "--q", "1"]),
        "unknown robot model \"nosuch\"",
    );
    bad(
        &armlab(&["fk", "puma560", "--q", "1,2,3"]),
        "expected 6 joint values, got 3",
    );
    bad(
        &armlab(&["fk", "planar2", "--q", "1,NaN"]),
        "value 2 (\"NaN\") is not a finite number",
    );
    bad(&armlab(&["fk", "planar2", "--q", "1,abc"]), "value 2");
    bad(
        &armlab(&["fk", "planar2", "--input", "/nonexistent/q.txt"]),
        "/nonexistent/q.txt",
    );
    bad(
        &armlab(&["fk", "planar2", "--config", "nosuch"]),
        "has no configuration \"nosuch\"",
    );
    bad(&armlab(&["fk", "planar2"]), "give the joint values");
    bad(
        &armlab(&["fk", "/nonexistent/robot.toml", "--q", "1"]),
        "/nonexistent/robot.toml",
    );
    // A bad row anywhere in a file: no pose is printed for the good rows before it.
    bad(
        &armlab_stdin(&["fk", "planar2", "--input", "-"], "0,0\n0,0\n1,2,3\n"),
        "-:3: expected 2 joint values, got 3",
    );
    bad(
        &armlab_stdin(&["fk", "planar2", "--input", "-"], "# nothing\n"),
        "no data rows",
    );
    // A malformed model file names file, line, column and field.
    let dir = std::env::temp_dir().join(format!("armlab-cli-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("arm.toml");
    std::fs::write(&f, "name = \"x\"\nconvention = \"standard\"\n[[joints]]\ntype = \"revolute\"\na = 1.0\nalpha = true\nd = 0.0\n").unwrap();
    let o = armlab(&["fk", f.to_str().unwrap(), "--q", "0"]);
    bad(&o, "arm.toml:6");
    assert!(String::from_utf8_lossy(&o.stderr).contains("alpha"));
}

#[test]
fn info_runs_on_the_default_robot() {
    let o = armlab(&["info"]);
    assert!(o.status.success());
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(text.contains("Anthropomorphic arm with spherical wrist"));
    assert!(text.contains("Jacobian rank 6"));
    let v = json(&armlab(&[
        "info",
        "puma560",
        "--q",
        "0,0,0,0,0,0",
        "--format",
        "json",
    ]));
    // q5 = 0: wrist singularity, rank 5.
    assert_eq!(v["end_effectors"][0]["jacobian_rank"], 5);
}

fn puma_pose_arg(q: &str) -> String {
    let v = json(&armlab(&["fk", "puma560", "--q", q, "--format", "json"]));
    v[0]["T"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|r| r.as_array().unwrap().iter().map(|x| x.to_string()))
        .collect::<Vec<_>>()
        .join(",")
}

#[test]
fn ik_all_postures_of_a_puma_pose() {
    let pose = puma_pose_arg("0.3,0.5,-1.2,0.4,0.8,-0.6");
    let v = json(&armlab(&[
        "ik", "puma560", "--pose", &pose, "--all", "--format", "json",
    ]));
    let t = &v[0];
    assert_eq!(t["status"], "ok");
    assert!(t["solver"].as_str().unwrap().starts_with("closed form"));
    let sols = t["solutions"].as_array().unwrap();
    assert_eq!(sols.len(), 8);
    let robot = armlab::kinematics::models::built_in("puma560").unwrap();
    for s in sols {
        let q: Vec<f64> = s["q"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert!(s["position_error"].as_f64().unwrap() < 1e-12);
        assert_eq!(s["within_limits"], robot.within_limits(&q, 1e-9));
        assert!(!s["posture"].as_str().unwrap().is_empty());
    }
    // Default: the solution closest to --seed-q.
    let v = json(&armlab(&[
        "ik",
        "puma560",
        "--pose",
        &pose,
        "--seed-q",
        "0.3,0.5,-1.2,0.4,0.8,-0.6",
        "--format",
        "json",
    ]));
    let q = &v[0]["solutions"][0]["q"];
    assert!((q[3].as_f64().unwrap() - 0.4).abs() < 1e-9);
    // --posture picks one by name, in any case and punctuation.
    let name = sols[3]["posture"]
        .as_str()
        .unwrap()
        .to_uppercase()
        .replace(", ", "_");
    let v = json(&armlab(&[
        "ik",
        "puma560",
        "--pose",
        &pose,
        "--posture",
        &name,
        "--format",
        "json",
    ]));
    assert_eq!(v[0]["solutions"][0]["posture"], sols[3]["posture"]);
}

/// Issue 45: `ik --format json` gives each solution's posture as its label (`"posture"`, the
/// same text as before and as the text output) and as fields (`"posture_parts"`); the label is
/// rebuilt here from the fields.
#[test]
fn ik_json_carries_the_posture_label_and_its_fields() {
    let pose = puma_pose_arg("0.3,0.5,-1.2,0.4,0.8,-0.6");
    let v = json(&armlab(&[
        "ik", "puma560", "--pose", &pose, "--all", "--format", "json",
    ]));
    let sols = v[0]["solutions"].as_array().unwrap();
    assert_eq!(sols.len(), 8);
    let mut seen = Vec::new();
    for s in sols {
        let label = s["posture"].as_str().unwrap();
        let parts = &s["posture_parts"];
        assert_eq!(parts["solver"], "closed_form", "{parts}");
        let word = |k: &str| parts[k].as_str().unwrap().replace('_', " ");
        let rebuilt = format!(
            "shoulder {}, elbow {}, wrist {}",
            word("shoulder"),
            word("elbow"),
            word("wrist")
        );
        assert_eq!(label, rebuilt);
        assert!(parts["extension"].is_null() && parts["branch"].is_null());
        assert_eq!(parts["reversed"], false);
        let free = parts["free"].as_array().unwrap();
        assert!(free.len() == 6 && free.iter().all(serde_json::Value::is_null));
        seen.push(label.to_string());
    }
    seen.sort();
    seen.dedup();
    assert_eq!(seen.len(), 8, "{seen:?}");
    // The text output prints the same labels, one per solution.
    let text = armlab(&["ik", "puma560", "--pose", &pose, "--all"]);
    assert!(text.status.success());
    let text = String::from_utf8(text.stdout).unwrap();
    for label in &seen {
        assert!(
            text.contains(&format!("  {label}: within limits"))
                || text.contains(&format!("  {label}: OUTSIDE the joint limits")),
            "{label} not in\n{text}"
        );
    }
    // Pieper's general case numbers its branches: "wrist flip, branch 3".
    let model = "assets/robots/skewed_arm_wrist.toml";
    let t = json(&armlab(&[
        "fk",
        model,
        "--q",
        "0.3,-0.4,0.9,0.3,0.8,-0.4",
        "--format",
        "json",
    ]));
    let pose: Vec<String> = t[0]["T"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|r| r.as_array().unwrap().iter().map(|x| x.to_string()))
        .collect();
    let v = json(&armlab(&[
        "ik",
        model,
        "--pose",
        &pose.join(","),
        "--all",
        "--format",
        "json",
    ]));
    let sols = v[0]["solutions"].as_array().unwrap();
    assert!(sols.len() >= 2, "{v}");
    for s in sols {
        let parts = &s["posture_parts"];
        let rebuilt = format!(
            "wrist {}, branch {}",
            parts["wrist"].as_str().unwrap().replace('_', " "),
            parts["branch"].as_u64().unwrap()
        );
        assert_eq!(s["posture"], rebuilt.as_str());
    }
    // The numerical solver's answer.
    let v = json(&armlab(&[
        "ik",
        "panda",
        "--position",
        "0.4,0.2,0.5",
        "--format",
        "json",
    ]));
    let s = &v[0]["solutions"][0];
    assert_eq!(s["posture"], "numerical");
    assert_eq!(
        s["posture_parts"],
        serde_json::json!({"solver": "numerical", "converged": true})
    );
}

#[test]
fn ik_batch_targets_planar_and_unreachable() {
    let input = "# px, py, phi\n0.7, 0.2, 0.3\n\n5, 0, 0   # too far\n";
    let v = json(&armlab_stdin(
        &[
            "ik", "planar3", "--input", "-", "--target", "planar", "--all", "--format", "json",
        ],
        input,
    ));
    let arr = v.as_array().unwrap();
    assert_eq!(arr.len(), 2);
    assert_eq!(arr[0]["status"], "ok");
    assert_eq!(arr[0]["solutions"].as_array().unwrap().len(), 2);
    assert_eq!(arr[1]["status"], "unreachable");
    assert!((arr[1]["distance"].as_f64().unwrap() - 4.0).abs() < 0.5);
    // A redundant arm with no closed form goes numerical.
    let v = json(&armlab(&[
        "ik",
        "panda",
        "--position",
        "0.4,0.2,0.5",
        "--format",
        "json",
    ]));
    assert_eq!(v[0]["status"], "ok");
    assert!(v[0]["solver"].as_str().unwrap().starts_with("numerical"));
    // The humanoid's left hand.
    let v = json(&armlab(&[
        "ik",
        "humanoid",
        "--ee",
        "left hand",
        "--position",
        "0.3,0.3,0.5",
        "--format",
        "json",
    ]));
    assert!(v[0]["solutions"].as_array().unwrap().len() == 1);
}

#[test]
fn ik_bad_input_exits_2() {
    bad(
        &armlab(&["ik", "puma560", "--pose", "1,0,0"]),
        "expected 16 numbers",
    );
    bad(
        &armlab(&["ik", "puma560", "--pose", "1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,2"]),
        "bottom row",
    );
    bad(
        &armlab(&["ik", "puma560", "--pose", "2,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1"]),
        "orthonormal",
    );
    bad(
        &armlab(&["ik", "puma560", "--position", "nan,0,0"]),
        "not a finite number",
    );
    bad(
        &armlab_stdin(
            &["ik", "planar2", "--input", "-", "--target", "position"],
            "1,0,0\n1,0\n",
        ),
        "-:2: expected 3 numbers",
    );
    bad(
        &armlab(&["ik", "planar2", "--position", "1,0,0.5"]),
        "--position",
    );
    bad(
        &armlab(&["ik", "humanoid", "--ee", "tail", "--position", "0,0,1"]),
        "no end-effector \"tail\"",
    );
    bad(
        &armlab(&[
            "ik",
            "dlr",
            "--solver",
            "closed-form",
            "--position",
            "0.3,0,0.5",
        ]),
        "no closed-form",
    );
    bad(
        &armlab(&[
            "ik",
            "puma560",
            "--position",
            "0.3,0,0.5",
            "--seed-q",
            "1,2",
        ]),
        "--seed-q: expected 6 joint values",
    );
}

/// Each parameter's `identifiable` agrees with `unidentifiable` (the analysis at the estimate):
/// estimated and not listed, or fixed / listed.
fn flags_agree_with_the_list(v: &serde_json::Value) {
    let listed: Vec<&str> = v["unidentifiable"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_str().unwrap())
        .collect();
    for p in v["parameters"].as_array().unwrap() {
        let name = p["name"].as_str().unwrap();
        let estimated = p["fixed"] == false;
        assert_eq!(
            p["identifiable"].as_bool().unwrap(),
            estimated && !listed.contains(&name),
            "{name}"
        );
    }
}

#[test]
fn calibrate_simulated_json_has_the_documented_keys() {
    let o = armlab(&[
        "calibrate",
        "puma560",
        "--simulate",
        "--poses",
        "30",
        "--seed",
        "5",
        "--noise-mm",
        "0.02",
        "--format",
        "json",
    ]);
    let v = json(&o);
    for key in [
        "parameters",
        "parameter_count",
        "rank",
        "rank_threshold",
        "unidentifiable",
        "correlations",
        "iterations",
        "converged",
        "observability",
        "fit",
        "validation",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    // The default: Hayati's beta2 instead of d2 on the parallel axes 2-3, every parameter
    // identifiable, the flags and the list reported at the estimate.
    assert_eq!(v["hayati_rows"], serde_json::json!([2]));
    assert_eq!(v["identifiability_at"], "estimate");
    assert_eq!(v["parameter_count"], 24);
    assert_eq!(v["rank"], 24);
    assert_eq!(v["unidentifiable"], serde_json::json!([]));
    assert_eq!(v["setup"], "pose");
    flags_agree_with_the_list(&v);
    // Plain DH (the lesson): at the nominal point only d2 + d3 is seen; d2 is kept nominal, and
    // the flags say so.
    let o = armlab(&[
        "calibrate",
        "puma560",
        "--simulate",
        "--poses",
        "30",
        "--seed",
        "5",
        "--noise-mm",
        "0.02",
        "--hayati",
        "off",
        "--format",
        "json",
    ]);
    let plain = json(&o);
    assert_eq!(
        plain["nominal_identifiability"]["rank"], 23,
        "axes 2 and 3 of the Puma are parallel"
    );
    assert_eq!(
        plain["nominal_identifiability"]["unidentifiable"],
        serde_json::json!(["d2", "d3"])
    );
    assert_eq!(plain["fixed_unidentifiable"][0]["name"], "d2");
    assert_eq!(plain["parameters"][13]["name"], "d2");
    assert_eq!(plain["parameters"][13]["identifiable"], false);
    assert_eq!(plain["parameters"][13]["estimate"], 0.0);
    assert!(
        plain["parameters"][13]["fixed_because"]
            .as_str()
            .unwrap()
            .contains("d2 + d3")
    );
    flags_agree_with_the_list(&plain);
    let p = &v["parameters"][0];
    for key in [
        "name",
        "joint",
        "kind",
        "nominal",
        "estimate",
        "std",
        "identifiable",
        "true",
    ] {
        assert!(p.get(key).is_some(), "parameter lacks {key}");
    }
    assert_eq!(p["name"], "a1");
    assert_eq!(p["kind"], "a");
    for key in ["O1", "O2", "O3", "O4"] {
        assert!(v["observability"][key].is_number());
    }
    for s in [
        &v["fit"]["before"],
        &v["fit"]["after"],
        &v["validation"]["after"],
    ] {
        for key in [
            "position_rms",
            "position_max",
            "orientation_rms",
            "orientation_max",
        ] {
            assert!(s[key].is_number(), "{key} in {s}");
        }
    }
    let it = &v["iterations"][0];
    for key in [
        "position_rms",
        "orientation_rms",
        "step_norm",
        "condition",
        "rank",
    ] {
        assert!(it.get(key).is_some());
    }
    assert_eq!(v["converged"], true);
    let after = v["validation"]["after"]["position_rms"].as_f64().unwrap();
    let before = v["validation"]["before"]["position_rms"].as_f64().unwrap();
    assert!(after < 0.1 * before, "{after} vs {before}");
}

#[test]
fn calibrate_from_a_measurement_file_and_write_the_model() {
    let dir = std::env::temp_dir().join(format!("armlab-cal-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let meas = dir.join("m.csv");
    let model = dir.join("calibrated.toml");
    let o = armlab(&[
        "calibrate",
        "puma560",
        "--simulate",
        "--poses",
        "30",
        "--noise-mm",
        "0",
        "--noise-mrad",
        "0",
        "--write-measurements",
        meas.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = armlab(&[
        "calibrate",
        "puma560",
        "--measurements",
        meas.to_str().unwrap(),
        "--write-model",
        model.to_str().unwrap(),
        "--format",
        "json",
    ]);
    let v = json(&o);
    assert!(
        v["fit"]["after"]["position_max"].as_f64().unwrap() < 1e-9,
        "{}",
        v["fit"]
    );
    // The written model reproduces the measured poses through the ordinary FK path.
    let text = std::fs::read_to_string(&meas).unwrap();
    let first = text.lines().find(|l| !l.starts_with('#')).unwrap();
    let nums: Vec<f64> = first
        .split(',')
        .map(|f| f.trim().parse().unwrap())
        .collect();
    let q: Vec<String> = nums[..6].iter().map(|x| format!("{x:?}")).collect();
    let fk = json(&armlab(&[
        "fk",
        model.to_str().unwrap(),
        "--q",
        &q.join(","),
        "--format",
        "json",
    ]));
    let t = &fk[0]["T"];
    for r in 0..4 {
        for c in 0..4 {
            let got = t[r][c].as_f64().unwrap();
            assert!((got - nums[6 + 4 * r + c]).abs() < 1e-9, "T[{r}][{c}]");
        }
    }
    // Bad files: a line with the wrong count, a non-number, mixed kinds; each names file:line.
    let bad_file = dir.join("bad.csv");
    std::fs::write(&bad_file, "# header\n0,0,0,0,0,0,1,2\n").unwrap();
    let o = armlab(&[
        "calibrate",
        "puma560",
        "--measurements",
        bad_file.to_str().unwrap(),
    ]);
    bad(&o, "line 2: 8 values");
    std::fs::write(&bad_file, "0,0,0,0,0,0,1,nan,3\n").unwrap();
    bad(
        &armlab(&[
            "calibrate",
            "puma560",
            "--measurements",
            bad_file.to_str().unwrap(),
        ]),
        "line 1: value 8",
    );
    std::fs::write(&bad_file, format!("0,0,0,0,0,0,1,2,3\n{first}\n")).unwrap();
    bad(
        &armlab(&[
            "calibrate",
            "puma560",
            "--measurements",
            bad_file.to_str().unwrap(),
        ]),
        "all lines of a file must be of one kind",
    );
    std::fs::write(&bad_file, "0,0,0,0,0,0,1,2,3\n").unwrap();
    bad(
        &armlab(&[
            "calibrate",
            "puma560",
            "--measurements",
            bad_file.to_str().unwrap(),
        ]),
        "equations from 1 poses",
    );
    bad(
        &armlab(&[
            "calibrate",
            "puma560",
            "--measurements",
            "/no/such/file.csv",
        ]),
        "cannot read",
    );
    bad(
        &armlab(&["calibrate", "puma560", "--simulate", "--fix", "q7"]),
        "no parameter named",
    );
    // Base and tool parameters: 36 in all, the lumped ones named.
    let v = json(&armlab(&[
        "calibrate",
        "puma560",
        "--simulate",
        "--with-base",
        "--with-tool",
        "--format",
        "json",
    ]));
    assert_eq!(v["nominal_identifiability"]["parameter_count"], 36);
    let names: Vec<&str> = v["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert!(names.contains(&"base_rz") && names.contains(&"tool_x"));
    assert!(v["nominal_identifiability"]["rank"].as_u64().unwrap() < 36);
    // The lumped ones keep one side nominal (d1 + base_z: d1), the rest is estimated.
    let fixed: Vec<&str> = v["fixed_unidentifiable"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["name"].as_str().unwrap())
        .collect();
    assert!(
        fixed.contains(&"d1") && fixed.contains(&"theta6"),
        "{fixed:?}"
    );
    assert_eq!(v["rank"], v["parameter_count"]);
    flags_agree_with_the_list(&v);
    // Hayati's beta for the parallel axes 2 and 3: every parameter identifiable.
    let v = json(&armlab(&[
        "calibrate",
        "puma560",
        "--simulate",
        "--hayati",
        "auto",
        "--format",
        "json",
    ]));
    assert_eq!(v["hayati_rows"], serde_json::json!([2]));
    assert_eq!(v["rank"], v["parameter_count"]);
    let beta = v["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == "beta2")
        .unwrap();
    assert_eq!(beta["kind"], "beta");
    // The accuracy maps: calibrated and nominal against the real arm, as PNG figures.
    let map = dir.join("acc.png");
    let o = armlab(&[
        "calibrate",
        "puma560",
        "--simulate",
        "--accuracy-map",
        map.to_str().unwrap(),
        "--map-cells",
        "64x64",
        "--map-samples",
        "20000",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for f in [map.clone(), dir.join("acc-before.png")] {
        let img = image::open(&f).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
        assert_eq!((img.width(), img.height()), (1200, 1000));
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The library's experiment (the workflow the app and Python call) is the report the command
/// line prints: the same JSON byte for byte, and the same text, for a simulated run described
/// to the library directly; and for a tracker setup with desired poses to correct.
#[test]
fn calibrate_prints_the_library_experiments_report() {
    use armlab::calibration::{
        CalibrationOptions, Experiment, NamedText, Setup, Simulation, Source, run,
    };
    let puma = armlab::kinematics::models::built_in("puma560").unwrap();
    let simulated = Experiment {
        source: Source::Simulated(Simulation {
            poses: 30,
            validation_poses: 30,
            seed: 5,
            noise_mm: 0.02,
            ..Simulation::default()
        }),
        options: CalibrationOptions::default().with_noise(0.02, 0.1),
        ..Experiment::new(puma.clone())
    };
    let args = [
        "calibrate",
        "puma560",
        "--simulate",
        "--poses",
        "30",
        "--seed",
        "5",
        "--noise-mm",
        "0.02",
    ];
    let dir = std::env::temp_dir().join(format!("armlab-cal-lib-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let targets = dir.join("targets.csv");
    let text =
        "x [mm], y [mm], z [mm], roll [deg], pitch [deg], yaw [deg]\n450, 150, 400, 180, 0, 0\n";
    std::fs::write(&targets, text).unwrap();
    let tracker = Experiment {
        setup: Setup::Tracker,
        targets: Some(NamedText {
            name: targets.display().to_string(),
            text: text.into(),
        }),
        ..Experiment::new(puma)
    };
    let tracker_args = [
        "calibrate",
        "puma560",
        "--simulate",
        "--setup",
        "tracker",
        "--correct-targets",
        targets.to_str().unwrap(),
    ];
    for (e, args) in [(simulated, &args[..]), (tracker, &tracker_args[..])] {
        let report = run(&e).unwrap();
        let o = armlab(&[args, &["--format", "json"]].concat());
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let printed = String::from_utf8(o.stdout).unwrap();
        assert_eq!(
            printed,
            format!("{}\n", serde_json::to_string_pretty(&report).unwrap())
        );
        let o = armlab(args);
        assert_eq!(String::from_utf8(o.stdout).unwrap(), report.to_string());
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn calibrate_pose_selection_beats_random_poses() {
    let o1 = |select: &str| {
        let v = json(&armlab(&[
            "calibrate",
            "planar3",
            "--simulate",
            "--poses",
            "8",
            "--select",
            select,
            "--format",
            "json",
        ]));
        v["observability"]["O1"].as_f64().unwrap()
    };
    let (random, chosen) = (o1("random"), o1("o1"));
    assert!(chosen > random, "O1 chosen {chosen} vs random {random}");
}

#[test]
fn reach_answers_each_point_with_postures_and_distance() {
    let input = "# Problem 2.17\n0.9,0\n\n2.0, 0.0  # far\n0.5,0.2\n";
    let v = json(&armlab_stdin(
        &["reach", "planar3", "--input", "-", "--format", "json"],
        input,
    ));
    let a = v.as_array().unwrap();
    assert_eq!(a.len(), 3);
    for p in a {
        for key in ["point", "reachable", "postures", "distance"] {
            assert!(p.get(key).is_some(), "missing {key}: {p}");
        }
    }
    assert_eq!(a[0]["point"], serde_json::json!([0.9, 0.0]));
    assert_eq!(a[0]["reachable"], true);
    assert_eq!(
        a[0]["postures"],
        serde_json::json!(["elbow down", "elbow up"])
    );
    assert!((a[0]["distance"].as_f64().unwrap() - 0.1).abs() < 1e-12);
    assert_eq!(a[1]["reachable"], false);
    assert!((a[1]["distance"].as_f64().unwrap() + 1.0).abs() < 1e-12);
    // Three coordinates for a spatial arm.
    let v = json(&armlab_stdin(
        &["reach", "puma560", "--input", "-", "--format", "json"],
        "0.5,0.1,0.8\n",
    ));
    assert_eq!(v[0]["point"].as_array().unwrap().len(), 3);
    // Bad input: one line naming the file and line.
    let dir = std::env::temp_dir().join(format!("armlab-reach-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("pts.txt");
    std::fs::write(&f, "0.5,0.2\n# ok\n0.5,0.2,0.1\n").unwrap();
    bad(
        &armlab(&["reach", "planar3", "--input", f.to_str().unwrap()]),
        "pts.txt:3: expected 2 coordinates (x,y), got 3",
    );
    std::fs::write(&f, "0.5,abc\n").unwrap();
    bad(
        &armlab(&["reach", "planar3", "--input", f.to_str().unwrap()]),
        "pts.txt:1: value 2",
    );
    bad(
        &armlab(&["reach", "dlr", "--input", f.to_str().unwrap()]),
        "point queries need",
    );
}

#[test]
fn workspace_json_says_how_the_measure_was_computed() {
    let dir = std::env::temp_dir().join(format!("armlab-wsj-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("p.png");
    let v = json(&armlab(&[
        "workspace",
        "planar3",
        "--out",
        out.to_str().unwrap(),
        "--size",
        "400x300",
        "--format",
        "json",
    ]));
    assert!(v["measure_method"].as_str().unwrap().starts_with("exact"));
    assert!(v["measure_error"].as_f64().unwrap() < 1e-6);
    let area = v["area"].as_f64().unwrap();
    assert!((area - 1.672_313_7).abs() < 1e-6, "{area}");
}

#[test]
fn self_motion_json_has_the_documented_shape() {
    let pose = "1,0,0,0.6, 0,1,0,0.1, 0,0,1,0, 0,0,0,1";
    let v = json(&armlab(&[
        "self-motion",
        "planar3",
        "--pose",
        pose,
        "--samples",
        "8",
        "--format",
        "json",
    ]));
    assert_eq!(v["parameter"], "phi");
    let samples = v["samples"].as_array().unwrap();
    assert_eq!(samples.len(), 8);
    assert!((samples[0]["value"].as_f64().unwrap() + std::f64::consts::PI).abs() < 1e-15);
    for s in samples {
        for b in s["branches"].as_array().unwrap() {
            for key in [
                "name",
                "q",
                "within_limits",
                "position_error",
                "orientation_error",
            ] {
                assert!(b.get(key).is_some(), "missing {key}");
            }
            assert!(b["position_error"].as_f64().unwrap() < 1e-12);
        }
    }
    for (name, ivs) in v["feasible"].as_object().unwrap() {
        for iv in ivs.as_array().unwrap() {
            let (lo, hi) = (iv[0].as_f64().unwrap(), iv[1].as_f64().unwrap());
            assert!(
                -std::f64::consts::PI <= lo && lo <= hi && hi <= std::f64::consts::PI,
                "{name}"
            );
        }
    }
    assert!(v["manifolds"].as_u64().unwrap() >= 1);
    assert_eq!(v["singular"], false);
    // One branch only.
    let v = json(&armlab(&[
        "self-motion",
        "planar3",
        "--pose",
        pose,
        "--samples",
        "4",
        "--branch",
        "elbow up",
        "--format",
        "json",
    ]));
    assert_eq!(v["feasible"].as_object().unwrap().len(), 1);
    bad(
        &armlab(&["self-motion", "planar3", "--pose", pose, "--branch", "nope"]),
        "no branch \"nope\"",
    );
    bad(
        &armlab(&["self-motion", "planar2", "--pose", pose]),
        "leaves no self-motion",
    );
    bad(
        &armlab(&["self-motion", "puma560", "--pose", pose]),
        "no self-motion",
    );
    bad(
        &armlab(&["self-motion", "planar3", "--pose", "1,2,3"]),
        "expected 16 numbers",
    );
    bad(
        &armlab(&[
            "ik",
            "puma560",
            "--pose",
            pose,
            "--task",
            "position+axis",
            "--solver",
            "closed-form",
        ]),
        "needs the numerical solver",
    );
}

/// The pose of a model's "ready" configuration as the 16 numbers of `--pose`.
fn ready_pose(model: &str) -> Vec<String> {
    let fk = json(&armlab(&[
        "fk", model, "--config", "ready", "--format", "json",
    ]));
    fk[0]["T"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|r| r.as_array().unwrap().iter().map(|x| x.to_string()))
        .collect()
}

#[test]
fn self_motion_of_an_srs_arm_by_the_arm_angle() {
    let pose = ready_pose("dlr");
    let v = json(&armlab(&[
        "self-motion",
        "dlr",
        "--pose",
        &pose.join(","),
        "--samples",
        "36",
        "--format",
        "json",
    ]));
    assert_eq!(v["parameter"], "arm angle");
    assert_eq!(v["singular"], false);
    assert_eq!(v["feasible"].as_object().unwrap().len(), 8);
    for s in v["samples"].as_array().unwrap() {
        assert_eq!(s["branches"].as_array().unwrap().len(), 8);
        for b in s["branches"].as_array().unwrap() {
            assert!(b["position_error"].as_f64().unwrap() < 1e-12, "{b}");
            assert!(b["orientation_error"].as_f64().unwrap() < 1e-11, "{b}");
        }
    }
    // The ready configuration is inside the limits, so some branch is at some arm angle.
    assert!(v["samples"].as_array().unwrap().iter().any(|s| {
        s["branches"]
            .as_array()
            .unwrap()
            .iter()
            .any(|b| b["within_limits"] == true)
    }));
    assert!(v["manifolds"].as_u64().unwrap() >= 1);
}

#[test]
fn numerical_self_motion_of_the_humanoid_arm() {
    let pose = ready_pose("humanoid");
    let v = json(&armlab(&[
        "self-motion",
        "humanoid",
        "--pose",
        &pose.join(","),
        "--samples",
        "24",
        "--format",
        "json",
    ]));
    assert_eq!(v["parameter"], "arc length");
    let samples = v["samples"].as_array().unwrap();
    assert_eq!(samples.len(), 24);
    for s in samples {
        for b in s["branches"].as_array().unwrap() {
            assert!(b["position_error"].as_f64().unwrap() < 1e-12, "{b}");
            assert!(b["orientation_error"].as_f64().unwrap() < 1e-12, "{b}");
        }
    }
}

#[test]
fn self_motion_of_the_panda_by_q7_and_of_the_four_link_arm_by_phi3() {
    // The pose as 16 numbers separated by spaces (the issue's "16 numbers").
    let pose = ready_pose("panda").join(" ");
    let v = json(&armlab(&[
        "self-motion",
        "panda",
        "--pose",
        &pose,
        "--samples",
        "36",
        "--format",
        "json",
    ]));
    assert_eq!(v["parameter"], "q7");
    assert_eq!(v["feasible"].as_object().unwrap().len(), 8);
    let samples = v["samples"].as_array().unwrap();
    for s in samples {
        let q7 = s["value"].as_f64().unwrap();
        for b in s["branches"].as_array().unwrap() {
            assert!(b["position_error"].as_f64().unwrap() < 1e-12, "{b}");
            assert!(b["orientation_error"].as_f64().unwrap() < 1e-12, "{b}");
            assert!((b["q"][6].as_f64().unwrap() - q7).abs() < 1e-15);
        }
    }
    // The ready configuration's q7 = pi/4 is inside a feasible interval of some branch.
    let q7 = std::f64::consts::FRAC_PI_4;
    assert!(v["feasible"].as_object().unwrap().values().any(|ivs| {
        ivs.as_array()
            .unwrap()
            .iter()
            .any(|iv| iv[0].as_f64().unwrap() <= q7 && q7 <= iv[1].as_f64().unwrap())
    }));
    let pose = ready_pose("planar4");
    let v = json(&armlab(&[
        "self-motion",
        "planar4",
        "--pose",
        &pose.join(","),
        "--samples",
        "12",
        "--format",
        "json",
    ]));
    assert_eq!(v["parameter"], "phi");
    assert_eq!(v["feasible"].as_object().unwrap().len(), 2);
    for s in v["samples"].as_array().unwrap() {
        for b in s["branches"].as_array().unwrap() {
            assert_eq!(b["q"].as_array().unwrap().len(), 4);
            assert!(b["position_error"].as_f64().unwrap() < 1e-12, "{b}");
        }
    }
}

#[test]
fn the_figure_command_lists_and_refuses() {
    let list = armlab(&["figure", "--list"]);
    assert!(list.status.success());
    let text = String::from_utf8_lossy(&list.stdout);
    for name in ["2.29", "2.30", "2.31", "2.32", "2.33", "problem-2.17"] {
        assert!(
            text.lines().any(|l| l.starts_with(name)),
            "{name} missing: {text}"
        );
    }
    bad(
        &armlab(&["figure", "2.99", "--out", "/tmp/x.png"]),
        "no figure \"2.99\"",
    );
    bad(&armlab(&["figure", "2.31"]), "--out");
    bad(&armlab(&["figure"]), "--list");
}

/// `armlab export`: a URDF Puma written and read back gets its DH table derived from the axes
/// in `info` (no NaN anywhere) and its closed form in `ik` (8 solutions); a model URDF cannot
/// hold is refused with one line and writes nothing.
#[test]
fn export_urdf_and_use_it() {
    let dir = std::env::temp_dir().join(format!("armlab-export-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let urdf = dir.join("puma.urdf");
    let toml = dir.join("puma.toml");
    let o = armlab(&[
        "export",
        "puma560",
        "--urdf",
        urdf.to_str().unwrap(),
        "--toml",
        toml.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains("wrote"));
    let o = armlab(&["info", urdf.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(!text.contains("NaN"), "{text}");
    assert!(
        text.contains("DH table derived from the joint axes"),
        "{text}"
    );
    assert!(
        text.contains("inverse kinematics: closed form (anthropomorphic arm with spherical wrist"),
        "{text}"
    );
    let pose = puma_pose_arg("0.3,0.5,-1.2,0.4,0.8,-0.6");
    let v = json(&armlab(&[
        "ik",
        urdf.to_str().unwrap(),
        "--pose",
        &pose,
        "--format",
        "json",
    ]));
    assert_eq!(v[0]["solution_count"], 8, "{v}");
    assert!(
        v[0]["solver"].as_str().unwrap().starts_with("closed form"),
        "{v}"
    );
    let o = armlab(&["info", toml.to_str().unwrap()]);
    assert!(o.status.success());
    let bad_path = dir.join("humanoid.urdf");
    bad(
        &armlab(&["export", "humanoid", "--urdf", bad_path.to_str().unwrap()]),
        "URDF's <mimic> follows exactly one joint",
    );
    assert!(!bad_path.exists());
    bad(&armlab(&["export", "puma560"]), "--urdf");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `armlab info` never prints NaN, for every built-in, every shipped model file, and every
/// built-in written as URDF (whose DH table is derived or whose absence is explained).
#[test]
fn info_has_no_nan_for_any_shipped_model() {
    let dir = std::env::temp_dir().join(format!("armlab-info-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let listed = json(&armlab(&["robots", "--format", "json"]));
    let mut models: Vec<String> = listed
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["name"].as_str().unwrap().to_string())
        .collect();
    for e in std::fs::read_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/robots")).unwrap() {
        models.push(e.unwrap().path().to_str().unwrap().to_string());
    }
    for name in models.clone() {
        if !name.contains('/') {
            let path = dir.join(format!("{name}.urdf"));
            let o = armlab(&["export", &name, "--urdf", path.to_str().unwrap()]);
            if o.status.success() {
                models.push(path.to_str().unwrap().to_string());
            }
        }
    }
    assert!(models.len() > 40, "{}", models.len());
    for m in &models {
        let o = armlab(&["info", m]);
        let text = String::from_utf8_lossy(&o.stdout);
        assert!(
            o.status.success(),
            "{m}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let words = text.split(|c: char| !c.is_ascii_alphanumeric());
        assert!(
            !words.map(str::to_lowercase).any(|w| w == "nan"),
            "{m}:\n{text}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A successful headless run prints nothing on stderr, even with no `XDG_RUNTIME_DIR` (Mesa's
/// Vulkan layer made libwayland print "error: XDG_RUNTIME_DIR is invalid or not set in the
/// environment." although nothing failed; issue 16).
#[test]
fn headless_commands_are_quiet_without_a_runtime_dir() {
    let dir = std::env::temp_dir().join(format!("armlab-quiet-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = |name: &str| dir.join(name).to_string_lossy().into_owned();
    let runs: [Vec<String>; 4] = [
        vec![
            "render".into(),
            "puma560".into(),
            "--out".into(),
            out("r.png"),
        ],
        vec![
            "workspace".into(),
            "planar2".into(),
            "--samples".into(),
            "2000".into(),
            "--out".into(),
            out("w.png"),
        ],
        vec!["figure".into(), "2.31".into(), "--out".into(), out("f.png")],
        vec![
            "view".into(),
            "puma560".into(),
            "--screenshot".into(),
            out("v.png"),
        ],
    ];
    for args in runs {
        let o = Command::new(env!("CARGO_BIN_EXE_armlab"))
            .args(&args)
            .env_remove("XDG_RUNTIME_DIR")
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{args:?}: {err}");
        assert!(err.trim().is_empty(), "{args:?} wrote to stderr: {err:?}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Valid but extreme inputs get one clear line, fast, without gigabytes (issue 16): a model
/// with 10,000 joints, limits of 1e300, a 1 GB file and a 2 MiB line, `--samples 1e12`,
/// `--size 100000x100000`.
#[test]
fn extreme_inputs_get_clear_errors() {
    let dir = std::env::temp_dir().join(format!("armlab-extreme-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = |n: &str| dir.join(n).to_string_lossy().into_owned();
    let joint = "[[joints]]\ntype = \"revolute\"\na = 0.1\nalpha = 0.0\nd = 0.0\n";
    let header = "name = \"x\"\nconvention = \"standard\"\n";
    std::fs::write(
        path("big.toml"),
        format!("{header}{}", joint.repeat(10_000)),
    )
    .unwrap();
    bad(&armlab(&["info", &path("big.toml")]), "at most 256");
    let huge_limits = format!("{header}{joint}limits = [-1e300, 1e300]\n");
    std::fs::write(path("limits.toml"), huge_limits).unwrap();
    bad(&armlab(&["info", &path("limits.toml")]), "out of range");
    // Sparse 1 GiB files: refused from their size before a byte is read.
    for name in ["huge.toml", "huge.txt"] {
        let f = std::fs::File::create(path(name)).unwrap();
        f.set_len(1 << 30).unwrap();
    }
    bad(
        &armlab(&["info", &path("huge.toml")]),
        "larger than the 16.0 MiB",
    );
    bad(
        &armlab(&["fk", "planar2", "--input", &path("huge.txt")]),
        "larger than the 256.0 MiB",
    );
    let long_line = "0.1,".repeat(600_000);
    bad(
        &armlab_stdin(&["fk", "planar2", "--input", "-"], &long_line),
        "-:1: line longer than 1048576 bytes",
    );
    bad(
        &armlab(&[
            "workspace",
            "planar2",
            "--samples",
            "1e12",
            "--out",
            &path("w.png"),
        ]),
        "--samples must be between 1 and 100000000",
    );
    let o = armlab(&[
        "render",
        "planar2",
        "--size",
        "100000x100000",
        "--out",
        &path("r.png"),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("from 16 to 8192"));
    bad(
        &armlab(&["calibrate", "puma560", "--simulate", "--poses", "1e9"]),
        "--poses must be between 1 and 100000",
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Output piped into a program that stops reading (`armlab fk ... | head`) ends quietly with
/// success, as other command-line tools do (it printed "armlab: error: ... Broken pipe").
#[test]
fn a_closed_output_pipe_is_not_an_error() {
    let mut child = Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args(["fk", "planar2", "--input", "-"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take()); // the reader is gone before anything is written
    let rows = "0.1, 0.2\n".repeat(50_000); // far more output than a pipe buffers
    child
        .stdin
        .take()
        .unwrap()
        .write_all(rows.as_bytes())
        .unwrap();
    let o = child.wait_with_output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        o.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// Issue 26's interface, run as the issue writes it: `armlab info FILE --format json` has
/// `end_effectors` with name, chain, dof, dh, dh_reason, closed_form, closed_form_reason,
/// redundancy_degree and self_motion, the first the default (the tool of the longest arm).
#[test]
fn info_json_describes_each_arm_of_a_tree() {
    let v = json(&armlab(&[
        "info",
        "tests/data/urdf_corpus/panda.urdf",
        "--format",
        "json",
    ]));
    let ees = v["end_effectors"].as_array().unwrap();
    for e in ees {
        for key in [
            "name",
            "chain",
            "dof",
            "dh",
            "dh_reason",
            "closed_form",
            "closed_form_reason",
            "redundancy_degree",
            "self_motion",
        ] {
            assert!(e.get(key).is_some(), "{key} missing in {e}");
        }
    }
    let tcp = &ees[0];
    assert_eq!(v["default_end_effector"], "panda_hand_tcp");
    assert_eq!(tcp["name"], "panda_hand_tcp");
    assert_eq!(tcp["dof"], 7);
    assert_eq!(tcp["chain"].as_array().unwrap().len(), 7);
    assert_eq!(tcp["dh"]["rows"].as_array().unwrap().len(), 7);
    assert!(tcp["dh_reason"].is_null());
    assert!(tcp["closed_form"].is_null());
    assert!(
        tcp["closed_form_reason"]
            .as_str()
            .unwrap()
            .contains("redundant")
    );
    assert_eq!(tcp["redundancy_degree"], 1);
    assert_eq!(tcp["self_motion"], "q7");
    // The Jaco 2: a near miss, in closed form.
    let v = json(&armlab(&[
        "info",
        "tests/data/urdf_corpus/kinova_j2s6s200.urdf",
        "--format",
        "json",
    ]));
    let e = &v["end_effectors"][0];
    assert_eq!(e["closed_form"], "anthropomorphic arm with spherical wrist");
    assert!(
        e["closed_form_near_miss"]
            .as_str()
            .unwrap()
            .contains("within")
    );
}

/// `--ee NAME` in every command; an unknown name lists the ones there are.
#[test]
fn ee_works_in_every_command() {
    let urdf = "tests/data/urdf_corpus/baxter.urdf";
    let v = json(&armlab(&[
        "info",
        urdf,
        "--ee",
        "left_gripper",
        "--format",
        "json",
    ]));
    assert_eq!(v["end_effectors"].as_array().unwrap().len(), 1);
    assert_eq!(v["end_effectors"][0]["chain"][0], "left_s0");
    let q = "0,0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0,0.1,0.2,0.3,0.4,0.5,0.6,0.7";
    let fk = json(&armlab(&[
        "fk",
        urdf,
        "--q",
        q,
        "--ee",
        "left_gripper",
        "--format",
        "json",
    ]));
    let t: Vec<f64> = fk[0]["T"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|r| r.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()))
        .collect();
    let pose: Vec<String> = t.iter().map(|x| format!("{x}")).collect();
    let ik = json(&armlab(&[
        "ik",
        urdf,
        "--pose",
        &pose.join(","),
        "--ee",
        "left_gripper",
        "--seed-q",
        q,
        "--format",
        "json",
    ]));
    let s = &ik[0]["solutions"][0];
    assert!(s["position_error"].as_f64().unwrap() < 1e-9, "{s}");
    assert_eq!(s["q"].as_array().unwrap().len(), 17, "the whole robot's q");
    let dir = std::env::temp_dir().join(format!("armlab_ee_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let toml = dir.join("left.toml");
    let o = armlab(&[
        "export",
        urdf,
        "--ee",
        "left_gripper",
        "--toml",
        toml.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let arm_fk = json(&armlab(&[
        "fk",
        toml.to_str().unwrap(),
        // Baxter's q: head_pan, the right arm (7), its finger, the left arm (7), its finger.
        "--q",
        "0,0.1,0.2,0.3,0.4,0.5,0.6",
        "--format",
        "json",
    ]));
    for k in 0..3 {
        let a = arm_fk[0]["p"][k].as_f64().unwrap();
        let b = fk[0]["p"][k].as_f64().unwrap();
        assert!(
            (a - b).abs() < 1e-9,
            "the exported arm's DH table: {a} vs {b}"
        );
    }
    let png = dir.join("left.png");
    let o = armlab(&[
        "workspace",
        urdf,
        "--ee",
        "left_gripper",
        "--samples",
        "2000",
        "--out",
        png.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = armlab(&["fk", urdf, "--q", q, "--ee", "no_such_frame"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("no end-effector \"no_such_frame\"") && err.contains("left_gripper"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A pose as `armlab info` prints it (six decimals) is a target `armlab ik` takes: it was refused
/// as not orthonormal (|R^T R - I| = 1.08e-6 > 1e-6). Here the gantry's pose at its ready
/// configuration, with its two wrist postures (the Cartesian family, issue 27).
#[test]
fn ik_takes_a_pose_printed_to_six_decimals() {
    let out = armlab(&[
        "ik",
        "assets/robots/gantry_wrist.toml",
        "--pose",
        "-0.660729,-0.279352,0.696707,0.469671,0.182387,-0.960101,-0.211993,0.478801,\
         0.728129,-0.012999,0.685316,0.768532,0,0,0,1",
        "--all",
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        text.contains(
            "closed form (Cartesian arm with spherical wrist (gantry type)); 2 solution(s)"
        ),
        "{text}"
    );
    assert!(
        text.contains("wrist no flip") && text.contains("wrist flip"),
        "{text}"
    );
    assert!(text.contains("q = [0.700000, 0.500000, 0.400000, 0.300000, 0.800000, -0.400000]"));
}

/// A spherical wrist at the base (issue 27): `armlab ik --all` lists the 8 postures of the chain
/// read from the tool, labelled where they sit ("tool shoulder", "base wrist"), in text and JSON.
#[test]
fn ik_lists_the_reversed_chain_postures_of_a_ball_shoulder() {
    let pose = "0.859962,-0.483871,-0.162276,0.547036,-0.510139,-0.824274,-0.245623,0.084962,\
                -0.014910,0.294010,-0.955686,0.754738,0,0,0,1";
    let model = "assets/robots/ball_shoulder_arm.toml";
    let out = armlab(&["ik", model, "--pose", pose, "--all"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        text.contains("spherical wrist at the base") && text.contains("8 solution(s)"),
        "{text}"
    );
    let v = json(&armlab(&[
        "ik", model, "--pose", pose, "--all", "--format", "json",
    ]));
    let sols = v[0]["solutions"].as_array().unwrap();
    assert_eq!(sols.len(), 8, "{v}");
    for s in sols {
        let p = s["posture"].as_str().unwrap();
        assert!(
            p.starts_with("tool shoulder") && p.contains("base wrist"),
            "{p}"
        );
        assert!(s["position_error"].as_f64().unwrap() < 1e-9, "{s}");
    }
}

/// Issue 46, item 11: `--ee` takes any link of a robot description by name, not only the
/// leaf-like ones offered as end-effectors (`--ee l_hand` on Atlas was refused: the hand
/// carries fingers). Checked against the chain's FK written out here; an unknown name lists
/// the end-effectors first, then every other link.
#[test]
fn ee_takes_any_link_by_name() {
    const URDF: &str = r#"<robot name="two_arms">
  <link name="pelvis"/> <link name="l_upper_arm"/> <link name="l_forearm"/> <link name="l_hand"/>
  <link name="l_finger"/> <link name="l_hand_camera"/> <link name="r_upper_arm"/> <link name="r_hand"/>
  <joint name="l_shoulder" type="revolute"><parent link="pelvis"/><child link="l_upper_arm"/>
    <origin xyz="0 0.2 1"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="l_elbow" type="revolute"><parent link="l_upper_arm"/><child link="l_forearm"/>
    <origin xyz="0 0.3 0"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="l_wrist" type="revolute"><parent link="l_forearm"/><child link="l_hand"/>
    <origin xyz="0 0 -0.3"/><axis xyz="1 0 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="l_grip" type="prismatic"><parent link="l_hand"/><child link="l_finger"/>
    <origin xyz="0 0 -0.1"/><axis xyz="0 1 0"/><limit lower="0" upper="0.04" effort="1" velocity="1"/></joint>
  <joint name="l_cam" type="fixed"><parent link="l_hand"/><child link="l_hand_camera"/>
    <origin xyz="0.05 0 0"/></joint>
  <joint name="r_shoulder" type="revolute"><parent link="pelvis"/><child link="r_upper_arm"/>
    <origin xyz="0 -0.2 1"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="r_elbow" type="revolute"><parent link="r_upper_arm"/><child link="r_hand"/>
    <origin xyz="0 -0.3 0"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
</robot>"#;
    let dir = std::env::temp_dir().join(format!("armlab-ee-link-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("two_arms.urdf");
    std::fs::write(&file, URDF).unwrap();
    let f = file.to_str().unwrap();
    let (q1, q2, q3): (f64, f64, f64) = (0.4, -0.7, 0.3);
    let q = format!("{q1},{q2},{q3},0.01,0.5,-0.2");
    // world_from_forearm = T(0, 0.2, 1) Rz(q1) T(0, 0.3, 0) Ry(q2): the elbow's axis point
    let (c, s) = (q1.cos(), q1.sin());
    let elbow = [0.0 - s * 0.3, 0.2 + c * 0.3, 1.0];
    let v = json(&armlab(&[
        "fk",
        f,
        "--q",
        &q,
        "--ee",
        "l_forearm",
        "--format",
        "json",
    ]));
    for k in 0..3 {
        let got = v[0]["p"][k].as_f64().unwrap();
        assert!(
            (got - elbow[k]).abs() < 1e-12,
            "p[{k}] = {got}, want {}",
            elbow[k]
        );
    }
    // the hand (with fingers and a camera below it): world_from_hand = ... Ry(q2) T(0, 0, -0.3)
    let down = [q2.sin() * -0.3, 0.0, q2.cos() * -0.3]; // Ry(q2) (0, 0, -0.3)
    let hand = [
        elbow[0] + c * down[0] - s * down[1],
        elbow[1] + s * down[0] + c * down[1],
        elbow[2] + down[2],
    ];
    let v = json(&armlab(&[
        "fk", f, "--q", &q, "--ee", "l_hand", "--format", "json",
    ]));
    for k in 0..3 {
        let got = v[0]["p"][k].as_f64().unwrap();
        assert!(
            (got - hand[k]).abs() < 1e-12,
            "p[{k}] = {got}, want {}",
            hand[k]
        );
    }
    // any link works for the other commands too
    let o = armlab(&["ik", f, "--ee", "l_forearm", "--position", "0,0.5,1"]);
    assert!(o.status.success(), "{o:?}");
    // an unknown name: the end-effectors first, then the other links
    let o = armlab(&["fk", f, "--q", &q, "--ee", "l_elbow_link"]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    let (ees, links) = err.split_once("any other link").expect(&err);
    assert!(ees.contains("l_finger") && ees.contains("r_hand"), "{err}");
    assert!(
        links.contains("l_forearm") && links.contains("l_upper_arm"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn symbolic_takes_a_model_or_a_rotation_not_both_nor_neither() {
    // clap's errors: exit code 2, nothing on stdout, the reason on stderr
    let refused = |args: &[&str], needle: &str| {
        let o = armlab(args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(o.stdout.is_empty(), "{args:?}: partial output");
        assert!(err.contains(needle), "{args:?}: {needle:?} not in {err}");
        assert!(!err.contains("panicked"));
    };
    refused(&["symbolic"], "<MODEL|--rotation <REPRESENTATION>>");
    refused(
        &["symbolic", "puma560", "--rotation", "zyz"],
        "cannot be used with",
    );
    refused(
        &["symbolic", "--rotation", "zyz", "--numbers"],
        "cannot be used with '--numbers'",
    );
    refused(
        &["symbolic", "--rotation", "rpy", "--ee", "0"],
        "cannot be used with '--ee <EE>'",
    );
    refused(
        &["symbolic", "--rotation", "xyz"],
        "[possible values: zxz, zyz, rpy, axis-angle, quaternion]",
    );
    // each alone works
    for args in [
        &["symbolic", "planar2"][..],
        &["symbolic", "--rotation", "zyz"][..],
    ] {
        let o = armlab(args);
        assert!(
            o.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}
