//! The left panel: the model (built-in list, a typed path, file dialogs), its joints (sliders,
//! named configurations), the editable DH table and the Save row. A typed cell applies when Enter
//! is pressed or the cell loses focus, never on a partial keystroke; a value that cannot apply
//! keeps the previous one and the cell stays red with the reason; edits can be undone.

use super::super::action::{Action, Actions};
use super::super::files::suggested_model_name;
use super::super::state::{AppState, DhField, format_number};
use crate::kinematics::models::BUILT_INS;
use egui::{Color32, RichText};
use std::collections::HashMap;

const ERROR_BG: Color32 = Color32::from_rgb(255, 215, 215);

/// The left panel's own state.
#[derive(Debug, Default)]
pub struct ModelPanel {
    /// Model path typed in the path field.
    pub load_path: String,
    /// File name in the Save row (.urdf or .toml): it follows the current model.
    pub save_path: String,
    /// The model (its spec) the Save row's name was made for.
    save_for: String,
    /// Cells being typed, by (joint, field): the text is applied on Enter or when the cell
    /// loses focus.
    editing: HashMap<(usize, DhField), String>,
}

impl ModelPanel {
    /// The whole panel; `ee` is the end-effector the right panel drives (a tree's derived DH
    /// table is its arm's).
    pub fn ui(
        &mut self,
        state: &AppState,
        ee: usize,
        ui: &mut egui::Ui,
        projector: bool,
        out: &mut Actions,
    ) {
        if self.save_for != state.spec() {
            // A new model: the Save row never points at another model's file.
            self.save_path = suggested_model_name(&state.robot().name);
            self.save_for = state.spec().to_string();
            self.editing.clear();
        }
        egui::ScrollArea::vertical()
            .id_salt("left panel scroll")
            .show(ui, |ui| {
                self.model_picker(state, ui, out);
                ui.label(RichText::new(&state.robot().description).small());
                ui.separator();
                ui.heading("Joints");
                joint_sliders(state, ui, out);
                configurations(state, ui, out);
                ui.separator();
                let plain_dh = state
                    .robot()
                    .joints()
                    .iter()
                    .all(|j| matches!(j.geometry, crate::kinematics::JointGeometry::Dh { .. }));
                if state.hidden.dh_table {
                    ui.label("DH table: hidden while the exercise is answered");
                } else if plain_dh {
                    egui::CollapsingHeader::new("DH table (editable)")
                        .default_open(!projector)
                        .show(ui, |ui| self.dh_table(state, ui, out));
                } else {
                    egui::CollapsingHeader::new("DH table (derived from the URDF's axes)")
                        .default_open(!projector)
                        .show(ui, |ui| derived_dh_table(state, ee, ui));
                }
                self.save_row(state, ui, out);
            });
    }

    /// The model chooser (built-ins), the path field (Enter opens it) and the file dialogs.
    fn model_picker(&mut self, state: &AppState, ui: &mut egui::Ui, out: &mut Actions) {
        let heading = ui.heading("Model");
        let current = state.spec().to_string();
        let combo = egui::ComboBox::from_id_salt("model")
            .selected_text(current.clone())
            .width(ui.available_width() - 8.0)
            .show_ui(ui, |ui| {
                for b in BUILT_INS {
                    if ui
                        .selectable_label(current == b.name, b.name)
                        .on_hover_text(b.summary)
                        .clicked()
                    {
                        out.push(Action::Load(b.name.to_string()));
                    }
                }
            });
        combo.response.labelled_by(heading.id);
        ui.horizontal(|ui| {
            let open_room = button_room(ui, "Open").max(70.0);
            let r = ui.add(
                egui::TextEdit::singleline(&mut self.load_path)
                    .hint_text("path/to/robot.toml or .urdf")
                    .desired_width((ui.available_width() - open_room).max(40.0)),
            );
            let enter = r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
            if ui
                .button("Open")
                .on_hover_text("Load a .toml or .urdf model file (or drop one on the window)")
                .clicked()
                || enter
            {
                out.push(Action::Load(self.load_path.trim().to_string()));
            }
        });
        let exam = state.hidden.exam;
        ui.horizontal(|ui| {
            if ui
                .button("Open file...")
                .on_hover_text("Choose a .toml or .urdf model file (Ctrl+O)")
                .clicked()
            {
                out.push(Action::OpenDialog);
            }
            if ui
                .add_enabled(!exam, egui::Button::new("Save model as..."))
                .on_disabled_hover_text("Off during an exam")
                .on_hover_text(
                    "Write the current (edited) model as a TOML model file, or URDF for a .urdf \
                     name (Ctrl+S)",
                )
                .clicked()
            {
                out.push(Action::SaveDialog);
            }
        });
        if ui
            .add_enabled(!exam, egui::Button::new("Save as lesson"))
            .on_disabled_hover_text("Off during an exam")
            .on_hover_text(
                "Append the current joints, target, view and overlays as a step of a lesson \
                 file (the open lesson's, else lesson.toml)",
            )
            .clicked()
        {
            out.push(Action::SaveAsLesson);
        }
    }

