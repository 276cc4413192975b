//! The Workspace tab: the workspace figure of the current model, or one of the excerpt's
//! figures (Figs 2.29-2.33, Problem 2.17), shown large, with the tool point and the IK target
//! marked on it and following the arm live. The same job computes the 3D view's workspace
//! overlay (the W key).

use super::super::action::{Action, Actions};
use super::super::state::{AppState, Level};
use super::super::workspace_job::{JobFigure, WorkspaceJob};
use super::{Tab, TabContext};
use crate::figure::workspace::WsView;
use crate::scene::Scene;
use crate::workspace::{TrackedPoint, planar_frame};

/// A figure the tab offers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Preset {
    /// The workspace of the current model (its plane, or the top view).
    ThisModel,
    /// One of the excerpt's figures: its name (`armlab figure NAME`), its model, and whether it
    /// is a workspace figure of that model (else a drawing of fixed configurations).
    Textbook {
        /// The figure's name, e.g. "2.30".
        name: &'static str,
        /// The built-in model it shows.
        model: &'static str,
        /// The workspace view it is, if it is one.
        view: Option<WsView>,
    },
}

/// Every preset, in the list's order.
pub const PRESETS: [(&str, Preset); 7] = [
    ("Workspace of this model", Preset::ThisModel),
    (
        "Fig. 2.29: joint-space rectangle",
        Preset::Textbook {
            name: "2.29",
            model: "planar2_fig2_30",
            view: Some(WsView::JointSpace),
        },
    ),
    (
        "Fig. 2.30: two-link workspace",
        Preset::Textbook {
            name: "2.30",
            model: "planar2_fig2_30",
            view: Some(WsView::Plane),
        },
    ),
    (
        "Fig. 2.31: two postures",
        Preset::Textbook {
            name: "2.31",
            model: "planar2",
            view: None,
        },
    ),
    (
        "Fig. 2.32: spherical wrist",
        Preset::Textbook {
            name: "2.32",
            model: "anthropomorphic_spherical_wrist",
            view: None,
        },
    ),
    (
        "Fig. 2.33: four configurations",
        Preset::Textbook {
            name: "2.33",
            model: "anthropomorphic3r",
            view: None,
        },
    ),
    (
        "Problem 2.17: three-link workspace",
        Preset::Textbook {
            name: "problem-2.17",
            model: "planar3",
            view: Some(WsView::Plane),
        },
    ),
];

/// The Workspace tab's state.
pub struct WorkspaceTab {
    /// The computation running or done (figure and overlay).
    pub job: Option<WorkspaceJob>,
    /// The figure shown.
    pub preset: Preset,
    /// The finished job of the same figure at another size, shown (figure, marks, dots) while
    /// `job` recomputes it for the tab's size: never a blank tab (a minute in a browser).
    previous: Option<WorkspaceJob>,
    texture: Option<egui::TextureHandle>,
    /// `texture` shows `previous`'s figure.
    texture_is_previous: bool,
    /// `texture` shows the job's figure as it forms.
    texture_is_preview: bool,
    /// The figure's pixel size the job was started for.
    size: [u32; 2],
    /// The figure's text scale the job was started for: 1, or in projector mode what makes its
    /// smallest text at least 16 px at the size the tab shows it.
    text_scale: f32,
}

impl Default for WorkspaceTab {
    fn default() -> Self {
        Self {
            job: None,
            preset: Preset::ThisModel,
            previous: None,
            texture: None,
            texture_is_previous: false,
            texture_is_preview: false,
            size: [1200, 900],
            text_scale: 1.0,
        }
    }
}

impl WorkspaceTab {
    /// The figure shown, as a lesson names it: `this-model`, or the excerpt figure's number.
    pub fn figure_name(&self) -> String {
        match self.preset {
            Preset::ThisModel => "this-model".into(),
            Preset::Textbook { name, .. } => name.into(),
        }
    }

