//! [`Figures`]: one GPU device, the scene renderer and the egui offscreen renderer, making PNG
//! figures of plots and of 3D scenes with their titles, legends and labels.

use super::plot2d::{self, Plot2d};
use super::{FigureError, Theme, apply_style_scaled, pixels_per_point};

/// The smallest label a 3D figure draws, in pixels of its own frame: readable at the size it is
/// recorded or written at.
pub const MIN_TEXT_PX: f32 = 16.0;
use crate::camera::Camera;
use crate::render::{Gpu, RenderSettings, RenderTarget, Renderer, ViewUniforms};
use crate::scene::Scene;
use crate::ui_render::offscreen::Offscreen;
use egui::Color32;

/// Where a plot's data lie on the canvas ([`Figures::plot_frame`]).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PlotFrame {
    /// `[x_min, x_max, y_min, y_max]` shown in the frame (data units).
    pub bounds: [f64; 4],
    /// The frame's size (px).
    pub px: [usize; 2],
    /// The frame on the canvas, `[left, top, right, bottom]` (px from the top left).
    pub rect_px: [f32; 4],
}

impl PlotFrame {
    fn of(frame: &plot2d::PlotFrame, ppp: f32) -> Self {
        let r = frame.rect;
        Self {
            bounds: frame.bounds,
            px: [
                ((r.width() * ppp).round() as usize).max(1),
                ((r.height() * ppp).round() as usize).max(1),
            ],
            rect_px: [r.min.x * ppp, r.min.y * ppp, r.max.x * ppp, r.max.y * ppp],
        }
    }
}

/// Multisampling of 3D figures (4x: smooth edges; lavapipe renders it deterministically).
pub const FIGURE_MSAA: u32 = 4;

/// A 3D figure: a scene seen by a camera, with a title and legend drawn over it.
#[derive(Debug, Clone)]
pub struct Scene3d<'a> {
    /// Title at the top.
    pub title: String,
    /// One line under the title.
    pub subtitle: String,
    /// A small caption at the bottom naming the figure's source; empty for none.
    pub caption: String,
    /// What to draw.
    pub scene: &'a Scene,
    /// From where.
    pub camera: Camera,
    /// Legend swatches (name, colour).
    pub legend: Vec<(String, Color32)>,
}

/// Makes figures headlessly with the app's renderer.
pub struct Figures {
    /// The device.
    pub gpu: Gpu,
    offscreen: Offscreen,
    renderer: Renderer,
    /// A multi-panel figure's composed vectors ([`Self::set_composite`]).
    composite: Option<super::vector::VectorPage>,
    /// Every text size times this (1: as laid out for the 800-point canvas); see
    /// [`super::apply_style_scaled`].
    pub text_scale: f32,
}

impl Figures {
    /// Opens the GPU (software adapter on machines without one) and builds both renderers.
    pub fn new() -> Result<Self, FigureError> {
        Self::with_gpu(Gpu::new_headless()?)
    }

    /// Builds both renderers on a device already open (the window's, in a browser).
    pub fn with_gpu(gpu: Gpu) -> Result<Self, FigureError> {
        let offscreen = Offscreen::new(&gpu.device);
        let renderer = Renderer::new(&gpu, FIGURE_MSAA)?;
        Ok(Self {
            gpu,
            offscreen,
            renderer,
            composite: None,
            text_scale: 1.0,
        })
    }

    /// Renders return a blank image at once and leave the pixels to [`Self::take_deferred`]
    /// (a browser cannot wait for the GPU; see [`Offscreen::defer_readback`]).
    pub fn defer_readback(&mut self) {
        self.offscreen.defer_readback();
    }

    /// From now on (`on`) each figure also keeps what it painted, for [`Self::take_vector`].
    pub fn capture_vectors(&mut self, on: bool) {
        self.offscreen.capture_shapes(on);
        super::vector::set_capturing(&self.offscreen.ctx, on);
    }

    /// The last figure as vectors (with [`Self::capture_vectors`] on).
    pub fn take_vector(&mut self) -> Option<super::vector::VectorPage> {
        if let Some(page) = self.composite.take() {
            return Some(page);
        }
        let capture = self.offscreen.take_capture()?;
        Some(super::vector::VectorPage::single(
            capture,
            super::vector::tags(&self.offscreen.ctx),
        ))
    }

    /// Whether figures keep their vectors ([`Self::capture_vectors`]).
    pub fn capturing(&self) -> bool {
        super::vector::capturing(&self.offscreen.ctx)
    }

