//! Simulated calibration data: a "real" robot (the nominal plus seeded deviations of the free
//! parameters) and measurements of it with seeded noise.

use super::CalibrationError;
use super::model::{Measurement, ParameterModel};
use super::setup::Setup;
use crate::kinematics::ik::numerical::SplitMix;
use crate::kinematics::pose::Pose;
use nalgebra::{Rotation3, Translation3, Vector3};

/// The largest simulated joint compliance (rad per N m): 50 N m of gravity on a shoulder then
/// turns it by up to 0.1 mrad, about what industrial arms of this size show.
pub const SIMULATED_COMPLIANCE: f64 = 2e-6;

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
    let (truth, mut rng) = draw_truth(model, opts)?;
    let robot = model.nominal_robot();
    let ranges = robot.sampling_ranges();
    let draw = |count: usize, rng: &mut Rng| -> Result<Vec<Measurement>, CalibrationError> {
        (0..count)
            .map(|_| {
                let q = random_q(&ranges, rng);
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

fn random_q(ranges: &[[f64; 2]], rng: &mut Rng) -> Vec<f64> {
    ranges
        .iter()
        .map(|[lo, hi]| lo + (hi - lo) * rng.uniform())
        .collect()
}

/// The true zeta (every free parameter moved within the tolerances) and the generator after it.
fn draw_truth(
    model: &ParameterModel,
    opts: &SimulationOptions,
) -> Result<(Vec<f64>, Rng), CalibrationError> {
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
        if p.kind == super::model::Kind::Compliance {
            // A real joint's compliance: up to SIMULATED_COMPLIANCE, never negative.
            *z += SIMULATED_COMPLIANCE * rng.uniform();
            continue;
        }
        let tol = if p.kind.is_angle() {
            opts.tolerance_deg.to_radians()
        } else {
            opts.tolerance_mm * 1e-3
        };
        *z += tol * (2.0 * rng.uniform() - 1.0);
    }
    Ok((truth, rng))
}

/// What [`simulate_setup`] builds besides [`SimulationOptions`]: the setup and its scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SetupScene {
    /// The setup simulated.
    pub setup: Setup,
    /// Pivot points, planes or spheres (fit and held-out data each get their own).
    pub groups: usize,
    /// The artefact's distance between its two sockets (m), for [`Setup::Distance`].
    pub distance: f64,
    /// The contact radius (sphere plus probe ball, m), for [`Setup::Sphere`].
    pub radius: f64,
    /// The pose of the tracker's frame in the robot's world frame, for [`Setup::Tracker`]: the
    /// measured points are `world_from_tracker^-1 p`.
    pub world_from_tracker: Pose,
}

impl Default for SetupScene {
    /// Full poses, 3 groups, a 300 mm artefact, a 25 mm contact radius, the tracker 2 m in
    /// front of the robot turned 90 degrees about the vertical.
    fn default() -> Self {
        Self {
            setup: Setup::Pose,
            groups: 3,
            distance: 0.3,
            radius: 0.025,
            world_from_tracker: Pose::from_parts(
                Translation3::new(2.0, 0.5, 0.3),
                Rotation3::from_axis_angle(&Vector3::z_axis(), std::f64::consts::FRAC_PI_2),
            ),
        }
    }
}

/// A simulated calibration of `scene.setup`: the "real" robot as [`simulate`] draws it, and
/// joint vectors that put its tool point where the setup needs it (a known distance from a
/// first point, on a pivot point, on a plane, on a sphere), found by minimum-norm Newton steps
/// from random starts within the joint limits; the noise (`opts.noise_mm`) moves the point the
/// robot is driven to. `opts.poses` is the number of measurements (pairs for a distance).
pub fn simulate_setup(
    model: &ParameterModel,
    scene: &SetupScene,
    opts: &SimulationOptions,
) -> Result<Simulated, CalibrationError> {
    match scene.setup {
        Setup::Pose => return simulate(model, opts),
        Setup::Position => {
            return simulate(
                model,
                &SimulationOptions {
                    position_only: true,
                    ..*opts
                },
            );
        }
        _ => {}
    }
    if !(scene.groups >= 1 && scene.distance > 0.0 && scene.radius > 0.0) {
        return Err(CalibrationError::InvalidOption(
            "a simulated setup needs at least one group, a positive distance and radius".into(),
        ));
    }
    let (truth, mut rng) = draw_truth(model, opts)?;
    let mut sim = Placer {
        model,
        truth: &truth,
        ranges: model.nominal_robot().sampling_ranges(),
        noise: opts.noise_mm * 1e-3,
        scene,
    };
    let measurements = sim.draw(opts.poses, &mut rng)?;
    let validation = sim.draw(opts.validation_poses, &mut rng)?;
    Ok(Simulated {
        truth,
        measurements,
        validation,
    })
}

/// Puts the true robot's tool point where a setup needs it.
struct Placer<'a> {
    model: &'a ParameterModel,
    truth: &'a [f64],
    ranges: Vec<[f64; 2]>,
    noise: f64,
    scene: &'a SetupScene,
}

/// A constraint on the tool point p: its value (1 or 3 rows) and gradient rows.
type Constraint<'c> = &'c dyn Fn(&Vector3<f64>) -> (Vec<f64>, Vec<Vector3<f64>>);

