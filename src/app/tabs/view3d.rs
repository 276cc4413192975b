//! The 3D view: the rendered scene shown at one texel per pixel, the scene's labels placed
//! without overlap, the IK target's gizmo, navigation (orbit, pan, zoom), framing and picking a
//! ghost arm by clicking near it.

use super::super::action::{Action, Actions};
use super::super::cell::CellAction;
use super::super::gizmo::Gizmo;
use super::super::reachability::ReachabilityAction;
use super::super::state::AppState;
use super::super::state::reachability::Ray;
use super::super::viewport::CONTACT_LABEL;
use super::super::viewport::{TextureRegistry, Viewport3d, ViewportImage};
use super::{Tab, TabContext};
use crate::camera::{Camera, Preset, Projection};
use crate::scene::{Scene, arm_points, point32};

/// The 3D view's own state.
pub struct View3d {
    /// The camera.
    pub camera: Camera,
    /// The IK target's gizmo.
    pub gizmo: Gizmo,
    /// The selected obstacle's gizmo (shown instead of the target's while one is selected).
    pub obstacle_gizmo: Gizmo,
    /// The viewport's size in pixels at the last layout (the 3D render uses it).
    pub viewport_px: [u32; 2],
    /// Where the viewport was laid out last (points, window coordinates).
    pub viewport_rect: egui::Rect,
    /// Keep the current target in view while it is dragged off screen.
    pub follow: bool,
    /// Labels of the scene rendered last (drawn by egui over the image).
    labels: Vec<crate::scene::Label>,
    /// Where the labels were drawn last (points): never overlapping (tests check).
    pub placed_labels: Vec<egui::Rect>,
    fitted: bool,
    /// Viewport size and camera right after the last framing: while the camera is untouched, a
    /// new viewport size (the first layout, a resized window) frames the arm again.
    framed: Option<([u32; 2], Camera)>,
    /// Where the pointer was last said to the reachability overlay (points; `None`: off the
    /// view, or dragging).
    pointed: Option<egui::Pos2>,
}

impl Default for View3d {
    fn default() -> Self {
        Self {
            camera: Camera::default(),
            gizmo: Gizmo::default(),
            obstacle_gizmo: Gizmo::default(),
            viewport_px: [800, 600],
            viewport_rect: egui::Rect::NOTHING,
            follow: false,
            labels: Vec::new(),
            placed_labels: Vec::new(),
            fitted: false,
            framed: None,
            pointed: None,
        }
    }
}

impl View3d {
    /// Uses `camera` as is (no automatic framing).
    pub fn set_camera(&mut self, camera: Camera) {
        self.camera = camera;
        self.fitted = true;
        self.framed = None;
    }

    /// Frames the arm again at the next render (a new model).
    pub fn refit(&mut self) {
        self.fitted = false;
    }

    /// Frames the arm, its targets and every ghost posture drawn in the viewport.
    pub fn fit(&mut self, state: &AppState) {
        if let Ok(mut pts) = arm_points(state.robot(), state.q()) {
            // The IK targets too (an unreachable one is the point of interest).
            pts.extend(
                state
                    .targets()
                    .iter()
                    .map(|t| point32(&t.world_from_tool.translation.vector)),
            );
            if state.display.ghosts {
                for ee in 0..state.targets().len() {
                    for g in state.ghosts(ee) {
                        if let Ok(p) = arm_points(state.robot(), &g.q) {
                            pts.extend(p);
                        }
                    }
                }
            }
            let [w, h] = self.viewport_px;
            self.camera.fit_points(&pts, w.max(16), h.max(16), 0.7);
        }
        self.fitted = true;
        self.framed = Some((self.viewport_px, self.camera));
    }

    /// Frames the arm if it has not been framed yet, or if the viewport changed size since the
    /// last framing and the user has not moved the camera since (the live window renders its
    /// first 3D frame before the panels are laid out, at a guessed size).
    pub fn frame_if_needed(&mut self, state: &AppState) {
        let resized = self
            .framed
            .is_some_and(|(size, camera)| size != self.viewport_px && camera == self.camera);
        if !self.fitted || resized {
            self.fit(state);
        }
    }

