//! A 3D transform gizmo for the IK target, drawn and picked in screen space.
//!
//! Three translation arrows (x red, y green, z blue), three plane handles (small squares, one per
//! coordinate plane, coloured as the plane's normal axis) and three rotation rings, along the
//! target's own axes or the world axes ([`GizmoSpace`]). Sizes are in pixels, so the gizmo looks
//! the same at any zoom. The geometry ([`Gizmo::pick`], [`Gizmo::drag_pose`], [`ray_from_pixel`])
//! is pure math against a [`Camera`] and a viewport size in pixels; only [`Gizmo::ui`] touches
//! egui (drawing with the painter over the viewport image, and pointer handling).

use crate::camera::Camera;
use crate::kinematics::pose::Pose;
use nalgebra::{Point3, Rotation3, Unit, Vector2, Vector3};

mod view;
use view::{View, cross2, dist_to_segment, px};
pub use view::{metres_per_pixel, ray_from_pixel};

type V2 = Vector2<f64>;
type V3 = Vector3<f64>;
type P3 = Point3<f64>;

/// Radius of the rotation rings, as a fraction of [`Gizmo::size_px`].
pub const RING_RADIUS: f64 = 0.7;
/// Inner edge of the plane squares along both in-plane axes, as a fraction of the size.
pub const PLANE_INNER: f64 = 0.22;
/// Outer edge of the plane squares, as a fraction of the size.
pub const PLANE_OUTER: f64 = 0.42;
/// Where an arrow's shaft starts, as a fraction of the size (the centre stays free).
const ARROW_START: f64 = 0.16;
/// Arrows whose projection is shorter than this fraction of the size are hidden, and dragging
/// them uses a pixel-to-metre scale instead of the ray-line solution.
const MIN_FORESHORTENING: f64 = 0.12;
/// Planes seen more edge-on than this (|cos| of normal and view direction) are hidden.
const MIN_PLANE_FACING: f64 = 0.15;
/// Below this facing a plane drag uses the pixel-to-metre fallback instead of ray intersection.
const MIN_PLANE_FACING_DRAG: f64 = 0.05;
/// Segments of a ring's polyline.
const RING_SEGMENTS: usize = 72;
/// Pixel penalties so that arrows and planes win over rings crossing them, and front over back.
const RING_BIAS: f64 = 1.5;
const BACK_BIAS: f64 = 3.0;
/// A drag never moves the target further than this many view heights (at the target's depth).
const MAX_DRAG_VIEWS: f64 = 10.0;
const AXIS_NAMES: [&str; 3] = ["x", "y", "z"];

/// Which frame the handles are aligned with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum GizmoSpace {
    /// The target's own axes (the columns of its rotation matrix).
    #[default]
    Local,
    /// The world axes.
    World,
}

/// A part of the gizmo; the index is the axis 0 = x, 1 = y, 2 = z.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Handle {
    /// Translation arrow along the axis.
    Axis(usize),
    /// Translation in the plane whose normal is the axis (0: the y-z plane, ...).
    Plane(usize),
    /// Rotation ring about the axis.
    Ring(usize),
}

/// What [`Gizmo::ui`] reports each frame.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GizmoOutput {
    /// The target's pose while dragging (the start pose again when the drag is cancelled).
    pub new_pose: Option<Pose>,
    /// The pointer is over a handle or a drag is under way: the viewport should not orbit.
    pub active: bool,
    /// A drag ended this frame (pointer released, or cancelled with Escape).
    pub released: bool,
}

/// A drag in progress.
#[derive(Debug, Clone, Copy, PartialEq)]
struct DragState {
    handle: Handle,
    start_px: [f32; 2],
    start_pose: Pose,
}

/// The gizmo's settings and interaction state.
#[derive(Debug, Clone, PartialEq)]
pub struct Gizmo {
    /// Frame of the handles.
    pub space: GizmoSpace,
    /// Length of the arrows in pixels (at `pixels_per_point` = 1; [`Gizmo::ui`] scales it).
    pub size_px: f32,
    /// How far from a handle (pixels) the pointer still picks it.
    pub pick_radius_px: f32,
    hovered: Option<Handle>,
    drag: Option<DragState>,
}

impl Default for Gizmo {
    fn default() -> Self {
        Self {
            space: GizmoSpace::Local,
            size_px: 90.0,
            pick_radius_px: 8.0,
            hovered: None,
            drag: None,
        }
    }
}

