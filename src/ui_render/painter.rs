//! Paints egui's tessellated output with wgpu: what the live app window draws its panels with.
//!
//! Why not egui-wgpu's renderer: its fragment shader keeps a run-time branch for "predictable
//! texture filtering" (and one for dithering) that Mesa 22's llvmpipe, the software rasterizer
//! of Debian 12, executes on both sides for every pixel; each widget and glyph then costs about
//! five times a plain texture fetch (a window-sized egui rectangle: 30 ms against 5.5 ms). This
//! painter does only what the window needs, as egui-wgpu does on its default path: vertex colour
//! times a hardware-filtered texel, gamma space, premultiplied alpha.
//!
//! Two more things a software rasterizer rewards: consecutive meshes that no clip rectangle
//! cuts go in one draw call (lavapipe charges for a draw call about what a hundred widgets
//! cost), and a registered opaque view under white vertices (the 3D view) is copied without
//! blending.
//!
//! Textures come from egui's [`egui::TexturesDelta`] (fonts, images) or are wgpu views
//! registered with [`UiPainter::register_native`] (the 3D view). Paint callbacks are not
//! supported (they are skipped).

use egui::epaint::{ClippedPrimitive, ImageData, Primitive, TextureId, Vertex};
use std::collections::HashMap;
use std::ops::Range;

mod frame;
pub use frame::UiFrame;

/// The painter's WGSL: `vs_main`, and `fs_gamma` / `fs_linear` (blended widgets) and
/// `fs_copy` / `fs_copy_linear` (opaque views) for non-sRGB / sRGB targets.
pub const UI_WGSL: &str = include_str!("../../shaders/ui.wgsl");

/// One indexed draw of a mesh primitive.
struct Draw {
    /// Scissor rectangle (px): x0, y0, x1, y1 (exclusive); never empty.
    clip: [u32; 4],
    /// Into the frame's index buffer, whose indices count from the frame's first vertex.
    indices: Range<u32>,
    /// The scissor cuts none of the draw's triangles.
    uncut: bool,
    /// An untinted registered view: drawn with the copy pipeline.
    opaque: bool,
    texture: TextureId,
}

/// A texture egui can show: ours (managed by egui's deltas) or a registered view.
struct Tex {
    texture: Option<wgpu::Texture>,
    bind: wgpu::BindGroup,
}

/// egui's output painted into a render pass (see the module documentation).
pub struct UiPainter {
    /// Blended (premultiplied alpha), vertex colour times texel: every widget.
    pipeline: wgpu::RenderPipeline,
    /// Unblended texel copy: registered opaque views shown untinted (the 3D view).
    opaque: wgpu::RenderPipeline,
    screen: wgpu::Buffer,
    screen_bind: wgpu::BindGroup,
    texture_layout: wgpu::BindGroupLayout,
    samplers: HashMap<egui::TextureOptions, wgpu::Sampler>,
    textures: HashMap<TextureId, Tex>,
    next_native: u64,
    vertices: Option<wgpu::Buffer>,
    indices: Option<wgpu::Buffer>,
    draws: Vec<Draw>,
    /// Staging of one frame's vertices and indices (kept to reuse the allocation).
    vertex_data: Vec<Vertex>,
    index_data: Vec<u32>,
    /// Textures the last frame freed, dropped once it has been drawn.
    pending_free: Vec<TextureId>,
    /// Reused staging memory for the meshes: a fresh staging buffer per frame (what
    /// `Queue::write_buffer` does) costs page faults every frame on a software device.
    belt: wgpu::util::StagingBelt,
}

/// Layout of group 0: the screen-size uniform, read by the vertex shader.
fn screen_bind_group_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let uniform = wgpu::BindGroupLayoutEntry {
        binding: 0,
        visibility: wgpu::ShaderStages::VERTEX,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    };
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("armlab ui screen"),
        entries: &[uniform],
    })
}

/// Layout of group 1: a filterable 2D texture and its sampler, read by the fragment shader.
fn texture_bind_group_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("armlab ui texture"),
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
    })
}

