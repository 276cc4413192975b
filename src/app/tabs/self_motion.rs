//! The Self-motion tab (Sect. 2.10.2): every joint against the self-motion parameter for every
//! branch, the current branch green where it is inside the limits, the limits as bands, the
//! current value as a cursor. It only paints what
//! [`AppState::self_motion`](super::super::state::AppState::self_motion) hands it.

use super::super::action::Actions;
use super::super::state::SelfMotionView;
use super::{Tab, TabContext};
use crate::kinematics::Robot;
use egui::Color32;
use egui_plot::{Axis, Line, Plot, Span, VLine};

/// Green of the feasible stretches.
const FEASIBLE: Color32 = Color32::from_rgb(40, 150, 80);

/// The Self-motion tab (its plots keep no state of their own).
#[derive(Default)]
pub struct SelfMotionTab;

impl Tab for SelfMotionTab {
    fn title(&self) -> &'static str {
        "Self-motion"
    }

    fn ui(&mut self, cx: &mut TabContext<'_>, ui: &mut egui::Ui, out: &mut Actions) {
        if let Some(view) = cx.self_motion.take() {
            plots(view, cx.state.robot(), cx.ee, ui, out);
        }
    }
}

/// The tab's plots of the self-motion `view` of `robot`'s end-effector `ee`: one small plot per
/// joint, stacked, x linked; above them the same slider as the Redundancy panel's, so the lesson
/// needs no scrolling of the side panel (in projector mode it is below the fold).
fn plots(
    view: Result<SelfMotionView, String>,
    robot: &Robot,
    ee: usize,
    ui: &mut egui::Ui,
    out: &mut Actions,
) {
    let view = match view {
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
    ui.horizontal(|ui| {
        ui.label(format!(
            "{} = {:.1} deg",
            view.parameter,
            view.value.to_degrees()
        ));
        if let Some(v) = crate::app::panels::redundancy::track(ui, &view) {
            out.push(crate::app::action::Action::SetSelfMotion(ee, v));
        }
    });
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
