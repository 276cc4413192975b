//! What the teacher does to a session: the state (relayed to every student, serialized once),
//! model files, questions (an exercise's sheet made on the server, its key kept there), closing
//! and showing them, bringing students back to following, the CSV export. Each returns the
//! error the teacher gets, in words.

use super::load::now_ms;
use super::session::{ModelFile, Question, Session, frame};
use super::store::Write;
use crate::class::protocol::{
    ClassState, QuestionKind, QuestionOut, QuestionRequest, RobotRef, ServerMessage,
};
use crate::exercise::{Key, SheetFile, generate};
use crate::kinematics::Robot;
use std::sync::Arc;

/// Where a question's arm comes from.
enum ArmSource {
    /// None: the exercise draws one (or an orientation kind needs none).
    None,
    /// A built-in robot, by name.
    Builtin(String),
    /// A model file the teacher sent.
    Model(Arc<ModelFile>),
}

/// An id for a model file: FNV-1a (64 bits) of its name and contents, hex. Not a secret: it
/// names the contents so that a client can tell a model it already has.
pub(crate) fn model_id(name: &str, text: &str) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in name.bytes().chain([0]).chain(text.bytes()) {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    format!("{h:016x}")
}

impl Session {
    /// The teacher's state: numbered, kept, and sent to every student. A state whose robot is
    /// a model file names one the teacher sent (students who lack it get it first).
    pub(crate) fn set_state(&self, state: ClassState) -> Result<(), String> {
        let mut inner = self.lock();
        if let RobotRef::Model { id, .. } = &state.robot {
            if !inner.models.contains_key(id) {
                return Err(format!(
                    "state: the robot names model {id:?}, which the teacher has not sent \
                     (send the file with a \"model\" message first)"
                ));
            }
            if inner.current_model.as_deref() != Some(id.as_str()) {
                inner.current_model = Some(id.clone());
                if let Some(m) = inner.current_model_message() {
                    self.to_students(&m);
                }
            }
        }
        inner.seq += 1;
        inner.state_dirty = true;
        let message = ServerMessage::State {
            state,
            seq: inner.seq,
        };
        let _ = self.students_tx.send(frame(&message));
        if let ServerMessage::State { state, .. } = message {
            inner.state = Some(state);
        }
        Ok(())
    }

    /// A model file: stored, then sent to everyone (the teacher learns its id from it).
    pub(crate) async fn add_model(&self, name: String, text: String) -> Result<(), String> {
        let model = Arc::new(ModelFile {
            id: model_id(&name, &text),
            name,
            text,
        });
        self.db
            .write(Write::Model {
                session: self.id.clone(),
                model: model.clone(),
            })
            .await?;
        let mut inner = self.lock();
        inner.models.insert(model.id.clone(), model.clone());
        inner.current_model = Some(model.id.clone());
        let message = ServerMessage::Model {
            id: model.id.clone(),
            name: model.name.clone(),
            text: model.text.clone(),
        };
        let f = frame(&message);
        let _ = self.students_tx.send(f.clone());
        let _ = self.teachers_tx.send(f);
        Ok(())
    }

    /// Where an exercise's arm comes from: the request's built-in, else the session's robot.
    fn arm_source(&self, req: &QuestionRequest) -> ArmSource {
        match (req.kind, &req.robot) {
            (QuestionKind::Exercise(k), _) if k.is_orientation() => ArmSource::None,
            (_, Some(name)) => ArmSource::Builtin(name.clone()),
            _ => {
                let inner = self.lock();
                match inner.state.as_ref().map(|s| &s.robot) {
                    Some(RobotRef::Builtin(name)) => ArmSource::Builtin(name.clone()),
                    Some(RobotRef::Model { id, .. }) => inner
                        .models
                        .get(id)
                        .map_or(ArmSource::None, |m| ArmSource::Model(m.clone())),
                    None => ArmSource::None,
                }
            }
        }
    }

