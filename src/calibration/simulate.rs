//! Simulated calibration data: a "real" robot (the nominal plus seeded deviations of the free
//! parameters) and measurements of it with seeded noise.

use super::CalibrationError;
use super::model::{Measurement, ParameterModel};
use crate::kinematics::ik::numerical::SplitMix;
use crate::kinematics::pose::Pose;
use nalgebra::{Rotation3, Translation3, Vector3};

/// What to simulate; every field with its unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SimulationOptions {
    /// Measured poses for the fit.
    pub poses: usize,
    /// Held-out poses for validation.
    pub validation_poses: usize,
    /// Each free length deviates uniformly within +- this (mm).
    pub tolerance_mm: f64,
    /// Each free angle (twists and joint offsets) deviates uniformly within +- this (degrees).
    pub tolerance_deg: f64,
    /// Position noise of a measurement (mm, one sigma, Gaussian per axis).
    pub noise_mm: f64,
    /// Orientation noise (mrad, one sigma, Gaussian per axis of a small rotation).
    pub noise_mrad: f64,
    /// Measure positions only (a laser tracker without orientation).
    pub position_only: bool,
    /// Seed: the same seed gives the same robot and data.
    pub seed: u64,
}

impl Default for SimulationOptions {
    /// 50 poses and 50 held out, 1 mm and 0.5 degree tolerances, 0.05 mm and 0.1 mrad noise,
    /// full poses, seed 1.
    fn default() -> Self {
        Self {
            poses: 50,
            validation_poses: 50,
            tolerance_mm: 1.0,
            tolerance_deg: 0.5,
            noise_mm: 0.05,
            noise_mrad: 0.1,
            position_only: false,
            seed: 1,
        }
    }
}

/// A simulated calibration problem.
#[derive(Debug, Clone)]
pub struct Simulated {
    /// The true zeta of the "real" robot.
    pub truth: Vec<f64>,
    /// Measurements for the fit.
    pub measurements: Vec<Measurement>,
    /// Held-out measurements.
    pub validation: Vec<Measurement>,
}

/// Uniform and Box–Muller normal numbers from the solver's SplitMix64.
struct Rng(SplitMix);

impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0.next_f64()
    }

    fn normal(&mut self) -> f64 {
        let u1 = self.uniform().max(1e-300);
        let u2 = self.uniform();
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }
}

/// A "real" robot and its measurements: every free parameter of `model` moved within the
/// tolerances, joint vectors drawn uniformly in the limits (their finite sampling ranges), the
/// real tool pose measured with Gaussian noise.
pub fn simulate(
    model: &ParameterModel,
    opts: &SimulationOptions,
) -> Result<Simulated, CalibrationError> {
    for (name, v) in [
        ("tolerance_mm", opts.tolerance_mm),
        ("tolerance_deg", opts.tolerance_deg),
        ("noise_mm", opts.noise_mm),
        ("noise_mrad", opts.noise_mrad),
    ] {
        if !(v >= 0.0 && v.is_finite()) {
            return Err(CalibrationError::InvalidOption(format!(
                "{name} must be >= 0 and finite, got {v}"
            )));
        }
    }
    let mut rng = Rng(SplitMix(opts.seed ^ 0xCA11_B8A7));
    let mut truth = model.nominal();
    for (z, p) in truth.iter_mut().zip(model.parameters()) {
        if p.fixed {
            continue;
        }
        let tol = if p.kind.is_angle() {
            opts.tolerance_deg.to_radians()
        } else {
            opts.tolerance_mm * 1e-3
        };
        *z += tol * (2.0 * rng.uniform() - 1.0);
    }
    let robot = model.nominal_robot();
    let ranges = robot.sampling_ranges();
    let draw = |count: usize, rng: &mut Rng| -> Result<Vec<Measurement>, CalibrationError> {
        (0..count)
            .map(|_| {
                let q: Vec<f64> = ranges
                    .iter()
                    .map(|[lo, hi]| lo + (hi - lo) * rng.uniform())
                    .collect();
                let (_, t) = model.frames(&truth, &q)?;
                let dp =
                    Vector3::new(rng.normal(), rng.normal(), rng.normal()) * opts.noise_mm * 1e-3;
                let p = t.translation.vector + dp;
                Ok(if opts.position_only {
                    Measurement::Position { q, p }
                } else {
                    let dphi = Vector3::new(rng.normal(), rng.normal(), rng.normal())
                        * opts.noise_mrad
                        * 1e-3;
                    let r = Rotation3::new(dphi) * t.rotation;
                    Measurement::Pose {
                        q,
                        world_from_tool: Pose::from_parts(Translation3::from(p), r),
                    }
                })
            })
            .collect()
    };
    let measurements = draw(opts.poses, &mut rng)?;
    let validation = draw(opts.validation_poses, &mut rng)?;
    Ok(Simulated {
        truth,
        measurements,
        validation,
    })
}
