//! egui rendered offscreen through egui-wgpu into a texture and read back: the same widgets,
//! fonts and plots the app shows, written to PNG with no window and no display.

use super::UiRenderError;
use egui::epaint::textures::TexturesDelta;

/// Output format of figures: egui prefers a non-sRGB target (it blends in gamma space).
pub const FIGURE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// An egui context and its wgpu renderer, reused across figures.
pub struct Offscreen {
    /// The egui context (fonts, style, memory).
    pub ctx: egui::Context,
    renderer: egui_wgpu::Renderer,
    background: Option<egui::Color32>,
    /// Texture updates of layout-only passes ([`Self::layout`]), applied by the next render.
    pending: TexturesDelta,
    /// Renders return at once and leave their read-back here (a browser cannot wait for it).
    defer_readback: bool,
    deferred: Option<crate::render::PendingRead>,
    /// Keep what each render paints ([`Self::capture_shapes`]).
    capture: bool,
    captured: Option<UiCapture>,
    /// The images of egui's managed textures (not the font atlas), kept for captures.
    images: std::collections::HashMap<egui::TextureId, std::sync::Arc<egui::ColorImage>>,
    /// egui's clock (s) and how far each pass moves it (0: it stands still).
    clock: (f64, f64),
}

/// What one render painted, before tessellation: egui's shapes in points, and the images they
/// show. The vector figures ([`crate::figure::vector`]) write it as SVG.
#[derive(Clone)]
pub struct UiCapture {
    /// Canvas size (px).
    pub size: [u32; 2],
    /// Pixels per egui point.
    pub pixels_per_point: f32,
    /// The colour the canvas was cleared to.
    pub background: egui::Color32,
    /// The shapes in paint order, with their clip rectangles (points).
    pub shapes: Vec<egui::epaint::ClippedShape>,
    /// The images of the textures the shapes use (managed textures and, where the figure
    /// added them, native ones such as a 3D view).
    pub images: std::collections::HashMap<egui::TextureId, std::sync::Arc<egui::ColorImage>>,
}

impl std::fmt::Debug for UiCapture {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("UiCapture")
            .field("size", &self.size)
            .field("shapes", &self.shapes.len())
            .field("images", &self.images.len())
            .finish()
    }
}

impl Drop for Offscreen {
    /// Texture updates of a layout never rendered (a figure abandoned after it was planned:
    /// its data failed, or its job was cancelled) go with it; epaint panics on dropping
    /// unapplied updates.
    fn drop(&mut self) {
        self.pending.clear();
    }
}

impl Offscreen {
    /// A context and a renderer set for predictable output (no dithering, texture filtering
    /// done in the shader): the same bytes on every run, for figures and golden images.
    pub fn new(device: &wgpu::Device) -> Self {
        Self::with_options(device, egui_wgpu::RendererOptions::PREDICTABLE)
    }

    /// A context and a renderer with the given options. The default options filter textures in
    /// hardware, much faster on a software rasterizer; the live app renders like this.
    pub fn with_options(device: &wgpu::Device, options: egui_wgpu::RendererOptions) -> Self {
        let ctx = egui::Context::default();
        let renderer = egui_wgpu::Renderer::new(device, FIGURE_FORMAT, options);
        Self {
            ctx,
            renderer,
            background: None,
            pending: TexturesDelta::default(),
            defer_readback: false,
            deferred: None,
            capture: false,
            captured: None,
            images: Default::default(),
            clock: (0.0, 0.0),
        }
    }

    /// Moves egui's clock `step` seconds on at each pass, so that what animates (a window
    /// fading in) ends as frames go by. Default 0: the clock stands at 0, and a picture comes
    /// out the same on every run.
    pub fn set_clock_step(&mut self, step: f64) {
        self.clock.1 = step;
    }

    /// egui's input for the next pass: [`raw_input`] at the clock's time, the clock moved on.
    fn input(
        &mut self,
        device: &wgpu::Device,
        size: [u32; 2],
        pixels_per_point: f32,
    ) -> Result<egui::RawInput, UiRenderError> {
        let mut input = raw_input(device, size, pixels_per_point)?;
        input.time = Some(self.clock.0);
        self.clock.0 += self.clock.1;
        Ok(input)
    }

    /// Makes a wgpu texture view (format `Rgba8Unorm`, gamma-encoded bytes) available to egui
    /// widgets as an image.
    pub fn register_texture(
        &mut self,
        device: &wgpu::Device,
        view: &wgpu::TextureView,
    ) -> egui::TextureId {
        self.renderer
            .register_native_texture(device, view, wgpu::FilterMode::Linear)
    }