    /// Shows the figure a lesson names (see [`Self::figure_name`]), computed for `state`'s
    /// model; an unknown name is refused with the names there are.
    pub fn choose_figure(&mut self, name: &str, state: &AppState) -> Result<(), String> {
        let found = PRESETS.iter().map(|(_, p)| *p).find(|p| match p {
            Preset::ThisModel => name == "this-model",
            Preset::Textbook { name: n, .. } => *n == name,
        });
        let Some(p) = found else {
            let names: Vec<String> = PRESETS
                .iter()
                .map(|(_, p)| match p {
                    Preset::ThisModel => "this-model".to_string(),
                    Preset::Textbook { name, .. } => name.to_string(),
                })
                .collect();
            return Err(format!(
                "figure {name:?}: the figures are {}",
                names.join(", ")
            ));
        };
        if p != self.preset || self.job.is_none() {
            self.preset = p;
            self.start(state);
        }
        Ok(())
    }

    /// Starts the job for the current model and preset (cancelling a running one).
    pub fn start(&mut self, state: &AppState) {
        if let Some(old) = self.job.take() {
            old.cancel();
        }
        self.previous = None;
        self.texture = None;
        self.texture_is_previous = false;
        self.texture_is_preview = false;
        let title = state.robot().name.to_lowercase();
        let figure = match self.preset {
            Preset::Textbook {
                view: None, name, ..
            } => JobFigure::Textbook(name, self.text_scale),
            Preset::Textbook {
                view: Some(view),
                name,
                ..
            } => JobFigure::Workspace(
                WorkspaceJob::options_for(state.robot(), view, self.size, Some(name))
                    .scaled(self.text_scale),
            ),
            Preset::ThisModel => {
                let view = if planar_frame(state.robot(), 0).is_some() {
                    WsView::Plane
                } else {
                    WsView::Top
                };
                JobFigure::Workspace(
                    WorkspaceJob::options_for(state.robot(), view, self.size, None)
                        .scaled(self.text_scale),
                )
            }
        };
        self.job = Some(WorkspaceJob::start(
            state.robot().clone(),
            state.spec().to_string(),
            title,
            figure,
        ));
    }

    /// The W key: the 3D view's workspace overlay on or off (computed when it comes on).
    pub fn toggle_overlay(&mut self, state: &mut AppState) {
        state.display.workspace ^= true;
        if state.display.workspace {
            self.ensure_started(state);
        }
    }

    /// The job, started if there is none.
    pub fn ensure_started(&mut self, state: &AppState) {
        if self.job.is_none() {
            self.start(state);
        }
    }

    /// The preset list and the Save button; choosing a figure of another model opens that
    /// model (the figure follows once it is open).
    fn preset_row(&mut self, cx: &mut TabContext<'_>, ui: &mut egui::Ui, out: &mut Actions) {
        ui.horizontal(|ui| {
            let label = ui.label("Figure:");
            let current = PRESETS
                .iter()
                .find(|(_, p)| *p == self.preset)
                .map_or("", |(n, _)| n);
            let mut pick = None;
            egui::ComboBox::from_id_salt("figure preset")
                .selected_text(current)
                .width(300.0)
                .show_ui(ui, |ui| {
                    for (name, p) in PRESETS {
                        if ui.selectable_label(self.preset == p, name).clicked() {
                            pick = Some(p);
                        }
                    }
                })
                .response
                .labelled_by(label.id);
            if let Some(p) = pick.filter(|p| *p != self.preset) {
                self.preset = p;
                match p {
                    Preset::Textbook { model, .. } if cx.state.spec() != model => {
                        out.push(Action::Load(model.to_string()));
                    }
                    _ => self.start(cx.state),
                }
            }
            let save = ui
                .add_enabled(
                    !cx.state.hidden.exam,
                    egui::Button::new("Save figure (PNG)"),
                )
                .on_hover_text("The figure at its full size, as the command line writes it")
                .on_disabled_hover_text("Off during an exam");
            if save.clicked()
                && let Some(img) = self.job.as_ref().and_then(|j| j.figure())
            {
                let stem = format!("{}-workspace", cx.state.spec().replace(['/', '.'], "_"));
                match super::super::files::deliver_png(&mut *cx.picker, img, &stem) {
                    Ok(m) => out.message(Level::Info, m),
                    Err(e) => out.message(Level::Error, format!("figure not saved: {e}")),
                }
            }
        });
    }

