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

/// Two lessons equal, NaN equal to NaN (TOML writes and reads `nan`): their debug forms, which
/// print every number in its shortest round-trip form.
fn same_lesson(a: &armlab::lesson::Lesson, b: &armlab::lesson::Lesson) -> bool {
    a == b || format!("{a:?}") == format!("{b:?}")
}

/// A lesson file (TOML): read as the app reads a dropped file (`Lesson::detect`) and as
/// `armlab lesson` does (`Lesson::parse`). An accepted lesson writes back (`to_toml`) and reads
/// again equal; its robot, where it is a built-in or embedded, gives each step's q with the
/// robot's number of joints or a step error; a rejected one names the file and a line of it (a
/// TOML syntax error) or a step of it.
pub fn lesson(data: &[u8]) {
    use armlab::lesson::{Lesson, LessonError, RobotSource};
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let file = "fuzz.toml";
    let parsed = Lesson::parse(text, file);
    match Lesson::detect(text, file) {
        None => {}
        Some(Ok(l)) => assert!(
            parsed.as_ref().is_ok_and(|p| same_lesson(p, &l)),
            "detect and parse disagree"
        ),
        Some(Err(message)) => {
            assert!(
                message.starts_with("fuzz.toml: "),
                "no file named: {message}"
            );
            assert!(parsed.is_err(), "detect refused what parse accepts");
        }
    }
    match parsed {
        Ok(lesson) => {
            let written = lesson.to_toml();
            let again = Lesson::parse(&written, "again.toml")
                .unwrap_or_else(|e| panic!("written lesson does not read back: {e}\n{written}"));
            assert!(
                same_lesson(&lesson, &again),
                "lesson round trip differs:\n{lesson:?}\n{again:?}\n{written}"
            );
            let robot = match lesson.robot_source().expect("a parsed lesson has a robot") {
                RobotSource::Spec(spec) => {
                    let _ = armlab::lesson::resolve_spec(&spec, Path::new("lessons/fuzz.toml"));
                    armlab::kinematics::models::built_in(&spec)
                }
                RobotSource::Embedded(model) => {
                    armlab::model_file::parse_model_text("lesson robot.toml", &model).ok()
                }
            };
            for i in 0..lesson.steps.len() {
                let _ = lesson.overlays(i);
                let Some(robot) = &robot else { continue };
                match lesson.step_q(i, robot, file) {
                    Ok(Some(q)) => assert_eq!(q.len(), robot.dof()),
                    Ok(None) => {}
                    Err(LessonError::Step { file: f, step, .. }) => {
                        assert_eq!(f, file);
                        assert_eq!(step, i + 1);
                    }
                    Err(e) => panic!("step_q: {e}"),
                }
            }
            if let Some(robot) = &robot {
                check_robot(robot);
            }
        }
        Err(e) => {
            let message = e.to_string();
            assert!(
                message.starts_with("fuzz.toml: "),
                "no file named: {message}"
            );
            match e {
                LessonError::Parse { line, .. } => {
                    let syntax = toml::from_str::<toml::Table>(text).is_err();
                    if syntax || line > 0 {
                        check_line(text, line, &message);
                    }
                }
                LessonError::Step { step, .. } => {
                    let steps = toml::from_str::<toml::Table>(text)
                        .ok()
                        .and_then(|t| t.get("steps").and_then(|s| s.as_array()).map(Vec::len))
                        .unwrap_or(0);
                    assert!(
                        step >= 1 && step <= steps,
                        "{message}: step {step} of {steps}"
                    );
                }
            }
        }
    }
}

/// A grade's bookkeeping: score of max, max the items, a mistake named only for a wrong item.
fn check_grade(g: &armlab::exercise::Grade, how: &str) {
    assert_eq!(
        g.max,
        g.items.len(),
        "{how}: max is not the number of items"
    );
    assert!(g.score <= g.max, "{how}: score {} of {}", g.score, g.max);
    assert_eq!(
        g.score,
        g.items.iter().filter(|i| i.correct).count(),
        "{how}: score is not the items right"
    );
    for i in &g.items {
        assert!(
            !(i.correct && i.mistake.is_some()),
            "{how}: {} is right with a mistake",
            i.item
        );
    }
}

