//! Draw lists in f32: the one place where f64 kinematics becomes f32 geometry. A [`Scene`] is
//! what the renderer draws (meshes, thick lines, points) plus the 3D labels an overlay writes.
//! [`arm_scene`] builds the arm of a robot at q: links as a stick figure along the DH geometry,
//! joint bodies (a cylinder along z for a revolute joint, a box for a prismatic one), DH frame
//! triads with labels, the ground grid and the end-effector.

use crate::kinematics::pose::Pose;
use crate::kinematics::visual::VisualGeometry;
use crate::kinematics::{JointKind, KinematicsError, Robot};
use crate::mesh::TriMesh;
use nalgebra::{Matrix4, Point3, Rotation3, Vector3};
use std::sync::Arc;

pub mod obstacles;
pub mod orientation;
pub mod reachability;

/// RGBA colour, each channel in [0, 1] (linear).
pub type Rgba = [f32; 4];

/// The unit shapes the renderer knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Shape {
    /// Radius 1, z in [-0.5, 0.5].
    Cylinder,
    /// The cube [-0.5, 0.5]^3.
    Cube,
    /// Radius 1.
    Sphere,
    /// Base radius 1 at z = 0, apex at z = 1.
    Cone,
}

/// One shape placed in the world: `world_from_unit` maps the unit shape (column-major 4x4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshInstance {
    /// The unit shape.
    pub shape: Shape,
    /// `world_from_unit`, column-major (may scale non-uniformly).
    pub world_from_unit: [[f32; 4]; 4],
    /// Colour; alpha < 1 is drawn translucent after the opaque meshes.
    pub color: Rgba,
}

/// A segment drawn `width_px` pixels wide whatever the zoom.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Line {
    /// Start (world, m).
    pub a: [f32; 3],
    /// End (world, m).
    pub b: [f32; 3],
    /// Colour.
    pub color: Rgba,
    /// Width (pixels).
    pub width_px: f32,
}

/// A round dot of `size_px` pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dot {
    /// Position (world, m).
    pub p: [f32; 3],
    /// Colour.
    pub color: Rgba,
    /// Diameter (pixels).
    pub size_px: f32,
}

/// Text anchored at a world point (drawn by the overlay, not the renderer).
#[derive(Debug, Clone, PartialEq)]
pub struct Label {
    /// Anchor (world, m).
    pub p: [f32; 3],
    /// Text.
    pub text: String,
    /// Colour.
    pub color: Rgba,
    /// May be moved off its anchor (with a leader line) so as not to cover other movable
    /// labels; fixed labels (frame axes) stay at their anchor.
    pub movable: bool,
}

/// A triangle mesh placed in the world (a URDF link's mesh file), drawn lit like the shapes.
#[derive(Debug, Clone, PartialEq)]
pub struct CustomMesh {
    /// The mesh (its frame's coordinates, m); instances of one mesh share its GPU copy.
    pub mesh: Arc<TriMesh>,
    /// A coarse copy a live view may draw instead while it moves on a software rasterizer
    /// (`None`: draw `mesh` always).
    pub coarse: Option<Arc<TriMesh>>,
    /// `world_from_mesh`, column-major.
    pub world_from_mesh: [[f32; 4]; 4],
    /// Colour; alpha < 1 is drawn translucent after the opaque meshes.
    pub color: Rgba,
}

/// Everything to draw in one view.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Scene {
    /// Lit meshes.
    pub meshes: Vec<MeshInstance>,
    /// Lit triangle meshes of their own (URDF mesh files).
    pub custom_meshes: Vec<CustomMesh>,
    /// Thick lines (unlit).
    pub lines: Vec<Line>,
    /// Dots (unlit).
    pub dots: Vec<Dot>,
    /// Dots drawn under everything else, whatever their depth (a workspace point cloud: it
    /// never hides the arm).
    pub underlay: Vec<Dot>,
    /// Labels for the overlay.
    pub labels: Vec<Label>,
}

impl Scene {
    /// The scene with every custom mesh that offers a coarse copy drawn with it (the live
    /// view's moving frames on a software rasterizer); `None` when there is none to swap.
    pub fn with_coarse_meshes(&self) -> Option<Scene> {
        if self.custom_meshes.iter().all(|m| m.coarse.is_none()) {
            return None;
        }
        let mut s = self.clone();
        for m in &mut s.custom_meshes {
            if let Some(c) = m.coarse.take() {
                m.mesh = c;
            }
        }
        Some(s)
    }

