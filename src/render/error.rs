//! The render layer's one error type.

/// What can go wrong opening the GPU, making targets or drawing.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// No adapter: neither a GPU nor a software driver is installed.
    #[error(
        "no graphics adapter found: install Mesa's software Vulkan driver (apt-get install mesa-vulkan-drivers libvulkan1) and run with WGPU_BACKEND=vulkan"
    )]
    NoAdapter {
        /// What wgpu said.
        #[source]
        source: wgpu::RequestAdapterError,
    },
    /// The adapter refused to open a device.
    #[error("could not open the graphics device on {adapter}: {source}")]
    RequestDevice {
        /// Adapter name.
        adapter: String,
        /// What wgpu said.
        #[source]
        source: wgpu::RequestDeviceError,
    },
    /// A width or height of 0 or above the device's texture limit.
    #[error("invalid render size {width}x{height}: each side must be between 1 and {max} pixels")]
    InvalidSize {
        /// Requested width (px).
        width: u32,
        /// Requested height (px).
        height: u32,
        /// The device's largest texture side (px).
        max: u32,
    },
    /// A sample count other than 1 or 4.
    #[error("unsupported MSAA sample count {count}: use 1 or 4")]
    UnsupportedSampleCount {
        /// Requested count.
        count: u32,
    },
    /// The target was made for another sample count than the renderer's pipelines.
    #[error("the renderer draws with {renderer} sample(s) per pixel but the target has {target}")]
    SampleCountMismatch {
        /// The renderer's sample count.
        renderer: u32,
        /// The target's sample count.
        target: u32,
    },
    /// A draw list would need a buffer larger than the device allows.
    #[error("too many {kind} to draw at once: {count} need {bytes} bytes, the device allows {max}")]
    TooMany {
        /// "meshes", "lines" or "dots".
        kind: &'static str,
        /// Number of items.
        count: usize,
        /// Bytes needed.
        bytes: u64,
        /// The device's largest buffer (bytes).
        max: u64,
    },
    /// A texture format [`read_texture_rgba`](super::read_texture_rgba) cannot read.
    #[error("cannot read back a {format:?} texture: only 8-bit RGBA/BGRA formats")]
    UnsupportedFormat {
        /// The texture's format.
        format: wgpu::TextureFormat,
    },
    /// The GPU rejected a command (a validation or out-of-memory error).
    #[error("the GPU rejected the frame: {source}")]
    Gpu {
        /// What wgpu said.
        #[from]
        source: wgpu::Error,
    },
    /// Waiting for the GPU failed.
    #[error("waiting for the GPU failed: {source}")]
    Poll {
        /// What wgpu said.
        #[from]
        source: wgpu::PollError,
    },
    /// Mapping the read-back buffer failed.
    #[error("could not map the read-back buffer: {source}")]
    Map {
        /// What wgpu said.
        #[from]
        source: wgpu::BufferAsyncError,
    },
    /// Mapping the read-back buffer's range failed.
    #[error("could not read the mapped read-back buffer: {source}")]
    MapRange {
        /// What wgpu said.
        #[from]
        source: wgpu::MapRangeError,
    },
}

/// The error an error scope caught, from the future its `pop` returns. On the desktop the scope's
/// verdict is waited for. A browser's WebGPU answers with a promise that the page's one thread
/// cannot wait for: there the verdict is taken only if it is already known (WebGL2's is), and
/// otherwise the scope is left unchecked (`None`; an error then reaches the console as an
/// uncaptured error).
pub(crate) fn scope_error<F>(pop: F) -> Option<wgpu::Error>
where
    F: std::future::Future<Output = Option<wgpu::Error>>,
{
    #[cfg(target_arch = "wasm32")]
    {
        let mut pop = std::pin::pin!(pop);
        let mut cx = std::task::Context::from_waker(std::task::Waker::noop());
        match pop.as_mut().poll(&mut cx) {
            std::task::Poll::Ready(e) => e,
            std::task::Poll::Pending => None,
        }
    }
    #[cfg(not(target_arch = "wasm32"))]
    pollster::block_on(pop)
}
