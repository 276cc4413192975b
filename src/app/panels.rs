//! The side panels: model and joints (left), readouts and inverse kinematics (right).

use super::state::{AppState, DhField, Level, format_number, without_negative_zero};
use super::ui::AppUi;
use crate::kinematics::models::BUILT_INS;
use crate::kinematics::pose::Pose;
use egui::{Color32, RichText};

const ERROR_BG: Color32 = Color32::from_rgb(255, 215, 215);

/// Left panel: model, joint sliders, configurations, the DH table.
pub fn left(app: &mut AppUi, ui: &mut egui::Ui) {
    egui::ScrollArea::vertical().show(ui, |ui| {
        model_picker(app, ui);
        ui.label(RichText::new(&app.state.robot().description).small());
        ui.separator();
        ui.heading("Joints");
        joint_sliders(app, ui);
        ui.horizontal_wrapped(|ui| {
            ui.label("Configuration:");
            let names: Vec<String> = app
                .state
                .robot()
                .configurations
                .iter()
                .map(|c| c.name.clone())
                .collect();
            for n in names {
                if ui.button(&n).clicked()
                    && let Err(e) = app.state.reset_to(&n)
                {
                    app.state.push_message(Level::Error, e.to_string());
                }
            }
        });
        ui.separator();
        let plain_dh = app
            .state
            .robot()
            .joints()
            .iter()
            .all(|j| matches!(j.geometry, crate::kinematics::JointGeometry::Dh { .. }));
        if plain_dh {
            egui::CollapsingHeader::new("DH table (editable)")
                .default_open(!app.projector)
                .show(ui, |ui| dh_table(&mut app.state, ui));
        } else {
            egui::CollapsingHeader::new("DH table (derived from the URDF's axes)")
                .default_open(!app.projector)
                .show(ui, |ui| derived_dh_table(app.state.robot(), ui));
        }
        save_row(app, ui);
    });
}

/// "Save as": the current robot (with its edited DH table) as URDF or as a TOML model file.
fn save_row(app: &mut AppUi, ui: &mut egui::Ui) {
    ui.horizontal(|ui| {
        ui.add(
            egui::TextEdit::singleline(&mut app.save_path)
                .hint_text("save as robot.urdf or robot.toml")
                .desired_width(ui.available_width() - 60.0),
        );
        if ui
            .button("Save")
            .on_hover_text(
                "Write the model as URDF (a name ending in .urdf) or as a TOML model file; the \
                 edited DH table is what is written",
            )
            .clicked()
        {
            if app.file_picker.downloads() {
                // The browser: the typed name becomes the download's.
                app.save_with_dialog();
            } else {
                let path = app.save_path.clone();
                match app.state.save_model(&path) {
                    Ok(m) => app.state.push_message(Level::Info, m),
                    Err(e) => app.state.push_message(Level::Error, e),
                }
            }
        }
    });
}

/// The DH table derived from a URDF chain's joint axes (read-only; millimetres and the angle
/// unit), its base and tool, or why there is none.
fn derived_dh_table(robot: &crate::kinematics::Robot, ui: &mut egui::Ui) {
    use crate::kinematics::Convention;
    use crate::kinematics::dh_derive::derive_dh;
    let d = match derive_dh(robot, 0, Convention::Standard) {
        Ok(d) => d,
        Err(e) => {
            ui.label(RichText::new(format!("{e}.")).small());
            return;
        }
    };
    egui::Grid::new("derived_dh")
        .striped(true)
        .spacing([8.0, 2.0])
        .show(ui, |ui| {
            for h in ["", "a [mm]", "alpha [°]", "d [mm]", "theta [°]", "offset"] {
                ui.label(RichText::new(h).small());
            }
            ui.end_row();
            for j in &d.joints {
                ui.label(j.name.clone().unwrap_or_default());
                ui.label(format!("{:.1}", 1e3 * j.row.a));
                ui.label(format!("{:.1}", j.row.alpha.to_degrees()));
                ui.label(format!("{:.1}", 1e3 * j.row.d));
                ui.label(format!("{:.1}", j.row.theta.to_degrees()));
                ui.label(match j.kind {
                    crate::kinematics::JointKind::Prismatic => {
                        format!("{:.1} mm", 1e3 * j.offset)
                    }
                    _ => format!("{:.1}°", j.offset.to_degrees()),
                });
                ui.end_row();
            }
        });
    let t = d.world_from_base.translation.vector;
    let tool = d.flange_from_tool.translation.vector;
    ui.label(
        RichText::new(format!(
            "Standard convention, forward kinematics equal to the URDF's; theta (revolute) or d \
             (prismatic) is q plus the offset. Base origin ({:.1}, {:.1}, {:.1}) mm, tool ({:.1}, \
             {:.1}, {:.1}) mm from frame {} ({}).",
            1e3 * t.x,
            1e3 * t.y,
            1e3 * t.z,
            1e3 * tool.x,
            1e3 * tool.y,
            1e3 * tool.z,
            d.joints.len(),
            match crate::kinematics::ik::ClosedForm::detect(robot) {
                Ok(cf) => format!("closed form: {}", cf.name()),
                Err(_) => "no closed form".into(),
            }
        ))
        .small(),
    );
}