/// The 16-byte screen uniform buffer and its bind group (group 0).
fn screen_uniform(
    device: &wgpu::Device,
    screen_layout: &wgpu::BindGroupLayout,
) -> (wgpu::Buffer, wgpu::BindGroup) {
    let screen = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("armlab ui screen"),
        size: 16,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let screen_bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("armlab ui screen"),
        layout: screen_layout,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: screen.as_entire_binding(),
        }],
    });
    (screen, screen_bind)
}

impl UiPainter {
    /// A painter for render passes into `format` (one sample, no depth, as eframe's window).
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Self {
        let screen_layout = screen_bind_group_layout(device);
        let texture_layout = texture_bind_group_layout(device);
        let (screen, screen_bind) = screen_uniform(device, &screen_layout);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("ui.wgsl"),
            source: wgpu::ShaderSource::Wgsl(UI_WGSL.into()),
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("armlab ui"),
            bind_group_layouts: &[Some(&screen_layout), Some(&texture_layout)],
            immediate_size: 0,
        });
        let fs = if format.is_srgb() {
            "fs_linear"
        } else {
            "fs_gamma"
        };
        let pipeline = make_pipeline(device, &layout, &module, format, fs, Some(PREMULTIPLIED));
        let copy = if format.is_srgb() {
            "fs_copy_linear"
        } else {
            "fs_copy"
        };
        let opaque = make_pipeline(device, &layout, &module, format, copy, None);
        Self {
            pipeline,
            opaque,
            screen,
            screen_bind,
            texture_layout,
            samplers: HashMap::new(),
            textures: HashMap::new(),
            next_native: 0,
            vertices: None,
            indices: None,
            draws: Vec::new(),
            vertex_data: Vec::new(),
            index_data: Vec::new(),
            pending_free: Vec::new(),
            belt: wgpu::util::StagingBelt::new(device.clone(), 1 << 20),
        }
    }

    fn bind(
        &mut self,
        device: &wgpu::Device,
        view: &wgpu::TextureView,
        options: egui::TextureOptions,
    ) -> wgpu::BindGroup {
        let sampler = self.samplers.entry(options).or_insert_with(|| {
            let filter = |f| match f {
                egui::TextureFilter::Nearest => wgpu::FilterMode::Nearest,
                egui::TextureFilter::Linear => wgpu::FilterMode::Linear,
            };
            let address = match options.wrap_mode {
                egui::TextureWrapMode::ClampToEdge => wgpu::AddressMode::ClampToEdge,
                egui::TextureWrapMode::Repeat => wgpu::AddressMode::Repeat,
                egui::TextureWrapMode::MirroredRepeat => wgpu::AddressMode::MirrorRepeat,
            };
            device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some("armlab ui"),
                mag_filter: filter(options.magnification),
                min_filter: filter(options.minification),
                address_mode_u: address,
                address_mode_v: address,
                ..Default::default()
            })
        });
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("armlab ui texture"),
            layout: &self.texture_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Sampler(sampler),
                },
            ],
        })
    }

    /// Makes a wgpu view (`Rgba8Unorm`, gamma-encoded, opaque) available to egui as an image.
    /// It is sampled without filtering (meant to be shown texel for texel) and, untinted,
    /// copied without blending: its alpha is not used.
    pub fn register_native(
        &mut self,
        device: &wgpu::Device,
        view: &wgpu::TextureView,
    ) -> TextureId {
        self.next_native += 1;
        let id = TextureId::User(self.next_native);
        self.update_native(device, view, id);
        id
    }

    /// Points a registered id at another view.
    pub fn update_native(
        &mut self,
        device: &wgpu::Device,
        view: &wgpu::TextureView,
        id: TextureId,
    ) {
        let bind = self.bind(device, view, egui::TextureOptions::NEAREST);
        self.textures.insert(
            id,
            Tex {
                texture: None,
                bind,
            },
        );
    }

    /// Applies the texture uploads of a frame (before painting it).
    pub fn set_textures(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        delta: &egui::TexturesDelta,
    ) {
        for (id, list) in &delta.set {
            for d in list {
                let ImageData::Color(image) = &d.image;
                let [w, h] = image.size.map(|v| v as u32);
                if w == 0 || h == 0 {
                    continue;
                }
                let bytes: &[u8] = bytemuck::cast_slice(image.pixels.as_slice());
                let size = wgpu::Extent3d {
                    width: w,
                    height: h,
                    depth_or_array_layers: 1,
                };
                let origin = d.pos.map_or([0, 0], |p| p.map(|v| v as u32));
                if d.pos.is_none() {
                    let texture = device.create_texture(&wgpu::TextureDescriptor {
                        label: Some("armlab ui egui texture"),
                        size,
                        mip_level_count: 1,
                        sample_count: 1,
                        dimension: wgpu::TextureDimension::D2,
                        format: wgpu::TextureFormat::Rgba8Unorm,
                        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                        view_formats: &[],
                    });
                    let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
                    let bind = self.bind(device, &view, d.options);
                    self.textures.insert(
                        *id,
                        Tex {
                            texture: Some(texture),
                            bind,
                        },
                    );
                }
                if let Some(texture) = self.textures.get(id).and_then(|t| t.texture.as_ref()) {
                    queue.write_texture(
                        wgpu::TexelCopyTextureInfo {
                            texture,
                            mip_level: 0,
                            origin: wgpu::Origin3d {
                                x: origin[0],
                                y: origin[1],
                                z: 0,
                            },
                            aspect: wgpu::TextureAspect::All,
                        },
                        bytes,
                        wgpu::TexelCopyBufferLayout {
                            offset: 0,
                            bytes_per_row: Some(4 * w),
                            rows_per_image: Some(h),
                        },
                        size,
                    );
                }
            }
        }
    }

    /// Forgets the textures a frame frees (after painting it).
    pub fn free_textures(&mut self, delta: &egui::TexturesDelta) {
        for id in &delta.free {
            self.textures.remove(id);
        }
    }

    /// Paints `frame` into `view` (the frame's size, the painter's format) in a render pass of
    /// its own, cleared to `clear` first, and submits it: the window's frame without a window
    /// (tests, benchmarks).
    pub fn render_frame(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        view: &wgpu::TextureView,
        frame: &UiFrame,
        clear: egui::Color32,
    ) {
        let mut textures = frame.take_textures();
        self.set_textures(device, queue, &textures);
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("armlab ui"),
        });
        self.prepare(
            device,
            queue,
            &mut encoder,
            &frame.prims,
            frame.size_px,
            frame.pixels_per_point,
        );
        {
            let mut pass = super::offscreen::clear_pass(&mut encoder, view, clear);
            self.paint(&mut pass);
        }
        queue.submit([encoder.finish()]);
        self.free_textures(&textures);
        textures.clear();
    }

    /// Stores `painter` where [`UiFrame`] callbacks find it.
    pub fn install(self, resources: &mut egui_wgpu::CallbackResources) {
        resources.insert(self);
    }

    /// Uploads the meshes of a frame laid out at `pixels_per_point` on a `size_px` target,
    /// through `encoder` (which must be submitted before the frame is painted).
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        prims: &[ClippedPrimitive],
        size_px: [u32; 2],
        pixels_per_point: f32,
    ) {
        let points = [size_px[0] as f32, size_px[1] as f32].map(|v| v / pixels_per_point);
        queue.write_buffer(
            &self.screen,
            0,
            bytemuck::cast_slice(&[points[0], points[1], 0.0, 0.0]),
        );
        self.draws.clear();
        self.vertex_data.clear();
        self.index_data.clear();
        for p in prims {
            let Primitive::Mesh(mesh) = &p.primitive else {
                continue;
            };
            // The clip rectangle in whole pixels, inside the target.
            let [x0, y0, x1, y1] = clip_pixels(p.clip_rect, size_px, pixels_per_point);
            if x1 <= x0 || y1 <= y0 || mesh.indices.is_empty() || mesh.vertices.is_empty() {
                continue;
            }
            let uncut = uncut_by(&mesh.vertices, [x0, y0, x1, y1], size_px, pixels_per_point);
            let clip = [x0 as u32, y0 as u32, x1 as u32, y1 as u32];
            self.push_mesh(mesh, clip, uncut);
        }
        upload(
            device,
            &mut self.belt,
            encoder,
            &mut self.vertices,
            bytemuck::cast_slice(&self.vertex_data),
            wgpu::BufferUsages::VERTEX,
        );
        upload(
            device,
            &mut self.belt,
            encoder,
            &mut self.indices,
            bytemuck::cast_slice(&self.index_data),
            wgpu::BufferUsages::INDEX,
        );
        self.belt.finish_and_recall_on_submit(encoder);
    }

    /// Stages one mesh's vertices and indices and draws it with the scissor `clip` (px),
    /// merged into the previous draw when both are uncut and show the same texture the same way.
    fn push_mesh(&mut self, mesh: &egui::epaint::Mesh, clip: [u32; 4], uncut: bool) {
        let base = self.vertex_data.len() as u32;
        let start = self.index_data.len() as u32;
        self.index_data
            .extend(mesh.indices.iter().map(|&i| base + i));
        self.vertex_data.extend_from_slice(&mesh.vertices);
        let end = self.index_data.len() as u32;
        // Consecutive meshes that no clip rectangle cuts and that show the same texture
        // are drawn at once (one draw call costs lavapipe as much as a hundred widgets),
        // with a scissor around all of them: the same pixels as one draw each.
        // A registered view (opaque by contract) under white vertices is a plain copy.
        let opaque = matches!(mesh.texture_id, TextureId::User(_))
            && mesh
                .vertices
                .iter()
                .all(|v| v.color == egui::Color32::WHITE);
        match self.draws.last_mut() {
            Some(last)
                if last.uncut
                    && uncut
                    && last.texture == mesh.texture_id
                    && last.opaque == opaque =>
            {
                last.indices.end = end;
                last.clip = union(last.clip, clip);
            }
            _ => self.draws.push(Draw {
                clip,
                indices: start..end,
                uncut,
                opaque,
                texture: mesh.texture_id,
            }),
        }
    }

    /// How many draw calls [`Self::paint`] makes for the prepared frame.
    pub fn draw_calls(&self) -> usize {
        self.draws.len()
    }

    /// Draws the prepared frame into `pass` (whose target is the `size_px` of [`Self::prepare`]).
    pub fn paint(&self, pass: &mut wgpu::RenderPass<'_>) {
        let (Some(vertices), Some(indices)) = (&self.vertices, &self.indices) else {
            return;
        };
        if self.draws.is_empty() {
            return;
        }
        pass.set_bind_group(0, &self.screen_bind, &[]);
        pass.set_vertex_buffer(0, vertices.slice(..));
        pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
        let mut bound = None;
        let mut opaque = None;
        for d in &self.draws {
            if opaque != Some(d.opaque) {
                pass.set_pipeline(if d.opaque {
                    &self.opaque
                } else {
                    &self.pipeline
                });
                opaque = Some(d.opaque);
            }
            let Some(tex) = self.textures.get(&d.texture) else {
                continue;
            };
            if bound != Some(d.texture) {
                pass.set_bind_group(1, &tex.bind, &[]);
                bound = Some(d.texture);
            }
            let [x0, y0, x1, y1] = d.clip;
            pass.set_scissor_rect(x0, y0, x1 - x0, y1 - y0);
            pass.draw_indexed(d.indices.clone(), 0, 0..1);
        }
    }
}

