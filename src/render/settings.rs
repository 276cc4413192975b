//! What a frame is seen from and lit with: [`ViewUniforms`], [`RenderSettings`], and their GPU
//! form.

use super::gpu_types::FrameUniforms;
use crate::camera::Camera;

/// Where the scene is seen from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewUniforms {
    /// `clip_from_world`, column-major, wgpu clip space (depth in [0, 1]).
    pub clip_from_world: [[f32; 4]; 4],
    /// Eye position (world, m): lighting and the back-to-front order of translucent meshes.
    pub eye: [f32; 3],
    /// Size of the target (px): line widths and dot sizes are measured against it. A zero or
    /// non-finite entry means "the target's size".
    pub viewport: [f32; 2],
}

impl ViewUniforms {
    /// The view of `camera` on a `width` x `height` pixel target.
    pub fn from_camera(camera: &Camera, width: u32, height: u32) -> Self {
        let m = camera.view_proj(width, height);
        let eye = camera.eye();
        Self {
            clip_from_world: std::array::from_fn(|c| std::array::from_fn(|r| m[(r, c)])),
            eye: [eye.x, eye.y, eye.z],
            viewport: [width as f32, height as f32],
        }
    }
}

/// Background and lighting. Light colours are white; intensities multiply the base colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderSettings {
    /// Background colour (linear RGBA). The default is a light grey-white that projects well.
    pub clear: [f32; 4],
    /// Ambient light on surfaces facing up (+z). Raising it flattens the shading; lowering it
    /// darkens faces the key light misses.
    pub ambient_sky: f32,
    /// Ambient light on surfaces facing down (-z); a bit below `ambient_sky` so up and down
    /// read differently.
    pub ambient_ground: f32,
    /// Direction towards the key light (world; need not be unit). Default: above, a little
    /// towards -y (the default camera's side).
    pub key_direction: [f32; 3],
    /// Key light intensity (Lambert). Higher gives more contrast between lit and unlit sides.
    pub key_intensity: f32,
    /// Light from the eye (Lambert on n·v): keeps every visible face readable from any view.
    pub headlight: f32,
    /// Strength of the key light's Blinn highlight (0 = matte).
    pub specular: f32,
    /// Blinn exponent: higher is a smaller, sharper highlight (clamped to >= 1).
    pub shininess: f32,
    /// Lines and dots are drawn as if moved this fraction of their distance towards the eye, so
    /// a line on a surface is not swallowed by it. Raising it lets lines show through thin
    /// objects; 0 gives plain depth testing.
    pub overlay_depth_bias: f32,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            clear: [0.86, 0.87, 0.89, 1.0],
            ambient_sky: 0.34,
            ambient_ground: 0.22,
            key_direction: [0.35, -0.45, 1.0],
            key_intensity: 0.5,
            headlight: 0.3,
            specular: 0.12,
            shininess: 40.0,
            overlay_depth_bias: 2e-3,
        }
    }
}

impl RenderSettings {
    /// No shading: every mesh shows its own colour exactly (flat figures, pixel tests).
    pub fn unlit() -> Self {
        Self {
            ambient_sky: 1.0,
            ambient_ground: 1.0,
            key_intensity: 0.0,
            headlight: 0.0,
            specular: 0.0,
            ..Self::default()
        }
    }
}

/// The frame uniforms for a target, view and settings.
pub(crate) fn frame_uniforms(
    target_size: (u32, u32),
    view: &ViewUniforms,
    s: &RenderSettings,
) -> FrameUniforms {
    let (w, h) = target_size;
    let vp = |given: f32, actual: u32| {
        if given.is_finite() && given > 0.0 {
            given
        } else {
            actual as f32
        }
    };
    let m = &view.clip_from_world;
    let e = view.eye;
    let eye_clip =
        std::array::from_fn(|r| m[0][r] * e[0] + m[1][r] * e[1] + m[2][r] * e[2] + m[3][r]);
    let k = s.key_direction;
    let len = (k[0] * k[0] + k[1] * k[1] + k[2] * k[2]).sqrt();
    let key = if len > 0.0 && len.is_finite() {
        k.map(|v| v / len)
    } else {
        [0.0, 0.0, 1.0]
    };
    FrameUniforms {
        clip_from_world: view.clip_from_world,
        eye: [e[0], e[1], e[2], 0.0],
        eye_clip,
        viewport: [
            vp(view.viewport[0], w),
            vp(view.viewport[1], h),
            s.overlay_depth_bias.clamp(0.0, 0.5),
            0.0,
        ],
        key_light: [key[0], key[1], key[2], s.key_intensity],
        ambient: [s.ambient_sky, s.ambient_ground, s.headlight, 0.0],
        specular: [s.specular, s.shininess.max(1.0), 0.0, 0.0],
    }
}
