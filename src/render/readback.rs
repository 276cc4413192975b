//! Reading a texture back to the CPU as an RGBA image.

use super::RenderError;

/// Rows of a texture-to-buffer copy are padded to this many bytes.
const ROW_ALIGN: u32 = wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;

/// `width * 4` rounded up to 256 bytes (the copy's row pitch).
pub(crate) fn padded_bytes_per_row(width: u32) -> u32 {
    (width * 4).div_ceil(ROW_ALIGN) * ROW_ALIGN
}

/// Copies mip 0 of a 2D texture to the CPU (blocking) as RGBA8, top row first.
///
/// The texture needs `COPY_SRC` usage and a format of 4 bytes per texel: `Rgba8Unorm(Srgb)`
/// (bytes as stored, i.e. sRGB-encoded for the sRGB format) or `Bgra8Unorm(Srgb)` (swizzled to
/// RGBA). Rows are copied with `bytes_per_row` padded to 256 bytes and the padding is stripped,
/// so any width reads back without shear. In a browser nothing can block: use
/// [`PendingRead`] there.
pub fn read_texture_rgba(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<image::RgbaImage, RenderError> {
    let pending = PendingRead::start(device, queue, texture)?;
    device.poll(wgpu::PollType::wait_indefinitely())?;
    // The callback has run once the wait returns; no result means it never will.
    pending.poll(device).unwrap_or(Err(RenderError::Map {
        source: wgpu::BufferAsyncError,
    }))
}

/// A texture read-back under way: the copy is submitted and the buffer's mapping requested;
/// [`Self::poll`] gives the image once the device has mapped it (a later frame in a browser).
#[derive(Debug)]
pub struct PendingRead {
    buffer: wgpu::Buffer,
    size: [u32; 2],
    padded: u32,
    bgra: bool,
    format: wgpu::TextureFormat,
    mapped: std::sync::Arc<std::sync::Mutex<Option<Result<(), wgpu::BufferAsyncError>>>>,
}

impl PendingRead {
    /// Submits the copy of `texture` (formats as [`read_texture_rgba`]) and asks for the
    /// buffer's mapping.
    pub fn start(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        texture: &wgpu::Texture,
    ) -> Result<Self, RenderError> {
        use wgpu::TextureFormat as F;
        let format = texture.format();
        let bgra = match format {
            F::Rgba8Unorm | F::Rgba8UnormSrgb => false,
            F::Bgra8Unorm | F::Bgra8UnormSrgb => true,
            _ => return Err(RenderError::UnsupportedFormat { format }),
        };
        let (width, height) = (texture.width(), texture.height());
        let padded = padded_bytes_per_row(width);
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("armlab read-back"),
            size: padded as u64 * height as u64,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("armlab read-back"),
        });
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded),
                    rows_per_image: Some(height),
                },
            },
            wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
        );
        queue.submit([encoder.finish()]);
        if let Some(e) = super::error::scope_error(scope.pop()) {
            return Err(e.into());
        }
        let mapped = std::sync::Arc::new(std::sync::Mutex::new(None));
        let slot = mapped.clone();
        buffer.map_async(wgpu::MapMode::Read, .., move |r| {
            if let Ok(mut s) = slot.lock() {
                *s = Some(r);
            }
        });
        Ok(Self {
            buffer,
            size: [width, height],
            padded,
            bgra,
            format,
            mapped,
        })
    }

    /// The image once the buffer is mapped (polls the device without waiting); `None` while
    /// the GPU has not finished.
    pub fn poll(&self, device: &wgpu::Device) -> Option<Result<image::RgbaImage, RenderError>> {
        if let Err(e) = device.poll(wgpu::PollType::Poll) {
            return Some(Err(e.into()));
        }
        let state = self.mapped.lock().ok()?.take()?;
        Some(
            state
                .map_err(|source| RenderError::Map { source })
                .and_then(|()| self.pixels()),
        )
    }

    fn pixels(&self) -> Result<image::RgbaImage, RenderError> {
        let [width, height] = self.size;
        let unpadded = width as usize * 4;
        let mut pixels = Vec::with_capacity(unpadded * height as usize);
        {
            let view = self.buffer.get_mapped_range(..)?;
            for row in view.chunks_exact(self.padded as usize) {
                pixels.extend_from_slice(&row[..unpadded]);
            }
        }
        self.buffer.unmap();
        if self.bgra {
            pixels.chunks_exact_mut(4).for_each(|px| px.swap(0, 2));
        }
        image::RgbaImage::from_raw(width, height, pixels).ok_or(RenderError::UnsupportedFormat {
            format: self.format,
        })
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn rows_pad_to_256_bytes() {
        assert_eq!(super::padded_bytes_per_row(64), 256);
        assert_eq!(super::padded_bytes_per_row(1000), 4096);
        assert_eq!(super::padded_bytes_per_row(1), 256);
    }
}
