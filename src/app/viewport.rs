//! The 3D viewport: the scene of the app (arm, ghost arms of every IK solution, target,
//! trail, workspace points) rendered by [`crate::render`] into a texture that egui shows, and
//! camera navigation. The same code draws live (eframe's device) and headlessly (screenshots).

use super::state::{AppState, Ghost};
use crate::camera::Camera;
use crate::render::{Gpu, RenderError, RenderSettings, RenderTarget, Renderer, ViewUniforms};
use crate::scene::{ArmStyle, Dot, Label, Line, Scene, arm_scene, point32};
use egui::TextureId;

/// Multisampling of the viewport: 4x gives smooth edges on a projector. On a software
/// rasterizer the live app draws moving frames at 1x and the still frame at this count (see
/// [`Viewport3d::adaptive`]).
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

impl TextureRegistry for crate::ui_render::painter::UiPainter {
    fn register(&mut self, device: &wgpu::Device, view: &wgpu::TextureView) -> TextureId {
        self.register_native(device, view)
    }
    fn update(&mut self, device: &wgpu::Device, view: &wgpu::TextureView, id: TextureId) {
        self.update_native(device, view, id)
    }
}

/// The 3D view of one frame, ready to be shown by egui.
#[derive(Debug, Clone)]
pub struct ViewportImage {
    /// The texture as an egui image.
    pub id: TextureId,
    /// The texture itself (`Rgba8Unorm`, gamma-encoded, the viewport's size in pixels).
    pub view: wgpu::TextureView,
    /// Drawn at the fast quality while the scene moves: repaint once more when it stops, and
    /// the still frame comes at full quality.
    pub refine: bool,
}

/// A renderer at one sample count and the target it draws into.
struct Layer {
    renderer: Renderer,
    target: Option<RenderTarget>,
}

impl Layer {
    fn new(gpu: &Gpu, msaa: u32) -> Result<Self, RenderError> {
        Ok(Self {
            renderer: Renderer::new(gpu, msaa)?,
            target: None,
        })
    }

    /// Draws into the target (made, or remade at a new size, first); returns its egui view.
    fn draw(
        &mut self,
        gpu: &Gpu,
        size: [u32; 2],
        scene: &Scene,
        view: &ViewUniforms,
        settings: &RenderSettings,
    ) -> Result<wgpu::TextureView, RenderError> {
        let [w, h] = size;
        let target = match self.target.take() {
            Some(t) if t.size() == (w, h) => t,
            _ => RenderTarget::new(gpu, w, h, self.renderer.sample_count())?,
        };
        let target = self.target.insert(target);
        self.renderer.render(gpu, target, scene, view, settings)?;
        Ok(target.egui_view())
    }
}

/// The GPU side of the viewport: our renderer and the target it draws into.
///
/// A frame whose scene, camera, size and background equal the last one's is not drawn again.
pub struct Viewport3d {
    gpu: Gpu,
    /// Renders at the full sample count.
    full: Layer,
    /// Renders at 1x while the scene moves (adaptive mode only).
    fast: Option<Layer>,
    /// The egui id of the texture shown last.
    id: Option<TextureId>,
    /// Fingerprint of what the shown texture holds and whether it is the full-quality frame.
    shown: Option<(u64, bool)>,
    /// The image returned last.
    image: Option<ViewportImage>,
    /// Frames drawn so far (not counting those served from the last image).
    draws: u64,
}

impl Viewport3d {
    /// A viewport on a device (eframe's, or a headless one), always at [`VIEWPORT_MSAA`].
    pub fn new(gpu: Gpu) -> Result<Self, RenderError> {
        Self::with_msaa(gpu, VIEWPORT_MSAA)
    }

    /// A viewport with `msaa` samples per pixel (1 or 4).
    pub fn with_msaa(gpu: Gpu, msaa: u32) -> Result<Self, RenderError> {
        let full = Layer::new(&gpu, msaa)?;
        Ok(Self {
            gpu,
            full,
            fast: None,
            id: None,
            shown: None,
            image: None,
            draws: 0,
        })
    }

