//! The keyboard: the desktop's shortcuts (Ctrl+O, Ctrl+S, undo, redo, quit), the single keys of
//! the view and the lesson, and the help window that lists them.

use super::action::{Action, Actions};
use super::panels::construction::ConstructionPanel;
use super::state::AppState;
use crate::camera::Preset;
use egui::Key;

/// The keyboard, read once a frame: the desktop's shortcuts (consumed, so Ctrl+O does not also
/// press O), then single keys unless a text field has the keyboard. The display keys (G, D, T)
/// and the construction keys (C, N, B) change `state.display` and `construction` at once; the
/// others become actions; PgDn / PgUp step from `lesson_step` (the lesson's step shown, if
/// any).
pub fn read(
    ctx: &egui::Context,
    state: &mut AppState,
    construction: &mut ConstructionPanel,
    lesson_step: Option<usize>,
    out: &mut Actions,
) {
    command_shortcuts(ctx, out);
    // A text field has the keyboard, or a list is open (the model list: a click meant for a
    // text field that lands on it must not turn the typed path into shortcuts).
    if ctx.egui_wants_keyboard_input() || egui::Popup::is_any_open(ctx) {
        return;
    }
    let pressed = |k: Key| ctx.input(|i| i.key_pressed(k));
    for (k, p) in [
        (Key::Num1, Preset::Top),
        (Key::Num2, Preset::Front),
        (Key::Num3, Preset::Side),
        (Key::Num4, Preset::Iso),
    ] {
        if pressed(k) {
            out.push(Action::CameraPreset(p));
        }
    }
    let keys = [
        (Key::F, Action::Fit),
        (Key::O, Action::ToggleProjection),
        (Key::P, Action::ToggleProjector),
        (Key::V, Action::ToggleSidePanels),
        (Key::F5, Action::TogglePresent),
        (Key::Escape, Action::EndPresent),
        (Key::W, Action::ToggleWorkspace),
        (Key::Space, Action::NextSolution),
    ];
    for (k, a) in keys {
        if pressed(k) {
            out.push(a);
        }
    }
    if let Some(step) = lesson_step {
        if pressed(Key::PageDown) {
            out.push(Action::LessonStep(step + 1));
        }
        if pressed(Key::PageUp) {
            out.push(Action::LessonStep(step.saturating_sub(1)));
        }
    }
    if pressed(Key::H) || pressed(Key::F1) {
        out.push(Action::ToggleHelp);
    }
    state_keys(ctx, state, construction, out);
}

/// The single keys that change the state at once (G, D, T; C, N, B; L) or reset it (R).
fn state_keys(
    ctx: &egui::Context,
    state: &mut AppState,
    construction: &mut ConstructionPanel,
    out: &mut Actions,
) {
    let pressed = |k: Key| ctx.input(|i| i.key_pressed(k));
    let d = &mut state.display;
    for (k, flag) in [
        (Key::G, &mut d.grid),
        (Key::D, &mut d.frames),
        (Key::T, &mut d.trail),
    ] {
        if pressed(k) {
            *flag ^= true;
        }
    }
    let c = construction;
    if pressed(Key::C) {
        c.shown ^= true;
    }
    if pressed(Key::N) {
        c.step += 1;
    }
    if pressed(Key::B) {
        c.step = c.step.saturating_sub(1);
    }
    if pressed(Key::L) {
        out.push(Action::SetLock(!state.lock()));
    }
    if pressed(Key::R) {
        let name = if state.robot().config("ready").is_some() {
            "ready"
        } else {
            "zero"
        };
        out.push(Action::ResetTo(name.into()));
    }
}

/// The Ctrl (Cmd) shortcuts: open, save, undo, redo, quit; they work while a text field has
/// the keyboard.
fn command_shortcuts(ctx: &egui::Context, out: &mut Actions) {
    let command = |k: Key, shift: bool| {
        let mut m = egui::Modifiers::COMMAND;
        m.shift = shift;
        ctx.input_mut(|i| i.consume_shortcut(&egui::KeyboardShortcut::new(m, k)))
    };
    if command(Key::O, false) {
        out.push(Action::OpenDialog);
    }
    if command(Key::S, false) {
        out.push(Action::SaveDialog);
    }
    if command(Key::Z, true) {
        out.push(Action::Redo);
    }
    if command(Key::Z, false) {
        out.push(Action::Undo);
    }
    if command(Key::Q, false) {
        ctx.send_viewport_cmd(egui::ViewportCommand::Close);
    }
}

/// The shortcut help window, while `open` (its close button clears it).
pub fn help_window(ctx: &egui::Context, open: &mut bool) {
    if *open {
        egui::Window::new("Keyboard shortcuts")
            .open(open)
            .collapsible(false)
            .show(ctx, help);
    }
}

/// The shortcut help window's contents.
fn help(ui: &mut egui::Ui) {
    egui::Grid::new("help").striped(true).show(ui, |ui| {
        for (k, what) in [
            ("1 / 2 / 3 / 4", "top / front / side / iso view"),
            (
                "F, double-click",
                "fit the robot (and its ghosts) in the view",
            ),
            ("O", "perspective / orthographic"),
            ("drag, right-drag, scroll", "orbit, pan, zoom"),
            (
                "gizmo arrows / squares / rings",
                "move and turn the IK target",
            ),
            ("Space", "next IK solution (posture)"),
            ("L", "lock the posture while dragging"),
            ("C", "show the construction behind the solution"),
            ("N / B", "next / previous construction step"),
            ("PgDn / PgUp", "next / previous lesson step"),
            ("R", "reset to the ready configuration"),
            ("D / G / T", "DH frames / grid / trail"),
            ("W", "workspace overlay"),
            ("V", "hide / show both side panels"),
            ("P", "projector mode (large fonts, the 3D view large)"),
            (
                "F5, Esc",
                "present this figure: the tab fills the window; F5 or Esc leaves",
            ),
            ("H, F1", "this help"),
            ("Ctrl+Z / Ctrl+Shift+Z", "undo / redo a model edit"),
            (
                "Ctrl+O / Ctrl+S",
                "open a model / save the model as (file dialog)",
            ),
            ("Ctrl+Q", "quit (the settings are remembered)"),
        ] {
            ui.strong(k);
            ui.label(what);
            ui.end_row();
        }
    });
}
