//! The Redundancy panel (n, m, r in words, the task the gizmo obeys, the self-motion slider) and
//! the Self-motion tab (every joint against the parameter for every branch, limits as bands,
//! the current value as a cursor). Both only paint what [`AppState::self_motion`] hands them.

use super::state::{AppState, Level, SelfMotionView};
use super::ui::AppUi;
use egui::{Color32, RichText, Sense, Stroke};
use egui_plot::{Axis, Line, Plot, Span, VLine};
use std::f64::consts::PI;

/// Green of the feasible stretches (track and curves).
const FEASIBLE: Color32 = Color32::from_rgb(40, 150, 80);
/// Shade of the infeasible stretches of the track.
const INFEASIBLE: Color32 = Color32::from_rgb(200, 200, 205);

/// The Redundancy section of the right panel.
pub fn panel(app: &mut AppUi, ui: &mut egui::Ui, ee: usize) {
    ui.heading("Redundancy");
    let red = app.state.redundancy();
    ui.monospace(format!("n = {}, m = {}, r = {}", red.n, red.m, red.r));
    ui.label(RichText::new(format!("{} (degree {})", red.words(), red.degree())).strong());
    let mut task = app.state.task();
    egui::ComboBox::from_label("task (tool frame)")
        .selected_text(task.name())
        .show_ui(ui, |ui| {
            for t in app.state.tasks() {
                ui.selectable_value(&mut task, t, t.name())
                    .on_hover_text(t.description());
            }
        });
    if task != app.state.task() {
        match app.state.set_task(task) {
            Ok(()) => app
                .state
                .push_message(Level::Info, format!("task: {}", task.description())),
            Err(e) => app.state.push_message(Level::Warning, e.to_string()),
        }
    }
    ui.label(RichText::new(app.state.task().description()).small());
    match app.state.self_motion(ee) {
        Ok(view) => slider_section(&mut app.state, ui, ee, &view),
        Err(why) => {
            ui.label(RichText::new(format!("no self-motion slider: {why}")).small());
        }
    }
}

/// The slider, its readouts and the branch choice.
fn slider_section(state: &mut AppState, ui: &mut egui::Ui, ee: usize, view: &SelfMotionView) {
    ui.label(RichText::new(format!("Self-motion: {}", view.meaning)).small());
    if let Some(v) = track(ui, view)
        && let Err(e) = state.set_self_motion(ee, v)
    {
        state.push_message(Level::Warning, e.to_string());
    }
    let mut deg = view.value.to_degrees();
    ui.horizontal(|ui| {
        ui.label(format!("{} =", view.parameter));
        let r = ui.add(
            egui::DragValue::new(&mut deg)
                .speed(0.2)
                .range(view.range[0].to_degrees()..=view.range[1].to_degrees())
                .suffix(" deg"),
        );
        if r.changed()
            && let Err(e) = state.set_self_motion(ee, deg.to_radians())
        {
            state.push_message(Level::Warning, e.to_string());
        }
    });
    ui.monospace(format!(
        "hand error {:.1e} m, {:.1e} rad",
        view.position_error, view.orientation_error
    ));
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
        if let Some(k) = pick.filter(|&k| k != view.branch)
            && let Err(e) = state.select_self_motion_branch(ee, k)
        {
            state.push_message(Level::Warning, e.to_string());
        }
    } else {
        ui.label(
            RichText::new("numerical: the feasible stretches are not known in advance").small(),
        );
    }
    ui.checkbox(&mut state.display.self_motion_path, "Trace the path");
}