/// Where the gizmo is this frame.
struct Layout {
    centre: P3,
    centre_px: V2,
    axes: [V3; 3],
    /// World length of the arrows (m) and their nominal length in pixels.
    len: f64,
    size_px: f64,
    /// Unit direction from the eye towards the centre.
    view_dir: V3,
    /// World vectors of one pixel right / down at the centre's depth.
    px_x: V3,
    px_y: V3,
}

/// A handle's outline in pixels.
enum Outline {
    Arrow(V2, V2),
    Quad([V2; 4]),
    /// Closed polyline; `true` for points on the half facing the camera (all, seen face-on).
    Ring(Vec<(V2, bool)>),
}

/// What a drag did, for the on-screen readout.
enum Readout {
    Distance(usize, f64),
    Offset(V3),
    Angle(usize, f64),
}

impl Gizmo {
    /// A gizmo in `space` with the default sizes (90 px arrows, 8 px pick radius).
    pub fn new(space: GizmoSpace) -> Self {
        Self {
            space,
            ..Self::default()
        }
    }

    /// The handles' axes in world coordinates for a target pose, in the current [`GizmoSpace`].
    pub fn axis_dirs(&self, world_from_target: &Pose) -> [Vector3<f64>; 3] {
        let m = world_from_target.rotation.matrix();
        match self.space {
            GizmoSpace::Local => [0, 1, 2].map(|i| m.column(i).into_owned()),
            GizmoSpace::World => [V3::x(), V3::y(), V3::z()],
        }
    }

    /// The square (pixels of a `viewport`-sized view, centre and half side) that the gizmo of
    /// a target at `pose` covers, arrows and rings included: labels keep off it.
    pub fn extent_px(
        &self,
        camera: &Camera,
        viewport: [u32; 2],
        pose: &Pose,
        scale: f64,
    ) -> Option<([f64; 2], f64)> {
        let (_, l) = self.frame(camera, viewport, pose, scale)?;
        // Arrows reach size_px, their names a little further.
        Some(([l.centre_px.x, l.centre_px.y], l.size_px * 1.2 + 10.0))
    }

    /// The handle being dragged, if any.
    pub fn dragging(&self) -> Option<Handle> {
        self.drag.map(|d| d.handle)
    }

    /// The handle under the pointer (or being dragged) at the last [`Gizmo::ui`] call.
    pub fn hovered(&self) -> Option<Handle> {
        self.hovered
    }

    /// The view and the gizmo's layout for a pose; sizes multiplied by `scale`.
    fn frame(
        &self,
        camera: &Camera,
        viewport: [u32; 2],
        pose: &Pose,
        scale: f64,
    ) -> Option<(View, Layout)> {
        let view = View::new(camera, viewport)?;
        let centre = P3::from(pose.translation.vector);
        let centre_px = view.project(&centre)?;
        let (px_x, px_y) = view.pixel_basis(&centre, centre_px)?;
        let (_, view_dir) = view.ray(centre_px)?;
        let size_px = self.size_px as f64 * scale;
        let len = size_px * px_y.norm();
        let axes = self.axis_dirs(pose);
        let l = Layout {
            centre,
            centre_px,
            axes,
            len,
            size_px,
            view_dir,
            px_x,
            px_y,
        };
        (len.is_finite() && len > 0.0).then_some((view, l))
    }

