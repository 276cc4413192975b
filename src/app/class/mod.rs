//! The live classroom in the app (issue 50): the client of a class server
//! (`armlab class serve`, or one started in the app), as teacher or student.
//!
//! - The teacher's app sends what it shows ([`crate::class::protocol::ClassState`]: the robot,
//!   q, and the rest as a lesson step, [`super::lesson::current_step`]) at most
//!   [`STATE_RATE_HZ`] times a second and only when it changed; asks questions (a "which
//!   posture is this?" poll, an exercise kind), and shows the room's answers as they come in.
//! - A student's app follows: each state the teacher sends is applied as a lesson step is
//!   ([`super::lesson::step_actions`]); a student who moves the arm or the camera explores on
//!   their own until "Follow the teacher". A poll is answered with one button per choice, an
//!   exercise in the Exercise tab, sent with "Send answer".
//!
//! [`ClassClient`] is one field of the app's window model; each frame it reads the app
//! (read only) and returns [`Action`]s, and its buttons, the toolbar's "Start class" and the
//! Exercise tab's "Send answer" come back to it as [`ClassAction`]s. The transport is a
//! [`link::ClassLink`]: a WebSocket on its own thread on the desktop (`desktop`), the page's
//! WebSocket in a browser (`browser`).

#[cfg(target_arch = "wasm32")]
pub mod browser;
#[cfg(all(feature = "app", not(target_arch = "wasm32")))]
pub mod desktop;
pub mod link;
pub mod panel;
#[cfg(all(feature = "app", not(target_arch = "wasm32")))]
pub mod rehearsal;
mod student;
mod teacher;

use super::action::{Action, Actions};
use super::file_picker::FilePicker;
use super::shell::AppUi;
use super::state::Level;
use super::tabs::Tabs;
use super::tabs::exercise::ClassSheetStatus;
use crate::class::protocol::{
    ClientMessage, Join, QuestionKind, QuestionOut, QuestionRequest, Role, ServerMessage, Tally,
    Welcome, parse_server,
};
use link::{ClassLink, LinkEvent, PageLink};

pub use teacher::{exercise_request, poll_request};

/// The most states a second the teacher's app sends.
pub const STATE_RATE_HZ: f64 = 30.0;

/// What the class window's buttons, the toolbar and the Exercise tab ask of the class client.
#[derive(Debug, Clone, PartialEq)]
pub enum ClassAction {
    /// Show or hide the Class window (the toolbar's "Start class").
    ToggleWindow,
    /// Start a class server in the app and join it as the teacher (desktop): on every network
    /// of the computer when `reachable`, else this computer only.
    StartHere {
        /// Listen on the classroom's network (0.0.0.0) instead of 127.0.0.1.
        reachable: bool,
    },
    /// Join a running server as the teacher, by its teacher link (`http://HOST:PORT/?token=T`).
    JoinTeacher(String),
    /// Join as a student: the server's WebSocket URL, the join code, the nickname.
    JoinStudent {
        /// `ws://HOST:PORT/ws`.
        ws: String,
        /// The join code.
        code: String,
        /// The nickname.
        name: String,
        /// The secret of an earlier welcome on this page (the same student again).
        resume: Option<String>,
    },
    /// Leave the class (a server started in the app stops).
    Leave,
    /// Teacher: ask the class.
    Ask(QuestionRequest),
    /// Teacher: stop taking answers to a question.
    Close(u64),
    /// Teacher: show a question's tally to the class, anonymised.
    Show(u64),
    /// Teacher: bring every student back to following.
    BringBack,
    /// Teacher: the session's answers as CSV.
    Export,
    /// Teacher: save the CSV the server sent (the file picker, a download in a browser).
    SaveCsv(String),
    /// Student: follow the teacher again.
    Follow,
    /// Student: answer question `id` (a poll's choice index, an exercise's file text).
    Answer {
        /// The question.
        id: u64,
        /// The answer, as [`ClientMessage::Answer`] carries it.
        answer: serde_json::Value,
    },
    /// Student: what became of the answer to the class question open in the Exercise tab.
    SheetStatus(u64, ClassSheetStatus),
}