/// Grades `answer` against `key`: a clean error or a well-kept grade.
fn grade_checked(
    key: &armlab::exercise::Key,
    answer: &armlab::exercise::Answer,
    how: &str,
) -> Option<armlab::exercise::Grade> {
    let g = armlab::exercise::grade(key, answer).ok()?;
    check_grade(&g, how);
    Some(g)
}

/// An exercise answer's rows (`exercise::parse_rows`): one row per line with data, as many
/// numbers as the line has fields, all finite; otherwise the error names the file and a line.
fn exercise_rows(text: &str) -> Option<Vec<Vec<f64>>> {
    match armlab::exercise::parse_rows(text, "answer.txt") {
        Ok(rows) => {
            let lines: Vec<usize> = text
                .lines()
                .map(|l| l.split('#').next().unwrap_or("").trim())
                .filter(|b| !b.is_empty())
                .map(|b| {
                    b.split(|c: char| c == ',' || c.is_whitespace())
                        .filter(|f| !f.is_empty())
                        .count()
                })
                .collect();
            assert_eq!(rows.len(), lines.len(), "rows are not the lines with data");
            for (row, n) in rows.iter().zip(&lines) {
                assert_eq!(row.len(), *n, "a row is not its line's fields");
                assert!(
                    row.iter().all(|v| v.is_finite()),
                    "a row not finite: {row:?}"
                );
            }
            Some(rows)
        }
        Err(e) => {
            let message = e.to_string();
            let line = message
                .strip_prefix("answer: answer.txt: line ")
                .and_then(|m| m.split(':').next())
                .and_then(|n| n.parse::<usize>().ok())
                .unwrap_or_else(|| panic!("no file and line in {message:?}"));
            check_line(text, line, &message);
            None
        }
    }
}

