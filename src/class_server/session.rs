//! One class session in memory: its secrets (the teacher token, the join code), what the
//! teacher shows (the latest state and model), the questions with their keys and answers, the
//! students, and the two broadcast channels (to the students, to the teacher's connections)
//! every message is serialized once for. The teacher's and the students' operations are in
//! [`super::teacher`] and [`super::student`].

use super::store::{Db, Write};
use crate::class::grading::{Graded, tally};
use crate::class::protocol::{ClassState, QuestionOut, QuestionRequest, ServerMessage, Tally};
use crate::exercise::Key;
use axum::extract::ws::Utf8Bytes;
use std::collections::{BTreeMap, HashMap};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use tokio::sync::broadcast;

/// Messages a student's connection may fall behind by before it is brought up to date from the
/// session's snapshot (at 30 states a second: about half a minute).
const STUDENT_BACKLOG: usize = 1024;
/// The same for a teacher's connection (tallies and rosters).
const TEACHER_BACKLOG: usize = 4096;

/// A model file the teacher sent.
#[derive(Debug)]
pub(crate) struct ModelFile {
    /// The server's id of it: a hash of its name and contents, hex.
    pub(crate) id: String,
    /// The file's name (its extension tells the format).
    pub(crate) name: String,
    /// Its contents.
    pub(crate) text: String,
}

/// One student of the session.
#[derive(Debug, Clone)]
pub(crate) struct Student {
    /// Their number (1-based).
    pub(crate) number: usize,
    /// Their nickname.
    pub(crate) name: String,
    /// The secret that makes a reconnecting client the same student.
    pub(crate) resume: String,
}

/// A student's answer to a question (their last one).
#[derive(Debug, Clone)]
pub(crate) struct AnswerRecord {
    /// What they sent.
    pub(crate) answer: serde_json::Value,
    /// Its grade.
    pub(crate) graded: Graded,
    /// When it arrived (ms since the Unix epoch).
    pub(crate) at_ms: i64,
}

/// A question of the session.
#[derive(Debug, Clone)]
pub(crate) struct Question {
    /// What the teacher asked.
    pub(crate) request: QuestionRequest,
    /// An exercise's key (never sent to anyone).
    pub(crate) key: Option<Arc<Key>>,
    /// The question as the students receive it.
    pub(crate) out: QuestionOut,
    /// Each student's last answer, by number.
    pub(crate) answers: BTreeMap<usize, AnswerRecord>,
}

impl Question {
    /// The question's id.
    pub(crate) fn id(&self) -> u64 {
        self.out.id
    }

    /// Whether answers are still taken.
    pub(crate) fn open(&self) -> bool {
        self.out.open
    }

    /// The room's answers so far, `joined` the students connected now.
    pub(crate) fn tally(&self, joined: usize) -> Tally {
        let answers: Vec<Graded> = self.answers.values().map(|a| a.graded.clone()).collect();
        tally(
            self.id(),
            self.request.kind,
            &self.request.choices,
            self.request.correct,
            &answers,
            joined,
        )
    }
}

/// What a session holds that changes: behind the session's lock.
#[derive(Debug, Default)]
pub(crate) struct Inner {
    /// Whether the teacher sees nicknames.
    pub(crate) names_shown: bool,
    /// When the session was made (ms since the Unix epoch).
    pub(crate) created_ms: i64,
    /// The latest state the teacher sent.
    pub(crate) state: Option<ClassState>,
    /// Its number (0 before the first).
    pub(crate) seq: u64,
    /// Whether the state changed since it was last written to the data file.
    pub(crate) state_dirty: bool,
    /// The model files the teacher sent, by id.
    pub(crate) models: HashMap<String, Arc<ModelFile>>,
    /// The model students get when they join (the one sent last, or the one the state names).
    pub(crate) current_model: Option<String>,
    /// The questions, by id.
    pub(crate) questions: BTreeMap<u64, Question>,
    /// The students, number `k` at index `k - 1`.
    pub(crate) students: Vec<Student>,
    /// Connections open now, per student number.
    pub(crate) online: HashMap<usize, usize>,
}

impl Inner {
    /// Students connected now.
    pub(crate) fn joined(&self) -> usize {
        self.online.values().filter(|n| **n > 0).count()
    }

    /// The roster the teacher sees: students connected now, their nicknames where the session
    /// shows names.
    pub(crate) fn roster(&self) -> ServerMessage {
        let names = if self.names_shown {
            let mut numbers: Vec<usize> = self
                .online
                .iter()
                .filter(|(_, n)| **n > 0)
                .map(|(k, _)| *k)
                .collect();
            numbers.sort_unstable();
            numbers
                .iter()
                .filter_map(|k| self.students.get(k - 1))
                .map(|s| s.name.clone())
                .collect()
        } else {
            Vec::new()
        };
        ServerMessage::Roster {
            joined: self.joined(),
            names,
        }
    }

    /// The model students get when they join, as its message.
    pub(crate) fn current_model_message(&self) -> Option<ServerMessage> {
        let model = self.models.get(self.current_model.as_ref()?)?;
        Some(ServerMessage::Model {
            id: model.id.clone(),
            name: model.name.clone(),
            text: model.text.clone(),
        })
    }

