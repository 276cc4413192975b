//! The live classroom's messages: JSON text frames on the server's `/ws`, one object each,
//! tagged by `"type"`. The guide's chapter "A live class" documents them for other clients (a
//! notebook, a test); the names here are the wire's.
//!
//! A client's first message is [`ClientMessage::Join`]; the server answers
//! [`ServerMessage::Welcome`] or [`ServerMessage::Error`]. Then the teacher drives
//! ([`ClientMessage::State`], [`ClientMessage::Model`], [`ClientMessage::Question`], ...) and
//! students answer ([`ClientMessage::Answer`]); the server relays the state to the students and
//! sends the teacher a [`Tally`] after each answer.
//!
//! Every message a client sends is read by [`parse_client`], which bounds its size (at most
//! [`MAX_MESSAGE_BYTES`]; a teacher's model file at most [`MAX_MODEL_BYTES`]) before and after
//! reading it, and answers what cannot be read with a [`ProtocolError`] naming the field.

use crate::exercise::{Kind, SheetFile};
use crate::lesson::Step;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::collections::BTreeMap;
use thiserror::Error;

/// The most bytes a client message may have (a model file excepted).
pub const MAX_MESSAGE_BYTES: usize = 64 * 1024;

/// The most bytes of a model file's contents the teacher may send ([`ClientMessage::Model`]).
pub const MAX_MODEL_BYTES: usize = 8 * 1024 * 1024;

/// The most characters of a student's nickname.
pub const MAX_NAME_CHARS: usize = 40;

/// The most choices of a poll.
pub const MAX_CHOICES: usize = 16;

/// Who a connection is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Role {
    /// Drives the session: the only role that may send the state, questions and the model, and
    /// see answers.
    Teacher,
    /// Follows and answers.
    Student,
}

/// The first message of a connection: `{"type": "join", "role": "teacher", "token": T}` or
/// `{"type": "join", "role": "student", "code": C, "name": N}`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Join {
    /// Teacher or student.
    pub role: Role,
    /// The teacher's secret token (teacher).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub token: Option<String>,
    /// The session's join code (student).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub code: Option<String>,
    /// The student's nickname (student; at most [`MAX_NAME_CHARS`] characters, shown as text).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// The secret a student got in an earlier welcome: the same student again after a
    /// reconnect (their answers stay theirs, counted once).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub resume: Option<String>,
}

/// Where the students' app gets the teacher's robot.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum RobotRef {
    /// A built-in robot, by name (`"puma560"`).
    Builtin(String),
    /// A model file the teacher sent ([`ClientMessage::Model`]), by the id the server gave it
    /// ([`ServerMessage::Model`] carries its contents).
    Model {
        /// The server's id of the contents.
        id: String,
        /// The file's name (its extension tells the format: `.toml`, `.urdf`).
        name: String,
    },
}

/// Where a lesson stands, for the caption under the students' view.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LessonAt {
    /// The lesson's title.
    pub title: String,
    /// The step shown (1-based).
    pub step: usize,
    /// The lesson's number of steps.
    pub steps: usize,
}

/// What the teacher shows, as every student's app draws it itself: the robot, the joints, and
/// the rest of the setup as a lesson step (the IK target, the camera, the tab, the overlays, the
/// construction's step, the figure, the orientation lab, the cell; its caption the lesson's).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClassState {
    /// The robot.
    pub robot: RobotRef,
    /// The joint values (rad; m for prismatic joints).
    pub q: Vec<f64>,
    /// The rest of the setup, as "Save as lesson" writes a step (its `q` left out: [`Self::q`]
    /// holds it).
    #[serde(default)]
    pub view: Step,
    /// The lesson being played, if one is.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lesson: Option<LessonAt>,
}

/// What a question asks: a quick poll, or an exercise of one of [`Kind`]s (its JSON name:
/// `"poll"`, `"dh-table"`, `"fk"`, ...).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum QuestionKind {
    /// Choose one of the choices.
    Poll,
    /// An exercise, graded by [`crate::exercise::grade`].
    Exercise(Kind),
}

impl QuestionKind {
    /// The JSON name (`"poll"`, `"dh-table"`).
    pub fn name(self) -> &'static str {
        match self {
            QuestionKind::Poll => "poll",
            QuestionKind::Exercise(k) => k.name(),
        }
    }

    /// The kind named `name`, if any.
    pub fn from_name(name: &str) -> Option<Self> {
        if name == "poll" {
            return Some(QuestionKind::Poll);
        }
        Kind::ALL
            .iter()
            .find(|k| k.name() == name)
            .map(|k| QuestionKind::Exercise(*k))
    }
}

