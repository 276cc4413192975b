//! What a robot looks like, as data (no I/O, no graphics): the visual geometry of its links as a
//! URDF's `<visual>` elements give it (boxes, cylinders, spheres, triangle meshes), each in the
//! frame of the joint whose child link carries it. The renderer's scene draws them; without
//! visuals the arm is drawn from its joints (a stick figure along the DH geometry).

use super::{JointId, Pose};
use crate::mesh::TriMesh;
use std::sync::Arc;

/// The shape of one visual, in the visual's frame (m).
#[derive(Debug, Clone, PartialEq)]
pub enum VisualGeometry {
    /// A box centred on the origin with these edge lengths.
    Box([f64; 3]),
    /// A cylinder along z centred on the origin.
    Cylinder {
        /// Radius (m).
        radius: f64,
        /// Length (m).
        length: f64,
    },
    /// A sphere about the origin.
    Sphere(f64),
    /// A triangle mesh (shared: links that use the same file share one copy).
    Mesh {
        /// The mesh as read (decimated only past the loader's budget).
        mesh: Arc<TriMesh>,
        /// A coarse copy (at most [`crate::mesh::COARSE_TRIANGLES`] triangles) for the frames a live view
        /// draws while it moves on a software rasterizer.
        coarse: Arc<TriMesh>,
    },
}

/// One visual element of a link.
#[derive(Debug, Clone, PartialEq)]
pub struct Visual {
    /// The joint whose child link carries it (its frame is that joint's frame); `None` for the
    /// root link (the robot's base frame).
    pub joint: Option<JointId>,
    /// `frame_from_visual` (the URDF `<origin>` of the visual).
    pub origin: Pose,
    /// The shape.
    pub geometry: VisualGeometry,
    /// RGBA in [0, 1] from the material, if it gives one.
    pub color: Option<[f32; 4]>,
}

/// How a joint without visuals is drawn, and checked for collision: its link as a polyline of
/// points (world frame, m) and its body on the joint axis. The scene draws exactly this; the
/// collision checker puts capsules of [`StickBody::link_radius`] along the polyline.
#[derive(Debug, Clone, PartialEq)]
pub struct StickBody {
    /// Parent origin, axis origin, (standard DH: the axis origin moved by d along z), output
    /// origin (world frame, m).
    pub polyline: Vec<nalgebra::Vector3<f64>>,
    /// Where the joint axis is drawn: its origin (world frame, m).
    pub axis_origin: nalgebra::Vector3<f64>,
    /// The joint axis (world frame, unit).
    pub axis: nalgebra::Vector3<f64>,
    /// The joint variable's length along the axis for a prismatic joint (m); 0 otherwise.
    pub extension: f64,
}

/// The drawn link radius as a fraction of the robot's longest chain (the scene's default
/// `link_radius`).
pub const LINK_RADIUS_FRACTION: f64 = 0.018;
/// The length of a revolute joint's body along its axis, as a fraction of the longest chain.
pub const JOINT_BODY_LENGTH_FRACTION: f64 = 0.07;

impl StickBody {
    /// The link radius a robot of `longest_chain` metres is drawn with (m).
    pub fn link_radius(longest_chain: f64) -> f64 {
        longest_chain * LINK_RADIUS_FRACTION
    }
}

/// For joint `j`: the frame whose z (DH) or `axis` (URDF) is the joint axis, in the world.
pub fn axis_frame(
    robot: &super::Robot,
    frames: &[Pose],
    j: usize,
) -> (Pose, nalgebra::Unit<nalgebra::Vector3<f64>>) {
    use super::pose::{rot_x, trans_x};
    use super::{Convention, JointGeometry};
    let joint = &robot.joints()[j];
    let parent = joint.parent.map_or(robot.base, |p| frames[p]);
    let f = parent * joint.pre;
    match &joint.geometry {
        JointGeometry::Dh {
            row,
            convention: Convention::Modified,
        } => (
            f * rot_x(row.alpha) * trans_x(row.a),
            nalgebra::Vector3::z_axis(),
        ),
        JointGeometry::Dh { .. } => (f, nalgebra::Vector3::z_axis()),
        JointGeometry::Origin {
            parent_from_joint,
            axis,
        } => (f * parent_from_joint, *axis),
    }
}

/// Joint `j`'s stick body at `q`, with `frames` = `robot.fk_frames(q)`: parent origin -> axis
/// origin -> (standard DH: along z by d) -> output origin.
pub fn stick_body(robot: &super::Robot, frames: &[Pose], q: &[f64], j: usize) -> StickBody {
    use super::{Convention, JointGeometry, JointKind};
    let joint = &robot.joints()[j];
    let parent_o = joint.parent.map_or(robot.base.translation.vector, |p| {
        frames[p].translation.vector
    });
    let (af, axis) = axis_frame(robot, frames, j);
    let ao = af.translation.vector;
    let z = af.rotation * axis.into_inner();
    let out_o = frames[j].translation.vector;
    let mut polyline = vec![parent_o, ao];
    let extension = if joint.kind == JointKind::Prismatic {
        robot.joint_variable(j, q) + joint.offset
    } else {
        0.0
    };
    if let JointGeometry::Dh {
        row,
        convention: Convention::Standard,
    } = joint.geometry
    {
        let d = if joint.kind == JointKind::Prismatic {
            extension
        } else {
            row.d
        };
        polyline.push(ao + z * d);
    }
    polyline.push(out_o);
    StickBody {
        polyline,
        axis_origin: ao,
        axis: z,
        extension,
    }
}