    /// A question: a poll as asked, or an exercise's sheet made here (its key kept). Stored,
    /// then sent to the students and, with a zero tally, to the teacher.
    pub(crate) async fn ask(&self, mut req: QuestionRequest) -> Result<(), String> {
        let seed = match (req.kind, req.seed) {
            (QuestionKind::Poll, _) => 0,
            (_, Some(s)) => s,
            (_, None) => super::secret::random_u64().map_err(|e| e.to_string())?,
        };
        if req.kind != QuestionKind::Poll {
            req.seed = Some(seed);
        }
        let source = self.arm_source(&req);
        let kind = req.kind;
        let (sheet, key) = tokio::task::spawn_blocking(move || make_sheet(kind, source, seed))
            .await
            .map_err(|e| format!("making the sheet failed: {e}"))??;
        let created_ms = now_ms();
        let (id, out) = {
            let mut inner = self.lock();
            let id = inner.next_question();
            let out = QuestionOut {
                id,
                kind: req.kind,
                prompt: req.prompt.clone(),
                choices: req.choices.clone(),
                sheet,
                open: true,
            };
            let q = Question {
                request: req.clone(),
                key: key.clone().map(Arc::new),
                out: out.clone(),
                answers: Default::default(),
            };
            inner.questions.insert(id, q);
            (id, out)
        };
        let stored = self
            .db
            .write(Write::Question {
                session: self.id.clone(),
                request: serde_json::to_string(&req).unwrap_or_default(),
                key: key.map(|k| serde_json::to_string(&k).unwrap_or_default()),
                sent: serde_json::to_string(&out).unwrap_or_default(),
                id,
                created_ms,
            })
            .await;
        if let Err(e) = stored {
            self.lock().questions.remove(&id);
            return Err(e);
        }
        let inner = self.lock();
        let message = ServerMessage::Question(out);
        let f = frame(&message);
        let _ = self.students_tx.send(f.clone());
        let _ = self.teachers_tx.send(f);
        if let Some(q) = inner.questions.get(&id) {
            self.to_teachers(&ServerMessage::Tally(q.tally(inner.joined())));
        }
        Ok(())
    }

    /// Closes question `id`: no more answers; everyone is told.
    pub(crate) async fn close(&self, id: u64) -> Result<(), String> {
        {
            let mut inner = self.lock();
            let q = inner
                .questions
                .get_mut(&id)
                .ok_or_else(|| no_question(id))?;
            q.out.open = false;
        }
        self.db
            .write(Write::Closed {
                session: self.id.clone(),
                id,
            })
            .await?;
        let f = frame(&ServerMessage::Closed { id });
        let _ = self.students_tx.send(f.clone());
        let _ = self.teachers_tx.send(f);
        Ok(())
    }

    /// Shows question `id`'s tally to the class (no names are in it).
    pub(crate) fn show(&self, id: u64) -> Result<(), String> {
        let inner = self.lock();
        let q = inner.questions.get(&id).ok_or_else(|| no_question(id))?;
        self.to_students(&ServerMessage::Results(q.tally(inner.joined())));
        Ok(())
    }

    /// Brings every student back to following.
    pub(crate) fn follow(&self) {
        self.to_students(&ServerMessage::Follow);
    }

    /// The session's answers as CSV.
    pub(crate) fn export(&self) -> String {
        super::export::csv(&self.id, &self.lock())
    }
}

/// The error of a question id the session does not have.
pub(crate) fn no_question(id: u64) -> String {
    format!("no question {id} in this session")
}

/// An exercise's sheet as the students get it and its key (a poll has neither).
fn make_sheet(
    kind: QuestionKind,
    source: ArmSource,
    seed: u64,
) -> Result<(Option<Box<SheetFile>>, Option<Key>), String> {
    let QuestionKind::Exercise(kind) = kind else {
        return Ok((None, None));
    };
    let robot: Option<Robot> = match source {
        ArmSource::None => None,
        ArmSource::Builtin(name) => Some(
            crate::kinematics::models::built_in(&name)
                .ok_or_else(|| format!("question: no built-in robot {name:?}"))?,
        ),
        ArmSource::Model(m) => Some(
            crate::model_file::parse_model_text(&m.name, &m.text)
                .map_err(|e| format!("question: the session's model {}: {e}", m.name))?,
        ),
    };
    let sheet = generate(kind, robot.as_ref(), seed, 1).map_err(|e| format!("question: {e}"))?;
    let file = SheetFile::of(&sheet).map_err(|e| format!("question: {e}"))?;
    Ok((Some(Box::new(file)), Some(sheet.key)))
}
