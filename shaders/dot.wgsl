// Round dots: each instance is one screen-space triangle around a circle `size_px` (+ an
// anti-aliasing margin) wide, made round in the fragment shader by coverage (discard outside).
// Dots behind the near plane are dropped. Depth is pulled towards the eye like lines.
// (Measured on lavapipe: one triangle per dot draws 1M dots about twice as fast as a quad; a
// non-instanced draw pulling dots from a storage buffer was slower still.)

// `Frame` and `frame` (group 0, binding 0) come from frame.wgsl, prepended.

// Twin of `DotGpu`.
struct DotIn {
    @location(0) p: vec3<f32>,
    @location(1) size_px: f32,
    @location(2) color: vec4<f32>,
};

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) color: vec4<f32>,
    // Offset from the dot's centre (px). Every corner has the centre's w, so perspective
    // interpolation is screen-linear here (WebGL2 has no `linear` qualifier).
    @location(1) local_px: vec2<f32>,
    @location(2) @interpolate(flat) radius: f32,
};

// Extra quad margin (px) for the anti-aliased edge.
const AA_PAD: f32 = 0.5;

@vertex
fn vs_main(@builtin(vertex_index) vi: u32, inst: DotIn) -> VertexOut {
    var out: VertexOut;
    out.color = inst.color;
    out.radius = inst.size_px * 0.5;
    out.local_px = vec2<f32>(0.0, 0.0);
    let c = frame.clip_from_world * vec4<f32>(inst.p, 1.0);
    if (c.z < 0.0 || !(inst.size_px > 0.0)) {
        out.clip = vec4<f32>(0.0, 0.0, -1.0, 1.0); // outside the clip volume: dropped
        return out;
    }
    // One triangle per dot (half the triangles of a quad; rasterizer setup dominates on a
    // software GPU): the equilateral triangle whose inscribed circle has radius
    // R = radius + AA_PAD has its corners 2R from the centre.
    let corner = vec2<f32>(select(select(1.7320508, -1.7320508, vi == 1u), 0.0, vi == 0u), select(-1.0, 2.0, vi == 0u));
    let local = corner * (out.radius + AA_PAD);
    let b = mix(c, frame.eye_clip, frame.viewport.z);
    let ndc = c.xy / c.w + local / (frame.viewport.xy * 0.5);
    out.clip = vec4<f32>(ndc * c.w, max(b.z / b.w, 0.0) * c.w, c.w);
    out.local_px = local;
    return out;
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let coverage = clamp(in.radius + 0.5 - length(in.local_px), 0.0, 1.0);
    if (coverage <= 0.0) {
        discard;
    }
    return vec4<f32>(in.color.rgb, in.color.a * coverage);
}