impl Serialize for QuestionKind {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for QuestionKind {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let name = String::deserialize(d)?;
        QuestionKind::from_name(&name).ok_or_else(|| {
            let kinds: Vec<&str> = std::iter::once("poll")
                .chain(Kind::ALL.iter().map(|k| k.name()))
                .collect();
            serde::de::Error::custom(format!(
                "unknown question kind {name:?}, expected one of {}",
                kinds.join(", ")
            ))
        })
    }
}

/// The teacher's question: `{"type": "question", "kind": "poll", "choices": [...]}` or an
/// exercise kind (`{"type": "question", "kind": "dh-table"}`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct QuestionRequest {
    /// A poll or an exercise kind.
    pub kind: QuestionKind,
    /// What a poll asks ("Which posture is this?"; shown as text).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub prompt: Option<String>,
    /// A poll's choices, in order (at most [`MAX_CHOICES`]; shown as text).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub choices: Vec<String>,
    /// A poll's right choice (0-based), if it has one: the tally's correct share counts it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub correct: Option<usize>,
    /// An exercise's arm: a built-in's name; absent, the session's robot (the arm kinds).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub robot: Option<String>,
    /// An exercise's seed (absent: drawn by the server).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// Students see their own grade, item by item, when they answer (absent: only that the
    /// answer arrived).
    #[serde(default)]
    pub feedback: bool,
}

/// What a client sends.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
// A message lives for one frame (parsed, handled, dropped): the state's size in the enum costs
// nothing worth a box in every constructor.
#[allow(clippy::large_enum_variant)]
pub enum ClientMessage {
    /// The first message (either role).
    Join(Join),
    /// Teacher: what every following student shows.
    State {
        /// The state.
        state: ClassState,
    },
    /// Teacher: a model file's contents (at most [`MAX_MODEL_BYTES`]), for a state whose robot
    /// is [`RobotRef::Model`]; answered by [`ServerMessage::Model`] with its id.
    Model {
        /// The file's name (`arm.urdf`, `arm.toml`).
        name: String,
        /// Its contents.
        text: String,
    },
    /// Teacher: asks the class.
    Question(QuestionRequest),
    /// Teacher: stops taking answers to question `id`.
    Close {
        /// The question.
        id: u64,
    },
    /// Teacher: shows the tally of question `id` to the class, anonymised (no names).
    Show {
        /// The question.
        id: u64,
    },
    /// Teacher: brings every student back to following.
    Follow,
    /// Teacher: the session's answers as CSV ([`ServerMessage::Export`]).
    Export,
    /// Student: an answer to question `id`: a poll's choice (its index), an exercise's answer
    /// as its file's text (a DH table as a model file, rows of numbers, names, or an
    /// orientation's lines).
    Answer {
        /// The question.
        id: u64,
        /// The answer.
        answer: serde_json::Value,
    },
    /// Either: leaves the session (a student's answers stay).
    Leave,
}

impl ClientMessage {
    /// The message's `"type"`, for errors and logs.
    pub fn type_name(&self) -> &'static str {
        match self {
            ClientMessage::Join(_) => "join",
            ClientMessage::State { .. } => "state",
            ClientMessage::Model { .. } => "model",
            ClientMessage::Question(_) => "question",
            ClientMessage::Close { .. } => "close",
            ClientMessage::Show { .. } => "show",
            ClientMessage::Follow => "follow",
            ClientMessage::Export => "export",
            ClientMessage::Answer { .. } => "answer",
            ClientMessage::Leave => "leave",
        }
    }

    /// Whether a student may send it (join, answer, leave).
    pub fn allowed_for_student(&self) -> bool {
        matches!(
            self,
            ClientMessage::Join(_) | ClientMessage::Answer { .. } | ClientMessage::Leave
        )
    }
}

/// The welcome of a joined client.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Welcome {
    /// Teacher or student.
    pub role: Role,
    /// The session's id.
    pub session: String,
    /// The session's join code.
    pub code: String,
    /// The students' link (`http://HOST:PORT/?code=C`).
    pub student_url: String,
    /// The students' link as a QR code: one string per row of modules, `#` dark, ` ` light
    /// (no quiet zone), for any client to draw.
    pub qr: Vec<String>,
    /// Students joined now.
    pub joined: usize,
    /// Whether the teacher sees the students' nicknames.
    pub names_shown: bool,
    /// The student's number in the session (1-based; students only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub student: Option<usize>,
    /// The student's secret for [`Join::resume`] after a reconnect (students only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub resume: Option<String>,
}