/// Premultiplied alpha, as egui blends.
const PREMULTIPLIED: wgpu::BlendState = wgpu::BlendState {
    color: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
        operation: wgpu::BlendOperation::Add,
    },
    alpha: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::OneMinusDstAlpha,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    },
};

/// The painter's pipeline with fragment entry point `fs` and `blend`.
fn make_pipeline(
    device: &wgpu::Device,
    layout: &wgpu::PipelineLayout,
    module: &wgpu::ShaderModule,
    format: wgpu::TextureFormat,
    fs: &str,
    blend: Option<wgpu::BlendState>,
) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("armlab ui"),
        layout: Some(layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: size_of::<Vertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &wgpu::vertex_attr_array![0 => Float32x2, 1 => Float32x2, 2 => Uint32],
            })],
        },
        primitive: wgpu::PrimitiveState {
            cull_mode: None,
            ..Default::default()
        },
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(fs),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format,
                blend,
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// `r` (points) in whole pixels, clamped to a `size_px` target: x0, y0, x1, y1.
fn clip_pixels(r: egui::Rect, size_px: [u32; 2], pixels_per_point: f32) -> [f32; 4] {
    let px = |v: f32| (v * pixels_per_point).round();
    let [w, h] = size_px.map(|v| v as f32);
    let (x0, y0) = (px(r.min.x).clamp(0.0, w), px(r.min.y).clamp(0.0, h));
    let (x1, y1) = (px(r.max.x).clamp(0.0, w), px(r.max.y).clamp(0.0, h));
    [x0, y0, x1, y1]
}