    /// Sets the page [`Self::take_vector`] returns next: a figure of several panels composes
    /// its panels' vectors as it composes their pixels.
    pub fn set_composite(&mut self, page: super::vector::VectorPage) {
        self.composite = Some(page);
    }

    /// The read-back of the last deferred figure, if any.
    pub fn take_deferred(&mut self) -> Option<crate::render::PendingRead> {
        self.offscreen.take_deferred()
    }

    /// A 2D plot figure of `size` pixels; `raster` (an image covering `plot.bounds`) is shown
    /// under the curves.
    pub fn plot(
        &mut self,
        size: [u32; 2],
        theme: Theme,
        plot: &Plot2d,
        raster: Option<egui::ColorImage>,
    ) -> Result<image::RgbaImage, FigureError> {
        apply_style_scaled(&self.offscreen.ctx, theme, self.text_scale);
        let tex = raster.map(|img| {
            self.offscreen
                .ctx
                .load_texture("raster", img, egui::TextureOptions::NEAREST)
        });
        let id = tex.as_ref().map(egui::TextureHandle::id);
        let ppp = pixels_per_point(size[0]);
        Ok(self
            .offscreen
            .render(&self.gpu.device, &self.gpu.queue, size, ppp, |ui| {
                egui::CentralPanel::default().show(ui, |ui| {
                    plot2d::show(ui, plot, id);
                });
            })?)
    }

    /// Where a plot's data will lie once drawn at `size`: a layout pass (nothing painted) finds
    /// its frame's size in pixels and the data bounds shown there (grown for an equal aspect), so
    /// that a raster can be computed for exactly those before the plot is drawn
    /// ([`Self::plot_at`]).
    pub fn plot_frame(
        &mut self,
        size: [u32; 2],
        theme: Theme,
        plot: &Plot2d,
    ) -> Result<PlotFrame, FigureError> {
        apply_style_scaled(&self.offscreen.ctx, theme, self.text_scale);
        let ppp = pixels_per_point(size[0]);
        let mut frame = None;
        self.offscreen.layout(&self.gpu.device, size, ppp, |ui| {
            egui::CentralPanel::default().show(ui, |ui| {
                frame = Some(plot2d::show(ui, plot, None));
            });
        })?;
        let frame = frame.ok_or(FigureError::NotLaidOut)?;
        Ok(PlotFrame::of(&frame, ppp))
    }

    /// Runs `f`, then puts the figure context's memory back as it was, so that what `f` painted
    /// (a forming figure's preview) leaves no trace in the next figure: egui_plot keeps each
    /// plot's bounds and layout between frames, which would shift the finished figure's frame.
    pub fn leaving_no_trace<R>(&mut self, f: impl FnOnce(&mut Self) -> R) -> R {
        let saved = self.offscreen.ctx.memory(|m| m.clone());
        let out = f(self);
        self.offscreen.ctx.memory_mut(|m| *m = saved);
        out
    }

    /// A plot with `raster` laid under its curves over the data bounds it was made for (those of
    /// [`Self::plot_frame`]), and where its frame was drawn.
    pub fn plot_at(
        &mut self,
        size: [u32; 2],
        theme: Theme,
        plot: &Plot2d,
        raster: Option<(egui::ColorImage, [f64; 4])>,
    ) -> Result<(image::RgbaImage, PlotFrame), FigureError> {
        apply_style_scaled(&self.offscreen.ctx, theme, self.text_scale);
        let ppp = pixels_per_point(size[0]);
        let tex = raster.map(|(img, bounds)| {
            let t = self
                .offscreen
                .ctx
                .load_texture("raster", img, egui::TextureOptions::NEAREST);
            (t, bounds)
        });
        let image = tex.as_ref().map(|(t, bounds)| (t.id(), *bounds));
        let mut frame = None;
        let pixels = self
            .offscreen
            .render(&self.gpu.device, &self.gpu.queue, size, ppp, |ui| {
                egui::CentralPanel::default().show(ui, |ui| {
                    frame = Some(plot2d::show_at(ui, plot, image));
                });
            })?;
        let frame = frame.ok_or(FigureError::NotLaidOut)?;
        Ok((pixels, PlotFrame::of(&frame, ppp)))
    }