/// An exercise key (JSON, as `armlab exercise new` writes it) or a student's sheet file, and
/// optionally an answer after a 0xFF byte. A key that parses has a model that is a robot or a
/// clean error, grades its own answer (every kind but dh-table holds it) to full marks when its
/// tolerances are not negative, grades the answer given and answers of the wrong shape with
/// score in 0..=max or a clean error. A sheet file that parses gives a robot with finite FK or
/// a clean error, and its arm written as axes again reads back with the same FK. Answer rows
/// parse finite, as many as the lines with data; words are lower case without separators.
pub fn exercise(data: &[u8]) {
    use armlab::exercise::{Answer, Key, KeyAnswer, SheetFile, item_count, key_robot, parse_words};
    let (head, answer) = match data.iter().position(|&b| b == 0xff) {
        Some(i) => (&data[..i], std::str::from_utf8(&data[i + 1..]).ok()),
        None => (data, None),
    };
    let Ok(text) = std::str::from_utf8(head) else {
        return;
    };
    if let Some(answer) = answer {
        exercise_rows(answer);
        for w in parse_words(answer) {
            assert!(!w.is_empty() && !w.contains([',', '#']) && !w.contains(char::is_whitespace));
            assert!(
                !w.chars().any(|c| c.is_ascii_uppercase()),
                "{w:?} not lower case"
            );
        }
    }
    match SheetFile::parse("fuzz.json", text) {
        Ok(sheet) => {
            let _ = sheet.answer_file_name();
            match sheet.robot() {
                Ok(robot) => {
                    check_robot(&robot);
                    if let Ok(urdf) = armlab::exercise::sheet_file::axes_urdf(&robot) {
                        let again = armlab::urdf::parse_urdf(&urdf, Path::new("axes.urdf"))
                            .unwrap_or_else(|e| {
                                panic!("axes URDF does not read back: {e}\n{urdf}")
                            });
                        check_same_kinematics(&robot, &again, "axes URDF");
                    }
                }
                Err(e) => assert!(e.to_string().contains("sheet.urdf"), "{e}"),
            }
        }
        Err(e) => assert!(e.to_string().contains("fuzz.json"), "{e}"),
    }
    let Ok(key) = serde_json::from_str::<Key>(text) else {
        return;
    };
    let robot = match key_robot(&key) {
        Ok(r) => {
            check_robot(&r);
            Some(r)
        }
        Err(e) => {
            assert!(e.to_string().contains("key.model.toml"), "{e}");
            None
        }
    };
    let max = item_count(&key);
    let fair = key.tolerance.length >= 0.0 && key.tolerance.angle >= 0.0;
    let full = |a: &Answer, what: &str| {
        let g = grade_checked(&key, a, what);
        if fair {
            let g = g.unwrap_or_else(|| panic!("{what}: the key's own answer is refused"));
            assert_eq!(g.max, max, "{what}: max is not item_count");
            assert_eq!(
                g.score, g.max,
                "{what}: the key's own answer: {:?}",
                g.items
            );
        }
    };
    match &key.answer {
        KeyAnswer::DhTable => {
            if let Some(r) = &robot {
                grade_checked(&key, &Answer::Model(Box::new(r.clone())), "own table");
            }
        }
        KeyAnswer::Fk { t } => full(&Answer::Rows(t.iter().map(|r| r.to_vec()).collect()), "fk"),
        KeyAnswer::Ik { solutions, .. } => {
            let rows: Vec<Vec<f64>> = solutions.iter().map(|(q, _)| q.clone()).collect();
            let g = grade_checked(&key, &Answer::Rows(rows), "ik");
            if let (true, Some(r), Some(g)) = (fair, &robot, g)
                && solutions.iter().all(|(q, _)| q.len() == r.dof())
            {
                assert_eq!(g.score, g.max, "ik: the key's own solutions: {:?}", g.items);
            }
        }
        KeyAnswer::Workspace { postures, area, .. } => {
            let mut row: Vec<f64> = postures.iter().map(|&p| p as f64).collect();
            row.push(*area);
            if *area >= 0.0 {
                full(&Answer::Rows(vec![row]), "workspace");
            } else {
                grade_checked(&key, &Answer::Rows(vec![row]), "workspace");
            }
        }
        KeyAnswer::Redundancy { n, m, r, .. } => full(
            &Answer::Rows(vec![vec![*n as f64, *m as f64, *r as f64]]),
            "redundancy",
        ),
        KeyAnswer::Identifiability { parameters, .. } => {
            full(&Answer::Words(parameters.clone()), "identifiability")
        }
        // An orientation key's own reference need not match a fuzzed question: graded or
        // refused cleanly.
        KeyAnswer::Euler(_)
        | KeyAnswer::Compose(_)
        | KeyAnswer::AxisAngle(_)
        | KeyAnswer::Quaternion(_)
        | KeyAnswer::FromQuestion => {
            grade_checked(
                &key,
                &Answer::Rows(vec![vec![0.5; 9]]),
                "orientation numbers",
            );
        }
    }
    // Answers of every shape: graded or refused cleanly.
    grade_checked(&key, &Answer::Rows(Vec::new()), "no rows");
    grade_checked(&key, &Answer::Words(Vec::new()), "no words");
    if let Some(r) = &robot {
        grade_checked(&key, &Answer::Model(Box::new(r.clone())), "a model");
    }
    let Some(answer) = answer else {
        return;
    };
    // The answer as `armlab exercise check` reads it for this key.
    if key.kind.is_orientation() {
        orientation_answer(&key, answer);
        return;
    }
    match &key.answer {
        KeyAnswer::DhTable => match armlab::model_file::parse_model_text("answer.toml", answer) {
            Ok(a) => {
                grade_checked(&key, &Answer::Model(Box::new(a)), "answer model");
            }
            Err(e) => assert!(e.to_string().contains("answer.toml"), "{e}"),
        },
        KeyAnswer::Identifiability { .. } => {
            grade_checked(&key, &Answer::Words(parse_words(answer)), "answer words");
        }
        _ => {
            if let Some(rows) = exercise_rows(answer) {
                grade_checked(&key, &Answer::Rows(rows), "answer rows");
            }
        }
    }
}