fn dh_table(state: &mut AppState, ui: &mut egui::Ui) {
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
            let rows = state.dh_cells().len();
            for j in 0..rows {
                ui.label(state.robot().joints()[j].name.clone());
                for (f, width) in DhField::ALL.into_iter().zip(widths) {
                    dh_cell(state, ui, j, f, width);
                }
                ui.end_row();
            }
        });
    if state.dh_has_errors() {
        ui.colored_label(
            Color32::from_rgb(170, 0, 0),
            "Red cells are not applied (hover for the reason).",
        );
    }
}

/// The model chooser (built-ins) and the path entry.
fn model_picker(app: &mut AppUi, ui: &mut egui::Ui) {
    let heading = ui.heading("Model");
    let current = app.state.spec().to_string();
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
                    app.load(b.name);
                }
            }
        });
    combo.response.labelled_by(heading.id);
    ui.horizontal(|ui| {
        ui.add(
            egui::TextEdit::singleline(&mut app.load_path)
                .hint_text("path/to/robot.toml or .urdf")
                .desired_width(ui.available_width() - 60.0),
        );
        if ui
            .button("Open")
            .on_hover_text("Load a .toml or .urdf model file (or drop one on the window)")
            .clicked()
        {
            let p = app.load_path.clone();
            app.load(&p);
        }
    });
    ui.horizontal(|ui| {
        let native = app.file_picker.available();
        let tip = |t: &'static str| {
            if native {
                t
            } else {
                "No file dialog here: type a path"
            }
        };
        if ui
            .button("Open file...")
            .on_hover_text(tip("Choose a .toml or .urdf model in a file dialog"))
            .clicked()
        {
            app.open_with_dialog();
        }
        if ui
            .button("Save model as...")
            .on_hover_text(tip(
                "Write the current (edited) model as a TOML model file, or URDF for a .urdf name",
            ))
            .clicked()
        {
            app.save_with_dialog();
        }
    });
}

/// One slider per joint, in the display unit.
fn joint_sliders(app: &mut AppUi, ui: &mut egui::Ui) {
    let unit = app.state.angle_unit();
    // Long sliders for fine control (a fixed length: one that followed the panel's width
    // would widen the panel it fills, frame after frame).
    ui.spacing_mut().slider_width = if app.projector { 260.0 } else { 200.0 };
    for k in 0..app.state.robot().dof() {
        let name = app.state.robot().dof_joint(k).name.clone();
        let (Ok(v), Ok([lo, hi]), Ok(quantity)) = (
            app.state.joint_display(k),
            app.state.joint_display_limits(k),
            app.state.joint_quantity(k),
        ) else {
            continue;
        };
        let mut value = v;
        let slider = egui::Slider::new(&mut value, lo..=hi)
            .text(format!("{name} [{}]", quantity.symbol(unit)))
            .max_decimals(2)
            .custom_formatter(|v, _| format_number(v, 2));
        if ui.add(slider).changed() {
            let si = quantity.from_display(value, unit);
            if let Err(e) = app.state.set_joint(k, si) {
                app.state.push_message(Level::Warning, e.to_string());
            }
        }
    }
}

/// One editable cell of the DH table: red with the reason on hover when not applied.
fn dh_cell(state: &mut AppState, ui: &mut egui::Ui, j: usize, f: DhField, width: f32) {
    let Some(cell) = state.dh_cell(j, f).cloned() else {
        return;
    };
    if !cell.editable {
        ui.label(RichText::new(cell.text).small().weak());
        return;
    }
    let mut text = cell.text.clone();
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
            "not applied: {e}; the arm keeps its last valid shape"
        )),
        None => r,
    };
    if r.changed() {
        let _ = state.edit_dh(j, f, &text);
    }
}