/// Where the connection stands.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Connection {
    /// Not in a class.
    #[default]
    Offline,
    /// Connecting, or connected and waiting for the welcome.
    Connecting,
    /// In the class.
    Joined,
    /// The connection dropped (why); the link is trying again.
    Lost(String),
    /// The server refused the join (why): wrong token or code; not tried again.
    Refused(String),
}

/// What became of a student's answer to the open question.
#[derive(Debug, Clone, PartialEq)]
pub enum AnswerStatus {
    /// Sent, not acknowledged yet.
    Sent,
    /// The server has it (with the grade, where the question gives feedback).
    Received(Option<crate::class::protocol::StudentGrade>),
    /// The server refused it (why).
    Refused(String),
}

/// What the teacher sees of who is in the class.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Roster {
    /// Students joined now.
    pub joined: usize,
    /// Their nicknames, where the session shows names.
    pub names: Vec<String>,
}

/// The fields of the Class window's forms.
#[derive(Debug, Clone, PartialEq)]
pub struct ClassForm {
    /// "Join as teacher": the teacher link typed.
    pub teacher_link: String,
    /// "Start a class here": reachable from the classroom network.
    pub reachable: bool,
    /// The exercise kind to ask.
    pub kind: crate::exercise::Kind,
    /// Students see their grade when they answer.
    pub feedback: bool,
    /// The nickname typed (a student page opened without `&name=`).
    pub nickname: String,
}

impl Default for ClassForm {
    fn default() -> Self {
        Self {
            teacher_link: String::new(),
            reachable: false,
            kind: crate::exercise::Kind::DhTable,
            feedback: true,
            nickname: String::new(),
        }
    }
}

/// A student page opened with a code but no nickname: the prompt asks for one.
#[derive(Debug, Clone, PartialEq)]
pub struct NamePrompt {
    /// The server's WebSocket URL.
    pub ws: String,
    /// The join code.
    pub code: String,
    /// The secret of an earlier welcome on this page, if any.
    pub resume: Option<String>,
}

/// Keeps a student's resume secret (the browser: in local storage, per join code).
pub type KeepResume = Box<dyn Fn(&str)>;

/// The app's class client (one field of the window model; see the module's documentation).
#[derive(Default)]
pub struct ClassClient {
    link: Option<Box<dyn ClassLink>>,
    /// The join message, sent again (with the resume secret) after every reconnection.
    join: Option<Join>,
    /// Where the connection stands.
    pub connection: Connection,
    /// The server's welcome: the links, the QR code, the code.
    pub welcome: Option<Welcome>,
    /// Student: the app follows the teacher (else the student explores on their own).
    pub following: bool,
    /// The open question (teacher: the last asked; student: the last received).
    pub question: Option<QuestionOut>,
    /// Student: what became of their answer to [`Self::question`].
    pub answer: Option<AnswerStatus>,
    /// Teacher: the room's answers to the last question.
    pub tally: Option<Tally>,
    /// Student: the tally the teacher showed the class.
    pub results: Option<Tally>,
    /// Teacher: who is in the class.
    pub roster: Roster,
    /// The Class window is shown.
    pub window: bool,
    /// The Class window's forms.
    pub form: ClassForm,
    /// A student page without a nickname: the prompt.
    pub prompt: Option<NamePrompt>,
    /// Called with the resume secret of each welcome (the browser keeps it in local storage).
    pub on_resume: Option<KeepResume>,
    teacher: teacher::TeacherSide,
    student: student::Follower,
    /// Messages for the status bar, handed over at the next frame.
    notes: Vec<(Level, String)>,
    #[cfg(all(feature = "app", not(target_arch = "wasm32")))]
    server: Option<crate::class_server::ServerHandle>,
}

