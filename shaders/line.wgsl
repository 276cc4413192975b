// Screen-space thick lines: each instance is a quad `width_px` wide, expanded in the vertex
// shader from the projected ends, with an anti-aliased edge and square caps. The segment is
// clipped to the near plane first, so a line with one end behind the camera draws the visible
// part. Depth is pulled towards the eye by a small fraction (`viewport.z`) so lines lying on a
// surface are not hidden by it.

// `Frame` and `frame` (group 0, binding 0) come from frame.wgsl, prepended.

// Twin of `LineGpu` (its padding word is not read).
struct LineIn {
    @location(0) a: vec3<f32>,
    @location(1) width_px: f32,
    @location(2) b: vec3<f32>,
    @location(3) color: vec4<f32>,
};

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) color: vec4<f32>,
    // Signed distance from the centre line (px), interpolated in screen space (the quad is a
    // parallelogram in pixels) without the `linear` qualifier, which WebGL2 lacks: across_px * w
    // and w interpolated perspective-correctly have the screen-linear across_px as their ratio.
    @location(1) across_w: f32,
    @location(2) @interpolate(flat) half_width: f32,
    @location(3) w: f32,
};

// Extra quad margin (px) for the anti-aliased edge.
const AA_PAD: f32 = 0.5;

// Clip position -> (ndc depth of the same point pulled towards the eye).
fn biased_depth(c: vec4<f32>) -> f32 {
    let b = mix(c, frame.eye_clip, frame.viewport.z);
    return max(b.z / b.w, 0.0);
}

@vertex
fn vs_main(@builtin(vertex_index) vi: u32, inst: LineIn) -> VertexOut {
    var out: VertexOut;
    out.color = inst.color;
    out.half_width = inst.width_px * 0.5;
    out.across_w = 0.0;
    out.w = 1.0;
    let ca0 = frame.clip_from_world * vec4<f32>(inst.a, 1.0);
    let cb0 = frame.clip_from_world * vec4<f32>(inst.b, 1.0);
    // In front of the near plane means z >= 0 in wgpu's clip space.
    if ((ca0.z < 0.0 && cb0.z < 0.0) || !(inst.width_px > 0.0)) {
        out.clip = vec4<f32>(0.0, 0.0, -1.0, 1.0); // outside the clip volume: dropped
        return out;
    }
    let t_near = ca0.z / (ca0.z - cb0.z);
    let ca = select(ca0, mix(ca0, cb0, t_near), ca0.z < 0.0);
    let cb = select(cb0, mix(ca0, cb0, t_near), cb0.z < 0.0);

    let half_vp = frame.viewport.xy * 0.5;
    let sa = ca.xy / ca.w * half_vp;
    let sb = cb.xy / cb.w * half_vp;
    let d = sb - sa;
    let len = length(d);
    let dir = select(vec2<f32>(1.0, 0.0), d / len, len > 1e-4);
    let normal = vec2<f32>(-dir.y, dir.x);

    // Triangle strip corners: 0 = (a, -), 1 = (a, +), 2 = (b, -), 3 = (b, +).
    let at_b = (vi & 2u) != 0u;
    let side = select(-1.0, 1.0, (vi & 1u) != 0u);
    let along = select(-1.0, 1.0, at_b);
    let reach = out.half_width + AA_PAD;
    let offset_px = normal * (side * reach) + dir * (along * out.half_width);

    let c = select(ca, cb, at_b);
    let ndc = c.xy / c.w + offset_px / half_vp;
    out.clip = vec4<f32>(ndc * c.w, biased_depth(c) * c.w, c.w);
    out.across_w = side * reach * c.w;
    out.w = c.w;
    return out;
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let across_px = in.across_w / in.w;
    let coverage = clamp(in.half_width + 0.5 - abs(across_px), 0.0, 1.0);
    if (coverage <= 0.0) {
        discard;
    }
    return vec4<f32>(in.color.rgb, in.color.a * coverage);
}
