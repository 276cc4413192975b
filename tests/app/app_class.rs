//! The live classroom in the desktop app (issue 50), driven like its users over loopback: a
//! real class server (port 0, a temporary SQLite file), a teacher's app that joins it through
//! the toolbar's "Start class" and the Class window's "Join as teacher", and two students'
//! apps. The link threads work while the test steps every app's frames, until what is
//! checked holds or a timeout passes.
//!
//! Checked against what the test itself sets and knows: the joint vector the teacher's app is
//! given (the students' q equal to it within 1e-12), the labels a user reads ("exploring on
//! your own", "answered 1 of 2"), and the textbook's eight postures of the Puma at a generic
//! pose (the poll's choices).

use armlab::app::AppUi;
use armlab::app::action::Action;
use armlab::app::class::link;
use armlab::app::state::AppState;
use armlab::class::protocol::{QuestionKind, Role};
use armlab::class_server::{ServerHandle, ServerOptions};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};
use std::time::{Duration, Instant};

type App = Harness<'static, AppUi>;

/// How long a condition may take to hold (the link threads on a loaded two-core machine).
const TIMEOUT: Duration = Duration::from_secs(30);

fn harness(app: AppUi) -> App {
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_ui_state(|ui, app: &mut AppUi| app.show(ui, None), app);
    h.step();
    h
}

/// A class server on a free loopback port with its data in a new temporary file.
fn server() -> (ServerHandle, std::path::PathBuf) {
    let data = std::env::temp_dir().join(format!(
        "armlab-app-class-{}-{}.sqlite",
        std::process::id(),
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .unwrap()
            .as_nanos()
    ));
    let _ = std::fs::remove_file(&data);
    let options = ServerOptions {
        port: 0,
        data: data.clone(),
        new_session: true,
        ..ServerOptions::default()
    };
    (
        armlab::class_server::start(options).expect("the server starts"),
        data,
    )
}

/// The teacher's app and two students' apps, in one class.
struct Room {
    teacher: App,
    a: App,
    b: App,
}

impl Room {
    /// Steps every app's frames until `done` holds (panics after [`TIMEOUT`], saying `what`).
    fn pump(&mut self, what: &str, mut done: impl FnMut(&Room) -> bool) {
        let start = Instant::now();
        loop {
            for h in [&mut self.teacher, &mut self.a, &mut self.b] {
                h.step();
            }
            if done(self) {
                return;
            }
            assert!(start.elapsed() < TIMEOUT, "{what}: not within {TIMEOUT:?}");
            std::thread::sleep(Duration::from_millis(5));
        }
    }
}

/// Steps `h` alone until `done` holds.
fn pump_one(h: &mut App, what: &str, mut done: impl FnMut(&App) -> bool) {
    let start = Instant::now();
    while !done(h) {
        h.step();
        assert!(start.elapsed() < TIMEOUT, "{what}: not within {TIMEOUT:?}");
        std::thread::sleep(Duration::from_millis(5));
    }
}

/// Clicks the widget labelled `label` with the pointer, moved first to an empty corner of the
/// 3D view (a tooltip left open where the pointer was would take the click).
fn click(h: &mut App, label: &str) {
    h.event(egui::Event::PointerMoved(egui::pos2(900.0, 700.0)));
    h.step();
    h.get_by_label(label).click();
}

/// The toolbar's "Start class" (under View at 1280 px) opens the Class window.
fn open_class_window(h: &mut App) {
    h.get_by_label("View").click();
    steps(h, 3);
    h.get_by_label("Start class").click();
    steps(h, 3);
}

fn steps(h: &mut App, n: usize) {
    for _ in 0..n {
        h.step();
    }
}

fn same_q(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-12)
}

fn shows(h: &App, text: &str) -> bool {
    h.query_all_by_label_contains(text).next().is_some()
}

/// A student's app joined with the server's code.
fn student(server: &ServerHandle, name: &str) -> App {
    let mut app = AppUi::new(AppState::from_spec("planar2").unwrap());
    let ws = format!("ws://{}/ws", server.addr);
    app.class
        .connect_student(link::open(&ws).unwrap(), &server.code, name, None);
    harness(app)
}

