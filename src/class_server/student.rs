//! A student's answer: graded on the server with the question's key (off the async threads),
//! stored as the student's last answer to the question before they are told it arrived, and
//! counted into the teacher's tally.

use super::load::now_ms;
use super::session::{AnswerRecord, Session, error_frame, frame};
use super::store::Write;
use super::teacher::no_question;
use crate::class::grading::{Graded, grade_exercise, poll_choice, student_grade};
use crate::class::protocol::{QuestionKind, ServerMessage};
use axum::extract::ws::Utf8Bytes;

impl Session {
    /// Student `number`'s answer to question `id`: the frames they get back (`received`, with
    /// their grade where the question gives feedback; or an error saying why the answer could
    /// not be read, which is still counted as unreadable).
    pub(crate) async fn answer(
        &self,
        number: usize,
        id: u64,
        answer: serde_json::Value,
    ) -> Vec<Utf8Bytes> {
        let (kind, key, choices, feedback) = {
            let inner = self.lock();
            let Some(q) = inner.questions.get(&id) else {
                return vec![error_frame(no_question(id))];
            };
            if !q.open() {
                return vec![error_frame(format!("question {id} is closed"))];
            }
            (
                q.request.kind,
                q.key.clone(),
                q.request.choices.len(),
                q.request.feedback,
            )
        };
        let graded = match (kind, key) {
            (QuestionKind::Exercise(_), Some(key)) => {
                let given = answer.clone();
                match tokio::task::spawn_blocking(move || grade_exercise(&key, &given)).await {
                    Ok(Ok(g)) => Graded::Exercise(g),
                    Ok(Err(e)) => Graded::Unreadable(e.to_string()),
                    Err(e) => Graded::Unreadable(format!("grading failed: {e}")),
                }
            }
            (QuestionKind::Exercise(_), None) => {
                Graded::Unreadable("the question has no key (its data is damaged)".into())
            }
            (QuestionKind::Poll, _) => match poll_choice(&answer, choices) {
                Ok(c) => Graded::Choice(c),
                Err(why) => Graded::Unreadable(why),
            },
        };
        let record = AnswerRecord {
            answer,
            graded,
            at_ms: now_ms(),
        };
        if let Err(e) = self.keep_answer(number, id, &record).await {
            return vec![error_frame(e)];
        }
        match &record.graded {
            Graded::Unreadable(why) => vec![error_frame(format!("answer to question {id}: {why}"))],
            Graded::Exercise(g) if feedback => vec![frame(&ServerMessage::Received {
                id,
                grade: Some(student_grade(g)),
            })],
            _ => vec![frame(&ServerMessage::Received { id, grade: None })],
        }
    }

    /// Keeps `record` as student `number`'s answer to `id` (in memory, then on disk), then
    /// sends the teacher the new tally.
    async fn keep_answer(
        &self,
        number: usize,
        id: u64,
        record: &AnswerRecord,
    ) -> Result<(), String> {
        {
            let mut inner = self.lock();
            let q = inner
                .questions
                .get_mut(&id)
                .ok_or_else(|| no_question(id))?;
            if !q.open() {
                return Err(format!("question {id} is closed"));
            }
            q.answers.insert(number, record.clone());
        }
        self.db
            .write(Write::Answer {
                session: self.id.clone(),
                question: id,
                student: number,
                record: record.clone(),
            })
            .await
            .map_err(|e| format!("the answer could not be stored: {e}"))?;
        let inner = self.lock();
        if let Some(q) = inner.questions.get(&id) {
            self.to_teachers(&ServerMessage::Tally(q.tally(inner.joined())));
        }
        Ok(())
    }
}
