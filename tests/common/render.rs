//! Helpers shared by the rendering tests (`render*.rs`): one device per test binary, sRGB
//! expectations, a render-and-read-back helper and small scenes (re-exported names).
#![allow(unused_imports)]

pub use armlab::camera::{Camera, Preset, Projection};
pub use armlab::render::{Gpu, RenderError, RenderSettings, RenderTarget, Renderer, ViewUniforms};
pub use armlab::scene::{ArmStyle, Dot, Line, MeshInstance, Scene, Shape, arm_scene};
pub use image::RgbaImage;
pub use nalgebra::Point3;
pub use std::sync::{Mutex, MutexGuard, OnceLock};
pub use std::time::Instant;

/// One device for the whole test binary (opening lavapipe takes a while).
pub fn gpu() -> &'static Gpu {
    static GPU: OnceLock<Result<Gpu, String>> = OnceLock::new();
    match GPU.get_or_init(|| Gpu::new_headless().map_err(|e| e.to_string())) {
        Ok(gpu) => gpu,
        Err(message) => panic!("{message}"),
    }
}

/// Lavapipe already spreads one frame over every core: running the GPU tests one at a time
/// costs nothing and keeps the timing test's number meaningful.
pub fn serial() -> MutexGuard<'static, ()> {
    static LOCK: Mutex<()> = Mutex::new(());
    LOCK.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Linear [0, 1] -> sRGB byte, as the Rgba8UnormSrgb target stores it.
pub fn srgb(linear: f32) -> u8 {
    let c = linear.clamp(0.0, 1.0);
    let s = if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0).round() as u8
}

/// `srgb` of each channel.
pub fn srgb3(c: [f32; 3]) -> [u8; 3] {
    c.map(srgb)
}

/// Asserts the pixel at `p` (pixel coordinates, as from `Camera::project`) is `rgb` ± `tol`.
pub fn close(px: &image::Rgba<u8>, rgb: [u8; 3], tol: u8) -> bool {
    (0..3).all(|k| px.0[k].abs_diff(rgb[k]) <= tol)
}

#[track_caller]
pub fn assert_pixel(img: &RgbaImage, p: [f32; 2], rgb: [u8; 3], tol: u8, what: &str) {
    let (x, y) = (p[0].floor() as u32, p[1].floor() as u32);
    assert!(
        x < img.width() && y < img.height(),
        "{what}: pixel ({x}, {y}) outside the image"
    );
    let got = img.get_pixel(x, y).0;
    assert!(
        close(img.get_pixel(x, y), rgb, tol),
        "{what}: pixel ({x}, {y}) is {got:?}, expected {rgb:?} ± {tol}"
    );
}

/// `scene` rendered at `size` with `samples` per pixel and read back.
pub fn render(
    scene: &Scene,
    camera: &Camera,
    size: (u32, u32),
    samples: u32,
    settings: &RenderSettings,
) -> RgbaImage {
    let gpu = gpu();
    let mut renderer = Renderer::new(gpu, samples).expect("renderer");
    let target = RenderTarget::new(gpu, size.0, size.1, samples).expect("target");
    let view = ViewUniforms::from_camera(camera, size.0, size.1);
    renderer
        .render(gpu, &target, scene, &view, settings)
        .expect("render");
    let img = target.read_rgba(gpu).expect("read back");
    assert_eq!(img.dimensions(), size);
    img
}

/// `world_from_unit` of a box/sphere/cylinder scaled by `s` and placed at `p`.
pub fn placed(p: [f32; 3], s: [f32; 3]) -> [[f32; 4]; 4] {
    [
        [s[0], 0.0, 0.0, 0.0],
        [0.0, s[1], 0.0, 0.0],
        [0.0, 0.0, s[2], 0.0],
        [p[0], p[1], p[2], 1.0],
    ]
}

/// A `shape` scaled by `s`, placed at `p`, in `color`.
pub fn mesh(shape: Shape, p: [f32; 3], s: [f32; 3], color: [f32; 4]) -> MeshInstance {
    MeshInstance {
        shape,
        world_from_unit: placed(p, s),
        color,
    }
}

/// A camera looking at the origin from the front preset at `distance` (m).
pub fn front_camera(distance: f32) -> Camera {
    let mut c = Camera {
        target: Point3::origin(),
        distance,
        ..Camera::default()
    };
    c.set_preset(Preset::Front);
    c
}

/// The clear colour as stored in the sRGB target.
pub fn background(settings: &RenderSettings) -> [u8; 3] {
    srgb3([settings.clear[0], settings.clear[1], settings.clear[2]])
}

/// Test colours (linear RGBA).
pub const RED: [f32; 4] = [0.8, 0.05, 0.05, 1.0];
pub const BLUE: [f32; 4] = [0.05, 0.1, 0.8, 1.0];
pub const GREEN: [f32; 4] = [0.05, 0.6, 0.1, 1.0];
