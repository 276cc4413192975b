//! A GPU buffer that grows (to the next power of two) and is otherwise reused frame to frame.

use super::{Gpu, RenderError};

/// A vertex buffer of instances, rewritten each frame.
#[derive(Debug)]
pub(crate) struct GrowBuffer {
    label: &'static str,
    /// What the instances are ("meshes", "lines", "dots"), for errors.
    kind: &'static str,
    usage: wgpu::BufferUsages,
    buffer: Option<wgpu::Buffer>,
    /// Times the buffer was (re)allocated, for tests of reuse.
    allocations: u32,
}

impl GrowBuffer {
    pub(crate) fn new(label: &'static str, kind: &'static str, usage: wgpu::BufferUsages) -> Self {
        Self {
            label,
            kind,
            usage: usage | wgpu::BufferUsages::COPY_DST,
            buffer: None,
            allocations: 0,
        }
    }

    /// Uploads `items` (replacing the previous contents), growing the buffer if they do not fit.
    /// Does nothing for an empty slice.
    pub(crate) fn write<T: bytemuck::Pod>(
        &mut self,
        gpu: &Gpu,
        items: &[T],
    ) -> Result<(), RenderError> {
        if items.is_empty() {
            return Ok(());
        }
        let bytes: &[u8] = bytemuck::cast_slice(items);
        let needed = bytes.len() as u64;
        let max = gpu.device.limits().max_buffer_size;
        if needed > max {
            return Err(RenderError::TooMany {
                kind: self.kind,
                count: items.len(),
                bytes: needed,
                max,
            });
        }
        if self.buffer.as_ref().is_none_or(|b| b.size() < needed) {
            let size = needed.next_power_of_two().max(4096).min(max).max(needed);
            self.buffer = Some(gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(self.label),
                size,
                usage: self.usage,
                mapped_at_creation: false,
            }));
            self.allocations += 1;
        }
        if let Some(b) = &self.buffer {
            gpu.queue.write_buffer(b, 0, bytes);
        }
        Ok(())
    }

    /// The buffer (after a non-empty [`Self::write`]).
    pub(crate) fn buffer(&self) -> Option<&wgpu::Buffer> {
        self.buffer.as_ref()
    }

    /// How many times the buffer was allocated.
    pub(crate) fn allocations(&self) -> u32 {
        self.allocations
    }
}