/// The slider track: the parameter's range, the current branch's feasible intervals green,
/// the rest shaded, the value as a handle. Returns a new value when dragged or clicked (arrow
/// keys step 1 deg while hovered).
fn track(ui: &mut egui::Ui, view: &SelfMotionView) -> Option<f64> {
    let width = ui.available_width().max(120.0);
    let (rect, response) = ui.allocate_exact_size(egui::vec2(width, 26.0), Sense::click_and_drag());
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
        "drag or click: green where the branch is inside the joint limits; arrow keys: 1 deg",
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

/// The Self-motion tab: one small plot per joint, stacked, x linked.
pub fn tab(state: &mut AppState, ui: &mut egui::Ui, ee: usize) {
    let view = match state.self_motion(ee) {
        Ok(v) if v.exact => v,
        Ok(_) => {
            ui.label(
                "The numerical self-motion has no closed-form parameter: walk it with the slider \
                 in the Redundancy panel (the path is traced in the 3D view).",
            );
            return;
        }
        Err(why) => {
            ui.label(format!("No self-motion for this robot and task: {why}."));
            return;
        }
    };
    ui.label(format!(
        "Every joint against {} (deg) for every branch: the current branch \"{}\" thick, green \
         where it is inside the limits; other branches thin; joint limits shaded; the cursor at \
         the current value.",
        view.parameter, view.names[view.branch]
    ));
    let robot = state.robot().clone();
    let limits = robot.limits();
    let n = robot.dof();
    egui::ScrollArea::vertical().show(ui, |ui| {
        let h = ((ui.available_height() - 8.0) / n as f32).clamp(90.0, 220.0);
        for (k, limit) in limits.iter().enumerate() {
            let name = &robot.dof_joint(k).name;
            joint_plot(ui, &view, (k, name, *limit), k + 1 == n, h);
        }
    });
}

/// One joint's plot.
fn joint_plot(
    ui: &mut egui::Ui,
    view: &SelfMotionView,
    (k, name, limit): (usize, &str, [f64; 2]),
    last: bool,
    height: f32,
) {
    let link = ui.make_persistent_id("self-motion plots");
    Plot::new(("self-motion joint", k))
        .height(height)
        .link_axis(link, [true, false])
        .link_cursor(link, [true, false])
        .x_axis_label(if last {
            format!("{} (deg)", view.parameter)
        } else {
            String::new()
        })
        .y_axis_label(format!("{name} (deg)"))
        .include_x(-180.0)
        .include_x(180.0)
        .show(ui, |pui| {
            if limit[0].is_finite() && limit[1].is_finite() {
                pui.span(
                    Span::new("", limit[0].to_degrees()..=limit[1].to_degrees())
                        .axis(Axis::Y)
                        .fill(Color32::from_rgba_unmultiplied(90, 130, 220, 30)),
                );
            }
            for (b, name) in view.names.iter().enumerate() {
                for (points, inside) in pieces(view, b, k) {
                    let current = b == view.branch;
                    let color = match (current, inside) {
                        (true, true) => FEASIBLE,
                        (true, false) => Color32::from_rgb(200, 70, 60),
                        (false, _) => Color32::from_gray(150),
                    };
                    pui.line(
                        Line::new(name.clone(), points)
                            .color(color)
                            .width(if current { 2.5 } else { 1.0 }),
                    );
                }
            }
            pui.vline(VLine::new("value", view.value.to_degrees()).color(Color32::BLACK));
        });
}

/// The samples of joint `k` on branch `b` as polylines (deg, deg), split where the branch is
/// missing, where the angle wraps, and where it enters or leaves the limits.
fn pieces(view: &SelfMotionView, b: usize, k: usize) -> Vec<(Vec<[f64; 2]>, bool)> {
    let name = &view.names[b];
    let mut out: Vec<(Vec<[f64; 2]>, bool)> = Vec::new();
    let mut last: Option<(f64, bool)> = None;
    for (v, sols) in &view.samples {
        let Some(s) = sols.iter().find(|s| &s.name == name) else {
            last = None;
            continue;
        };
        let y = s.q[k].to_degrees();
        let p = [v.to_degrees(), y];
        match (last, out.last_mut()) {
            (Some((y0, w)), Some(piece)) if w == s.within_limits && (y - y0).abs() < 90.0 => {
                piece.0.push(p);
            }
            _ => out.push((vec![p], s.within_limits)),
        }
        last = Some((y, s.within_limits));
    }
    out
}