impl Placer<'_> {
    fn point(&self, q: &[f64]) -> Result<Vector3<f64>, CalibrationError> {
        Ok(self.model.frames(self.truth, q)?.1.translation.vector)
    }

    /// `count` measurements of the setup, in groups of equal size.
    fn draw(&mut self, count: usize, rng: &mut Rng) -> Result<Vec<Measurement>, CalibrationError> {
        let groups = self.scene.groups.min(count.max(1));
        let mut out = Vec::with_capacity(count);
        for g in 0..groups {
            let n = count / groups + usize::from(g < count % groups);
            self.group(g, n, rng, &mut out)?;
        }
        Ok(out)
    }

    fn group(
        &self,
        g: usize,
        n: usize,
        rng: &mut Rng,
        out: &mut Vec<Measurement>,
    ) -> Result<(), CalibrationError> {
        let centre = self.point(&random_q(&self.ranges, rng))?;
        let normal = Vector3::new(rng.normal(), rng.normal(), rng.normal()).normalize();
        let (d, r) = (self.scene.distance, self.scene.radius);
        for _ in 0..n {
            let e = self.noise * rng.normal();
            let ev = Vector3::new(rng.normal(), rng.normal(), rng.normal()) * self.noise;
            let m = match self.scene.setup {
                Setup::Tracker => {
                    let q = random_q(&self.ranges, rng);
                    let p = self.scene.world_from_tracker.inverse()
                        * nalgebra::Point3::from(self.point(&q)? + ev);
                    Measurement::Position { q, p: p.coords }
                }
                Setup::Distance => {
                    let qa = random_q(&self.ranges, rng);
                    let pa = self.point(&qa)?;
                    let c = move |p: &Vector3<f64>| {
                        let v = p - pa;
                        (vec![v.norm() - (d + e)], vec![v.normalize()])
                    };
                    let qb = self.place(&c, rng)?;
                    Measurement::Distance {
                        qa,
                        qb,
                        distance: d,
                    }
                }
                Setup::Pivot => {
                    let target = centre + ev;
                    let c = move |p: &Vector3<f64>| {
                        let v = p - target;
                        (
                            vec![v[0], v[1], v[2]],
                            vec![Vector3::x(), Vector3::y(), Vector3::z()],
                        )
                    };
                    Measurement::Pivot {
                        q: self.place(&c, rng)?,
                        point: g,
                    }
                }
                Setup::Plane => {
                    let c =
                        move |p: &Vector3<f64>| (vec![normal.dot(&(p - centre)) - e], vec![normal]);
                    Measurement::Plane {
                        q: self.place(&c, rng)?,
                        plane: g,
                    }
                }
                _ => {
                    let c = move |p: &Vector3<f64>| {
                        let v = p - centre;
                        (vec![v.norm() - (r + e)], vec![v.normalize()])
                    };
                    Measurement::Sphere {
                        q: self.place(&c, rng)?,
                        sphere: g,
                        radius: r,
                    }
                }
            };
            out.push(m);
        }
        Ok(())
    }

    /// A joint vector within the limits whose true tool point satisfies `c` (to 1e-12 m), by
    /// minimum-norm Newton steps from random starts (finite-difference tool Jacobian).
    fn place(&self, c: Constraint<'_>, rng: &mut Rng) -> Result<Vec<f64>, CalibrationError> {
        let robot = self.model.nominal_robot();
        for _ in 0..200 {
            let mut q = random_q(&self.ranges, rng);
            for _ in 0..60 {
                let p = self.point(&q)?;
                let (val, grad) = c(&p);
                if val.iter().all(|v| v.abs() < 1e-12) {
                    if robot.within_limits(&q, 0.0) {
                        return Ok(q);
                    }
                    break;
                }
                // J = dc/dq = grad^T dp/dq, rows x n.
                let n = q.len();
                let mut jq = nalgebra::DMatrix::zeros(3, n);
                for k in 0..n {
                    let mut qk = q.clone();
                    let h = 1e-7;
                    qk[k] += h;
                    let dp = (self.point(&qk)? - p) / h;
                    jq.set_column(k, &dp);
                }
                let j = nalgebra::DMatrix::from_fn(val.len(), n, |r, k| {
                    grad[r].dot(&jq.column(k).fixed_rows::<3>(0))
                });
                let b = nalgebra::DVector::from_iterator(val.len(), val.iter().map(|v| -v));
                let Ok(dq) = j.clone().svd(true, true).solve(&b, 1e-10) else {
                    break;
                };
                let scale = (0.5 / dq.amax().max(1e-300)).min(1.0);
                for k in 0..n {
                    q[k] += dq[k] * scale;
                }
            }
        }
        Err(CalibrationError::InvalidOption(
            "could not place the simulated tool where the setup needs it (200 random starts): \
             the distance, radius or scene is out of the arm's reach"
                .into(),
        ))
    }
}

/// `count` noise-free measurements of the nominal arm (no deviations) in `scene`: the example
/// rows of a measurement-file template.
pub fn nominal_examples(
    model: &ParameterModel,
    scene: &SetupScene,
    count: usize,
    seed: u64,
) -> Result<Vec<Measurement>, CalibrationError> {
    let opts = SimulationOptions {
        poses: count,
        validation_poses: 0,
        tolerance_mm: 0.0,
        tolerance_deg: 0.0,
        noise_mm: 0.0,
        noise_mrad: 0.0,
        position_only: false,
        seed,
    };
    Ok(simulate_setup(model, scene, &opts)?.measurements)
}