    /// The next question's id.
    pub(crate) fn next_question(&self) -> u64 {
        self.questions.keys().next_back().map_or(1, |k| k + 1)
    }
}

/// A session as stored: its secrets and what it holds.
#[derive(Debug)]
pub(crate) struct Stored {
    /// The session's id.
    pub(crate) id: String,
    /// The teacher's token.
    pub(crate) token: String,
    /// The join code.
    pub(crate) code: String,
    /// The rest.
    pub(crate) inner: Inner,
}

/// One class session.
#[derive(Debug)]
pub(crate) struct Session {
    /// The session's id.
    pub(crate) id: String,
    /// The teacher's token.
    pub(crate) token: String,
    /// The join code.
    pub(crate) code: String,
    /// The students' link.
    pub(crate) student_url: String,
    /// The link as QR rows.
    pub(crate) qr: Vec<String>,
    /// The data file.
    pub(crate) db: Db,
    /// Every message for the students, serialized once.
    pub(crate) students_tx: broadcast::Sender<Utf8Bytes>,
    /// Every message for the teacher's connections.
    pub(crate) teachers_tx: broadcast::Sender<Utf8Bytes>,
    /// What changes.
    inner: Mutex<Inner>,
}

/// A server message as its text frame, ready to share.
pub(crate) fn frame(m: &ServerMessage) -> Utf8Bytes {
    m.to_text().into()
}

/// An error message as its text frame.
pub(crate) fn error_frame(message: impl Into<String>) -> Utf8Bytes {
    frame(&ServerMessage::Error {
        message: message.into(),
    })
}

impl Session {
    /// The session of `stored`, reached at `student_url`.
    pub(crate) fn new(stored: Stored, student_url: String, db: Db) -> Self {
        let qr = super::qr::qr_rows(&student_url);
        Self {
            id: stored.id,
            token: stored.token,
            code: stored.code,
            student_url,
            qr,
            db,
            students_tx: broadcast::channel(STUDENT_BACKLOG).0,
            teachers_tx: broadcast::channel(TEACHER_BACKLOG).0,
            inner: Mutex::new(stored.inner),
        }
    }

    /// The session's lock (a poisoned lock is taken as it is: every change is complete).
    pub(crate) fn lock(&self) -> MutexGuard<'_, Inner> {
        self.inner.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Sends `m` to every student (none listening is no error).
    pub(crate) fn to_students(&self, m: &ServerMessage) {
        let _ = self.students_tx.send(frame(m));
    }

    /// Sends `m` to every teacher connection.
    pub(crate) fn to_teachers(&self, m: &ServerMessage) {
        let _ = self.teachers_tx.send(frame(m));
    }

    /// What a student gets on joining (and after falling behind): the model, the state, the
    /// open questions.
    pub(crate) fn student_snapshot(&self, inner: &Inner) -> Vec<Utf8Bytes> {
        let mut out = Vec::new();
        if let Some(m) = inner.current_model_message() {
            out.push(frame(&m));
        }
        if let Some(state) = &inner.state {
            out.push(frame(&ServerMessage::State {
                state: state.clone(),
                seq: inner.seq,
            }));
        }
        for q in inner.questions.values().filter(|q| q.open()) {
            out.push(frame(&ServerMessage::Question(q.out.clone())));
        }
        out
    }

    /// The roster changed (a student joined or left): the teacher gets it, and each open
    /// question's tally with its new count of students (its "answered 3 of N").
    pub(crate) fn roster_changed(&self, inner: &Inner) {
        let joined = inner.joined();
        for q in inner.questions.values().filter(|q| q.open()) {
            self.to_teachers(&ServerMessage::Tally(q.tally(joined)));
        }
        self.to_teachers(&inner.roster());
    }

    /// What a teacher gets on joining: the students' snapshot, each open question's tally, the
    /// roster.
    pub(crate) fn teacher_snapshot(&self, inner: &Inner) -> Vec<Utf8Bytes> {
        let mut out = self.student_snapshot(inner);
        let joined = inner.joined();
        for q in inner.questions.values().filter(|q| q.open()) {
            out.push(frame(&ServerMessage::Tally(q.tally(joined))));
        }
        out.push(frame(&inner.roster()));
        out
    }

    /// Writes the state to the data file if it changed since the last write.
    pub(crate) fn flush_state(&self) {
        let mut inner = self.lock();
        if !inner.state_dirty {
            return;
        }
        inner.state_dirty = false;
        let Some(state) = &inner.state else {
            return;
        };
        self.db.send(Write::State {
            session: self.id.clone(),
            state: serde_json::to_string(state).unwrap_or_default(),
            seq: inner.seq,
            model: inner.current_model.clone(),
        });
    }

    /// A student's connection closed (or left): the roster changes.
    pub(crate) fn student_left(&self, number: usize) {
        let mut inner = self.lock();
        if let Some(n) = inner.online.get_mut(&number) {
            *n = n.saturating_sub(1);
            if *n == 0 {
                inner.online.remove(&number);
            }
        }
        self.roster_changed(&inner);
    }
}