    /// The live app's viewport: on a software rasterizer (a CPU adapter) frames drawn while
    /// the scene moves use 1x multisampling and the frame after it stops uses
    /// [`VIEWPORT_MSAA`] (see [`ViewportImage::refine`]); on a GPU every frame is full quality.
    pub fn adaptive(gpu: Gpu) -> Result<Self, RenderError> {
        let cpu = gpu.adapter_info.device_type == wgpu::DeviceType::Cpu;
        let mut vp = Self::new(gpu)?;
        if cpu && VIEWPORT_MSAA > 1 {
            vp.fast = Some(Layer::new(&vp.gpu, 1)?);
        }
        Ok(vp)
    }

    /// Samples per pixel of the full-quality frames.
    pub fn msaa(&self) -> u32 {
        self.full.renderer.sample_count()
    }

    /// The device.
    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }

    /// How many frames were drawn (a frame equal to the one shown is not drawn again).
    pub fn draws(&self) -> u64 {
        self.draws
    }

    /// Renders `scene` at `size` pixels (unless the same frame is shown already) and returns
    /// the image showing it.
    pub fn render(
        &mut self,
        registry: &mut dyn TextureRegistry,
        scene: &Scene,
        camera: &Camera,
        size: [u32; 2],
        dark: bool,
    ) -> Result<ViewportImage, RenderError> {
        let [w, h] = [size[0].max(16), size[1].max(16)];
        let view = ViewUniforms::from_camera(camera, w, h);
        let key = fingerprint(scene, &view, dark, [w, h]);
        let same = self.shown.is_some_and(|(k, _)| k == key);
        if let (true, Some((_, true)), Some(image)) = (same, self.shown, &self.image) {
            return Ok(image.clone());
        }
        // Moving (or first) frame: the fast layer if there is one; a still frame: full.
        let fast = !same && self.fast.is_some();
        let layer = match (&mut self.fast, fast) {
            (Some(l), true) => l,
            _ => &mut self.full,
        };
        let mut settings = RenderSettings::default();
        if dark {
            settings.clear = [0.015, 0.017, 0.02, 1.0];
        }
        // Moving frames on a software rasterizer draw a URDF's meshes coarse (the still frame
        // after them is full).
        let coarse = if fast {
            scene.with_coarse_meshes()
        } else {
            None
        };
        let texture_view = layer.draw(
            &self.gpu,
            [w, h],
            coarse.as_ref().unwrap_or(scene),
            &view,
            &settings,
        )?;
        self.draws += 1;
        let id = match self.id {
            Some(id) => {
                if self.image.as_ref().is_none_or(|i| i.view != texture_view) {
                    registry.update(&self.gpu.device, &texture_view, id);
                }
                id
            }
            None => registry.register(&self.gpu.device, &texture_view),
        };
        self.id = Some(id);
        self.shown = Some((key, !fast));
        let image = ViewportImage {
            id,
            view: texture_view,
            refine: fast,
        };
        self.image = Some(image.clone());
        Ok(image)
    }
}

/// Link meshes of a ghost, each left out where the arm's or an earlier ghost's mesh already is
/// (none today: ghosts are drawn with the joints' bodies).
fn add_new_meshes(scene: &mut Scene, meshes: Vec<crate::scene::CustomMesh>, tol: f32) {
    for m in meshes {
        let same = |o: &crate::scene::CustomMesh| {
            o.world_from_mesh
                .iter()
                .flatten()
                .zip(m.world_from_mesh.iter().flatten())
                .all(|(a, b)| (a - b).abs() <= tol)
        };
        if !scene.custom_meshes.iter().any(same) {
            scene.custom_meshes.push(m);
        }
    }
}

