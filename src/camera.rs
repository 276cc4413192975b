//! An orbit camera in f32 (no GPU, no UI types): view and projection matrices for wgpu's clip
//! space (depth in [0, 1]), preset views, fitting a bounding sphere, and projecting world points
//! to pixels (used for labels, picking and tests). World frame: z up, metres.

use nalgebra::{Matrix4, Point3, Vector3, Vector4};

/// Perspective or orthographic projection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Projection {
    /// Perspective with vertical field of view `fov_y` (rad).
    Perspective {
        /// Vertical field of view (rad).
        fov_y: f32,
    },
    /// Orthographic: `height` metres of the world fill the view vertically.
    Orthographic {
        /// Visible height (m).
        height: f32,
    },
}

/// Named viewpoints.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Preset {
    /// From +z looking down: x to the right, y up on screen.
    Top,
    /// From -y looking along +y: x to the right, z up (the x-z plane, a data sheet's side view).
    Front,
    /// From +x looking along -x: y to the right, z up.
    Side,
    /// Isometric-like view from (+x, -y, +z).
    Iso,
}

/// An orbit camera looking at `target` from `distance` at azimuth `yaw` (rad, from +x towards
/// +y) and elevation `pitch` (rad, positive above the x-y plane).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Point looked at (world, m).
    pub target: Point3<f32>,
    /// Distance from the target (m).
    pub distance: f32,
    /// Azimuth of the eye around z (rad).
    pub yaw: f32,
    /// Elevation of the eye (rad), within (-pi/2, pi/2).
    pub pitch: f32,
    /// Projection.
    pub projection: Projection,
}

/// Near/far planes relative to the distance.
const NEAR_FACTOR: f32 = 0.01;
const FAR_FACTOR: f32 = 20.0;
/// Largest elevation; exactly pi/2 makes the up vector degenerate.
const MAX_PITCH: f32 = std::f32::consts::FRAC_PI_2 - 1e-4;

impl Camera {
    /// The perspective view's vertical field of view (rad): 35 degrees.
    pub fn default_fov() -> f32 {
        35f32.to_radians()
    }
}

impl Default for Camera {
    fn default() -> Self {
        let mut c = Self {
            target: Point3::new(0.0, 0.0, 0.3),
            distance: 3.0,
            yaw: 0.0,
            pitch: 0.0,
            projection: Projection::Perspective {
                fov_y: 35f32.to_radians(),
            },
        };
        c.set_preset(Preset::Iso);
        c
    }
}

/// wgpu clip space has depth in [0, 1]; nalgebra's projections are OpenGL's [-1, 1].
fn gl_to_wgpu() -> Matrix4<f32> {
    Matrix4::new(
        1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.5, 0.5, 0.0, 0.0, 0.0, 1.0,
    )
}

impl Camera {
    /// Sets the viewpoint to a preset (keeps target and distance).
    pub fn set_preset(&mut self, p: Preset) {
        let (yaw, pitch) = match p {
            Preset::Top => (-std::f32::consts::FRAC_PI_2, MAX_PITCH),
            Preset::Front => (-std::f32::consts::FRAC_PI_2, 0.0),
            Preset::Side => (0.0, 0.0),
            Preset::Iso => (-std::f32::consts::FRAC_PI_4 * 0.75, 0.45),
        };
        self.yaw = yaw;
        self.pitch = pitch;
    }

    /// Eye position (world, m).
    pub fn eye(&self) -> Point3<f32> {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        self.target + Vector3::new(cp * cy, cp * sy, sp) * self.distance
    }

    /// `view_from_world`.
    pub fn view(&self) -> Matrix4<f32> {
        let eye = self.eye();
        // Looking straight down, "up" on screen is the direction of the yaw.
        let up = if self.pitch.abs() > 1.5 {
            let (sy, cy) = self.yaw.sin_cos();
            -Vector3::new(cy, sy, 0.0) * self.pitch.signum()
        } else {
            Vector3::z()
        };
        Matrix4::look_at_rh(&eye, &self.target, &up)
    }

    /// `clip_from_view` for an aspect ratio width / height.
    pub fn proj(&self, aspect: f32) -> Matrix4<f32> {
        let near = self.distance * NEAR_FACTOR;
        let far = self.distance * FAR_FACTOR;
        let m = match self.projection {
            Projection::Perspective { fov_y } => Matrix4::new_perspective(aspect, fov_y, near, far),
            Projection::Orthographic { height } => {
                let h = height * 0.5;
                let w = h * aspect;
                Matrix4::new_orthographic(-w, w, -h, h, near, far)
            }
        };
        gl_to_wgpu() * m
    }

    /// `clip_from_world` for a viewport of `width` x `height` pixels.
    pub fn view_proj(&self, width: u32, height: u32) -> Matrix4<f32> {
        self.proj(width as f32 / height.max(1) as f32) * self.view()
    }

    /// Pixel coordinates (x right, y down, origin top-left) of a world point, or `None` if it is
    /// behind the camera.
    pub fn project(&self, p: &Point3<f32>, width: u32, height: u32) -> Option<[f32; 2]> {
        let clip = self.view_proj(width, height) * Vector4::new(p.x, p.y, p.z, 1.0);
        if clip.w <= 1e-9 {
            return None;
        }
        let (x, y) = (clip.x / clip.w, clip.y / clip.w);
        Some([
            (x + 1.0) * 0.5 * width as f32,
            (1.0 - y) * 0.5 * height as f32,
        ])
    }

