//! Exercises checked automatically: sheets for a class, and grading by equivalence.
//!
//! The DH grader's verdicts are checked against an independent brute force written here: two
//! tables describe the same arm when some sign and right-angle offset per joint makes their
//! forward kinematics agree at random joint vectors.

use armlab::exercise::{
    Answer, Key, KeyAnswer, Kind, Rng, Tolerance, generate, grade, grade_dh, sheet_arm,
};
use armlab::kinematics::dh::standard_to_modified;
use armlab::kinematics::models::built_in;
use armlab::kinematics::{Convention, DhJoint, Pose, Robot};
use std::f64::consts::{FRAC_PI_2, PI};

fn table(robot: &Robot) -> (Convention, Vec<DhJoint>) {
    let (c, t) = robot.dh_table().unwrap();
    (
        c,
        t.iter()
            .map(|(k, r, o)| DhJoint::new(*k, *r).offset(*o))
            .collect(),
    )
}

fn build(conv: Convention, rows: &[DhJoint]) -> Robot {
    Robot::from_dh("answer", conv, rows, Pose::identity(), Pose::identity()).unwrap()
}

/// The brute force: signs in {+1, -1}, offsets in {-pi/2, 0, pi/2, pi} per revolute joint.
fn same_arm_brute_force(reference: &Robot, answer: &Robot) -> bool {
    let n = reference.dof();
    let samples: Vec<Vec<f64>> = (0..3)
        .map(|s| {
            (0..n)
                .map(|k| 0.37 * (s + 1) as f64 - 0.29 * k as f64)
                .collect()
        })
        .collect();
    let want: Vec<Pose> = samples.iter().map(|q| reference.fk(q).unwrap()).collect();
    let offsets = [-FRAC_PI_2, 0.0, FRAC_PI_2, PI];
    let combos = 2usize.pow(n as u32) * 4usize.pow(n as u32);
    (0..combos).any(|c| {
        let mut code = c;
        let mut sign = vec![0.0; n];
        let mut off = vec![0.0; n];
        for k in 0..n {
            sign[k] = if code % 2 == 0 { 1.0 } else { -1.0 };
            code /= 2;
            off[k] = offsets[code % 4];
            code /= 4;
        }
        samples.iter().zip(&want).all(|(q, w)| {
            let qa: Vec<f64> = (0..n).map(|k| sign[k] * q[k] + off[k]).collect();
            let t = answer.fk(&qa).unwrap();
            (t.translation.vector - w.translation.vector).norm() < 1e-9
                && (t.rotation.matrix() - w.rotation.matrix()).abs().max() < 1e-9
        })
    })
}

#[test]
fn one_sign_changed_the_grader_agrees_with_brute_force_and_names_a_real_slip() {
    for name in ["puma560", "anthropomorphic3r", "planar3"] {
        let reference = sheet_arm(&built_in(name).unwrap(), None).unwrap();
        let (conv, rows) = table(&reference);
        let mut wrong_seen = 0;
        for i in 0..rows.len() {
            for p in 0..3 {
                let mut edited = rows.clone();
                let v = match p {
                    0 => &mut edited[i].row.alpha,
                    1 => &mut edited[i].row.a,
                    _ => &mut edited[i].row.d,
                };
                if *v == 0.0 {
                    continue;
                }
                *v = -*v;
                let answer = build(conv, &edited);
                let g = grade_dh(&reference, &answer, Tolerance::default());
                let graded_right = g.score == g.max;
                assert_eq!(
                    graded_right,
                    same_arm_brute_force(&reference, &answer),
                    "{name} row {} param {p}: {g:?}",
                    i + 1
                );
                if !graded_right {
                    wrong_seen += 1;
                    // the slip is named: its row and parameter
                    let param = ["alpha", "a", "d"][p];
                    let wrong: Vec<_> = g.items.iter().filter(|it| !it.correct).collect();
                    assert_eq!(wrong.len(), 1, "{name}: {g:?}");
                    assert!(
                        wrong[0]
                            .feedback
                            .starts_with(&format!("row {}: {param}", i + 1)),
                        "{name} row {} {param}: {}",
                        i + 1,
                        wrong[0].feedback
                    );
                    assert!(wrong[0].feedback.contains("wrong sign"));
                }
            }
        }
        if name == "puma560" {
            assert!(wrong_seen >= 3, "{name}: {wrong_seen}");
        }
    }
}