/// The teacher joins through the toolbar's entry and the teacher link; two students join.
fn join(server: &ServerHandle) -> Room {
    let mut teacher = harness(AppUi::new(AppState::from_spec("puma560").unwrap()));
    open_class_window(&mut teacher);
    teacher.get_by_label("Teacher link:").focus();
    teacher.step();
    teacher
        .get_by_label("Teacher link:")
        .type_text(&server.teacher_url);
    teacher.step();
    teacher.get_by_label("Join as teacher").click();
    let (a, b) = (student(server, "Ada"), student(server, "Bo"));
    let mut room = Room { teacher, a, b };
    room.pump("everyone joined", |r| {
        r.teacher.state().class.connected()
            && r.teacher.state().class.roster.joined == 2
            && r.a.state().class.connected()
            && r.b.state().class.connected()
    });
    assert_eq!(room.teacher.state().class.role(), Some(Role::Teacher));
    assert!(shows(&room.teacher, "2 student(s) joined"));
    room
}

/// The teacher moves the arm; a student explores, follows again, explores, and is brought
/// back. Returns the teacher's q at the end.
fn follow_and_explore(room: &mut Room) -> Vec<f64> {
    let q = vec![0.3, 0.8, -1.0, 0.4, 0.6, 0.2];
    room.teacher.state_mut().apply(Action::SetQ(q.clone()));
    room.pump("the students follow", |r| {
        same_q(r.a.state().state.q(), &q) && same_q(r.b.state().state.q(), &q)
    });
    assert_eq!(
        room.a.state().state.spec(),
        "puma560",
        "the teacher's robot"
    );
    assert!(shows(&room.a, "following the teacher"));
    // A student moves a joint: exploring on their own, and the teacher's next move waits.
    room.a.state_mut().apply(Action::SetJoint(0, -0.5));
    room.pump("exploring", |r| shows(&r.a, "exploring on your own"));
    let q2 = vec![0.2, 0.7, -0.9, 0.3, 0.5, 0.1];
    room.teacher.state_mut().apply(Action::SetQ(q2.clone()));
    room.pump("b follows", |r| same_q(r.b.state().state.q(), &q2));
    let explorer = room.a.state().state.q()[0];
    assert_eq!(explorer, -0.5, "the explorer keeps their own arm");
    // "Follow the teacher": back to the teacher's q at once.
    room.a.get_by_label("Follow the teacher").click();
    room.pump("follow again", |r| same_q(r.a.state().state.q(), &q2));
    // Exploring again; the teacher's "Bring everyone back" brings them back.
    room.a.state_mut().apply(Action::SetJoint(1, 0.1));
    room.pump("exploring again", |r| shows(&r.a, "exploring on your own"));
    click(&mut room.teacher, "Bring everyone back");
    room.pump("brought back", |r| {
        same_q(r.a.state().state.q(), &q2) && shows(&r.a, "following the teacher")
    });
    q2
}

/// The posture poll: the Puma at a generic pose has eight postures (the textbook's shoulder x
/// elbow x wrist); one student answers, the teacher sees it counted. Returns its id.
fn poll(room: &mut Room) -> u64 {
    click(&mut room.teacher, "Ask: which posture is this?");
    room.pump("the poll arrives", |r| {
        r.a.state().class.question.is_some() && r.b.state().class.question.is_some()
    });
    let question = room.a.state().class.question.clone().unwrap();
    assert_eq!(question.kind, QuestionKind::Poll);
    assert_eq!(question.choices.len(), 8, "{:?}", question.choices);
    // the question window's first frame sizes it: a frame more shows its buttons
    steps(&mut room.a, 2);
    room.a.get_by_label(&question.choices[3]).click();
    room.pump("the answer counted", |r| {
        shows(&r.teacher, "answered 1 of 2")
    });
    let tally = room.teacher.state().class.tally.clone().unwrap();
    assert_eq!(tally.counts.iter().sum::<usize>(), 1);
    assert_eq!(tally.counts[3], 1, "{tally:?}");
    assert!(shows(&room.a, "answer sent"));
    question.id
}

