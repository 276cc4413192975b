//! Simulated students, for rehearsing a class alone (`armlab class demo`) and for the guide's
//! pictures of one: each is a real client of the class server (a [`DesktopLink`] of its own)
//! that joins with the code, follows the teacher's states, and answers the questions it can
//! work out, right or with one of the mistakes students make, so that the teacher's tally fills
//! as in a room.
//!
//! What a simulated student works out, from what every student gets and nothing more (the key
//! stays on the server):
//! - a "which posture is this?" poll: the posture the teacher's arm is in, found as the app's
//!   IK panel finds it (every solution at the arm's tool pose, the one at the arm's q);
//! - a DH table: the exercise's own generator run again on the class's robot with the sheet's
//!   seed (checked to give the very sheet received), its key's table written as the answer file;
//!   mistaken: an alpha's sign flipped, a and d swapped, a d's sign flipped;
//! - forward kinematics: T at the sheet's q, the key made again as for a DH table; mistaken:
//!   R transposed;
//! - Euler angles: from the sheet's matrix; mistaken: the transpose's angles, degrees written
//!   as radians;
//! - a quaternion: from the sheet's matrix; mistaken: the conjugate.
//!
//! The other kinds go unanswered (said by [`ANSWERED_KINDS`]).

use super::desktop::DesktopLink;
use super::link::{ClassLink, LinkEvent};
use crate::app::state::AppState;
use crate::class::protocol::{
    ClassState, ClientMessage, Join, QuestionKind, QuestionOut, RobotRef, Role, ServerMessage,
    parse_server,
};
use crate::exercise::orientation::{EulerConvention, EulerReference};
use crate::exercise::sheet_file::SheetFile;
use crate::exercise::{Kind, Rng};
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// The kinds simulated students answer (polls too); others stay unanswered.
pub const ANSWERED_KINDS: [Kind; 4] = [Kind::DhTable, Kind::Fk, Kind::Euler, Kind::Quaternion];

/// Nicknames, in turn (numbered after the first round).
const NAMES: [&str; 24] = [
    "Ada", "Bo", "Chen", "Dara", "Emil", "Fatou", "Gus", "Hana", "Ivo", "Jun", "Kofi", "Lena",
    "Mika", "Nour", "Omar", "Pia", "Quinn", "Rosa", "Sven", "Tao", "Uma", "Vik", "Wen", "Yara",
];

/// How fast the simulated students answer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Pace {
    /// At once (pictures, tests).
    AtOnce,
    /// Spread over `spread`, as a room answers.
    Spread(Duration),
}

