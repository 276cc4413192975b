//! The live classroom's protocol (issue 50): the issue's own envelopes read as written, every
//! message type round-tripped, the size limits and the field checks; and the tally counted
//! against a count written here.

use armlab::class::grading::{Graded, grade_exercise, tally};
use armlab::class::protocol::{
    ClassState, ClientMessage, MAX_MESSAGE_BYTES, MAX_MODEL_BYTES, ProtocolError, QuestionKind,
    RobotRef, Role, ServerMessage, parse_client, parse_server,
};
use armlab::exercise::{Kind, generate};
use serde_json::json;

#[test]
fn the_issues_envelopes_read_as_written() {
    let t = parse_client(r#"{"type": "join", "role": "teacher", "token": "T"}"#).unwrap();
    let ClientMessage::Join(j) = t else {
        panic!("{t:?}")
    };
    assert_eq!((j.role, j.token.as_deref()), (Role::Teacher, Some("T")));
    let s =
        parse_client(r#"{"type": "join", "role": "student", "code": "C", "name": "N"}"#).unwrap();
    let ClientMessage::Join(j) = s else {
        panic!("{s:?}")
    };
    assert_eq!(
        (j.role, j.code.as_deref(), j.name.as_deref()),
        (Role::Student, Some("C"), Some("N"))
    );
    let st = parse_client(
        r#"{"type": "state", "state": {"robot": {"builtin": "puma560"}, "q": [0.1, 0.2, 0.3, 0, 0, 0]}}"#,
    )
    .unwrap();
    let ClientMessage::State { state } = st else {
        panic!()
    };
    assert_eq!(state.q, vec![0.1, 0.2, 0.3, 0.0, 0.0, 0.0]);
    assert_eq!(state.robot, RobotRef::Builtin("puma560".into()));
    let q = parse_client(r#"{"type": "question", "kind": "poll", "choices": ["a", "b"]}"#).unwrap();
    let ClientMessage::Question(q) = q else {
        panic!()
    };
    assert_eq!(q.kind, QuestionKind::Poll);
    let q = parse_client(r#"{"type": "question", "kind": "dh-table"}"#).unwrap();
    let ClientMessage::Question(q) = q else {
        panic!()
    };
    assert_eq!(q.kind, QuestionKind::Exercise(Kind::DhTable));
    let a = parse_client(r#"{"type": "answer", "id": 3, "answer": 1}"#).unwrap();
    assert_eq!(
        a,
        ClientMessage::Answer {
            id: 3,
            answer: json!(1)
        }
    );
    for m in [
        r#"{"type": "leave"}"#,
        r#"{"type": "follow"}"#,
        r#"{"type": "export"}"#,
        r#"{"type": "close", "id": 1}"#,
        r#"{"type": "show", "id": 1}"#,
        r#"{"type": "model", "name": "a.urdf", "text": "<robot/>"}"#,
    ] {
        let parsed = parse_client(m).unwrap_or_else(|e| panic!("{m}: {e}"));
        // and written back, the same message
        assert_eq!(parse_client(&parsed.to_text()).unwrap(), parsed);
    }
}

#[test]
fn malformed_and_unknown_messages_are_errors_naming_what() {
    for (m, want) in [
        ("not json", "malformed"),
        (r#"{"type": "join", "role": "pirate"}"#, "pirate"),
        (r#"{"type": "dance"}"#, "dance"),
        (
            r#"{"type": "join", "role": "teacher", "token": "T", "extra": 1}"#,
            "extra",
        ),
        (r#"{"type": "question", "kind": "karaoke"}"#, "karaoke"),
        (
            r#"{"type": "question", "kind": "poll", "choices": ["only"]}"#,
            "choices",
        ),
        (
            r#"{"type": "question", "kind": "poll", "choices": ["a", "b"], "correct": 2}"#,
            "correct",
        ),
        (r#"{"type": "answer", "id": -1, "answer": 0}"#, "malformed"),
        (
            r#"{"type": "join", "role": "student", "code": "C", "name": "a\u0007b"}"#,
            "name",
        ),
        ("[]", "malformed"),
        ("", "malformed"),
    ] {
        let e = parse_client(m).expect_err(m).to_string();
        assert!(e.contains(want), "{m}: {e}");
    }
    let long = "x".repeat(41);
    let m = json!({"type": "join", "role": "student", "code": "C", "name": long}).to_string();
    assert!(matches!(
        parse_client(&m),
        Err(ProtocolError::Field { field: "name", .. })
    ));
}

#[test]
fn size_limits_hold_for_messages_and_model_files() {
    let pad = "x".repeat(MAX_MESSAGE_BYTES);
    let m = json!({"type": "join", "role": "student", "code": pad}).to_string();
    assert!(matches!(
        parse_client(&m),
        Err(ProtocolError::Oversized {
            limit: MAX_MESSAGE_BYTES,
            ..
        })
    ));
    // a model file may be larger, up to its own limit
    let text = "x".repeat(MAX_MESSAGE_BYTES * 4);
    let m = json!({"type": "model", "name": "a.urdf", "text": text}).to_string();
    assert!(parse_client(&m).is_ok());
    let text = "x".repeat(MAX_MODEL_BYTES + 1);
    let m = json!({"type": "model", "name": "a.urdf", "text": text}).to_string();
    assert!(matches!(
        parse_client(&m),
        Err(ProtocolError::Oversized { .. })
    ));
    let m = "y".repeat(MAX_MODEL_BYTES * 2);
    assert!(matches!(
        parse_client(&m),
        Err(ProtocolError::Oversized { .. })
    ));
}

#[test]
fn server_messages_round_trip() {
    let state = ClassState {
        robot: RobotRef::Model {
            id: "abc".into(),
            name: "arm.urdf".into(),
        },
        q: vec![0.5, -1.0],
        view: Default::default(),
        lesson: None,
    };
    let m = ServerMessage::State { state, seq: 7 };
    let text = m.to_text();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["type"], "state");
    assert_eq!(v["state"]["q"], json!([0.5, -1.0]));
    assert_eq!(parse_server(&text).unwrap(), m);
    let e = ServerMessage::Error {
        message: "no".into(),
    };
    assert_eq!(
        serde_json::from_str::<serde_json::Value>(&e.to_text()).unwrap(),
        json!({"type": "error", "message": "no"})
    );
}

#[test]
fn a_tally_counts_as_counted_by_hand() {
    // a poll: choices 0, 1, 1, 2, 1, of which 1 is right
    let answers: Vec<Graded> = [0, 1, 1, 2, 1].iter().map(|c| Graded::Choice(*c)).collect();
    let choices: Vec<String> = ["a", "b", "c"].iter().map(|s| s.to_string()).collect();
    let t = tally(4, QuestionKind::Poll, &choices, Some(1), &answers, 8);
    assert_eq!((t.answered, t.joined), (5, 8));
    assert_eq!(t.counts, vec![1, 3, 1]);
    assert!((t.correct_percent - 60.0).abs() < 1e-12);
    // a DH table: one right, one with alpha's sign wrong, one unreadable
    let sheet = generate(
        Kind::DhTable,
        Some(&armlab::kinematics::models::built_in("planar3").unwrap()),
        5,
        1,
    )
    .unwrap();
    let right =
        armlab::model_file::to_toml(&armlab::exercise::key_robot(&sheet.key).unwrap()).unwrap();
    let g = grade_exercise(&sheet.key, &json!(right)).unwrap();
    assert_eq!(g.score, g.max, "{g:?}");
    let wrong = grade_exercise(&sheet.key, &json!("[robot]\nname = 1")).map_err(|e| e.to_string());
    assert!(wrong.is_err());
    let answers = vec![Graded::Exercise(g.clone()), Graded::Unreadable("x".into())];
    let t = tally(
        1,
        QuestionKind::Exercise(Kind::DhTable),
        &[],
        None,
        &answers,
        2,
    );
    assert_eq!(t.counts[g.max], 1);
    assert_eq!(t.unreadable, 1);
    assert!((t.correct_percent - 50.0).abs() < 1e-12);
}