/// A DH-table question, with feedback: the sheet opens in the student's Exercise tab, "Send
/// answer" sends the typed table (all zeros: the Puma's table has a2, a3, d4 and alphas of +-90
/// degrees, so nothing can be entirely right), the teacher counts it with its mistakes; closed,
/// the student's inputs are off, and "Bring everyone back" returns them to the teacher's robot
/// and `q`.
fn exercise(room: &mut Room, poll_id: u64, q: &[f64]) {
    click(&mut room.teacher, "Ask this exercise");
    room.pump("the sheet opens", |r| {
        let sheet = r.a.state().tabs.exercise.sheet.as_ref();
        sheet.is_some_and(|s| s.class.is_some()) && r.a.state().tab == armlab::app::tabs::EXERCISE
    });
    let id = room.a.state().class.question.as_ref().unwrap().id;
    assert_ne!(id, poll_id);
    steps(&mut room.a, 2);
    // below the table: scrolled into view as a user would
    room.a.get_by_label("Send answer").scroll_to_me();
    steps(&mut room.a, 3);
    click(&mut room.a, "Send answer");
    room.pump("the exercise counted", |r| {
        let t = r.teacher.state().class.tally.as_ref();
        t.is_some_and(|t| t.id == id && t.answered == 1) && shows(&r.a, "answer sent: score")
    });
    let tally = room.teacher.state().class.tally.clone().unwrap();
    assert_eq!(tally.correct_percent, 0.0, "{tally:?}");
    assert!(!tally.mistakes.is_empty(), "{tally:?}");
    assert!(shows(&room.teacher, "answered 1 of 2"));
    click(&mut room.teacher, "Close question");
    room.pump("closed", |r| {
        shows(&r.a, "The teacher closed the question.")
    });
    steps(&mut room.a, 2);
    let send = room.a.get_by_label("Send answer");
    assert!(send.accesskit_node().is_disabled(), "inputs off");
    click(&mut room.teacher, "Bring everyone back");
    room.pump("following after the question", |r| {
        r.a.state().state.spec() == "puma560" && same_q(r.a.state().state.q(), q)
    });
    let a = room.a.state();
    assert!(
        a.tabs.exercise.sheet.is_none(),
        "the question's sheet closed"
    );
    assert!(!a.state.hidden.exam, "nothing hidden any more");
}

#[test]
fn students_follow_explore_come_back_and_answer_the_teachers_questions() {
    let (server, data) = server();
    let mut room = join(&server);
    let q = follow_and_explore(&mut room);
    let poll_id = poll(&mut room);
    exercise(&mut room, poll_id, &q);
    export(&mut room, &data);
    let _ = server.stop();
    let _ = std::fs::remove_file(&data);
}

/// Saves to one path, as a file dialog would where the user chose it.
struct SaveTo(std::path::PathBuf);

impl armlab::app::file_picker::FilePicker for SaveTo {
    fn available(&self) -> bool {
        true
    }
    fn open(&mut self, _: armlab::app::file_picker::FileKind) -> Option<std::path::PathBuf> {
        None
    }
    fn save(
        &mut self,
        _: armlab::app::file_picker::FileKind,
        _: &str,
    ) -> Option<std::path::PathBuf> {
        Some(self.0.clone())
    }
}

/// "Export CSV" in the teacher's Class window: the file the dialog names holds the header and
/// one line per answer the students sent (the poll's and the exercise's, both by student 1).
fn export(room: &mut Room, data: &std::path::Path) {
    let csv = data.with_extension("csv");
    let _ = std::fs::remove_file(&csv);
    room.teacher.state_mut().file_picker = Box::new(SaveTo(csv.clone()));
    click(&mut room.teacher, "Export CSV");
    room.pump("the CSV saved", |_| csv.exists());
    let text = std::fs::read_to_string(&csv).unwrap();
    let records = csv_records(&text);
    assert_eq!(
        records[0][..6],
        ["session", "question", "kind", "student", "name", "answer"]
    );
    assert_eq!(records.len(), 3, "{text}");
    let kinds: Vec<&str> = records[1..].iter().map(|r| r[2].as_str()).collect();
    assert_eq!(kinds, ["poll", "dh-table"]);
    assert!(records[1..].iter().all(|r| r[3] == "1"), "{text}");
    // the poll's answer is the choice the student clicked
    assert_eq!(records[1][5], "3");
    let _ = std::fs::remove_file(&csv);
}