    /// A 3D figure: the scene rendered by the app's renderer at full size, with title, legend
    /// and the scene's labels drawn over it by egui.
    pub fn scene(
        &mut self,
        size: [u32; 2],
        theme: Theme,
        fig: &Scene3d<'_>,
    ) -> Result<image::RgbaImage, FigureError> {
        apply_style_scaled(&self.offscreen.ctx, theme, self.text_scale);
        let [w, h] = size;
        let target = RenderTarget::new(&self.gpu, w, h, FIGURE_MSAA)?;
        let mut settings = RenderSettings::default();
        if theme == Theme::Dark {
            settings.clear = [0.02, 0.022, 0.026, 1.0];
        } else {
            settings.clear = [1.0, 1.0, 1.0, 1.0];
        }
        let view = ViewUniforms::from_camera(&fig.camera, w, h);
        self.renderer
            .render(&self.gpu, &target, fig.scene, &view, &settings)?;
        let id = self
            .offscreen
            .register_texture(&self.gpu.device, &target.egui_view());
        let ppp = pixels_per_point(w);
        let result = self
            .offscreen
            .render(&self.gpu.device, &self.gpu.queue, size, ppp, |ui| {
                paint_scene_overlay(ui, fig, id, (size, ppp));
            });
        if self.offscreen.take_capture().is_some_and(|mut c| {
            // A vector figure embeds the 3D view as an image under its vector text.
            match target.read_egui_rgba(&self.gpu) {
                Ok(img) => {
                    let size = [img.width() as usize, img.height() as usize];
                    let view = egui::ColorImage::from_rgba_unmultiplied(size, img.as_raw());
                    c.images.insert(id, std::sync::Arc::new(view));
                    self.offscreen.put_capture(c);
                    false
                }
                Err(_) => true,
            }
        }) {
            return Err(FigureError::NotLaidOut);
        }
        self.offscreen.free_texture(id);
        Ok(result?)
    }
}

/// A 3D figure's egui pass: the rendered view (texture `id`), its labels, title, subtitle,
/// caption and legend, on a canvas of `size` pixels at `ppp` pixels per point.
fn paint_scene_overlay(
    ui: &mut egui::Ui,
    fig: &Scene3d<'_>,
    id: egui::TextureId,
    (size, ppp): ([u32; 2], f32),
) {
    let [w, h] = size;
    let rect = ui.max_rect();
    let painter = ui.painter();
    painter.image(
        id,
        rect,
        egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0)),
        Color32::WHITE,
    );
    let font = |pt: f32| super::font(ui.ctx(), pt);
    // The labels are sized for the frame they are drawn into: at least MIN_TEXT_PX
    // pixels whatever its size (a recording's 640-pixel frame had 9-pixel labels).
    // Titles and captions keep the layout's scale: they must fit their panel.
    let mut label_font = font(13.0);
    label_font.size = label_font.size.max(MIN_TEXT_PX / ppp);
    super::labels::draw_labels(
        painter,
        rect,
        ([w, h], &fig.camera),
        &fig.scene.labels,
        &[],
        &label_font,
    );
    let text = ui.visuals().text_color();
    painter.text(
        rect.center_top() + egui::vec2(0.0, 8.0),
        egui::Align2::CENTER_TOP,
        &fig.title,
        font(20.0),
        text,
    );
    if !fig.subtitle.is_empty() {
        painter.text(
            rect.center_top() + egui::vec2(0.0, 34.0),
            egui::Align2::CENTER_TOP,
            &fig.subtitle,
            font(12.0),
            text,
        );
    }
    let weak = ui.visuals().weak_text_color();
    paint_caption_and_legend(painter, rect, fig, (text, weak), &font);
}

/// The caption (bottom right) and the legend swatches (top right) of a 3D figure.
fn paint_caption_and_legend(
    painter: &egui::Painter,
    rect: egui::Rect,
    fig: &Scene3d<'_>,
    (text, weak): (Color32, Color32),
    font: &dyn Fn(f32) -> egui::FontId,
) {
    if !fig.caption.is_empty() {
        painter.text(
            rect.right_bottom() - egui::vec2(10.0, 8.0),
            egui::Align2::RIGHT_BOTTOM,
            &fig.caption,
            font(11.0),
            weak,
        );
    }
    let mut y = rect.top() + 60.0;
    for (name, color) in &fig.legend {
        let swatch =
            egui::Rect::from_min_size(egui::pos2(rect.right() - 190.0, y), egui::vec2(14.0, 14.0));
        painter.rect_filled(swatch, 2.0, *color);
        painter.text(
            swatch.right_center() + egui::vec2(6.0, 0.0),
            egui::Align2::LEFT_CENTER,
            name,
            font(13.0),
            text,
        );
        y += 20.0;
    }
}
