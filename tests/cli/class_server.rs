//! The class server (issue 50) with real WebSocket clients on loopback (tokio-tungstenite): a
//! teacher and ten students following, a late join, a DH-table question answered right and
//! wrong and graded with its named mistakes, a poll's counts, a restart keeping everything, the
//! security rules (a student driving, wrong tokens and codes, the attempt limit per address,
//! oversized and malformed messages, a flood, markup in a nickname), the CSV export, and the
//! `armlab class serve` binary itself (its first lines; a kill and restart losing no answer
//! that was acknowledged).
//!
//! Expected values are made here independently: the exercise's key by `exercise::generate` with
//! the seed the question named, the counts from what the students sent.

use armlab::class::protocol::{
    ClassState, ClientMessage, Join, QuestionKind, QuestionOut, QuestionRequest, RobotRef, Role,
    ServerMessage, Tally, Welcome,
};
use armlab::class_server::{ServerHandle, ServerOptions, start};
use armlab::exercise::{KEY_FORMAT, Kind, SheetFile, generate, key_robot};
use armlab::kinematics::models::built_in;
use futures_util::{SinkExt, StreamExt};
use std::path::{Path, PathBuf};
use std::time::Duration;
use tokio::net::TcpStream;
use tokio_tungstenite::tungstenite::Message;
use tokio_tungstenite::{MaybeTlsStream, WebSocketStream, connect_async};

/// How long a client waits for a message it expects.
const WAIT: Duration = Duration::from_secs(10);

