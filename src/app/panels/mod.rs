//! The side panels. Each panel group is a module that owns its state, reads the shared state
//! and returns actions: the model and its joints (left), the readouts and inverse kinematics
//! with the cell, reachability, construction and redundancy sections (right).

pub mod cell;
pub mod construction;
pub mod ik;
pub mod model;
pub mod reachability;
pub mod redundancy;
pub mod symbols;

/// A warning in a space reserved for it: at least one text row whether or not there is a
/// warning, grown to fit its text while no pointer button is down, and frozen while one is (a
/// drag): nothing below moves under the pointer when a warning comes and goes during a drag
/// (the self-motion slider jumped 67 px down when one appeared). A warning longer than the
/// frozen space is cut there and shown whole on hover, and whole after the release.
/// `key` names the place (one reserved space per key).
pub fn reserved_warning(ui: &mut egui::Ui, key: &str, text: Option<egui::RichText>) {
    let id = ui.scope_id().with(("reserved warning", key));
    let width = ui.available_width();
    let row = ui.text_style_height(&egui::TextStyle::Body);
    let galley = text.as_ref().map(|t| {
        egui::WidgetText::from(t.clone()).into_galley(
            ui,
            Some(egui::TextWrapMode::Wrap),
            width,
            egui::TextStyle::Body,
        )
    });
    let needed = galley.as_ref().map_or(row, |g| g.size().y.max(row));
    let held = ui.input(|i| i.pointer.any_down());
    let kept: Option<f32> = ui.data(|d| d.get_temp(id));
    let height = match (held, kept) {
        (true, Some(h)) => h,
        _ => needed,
    };
    ui.data_mut(|d| d.insert_temp(id, height));
    let (rect, response) = ui.allocate_exact_size(egui::vec2(width, height), egui::Sense::hover());
    let Some(galley) = galley else {
        return;
    };
    // Its text to assistive tools (and to tests that read the window).
    let said = galley.text().to_string();
    response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Label, true, &said));
    let cut = galley.size().y > height + 0.5;
    ui.painter()
        .with_clip_rect(rect.intersect(ui.clip_rect()))
        .galley(rect.min, galley, ui.visuals().text_color());
    if cut && let Some(t) = text {
        response.on_hover_text(t);
    }
}
