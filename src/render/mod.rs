//! The wgpu renderer: draws a [`Scene`](crate::scene::Scene) into a [`RenderTarget`] texture.
//!
//! It knows only the scene's f32 draw lists and f32 matrices: no UI toolkit, no kinematics.
//! The app shows the target's colour texture; the headless path reads it back to an image.
//! Both go through the same [`Renderer`], so the window and the PNG are the same pixels.
//!
//! - [`Gpu`]: a device and queue, opened headless (software Vulkan in tests) or handed in by
//!   the app ([`Gpu::from_parts`]).
//! - [`RenderTarget`]: colour (sRGB, [`COLOR_FORMAT`]), optional 4x MSAA, depth; read back with
//!   [`RenderTarget::read_rgba`].
//! - [`Renderer`]: instanced lit meshes (opaque, then translucent sorted back to front),
//!   screen-space lines and round dots; see [`Renderer::render`] for the draw order.
//!
//! Colours everywhere are linear RGBA; the sRGB target encodes them on write.
//!
//! How each kind is drawn:
//! - **Meshes**: the four unit shapes (48 segments around) are built once; instances carry
//!   `world_from_unit` and the inverse-transpose of its 3x3 part (computed on the CPU, so
//!   normals stay right under non-uniform scale). Back faces are culled; mirrored transforms
//!   use a clockwise-front pipeline. Opaque instances are drawn grouped by shape; instances
//!   with alpha < 1 afterwards, sorted back to front by the distance from the eye to their
//!   origin, alpha-blended with depth test on and depth write off.
//! - **Lines**: one instanced quad each, expanded to `width_px` in the vertex shader, with
//!   square caps and an anti-aliased edge. The segment is clipped to the near plane first, so a
//!   line with one end behind the camera draws its visible part.
//! - **Dots**: one instanced screen-space triangle each, made round (anti-aliased) in the
//!   fragment shader; dots behind the near plane are dropped.
//! - Lines and dots are depth-tested against the meshes, pulled towards the eye by
//!   [`RenderSettings::overlay_depth_bias`] of their distance so lines on a surface show.
//!   Opaque ones (alpha = 1) write depth and are drawn before translucent meshes; translucent
//!   ones are drawn last without depth writes.

mod buffer;
mod error;
mod gamma;
mod geometry;
mod gpu;
mod gpu_types;
mod instances;
mod pipelines;
mod readback;
mod renderer;
mod settings;
mod target;

pub use error::RenderError;
pub use gpu::Gpu;
pub use readback::{PendingRead, read_texture_rgba};
pub use renderer::Renderer;
pub use settings::{RenderSettings, ViewUniforms};
pub use target::RenderTarget;

/// Format of the colour texture a [`RenderTarget`] owns (sRGB-encoded 8-bit RGBA).
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

/// Format of the depth buffer.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// WGSL of the lit mesh pipeline.
pub const MESH_WGSL: &str = concat!(
    include_str!("../../shaders/frame.wgsl"),
    include_str!("../../shaders/mesh.wgsl")
);
/// WGSL of the screen-space line pipeline.
pub const LINE_WGSL: &str = concat!(
    include_str!("../../shaders/frame.wgsl"),
    include_str!("../../shaders/line.wgsl")
);
/// WGSL of the round dot pipeline.
pub const DOT_WGSL: &str = concat!(
    include_str!("../../shaders/frame.wgsl"),
    include_str!("../../shaders/dot.wgsl")
);

/// WGSL of the sRGB re-encoding copy ([`RenderTarget::egui_view`] where formats cannot alias).
pub const ENCODE_WGSL: &str = include_str!("../../shaders/encode.wgsl");

/// Every shader as (file name, source), for validation.
pub const SHADERS: &[(&str, &str)] = &[
    ("mesh.wgsl", MESH_WGSL),
    ("line.wgsl", LINE_WGSL),
    ("dot.wgsl", DOT_WGSL),
    ("encode.wgsl", ENCODE_WGSL),
];

/// Sample counts a [`Renderer`] and a [`RenderTarget`] accept.
pub const SAMPLE_COUNTS: [u32; 2] = [1, 4];
