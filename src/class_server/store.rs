//! The class server's data file (SQLite through rusqlite, WAL journal): sessions, model files,
//! the latest state, questions with their keys, students and their answers. Opened and read
//! whole at start; then one writer thread owns the connection and takes writes from a channel,
//! so that no async task waits on the disk unless it asked to ([`Db::write`]: an answer is
//! stored before the student is told it arrived).

use super::ServerError;
use super::session::{AnswerRecord, ModelFile, Stored, Student};
use crate::class::grading::Graded;
use crate::exercise::{Grade, Item, Mistake};
use rusqlite::{Connection, params};
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::sync::Arc;
use std::sync::mpsc;
use std::thread::JoinHandle;
use tokio::sync::oneshot;

/// The tables (created if missing).
const SCHEMA: &str = "
CREATE TABLE IF NOT EXISTS sessions (
    id TEXT PRIMARY KEY, token TEXT NOT NULL, code TEXT NOT NULL UNIQUE,
    names_shown INTEGER NOT NULL, created_ms INTEGER NOT NULL,
    state TEXT, seq INTEGER NOT NULL DEFAULT 0, model TEXT);
CREATE TABLE IF NOT EXISTS models (
    session TEXT NOT NULL, id TEXT NOT NULL, name TEXT NOT NULL, text TEXT NOT NULL,
    PRIMARY KEY (session, id));
CREATE TABLE IF NOT EXISTS questions (
    session TEXT NOT NULL, id INTEGER NOT NULL, request TEXT NOT NULL, key TEXT,
    sent TEXT NOT NULL, open INTEGER NOT NULL, created_ms INTEGER NOT NULL,
    PRIMARY KEY (session, id));
CREATE TABLE IF NOT EXISTS students (
    session TEXT NOT NULL, number INTEGER NOT NULL, name TEXT NOT NULL, resume TEXT NOT NULL,
    PRIMARY KEY (session, number));
CREATE TABLE IF NOT EXISTS answers (
    session TEXT NOT NULL, question INTEGER NOT NULL, student INTEGER NOT NULL,
    answer TEXT NOT NULL, graded TEXT NOT NULL, score INTEGER, max INTEGER,
    mistakes TEXT NOT NULL, answered_ms INTEGER NOT NULL,
    PRIMARY KEY (session, question, student));
";

/// One write to the data file.
#[derive(Debug)]
pub(crate) enum Write {
    /// The latest state.
    State {
        /// The session.
        session: String,
        /// The state (JSON).
        state: String,
        /// Its number.
        seq: u64,
        /// The model students get on joining.
        model: Option<String>,
    },
    /// A model file (now the one students get on joining).
    Model {
        /// The session.
        session: String,
        /// The file.
        model: Arc<ModelFile>,
    },
    /// A new question.
    Question {
        /// The session.
        session: String,
        /// The request (JSON).
        request: String,
        /// The key (JSON), for an exercise.
        key: Option<String>,
        /// The question as students get it (JSON).
        sent: String,
        /// Its id.
        id: u64,
        /// When it was asked (ms since the Unix epoch).
        created_ms: i64,
    },
    /// A question closed.
    Closed {
        /// The session.
        session: String,
        /// The question.
        id: u64,
    },
    /// A student, new or renamed.
    Student {
        /// The session.
        session: String,
        /// The student.
        student: Student,
    },
    /// A student's answer (replacing their earlier one to the question).
    Answer {
        /// The session.
        session: String,
        /// The question.
        question: u64,
        /// The student's number.
        student: usize,
        /// The answer and its grade.
        record: AnswerRecord,
    },
}

/// What the writer thread is asked.
enum Job {
    /// A write, and where to say it is done.
    Write(Write, Option<oneshot::Sender<Result<(), String>>>),
    /// Stop after the writes queued before.
    Stop,
}

/// The way to the writer thread (cheap to clone).
#[derive(Debug, Clone)]
pub(crate) struct Db {
    /// The writer's queue.
    tx: mpsc::Sender<Job>,
}

impl std::fmt::Debug for Job {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Job")
    }
}

impl Db {
    /// Queues a write without waiting for it (a lost write is said on stderr by the writer).
    pub(crate) fn send(&self, w: Write) {
        let _ = self.tx.send(Job::Write(w, None));
    }

