//! The 3D viewport: the scene of the app (arm, ghost arms of every IK solution, target,
//! trail, workspace points) rendered by [`crate::render`] into a texture that egui shows, and
//! camera navigation. The same code draws live (eframe's device) and headlessly (screenshots).

use super::state::AppState;
use crate::camera::Camera;
use crate::render::{Gpu, RenderError, RenderSettings, RenderTarget, Renderer, ViewUniforms};
use crate::scene::{ArmStyle, Dot, Label, Line, Scene, arm_scene, robot_scale};
use egui::TextureId;

/// Multisampling of the viewport: 4x gives smooth edges on a projector; the live app drops to 1
/// when frames get slow (software rendering), see [`Viewport3d::set_msaa`].
pub const VIEWPORT_MSAA: u32 = 4;

/// Registers wgpu texture views with whichever egui renderer shows them.
pub trait TextureRegistry {
    /// Registers `view` (format `Rgba8Unorm`) as a new egui texture.
    fn register(&mut self, device: &wgpu::Device, view: &wgpu::TextureView) -> TextureId;
    /// Points an existing id at a new view (after a resize).
    fn update(&mut self, device: &wgpu::Device, view: &wgpu::TextureView, id: TextureId);
}

impl TextureRegistry for egui_wgpu::Renderer {
    fn register(&mut self, device: &wgpu::Device, view: &wgpu::TextureView) -> TextureId {
        self.register_native_texture(device, view, wgpu::FilterMode::Linear)
    }
    fn update(&mut self, device: &wgpu::Device, view: &wgpu::TextureView, id: TextureId) {
        self.update_egui_texture_from_wgpu_texture(device, view, wgpu::FilterMode::Linear, id);
    }
}

/// The GPU side of the viewport: our renderer and the target it draws into.
pub struct Viewport3d {
    gpu: Gpu,
    renderer: Renderer,
    target: Option<(RenderTarget, TextureId)>,
    msaa: u32,
    stale_id: Option<TextureId>,
}

impl Viewport3d {
    /// A viewport on a device (eframe's, or a headless one).
    pub fn new(gpu: Gpu) -> Result<Self, RenderError> {
        Self::with_msaa(gpu, VIEWPORT_MSAA)
    }

    /// A viewport with `msaa` samples per pixel (1 or 4).
    pub fn with_msaa(gpu: Gpu, msaa: u32) -> Result<Self, RenderError> {
        let renderer = Renderer::new(&gpu, msaa)?;
        Ok(Self {
            gpu,
            renderer,
            target: None,
            msaa,
            stale_id: None,
        })
    }

    /// Samples per pixel.
    pub fn msaa(&self) -> u32 {
        self.msaa
    }

    /// Changes the multisampling (rebuilds the pipelines; the next render rebuilds the target
    /// and keeps its egui texture id).
    pub fn set_msaa(&mut self, msaa: u32) -> Result<(), RenderError> {
        if msaa != self.msaa {
            self.renderer = Renderer::new(&self.gpu, msaa)?;
            self.msaa = msaa;
            if let Some((_, id)) = self.target.take() {
                self.stale_id = Some(id);
            }
        }
        Ok(())
    }

    /// The device.
    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }

    /// Renders `scene` at `size` pixels and returns the egui texture showing it.
    pub fn render(
        &mut self,
        registry: &mut dyn TextureRegistry,
        scene: &Scene,
        camera: &Camera,
        size: [u32; 2],
        dark: bool,
    ) -> Result<TextureId, RenderError> {
        let [w, h] = [size[0].max(16), size[1].max(16)];
        let stale = self.target.as_ref().is_none_or(|(t, _)| t.size() != (w, h));
        if stale {
            let target = RenderTarget::new(&self.gpu, w, h, self.msaa)?;
            let id = match self
                .target
                .take()
                .map(|(_, id)| id)
                .or(self.stale_id.take())
            {
                Some(id) => {
                    registry.update(&self.gpu.device, &target.egui_view(), id);
                    id
                }
                None => registry.register(&self.gpu.device, &target.egui_view()),
            };
            self.target = Some((target, id));
        }
        let Some((target, id)) = &self.target else {
            unreachable!("target just created")
        };
        let mut settings = RenderSettings::default();
        if dark {
            settings.clear = [0.015, 0.017, 0.02, 1.0];
        }
        self.renderer.render(
            &self.gpu,
            target,
            scene,
            &ViewUniforms::from_camera(camera, w, h),
            &settings,
        )?;
        Ok(*id)
    }
}