    /// The Save row: a file name that follows the model, and Save (or Enter).
    fn save_row(&mut self, state: &AppState, ui: &mut egui::Ui, out: &mut Actions) {
        ui.horizontal(|ui| {
            let save_room = button_room(ui, "Save").max(70.0);
            let r = ui.add(
                egui::TextEdit::singleline(&mut self.save_path)
                    .hint_text("save as robot.urdf or robot.toml")
                    .desired_width((ui.available_width() - save_room).max(40.0)),
            );
            let enter = r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
            let can = !state.dh_has_errors() && !state.hidden.exam;
            let save = ui.add_enabled(can, egui::Button::new("Save"));
            let save = save
                .on_hover_text(
                    "Write the model as URDF (a name ending in .urdf) or as a TOML model file; \
                     the edited DH table is what is written",
                )
                .on_disabled_hover_text(if state.hidden.exam {
                    "Off during an exam"
                } else {
                    "Red cells hold values that are not applied: correct them first"
                });
            if save.clicked() || (enter && can) {
                out.push(Action::SaveModel(self.save_path.trim().to_string()));
            }
        });
    }

    /// The editable DH table, scrolled sideways inside the panel, with Undo, Redo and Reset.
    fn dh_table(&mut self, state: &AppState, ui: &mut egui::Ui, out: &mut Actions) {
        let unit = state.angle_unit();
        // Each column as wide as its longest entry (the grid alone would squeeze the cells to
        // egui's minimum and cut "-180" to "-18"): text, the field's margins, room for the caret.
        let font = egui::TextStyle::Body.resolve(ui.style());
        let margin = 2.0 * ui.spacing().button_padding.x + 6.0;
        let widths = DhField::ALL.map(|f| {
            (0..state.dh_cells().len())
                .filter_map(|j| state.dh_cell(j, f))
                .map(|cell| {
                    ui.fonts_mut(|fonts| {
                        fonts
                            .layout_no_wrap(cell.text.clone(), font.clone(), Color32::WHITE)
                            .size()
                            .x
                    })
                })
                .fold(24.0_f32, f32::max)
                + margin
        });
        egui::ScrollArea::horizontal()
            .id_salt("dh table scroll")
            .show(ui, |ui| {
                ui.style_mut().wrap_mode = Some(egui::TextWrapMode::Extend);
                egui::Grid::new("dh")
                    .striped(true)
                    .spacing([4.0, 2.0])
                    .show(ui, |ui| {
                        ui.label("");
                        for f in DhField::ALL {
                            let q = f.quantity(crate::kinematics::JointKind::Revolute);
                            let sym = if matches!(f, DhField::A | DhField::D) {
                                "mm"
                            } else {
                                q.symbol(unit)
                            };
                            ui.label(RichText::new(format!("{} [{sym}]", f.name())).small());
                        }
                        ui.end_row();
                        for j in 0..state.dh_cells().len() {
                            ui.label(state.robot().joints()[j].name.clone());
                            for (f, width) in DhField::ALL.into_iter().zip(widths) {
                                self.dh_cell(state, ui, (j, f), width, out);
                            }
                            ui.end_row();
                        }
                    });
            });
        edit_buttons(state, ui, out);
    }

