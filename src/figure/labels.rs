//! Scene labels drawn by egui over a rendered 3D view: the app's viewport, the window's
//! screenshots and the headless 3D figures all place them with one placer ([`place`]), so that
//! no two labels overlap, none covers an obstacle (the IK target's gizmo) and none leaves the
//! view. Each label tries spots around its anchor, nearest first; a label moved away from its
//! anchor gets a thin leader line back to it; a label with no free spot near enough is left out
//! (the most important labels are placed first: construction and posture labels, then frame
//! labels).

use crate::camera::Camera;
use crate::scene::Label;
use egui::{Align2, Color32, FontId, Painter, Pos2, Rect, Stroke, Vec2, vec2};

/// Gap (points) between a label and its anchor, and between labels.
const GAP: f32 = 3.0;
/// How far (points) a label may move from its anchor before it is left out.
const MAX_MOVE: f32 = 90.0;

/// A label to place: its anchor, its size and its rank (lower is placed first).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToPlace {
    /// Where it points (view coordinates, points).
    pub anchor: Pos2,
    /// Its text's size (points).
    pub size: Vec2,
    /// Placed in ascending order of rank (ties keep the input order).
    pub rank: u8,
}

/// Where each label goes: a rectangle free of the others, of `obstacles` and inside `view`, as
/// near its anchor as can be; `None` for a label with no free spot within reach.
pub fn place(labels: &[ToPlace], obstacles: &[Rect], view: Rect) -> Vec<Option<Rect>> {
    let mut order: Vec<usize> = (0..labels.len()).collect();
    order.sort_by_key(|&i| labels[i].rank);
    let mut taken: Vec<Rect> = obstacles.to_vec();
    let mut out = vec![None; labels.len()];
    let inside = view.shrink(1.0);
    for i in order {
        let l = &labels[i];
        let spot = candidates(l.anchor, l.size).find(|r| {
            inside.contains_rect(*r) && !taken.iter().any(|t| t.expand(GAP).intersects(*r))
        });
        if let Some(r) = spot {
            taken.push(r);
            out[i] = Some(r);
        }
    }
    out
}

/// The spots a label of `size` anchored at `a` tries, nearest first: above right of the anchor
/// (the home spot), then around it on rings of growing radius.
fn candidates(a: Pos2, size: Vec2) -> impl Iterator<Item = Rect> {
    let home = Align2::LEFT_BOTTOM.anchor_size(a + vec2(GAP, -GAP), size);
    let step = size.y + GAP;
    let rings = (1..)
        .map(move |k| k as f32 * step)
        .take_while(|r| *r <= MAX_MOVE);
    std::iter::once(home).chain(rings.flat_map(move |r| {
        (0..12).map(move |k| {
            let t = k as f32 * std::f32::consts::TAU / 12.0;
            // Rotate from "up" so that nearly-home spots come first.
            let d = vec2(t.sin(), -t.cos()) * r;
            home.translate(d)
        })
    }))
}

/// Draws `labels` of a view rendered at `size_px` pixels by `camera` and shown in `view`
/// (points), placed by [`place`] around `obstacles` (points); labels whose anchor is behind the
/// camera or outside the view are skipped. Returns the rectangles drawn.
pub fn draw_labels(
    painter: &Painter,
    view: Rect,
    (size_px, camera): ([u32; 2], &Camera),
    labels: &[Label],
    obstacles: &[Rect],
    font: &FontId,
) -> Vec<Rect> {
    let [w, h] = size_px;
    let scale = view.width() / w.max(1) as f32;
    let mut shown = Vec::new();
    let mut galleys = Vec::new();
    for l in labels {
        let Some(p) = camera.project(&l.p.into(), w, h) else {
            continue;
        };
        let anchor = view.min + vec2(p[0], p[1]) * scale;
        if !view.contains(anchor) {
            continue;
        }
        let c = l.color.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8);
        let color = Color32::from_rgb(c[0], c[1], c[2]);
        let galley = painter.layout_no_wrap(l.text.clone(), font.clone(), color);
        shown.push(ToPlace {
            anchor,
            size: galley.size(),
            // Movable labels (posture names, constructions) before frame labels.
            rank: u8::from(!l.movable),
        });
        galleys.push((galley, color, l.movable));
    }
    let spots = place(&shown, obstacles, view);
    let mut drawn = Vec::new();
    for ((to, spot), (galley, color, plate)) in shown.iter().zip(spots).zip(galleys) {
        let Some(at) = spot else { continue };
        let home = Align2::LEFT_BOTTOM.anchor_size(to.anchor + vec2(GAP, -GAP), to.size);
        if plate {
            // A light plate keeps the text readable over the arm.
            painter.rect_filled(at.expand(1.5), 2.0, Color32::from_white_alpha(190));
        }
        if at != home {
            let end = at.clamp_point_to(to.anchor);
            painter.line_segment(
                [to.anchor, end],
                Stroke::new(1.0, color.gamma_multiply(0.5)),
            );
        }
        painter.galley(at.min, galley, color);
        drawn.push(at);
    }
    drawn
}

/// The nearest point of `r` to `p`.
trait Clamp {
    fn clamp_point_to(&self, p: Pos2) -> Pos2;
}

impl Clamp for Rect {
    fn clamp_point_to(&self, p: Pos2) -> Pos2 {
        Pos2::new(
            p.x.clamp(self.min.x, self.max.x),
            p.y.clamp(self.min.y, self.max.y),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn view() -> Rect {
        Rect::from_min_size(Pos2::ZERO, vec2(400.0, 400.0))
    }

    #[test]
    fn crowded_labels_never_overlap_and_stay_near() {
        let labels: Vec<ToPlace> = (0..20)
            .map(|k| ToPlace {
                anchor: Pos2::new(200.0 + (k % 3) as f32, 200.0),
                size: vec2(60.0, 14.0),
                rank: (k % 2) as u8,
            })
            .collect();
        let spots = place(&labels, &[], view());
        let placed: Vec<Rect> = spots.iter().flatten().copied().collect();
        assert!(placed.len() >= 10, "{} placed", placed.len());
        for (i, a) in placed.iter().enumerate() {
            assert!(view().contains_rect(*a));
            for b in &placed[i + 1..] {
                assert!(!a.intersects(*b), "{a:?} {b:?}");
            }
        }
        for (l, s) in labels.iter().zip(&spots) {
            if let Some(r) = s {
                assert!((r.center() - l.anchor).length() <= MAX_MOVE + 40.0);
            }
        }
    }

    #[test]
    fn labels_keep_off_obstacles_and_inside_the_view() {
        let gizmo = Rect::from_center_size(Pos2::new(200.0, 200.0), vec2(80.0, 80.0));
        let labels = [
            ToPlace {
                anchor: Pos2::new(200.0, 200.0),
                size: vec2(50.0, 14.0),
                rank: 0,
            },
            ToPlace {
                anchor: Pos2::new(395.0, 5.0),
                size: vec2(50.0, 14.0),
                rank: 0,
            },
        ];
        let spots = place(&labels, &[gizmo], view());
        let a = spots[0].expect("a spot outside the gizmo");
        assert!(!a.intersects(gizmo));
        let b = spots[1].expect("a spot inside the view");
        assert!(view().contains_rect(b));
    }
}