/// Whether the scissor `[x0, y0, x1, y1]` (px, from [`clip_pixels`]) cuts none of the triangles
/// of a mesh with these vertices.
fn uncut_by(
    vertices: &[Vertex],
    [x0, y0, x1, y1]: [f32; 4],
    size_px: [u32; 2],
    pixels_per_point: f32,
) -> bool {
    let [w, h] = size_px.map(|v| v as f32);
    // Does the scissor cut this mesh? A pixel is drawn when its centre is inside a
    // triangle, so compare the pixels whose centres lie within the mesh's bounds with
    // the scissor's (pixels outside the target do not exist either way).
    let bounds = mesh_bounds(vertices);
    let first = |v: f32| (v * pixels_per_point - 0.5).ceil().max(0.0);
    let last = |v: f32, n: f32| (v * pixels_per_point - 0.5).floor().min(n - 1.0);
    first(bounds.min.x) >= x0
        && first(bounds.min.y) >= y0
        && last(bounds.max.x, w) < x1
        && last(bounds.max.y, h) < y1
}

/// The bounding rectangle of `vertices` (points).
fn mesh_bounds(vertices: &[Vertex]) -> egui::Rect {
    let mut r = egui::Rect::NOTHING;
    for v in vertices {
        r.extend_with(v.pos);
    }
    r
}