    /// The figure's size for the area it is shown in: the area's pixels, at least 800 px
    /// wide (the figures' layout is made for 800 points; smaller would shrink their text).
    fn size_for(area: egui::Vec2, ppp: f32) -> [u32; 2] {
        let w = (area.x * ppp).max(800.0);
        let h = (area.y * ppp * w / (area.x * ppp).max(1.0)).clamp(450.0, 4096.0);
        [w.round() as u32, h.round() as u32]
    }

    /// Whether a figure is on screen (the tab's, or the previous size's while it recomputes).
    pub fn showing_figure(&self) -> bool {
        self.texture.is_some()
    }

    /// The job whose figure (and dots) are shown: the previous size's while the new one
    /// computes.
    fn shown_job(&self) -> Option<&WorkspaceJob> {
        if self.texture_is_previous {
            self.previous.as_ref()
        } else {
            self.job.as_ref()
        }
    }

    /// Marks the tool point and the IK target on a workspace figure shown in `rect`, where
    /// the plot's data lie as the job's frame says.
    fn live_marks(&self, state: &AppState, ee: usize, ui: &egui::Ui, rect: egui::Rect) {
        let Some(job) = self.shown_job() else { return };
        let (Some(frame), Some((view, point))) = (job.frame(), job.view()) else {
            return;
        };
        let Some(img) = job.figure() else { return };
        let scale = rect.width() / img.width() as f32;
        let [x0, x1, y0, y1] = frame.bounds;
        let [fx0, fy0, fx1, fy1] = frame.rect_px;
        let to_screen = |d: [f64; 2]| {
            let u = ((d[0] - x0) / (x1 - x0)) as f32;
            let v = ((d[1] - y0) / (y1 - y0)) as f32;
            rect.min + egui::vec2(fx0 + u * (fx1 - fx0), fy1 - v * (fy1 - fy0)) * scale
        };
        let robot = state.robot();
        let plane = planar_frame(robot, ee);
        let data = |p: &nalgebra::Vector3<f64>, q: &[f64]| -> Option<[f64; 2]> {
            match (view, &plane) {
                (WsView::JointSpace, _) => Some([q.first()?.to_degrees(), q.get(1)?.to_degrees()]),
                (WsView::Plane, Some(f)) => Some(f.to_plane([p.x, p.y, p.z])),
                (WsView::Side, _) => Some([p.x.hypot(p.y), p.z]),
                _ => Some([p.x, p.y]),
            }
        };
        let painter = ui.painter_at(rect);
        let ink = egui::Color32::from_rgb(20, 20, 24);
        let tool = match point {
            TrackedPoint::WristCentre if robot.dof() == 6 => {
                crate::construction::WristPoint::of(robot, state.q())
                    .map(|w| w.p_w)
                    .ok()
            }
            _ => robot
                .fk_ee(state.q(), ee)
                .ok()
                .map(|t| t.translation.vector),
        };
        if let Some(p) = tool
            && let Some(d) = data(&p, state.q())
        {
            let at = to_screen(d);
            painter.circle(at, 6.0, egui::Color32::WHITE, egui::Stroke::new(2.0, ink));
            painter.text(
                at + egui::vec2(9.0, -9.0),
                egui::Align2::LEFT_BOTTOM,
                "tool",
                egui::FontId::proportional(13f32.max(super::super::layout::text_floor(ui.ctx()))),
                ink,
            );
        }
        if view != WsView::JointSpace
            && let Ok(t) = state.target(ee)
            && let Some(d) = data(&t.world_from_tool.translation.vector, state.q())
        {
            let at = to_screen(d);
            let red = egui::Color32::from_rgb(200, 30, 30);
            let s = egui::Stroke::new(2.0, red);
            painter.line_segment([at - egui::vec2(7.0, 0.0), at + egui::vec2(7.0, 0.0)], s);
            painter.line_segment([at - egui::vec2(0.0, 7.0), at + egui::vec2(0.0, 7.0)], s);
            painter.text(
                at + egui::vec2(9.0, 9.0),
                egui::Align2::LEFT_TOP,
                "target",
                egui::FontId::proportional(13f32.max(super::super::layout::text_floor(ui.ctx()))),
                red,
            );
        }
    }
}

