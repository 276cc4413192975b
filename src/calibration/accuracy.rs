//! Accuracy over the workspace (Sect. 2.10.1: accuracy "varies with the end-effector position"):
//! the position deviation between two models of one arm (nominal vs real, calibrated vs real)
//! at the same joint readings, mapped over the top view of the workspace.

use super::CalibrationError;
use super::model::ParameterModel;
use crate::kinematics::ik::numerical::SplitMix;
use rayon::prelude::*;

/// The deviation map: per cell of a top-view grid (world x, y), the root mean square position
/// deviation (m) over the sampled configurations whose tool point (of the first model) falls in
/// it: the accuracy to expect at that position, whatever the height and orientation.
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct AccuracyMap {
    /// `[x_min, x_max, y_min, y_max]` (m, world frame).
    pub bounds: [f64; 4],
    /// Cells along x.
    pub width: usize,
    /// Cells along y.
    pub height: usize,
    /// Row-major from `y_min` upwards: the RMS deviation (m), NaN where no sample landed.
    pub values: Vec<f64>,
    /// Samples per cell.
    pub counts: Vec<u32>,
    /// Largest deviation over all samples (m).
    pub max: f64,
    /// Root mean square deviation over all samples (m).
    pub rms: f64,
    /// Samples drawn.
    pub samples: usize,
}

/// Samples `samples` joint vectors uniformly in the limits (seeded, in parallel) and maps the
/// distance between the tool points of the model with `zeta_a` and with `zeta_b` on a
/// `width` x `height` top-view grid spanning the sampled tool points of `zeta_a`.
pub fn accuracy_map(
    model: &ParameterModel,
    zeta_a: &[f64],
    zeta_b: &[f64],
    [width, height]: [usize; 2],
    samples: usize,
    seed: u64,
) -> Result<AccuracyMap, CalibrationError> {
    if width == 0 || height == 0 || width * height > 16_000_000 || samples == 0 {
        return Err(CalibrationError::InvalidOption(format!(
            "an accuracy map needs 1..16M cells and samples > 0, got {width} x {height}, {samples}"
        )));
    }
    let points = sample_deviations(model, zeta_a, zeta_b, samples, seed)?;
    Ok(bin(&points, width, height))
}

/// `[x, y, deviation]` of `samples` joint vectors drawn in the limits: the tool point of the
/// model with `zeta_a` and its distance to that of `zeta_b` (seeded chunks, in parallel, in the
/// order of the chunks).
fn sample_deviations(
    model: &ParameterModel,
    zeta_a: &[f64],
    zeta_b: &[f64],
    samples: usize,
    seed: u64,
) -> Result<Vec<[f64; 3]>, CalibrationError> {
    let (ra, rb) = (model.robot_with(zeta_a)?, model.robot_with(zeta_b)?);
    let ranges = ra.sampling_ranges();
    const CHUNK: usize = 8192;
    // One pass for the points and deviations: [x, y, deviation].
    let points: Vec<[f64; 3]> = (0..samples.div_ceil(CHUNK))
        .into_par_iter()
        .flat_map_iter(|c| {
            let mut g = SplitMix(seed ^ (c as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
            let n = CHUNK.min(samples - c * CHUNK);
            let mut q = vec![0.0; ranges.len()];
            let (ra, rb, ranges) = (&ra, &rb, &ranges);
            (0..n).map(move |_| {
                for (v, [lo, hi]) in q.iter_mut().zip(ranges) {
                    *v = lo + (hi - lo) * g.next_f64();
                }
                let a = ra.fk_ee_position_prechecked(&q, 0);
                let b = rb.fk_ee_position_prechecked(&q, 0);
                let d =
                    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
                [a[0], a[1], d]
            })
        })
        .collect();
    Ok(points)
}

/// The points binned into a `width` x `height` top-view grid over their own extent (half a
/// percent of margin): the RMS deviation per cell.
fn bin(points: &[[f64; 3]], width: usize, height: usize) -> AccuracyMap {
    let mut bounds = [
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    let (mut max, mut sum2) = (0.0f64, 0.0);
    for p in points {
        bounds[0] = bounds[0].min(p[0]);
        bounds[1] = bounds[1].max(p[0]);
        bounds[2] = bounds[2].min(p[1]);
        bounds[3] = bounds[3].max(p[1]);
        max = max.max(p[2]);
        sum2 += p[2] * p[2];
    }
    // A margin of half a percent, and a square-ish extent for a degenerate (planar or point) set.
    let span = (bounds[1] - bounds[0]).max(bounds[3] - bounds[2]).max(1e-6);
    let pad = 0.005 * span;
    let bounds = [
        bounds[0] - pad,
        bounds[1] + pad,
        bounds[2] - pad,
        bounds[3] + pad,
    ];
    let mut sums = vec![0.0; width * height];
    let mut counts = vec![0u32; width * height];
    let (sx, sy) = (
        width as f64 / (bounds[1] - bounds[0]),
        height as f64 / (bounds[3] - bounds[2]),
    );
    for p in points {
        let i = (((p[0] - bounds[0]) * sx) as usize).min(width - 1);
        let j = (((p[1] - bounds[2]) * sy) as usize).min(height - 1);
        sums[j * width + i] += p[2] * p[2];
        counts[j * width + i] += 1;
    }
    let values = sums
        .iter()
        .zip(&counts)
        .map(|(s, &n)| {
            if n > 0 {
                (s / f64::from(n)).sqrt()
            } else {
                f64::NAN
            }
        })
        .collect();
    AccuracyMap {
        bounds,
        width,
        height,
        values,
        counts,
        max,
        rms: (sum2 / points.len() as f64).sqrt(),
        samples: points.len(),
    }
}
