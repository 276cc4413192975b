//! The device and queue the renderer draws with.

use super::RenderError;

/// A wgpu device, its queue and what adapter they run on.
#[derive(Debug, Clone)]
pub struct Gpu {
    /// The logical device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// Name, backend and type (e.g. "llvmpipe", Vulkan, Cpu) of the adapter.
    pub adapter_info: wgpu::AdapterInfo,
}

impl Gpu {
    /// Opens a device with no window and no surface, blocking until it is ready.
    ///
    /// Backends come from `WGPU_BACKEND` (e.g. `vulkan`, `gl`), else all compiled in; an
    /// adapter is picked by `WGPU_ADAPTER_NAME` if set, else wgpu's default choice (on a machine
    /// without a GPU: Mesa's lavapipe). The device gets the adapter's own limits, so large
    /// figures are possible where the hardware allows.
    pub fn new_headless() -> Result<Gpu, RenderError> {
        pollster::block_on(Self::new_headless_async())
    }

    async fn new_headless_async() -> Result<Gpu, RenderError> {
        let backends = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::all());
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle().with_env();
        desc.backends = backends;
        let instance = wgpu::Instance::new(desc);
        let adapter = wgpu::util::initialize_adapter_from_env_or_default(&instance, None)
            .await
            .map_err(|source| RenderError::NoAdapter { source })?;
        let adapter_info = adapter.get_info();
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("armlab"),
                required_features: wgpu::Features::empty(),
                required_limits: adapter.limits(),
                ..Default::default()
            })
            .await
            .map_err(|source| RenderError::RequestDevice {
                adapter: adapter_info.name.clone(),
                source,
            })?;
        Ok(Gpu {
            device,
            queue,
            adapter_info,
        })
    }

    /// Wraps a device someone else opened (e.g. the window's, so the render texture can be shown
    /// without a copy).
    pub fn from_parts(
        device: wgpu::Device,
        queue: wgpu::Queue,
        adapter_info: wgpu::AdapterInfo,
    ) -> Gpu {
        Gpu {
            device,
            queue,
            adapter_info,
        }
    }

    /// Largest texture side this device accepts (px).
    pub fn max_texture_side(&self) -> u32 {
        self.device.limits().max_texture_dimension_2d
    }

    /// Checks a render size against the device: both sides in `1..=max_texture_side()`.
    pub fn check_size(&self, width: u32, height: u32) -> Result<(), RenderError> {
        let max = self.max_texture_side();
        if width == 0 || height == 0 || width > max || height > max {
            return Err(RenderError::InvalidSize { width, height, max });
        }
        Ok(())
    }
}