    /// A camera preset, then framing.
    pub fn preset(&mut self, p: Preset, state: &AppState) {
        self.camera.set_preset(p);
        self.fit(state);
    }

    /// Looks from azimuth `yaw` and elevation `pitch` (rad; the elevation kept short of the
    /// poles) at `distance` (m), or framed to fit where no distance is given.
    pub fn look_from(&mut self, yaw: f32, pitch: f32, distance: Option<f32>, state: &AppState) {
        self.camera.yaw = yaw;
        self.camera.pitch = pitch.clamp(-1.55, 1.55);
        match distance {
            Some(distance) => self.set_camera(Camera {
                distance,
                ..self.camera
            }),
            None => self.fit(state),
        }
    }

    /// Frames everything the arm can reach (a box of its longest chain around the base), so
    /// that a workspace overlay is seen whole.
    pub fn fit_reach(&mut self, state: &AppState) {
        let reach = state.robot().longest_chain_length() as f32;
        let o = state.robot().base.translation.vector.map(|v| v as f32);
        let corners: Vec<nalgebra::Point3<f32>> = (0..8)
            .map(|c| {
                let s = |bit: i32| if c & bit == 0 { -reach } else { reach };
                nalgebra::Point3::new(o.x + s(1), o.y + s(2), o.z + s(4))
            })
            .collect();
        let [w, h] = self.viewport_px;
        let mut camera = self.camera;
        camera.fit_points(&corners, w, h, 0.9);
        self.set_camera(camera);
    }

    /// Perspective / orthographic, then framing.
    pub fn toggle_projection(&mut self, state: &AppState) {
        self.camera.projection = match self.camera.projection {
            Projection::Perspective { .. } => Projection::Orthographic { height: 1.0 },
            Projection::Orthographic { .. } => Projection::Perspective {
                fov_y: 35f32.to_radians(),
            },
        };
        self.fit(state);
    }

    /// Renders `scene` for the viewport at its last size; returns the image to show, or the
    /// error for the status bar.
    pub fn render(
        &mut self,
        vp: &mut Viewport3d,
        registry: &mut dyn TextureRegistry,
        mut scene: Scene,
        dark: bool,
    ) -> Result<ViewportImage, String> {
        let rendered = vp.render(registry, &scene, &self.camera, self.viewport_px, dark);
        self.labels = std::mem::take(&mut scene.labels);
        rendered.map_err(|e| format!("3D view: {e}"))
    }

    /// Where a user would grab the IK target's gizmo to drag it (in points, window
    /// coordinates): the first visible plane square (else arrow) of end-effector `ee`; `None`
    /// before the viewport was laid out. The web page's test drags it.
    pub fn gizmo_grip(&self, state: &AppState, ee: usize) -> Option<egui::Pos2> {
        let pose = state.target(ee).ok()?.world_from_tool;
        self.grip(&self.gizmo, &pose)
    }

    /// Where a user would grab the selected obstacle's gizmo (as [`View3d::gizmo_grip`]);
    /// `None` when no obstacle is selected.
    pub fn obstacle_grip(&self, state: &AppState) -> Option<egui::Pos2> {
        let (_, pose) = selected_obstacle(state)?;
        self.grip(&self.obstacle_gizmo, &pose)
    }

    /// The first visible plane square (else arrow) of `gizmo` at `pose`, in window points.
    fn grip(&self, gizmo: &Gizmo, pose: &crate::kinematics::Pose) -> Option<egui::Pos2> {
        use super::super::gizmo::Handle;
        let rect = self.viewport_rect;
        let ppp = self.viewport_px[0] as f32 / rect.width();
        if !(ppp.is_finite() && ppp > 0.0) {
            return None;
        }
        let handles = [0, 1, 2].map(Handle::Plane).into_iter();
        handles
            .chain([0, 1, 2].map(Handle::Axis))
            .find_map(|h| gizmo.grip_px(&self.camera, self.viewport_px, pose, ppp as f64, h))
            .map(|[x, y]| rect.min + egui::vec2(x as f32, y as f32) / ppp)
    }