/// The app's 3D scene for the current state: the arm, ghosts of the other solutions labelled
/// with their posture (greyed when outside the limits), the targets, trails and workspace dots.
pub fn build_scene(state: &AppState, workspace: Option<&[Dot]>, projector: bool) -> Scene {
    let robot = state.robot();
    let d = state.display;
    let style = ArmStyle {
        frames: d.frames,
        frame_labels: d.labels,
        grid: d.grid,
        ..ArmStyle::default()
    };
    let mut scene = arm_scene(robot, state.q(), &style).unwrap_or_default();
    if projector {
        for l in &mut scene.lines {
            l.width_px *= 1.6;
        }
    }
    let scale = robot_scale(robot) as f32;
    for (ee, target) in state.targets().iter().enumerate() {
        if d.ghosts {
            for g in state.ghosts(ee) {
                if g.selected {
                    continue;
                }
                let mut ghost = ArmStyle {
                    frames: false,
                    frame_labels: false,
                    grid: false,
                    alpha: 0.28,
                    ..ArmStyle::default()
                };
                if !g.within_limits {
                    let grey = [0.55, 0.55, 0.57, 1.0];
                    ghost = ArmStyle {
                        link: grey,
                        revolute: grey,
                        prismatic: grey,
                        tool: grey,
                        alpha: 0.18,
                        ..ghost
                    };
                }
                if let Ok(s) = arm_scene(robot, &g.q, &ghost) {
                    scene.meshes.extend(s.meshes);
                    // Label at the elbow (the middle joint frame), where the postures differ.
                    let frames = robot.fk_frames(&g.q).unwrap_or_default();
                    let chain = robot.chain_to(robot.end_effectors()[ee].parent);
                    if let Some(f) = chain
                        .get(chain.len().saturating_sub(1) / 2)
                        .and_then(|&j| frames.get(j))
                    {
                        let p = f.translation.vector;
                        let text = if g.within_limits {
                            g.posture.clone()
                        } else {
                            format!("{} (outside limits)", g.posture)
                        };
                        scene.labels.push(Label {
                            p: [p.x as f32, p.y as f32, p.z as f32 + scale * 0.06],
                            text,
                            color: [0.25, 0.25, 0.3, 1.0],
                        });
                    }
                }
            }
        }
        merge_close_labels(&mut scene.labels, scale * 0.02);
        // The target: a small triad and a dot, red when unreachable.
        let t = &target.world_from_tool;
        let o = t.translation.vector;
        let o32 = [o.x as f32, o.y as f32, o.z as f32];
        let color = if target.reach.is_reached() {
            [0.1, 0.1, 0.12, 1.0]
        } else {
            [0.9, 0.1, 0.1, 1.0]
        };
        scene.dots.push(Dot {
            p: o32,
            color,
            size_px: if projector { 16.0 } else { 11.0 },
        });
        for k in 0..3 {
            let a = t.rotation * nalgebra::Vector3::ith(k, 1.0) * (scale as f64 * 0.08);
            scene.lines.push(Line {
                a: o32,
                b: [
                    o32[0] + a.x as f32,
                    o32[1] + a.y as f32,
                    o32[2] + a.z as f32,
                ],
                color: crate::scene::AXIS_COLORS[k],
                width_px: 2.0,
            });
        }
        if d.trail
            && let Some(trail) = state.trail(ee)
        {
            let pts: Vec<[f32; 3]> = trail
                .iter()
                .map(|p| [p.x as f32, p.y as f32, p.z as f32])
                .collect();
            for w in pts.windows(2) {
                scene.lines.push(Line {
                    a: w[0],
                    b: w[1],
                    color: [0.55, 0.2, 0.75, 1.0],
                    width_px: 2.0,
                });
            }
        }
    }
    if d.workspace
        && let Some(dots) = workspace
    {
        scene.dots.extend_from_slice(dots);
    }
    scene
}

/// Ghost labels that fall on the same spot (postures differing only at the wrist share an elbow)
/// become one label with a line per posture.
fn merge_close_labels(labels: &mut Vec<Label>, tol: f32) {
    let mut out: Vec<Label> = Vec::with_capacity(labels.len());
    for l in labels.drain(..) {
        let near = out.iter_mut().find(|o| {
            let d: f32 = o.p.iter().zip(&l.p).map(|(a, b)| (a - b) * (a - b)).sum();
            d.sqrt() < tol && o.color == l.color
        });
        match near {
            Some(o) => {
                o.text.push('\n');
                o.text.push_str(&l.text);
            }
            None => out.push(l),
        }
    }
    *labels = out;
}
