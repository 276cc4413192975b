//! Scene labels drawn by egui over a rendered 3D view (the app's viewport and the headless
//! scene figures): each at its anchor's projection; the movable ones (ghost posture names)
//! are moved up, or else down, out of each other's way, with a thin leader line back to
//! their anchor.

use crate::camera::Camera;
use crate::scene::Label;
use egui::{Align2, Color32, FontId, Painter, Rect, Stroke, vec2};

/// Gap (points) between a label and its anchor, and between stacked labels.
const GAP: f32 = 3.0;

/// Draws `labels` of a view rendered at `size_px` pixels by `camera` and shown in `view`
/// (points); labels whose anchor is behind the camera are skipped.
pub fn draw_labels(
    painter: &Painter,
    view: Rect,
    size_px: [u32; 2],
    camera: &Camera,
    labels: &[Label],
    font: &FontId,
) {
    let [w, h] = size_px;
    let scale = view.width() / w.max(1) as f32;
    let mut placed: Vec<Rect> = Vec::new();
    // Fixed labels first; movable ones avoid only each other (frame labels are small and
    // many: steering posture names around every axis tip would carry them far from their arm).
    let mut order: Vec<&Label> = labels.iter().filter(|l| !l.movable).collect();
    order.extend(labels.iter().filter(|l| l.movable));
    for l in order {
        let Some(p) = camera.project(&l.p.into(), w, h) else {
            continue;
        };
        let anchor = view.min + vec2(p[0], p[1]) * scale;
        let c = l.color.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8);
        let color = Color32::from_rgb(c[0], c[1], c[2]);
        let galley = painter.layout_no_wrap(l.text.clone(), font.clone(), color);
        let mut home = Align2::LEFT_BOTTOM.anchor_size(anchor + vec2(GAP, -GAP), galley.size());
        if l.movable && home.max.x > view.max.x - GAP {
            // Kept inside the view rather than cut at its right edge.
            home = home.translate(vec2(
                (view.max.x - GAP - home.max.x).max(view.min.x - home.min.x),
                0.0,
            ));
        }
        let at = if l.movable {
            let r = free_spot(home, &placed, view);
            placed.push(r);
            // A light plate keeps the text readable over the arm and the gizmo.
            painter.rect_filled(r.expand(1.5), 2.0, Color32::from_white_alpha(190));
            r
        } else {
            home
        };
        if at != home {
            let end = if at.center().y < anchor.y {
                at.left_bottom()
            } else {
                at.left_top()
            };
            painter.line_segment([anchor, end], Stroke::new(1.0, color.gamma_multiply(0.5)));
        }
        painter.galley(at.min, galley, color);
    }
}

/// The nearest place above `home` (or, when that leaves `view`, below it) where a rectangle
/// of its size overlaps none of `taken`.
fn free_spot(home: Rect, taken: &[Rect], view: Rect) -> Rect {
    let slide = |up: bool| {
        let mut r = home;
        for _ in 0..=taken.len() {
            let Some(o) = taken.iter().find(|o| o.intersects(r)) else {
                return Some(r);
            };
            let dy = if up {
                o.min.y - GAP - r.max.y
            } else {
                o.max.y + GAP - r.min.y
            };
            r = r.translate(vec2(0.0, dy));
        }
        None
    };
    match slide(true) {
        Some(r) if r.min.y >= view.min.y => r,
        _ => slide(false).unwrap_or(home),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use egui::Pos2;

    #[test]
    fn stacked_labels_do_not_overlap_and_stay_near() {
        let view = Rect::from_min_size(Pos2::ZERO, vec2(400.0, 400.0));
        let mut taken = Vec::new();
        for _ in 0..5 {
            let home = Rect::from_min_size(Pos2::new(100.0, 200.0), vec2(80.0, 14.0));
            let r = free_spot(home, &taken, view);
            assert!(taken.iter().all(|t: &Rect| !t.intersects(r)));
            assert!((r.min.y - 200.0).abs() <= 5.0 * 17.0 + 1e-3);
            taken.push(r);
        }
        // Near the top edge, labels go down instead.
        let home = Rect::from_min_size(Pos2::new(10.0, 2.0), vec2(80.0, 14.0));
        let a = free_spot(home, &[], view);
        let b = free_spot(home, &[a], view);
        assert!(b.min.y > a.max.y && b.min.y >= view.min.y);
    }
}
