//! `armlab rotation` as a script uses it: conversions in text and JSON against matrices written
//! out in this file, the singular cases, composition step by step, and bad input (exit code 2,
//! one line naming the flag).

use serde_json::Value;
use std::f64::consts::PI;
use std::process::{Command, Output};

type M3 = [[f64; 3]; 3];

fn armlab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_armlab"))
        .arg("rotation")
        .args(args)
        .output()
        .expect("run armlab")
}

fn text(args: &[&str]) -> String {
    let o = armlab(args);
    assert!(
        o.status.success(),
        "stderr: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stdout).unwrap()
}

fn json(args: &[&str]) -> Value {
    let mut all = args.to_vec();
    all.extend(["--format", "json"]);
    serde_json::from_str(&text(&all)).expect("JSON on stdout")
}

/// Exit code 2, nothing on stdout, one line on stderr containing every needle.
fn bad(args: &[&str], needles: &[&str]) {
    let o = armlab(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    assert!(o.stdout.is_empty(), "{args:?}: partial output");
    assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
    for needle in needles {
        assert!(err.contains(needle), "{args:?}: {needle:?} not in {err:?}");
    }
    assert!(!err.contains("panicked"));
}

// Elementary rotations and products, written out here.
fn rx(d: f64) -> M3 {
    let (c, s) = (d.to_radians().cos(), d.to_radians().sin());
    [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]
}
fn ry(d: f64) -> M3 {
    let (c, s) = (d.to_radians().cos(), d.to_radians().sin());
    [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]
}
fn rz(d: f64) -> M3 {
    let (c, s) = (d.to_radians().cos(), d.to_radians().sin());
    [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
}
fn mul(a: M3, b: M3) -> M3 {
    let mut m = [[0.0; 3]; 3];
    for (i, row) in m.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    m
}
fn matrix_of(v: &Value) -> M3 {
    let mut m = [[0.0; 3]; 3];
    for (i, row) in m.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = v[i][j].as_f64().expect("a number");
        }
    }
    m
}
fn max_diff(a: M3, b: M3) -> f64 {
    (0..9)
        .map(|k| (a[k / 3][k % 3] - b[k / 3][k % 3]).abs())
        .fold(0.0, f64::max)
}
fn triple(v: &Value) -> [f64; 3] {
    [0, 1, 2].map(|k| v[k].as_f64().expect("a number"))
}
/// The matrix of a set of angles (rad) in a representation, from the products above.
fn euler(kind: &str, a: [f64; 3]) -> M3 {
    let [p, t, s] = a.map(f64::to_degrees);
    match kind {
        "zyz" => mul(mul(rz(p), ry(t)), rz(s)),
        "zxz" => mul(mul(rz(p), rx(t)), rz(s)),
        "rpy" => mul(mul(rz(p), ry(t)), rx(s)),
        _ => unreachable!(),
    }
}
/// Rodrigues' formula written out.
fn angle_axis(theta: f64, r: [f64; 3]) -> M3 {
    let (c, s, v) = (theta.cos(), theta.sin(), 1.0 - theta.cos());
    let [x, y, z] = r;
    [
        [x * x * v + c, x * y * v - z * s, x * z * v + y * s],
        [x * y * v + z * s, y * y * v + c, y * z * v - x * s],
        [x * z * v - y * s, y * z * v + x * s, z * z * v + c],
    ]
}

#[test]
fn converts_zyz_to_every_representation_in_text_with_units() {
    let out = text(&["--from", "zyz:30,45,60"]);
    assert!(out.contains("read in degrees"), "{out}");
    assert!(out.contains("dimensionless"), "{out}");
    assert!(out.contains("(30°, 45°, 60°) = (0.523599, 0.785398, 1.047198) rad"));
    assert!(
        out.contains("(-150°, -45°, -120°)"),
        "the second ZYZ solution: {out}"
    );
    // ZXZ = ZYZ with phi + 90° and psi - 90°.
    assert!(out.contains("(120°, 45°, -30°)"), "{out}");
    for section in ["ZXZ", "roll-pitch-yaw", "angle and axis", "quaternion"] {
        assert!(out.contains(section), "{section} missing: {out}");
    }
    // --to narrows the list; the matrix stays.
    let out = text(&["--from", "zyz:30,45,60", "--to", "quaternion"]);
    assert!(out.contains("quaternion") && out.contains("rotation matrix"));
    assert!(!out.contains("ZYZ") && !out.contains("angle and axis"));
}

#[test]
fn json_has_the_issues_keys_and_values_in_radians() {
    let v = json(&["--from", "zyz:30,45,60"]);
    let m = mul(mul(rz(30.0), ry(45.0)), rz(60.0));
    assert!(max_diff(matrix_of(&v["matrix"]), m) < 1e-15);
    for key in ["matrix", "zyz", "zxz", "rpy", "axis_angle", "quaternion"] {
        assert!(v.get(key).is_some(), "no key {key}");
    }
    for kind in ["zyz", "zxz", "rpy"] {
        let e = &v[kind];
        for key in ["solutions", "singular", "determined", "value"] {
            assert!(e.get(key).is_some(), "{kind} has no {key}");
        }
        assert_eq!(e["singular"], false);
        assert!(e["determined"].is_null() && e["value"].is_null());
        let solutions = e["solutions"].as_array().unwrap();
        assert_eq!(solutions.len(), 2, "{kind}");
        for s in solutions {
            assert!(max_diff(euler(kind, triple(s)), m) < 1e-14, "{kind} {s}");
        }
    }
    let zyz = triple(&v["zyz"]["solutions"][0]);
    let expected = [30f64, 45.0, 60.0].map(f64::to_radians);
    assert!((0..3).all(|k| (zyz[k] - expected[k]).abs() < 1e-15));
    let theta = v["axis_angle"]["angle"].as_f64().unwrap();
    let axis = triple(&v["axis_angle"]["axis"]);
    assert!((0.0..=PI).contains(&theta));
    assert!(max_diff(angle_axis(theta, axis), m) < 1e-14);
    let eta = v["quaternion"]["eta"].as_f64().unwrap();
    let eps = triple(&v["quaternion"]["epsilon"]);
    // eta = cos(theta/2) >= 0, epsilon = sin(theta/2) r, (2.30)-(2.31).
    assert!(eta >= 0.0 && (eta - (theta / 2.0).cos()).abs() < 1e-14);
    assert!((0..3).all(|k| (eps[k] - (theta / 2.0).sin() * axis[k]).abs() < 1e-14));
    // --rad reads the same rotation in radians.
    let r = json(&[
        "--from",
        "zyz:0.5235987755982988,0.7853981633974483,1.0471975511965979",
        "--rad",
    ]);
    assert!(max_diff(matrix_of(&r["matrix"]), m) < 1e-15);
}

#[test]
fn singular_cases_in_words_and_in_json() {
    let out = text(&["--from", "zyz:30,0,45", "--to", "zyz"]);
    assert!(out.contains("only phi + psi is determined: 75°"), "{out}");
    let v = json(&["--from", "zyz:30,0,45"]);
    for kind in ["zyz", "zxz"] {
        let e = &v[kind];
        assert_eq!(e["singular"], true);
        assert_eq!(e["determined"], "phi+psi");
        assert!((e["value"].as_f64().unwrap() - 75f64.to_radians()).abs() < 1e-15);
        assert_eq!(e["solutions"].as_array().unwrap().len(), 1);
    }
    assert_eq!(v["rpy"]["singular"], false);
    // theta = 180°: only phi - psi.
    let v = json(&["--from", "zxz:30,180,45"]);
    assert_eq!(v["zxz"]["determined"], "phi-psi");
    assert!((v["zxz"]["value"].as_f64().unwrap() - (-15f64).to_radians()).abs() < 1e-12);
    // RPY at theta = +90° depends on phi - psi, at -90° on phi + psi (Problem 2.3).
    for (theta, combination, value) in [("90", "phi-psi", 30.0), ("-90", "phi+psi", 70.0)] {
        let v = json(&["--from", &format!("rpy:50,{theta},20"), "--to", "rpy"]);
        let e = &v["rpy"];
        assert_eq!(e["determined"], combination, "theta {theta}");
        assert!((e["value"].as_f64().unwrap() - f64::to_radians(value)).abs() < 1e-12);
        let member = triple(&e["solutions"][0]);
        assert!(max_diff(euler("rpy", member), matrix_of(&v["matrix"])) < 1e-14);
    }
    // Angle and axis at theta = 0 (any axis: null) and pi (r and -r).
    let v = json(&["--from", "quaternion:1,0,0,0", "--to", "axis-angle"]);
    assert!(v["axis_angle"]["axis"].is_null());
    assert_eq!(v["axis_angle"]["angle"], 0.0);
    let v = json(&[
        "--from",
        "axis-angle:180,0,3,-4",
        "--to",
        "axis-angle,quaternion",
    ]);
    let axes = v["axis_angle"]["axes"].as_array().unwrap();
    assert_eq!(axes.len(), 2);
    let r = triple(&v["axis_angle"]["axis"]);
    assert!(
        (r[1] + 0.6).abs() < 1e-15 && (r[2] - 0.8).abs() < 1e-15,
        "{r:?}"
    );
    let text = text(&["--from", "axis-angle:180,0,3,-4", "--to", "axis-angle"]);
    assert!(
        text.contains("a half turn") && text.contains("-r ="),
        "{text}"
    );
}

#[test]
fn other_inputs_matrix_quaternion_axis_angle() {
    // A matrix typed to 9 digits: accepted and made orthonormal.
    let m = mul(rz(20.0), rx(70.0));
    let typed: Vec<String> = m.iter().flatten().map(|x| format!("{x:.9}")).collect();
    let v = json(&["--from", &format!("matrix:{}", typed.join(","))]);
    let back = matrix_of(&v["matrix"]);
    assert!(max_diff(back, m) < 1e-9);
    let rtr = mul([0, 1, 2].map(|i| [0, 1, 2].map(|j| back[j][i])), back);
    assert!(max_diff(rtr, [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]) < 1e-15);
    // A quaternion is normalized: {2, (0, 0, 2)} is 90° about z.
    let v = json(&["--from", "quaternion:2,0,0,2"]);
    assert!(max_diff(matrix_of(&v["matrix"]), rz(90.0)) < 1e-15);
    // Angle and axis, the axis normalized.
    let v = json(&["--from", "axis-angle:90,0,0,5"]);
    assert!(max_diff(matrix_of(&v["matrix"]), rz(90.0)) < 1e-15);
    let v = json(&["--from", "rpy:10,20,30"]);
    let m = mul(mul(rz(10.0), ry(20.0)), rx(30.0));
    assert!(max_diff(matrix_of(&v["matrix"]), m) < 1e-15);
}

#[test]
fn compose_prints_each_partial_product() {
    let seq = "current Rz(30) Ry(45); fixed Rx(10)";
    let v = json(&["--compose", seq]);
    let steps = v["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 3);
    let after = [
        rz(30.0),
        mul(rz(30.0), ry(45.0)),
        mul(rx(10.0), mul(rz(30.0), ry(45.0))),
    ];
    for ((s, m), (frame, axis, angle)) in steps.iter().zip(after).zip([
        ("current", "z", 30.0),
        ("current", "y", 45.0),
        ("fixed", "x", 10.0),
    ]) {
        assert_eq!(s["frame"], frame);
        assert_eq!(s["axis"], axis);
        assert!((s["angle"].as_f64().unwrap() - f64::to_radians(angle)).abs() < 1e-15);
        assert!(max_diff(matrix_of(&s["matrix"]), m) < 1e-15);
    }
    assert!(max_diff(matrix_of(&v["matrix"]), after[2]) < 1e-15);
    assert!(v["zyz"]["solutions"].is_array() && v["quaternion"]["eta"].is_number());
    let out = text(&["--compose", seq]);
    assert!(out.contains("R2 = R1 Ry(45°)"), "{out}");
    assert!(out.contains("R3 = Rx(10°) R2"), "{out}");
    assert!(out.contains("R = Rx(10°) Rz(30°) Ry(45°)"), "{out}");
    // About the current axes, then the list reversed about the fixed ones: the same frame.
    let a = json(&["--compose", "current Rz(30) Ry(45) Rx(10)"]);
    let b = json(&["--compose", "fixed Rx(10) Ry(45) Rz(30);"]);
    assert!(max_diff(matrix_of(&a["matrix"]), matrix_of(&b["matrix"])) < 1e-15);
    // The order matters otherwise.
    let c = json(&["--compose", "fixed Rz(30) Ry(45) Rx(10)"]);
    assert!(max_diff(matrix_of(&a["matrix"]), matrix_of(&c["matrix"])) > 0.1);
    // Radians.
    let d = json(&["--compose", "current Rz(0.5235987755982988)", "--rad"]);
    assert!(max_diff(matrix_of(&d["matrix"]), rz(30.0)) < 1e-15);
}

#[test]
fn bad_input_names_the_flag_and_what_was_expected() {
    bad(
        &["--from", "xyz:1,2,3"],
        &["--from", "unknown representation", "zyz"],
    );
    bad(&["--from", "30,45,60"], &["--from", "KIND:VALUES"]);
    bad(
        &["--from", "zyz:30,45"],
        &["--from zyz", "expected 3", "got 2"],
    );
    bad(&["--from", "rpy:30,x,45"], &["--from rpy", "value 2"]);
    bad(
        &["--from", "matrix:1,0,0,0,1,0,0,0,1.1"],
        &["--from matrix", "not a rotation matrix", "tolerance"],
    );
    bad(
        &["--from", "matrix:1,0,0,0,1,0,0,0,-1"],
        &["--from matrix", "reflection"],
    );
    bad(
        &["--from", "matrix:1,0,0,0,1,0,0,0"],
        &["--from matrix", "expected 9"],
    );
    bad(
        &["--from", "quaternion:0,0,0,0"],
        &["--from quaternion", "zero"],
    );
    bad(
        &["--from", "axis-angle:30,0,0,0"],
        &["--from axis-angle", "axis", "zero"],
    );
    bad(&["--from", "zyz:nan,1,2"], &["--from zyz", "finite"]);
    bad(
        &["--compose", "curent Rz(3)"],
        &["--compose", "group 1", "current"],
    );
    bad(
        &["--compose", "fixed Rq(3)"],
        &["--compose", "group 1, rotation 1", "Rq(3)"],
    );
    bad(
        &["--compose", "fixed Rz(30) Rx(abc)"],
        &["--compose", "rotation 2", "abc"],
    );
    bad(&["--compose", "fixed Rz(30"], &["--compose", "Rz(30"]);
    bad(&["--compose", "current"], &["--compose", "no rotation"]);
    bad(
        &["--compose", "current Rz(1);; fixed Rx(2)"],
        &["--compose", "group 2 is empty"],
    );
    bad(&[], &["--from", "--compose"]);
    bad(
        &["--from", "zyz:1,2,3", "--compose", "current Rz(1)"],
        &["exactly one"],
    );
}
