//! Paints egui's tessellated output with wgpu: what the live app window draws its panels with.
//!
//! Why not egui-wgpu's renderer: its fragment shader keeps a run-time branch for "predictable
//! texture filtering" (and one for dithering) that Mesa 22's llvmpipe, the software rasterizer
//! of Debian 12, executes on both sides for every pixel; each widget and glyph then costs about
//! five times a plain texture fetch (a window-sized egui rectangle: 30 ms against 5.5 ms). This
//! painter does only what the window needs, as egui-wgpu does on its default path: vertex colour
//! times a hardware-filtered texel, gamma space, premultiplied alpha.
//!
//! Textures come from egui's [`egui::TexturesDelta`] (fonts, images) or are wgpu views
//! registered with [`UiPainter::register_native`] (the 3D view). Paint callbacks are not
//! supported (they are skipped).

use egui::epaint::{ClippedPrimitive, ImageData, Primitive, TextureId, Vertex};
use std::collections::HashMap;
use std::ops::Range;

/// The painter's WGSL: `vs_main`, and `fs_gamma` / `fs_linear` for non-sRGB / sRGB targets.
pub const UI_WGSL: &str = include_str!("../../shaders/ui.wgsl");

/// One indexed draw of a mesh primitive.
struct Draw {
    /// Scissor rectangle (px): x, y, width, height; never empty.
    clip: [u32; 4],
    indices: Range<u32>,
    base_vertex: i32,
    texture: TextureId,
}

/// A texture egui can show: ours (managed by egui's deltas) or a registered view.
struct Tex {
    texture: Option<wgpu::Texture>,
    bind: wgpu::BindGroup,
}

/// egui's output painted into a render pass (see the module documentation).
pub struct UiPainter {
    pipeline: wgpu::RenderPipeline,
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

impl UiPainter {
    /// A painter for render passes into `format` (one sample, no depth, as eframe's window).
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Self {
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
        let screen_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("armlab ui screen"),
            entries: &[uniform],
        });
        let texture_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
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
        });
        let screen = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("armlab ui screen"),
            size: 16,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let screen_bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("armlab ui screen"),
            layout: &screen_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: screen.as_entire_binding(),
            }],
        });
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("ui.wgsl"),
            source: wgpu::ShaderSource::Wgsl(UI_WGSL.into()),
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("armlab ui"),
            bind_group_layouts: &[Some(&screen_layout), Some(&texture_layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("armlab ui"),
            layout: Some(&layout),
            vertex: wgpu::VertexState {
                module: &module,
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
                module: &module,
                entry_point: Some(if format.is_srgb() {
                    "fs_linear"
                } else {
                    "fs_gamma"
                }),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format,
                    // Premultiplied alpha, as egui blends.
                    blend: Some(wgpu::BlendState {
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
                    }),
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        Self {
            pipeline,
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

    /// Makes a wgpu view (`Rgba8Unorm`, gamma-encoded) available to egui as an image.
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
        let bind = self.bind(device, view, egui::TextureOptions::LINEAR);
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
            let r = p.clip_rect;
            let px =
                |v: f32, max: u32| (v * pixels_per_point).round().clamp(0.0, max as f32) as u32;
            let [w, h] = size_px;
            let (x0, y0) = (px(r.min.x, w), px(r.min.y, h));
            let (x1, y1) = (px(r.max.x, w), px(r.max.y, h));
            if x1 <= x0 || y1 <= y0 || mesh.indices.is_empty() {
                continue;
            }
            let start = self.index_data.len() as u32;
            self.index_data.extend_from_slice(&mesh.indices);
            self.draws.push(Draw {
                clip: [x0, y0, x1 - x0, y1 - y0],
                indices: start..self.index_data.len() as u32,
                base_vertex: self.vertex_data.len() as i32,
                texture: mesh.texture_id,
            });
            self.vertex_data.extend_from_slice(&mesh.vertices);
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

    /// Draws the prepared frame into `pass` (whose target is the `size_px` of [`Self::prepare`]).
    pub fn paint(&self, pass: &mut wgpu::RenderPass<'_>) {
        let (Some(vertices), Some(indices)) = (&self.vertices, &self.indices) else {
            return;
        };
        if self.draws.is_empty() {
            return;
        }
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.screen_bind, &[]);
        pass.set_vertex_buffer(0, vertices.slice(..));
        pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
        let mut bound = None;
        for d in &self.draws {
            let Some(tex) = self.textures.get(&d.texture) else {
                continue;
            };
            if bound != Some(d.texture) {
                pass.set_bind_group(1, &tex.bind, &[]);
                bound = Some(d.texture);
            }
            let [x, y, w, h] = d.clip;
            pass.set_scissor_rect(x, y, w, h);
            pass.draw_indexed(d.indices.clone(), d.base_vertex, 0..1);
        }
    }
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

/// A whole egui frame (laid out by another context) painted by the [`UiPainter`] in a render
/// pass of egui-wgpu: the app hands eframe this one callback instead of its widgets.
pub struct UiFrame {
    /// The tessellated frame.
    pub prims: Vec<ClippedPrimitive>,
    /// Its texture uploads and frees (taken by the first paint; a frame never painted drops
    /// them).
    pub textures: std::sync::Mutex<egui::TexturesDelta>,
    /// Target size (px).
    pub size_px: [u32; 2],
    /// Pixels per egui point.
    pub pixels_per_point: f32,
}

impl UiFrame {
    /// The frame's texture changes, taken out (empty after the first call).
    fn take_textures(&self) -> egui::TexturesDelta {
        match self.textures.lock() {
            Ok(mut t) => std::mem::take(&mut *t),
            Err(poisoned) => std::mem::take(&mut *poisoned.into_inner()),
        }
    }
}

impl Drop for UiFrame {
    fn drop(&mut self) {
        // egui insists that texture changes are handled; a frame dropped unpainted has none
        // to hand on (the next full frame re-sends what a texture needs).
        self.take_textures().clear();
    }
}

impl egui_wgpu::CallbackTrait for UiFrame {
    fn prepare(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        _screen: &egui_wgpu::ScreenDescriptor,
        encoder: &mut wgpu::CommandEncoder,
        resources: &mut egui_wgpu::CallbackResources,
    ) -> Vec<wgpu::CommandBuffer> {
        if let Some(p) = resources.get_mut::<UiPainter>() {
            for id in std::mem::take(&mut p.pending_free) {
                p.textures.remove(&id);
            }
            let mut textures = self.take_textures();
            p.set_textures(device, queue, &textures);
            p.prepare(
                device,
                queue,
                encoder,
                &self.prims,
                self.size_px,
                self.pixels_per_point,
            );
            p.pending_free.extend(textures.free.iter().copied());
            textures.clear();
        }
        Vec::new()
    }

    fn paint(
        &self,
        info: egui::PaintCallbackInfo,
        pass: &mut wgpu::RenderPass<'static>,
        resources: &egui_wgpu::CallbackResources,
    ) {
        if let Some(p) = resources.get::<UiPainter>() {
            // The callback's viewport is the whole window; the painter sets its own scissors.
            let [w, h] = info.screen_size_px;
            pass.set_viewport(0.0, 0.0, w as f32, h as f32, 0.0, 1.0);
            p.paint(pass);
        }
    }
}
