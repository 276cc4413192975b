//! The Exercise tab: opens a student's sheet (`armlab exercise new` writes `sheet.json`) in exam
//! mode, or a teacher's key for practice; shows its question, hides from the panels what the
//! sheet asks for (the DH table and the frames, the pose readouts, the IK solutions and ghosts),
//! takes the answer (a DH table in a grid, or rows of numbers); an exam saves it to be handed in
//! (`armlab exercise grade` grades the class), practice grades it here item by item. Grading
//! is [`crate::exercise`]'s.
//!
//! An orientation sheet (euler, compose, axis-angle, quaternion) has no arm: the app keeps its
//! own, and the answer is typed line by line as its file has it (`phi theta psi`, the matrix's
//! rows, ...), with a degrees toggle where the answer holds angles.

use super::super::action::{Action, Actions};
use super::super::state::{AppState, Hidden, Level};
use super::{Tab, TabContext};
use crate::exercise::orientation::{answer_lines, parse_answer, takes_degrees};
use crate::exercise::{Answer, Grade, Key, KeyAnswer, Kind, SheetFile, grade, parse_rows};
use crate::kinematics::{Convention, DhJoint, DhRow, JointKind, Pose, Robot};
use egui::{Color32, RichText};

/// One row of the DH-table answer, as typed (m, deg).
#[derive(Debug, Clone, PartialEq)]
pub struct AnswerRow {
    /// Prismatic instead of revolute.
    pub prismatic: bool,
    /// a (m).
    pub a: String,
    /// alpha (deg).
    pub alpha_deg: String,
    /// d (m; the constant part of a prismatic joint's d is its offset).
    pub d: String,
    /// theta (deg): a revolute joint's offset, a prismatic joint's constant angle.
    pub theta_deg: String,
}

impl Default for AnswerRow {
    fn default() -> Self {
        Self {
            prismatic: false,
            a: "0".into(),
            alpha_deg: "0".into(),
            d: "0".into(),
            theta_deg: "0".into(),
        }
    }
}

/// What the tab says before a sheet is open (Markdown).
const INTRODUCTION: &str = "Open your sheet (`student-NN/sheet.json`, made by `armlab exercise \
                            new`) or drop it on the window: its question shows here, what it \
                            asks for is hidden in the panels, and your answer is saved beside \
                            it to be handed in. A teacher's key (`keys/student-NN.json`) opens \
                            the same sheet for practice, graded here.";

/// The sheet being answered.
#[derive(Debug, Clone)]
pub struct OpenSheet {
    /// What the sheet asks for.
    pub kind: Kind,
    /// The question (Markdown).
    pub question: String,
    /// Practice (a key was opened): the key, and Check grades here. Exam (a sheet file was
    /// opened): `None`, and the answer is saved to be handed in.
    pub key: Option<Key>,
    /// Exam: where "Save answer" writes (`student-NN.toml` or `.txt` beside the sheet).
    pub answer_path: String,
    /// The DH-table answer (dh-table sheets).
    pub rows: Vec<AnswerRow>,
    /// The modified convention instead of the standard one.
    pub modified: bool,
    /// The rows-of-numbers answer (other sheets).
    pub text: String,
    /// An orientation answer's lines as typed, one per line of its file.
    pub lines: Vec<String>,
    /// The orientation answer's angles are in degrees (the file's first line `# deg`).
    pub degrees: bool,
    /// The last grade, or why the answer could not be graded.
    pub result: Option<Result<Grade, String>>,
    /// A live class's question (the sheet came from the teacher): "Send answer" sends the
    /// answer to the class server instead of saving it.
    pub class: Option<ClassQuestion>,
}

/// A live class's question answered in the tab: its id, what became of the answer, and
/// whether the teacher closed it (the inputs are then off).
#[derive(Debug, Clone, PartialEq)]
pub struct ClassQuestion {
    /// The question's id in the session.
    pub id: u64,
    /// What became of the answer (`Open` before any was sent).
    pub status: ClassSheetStatus,
    /// The teacher closed the question.
    pub closed: bool,
}

