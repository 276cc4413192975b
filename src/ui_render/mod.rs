//! egui on wgpu: the bridge between the widgets and the GPU, beside [`crate::render`] (which
//! knows no egui). [`painter`] paints egui's tessellated output with armlab's own pipelines (what
//! the live window draws its panels with); [`offscreen`] runs an egui context into a texture and
//! reads it back (figures, screenshots of the whole window, the browser's deferred read-back).

pub mod offscreen;
pub mod painter;

pub use offscreen::{FIGURE_FORMAT, Offscreen};
pub use painter::{UiFrame, UiPainter};

use thiserror::Error;

/// What can go wrong while painting egui offscreen.
#[derive(Debug, Error)]
pub enum UiRenderError {
    /// The GPU layer failed (no adapter, device lost, read-back).
    #[error(transparent)]
    Render(#[from] crate::render::RenderError),
    /// A canvas of zero or above 8192 pixels.
    #[error("figure size {width}x{height} is not between 1x1 and 8192x8192 pixels")]
    Size {
        /// Width asked for (px).
        width: u32,
        /// Height asked for (px).
        height: u32,
    },
}