/// An orientation answer file (`exercise::orientation::parse_answer`): graded or refused with
/// the file named and a line of the text.
fn orientation_answer(key: &armlab::exercise::Key, text: &str) {
    use armlab::exercise::{Answer, ExerciseError, orientation::parse_answer};
    match parse_answer(key.kind, text, "answer.txt") {
        Ok(a) => {
            grade_checked(key, &Answer::Orientation(a), "answer orientation");
        }
        Err(e) => {
            let message = e.to_string();
            assert!(message.contains("answer.txt"), "no file named: {message}");
            match e {
                ExerciseError::AnswerField { line, .. } => check_line(text, line, &message),
                other => panic!("not a field's error: {other}"),
            }
        }
    }
}

/// The names of a robot's joints in a calibration file: `q1..qn` styles are the `measurements`
/// target's; these are a cell's (UR-like names, a rail).
const JOINT_NAMES: [&str; 8] = [
    "shoulder_pan_joint",
    "shoulder_lift_joint",
    "elbow_joint",
    "wrist_1_joint",
    "wrist_2_joint",
    "wrist_3_joint",
    "rail",
    "J8",
];

/// Measurements equal (`exact`) or within a template's rounding (4 decimals of degrees and
/// millimetres, 9 of a quaternion), groups equal up to their labels.
fn same_measurements(
    a: &[armlab::calibration::Measurement],
    b: &[armlab::calibration::Measurement],
    exact: bool,
    how: &str,
) {
    use armlab::calibration::Measurement as M;
    assert_eq!(
        a.len(),
        b.len(),
        "{how}: {} measurements, then {}",
        a.len(),
        b.len()
    );
    let close = |x: f64, y: f64| {
        if exact {
            x == y
        } else {
            (x - y).abs() <= 1e-6 * (1.0 + x.abs())
        }
    };
    let group = |m: &M| match m {
        M::Pivot { point: g, .. } | M::Plane { plane: g, .. } | M::Sphere { sphere: g, .. } => {
            Some(*g)
        }
        _ => None,
    };
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        assert_eq!(x.kind(), y.kind(), "{how}: measurement {i} changed kind");
        for (qx, qy) in x.joint_vectors().iter().zip(y.joint_vectors()) {
            assert!(
                qx.iter().zip(qy).all(|(u, v)| close(*u, *v)),
                "{how}: measurement {i}: q {qx:?} then {qy:?}"
            );
        }
        let ok = match (x, y) {
            (
                M::Pose {
                    world_from_tool: p, ..
                },
                M::Pose {
                    world_from_tool: r, ..
                },
            ) => {
                let (hp, hr) = (p.to_homogeneous(), r.to_homogeneous());
                let scale = 1.0 + p.translation.vector.amax();
                (hp - hr).amax() <= if exact { 1e-9 * scale } else { 1e-6 * scale }
            }
            (M::Position { p, .. }, M::Position { p: r, .. }) => {
                p.iter().zip(r.iter()).all(|(u, v)| close(*u, *v))
            }
            (M::Distance { distance: u, .. }, M::Distance { distance: v, .. })
            | (M::Sphere { radius: u, .. }, M::Sphere { radius: v, .. }) => close(*u, *v),
            _ => true,
        };
        assert!(ok, "{how}: measurement {i}: {x:?} then {y:?}");
        for (j, (x2, y2)) in a.iter().zip(b).enumerate() {
            if let (Some(gx), Some(gx2), Some(gy), Some(gy2)) =
                (group(x), group(x2), group(y), group(y2))
            {
                assert_eq!(
                    gx == gx2,
                    gy == gy2,
                    "{how}: measurements {i} and {j} regrouped"
                );
            }
        }
    }
}