/// What happens to a class question's sheet, as the class client tells the tab.
#[derive(Debug, Clone, PartialEq)]
pub enum ClassSheetStatus {
    /// The sheet of this kind just opened is the class's question (nothing sent yet).
    Open(Kind),
    /// The answer was sent.
    Sent,
    /// The server has it, with the grade where the question gives feedback.
    Received(Option<crate::class::protocol::StudentGrade>),
    /// The server refused it (why).
    Refused(String),
    /// The teacher closed the question.
    Closed,
}

/// The Exercise tab's own state.
#[derive(Debug, Default)]
pub struct ExerciseTab {
    /// The sheet's (or key's) path typed in the tab.
    pub key_path: String,
    /// The sheet being answered.
    pub sheet: Option<OpenSheet>,
    /// The question's rendered Markdown, kept between frames.
    pub question_view: crate::app::markdown::MarkdownCache,
}

impl Tab for ExerciseTab {
    fn title(&self) -> &'static str {
        "Exercise"
    }

    fn ui(&mut self, _cx: &mut TabContext<'_>, ui: &mut egui::Ui, out: &mut Actions) {
        egui::ScrollArea::vertical().show(ui, |ui| self.contents(ui, out));
    }
}

/// A student's sheet (exam) or a teacher's key (practice), read before its arm is loaded.
#[derive(Debug, Clone)]
pub enum Opening {
    /// A key: practice, graded in the tab.
    Practice(Box<Key>),
    /// A student's sheet: an exam, the answer saved to be handed in.
    Exam(Box<SheetFile>),
}

impl Opening {
    /// Reads a sheet (by its format tag) or else a key; `name` (the file) for messages.
    pub fn read(name: &str, text: &str) -> Result<Self, String> {
        if text.contains(crate::exercise::SHEET_FORMAT) {
            let sheet = SheetFile::parse(name, text).map_err(|e| e.to_string())?;
            return Ok(Self::Exam(Box::new(sheet)));
        }
        parse_key(name, text).map(|k| Self::Practice(Box::new(k)))
    }

    /// The arm to load: a model file's name (its format) and text; `None` for an orientation
    /// sheet, which has no arm.
    pub fn arm(&self) -> Option<(&'static str, &str)> {
        match self {
            Self::Practice(k) if k.kind.is_orientation() => None,
            Self::Exam(s) if s.kind.is_orientation() => None,
            Self::Practice(k) => Some(("sheet.toml", &k.model)),
            Self::Exam(s) => Some(("sheet.urdf", &s.arm)),
        }
    }
}

impl ExerciseTab {
    /// Opens `opening` (read from the file `path`), whose arm `state` has just loaded.
    pub fn open(&mut self, opening: Opening, path: &str, state: &AppState) -> Actions {
        match opening {
            Opening::Practice(key) => self.open_key(*key, state),
            Opening::Exam(sheet) => self.open_exam(&sheet, path, state),
        }
    }

    /// Opens the key `key` for practice (its arm `state` has just loaded): returns what the
    /// sheet sets up (the key's q and the target on the tool, what the sheet asks for hidden,
    /// the Exercise tab shown). Check grades the answer against the key.
    pub fn open_key(&mut self, key: Key, state: &AppState) -> Actions {
        let out = setup(key.kind, &key.q, false, state);
        self.sheet = Some(OpenSheet::new(key.kind, key.question.clone(), state));
        if let Some(s) = &mut self.sheet {
            s.key = Some(key);
        }
        out
    }

    /// Opens the student's sheet file `sheet` (read from `path`; its arm `state` has just
    /// loaded) in exam mode: the same set-up as a key's, and besides every way out of the
    /// answer disabled (saving the model, the symbols, the figure export); the answer is saved
    /// beside the sheet as `student-NN.toml` or `.txt` to be handed in.
    pub fn open_exam(&mut self, sheet: &SheetFile, path: &str, state: &AppState) -> Actions {
        let out = setup(sheet.kind, &sheet.q, true, state);
        let mut open = OpenSheet::new(sheet.kind, sheet.question.clone(), state);
        let dir = std::path::Path::new(path)
            .parent()
            .unwrap_or(std::path::Path::new(""));
        open.answer_path = dir
            .join(sheet.answer_file_name())
            .to_string_lossy()
            .into_owned();
        self.sheet = Some(open);
        out
    }

