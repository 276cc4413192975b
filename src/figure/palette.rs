//! Colours of workspace figures: posture classes (colour-blind safe), "several postures",
//! pixels with too few samples to tell, plain points, and a sequential map for scalar fields.

use super::raster::UNSURE;
use egui::Color32;

/// Colours of posture classes (colour-blind safe), of "several postures", and of plain points.
pub(crate) const CLASS_COLORS: [[u8; 3]; 6] = [
    [0, 114, 178],
    [230, 159, 0],
    [204, 121, 167],
    [86, 180, 233],
    [213, 94, 0],
    [240, 228, 66],
];
/// "Several postures".
pub(crate) const SEVERAL: [u8; 3] = [0, 158, 115];
/// Points without classes.
pub(crate) const PLAIN: [u8; 3] = [70, 110, 190];
/// Pixels reached by too few samples to tell the postures (see [`super::raster::UNSURE`]).
pub(crate) const UNSURE_GREY: [u8; 3] = [165, 165, 165];

/// An opaque egui colour.
pub(crate) fn c32(c: [u8; 3]) -> Color32 {
    Color32::from_rgb(c[0], c[1], c[2])
}

/// A perceptually ordered map for t in [0, 1] (dark blue -> teal -> yellow).
pub(crate) fn sequential(t: f32) -> [u8; 3] {
    const STOPS: [[f32; 3]; 5] = [
        [68.0, 1.0, 84.0],
        [59.0, 82.0, 139.0],
        [33.0, 145.0, 140.0],
        [94.0, 201.0, 98.0],
        [253.0, 231.0, 37.0],
    ];
    let x = t.clamp(0.0, 1.0) * 4.0;
    let i = (x.floor() as usize).min(3);
    let f = x - i as f32;
    std::array::from_fn(|k| (STOPS[i][k] + (STOPS[i + 1][k] - STOPS[i][k]) * f).round() as u8)
}

/// Legend and palette for class masks.
pub(crate) fn class_palette(names: &[String]) -> (Vec<(String, Color32)>, impl Fn(u32) -> [u8; 4]) {
    let n = names.len().min(CLASS_COLORS.len());
    let mut legend: Vec<(String, Color32)> = (0..n)
        .map(|k| (format!("{} only", names[k]), c32(CLASS_COLORS[k])))
        .collect();
    if n == 2 {
        legend.push(("both postures".into(), c32(SEVERAL)));
    } else if n > 2 {
        legend.push(("several postures".into(), c32(SEVERAL)));
    }
    let palette = move |m: u32| {
        if m == UNSURE {
            return [UNSURE_GREY[0], UNSURE_GREY[1], UNSURE_GREY[2], 235];
        }
        let m = m & ((1u32 << n.max(1)) - 1);
        let c = if m.count_ones() == 1 {
            CLASS_COLORS[m.trailing_zeros() as usize]
        } else if m == 0 {
            PLAIN
        } else {
            SEVERAL
        };
        [c[0], c[1], c[2], 235]
    };
    (legend, palette)
}
