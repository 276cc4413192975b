//! The render pipelines: lit meshes (opaque / translucent, each for both windings), lines and
//! dots (depth-writing / not).

use super::gpu_types::{DotGpu, FrameUniforms, LineGpu, MeshInstanceGpu, MeshVertex};
use super::{COLOR_FORMAT, DEPTH_FORMAT, DOT_WGSL, LINE_WGSL, MESH_WGSL};
use std::borrow::Cow;

/// Opaque or alpha-blended without depth writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Pass {
    /// Depth written; meshes not blended, lines and dots blended only at their edges.
    Opaque,
    /// Alpha-blended, depth tested but not written.
    Translucent,
}

/// Every pipeline the renderer uses, built for one sample count.
#[derive(Debug)]
pub(crate) struct Pipelines {
    /// Layout of group 0: the frame uniforms.
    pub frame_layout: wgpu::BindGroupLayout,
    /// Meshes, indexed by `[translucent][mirrored]` (a mirrored instance winds clockwise).
    pub mesh: [[wgpu::RenderPipeline; 2]; 2],
    /// Lines, indexed by `[translucent]`.
    pub line: [wgpu::RenderPipeline; 2],
    /// Dots, indexed by `[translucent]`.
    pub dot: [wgpu::RenderPipeline; 2],
    /// Underlay dots: no depth test or write, drawn first (covered by everything else).
    pub dot_underlay: wgpu::RenderPipeline,
}

const MESH_VERTEX_ATTRS: [wgpu::VertexAttribute; 2] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3];
const MESH_INSTANCE_ATTRS: [wgpu::VertexAttribute; 8] = wgpu::vertex_attr_array![
    2 => Float32x4, 3 => Float32x4, 4 => Float32x4, 5 => Float32x4,
    6 => Float32x4, 7 => Float32x4, 8 => Float32x4, 9 => Float32x4,
];
const LINE_ATTRS: [wgpu::VertexAttribute; 4] = [
    wgpu::VertexAttribute {
        format: wgpu::VertexFormat::Float32x3,
        offset: 0,
        shader_location: 0,
    },
    wgpu::VertexAttribute {
        format: wgpu::VertexFormat::Float32,
        offset: 12,
        shader_location: 1,
    },
    wgpu::VertexAttribute {
        format: wgpu::VertexFormat::Float32x3,
        offset: 16,
        shader_location: 2,
    },
    wgpu::VertexAttribute {
        format: wgpu::VertexFormat::Float32x4,
        offset: 32,
        shader_location: 3,
    },
];
const DOT_ATTRS: [wgpu::VertexAttribute; 3] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32, 2 => Float32x4];

fn instance_layout<T>(attributes: &[wgpu::VertexAttribute]) -> wgpu::VertexBufferLayout<'_> {
    wgpu::VertexBufferLayout {
        array_stride: size_of::<T>() as u64,
        step_mode: wgpu::VertexStepMode::Instance,
        attributes,
    }
}

struct PipelineSpec<'a> {
    label: &'static str,
    module: &'a wgpu::ShaderModule,
    buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    topology: wgpu::PrimitiveTopology,
    front_face: wgpu::FrontFace,
    cull_mode: Option<wgpu::Face>,
    blend: Option<wgpu::BlendState>,
    depth_write: bool,
    /// `Always` for the underlay, `Less` otherwise.
    depth_compare: wgpu::CompareFunction,
}

/// Layout of group 0: the frame uniforms, visible to vertex and fragment stages.
fn frame_bind_group_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("armlab frame"),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(size_of::<FrameUniforms>() as u64),
            },
            count: None,
        }],
    })
}

/// Compiles one WGSL shader.
fn shader_module(
    device: &wgpu::Device,
    label: &'static str,
    source: &'static str,
) -> wgpu::ShaderModule {
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(Cow::Borrowed(source)),
    })
}