    /// The egui-wgpu renderer (to register native textures through the app's viewport).
    pub fn renderer_mut(&mut self) -> &mut egui_wgpu::Renderer {
        &mut self.renderer
    }

    /// Forgets a texture registered with [`Self::register_texture`].
    pub fn free_texture(&mut self, id: egui::TextureId) {
        self.renderer.free_texture(&id);
    }

    /// The colour the canvas is cleared to before egui paints (default: the style's panel
    /// fill). The app paints its panels transparent over this clear, which is much cheaper on
    /// a software rasterizer than a window-sized egui rectangle.
    pub fn set_background(&mut self, color: Option<egui::Color32>) {
        self.background = color;
    }

    /// Lays out `ui` on a `size` pixel canvas with `pixels_per_point` pixels per egui point, and
    /// returns the RGBA pixels. The layout runs twice so that sizes measured in the first pass
    /// (plots, legends, text) are settled in the second; only the second is painted.
    pub fn render(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        size: [u32; 2],
        pixels_per_point: f32,
        mut ui: impl FnMut(&mut egui::Ui),
    ) -> Result<image::RgbaImage, UiRenderError> {
        let input = self.input(device, size, pixels_per_point)?;
        let mut deltas = std::mem::take(&mut self.pending);
        let mut output = self.ctx.run_ui(input.clone(), &mut ui);
        deltas.append(std::mem::take(&mut output.textures_delta));
        let mut output = self.ctx.run_ui(input, &mut ui);
        deltas.append(std::mem::take(&mut output.textures_delta));
        output.textures_delta = deltas;
        if self.capture {
            self.keep_capture(size, &output);
        }
        let texture = canvas(device, size, true);
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        self.paint(device, queue, &view, size, output);
        if self.defer_readback {
            let read = crate::render::PendingRead::start(device, queue, &texture)?;
            self.deferred = Some(read);
            return Ok(image::RgbaImage::new(size[0], size[1]));
        }
        crate::render::read_texture_rgba(device, queue, &texture).map_err(UiRenderError::Render)
    }

    /// From now on [`Self::render`] returns a blank image of the right size at once and leaves
    /// the pixels' read-back to [`Self::take_deferred`] (in a browser, where nothing can wait for
    /// the GPU).
    pub fn defer_readback(&mut self) {
        self.defer_readback = true;
    }

    /// From now on (`on`) each [`Self::render`] also keeps its shapes and images for
    /// [`Self::take_capture`] (vector figures).
    pub fn capture_shapes(&mut self, on: bool) {
        self.capture = on;
        if !on {
            self.captured = None;
        }
    }

    /// What the last render painted, when [`Self::capture_shapes`] is on.
    pub fn take_capture(&mut self) -> Option<UiCapture> {
        self.captured.take()
    }

    /// Puts a capture back (after the figure added the images of its native textures, e.g. a
    /// 3D view it read back).
    pub fn put_capture(&mut self, capture: UiCapture) {
        self.captured = Some(capture);
    }

    /// Records the output's shapes and the images of the textures it sets.
    fn keep_capture(&mut self, size: [u32; 2], output: &egui::FullOutput) {
        for (id, list) in &output.textures_delta.set {
            for delta in list {
                let egui::ImageData::Color(img) = &delta.image;
                if *id != egui::TextureId::default() && delta.pos.is_none() {
                    self.images.insert(*id, img.clone());
                }
            }
        }
        for id in &output.textures_delta.free {
            self.images.remove(id);
        }
        self.captured = Some(UiCapture {
            size,
            pixels_per_point: output.pixels_per_point,
            background: self
                .background
                .unwrap_or(self.ctx.global_style().visuals.panel_fill),
            shapes: output.shapes.clone(),
            images: self.images.clone(),
        });
    }

    /// The read-back of the last deferred render, if any.
    pub fn take_deferred(&mut self) -> Option<crate::render::PendingRead> {
        self.deferred.take()
    }