    /// Writes and waits until the write is on disk; the error in words.
    pub(crate) async fn write(&self, w: Write) -> Result<(), String> {
        let (done, wait) = oneshot::channel();
        self.tx
            .send(Job::Write(w, Some(done)))
            .map_err(|_| "the data file is closed (the server is stopping)".to_string())?;
        wait.await
            .unwrap_or_else(|_| Err("the data file's writer stopped".into()))
    }
}

/// The writer thread, to stop at shutdown.
#[derive(Debug)]
pub(crate) struct Writer {
    /// Its queue.
    tx: mpsc::Sender<Job>,
    /// The thread.
    thread: Option<JoinHandle<()>>,
}

impl Writer {
    /// Stops the writer after every write queued so far, and waits for it.
    pub(crate) fn stop(mut self) {
        let _ = self.tx.send(Job::Stop);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// What to do with the data file's sessions on opening it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Opening {
    /// Make a new session even if the file holds some.
    pub(crate) new_session: bool,
    /// The newest session (and a new one) shows the teacher the students' nicknames.
    pub(crate) show_names: bool,
}

/// Opens (or makes) the data file at `path`, reads every session in it (making a new one if it
/// holds none or `opening` asks for one), and starts its writer. The newest session is last.
pub(crate) fn open(
    path: &Path,
    opening: Opening,
) -> Result<(Db, Writer, Vec<Stored>), ServerError> {
    let conn = Connection::open(path).map_err(|source| ServerError::Open {
        path: path.to_path_buf(),
        source,
    })?;
    let sql = |what: &'static str| move |source| ServerError::Sql { what, source };
    conn.pragma_update(None, "journal_mode", "WAL")
        .map_err(sql("setting the WAL journal"))?;
    conn.pragma_update(None, "synchronous", "NORMAL")
        .map_err(sql("setting synchronous writes"))?;
    conn.busy_timeout(std::time::Duration::from_secs(5))
        .map_err(sql("setting the busy timeout"))?;
    conn.execute_batch(SCHEMA)
        .map_err(sql("making the tables"))?;
    let mut sessions = super::load::load(&conn)?;
    if sessions.is_empty() || opening.new_session {
        sessions.push(super::load::new_session(&conn, opening.show_names)?);
    } else if opening.show_names
        && let Some(newest) = sessions.last_mut()
    {
        newest.inner.names_shown = true;
        conn.execute(
            "UPDATE sessions SET names_shown = 1 WHERE id = ?1",
            [&newest.id],
        )
        .map_err(sql("showing names"))?;
    }
    let (tx, rx) = mpsc::channel();
    let thread = std::thread::Builder::new()
        .name("armlab-class-store".into())
        .spawn(move || writer(conn, rx))
        .map_err(|source| ServerError::Runtime { source })?;
    Ok((
        Db { tx: tx.clone() },
        Writer {
            tx,
            thread: Some(thread),
        },
        sessions,
    ))
}

/// The writer thread: each write in order, its outcome to whoever waits for it.
fn writer(conn: Connection, rx: mpsc::Receiver<Job>) {
    while let Ok(job) = rx.recv() {
        match job {
            Job::Write(w, done) => {
                let outcome = apply(&conn, &w).map_err(|e| format!("cannot store: {e}"));
                if let Err(e) = &outcome
                    && done.is_none()
                {
                    eprintln!("armlab class: {e}");
                }
                if let Some(done) = done {
                    let _ = done.send(outcome);
                }
            }
            Job::Stop => break,
        }
    }
}

/// One write as SQL.
fn apply(conn: &Connection, w: &Write) -> rusqlite::Result<()> {
    match w {
        Write::State {
            session,
            state,
            seq,
            model,
        } => conn.execute(
            "UPDATE sessions SET state = ?2, seq = ?3, model = ?4 WHERE id = ?1",
            params![session, state, *seq as i64, model],
        ),
        Write::Model { session, model } => write_model(conn, session, model),
        Write::Question {
            session,
            request,
            key,
            sent,
            id,
            created_ms,
        } => conn.execute(
            "INSERT OR REPLACE INTO questions (session, id, request, key, sent, open, created_ms) \
             VALUES (?1, ?2, ?3, ?4, ?5, 1, ?6)",
            params![session, *id as i64, request, key, sent, created_ms],
        ),
        Write::Closed { session, id } => conn.execute(
            "UPDATE questions SET open = 0 WHERE session = ?1 AND id = ?2",
            params![session, *id as i64],
        ),
        Write::Student { session, student } => conn.execute(
            "INSERT OR REPLACE INTO students (session, number, name, resume) VALUES (?1, ?2, ?3, ?4)",
            params![session, student.number as i64, student.name, student.resume],
        ),
        Write::Answer {
            session,
            question,
            student,
            record,
        } => write_answer(conn, session, *question, *student, record),
    }
    .map(|_| ())
}

/// A model file, and the session's current model.
fn write_model(conn: &Connection, session: &str, model: &ModelFile) -> rusqlite::Result<usize> {
    conn.execute(
        "INSERT OR REPLACE INTO models (session, id, name, text) VALUES (?1, ?2, ?3, ?4)",
        params![session, model.id, model.name, model.text],
    )?;
    conn.execute(
        "UPDATE sessions SET model = ?2 WHERE id = ?1",
        params![session, model.id],
    )
}

/// An answer, replacing the student's earlier one.
fn write_answer(
    conn: &Connection,
    session: &str,
    question: u64,
    student: usize,
    r: &AnswerRecord,
) -> rusqlite::Result<usize> {
    let (score, max) = match &r.graded {
        Graded::Exercise(g) => (Some(g.score as i64), Some(g.max as i64)),
        _ => (None, None),
    };
    let mistakes = super::export::mistakes(&r.graded).join(";");
    conn.execute(
        "INSERT OR REPLACE INTO answers \
         (session, question, student, answer, graded, score, max, mistakes, answered_ms) \
         VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9)",
        params![
            session,
            question as i64,
            student as i64,
            r.answer.to_string(),
            graded_json(&r.graded),
            score,
            max,
            mistakes,
            r.at_ms
        ],
    )
}

/// A graded answer as stored: the grade with its items and named mistakes.
#[derive(Debug, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
enum GradedRecord {
    /// A poll's choice.
    Choice(usize),
    /// An exercise's grade.
    Exercise {
        /// Items right.
        score: usize,
        /// Items.
        max: usize,
        /// Each item.
        items: Vec<ItemRecord>,
    },
    /// An answer of the wrong shape, and why.
    Unreadable(String),
}

/// A graded item as stored.
#[derive(Debug, Serialize, Deserialize)]
struct ItemRecord {
    /// What it is.
    item: String,
    /// Right or not.
    correct: bool,
    /// In words.
    feedback: String,
    /// The mistake, named.
    mistake: Option<Mistake>,
}

/// `g` as its stored JSON.
pub(crate) fn graded_json(g: &Graded) -> String {
    let record = match g {
        Graded::Choice(c) => GradedRecord::Choice(*c),
        Graded::Unreadable(why) => GradedRecord::Unreadable(why.clone()),
        Graded::Exercise(grade) => GradedRecord::Exercise {
            score: grade.score,
            max: grade.max,
            items: grade
                .items
                .iter()
                .map(|i| ItemRecord {
                    item: i.item.clone(),
                    correct: i.correct,
                    feedback: i.feedback.clone(),
                    mistake: i.mistake,
                })
                .collect(),
        },
    };
    serde_json::to_string(&record).unwrap_or_default()
}

/// The grade stored as `text`.
pub(crate) fn graded_from_json(text: &str) -> Result<Graded, serde_json::Error> {
    Ok(match serde_json::from_str(text)? {
        GradedRecord::Choice(c) => Graded::Choice(c),
        GradedRecord::Unreadable(why) => Graded::Unreadable(why),
        GradedRecord::Exercise { score, max, items } => Graded::Exercise(Grade {
            score,
            max,
            items: items
                .into_iter()
                .map(|i| Item {
                    item: i.item,
                    correct: i.correct,
                    feedback: i.feedback,
                    mistake: i.mistake,
                })
                .collect(),
        }),
    })
}