    /// Frames a bounding sphere (centre, radius in m) so it fills the view with a margin.
    pub fn fit(&mut self, center: Point3<f32>, radius: f32, aspect: f32) {
        let r = radius.max(1e-3) * 1.1;
        self.target = center;
        match &mut self.projection {
            Projection::Perspective { fov_y } => {
                let half = (*fov_y * 0.5).min((*fov_y * 0.5).tan().atan2(1.0 / aspect.max(1e-3)));
                self.distance = r / half.sin();
            }
            Projection::Orthographic { height } => {
                *height = 2.0 * r / aspect.min(1.0);
                self.distance = 3.0 * r;
            }
        }
    }

    /// Frames a set of points tightly: after [`Self::fit`] on their bounding sphere, moves the
    /// target to the centre of their projection and scales the distance (or orthographic height)
    /// so they fill `fill` (e.g. 0.8) of the view. A few fixed-point iterations, deterministic.
    pub fn fit_points(&mut self, points: &[Point3<f32>], width: u32, height: u32, fill: f32) {
        if points.is_empty() {
            return;
        }
        let (mut lo, mut hi) = (points[0], points[0]);
        for p in points {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        let c = nalgebra::center(&lo, &hi);
        let r = points.iter().map(|p| (p - c).norm()).fold(0.0, f32::max);
        self.fit(c, r, width as f32 / height.max(1) as f32);
        for _ in 0..4 {
            let vp = self.view_proj(width, height);
            let (mut nlo, mut nhi) = ([f32::MAX; 2], [f32::MIN; 2]);
            for p in points {
                let clip = vp * Vector4::new(p.x, p.y, p.z, 1.0);
                if clip.w <= 1e-6 {
                    return;
                }
                for k in 0..2 {
                    let v = clip[k] / clip.w;
                    nlo[k] = nlo[k].min(v);
                    nhi[k] = nhi[k].max(v);
                }
            }
            let extent = ((nhi[0] - nlo[0]) * 0.5)
                .max((nhi[1] - nlo[1]) * 0.5)
                .max(1e-4);
            // Re-centre: the NDC centre offset, as a pan by fractions of the view height.
            let aspect = width as f32 / height.max(1) as f32;
            let (cx, cy) = ((nhi[0] + nlo[0]) * 0.5, (nhi[1] + nlo[1]) * 0.5);
            self.pan(-cx * aspect * 0.5, cy * 0.5);
            self.zoom(extent / fill);
        }
    }

    /// Orbits by mouse-like deltas (rad).
    pub fn orbit(&mut self, d_yaw: f32, d_pitch: f32) {
        self.yaw += d_yaw;
        self.pitch = (self.pitch + d_pitch).clamp(-MAX_PITCH, MAX_PITCH);
    }

    /// Zooms by a factor (> 1 moves away).
    pub fn zoom(&mut self, factor: f32) {
        self.distance = (self.distance * factor).clamp(1e-3, 1e4);
        if let Projection::Orthographic { height } = &mut self.projection {
            *height = (*height * factor).clamp(1e-3, 1e4);
        }
    }

    /// Pans the target in the view plane by a fraction of the visible height.
    pub fn pan(&mut self, dx: f32, dy: f32) {
        let v = self.view();
        let right = Vector3::new(v[(0, 0)], v[(0, 1)], v[(0, 2)]);
        let up = Vector3::new(v[(1, 0)], v[(1, 1)], v[(1, 2)]);
        let scale = match self.projection {
            Projection::Perspective { fov_y } => 2.0 * self.distance * (fov_y * 0.5).tan(),
            Projection::Orthographic { height } => height,
        };
        self.target += (right * -dx + up * dy) * scale;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn target_projects_to_the_centre_and_presets_orient_axes() {
        for preset in [Preset::Top, Preset::Front, Preset::Side, Preset::Iso] {
            let mut c = Camera::default();
            c.set_preset(preset);
            let p = c.project(&c.target, 800, 600).unwrap();
            assert!(
                (p[0] - 400.0).abs() < 1e-3 && (p[1] - 300.0).abs() < 1e-3,
                "{preset:?}"
            );
        }
        let mut c = Camera {
            target: Point3::origin(),
            ..Default::default()
        };
        c.set_preset(Preset::Front);
        let x = c.project(&Point3::new(0.1, 0.0, 0.0), 800, 600).unwrap();
        let z = c.project(&Point3::new(0.0, 0.0, 0.1), 800, 600).unwrap();
        assert!(
            x[0] > 400.0 && (x[1] - 300.0).abs() < 1e-3,
            "x to the right"
        );
        assert!(z[1] < 300.0, "z up");
        c.set_preset(Preset::Top);
        let y = c.project(&Point3::new(0.0, 0.1, 0.0), 800, 600).unwrap();
        let x = c.project(&Point3::new(0.1, 0.0, 0.0), 800, 600).unwrap();
        assert!(y[1] < 300.0 && x[0] > 400.0, "top: y up, x right");
    }
}
