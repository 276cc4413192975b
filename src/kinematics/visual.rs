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