    /// The visible handles' outlines in pixels (hidden: arrows pointing at the camera, planes
    /// seen edge-on, anything behind the camera).
    fn outlines(view: &View, l: &Layout) -> Vec<(Handle, Outline)> {
        let mut out = Vec::new();
        let at = |v: V3| view.project(&(l.centre + v * l.len));
        for i in 0..3 {
            let (a, b) = (l.axes[(i + 1) % 3], l.axes[(i + 2) % 3]);
            let ring: Option<Vec<_>> = (0..RING_SEGMENTS)
                .map(|s| {
                    let phi = std::f64::consts::TAU * s as f64 / RING_SEGMENTS as f64;
                    let v = (a * phi.cos() + b * phi.sin()) * RING_RADIUS;
                    at(v).map(|q| (q, v.dot(&l.view_dir) <= 0.1 * RING_RADIUS))
                })
                .collect();
            if let Some(r) = ring {
                out.push((Handle::Ring(i), Outline::Ring(r)));
            }
        }
        for i in 0..3 {
            let (a, b) = (l.axes[(i + 1) % 3], l.axes[(i + 2) % 3]);
            let (p, q) = (PLANE_INNER, PLANE_OUTER);
            let corners = [(p, p), (q, p), (q, q), (p, q)].map(|(u, v)| at(a * u + b * v));
            if let [Some(c0), Some(c1), Some(c2), Some(c3)] = corners
                && l.axes[i].dot(&l.view_dir).abs() >= MIN_PLANE_FACING
            {
                out.push((Handle::Plane(i), Outline::Quad([c0, c1, c2, c3])));
            }
        }
        for i in 0..3 {
            if let (Some(from), Some(tip)) = (at(l.axes[i] * ARROW_START), at(l.axes[i]))
                && (tip - l.centre_px).norm() >= MIN_FORESHORTENING * l.size_px
            {
                out.push((Handle::Axis(i), Outline::Arrow(from, tip)));
            }
        }
        out
    }

    /// Pure: where to grab `handle` (pixel coordinates in the viewport, drawn at `scale` pixels
    /// per point): the middle of an arrow's shaft or of a plane's square; `None` for a ring or
    /// a hidden handle.
    pub fn grip_px(
        &self,
        camera: &Camera,
        viewport_px: [u32; 2],
        world_from_target: &Pose,
        scale: f64,
        handle: Handle,
    ) -> Option<[f64; 2]> {
        let (view, l) = self.frame(camera, viewport_px, world_from_target, scale)?;
        let (_, outline) = Self::outlines(&view, &l)
            .into_iter()
            .find(|(h, _)| *h == handle)?;
        let p = match outline {
            Outline::Arrow(from, tip) => (from + tip) / 2.0,
            Outline::Quad(c) => (c[0] + c[1] + c[2] + c[3]) / 4.0,
            Outline::Ring(_) => return None,
        };
        Some([p.x, p.y])
    }

    /// Pure: which handle is under the pointer (pixel coordinates in the viewport), if any.
    /// The closest handle within [`Gizmo::pick_radius_px`] wins, arrows and planes before rings
    /// crossing them.
    pub fn pick(
        &self,
        camera: &Camera,
        viewport_px: [u32; 2],
        world_from_target: &Pose,
        pointer_px: [f32; 2],
    ) -> Option<Handle> {
        let (view, l) = self.frame(camera, viewport_px, world_from_target, 1.0)?;
        self.pick_in(&view, &l, px(pointer_px), 1.0)
    }

    fn pick_in(&self, view: &View, l: &Layout, p: V2, scale: f64) -> Option<Handle> {
        let mut best: Option<(f64, Handle)> = None;
        for (h, o) in Self::outlines(view, l) {
            let d = match &o {
                Outline::Arrow(from, tip) => dist_to_segment(p, *from, *tip),
                Outline::Quad(c) => {
                    let s = [0, 1, 2, 3].map(|k| cross2(c[(k + 1) % 4] - c[k], p - c[k]));
                    if s.iter().all(|v| *v >= 0.0) || s.iter().all(|v| *v <= 0.0) {
                        0.0
                    } else {
                        let edge = |k: usize| dist_to_segment(p, c[k], c[(k + 1) % 4]);
                        (0..4).map(edge).fold(f64::MAX, f64::min)
                    }
                }
                Outline::Ring(r) => (0..r.len())
                    .map(|k| {
                        let ((a, fa), (b, fb)) = (r[k], r[(k + 1) % r.len()]);
                        let bias = if fa || fb { RING_BIAS } else { BACK_BIAS };
                        dist_to_segment(p, a, b) + bias * scale
                    })
                    .fold(f64::MAX, f64::min),
            };
            if d <= self.pick_radius_px as f64 * scale && best.is_none_or(|(bd, _)| d < bd) {
                best = Some((d, h));
            }
        }
        best.map(|(_, h)| h)
    }