    /// Closes the sheet: returns what shows the panels' contents again.
    pub fn close(&mut self, state: &AppState) -> Actions {
        self.sheet = None;
        let mut d = state.display;
        d.frames = true;
        d.labels = true;
        Actions(vec![
            Action::SetHidden(Hidden::default()),
            Action::SetDisplay(d),
        ])
    }

    /// A class question's news: `Open(kind)` makes the sheet just opened (of that kind) the
    /// class's question `id`; the others say what became of its answer. News of another
    /// question than the open one is dropped.
    pub fn class_status(&mut self, id: u64, status: ClassSheetStatus) {
        let Some(sheet) = &mut self.sheet else {
            return;
        };
        if let ClassSheetStatus::Open(kind) = status {
            if kind == sheet.kind && sheet.key.is_none() {
                sheet.class = Some(ClassQuestion {
                    id,
                    status,
                    closed: false,
                });
            }
            return;
        }
        if let Some(c) = sheet.class.as_mut().filter(|c| c.id == id) {
            match status {
                ClassSheetStatus::Closed => c.closed = true,
                status => c.status = status,
            }
        }
    }

    fn contents(&mut self, ui: &mut egui::Ui, out: &mut Actions) {
        ui.horizontal(|ui| {
            let l = ui.label("Sheet:");
            let r = ui
                .add(
                    egui::TextEdit::singleline(&mut self.key_path)
                        .hint_text("student-01/sheet.json")
                        .desired_width(320.0),
                )
                .labelled_by(l.id);
            let enter = r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
            if ui.button("Open sheet").clicked() || enter {
                out.push(Action::OpenExercise(self.key_path.clone()));
            }
            if self.sheet.is_some() && ui.button("Close sheet").clicked() {
                out.push(Action::CloseExercise);
            }
        });
        let Some(sheet) = &mut self.sheet else {
            let size = egui::TextStyle::Body.resolve(ui.style()).size;
            crate::app::markdown::show(ui, &mut self.question_view, INTRODUCTION, size);
            return;
        };
        ui.separator();
        if sheet.key.is_none() {
            let note = if sheet.class.is_some() {
                "The teacher's question: Send answer sends your answer to the class."
            } else {
                "Exam: saving the model, the symbols and figure export are off until the \
                 sheet is closed."
            };
            ui.label(RichText::new(note).color(Color32::from_rgb(150, 90, 0)));
        }
        // A step above the window's body text (13.5 -> 15), so larger still in projector mode.
        let body = egui::TextStyle::Body.resolve(ui.style()).size;
        let size = (body * 15.0 / 13.5).max(super::super::layout::text_floor(ui.ctx()));
        crate::app::markdown::show(ui, &mut self.question_view, &sheet.question, size);
        ui.separator();
        ui.heading("Your answer");
        let closed = sheet.class.as_ref().is_some_and(|c| c.closed);
        ui.add_enabled_ui(!closed, |ui| answer_entry(ui, sheet));
        if sheet.key.is_some() {
            check_row(ui, sheet, out);
        } else if sheet.class.is_some() {
            class_row(ui, sheet, out);
        } else {
            save_row(ui, sheet, out);
        }
    }
}

/// What opening a sheet of `kind` at `q` sets up: the arm at q, the target on its tool, what
/// the sheet asks for hidden (and in an exam every way out of the answer), the tab shown.
fn setup(kind: Kind, q: &[f64], exam: bool, state: &AppState) -> Actions {
    let mut out = Actions::default();
    let how = if exam { "to answer" } else { "for practice" };
    if kind.is_orientation() {
        // no arm: the app's own stays as it is; an exam still closes every way out
        out.push(Action::SetHidden(Hidden {
            exam,
            ..Hidden::default()
        }));
        out.push(Action::ShowTab(super::EXERCISE));
        out.message(
            Level::Info,
            format!("exercise: {} sheet opened {how}", kind.name()),
        );
        return out;
    }
    // Said after the arm's loading message, which spoke of its opening pose, not the sheet's q.
    out.message(
        Level::Info,
        format!(
            "exercise: {} sheet opened {how}; the arm is at the sheet's q",
            kind.name()
        ),
    );
    out.push(Action::SetQ(q.to_vec()));
    out.push(Action::TargetToTool(0));
    let dh = kind == Kind::DhTable;
    let ik = kind == Kind::Ik;
    out.push(Action::SetHidden(Hidden {
        dh_table: dh || exam,
        pose: kind == Kind::Fk,
        solutions: ik,
        workspace: kind == Kind::Workspace,
        exam,
    }));
    let mut d = state.display;
    d.frames = !dh;
    d.labels = !dh;
    d.ghosts = !ik;
    d.workspace = false;
    out.push(Action::SetDisplay(d));
    out.push(Action::ShowConstruction(false));
    out.push(Action::ShowTab(super::EXERCISE));
    out
}