/// Builds one pipeline from `spec`: entry points `vs_main` / `fs_main`, depth test `Less`
/// against [`DEPTH_FORMAT`], one [`COLOR_FORMAT`] target, `sample_count` samples per pixel.
fn render_pipeline(
    device: &wgpu::Device,
    layout: &wgpu::PipelineLayout,
    sample_count: u32,
    spec: PipelineSpec<'_>,
) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(spec.label),
        layout: Some(layout),
        vertex: wgpu::VertexState {
            module: spec.module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: spec.buffers,
        },
        primitive: wgpu::PrimitiveState {
            topology: spec.topology,
            strip_index_format: None,
            front_face: spec.front_face,
            cull_mode: spec.cull_mode,
            unclipped_depth: false,
            polygon_mode: wgpu::PolygonMode::Fill,
            conservative: false,
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(spec.depth_write),
            depth_compare: Some(spec.depth_compare),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: wgpu::MultisampleState {
            count: sample_count,
            mask: !0,
            alpha_to_coverage_enabled: false,
        },
        fragment: Some(wgpu::FragmentState {
            module: spec.module,
            entry_point: Some("fs_main"),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format: COLOR_FORMAT,
                blend: spec.blend,
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}

impl Pipelines {
    /// Compiles the shaders and builds every pipeline for `sample_count` samples per pixel.
    pub(crate) fn new(device: &wgpu::Device, sample_count: u32) -> Self {
        let frame_layout = frame_bind_group_layout(device);
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("armlab"),
            bind_group_layouts: &[Some(&frame_layout)],
            immediate_size: 0,
        });
        let (mesh_module, line_module, dot_module) = (
            shader_module(device, "mesh.wgsl", MESH_WGSL),
            shader_module(device, "line.wgsl", LINE_WGSL),
            shader_module(device, "dot.wgsl", DOT_WGSL),
        );
        let build = |spec: PipelineSpec<'_>| render_pipeline(device, &layout, sample_count, spec);
        let mesh_buffers = [
            Some(wgpu::VertexBufferLayout {
                array_stride: size_of::<MeshVertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &MESH_VERTEX_ATTRS,
            }),
            Some(instance_layout::<MeshInstanceGpu>(&MESH_INSTANCE_ATTRS)),
        ];
        let line_buffers = [Some(instance_layout::<LineGpu>(&LINE_ATTRS))];
        let dot_buffers = [Some(instance_layout::<DotGpu>(&DOT_ATTRS))];
        let blend_for = |pass| match pass {
            Pass::Opaque => None,
            Pass::Translucent => Some(wgpu::BlendState::ALPHA_BLENDING),
        };
        let mesh = |pass: Pass, front_face| {
            build(PipelineSpec {
                label: "armlab mesh",
                module: &mesh_module,
                buffers: &mesh_buffers,
                topology: wgpu::PrimitiveTopology::TriangleList,
                front_face,
                cull_mode: Some(wgpu::Face::Back),
                blend: blend_for(pass),
                depth_write: pass == Pass::Opaque,
                depth_compare: wgpu::CompareFunction::Less,
            })
        };
        let overlay = |label, module, buffers, topology, pass: Pass| {
            build(PipelineSpec {
                label,
                module,
                buffers,
                topology,
                front_face: wgpu::FrontFace::Ccw,
                cull_mode: None,
                // Lines and dots blend in both passes: their anti-aliased edges need it.
                blend: Some(wgpu::BlendState::ALPHA_BLENDING),
                depth_write: pass == Pass::Opaque,
                depth_compare: wgpu::CompareFunction::Less,
            })
        };
        let dot_underlay = build(PipelineSpec {
            label: "armlab underlay dot",
            module: &dot_module,
            buffers: &dot_buffers,
            topology: wgpu::PrimitiveTopology::TriangleList,
            front_face: wgpu::FrontFace::Ccw,
            cull_mode: None,
            blend: Some(wgpu::BlendState::ALPHA_BLENDING),
            depth_write: false,
            depth_compare: wgpu::CompareFunction::Always,
        });
        use wgpu::FrontFace::{Ccw, Cw};
        use wgpu::PrimitiveTopology::{TriangleList, TriangleStrip};
        Self {
            mesh: [
                [mesh(Pass::Opaque, Ccw), mesh(Pass::Opaque, Cw)],
                [mesh(Pass::Translucent, Ccw), mesh(Pass::Translucent, Cw)],
            ],
            line: [Pass::Opaque, Pass::Translucent]
                .map(|p| overlay("armlab line", &line_module, &line_buffers, TriangleStrip, p)),
            dot: [Pass::Opaque, Pass::Translucent]
                .map(|p| overlay("armlab dot", &dot_module, &dot_buffers, TriangleList, p)),
            dot_underlay,
            frame_layout,
        }
    }
}