impl Tab for WorkspaceTab {
    fn title(&self) -> &'static str {
        "Workspace"
    }

    fn ui(&mut self, cx: &mut TabContext<'_>, ui: &mut egui::Ui, out: &mut Actions) {
        if cx.state.hidden.workspace {
            ui.label(
                "The workspace is what the exercise asks for: hidden until the sheet is closed.",
            );
            return;
        }
        // Presenting, the figure alone fills the window.
        if !cx.layout.present {
            self.preset_row(cx, ui, out);
        }
        let area = ui.available_size();
        let ppp = ui.ctx().pixels_per_point();
        let size = Self::size_for(area, ppp);
        let scale = if cx.layout.projector {
            projector_text_scale(area.x * ppp)
        } else {
            1.0
        };
        if (scale - self.text_scale).abs() > 0.01 {
            self.text_scale = scale;
            self.size = [0, 0]; // the figure is drawn again for its new text
        }
        let resized = size != self.size
            && self
                .job
                .as_ref()
                .is_some_and(|j| j.progress().is_none() && j.figure().is_some());
        if self.job.is_none() || resized {
            self.size = size;
            let done = if resized { self.job.take() } else { None };
            self.start(cx.state);
            // The finished figure stays on screen until the one sized to the tab is done.
            if let Some(done) = done {
                self.previous = Some(done);
                self.texture_is_previous = true;
            }
        }
        if self.texture_is_previous && self.job.as_ref().is_some_and(|j| j.figure().is_some()) {
            self.texture = None;
            self.previous = None;
            self.texture_is_previous = false;
        }
        let Some(job) = &self.job else { return };
        if let Some(f) = job.progress() {
            ui.add(egui::ProgressBar::new(f).text("computing the workspace..."));
        }
        if let Some(err) = job.error() {
            ui.colored_label(egui::Color32::from_rgb(190, 0, 0), err);
            return;
        }
        if let Some(err) = job.figure_error() {
            let text = format!("no figure: {err}");
            ui.colored_label(egui::Color32::from_rgb(190, 0, 0), text);
        }
        // The figure as it forms (not over the finished figure of another size).
        if !self.texture_is_previous
            && let Some(img) = job.take_preview()
        {
            self.texture = Some(figure_texture(ui, &img));
            self.texture_is_preview = true;
        }
        if self.texture_is_preview && job.figure().is_some() {
            self.texture = None;
            self.texture_is_preview = false;
        }
        let shown = self.shown_job();
        if self.texture.is_none()
            && let Some(img) = shown.and_then(|j| j.figure())
        {
            self.texture = Some(figure_texture(ui, img));
        }
        if let Some(t) = &self.texture {
            let r = ui
                .centered_and_justified(|ui| ui.add(egui::Image::new(t).shrink_to_fit()))
                .inner;
            self.live_marks(cx.state, cx.ee, ui, r.rect);
        }
    }

    fn decorate(&self, state: &AppState, scene: &mut Scene) {
        if state.display.workspace
            && let Some(dots) = (self.job.as_ref().and_then(|j| j.dots()))
                .or_else(|| self.previous.as_ref().and_then(|j| j.dots()))
        {
            // Under the arm: the cloud never hides it.
            scene.underlay.extend_from_slice(dots);
        }
    }

    fn model_changed(&mut self) {
        if let Some(job) = self.job.take() {
            job.cancel();
        }
        self.previous = None;
        self.texture = None;
        self.texture_is_previous = false;
        self.texture_is_preview = false;
    }
}

/// The text scale that makes a figure's smallest text (10 points of its 800-point layout: the
/// marks' letters; ticks and captions are 11) at least
/// [`crate::app::layout::PROJECTOR_MIN_TEXT`] pixels when it is shown `shown_px` pixels wide:
/// a figure's text is `points x scale x shown_px / 800` pixels whatever size it is drawn at.
pub fn projector_text_scale(shown_px: f32) -> f32 {
    let min = crate::app::layout::PROJECTOR_MIN_TEXT;
    (min * 800.0 / (10.0 * shown_px.max(1.0))).max(1.0)
}

/// A figure's pixels as a texture.
fn figure_texture(ui: &egui::Ui, img: &image::RgbaImage) -> egui::TextureHandle {
    let color = egui::ColorImage::from_rgba_unmultiplied(
        [img.width() as usize, img.height() as usize],
        img.as_raw(),
    );
    ui.ctx()
        .load_texture("workspace figure", color, egui::TextureOptions::LINEAR)
}