/// A question as the students receive it: a poll's prompt and choices, or an exercise's sheet
/// (the student's part, [`SheetFile`]: never its key).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QuestionOut {
    /// The question's id in the session.
    pub id: u64,
    /// A poll or an exercise kind.
    pub kind: QuestionKind,
    /// A poll's prompt.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub prompt: Option<String>,
    /// A poll's choices.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub choices: Vec<String>,
    /// An exercise's sheet.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sheet: Option<Box<SheetFile>>,
    /// Whether answers are still taken.
    pub open: bool,
}

/// One graded item as a student sees it (with feedback on).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GradedItem {
    /// What it is ("row 3").
    pub item: String,
    /// Right or not.
    pub correct: bool,
    /// In words.
    pub feedback: String,
}

/// A student's grade, as they see it (with feedback on).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StudentGrade {
    /// Items right.
    pub score: usize,
    /// Items.
    pub max: usize,
    /// Each item.
    pub items: Vec<GradedItem>,
}

/// The room's answers to one question, as the teacher sees them after each answer (and the
/// class, anonymised, when the teacher shows it).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Tally {
    /// The question.
    pub id: u64,
    /// Its kind.
    pub kind: QuestionKind,
    /// Students who answered (each counted once: their last answer).
    pub answered: usize,
    /// Students in the session: joined now, or who answered.
    pub joined: usize,
    /// A poll: how many chose each choice. An exercise: how many scored 0, 1, ..., `max`.
    pub counts: Vec<usize>,
    /// An exercise's number of items (0 for a poll).
    #[serde(default)]
    pub max: usize,
    /// Answers entirely right, in % of those answered (0 where none answered, or a poll has
    /// no right choice).
    pub correct_percent: f64,
    /// Each named mistake ("row 3: alpha with the wrong sign (z turned the other way)") and
    /// how many answers made it.
    pub mistakes: BTreeMap<String, usize>,
    /// Answers that could not be read (the wrong shape), counted apart.
    #[serde(default)]
    pub unreadable: usize,
    /// A poll's choices (for the bars' labels).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub choices: Vec<String>,
}

/// What the server sends.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
// A message lives for one frame (parsed, handled, dropped): the state's size in the enum costs
// nothing worth a box in every constructor.
#[allow(clippy::large_enum_variant)]
pub enum ServerMessage {
    /// The join worked.
    Welcome(Welcome),
    /// A message could not be taken; the connection goes on (unless it never joined).
    Error {
        /// What was wrong, in words.
        message: String,
    },
    /// What the teacher shows (to students: every state the teacher sends; to a late or
    /// reconnected one at once).
    State {
        /// The state.
        state: ClassState,
        /// The state's number in the session (1, 2, ...): a gap means states were skipped.
        seq: u64,
    },
    /// A model file's contents, for a [`RobotRef::Model`] (before the first state naming it).
    Model {
        /// Its id.
        id: String,
        /// Its name.
        name: String,
        /// Its contents.
        text: String,
    },
    /// A question (students; the teacher gets it back with its id).
    Question(QuestionOut),
    /// Student: the answer arrived (and was graded: with feedback on, the grade).
    Received {
        /// The question.
        id: u64,
        /// The grade, where the question gives feedback.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        grade: Option<StudentGrade>,
    },
    /// The question takes no more answers.
    Closed {
        /// The question.
        id: u64,
    },
    /// Teacher: the room's answers so far (after each answer).
    Tally(Tally),
    /// Students: the tally the teacher shows the class (no names in it).
    Results(Tally),
    /// Students: follow the teacher again.
    Follow,
    /// Teacher: who is in the session (after each join and leave).
    Roster {
        /// Students joined now.
        joined: usize,
        /// Their nicknames, where the session shows names (else empty).
        names: Vec<String>,
    },
    /// Teacher: the session's answers as CSV.
    Export {
        /// The CSV text (a header line, then one line per answer).
        csv: String,
    },
}

/// What is wrong with a client's message.
#[derive(Debug, Error, PartialEq)]
pub enum ProtocolError {
    /// More bytes than allowed.
    #[error("message too large: {bytes} bytes, at most {limit}")]
    Oversized {
        /// Its size.
        bytes: usize,
        /// The limit for its kind.
        limit: usize,
    },
    /// Not a message of the protocol.
    #[error("malformed message: {reason}")]
    Malformed {
        /// serde's words, naming the field.
        reason: String,
    },
    /// A message's field outside what it may hold.
    #[error("{field}: {reason}")]
    Field {
        /// The field (`name`, `choices`).
        field: &'static str,
        /// What is wrong.
        reason: String,
    },
}