    /// Appends another scene.
    pub fn extend(&mut self, other: Scene) {
        self.meshes.extend(other.meshes);
        self.custom_meshes.extend(other.custom_meshes);
        self.lines.extend(other.lines);
        self.dots.extend(other.dots);
        self.underlay.extend(other.underlay);
        self.labels.extend(other.labels);
    }

    /// Centre and radius (m) of a sphere holding every mesh origin, line end and dot.
    pub fn bounds(&self) -> (Point3<f32>, f32) {
        let mut pts: Vec<Point3<f32>> = Vec::new();
        pts.extend(self.meshes.iter().map(|m| {
            Point3::new(
                m.world_from_unit[3][0],
                m.world_from_unit[3][1],
                m.world_from_unit[3][2],
            )
        }));
        pts.extend(self.custom_meshes.iter().map(|m| {
            Point3::new(
                m.world_from_mesh[3][0],
                m.world_from_mesh[3][1],
                m.world_from_mesh[3][2],
            )
        }));
        pts.extend(
            self.lines
                .iter()
                .flat_map(|l| [Point3::from(l.a), Point3::from(l.b)]),
        );
        pts.extend(self.dots.iter().map(|d| Point3::from(d.p)));
        pts.extend(self.underlay.iter().map(|d| Point3::from(d.p)));
        if pts.is_empty() {
            return (Point3::origin(), 1.0);
        }
        let (mut lo, mut hi) = (pts[0], pts[0]);
        for p in &pts {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        let c = nalgebra::center(&lo, &hi);
        let r = pts.iter().map(|p| (p - c).norm()).fold(0.0, f32::max);
        (c, r)
    }
}

/// Colours and sizes of the arm drawing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArmStyle {
    /// Link colour.
    pub link: Rgba,
    /// Revolute joint body colour.
    pub revolute: Rgba,
    /// Prismatic joint body colour.
    pub prismatic: Rgba,
    /// End-effector colour.
    pub tool: Rgba,
    /// Draw the DH frame triads.
    pub frames: bool,
    /// Label the frames (x_i, z_i and the frame number).
    pub frame_labels: bool,
    /// Draw the ground grid.
    pub grid: bool,
    /// Multiplies every colour's alpha (ghost arms use < 1).
    pub alpha: f32,
    /// Link radius as a fraction of the robot's size.
    pub link_radius: f32,
}

impl Default for ArmStyle {
    fn default() -> Self {
        Self {
            link: [0.93, 0.55, 0.15, 1.0],
            revolute: [0.20, 0.35, 0.75, 1.0],
            prismatic: [0.30, 0.60, 0.35, 1.0],
            tool: [0.35, 0.35, 0.38, 1.0],
            frames: true,
            frame_labels: true,
            grid: true,
            alpha: 1.0,
            link_radius: 0.018,
        }
    }
}

/// Axis colours: x red, y green, z blue.
pub const AXIS_COLORS: [Rgba; 3] = [
    [0.85, 0.15, 0.15, 1.0],
    [0.15, 0.65, 0.2, 1.0],
    [0.15, 0.3, 0.9, 1.0],
];

fn v32(v: &Vector3<f64>) -> [f32; 3] {
    [v.x as f32, v.y as f32, v.z as f32]
}

fn col_major(m: &Matrix4<f64>) -> [[f32; 4]; 4] {
    std::array::from_fn(|c| std::array::from_fn(|r| m[(r, c)] as f32))
}

/// `world_from_unit` of a cylinder/cube from `a` to `b` with the given cross-section radius.
fn segment_transform(a: &Vector3<f64>, b: &Vector3<f64>, radius: f64) -> Option<Matrix4<f64>> {
    let d = b - a;
    let len = d.norm();
    if len < 1e-9 {
        return None;
    }
    let rot = Rotation3::rotation_between(&Vector3::z(), &d)
        .unwrap_or_else(|| Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI));
    let mut m =
        rot.to_homogeneous() * Matrix4::new_nonuniform_scaling(&Vector3::new(radius, radius, len));
    let mid = (a + b) * 0.5;
    m[(0, 3)] = mid.x;
    m[(1, 3)] = mid.y;
    m[(2, 3)] = mid.z;
    Some(m)
}

