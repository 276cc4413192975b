//! Shows a texture of the renderer (the 3D view) inside an egui layout through an egui-wgpu
//! paint callback: one textured triangle with a minimal shader, instead of an egui image.
//!
//! Why: egui-wgpu's own shader carries a run-time branch for its "predictable texture
//! filtering" that software rasterizers (lavapipe from Mesa 22) execute on both sides, which
//! makes every pixel egui paints several times dearer than a plain texture fetch. The 3D view is
//! the largest thing in the app window; copying it with this blit keeps its cost at a texture
//! fetch per pixel. The pixels are the same: the texture has exactly the size of the rectangle.
//!
//! [`install`] must run once per egui-wgpu renderer (with the format it draws into) before a
//! frame holding a [`TextureBlit`] is painted; a blit without resources draws nothing.

use egui_wgpu::CallbackResources;

/// The blit's WGSL: `vs_main`, and `fs_gamma` / `fs_linear` for non-sRGB / sRGB targets.
pub const BLIT_WGSL: &str = r#"
struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
};

@group(0) @binding(0) var t_color: texture_2d<f32>;
@group(0) @binding(1) var s_color: sampler;

// One triangle covering the callback's viewport: uv (0, 0) at its top left, (1, 1) at the
// bottom right.
@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> VertexOut {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    var out: VertexOut;
    out.clip = vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, 0.0, 1.0);
    out.uv = uv;
    return out;
}

// The texture holds gamma-encoded colour; so does a non-sRGB target.
@fragment
fn fs_gamma(in: VertexOut) -> @location(0) vec4<f32> {
    return vec4<f32>(textureSample(t_color, s_color, in.uv).rgb, 1.0);
}

// An sRGB target encodes on write: decode first.
@fragment
fn fs_linear(in: VertexOut) -> @location(0) vec4<f32> {
    let c = textureSample(t_color, s_color, in.uv).rgb;
    let lo = c / 12.92;
    let hi = pow((c + vec3<f32>(0.055)) / 1.055, vec3<f32>(2.4));
    return vec4<f32>(select(hi, lo, c <= vec3<f32>(0.04045)), 1.0);
}
"#;

/// The pipeline (for one target format) and the bind group of the texture shown last.
struct BlitResources {
    layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    pipeline: wgpu::RenderPipeline,
    bound: Option<(wgpu::TextureView, wgpu::BindGroup)>,
}

/// Builds the blit pipeline for render passes into `format` (one sample, no depth, as egui-wgpu
/// paints) and stores it in `renderer`'s callback resources.
pub fn install(
    renderer: &mut egui_wgpu::Renderer,
    device: &wgpu::Device,
    format: wgpu::TextureFormat,
) {
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("armlab blit"),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: true },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 1,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                count: None,
            },
        ],
    });
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("blit.wgsl"),
        source: wgpu::ShaderSource::Wgsl(BLIT_WGSL.into()),
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("armlab blit"),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("armlab blit"),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some(if format.is_srgb() {
                "fs_linear"
            } else {
                "fs_gamma"
            }),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format,
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    });
    let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("armlab blit"),
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    });
    renderer.callback_resources.insert(BlitResources {
        layout,
        sampler,
        pipeline,
        bound: None,
    });
}

/// Whether [`install`] ran for `renderer`.
pub fn installed(renderer: &egui_wgpu::Renderer) -> bool {
    renderer.callback_resources.contains::<BlitResources>()
}

/// A paint callback drawing `view` (format `Rgba8Unorm`, gamma-encoded) over its rectangle.
#[derive(Debug, Clone)]
pub struct TextureBlit {
    /// The texture to show.
    pub view: wgpu::TextureView,
}

impl TextureBlit {
    /// The egui shape drawing `view` over `rect` (points).
    pub fn shape(view: wgpu::TextureView, rect: egui::Rect) -> egui::Shape {
        egui::Shape::Callback(egui_wgpu::Callback::new_paint_callback(rect, Self { view }))
    }
}

impl egui_wgpu::CallbackTrait for TextureBlit {
    fn prepare(
        &self,
        device: &wgpu::Device,
        _queue: &wgpu::Queue,
        _screen: &egui_wgpu::ScreenDescriptor,
        _encoder: &mut wgpu::CommandEncoder,
        resources: &mut CallbackResources,
    ) -> Vec<wgpu::CommandBuffer> {
        if let Some(r) = resources.get_mut::<BlitResources>()
            && r.bound.as_ref().is_none_or(|(v, _)| *v != self.view)
        {
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("armlab blit"),
                layout: &r.layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: wgpu::BindingResource::TextureView(&self.view),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::Sampler(&r.sampler),
                    },
                ],
            });
            r.bound = Some((self.view.clone(), group));
        }
        Vec::new()
    }

    fn paint(
        &self,
        _info: egui::PaintCallbackInfo,
        pass: &mut wgpu::RenderPass<'static>,
        resources: &CallbackResources,
    ) {
        if let Some(r) = resources.get::<BlitResources>()
            && let Some((view, group)) = &r.bound
            && *view == self.view
        {
            pass.set_pipeline(&r.pipeline);
            pass.set_bind_group(0, group, &[]);
            pass.draw(0..3, 0..1);
        }
    }
}