impl ClassClient {
    /// The role joined as (or asked for).
    pub fn role(&self) -> Option<Role> {
        self.welcome
            .as_ref()
            .map(|w| w.role)
            .or(self.join.as_ref().map(|j| j.role))
    }

    /// Whether the class is joined now.
    pub fn connected(&self) -> bool {
        self.connection == Connection::Joined
    }

    /// Joins as the teacher over `link` with `token`.
    pub fn connect_teacher(&mut self, link: Box<dyn ClassLink>, token: &str) {
        self.connect(
            link,
            Join {
                role: Role::Teacher,
                token: Some(token.to_string()),
                code: None,
                name: None,
                resume: None,
            },
        );
    }

    /// Joins as a student over `link` with the join `code` and the nickname `name`; `resume`
    /// is a secret of an earlier welcome (the same student again).
    pub fn connect_student(
        &mut self,
        link: Box<dyn ClassLink>,
        code: &str,
        name: &str,
        resume: Option<String>,
    ) {
        self.connect(
            link,
            Join {
                role: Role::Student,
                token: None,
                code: Some(code.to_string()),
                name: Some(name.to_string()),
                resume,
            },
        );
        self.following = true;
    }

    fn connect(&mut self, link: Box<dyn ClassLink>, join: Join) {
        self.leave();
        self.link = Some(link);
        self.join = Some(join);
        self.connection = Connection::Connecting;
    }

    /// Leaves the class: the link closes (the server started here stops); what the app shows
    /// stays.
    pub fn leave(&mut self) {
        if let Some(link) = &mut self.link {
            link.send(ClientMessage::Leave.to_text());
        }
        #[cfg(all(feature = "app", not(target_arch = "wasm32")))]
        if let Some(s) = self.server.take()
            && let Err(e) = s.stop()
        {
            self.notes.push((Level::Warning, format!("class: {e}")));
        }
        *self = Self {
            form: std::mem::take(&mut self.form),
            window: self.window,
            on_resume: self.on_resume.take(),
            notes: std::mem::take(&mut self.notes),
            ..Self::default()
        };
    }

    /// One frame: reads what arrived, sends the teacher's state or applies the teacher's,
    /// lays out the class's windows; `app` is the window model as it is now (read only; this
    /// client is taken out of it meanwhile). What the app should do goes to `out`.
    pub fn frame(mut self, ctx: &egui::Context, app: &AppUi, out: &mut Actions) -> Self {
        self.receive(ctx, out);
        match self.role() {
            Some(Role::Teacher) if self.connected() => self.send_state(ctx, app),
            Some(Role::Student) => self.follow(app, out),
            _ => {}
        }
        for (level, text) in self.notes.drain(..) {
            out.message(level, text);
        }
        panel::show(&mut self, ctx, app, out);
        if self.link.is_some() {
            // What the link brings wakes the window; this is for the reconnections' notes.
            ctx.request_repaint_after(std::time::Duration::from_millis(250));
        }
        self
    }

    /// Sends `message` if connected.
    fn send(&mut self, message: &ClientMessage) {
        if let Some(link) = &mut self.link {
            link.send(message.to_text());
        }
    }

    /// Reads the link's events and the server's messages.
    fn receive(&mut self, ctx: &egui::Context, out: &mut Actions) {
        let Some(link) = &mut self.link else {
            return;
        };
        link.wake_with(ctx);
        for event in link.poll() {
            match event {
                LinkEvent::Opened => {
                    self.connection = Connection::Connecting;
                    if let Some(join) = self.join.clone() {
                        self.send(&ClientMessage::Join(join));
                    }
                }
                LinkEvent::Message(text) => match parse_server(&text) {
                    Ok(m) => self.handle(m, out),
                    Err(e) => self.note(Level::Warning, format!("class: the server sent {e}")),
                },
                LinkEvent::Closed(why) => self.closed(why),
            }
            if self.link.is_none() {
                return; // refused: the link is gone
            }
        }
    }