impl OpenSheet {
    fn new(kind: Kind, question: String, state: &AppState) -> Self {
        let dh = kind == Kind::DhTable;
        Self {
            kind,
            question,
            key: None,
            answer_path: String::new(),
            rows: vec![AnswerRow::default(); if dh { state.robot().dof() } else { 0 }],
            modified: false,
            text: String::new(),
            lines: vec![String::new(); answer_lines(kind).len()],
            degrees: takes_degrees(kind),
            result: None,
            class: None,
        }
    }
}

/// Practice: Check grades the answer against the key, item by item.
fn check_row(ui: &mut egui::Ui, sheet: &mut OpenSheet, out: &mut Actions) {
    if ui.button("Check").clicked() {
        sheet.result = Some(check(sheet));
        if let Some(Ok(g)) = &sheet.result {
            out.message(
                Level::Info,
                format!("exercise: score {} of {}", g.score, g.max),
            );
        }
    }
    match &sheet.result {
        Some(Ok(g)) => feedback(ui, g),
        Some(Err(e)) => {
            ui.colored_label(Color32::from_rgb(180, 40, 30), e);
        }
        None => {}
    }
}

/// Names a text field `name` for screen readers (and UI tests), with `value` as its text.
fn name_text_input(e: &egui::Response, name: &str, value: &str) {
    e.widget_info(|| {
        let mut info = egui::WidgetInfo::labeled(egui::Role::TextInput, true, name);
        info.current_text_value = Some(value.to_string());
        info
    });
}

/// The answer's inputs: a DH table's grid, an orientation's lines, or rows of numbers.
fn answer_entry(ui: &mut egui::Ui, sheet: &mut OpenSheet) {
    if sheet.kind == Kind::DhTable {
        dh_grid(ui, sheet);
    } else if sheet.kind.is_orientation() {
        orientation_entry(ui, sheet);
    } else {
        ui.add(
            egui::TextEdit::multiline(&mut sheet.text)
                .hint_text("rows of numbers, or names, as the question says")
                .desired_rows(6)
                .font(egui::TextStyle::Monospace),
        );
    }
}

/// A live class's question: Send answer sends the same text Save answer would write; then
/// what became of it (sent, received, the grade where the teacher gives feedback, refused),
/// and the inputs off once the teacher closed the question.
fn class_row(ui: &mut egui::Ui, sheet: &mut OpenSheet, out: &mut Actions) {
    let Some(class) = sheet.class.clone() else {
        return;
    };
    if ui
        .add_enabled(!class.closed, egui::Button::new("Send answer"))
        .on_disabled_hover_text("The teacher closed the question")
        .clicked()
    {
        match answer_text(sheet) {
            Ok(text) => {
                sheet.result = None;
                out.push(Action::Class(crate::app::class::ClassAction::Answer {
                    id: class.id,
                    answer: serde_json::Value::String(text),
                }));
            }
            Err(e) => sheet.result = Some(Err(e)),
        }
    }
    let red = Color32::from_rgb(180, 40, 30);
    match &class.status {
        ClassSheetStatus::Sent => _ = ui.label("answer sent"),
        ClassSheetStatus::Received(None) => _ = ui.label("answer sent: the teacher has it"),
        ClassSheetStatus::Received(Some(g)) => class_grade(ui, g),
        ClassSheetStatus::Refused(e) => _ = ui.colored_label(red, format!("not taken: {e}")),
        ClassSheetStatus::Open(_) | ClassSheetStatus::Closed => {}
    }
    if class.closed {
        ui.label("The teacher closed the question.");
    }
    if let Some(Err(e)) = &sheet.result {
        ui.colored_label(red, e);
    }
}

