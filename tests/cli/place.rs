//! `armlab place` (issue 49) run as a user runs it: the issue's flags, the text report and the
//! JSON keys on a two-link planar arm whose best placement is known by geometry (three tasks
//! 1.98 m around one point of the grid: only that point is within the arm's 2 m of all three),
//! the heat map written as PNG and SVG, and bad input (an empty area, a zero step, zero yaws, a
//! bad line of the task file, a figure of another kind): one clear line naming what is wrong,
//! exit code 2, nothing on stdout, no panic.

use serde_json::Value;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn armlab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args(args)
        .env("WGPU_BACKEND", "vulkan")
        .output()
        .expect("run armlab")
}

fn ok(o: &Output) -> String {
    assert!(
        o.status.success(),
        "stderr: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stdout.clone()).unwrap()
}

/// Exit code 2, nothing on stdout, one line on stderr holding every needle, no panic.
fn bad(o: &Output, needles: &[&str]) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert!(
        o.stdout.is_empty(),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    assert_eq!(
        err.trim_end().lines().count(),
        1,
        "one line expected: {err}"
    );
    for n in needles {
        assert!(err.contains(n), "{n:?} not in {err:?}");
    }
    assert!(!err.contains("panicked"));
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("armlab-place-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.display().to_string()
}

/// Three tasks 1.98 m from (0.3, -0.2) at 90, 210 and 330 degrees, named, in the 6-column
/// layout (the orientation does not matter to the two-link arm).
fn triangle(dir: &Path) -> String {
    let mut text = String::from(
        "# three tasks around (0.3, -0.2)\nname, x, y, z, roll_deg, pitch_deg, yaw_deg\n",
    );
    for (name, a) in [("top", 90.0f64), ("lft", 210.0), ("rgt", 330.0)] {
        let (s, c) = a.to_radians().sin_cos();
        text.push_str(&format!(
            "{name}, {}, {}, 0, 0, 0, 45\n",
            0.3 + 1.98 * c,
            -0.2 + 1.98 * s
        ));
    }
    write(dir, "poses.csv", &text)
}

fn keys(v: &Value) -> BTreeSet<&str> {
    v.as_object()
        .unwrap_or_else(|| panic!("not an object: {v}"))
        .keys()
        .map(String::as_str)
        .collect()
}

fn set(names: &[&'static str]) -> BTreeSet<&'static str> {
    names.iter().copied().collect()
}

#[test]
fn the_best_placement_of_the_planar_arm_is_where_geometry_puts_it() {
    let dir = scratch("text");
    let tasks = triangle(&dir);
    let o = armlab(&[
        "place",
        "planar2",
        "--tasks",
        &tasks,
        "--area",
        "-1,1,-1,1",
        "--step",
        "0.05",
        "--yaws",
        "4",
    ]);
    let text = ok(&o);
    assert!(text.contains("41 x 41 base positions at 0.05 m"), "{text}");
    assert!(
        text.contains("rank    x [m]    y [m]  yaw [deg]  fraction"),
        "{text}"
    );
    let first = text
        .lines()
        .find(|l| l.trim_start().starts_with("1 "))
        .unwrap();
    let cols: Vec<&str> = first.split_whitespace().collect();
    assert_eq!(
        &cols[..6],
        ["1", "0.300", "-0.200", "0.0", "1.000", "3/3"],
        "{first}"
    );
    assert!(text.contains("At the best placement (x 0.300 m, y -0.200 m, yaw 0.0 deg):"));
    assert!(text.contains("task \"top\" (line 3): "), "{text}");
    assert!(text.contains("the tasks' positions"), "{text}");
}

#[test]
fn json_has_the_documented_keys() {
    let dir = scratch("json");
    let tasks = triangle(&dir);
    let o = armlab(&[
        "place",
        "planar2",
        "--tasks",
        &tasks,
        "--area",
        "-1,1,-1,1",
        "--step",
        "0.1",
        "--yaws",
        "2",
        "--best",
        "3",
        "--format",
        "json",
    ]);
    let v: Value = serde_json::from_str(&ok(&o)).unwrap();
    assert_eq!(
        keys(&v),
        set(&[
            "model",
            "end_effector",
            "tasks",
            "area",
            "step",
            "yaws",
            "x",
            "y",
            "yaw_deg",
            "solver",
            "task_match",
            "scene",
            "posture_names",
            "evaluations",
            "heat",
            "heat_yaw_deg",
            "blocked_positions",
            "best",
            "figure",
        ])
    );
    assert_eq!(v["area"], serde_json::json!([-1.0, 1.0, -1.0, 1.0]));
    assert_eq!(v["x"].as_array().unwrap().len(), 21);
    assert_eq!(v["yaw_deg"], serde_json::json!([0.0, 180.0]));
    assert_eq!(v["evaluations"], 21 * 21 * 2 * 3);
    assert_eq!(v["solver"]["kind"], "closed_form");
    assert_eq!(v["task_match"], "position");
    assert_eq!(
        v["posture_names"],
        serde_json::json!(["elbow up", "elbow down"])
    );
    let heat = v["heat"].as_array().unwrap();
    assert_eq!((heat.len(), heat[0].as_array().unwrap().len()), (21, 21));
    // heat[i][j] at x[i], y[j]: the point (0.3, -0.2) reaches all three.
    assert_eq!(heat[13][8], 1.0);
    assert_eq!(
        keys(&v["tasks"][0]),
        set(&["name", "line", "position", "rpy_deg", "pose"])
    );
    assert_eq!(v["tasks"][0]["name"], "top");
    assert_eq!(v["tasks"][0]["rpy_deg"][2], 45.0);
    let best = &v["best"];
    assert_eq!(best.as_array().unwrap().len(), 3);
    assert_eq!(
        keys(&best[0]),
        set(&[
            "rank",
            "x",
            "y",
            "yaw_deg",
            "index",
            "fraction",
            "reached",
            "solutions",
            "steady",
            "base_contacts",
            "tasks",
        ])
    );
    assert!((best[0]["x"].as_f64().unwrap() - 0.3).abs() < 1e-9);
    assert!((best[0]["y"].as_f64().unwrap() + 0.2).abs() < 1e-9);
    assert_eq!(best[0]["reached"], 3);
    let t = &best[0]["tasks"][0];
    assert_eq!(
        keys(t),
        set(&["task", "reached", "postures", "posture_mask", "solutions"])
    );
    let s = &t["solutions"][0];
    assert_eq!(
        keys(s),
        set(&[
            "posture",
            "posture_parts",
            "postures",
            "q",
            "q_display",
            "position_error",
            "orientation_error",
        ])
    );
    assert!(s["position_error"].as_f64().unwrap() < 1e-9);
}

#[test]
fn the_heat_map_is_written_as_png_and_svg() {
    let dir = scratch("figure");
    let tasks = triangle(&dir);
    for ext in ["png", "svg"] {
        let fig = dir.join(format!("heat.{ext}"));
        let o = armlab(&[
            "place",
            "planar2",
            "--tasks",
            &tasks,
            "--area",
            "-1,1,-1,1",
            "--step",
            "0.1",
            "--yaws",
            "2",
            "--out",
            fig.to_str().unwrap(),
        ]);
        ok(&o);
        if ext == "png" {
            let img = image::open(&fig).unwrap().to_rgba8();
            assert_eq!(img.dimensions(), (1200, 1100));
            let has = |c: [u8; 3]| img.pixels().any(|p| p.0[..3] == c);
            assert!(has([253, 231, 37]), "the top colour (all tasks) is drawn");
            assert!(has([68, 1, 84]), "the bottom colour (no task) is drawn");
            assert!(has([213, 94, 0]), "the best placement is marked");
        } else {
            let svg = std::fs::read_to_string(&fig).unwrap();
            assert!(
                svg.starts_with("<svg") || svg.starts_with("<?xml"),
                "{}",
                &svg[..80]
            );
            assert!(svg.contains("<image"), "the heat raster is an image");
            assert!(svg.contains("Base placement of"));
            assert!(
                svg.contains(">top<") && svg.contains(">rgt<"),
                "the tasks are named"
            );
        }
    }
}

#[test]
fn bad_input_gets_one_clear_line() {
    let dir = scratch("bad");
    let tasks = triangle(&dir);
    let run = |extra: &[&str]| {
        let mut a = vec!["place", "planar2", "--tasks", tasks.as_str()];
        a.extend_from_slice(extra);
        armlab(&a)
    };
    bad(
        &run(&["--area", "1,0,-1,1"]),
        &["--area", "empty area", "x1 = 0 m"],
    );
    bad(
        &run(&["--area", "-1,1,-1"]),
        &["--area", "expected 4 numbers"],
    );
    bad(
        &run(&["--area", "-1,1,-1,1", "--step", "0"]),
        &["--step", "positive"],
    );
    bad(
        &run(&["--area", "-1,1,-1,1", "--step", "-0.1"]),
        &["--step", "positive"],
    );
    bad(
        &run(&["--area", "-1,1,-1,1", "--yaws", "0"]),
        &["--yaws", "at least 1"],
    );
    bad(
        &run(&["--area", "-100,100,-100,100", "--step", "0.001"]),
        &["over the limit", "--force"],
    );
    bad(
        &run(&["--area", "-1,1,-1,1", "--out", "heat.txt"]),
        &["--out", ".png, .svg or .pdf"],
    );
    let broken = write(
        &dir,
        "broken.csv",
        "0.5, 0.1, 0.2, 0, 0, 0\n0.5, oops, 0.2, 0, 0, 0\n",
    );
    bad(
        &armlab(&[
            "place",
            "planar2",
            "--tasks",
            &broken,
            "--area",
            "-1,1,-1,1",
        ]),
        &["broken.csv:2", "value 2", "oops"],
    );
    let short = write(&dir, "short.csv", "0.5, 0.1, 0.2\n");
    bad(
        &armlab(&["place", "planar2", "--tasks", &short, "--area", "-1,1,-1,1"]),
        &["short.csv:1", "expected 6 numbers", "or 16"],
    );
    let empty = write(&dir, "empty.csv", "# nothing yet\n");
    bad(
        &armlab(&["place", "planar2", "--tasks", &empty, "--area", "-1,1,-1,1"]),
        &["empty.csv", "no task poses"],
    );
    let skew = write(&dir, "skew.csv", "1 0 0 0  0 1 0.5 0  0 0 1 0  0 0 0 1\n");
    bad(
        &armlab(&["place", "planar2", "--tasks", &skew, "--area", "-1,1,-1,1"]),
        &["skew.csv:1", "not rigid", "orthonormal"],
    );
    bad(
        &armlab(&[
            "place",
            "planar2",
            "--tasks",
            "/nonexistent/poses.csv",
            "--area",
            "0,1,0,1",
        ]),
        &["/nonexistent/poses.csv"],
    );
}

#[test]
fn the_issue_flags_are_there() {
    let help = ok(&armlab(&["place", "--help"]));
    for flag in [
        "--tasks <FILE>",
        "--area <X0,X1,Y0,Y1>",
        "--step <STEP>",
        "--yaws <YAWS>",
        "--scene <FILE>",
        "--ee <EE>",
        "--out <FILE>",
        "--best <BEST>",
        "--format <FORMAT>",
    ] {
        assert!(help.contains(flag), "{flag} not in {help}");
    }
    assert!(help.contains("[default: 0.05]") && help.contains("[default: 36]"));
}
