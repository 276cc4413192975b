//! The texture the renderer draws into, and reading it back.

use super::{COLOR_FORMAT, DEPTH_FORMAT, Gpu, RenderError, SAMPLE_COUNTS, read_texture_rgba};

/// A colour texture ([`COLOR_FORMAT`]) with its depth buffer and, for MSAA, a multisampled colour
/// texture that is resolved into it at the end of each frame.
#[derive(Debug)]
pub struct RenderTarget {
    color: wgpu::Texture,
    /// Where the device cannot view the colour texture as [`EGUI_FORMAT`] (WebGL2): a copy in
    /// that format, re-encoded after every frame by the renderer.
    encoded: Option<wgpu::Texture>,
    color_view: wgpu::TextureView,
    msaa_view: Option<wgpu::TextureView>,
    depth_view: wgpu::TextureView,
    width: u32,
    height: u32,
    sample_count: u32,
}

/// The non-sRGB view format under which egui samples the colour texture.
pub const EGUI_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

impl RenderTarget {
    /// A `width` x `height` target drawn with `sample_count` (1 or 4) samples per pixel.
    ///
    /// Errors on a zero side, a side above the device's limit, or another sample count.
    pub fn new(gpu: &Gpu, width: u32, height: u32, sample_count: u32) -> Result<Self, RenderError> {
        Self::create(gpu, width, height, sample_count, false)
    }

    /// Like [`Self::new`], but with the re-encoded copy behind [`Self::egui_view`] that devices
    /// without format aliasing get (WebGL2), so it can be checked on any device.
    pub fn with_encoded_copy(
        gpu: &Gpu,
        width: u32,
        height: u32,
        sample_count: u32,
    ) -> Result<Self, RenderError> {
        Self::create(gpu, width, height, sample_count, true)
    }

