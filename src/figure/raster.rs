//! Large point sets as an image: each sample sets a bit for its class in the pixel it falls in,
//! and a palette maps each combination of classes to a colour. A million samples take a few
//! milliseconds and show the regions of Fig. 2.30 (one posture only, both postures) directly.

/// A class-occupancy raster over a rectangle of the plane.
#[derive(Debug, Clone, PartialEq)]
pub struct ClassRaster {
    /// Pixels across.
    pub width: u32,
    /// Pixels down.
    pub height: u32,
    /// Bounds `[x_min, x_max, y_min, y_max]` (m or rad, the plot's units).
    pub bounds: [f64; 4],
    /// One bitmask per pixel, row-major from the top row (bit k = class k hit it;
    /// [`UNSURE`] after [`ClassRaster::mark_unsure`]).
    pub masks: Vec<u32>,
    /// Samples that fell in each pixel (saturating).
    pub counts: Vec<u32>,
}

/// Mask of a pixel that samples reached but too few to tell whether one posture only reaches it
/// (see [`ClassRaster::mark_unsure`]).
pub const UNSURE: u32 = 1 << 31;

/// Samples a single-class pixel needs (itself, or with its 8 neighbours when they all show the
/// same class) before it is shown as "that posture only": if two postures reach a pixel about
/// equally often, 8 samples all of one of them happen 2 * 2^-8 < 1 % of the time.
pub const MIN_EVIDENCE: u32 = 8;

impl ClassRaster {
    /// An empty raster.
    pub fn new(width: u32, height: u32, bounds: [f64; 4]) -> Self {
        Self {
            width,
            height,
            bounds,
            masks: vec![0; width as usize * height as usize],
            counts: vec![0; width as usize * height as usize],
        }
    }

    /// Pixel of a point, if inside.
    #[inline]
    pub fn pixel(&self, x: f64, y: f64) -> Option<usize> {
        let [x0, x1, y0, y1] = self.bounds;
        let u = (x - x0) / (x1 - x0) * self.width as f64;
        let v = (y1 - y) / (y1 - y0) * self.height as f64;
        if u >= 0.0 && v >= 0.0 && u < self.width as f64 && v < self.height as f64 {
            Some(v as usize * self.width as usize + u as usize)
        } else {
            None
        }
    }

    /// Marks class `class` (< 32) at every point.
    pub fn splat(&mut self, points: impl Iterator<Item = ([f64; 2], u8)>) {
        for (p, c) in points {
            if let Some(i) = self.pixel(p[0], p[1]) {
                self.masks[i] |= 1 << (c.min(30));
                self.counts[i] = self.counts[i].saturating_add(1);
            }
        }
    }

    /// Fills isolated empty pixels whose four neighbours are set (sampling holes inside a region),
    /// so densities below one sample per pixel still read as areas.
    pub fn close_holes(&mut self) {
        let (w, h) = (self.width as usize, self.height as usize);
        let src = self.masks.clone();
        for y in 1..h.saturating_sub(1) {
            for x in 1..w.saturating_sub(1) {
                let i = y * w + x;
                if src[i] == 0 {
                    let n = [src[i - 1], src[i + 1], src[i - w], src[i + w]];
                    if n.iter().all(|&m| m != 0) {
                        self.masks[i] = n[0] | n[1] | n[2] | n[3];
                    }
                }
            }
        }
    }

    /// Turns single-class pixels without enough evidence into [`UNSURE`]: a pixel one sample
    /// reached shows one class whatever else reaches it, which at a sparse rim paints speckles
    /// of "X only" that are not true. A single-class pixel keeps its class when it holds at
    /// least `min_samples` samples, or when its 3x3 neighbourhood does and shows that class
    /// only (regions that one posture alone reaches are areas, not specks).
    pub fn mark_unsure(&mut self, min_samples: u32) {
        let (w, h) = (self.width as usize, self.height as usize);
        let src = self.masks.clone();
        for y in 0..h {
            for x in 0..w {
                let i = y * w + x;
                let m = src[i];
                if m.count_ones() != 1 || self.counts[i] >= min_samples {
                    continue;
                }
                let (mut pooled, mut n) = (0u32, 0u32);
                for yy in y.saturating_sub(1)..(y + 2).min(h) {
                    for xx in x.saturating_sub(1)..(x + 2).min(w) {
                        pooled |= src[yy * w + xx] & !UNSURE;
                        n = n.saturating_add(self.counts[yy * w + xx]);
                    }
                }
                if pooled != m || n < min_samples {
                    self.masks[i] = UNSURE;
                }
            }
        }
    }

