// egui's tessellated meshes (the app window's widgets), painted by `UiPainter`
// (src/figure/ui_painter.rs): vertex colour times a hardware-filtered texel, gamma space,
// premultiplied alpha, as egui-wgpu's default path does, without its run-time branches.
struct Screen {
    size_points: vec2<f32>,
    pad: vec2<f32>,
};
@group(0) @binding(0) var<uniform> screen: Screen;
@group(1) @binding(0) var t_color: texture_2d<f32>;
@group(1) @binding(1) var s_color: sampler;

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
    @location(1) color: vec4<f32>, // premultiplied, gamma-encoded
};

@vertex
fn vs_main(
    @location(0) pos: vec2<f32>,
    @location(1) uv: vec2<f32>,
    @location(2) color: u32,
) -> VertexOut {
    var out: VertexOut;
    out.clip = vec4<f32>(
        2.0 * pos.x / screen.size_points.x - 1.0,
        1.0 - 2.0 * pos.y / screen.size_points.y,
        0.0,
        1.0,
    );
    out.uv = uv;
    out.color = unpack4x8unorm(color);
    return out;
}

// A non-sRGB target: egui's colours and textures are gamma-encoded already.
@fragment
fn fs_gamma(in: VertexOut) -> @location(0) vec4<f32> {
    return in.color * textureSample(t_color, s_color, in.uv);
}

// An sRGB target encodes on write: decode first.
@fragment
fn fs_linear(in: VertexOut) -> @location(0) vec4<f32> {
    let c = in.color * textureSample(t_color, s_color, in.uv);
    let lo = c.rgb / 12.92;
    let hi = pow((c.rgb + vec3<f32>(0.055)) / 1.055, vec3<f32>(2.4));
    return vec4<f32>(select(hi, lo, c.rgb <= vec3<f32>(0.04045)), c.a);
}

// An opaque image (the 3D view) shown untinted, without blending: a plain copy of its texels,
// which the software rasterizer does much faster than the blended path.
@fragment
fn fs_copy(in: VertexOut) -> @location(0) vec4<f32> {
    return textureSample(t_color, s_color, in.uv);
}

// The same onto an sRGB target.
@fragment
fn fs_copy_linear(in: VertexOut) -> @location(0) vec4<f32> {
    let c = textureSample(t_color, s_color, in.uv);
    let lo = c.rgb / 12.92;
    let hi = pow((c.rgb + vec3<f32>(0.055)) / 1.055, vec3<f32>(2.4));
    return vec4<f32>(select(hi, lo, c.rgb <= vec3<f32>(0.04045)), c.a);
}
