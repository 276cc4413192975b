//! The right panel: the end-effector (a combo box, grouped, for robots with many), the cell's
//! obstacles (while there is a cell), the pose readouts and the Jacobian, the IK target and
//! every solution (counted from 1) with what it hits, then the construction and redundancy
//! sections.

use super::super::action::{Action, Actions};
use super::super::state::{AppState, EeTarget, format_number, without_negative_zero};
use super::construction::ConstructionPanel;
use crate::kinematics::pose::Pose;
use egui::{Color32, RichText};

/// Pitch (rad) within which roll and yaw of RPY angles, or theta near 0 or pi for ZYZ, are
/// reported as near the representation's singularity (gimbal lock): 1 deg.
const GIMBAL_WARNING: f64 = 0.017_453_292_519_943_295;

/// The right panel's own state.
#[derive(Default)]
pub struct IkPanel {
    /// The end-effector the readouts and the target refer to.
    pub ee: usize,
    /// The construction overlay.
    pub construction: ConstructionPanel,
    /// The kinematics in symbols, with the partial product's frame highlighted.
    pub symbols: super::symbols::SymbolsPanel,
    /// The cell's obstacles (shown while there is a cell).
    pub cell: super::cell::CellPanel,
    /// The reachability overlay and base placement (shown while the overlay is on).
    pub reach: super::reachability::ReachabilityPanel,
}

impl IkPanel {
    /// Adds what the panel shows over the 3D view (the construction, the symbols of `ee`) to
    /// the scene.
    pub fn decorate(&mut self, state: &AppState, ee: usize, scene: &mut crate::scene::Scene) {
        self.construction.decorate(state, scene);
        self.symbols.decorate(state, ee, scene);
        self.reach.decorate(state, ee, scene);
    }

    /// The whole panel.
    pub fn ui(&mut self, state: &mut AppState, ui: &mut egui::Ui, out: &mut Actions) {
        egui::ScrollArea::vertical()
            .id_salt("right panel scroll")
            .show(ui, |ui| {
                let n_ee = state.robot().end_effectors().len();
                self.ee = self.ee.min(n_ee.saturating_sub(1));
                if n_ee > 1 {
                    ee_picker(state, ui, self.ee, out);
                }
                let ee = self.ee;
                // The cell first: an obstacle just added or clicked is edited here at once.
                if state.cell_scene().is_some() {
                    self.cell.ui(state, ui, out);
                    ui.separator();
                }
                if super::reachability::shown(state) {
                    self.reach.ui(state, ee, ui, out);
                    ui.separator();
                }
                if state.hidden.pose {
                    ui.label("Pose: hidden while the exercise is answered");
                } else {
                    pose_readouts(state, ui, ee);
                }
                ui.separator();
                if state.hidden.solutions {
                    ui.label("Inverse kinematics: hidden while the exercise is answered");
                } else {
                    ik_section(state, ui, ee, out);
                }
                ui.separator();
                self.construction.ui(state, ui);
                ui.separator();
                self.symbols.ui(state, ui, ee);
                ui.separator();
                super::redundancy::panel(state, ui, ee, out);
            });
    }
}

/// The end-effector chooser: a combo box (a robot may have dozens of frames), grouped by arm
/// (its tool first, then its other frames and fingers), then the other frames.
fn ee_picker(state: &AppState, ui: &mut egui::Ui, current: usize, out: &mut Actions) {
    let ees = state.robot().end_effectors();
    let cat = state.ee_catalog();
    let mut groups: Vec<(String, Vec<usize>)> = cat
        .arms
        .iter()
        .enumerate()
        .map(|(i, a)| {
            let mut all = vec![a.tool];
            all.extend(&a.frames);
            (format!("Arm {} ({} joints)", i + 1, a.dof), all)
        })
        .collect();
    if !cat.other.is_empty() {
        groups.push(("Other frames".into(), cat.other.clone()));
    }
    ui.horizontal(|ui| {
        let label = ui.label("End-effector:");
        egui::ComboBox::from_id_salt("end-effector")
            .selected_text(ees[current].name.clone())
            .width((ui.available_width() - 8.0).max(60.0))
            .show_ui(ui, |ui| {
                for (title, members) in &groups {
                    ui.label(RichText::new(title).strong());
                    for &k in members {
                        let text = format!("  {}", ees[k].name);
                        if ui.selectable_label(k == current, text).clicked() {
                            out.push(Action::SelectEe(k));
                        }
                    }
                }
            })
            .response
            .labelled_by(label.id);
    });
}