    /// Keeps the point `p` (world, m) inside the viewport: pans the camera to it when it left
    /// the middle 80 % of the view.
    fn keep_in_view(&mut self, p: &nalgebra::Vector3<f64>) {
        let [w, h] = self.viewport_px;
        let inside = self.camera.project(&point32(p), w, h).is_some_and(|px| {
            let (x, y) = (px[0] / w as f32, px[1] / h as f32);
            (0.1..0.9).contains(&x) && (0.1..0.9).contains(&y)
        });
        if !inside {
            self.camera.target = point32(p);
        }
    }

    /// The viewport: the image, its labels, the gizmo (the IK target's, or the selected
    /// obstacle's) and navigation; a click picks a ghost's posture or an obstacle.
    fn viewport(&mut self, cx: &mut TabContext<'_>, ui: &mut egui::Ui, out: &mut Actions) {
        let rect = ui.available_rect_before_wrap();
        self.set_rect(ui, rect);
        let ppp = ui.ctx().pixels_per_point();
        let ee = cx.ee;
        let font = egui::FontId::proportional(12.5 * cx.layout.text_scale());
        let obstacle = selected_obstacle(cx.state);
        let target = cx.state.target(ee).ok();
        // The gizmo shown is kept clear of labels.
        let gizmo_pose = match (&obstacle, target) {
            (Some((_, pose)), _) => Some(*pose),
            (None, Some(t)) => Some(t.world_from_tool),
            (None, None) => None,
        };
        let gizmo = gizmo_pose.and_then(|pose| {
            let g = if obstacle.is_some() {
                &self.obstacle_gizmo
            } else {
                &self.gizmo
            };
            let ([x, y], half) =
                g.extent_px(&self.camera, self.viewport_px, &pose, f64::from(ppp))?;
            let c = rect.min + egui::vec2(x as f32, y as f32) / ppp;
            Some(egui::Rect::from_center_size(
                c,
                egui::Vec2::splat(2.0 * half as f32 / ppp),
            ))
        });
        let response = self.paint(ui, cx.image.as_ref(), &font, gizmo.as_slice());
        let mut gizmo_active = false;
        if let Some((k, pose)) = obstacle {
            let g = self
                .obstacle_gizmo
                .ui(ui, &response, rect, &self.camera, &pose, false);
            gizmo_active = g.active;
            if let Some(p) = g.new_pose
                && let Some(o) = cx.state.cell_scene().and_then(|c| c.obstacles.get(k))
            {
                let o = super::super::cell::moved(o, &pose, &p);
                out.push(Action::Cell(CellAction::Set(k, o)));
            }
        } else if let Some(t) = target {
            let pose = t.world_from_tool;
            let unreachable = !t.reach.is_reached();
            let g = self
                .gizmo
                .ui(ui, &response, rect, &self.camera, &pose, unreachable);
            gizmo_active = g.active;
            if let Some(p) = g.new_pose {
                out.push(Action::SetTarget(ee, p));
                if self.follow {
                    self.keep_in_view(&p.translation.vector);
                }
            }
        }
        self.navigate(ui, &response, rect, gizmo_active);
        if cx.state.display.reachability {
            self.point(&response, (rect, ppp), gizmo_active, out);
        }
        if response.double_clicked() {
            self.fit(cx.state);
        } else if response.clicked()
            && !gizmo_active
            && let Some(pos) = response.interact_pointer_pos()
        {
            self.click(cx.state, ee, (pos - rect.min) * ppp, out);
        }
    }

