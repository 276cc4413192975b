//! Issue 47's orientation exercises from the command line: `armlab exercise new --kind euler`
//! writes sheets with no answer in the student's folder and keys with the JSON keys;
//! `exercise check --format json` grades as the other kinds do; `exercise grade` counts the
//! named mistakes of a class. Answers are computed here from the key's plain JSON (elementary
//! rotations multiplied out by hand), never by armlab.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn armlab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args(args)
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

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("armlab-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

type M = [[f64; 3]; 3];

fn mul(a: &M, b: &M) -> M {
    let mut out = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            out[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    out
}

fn elementary(axis: &str, a: f64) -> M {
    let (s, c) = a.sin_cos();
    match axis {
        "x" => [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]],
        "y" => [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]],
        "z" => [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]],
        _ => panic!("axis {axis}"),
    }
}

fn read_json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The matrix of the key's sequence: current steps on the right, fixed steps on the left.
fn product(steps: &Value, swap: bool) -> M {
    let mut r = elementary("x", 0.0);
    for s in steps.as_array().unwrap() {
        let e = elementary(s["axis"].as_str().unwrap(), s["angle"].as_f64().unwrap());
        let current = (s["frame"] == "current") != swap;
        r = if current { mul(&r, &e) } else { mul(&e, &r) };
    }
    r
}

fn rows(m: &M) -> String {
    m.iter()
        .map(|r| format!("{:.6} {:.6} {:.6}\n", r[0], r[1], r[2]))
        .collect()
}

/// ZYZ (2.19), ZXZ (Problem 2.1) or RPY (2.22) angles of a regular matrix, in degrees, phi from
/// the matrix and psi from the last row or column, written out here.
fn euler_degrees(conv: &str, m: &Value) -> [f64; 3] {
    let r = |i: usize, j: usize| m[i][j].as_f64().unwrap();
    let a = match conv {
        "zyz" => [
            r(1, 2).atan2(r(0, 2)),
            r(0, 2).hypot(r(1, 2)).atan2(r(2, 2)),
            r(2, 1).atan2(-r(2, 0)),
        ],
        "zxz" => [
            r(0, 2).atan2(-r(1, 2)),
            r(0, 2).hypot(r(1, 2)).atan2(r(2, 2)),
            r(2, 0).atan2(r(2, 1)),
        ],
        _ => [
            r(1, 0).atan2(r(0, 0)),
            (-r(2, 0)).atan2(r(2, 1).hypot(r(2, 2))),
            r(2, 1).atan2(r(2, 2)),
        ],
    };
    a.map(f64::to_degrees)
}

/// One euler sheet of the class in `out`: its files, its key's JSON keys, nothing of the answer
/// in the student's folder; on a regular sheet the angles worked out here get full marks from
/// `check --format json`, and the same numbers without `# deg` are named degrees read as
/// radians. Returns whether the sheet was regular (and checked so).
fn check_euler_sheet(dir: &Path, out: &Path, s: usize) -> bool {
    let folder = out.join(format!("student-{s:02}"));
    for f in ["sheet.md", "sheet.json", "figure.png"] {
        assert!(folder.join(f).is_file(), "{f}");
    }
    let key_path = out.join(format!("keys/student-{s:02}.json"));
    let key = read_json(&key_path);
    assert_eq!(key["kind"], "euler");
    let conv = key["convention"].as_str().unwrap().to_string();
    let sheet = read_json(&folder.join("sheet.json"));
    assert_eq!(sheet["matrix"], key["matrix"]);
    assert_eq!(sheet["convention"], key["convention"]);
    for f in std::fs::read_dir(&folder).unwrap() {
        let text = String::from_utf8_lossy(&std::fs::read(f.unwrap().path()).unwrap()).into_owned();
        for word in ["\"answer\"", "\"solutions\"", "armlab exercise key"] {
            assert!(!text.contains(word), "{word} in the student's folder");
        }
    }
    // a regular sheet: the angles by hand are right; without `# deg`, a named mistake
    let m = &key["matrix"];
    let middle = if conv == "rpy" {
        m[2][1].as_f64().unwrap().hypot(m[2][2].as_f64().unwrap())
    } else {
        m[0][2].as_f64().unwrap().hypot(m[1][2].as_f64().unwrap())
    };
    if middle < 0.2 {
        return false;
    }
    let a = euler_degrees(&conv, m);
    let answer = dir.join(format!("student-{s:02}.txt"));
    std::fs::write(
        &answer,
        format!("# deg\n{:.4}, {:.4}, {:.4}\n", a[0], a[1], a[2]),
    )
    .unwrap();
    let args = |a: &Path| {
        [
            "exercise".to_string(),
            "check".into(),
            key_path.display().to_string(),
            a.display().to_string(),
            "--format".into(),
            "json".into(),
        ]
    };
    let run = |a: &Path| -> Value {
        let args = args(a);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        serde_json::from_str(&ok(&armlab(&args))).unwrap()
    };
    let v = run(&answer);
    assert_eq!(
        (v["score"].as_u64(), v["max"].as_u64()),
        (Some(1), Some(1)),
        "{v}"
    );
    assert_eq!(v["items"][0]["correct"], true);
    assert!(v["items"][0]["mistake"].is_null());
    // the same numbers without `# deg`: degrees read as radians
    std::fs::write(&answer, format!("{:.4} {:.4} {:.4}\n", a[0], a[1], a[2])).unwrap();
    let v = run(&answer);
    assert_eq!(v["score"], 0);
    assert_eq!(v["items"][0]["mistake"], "degrees_as_radians", "{v}");
    assert!(
        v["items"][0]["feedback"]
            .as_str()
            .unwrap()
            .starts_with("degrees read as radians")
    );
    true
}

