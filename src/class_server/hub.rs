//! Every session the server keeps, found by the teacher's token or the join code; the failed
//! join attempts per address; and joining: the welcome, then what the joiner must see at once
//! (the model, the state, the open questions; for the teacher their tallies and the roster).

use super::http::limits_message;
use super::limits::JoinAttempts;
use super::secret::{SECRET_BYTES, normalized_code, random_hex, same_secret};
use super::session::{Session, Student, frame};
use super::store::Write;
use crate::class::protocol::{Join, Role, ServerMessage, Welcome};
use axum::extract::ws::Utf8Bytes;
use std::net::IpAddr;
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Instant;
use tokio::sync::{broadcast, watch};

/// Every session, the attempts, and the server's shutdown signal.
#[derive(Debug)]
pub(crate) struct Hub {
    /// The sessions, oldest first.
    pub(crate) sessions: Vec<Arc<Session>>,
    /// Failed join attempts per address.
    attempts: Mutex<JoinAttempts>,
    /// Turns true when the server stops.
    pub(crate) shutdown: watch::Receiver<bool>,
    /// One clone per open WebSocket connection (its count tells when all have closed).
    pub(crate) connections: Arc<()>,
}

/// Who a joined connection is.
#[derive(Debug, Clone)]
pub(crate) enum Joiner {
    /// The teacher of the session.
    Teacher(Arc<Session>),
    /// Student `number` of the session.
    Student(Arc<Session>, usize),
}

/// A join that worked: who, their subscription to the session's messages, and the frames to
/// send first (the welcome, then the snapshot).
#[derive(Debug)]
pub(crate) struct Joined {
    /// Who joined.
    pub(crate) joiner: Joiner,
    /// The session's messages for them, from the moment of the snapshot on.
    pub(crate) subscription: broadcast::Receiver<Utf8Bytes>,
    /// The welcome and the snapshot.
    pub(crate) frames: Vec<Utf8Bytes>,
}

impl Hub {
    /// The hub of `sessions`, stopping when `shutdown` turns true.
    pub(crate) fn new(sessions: Vec<Arc<Session>>, shutdown: watch::Receiver<bool>) -> Self {
        Self {
            sessions,
            attempts: Mutex::new(JoinAttempts::default()),
            shutdown,
            connections: Arc::new(()),
        }
    }

    /// The session whose teacher token is `token`.
    pub(crate) fn by_token(&self, token: &str) -> Option<Arc<Session>> {
        self.sessions
            .iter()
            .find(|s| same_secret(&s.token, token))
            .cloned()
    }

    /// The session whose join code is `code` (any case, spaces around ignored).
    pub(crate) fn by_code(&self, code: &str) -> Option<Arc<Session>> {
        let code = normalized_code(code);
        self.sessions
            .iter()
            .find(|s| same_secret(&s.code, &code))
            .cloned()
    }

    /// Whether joins from `ip` are refused for now (too many failed attempts).
    pub(crate) fn blocked(&self, ip: IpAddr) -> bool {
        let mut a = self.attempts.lock().unwrap_or_else(PoisonError::into_inner);
        a.blocked(ip, Instant::now())
    }

    /// Counts a failed attempt of `ip`.
    pub(crate) fn failed(&self, ip: IpAddr, now: Instant) {
        let mut a = self.attempts.lock().unwrap_or_else(PoisonError::into_inner);
        a.failed(ip, now);
    }

    /// A join from `ip`: the teacher with the token, or a student with the code (a new
    /// student, or with `resume` an earlier one again). A wrong token or code is a failed
    /// attempt of the address; past the limit every join from it is refused for a while.
    pub(crate) async fn join(&self, join: Join, ip: IpAddr) -> Result<Joined, String> {
        if self.blocked(ip) {
            return Err(limits_message());
        }
        match join.role {
            Role::Teacher => {
                let Some(session) = join.token.as_deref().and_then(|t| self.by_token(t)) else {
                    self.failed(ip, Instant::now());
                    return Err("wrong teacher token".into());
                };
                Ok(join_teacher(session))
            }
            Role::Student => {
                let Some(session) = join.code.as_deref().and_then(|c| self.by_code(c)) else {
                    self.failed(ip, Instant::now());
                    return Err("wrong join code: no class session has it".into());
                };
                join_student(session, join.name, join.resume).await
            }
        }
    }
}

/// The welcome of a session.
fn welcome(session: &Session, role: Role, joined: usize, names_shown: bool) -> Welcome {
    Welcome {
        role,
        session: session.id.clone(),
        code: session.code.clone(),
        student_url: session.student_url.clone(),
        qr: session.qr.clone(),
        joined,
        names_shown,
        student: None,
        resume: None,
    }
}

/// The teacher joins: the welcome and the teacher's snapshot.
fn join_teacher(session: Arc<Session>) -> Joined {
    let inner = session.lock();
    let subscription = session.teachers_tx.subscribe();
    let w = welcome(&session, Role::Teacher, inner.joined(), inner.names_shown);
    let mut frames = vec![frame(&ServerMessage::Welcome(w))];
    frames.extend(session.teacher_snapshot(&inner));
    drop(inner);
    Joined {
        joiner: Joiner::Teacher(session),
        subscription,
        frames,
    }
}

/// A nickname as given: trimmed; none if empty.
fn nickname(name: Option<String>) -> Option<String> {
    name.map(|n| n.trim().to_string()).filter(|n| !n.is_empty())
}

/// A student joins (or comes back with `resume`): stored before the welcome is sent.
async fn join_student(
    session: Arc<Session>,
    name: Option<String>,
    resume: Option<String>,
) -> Result<Joined, String> {
    let name = nickname(name);
    let secret = random_hex(SECRET_BYTES).map_err(|e| e.to_string())?;
    let (number, changed, subscription, frames) = {
        let mut inner = session.lock();
        let earlier = resume.as_deref().and_then(|r| {
            inner
                .students
                .iter()
                .find(|s| same_secret(&s.resume, r))
                .map(|s| s.number)
        });
        let (number, changed) = match (earlier, name) {
            (Some(n), Some(name)) if inner.students[n - 1].name != name => {
                inner.students[n - 1].name = name;
                (n, true)
            }
            (Some(n), _) => (n, false),
            (None, Some(name)) => {
                let number = inner.students.len() + 1;
                inner.students.push(Student {
                    number,
                    name,
                    resume: secret,
                });
                (number, true)
            }
            (None, None) => {
                return Err(format!(
                    "a nickname is required: name, 1 to {} characters",
                    crate::class::protocol::MAX_NAME_CHARS
                ));
            }
        };
        *inner.online.entry(number).or_default() += 1;
        let subscription = session.students_tx.subscribe();
        let mut w = welcome(&session, Role::Student, inner.joined(), inner.names_shown);
        w.student = Some(number);
        w.resume = Some(inner.students[number - 1].resume.clone());
        let mut frames = vec![frame(&ServerMessage::Welcome(w))];
        frames.extend(session.student_snapshot(&inner));
        session.roster_changed(&inner);
        let changed = changed.then(|| inner.students[number - 1].clone());
        (number, changed, subscription, frames)
    };
    if let Some(student) = changed {
        let stored = session
            .db
            .write(Write::Student {
                session: session.id.clone(),
                student,
            })
            .await;
        if let Err(e) = stored {
            session.student_left(number);
            return Err(e);
        }
    }
    Ok(Joined {
        joiner: Joiner::Student(session, number),
        subscription,
        frames,
    })
}