/// A fresh data file in a folder of its own.
fn data_file(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("armlab-class-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir.join("class.sqlite")
}

/// A server on a free loopback port with `data`.
fn server(data: &Path, show_names: bool) -> ServerHandle {
    start(ServerOptions {
        port: 0,
        data: data.to_path_buf(),
        // A folder without a web build: `/` says how to make one.
        web: data.parent().map(PathBuf::from),
        show_names,
        ..ServerOptions::default()
    })
    .expect("the server starts")
}

/// A WebSocket client of the class.
struct Client {
    ws: WebSocketStream<MaybeTlsStream<TcpStream>>,
}

impl Client {
    /// Connects to `/ws` of `server`.
    async fn connect(server: &ServerHandle) -> Client {
        let url = format!("ws://{}/ws", server.addr);
        let (ws, _) = connect_async(url).await.expect("the WebSocket connects");
        Client { ws }
    }

    /// Sends a message.
    async fn send(&mut self, m: &ClientMessage) {
        self.send_text(&m.to_text()).await;
    }

    /// Sends a text frame as it is (a failure after [`WAIT`]: a server that stopped reading
    /// must not hang the test).
    async fn send_text(&mut self, t: &str) {
        tokio::time::timeout(WAIT, self.ws.send(Message::text(t)))
            .await
            .expect("sent in time")
            .expect("sent");
    }

    /// The next text frame, raw.
    async fn recv_text(&mut self) -> String {
        loop {
            let m = tokio::time::timeout(WAIT, self.ws.next())
                .await
                .expect("a message in time")
                .expect("the connection is open")
                .expect("a frame");
            match m {
                Message::Text(t) => return t.to_string(),
                Message::Close(_) => panic!("the server closed the connection"),
                _ => {}
            }
        }
    }

    /// The next message.
    async fn recv(&mut self) -> ServerMessage {
        let t = self.recv_text().await;
        armlab::class::protocol::parse_server(&t).unwrap_or_else(|e| panic!("{e}: {t}"))
    }

    /// The first message `pick` takes, skipping the others.
    async fn recv_until<T>(&mut self, mut pick: impl FnMut(ServerMessage) -> Option<T>) -> T {
        loop {
            if let Some(t) = pick(self.recv().await) {
                return t;
            }
        }
    }

    /// The raw text of the first message `pick` takes (as the server wrote it).
    async fn recv_raw_until(&mut self, mut pick: impl FnMut(&ServerMessage) -> bool) -> String {
        loop {
            let t = self.recv_text().await;
            let m =
                armlab::class::protocol::parse_server(&t).unwrap_or_else(|e| panic!("{e}: {t}"));
            if pick(&m) {
                return t;
            }
        }
    }

    /// The next error's words (skipping other messages).
    async fn error(&mut self) -> String {
        self.recv_until(|m| match m {
            ServerMessage::Error { message } => Some(message),
            _ => None,
        })
        .await
    }

    /// The messages that arrive within `ms` (none expected, usually).
    async fn quiet_for(&mut self, ms: u64) -> Vec<String> {
        let mut got = Vec::new();
        let end = tokio::time::Instant::now() + Duration::from_millis(ms);
        while let Ok(Some(Ok(m))) = tokio::time::timeout_at(end, self.ws.next()).await {
            if let Message::Text(t) = m {
                got.push(t.to_string());
            }
        }
        got
    }
}

/// Joins as the teacher: the client and its welcome.
async fn teacher(server: &ServerHandle) -> (Client, Welcome) {
    let mut c = Client::connect(server).await;
    c.send(&ClientMessage::Join(Join {
        role: Role::Teacher,
        token: Some(server.token.clone()),
        code: None,
        name: None,
        resume: None,
    }))
    .await;
    match c.recv().await {
        ServerMessage::Welcome(w) => (c, w),
        other => panic!("expected a welcome, got {other:?}"),
    }
}

/// A student's join message.
fn student_join(code: &str, name: &str, resume: Option<String>) -> ClientMessage {
    ClientMessage::Join(Join {
        role: Role::Student,
        token: None,
        code: Some(code.into()),
        name: Some(name.into()),
        resume,
    })
}

/// Joins as student `name`: the client and its welcome.
async fn student(server: &ServerHandle, name: &str) -> (Client, Welcome) {
    let mut c = Client::connect(server).await;
    c.send(&student_join(&server.code, name, None)).await;
    match c.recv().await {
        ServerMessage::Welcome(w) => (c, w),
        other => panic!("expected a welcome, got {other:?}"),
    }
}

/// The teacher's state with the Puma 560 at `q`.
fn puma_state(q: Vec<f64>) -> ClientMessage {
    ClientMessage::State {
        state: ClassState {
            robot: RobotRef::Builtin("puma560".into()),
            q,
            view: Default::default(),
            lesson: None,
        },
    }
}

/// A question request of `kind`, the rest absent.
fn request(kind: QuestionKind) -> QuestionRequest {
    QuestionRequest {
        kind,
        prompt: None,
        choices: Vec::new(),
        correct: None,
        robot: None,
        seed: None,
        feedback: false,
    }
}

/// A poll of three choices, the first right.
fn poll() -> ClientMessage {
    ClientMessage::Question(QuestionRequest {
        prompt: Some("Which posture is this?".into()),
        choices: vec!["elbow up".into(), "elbow down".into(), "neither".into()],
        correct: Some(0),
        ..request(QuestionKind::Poll)
    })
}

/// The next question a client gets.
async fn question(c: &mut Client) -> QuestionOut {
    c.recv_until(|m| match m {
        ServerMessage::Question(q) => Some(q),
        _ => None,
    })
    .await
}

/// The teacher's tallies until one with `answered` answers.
async fn tally_with(c: &mut Client, answered: usize) -> Tally {
    c.recv_until(|m| match m {
        ServerMessage::Tally(t) if t.answered == answered => Some(t),
        _ => None,
    })
    .await
}

/// An answer message.
fn answer(id: u64, v: serde_json::Value) -> ClientMessage {
    ClientMessage::Answer { id, answer: v }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn ten_students_follow_the_teacher_and_a_late_one_gets_the_state_at_once() {
    let data = data_file("follow");
    let server = server(&data, false);
    let (mut t, w) = teacher(&server).await;
    assert_eq!(w.role, Role::Teacher);
    assert_eq!(w.code, server.code);
    assert_eq!(w.student_url, server.student_url);
    assert!(!w.qr.is_empty() && w.qr.iter().all(|r| r.len() == w.qr.len()));
    let mut students = Vec::new();
    for k in 1..=10 {
        let (c, w) = student(&server, &format!("student {k}")).await;
        assert_eq!((w.role, w.student), (Role::Student, Some(k)));
        assert!(w.resume.as_ref().is_some_and(|r| r.len() >= 32));
        students.push(c);
    }
    let roster = t
        .recv_until(|m| match m {
            ServerMessage::Roster { joined: 10, names } => Some(names),
            _ => None,
        })
        .await;
    assert!(roster.is_empty(), "names are not shown: {roster:?}");
    let q = vec![0.1, -0.2, 0.3, 0.4, -0.5, 0.6];
    t.send(&puma_state(q.clone())).await;
    for s in &mut students {
        let (state, seq) = s
            .recv_until(|m| match m {
                ServerMessage::State { state, seq } => Some((state, seq)),
                _ => None,
            })
            .await;
        assert_eq!((state.q.clone(), seq), (q.clone(), 1));
        assert_eq!(state.robot, RobotRef::Builtin("puma560".into()));
    }
    // The teacher brings everyone back to following.
    t.send(&ClientMessage::Follow).await;
    for s in &mut students {
        s.recv_until(|m| matches!(m, ServerMessage::Follow).then_some(()))
            .await;
    }
    // A late student gets the state right after the welcome.
    let (mut late, w) = student(&server, "late").await;
    assert_eq!(w.student, Some(11));
    match late.recv().await {
        ServerMessage::State { state, seq } => assert_eq!((state.q, seq), (q.clone(), 1)),
        other => panic!("expected the state at once, got {other:?}"),
    }
    // A student leaves: the roster says so.
    students[0].send(&ClientMessage::Leave).await;
    t.recv_until(|m| match m {
        ServerMessage::Roster { joined: 10, .. } => Some(()),
        _ => None,
    })
    .await;
    server.stop().unwrap();
}

/// The TOML model `text` with the sign of joint `k`'s alpha (1-based) flipped.
fn flip_alpha(text: &str, k: usize) -> String {
    let mut seen = 0;
    text.lines()
        .map(|l| {
            let Some(v) = l.strip_prefix("alpha = ") else {
                return l.to_string();
            };
            seen += 1;
            if seen != k {
                return l.to_string();
            }
            let flipped = if let Some(s) = v.strip_prefix("\"-") {
                format!("\"{s}")
            } else if let Some(s) = v.strip_prefix('"') {
                format!("\"-{s}")
            } else if let Some(s) = v.strip_prefix('-') {
                s.to_string()
            } else {
                format!("-{v}")
            };
            format!("alpha = {flipped}")
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// Every student gets the sheet file of `sheet` (the student's part), and their text holds
/// nothing of its key.
async fn students_get_the_sheet_only(students: &mut [Client], sheet: &armlab::exercise::Sheet) {
    for s in students {
        let text = s
            .recv_raw_until(|m| matches!(m, ServerMessage::Question(_)))
            .await;
        assert!(!text.contains(KEY_FORMAT) && !text.contains(&sheet.key.model));
        let ServerMessage::Question(q) = armlab::class::protocol::parse_server(&text).unwrap()
        else {
            unreachable!()
        };
        assert_eq!(*q.sheet.unwrap(), SheetFile::of(sheet).unwrap());
    }
}

/// The key of question `id` in the server's data file.
fn stored_key(data: &Path, id: u64) -> armlab::exercise::Key {
    let stored: String = rusqlite::Connection::open(data)
        .unwrap()
        .query_row(
            "SELECT key FROM questions WHERE id = ?1",
            [id as i64],
            |r| r.get(0),
        )
        .unwrap();
    serde_json::from_str(&stored).unwrap()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_dh_table_question_is_graded_on_the_server_with_its_mistakes_counted() {
    let data = data_file("dh");
    let server = server(&data, false);
    let (mut t, _) = teacher(&server).await;
    let mut students = Vec::new();
    for k in 1..=10 {
        students.push(student(&server, &format!("s{k}")).await.0);
    }
    t.send(&puma_state(vec![0.0; 6])).await;
    let seed = 4242;
    t.send(&ClientMessage::Question(QuestionRequest {
        seed: Some(seed),
        feedback: true,
        ..request(QuestionKind::Exercise(Kind::DhTable))
    }))
    .await;
    // The key, made here as the server should have made it: the session's robot, the seed.
    let sheet = generate(Kind::DhTable, Some(&built_in("puma560").unwrap()), seed, 1).unwrap();
    let right = armlab::model_file::to_toml(&key_robot(&sheet.key).unwrap()).unwrap();
    // Row 3's alpha flipped: a real mistake (flipping row 1's or the wrist's gives another
    // table of the same arm, which the grader rightly accepts).
    let wrong = flip_alpha(&right, 3);
    assert_ne!(wrong, right);
    let out = question(&mut t).await;
    assert_eq!(out.kind, QuestionKind::Exercise(Kind::DhTable));
    students_get_the_sheet_only(&mut students, &sheet).await;
    // The key the server stored is the one made here.
    assert_eq!(stored_key(&data, out.id), sheet.key);
    // Student 10 first sends something unreadable, then the wrong table: the last counts.
    students[9]
        .send(&answer(out.id, "not a model".into()))
        .await;
    assert!(
        students[9]
            .error()
            .await
            .starts_with(&format!("answer to question {}", out.id))
    );
    tally_with(&mut t, 1).await;
    for (k, s) in students.iter_mut().enumerate() {
        let text = if k < 6 { &right } else { &wrong };
        s.send(&answer(out.id, text.as_str().into())).await;
        let grade = s
            .recv_until(|m| match m {
                ServerMessage::Received { id, grade } if id == out.id => Some(grade),
                _ => None,
            })
            .await
            .expect("feedback is on");
        assert_eq!(grade.score == grade.max, k < 6, "student {}", k + 1);
    }
    // Student 10's wrong table replaced their unreadable answer.
    let tally = t
        .recv_until(|m| match m {
            ServerMessage::Tally(t) if t.answered == 10 && t.unreadable == 0 => Some(t),
            _ => None,
        })
        .await;
    assert_eq!(tally.joined, 10);
    assert!((tally.correct_percent - 60.0).abs() < 1e-9, "{tally:?}");
    let alpha: Vec<(&String, &usize)> = tally
        .mistakes
        .iter()
        .filter(|(m, _)| m.contains("alpha with the wrong sign"))
        .collect();
    assert_eq!(alpha.len(), 1, "{:?}", tally.mistakes);
    assert_eq!(*alpha[0].1, 4);
    assert_eq!(tally.counts.iter().sum::<usize>(), 10);
    assert_eq!(tally.counts[tally.max], 6);
    server.stop().unwrap();
}

/// An fk exercise on the session's robot (the uploaded model `text`), and an orientation one,
/// which takes none: the student's sheets are the sheets made here, never their keys.
async fn exercises_on_the_uploaded_model(t: &mut Client, late: &mut Client, text: &str) {
    t.send(&ClientMessage::Question(QuestionRequest {
        seed: Some(11),
        ..request(QuestionKind::Exercise(Kind::Fk))
    }))
    .await;
    let robot = armlab::model_file::parse_model_text("cell.toml", text).unwrap();
    let fk = generate(Kind::Fk, Some(&robot), 11, 1).unwrap();
    let got = question(late).await;
    assert_eq!(*got.sheet.unwrap(), SheetFile::of(&fk).unwrap());
    t.send(&ClientMessage::Question(QuestionRequest {
        seed: Some(12),
        ..request(QuestionKind::Exercise(Kind::Euler))
    }))
    .await;
    let euler = generate(Kind::Euler, None, 12, 1).unwrap();
    let raw = late
        .recv_raw_until(|m| matches!(m, ServerMessage::Question(_)))
        .await;
    assert!(
        !raw.contains(KEY_FORMAT) && !raw.contains("\"answer\""),
        "{raw}"
    );
    let ServerMessage::Question(q) = armlab::class::protocol::parse_server(&raw).unwrap() else {
        unreachable!()
    };
    assert_eq!(*q.sheet.unwrap(), SheetFile::of(&euler).unwrap());
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_model_file_reaches_every_student_before_the_state_that_names_it() {
    let data = data_file("model");
    let server = server(&data, false);
    let (mut t, _) = teacher(&server).await;
    let (mut s, _) = student(&server, "early").await;
    let text = armlab::model_file::to_toml(&built_in("scara").unwrap()).unwrap();
    let named = |id: &str| ClientMessage::State {
        state: ClassState {
            robot: RobotRef::Model {
                id: id.into(),
                name: "cell.toml".into(),
            },
            q: vec![0.1, 0.2, 0.05, 0.3],
            view: Default::default(),
            lesson: None,
        },
    };
    // A state naming a model the teacher never sent: refused, nobody gets it.
    t.send(&named("0123456789abcdef")).await;
    assert!(t.error().await.contains("has not sent"));
    assert_eq!(s.quiet_for(200).await, Vec::<String>::new());
    t.send(&ClientMessage::Model {
        name: "cell.toml".into(),
        text: text.clone(),
    })
    .await;
    let id = t
        .recv_until(|m| match m {
            ServerMessage::Model {
                id,
                name,
                text: got,
            } => Some((id, name, got)),
            _ => None,
        })
        .await;
    assert_eq!((id.1.as_str(), id.2.as_str()), ("cell.toml", text.as_str()));
    let id = id.0;
    t.send(&named(&id)).await;
    match (s.recv().await, s.recv().await) {
        (
            ServerMessage::Model {
                id: got, text: t2, ..
            },
            ServerMessage::State { state, .. },
        ) => {
            assert_eq!((got, t2), (id.clone(), text.clone()));
            assert_eq!(state.q, vec![0.1, 0.2, 0.05, 0.3]);
        }
        other => panic!("expected the model, then the state: {other:?}"),
    }
    // A late student gets the model, then the state.
    let (mut late, _) = student(&server, "late").await;
    assert!(matches!(late.recv().await, ServerMessage::Model { id: got, .. } if got == id));
    assert!(matches!(late.recv().await, ServerMessage::State { .. }));
    exercises_on_the_uploaded_model(&mut t, &mut late, &text).await;
    server.stop().unwrap();
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_poll_is_counted_as_the_teacher_sees_it_and_shown_and_closed() {
    let data = data_file("poll");
    let server = server(&data, false);
    let (mut t, _) = teacher(&server).await;
    let mut students = Vec::new();
    for k in 1..=10 {
        students.push(student(&server, &format!("s{k}")).await.0);
    }
    t.send(&poll()).await;
    let id = question(&mut t).await.id;
    let zero = tally_with(&mut t, 0).await;
    assert_eq!((zero.counts.clone(), zero.joined), (vec![0, 0, 0], 10));
    // Five say elbow up, three elbow down, two neither; then one of the "neither" changes to
    // elbow up: counted once, by the last answer.
    let choices = [0, 0, 0, 0, 0, 1, 1, 1, 2, 2];
    for (s, c) in students.iter_mut().zip(choices) {
        assert_eq!(question(s).await.id, id);
        s.send(&answer(id, c.into())).await;
        s.recv_until(|m| matches!(m, ServerMessage::Received { .. }).then_some(()))
            .await;
    }
    students[9].send(&answer(id, 0.into())).await;
    students[9]
        .recv_until(|m| matches!(m, ServerMessage::Received { .. }).then_some(()))
        .await;
    let tally = t
        .recv_until(|m| match m {
            ServerMessage::Tally(t) if t.counts == [6, 3, 1] => Some(t),
            _ => None,
        })
        .await;
    assert_eq!((tally.answered, tally.joined), (10, 10));
    assert!((tally.correct_percent - 60.0).abs() < 1e-9);
    // A choice that is not one is an error, counted as unreadable.
    students[0].send(&answer(id, 7.into())).await;
    assert!(students[0].error().await.contains("choice 7"));
    let t2 = tally_with(&mut t, 10).await;
    assert_eq!((t2.unreadable, t2.counts.clone()), (1, vec![5, 3, 1]));
    // Shown to the class: the same counts, no names in it.
    t.send(&ClientMessage::Show { id }).await;
    let shown = students[1]
        .recv_until(|m| match m {
            ServerMessage::Results(r) => Some(r),
            _ => None,
        })
        .await;
    assert_eq!(shown.counts, vec![5, 3, 1]);
    // Closed: everyone is told; a later answer is refused.
    t.send(&ClientMessage::Close { id }).await;
    for s in &mut students {
        s.recv_until(|m| matches!(m, ServerMessage::Closed { id: i } if i == id).then_some(()))
            .await;
    }
    students[2].send(&answer(id, 1.into())).await;
    assert!(students[2].error().await.contains("closed"));
    server.stop().unwrap();
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_restart_keeps_the_state_questions_and_answers_and_students_resume() {
    let data = data_file("restart");
    let first = server(&data, false);
    let (token, code) = (first.token.clone(), first.code.clone());
    let (mut t, _) = teacher(&first).await;
    let q = vec![0.5, 0.4, 0.3, 0.2, 0.1, 0.0];
    t.send(&puma_state(vec![0.0; 6])).await;
    t.send(&puma_state(q.clone())).await;
    t.send(&poll()).await;
    let id = question(&mut t).await.id;
    let mut resumes = Vec::new();
    for (k, c) in [0, 1, 1].into_iter().enumerate() {
        let (mut s, w) = student(&first, &format!("s{k}")).await;
        s.send(&answer(id, c.into())).await;
        s.recv_until(|m| matches!(m, ServerMessage::Received { .. }).then_some(()))
            .await;
        resumes.push((w.student.unwrap(), w.resume.unwrap()));
    }
    drop(t);
    first.stop().unwrap();

    let second = server(&data, false);
    assert_eq!((second.token.clone(), second.code.clone()), (token, code));
    let (mut t, _) = teacher(&second).await;
    let (state, seq) = t
        .recv_until(|m| match m {
            ServerMessage::State { state, seq } => Some((state, seq)),
            _ => None,
        })
        .await;
    assert_eq!((state.q, seq), (q.clone(), 2));
    assert_eq!(question(&mut t).await.id, id);
    let tally = tally_with(&mut t, 3).await;
    assert_eq!(tally.counts, vec![1, 2, 0]);
    // Student 2 comes back and changes their answer: the same student, counted once.
    let (number, secret) = resumes[1].clone();
    let mut s = Client::connect(&second).await;
    s.send(&student_join(&second.code, "s1", Some(secret)))
        .await;
    let ServerMessage::Welcome(w) = s.recv().await else {
        panic!("no welcome")
    };
    assert_eq!(w.student, Some(number));
    match s.recv().await {
        ServerMessage::State { state, .. } => assert_eq!(state.q, q),
        other => panic!("expected the state, got {other:?}"),
    }
    assert_eq!(question(&mut s).await.id, id);
    s.send(&answer(id, 0.into())).await;
    let after = t
        .recv_until(|m| match m {
            ServerMessage::Tally(t) if t.counts == [2, 1, 0] => Some(t),
            _ => None,
        })
        .await;
    assert_eq!(after.answered, 3);
    second.stop().unwrap();
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_student_cannot_drive_and_bad_messages_get_errors_on_a_living_connection() {
    let data = data_file("security");
    let server = server(&data, false);
    let (mut t, _) = teacher(&server).await;
    let (mut mallory, _) = student(&server, "mallory").await;
    let (mut other, _) = student(&server, "other").await;
    t.send(&poll()).await;
    let id = question(&mut t).await.id;
    question(&mut mallory).await;
    question(&mut other).await;
    let _ = t.quiet_for(200).await;
    let driving = [
        puma_state(vec![1.0; 6]),
        poll(),
        ClientMessage::Follow,
        ClientMessage::Close { id },
        ClientMessage::Export,
        ClientMessage::Model {
            name: "x.toml".into(),
            text: "name = \"x\"".into(),
        },
    ];
    for m in &driving {
        mallory.send(m).await;
        assert_eq!(
            mallory.error().await,
            "students may send only join, answer and leave",
            "{}",
            m.type_name()
        );
    }
    // Nobody got anything of it.
    assert_eq!(other.quiet_for(300).await, Vec::<String>::new());
    assert_eq!(t.quiet_for(100).await, Vec::<String>::new());
    // Malformed, binary, a second join, oversized: errors, and the connection goes on.
    mallory.send_text("{\"type\": \"answer\", \"id\": ").await;
    assert!(mallory.error().await.starts_with("malformed message"));
    mallory
        .ws
        .send(Message::binary(vec![1u8, 2, 3]))
        .await
        .unwrap();
    assert!(mallory.error().await.contains("binary"));
    mallory
        .send(&student_join(&server.code, "again", None))
        .await;
    assert!(mallory.error().await.contains("already joined"));
    let big = answer(id, "x".repeat(70 * 1024).into());
    mallory.send(&big).await;
    assert!(mallory.error().await.starts_with("message too large"));
    mallory.send(&answer(id, 1.into())).await;
    mallory
        .recv_until(|m| matches!(m, ServerMessage::Received { .. }).then_some(()))
        .await;
    assert_eq!(tally_with(&mut t, 1).await.counts, vec![0, 1, 0]);
    server.stop().unwrap();
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn wrong_tokens_and_codes_are_refused_and_limited_per_address() {
    let data = data_file("attempts");
    let server = server(&data, false);
    // The first message must be a join; a wrong token, then the right one, on one connection.
    let mut c = Client::connect(&server).await;
    c.send(&ClientMessage::Follow).await;
    assert!(
        c.error()
            .await
            .starts_with("the first message must be a join")
    );
    let mut join = Join {
        role: Role::Teacher,
        token: Some("0".repeat(32)),
        code: None,
        name: None,
        resume: None,
    };
    c.send(&ClientMessage::Join(join.clone())).await;
    assert_eq!(c.error().await, "wrong teacher token");
    join.token = Some(server.token.clone());
    c.send(&ClientMessage::Join(join)).await;
    assert!(matches!(c.recv().await, ServerMessage::Welcome(w) if w.role == Role::Teacher));
    // A wrong code; a missing nickname.
    let mut s = Client::connect(&server).await;
    s.send(&student_join("0OIL10", "eve", None)).await;
    assert!(s.error().await.starts_with("wrong join code"));
    s.send(&student_join(&server.code, "   ", None)).await;
    assert!(s.error().await.contains("nickname is required"));
    // Two failures so far; eight more reach the limit, then even the right code is refused.
    for k in 0..8 {
        s.send(&student_join(&format!("Z0Z0Z{k}"), "eve", None))
            .await;
        assert!(
            s.error().await.starts_with("wrong join code"),
            "attempt {k}"
        );
    }
    s.send(&student_join(&server.code, "eve", None)).await;
    assert!(
        s.error()
            .await
            .starts_with("too many join attempts from this address; wait a minute")
    );
    let mut fresh = Client::connect(&server).await;
    fresh.send(&student_join(&server.code, "eve", None)).await;
    assert!(fresh.error().await.starts_with("too many join attempts"));
    // HTTP: the export needs the token too (refused while the address is blocked).
    if let Some(status) = curl_status(&format!("http://{}/export.csv?token=nope", server.addr)) {
        assert_eq!(status, "429");
    }
    server.stop().unwrap();
}

/// The HTTP status of a GET with curl, if curl is there (the tests write no HTTP by hand).
fn curl_status(url: &str) -> Option<String> {
    let out = std::process::Command::new("curl")
        .args(["-s", "-o", "/dev/null", "-w", "%{http_code}", url])
        .output()
        .ok()?;
    Some(String::from_utf8_lossy(&out.stdout).trim().to_string())
}

/// The body and content type of a GET with curl, if curl is there.
fn curl_get(url: &str) -> Option<(String, String)> {
    let out = std::process::Command::new("curl")
        .args(["-s", "-w", "\n%{content_type}", url])
        .output()
        .ok()?;
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    let (body, kind) = text.rsplit_once('\n')?;
    Some((body.to_string(), kind.to_string()))
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_flood_is_limited_and_the_connection_and_server_go_on() {
    let data = data_file("flood");
    let server = server(&data, false);
    let (mut t, _) = teacher(&server).await;
    let (mut flooder, _) = student(&server, "flood").await;
    let (mut calm, _) = student(&server, "calm").await;
    t.send(&poll()).await;
    let id = question(&mut t).await.id;
    question(&mut flooder).await;
    question(&mut calm).await;
    let started = std::time::Instant::now();
    for k in 0..500u64 {
        flooder.send(&answer(id, (k % 3).into())).await;
    }
    // What comes back: a receipt for each message let through (the burst of 20, less the
    // join, then 10 a second), one rate-limit error a second.
    let back = flooder.quiet_for(1500).await;
    let seconds = started.elapsed().as_secs_f64();
    let received = back.iter().filter(|t| t.contains("\"received\"")).count();
    let limited = back.iter().filter(|t| t.contains("rate limit")).count();
    assert!(
        (19..=20 + (10.0 * seconds).ceil() as usize).contains(&received),
        "{received} receipts in {seconds} s"
    );
    assert!(
        limited >= 1 && limited as f64 <= seconds + 1.0,
        "{limited} errors"
    );
    // The connection and the server go on.
    flooder.send(&answer(id, 2.into())).await;
    flooder
        .recv_until(|m| matches!(m, ServerMessage::Received { .. }).then_some(()))
        .await;
    t.send(&puma_state(vec![0.2; 6])).await;
    let state = calm
        .recv_until(|m| match m {
            ServerMessage::State { state, .. } => Some(state),
            _ => None,
        })
        .await;
    assert_eq!(state.q, vec![0.2; 6]);
    // The teacher's 30 states a second pass the teacher's limit.
    for k in 0..60 {
        t.send(&puma_state(vec![f64::from(k); 6])).await;
        tokio::time::sleep(Duration::from_millis(33)).await;
    }
    let mut last = 0;
    while last < 61 {
        last = calm
            .recv_until(|m| match m {
                ServerMessage::State { seq, .. } => Some(seq),
                _ => None,
            })
            .await;
    }
    assert!(
        !t.quiet_for(100)
            .await
            .iter()
            .any(|m| m.contains("rate limit"))
    );
    server.stop().unwrap();
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn markup_in_a_nickname_comes_back_as_text_and_the_export_lists_the_answers() {
    let data = data_file("markup");
    let server = server(&data, true);
    let (mut t, w) = teacher(&server).await;
    assert!(w.names_shown);
    let nasty = "<script>alert(1)</script>";
    let (mut s, _) = student(&server, nasty).await;
    let (mut plain, _) = student(&server, "Ada, \"the first\"").await;
    let raw = t
        .recv_raw_until(|m| matches!(m, ServerMessage::Roster { joined: 2, .. }))
        .await;
    let ServerMessage::Roster { names, .. } = armlab::class::protocol::parse_server(&raw).unwrap()
    else {
        unreachable!()
    };
    assert_eq!(
        names,
        vec![nasty.to_string(), "Ada, \"the first\"".to_string()]
    );
    assert!(
        raw.contains(&format!("\"{nasty}\"")),
        "a JSON string as it is: {raw}"
    );
    t.send(&poll()).await;
    let id = question(&mut t).await.id;
    for (c, choice) in [(&mut s, 1), (&mut plain, 0)] {
        question(c).await;
        c.send(&answer(id, choice.into())).await;
        c.recv_until(|m| matches!(m, ServerMessage::Received { .. }).then_some(()))
            .await;
    }
    t.send(&ClientMessage::Export).await;
    let csv = t
        .recv_until(|m| match m {
            ServerMessage::Export { csv } => Some(csv),
            _ => None,
        })
        .await;
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("session,question,kind,student,name,answer,correct,score,max,mistakes,answered_at")
    );
    let first: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        &first[1..9],
        &[&id.to_string(), "poll", "1", nasty, "1", "false", "0", "1"]
    );
    let second = lines.next().unwrap();
    assert!(
        second.contains(",2,\"Ada, \"\"the first\"\"\",0,true,1,1,"),
        "RFC 4180 quoting: {second}"
    );
    assert_eq!(lines.next(), None);
    // Over HTTP (with curl where there is one): the same CSV with the token, 403 without.
    let base = format!("http://{}", server.addr);
    if let Some((body, kind)) = curl_get(&format!("{base}/export.csv?token={}", server.token)) {
        assert_eq!(body, csv);
        assert!(kind.starts_with("text/csv"), "{kind}");
        assert_eq!(curl_status(&format!("{base}/export.csv")).unwrap(), "403");
        // No web build here: the page says how to build it, as plain text.
        let (page, kind) = curl_get(&format!("{base}/")).unwrap();
        assert!(page.contains("web/build.sh") && kind.starts_with("text/plain"));
    } else {
        eprintln!("no curl: /export.csv and / not checked over HTTP");
    }
    server.stop().unwrap();
}

/// Starts `armlab class serve` on a free port: the child and its first two lines.
fn spawn_binary(data: &std::path::Path) -> (std::process::Child, String, String) {
    use std::io::BufRead;
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args(["class", "serve", "--port", "0", "--data"])
        .arg(data)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("armlab runs");
    let mut out = std::io::BufReader::new(child.stdout.take().unwrap());
    let (mut a, mut b) = (String::new(), String::new());
    out.read_line(&mut a).unwrap();
    out.read_line(&mut b).unwrap();
    // Keep reading (and dropping) the rest so that the child never blocks on a full pipe.
    std::thread::spawn(move || {
        let mut sink = String::new();
        while out.read_line(&mut sink).is_ok_and(|n| n > 0) {
            sink.clear();
        }
    });
    (child, a.trim_end().to_string(), b.trim_end().to_string())
}

/// The value of `key` in a link's query.
fn query_value(url: &str, key: &str) -> String {
    url.split_once(&format!("?{key}="))
        .map(|(_, v)| v.to_string())
        .unwrap_or_else(|| panic!("no {key} in {url}"))
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_binary_prints_its_links_first_and_a_kill_loses_no_acknowledged_answer() {
    let data = data_file("binary");
    let (mut child, teacher_line, student_line) = spawn_binary(&data);
    let teacher_url = teacher_line
        .strip_prefix("teacher: ")
        .expect(&teacher_line)
        .to_string();
    let student_url = student_line
        .strip_prefix("students: ")
        .expect(&student_line)
        .to_string();
    let token = query_value(&teacher_url, "token");
    let code = query_value(&student_url, "code");
    assert!(
        token.len() >= 32 && token.bytes().all(|b| b.is_ascii_hexdigit()),
        "{token}"
    );
    assert_eq!(code.len(), 6);
    let hostport = teacher_url
        .strip_prefix("http://")
        .and_then(|r| r.split_once('/'))
        .map(|(h, _)| h.to_string())
        .unwrap();
    assert!(hostport.starts_with("127.0.0.1:") && !hostport.ends_with(":0"));
    let connect = |hostport: String| async move {
        connect_async(format!("ws://{hostport}/ws"))
            .await
            .unwrap()
            .0
    };
    let join_teacher = ClientMessage::Join(Join {
        role: Role::Teacher,
        token: Some(token.clone()),
        code: None,
        name: None,
        resume: None,
    });
    let mut t = Client {
        ws: connect(hostport.clone()).await,
    };
    t.send(&join_teacher).await;
    assert!(matches!(t.recv().await, ServerMessage::Welcome(_)));
    t.send(&puma_state(vec![0.7; 6])).await;
    t.send(&poll()).await;
    let id = question(&mut t).await.id;
    let mut s = Client {
        ws: connect(hostport.clone()).await,
    };
    s.send(&student_join(&code, "kept", None)).await;
    question(&mut s).await;
    s.send(&answer(id, 2.into())).await;
    s.recv_until(|m| matches!(m, ServerMessage::Received { .. }).then_some(()))
        .await;
    // The state is written a few times a second; the answer was written before its receipt.
    tokio::time::sleep(Duration::from_millis(600)).await;
    child.kill().unwrap();
    child.wait().unwrap();

    let (mut child, teacher_again, _) = spawn_binary(&data);
    assert_eq!(query_value(&teacher_again, "token"), token);
    let hostport = teacher_again
        .strip_prefix("teacher: http://")
        .and_then(|r| r.split_once('/'))
        .map(|(h, _)| h.to_string())
        .unwrap();
    let mut t = Client {
        ws: connect(hostport).await,
    };
    t.send(&join_teacher).await;
    assert!(matches!(t.recv().await, ServerMessage::Welcome(_)));
    match t.recv().await {
        ServerMessage::State { state, seq } => assert_eq!((state.q, seq), (vec![0.7; 6], 1)),
        other => panic!("expected the state, got {other:?}"),
    }
    assert_eq!(tally_with(&mut t, 1).await.counts, vec![0, 0, 1]);
    child.kill().unwrap();
    child.wait().unwrap();
}

/// The question the teacher just asked, once `n` answered it.
async fn answered_by_all(t: &mut Client, n: usize) -> Tally {
    let id = question(t).await.id;
    t.recv_until(|m| match m {
        ServerMessage::Tally(tally) if tally.id == id && tally.answered == n => Some(tally),
        _ => None,
    })
    .await
}

/// `armlab class demo`'s simulated students, against a teacher made here: ten join and follow
/// the Puma; a DH-table question gets ten readable answers, each wrong one with a mistake the
/// server's grader names (alpha's or d's sign, a and d swapped: what they make), some right;
/// fk, euler and quaternion questions too; the posture poll's most chosen answer is the arm's posture. The arm's posture is found here
/// from the closed-form IK at the arm's tool pose: the solution equal to q.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn simulated_students_answer_as_a_room_does() {
    use armlab::app::class::rehearsal::{Pace, Rehearsal};
    let data = data_file("rehearsal");
    let server = server(&data, false);
    let (mut t, _) = teacher(&server).await;
    let q = vec![0.3, 0.5, -1.2, 0.4, 0.8, -0.6];
    t.send(&puma_state(q.clone())).await;
    let ws = format!("ws://{}/ws", server.addr);
    let room = Rehearsal::start(&ws, &server.code, 10, 7, Pace::AtOnce);
    t.recv_until(|m| match m {
        ServerMessage::Roster { joined: 10, .. } => Some(()),
        _ => None,
    })
    .await;
    t.send(&ClientMessage::Question(QuestionRequest {
        seed: Some(99),
        ..request(QuestionKind::Exercise(Kind::DhTable))
    }))
    .await;
    let tally = answered_by_all(&mut t, 10).await;
    assert_eq!(tally.unreadable, 0, "{tally:?}");
    let right = tally.counts[tally.max];
    assert!(
        (1..10).contains(&right),
        "some right, some wrong: {tally:?}"
    );
    let named: usize = tally.mistakes.values().sum();
    assert!(named >= 10 - right, "each wrong answer named: {tally:?}");
    for m in tally.mistakes.keys() {
        assert!(
            m.contains("wrong sign") || m.contains("swapped"),
            "a mistake the simulated students make: {m}"
        );
    }
    // The other kinds they answer: every answer readable, some right, each wrong one named.
    for kind in [Kind::Fk, Kind::Euler, Kind::Quaternion] {
        t.send(&ClientMessage::Question(QuestionRequest {
            seed: Some(5),
            ..request(QuestionKind::Exercise(kind))
        }))
        .await;
        let tally = answered_by_all(&mut t, 10).await;
        assert_eq!(tally.unreadable, 0, "{kind:?}: {tally:?}");
        let right = tally.counts[tally.max];
        assert!(right >= 1, "{kind:?}: {tally:?}");
        let named: usize = tally.mistakes.values().sum();
        assert!(
            named >= 10 - right,
            "{kind:?}: each wrong answer named: {tally:?}"
        );
    }
    // The posture poll: choices in an order made here, the arm's posture among them.
    let robot = built_in("puma560").unwrap();
    let tool = robot.fk(&q).unwrap();
    let solutions = armlab::kinematics::ik::closed_form::ClosedForm::detect(&robot)
        .unwrap()
        .solve(&robot, &armlab::kinematics::ik::Target::Pose(tool))
        .unwrap();
    let mut choices: Vec<String> = solutions
        .solutions
        .iter()
        .map(|s| s.posture.to_string())
        .collect();
    choices.sort();
    choices.dedup();
    let at_q = solutions
        .solutions
        .iter()
        .find(|s| s.q.iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-9))
        .expect("q is one of its tool pose's solutions");
    let arm = choices
        .iter()
        .position(|c| *c == at_q.posture.to_string())
        .unwrap();
    assert_eq!(choices.len(), 8, "the Puma's eight postures: {choices:?}");
    t.send(&ClientMessage::Question(QuestionRequest {
        prompt: Some("Which posture is this?".into()),
        choices: choices.clone(),
        ..request(QuestionKind::Poll)
    }))
    .await;
    let tally = answered_by_all(&mut t, 10).await;
    let most = (0..tally.counts.len())
        .max_by_key(|&i| tally.counts[i])
        .unwrap();
    assert_eq!(most, arm, "{:?} of {choices:?}", tally.counts);
    assert!(room.errors().is_empty(), "{:?}", room.errors());
    drop(room);
    server.stop().unwrap();
}

/// Runs `armlab class demo ARGS...` and checks that it succeeded.
fn run_demo(args: &[&str]) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args(["class", "demo"])
        .args(args)
        .output()
        .expect("armlab runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// `armlab class demo --screenshot` and `--student-screenshot`: the pictures are written, at
/// the size asked, once the room answered (the command's own wait: it fails after a minute).
#[test]
fn the_demo_writes_the_teachers_and_a_students_window() {
    let dir = data_file("demo").with_extension("d");
    std::fs::create_dir_all(&dir).unwrap();
    let (teacher, student) = (dir.join("teacher.png"), dir.join("student.png"));
    let (t, s) = (teacher.to_str().unwrap(), student.to_str().unwrap());
    let q = "0.3,0.5,-1.2,0.4,0.8,-0.6";
    run_demo(&[
        "puma560",
        "--students",
        "6",
        "--ask",
        "posture",
        "--q",
        q,
        "--size",
        "640x400",
        "--screenshot",
        t,
        "--student-screenshot",
        s,
    ]);
    for p in [&teacher, &student] {
        let img = image::open(p).unwrap();
        assert_eq!((img.width(), img.height()), (640, 400), "{}", p.display());
    }
}

/// `armlab class demo --seed S --ask dh-table` asks the sheet S draws: two rehearsals with the same
/// seed store the same question as sent to the students (its sheet, arm and q), another seed
/// another one; the request the server keeps names the seed.
#[test]
fn the_demos_seed_draws_the_question_it_asks() {
    let sent = |name: &str, seed: &str| {
        let data = data_file(name);
        let picture = data.with_extension("png");
        let (d, p) = (data.to_str().unwrap(), picture.to_str().unwrap());
        run_demo(&[
            "puma560",
            "--students",
            "2",
            "--ask",
            "dh-table",
            "--seed",
            seed,
            "--size",
            "320x200",
            "--data",
            d,
            "--screenshot",
            p,
        ]);
        let db = rusqlite::Connection::open(&data).unwrap();
        let (request, sent): (String, String) = db
            .query_row("SELECT request, sent FROM questions", [], |r| {
                Ok((r.get(0)?, r.get(1)?))
            })
            .unwrap();
        let request: serde_json::Value = serde_json::from_str(&request).unwrap();
        assert_eq!(request["seed"].to_string(), seed, "{request}");
        let sent: serde_json::Value = serde_json::from_str(&sent).unwrap();
        sent["sheet"].clone()
    };
    let first = sent("demo-seed-a", "7");
    assert!(first["question"].as_str().unwrap().contains("DH table"));
    assert_eq!(
        first,
        sent("demo-seed-b", "7"),
        "the same seed, the same sheet"
    );
    assert_ne!(
        first,
        sent("demo-seed-c", "8"),
        "another seed, another sheet"
    );
}

/// A student who joins while a question is open counts in its tally at once ("answered 0 of
/// 2", not "of 1" until somebody answers), and one who leaves stops counting (found in the
/// browser test: a third page's student never reached the teacher's count).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_open_questions_tally_follows_the_students_joining_and_leaving() {
    let data = data_file("late-tally");
    let server = server(&data, false);
    let (mut t, _) = teacher(&server).await;
    let (_a, _) = student(&server, "a").await;
    t.send(&poll()).await;
    let id = question(&mut t).await.id;
    let (mut b, _) = student(&server, "b").await;
    let joined = |n: usize| {
        move |m: ServerMessage| match m {
            ServerMessage::Tally(x) if x.id == id && x.joined == n => Some(x),
            _ => None,
        }
    };
    let tally = t.recv_until(joined(2)).await;
    assert_eq!(tally.answered, 0);
    b.send(&ClientMessage::Leave).await;
    let tally = t.recv_until(joined(1)).await;
    assert_eq!(tally.answered, 0);
    server.stop().unwrap();
}

/// Reads a QR code given as rows of modules (`dark(x, y)`, `side` modules a side, a quiet zone
/// included) with an independent decoder (rqrr), at 4 pixels a module.
fn decode_qr(side: usize, dark: impl Fn(usize, usize) -> bool) -> String {
    const PX: usize = 4;
    let mut img = rqrr::PreparedImage::prepare_from_greyscale(side * PX, side * PX, |x, y| {
        if dark(x / PX, y / PX) { 0 } else { 255 }
    });
    let grids = img.detect_grids();
    assert_eq!(grids.len(), 1, "one QR code");
    grids[0].decode().expect("the QR code reads").1
}

/// The QR codes of the student link, as the Class window draws it (the welcome's rows) and as
/// `armlab class serve` prints it (half blocks, light drawn on a dark terminal), both read back
/// by an independent decoder: the student link exactly.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_qr_codes_read_back_as_the_student_link() {
    let data = data_file("qr");
    let server = server(&data, false);
    let (_t, w) = teacher(&server).await;
    assert_eq!(w.student_url, server.student_url);
    let rows: Vec<Vec<bool>> =
        w.qr.iter()
            .map(|r| r.chars().map(|c| c == '#').collect())
            .collect();
    let n = rows.len();
    // the window's code, with a quiet zone of four modules added here
    let window = decode_qr(n + 8, |x, y| {
        (4..n + 4).contains(&x) && (4..n + 4).contains(&y) && rows[y - 4][x - 4]
    });
    assert_eq!(window, server.student_url);
    // the terminal's: each character two modules (top, bottom); drawn means light
    let printed = armlab::class_server::qr::terminal(&w.qr);
    let lines: Vec<Vec<char>> = printed.lines().map(|l| l.chars().collect()).collect();
    let side = lines[0].len();
    let terminal = decode_qr(side, |x, y| {
        let c = lines
            .get(y / 2)
            .and_then(|l| l.get(x))
            .copied()
            .unwrap_or('█');
        let light = match c {
            '█' => true,
            '▀' => y % 2 == 0,
            '▄' => y % 2 == 1,
            _ => false,
        };
        !light
    });
    assert_eq!(terminal, server.student_url);
    server.stop().unwrap();
}

/// A model file near the 8 MB limit reaches a student whole over the WebSocket; one over it
/// is refused with an error naming the size, and the teacher's connection goes on.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_model_file_of_nearly_8_mb_reaches_the_students_and_a_larger_one_is_refused() {
    use armlab::class::protocol::MAX_MODEL_BYTES;
    let data = data_file("big-model");
    let server = server(&data, false);
    let (mut t, _) = teacher(&server).await;
    let (mut s, _) = student(&server, "s").await;
    let model = armlab::model_file::to_toml(&built_in("puma560").unwrap()).unwrap();
    // A real file's bulk (comments here), up to 7.5 MB.
    let mut text = model.clone();
    let mut k = 0;
    while text.len() < MAX_MODEL_BYTES - 512 * 1024 {
        text.push_str(&format!(
            "# calibration note {k}: measured on the cell, kept for the record\n"
        ));
        k += 1;
    }
    t.send(&ClientMessage::Model {
        name: "big.toml".into(),
        text: text.clone(),
    })
    .await;
    let got = s
        .recv_until(|m| match m {
            ServerMessage::Model { text, .. } => Some(text),
            _ => None,
        })
        .await;
    assert_eq!(got.len(), text.len());
    assert!(got == text, "the model arrived whole");
    // The teacher sends a second 7.5 MB file and one over the limit without reading its own
    // copies (15 MB waiting for it, more than the sockets hold): the server reads on while it
    // writes (the two once took turns, and such a client stalled its own connection).
    t.send(&ClientMessage::Model {
        name: "big2.toml".into(),
        text: text.clone(),
    })
    .await;
    let over = "#".repeat(MAX_MODEL_BYTES + 1);
    t.send(&ClientMessage::Model {
        name: "huge.toml".into(),
        text: over,
    })
    .await;
    // Then it reads: its two copies, and the error for the third, in whichever order the reply
    // and the broadcast came (the connection still drives).
    let (mut copies, mut error) = (Vec::new(), None);
    while copies.len() < 2 || error.is_none() {
        match t.recv().await {
            ServerMessage::Model { name, text, .. } => copies.push((name, text.len())),
            ServerMessage::Error { message } => error = Some(message),
            _ => {}
        }
    }
    let want = |name: &str| (name.to_string(), text.len());
    assert_eq!(copies, [want("big.toml"), want("big2.toml")]);
    let e = error.unwrap();
    assert!(e.contains("too large"), "{e}");
    t.send(&puma_state(vec![0.1; 6])).await;
    let q = s
        .recv_until(|m| match m {
            ServerMessage::State { state, .. } => Some(state.q),
            _ => None,
        })
        .await;
    assert_eq!(q, vec![0.1; 6]);
    server.stop().unwrap();
}

/// `--new` starts a second session beside the stored one: each has its own links, and the
/// first's still work after the restart (its teacher drives its own students only).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_new_session_sits_beside_the_old_one_and_both_links_work() {
    let data = data_file("two-sessions");
    let first = server(&data, false);
    let (old_token, old_code) = (first.token.clone(), first.code.clone());
    first.stop().unwrap();
    let second = start(ServerOptions {
        port: 0,
        data: data.clone(),
        web: data.parent().map(PathBuf::from),
        new_session: true,
        ..ServerOptions::default()
    })
    .expect("the server starts");
    assert_ne!(second.token, old_token);
    assert_ne!(second.code, old_code);
    let (mut new_teacher, _) = teacher(&second).await;
    let (mut new_student, _) = student(&second, "new").await;
    // The first session's teacher and student, by the old links.
    let mut old_teacher = Client::connect(&second).await;
    old_teacher
        .send(&ClientMessage::Join(Join {
            role: Role::Teacher,
            token: Some(old_token),
            code: None,
            name: None,
            resume: None,
        }))
        .await;
    let w = old_teacher
        .recv_until(|m| match m {
            ServerMessage::Welcome(w) => Some(w),
            _ => None,
        })
        .await;
    assert_eq!(w.code, old_code);
    let mut old_student = Client::connect(&second).await;
    old_student
        .send(&student_join(&old_code, "old", None))
        .await;
    assert!(matches!(
        old_student.recv().await,
        ServerMessage::Welcome(_)
    ));
    old_teacher.send(&puma_state(vec![0.2; 6])).await;
    new_teacher.send(&puma_state(vec![-0.3; 6])).await;
    let q_of = |m: ServerMessage| match m {
        ServerMessage::State { state, .. } => Some(state.q),
        _ => None,
    };
    assert_eq!(old_student.recv_until(q_of).await, vec![0.2; 6]);
    assert_eq!(new_student.recv_until(q_of).await, vec![-0.3; 6]);
    // Neither hears the other session.
    assert!(old_student.quiet_for(200).await.is_empty());
    assert!(new_student.quiet_for(200).await.is_empty());
    second.stop().unwrap();
}