fn matrix_grid(ui: &mut egui::Ui, id: &str, m: &nalgebra::Matrix4<f64>) {
    egui::Grid::new(id).spacing([10.0, 1.0]).show(ui, |ui| {
        for r in 0..4 {
            for c in 0..4 {
                let v = m[(r, c)];
                ui.monospace(format!("{:>8.4}", if v.abs() < 5e-5 { 0.0 } else { v }));
            }
            ui.end_row();
        }
    });
}

/// Right panel: pose readouts, Jacobian and singularity, the IK target and its solutions.
pub fn right(app: &mut AppUi, ui: &mut egui::Ui) {
    egui::ScrollArea::vertical().show(ui, |ui| {
        let n_ee = app.state.robot().end_effectors().len();
        if n_ee > 1 {
            ui.horizontal(|ui| {
                ui.label("End-effector:");
                for e in 0..n_ee {
                    let name = app.state.robot().end_effectors()[e].name.clone();
                    ui.selectable_value(&mut app.ee, e, name);
                }
            });
        }
        let ee = app.ee.min(n_ee.saturating_sub(1));
        pose_readouts(app, ui, ee);
        ui.separator();
        ui.heading("Inverse kinematics");
        let analyzer = app.state.analyzer();
        match (analyzer.family(), analyzer.why_no_closed_form()) {
            (Some(f), _) => ui.label(RichText::new(format!("closed form: {f}")).small()),
            (None, why) => ui.label(
                RichText::new(format!(
                    "numerical (Levenberg-Marquardt); no closed form: {}",
                    why.unwrap_or("-")
                ))
                .small(),
            ),
        };
        let mut lock = app.state.lock();
        if ui
            .checkbox(&mut lock, "Lock posture while dragging (L)")
            .changed()
        {
            app.state.set_lock(lock);
        }
        if ui
            .button("Target = tool pose")
            .on_hover_text("Put the target on the current tool pose")
            .clicked()
            && let Ok(t) = app.state.robot().fk_ee(app.state.q(), ee)
        {
            let _ = app.state.set_target(ee, t);
        }
        target_editor(app, ui, ee);
        let Ok(target) = app.state.target(ee).cloned() else {
            return;
        };
        if let Some(msg) = target.reach.message() {
            ui.colored_label(Color32::from_rgb(200, 0, 0), msg);
        }
        if let Some(result) = &target.result {
            solution_list(app, ui, ee, &target, result);
        }
        ui.separator();
        super::construction_panel::panel(app, ui);
        ui.separator();
        super::redundancy_panel::panel(app, ui, ee);
    });
}

fn target_editor(app: &mut AppUi, ui: &mut egui::Ui, ee: usize) {
    let Ok(target) = app.state.target(ee) else {
        return;
    };
    let t = target.world_from_tool;
    let mut p = t.translation.vector * 1e3;
    let rpy = crate::kinematics::orientation::rpy_from_rotation(&t.rotation).angles;
    let mut a = rpy.map(f64::to_degrees);
    let mut changed = false;
    ui.horizontal(|ui| {
        ui.label("target [mm]");
        for (k, axis) in ["x", "y", "z"].into_iter().enumerate() {
            let r = ui.add(
                egui::DragValue::new(&mut p[k])
                    .speed(1.0)
                    .max_decimals(1)
                    .custom_formatter(|v, _| format_number(v, 1)),
            );
            changed |= named(&r, format!("target {axis} [mm]"), p[k]).changed();
        }
    });
    ui.horizontal(|ui| {
        ui.label("RPY [deg]");
        for (k, angle) in ["roll", "pitch", "yaw"].into_iter().enumerate() {
            let r = ui.add(
                egui::DragValue::new(&mut a[k])
                    .speed(0.5)
                    .max_decimals(1)
                    .custom_formatter(|v, _| format_number(v, 1)),
            );
            changed |= named(&r, format!("target {angle} [deg]"), a[k]).changed();
        }
    });
    if changed {
        let r = crate::kinematics::orientation::rotation_from_rpy(&a.map(f64::to_radians));
        let pose = Pose::from_parts(nalgebra::Translation3::from(p / 1e3), r);
        if let Err(e) = app.state.set_target(ee, pose) {
            app.state.push_message(Level::Warning, e.to_string());
        }
    }
}