/// The arm of `robot` at `q`, in world coordinates.
pub fn arm_scene(robot: &Robot, q: &[f64], style: &ArmStyle) -> Result<Scene, KinematicsError> {
    let frames = robot.fk_frames(q)?;
    let scale = robot.longest_chain_length();
    let mut p = ArmPainter {
        s: Scene::default(),
        style,
        scale,
        r_link: scale * style.link_radius as f64,
    };
    // The links' own visuals (a URDF's), where it has them.
    // Ghost arms (faded) are drawn with the joints' bodies: a URDF's meshes, translucent and
    // overlapping once per posture, cost the software rasterizer more fill than a frame has.
    let drawn = if style.alpha < 1.0 {
        vec![false; robot.joints().len() + 1]
    } else {
        add_visuals(&mut p.s, robot, &frames, style)
    };
    // Base pedestal.
    let base_o = robot.base.translation.vector;
    let base_z = robot.base.rotation * Vector3::z();
    if !drawn[0] {
        let r = p.r_link;
        p.segment(
            &(base_o - base_z * r * 2.0),
            &base_o,
            r * 3.5,
            style.tool,
            Shape::Cylinder,
        );
    }
    for j in 0..robot.joints().len() {
        if !drawn[j + 1] {
            p.joint(robot, &frames, q, j);
        }
    }
    p.s.dots.retain(|d| d.size_px > 0.0);
    for e in robot.end_effectors() {
        p.gripper(&(frames[e.parent] * e.tool));
    }
    if style.frames {
        p.triad(&robot.base, "0");
        for (j, f) in frames.iter().enumerate() {
            p.triad(f, &(j + 1).to_string());
        }
    }
    if style.grid {
        p.s.lines.extend(ground_grid(scale as f32));
    }
    Ok(p.s)
}

/// On a tree (a humanoid's arms) only the frames of the chain to end-effector `ee` keep their
/// labels; the others' triads stay, unlabelled.
pub fn label_driven_chain_only(scene: &mut Scene, robot: &Robot, ee: usize) {
    // A tree (a humanoid's arms): only the frames of the driven chain are labelled, unless
    // every label is asked for; the others' triads stay, unlabelled.
    let ee_link = robot.end_effectors()[ee.min(robot.end_effectors().len() - 1)].parent;
    let mut names: Vec<String> = vec!["0".into()];
    names.extend(robot.chain_to(ee_link).iter().map(|j| (j + 1).to_string()));
    // Labels of frames at one point are merged, a line each ("z0\nx1").
    let on_chain = |line: &str| {
        let frame = line.trim_start_matches(['x', 'y', 'z']);
        let is_frame = frame.len() < line.len() && frame.parse::<usize>().is_ok();
        !is_frame || names.iter().any(|n| n == frame)
    };
    for l in &mut scene.labels {
        l.text = l
            .text
            .lines()
            .filter(|t| on_chain(t))
            .collect::<Vec<_>>()
            .join("\n");
    }
    scene.labels.retain(|l| !l.text.is_empty());
}

/// Draws the parts of one arm into a scene, with the sizes and the fade they share.
struct ArmPainter<'a> {
    s: Scene,
    style: &'a ArmStyle,
    /// The robot's size (m).
    scale: f64,
    /// Link radius (m).
    r_link: f64,
}

