//! The class's windows: the teacher's Class window (the student link, its QR code and the
//! join code large, who joined, questions and the room's answers as they come in), the
//! student's banner (following, or exploring on their own with "Follow the teacher") and
//! question window (a poll's choices, the results the teacher shows), and a student page's
//! nickname prompt. Every user text (nicknames, prompts, choices, captions) is a plain label.

use super::teacher::exercise_request;
use super::{AnswerStatus, ClassAction, ClassClient, Connection, poll_request};
use crate::app::action::{Action, Actions};
use crate::app::shell::AppUi;
use crate::app::state::Level;
use crate::class::protocol::{QuestionKind, Role, Tally};
use egui::{Color32, RichText};

/// The QR code's side on screen (points): large enough to scan off a projector.
pub const QR_SIDE: f32 = 260.0;

/// The most height of the teacher's bars and mistakes before they scroll (points).
const TALLY_HEIGHT: f32 = 240.0;

/// Lays out the class's windows for the client's role.
pub fn show(c: &mut ClassClient, ctx: &egui::Context, app: &AppUi, out: &mut Actions) {
    if c.window {
        let mut open = true;
        // Sized to its contents, which grow once the class starts.
        egui::Window::new("Class")
            .open(&mut open)
            .collapsible(false)
            .resizable(false)
            // over the left panel, off the 3D view's middle (the target's gizmo) and the IK
            // panel's postures (the poll's choices)
            .default_pos(egui::pos2(8.0, 44.0))
            .show(ctx, |ui| class_window(ui, c, app, out));
        c.window = open;
    }
    if c.role() == Some(Role::Student) {
        banner(ctx, c, out);
        question_window(ctx, c, out);
    }
    if let Some(prompt) = c.prompt.clone() {
        name_prompt(ctx, c, &prompt, out);
    }
}

/// The Class window's contents: how to start or join, or the teacher's class.
fn class_window(ui: &mut egui::Ui, c: &mut ClassClient, app: &AppUi, out: &mut Actions) {
    connection_line(ui, c);
    match c.role() {
        Some(Role::Teacher) if c.welcome.is_some() => teacher_view(ui, c, app, out),
        Some(Role::Student) => {
            ui.label("You are a student in this class.");
            leave_button(ui, c, out);
        }
        _ => start_view(ui, c, out),
    }
}

/// Where the connection stands, in words.
fn connection_line(ui: &mut egui::Ui, c: &ClassClient) {
    let (text, color) = match &c.connection {
        Connection::Offline => ("not in a class".to_string(), Color32::GRAY),
        Connection::Connecting => ("connecting...".to_string(), Color32::GRAY),
        Connection::Joined => ("connected".to_string(), Color32::from_rgb(30, 130, 60)),
        Connection::Lost(why) => (
            format!("connection lost, reconnecting: {why}"),
            Color32::from_rgb(180, 100, 0),
        ),
        Connection::Refused(why) => (format!("refused: {why}"), Color32::from_rgb(180, 40, 30)),
    };
    ui.add(egui::Label::new(RichText::new(text).color(color)).wrap());
}

/// Not in a class yet: "Start a class here" (desktop) and "Join as teacher".
fn start_view(ui: &mut egui::Ui, c: &mut ClassClient, out: &mut Actions) {
    if cfg!(all(feature = "app", not(target_arch = "wasm32"))) {
        ui.checkbox(
            &mut c.form.reachable,
            "reachable from the classroom network",
        )
        .on_hover_text(
            "Listen on every network of this computer (0.0.0.0), not only on this \
                 computer: the students' laptops reach it by its address",
        );
        if ui.button("Start a class here").clicked() {
            let reachable = c.form.reachable;
            out.push(Action::Class(ClassAction::StartHere { reachable }));
        }
        ui.separator();
    }
    ui.horizontal(|ui| {
        let l = ui.label("Teacher link:");
        ui.add(
            egui::TextEdit::singleline(&mut c.form.teacher_link)
                .hint_text("http://HOST:PORT/?token=...")
                .desired_width(260.0),
        )
        .labelled_by(l.id);
    });
    if ui.button("Join as teacher").clicked() {
        let link = c.form.teacher_link.clone();
        out.push(Action::Class(ClassAction::JoinTeacher(link)));
    }
}