/// Gives a number field an accessible name (screen readers, UI tests).
fn named(r: &egui::Response, name: String, value: f64) -> &egui::Response {
    r.widget_info(|| {
        let mut info = egui::WidgetInfo::labeled(egui::Role::SpinButton, r.enabled(), &name);
        info.value = Some(value);
        info
    });
    r
}

/// The pose readouts (T, p, phi) and the Jacobian's rank, manipulability and singularity.
fn pose_readouts(app: &mut AppUi, ui: &mut egui::Ui, ee: usize) {
    ui.heading("Pose");
    if let Ok(r) = app.state.readouts(ee) {
        ui.label("T (world from tool):");
        matrix_grid(ui, "T", &r.t);
        let mm = |v: f64| without_negative_zero(v * 1e3, 1);
        ui.monospace(format!(
            "p = [{:.1}, {:.1}, {:.1}] mm",
            mm(r.p.x),
            mm(r.p.y),
            mm(r.p.z)
        ));
        let kind = r.phi_kind.as_str().to_uppercase();
        let sing = if r.phi_singular {
            "  (representation singular)"
        } else {
            ""
        };
        let deg = |v: f64| without_negative_zero(v.to_degrees(), 2);
        ui.monospace(format!(
            "phi {kind} = [{:.2}, {:.2}, {:.2}] deg{sing}",
            deg(r.phi.x),
            deg(r.phi.y),
            deg(r.phi.z)
        ));
        ui.horizontal(|ui| {
            ui.radio_value(
                &mut app.state.orientation,
                crate::kinematics::EulerKind::Zyz,
                "ZYZ",
            );
            ui.radio_value(
                &mut app.state.orientation,
                crate::kinematics::EulerKind::Rpy,
                "RPY",
            );
        });
        ui.separator();
        ui.heading("Jacobian");
        ui.monospace(format!("rank {} of {}", r.rank, r.task_rank));
        ui.monospace(format!("manipulability {:.5}", r.manipulability));
        ui.monospace(format!("smallest singular value {:.2e}", r.min_sv));
        if let Some(s) = &r.singularity {
            ui.colored_label(
                Color32::from_rgb(200, 60, 0),
                RichText::new(format!("(!) {}", s.message())).strong(),
            );
        }
    }
}

/// The closed-form solutions, each with its posture colour and short label, and the legend.
fn solution_list(
    app: &mut AppUi,
    ui: &mut egui::Ui,
    ee: usize,
    target: &super::state::EeTarget,
    result: &crate::kinematics::ik::IkResult,
) {
    ui.label(format!("{} solution(s):", result.solutions.len()));
    for (i, s) in result.solutions.iter().enumerate() {
        let selected = target.selected == Some(i);
        let short = crate::kinematics::ik::closed_form::short_label(&s.posture);
        let mut text = RichText::new(format!("{}. {} ({short})", i + 1, s.posture));
        if !s.within_limits {
            text = text.color(Color32::GRAY).italics();
        }
        // The posture's colour, as on its ghost and in the workspace figures.
        let swatch = match app.state.posture_class(&s.posture) {
            Some(c) if s.within_limits => {
                let [r, g, b, _] = super::viewport::posture_rgba(c).map(|v| (v * 255.0) as u8);
                Color32::from_rgb(r, g, b)
            }
            _ => Color32::GRAY,
        };
        let r = ui
            .horizontal(|ui| {
                let (rect, _) =
                    ui.allocate_exact_size(egui::vec2(12.0, 12.0), egui::Sense::hover());
                ui.painter().rect_filled(rect, 2.0, swatch);
                ui.selectable_label(selected, text)
            })
            .inner;
        let r = r.on_hover_text(format!(
            "q = {:?} ({})",
            s.q.iter()
                .map(|v| (v.to_degrees() * 10.0).round() / 10.0)
                .collect::<Vec<_>>(),
            if s.within_limits {
                "within limits"
            } else {
                "outside the joint limits"
            }
        ));
        if r.clicked()
            && let Err(e) = app.state.select_solution(ee, i)
        {
            app.state.push_message(Level::Warning, e.to_string());
        }
    }
    if !result.solutions.is_empty()
        && app
            .state
            .posture_class(&result.solutions[0].posture)
            .is_some()
    {
        ui.label(
            RichText::new(crate::kinematics::ik::closed_form::SHORT_LEGEND)
                .small()
                .weak(),
        );
    }
}