    /// The connection closed; the link tries again (the status bar says so once).
    fn closed(&mut self, why: String) {
        if matches!(self.connection, Connection::Joined | Connection::Connecting)
            && self.welcome.is_some()
        {
            self.note(
                Level::Warning,
                format!("class: connection lost ({why}); reconnecting"),
            );
        }
        if !matches!(self.connection, Connection::Refused(_)) {
            self.connection = Connection::Lost(why);
        }
    }

    /// One message of the server.
    fn handle(&mut self, m: ServerMessage, out: &mut Actions) {
        match m {
            ServerMessage::Welcome(w) => self.welcomed(w),
            ServerMessage::Error { message } => self.refused(message, out),
            ServerMessage::State { state, seq } => self.student.arrived(state, seq),
            ServerMessage::Model { id, name, text } => match self.role() {
                Some(Role::Teacher) => self.teacher.model_stored(id, name),
                _ => self.student.model_arrived(id, name, text),
            },
            ServerMessage::Question(q) => self.question_arrived(q, out),
            ServerMessage::Received { id, grade } => {
                self.answer = Some(AnswerStatus::Received(grade.clone()));
                let status = ClassSheetStatus::Received(grade);
                out.push(Action::Class(ClassAction::SheetStatus(id, status)));
            }
            ServerMessage::Closed { id } => {
                if let Some(q) = self.question.as_mut().filter(|q| q.id == id) {
                    q.open = false;
                    let status = ClassSheetStatus::Closed;
                    out.push(Action::Class(ClassAction::SheetStatus(id, status)));
                }
            }
            ServerMessage::Tally(t) => self.tally = Some(t),
            ServerMessage::Results(t) => self.results = Some(t),
            ServerMessage::Follow => self.follow_again(),
            ServerMessage::Roster { joined, names } => self.roster = Roster { joined, names },
            ServerMessage::Export { csv } => out.push(Action::Class(ClassAction::SaveCsv(csv))),
        }
    }

    fn welcomed(&mut self, w: Welcome) {
        if let (Some(secret), Some(join)) = (&w.resume, &mut self.join) {
            join.resume = Some(secret.clone());
            if let Some(keep) = &self.on_resume {
                keep(secret);
            }
        }
        let first = self.welcome.is_none();
        self.connection = Connection::Joined;
        self.roster.joined = w.joined;
        if first {
            let who = match w.role {
                Role::Teacher => format!("class: you teach; students join with code {}", w.code),
                Role::Student => "class: joined; following the teacher".to_string(),
            };
            self.note(Level::Info, who);
        }
        self.welcome = Some(w);
        // Whatever was sent before the reconnection is sent again; the state numbers start
        // afresh (a restarted server counts anew).
        self.teacher.reconnected();
        self.student.rejoined();
    }

    /// An error reply: before a welcome (the first, or after a reconnection), the join was
    /// refused (the link closes); after it, a message refused (an answer in flight is marked).
    fn refused(&mut self, message: String, out: &mut Actions) {
        if self.connection != Connection::Joined {
            self.note(Level::Error, format!("class: {message}"));
            self.link = None;
            self.connection = Connection::Refused(message);
            return;
        }
        if self.answer == Some(AnswerStatus::Sent) {
            self.answer = Some(AnswerStatus::Refused(message.clone()));
            if let Some(q) = &self.question {
                let status = ClassSheetStatus::Refused(message.clone());
                out.push(Action::Class(ClassAction::SheetStatus(q.id, status)));
            }
        }
        self.note(Level::Warning, format!("class: {message}"));
    }