/// A class question's grade as the student sees it, item by item.
fn class_grade(ui: &mut egui::Ui, g: &crate::class::protocol::StudentGrade) {
    ui.label(RichText::new(format!("answer sent: score {} of {}", g.score, g.max)).strong());
    for item in &g.items {
        let (mark, color) = if item.correct {
            ("right", Color32::from_rgb(30, 130, 60))
        } else {
            ("wrong", Color32::from_rgb(180, 40, 30))
        };
        ui.colored_label(color, format!("{mark}  {}: {}", item.item, item.feedback));
    }
}

/// Exam: the answer's file name and Save answer (a DH table as a model file, rows as typed).
fn save_row(ui: &mut egui::Ui, sheet: &mut OpenSheet, out: &mut Actions) {
    ui.horizontal(|ui| {
        let l = ui.label("Hand in as:");
        ui.add(egui::TextEdit::singleline(&mut sheet.answer_path).desired_width(320.0))
            .labelled_by(l.id);
        if ui.button("Save answer").clicked() {
            match answer_text(sheet) {
                Ok(text) => {
                    sheet.result = None;
                    out.push(Action::SaveAnswer {
                        path: sheet.answer_path.trim().to_string(),
                        text,
                    });
                }
                Err(e) => sheet.result = Some(Err(e)),
            }
        }
    });
    if let Some(Err(e)) = &sheet.result {
        ui.colored_label(Color32::from_rgb(180, 40, 30), e);
    }
}

/// The answer as the file handed in: the typed DH table as a model file, an orientation's
/// lines (after `# deg` where they are degrees), else the text.
fn answer_text(sheet: &OpenSheet) -> Result<String, String> {
    if sheet.kind.is_orientation() {
        return Ok(orientation_text(sheet));
    }
    if sheet.kind != Kind::DhTable {
        return Ok(sheet.text.clone());
    }
    crate::model_file::to_toml(&answer_robot(sheet)?)
        .ok_or_else(|| "the typed table is no DH model file".to_string())
}

/// An orientation answer as its file: `# deg` first where the angles are degrees, then the
/// typed lines.
fn orientation_text(sheet: &OpenSheet) -> String {
    let mut text = String::new();
    if sheet.degrees && takes_degrees(sheet.kind) {
        text.push_str("# deg\n");
    }
    for line in &sheet.lines {
        text.push_str(line.trim());
        text.push('\n');
    }
    text
}

/// The orientation answer: one field per line of its file, named by its numbers
/// (`phi theta psi`, `row 1: r11 r12 r13`), and the degrees toggle where it holds angles.
fn orientation_entry(ui: &mut egui::Ui, sheet: &mut OpenSheet) {
    let layout = answer_lines(sheet.kind);
    if takes_degrees(sheet.kind) {
        ui.checkbox(&mut sheet.degrees, "angles in degrees");
    }
    ui.label("Numbers separated by spaces or commas.");
    sheet.lines.resize(layout.len(), String::new());
    // One row each, not a grid: a grid's first frame gave the field 40 points (found live: a
    // typed line showed only its last three letters).
    for (i, (line, names)) in sheet.lines.iter_mut().zip(layout).enumerate() {
        let name = if layout.len() > 1 {
            format!("row {}: {}", i + 1, names.join(" "))
        } else {
            names.join(" ")
        };
        ui.horizontal(|ui| {
            ui.label(RichText::new(&name).monospace());
            let e = ui.add(
                egui::TextEdit::singleline(line)
                    .hint_text(names.join(" "))
                    .desired_width(320.0)
                    .font(egui::TextStyle::Monospace),
            );
            // named for screen readers (and UI tests): "answer: phi theta psi"
            name_text_input(&e, &format!("answer: {name}"), line);
        });
    }
}