    /// Pure: the new pose after dragging `handle` from `start_px` to `now_px`, given the pose at
    /// the start of the drag.
    ///
    /// * Arrow: the point of the axis line closest to the pointer ray moves with the pointer, so
    ///   the grabbed point follows it along the projected axis. When the axis points at the
    ///   camera (projected shorter than 12 % of its length), the pointer motion along the
    ///   projected axis (or upwards) times the metres per pixel at the target is used instead.
    /// * Plane: the pointer ray's hit on the plane through the target moves with the pointer
    ///   (seen edge-on: the pointer motion in metres, projected into the plane).
    /// * Ring: the angle swept by the pointer around the projected centre, about the axis;
    ///   counter-clockwise on screen rotates counter-clockwise as seen by the camera.
    ///
    /// Always finite: degenerate cases give the start pose or a motion clamped to ten view
    /// heights.
    pub fn drag_pose(
        &self,
        camera: &Camera,
        viewport_px: [u32; 2],
        start_pose: &Pose,
        handle: Handle,
        start_px: [f32; 2],
        now_px: [f32; 2],
    ) -> Pose {
        self.frame(camera, viewport_px, start_pose, 1.0)
            .and_then(|(v, l)| Self::drag_in(&v, &l, start_pose, handle, px(start_px), px(now_px)))
            .map_or(*start_pose, |(p, _)| p)
    }

    fn drag_in(
        view: &View,
        l: &Layout,
        start: &Pose,
        handle: Handle,
        s: V2,
        n: V2,
    ) -> Option<(Pose, Readout)> {
        let mpp = l.px_y.norm();
        let limit = MAX_DRAG_VIEWS * mpp * view.size.y;
        let translate =
            |d: V3| Pose::from_parts((start.translation.vector + d).into(), start.rotation);
        let (pose, readout) = match handle {
            Handle::Axis(i) if i < 3 => {
                let a = l.axes[i];
                // Screen direction of the axis and its foreshortening (1 when seen side-on).
                let q = view.project(&(l.centre + a * mpp))? - l.centre_px;
                let f = q.norm();
                let screen = || (n - s).dot(&if f > 1e-6 { q / f } else { -V2::y() }) * mpp;
                // Parameter along the axis of the point closest to the pointer ray.
                let param = |p: V2| {
                    let (o, d) = view.ray(p)?;
                    let (b, w0) = (a.dot(&d), l.centre - o);
                    let t = (b * d.dot(&w0) - a.dot(&w0)) / (1.0 - b * b);
                    let in_front = view.ortho || d.dot(&w0) + t * b > 0.0;
                    (1.0 - b * b > 1e-12 && t.is_finite() && in_front).then_some(t)
                };
                let d = match (param(s), param(n)) {
                    (Some(t0), Some(t1)) if f >= MIN_FORESHORTENING => t1 - t0,
                    _ => screen(),
                };
                let d = d.clamp(-limit, limit);
                (translate(a * d), Readout::Distance(i, d))
            }
            Handle::Plane(i) if i < 3 => {
                let nrm = l.axes[i];
                let hit = |p: V2| {
                    let (o, d) = view.ray(p)?;
                    let t = (l.centre - o).dot(&nrm) / d.dot(&nrm);
                    (t.is_finite() && (view.ortho || t > 0.0)).then(|| o + d * t)
                };
                let facing = nrm.dot(&l.view_dir).abs() >= MIN_PLANE_FACING_DRAG;
                let mut d = match (hit(s), hit(n)) {
                    (Some(h0), Some(h1)) if facing => h1 - h0,
                    _ => l.px_x * (n - s).x + l.px_y * (n - s).y,
                };
                d -= nrm * nrm.dot(&d);
                d *= (limit / d.norm()).min(1.0);
                (translate(d), Readout::Offset(d))
            }
            Handle::Ring(i) if i < 3 => {
                let a = l.axes[i];
                let (u0, u1) = (s - l.centre_px, n - l.centre_px);
                // Counter-clockwise on screen (y down) is a negative 2D cross product.
                let ccw = if u0.norm() > 1e-6 && u1.norm() > 1e-6 {
                    (-cross2(u0, u1)).atan2(u0.dot(&u1))
                } else {
                    0.0
                };
                // Seen from the tip of the axis, a positive rotation is counter-clockwise.
                let angle = if a.dot(&l.view_dir) < 0.0 { ccw } else { -ccw };
                let mut r =
                    Rotation3::from_axis_angle(&Unit::new_normalize(a), angle) * start.rotation;
                r.renormalize();
                let pose = Pose::from_parts(start.translation, r);
                (pose, Readout::Angle(i, angle))
            }
            _ => return None,
        };
        let finite = pose.to_homogeneous().iter().all(|v| v.is_finite());
        finite.then_some((pose, readout))
    }