/// A 64-bit fingerprint of everything a viewport frame depends on (FNV-1a over the bits).
fn fingerprint(scene: &Scene, view: &ViewUniforms, dark: bool, size: [u32; 2]) -> u64 {
    struct Fnv(u64);
    impl Fnv {
        fn u32(&mut self, v: u32) {
            self.0 = (self.0 ^ v as u64).wrapping_mul(0x0100_0000_01b3);
        }
        fn f(&mut self, v: &[f32]) {
            v.iter().for_each(|x| self.u32(x.to_bits()));
        }
    }
    let mut h = Fnv(0xcbf2_9ce4_8422_2325);
    h.u32(size[0]);
    h.u32(size[1]);
    h.u32(dark as u32);
    view.clip_from_world.iter().for_each(|c| h.f(c));
    h.f(&view.eye);
    h.f(&view.viewport);
    h.u32(scene.meshes.len() as u32);
    for m in &scene.meshes {
        h.u32(m.shape as u32);
        m.world_from_unit.iter().for_each(|c| h.f(c));
        h.f(&m.color);
    }
    h.u32(scene.custom_meshes.len() as u32);
    for m in &scene.custom_meshes {
        let id = std::sync::Arc::as_ptr(&m.mesh) as usize as u64;
        h.u32(id as u32);
        h.u32((id >> 32) as u32);
        m.world_from_mesh.iter().for_each(|c| h.f(c));
        h.f(&m.color);
    }
    h.u32(scene.lines.len() as u32);
    for l in &scene.lines {
        h.f(&l.a);
        h.f(&l.b);
        h.f(&l.color);
        h.f(&[l.width_px]);
    }
    for dots in [&scene.dots, &scene.underlay] {
        h.u32(dots.len() as u32);
        for d in dots {
            h.f(&d.p);
            h.f(&d.color);
            h.f(&[d.size_px]);
        }
    }
    h.0
}

/// Most measured poses drawn as ghost arms (the others as tool points only): translucent arms
/// cost fill on a software rasterizer.
pub const MAX_POSE_GHOSTS: usize = 12;

/// Adds the measured poses of a calibration to `scene`: every tool point as a dot, and up to
/// [`MAX_POSE_GHOSTS`] of them, evenly chosen, as faint ghost arms.
pub fn add_measured_poses(scene: &mut Scene, robot: &crate::kinematics::Robot, poses: &[Vec<f64>]) {
    let ghost = ArmStyle {
        frames: false,
        frame_labels: false,
        grid: false,
        alpha: 0.12,
        ..ArmStyle::default()
    };
    let every = poses.len().div_ceil(MAX_POSE_GHOSTS).max(1);
    for (k, q) in poses.iter().enumerate() {
        let Ok(t) = robot.fk(q) else { continue };
        let p = crate::scene::point32(&t.translation.vector);
        scene.dots.push(Dot {
            p: [p.x, p.y, p.z],
            color: [0.85, 0.35, 0.0, 1.0],
            size_px: 6.0,
        });
        if k % every == 0
            && let Ok(s) = arm_scene(robot, q, &ghost)
        {
            scene.meshes.extend(s.meshes);
            scene.custom_meshes.extend(s.custom_meshes);
        }
    }
}

/// The whole 3D scene of the window: [`build_scene`], what every tab and the right panel
/// add over it, and the self-motion's path of `ee`.
pub fn scene_of(
    state: &mut AppState,
    (tabs, ik): (&super::tabs::Tabs, &mut super::panels::ik::IkPanel),
    ee: usize,
    projector: bool,
) -> Scene {
    let mut scene = build_scene(state, ee, projector);
    tabs.decorate(state, &mut scene);
    ik.decorate(state, ee, &mut scene);
    add_self_motion_of(&mut scene, state, ee);
    scene
}

