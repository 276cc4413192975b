// Per-frame uniforms shared by every pipeline: the twin of `FrameUniforms` (gpu_types.rs).
// Prepended to mesh.wgsl, line.wgsl and dot.wgsl (see `render::MESH_WGSL` and the others).

struct Frame {
    clip_from_world: mat4x4<f32>,
    eye: vec4<f32>,        // xyz: eye (world)
    eye_clip: vec4<f32>,   // clip_from_world * (eye, 1)
    viewport: vec4<f32>,   // xy: size (px); z: overlay depth bias
    key_light: vec4<f32>,  // xyz: unit direction towards the light; w: intensity
    ambient: vec4<f32>,    // x: from above (+z); y: from below; z: headlight intensity
    specular: vec4<f32>,   // x: strength; y: shininess
};

@group(0) @binding(0) var<uniform> frame: Frame;