/// "Leave the class" (and stop the server started here).
fn leave_button(ui: &mut egui::Ui, c: &ClassClient, out: &mut Actions) {
    let label = if c.serving() {
        "End the class (stop the server)"
    } else {
        "Leave the class"
    };
    if ui.button(label).clicked() {
        out.push(Action::Class(ClassAction::Leave));
    }
}

/// The teacher's class: the link and QR code, who joined, questions and answers.
fn teacher_view(ui: &mut egui::Ui, c: &mut ClassClient, app: &AppUi, out: &mut Actions) {
    let Some(w) = &c.welcome else {
        return;
    };
    // the QR code and, beside it, the code in letters large enough to read off a projector
    ui.set_min_width(QR_SIDE + 220.0);
    ui.horizontal(|ui| {
        ui.label("Student link:");
        ui.add(egui::Label::new(RichText::new(&w.student_url).monospace()).selectable(true));
    });
    ui.horizontal_top(|ui| {
        qr_code(ui, &w.qr, QR_SIDE);
        ui.vertical(|ui| {
            ui.label("Join code:");
            let code = RichText::new(&w.code).size(40.0).monospace().strong();
            ui.add(egui::Label::new(code).wrap_mode(egui::TextWrapMode::Extend));
            ui.label(format!("{} student(s) joined", c.roster.joined));
            if !c.roster.names.is_empty() {
                // nicknames as plain text, never markup
                ui.add(egui::Label::new(c.roster.names.join(", ")).wrap());
            }
            if ui.button("Bring everyone back").clicked() {
                out.push(Action::Class(ClassAction::BringBack));
            }
        });
    });
    ui.separator();
    ask_buttons(ui, c, app, out);
    if let Some(q) = &c.question {
        ui.separator();
        question_tally(ui, c, q.id, q.open, out);
    }
    ui.separator();
    leave_button(ui, c, out);
}

/// The teacher's questions: the posture poll, an exercise kind with or without feedback.
fn ask_buttons(ui: &mut egui::Ui, c: &mut ClassClient, app: &AppUi, out: &mut Actions) {
    if ui
        .button("Ask: which posture is this?")
        .on_hover_text("A poll whose choices are the target's postures, as the IK panel lists them")
        .clicked()
    {
        match poll_request(app) {
            Ok(q) => out.push(Action::Class(ClassAction::Ask(q))),
            Err(e) => out.message(Level::Warning, format!("class: {e}")),
        }
    }
    ui.horizontal(|ui| {
        egui::ComboBox::from_label("Exercise kind")
            .selected_text(c.form.kind.name())
            .show_ui(ui, |ui| {
                for k in crate::exercise::Kind::ALL {
                    ui.selectable_value(&mut c.form.kind, k, k.name());
                }
            });
        ui.checkbox(&mut c.form.feedback, "feedback to students");
    });
    if ui.button("Ask this exercise").clicked() {
        let q = exercise_request(c.form.kind, c.form.feedback);
        out.push(Action::Class(ClassAction::Ask(q)));
    }
}

/// The room's answers to question `id`: answered of joined, correct in %, the bars, each
/// named mistake with its count; Show to class, Close question, Export CSV.
fn question_tally(ui: &mut egui::Ui, c: &ClassClient, id: u64, open: bool, out: &mut Actions) {
    let q = c.question.as_ref();
    let what = q.map_or(String::new(), |q| match (&q.prompt, q.kind) {
        (Some(p), _) => p.clone(),
        (None, k) => format!("exercise: {}", k.name()),
    });
    ui.add(egui::Label::new(RichText::new(what).strong()).wrap());
    if !open {
        ui.label("closed");
    }
    match &c.tally {
        Some(t) if t.id == id => tally_view(ui, t),
        _ => _ = ui.label(format!("answered 0 of {}", c.roster.joined)),
    }
    ui.horizontal(|ui| {
        if ui.button("Show to class").clicked() {
            out.push(Action::Class(ClassAction::Show(id)));
        }
        if ui
            .add_enabled(open, egui::Button::new("Close question"))
            .clicked()
        {
            out.push(Action::Class(ClassAction::Close(id)));
        }
        if ui.button("Export CSV").clicked() {
            out.push(Action::Class(ClassAction::Export));
        }
    });
}