/// A calibration measurement file as a cell writes it: the first byte picks 1 to 8 joints, the
/// setup, whether the robot's joints have names (else `q1..qn`) and whether a sphere radius is
/// given; the second which joints are prismatic. Headered CSV (units, FIGAROH's columns, the
/// robot's joint names), robot_cal_tools YAML, plain rows and `template`'s files. What parses
/// holds the measurements of the setup, finite, that `write_measurements` writes and reads back
/// exactly and `template` (for the setup's own kind) within its rounding; the same text read as
/// desired poses (`parse_targets`) gives rigid, finite poses; errors name the file and a line.
pub fn calibration_files(data: &[u8]) {
    use armlab::calibration::{
        JointColumns, Measurement, Setup, parse_setup, parse_targets, template, write_measurements,
    };
    let Some((&[a, b], rest)) = data.split_first_chunk::<2>() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    let dof = 1 + usize::from(a % 8);
    let setup = Setup::ALL[usize::from(a / 8) % Setup::ALL.len()];
    let named = a / 56 % 2 == 1;
    let radius = (a / 112 % 2 == 0).then_some(0.025);
    let joints = JointColumns {
        names: (0..dof)
            .map(|k| {
                if named {
                    JOINT_NAMES[k].to_string()
                } else {
                    format!("q{}", k + 1)
                }
            })
            .collect(),
        angular: (0..dof).map(|k| b >> k & 1 == 0).collect(),
    };
    let file = "fuzz.csv";
    let check_error = |e: &armlab::calibration::MeasurementFileError| {
        assert_eq!(e.source_name, file);
        if e.line > 0 {
            check_line(text, e.line, &e.to_string());
        }
    };
    match parse_targets(text, file) {
        Ok(poses) => {
            for p in &poses {
                let h = p.to_homogeneous();
                assert!(h.iter().all(|v| v.is_finite()), "a target not finite");
                let r = p.rotation.matrix();
                let err = (r.transpose() * r - nalgebra::Matrix3::identity()).amax();
                assert!(err < 1e-6, "a target's rotation is not orthonormal ({err})");
            }
        }
        Err(e) => check_error(&e),
    }
    let parsed = match parse_setup(text, file, &joints, setup, radius) {
        Ok(f) => f,
        Err(e) => {
            check_error(&e);
            return;
        }
    };
    let ms = &parsed.measurements;
    assert!(!ms.is_empty(), "an empty file parsed");
    let kinds: &[&str] = match setup {
        Setup::Pose | Setup::Tracker => &["pose", "position"],
        Setup::Position => &["position"],
        Setup::Distance => &["distance"],
        Setup::Pivot => &["pivot"],
        Setup::Plane => &["plane"],
        Setup::Sphere => &["sphere"],
    };
    for m in ms {
        assert!(
            kinds.contains(&m.kind()),
            "a {} measurement for {setup:?}",
            m.kind()
        );
        assert_eq!(m.kind(), ms[0].kind(), "mixed kinds parsed");
        for q in m.joint_vectors() {
            assert_eq!(q.len(), dof);
            assert!(q.iter().all(|v| v.is_finite()), "q not finite: {q:?}");
        }
        let finite = match m {
            Measurement::Pose {
                world_from_tool, ..
            } => world_from_tool
                .to_homogeneous()
                .iter()
                .all(|v| v.is_finite()),
            Measurement::Position { p, .. } => p.iter().all(|v| v.is_finite()),
            Measurement::Distance { distance: v, .. } | Measurement::Sphere { radius: v, .. } => {
                v.is_finite() && *v > 0.0
            }
            Measurement::Pivot { .. } | Measurement::Plane { .. } => true,
        };
        assert!(finite, "a measurement with a non-finite value: {m:?}");
    }
    let written = write_measurements(ms);
    let again = parse_setup(&written, "written.csv", &joints, setup, radius)
        .unwrap_or_else(|e| panic!("written measurements do not read back: {e}\n{written}"));
    same_measurements(ms, &again.measurements, true, "write_measurements");
    // The template of the setup's own kind, for values a cell could log (its rounding is
    // 1e-4 degree and millimetre).
    let own = match setup {
        Setup::Pose => "pose",
        Setup::Position | Setup::Tracker => "position",
        _ => kinds[0],
    };
    let moderate = ms.iter().all(|m| {
        let big = |v: &f64| v.abs() > 1e6;
        !m.joint_vectors().iter().any(|q| q.iter().any(big))
            && match m {
                Measurement::Pose {
                    world_from_tool, ..
                } => !world_from_tool.translation.vector.iter().any(big),
                Measurement::Position { p, .. } => !p.iter().any(big),
                Measurement::Distance { distance: v, .. }
                | Measurement::Sphere { radius: v, .. } => !big(v) && *v > 1e-3,
                _ => true,
            }
    });
    if ms[0].kind() == own && moderate {
        let t = template(&joints, setup, ms);
        let again = parse_setup(&t, "template.csv", &joints, setup, None)
            .unwrap_or_else(|e| panic!("the template does not read back: {e}\n{t}"));
        same_measurements(ms, &again.measurements, false, "template");
    }
}

