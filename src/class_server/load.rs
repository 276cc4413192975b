//! Reading the data file at start: every session with its model files, latest state, questions
//! (requests, keys, what the students got), students and answers; and making a new session.
//! A row that cannot be read is an error naming its table and row, never a panic.

use super::ServerError;
use super::secret::{SECRET_BYTES, join_code, random_hex};
use super::session::{AnswerRecord, Inner, ModelFile, Question, Stored, Student};
use super::store::graded_from_json;
use rusqlite::{Connection, OptionalExtension};
use std::collections::BTreeMap;
use std::sync::Arc;

/// A failed query, named.
fn sql(what: &'static str) -> impl Fn(rusqlite::Error) -> ServerError {
    move |source| ServerError::Sql { what, source }
}

/// A stored value that cannot be read.
fn corrupt(what: &'static str, row: String, e: impl std::fmt::Display) -> ServerError {
    ServerError::Corrupt {
        what,
        row,
        reason: e.to_string(),
    }
}

/// Milliseconds since the Unix epoch, now.
pub(crate) fn now_ms() -> i64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_millis() as i64)
}

/// Every session of the data file, oldest first.
pub(crate) fn load(conn: &Connection) -> Result<Vec<Stored>, ServerError> {
    let mut stmt = conn
        .prepare(
            "SELECT id, token, code, names_shown, created_ms, state, seq, model FROM sessions \
             ORDER BY created_ms, rowid",
        )
        .map_err(sql("reading the sessions"))?;
    type Row = (
        String,
        String,
        String,
        bool,
        i64,
        Option<String>,
        i64,
        Option<String>,
    );
    let rows: Vec<Row> = stmt
        .query_map([], |r| {
            Ok((
                r.get(0)?,
                r.get(1)?,
                r.get(2)?,
                r.get(3)?,
                r.get(4)?,
                r.get(5)?,
                r.get(6)?,
                r.get(7)?,
            ))
        })
        .and_then(|rows| rows.collect())
        .map_err(sql("reading the sessions"))?;
    let mut sessions = Vec::new();
    for (id, token, code, names_shown, created_ms, state, seq, model) in rows {
        let state = match state {
            Some(s) => Some(serde_json::from_str(&s).map_err(|e| corrupt("state", id.clone(), e))?),
            None => None,
        };
        let inner = Inner {
            names_shown,
            created_ms,
            state,
            seq: seq.max(0) as u64,
            current_model: model,
            models: models(conn, &id)?,
            questions: questions(conn, &id)?,
            students: students(conn, &id)?,
            ..Inner::default()
        };
        sessions.push(Stored {
            id,
            token,
            code,
            inner,
        });
    }
    Ok(sessions)
}

/// A session's model files, by id.
fn models(
    conn: &Connection,
    session: &str,
) -> Result<std::collections::HashMap<String, Arc<ModelFile>>, ServerError> {
    let mut stmt = conn
        .prepare("SELECT id, name, text FROM models WHERE session = ?1")
        .map_err(sql("reading the model files"))?;
    let rows = stmt
        .query_map([session], |r| {
            Ok(ModelFile {
                id: r.get(0)?,
                name: r.get(1)?,
                text: r.get(2)?,
            })
        })
        .and_then(|rows| rows.collect::<Result<Vec<_>, _>>())
        .map_err(sql("reading the model files"))?;
    Ok(rows
        .into_iter()
        .map(|m| (m.id.clone(), Arc::new(m)))
        .collect())
}

/// A session's students, in number order (number `k` at index `k - 1`).
fn students(conn: &Connection, session: &str) -> Result<Vec<Student>, ServerError> {
    let mut stmt = conn
        .prepare("SELECT number, name, resume FROM students WHERE session = ?1 ORDER BY number")
        .map_err(sql("reading the students"))?;
    let rows: Vec<(i64, String, String)> = stmt
        .query_map([session], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)))
        .and_then(|rows| rows.collect())
        .map_err(sql("reading the students"))?;
    let mut out = Vec::new();
    for (number, name, resume) in rows {
        if number != out.len() as i64 + 1 {
            return Err(corrupt(
                "student",
                format!("{session}/{number}"),
                format!("expected student {}", out.len() + 1),
            ));
        }
        out.push(Student {
            number: number as usize,
            name,
            resume,
        });
    }
    Ok(out)
}