    /// One editable cell: the committed text, or the text being typed while it has focus;
    /// red with the reason on hover when not applied. Enter or leaving the cell commits.
    fn dh_cell(
        &mut self,
        state: &AppState,
        ui: &mut egui::Ui,
        (j, f): (usize, DhField),
        width: f32,
        out: &mut Actions,
    ) {
        let Some(cell) = state.dh_cell(j, f) else {
            return;
        };
        if !cell.editable {
            ui.label(RichText::new(&cell.text).small().weak());
            return;
        }
        let typing = self.editing.contains_key(&(j, f));
        let mut text = self
            .editing
            .get(&(j, f))
            .cloned()
            .unwrap_or_else(|| cell.text.clone());
        let mut edit = egui::TextEdit::singleline(&mut text)
            .desired_width(width)
            .min_size(egui::vec2(width, 0.0));
        if cell.error.is_some() {
            edit = edit
                .background_color(ERROR_BG)
                .text_color(Color32::from_rgb(150, 0, 0));
        }
        let r = ui.add(edit);
        // Named for screen readers (and UI tests): "q2 alpha".
        let name = format!("{} {}", state.robot().joints()[j].name, f.name());
        r.widget_info(|| {
            let mut info = egui::WidgetInfo::labeled(egui::Role::TextInput, ui.is_enabled(), &name);
            info.current_text_value = Some(text.clone());
            info
        });
        let r = match &cell.error {
            Some(e) => r.on_hover_text(format!(
                "not applied: {e}; the arm keeps its last valid value"
            )),
            None => r,
        };
        if r.has_focus() || r.changed() {
            self.editing.insert((j, f), text.clone());
        }
        let escaped = r.has_focus() && ui.input(|i| i.key_pressed(egui::Key::Escape));
        if escaped {
            self.editing.remove(&(j, f));
        } else if r.lost_focus() && typing {
            self.editing.remove(&(j, f));
            if text != cell.text || cell.error.is_some() {
                out.push(Action::CommitDh {
                    joint: j,
                    field: f,
                    text,
                });
            }
        }
    }
}

/// One slider per joint, in the display unit; the slider fills the panel's width.
fn joint_sliders(state: &AppState, ui: &mut egui::Ui, out: &mut Actions) {
    let unit = state.angle_unit();
    ui.spacing_mut().slider_width = (ui.available_width() - 150.0).clamp(80.0, 420.0);
    for k in 0..state.robot().dof() {
        let name = state.robot().dof_joint(k).name.clone();
        let (Ok(v), Ok([lo, hi]), Ok(quantity)) = (
            state.joint_display(k),
            state.joint_display_limits(k),
            state.joint_quantity(k),
        ) else {
            continue;
        };
        let mut value = v;
        // Two decimals shown by the formatter only: a slider with `max_decimals` rounds the
        // value it is handed every frame and reports a change nobody made, which moved the arm
        // (the self-motion's hand drifted 0.05 mm a sweep, and the target followed it). For
        // the same reason a value outside the range is not clamped until the user moves it.
        let slider = egui::Slider::new(&mut value, lo..=hi)
            .clamping(egui::SliderClamping::Edits)
            .text(format!("{name} [{}]", quantity.symbol(unit)))
            .custom_formatter(|v, _| format_number(v, 2));
        if ui.add(slider).changed() {
            out.push(Action::SetJoint(k, quantity.from_display(value, unit)));
        }
    }
}

/// The named configurations as buttons.
fn configurations(state: &AppState, ui: &mut egui::Ui, out: &mut Actions) {
    ui.horizontal_wrapped(|ui| {
        ui.label("Configuration:");
        for c in &state.robot().configurations {
            if ui.button(&c.name).clicked() {
                out.push(Action::ResetTo(c.name.clone()));
            }
        }
    });
}