/// The app's 3D scene for the current state: the arm, ghosts of the other solutions labelled
/// with their posture (greyed when outside the limits), the targets and trails (the tabs add
/// their overlays: the workspace dots, the measured poses). `ee` is the end-effector the IK
/// panel drives: on a tree, only its chain's frames are labelled unless every label is asked for.
pub fn build_scene(state: &AppState, ee: usize, projector: bool) -> Scene {
    let robot = state.robot();
    let d = state.display;
    // A dh-table sheet hides the joints' frames (they are its answer): only frames 0 and n,
    // as the sheet's figure draws them.
    let hide_dh = state.hidden.dh_table;
    let style = ArmStyle {
        frames: d.frames && !hide_dh,
        frame_labels: d.labels && !hide_dh,
        grid: d.grid,
        ..ArmStyle::default()
    };
    let mut scene = arm_scene(robot, state.q(), &style).unwrap_or_default();
    if hide_dh && let Ok(tool) = robot.fk(state.q()) {
        let len = 0.18 * robot.characteristic_length().max(0.1);
        crate::scene::frame_triad(&mut scene, &robot.base, "0", len);
        crate::scene::frame_triad(&mut scene, &tool, &robot.dof().to_string(), len);
    }
    if !d.all_labels && robot.end_effectors().len() > 1 {
        crate::scene::label_driven_chain_only(&mut scene, robot, ee);
    }
    if projector {
        for l in &mut scene.lines {
            l.width_px *= 1.6;
        }
    }
    let scale = robot.longest_chain_length() as f32;
    add_cell(&mut scene, state, scale);
    // One IK target per arm (its tool), and the chosen end-effector's: not one on each of the
    // dozens of frames a robot description names.
    let tools = state.ee_catalog().tools();
    let shown = |k: usize| k == ee || tools.is_empty() || tools.contains(&k);
    for (ee, target) in state
        .targets()
        .iter()
        .enumerate()
        .filter(|(k, _)| shown(*k))
    {
        if d.ghosts {
            for g in state.ghosts(ee) {
                if !g.selected {
                    add_ghost(&mut scene, robot, &g, ee, true);
                }
            }
        }
        merge_close_labels(&mut scene.labels, scale * 0.02);
        add_target(&mut scene, target, scale, projector);
        if d.trail
            && let Some(trail) = state.trail(ee)
        {
            let pts: Vec<[f32; 3]> = trail.iter().map(|t| point32(&t.p).into()).collect();
            // No line across a jump (a reset, a typed value).
            for (k, w) in pts.windows(2).enumerate() {
                if trail[k + 1].after_jump {
                    continue;
                }
                scene.lines.push(Line {
                    a: w[0],
                    b: w[1],
                    color: [0.55, 0.2, 0.75, 1.0],
                    width_px: 2.0,
                });
            }
        }
    }
    scene
}

/// The colour of a posture in collision: its ghost, its contact points, the pair's name.
pub const COLLISION_RED: [f32; 4] = [0.88, 0.1, 0.08, 1.0];
/// The obstacles' colour in the 3D view: translucent grey (the arm inside stays visible).
pub const OBSTACLE_GREY: [f32; 4] = [0.52, 0.54, 0.58, 0.4];
/// The colour of a plane (a floor, a wall of infinite extent): opaque light grey.
pub const FLOOR_GREY: [f32; 4] = [0.74, 0.75, 0.77, 1.0];
/// The colour of the selected obstacle (the one the gizmo moves).
pub const OBSTACLE_SELECTED: [f32; 4] = [0.3, 0.5, 0.85, 0.5];
/// The colour of a contact's name ("link3 hits table, 12 mm"): the 3D view places these
/// labels first (see [`super::tabs::view3d::View3d::paint`]).
pub const CONTACT_LABEL: [f32; 4] = [0.75, 0.05, 0.05, 1.0];
/// Most contacts named at one posture (the deepest; every contact gets its dot).
const CONTACTS_NAMED: usize = 3;

/// The cell's obstacles (translucent grey, the selected one blue), and where the arm is in
/// collision its contacts, marked and named.
fn add_cell(scene: &mut Scene, state: &AppState, scale: f32) {
    let Some(cell) = state.cell_scene() else {
        return;
    };
    use crate::scene::obstacles::{ObstacleStyle, add_obstacle};
    let l = f64::from(scale);
    let grey = ObstacleStyle {
        color: OBSTACLE_GREY,
        plane_half_size: 0.6 * l,
        plane_thickness: 0.004 * l,
        labels: true,
    };
    let selected = state.selected_obstacle();
    for (k, (o, pose)) in cell
        .obstacles
        .iter()
        .zip(state.obstacle_poses())
        .enumerate()
    {
        let color = match (selected == Some(k), &o.shape) {
            (true, _) => OBSTACLE_SELECTED,
            // A floor is opaque: nothing is under it, and a translucent square the size of the
            // view costs a software rasterizer a blend per pixel every frame.
            (false, crate::collision::ObstacleShape::Plane) => FLOOR_GREY,
            (false, _) => OBSTACLE_GREY,
        };
        let style = ObstacleStyle { color, ..grey };
        add_obstacle(scene, o, &pose, &style);
    }
    if let Some(r) = state.arm_collision() {
        add_contacts(scene, r, scale);
    }
}