    /// A click at a pixel of the viewport: the posture of the ghost arm there, else the
    /// obstacle there (the gizmo then moves it), else (clicking empty space) no obstacle.
    /// While the reachability overlay is on, the overlay decides (a direction of the shown
    /// voxel, else the ghost there, else a voxel of the slice).
    fn click(&self, state: &AppState, ee: usize, at: egui::Vec2, out: &mut Actions) {
        if state.display.reachability {
            let (ray, ghost) = (self.ray_at(at), self.pick_ghost(state, ee, at));
            out.push(Action::Reachability(ReachabilityAction::Click {
                ray,
                ghost,
            }));
        } else if let Some(index) = self.pick_ghost(state, ee, at) {
            out.push(Action::SelectSolution(ee, index));
        } else if let Some(k) = self.pick_obstacle(state, at) {
            out.push(Action::Cell(CellAction::Select(Some(k))));
        } else if state.selected_obstacle().is_some() {
            out.push(Action::Cell(CellAction::Select(None)));
        }
    }

    /// Tells the reachability overlay where the pointer looks when it moved (nothing while a
    /// gizmo or the camera is dragged); `view` is the viewport's rectangle and pixels per point.
    fn point(
        &mut self,
        response: &egui::Response,
        (rect, ppp): (egui::Rect, f32),
        busy: bool,
        out: &mut Actions,
    ) {
        let at = response
            .hover_pos()
            .filter(|_| !busy && !response.dragged());
        if at == self.pointed {
            return;
        }
        self.pointed = at;
        let ray = at.map(|p| self.ray_at((p - rect.min) * ppp));
        out.push(Action::Reachability(ReachabilityAction::Point(ray)));
    }

    /// The ray through a pixel of the viewport (world, m).
    fn ray_at(&self, at: egui::Vec2) -> Ray {
        let (o, d) = super::super::gizmo::ray_from_pixel(&self.camera, self.viewport_px, at.into());
        Ray {
            origin: [o.x, o.y, o.z],
            dir: [d.x, d.y, d.z],
        }
    }

    /// The obstacle under a pixel of the viewport (the nearest along the ray; planes left
    /// out: a floor would catch every click below the horizon).
    fn pick_obstacle(&self, state: &AppState, at: egui::Vec2) -> Option<usize> {
        let world = state.collision_world()?;
        let (o, d) = super::super::gizmo::ray_from_pixel(&self.camera, self.viewport_px, at.into());
        let ray = ([o.x, o.y, o.z], [d.x, d.y, d.z]);
        let hit = world.obstacle_on_ray(state.robot(), state.q(), ray, false);
        hit.ok().flatten().map(|(k, _)| k)
    }

    /// Takes `rect` (points) as the view's place: the image is rendered at its size in pixels.
    pub fn set_rect(&mut self, ui: &egui::Ui, rect: egui::Rect) {
        self.viewport_rect = rect;
        let ppp = ui.ctx().pixels_per_point();
        self.viewport_px = [
            ((rect.width() * ppp).round() as u32).max(16),
            ((rect.height() * ppp).round() as u32).max(16),
        ];
    }