/// A tally: answered of joined, correct in %, the bars, the mistakes by count.
fn tally_view(ui: &mut egui::Ui, t: &Tally) {
    ui.label(format!("answered {} of {}", t.answered, t.joined));
    ui.label(format!("correct {:.0} %", t.correct_percent));
    if t.unreadable > 0 {
        ui.label(format!("{} answer(s) could not be read", t.unreadable));
    }
    // An exercise's many scores and mistakes scroll, so that the window stays on screen.
    egui::ScrollArea::vertical()
        .id_salt("class tally")
        .max_height(TALLY_HEIGHT)
        .show(ui, |ui| {
            bars(ui, t);
            let mut mistakes: Vec<(&String, &usize)> = t.mistakes.iter().collect();
            mistakes.sort_by(|a, b| b.1.cmp(a.1).then(a.0.cmp(b.0)));
            for (m, n) in mistakes {
                ui.add(egui::Label::new(format!("{n} x {m}")).wrap());
            }
        });
}

/// The tally's counts as horizontal bars: a poll's choices, an exercise's scores.
pub fn bars(ui: &mut egui::Ui, t: &Tally) {
    let most = t.counts.iter().copied().max().unwrap_or(0).max(1) as f32;
    for (i, n) in t.counts.iter().enumerate() {
        let name = match t.choices.get(i) {
            Some(choice) => choice.clone(),
            None => format!("score {i} of {}", t.max),
        };
        ui.horizontal(|ui| {
            let (rect, r) = ui.allocate_exact_size(egui::vec2(160.0, 14.0), egui::Sense::hover());
            let mut bar = rect;
            bar.set_width(rect.width() * *n as f32 / most);
            ui.painter().rect_filled(rect, 2.0, Color32::from_gray(225));
            ui.painter()
                .rect_filled(bar, 2.0, Color32::from_rgb(60, 120, 200));
            let text = format!("{name}: {n}");
            r.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Label, true, &text));
            ui.label(format!("{n}  {name}"));
        });
    }
}

/// The QR code of `rows` (`#` dark), a quiet zone of four modules around, `side` points wide.
pub fn qr_code(ui: &mut egui::Ui, rows: &[String], side: f32) {
    let n = rows.len();
    if n == 0 {
        ui.label("(the link is too long for a QR code)");
        return;
    }
    let cells = n + 8;
    let module = (side / cells as f32).floor().max(2.0);
    let size = module * cells as f32;
    let (rect, r) = ui.allocate_exact_size(egui::vec2(size, size), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 0.0, Color32::WHITE);
    for (y, row) in rows.iter().enumerate() {
        for (x, dark) in row.chars().map(|ch| ch == '#').enumerate() {
            if dark {
                let min = rect.min + egui::vec2((x + 4) as f32, (y + 4) as f32) * module;
                let cell = egui::Rect::from_min_size(min, egui::vec2(module, module));
                painter.rect_filled(cell, 0.0, Color32::BLACK);
            }
        }
    }
    r.widget_info(|| {
        egui::WidgetInfo::labeled(egui::Role::Image, true, "QR code of the student link")
    });
}

/// The student's banner at the top of the window: following (with the lesson's step and
/// caption), or exploring on their own with "Follow the teacher" (while answering an exercise,
/// the question window has that button).
fn banner(ctx: &egui::Context, c: &ClassClient, out: &mut Actions) {
    let trouble = matches!(c.connection, Connection::Lost(_) | Connection::Refused(_));
    if c.student_answering() && !trouble {
        // The question window says so, with "Follow the teacher": a banner here would cover
        // the Exercise tab's sheet line (seen in `armlab class demo --student-screenshot`).
        return;
    }
    egui::Area::new(egui::Id::unique("class banner"))
        .anchor(egui::Align2::CENTER_TOP, egui::vec2(0.0, 44.0))
        .show(ctx, |ui| {
            egui::Frame::popup(ui.style()).show(ui, |ui| {
                ui.set_max_width(640.0);
                match &c.connection {
                    Connection::Lost(_) => _ = ui.label("connection lost: reconnecting..."),
                    Connection::Refused(why) => _ = ui.label(format!("not in the class: {why}")),
                    _ if c.following => following_line(ui, c),
                    _ => {
                        ui.horizontal(|ui| {
                            ui.label(RichText::new("exploring on your own").strong());
                            follow_button(ui, out);
                        });
                    }
                }
            });
        });
}