/// A session's questions, each with its answers.
fn questions(conn: &Connection, session: &str) -> Result<BTreeMap<u64, Question>, ServerError> {
    let mut stmt = conn
        .prepare("SELECT id, request, key, sent, open FROM questions WHERE session = ?1")
        .map_err(sql("reading the questions"))?;
    type Row = (i64, String, Option<String>, String, bool);
    let rows: Vec<Row> = stmt
        .query_map([session], |r| {
            Ok((r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?, r.get(4)?))
        })
        .and_then(|rows| rows.collect())
        .map_err(sql("reading the questions"))?;
    let mut out = BTreeMap::new();
    for (id, request, key, sent, open) in rows {
        let row = || format!("{session}/{id}");
        let mut q = Question {
            request: serde_json::from_str(&request).map_err(|e| corrupt("question", row(), e))?,
            key: match key {
                Some(k) => Some(Arc::new(
                    serde_json::from_str(&k).map_err(|e| corrupt("key", row(), e))?,
                )),
                None => None,
            },
            out: serde_json::from_str(&sent).map_err(|e| corrupt("question", row(), e))?,
            answers: answers(conn, session, id)?,
        };
        q.out.open = open;
        out.insert(id as u64, q);
    }
    Ok(out)
}

/// A question's answers, by student number.
fn answers(
    conn: &Connection,
    session: &str,
    question: i64,
) -> Result<BTreeMap<usize, AnswerRecord>, ServerError> {
    let mut stmt = conn
        .prepare(
            "SELECT student, answer, graded, answered_ms FROM answers \
             WHERE session = ?1 AND question = ?2",
        )
        .map_err(sql("reading the answers"))?;
    let rows: Vec<(i64, String, String, i64)> = stmt
        .query_map(rusqlite::params![session, question], |r| {
            Ok((r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?))
        })
        .and_then(|rows| rows.collect())
        .map_err(sql("reading the answers"))?;
    let mut out = BTreeMap::new();
    for (student, answer, graded, at_ms) in rows {
        let row = || format!("{session}/{question}/{student}");
        out.insert(
            student as usize,
            AnswerRecord {
                answer: serde_json::from_str(&answer).map_err(|e| corrupt("answer", row(), e))?,
                graded: graded_from_json(&graded).map_err(|e| corrupt("grade", row(), e))?,
                at_ms,
            },
        );
    }
    Ok(out)
}

/// Makes and stores a new session: a session id, a teacher token of 128 random bits, a join
/// code no stored session has.
pub(crate) fn new_session(conn: &Connection, show_names: bool) -> Result<Stored, ServerError> {
    let code = loop {
        let code = join_code()?;
        let taken = conn
            .query_row(
                "SELECT 1 FROM sessions WHERE code = ?1",
                [&code],
                |_| Ok(()),
            )
            .optional()
            .map_err(sql("checking a join code"))?;
        if taken.is_none() {
            break code;
        }
    };
    let stored = Stored {
        id: random_hex(8)?,
        token: random_hex(SECRET_BYTES)?,
        code,
        inner: Inner {
            names_shown: show_names,
            created_ms: now_ms(),
            ..Inner::default()
        },
    };
    conn.execute(
        "INSERT INTO sessions (id, token, code, names_shown, created_ms) VALUES (?1, ?2, ?3, ?4, ?5)",
        rusqlite::params![
            stored.id,
            stored.token,
            stored.code,
            stored.inner.names_shown,
            stored.inner.created_ms
        ],
    )
    .map_err(sql("storing the new session"))?;
    Ok(stored)
}