    /// A question: the teacher's own back with its id; a student's poll shows in the
    /// question window, an exercise opens in the Exercise tab (the teacher's view waits).
    fn question_arrived(&mut self, q: QuestionOut, out: &mut Actions) {
        self.answer = None;
        self.results = None;
        if self.role() == Some(Role::Teacher) {
            self.tally = None;
            self.question = Some(q);
            return;
        }
        if let (QuestionKind::Exercise(kind), Some(sheet)) = (q.kind, &q.sheet) {
            match serde_json::to_string(sheet) {
                Ok(text) => {
                    let name = format!("class-question-{}.json", q.id);
                    out.push(Action::OpenText { name, text });
                    let status = ClassSheetStatus::Open(kind);
                    out.push(Action::Class(ClassAction::SheetStatus(q.id, status)));
                    self.student.answering = true;
                }
                Err(e) => self.note(Level::Error, format!("class: the question's sheet: {e}")),
            }
        }
        self.question = Some(q);
    }

    /// Student: following the teacher again (leaving a class question's sheet as it is): the
    /// teacher's latest state is applied at the next frame.
    fn follow_again(&mut self) {
        self.following = true;
        self.student.reapply = true;
        self.student.done_answering();
    }

    fn note(&mut self, level: Level, text: String) {
        self.notes.push((level, text));
    }

    /// Applies a [`ClassAction`]: `tabs` for the Exercise tab (a class question's status is
    /// shown there), `picker` saves the CSV.
    pub fn apply(&mut self, action: ClassAction, tabs: &mut Tabs, picker: &mut dyn FilePicker) {
        let exercise = &mut tabs.exercise;
        match action {
            ClassAction::ToggleWindow => self.window ^= true,
            ClassAction::StartHere { reachable } => self.start_here(reachable),
            ClassAction::JoinTeacher(text) => self.join_teacher(&text),
            ClassAction::JoinStudent {
                ws,
                code,
                name,
                resume,
            } => match link::open(&ws) {
                Ok(l) => {
                    self.prompt = None;
                    self.connect_student(l, &code, &name, resume);
                }
                Err(e) => self.note(Level::Error, format!("class: {e}")),
            },
            ClassAction::Leave => self.leave(),
            ClassAction::Ask(q) => self.send(&ClientMessage::Question(q)),
            ClassAction::Close(id) => self.send(&ClientMessage::Close { id }),
            ClassAction::Show(id) => self.send(&ClientMessage::Show { id }),
            ClassAction::BringBack => self.send(&ClientMessage::Follow),
            ClassAction::Export => self.send(&ClientMessage::Export),
            ClassAction::SaveCsv(csv) => {
                let stem = self
                    .welcome
                    .as_ref()
                    .map_or("class", |w| w.session.as_str());
                let saved = save_csv(picker, &format!("armlab-class-{stem}.csv"), &csv);
                match saved {
                    Ok(m) => self.note(Level::Info, m),
                    Err(e) => self.note(Level::Error, e),
                }
            }
            ClassAction::Follow => self.follow_again(),
            ClassAction::Answer { id, answer } => {
                self.send(&ClientMessage::Answer { id, answer });
                self.answer = Some(AnswerStatus::Sent);
                exercise.class_status(id, ClassSheetStatus::Sent);
            }
            ClassAction::SheetStatus(id, status) => exercise.class_status(id, status),
        }
    }

    /// "Join as teacher": the teacher link's server and token.
    fn join_teacher(&mut self, text: &str) {
        let joined = PageLink::parse(text).and_then(|l| {
            let token = l.token.ok_or("the teacher link holds ?token=...")?;
            link::open(&l.ws).map(|link| (link, token))
        });
        match joined {
            Ok((link, token)) => self.connect_teacher(link, &token),
            Err(e) => self.note(Level::Error, format!("class: {e}")),
        }
    }