/// The DH table derived from a URDF chain's joint axes (read-only; millimetres and degrees),
/// its base and tool, or why there is none: on a tree, the table of end-effector `ee`'s arm
/// (computed when the robot was loaded, [`AppState::arm_report`]).
fn derived_dh_table(state: &AppState, ee: usize, ui: &mut egui::Ui) {
    let Some(report) = state.arm_report(ee).or_else(|| state.arm_report(0)) else {
        return;
    };
    if state.robot().end_effectors().len() > 1 {
        ui.label(
            RichText::new(format!(
                "The arm of \"{}\" ({} joints): {}",
                report.name,
                report.variables,
                report.chain.join(", ")
            ))
            .small(),
        );
    }
    if let Some(why) = &report.dh_reason {
        ui.label(RichText::new(format!("{why}.")).small());
    }
    let Some(d) = &report.dh else {
        return;
    };
    egui::ScrollArea::horizontal()
        .id_salt("derived dh scroll")
        .show(ui, |ui| {
            ui.style_mut().wrap_mode = Some(egui::TextWrapMode::Extend);
            egui::Grid::new("derived_dh")
                .striped(true)
                .spacing([8.0, 2.0])
                .show(ui, |ui| {
                    for h in ["", "a [mm]", "alpha [°]", "d [mm]", "theta [°]", "offset"] {
                        ui.label(RichText::new(h).small());
                    }
                    ui.end_row();
                    let n = |v: f64| format_number(v, 1);
                    for j in &d.joints {
                        ui.label(j.name.clone().unwrap_or_default());
                        ui.label(n(1e3 * j.row.a));
                        ui.label(n(j.row.alpha.to_degrees()));
                        ui.label(n(1e3 * j.row.d));
                        ui.label(n(j.row.theta.to_degrees()));
                        ui.label(match j.kind {
                            crate::kinematics::JointKind::Prismatic => {
                                format!("{} mm", n(1e3 * j.offset))
                            }
                            _ => format!("{}°", n(j.offset.to_degrees())),
                        });
                        ui.end_row();
                    }
                });
        });
    let t = d.world_from_base.translation.vector;
    let tool = d.flange_from_tool.translation.vector;
    let n = |v: f64| format_number(1e3 * v, 1);
    ui.label(
        RichText::new(format!(
            "Standard convention, forward kinematics equal to the URDF's; theta (revolute) or d \
             (prismatic) is q plus the offset. Base origin ({}, {}, {}) mm, tool ({}, {}, {}) mm \
             from frame {} ({}).",
            n(t.x),
            n(t.y),
            n(t.z),
            n(tool.x),
            n(tool.y),
            n(tool.z),
            d.joints.len(),
            match report.closed_form {
                Some(f) => format!("closed form: {f}"),
                None => "no closed form".into(),
            }
        ))
        .small(),
    );
}

/// The red cells' warning, and Undo, Redo and Reset under the DH table.
fn edit_buttons(state: &AppState, ui: &mut egui::Ui, out: &mut Actions) {
    if state.dh_has_errors() {
        ui.colored_label(
            Color32::from_rgb(170, 0, 0),
            "Red cells are not applied (hover for the reason); the arm keeps its last valid \
             values, and Save waits until they are corrected.",
        );
    }
    ui.horizontal_wrapped(|ui| {
        if ui
            .add_enabled(state.can_undo(), egui::Button::new("Undo"))
            .on_hover_text("Undo the last edit (Ctrl+Z)")
            .clicked()
        {
            out.push(Action::Undo);
        }
        if ui
            .add_enabled(state.can_redo(), egui::Button::new("Redo"))
            .on_hover_text("Redo (Ctrl+Shift+Z)")
            .clicked()
        {
            out.push(Action::Redo);
        }
        if ui
            .add_enabled(
                state.is_edited() || state.dh_has_errors(),
                egui::Button::new("Reset"),
            )
            .on_hover_text("Back to the model's values as it was opened")
            .clicked()
        {
            out.push(Action::ResetEdits);
        }
    });
}

/// The width a button labelled `text` takes after a field in a row, spacing included: in
/// projector mode's larger text a fixed 70 points wrapped "Open" as "Ope n".
fn button_room(ui: &mut egui::Ui, text: &str) -> f32 {
    let font = egui::TextStyle::Button.resolve(ui.style());
    let w = ui.fonts_mut(|f| {
        f.layout_no_wrap(text.to_string(), font, Color32::WHITE)
            .size()
            .x
    });
    w + 2.0 * ui.spacing().button_padding.x + ui.spacing().item_spacing.x + 4.0
}