/// The records of RFC 4180 CSV text: fields split at commas outside quotes, `""` a quote,
/// line breaks inside quotes kept in the field.
fn csv_records(text: &str) -> Vec<Vec<String>> {
    let (mut records, mut record, mut field) = (Vec::new(), Vec::new(), String::new());
    let (mut quoted, mut chars) = (false, text.chars().peekable());
    while let Some(c) = chars.next() {
        match (quoted, c) {
            (true, '"') if chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            (_, '"') => quoted = !quoted,
            (false, ',') => record.push(std::mem::take(&mut field)),
            (false, '\n') => {
                record.push(std::mem::take(&mut field));
                records.push(std::mem::take(&mut record));
            }
            (false, '\r') => {}
            _ => field.push(c),
        }
    }
    if !field.is_empty() || !record.is_empty() {
        record.push(field);
        records.push(record);
    }
    records
}

#[test]
fn the_toolbar_has_start_class_and_a_wrong_token_is_a_message() {
    let (server, data) = server();
    let mut h = harness(AppUi::new(AppState::from_spec("planar2").unwrap()));
    // 1920 px: in the toolbar's row; 1280 px: the View menu holds it, the row as before.
    h.set_size(egui::vec2(1920.0, 800.0));
    steps(&mut h, 3);
    assert!(
        h.query_by_label("Start class").is_some(),
        "in the row at 1920 px"
    );
    h.set_size(egui::vec2(1280.0, 800.0));
    steps(&mut h, 3);
    assert!(
        h.query_by_label("Start class").is_none(),
        "under View at 1280 px"
    );
    assert!(
        h.state().rects.top.max.x <= 1280.5,
        "{:?}",
        h.state().rects.top
    );
    open_class_window(&mut h);
    assert!(shows(&h, "Join as teacher"));
    let wrong = format!(
        "http://{}/?token=00000000000000000000000000000000",
        server.addr
    );
    h.state_mut()
        .apply(Action::Class(armlab::app::class::ClassAction::JoinTeacher(
            wrong,
        )));
    pump_one(&mut h, "the refusal", |h| {
        matches!(
            h.state().class.connection,
            armlab::app::class::Connection::Refused(_)
        )
    });
    let last = h.state().state.last_message().unwrap().text.clone();
    assert!(last.starts_with("class:"), "{last}");
    assert_eq!(h.state().state.robot().dof(), 2, "the app keeps its state");
    let _ = server.stop();
    let _ = std::fs::remove_file(&data);
}

/// A student page opened without a nickname: the prompt's field has the focus, a whole
/// sentence typed into it stays whole, and Enter joins with it (the prompt closes, the client
/// connects as that student).
#[test]
fn the_nickname_prompt_takes_a_typed_sentence_and_enter_joins() {
    let (server, _data) = server();
    let mut app = AppUi::new(AppState::from_spec("planar2").unwrap());
    app.class.prompt = Some(armlab::app::class::NamePrompt {
        ws: format!("ws://{}/ws", server.addr),
        code: server.code.clone(),
        resume: None,
    });
    let mut h = harness(app);
    steps(&mut h, 2);
    let name = "Chen, who types whole sentences";
    // no click first: the field has the focus when the prompt opens
    h.event(egui::Event::Text(name.into()));
    h.step();
    h.step();
    assert_eq!(h.state().class.form.nickname, name);
    h.key_press(egui::Key::Enter);
    pump_one(&mut h, "joined with the typed name", |h| {
        h.state().class.prompt.is_none() && h.state().class.connected()
    });
    assert_eq!(h.state().class.role(), Some(Role::Student));
    server.stop().unwrap();
}