/// The DH-table answer: one editable row per joint, and the convention.
fn dh_grid(ui: &mut egui::Ui, sheet: &mut OpenSheet) {
    ui.horizontal(|ui| {
        ui.radio_value(&mut sheet.modified, false, "standard DH");
        ui.radio_value(&mut sheet.modified, true, "modified DH");
        if ui.button("+ row").clicked() {
            sheet.rows.push(AnswerRow::default());
        }
        if ui.button("- row").clicked() {
            sheet.rows.pop();
        }
    });
    egui::Grid::new("exercise dh answer")
        .striped(true)
        .show(ui, |ui| {
            for h in [
                "row",
                "prismatic",
                "a (m)",
                "alpha (deg)",
                "d (m)",
                "theta (deg)",
            ] {
                ui.label(RichText::new(h).strong());
            }
            ui.end_row();
            for (i, r) in sheet.rows.iter_mut().enumerate() {
                ui.label((i + 1).to_string());
                let c = ui.checkbox(&mut r.prismatic, "");
                // named for screen readers (and UI tests): "row 2 prismatic", "row 2 alpha"
                let name = format!("row {} prismatic", i + 1);
                c.widget_info(|| {
                    egui::WidgetInfo::selected(egui::Role::CheckBox, true, r.prismatic, &name)
                });
                for (field, what) in [
                    (&mut r.a, "a"),
                    (&mut r.alpha_deg, "alpha"),
                    (&mut r.d, "d"),
                    (&mut r.theta_deg, "theta"),
                ] {
                    let e = ui.add(egui::TextEdit::singleline(field).desired_width(70.0));
                    name_text_input(&e, &format!("row {} {what}", i + 1), field);
                }
                ui.end_row();
            }
        });
}

/// The typed table as a robot (frame 0 the base, frame n the tool).
fn answer_robot(sheet: &OpenSheet) -> Result<Robot, String> {
    let num = |s: &str, what: &str, i: usize| {
        s.trim()
            .parse::<f64>()
            .map_err(|_| format!("row {}: {what} {s:?} is not a number", i + 1))
    };
    let mut joints = Vec::new();
    for (i, r) in sheet.rows.iter().enumerate() {
        let (a, alpha) = (
            num(&r.a, "a", i)?,
            num(&r.alpha_deg, "alpha", i)?.to_radians(),
        );
        let (d, theta) = (
            num(&r.d, "d", i)?,
            num(&r.theta_deg, "theta", i)?.to_radians(),
        );
        let joint = if r.prismatic {
            DhJoint::new(
                JointKind::Prismatic,
                DhRow {
                    a,
                    alpha,
                    d: 0.0,
                    theta,
                },
            )
            .offset(d)
        } else {
            DhJoint::new(
                JointKind::Revolute,
                DhRow {
                    a,
                    alpha,
                    d,
                    theta: 0.0,
                },
            )
            .offset(theta)
        };
        joints.push(joint.unbounded());
    }
    let conv = if sheet.modified {
        Convention::Modified
    } else {
        Convention::Standard
    };
    Robot::from_dh("answer", conv, &joints, Pose::identity(), Pose::identity())
        .map_err(|e| e.to_string())
}

/// Grades the answer typed in the tab.
fn check(sheet: &OpenSheet) -> Result<Grade, String> {
    let key = sheet
        .key
        .as_ref()
        .ok_or("a sheet is graded by the teacher")?;
    if key.kind.is_orientation() {
        let text = orientation_text(sheet);
        let answer = parse_answer(key.kind, &text, "answer").map_err(|e| e.to_string())?;
        return grade(key, &Answer::Orientation(answer)).map_err(|e| e.to_string());
    }
    let answer = match key.answer {
        KeyAnswer::DhTable => Answer::Model(Box::new(answer_robot(sheet)?)),
        KeyAnswer::Identifiability { .. } => {
            Answer::Words(crate::exercise::parse_words(&sheet.text))
        }
        _ => Answer::Rows(parse_rows(&sheet.text, "answer").map_err(|e| e.to_string())?),
    };
    grade(key, &answer).map_err(|e| e.to_string())
}

/// The grade, item by item: right in green, wrong in red with what is wrong.
fn feedback(ui: &mut egui::Ui, g: &Grade) {
    ui.label(RichText::new(format!("score {} of {}", g.score, g.max)).strong());
    for item in &g.items {
        let (mark, color) = if item.correct {
            ("right", Color32::from_rgb(30, 130, 60))
        } else {
            ("wrong", Color32::from_rgb(180, 40, 30))
        };
        ui.colored_label(color, format!("{mark}  {}: {}", item.item, item.feedback));
    }
}

/// The exercise key in `text` (the file `name`, for messages).
pub fn parse_key(name: &str, text: &str) -> Result<Key, String> {
    serde_json::from_str(text).map_err(|e| format!("{name}: not an armlab exercise key: {e}"))
}
