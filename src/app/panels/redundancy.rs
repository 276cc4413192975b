//! The Redundancy section of the right panel: n, m and r in words, the task the gizmo obeys,
//! and the self-motion slider (the hand held at the pose it had when the self-motion started;
//! the readout is the error against that pose).

use super::super::action::{Action, Actions};
use super::super::state::{AppState, SelfMotionView};
use egui::{Color32, RichText, Sense, Stroke};
use std::f64::consts::PI;

/// Green of the feasible stretches of the track.
const FEASIBLE: Color32 = Color32::from_rgb(40, 150, 80);
/// Red of the stretches where the arm hits itself or an obstacle.
pub const COLLIDING: Color32 = Color32::from_rgb(205, 40, 30);
/// Shade of the infeasible stretches of the track.
const INFEASIBLE: Color32 = Color32::from_rgb(200, 200, 205);

/// The Redundancy section of the right panel.
pub fn panel(state: &mut AppState, ui: &mut egui::Ui, ee: usize, out: &mut Actions) {
    ui.heading("Redundancy");
    let red = state.redundancy_of(ee);
    ui.monospace(format!("n = {}, m = {}, r = {}", red.n, red.m, red.r));
    ui.label(RichText::new(format!("{} (degree {})", red.words(), red.degree())).strong());
    let mut task = state.task();
    egui::ComboBox::from_label("task (tool frame)")
        .selected_text(task.name())
        .show_ui(ui, |ui| {
            for t in state.tasks() {
                ui.selectable_value(&mut task, t, t.name())
                    .on_hover_text(t.description());
            }
        });
    if task != state.task() {
        out.push(Action::SetTask(task));
    }
    ui.label(RichText::new(state.task().description()).small());
    match state.self_motion(ee) {
        Ok(view) => slider_section(state, ui, ee, &view, out),
        Err(why) => {
            ui.label(RichText::new(format!("no self-motion slider: {why}")).small());
        }
    }
}

/// The slider, its readouts and the branch choice.
fn slider_section(
    state: &mut AppState,
    ui: &mut egui::Ui,
    ee: usize,
    view: &SelfMotionView,
    out: &mut Actions,
) {
    ui.label(RichText::new(format!("Self-motion: {}", view.meaning)).small());
    if let Some(v) = track(ui, view) {
        out.push(Action::SetSelfMotion(ee, v));
    }
    colliding_line(ui, view, state.collisions_on());
    let mut deg = view.value.to_degrees();
    ui.horizontal(|ui| {
        ui.label(format!("{} =", view.parameter));
        let r = ui.add(
            egui::DragValue::new(&mut deg)
                .speed(0.2)
                .range(view.range[0].to_degrees()..=view.range[1].to_degrees())
                .suffix(" deg"),
        );
        if r.changed() {
            out.push(Action::SetSelfMotion(ee, deg.to_radians()));
        }
    });
    ui.monospace(format!(
        "hand error {:.1e} m, {:.1e} rad",
        view.position_error, view.orientation_error
    ))
    .on_hover_text("against the pose the hand had when the self-motion started");
    if let Some(k) = view.manifolds {
        ui.label(format!(
            "{k} disjoint self-motion curve(s) inside the limits"
        ));
    }
    if view.singular {
        ui.colored_label(
            Color32::from_rgb(200, 60, 0),
            "(!) algorithmic singularity: the shoulder-wrist line is along axis 1",
        );
    }
    if view.exact {
        let mut pick = None;
        egui::ComboBox::from_label("branch")
            .selected_text(&view.names[view.branch])
            .show_ui(ui, |ui| {
                for (k, name) in view.names.iter().enumerate() {
                    let width: f64 = view.feasible[k].iter().map(|iv| iv[1] - iv[0]).sum();
                    let label = format!("{name} ({:.0} deg feasible)", width.to_degrees());
                    if ui.selectable_label(k == view.branch, label).clicked() {
                        pick = Some(k);
                    }
                }
            });
        if let Some(k) = pick.filter(|&k| k != view.branch) {
            out.push(Action::SelectBranch(ee, k));
        }
    } else {
        ui.label(
            RichText::new("numerical: the feasible stretches are not known in advance").small(),
        );
    }
    ui.checkbox(&mut state.display.self_motion_path, "Trace the path");
}