    /// egui: draws the gizmo over the viewport image in `rect` (points; the camera works in
    /// `rect.size() * pixels_per_point` pixels, rounded, at least 16), handles hover, press, drag
    /// and release from `response` (a `Sense::click_and_drag` response over the viewport) and
    /// returns the new pose while dragging. A press on a handle starts a drag at once (no drag
    /// threshold); Escape cancels it (the start pose is returned). No hover is reported while
    /// the button is held for something else (an orbit passing over the gizmo).
    /// `unreachable` draws the centre red. Sizes are scaled by `pixels_per_point`.
    pub fn ui(
        &mut self,
        ui: &egui::Ui,
        response: &egui::Response,
        rect: egui::Rect,
        camera: &Camera,
        world_from_target: &Pose,
        unreachable: bool,
    ) -> GizmoOutput {
        use egui::CursorIcon::{Grab, Grabbing};
        let ppp = ui.ctx().pixels_per_point();
        let scale = ppp as f64;
        let size = rect.size() * ppp;
        let viewport = [size.x, size.y].map(|v| (v.round() as u32).max(16));
        let to_px = |p: egui::Pos2| px(((p - rect.min) * ppp).into());
        let (pressed, down) = ui.input(|i| (i.pointer.primary_pressed(), i.pointer.primary_down()));
        let (origin, latest) = ui.input(|i| (i.pointer.press_origin(), i.pointer.latest_pos()));
        let escape = ui.input(|i| i.key_pressed(egui::Key::Escape));
        let mut out = GizmoOutput::default();
        let mut readout = None;

        if let Some(d) = self.drag {
            if escape {
                out.new_pose = Some(d.start_pose);
            } else if let Some(p) = response.interact_pointer_pos().or(latest) {
                let (s, n) = (px(d.start_px), to_px(p));
                let e = self.frame(camera, viewport, &d.start_pose, 1.0);
                let e = e.and_then(|(v, l)| Self::drag_in(&v, &l, &d.start_pose, d.handle, s, n));
                let (pose, r) = e.unzip();
                out.new_pose = Some(pose.unwrap_or(d.start_pose));
                readout = r;
            }
            if escape || !down {
                out.released = true;
                self.drag = None;
            }
        }
        let dragged = out.new_pose.filter(|_| self.drag.is_some());
        let pose = dragged.unwrap_or(*world_from_target);
        let Some((view, l)) = self.frame(camera, viewport, &pose, scale) else {
            self.hovered = None;
            out.active = self.drag.is_some();
            return out;
        };
        if self.drag.is_none()
            && pressed
            && let Some(o) = origin.filter(|o| rect.contains(*o))
            && (response.is_pointer_button_down_on() || response.contains_pointer())
            && let Some(handle) = self.pick_in(&view, &l, to_px(o), scale)
        {
            let start_px = [to_px(o).x as f32, to_px(o).y as f32];
            self.drag = Some(DragState {
                handle,
                start_px,
                start_pose: *world_from_target,
            });
        }
        self.hovered = match self.drag {
            Some(d) => Some(d.handle),
            None if down || out.released => None,
            None => response
                .hover_pos()
                .and_then(|p| self.pick_in(&view, &l, to_px(p), scale)),
        };
        out.active = self.hovered.is_some() || self.drag.is_some();
        if out.active {
            ui.ctx()
                .set_cursor_icon(if self.drag.is_some() { Grabbing } else { Grab });
        }
        self.paint(ui, rect, &view, &l, unreachable, readout);
        out
    }

