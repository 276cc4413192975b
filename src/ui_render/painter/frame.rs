//! A whole egui frame handed to eframe as one paint callback, painted by the [`UiPainter`].

use super::UiPainter;
use egui::epaint::ClippedPrimitive;

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
    pub(super) fn take_textures(&self) -> egui::TexturesDelta {
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