impl ArmPainter<'_> {
    /// A colour with the style's alpha applied.
    fn fade(&self, c: Rgba) -> Rgba {
        [c[0], c[1], c[2], c[3] * self.style.alpha]
    }

    /// A cylinder or box of cross-section radius `r` from `a` to `b`.
    fn segment(&mut self, a: &Vector3<f64>, b: &Vector3<f64>, r: f64, color: Rgba, shape: Shape) {
        if let Some(m) = segment_transform(a, b, r) {
            let color = self.fade(color);
            self.s.meshes.push(MeshInstance {
                shape,
                world_from_unit: col_major(&m),
                color,
            });
        }
    }

    /// Joint j's link polyline (parent origin -> axis origin -> (standard DH: along z by d) ->
    /// output origin) and its body at the axis origin.
    fn joint(&mut self, robot: &Robot, frames: &[Pose], q: &[f64], j: usize) {
        let (style, r_link) = (self.style, self.r_link);
        let joint = &robot.joints()[j];
        let body = crate::kinematics::visual::stick_body(robot, frames, q, j);
        let (ao, z, out_o) = (
            body.axis_origin,
            body.axis,
            body.polyline[body.polyline.len() - 1],
        );
        let pts = body.polyline;
        for w in pts.windows(2) {
            self.segment(&w[0], &w[1], r_link, style.link, Shape::Cylinder);
        }
        let color = self.fade(style.link);
        self.s.dots.push(Dot {
            p: v32(&out_o),
            color,
            size_px: 0.0,
        });
        let h = self.scale * 0.07;
        match joint.kind {
            JointKind::Revolute => self.segment(
                &(ao - z * h * 0.5),
                &(ao + z * h * 0.5),
                r_link * 1.9,
                style.revolute,
                Shape::Cylinder,
            ),
            JointKind::Prismatic => {
                let d = body.extension;
                let start = ao + z * (d - h).min(0.0);
                let end = ao + z * d.max(h * 0.5);
                self.segment(&start, &end, r_link * 1.6, style.prismatic, Shape::Cube);
            }
            JointKind::Fixed => {}
        }
    }

    /// An end-effector: a small two-finger gripper along the tool z.
    fn gripper(&mut self, t: &Pose) {
        let (tool, r) = (self.style.tool, self.r_link);
        let o = t.translation.vector;
        let (x, z) = (t.rotation * Vector3::x(), t.rotation * Vector3::z());
        let w = self.scale * 0.03;
        self.segment(&(o - z * w * 1.5), &o, r * 1.2, tool, Shape::Cylinder);
        for side in [-1.0, 1.0] {
            let a = o + x * (side * w);
            self.segment(&(o - z * w * 0.3), &a, r * 0.6, tool, Shape::Cylinder);
            self.segment(&a, &(a + z * w * 1.2), r * 0.6, tool, Shape::Cylinder);
        }
    }

    /// A frame's triad, x and z labelled with the frame's number.
    fn triad(&mut self, t: &Pose, name: &str) {
        let len = (self.scale * 0.12) as f32;
        let o = v32(&t.translation.vector);
        for (k, color) in AXIS_COLORS.iter().enumerate() {
            let dir = t.rotation * Vector3::ith(k, 1.0);
            let tip = [
                o[0] + dir.x as f32 * len,
                o[1] + dir.y as f32 * len,
                o[2] + dir.z as f32 * len,
            ];
            let color = self.fade(*color);
            self.s.lines.push(Line {
                a: o,
                b: tip,
                color,
                width_px: 2.5,
            });
            if self.style.frame_labels && k != 1 {
                let axis = ["x", "y", "z"][k];
                self.s.labels.push(Label {
                    p: tip,
                    text: format!("{axis}{name}"),
                    color,
                    movable: false,
                });
            }
        }
    }
}

/// Adds the robot's visuals at the frames of their links (faded like the rest of the arm);
/// returns, for the base (index 0) and each joint's child link (j + 1), whether it has any, so
/// that the generic link and body are left out there.
fn add_visuals(s: &mut Scene, robot: &Robot, frames: &[Pose], style: &ArmStyle) -> Vec<bool> {
    let mut drawn = vec![false; robot.joints().len() + 1];
    for v in &robot.visuals {
        let frame = v.joint.map_or(robot.base, |j| frames[j]) * v.origin;
        let c = v.color.unwrap_or(style.link);
        let color = [c[0], c[1], c[2], c[3] * style.alpha];
        let m = frame.to_homogeneous();
        let unit = |scale: Vector3<f64>| col_major(&(m * Matrix4::new_nonuniform_scaling(&scale)));
        match &v.geometry {
            VisualGeometry::Box(size) => s.meshes.push(MeshInstance {
                shape: Shape::Cube,
                world_from_unit: unit(Vector3::from(*size)),
                color,
            }),
            VisualGeometry::Cylinder { radius, length } => s.meshes.push(MeshInstance {
                shape: Shape::Cylinder,
                world_from_unit: unit(Vector3::new(*radius, *radius, *length)),
                color,
            }),
            VisualGeometry::Sphere(r) => s.meshes.push(MeshInstance {
                shape: Shape::Sphere,
                world_from_unit: unit(Vector3::new(*r, *r, *r)),
                color,
            }),
            // The coarse copy is offered for a live view's moving frames.
            VisualGeometry::Mesh { mesh, coarse } => s.custom_meshes.push(CustomMesh {
                mesh: mesh.clone(),
                coarse: Some(coarse.clone()),
                world_from_mesh: col_major(&m),
                color,
            }),
        }
        drawn[v.joint.map_or(0, |j| j + 1)] = true;
    }
    drawn
}