    /// Paints `image` (rendered for this view) in the view's rectangle on whole pixels, and
    /// the scene's labels over it in `font`, clear of `avoid`; returns the view's response
    /// (click and drag).
    pub fn paint(
        &mut self,
        ui: &mut egui::Ui,
        image: Option<&ViewportImage>,
        font: &egui::FontId,
        avoid: &[egui::Rect],
    ) -> egui::Response {
        let rect = self.viewport_rect;
        let ppp = ui.ctx().pixels_per_point();
        let response = ui.allocate_rect(rect, egui::Sense::click_and_drag());
        if let Some(im) = image {
            // On whole pixels, the texture's size: a texel per pixel, no resampling.
            let [w, h] = self.viewport_px;
            let at = (rect.min.to_vec2() * ppp).round() / ppp;
            let rect =
                egui::Rect::from_min_size(at.to_pos2(), egui::vec2(w as f32, h as f32) / ppp);
            ui.painter().image(
                im.id,
                rect,
                egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0)),
                egui::Color32::WHITE,
            );
        }
        // What a posture hits is placed first and may cover the gizmo (a contact at the hand
        // lies under the target's gizmo: kept clear of it, its name had nowhere to go); the
        // other labels keep clear of both.
        let view = (self.viewport_px, &self.camera);
        let contact = |l: &&crate::scene::Label| l.color == CONTACT_LABEL;
        let (first, rest): (Vec<_>, Vec<_>) =
            self.labels.iter().cloned().partition(|l| contact(&l));
        let draw = crate::figure::labels::draw_labels;
        let mut placed = draw(ui.painter(), rect, view, &first, &[], font);
        let keep_clear: Vec<egui::Rect> = avoid.iter().chain(&placed).copied().collect();
        placed.extend(draw(ui.painter(), rect, view, &rest, &keep_clear, font));
        self.placed_labels = placed;
        response
    }

    /// Orbit (drag), pan (right or middle drag) and zoom (scroll, pinch).
    pub fn navigate(
        &mut self,
        ui: &egui::Ui,
        response: &egui::Response,
        rect: egui::Rect,
        gizmo_active: bool,
    ) {
        if !gizmo_active {
            if response.dragged_by(egui::PointerButton::Primary) {
                let d = response.drag_delta();
                self.camera.orbit(-d.x * 0.008, d.y * 0.008);
            } else if response.dragged_by(egui::PointerButton::Secondary)
                || response.dragged_by(egui::PointerButton::Middle)
            {
                let d = response.drag_delta();
                self.camera.pan(d.x / rect.height(), d.y / rect.height());
            }
        }
        if response.hovered() {
            let (scroll, zoom) = ui.input(|i| (i.smooth_scroll_delta.y, i.zoom_delta()));
            if scroll != 0.0 {
                self.camera.zoom((-scroll * 0.002).exp());
            }
            if zoom != 1.0 {
                self.camera.zoom(1.0 / zoom);
            }
        }
    }

    /// The ghost arm nearest to a click (pixel position in the viewport): the solution index of
    /// the one whose joint projects closest, within 40 px; a ghost within the limits wins over
    /// one outside them (postures differing only at the wrist share their joint positions).
    fn pick_ghost(&self, state: &AppState, ee: usize, at: egui::Vec2) -> Option<usize> {
        let robot = state.robot();
        let [w, h] = self.viewport_px;
        let chain = robot
            .chain_to(robot.end_effectors()[ee.min(robot.end_effectors().len() - 1)].parent)
            .to_vec();
        let mut best: Option<(bool, f32, usize)> = None;
        let target = state.target(ee).ok()?;
        let result = target.result.as_ref()?;
        for g in state.ghosts(ee).iter().filter(|g| !g.selected) {
            let Some(index) = result.solutions.iter().position(|s| s.q == g.q) else {
                continue;
            };
            let Ok(frames) = robot.fk_frames(&g.q) else {
                continue;
            };
            for &j in &chain {
                let p = point32(&frames[j].translation.vector);
                if let Some(px) = self.camera.project(&p, w, h) {
                    let d = (egui::vec2(px[0], px[1]) - at).length();
                    let key = (!g.within_limits, d);
                    if d < 40.0 && best.is_none_or(|b| key < (b.0, b.1)) {
                        best = Some((key.0, d, index));
                    }
                }
            }
        }
        best.map(|(_, _, index)| index)
    }
}

impl Tab for View3d {
    fn title(&self) -> &'static str {
        "3D view"
    }

    fn ui(&mut self, cx: &mut TabContext<'_>, ui: &mut egui::Ui, out: &mut Actions) {
        self.viewport(cx, ui, out);
    }

    fn model_changed(&mut self) {
        self.fitted = false;
    }
}

/// The selected obstacle and its world pose (m), if one is selected.
fn selected_obstacle(state: &AppState) -> Option<(usize, crate::kinematics::Pose)> {
    let k = state.selected_obstacle()?;
    state.obstacle_poses().get(k).map(|p| (k, *p))
}