    fn create(
        gpu: &Gpu,
        width: u32,
        height: u32,
        sample_count: u32,
        copy: bool,
    ) -> Result<Self, RenderError> {
        gpu.check_size(width, height)?;
        if !SAMPLE_COUNTS.contains(&sample_count) {
            return Err(RenderError::UnsupportedSampleCount {
                count: sample_count,
            });
        }
        // Errors while creating the textures (e.g. out of memory, or a view format the backend
        // cannot alias) come back as values, not as the device's panic.
        let oom = gpu.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let invalid = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let size = wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        };
        let texture = |label, format, samples, usage| {
            make_texture(&gpu.device, label, size, format, samples, usage, &[])
        };
        let (color, encoded) = color_textures(&gpu.device, size, copy);
        let color_view = color.create_view(&wgpu::TextureViewDescriptor::default());
        let msaa_view = (sample_count > 1).then(|| {
            texture(
                "armlab colour msaa",
                COLOR_FORMAT,
                sample_count,
                wgpu::TextureUsages::RENDER_ATTACHMENT,
            )
            .create_view(&wgpu::TextureViewDescriptor::default())
        });
        let depth_view = texture(
            "armlab depth",
            DEPTH_FORMAT,
            sample_count,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        )
        .create_view(&wgpu::TextureViewDescriptor::default());
        for scope in [invalid, oom] {
            if let Some(e) = super::error::scope_error(scope.pop()) {
                return Err(e.into());
            }
        }
        Ok(Self {
            color,
            encoded,
            color_view,
            msaa_view,
            depth_view,
            width,
            height,
            sample_count,
        })
    }

    /// The resolved colour texture (what the app shows and [`Self::read_rgba`] reads).
    pub fn color_texture(&self) -> &wgpu::Texture {
        &self.color
    }

    /// A view of [`Self::color_texture`].
    pub fn color_view(&self) -> &wgpu::TextureView {
        &self.color_view
    }

    /// A view of the colour texture as `Rgba8Unorm`: the same sRGB-encoded bytes, read without
    /// conversion, which is what egui-wgpu expects of a native texture (egui blends in gamma
    /// space). The app and the figures show the 3D view through it. On a device that cannot
    /// alias texture formats (WebGL2) it is a copy that the renderer re-encodes every frame.
    pub fn egui_view(&self) -> wgpu::TextureView {
        match &self.encoded {
            Some(t) => t.create_view(&wgpu::TextureViewDescriptor::default()),
            None => self.color.create_view(&wgpu::TextureViewDescriptor {
                format: Some(EGUI_FORMAT),
                ..Default::default()
            }),
        }
    }

    /// The re-encoded copy's view, where there is one (see [`Self::egui_view`]).
    pub(crate) fn encoded_view(&self) -> Option<wgpu::TextureView> {
        self.encoded
            .as_ref()
            .map(|t| t.create_view(&wgpu::TextureViewDescriptor::default()))
    }

    /// Copies what [`Self::egui_view`] shows to the CPU (blocking): the colour texture's bytes,
    /// or those of the re-encoded copy where there is one (they should be the same).
    pub fn read_egui_rgba(&self, gpu: &Gpu) -> Result<image::RgbaImage, RenderError> {
        read_texture_rgba(
            &gpu.device,
            &gpu.queue,
            self.encoded.as_ref().unwrap_or(&self.color),
        )
    }

    /// (width, height) in pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// Samples per pixel (1 or 4).
    pub fn sample_count(&self) -> u32 {
        self.sample_count
    }

    /// The colour attachment of a render pass: the MSAA texture resolved into the colour
    /// texture, or the colour texture itself.
    pub(crate) fn color_attachment(
        &self,
        clear: wgpu::Color,
    ) -> wgpu::RenderPassColorAttachment<'_> {
        let (view, resolve_target, store) = match &self.msaa_view {
            Some(msaa) => (msaa, Some(&self.color_view), wgpu::StoreOp::Discard),
            None => (&self.color_view, None, wgpu::StoreOp::Store),
        };
        wgpu::RenderPassColorAttachment {
            view,
            depth_slice: None,
            resolve_target,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(clear),
                store,
            },
        }
    }

    /// The depth attachment, cleared to the far plane.
    pub(crate) fn depth_attachment(&self) -> wgpu::RenderPassDepthStencilAttachment<'_> {
        wgpu::RenderPassDepthStencilAttachment {
            view: &self.depth_view,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(1.0),
                store: wgpu::StoreOp::Discard,
            }),
            stencil_ops: None,
        }
    }

    /// Copies the colour texture to the CPU (blocking): sRGB-encoded RGBA8, top row first.
    ///
    /// Rows are copied with `bytes_per_row` padded to 256 bytes and the padding is stripped, so
    /// any width reads back without shear.
    pub fn read_rgba(&self, gpu: &Gpu) -> Result<image::RgbaImage, RenderError> {
        read_texture_rgba(&gpu.device, &gpu.queue, &self.color)
    }
}

/// A 2D texture of `size` with one mip level.
fn make_texture(
    device: &wgpu::Device,
    label: &str,
    size: wgpu::Extent3d,
    format: wgpu::TextureFormat,
    sample_count: u32,
    usage: wgpu::TextureUsages,
    view_formats: &[wgpu::TextureFormat],
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size,
        mip_level_count: 1,
        sample_count,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats,
    })
}

/// The colour texture, with the [`EGUI_FORMAT`] view alias egui samples. The alias needs
/// view-format support, which some GL drivers and WebGL2 lack: there (or when `copy` asks for
/// it) the texture is made without it, with an [`EGUI_FORMAT`] copy that the renderer
/// re-encodes after every frame.
fn color_textures(
    device: &wgpu::Device,
    size: wgpu::Extent3d,
    copy: bool,
) -> (wgpu::Texture, Option<wgpu::Texture>) {
    let usage = wgpu::TextureUsages::RENDER_ATTACHMENT
        | wgpu::TextureUsages::COPY_SRC
        | wgpu::TextureUsages::TEXTURE_BINDING;
    let colour = |view_formats| {
        make_texture(
            device,
            "armlab colour",
            size,
            COLOR_FORMAT,
            1,
            usage,
            view_formats,
        )
    };
    let alias = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let aliased = colour(&[EGUI_FORMAT]);
    match super::error::scope_error(alias.pop()) {
        None if !copy => (aliased, None),
        _ => {
            let label = "armlab colour (encoded)";
            let encoded = make_texture(device, label, size, EGUI_FORMAT, 1, usage, &[]);
            (colour(&[]), Some(encoded))
        }
    }
}
