//! Issue 47: the Exercise tab takes orientation answers as it takes DH tables. A key or a sheet
//! of the kinds euler, compose, axis-angle and quaternion opens without touching the arm, shows
//! its question and one field per line of the answer file, with a degrees toggle; Check grades
//! a key's answer (practice), Save answer writes a sheet's answer file (exam). The answers are
//! worked out here from the key's plain JSON, and typed key by key into the fields as a
//! keyboard does, with no shortcut firing on the way.

use armlab::app::AppUi;
use armlab::app::state::AppState;
use armlab::exercise::{Kind, SheetFile, generate};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};
use serde_json::Value;

fn harness(app: AppUi) -> Harness<'static, AppUi> {
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_ui_state(|ui, app: &mut AppUi| app.show(ui, None), app);
    h.run();
    h
}

/// Types `text` as a keyboard does: per character its key down, its text, its key up, a frame
/// each (a shortcut reads the key; a text field takes the text).
fn type_line(h: &mut Harness<'static, AppUi>, text: &str) {
    for c in text.chars() {
        let key = match c {
            ' ' => Some(egui::Key::Space),
            _ => egui::Key::from_name(&c.to_ascii_uppercase().to_string()),
        };
        if let Some(k) = key {
            h.key_down(k);
        }
        h.event(egui::Event::Text(c.to_string()));
        if let Some(k) = key {
            h.key_up(k);
        }
        h.run();
    }
}

/// What a stray shortcut would change.
fn settings(app: &AppUi) -> String {
    format!(
        "{:?} {:?} {:?} {} {:?} {}",
        app.state.display,
        app.layout,
        app.tabs.view3d.camera,
        app.show_help,
        app.state.q(),
        app.state.robot().name
    )
}

/// Clicks the field named `name` and types `text` into it.
fn fill(h: &mut Harness<'static, AppUi>, name: &str, text: &str) {
    h.get_by_label(name).click();
    h.run();
    type_line(h, text);
    h.key_press(egui::Key::Escape);
    h.run();
}

fn entry(m: &Value, i: usize, j: usize) -> f64 {
    m[i][j].as_f64().unwrap()
}