    fn paint(
        &self,
        ui: &egui::Ui,
        rect: egui::Rect,
        view: &View,
        l: &Layout,
        unreachable: bool,
        readout: Option<Readout>,
    ) {
        use egui::{Align2, Color32, FontId, Shape, Stroke};
        let ppp = ui.ctx().pixels_per_point();
        let painter = ui.painter_at(rect);
        let pos = |v: V2| rect.min + egui::vec2(v.x as f32, v.y as f32) / ppp;
        let axis_color = [(235, 70, 70), (80, 200, 80), (75, 125, 245)]
            .map(|(r, g, b)| Color32::from_rgb(r, g, b));
        let highlight = Color32::from_rgb(255, 215, 40);
        let color_of = |h: Handle, i: usize| match (self.hovered == Some(h), self.drag.is_some()) {
            (true, _) => highlight,
            (false, true) => axis_color[i].gamma_multiply(0.35),
            (false, false) => axis_color[i],
        };
        let width = |h: Handle| if self.hovered == Some(h) { 3.5 } else { 2.5 };
        // In the order of `outlines`: rings (back halves dimmed), planes, arrows; then the centre.
        for (h, o) in &Self::outlines(view, l) {
            let (Handle::Axis(i) | Handle::Plane(i) | Handle::Ring(i)) = *h;
            let c = color_of(*h, i);
            match o {
                Outline::Ring(r) => {
                    for k in 0..r.len() {
                        let ((a, fa), (b, fb)) = (r[k], r[(k + 1) % r.len()]);
                        let c = c.gamma_multiply(if fa && fb { 1.0 } else { 0.3 });
                        painter.line_segment([pos(a), pos(b)], Stroke::new(width(*h) - 0.5, c));
                    }
                }
                Outline::Quad(q) => {
                    let (pts, fill) = (q.iter().map(|v| pos(*v)).collect(), c.gamma_multiply(0.35));
                    painter.add(Shape::convex_polygon(pts, fill, Stroke::new(1.5, c)));
                }
                Outline::Arrow(from, tip) => {
                    let (from, tip) = (pos(*from), pos(*tip));
                    let dir = (tip - from).normalized();
                    let (base, side) = (tip - dir * 13.0, dir.rot90() * 5.5);
                    painter.line_segment([from, base], Stroke::new(width(*h), c));
                    let head = vec![tip, base + side, base - side];
                    painter.add(Shape::convex_polygon(head, c, Stroke::NONE));
                    let font = FontId::proportional(
                        13f32.max(crate::app::layout::text_floor(painter.ctx())),
                    );
                    painter.text(
                        tip + dir * 9.0,
                        Align2::CENTER_CENTER,
                        AXIS_NAMES[i],
                        font,
                        c,
                    );
                }
            }
        }
        let centre = pos(l.centre_px);
        let fill = [Color32::from_gray(240), Color32::from_rgb(230, 30, 30)][unreachable as usize];
        painter.circle_filled(centre, 5.0, fill);
        painter.circle_stroke(centre, 5.0, Stroke::new(1.5, Color32::from_gray(30)));
        self.paint_readout(ui, &painter, rect, centre, readout, highlight);
    }

    /// While dragging: the swept angle's spokes (rotation rings) and a readout of the drag next
    /// to the pointer.
    fn paint_readout(
        &self,
        ui: &egui::Ui,
        painter: &egui::Painter,
        rect: egui::Rect,
        centre: egui::Pos2,
        readout: Option<Readout>,
        highlight: egui::Color32,
    ) {
        use egui::{Align2, Color32, FontId, Shape, Stroke};
        let ppp = ui.ctx().pixels_per_point();
        let (Some(d), Some(r), Some(p)) =
            (self.drag, readout, ui.input(|i| i.pointer.latest_pos()))
        else {
            return;
        };
        if let Handle::Ring(_) = d.handle {
            let s = Stroke::new(1.0, highlight);
            let start = rect.min + egui::vec2(d.start_px[0], d.start_px[1]) / ppp;
            painter.add(Shape::dashed_line(&[centre, start], s, 4.0, 3.0));
            painter.line_segment([centre, p], s);
        }
        let text = match r {
            Readout::Distance(i, m) => format!("Δ{} = {m:+.4} m", AXIS_NAMES[i]),
            Readout::Offset(v) => format!("Δ = ({:+.4}, {:+.4}, {:+.4}) m", v.x, v.y, v.z),
            Readout::Angle(i, a) => format!("θ{} = {:+.2}°", AXIS_NAMES[i], a.to_degrees()),
        };
        let floor = crate::app::layout::text_floor(painter.ctx());
        let (at, font) = (
            p + egui::vec2(14.0, -14.0),
            FontId::monospace(13f32.max(floor)),
        );
        for (off, c) in [(1.0, Color32::BLACK), (0.0, Color32::WHITE)] {
            painter.text(
                at + egui::vec2(off, off),
                Align2::LEFT_BOTTOM,
                &text,
                font.clone(),
                c,
            );
        }
    }
}