/// Reads a client's message: at most [`MAX_MESSAGE_BYTES`] (a model file at most
/// [`MAX_MODEL_BYTES`] of contents), then its fields checked (a nickname's length and
/// characters, a poll's choices, finite joint values). Never panics, whatever `text` holds.
///
/// # Examples
///
/// ```
/// use armlab::class::protocol::{ClientMessage, Role, parse_client};
///
/// let m = parse_client(r#"{"type": "join", "role": "student", "code": "K7QX2M", "name": "Ada"}"#)?;
/// let ClientMessage::Join(join) = m else { panic!() };
/// assert_eq!(join.role, Role::Student);
/// assert!(parse_client(r#"{"type": "join", "role": "pirate"}"#).is_err());
/// # Ok::<(), armlab::class::protocol::ProtocolError>(())
/// ```
pub fn parse_client(text: &str) -> Result<ClientMessage, ProtocolError> {
    // Room for the contents' JSON escaping and the envelope.
    let model_limit = MAX_MODEL_BYTES + MAX_MODEL_BYTES / 8 + MAX_MESSAGE_BYTES;
    if text.len() > model_limit {
        return Err(ProtocolError::Oversized {
            bytes: text.len(),
            limit: MAX_MESSAGE_BYTES,
        });
    }
    let message: ClientMessage =
        serde_json::from_str(text).map_err(|e| ProtocolError::Malformed {
            reason: e.to_string(),
        })?;
    match &message {
        ClientMessage::Model { text: contents, .. } if contents.len() > MAX_MODEL_BYTES => {
            return Err(ProtocolError::Oversized {
                bytes: contents.len(),
                limit: MAX_MODEL_BYTES,
            });
        }
        ClientMessage::Model { .. } => {}
        _ if text.len() > MAX_MESSAGE_BYTES => {
            return Err(ProtocolError::Oversized {
                bytes: text.len(),
                limit: MAX_MESSAGE_BYTES,
            });
        }
        _ => {}
    }
    check_fields(&message)?;
    Ok(message)
}

/// The checks serde cannot make.
fn check_fields(message: &ClientMessage) -> Result<(), ProtocolError> {
    let field = |field: &'static str, reason: String| Err(ProtocolError::Field { field, reason });
    match message {
        ClientMessage::Join(j) => {
            if let Some(name) = &j.name {
                let n = name.chars().count();
                if n > MAX_NAME_CHARS {
                    return field("name", format!("{n} characters, at most {MAX_NAME_CHARS}"));
                }
                if name.chars().any(char::is_control) {
                    return field("name", "holds a control character".into());
                }
            }
        }
        ClientMessage::State { state } if state.q.iter().any(|v| !v.is_finite()) => {
            return field("state.q", "a value that is not finite".into());
        }
        ClientMessage::Model { name, .. } if name.chars().count() > 200 => {
            return field("name", "longer than 200 characters".into());
        }
        ClientMessage::Question(q) => {
            if q.kind == QuestionKind::Poll {
                if q.choices.len() < 2 || q.choices.len() > MAX_CHOICES {
                    return field(
                        "choices",
                        format!("{} choices; a poll has 2 to {MAX_CHOICES}", q.choices.len()),
                    );
                }
                if q.correct.is_some_and(|c| c >= q.choices.len()) {
                    return field("correct", "not the index of a choice".into());
                }
            } else if !q.choices.is_empty() || q.correct.is_some() {
                return field("choices", "only a poll has choices".into());
            }
        }
        _ => {}
    }
    Ok(())
}

/// Reads a server's message (for clients: the app, the tests).
pub fn parse_server(text: &str) -> Result<ServerMessage, ProtocolError> {
    serde_json::from_str(text).map_err(|e| ProtocolError::Malformed {
        reason: e.to_string(),
    })
}

impl ServerMessage {
    /// The message as its JSON text frame.
    pub fn to_text(&self) -> String {
        serde_json::to_string(self).expect("a server message is plain data")
    }
}

impl ClientMessage {
    /// The message as its JSON text frame.
    pub fn to_text(&self) -> String {
        serde_json::to_string(self).expect("a client message is plain data")
    }
}
