//! A session's answers as CSV (RFC 4180): one line per student and question, their last answer,
//! with its grade, named mistakes and time (UTC). Nicknames only where the session shows them.

use super::session::{AnswerRecord, Inner, Question};
use crate::class::grading::{Graded, mistake_label};
use crate::class::protocol::QuestionKind;

/// The header line's fields.
pub(crate) const HEADER: [&str; 11] = [
    "session",
    "question",
    "kind",
    "student",
    "name",
    "answer",
    "correct",
    "score",
    "max",
    "mistakes",
    "answered_at",
];

/// The session's answers as CSV text: the header, then one line per answer, by question and
/// student.
pub(crate) fn csv(session: &str, inner: &Inner) -> String {
    let mut out = line(HEADER.iter().map(|h| h.to_string()));
    for q in inner.questions.values() {
        for (student, a) in &q.answers {
            let name = if inner.names_shown {
                inner
                    .students
                    .get(student - 1)
                    .map(|s| s.name.clone())
                    .unwrap_or_default()
            } else {
                String::new()
            };
            let (correct, score, max) = outcome(q, a);
            out.push_str(&line([
                session.to_string(),
                q.id().to_string(),
                q.request.kind.name().to_string(),
                student.to_string(),
                name,
                answer_text(&a.answer),
                correct,
                score,
                max,
                mistakes(&a.graded).join(";"),
                utc_time(a.at_ms),
            ]));
        }
    }
    out
}

/// Whether an answer is right, its score and the most it could score, as CSV fields (empty
/// where there is nothing to say: a poll without a right choice, an unreadable answer's
/// score).
fn outcome(q: &Question, a: &AnswerRecord) -> (String, String, String) {
    match &a.graded {
        Graded::Choice(c) => match q.request.correct {
            Some(right) => {
                let ok = *c == right;
                (ok.to_string(), u8::from(ok).to_string(), "1".into())
            }
            None => (String::new(), String::new(), String::new()),
        },
        Graded::Exercise(g) => (
            (g.score == g.max && g.max > 0).to_string(),
            g.score.to_string(),
            g.max.to_string(),
        ),
        Graded::Unreadable(_) => {
            let max = match q.request.kind {
                QuestionKind::Poll => "1".to_string(),
                QuestionKind::Exercise(_) => String::new(),
            };
            ("false".into(), "0".into(), max)
        }
    }
}

/// The mistakes an answer made, as the tally names them; an unreadable answer's reason.
pub(crate) fn mistakes(g: &Graded) -> Vec<String> {
    match g {
        Graded::Exercise(grade) => grade
            .items
            .iter()
            .filter(|i| !i.correct)
            .map(mistake_label)
            .collect(),
        Graded::Unreadable(why) => vec![format!("unreadable: {why}")],
        Graded::Choice(_) => Vec::new(),
    }
}

/// An answer as a CSV field: a string's text, anything else its JSON.
fn answer_text(v: &serde_json::Value) -> String {
    match v {
        serde_json::Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// A field a spreadsheet would run as a formula (`=`, `+`, `@`, a tab or a carriage return
/// first, or `-` not starting a number: a nickname or an answer is user text) gets a `'` in
/// front, which spreadsheets show as text (OWASP's advice on CSV injection).
fn defused(f: String) -> String {
    let mut chars = f.chars();
    let risky = match chars.next() {
        Some('=' | '+' | '@' | '\t' | '\r') => true,
        Some('-') => !chars.next().is_some_and(|c| c.is_ascii_digit() || c == '.'),
        _ => false,
    };
    if risky { format!("'{f}") } else { f }
}

/// One CSV line (RFC 4180): fields with a comma, quote or line break quoted, quotes doubled,
/// formulas defused ([`defused`]); the line ends with `\n`, as the exercise CSV's lines do.
fn line(fields: impl IntoIterator<Item = String>) -> String {
    let quoted: Vec<String> = fields
        .into_iter()
        .map(defused)
        .map(|f| {
            if f.contains([',', '"', '\n', '\r']) {
                format!("\"{}\"", f.replace('"', "\"\""))
            } else {
                f
            }
        })
        .collect();
    quoted.join(",") + "\n"
}

/// A time (ms since the Unix epoch) as RFC 3339 in UTC, to the second
/// (`2025-03-04T09:15:02Z`).
pub(crate) fn utc_time(ms: i64) -> String {
    let secs = ms.div_euclid(1000);
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    let (y, m, d) = civil_from_days(days);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem % 3600 / 60,
        rem % 60
    )
}

/// The proleptic Gregorian date of a day count from 1970-01-01 (Howard Hinnant's
/// `civil_from_days`).
fn civil_from_days(z: i64) -> (i64, i64, i64) {
    let z = z + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    (y, m, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn times_are_utc_dates_of_known_days() {
        assert_eq!(utc_time(0), "1970-01-01T00:00:00Z");
        // 2000-02-29 12:34:56 UTC is 951827696 s after the epoch (a leap day).
        assert_eq!(utc_time(951_827_696_000), "2000-02-29T12:34:56Z");
        // 2024-12-31 23:59:59 UTC.
        assert_eq!(utc_time(1_735_689_599_999), "2024-12-31T23:59:59Z");
    }

    #[test]
    fn fields_with_commas_quotes_and_breaks_are_quoted() {
        let l = line([
            "a".to_string(),
            "b,c".into(),
            "say \"hi\"".into(),
            "x\ny".into(),
        ]);
        assert_eq!(l, "a,\"b,c\",\"say \"\"hi\"\"\",\"x\ny\"\n");
    }

    #[test]
    fn formulas_in_user_text_are_shown_as_text() {
        let l = line([
            "=HYPERLINK(\"x\")".to_string(),
            "+1".into(),
            "@SUM(A1)".into(),
            "-cmd".into(),
            "-0.5 1.2".into(),
            "0.5".into(),
        ]);
        assert_eq!(
            l,
            "\"'=HYPERLINK(\"\"x\"\")\",'+1,'@SUM(A1),'-cmd,-0.5 1.2,0.5\n"
        );
    }
}