/// Grid lines in the plane z = 0 around the origin, spaced 0.1 m (or 0.5 m for big robots).
pub fn ground_grid(scale: f32) -> Vec<Line> {
    let step = if scale > 3.0 { 0.5 } else { 0.1 };
    let n = ((scale * 0.9 / step).ceil() as i32).clamp(2, 40);
    let ext = n as f32 * step;
    let mut out = Vec::new();
    for i in -n..=n {
        let c = i as f32 * step;
        let major = i % 5 == 0;
        let color = if major {
            [0.55, 0.55, 0.58, 1.0]
        } else {
            [0.78, 0.78, 0.8, 1.0]
        };
        let width_px = if major { 1.5 } else { 1.0 };
        out.push(Line {
            a: [c, -ext, 0.0],
            b: [c, ext, 0.0],
            color,
            width_px,
        });
        out.push(Line {
            a: [-ext, c, 0.0],
            b: [ext, c, 0.0],
            color,
            width_px,
        });
    }
    out
}

/// Points a camera should frame to show the arm at `q`: base, joint frame origins and tools,
/// each padded by the size of the joint bodies along the three axes (world, m).
pub fn arm_points(robot: &Robot, q: &[f64]) -> Result<Vec<Point3<f32>>, KinematicsError> {
    let frames = robot.fk_frames(q)?;
    let pad = robot.longest_chain_length() * 0.1;
    let mut out = Vec::new();
    let centres = std::iter::once(robot.base.translation.vector)
        .chain(frames.iter().map(|f| f.translation.vector))
        .chain(
            robot
                .end_effectors()
                .iter()
                .map(|e| (frames[e.parent] * e.tool).translation.vector),
        );
    for c in centres {
        for k in 0..3 {
            for s in [-1.0, 1.0] {
                out.push(point32(&(c + Vector3::ith(k, s * pad))));
            }
        }
    }
    Ok(out)
}

/// Centre and radius (m) of a sphere around the arm at `q` (base, every joint frame and tool,
/// plus a margin for the joint bodies): what a camera should frame.
pub fn arm_bounds(robot: &Robot, q: &[f64]) -> Result<(Point3<f32>, f32), KinematicsError> {
    let frames = robot.fk_frames(q)?;
    let mut pts: Vec<Vector3<f64>> = vec![robot.base.translation.vector];
    pts.extend(frames.iter().map(|f| f.translation.vector));
    pts.extend(
        robot
            .end_effectors()
            .iter()
            .map(|e| (frames[e.parent] * e.tool).translation.vector),
    );
    let (mut lo, mut hi) = (pts[0], pts[0]);
    for p in &pts {
        lo = lo.inf(p);
        hi = hi.sup(p);
    }
    let c = (lo + hi) * 0.5;
    let r = pts.iter().map(|p| (p - c).norm()).fold(0.0, f64::max)
        + robot.longest_chain_length() * 0.08;
    Ok((point32(&c), r as f32))
}

/// The world point `p` (m, f64) as the renderer's f32.
pub fn point32(p: &Vector3<f64>) -> Point3<f32> {
    Point3::from(v32(p))
}

/// Adds a labelled frame triad (x red, y green, z blue, each `len` m long, labels `x{name}`,
/// `y{name}`, `z{name}`) at `world_from_frame`: a sheet's base and tool frames, an IK target.
pub fn frame_triad(scene: &mut Scene, world_from_frame: &Pose, name: &str, len: f64) {
    let o = world_from_frame.translation.vector;
    for (k, color) in AXIS_COLORS.iter().enumerate() {
        let tip = o + world_from_frame.rotation * Vector3::ith(k, len);
        scene.lines.push(Line {
            a: v32(&o),
            b: v32(&tip),
            color: *color,
            width_px: 3.0,
        });
        scene.labels.push(Label {
            p: v32(&tip),
            text: format!("{}{name}", ["x", "y", "z"][k]),
            color: *color,
            movable: false,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::models::BUILT_INS;

    #[test]
    fn every_built_in_makes_a_finite_scene() {
        for b in BUILT_INS {
            let r = (b.build)();
            let q = r.config("ready").unwrap().to_vec();
            let s = arm_scene(&r, &q, &ArmStyle::default()).unwrap();
            assert!(s.meshes.len() >= r.joints().len(), "{}", b.name);
            assert!(
                s.meshes
                    .iter()
                    .all(|m| m.world_from_unit.iter().flatten().all(|v| v.is_finite()))
            );
            assert!(s.labels.iter().any(|l| l.text == "z1"));
            let (_, radius) = s.bounds();
            assert!(radius > 0.0 && radius.is_finite());
        }
    }
}