    /// "Start a class here": a server in the app's process, joined as the teacher over
    /// loopback (whatever address it listens on).
    #[cfg(all(feature = "app", not(target_arch = "wasm32")))]
    fn start_here(&mut self, reachable: bool) {
        let server = match teacher::start_server(reachable) {
            Ok(s) => s,
            Err(e) => return self.note(Level::Error, format!("class: cannot start a server: {e}")),
        };
        let ws = format!("ws://127.0.0.1:{}/ws", server.addr.port());
        match link::open(&ws) {
            Ok(link) => {
                let token = server.token.clone();
                for w in &server.warnings {
                    self.note(Level::Warning, format!("class: {w}"));
                }
                if reachable {
                    self.note(Level::Info, format!("class: {}", server.network_hint));
                }
                self.connect_teacher(link, &token);
                self.server = Some(server);
            }
            Err(e) => {
                let _ = server.stop();
                self.note(Level::Error, format!("class: {e}"));
            }
        }
    }

    #[cfg(not(all(feature = "app", not(target_arch = "wasm32"))))]
    fn start_here(&mut self, _reachable: bool) {
        let m = "class: a browser cannot start a server; open the teacher link instead";
        self.note(Level::Warning, m.into());
    }

    /// Where the class stands, as JSON (the web page's `status()`): `{"role"` (`"teacher"`,
    /// `"student"` or null), `"connected"`, `"following"`, `"question"` (`{"id", "kind"}` or
    /// null), `"answered"` (the teacher: answers counted; a student: 1 once the server has
    /// theirs), `"joined"`, `"counts"`, `"correct_percent"`, `"mistakes"` (the teacher's tally,
    /// or the results shown to a student)`}`.
    pub fn status(&self) -> serde_json::Value {
        let tally = match self.role() {
            Some(Role::Teacher) => self.tally.as_ref(),
            _ => self.results.as_ref(),
        };
        let answered = match self.role() {
            Some(Role::Teacher) => tally.map_or(0, |t| t.answered),
            _ => usize::from(matches!(self.answer, Some(AnswerStatus::Received(_)))),
        };
        serde_json::json!({
            "role": self.role(),
            "connected": self.connected(),
            "prompt": self.prompt.is_some(),
            "following": self.following,
            "question": self.question.as_ref().map(|q| serde_json::json!({
                "id": q.id,
                "kind": q.kind,
                "open": q.open,
                "choices": q.choices,
            })),
            "answered": answered,
            "joined": tally.map_or(self.roster.joined, |t| t.joined),
            "counts": tally.map(|t| t.counts.clone()),
            "correct_percent": tally.map(|t| t.correct_percent),
            "mistakes": tally.map(|t| t.mistakes.clone()),
        })
    }

    /// Whether a server runs in the app.
    pub fn serving(&self) -> bool {
        #[cfg(all(feature = "app", not(target_arch = "wasm32")))]
        {
            self.server.is_some()
        }
        #[cfg(not(all(feature = "app", not(target_arch = "wasm32"))))]
        {
            false
        }
    }
}

/// Saves the class's CSV: a download in a browser; where the file dialog says on the desktop,
/// or `name` in the current folder where there is no dialog. The message for the status bar.
fn save_csv(picker: &mut dyn FilePicker, name: &str, csv: &str) -> Result<String, String> {
    if picker.downloads() {
        return if picker.download(name, "text/csv", csv.as_bytes()) {
            Ok(format!("downloading {name}"))
        } else {
            Err(format!("the browser refused the download of {name}"))
        };
    }
    let path = if picker.available() {
        match picker.save(super::file_picker::FileKind::ClassCsv, name) {
            Some(p) => p,
            None => return Ok("export cancelled".into()),
        }
    } else {
        std::path::PathBuf::from(name)
    };
    #[cfg(not(target_arch = "wasm32"))]
    {
        std::fs::write(&path, csv).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        let full = std::fs::canonicalize(&path).unwrap_or(path);
        Ok(format!("class answers saved in {}", full.display()))
    }
    #[cfg(target_arch = "wasm32")]
    {
        Err(format!("{}: no files in a browser", path.display()))
    }
}