/// A regular ZYZ (2.19), ZXZ (Problem 2.1) or RPY (2.22) sheet's angles in degrees, written
/// out here.
fn euler_degrees(conv: &str, m: &Value) -> [f64; 3] {
    let r = |i, j| entry(m, i, j);
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

/// The first regular euler sheet of a class: its key as armlab writes it and as plain JSON.
fn regular_euler_key() -> (String, Value) {
    for student in 1..=30 {
        let key =
            serde_json::to_string(&generate(Kind::Euler, None, 31, student).unwrap().key).unwrap();
        let v: Value = serde_json::from_str(&key).unwrap();
        let m = &v["matrix"];
        let middle = if v["convention"] == "rpy" {
            entry(m, 2, 1).hypot(entry(m, 2, 2))
        } else {
            entry(m, 0, 2).hypot(entry(m, 1, 2))
        };
        if middle > 0.3 {
            return (key, v);
        }
    }
    panic!("no regular sheet");
}

/// Practice: a key of Euler angles opens over the Puma without loading an arm; the answer
/// typed as one line in degrees gets full marks; the angles of the transpose are named.
#[test]
fn an_euler_key_is_answered_in_one_typed_line_and_checked() {
    let (key, v) = regular_euler_key();
    let mut app = AppUi::new(AppState::from_spec("puma560").unwrap());
    let q = app.state.q().to_vec();
    app.open_exercise_text("key.json", &key).unwrap();
    assert_eq!(app.tab, armlab::app::tabs::EXERCISE);
    assert_eq!(app.state.robot().dof(), 6, "the arm stays");
    assert_eq!(app.state.q(), q.as_slice());
    assert!(!app.state.hidden.exam && !app.state.hidden.dh_table);
    let mut h = harness(app);
    assert!(h.query_by_label("angles in degrees").is_some());
    let before = settings(h.state());
    // the field is wide enough for the line (in a grid it was 40 points: found live)
    let field = h.get_by_label("answer: phi theta psi");
    let width = field.accesskit_node().bounding_box().unwrap().width();
    assert!(width >= 250.0, "the answer field is {width} points wide");
    let a = euler_degrees(v["convention"].as_str().unwrap(), &v["matrix"]);
    let typed = format!("{:.3}, {:.3} {:.3}", a[0], a[1], a[2]);
    fill(&mut h, "answer: phi theta psi", &typed);
    assert_eq!(
        h.state().tabs.exercise.sheet.as_ref().unwrap().lines[0],
        typed
    );
    assert_eq!(
        settings(h.state()),
        before,
        "a key typed into the field fired a shortcut"
    );
    h.get_by_label("Check").click();
    h.run();
    assert!(h.query_by_label("score 1 of 1").is_some());
    // the angles in radians with the degrees toggle still on: radians read as degrees
    let open = h.state_mut().tabs.exercise.sheet.as_mut().unwrap();
    open.lines[0] = a.map(f64::to_radians).map(|x| format!("{x:.6}")).join(" ");
    h.run();
    h.get_by_label("Check").click();
    h.run();
    assert!(h.query_by_label("score 0 of 1").is_some());
    assert!(
        h.query_by_label_contains("radians read as degrees")
            .is_some(),
        "no mistake named"
    );
    // the toggle off: the same line is right
    h.get_by_label("angles in degrees").click();
    h.run();
    h.get_by_label("Check").click();
    h.run();
    assert!(h.query_by_label("score 1 of 1").is_some());
    // a bad line is said with its field
    let open = h.state_mut().tabs.exercise.sheet.as_mut().unwrap();
    open.lines[0] = "0.1 zero 0.3".into();
    h.run();
    h.get_by_label("Check").click();
    h.run();
    assert!(h.query_by_label_contains("field theta").is_some());
}

/// Practice: a compose key takes the matrix row by row, one typed line per row.
#[test]
fn a_compose_key_takes_three_typed_rows() {
    let key = serde_json::to_string(&generate(Kind::Compose, None, 8, 3).unwrap().key).unwrap();
    let v: Value = serde_json::from_str(&key).unwrap();
    // the product, by hand: current steps on the right, fixed steps on the left
    let mut r = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for s in v["sequence"].as_array().unwrap() {
        let (sn, c) = s["angle"].as_f64().unwrap().sin_cos();
        let e = match s["axis"].as_str().unwrap() {
            "x" => [[1.0, 0.0, 0.0], [0.0, c, -sn], [0.0, sn, c]],
            "y" => [[c, 0.0, sn], [0.0, 1.0, 0.0], [-sn, 0.0, c]],
            _ => [[c, -sn, 0.0], [sn, c, 0.0], [0.0, 0.0, 1.0]],
        };
        let (a, b) = if s["frame"] == "current" {
            (r, e)
        } else {
            (e, r)
        };
        r = [0, 1, 2].map(|i| [0, 1, 2].map(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()));
    }
    let mut app = AppUi::new(AppState::from_spec("planar3").unwrap());
    app.open_exercise_text("key.json", &key).unwrap();
    assert_eq!(app.state.robot().dof(), 3, "the arm stays");
    let mut h = harness(app);
    assert!(
        h.query_by_label("angles in degrees").is_none(),
        "a matrix has no angle"
    );
    let before = settings(h.state());
    for (i, row) in r.iter().enumerate() {
        let k = i + 1;
        let name = format!("answer: row {k}: r{k}1 r{k}2 r{k}3");
        fill(
            &mut h,
            &name,
            &format!("{:.4} {:.4} {:.4}", row[0], row[1], row[2]),
        );
    }
    assert_eq!(settings(h.state()), before);
    h.get_by_label("Check").click();
    h.run();
    assert!(h.query_by_label("score 1 of 1").is_some());
}

/// Exam: an axis-angle sheet opens without its key and without touching the arm; the typed
/// line is saved as `student-NN.txt` beside the sheet, `# deg` first, and the teacher's key
/// gives it full marks.
#[test]
fn an_axis_angle_exam_saves_the_answer_file() {
    let dir = std::env::temp_dir().join(format!("armlab-exam-aa-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let student = dir.join("student-04");
    std::fs::create_dir_all(&student).unwrap();
    let sheet = (1..=20)
        .map(|s| generate(Kind::AxisAngle, None, 5, s).unwrap())
        .find(|s| {
            let m = s.key.matrix.unwrap();
            let c = (m[0][0] + m[1][1] + m[2][2] - 1.0) / 2.0;
            c.abs() < 0.9 // away from theta = 0 and pi
        })
        .unwrap();
    let path = student.join("sheet.json");
    let file = SheetFile::of(&sheet).unwrap();
    std::fs::write(&path, serde_json::to_string(&file).unwrap()).unwrap();
    // theta and r by (2.27)-(2.28), here
    let m = sheet.key.matrix.unwrap();
    let theta = ((m[0][0] + m[1][1] + m[2][2] - 1.0) / 2.0).acos();
    let s2 = 2.0 * theta.sin();
    let r = [
        (m[2][1] - m[1][2]) / s2,
        (m[0][2] - m[2][0]) / s2,
        (m[1][0] - m[0][1]) / s2,
    ];
    let mut app = AppUi::new(AppState::from_spec("puma560").unwrap());
    app.load(path.to_str().unwrap());
    assert!(app.state.hidden.exam);
    assert_eq!(app.state.robot().dof(), 6, "the arm stays");
    let opened = app.tabs.exercise.sheet.as_ref().unwrap();
    assert!(opened.key.is_none());
    let answer_path = std::path::PathBuf::from(&opened.answer_path);
    assert_eq!(
        answer_path.file_name().unwrap().to_str().unwrap(),
        format!("student-{:02}.txt", sheet.key.student)
    );
    let mut h = harness(app);
    assert!(
        h.query_by_label("Check").is_none(),
        "an exam grades nothing"
    );
    let before = settings(h.state());
    let typed = format!(
        "{:.3} {:.5} {:.5} {:.5}",
        theta.to_degrees(),
        r[0],
        r[1],
        r[2]
    );
    fill(&mut h, "answer: theta x y z", &typed);
    assert_eq!(settings(h.state()), before);
    h.get_by_label("Save answer").click();
    h.run();
    let written = std::fs::read_to_string(&answer_path).unwrap();
    assert_eq!(written, format!("# deg\n{typed}\n"));
    // the teacher's key grades it: full marks
    let a = armlab::exercise::orientation::parse_answer(Kind::AxisAngle, &written, "a").unwrap();
    let g = armlab::exercise::grade(&sheet.key, &armlab::exercise::Answer::Orientation(a)).unwrap();
    assert_eq!((g.score, g.max), (1, 1), "{:?}", g.items);
    let _ = std::fs::remove_dir_all(&dir);
}

/// An euler sheet's matrix is an indented code block in its Markdown: the tab shows each of its
/// rows as one monospaced line with its spacing kept (the columns line up), and nothing of the
/// markup. The rows are read here from the question's text. (A code block drawn as such has a
/// copy button whose icon no font of the app has: the harness panics on a missing glyph.)
#[test]
fn an_euler_sheets_matrix_rows_show_as_aligned_lines() {
    let sheet = generate(Kind::Euler, None, 11, 1).unwrap();
    let file = SheetFile::of(&sheet).unwrap();
    let rows: Vec<&str> = file
        .question
        .lines()
        .filter(|l| l.starts_with("    ["))
        .map(str::trim)
        .collect();
    assert_eq!(rows.len(), 3, "{}", file.question);
    let mut app = AppUi::new(AppState::from_spec("planar3").unwrap());
    app.open_exercise_text("sheet.json", &serde_json::to_string(&file).unwrap())
        .unwrap();
    let h = harness(app);
    for row in rows {
        let shown = row.replace(' ', "\u{a0}");
        assert!(
            h.query_all_by_label(&shown).next().is_some(),
            "row {row:?} not shown as one line"
        );
    }
    assert!(h.query_all_by_label_contains("# Euler").next().is_none());
    assert!(
        h.query_all_by_label("Euler angles of a rotation matrix")
            .next()
            .is_some()
    );
}

/// The code-block rewrite on its own: an indented block and a fenced one with a backtick become
/// inline code lines (spaces kept as no-break spaces, a fence longer than the line's backticks),
/// the text around them unchanged; a text without a code block comes back borrowed.
#[test]
fn code_blocks_become_lines_of_inline_code() {
    use armlab::app::markdown::without_code_blocks;
    let plain = "# Title\n\n| a | b |\n|---|---|\n| 1 | 2 |\n";
    assert!(matches!(
        without_code_blocks(plain),
        std::borrow::Cow::Borrowed(_)
    ));
    let text = "Rows:\n\n    [ 1.0  0.0 ]\n    [ 0.0  1.0 ]\n\nthen\n\n```\na `b` c\n```\nend\n";
    let nb = '\u{a0}';
    let want = format!(
        "Rows:\n\n`[{nb}1.0{nb}{nb}0.0{nb}]`\\\n`[{nb}0.0{nb}{nb}1.0{nb}]`\n\nthen\n\n``a{nb}`b`{nb}c``\n\nend\n"
    );
    assert_eq!(without_code_blocks(text), want);
}

/// In projector mode the sheet's question grows with the rest of the window: a matrix row and a
/// paragraph of the question are drawn at least 1.3 times as tall as in the normal mode (the
/// window's text grows 1.4 times; the question once stayed at the 16 px floor, smaller than the
/// tab's own buttons).
#[test]
fn a_sheets_question_grows_in_projector_mode() {
    let sheet = generate(Kind::Euler, None, 11, 1).unwrap();
    let file = SheetFile::of(&sheet).unwrap();
    let row = file
        .question
        .lines()
        .find(|l| l.starts_with("    ["))
        .unwrap()
        .trim()
        .replace(' ', "\u{a0}");
    let heights = [false, true].map(|projector| {
        let mut app = AppUi::new(AppState::from_spec("planar3").unwrap());
        app.layout.projector = projector;
        app.open_exercise_text("sheet.json", &serde_json::to_string(&file).unwrap())
            .unwrap();
        let h = harness(app);
        let row_height = h.get_by_label(&row).rect().height();
        let button_height = h.get_by_label("Open sheet").rect().height();
        (row_height, button_height)
    });
    let (normal, projector) = (heights[0], heights[1]);
    assert!(
        projector.0 >= 1.3 * normal.0,
        "matrix row {} px tall in projector mode, {} px in normal mode",
        projector.0,
        normal.0
    );
    assert!(
        projector.0 >= 0.9 * projector.1 - 8.0,
        "the question's text ({} px) is well under the buttons' ({} px)",
        projector.0,
        projector.1
    );
}