/// The inverse kinematics: the solver, the lock, the target and its solutions.
fn ik_section(state: &AppState, ui: &mut egui::Ui, ee: usize, out: &mut Actions) {
    ui.heading("Inverse kinematics");
    let analyzer = state.analyzer();
    let several = state.robot().end_effectors().len() > 1;
    if several && let Some(r) = state.arm_report(ee) {
        // A tree: the arm of this end-effector, alone.
        let text = match (r.closed_form, &r.closed_form_reason) {
            (Some(f), _) => format!(
                "arm of {} ({} joints): closed form {f}",
                r.name, r.variables
            ),
            (None, why) => format!(
                "arm of {} ({} joints): numerical (Levenberg-Marquardt); no closed form: {}",
                r.name,
                r.variables,
                why.as_deref().unwrap_or("-")
            ),
        };
        ui.label(RichText::new(text).small());
    } else {
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
    }
    let mut lock = state.lock();
    if ui
        .checkbox(&mut lock, "Lock posture while dragging (L)")
        .changed()
    {
        out.push(Action::SetLock(lock));
    }
    if ui
        .button("Target = tool pose")
        .on_hover_text("Put the target on the current tool pose")
        .clicked()
    {
        out.push(Action::TargetToTool(ee));
    }
    target_editor(state, ui, ee, out);
    let Ok(target) = state.target(ee) else {
        return;
    };
    // Unreached, or reached in collision: one reserved space, so nothing below moves when
    // either comes or goes during a drag.
    let reach = target
        .reach
        .message()
        .or_else(|| state.collision_warning(ee));
    let reach = reach.map(|m| RichText::new(m).color(Color32::from_rgb(200, 0, 0)));
    super::reserved_warning(ui, "reach", reach);
    if let Some(result) = &target.result {
        solution_list(state, ui, ee, target, result, out);
    }
}

/// What a solution hits ("link3 hits table, 12 mm", red) or its clearance ("free, 45 mm
/// clear"), under its line in the list.
fn collision_line(ui: &mut egui::Ui, report: &crate::collision::CollisionReport) {
    let color = if report.in_collision {
        Color32::from_rgb(200, 0, 0)
    } else {
        Color32::from_rgb(40, 120, 60)
    };
    // One line, cut to the panel (the whole on hover): the list keeps its height while the
    // pairs change during a drag.
    let text = report.summary();
    let hover = match (&report.closest, report.in_collision) {
        (Some(c), false) => format!("{text}: the nearest pair is {} and {}", c.a, c.b),
        _ => text.clone(),
    };
    ui.horizontal(|ui| {
        ui.add_space(18.0);
        ui.add(egui::Label::new(RichText::new(&text).small().color(color)).truncate())
            .on_hover_text(hover);
    });
}

fn matrix_grid(ui: &mut egui::Ui, id: &str, m: &nalgebra::Matrix4<f64>) {
    egui::Grid::new(id).spacing([10.0, 1.0]).show(ui, |ui| {
        for r in 0..4 {
            for c in 0..4 {
                let v = without_negative_zero(m[(r, c)], 4);
                ui.monospace(format!("{v:>8.4}"));
            }
            ui.end_row();
        }
    });
}

