//! The Exercise tab: opens a sheet's key (`armlab exercise new` writes them), shows its
//! question, hides from the panels what the sheet asks for (the DH table and the frames, the
//! pose readouts, the IK solutions and ghosts), takes the answer (a DH table in a grid, or rows
//! of numbers) and shows the grade item by item. Grading is [`crate::exercise`]'s.

use super::super::action::{Action, Actions};
use super::super::state::{AppState, Hidden, Level};
use super::{Tab, TabContext};
use crate::exercise::{Answer, Grade, Key, KeyAnswer, grade, parse_rows};
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

/// The sheet being answered.
#[derive(Debug, Clone)]
pub struct OpenSheet {
    /// Its key.
    pub key: Key,
    /// The DH-table answer (dh-table sheets).
    pub rows: Vec<AnswerRow>,
    /// The modified convention instead of the standard one.
    pub modified: bool,
    /// The rows-of-numbers answer (other sheets).
    pub text: String,
    /// The last grade, or why the answer could not be graded.
    pub result: Option<Result<Grade, String>>,
}

/// The Exercise tab's own state.
#[derive(Debug, Default)]
pub struct ExerciseTab {
    /// The key file's path typed in the tab.
    pub key_path: String,
    /// The sheet being answered.
    pub sheet: Option<OpenSheet>,
}

impl Tab for ExerciseTab {
    fn title(&self) -> &'static str {
        "Exercise"
    }

    fn ui(&mut self, _cx: &mut TabContext<'_>, ui: &mut egui::Ui, out: &mut Actions) {
        egui::ScrollArea::vertical().show(ui, |ui| self.contents(ui, out));
    }
}

impl ExerciseTab {
    /// Opens the sheet of `key`, whose arm `state` has just loaded: returns what the sheet sets
    /// up (the key's q and the target on the tool, what the sheet asks for hidden, the Exercise
    /// tab shown).
    pub fn open(&mut self, key: Key, state: &AppState) -> Actions {
        let mut out = Actions::default();
        out.push(Action::SetQ(key.q.clone()));
        out.push(Action::TargetToTool(0));
        let dh = matches!(key.answer, KeyAnswer::DhTable);
        let ik = matches!(key.answer, KeyAnswer::Ik { .. });
        out.push(Action::SetHidden(Hidden {
            dh_table: dh,
            pose: matches!(key.answer, KeyAnswer::Fk { .. }),
            solutions: ik,
        }));
        let mut d = state.display;
        d.frames = !dh;
        d.labels = !dh;
        d.ghosts = !ik;
        out.push(Action::SetDisplay(d));
        out.push(Action::ShowConstruction(false));
        out.push(Action::ShowTab(super::EXERCISE));
        self.sheet = Some(OpenSheet {
            rows: vec![AnswerRow::default(); if dh { state.robot().dof() } else { 0 }],
            key,
            modified: false,
            text: String::new(),
            result: None,
        });
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

    fn contents(&mut self, ui: &mut egui::Ui, out: &mut Actions) {
        ui.horizontal(|ui| {
            ui.label("Key:");
            let r = ui.add(
                egui::TextEdit::singleline(&mut self.key_path)
                    .hint_text("keys/student-01.json")
                    .desired_width(320.0),
            );
            let enter = r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
            if ui.button("Open sheet").clicked() || enter {
                out.push(Action::OpenExercise(self.key_path.clone()));
            }
            if self.sheet.is_some() && ui.button("Close sheet").clicked() {
                out.push(Action::CloseExercise);
            }
        });
        let Some(sheet) = &mut self.sheet else {
            ui.label(
                "Open the key of a sheet made by `armlab exercise new` (or drop it on the window): \
                 its question shows here, what it asks for is hidden in the panels, and the \
                 answer is graded here.",
            );
            return;
        };
        ui.separator();
        ui.add(egui::Label::new(RichText::new(&sheet.key.question).size(15.0)).wrap());
        ui.separator();
        ui.heading("Your answer");
        if matches!(sheet.key.answer, KeyAnswer::DhTable) {
            dh_grid(ui, sheet);
        } else {
            ui.add(
                egui::TextEdit::multiline(&mut sheet.text)
                    .hint_text("rows of numbers, or names, as the question says")
                    .desired_rows(6)
                    .font(egui::TextStyle::Monospace),
            );
        }
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
                    let name = format!("row {} {what}", i + 1);
                    let value = field.clone();
                    e.widget_info(|| {
                        let mut info =
                            egui::WidgetInfo::labeled(egui::Role::TextInput, true, &name);
                        info.current_text_value = Some(value.clone());
                        info
                    });
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
    let answer = match sheet.key.answer {
        KeyAnswer::DhTable => Answer::Model(Box::new(answer_robot(sheet)?)),
        KeyAnswer::Identifiability { .. } => {
            Answer::Words(crate::exercise::parse_words(&sheet.text))
        }
        _ => Answer::Rows(parse_rows(&sheet.text, "answer").map_err(|e| e.to_string())?),
    };
    grade(&sheet.key, &answer).map_err(|e| e.to_string())
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
