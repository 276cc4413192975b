//! Grading a class's answers as they come in, with the exercise grader
//! ([`crate::exercise::grade`]), and counting them into the teacher's [`Tally`]. Pure compute:
//! the server stores and sends; nothing here reads a file or a socket.

use super::protocol::{GradedItem, QuestionKind, StudentGrade, Tally};
use crate::exercise::{Answer, ExerciseError, Grade, Key, KeyAnswer, grade, orientation};
use std::collections::BTreeMap;

/// One student's answer, graded: what the tally counts.
#[derive(Debug, Clone, PartialEq)]
pub enum Graded {
    /// A poll's choice (0-based).
    Choice(usize),
    /// An exercise's grade.
    Exercise(Grade),
    /// An answer of the wrong shape (why, in words).
    Unreadable(String),
}

/// Reads and grades an exercise answer: `answer` is the answer file's text (a DH table as a
/// TOML model file, rows of numbers, parameter names, an orientation's lines), as the app's
/// Exercise tab saves it. The key never leaves the caller.
pub fn grade_exercise(key: &Key, answer: &serde_json::Value) -> Result<Grade, ExerciseError> {
    let bad = |reason: &str| ExerciseError::Answer {
        reason: reason.to_string(),
    };
    let text = answer
        .as_str()
        .ok_or_else(|| bad("an exercise's answer is its file's text, a JSON string"))?;
    let parsed = if key.kind.is_orientation() {
        Answer::Orientation(orientation::parse_answer(key.kind, text, "answer")?)
    } else {
        match key.answer {
            KeyAnswer::DhTable => {
                let robot =
                    crate::model_file::parse_model(text, std::path::Path::new("answer.toml"))
                        .map_err(|e| ExerciseError::Answer {
                            reason: e.to_string(),
                        })?;
                Answer::Model(Box::new(robot))
            }
            KeyAnswer::Identifiability { .. } => Answer::Words(crate::exercise::parse_words(text)),
            _ => Answer::Rows(crate::exercise::parse_rows(text, "answer")?),
        }
    };
    grade(key, &parsed)
}

/// Reads a poll answer: the index of one of `choices` choices.
pub fn poll_choice(answer: &serde_json::Value, choices: usize) -> Result<usize, String> {
    match answer.as_u64() {
        Some(i) if (i as usize) < choices => Ok(i as usize),
        Some(i) => Err(format!(
            "choice {i}: the poll has {choices} choices (0 to {})",
            choices.saturating_sub(1)
        )),
        None => Err("a poll's answer is the index of a choice (0, 1, ...)".into()),
    }
}

/// A grade as the student sees it (no mistake names: the items' words).
pub fn student_grade(g: &Grade) -> StudentGrade {
    StudentGrade {
        score: g.score,
        max: g.max,
        items: g
            .items
            .iter()
            .map(|i| GradedItem {
                item: i.item.clone(),
                correct: i.correct,
                feedback: i.feedback.clone(),
            })
            .collect(),
    }
}

/// The name a tally counts a wrong item under: the item and its mistake in a teacher's words
/// ("row 3: alpha with the wrong sign (z turned the other way)"), or the item alone where no
/// mistake is named.
pub fn mistake_label(item: &crate::exercise::Item) -> String {
    match item.mistake {
        Some(m) => format!("{}: {m}", item.item),
        None => format!("{}: wrong", item.item),
    }
}

/// Counts the answers of one question (each student's last one): `choices` a poll's choices
/// and its right one; `max` an exercise's number of items (0 before any readable answer);
/// `joined` the students in the session.
pub fn tally(
    id: u64,
    kind: QuestionKind,
    choices: &[String],
    correct_choice: Option<usize>,
    answers: &[Graded],
    joined: usize,
) -> Tally {
    let mut mistakes = BTreeMap::new();
    let (mut right, mut unreadable) = (0, 0);
    let max = answers
        .iter()
        .filter_map(|a| match a {
            Graded::Exercise(g) => Some(g.max),
            _ => None,
        })
        .max()
        .unwrap_or(0);
    let mut counts = match kind {
        QuestionKind::Poll => vec![0; choices.len()],
        QuestionKind::Exercise(_) => vec![0; max + 1],
    };
    for a in answers {
        match a {
            Graded::Choice(c) => {
                if let Some(n) = counts.get_mut(*c) {
                    *n += 1;
                }
                right += usize::from(correct_choice == Some(*c));
            }
            Graded::Exercise(g) => {
                counts[g.score.min(max)] += 1;
                right += usize::from(g.score == g.max && g.max > 0);
                for item in g.items.iter().filter(|i| !i.correct) {
                    *mistakes.entry(mistake_label(item)).or_insert(0) += 1;
                }
            }
            Graded::Unreadable(_) => unreadable += 1,
        }
    }
    let answered = answers.len();
    let ungraded = kind == QuestionKind::Poll && correct_choice.is_none();
    let correct_percent = if answered == 0 || ungraded {
        0.0
    } else {
        100.0 * right as f64 / answered as f64
    };
    Tally {
        id,
        kind,
        answered,
        joined: joined.max(answered),
        counts,
        max,
        correct_percent,
        mistakes,
        unreadable,
        choices: choices.to_vec(),
    }
}
