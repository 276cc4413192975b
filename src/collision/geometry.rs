//! The robot's links as convex collision parts, each fixed in its link's frame, or (a stick
//! body) placed along the drawn stick figure at each configuration.

use crate::kinematics::visual::{JOINT_BODY_LENGTH_FRACTION, StickBody, VisualGeometry};
use crate::kinematics::{JointId, JointKind, Pose, Robot};
use crate::mesh::TriMesh;
use parry3d_f64::math::{Pose as PPose, Rot3, Vec3};
use parry3d_f64::shape::{Ball, Capsule, Cylinder, Shape, SharedShape};

/// How meshes become convex parts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct GeometryOptions {
    /// Split each mesh into convex pieces (parry's VHACD) instead of taking its convex hull:
    /// closer to a concave link (a gripper's fingers), slower to build (about a second per
    /// mesh) and to check (one query per piece).
    pub decompose_meshes: bool,
}

/// What a body is.
#[derive(Debug, Clone, PartialEq)]
pub enum BodyKind {
    /// A link of the robot: the joint whose child it is (`None`: the root link, the base).
    Link(Option<JointId>),
    /// An obstacle of the scene (its index in [`super::CellScene::obstacles`]).
    Obstacle(usize),
}

/// One rigid body that collision reports name: a link or an obstacle.
#[derive(Debug, Clone)]
pub struct Body {
    /// The name reports use: the URDF link's name, "base" and "link1".."linkN" for a DH model
    /// (link i moves with joint i), or the obstacle's name.
    pub name: String,
    /// Link or obstacle.
    pub kind: BodyKind,
    /// Whether it moves with no joint variable (the base, links on fixed joints to it, world
    /// obstacles).
    pub fixed: bool,
    /// Convex parts in the body's frame (`frame_from_part`, m).
    pub(super) parts: Vec<(PPose, SharedShape)>,
    /// Whether the body is the drawn stick figure (capsules along its joint's polyline), placed
    /// per configuration.
    pub(super) stick: bool,
}

/// The links of one robot as collision bodies, built once per robot.
#[derive(Debug, Clone)]
pub struct RobotGeometry {
    /// One body per link with geometry: the root link first, then the joints' child links in
    /// joint order.
    pub bodies: Vec<Body>,
    /// The radius of the stick figure's capsules (m).
    pub link_radius: f64,
    /// The robot's size the joints' bodies scale with (m).
    pub(super) scale: f64,
    /// What building it said (a mesh with too few points for a hull).
    pub warnings: Vec<String>,
}

/// nalgebra pose to parry pose.
pub(super) fn to_parry(p: &Pose) -> PPose {
    let q = nalgebra::UnitQuaternion::from_rotation_matrix(&p.rotation);
    let t = p.translation.vector;
    PPose::from_parts(
        Vec3::new(t.x, t.y, t.z),
        Rot3::from_xyzw(q.i, q.j, q.k, q.w),
    )
}

/// A mesh's convex parts: its hull, or a convex decomposition.
pub(super) fn mesh_parts(
    mesh: &TriMesh,
    decompose: bool,
) -> Result<Vec<(PPose, SharedShape)>, String> {
    let points: Vec<Vec3> = mesh
        .positions
        .iter()
        .map(|p| Vec3::new(p[0].into(), p[1].into(), p[2].into()))
        .collect();
    if points.len() < 4 || mesh.triangles.is_empty() {
        return Err("the mesh has no volume (fewer than 4 points or no triangles)".into());
    }
    if decompose {
        let decomposed = SharedShape::convex_decomposition(&points, &mesh.triangles);
        if let Some(c) = decomposed.as_compound() {
            let parts: Vec<_> = c.shapes().to_vec();
            if !parts.is_empty() {
                return Ok(parts);
            }
        }
    }
    SharedShape::convex_hull(&points)
        .map(|s| vec![(PPose::IDENTITY, s)])
        .ok_or_else(|| "the mesh's points are flat or degenerate: no convex hull".into())
}

/// One primitive or mesh as convex parts in the link frame.
fn visual_parts(
    origin: &Pose,
    geometry: &VisualGeometry,
    options: GeometryOptions,
) -> Result<Vec<(PPose, SharedShape)>, String> {
    let frame_from_shape = to_parry(origin);
    // URDF cylinders are along z; parry's along y.
    let y_to_z = PPose::from_rotation(Rot3::from_rotation_x(std::f64::consts::FRAC_PI_2));
    Ok(match geometry {
        VisualGeometry::Box(s) => vec![(
            frame_from_shape,
            SharedShape::cuboid(s[0] / 2.0, s[1] / 2.0, s[2] / 2.0),
        )],
        VisualGeometry::Cylinder { radius, length } => vec![(
            frame_from_shape * y_to_z,
            SharedShape::cylinder(length / 2.0, *radius),
        )],
        VisualGeometry::Sphere(r) => vec![(frame_from_shape, SharedShape::ball(*r))],
        VisualGeometry::Mesh { mesh, .. } => mesh_parts(mesh, options.decompose_meshes)?
            .into_iter()
            .map(|(p, s)| (frame_from_shape * p, s))
            .collect(),
    })
}