/// The smallest rectangle around both `a` and `b` (x0, y0, x1, y1).
fn union(a: [u32; 4], b: [u32; 4]) -> [u32; 4] {
    [
        a[0].min(b[0]),
        a[1].min(b[1]),
        a[2].max(b[2]),
        a[3].max(b[3]),
    ]
}

/// Writes `bytes` into `buffer` through the staging `belt`, (re)creating the buffer when it is
/// missing or too small.
fn upload(
    device: &wgpu::Device,
    belt: &mut wgpu::util::StagingBelt,
    encoder: &mut wgpu::CommandEncoder,
    buffer: &mut Option<wgpu::Buffer>,
    bytes: &[u8],
    usage: wgpu::BufferUsages,
) {
    let needed = (bytes.len() as u64).next_multiple_of(wgpu::COPY_BUFFER_ALIGNMENT);
    let Some(size) = wgpu::BufferSize::new(needed) else {
        return;
    };
    if buffer.as_ref().is_none_or(|b| b.size() < needed) {
        *buffer = Some(device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("armlab ui"),
            size: needed.next_power_of_two().max(1 << 16),
            usage: usage | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        }));
    }
    if let Some(b) = buffer {
        let mut view = belt.write_buffer(encoder, b, 0, size);
        view.slice(..bytes.len()).copy_from_slice(bytes);
        // Copies come in multiples of 4 bytes: zero the tail.
        let pad = needed as usize - bytes.len();
        view.slice(bytes.len()..).copy_from_slice(&[0u8; 4][..pad]);
    }
}