/// "Follow the teacher": back to the teacher's view.
fn follow_button(ui: &mut egui::Ui, out: &mut Actions) {
    if ui.button("Follow the teacher").clicked() {
        out.push(Action::Class(ClassAction::Follow));
    }
}

/// "following the teacher", the lesson's step and its caption (plain text).
fn following_line(ui: &mut egui::Ui, c: &ClassClient) {
    let state = c.teacher_state();
    let lesson = state.and_then(|s| s.lesson.as_ref());
    let head = match lesson {
        Some(l) => format!(
            "following the teacher: {}, step {} of {}",
            l.title, l.step, l.steps
        ),
        None => "following the teacher".to_string(),
    };
    ui.label(RichText::new(head).strong());
    if let Some(caption) = state
        .map(|s| s.view.caption.trim())
        .filter(|t| !t.is_empty())
    {
        let size = egui::TextStyle::Body.resolve(ui.style()).size * 1.35;
        ui.add(egui::Label::new(RichText::new(caption).size(size)).wrap());
    }
}

/// The student's question window: a poll's prompt and one button per choice, what became of
/// the answer, and the results the teacher showed.
fn question_window(ctx: &egui::Context, c: &ClassClient, out: &mut Actions) {
    let Some(q) = &c.question else {
        return;
    };
    egui::Window::new("Question")
        .collapsible(false)
        .anchor(egui::Align2::RIGHT_BOTTOM, egui::vec2(-16.0, -48.0))
        .show(ctx, |ui| {
            if let Some(p) = &q.prompt {
                ui.add(egui::Label::new(RichText::new(p).strong()).wrap());
            }
            if q.kind == QuestionKind::Poll {
                for (i, choice) in q.choices.iter().enumerate() {
                    // the choice's text as a plain label on the button
                    if ui.add_enabled(q.open, egui::Button::new(choice)).clicked() {
                        let answer = serde_json::Value::from(i);
                        out.push(Action::Class(ClassAction::Answer { id: q.id, answer }));
                    }
                }
            } else {
                ui.label("Answer in the Exercise tab, then Send answer.");
                if c.student_answering() {
                    ui.horizontal(|ui| {
                        ui.label("(the teacher's view waits)");
                        follow_button(ui, out);
                    });
                }
            }
            match &c.answer {
                Some(AnswerStatus::Sent) => _ = ui.label("answer sent"),
                Some(AnswerStatus::Received(_)) => _ = ui.label("answer sent: the teacher has it"),
                Some(AnswerStatus::Refused(e)) => _ = ui.label(format!("not taken: {e}")),
                None => {}
            }
            if !q.open {
                ui.label("The teacher closed the question.");
            }
            if let Some(t) = c.results.as_ref().filter(|t| t.id == q.id) {
                ui.separator();
                ui.label(format!(
                    "The class answered ({} of {}):",
                    t.answered, t.joined
                ));
                bars(ui, t);
            }
        });
}

/// A student page opened without a nickname: asks for one, then joins.
fn name_prompt(
    ctx: &egui::Context,
    c: &mut ClassClient,
    prompt: &super::NamePrompt,
    out: &mut Actions,
) {
    egui::Window::new("Join the class")
        .collapsible(false)
        .anchor(egui::Align2::CENTER_CENTER, egui::Vec2::ZERO)
        .show(ctx, |ui| {
            let mut go = false;
            ui.horizontal(|ui| {
                let l = ui.label("Your nickname:");
                let r = ui
                    .add(egui::TextEdit::singleline(&mut c.form.nickname).desired_width(200.0))
                    .labelled_by(l.id);
                // The page opens ready to type: the field takes the focus once, on the prompt's
                // first frame (every frame would take it back from Enter, which then never
                // joined).
                let once = r.id.with("focused once");
                if ui.memory(|m| m.data.get_temp::<bool>(once).is_none()) {
                    ui.memory_mut(|m| m.data.insert_temp(once, true));
                    r.request_focus();
                }
                go = r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
            });
            let name = c.form.nickname.trim().to_string();
            let fits = (1..=crate::class::protocol::MAX_NAME_CHARS).contains(&name.chars().count());
            if ui.add_enabled(fits, egui::Button::new("Join")).clicked() || (go && fits) {
                out.push(Action::Class(ClassAction::JoinStudent {
                    ws: prompt.ws.clone(),
                    code: prompt.code.clone(),
                    name,
                    resume: prompt.resume.clone(),
                }));
            }
        });
}
