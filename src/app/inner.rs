//! The app's widgets laid out in a context of their own and painted by
//! [`crate::ui_render::painter::UiPainter`] inside one paint callback of eframe's frame, rather
//! than painted by egui-wgpu (whose shader is several times dearer per pixel on Mesa 22's
//! software rasterizer; see the painter's documentation). eframe's context keeps the window:
//! it receives the input, which is handed on unchanged, and gets back what the inner context
//! asks of the platform (cursor, clipboard, repaints, viewport commands).

use crate::ui_render::painter::UiFrame;

/// The inner context.
#[derive(Default)]
pub struct InnerUi {
    ctx: egui::Context,
}

impl InnerUi {
    /// Runs `ui` on this frame's input of `outer`, forwards the platform side of its output to
    /// `outer`, and returns the frame to paint.
    pub fn run(&mut self, outer: &egui::Context, ui: impl FnMut(&mut egui::Ui)) -> UiFrame {
        let raw = outer.input(|i| i.raw.clone());
        let ppp = outer.pixels_per_point();
        let size = outer.content_rect().size() * ppp;
        let out = self.ctx.run_ui(raw, ui);
        let egui::FullOutput {
            mut platform_output,
            textures_delta,
            shapes,
            pixels_per_point,
            viewport_output,
        } = out;
        // The inner context's passes are its own: counted into the outer's output, every frame
        // looks like a discarded one to eframe's context (which then warns on screen).
        platform_output.num_completed_passes = 0;
        platform_output.request_discard_reasons.clear();
        outer.output_mut(|o| o.append(platform_output));
        for (id, v) in viewport_output {
            if id != egui::ViewportId::ROOT {
                continue;
            }
            for c in v.commands {
                outer.send_viewport_cmd(c);
            }
            if v.repaint_delay.is_zero() {
                outer.request_repaint();
            } else if v.repaint_delay < std::time::Duration::from_secs(3600) {
                outer.request_repaint_after(v.repaint_delay);
            }
        }
        UiFrame {
            prims: self.ctx.tessellate(shapes, pixels_per_point),
            textures: std::sync::Mutex::new(textures_delta),
            size_px: [size.x.round() as u32, size.y.round() as u32],
            pixels_per_point,
        }
    }
}