/// A live-class message (issue 50), as the server reads a client's ([`parse_client`]) and a
/// client reads the server's ([`parse_server`]); bytes that are not UTF-8 are read with their
/// bad sequences replaced. Never a panic. A client message that parses keeps its limits: at
/// most 64 KB, or a model file whose contents are at most 8 MB; a nickname of at most 40
/// characters without control characters; finite joint values; a poll with 2 to 16 choices and
/// a right choice among them, an exercise with none; and written back (`to_text`) it reads
/// again equal. A rejected message's error has words. A server message that parses writes back
/// and reads again equal.
///
/// [`parse_client`]: armlab::class::protocol::parse_client
/// [`parse_server`]: armlab::class::protocol::parse_server
pub fn class_message(data: &[u8]) {
    use armlab::class::protocol::{
        ClientMessage, MAX_CHOICES, MAX_MESSAGE_BYTES, MAX_MODEL_BYTES, MAX_NAME_CHARS,
        QuestionKind, parse_client, parse_server,
    };
    let text = String::from_utf8_lossy(data);
    match parse_client(&text) {
        Ok(m) => {
            match &m {
                ClientMessage::Model { text: contents, .. } => {
                    assert!(
                        contents.len() <= MAX_MODEL_BYTES,
                        "a model over 8 MB passed"
                    )
                }
                _ => assert!(
                    text.len() <= MAX_MESSAGE_BYTES,
                    "a message over 64 KB passed"
                ),
            }
            match &m {
                ClientMessage::Join(j) => {
                    if let Some(name) = &j.name {
                        assert!(name.chars().count() <= MAX_NAME_CHARS, "a long name passed");
                        assert!(!name.chars().any(char::is_control), "a control character");
                    }
                }
                ClientMessage::State { state } => {
                    assert!(state.q.iter().all(|v| v.is_finite()), "q not finite")
                }
                ClientMessage::Question(q) if q.kind == QuestionKind::Poll => {
                    assert!((2..=MAX_CHOICES).contains(&q.choices.len()), "poll choices");
                    assert!(
                        q.correct.is_none_or(|c| c < q.choices.len()),
                        "right choice"
                    );
                }
                ClientMessage::Question(q) => {
                    assert!(
                        q.choices.is_empty() && q.correct.is_none(),
                        "exercise choices"
                    )
                }
                _ => {}
            }
            let written = m.to_text();
            let back: ClientMessage = serde_json::from_str(&written)
                .unwrap_or_else(|e| panic!("a client message does not read back: {e}\n{written}"));
            assert_eq!(back, m, "a client message changed on writing");
        }
        Err(e) => assert!(!e.to_string().trim().is_empty(), "an error without words"),
    }
    if let Ok(m) = parse_server(&text) {
        let written = m.to_text();
        let back = parse_server(&written)
            .unwrap_or_else(|e| panic!("a server message does not read back: {e}\n{written}"));
        assert_eq!(back, m, "a server message changed on writing");
    }
}
