// Copies a texture sampled through its sRGB view (texels decoded to linear) into an Rgba8Unorm
// target, encoding them to sRGB again: the same bytes under a non-sRGB format, for devices that
// cannot alias the two formats (WebGL2). One full-screen triangle; texel for texel.

@group(0) @binding(0) var t_color: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) vi: u32) -> @builtin(position) vec4<f32> {
    let x = f32(i32(vi & 1u) * 4 - 1);
    let y = f32(i32(vi >> 1u) * 4 - 1);
    return vec4<f32>(x, y, 0.0, 1.0);
}

@fragment
fn fs_main(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
    let c = textureLoad(t_color, vec2<i32>(pos.xy), 0);
    let lo = c.rgb * 12.92;
    let hi = 1.055 * pow(c.rgb, vec3<f32>(1.0 / 2.4)) - vec3<f32>(0.055);
    return vec4<f32>(select(hi, lo, c.rgb <= vec3<f32>(0.0031308)), c.a);
}
