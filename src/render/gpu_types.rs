//! Structs shared with the shaders. Each mirrors its WGSL twin field by field (same names, same
//! order); a const assertion pins the size so a change on one side shows on the other.

use bytemuck::{Pod, Zeroable};

/// Per-frame uniforms: `struct Frame` in every shader (group 0, binding 0).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub(crate) struct FrameUniforms {
    /// Column-major `clip_from_world`.
    pub clip_from_world: [[f32; 4]; 4],
    /// xyz: eye (world, m); w: 0.
    pub eye: [f32; 4],
    /// `clip_from_world * (eye, 1)`: lerping a clip position towards it moves the point
    /// towards the eye (the overlay depth bias).
    pub eye_clip: [f32; 4],
    /// xy: viewport size (px); z: overlay depth bias (fraction of the distance to the eye); w: 0.
    pub viewport: [f32; 4],
    /// xyz: unit direction towards the key light (world); w: key intensity.
    pub key_light: [f32; 4],
    /// x: ambient from above (+z); y: ambient from below; z: headlight intensity; w: 0.
    pub ambient: [f32; 4],
    /// x: specular strength; y: shininess (Blinn exponent); zw: 0.
    pub specular: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<FrameUniforms>() == 160);

/// Vertex of a unit shape (`VertexIn` in mesh.wgsl).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub(crate) struct MeshVertex {
    /// Position in the unit shape's frame.
    pub position: [f32; 3],
    /// Outward unit normal.
    pub normal: [f32; 3],
}
const _: () = assert!(std::mem::size_of::<MeshVertex>() == 24);

/// One mesh instance (`InstanceIn` in mesh.wgsl; the matrices as columns).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub(crate) struct MeshInstanceGpu {
    /// Columns of `world_from_unit`.
    pub world_from_unit: [[f32; 4]; 4],
    /// Columns (xyz; w = 0) of the inverse-transpose of its 3x3 part, up to a positive factor.
    pub normal_from_unit: [[f32; 4]; 3],
    /// Linear RGBA.
    pub color: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<MeshInstanceGpu>() == 128);

/// One line (`LineIn` in line.wgsl).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub(crate) struct LineGpu {
    /// Start (world, m).
    pub a: [f32; 3],
    /// Width (px).
    pub width_px: f32,
    /// End (world, m).
    pub b: [f32; 3],
    /// Unused (keeps 16-byte columns).
    pub pad: f32,
    /// Linear RGBA.
    pub color: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<LineGpu>() == 48);

/// One dot (`DotIn` in dot.wgsl).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub(crate) struct DotGpu {
    /// Centre (world, m).
    pub p: [f32; 3],
    /// Diameter (px).
    pub size_px: f32,
    /// Linear RGBA.
    pub color: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<DotGpu>() == 32);