/// Under the slider, where the current branch collides (red on the track), in words: "red:
/// 40..55 deg link3 hits table"; a line kept (empty) while collisions are `checked`, so nothing
/// below moves as stretches come and go.
fn colliding_line(ui: &mut egui::Ui, view: &SelfMotionView, checked: bool) {
    let here: Vec<String> = view
        .colliding
        .iter()
        .filter(|s| s.branch == view.branch)
        .map(|s| {
            format!(
                "{:.0}..{:.0} deg {} hits {}",
                s.from.to_degrees(),
                s.to.to_degrees(),
                s.a,
                s.b
            )
        })
        .collect();
    let text = (!here.is_empty()).then(|| {
        RichText::new(format!("red: {}", here.join("; ")))
            .small()
            .color(COLLIDING)
    });
    if view.exact && checked {
        super::reserved_warning(ui, "self-motion collisions", text);
    }
}

/// The slider track: the parameter's range, the current branch's feasible intervals green,
/// the rest shaded, the value as a handle. Returns a new value when dragged or clicked (arrow
/// keys step 1 deg while hovered).
pub(crate) fn track(ui: &mut egui::Ui, view: &SelfMotionView) -> Option<f64> {
    let width = ui.available_width().max(120.0);
    let (rect, response) = ui.allocate_exact_size(egui::vec2(width, 26.0), Sense::click_and_drag());
    // A slider to assistive tools (and to tests that drive the window).
    response.widget_info(|| {
        egui::WidgetInfo::slider(true, view.value.to_degrees(), "self-motion slider")
    });
    let [lo, hi] = view.range;
    let x_of = |v: f64| rect.left() + ((v - lo) / (hi - lo)) as f32 * rect.width();
    let bar = egui::Rect::from_min_max(
        egui::pos2(rect.left(), rect.center().y - 5.0),
        egui::pos2(rect.right(), rect.center().y + 5.0),
    );
    let painter = ui.painter_at(rect);
    painter.rect_filled(bar, 2.0, INFEASIBLE);
    let feasible = &view.feasible[view.branch];
    if view.exact {
        for iv in feasible {
            let r = egui::Rect::from_min_max(
                egui::pos2(x_of(iv[0]), bar.top()),
                egui::pos2(x_of(iv[1]), bar.bottom()),
            );
            painter.rect_filled(r, 0.0, FEASIBLE);
        }
        // Where the arm hits itself or an obstacle: red over the green.
        for s in view.colliding.iter().filter(|s| s.branch == view.branch) {
            let r = egui::Rect::from_min_max(
                egui::pos2(x_of(s.from), bar.top()),
                egui::pos2(x_of(s.to).max(x_of(s.from) + 1.0), bar.bottom()),
            );
            painter.rect_filled(r, 0.0, COLLIDING);
        }
    }
    let ink = ui.visuals().text_color();
    for t in [-PI, -PI / 2.0, 0.0, PI / 2.0, PI] {
        let x = x_of(t);
        painter.line_segment(
            [egui::pos2(x, bar.bottom()), egui::pos2(x, rect.bottom())],
            Stroke::new(1.0, ink),
        );
    }
    let hx = x_of(view.value.clamp(lo, hi));
    painter.circle(
        egui::pos2(hx, rect.center().y),
        7.0,
        ui.visuals().widgets.active.bg_fill,
        Stroke::new(1.5, ink),
    );
    let response = response.on_hover_text(
        "drag or click: green where the branch is inside the joint limits, red where the arm \
         hits itself or an obstacle there; arrow keys: 1 deg",
    );
    if let Some(p) = response.interact_pointer_pos()
        && (response.dragged() || response.clicked())
    {
        let v = lo + ((p.x - rect.left()) / rect.width()) as f64 * (hi - lo);
        return Some(v.clamp(lo, hi));
    }
    if response.hovered() {
        let step = ui.input(|i| {
            f64::from(i.key_pressed(egui::Key::ArrowRight))
                - f64::from(i.key_pressed(egui::Key::ArrowLeft))
        });
        if step != 0.0 {
            return Some((view.value + step.to_radians()).clamp(lo, hi));
        }
    }
    None
}