/// Marks the contacts of `report` (a red dot in a translucent red ball at each) and names the
/// deepest pairs next to them ("link3 hits table, 12 mm"; the label placer leaves a name out
/// where it finds no room, e.g. under the gizmo).
fn add_contacts(scene: &mut Scene, report: &crate::collision::CollisionReport, scale: f32) {
    // A translucent red ball around each contact (twice a link's radius): the point itself
    // lies inside the link and the obstacle, where a dot alone would be hidden.
    let r = 2.0 * crate::kinematics::visual::LINK_RADIUS_FRACTION as f32 * scale;
    for (k, c) in report.pairs.iter().enumerate() {
        let p = c.at.map(|v| v as f32);
        scene.dots.push(Dot {
            p,
            color: COLLISION_RED,
            size_px: 9.0,
        });
        scene.meshes.push(crate::scene::MeshInstance {
            shape: crate::scene::Shape::Sphere,
            world_from_unit: [
                [r, 0.0, 0.0, 0.0],
                [0.0, r, 0.0, 0.0],
                [0.0, 0.0, r, 0.0],
                [p[0], p[1], p[2], 1.0],
            ],
            color: [COLLISION_RED[0], COLLISION_RED[1], COLLISION_RED[2], 0.55],
        });
        if k < CONTACTS_NAMED {
            let one = crate::collision::CollisionReport {
                in_collision: true,
                pairs: vec![c.clone()],
                clearance_m: Some(0.0),
                closest: None,
            };
            scene.labels.push(Label {
                p: [p[0], p[1], p[2] + scale * 0.03],
                text: one.summary(),
                color: CONTACT_LABEL,
                movable: true,
            });
        }
    }
}

/// The IK target: a small triad and a dot, red when unreachable.
fn add_target(scene: &mut Scene, target: &super::state::EeTarget, scale: f32, projector: bool) {
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
}

/// A translucent ghost arm at `g.q` (grey when outside the limits) labelled with its posture at
/// the elbow (with `label`); bodies it shares with what is drawn already are skipped.
fn add_ghost(
    scene: &mut Scene,
    robot: &crate::kinematics::Robot,
    g: &Ghost,
    ee: usize,
    label: bool,
) {
    let scale = robot.longest_chain_length() as f32;
    let mut ghost = ArmStyle {
        frames: false,
        frame_labels: false,
        grid: false,
        alpha: 0.28,
        ..ArmStyle::default()
    };
    if let Some(c) = g.class {
        // The posture's colour, as in the workspace figures and the solution list.
        ghost.link = posture_rgba(c);
    }
    let hits = g.collision.as_ref().filter(|r| r.in_collision);
    if !g.within_limits || hits.is_some() {
        let c = if hits.is_some() {
            COLLISION_RED
        } else {
            [0.55, 0.55, 0.57, 1.0]
        };
        ghost = ArmStyle {
            link: c,
            revolute: c,
            prismatic: c,
            tool: c,
            alpha: if g.within_limits { 0.35 } else { 0.18 },
            ..ghost
        };
    }
    let Ok(s) = arm_scene(robot, &g.q, &ghost) else {
        return;
    };
    // Bodies a ghost shares with the arm or with an earlier ghost (the base, and every link
    // before the joints where the postures part) are drawn once: stacked translucent copies
    // would darken them and cost fill.
    let tol = scale * 1e-5;
    for m in s.meshes {
        if !scene.meshes.iter().any(|o| same_body(o, &m, tol)) {
            scene.meshes.push(m);
        }
    }
    add_new_meshes(scene, s.custom_meshes, tol);
    if let Some(r) = hits {
        add_contacts(scene, r, scale);
    }
    if !label {
        return;
    }
    // Label at the elbow (the middle joint frame), where the postures differ.
    let frames = robot.fk_frames(&g.q).unwrap_or_default();
    let chain = robot.chain_to(robot.end_effectors()[ee].parent);
    if let Some(f) = chain
        .get(chain.len().saturating_sub(1) / 2)
        .and_then(|&j| frames.get(j))
    {
        let p = f.translation.vector;
        // Short ("R U N"): the list and the legend spell them out, and full labels would pile
        // up where the postures share an elbow.
        let short = g.posture.short();
        let text = if g.within_limits {
            short
        } else {
            format!("{short} (out)")
        };
        scene.labels.push(Label {
            p: [p.x as f32, p.y as f32, p.z as f32 + scale * 0.06],
            text,
            color: [0.25, 0.25, 0.3, 1.0],
            movable: true,
        });
    }
}