/// `exercise new --kind euler` (the flag form) writes sheets and keys; nothing of the answer is
/// in a student's folder; `check --format json` answers as for the other kinds, naming the
/// mistake; a bad answer file exits 2 naming its file, line and field.
#[test]
fn euler_sheets_from_the_command_line() {
    let dir = temp("euler-cli");
    let out = dir.join("class");
    let said = ok(&armlab(&[
        "exercise",
        "new",
        "--kind",
        "euler",
        "--students",
        "12",
        "--seed",
        "4",
        "--out",
        out.to_str().unwrap(),
        "--size",
        "160x120",
    ]));
    assert_eq!(said.lines().count(), 12, "{said}");
    let checked = (1..=12)
        .filter(|&s| check_euler_sheet(&dir, &out, s))
        .count();
    assert!(checked >= 5, "{checked} regular sheets");
    // a bad file: exit 2, one line naming the file, the line and the field
    let key_path = out.join("keys/student-01.json");
    let bad = dir.join("bad.txt");
    std::fs::write(&bad, "# deg\n10 twenty 30\n").unwrap();
    let o = armlab(&[
        "exercise",
        "check",
        key_path.to_str().unwrap(),
        bad.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("bad.txt") && err.contains("line 2") && err.contains("field theta"),
        "{err}"
    );
    assert!(o.stdout.is_empty() && !err.contains("panicked"));
    // an orientation exercise draws no arm
    let o = armlab(&[
        "exercise",
        "new",
        "euler",
        "--robot",
        "puma560",
        "--seed",
        "1",
        "--out",
        dir.join("no").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Sheet `s` of the compose class in `out`: no figure, the key's JSON keys, nothing of the
/// product in the student's folder; writes its answer into `answers`: students 1 and 2 the
/// product worked out here, 3 with every frame swapped, 4 the transpose, 5 a file a row short,
/// 6 none.
fn write_compose_answer(out: &Path, answers: &Path, s: usize) {
    let folder = out.join(format!("student-{s:02}"));
    assert!(!folder.join("figure.png").exists());
    let key = read_json(&out.join(format!("keys/student-{s:02}.json")));
    assert_eq!(key["kind"], "compose");
    assert!(key.get("matrix").is_none());
    let sheet = read_json(&folder.join("sheet.json"));
    assert_eq!(sheet["sequence"], key["sequence"]);
    let r = product(&key["sequence"], false);
    // nothing of the product in the student's folder
    for f in std::fs::read_dir(&folder).unwrap() {
        let text = std::fs::read_to_string(f.unwrap().path()).unwrap();
        for v in r
            .iter()
            .flatten()
            .filter(|v| v.abs() > 1e-3 && (v.abs() - 1.0).abs() > 1e-3)
        {
            assert!(
                !text.contains(&format!("{v:.4}")),
                "{v:.4} in the student's folder"
            );
        }
    }
    let text = match s {
        1 | 2 => rows(&r),
        3 => rows(&product(&key["sequence"], true)),
        4 => rows(&[0, 1, 2].map(|i| [0, 1, 2].map(|j| r[j][i]))),
        5 => "1 0 0\n0 1 0\n".into(),
        _ => return,
    };
    std::fs::write(answers.join(format!("student-{s:02}.txt")), text).unwrap();
}

/// A compose class graded at once: right answers, one composed about the wrong axes, one
/// transposed, one unreadable and one missing; the CSV and the summary count each named
/// mistake. No figure is written (the final frame is the answer).
#[test]
fn a_compose_class_is_graded_and_its_mistakes_counted() {
    let dir = temp("compose-cli");
    let out = dir.join("class");
    ok(&armlab(&[
        "exercise",
        "new",
        "compose",
        "--class",
        "6",
        "--seed",
        "2",
        "--out",
        out.to_str().unwrap(),
    ]));
    let answers = dir.join("answers");
    std::fs::create_dir_all(&answers).unwrap();
    for s in 1..=6 {
        write_compose_answer(&out, &answers, s);
    }
    let csv = dir.join("grades.csv");
    let summary = ok(&armlab(&[
        "exercise",
        "grade",
        out.join("keys").to_str().unwrap(),
        answers.to_str().unwrap(),
        "--out",
        csv.to_str().unwrap(),
    ]));
    assert!(
        summary.contains("graded 4 of 6 students; 2 of 6 items right"),
        "{summary}"
    );
    assert!(summary.contains("  1  this is the transpose"), "{summary}");
    assert!(summary.contains("not graded: student-05"), "{summary}");
    assert!(
        summary.contains("not graded: student-06: no answer"),
        "{summary}"
    );
    let table = std::fs::read_to_string(&csv).unwrap();
    let line = |s: &str| {
        table
            .lines()
            .find(|l| l.starts_with(s))
            .unwrap()
            .to_string()
    };
    assert!(line("student-01,").contains(",1,1,"), "{table}");
    assert!(line("student-04,").contains("transpose"), "{table}");
    let three = line("student-03,");
    assert!(
        three.contains("fixed_for_current")
            || three.contains("current_for_fixed")
            || three.contains("reversed_order"),
        "{three}"
    );
    assert!(line("student-05,").contains("line 3"), "{table}");
    // JSON: every student's items, the mistakes counted
    let json = ok(&armlab(&[
        "exercise",
        "grade",
        out.join("keys").to_str().unwrap(),
        answers.to_str().unwrap(),
        "--out",
        csv.to_str().unwrap(),
        "--format",
        "json",
    ]));
    let v: Value = serde_json::from_str(&json).unwrap();
    let mistakes = v["mistakes"].as_array().unwrap();
    assert!(
        mistakes.iter().any(|m| m[0] == "transpose" && m[1] == 1),
        "{v}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// axis-angle and quaternion keys carry the given matrix; their figure is written.
#[test]
fn axis_angle_and_quaternion_sheets_carry_their_matrix() {
    let dir = temp("aa-q-cli");
    for kind in ["axis-angle", "quaternion"] {
        let out = dir.join(kind);
        ok(&armlab(&[
            "exercise",
            "new",
            kind,
            "--class",
            "2",
            "--seed",
            "6",
            "--out",
            out.to_str().unwrap(),
            "--size",
            "160x120",
        ]));
        let key = read_json(&out.join("keys/student-02.json"));
        assert_eq!(key["kind"], kind);
        assert_eq!(key["matrix"].as_array().unwrap().len(), 3);
        assert!(out.join("student-02/figure.png").is_file());
        let sheet = read_json(&out.join("student-02/sheet.json"));
        assert_eq!(sheet["matrix"], key["matrix"]);
        assert!(sheet.get("answer").is_none() && sheet.get("arm").is_none());
    }
    let _ = std::fs::remove_dir_all(&dir);
}
