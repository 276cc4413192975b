//! The window's frame around the tabs: the two side panels (resizable, never so wide that the
//! central area loses its share) and the status bar, with where each part was laid out.

use super::action::Actions;
use super::layout::Layout;
use super::panels::ik::IkPanel;
use super::panels::model::ModelPanel;
use super::state::{AppState, Level};

/// How long a status message stays (s) before the bar shows the usual hint again: information,
/// warnings, errors.
const MESSAGE_SECONDS: [f64; 3] = [6.0, 12.0, 30.0];

/// Where the parts of the window were laid out last (points, window coordinates).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PanelRects {
    /// The left panel (`None` when collapsed).
    pub left: Option<egui::Rect>,
    /// The right panel (`None` when collapsed).
    pub right: Option<egui::Rect>,
    /// The central area (the tabs).
    pub central: egui::Rect,
    /// The toolbar.
    pub top: egui::Rect,
    /// The status bar.
    pub bottom: egui::Rect,
}

impl Default for PanelRects {
    fn default() -> Self {
        Self {
            left: None,
            right: None,
            central: egui::Rect::NOTHING,
            top: egui::Rect::NOTHING,
            bottom: egui::Rect::NOTHING,
        }
    }
}

/// The left panel (`model`) and the right one (`ik`) of the current mode of `layout`:
/// resizable with visible edges, never so wide that the central area loses its share of the
/// window, their content scrolling inside them; where they went is kept in `rects`.
pub fn side_panels(
    ui: &mut egui::Ui,
    layout: &Layout,
    (model, ik, rects): (&mut ModelPanel, &mut IkPanel, &mut PanelRects),
    state: &mut AppState,
    out: &mut Actions,
) {
    let width = ui.max_rect().width();
    let window = ui.ctx().content_rect().width();
    let sides = layout.sides();
    let (left_id, right_id) = layout.panel_ids();
    let (left_default, right_default) = layout.default_widths(width, window);
    let right_w = egui::PanelState::load(ui.ctx(), ui.scope_id().with(right_id))
        .map_or(right_default, |s| s.size().x);
    rects.left = None;
    rects.right = None;
    if sides.left {
        let other = if sides.right { right_w } else { 0.0 };
        let r = egui::Panel::left(left_id)
            .resizable(true)
            .default_size(left_default)
            .size_range(Layout::width_range(width, window, other))
            .show(ui, |ui| {
                fit_to_panel(ui);
                model.ui(state, ik.ee, ui, layout.projector, out);
            });
        rects.left = Some(r.response.rect);
    }
    if sides.right {
        let other = rects.left.map_or(0.0, |r| r.width());
        let r = egui::Panel::right(right_id)
            .resizable(true)
            .default_size(right_default)
            .size_range(Layout::width_range(width, window, other))
            .show(ui, |ui| {
                fit_to_panel(ui);
                ik.ui(state, ui, out);
            });
        rects.right = Some(r.response.rect);
    }
}

/// Keeps a side panel's content inside it: text wraps at the panel's width instead of widening
/// it (wide tables scroll sideways inside their own area).
fn fit_to_panel(ui: &mut egui::Ui) {
    ui.style_mut().wrap_mode = Some(egui::TextWrapMode::Wrap);
    let w = ui.available_width();
    ui.set_max_width(w);
}

/// The bars at the window's bottom: the status bar ([`status_bar`], with its state, end-effector
/// and the workspace job's progress) and, above it, the lesson's bar when a lesson is open.
/// Returns the status bar's rectangle.
pub fn bottom_bars(
    ui: &mut egui::Ui,
    (state, ee, progress): (&AppState, usize, Option<f32>),
    seen: &mut (u64, f64),
    lesson: Option<&mut super::lesson::LessonPlayer>,
    out: &mut Actions,
) -> egui::Rect {
    let bottom = egui::Panel::bottom("status").show(ui, |ui| {
        status_bar(ui, state, ee, progress, seen);
    });
    if let Some(player) = lesson {
        egui::Panel::bottom("lesson").show(ui, |ui| player.bar(ui, out));
    }
    bottom.response.rect
}

/// The status bar: the workspace job's `progress` (0 to 1), and the newest message of `state`
/// until it expires (or the reason the target of `ee` is not reached; then, while the arm is in
/// collision, what it hits; or the usual hint).
/// `seen` is the count of messages seen and when the newest came (s, egui time).
pub fn status_bar(
    ui: &mut egui::Ui,
    state: &AppState,
    ee: usize,
    progress: Option<f32>,
    seen: &mut (u64, f64),
) {
    let now = ui.input(|i| i.time);
    if state.messages_pushed() != seen.0 {
        *seen = (state.messages_pushed(), now);
    }
    ui.horizontal(|ui| {
        if let Some(f) = progress {
            ui.add(
                egui::ProgressBar::new(f)
                    .desired_width(160.0)
                    .text("workspace"),
            );
        }
        // While the arm is in collision, what it hits, once the newest message had its time.
        let collision = || {
            state
                .collision_warning(ee)
                .map(|text| super::state::StatusMessage {
                    level: Level::Warning,
                    text,
                })
        };
        let line = state
            .status_line(ee)
            .filter(|m| {
                let is_newest = state.last_message() == Some(m);
                let ttl = MESSAGE_SECONDS[m.level as usize];
                !is_newest || now - seen.1 < ttl
            })
            .or_else(collision);
        match line {
            Some(m) => {
                let color = match m.level {
                    Level::Info => ui.visuals().text_color(),
                    Level::Warning => egui::Color32::from_rgb(180, 90, 0),
                    Level::Error => egui::Color32::from_rgb(190, 0, 0),
                };
                // A long message wraps onto more lines instead of running off the window, and
                // its whole text shows on hover too (a status line was cut at 1280 px).
                ui.add(egui::Label::new(egui::RichText::new(&m.text).color(color)).wrap())
                    .on_hover_text(&m.text);
                // The bar is redrawn when the message is due to go.
                ui.ctx()
                    .request_repaint_after(std::time::Duration::from_secs(1));
            }
            None => {
                ui.label(
                    "Drag the gizmo to move the IK target; drag empty space to orbit, \
                     right-drag to pan, scroll to zoom. H: help.",
                );
            }
        }
    });
}

/// How long (s) the way out of "present this figure" is shown after entering it.
const PRESENT_HINT_SECONDS: f64 = 4.0;

/// While presenting, says for a few seconds in the window's lower right corner how to leave
/// (then the figure is clean for the room); `presenting` is the layout's flag.
pub fn present_hint(ctx: &egui::Context, presenting: bool, text_scale: f32) {
    let id = egui::Id::unique("present since");
    let now = ctx.input(|i| i.time);
    if !presenting {
        ctx.data_mut(|d| d.remove::<f64>(id));
        return;
    }
    let since = ctx.data_mut(|d| *d.get_temp_mut_or(id, now));
    let left = PRESENT_HINT_SECONDS - (now - since);
    if left <= 0.0 {
        return;
    }
    ctx.request_repaint_after(std::time::Duration::from_secs_f64(left));
    egui::Area::new(egui::Id::unique("present hint"))
        .anchor(egui::Align2::RIGHT_BOTTOM, egui::vec2(-12.0, -12.0))
        .interactable(false)
        .show(ctx, |ui| {
            egui::Frame::popup(ui.style()).show(ui, |ui| {
                let size = 14.0 * text_scale.max(1.0);
                ui.label(egui::RichText::new("F5 or Esc: leave the presentation").size(size));
            });
        });
}