impl RobotGeometry {
    /// The robot's collision bodies: its `collisions` (a URDF's), and for every link without
    /// any, the stick figure the scene draws for it.
    pub fn of(robot: &Robot, options: GeometryOptions) -> RobotGeometry {
        let scale = robot.longest_chain_length();
        let mut warnings = Vec::new();
        let n = robot.joints().len();
        let mut parts: Vec<Vec<(PPose, SharedShape)>> = vec![Vec::new(); n + 1];
        for c in &robot.collisions {
            let slot = c.joint.map_or(0, |j| j + 1);
            match visual_parts(&c.origin, &c.geometry, options) {
                Ok(p) => parts[slot].extend(p),
                Err(e) => warnings.push(format!(
                    "link \"{}\": a collision mesh is left out: {e}",
                    link_name(robot, c.joint)
                )),
            }
        }
        let mut bodies = Vec::with_capacity(n + 1);
        for (slot, parts) in parts.into_iter().enumerate() {
            let joint = slot.checked_sub(1);
            bodies.push(Body {
                name: link_name(robot, joint),
                kind: BodyKind::Link(joint),
                fixed: joint.is_none_or(|j| moves_with_nothing(robot, j)),
                stick: parts.is_empty(),
                parts,
            });
        }
        RobotGeometry {
            bodies,
            link_radius: StickBody::link_radius(scale),
            scale,
            warnings,
        }
    }

    /// The index of the body of `joint`'s child link (`None`: the root link).
    pub fn body_of(&self, joint: Option<JointId>) -> usize {
        joint.map_or(0, |j| j + 1)
    }

    /// The stick body of joint `j` (`None`: the base pedestal) at a configuration, as convex
    /// parts in the world frame: capsules along its polyline, and a prismatic joint's body.
    pub(super) fn stick_parts(
        &self,
        robot: &Robot,
        frames: &[Pose],
        q: &[f64],
        j: Option<JointId>,
        out: &mut Vec<(PPose, StickPart)>,
    ) {
        let r = self.link_radius;
        let v = |p: &nalgebra::Vector3<f64>| Vec3::new(p.x, p.y, p.z);
        let Some(j) = j else {
            // The base pedestal: a cylinder of 3.5 link radii, 2 deep, under the base.
            let o = robot.base.translation.vector;
            let z = robot.base.rotation * nalgebra::Vector3::z();
            out.push(cylinder_between(v(&(o - z * r * 2.0)), v(&o), r * 3.5));
            return;
        };
        let body = crate::kinematics::visual::stick_body(robot, frames, q, j);
        for w in body.polyline.windows(2) {
            if (w[1] - w[0]).norm() > 1e-12 {
                let c = Capsule::new(v(&w[0]), v(&w[1]), r);
                out.push((PPose::IDENTITY, StickPart::Capsule(c)));
            }
        }
        // A prismatic joint's sliding body, as drawn. A revolute joint's drum is left out: at
        // a spherical wrist three drums overlap by construction, and the links' capsules
        // already cover the joint.
        if robot.joints()[j].kind == JointKind::Prismatic {
            let (ao, z) = (body.axis_origin, body.axis);
            let h = self.scale * JOINT_BODY_LENGTH_FRACTION;
            let d = body.extension;
            let (a, b) = (ao + z * (d - h).min(0.0), ao + z * d.max(h * 0.5));
            let c = Capsule::new(v(&a), v(&b), r * 1.6);
            out.push((PPose::IDENTITY, StickPart::Capsule(c)));
        }
    }
}

/// A stick body's part, made anew at each configuration: owned, so that placing a stick
/// figure allocates no shared shape (those allocations were a sixth of a Puma report).
#[derive(Debug, Clone, Copy)]
pub(super) enum StickPart {
    /// A link segment or a prismatic joint's body.
    Capsule(Capsule),
    /// The base pedestal.
    Cylinder(Cylinder),
    /// The pedestal of a base with no depth.
    Ball(Ball),
}

impl StickPart {
    /// The part as parry's queries take it.
    pub(super) fn shape(&self) -> &dyn Shape {
        match self {
            StickPart::Capsule(c) => c,
            StickPart::Cylinder(c) => c,
            StickPart::Ball(b) => b,
        }
    }
}

/// A cylinder of `radius` from `a` to `b` (world), as a parry cylinder and its pose; a ball
/// when `a` and `b` coincide.
fn cylinder_between(a: Vec3, b: Vec3, radius: f64) -> (PPose, StickPart) {
    let axis = b - a;
    let len = axis.length();
    if len < 1e-12 {
        return (
            PPose::from_translation(a),
            StickPart::Ball(Ball::new(radius)),
        );
    }
    let rot = Rot3::from_rotation_arc(Vec3::Y, axis / len);
    (
        PPose::from_parts((a + b) * 0.5, rot),
        StickPart::Cylinder(Cylinder::new(len / 2.0, radius)),
    )
}

/// Whether joint `j`'s child link moves with no joint variable (fixed joints down from the
/// base).
fn moves_with_nothing(robot: &Robot, j: JointId) -> bool {
    robot
        .chain_to(j)
        .iter()
        .all(|&k| robot.joints()[k].kind == JointKind::Fixed)
}

/// The name of `joint`'s child link: the URDF link's, else "linkN" (N = joint index + 1), or
/// the root link's ("base" for a DH model).
pub(super) fn link_name(robot: &Robot, joint: Option<JointId>) -> String {
    match joint {
        None => robot.root_link.clone().unwrap_or_else(|| "base".into()),
        Some(j) => robot
            .link_frames
            .iter()
            .find(|(_, k)| *k == j)
            .map_or_else(|| format!("link{}", j + 1), |(n, _)| n.clone()),
    }
}

/// parry pose to nalgebra pose.
pub(super) fn from_parry(p: &PPose) -> Pose {
    let r = p.rotation;
    let q =
        nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(r.w, r.x, r.y, r.z));
    let t = p.translation;
    Pose::from_parts(
        nalgebra::Translation3::new(t.x, t.y, t.z),
        q.to_rotation_matrix(),
    )
}
