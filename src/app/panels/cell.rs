//! The right panel's Cell section: collisions on or off, the obstacles (click one to select
//! it: the 3D view's gizmo then moves it), the selected one's size, position (mm) and roll,
//! pitch, yaw (deg) as drag values, Delete, and the scene file's name with Open and Save.

use super::super::action::{Action, Actions};
use super::super::cell::{self, CellAction, DEFAULT_SCENE_FILE};
use super::super::state::{AppState, format_number};
use crate::collision::{CellScene, ObstacleFrame};
use egui::{Color32, RichText};

/// The Cell section's own state: the scene file's name typed.
pub struct CellPanel {
    /// The scene file Open reads and Save writes (where no file dialog answers).
    pub path: String,
}

impl Default for CellPanel {
    fn default() -> Self {
        Self {
            path: DEFAULT_SCENE_FILE.to_string(),
        }
    }
}

impl CellPanel {
    /// The section (shown while there is a cell).
    pub fn ui(&mut self, state: &AppState, ui: &mut egui::Ui, out: &mut Actions) {
        let Some(scene) = state.cell_scene() else {
            return;
        };
        ui.heading("Cell");
        let mut on = state.collisions_on();
        if ui
            .checkbox(&mut on, "Check collisions")
            .on_hover_text("The arm and every posture checked against itself and the obstacles")
            .changed()
        {
            out.push(Action::Cell(CellAction::Check(on)));
        }
        if let Some(p) = state.cell_problem() {
            ui.label(RichText::new(p).small().color(Color32::from_rgb(190, 0, 0)));
        }
        let selected = state.selected_obstacle();
        if scene.obstacles.is_empty() {
            ui.label(RichText::new("no obstacles: the arm against itself").small());
        }
        for (k, o) in scene.obstacles.iter().enumerate() {
            let text = format!("{} ({})", o.name, o.shape_word());
            if ui.selectable_label(selected == Some(k), text).clicked() {
                let pick = if selected == Some(k) { None } else { Some(k) };
                out.push(Action::Cell(CellAction::Select(pick)));
            }
        }
        if let Some(k) = selected {
            obstacle_editor(scene, k, ui, out);
        }
        self.file_row(ui, out);
    }

    /// The scene file's name, Open and Save.
    fn file_row(&mut self, ui: &mut egui::Ui, out: &mut Actions) {
        ui.horizontal(|ui| {
            let label = ui.label("scene file");
            ui.add(
                egui::TextEdit::singleline(&mut self.path)
                    .desired_width((ui.available_width() - 110.0).max(60.0)),
            )
            .labelled_by(label.id);
            let path = self.path.trim().to_string();
            if ui.button("Open").clicked() {
                out.push(Action::Cell(CellAction::Open(Some(path.clone()))));
            }
            if ui.button("Save").clicked() {
                out.push(Action::Cell(CellAction::Save(Some(path))));
            }
        });
    }
}

/// Obstacle `k`'s size, position and angles as drag values, its frame, Delete and Done.
fn obstacle_editor(scene: &CellScene, k: usize, ui: &mut egui::Ui, out: &mut Actions) {
    let o = &scene.obstacles[k];
    let mut changed = o.clone();
    let sizes = cell::sizes(&o.shape);
    if !sizes.is_empty() {
        let mut mm: Vec<f64> = sizes.iter().map(|(_, v)| v * 1e3).collect();
        let mut any = false;
        ui.horizontal_wrapped(|ui| {
            ui.label("size [mm]");
            for ((name, _), v) in sizes.iter().zip(&mut mm) {
                any |= drag(ui, v, 2.0, format!("{} size {name} [mm]", o.name)).changed();
            }
        });
        if any {
            let m: Vec<f64> = mm.iter().map(|v| v / 1e3).collect();
            changed.shape = cell::with_sizes(&o.shape, &m);
        }
    }
    let mut xyz = o.xyz.map(|v| v * 1e3);
    ui.horizontal_wrapped(|ui| {
        ui.label("position [mm]");
        for (axis, v) in ["x", "y", "z"].into_iter().zip(&mut xyz) {
            drag(ui, v, 2.0, format!("{} {axis} [mm]", o.name));
        }
    });
    changed.xyz = xyz.map(|v| v / 1e3);
    let mut rpy = o.rpy.map(f64::to_degrees);
    ui.horizontal_wrapped(|ui| {
        ui.label("RPY [deg]");
        for (angle, v) in ["roll", "pitch", "yaw"].into_iter().zip(&mut rpy) {
            drag(ui, v, 0.5, format!("{} {angle} [deg]", o.name));
        }
    });
    changed.rpy = rpy.map(f64::to_radians);
    if let ObstacleFrame::Link(link) = &o.frame {
        ui.label(RichText::new(format!("moves with the link {link}")).small());
    }
    // A drag value's text round trip (mm, deg) must not count as a change.
    let moved = changed.shape != o.shape
        || changed
            .xyz
            .iter()
            .zip(&o.xyz)
            .any(|(a, b)| (a - b).abs() > 1e-9)
        || changed
            .rpy
            .iter()
            .zip(&o.rpy)
            .any(|(a, b)| (a - b).abs() > 1e-9);
    if moved {
        out.push(Action::Cell(CellAction::Set(k, changed)));
    }
    ui.horizontal(|ui| {
        if ui.button("Delete obstacle").clicked() {
            out.push(Action::Cell(CellAction::Delete(k)));
        }
        if ui
            .button("Done")
            .on_hover_text("Deselect: the gizmo moves the IK target again")
            .clicked()
        {
            out.push(Action::Cell(CellAction::Select(None)));
        }
    });
}

/// A number field named `name` (screen readers, UI tests) dragged at `speed` per point.
fn drag(ui: &mut egui::Ui, v: &mut f64, speed: f64, name: String) -> egui::Response {
    let r = ui.add(
        egui::DragValue::new(v)
            .speed(speed)
            .max_decimals(1)
            .custom_formatter(|v, _| format_number(v, 1)),
    );
    let value = *v;
    r.widget_info(|| {
        let mut info = egui::WidgetInfo::labeled(egui::Role::SpinButton, r.enabled(), &name);
        info.value = Some(value);
        info
    });
    r
}
