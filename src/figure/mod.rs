//! Figures: egui layouts (titles, axes, legends) rendered offscreen through egui-wgpu, with the
//! 3D scenes drawn by [`crate::render`] shown inside them. Used by the headless CLI and, through
//! the same code, by the app.

pub mod accuracy;
#[cfg(feature = "app")]
pub mod animation;
pub mod figures;
pub mod labels;
pub mod orientation;
pub(crate) mod palette;
pub mod placement;
pub mod plot2d;
pub mod raster;
pub mod reachability;
pub mod self_motion;
pub mod textbook;
pub mod vector;
pub mod workspace;

use thiserror::Error;

/// What can go wrong while making a figure.
#[derive(Debug, Error)]
pub enum FigureError {
    /// The GPU layer failed (no adapter, device lost, readback).
    #[error(transparent)]
    Render(#[from] crate::render::RenderError),
    /// Painting the figure's egui layout failed (its size, the GPU).
    #[error(transparent)]
    UiRender(#[from] crate::ui_render::UiRenderError),
    /// The workspace computation failed.
    #[error(transparent)]
    Workspace(#[from] crate::workspace::WorkspaceError),
    /// Bad robot input (wrong joint count, NaN).
    #[error(transparent)]
    Kinematics(#[from] crate::kinematics::KinematicsError),
    /// The plot's frame was not laid out, so its size could not be measured.
    #[error("figure layout: the plot was not laid out")]
    NotLaidOut,
    /// The figure's subject could not be computed (a figure of the excerpt).
    #[error(transparent)]
    Construction(#[from] crate::construction::ConstructionError),
    /// The figure was handed data of another kind than its plan asked for.
    #[error("the figure was handed {got} where its plan asked for {wanted}")]
    WrongData {
        /// What the plan asked for.
        wanted: &'static str,
        /// What came.
        got: &'static str,
    },
}

/// Light or dark colours.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Theme {
    /// Dark text on white (print, projector).
    #[default]
    Light,
    /// Light text on dark grey.
    Dark,
}

/// Sets egui's visuals and text sizes for figures: the layout is made for an 800-point-wide
/// canvas, and `pixels_per_point` scales it to the requested size.
pub fn apply_style(ctx: &egui::Context, theme: Theme) {
    apply_style_scaled(ctx, theme, 1.0);
}

/// Where [`apply_style_scaled`] keeps the text scale for [`font`].
const TEXT_SCALE: &str = "armlab figure text scale";

/// [`apply_style`] with every text size times `text_scale`: a figure shown smaller than its
/// canvas (the app's Workspace tab beside its panels, in projector mode) keeps its text
/// readable at the size it is seen.
pub fn apply_style_scaled(ctx: &egui::Context, theme: Theme, text_scale: f32) {
    ctx.data_mut(|d| d.insert_temp(egui::Id::unique(TEXT_SCALE), text_scale));
    ctx.set_visuals(match theme {
        Theme::Light => egui::Visuals::light(),
        Theme::Dark => egui::Visuals::dark(),
    });
    ctx.global_style_mut(|s| {
        use egui::{FontId, TextStyle};
        let k = text_scale;
        s.text_styles
            .insert(TextStyle::Heading, FontId::proportional(20.0 * k));
        s.text_styles
            .insert(TextStyle::Body, FontId::proportional(14.0 * k));
        s.text_styles
            .insert(TextStyle::Small, FontId::proportional(12.0 * k));
        s.text_styles
            .insert(TextStyle::Button, FontId::proportional(14.0 * k));
        s.text_styles
            .insert(TextStyle::Monospace, FontId::monospace(13.0 * k));
        s.animation_time = 0.0;
    });
}

/// A proportional font of `size` points times the figure's text scale
/// ([`apply_style_scaled`]).
pub fn font(ctx: &egui::Context, size: f32) -> egui::FontId {
    let k: f32 = ctx
        .data(|d| d.get_temp(egui::Id::unique(TEXT_SCALE)))
        .unwrap_or(1.0);
    egui::FontId::proportional(size * k)
}

/// Pixels per egui point for a figure `width` pixels wide (layouts are designed at 800).
pub fn pixels_per_point(width: u32) -> f32 {
    (width as f32 / 800.0).max(0.25)
}

/// Encodes `img` as an 8-bit RGBA PNG into `out` (fast compression, no timestamps or metadata,
/// so the same pixels always give the same bytes): what figures, screenshots and downloads write.
pub fn encode_png(img: &image::RgbaImage, out: impl std::io::Write) -> image::ImageResult<()> {
    use image::ImageEncoder;
    image::codecs::png::PngEncoder::new_with_quality(
        out,
        image::codecs::png::CompressionType::Fast,
        image::codecs::png::FilterType::Adaptive,
    )
    .write_image(
        img.as_raw(),
        img.width(),
        img.height(),
        image::ExtendedColorType::Rgba8,
    )
}