#[test]
fn the_issue_s_example_feedback() {
    let reference = sheet_arm(&built_in("puma560").unwrap(), None).unwrap();
    let (conv, mut rows) = table(&reference);
    rows[2].row.alpha = -rows[2].row.alpha;
    let g = grade_dh(&reference, &build(conv, &rows), Tolerance::default());
    let wrong: Vec<_> = g.items.iter().filter(|i| !i.correct).collect();
    assert_eq!(
        wrong[0].feedback,
        "row 3: alpha3 has the wrong sign: z2 turns into z3 the other way"
    );
    assert_eq!(wrong[0].mistake, Some(armlab::exercise::Mistake::AlphaSign));
    assert_eq!(g.score, 5);
}

/// Runs the armlab binary; its standard output (the run must succeed).
#[cfg(feature = "app")]
fn run(args: &[&str]) -> String {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args(args)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8(o.stdout).unwrap()
}

/// Every mistake's CSV name is its JSON name.
#[test]
fn a_mistake_has_one_name() {
    use armlab::exercise::{Mistake, mistake_name};
    let all = [
        Mistake::JointCount,
        Mistake::NotDhTable,
        Mistake::JointKind,
        Mistake::AlphaSign,
        Mistake::ASign,
        Mistake::DSign,
        Mistake::ASwappedWithD,
        Mistake::AlphaWrong,
        Mistake::AWrong,
        Mistake::DWrong,
        Mistake::Unplaced,
        Mistake::TSign,
        Mistake::TPosition,
        Mistake::TRotation,
        Mistake::MissingSolution,
        Mistake::ExtraSolution,
        Mistake::PostureCount,
        Mistake::Area,
        Mistake::JointNumber,
        Mistake::OperationalSpace,
        Mistake::TaskComponents,
        Mistake::MissedUnidentifiable,
        Mistake::NamedIdentifiable,
        Mistake::FixedForCurrent,
        Mistake::CurrentForFixed,
        Mistake::Transpose,
        Mistake::DegreesAsRadians,
        Mistake::RadiansAsDegrees,
        Mistake::OtherConvention,
        Mistake::ReversedOrder,
        Mistake::AngleSign,
        Mistake::NonUnitQuaternion,
        Mistake::NonUnitAxis,
        Mistake::EpsilonFirst,
        Mistake::HalfAngle,
        Mistake::FullAngle,
    ];
    for m in all {
        assert_eq!(
            serde_json::to_string(&m).unwrap(),
            format!("\"{}\"", mistake_name(m))
        );
    }
}

/// A CSV file's rows (RFC 4180: quoted fields, doubled quotes), read here, not by armlab.
#[cfg(feature = "app")]
fn csv_rows(text: &str) -> Vec<Vec<String>> {
    let (mut rows, mut row, mut field) = (Vec::new(), Vec::new(), String::new());
    let mut chars = text.chars().peekable();
    let mut quoted = false;
    while let Some(c) = chars.next() {
        match (quoted, c) {
            (true, '"') if chars.peek() == Some(&'"') => {
                chars.next();
                field.push('"');
            }
            (true, '"') => quoted = false,
            (true, c) => field.push(c),
            (false, '"') => quoted = true,
            (false, ',') => row.push(std::mem::take(&mut field)),
            (false, '\n') => {
                row.push(std::mem::take(&mut field));
                rows.push(std::mem::take(&mut row));
            }
            (false, c) => field.push(c),
        }
    }
    rows
}

