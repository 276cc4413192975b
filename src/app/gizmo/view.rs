//! The camera's projection in f64 for the gizmo: pixels to world rays and back, and the size
//! of a pixel at a depth.

use super::{P3, V2, V3};
use crate::camera::{Camera, Projection};
use nalgebra::{Matrix4, Point3, Vector3, Vector4};

/// The world ray under a pixel (origin top-left, y down) of a `viewport_px` viewport: its origin
/// on the near plane and its unit direction. Works for both projections (orthographic rays are
/// parallel). Falls back to the camera's axis if the view-projection matrix is singular.
pub fn ray_from_pixel(
    camera: &Camera,
    viewport_px: [u32; 2],
    pixel: [f32; 2],
) -> (Point3<f64>, Vector3<f64>) {
    let eye = camera.eye().cast::<f64>();
    let fallback = (eye, (camera.target.cast::<f64>() - eye).normalize());
    View::new(camera, viewport_px)
        .and_then(|v| v.ray(px(pixel)))
        .unwrap_or(fallback)
}

/// Metres per pixel in the view plane at the depth of `point` (what one pixel of pointer motion
/// means there), or `None` if the point is behind the camera.
pub fn metres_per_pixel(
    camera: &Camera,
    viewport_px: [u32; 2],
    point: &Point3<f64>,
) -> Option<f64> {
    let view = View::new(camera, viewport_px)?;
    let (_, ey) = view.pixel_basis(point, view.project(point)?)?;
    Some(ey.norm())
}

pub(super) fn px(p: [f32; 2]) -> V2 {
    V2::new(p[0] as f64, p[1] as f64)
}

pub(super) fn dist_to_segment(p: V2, a: V2, b: V2) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(&ab) / ab.norm_squared().max(1e-300)).clamp(0.0, 1.0);
    (a + ab * t - p).norm()
}

pub(super) fn cross2(a: V2, b: V2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// The camera's view-projection in f64 with its inverse, for one viewport size.
pub(super) struct View {
    vp: Matrix4<f64>,
    inv: Matrix4<f64>,
    /// Viewport size (px).
    pub(super) size: V2,
    /// An orthographic projection (parallel rays).
    pub(super) ortho: bool,
}

impl View {
    pub(super) fn new(camera: &Camera, viewport_px: [u32; 2]) -> Option<Self> {
        let [w, h] = [viewport_px[0].max(1), viewport_px[1].max(1)];
        let vp = camera.view_proj(w, h).cast::<f64>();
        let inv = vp.try_inverse()?;
        let ortho = matches!(camera.projection, Projection::Orthographic { .. });
        let size = V2::new(w as f64, h as f64);
        Some(Self {
            vp,
            inv,
            size,
            ortho,
        })
    }

    /// Pixel of a world point, like [`Camera::project`].
    pub(super) fn project(&self, p: &P3) -> Option<V2> {
        let c = self.vp * p.to_homogeneous();
        let q = V2::new((c.x / c.w + 1.0) * 0.5, (1.0 - c.y / c.w) * 0.5).component_mul(&self.size);
        (c.w > 1e-9 && q.iter().all(|v| v.is_finite())).then_some(q)
    }

    /// World point at pixel `q` and normalised device depth `z`.
    pub(super) fn unproject(&self, q: V2, z: f64) -> Option<P3> {
        let (x, y) = (2.0 * q.x / self.size.x - 1.0, 1.0 - 2.0 * q.y / self.size.y);
        let h = self.inv * Vector4::new(x, y, z, 1.0);
        (h.w.abs() > 1e-300).then(|| P3::new(h.x / h.w, h.y / h.w, h.z / h.w))
    }

    /// Origin (near plane) and unit direction of the ray under pixel `q`.
    pub(super) fn ray(&self, q: V2) -> Option<(P3, V3)> {
        let near = self.unproject(q, 0.0)?;
        let dir = (self.unproject(q, 1.0)? - near).try_normalize(1e-300)?;
        Some((near, dir))
    }

    /// World vectors of one pixel right and one pixel down at the depth of `p` (projected at `c`).
    pub(super) fn pixel_basis(&self, p: &P3, c: V2) -> Option<(V3, V3)> {
        let clip = self.vp * p.to_homogeneous();
        let z = clip.z / clip.w;
        let o = self.unproject(c, z)?;
        let ex = self.unproject(c + V2::x(), z)? - o;
        let ey = self.unproject(c + V2::y(), z)? - o;
        (ex.iter().chain(ey.iter()).all(|v| v.is_finite())).then_some((ex, ey))
    }
}