    /// Fraction of the set pixels whose mask equals `mask`.
    pub fn fraction(&self, mask: u32) -> f64 {
        let set = self.masks.iter().filter(|&&m| m != 0).count();
        if set == 0 {
            0.0
        } else {
            self.masks.iter().filter(|&&m| m == mask).count() as f64 / set as f64
        }
    }

    /// RGBA image (transparent where no class) using `palette(mask) -> [r, g, b, a]`.
    pub fn to_image(&self, palette: impl Fn(u32) -> [u8; 4]) -> egui::ColorImage {
        let pixels = self.masks.iter().map(|&m| {
            if m == 0 {
                egui::Color32::TRANSPARENT
            } else {
                let [r, g, b, a] = palette(m);
                egui::Color32::from_rgba_unmultiplied(r, g, b, a)
            }
        });
        egui::ColorImage::new(
            [self.width as usize, self.height as usize],
            pixels.collect(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn single_samples_do_not_claim_one_posture_only() {
        // 10x10 pixels over [0, 10]^2: pixel (x, y) has its centre at (x + 0.5, 9.5 - y).
        let mut r = ClassRaster::new(10, 10, [0.0, 10.0, 0.0, 10.0]);
        let at = |x: usize, y: usize| [x as f64 + 0.5, 9.5 - y as f64];
        let mut pts = Vec::new();
        // A lone sample of class 0 at (1, 1), next to a mixed pixel at (2, 1).
        pts.push((at(1, 1), 0u8));
        pts.push((at(2, 1), 0));
        pts.push((at(2, 1), 1));
        // A 3x3 block of class 1 with one sample per pixel at (6..9, 6..9): an area.
        for y in 6..9 {
            for x in 6..9 {
                pts.push((at(x, y), 1));
            }
        }
        // Nine samples of class 0 in one pixel (4, 8): enough on its own.
        pts.extend(std::iter::repeat_n((at(4, 8), 0u8), 9));
        r.splat(pts.into_iter());
        r.mark_unsure(MIN_EVIDENCE);
        let m = |x: usize, y: usize| r.masks[y * 10 + x];
        assert_eq!(m(1, 1), UNSURE, "one sample claims nothing");
        assert_eq!(m(2, 1), 0b11, "two classes seen are two classes");
        assert_eq!(
            m(7, 7),
            0b10,
            "the centre of a one-class area keeps its class"
        );
        assert_eq!(m(6, 6), UNSURE, "a corner sees 4 samples only");
        assert_eq!(m(7, 6), UNSURE, "an edge sees 6 samples only");
        assert_eq!(m(4, 8), 0b01);
        assert_eq!(m(0, 0), 0);
    }

    #[test]
    fn splat_sets_bits_at_the_right_pixels() {
        let mut r = ClassRaster::new(10, 10, [0.0, 1.0, 0.0, 1.0]);
        r.splat(
            [
                ([0.05, 0.95], 0u8),
                ([0.05, 0.95], 1u8),
                ([0.95, 0.05], 1u8),
                ([2.0, 0.5], 0u8),
            ]
            .into_iter(),
        );
        assert_eq!(r.masks[0], 0b11);
        assert_eq!(r.masks[99], 0b10);
        assert_eq!(r.masks.iter().filter(|&&m| m != 0).count(), 2);
        assert!((r.fraction(0b11) - 0.5).abs() < 1e-12);
    }
}