/// The colour of posture class `c` (the workspace figures' palette), opaque.
pub fn posture_rgba(c: u8) -> [f32; 4] {
    let [r, g, b] = crate::figure::palette::CLASS_COLORS
        [c as usize % crate::figure::palette::CLASS_COLORS.len()]
    .map(|v| f32::from(v) / 255.0);
    [r, g, b, 1.0]
}

/// The self-motion of `ee` in `state`, where its arm has one, as [`add_self_motion`] draws it
/// (with the other branches' ghosts and the traced path as the display says).
pub fn add_self_motion_of(scene: &mut Scene, state: &mut AppState, ee: usize) {
    if let Ok(view) = state.self_motion(ee) {
        let ghosts = if state.display.ghosts {
            state.self_motion_ghosts(ee)
        } else {
            Vec::new()
        };
        let path = state.display.self_motion_path;
        add_self_motion(scene, state.robot(), &view, &ghosts, path);
    }
}

/// The self-motion in the 3D view: the other branches at the current parameter as ghosts, and
/// (with `path`) the traced point over the parameter's range, green where the branch is inside
/// the limits, grey elsewhere (for an SRS arm, the elbow circle about the shoulder-wrist axis).
pub fn add_self_motion(
    scene: &mut Scene,
    robot: &crate::kinematics::Robot,
    view: &crate::app::state::SelfMotionView,
    ghosts: &[Ghost],
    path: bool,
) {
    // Only the branches inside the limits are labelled: the others (grey) would pile their
    // names up at the elbow.
    for g in ghosts {
        add_ghost(scene, robot, g, 0, g.within_limits);
    }
    if !path {
        return;
    }
    let n = view.path.len();
    // The closing segment only for a closed path of 3 or more points (`then_some` would
    // compute n - 1 for an empty path too, and overflow).
    let closing = if view.exact && n > 2 {
        Some((n - 1, 0))
    } else {
        None
    };
    let pairs = (0..n.saturating_sub(1)).map(|i| (i, i + 1)).chain(closing);
    for (i, j) in pairs {
        let ((Some(a), fa), (Some(b), fb)) = (view.path[i], view.path[j]) else {
            continue;
        };
        let color = if fa && fb {
            [0.16, 0.59, 0.31, 1.0]
        } else {
            [0.6, 0.6, 0.63, 1.0]
        };
        scene.lines.push(Line {
            a: point32(&a).into(),
            b: point32(&b).into(),
            color,
            width_px: 2.5,
        });
    }
}

/// Whether two mesh instances are the same body: same shape and `world_from_unit` equal
/// within `tol` (m) entry by entry.
fn same_body(a: &crate::scene::MeshInstance, b: &crate::scene::MeshInstance, tol: f32) -> bool {
    a.shape == b.shape
        && a.world_from_unit
            .iter()
            .flatten()
            .zip(b.world_from_unit.iter().flatten())
            .all(|(x, y)| (x - y).abs() <= tol)
}

/// Ghost labels that fall on the same spot (postures differing only at the wrist share an elbow)
/// become one label with a line per posture; a line already there is not repeated.
fn merge_close_labels(labels: &mut Vec<Label>, tol: f32) {
    let mut out: Vec<Label> = Vec::with_capacity(labels.len());
    for l in labels.drain(..) {
        let near = out.iter_mut().find(|o| {
            let d: f32 = o.p.iter().zip(&l.p).map(|(a, b)| (a - b) * (a - b)).sum();
            d.sqrt() < tol && o.color == l.color
        });
        match near {
            // The same words once (postures hitting the table at one spot name it once).
            Some(o) if o.text.lines().any(|t| t == l.text) => {}
            Some(o) => {
                o.text.push('\n');
                o.text.push_str(&l.text);
            }
            None => out.push(l),
        }
    }
    *labels = out;
}