/// Issue 46: the teacher grades a folder of answers at once. Four keys: a right answer, one
/// with alpha3's sign flipped, none, an unreadable one; and an answer without a key.
#[cfg(feature = "app")]
#[test]
fn a_class_is_graded_at_once() {
    let dir = std::env::temp_dir().join(format!("armlab-grade-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let out = dir.join("class");
    run(&[
        "exercise",
        "new",
        "dh-table",
        "--robot",
        "puma560",
        "--seed",
        "3",
        "--class",
        "4",
        "--out",
        &out.to_string_lossy(),
        "--size",
        "160x120",
    ]);
    let answers = dir.join("answers");
    std::fs::create_dir_all(&answers).unwrap();
    let key = |s: usize| -> Key {
        let path = out.join(format!("keys/student-{s:02}.json"));
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
    };
    std::fs::write(answers.join("student-01.toml"), key(1).model).unwrap();
    let arm = armlab::model_file::parse_model(&key(2).model, "key.toml".as_ref()).unwrap();
    let (conv, mut rows) = table(&arm);
    rows[2].row.alpha = -rows[2].row.alpha;
    let slip = armlab::model_file::to_toml(&build(conv, &rows)).unwrap();
    std::fs::write(answers.join("student-02.toml"), slip).unwrap();
    std::fs::write(answers.join("student-04.toml"), "this is not a model [").unwrap();
    std::fs::write(answers.join("student-99.toml"), key(1).model).unwrap();
    let csv = dir.join("grades.csv");
    let summary = run(&[
        "exercise",
        "grade",
        &out.join("keys").to_string_lossy(),
        &answers.to_string_lossy(),
        "--out",
        &csv.to_string_lossy(),
    ]);
    let rows = csv_rows(&std::fs::read_to_string(&csv).unwrap());
    assert_eq!(rows.len(), 5, "{rows:?}");
    assert_eq!(
        rows[0][..6],
        ["student", "answer", "score", "max", "error", "mistakes"]
    );
    let by = |s: &str| rows.iter().find(|r| r[0] == s).unwrap().clone();
    let (one, two, three, four) = (
        by("student-01"),
        by("student-02"),
        by("student-03"),
        by("student-04"),
    );
    assert_eq!(one[1..4], ["student-01.toml", "6", "6"]);
    assert_eq!(one[4..6], ["", ""]);
    assert_eq!(two[2..4], ["5", "6"]);
    assert_eq!(two[5], "alpha_sign");
    let wrong: Vec<&String> = two[6..].iter().filter(|c| c.contains("WRONG")).collect();
    assert_eq!(wrong.len(), 1);
    assert!(
        wrong[0].starts_with("row 3: WRONG: row 3: alpha3 has the wrong sign"),
        "{wrong:?}"
    );
    assert_eq!(three[1..5], ["", "0", "6", "no answer"]);
    assert_eq!(four[2..4], ["0", "6"]);
    assert!(four[4].contains("student-04.toml"), "{four:?}");
    assert!(
        summary.contains("graded 2 of 4 students; 11 of 24 items right"),
        "{summary}"
    );
    assert!(
        summary.contains("  1  alpha with the wrong sign (z turned the other way)"),
        "{summary}"
    );
    assert!(
        summary.contains("not graded: student-03: no answer"),
        "{summary}"
    );
    assert!(summary.contains("no key for the answer"), "{summary}");
    assert!(summary.contains("student-99.toml"), "{summary}");
    // Two answers of one student is an error naming both.
    std::fs::write(answers.join("student-01.txt"), "0").unwrap();
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args(["exercise", "grade"])
        .arg(out.join("keys"))
        .arg(&answers)
        .arg("--out")
        .arg(&csv)
        .output()
        .unwrap();
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("student-01.toml") && err.contains("student-01.txt"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_modified_convention_and_other_frames_get_full_marks() {
    for name in [
        "puma560",
        "stanford",
        "anthropomorphic_spherical_wrist",
        "scara",
    ] {
        let reference = sheet_arm(&built_in(name).unwrap(), None).unwrap();
        let (_, rows) = table(&reference);
        let std_rows: Vec<_> = rows.iter().map(|r| r.row).collect();
        let (modified, tool) = standard_to_modified(&std_rows);
        if tool != Pose::identity() {
            continue;
        }
        let mrows: Vec<DhJoint> = rows
            .iter()
            .zip(modified)
            .map(|(r, m)| DhJoint::new(r.kind, m).offset(r.offset))
            .collect();
        let g = grade_dh(
            &reference,
            &build(Convention::Modified, &mrows),
            Tolerance::default(),
        );
        assert_eq!(g.score, g.max, "{name} modified: {g:?}");
    }
    // x1 the other way and z2 the other way (a valid choice) on the anthropomorphic arm
    let reference = sheet_arm(&built_in("anthropomorphic_spherical_wrist").unwrap(), None).unwrap();
    let (conv, mut rows) = table(&reference);
    rows[0].row.alpha = -rows[0].row.alpha;
    let g = grade_dh(&reference, &build(conv, &rows), Tolerance::default());
    assert_eq!(g.score, g.max, "{g:?}");
    assert!(
        g.items.iter().any(|i| i.feedback.contains("your q")),
        "{g:?}"
    );
}

#[test]
fn a_class_of_thirty_sheets_all_different_each_key_grades_itself_right() {
    let mut seen = std::collections::HashSet::new();
    for student in 1..=30 {
        let sheet = generate(Kind::DhTable, None, 7, student).unwrap();
        let q: Vec<String> = sheet.key.q.iter().map(|v| format!("{v:.6}")).collect();
        assert!(
            seen.insert((sheet.key.model.clone(), q)),
            "sheet {student} repeats another"
        );
        let reference = armlab::exercise::key_robot(&sheet.key).unwrap();
        let g = grade(&sheet.key, &Answer::Model(Box::new(reference))).unwrap();
        assert_eq!(g.score, g.max, "sheet {student}: {g:?}");
        assert!(sheet.markdown.contains("DH table"));
    }
    // the same seed gives the same class
    let again = generate(Kind::DhTable, None, 7, 4).unwrap();
    assert_eq!(again.key, generate(Kind::DhTable, None, 7, 4).unwrap().key);
}

fn rows_of_key(key: &Key) -> Vec<Vec<f64>> {
    match &key.answer {
        KeyAnswer::Fk { t } => t.iter().map(|r| r.to_vec()).collect(),
        KeyAnswer::Ik { solutions, .. } => solutions.iter().map(|(q, _)| q.clone()).collect(),
        KeyAnswer::Workspace { postures, area, .. } => {
            let mut r: Vec<Vec<f64>> = postures.iter().map(|&p| vec![p as f64]).collect();
            r.push(vec![*area]);
            r
        }
        KeyAnswer::Redundancy { n, m, r, .. } => vec![vec![*n as f64, *m as f64, *r as f64]],
        _ => unreachable!("{:?}", key.answer),
    }
}

#[test]
fn fk_ik_workspace_and_redundancy_sheets_grade_the_key_right_and_a_slip_wrong() {
    let puma = built_in("puma560").unwrap();
    let planar = built_in("planar2").unwrap();
    for (kind, robot) in [
        (Kind::Fk, Some(&puma)),
        (Kind::Ik, Some(&puma)),
        (Kind::Redundancy, Some(&puma)),
        (Kind::Workspace, Some(&planar)),
        (Kind::Workspace, None),
    ] {
        let sheet = generate(kind, robot, 3, 2).unwrap();
        let rows = rows_of_key(&sheet.key);
        let g = grade(&sheet.key, &Answer::Rows(rows.clone())).unwrap();
        assert_eq!(g.score, g.max, "{kind:?}: {g:?}");
        let mut slipped = rows.clone();
        slipped[0][0] += 0.5;
        let g = grade(&sheet.key, &Answer::Rows(slipped)).unwrap();
        assert!(g.score < g.max, "{kind:?}: {g:?}");
    }
    // ik: eight Puma postures, each checked by FK here (independent of the solver)
    let sheet = generate(Kind::Ik, Some(&puma), 3, 2).unwrap();
    let KeyAnswer::Ik { target, solutions } = &sheet.key.answer else {
        panic!()
    };
    assert_eq!(solutions.len(), 8);
    let arm = armlab::exercise::key_robot(&sheet.key).unwrap();
    for (q, _) in solutions {
        let t = armlab::kinematics::pose::pose_to_rows(&arm.fk(q).unwrap());
        for i in 0..3 {
            for j in 0..4 {
                assert!((t[i][j] - target[i][j]).abs() < 1e-9);
            }
        }
    }
    // workspace: the counts follow from the distances (independent of the key's code)
    let sheet = generate(Kind::Workspace, Some(&planar), 5, 1).unwrap();
    let KeyAnswer::Workspace {
        points,
        postures,
        area,
    } = &sheet.key.answer
    else {
        panic!()
    };
    assert!((area - 4.0 * PI).abs() < 1e-12, "planar2 has a1 = a2 = 1 m");
    for (p, n) in points.iter().zip(postures) {
        let r = p[0].hypot(p[1]);
        let expect = if r > 2.0 + 1e-3 {
            0
        } else if (r - 2.0).abs() < 1e-3 {
            1
        } else {
            2
        };
        assert_eq!(*n, expect, "point {p:?}");
    }
}

/// The issue's commands: a class of 30 dh-table sheets, then grading from the files.
#[cfg(feature = "app")]
#[test]
fn the_cli_writes_a_class_and_grades_from_files() {
    let dir = std::env::temp_dir().join(format!("armlab-exercise-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let out = dir.to_string_lossy().to_string();
    run(&[
        "exercise", "new", "dh-table", "--random", "--seed", "11", "--class", "30", "--out", &out,
        "--size", "320x240",
    ]);
    for s in 1..=30 {
        assert!(dir.join(format!("student-{s:02}/sheet.md")).is_file());
        assert!(dir.join(format!("student-{s:02}/figure.png")).is_file());
        assert!(dir.join(format!("student-{s:02}/sheet.json")).is_file());
        assert!(dir.join(format!("keys/student-{s:02}.json")).is_file());
        // a key is never where the student's sheet is
        for f in std::fs::read_dir(dir.join(format!("student-{s:02}"))).unwrap() {
            let bytes = std::fs::read(f.unwrap().path()).unwrap();
            let text = String::from_utf8_lossy(&bytes);
            assert!(!text.contains(armlab::exercise::KEY_FORMAT));
            assert!(!text.contains("\"answer\"") && !text.contains("\"model\""));
        }
    }
    let key_path = dir.join("keys/student-05.json");
    let key: Key = serde_json::from_str(&std::fs::read_to_string(&key_path).unwrap()).unwrap();
    let answer = dir.join("answer.toml");
    std::fs::write(&answer, &key.model).unwrap();
    let json = run(&[
        "exercise",
        "check",
        &key_path.to_string_lossy(),
        &answer.to_string_lossy(),
        "--format",
        "json",
    ]);
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["score"], v["max"]);
    assert!(v["items"][0]["item"].is_string() && v["items"][0]["feedback"].is_string());
    assert_eq!(v["items"][0]["correct"], true);
    let text = run(&[
        "exercise",
        "check",
        "--against",
        "planar3",
        &answer.to_string_lossy(),
    ]);
    assert!(text.starts_with("score "), "{text}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn identifiability_sheets_name_the_parallel_axes_lesson() {
    use armlab::exercise::parse_words;
    let puma = built_in("puma560").unwrap();
    let sheet = generate(Kind::Identifiability, Some(&puma), 1, 1).unwrap();
    let KeyAnswer::Identifiability {
        setup, parameters, ..
    } = &sheet.key.answer
    else {
        panic!("{:?}", sheet.key.answer)
    };
    // Full poses of a plain-DH Puma: axes 2 and 3 are parallel, so d2 and d3 are seen only as
    // d2 + d3 (Sect. 2.11); everything else is identifiable.
    assert_eq!(setup, "pose");
    assert_eq!(parameters, &vec!["d2".to_string(), "d3".to_string()]);
    let g = grade(&sheet.key, &Answer::Words(parse_words("d2, d3\n"))).unwrap();
    assert_eq!((g.score, g.max), (2, 2));
    let g = grade(&sheet.key, &Answer::Words(parse_words("D2 a2"))).unwrap();
    assert_eq!(g.score, 1);
    let missed = g.items.iter().find(|i| i.item == "d3").unwrap();
    assert!(missed.feedback.contains("d2 + d3"), "{}", missed.feedback);
    let extra = g.items.iter().find(|i| i.item == "a2").unwrap();
    assert!(!extra.correct && extra.feedback.contains("can be identified"));
    assert!(sheet.markdown.contains("Identifiability"));
}

/// Issue 46, item 2: a student's sheet file, for every kind, carries the question, the arm and
/// its q and nothing of the answer: no key field, no DH row, no convention; its arm (a URDF of
/// axes) is the key's arm, checked by the FK of both at random joint vectors.
#[test]
fn a_sheet_file_carries_its_arm_and_question_and_no_answer() {
    use armlab::exercise::{SheetFile, key_robot};
    let kinds = [
        Kind::DhTable,
        Kind::Fk,
        Kind::Ik,
        Kind::Workspace,
        Kind::Redundancy,
        Kind::Identifiability,
    ];
    for kind in kinds {
        for student in 1..=4 {
            let sheet = generate(kind, None, 17, student).unwrap();
            let file = SheetFile::of(&sheet).unwrap();
            let json = serde_json::to_string_pretty(&file).unwrap();
            assert_no_answer(&json, &sheet.markdown);
            let back = SheetFile::parse("sheet.json", &json).unwrap();
            assert_eq!(back, file);
            assert_eq!(
                back.answer_file_name(),
                format!(
                    "student-{student:02}.{}",
                    if kind == Kind::DhTable { "toml" } else { "txt" }
                )
            );
            let arm = back.robot().unwrap();
            let reference = key_robot(&sheet.key).unwrap();
            assert_eq!(arm.dof(), reference.dof());
            let mut rng = Rng::new(3, student);
            for _ in 0..20 {
                let q: Vec<f64> = (0..arm.dof()).map(|_| 6.0 * rng.uniform() - 3.0).collect();
                let a = arm.fk(&q).unwrap().to_homogeneous();
                let b = reference.fk(&q).unwrap().to_homogeneous();
                assert!(
                    (a - b).amax() < 1e-9,
                    "{kind:?} sheet {student}: {a} vs {b}"
                );
            }
        }
    }
    assert!(SheetFile::parse("x.json", "{}").is_err());
    // Issue 47: an orientation sheet has no arm; it carries its question (the given matrix and
    // the convention asked for, or the sequence) and nothing of the answer.
    for (kind, given) in [
        (Kind::Euler, ["convention", "matrix"].as_slice()),
        (Kind::Compose, ["sequence"].as_slice()),
        (Kind::AxisAngle, ["matrix"].as_slice()),
        (Kind::Quaternion, ["matrix"].as_slice()),
    ] {
        for student in 1..=6 {
            let sheet = generate(kind, None, 17, student).unwrap();
            assert!(sheet.robot.is_none());
            let file = SheetFile::of(&sheet).unwrap();
            let json = serde_json::to_string_pretty(&file).unwrap();
            let v: serde_json::Value = serde_json::from_str(&json).unwrap();
            let mut keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
            keys.sort_unstable();
            let mut want = vec!["format", "kind", "question", "seed", "student"];
            want.extend(given);
            want.sort_unstable();
            assert_eq!(keys, want, "{kind:?}");
            assert_eq!(v["question"], sheet.markdown.as_str());
            for (field, value) in [("matrix", &v["matrix"]), ("sequence", &v["sequence"])] {
                let key = serde_json::to_value(&sheet.key).unwrap();
                assert_eq!(
                    value, &key[field],
                    "{kind:?}: the sheet's {field} is the key's"
                );
            }
            assert!(back_is_no_arm(&json));
            assert_no_orientation_answer(&sheet.key, &[&json, &sheet.markdown]);
        }
    }
}

/// An orientation sheet file reads back, and has no arm to load.
fn back_is_no_arm(json: &str) -> bool {
    let back = armlab::exercise::SheetFile::parse("sheet.json", json).unwrap();
    back.arm.is_empty() && back.q.is_empty() && back.robot().is_err()
}

/// None of the numbers of the key's answer appears in the student's texts (written as the
/// sheet would write them: four to six decimals, or degrees), and no key field does.
fn assert_no_orientation_answer(key: &Key, texts: &[&str]) {
    let answer = serde_json::to_value(&key.answer).unwrap();
    let mut numbers = Vec::new();
    let mut stack = vec![&answer];
    while let Some(v) = stack.pop() {
        match v {
            serde_json::Value::Number(n) => numbers.push(n.as_f64().unwrap()),
            serde_json::Value::Array(a) => stack.extend(a),
            serde_json::Value::Object(o) => stack.extend(o.values()),
            _ => {}
        }
    }
    // a number also in the question's matrix (a 0 or a 1, an entry of a half turn's axis
    // equal to one of the matrix) says nothing
    let given: Vec<f64> = key.matrix.iter().flatten().flatten().copied().collect();
    for text in texts {
        for word in [
            "\"answer\"",
            "\"solutions\"",
            "\"product\"",
            "\"epsilon\"",
            "tolerance",
            armlab::exercise::KEY_FORMAT,
        ] {
            assert!(!text.contains(word), "the student's file holds {word:?}");
        }
        for x in &numbers {
            if x.abs() < 1e-3 || (x.abs() - 1.0).abs() < 1e-3 {
                continue;
            }
            if given.iter().any(|g| (g.abs() - x.abs()).abs() < 1e-4) {
                continue;
            }
            for shown in [
                format!("{x:.4}"),
                format!("{x:.6}"),
                format!("{:.1}", x.to_degrees()),
            ] {
                assert!(
                    !text.contains(&shown),
                    "{:?}: the answer's {shown} is in the student's file",
                    key.kind
                );
            }
        }
    }
}

/// A sheet file's JSON holds the question (what `sheet.md` says), the arm and q, and nothing
/// else: no key field, and an arm made of axes alone (every joint origin without rotation, no
/// DH word).
fn assert_no_answer(json: &str, question: &str) {
    let v: serde_json::Value = serde_json::from_str(json).unwrap();
    let mut keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
    keys.sort_unstable();
    assert_eq!(
        keys,
        ["arm", "format", "kind", "q", "question", "seed", "student"]
    );
    assert_eq!(v["question"], question);
    let arm = v["arm"].as_str().unwrap();
    for word in ["alpha", "convention", "theta", "dh", "DH"] {
        assert!(!arm.contains(word), "the arm holds {word:?}: {arm}");
    }
    let joints = arm.split("<joint ").skip(1);
    for j in joints.filter(|j| !j.contains("type=\"fixed\"")) {
        assert!(j.contains("rpy=\"0 0 0\""), "a rotated joint origin: {j}");
    }
}