/// The target's position (mm) and RPY angles (deg): a field applies when Enter is pressed or
/// it loses focus (or while it is dragged).
fn target_editor(state: &AppState, ui: &mut egui::Ui, ee: usize, out: &mut Actions) {
    let Ok(target) = state.target(ee) else {
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
    if (a[1].to_radians().abs() - std::f64::consts::FRAC_PI_2).abs() < GIMBAL_WARNING {
        ui.label(
            RichText::new(
                "pitch near ±90°: roll and yaw turn about the same axis (gimbal lock), so only \
                 their sum or difference is defined",
            )
            .small()
            .color(Color32::from_rgb(180, 90, 0)),
        );
    }
    if changed {
        let r = crate::kinematics::orientation::rotation_from_rpy(&a.map(f64::to_radians));
        let pose = Pose::from_parts(nalgebra::Translation3::from(p / 1e3), r);
        out.push(Action::SetTarget(ee, pose));
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

/// The pose readouts (T, p, phi) and the Jacobian's rank, manipulability and singularity. The
/// numbers have fixed widths, so that a line keeps its length (and its wrapping) as they change
/// during a drag: "phi" wrapped at one pose and not at the next, and moved what was below.
fn pose_readouts(state: &mut AppState, ui: &mut egui::Ui, ee: usize) {
    ui.heading("Pose");
    let Ok(r) = state.readouts(ee) else { return };
    ui.label("T (world from tool):");
    egui::ScrollArea::horizontal()
        .id_salt("T scroll")
        .show(ui, |ui| {
            ui.style_mut().wrap_mode = Some(egui::TextWrapMode::Extend);
            matrix_grid(ui, "T", &r.t)
        });
    let mm = |v: f64| without_negative_zero(v * 1e3, 1);
    ui.monospace(format!(
        "p = [{:7.1}, {:7.1}, {:7.1}] mm",
        mm(r.p.x),
        mm(r.p.y),
        mm(r.p.z)
    ));
    let kind = r.phi_kind.as_str().to_uppercase();
    let deg = |v: f64| without_negative_zero(v.to_degrees(), 1);
    ui.monospace(format!(
        "phi {kind} = [{:6.1},{:6.1},{:6.1}] deg",
        deg(r.phi.x),
        deg(r.phi.y),
        deg(r.phi.z)
    ));
    let gimbal = r.phi_singular.then(|| {
        RichText::new(format!(
            "{kind} is at its representation singularity (gimbal lock): only the sum or \
             difference of the first and last angles is defined"
        ))
        .small()
        .color(Color32::from_rgb(180, 90, 0))
    });
    super::reserved_warning(ui, "gimbal", gimbal);
    ui.horizontal(|ui| {
        ui.radio_value(
            &mut state.orientation,
            crate::kinematics::EulerKind::Zyz,
            "ZYZ",
        );
        ui.radio_value(
            &mut state.orientation,
            crate::kinematics::EulerKind::Rpy,
            "RPY",
        );
    });
    ui.separator();
    ui.heading("Jacobian");
    ui.monospace(format!("rank {} of {}", r.rank, r.task_rank));
    ui.monospace(format!("manipulability {:.5}", r.manipulability));
    ui.monospace(format!("smallest singular value {:.2e}", r.min_sv));
    let singular = r.singularity.as_ref().map(|s| {
        RichText::new(format!("(!) {}", s.message()))
            .strong()
            .color(Color32::from_rgb(200, 60, 0))
    });
    super::reserved_warning(ui, "singularity", singular);
}

/// The closed-form solutions, counted from 1, each with its posture colour and short label,
/// and the legend.
fn solution_list(
    state: &AppState,
    ui: &mut egui::Ui,
    ee: usize,
    target: &EeTarget,
    result: &crate::kinematics::ik::IkResult,
    out: &mut Actions,
) {
    ui.label(format!("{} solution(s):", result.solutions.len()));
    let collisions = state.solution_collisions(ee);
    for (i, s) in result.solutions.iter().enumerate() {
        let selected = target.selected == Some(i);
        let (long, short) = (s.posture.to_string(), s.posture.short());
        // A label with no short form ("branch 3" of a general arm) is not repeated.
        let label = if short == long {
            format!("{}. {long}", i + 1)
        } else {
            format!("{}. {long} ({short})", i + 1)
        };
        let mut text = RichText::new(label);
        if !s.within_limits {
            text = text.color(Color32::GRAY).italics();
        }
        // The posture's colour, as on its ghost and in the workspace figures.
        let swatch = match state.posture_class(&s.posture) {
            Some(c) if s.within_limits => {
                let [r, g, b, _] =
                    super::super::viewport::posture_rgba(c).map(|v| (v * 255.0) as u8);
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
            "q = [{}] deg ({})",
            s.q.iter()
                .map(|v| format_number(v.to_degrees(), 1))
                .collect::<Vec<_>>()
                .join(", "),
            if s.within_limits {
                "within limits"
            } else {
                "outside the joint limits"
            }
        ));
        if r.clicked() {
            out.push(Action::SelectSolution(ee, i));
        }
        if let Some(c) = collisions.get(i) {
            collision_line(ui, c);
        }
    }
    if !result.solutions.is_empty() && state.posture_class(&result.solutions[0].posture).is_some() {
        use crate::kinematics::ik::closed_form::{SHORT_LEGEND, SHORT_LEGEND_UR};
        let ur = result.solutions[0].posture.has_up_down_wrist();
        let legend = if ur { SHORT_LEGEND_UR } else { SHORT_LEGEND };
        ui.label(RichText::new(legend).small().weak());
    }
}