    /// Lays `ui` out as [`Self::render`] would (two passes) without painting: for a figure that
    /// needs the size of a widget before it can make its content. Texture updates are kept for
    /// the next render.
    pub fn layout(
        &mut self,
        device: &wgpu::Device,
        size: [u32; 2],
        pixels_per_point: f32,
        mut ui: impl FnMut(&mut egui::Ui),
    ) -> Result<(), UiRenderError> {
        let input = self.input(device, size, pixels_per_point)?;
        for _ in 0..2 {
            let mut output = self.ctx.run_ui(input.clone(), &mut ui);
            self.pending
                .append(std::mem::take(&mut output.textures_delta));
        }
        Ok(())
    }

    /// One frame as a window draws it: a single layout pass, tessellation, and painting into
    /// `view` (format [`FIGURE_FORMAT`], `size` pixels), submitted but not waited for and not
    /// read back. Returns egui's output for the frame (cursor, repaint requests, ...).
    pub fn frame(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        view: &wgpu::TextureView,
        size: [u32; 2],
        pixels_per_point: f32,
        ui: impl FnMut(&mut egui::Ui),
    ) -> Result<egui::PlatformOutput, UiRenderError> {
        let input = self.input(device, size, pixels_per_point)?;
        let mut output = self.ctx.run_ui(input, ui);
        let platform = std::mem::take(&mut output.platform_output);
        self.paint(device, queue, view, size, output);
        Ok(platform)
    }

    /// Uploads the output's textures, tessellates its shapes and paints them into `view`.
    fn paint(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        view: &wgpu::TextureView,
        size: [u32; 2],
        output: egui::FullOutput,
    ) {
        let mut deltas = output.textures_delta;
        for (id, list) in &deltas.set {
            for delta in list {
                self.renderer.update_texture(device, queue, *id, delta);
            }
        }
        let prims = self.ctx.tessellate(output.shapes, output.pixels_per_point);
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: size,
            pixels_per_point: output.pixels_per_point,
        };
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("figure"),
        });
        let user = self
            .renderer
            .update_buffers(device, queue, &mut encoder, &prims, &screen);
        let bg = self
            .background
            .unwrap_or(self.ctx.global_style().visuals.panel_fill);
        {
            let pass = clear_pass(&mut encoder, view, bg);
            let mut pass = pass.forget_lifetime();
            self.renderer.render(&mut pass, &prims, &screen);
        }
        queue.submit(user.into_iter().chain(std::iter::once(encoder.finish())));
        for id in &deltas.free {
            self.renderer.free_texture(id);
        }
        deltas.clear();
    }
}

/// egui's input for a `size` pixel canvas at `pixels_per_point` (no events, time 0).
fn raw_input(
    device: &wgpu::Device,
    size: [u32; 2],
    pixels_per_point: f32,
) -> Result<egui::RawInput, UiRenderError> {
    let [w, h] = size;
    if w == 0 || h == 0 || w > 8192 || h > 8192 {
        return Err(UiRenderError::Size {
            width: w,
            height: h,
        });
    }
    let mut input = egui::RawInput {
        screen_rect: Some(egui::Rect::from_min_size(
            egui::Pos2::ZERO,
            egui::vec2(w as f32, h as f32) / pixels_per_point,
        )),
        max_texture_side: Some(device.limits().max_texture_dimension_2d as usize),
        time: Some(0.0),
        ..Default::default()
    };
    input
        .viewports
        .entry(egui::ViewportId::ROOT)
        .or_default()
        .native_pixels_per_point = Some(pixels_per_point);
    Ok(input)
}

/// A `size` pixel texture in [`FIGURE_FORMAT`] to paint a window or a figure into; `readable`
/// adds the copy-out usage a read-back needs (a window's surface has none: a software rasterizer
/// keeps such a texture cheaper to draw into).
pub fn canvas(device: &wgpu::Device, size: [u32; 2], readable: bool) -> wgpu::Texture {
    let mut usage = wgpu::TextureUsages::RENDER_ATTACHMENT;
    if readable {
        usage |= wgpu::TextureUsages::COPY_SRC;
    }
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some("canvas"),
        size: wgpu::Extent3d {
            width: size[0],
            height: size[1],
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: FIGURE_FORMAT,
        usage,
        view_formats: &[],
    })
}

/// A render pass into `view` (one sample, no depth) that first clears it to `color` (opaque).
pub(crate) fn clear_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    view: &wgpu::TextureView,
    color: egui::Color32,
) -> wgpu::RenderPass<'e> {
    let c = color.to_normalized_gamma_f32().map(f64::from);
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("canvas"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view,
            resolve_target: None,
            depth_slice: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color {
                    r: c[0],
                    g: c[1],
                    b: c[2],
                    a: 1.0,
                }),
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}