/// A room of simulated students, run on a thread of its own until dropped.
pub struct Rehearsal {
    stop: Arc<AtomicBool>,
    answered: Arc<AtomicUsize>,
    errors: Arc<Mutex<Vec<String>>>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Rehearsal {
    /// Starts `students` simulated students joining the class at `ws` (`ws://HOST:PORT/ws`)
    /// with the join `code`; `seed` draws who errs and how (a student in three, about);
    /// `pace` says when they answer.
    pub fn start(ws: &str, code: &str, students: usize, seed: u64, pace: Pace) -> Self {
        let stop = Arc::new(AtomicBool::new(false));
        let answered = Arc::new(AtomicUsize::new(0));
        let errors = Arc::new(Mutex::new(Vec::new()));
        let bots: Vec<Bot> = (0..students)
            .map(|k| Bot::new(DesktopLink::connect(ws), code, k, seed, pace))
            .collect();
        let (s, a, e) = (stop.clone(), answered.clone(), errors.clone());
        let thread = std::thread::Builder::new()
            .name("armlab rehearsal".into())
            .spawn(move || run(bots, &s, &a, &e))
            .ok();
        Self {
            stop,
            answered,
            errors,
            thread,
        }
    }

    /// Answers sent so far, all questions together.
    pub fn answered(&self) -> usize {
        self.answered.load(Ordering::Relaxed)
    }

    /// What the server refused of the simulated students (its error messages), so far.
    pub fn errors(&self) -> Vec<String> {
        self.errors.lock().map(|e| e.clone()).unwrap_or_default()
    }
}

impl Drop for Rehearsal {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// Polls every student's link until told to stop.
fn run(mut bots: Vec<Bot>, stop: &AtomicBool, answered: &AtomicUsize, errors: &Mutex<Vec<String>>) {
    while !stop.load(Ordering::Relaxed) {
        for bot in &mut bots {
            for e in bot.step(answered) {
                if let Ok(mut all) = errors.lock() {
                    all.push(e);
                }
            }
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    for bot in &mut bots {
        bot.link.send(ClientMessage::Leave.to_text());
    }
}

/// One simulated student.
struct Bot {
    link: DesktopLink,
    join: Join,
    rng: Rng,
    /// The chance of a mistake in an answer, 0 to 1.
    err: f64,
    pace: Pace,
    /// The teacher's latest state.
    state: Option<ClassState>,
    /// The model files the server sent: id -> (name, contents).
    models: HashMap<String, (String, String)>,
    /// Questions to answer, and when.
    pending: Vec<(QuestionOut, Instant)>,
}

impl Bot {
    fn new(link: DesktopLink, code: &str, k: usize, seed: u64, pace: Pace) -> Self {
        let name = match k / NAMES.len() {
            0 => NAMES[k].to_string(),
            round => format!("{} {}", NAMES[k % NAMES.len()], round + 1),
        };
        let mut rng = Rng::new(seed, k + 1);
        // Most answer right; a few err often.
        let err = if rng.uniform() < 0.6 { 0.1 } else { 0.7 };
        Self {
            link,
            join: Join {
                role: Role::Student,
                token: None,
                code: Some(code.to_string()),
                name: Some(name),
                resume: None,
            },
            rng,
            err,
            pace,
            state: None,
            models: HashMap::new(),
            pending: Vec::new(),
        }
    }

    /// Reads what arrived, sends the answers that are due; returns the server's errors.
    fn step(&mut self, answered: &AtomicUsize) -> Vec<String> {
        let mut errors = Vec::new();
        for event in self.link.poll() {
            match event {
                LinkEvent::Opened => {
                    let join = ClientMessage::Join(self.join.clone());
                    self.link.send(join.to_text());
                }
                LinkEvent::Message(text) => {
                    if let Some(e) = self.receive(&text) {
                        errors.push(e);
                    }
                }
                LinkEvent::Closed(_) => {}
            }
        }
        let now = Instant::now();
        let (due, later): (Vec<_>, Vec<_>) = std::mem::take(&mut self.pending)
            .into_iter()
            .partition(|(_, at)| *at <= now);
        self.pending = later;
        for (question, _) in due {
            if let Some(answer) = self.answer(&question) {
                let id = question.id;
                self.link
                    .send(ClientMessage::Answer { id, answer }.to_text());
                answered.fetch_add(1, Ordering::Relaxed);
            }
        }
        errors
    }

    /// Takes one server message; an error's words are returned.
    fn receive(&mut self, text: &str) -> Option<String> {
        match parse_server(text).ok()? {
            ServerMessage::Welcome(w) => self.join.resume = w.resume.or(self.join.resume.take()),
            ServerMessage::State { state, .. } => self.state = Some(state),
            ServerMessage::Model { id, name, text } => {
                self.models.insert(id, (name, text));
            }
            ServerMessage::Question(q) if q.open => {
                let delay = match self.pace {
                    Pace::AtOnce => Duration::ZERO,
                    Pace::Spread(d) => d.mul_f64(0.1 + 0.9 * self.rng.uniform()),
                };
                self.pending.retain(|(p, _)| p.id != q.id);
                self.pending.push((q, Instant::now() + delay));
            }
            ServerMessage::Closed { id } => self.pending.retain(|(p, _)| p.id != id),
            ServerMessage::Error { message } => return Some(message),
            _ => {}
        }
        None
    }

    /// Whether this answer errs (drawn).
    fn errs(&mut self) -> bool {
        self.rng.uniform() < self.err
    }

    /// The answer to `q` (a poll's choice index, an exercise's file text), or `None` where this
    /// student cannot work it out.
    fn answer(&mut self, q: &QuestionOut) -> Option<serde_json::Value> {
        match q.kind {
            QuestionKind::Poll => {
                let right = self.posture_choice(&q.choices);
                let n = q.choices.len().max(1);
                let pick = match right {
                    Some(r) if !self.errs() => r,
                    Some(r) => (r + 1 + (self.rng.uniform() * (n - 1) as f64) as usize) % n,
                    None => (self.rng.uniform() * n as f64) as usize % n,
                };
                Some(pick.into())
            }
            QuestionKind::Exercise(kind) => {
                let sheet = q.sheet.as_deref()?;
                let wrong = self.errs();
                let which = self.rng.uniform();
                let text = match kind {
                    Kind::DhTable => self.dh_table(sheet, wrong, which)?,
                    Kind::Fk => self.fk(sheet, wrong)?,
                    Kind::Euler => euler(sheet, wrong, which)?,
                    Kind::Quaternion => quaternion(sheet, wrong)?,
                    _ => return None,
                };
                Some(text.into())
            }
        }
    }

    /// The class's robot: a built-in, or the model file the server sent.
    fn robot(&self) -> Option<crate::kinematics::robot::Robot> {
        match &self.state.as_ref()?.robot {
            RobotRef::Builtin(name) => crate::kinematics::models::built_in(name),
            RobotRef::Model { id, .. } => {
                let (name, text) = self.models.get(id)?;
                crate::model_file::parse_model_text(name, text).ok()
            }
        }
    }

    /// The poll's choice naming the posture the teacher's arm is in, found as the teacher's
    /// app finds it: every IK solution at the tool's pose, the one at q.
    fn posture_choice(&self, choices: &[String]) -> Option<usize> {
        let state = self.state.as_ref()?;
        let robot = self.robot()?;
        let name = robot.name.clone();
        let mut app = AppState::new(robot, name);
        app.set_q(&state.q).ok()?;
        let tool = app.robot().fk_ee(app.q(), 0).ok()?;
        app.set_target(0, tool).ok()?;
        let at_q = |g: &[f64]| {
            g.len() == state.q.len() && g.iter().zip(&state.q).all(|(a, b)| (a - b).abs() < 1e-6)
        };
        let ghost = app.ghosts(0).into_iter().find(|g| at_q(&g.q))?;
        let name = ghost.posture.posture()?.to_string();
        choices.iter().position(|c| *c == name)
    }

    /// The sheet of `kind` made again by the exercise's generator on the class's robot with
    /// the received sheet's seed: the key every student could work out, used only where it
    /// gives the very sheet received.
    fn made_again(&self, kind: Kind, sheet: &SheetFile) -> Option<crate::exercise::Sheet> {
        let robot = self.robot()?;
        let made = crate::exercise::generate(kind, Some(&robot), sheet.seed, sheet.student).ok()?;
        (SheetFile::of(&made).ok().as_ref() == Some(sheet)).then_some(made)
    }

    /// A DH table of the sheet's arm as its model file (the key's table). Mistaken (`which`
    /// picks): alpha's sign flipped in row 3, a and d swapped in the first row where they
    /// differ, or d's sign flipped in the first row with a d.
    fn dh_table(&self, sheet: &SheetFile, wrong: bool, which: f64) -> Option<String> {
        let made = self.made_again(Kind::DhTable, sheet)?;
        let mut arm = crate::exercise::key_robot(&made.key).ok()?;
        let (_, table) = arm.dh_table()?;
        let rows: Vec<crate::kinematics::dh::DhRow> = table.iter().map(|r| r.1).collect();
        let swap = rows.iter().position(|r| (r.a - r.d).abs() > 1e-3);
        let with_d = rows.iter().position(|r| r.d.abs() > 1e-3);
        let mistake = match (which, swap, with_d) {
            (w, Some(j), _) if (1.0 / 3.0..2.0 / 3.0).contains(&w) => Some((j, Mistake::Swap)),
            (w, _, Some(j)) if w >= 2.0 / 3.0 => Some((j, Mistake::DSign)),
            _ if rows.len() >= 3 => Some((2, Mistake::AlphaSign)),
            _ => None,
        };
        if let (true, Some((j, m))) = (wrong, mistake) {
            let mut row = rows[j];
            match m {
                Mistake::AlphaSign => row.alpha = -row.alpha,
                Mistake::Swap => std::mem::swap(&mut row.a, &mut row.d),
                Mistake::DSign => row.d = -row.d,
            }
            arm.set_dh_row(j, row).ok()?;
        }
        crate::model_file::to_toml(&arm)
    }

    /// T at the sheet's q (the key's), its first three rows; mistaken: R transposed.
    fn fk(&self, sheet: &SheetFile, wrong: bool) -> Option<String> {
        let made = self.made_again(Kind::Fk, sheet)?;
        let crate::exercise::KeyAnswer::Fk { t } = made.key.answer else {
            return None;
        };
        let rows: Vec<Vec<f64>> = (0..3)
            .map(|i| {
                (0..4)
                    .map(|j| if wrong && j < 3 { t[j][i] } else { t[i][j] })
                    .collect()
            })
            .collect();
        Some(rows_text(&rows))
    }
}

/// The DH-table mistakes a simulated student makes.
#[derive(Debug, Clone, Copy)]
enum Mistake {
    AlphaSign,
    Swap,
    DSign,
}

/// Rows as an answer file: numbers separated by spaces, one row a line.
fn rows_text(rows: &[Vec<f64>]) -> String {
    let mut text = String::new();
    for r in rows {
        let line: Vec<String> = r.iter().map(|v| format!("{v:.9}")).collect();
        text.push_str(&line.join(" "));
        text.push('\n');
    }
    text
}

/// The sheet's matrix as a rotation.
fn matrix(sheet: &SheetFile) -> Option<nalgebra::Matrix3<f64>> {
    let m = sheet.matrix?;
    Some(nalgebra::Matrix3::from_fn(|i, j| m[i][j]))
}

/// `phi theta psi` of the sheet's matrix in its convention; mistaken (`which` picks): the
/// transpose's angles, or the right angles in degrees without the `# deg` line.
fn euler(sheet: &SheetFile, wrong: bool, which: f64) -> Option<String> {
    let convention: EulerConvention = sheet.convention?;
    let m = matrix(sheet)?;
    let transposed = wrong && which < 0.5;
    let of = if transposed { m.transpose() } else { m };
    let angles = *EulerReference::of(&of, convention).solutions.first()?;
    let row: Vec<f64> = if wrong && !transposed {
        angles.iter().map(|a| a.to_degrees()).collect()
    } else {
        angles.to_vec()
    };
    Some(rows_text(&[row]))
}

/// `eta ex ey ez` of the sheet's matrix, (2.33)-(2.34); mistaken: the conjugate.
fn quaternion(sheet: &SheetFile, wrong: bool) -> Option<String> {
    let r = nalgebra::Rotation3::from_matrix_unchecked(matrix(sheet)?);
    let q = crate::kinematics::orientation::quaternion_from_rotation(&r);
    let s = if wrong { -1.0 } else { 1.0 };
    Some(rows_text(&[vec![q.w, s * q.i, s * q.j, s * q.k]]))
}
