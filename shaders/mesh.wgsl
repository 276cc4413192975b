// Lit, instanced unit shapes (cylinder, cube, sphere, cone).
// Lighting: hemisphere ambient + a soft key light (Lambert + a little Blinn specular) + a
// headlight from the eye, so no face the camera sees goes black.

// `Frame` and `frame` (group 0, binding 0) come from frame.wgsl, prepended.

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
};

// Twin of `MeshInstanceGpu`: world_from_unit as 4 columns, normal_from_unit as 3, colour.
struct InstanceIn {
    @location(2) world_from_unit_0: vec4<f32>,
    @location(3) world_from_unit_1: vec4<f32>,
    @location(4) world_from_unit_2: vec4<f32>,
    @location(5) world_from_unit_3: vec4<f32>,
    @location(6) normal_from_unit_0: vec4<f32>,
    @location(7) normal_from_unit_1: vec4<f32>,
    @location(8) normal_from_unit_2: vec4<f32>,
    @location(9) color: vec4<f32>,
};

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) color: vec4<f32>,
};

@vertex
fn vs_main(v: VertexIn, inst: InstanceIn) -> VertexOut {
    let world_from_unit = mat4x4<f32>(
        inst.world_from_unit_0,
        inst.world_from_unit_1,
        inst.world_from_unit_2,
        inst.world_from_unit_3,
    );
    let normal_from_unit = mat3x3<f32>(
        inst.normal_from_unit_0.xyz,
        inst.normal_from_unit_1.xyz,
        inst.normal_from_unit_2.xyz,
    );
    let world = world_from_unit * vec4<f32>(v.position, 1.0);
    var out: VertexOut;
    out.clip = frame.clip_from_world * world;
    out.world = world.xyz;
    out.normal = normal_from_unit * v.normal;
    out.color = inst.color;
    return out;
}

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    let v = normalize(frame.eye.xyz - in.world);
    // A fully degenerate instance (all scales 0) has no normal: face the viewer then.
    let len2 = dot(in.normal, in.normal);
    var n = select(v, in.normal * inverseSqrt(len2), len2 > 1e-20);
    if (!front) {
        n = -n;
    }
    let l = frame.key_light.xyz;
    let hemi = mix(frame.ambient.y, frame.ambient.x, n.z * 0.5 + 0.5);
    let key = max(dot(n, l), 0.0) * frame.key_light.w;
    let head = max(dot(n, v), 0.0) * frame.ambient.z;
    let h = normalize(l + v);
    let spec = frame.specular.x * pow(max(dot(n, h), 0.0), frame.specular.y) * step(0.0, dot(n, l));
    let rgb = in.color.rgb * (hemi + key + head) + vec3<f32>(spec * frame.key_light.w);
    return vec4<f32>(rgb, in.color.a);
}
