//! The accuracy map of a calibration (Sect. 2.10.1) as a figure: the deviation between two
//! models over the top view of the workspace, coloured with a colour bar in mm. Paints the map
//! it is handed ([`crate::calibration::accuracy_map`] computes it).

use super::figures::Figures;
use super::palette::{c32, sequential};
use super::plot2d::{ColorBar, Plot2d};
use super::{FigureError, Theme};
use crate::calibration::AccuracyMap;

/// The plot and raster of `map`, titled `title`.
///
/// `scale_max` (m) sets the top of the colour scale (larger values take its top colour), so that
/// two maps compared side by side share one scale; `None` scales to this map's own largest value.
pub fn accuracy_plot(
    map: &AccuracyMap,
    title: &str,
    scale_max: Option<f64>,
) -> (Plot2d, egui::ColorImage) {
    let top = scale_max.unwrap_or_else(|| {
        map.values
            .iter()
            .copied()
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max)
    });
    let max_mm = (top * 1e3).max(1e-9);
    let mut img = egui::ColorImage::new(
        [map.width, map.height],
        vec![egui::Color32::TRANSPARENT; map.width * map.height],
    );
    for j in 0..map.height {
        for i in 0..map.width {
            let v = map.values[j * map.width + i];
            if v.is_finite() {
                // Image rows go down, the map's rows up.
                let [r, g, b] = sequential(((v * 1e3 / max_mm) as f32).min(1.0));
                img.pixels[(map.height - 1 - j) * map.width + i] = egui::Color32::from_rgb(r, g, b);
            }
        }
    }
    let plot = Plot2d {
        title: title.into(),
        subtitle: format!(
            "RMS position deviation per cell, top view, {} samples in the joint limits; over all: rms {:.4} mm, max {:.4} mm",
            map.samples,
            map.rms * 1e3,
            map.max * 1e3
        ),
        x_label: "x [m]".into(),
        y_label: "y [m]".into(),
        bounds: map.bounds,
        equal_aspect: true,
        colorbar: Some(ColorBar {
            label: "RMS position deviation in the cell [mm] (sequential map, dark blue to yellow)"
                .into(),
            min: 0.0,
            max: max_mm,
            colors: (0..64).map(|k| c32(sequential(k as f32 / 63.0))).collect(),
        }),
        ..Plot2d::default()
    };
    (plot, img)
}

/// Renders the accuracy map to an image of `size` pixels.
pub fn accuracy_figure(
    figures: &mut Figures,
    map: &AccuracyMap,
    title: &str,
    size: [u32; 2],
    theme: Theme,
) -> Result<image::RgbaImage, FigureError> {
    let (plot, img) = accuracy_plot(map, title, None);
    figures.plot(size, theme, &plot, Some(img))
}
