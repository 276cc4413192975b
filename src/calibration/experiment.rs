//! One calibration experiment end to end: the setup and its scene, the data (measurement files'
//! text, or a simulated "real" arm), the options, the calibration with its identifiability at
//! the nominal point and at the estimate, the held-out check and the target correction. The
//! command line, the app's Calibration tab and Python describe an [`Experiment`], call [`run`]
//! once and print the [`Report`] it returns.

use super::{
    CalibrationError, CalibrationOptions, Criterion, JointColumns, Measurement,
    MeasurementFileError, ParameterModel, Report, Setup, SetupScene, SimulationOptions,
    TargetCorrection, calibrate, correct_targets, dh_form, fit, nominal_examples, parse_setup,
    parse_targets, register_tracker, select_poses, simulate_setup, template,
};
use crate::kinematics::pose::Pose;
use crate::kinematics::{Convention, Robot};
use nalgebra::{Rotation3, Translation3, Vector3};
use thiserror::Error;

/// Why an experiment could not run: a bad file (measurements or desired poses), or a
/// calibration that could not start (a calibration that does not converge is a report).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ExperimentError {
    /// A measurement or target file that cannot be read as its setup says.
    #[error(transparent)]
    File(#[from] MeasurementFileError),
    /// The model, the options or the data refused by the calibration.
    #[error(transparent)]
    Calibration(#[from] CalibrationError),
}

/// What the parameter model estimates besides the DH rows, and how it treats parallel axes.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelOptions {
    /// Hayati's beta instead of d on parallel consecutive axes (standard DH tables only; a
    /// modified table keeps plain DH).
    pub hayati: bool,
    /// Also estimate the base transform (6 parameters).
    pub with_base: bool,
    /// Also estimate the tool transform (6 parameters).
    pub with_tool: bool,
    /// Also estimate one compliance per revolute joint (rad per N m).
    pub with_compliance: bool,
    /// Parameters kept at their nominal values, by name ("d1", "theta6").
    pub fix: Vec<String>,
}

impl Default for ModelOptions {
    /// Hayati's beta on, nothing else estimated, nothing fixed.
    fn default() -> Self {
        Self {
            hayati: true,
            with_base: false,
            with_tool: false,
            with_compliance: false,
            fix: Vec::new(),
        }
    }
}

impl ModelOptions {
    /// The calibration model of `robot` with these options.
    pub fn model(&self, robot: &Robot) -> Result<ParameterModel, CalibrationError> {
        self.build(robot, false, self.with_compliance)
    }

    /// The model with `compliance` or not; with `tracker`, the base estimated last (so that a
    /// tracker's six parameters follow the others).
    fn build(
        &self,
        robot: &Robot,
        tracker: bool,
        compliance: bool,
    ) -> Result<ParameterModel, CalibrationError> {
        let mut model = ParameterModel::new(robot)?;
        if self.with_base && !tracker {
            model = model.with_base();
        }
        if self.with_tool {
            model = model.with_tool();
        }
        if self.hayati && model.convention() == Convention::Standard {
            model = model.with_hayati()?;
        }
        if compliance {
            model = model.with_compliance()?;
        }
        if tracker {
            model = model.with_base();
        }
        let names: Vec<&str> = self.fix.iter().map(String::as_str).collect();
        model.fix(&names)?;
        Ok(model)
    }
}

/// How simulated poses are chosen (pose and position setups; the others place random joint
/// vectors where the setup needs the tool).
#[derive(Debug, Clone, PartialEq)]
pub enum Selection {
    /// Uniformly random joint vectors within the limits.
    Random,
    /// The poses maximising the criterion among 10x as many random candidates.
    Best(Criterion),
    /// All within 0.02 rad (or m) of this joint vector (the lesson "converged is not
    /// accurate").
    Alike(Vec<f64>),
}

/// A simulated experiment: a "real" arm (the nominal plus seeded deviations) and its
/// measurements with seeded noise; units as named.
#[derive(Debug, Clone, PartialEq)]
pub struct Simulation {
    /// Measurements for the fit.
    pub poses: usize,
    /// Held-out measurements.
    pub validation_poses: usize,
    /// How the poses are chosen.
    pub selection: Selection,
    /// Length deviations of the real arm, uniform within +- this (mm).
    pub tolerance_mm: f64,
    /// Angle deviations, uniform within +- this (degrees).
    pub tolerance_deg: f64,
    /// Position noise (mm, one sigma).
    pub noise_mm: f64,
    /// Orientation noise (mrad, one sigma).
    pub noise_mrad: f64,
    /// Measure positions only (the pose setup becomes the position setup).
    pub position_only: bool,
    /// Seed: the same seed gives the same arm and data.
    pub seed: u64,
    /// Pivot points, planes or spheres of the scene.
    pub groups: usize,
    /// The distance setup's artefact length (m).
    pub distance: f64,
    /// The sphere setup's contact radius, sphere plus probe ball (m).
    pub radius: f64,
    /// The real arm's joints bend under gravity (a compliance each, up to
    /// [`super::SIMULATED_COMPLIANCE`]), whether the model estimates compliances or not.
    pub bend: bool,
}

impl Default for Simulation {
    /// `armlab calibrate --simulate`'s defaults: 50 random poses and 50 held out, 1 mm and 0.5
    /// degree tolerances, 0.05 mm and 0.1 mrad noise, full poses, seed 1; three groups, a
    /// 300 mm artefact, a 25 mm contact radius; a rigid arm.
    fn default() -> Self {
        Self {
            poses: 50,
            validation_poses: 50,
            selection: Selection::Random,
            tolerance_mm: 1.0,
            tolerance_deg: 0.5,
            noise_mm: 0.05,
            noise_mrad: 0.1,
            position_only: false,
            seed: 1,
            groups: 3,
            distance: 0.3,
            radius: 0.025,
            bend: false,
        }
    }
}

/// The text of a measurement (or desired-pose) file and the name its errors and warnings give
/// it (a path, or "-").
#[derive(Debug, Clone, PartialEq)]
pub struct NamedText {
    /// The name (a path).
    pub name: String,
    /// The file's text.
    pub text: String,
}

/// Where the measurements come from.
#[derive(Debug, Clone, PartialEq)]
pub enum Source {
    /// Measurement files, read as the experiment's setup says (plain or headered CSV, YAML).
    Measured {
        /// The measurements fitted.
        fit: NamedText,
        /// Held-out measurements, same format.
        validation: Option<NamedText>,
        /// The sphere setup's contact radius when the file does not give it (m).
        radius: Option<f64>,
    },
    /// A simulated arm and its measurements.
    Simulated(Simulation),
}

/// One calibration experiment.
#[derive(Debug, Clone, PartialEq)]
pub struct Experiment {
    /// The nominal arm: a serial chain, a DH table or not (a chain that is not one is
    /// calibrated through its derived standard DH table, with a warning).
    pub robot: Robot,
    /// How the measurements are taken.
    pub setup: Setup,
    /// What the model estimates.
    pub model: ModelOptions,
    /// The data.
    pub source: Source,
    /// The least squares' options (the noise weights included).
    pub options: CalibrationOptions,
    /// Desired tool poses (a file's text, see [`parse_targets`]) to correct on the calibrated
    /// arm in every posture of the nominal closed form.
    pub targets: Option<NamedText>,
}

/// The target correction of a report: the file, its number of desired poses, the rows.
#[derive(Debug, Clone, PartialEq)]
pub struct Corrections {
    /// The desired poses' file.
    pub name: String,
    /// Desired poses in it.
    pub poses: usize,
    /// One row per pose and posture.
    pub rows: Vec<TargetCorrection>,
}

/// The robot to calibrate: `original` itself, or, for a chain that is not a DH table (a URDF
/// arm), its derived standard DH table (true).
pub fn dh_robot(original: &Robot) -> Result<(Robot, bool), CalibrationError> {
    match ParameterModel::new(original) {
        Err(CalibrationError::NotSerialDh(_)) => Ok((dh_form(original)?, true)),
        _ => Ok((original.clone(), false)),
    }
}

/// An annotated measurement-file template for `setup` on `robot` (the text, and its number of
/// example rows, four measurements from the nominal model; two groups, the artefact length
/// `distance` and contact radius `radius` in m, the tracker at the world origin).
pub fn measurement_template(
    robot: &Robot,
    model: &ModelOptions,
    setup: Setup,
    distance: f64,
    radius: f64,
    seed: u64,
) -> Result<(String, usize), CalibrationError> {
    let (robot, _) = dh_robot(robot)?;
    let model = model.model(&robot)?;
    let scene = SetupScene {
        setup,
        groups: 2,
        distance,
        radius,
        world_from_tracker: Pose::identity(),
    };
    let examples = nominal_examples(&model, &scene, 4, seed)?;
    let joints = JointColumns::of(model.nominal_robot());
    Ok((template(&joints, setup, &examples), examples.len()))
}

/// The data of a run.
struct Data {
    ms: Vec<Measurement>,
    validation: Option<Vec<Measurement>>,
    truth: Option<Vec<f64>>,
    warnings: Vec<String>,
}

/// Runs the experiment: builds the model, reads or simulates the data, registers a tracker,
/// calibrates ([`calibrate`]: identifiability at the nominal point and at the estimate),
/// checks the held-out data and corrects the desired poses. One computation; the report prints
/// as text (`Display`) and serialises to `armlab calibrate --format json`'s keys.
///
/// ```
/// use armlab::calibration::{Experiment, Simulation, Source, run};
/// let e = Experiment {
///     source: Source::Simulated(Simulation { poses: 30, seed: 5, ..Simulation::default() }),
///     ..Experiment::new(armlab::kinematics::models::built_in("puma560").unwrap())
/// };
/// let report = run(&e).unwrap();
/// assert!(report.calibration.converged);
/// assert_eq!(report.calibration.at_estimate.rank, 24); // beta2 instead of d2: all identified
/// assert!(report.to_string().contains("identifiability at the estimate"));
/// ```
pub fn run(e: &Experiment) -> Result<Report, ExperimentError> {
    let (robot, derived) = dh_robot(&e.robot)?;
    let base_model = e.model.build(&robot, false, e.model.with_compliance)?;
    let mut data = match &e.source {
        Source::Measured {
            fit,
            validation,
            radius,
        } => measured(e.setup, &robot, fit, validation.as_ref(), *radius)?,
        Source::Simulated(sim) => simulated(e, sim, &robot, &base_model)?,
    };
    if derived {
        data.warnings.push(format!(
            "{} is not a DH table: calibrated through its derived standard DH table (same FK); \
             the calibrated model written as URDF carries the result into its joint origins",
            e.robot.name
        ));
    }
    let (model, tracker) = if e.setup == Setup::Tracker {
        let registered = register_tracker(&base_model, &base_model.nominal(), &data.ms)?;
        let mut moved = robot.clone();
        moved.base = registered * robot.base;
        if let Some(t) = &mut data.truth {
            // The true base correction: Trans(t) Rot(r) registered = tracker_from_world (true).
            let truth = SetupScene::default().world_from_tracker.inverse() * registered.inverse();
            t.extend(truth.translation.vector.iter());
            t.extend(truth.rotation.scaled_axis().iter());
        }
        (e.model.build(&moved, true, e.model.with_compliance)?, true)
    } else {
        (base_model, false)
    };
    let calibration = calibrate(&model, &data.ms, &e.options)?;
    let validation = match &data.validation {
        Some(v) => Some((
            fit(&model, &model.nominal(), v)?,
            fit(&model, &calibration.estimate, v)?,
        )),
        None => None,
    };
    let mut calibrated = model.robot_with(&calibration.estimate)?;
    let tracker_from_base = tracker.then_some(calibrated.base);
    if tracker {
        // The tracker's pose is the cell's, not the robot's: the calibrated robot keeps its base.
        calibrated.base = robot.base;
    }
    let corrections = match &e.targets {
        Some(t) => {
            let poses = parse_targets(&t.text, &t.name)?;
            Some(Corrections {
                name: t.name.clone(),
                poses: poses.len(),
                rows: correct_targets(&robot, &calibrated, &poses)?,
            })
        }
        None => None,
    };
    Ok(Report {
        setup: reported_setup(e.setup, &data.ms),
        warnings: data.warnings,
        measurements: data.ms,
        model,
        calibration,
        validation,
        truth: data.truth,
        chain: derived.then(|| e.robot.clone()),
        nominal_robot: robot,
        calibrated,
        tracker_from_base,
        corrections,
    })
}

impl Experiment {
    /// `robot` calibrated from the default simulation (see [`Simulation::default`]) with full
    /// poses, the default model options and least squares weighted by the simulation's noise.
    pub fn new(robot: Robot) -> Self {
        Self {
            robot,
            setup: Setup::Pose,
            model: ModelOptions::default(),
            source: Source::Simulated(Simulation::default()),
            options: CalibrationOptions::default().with_noise(0.05, 0.1),
            targets: None,
        }
    }
}

impl CalibrationOptions {
    /// These options with the rows weighted by the measurement noise: `noise_mm` (mm, one
    /// sigma) for positions, `noise_mrad` (mrad) for orientations, each at least 1e-9 of the SI
    /// unit (noise-free data still weigh finitely).
    #[must_use]
    pub fn with_noise(self, noise_mm: f64, noise_mrad: f64) -> Self {
        Self {
            position_sigma: (noise_mm * 1e-3).max(1e-9),
            orientation_sigma: (noise_mrad * 1e-3).max(1e-9),
            ..self
        }
    }
}

/// The setup the report names: `pose` read from a file of positions is `position`.
fn reported_setup(setup: Setup, ms: &[Measurement]) -> Setup {
    match ms.first() {
        Some(Measurement::Position { .. }) if setup == Setup::Pose => Setup::Position,
        _ => setup,
    }
}

/// The data of measurement files; the files' warnings prefixed with their names.
fn measured(
    setup: Setup,
    robot: &Robot,
    fit: &NamedText,
    validation: Option<&NamedText>,
    radius: Option<f64>,
) -> Result<Data, ExperimentError> {
    let joints = JointColumns::of(robot);
    let parsed = parse_setup(&fit.text, &fit.name, &joints, setup, radius)?;
    let mut warnings: Vec<String> = parsed
        .warnings
        .iter()
        .map(|w| format!("{}: {w}", fit.name))
        .collect();
    let validation = match validation {
        Some(v) => {
            let file = parse_setup(&v.text, &v.name, &joints, setup, radius)?;
            warnings.extend(file.warnings.iter().map(|w| format!("{}: {w}", v.name)));
            Some(file.measurements)
        }
        None => None,
    };
    Ok(Data {
        ms: parsed.measurements,
        validation,
        truth: None,
        warnings,
    })
}

/// The data of a simulation: a "real" arm (bending under gravity or not), its measurements
/// (chosen as the selection says) and held-out ones; the truth in the model's zeta (the real
/// arm's compliances, last in zeta, cut off or padded with zeros when the model differs).
fn simulated(
    e: &Experiment,
    sim: &Simulation,
    robot: &Robot,
    model: &ParameterModel,
) -> Result<Data, CalibrationError> {
    let pose_like = matches!(e.setup, Setup::Pose | Setup::Position);
    let selection = if pose_like {
        &sim.selection
    } else {
        &Selection::Random
    };
    let real = if sim.bend == e.model.with_compliance || !pose_like {
        model.clone()
    } else {
        e.model.build(robot, false, sim.bend)?
    };
    let opts = SimulationOptions {
        poses: match selection {
            Selection::Best(_) => 10 * sim.poses,
            _ => sim.poses,
        },
        validation_poses: sim.validation_poses,
        tolerance_mm: sim.tolerance_mm,
        tolerance_deg: sim.tolerance_deg,
        noise_mm: sim.noise_mm,
        noise_mrad: sim.noise_mrad,
        position_only: sim.position_only || e.setup == Setup::Position,
        seed: sim.seed,
    };
    let scene = SetupScene {
        setup: if sim.position_only && e.setup == Setup::Pose {
            Setup::Position
        } else {
            e.setup
        },
        groups: sim.groups,
        distance: sim.distance,
        radius: sim.radius,
        ..SetupScene::default()
    };
    let out = simulate_setup(&real, &scene, &opts)?;
    let ms = match selection {
        Selection::Random => out.measurements,
        Selection::Alike(q0) => alike(&real, &out.truth, q0, sim)?,
        Selection::Best(c) => select_poses(model, &out.measurements, sim.poses, *c, &e.options)?
            .into_iter()
            .map(|i| out.measurements[i].clone())
            .collect(),
    };
    let mut truth = out.truth;
    truth.resize(model.parameters().len(), 0.0);
    Ok(Data {
        ms,
        validation: Some(out.validation),
        truth: Some(truth),
        warnings: Vec::new(),
    })
}

/// `sim.poses` poses within 0.02 rad (or m) of `q0`, measured on the true parameters with the
/// stated noise (deterministic).
fn alike(
    real: &ParameterModel,
    truth: &[f64],
    q0: &[f64],
    sim: &Simulation,
) -> Result<Vec<Measurement>, CalibrationError> {
    (0..sim.poses)
        .map(|k| {
            let n = |i: usize| ((k * 13 + i * 5) % 17) as f64 / 8.0 - 1.0;
            let q: Vec<f64> = q0
                .iter()
                .enumerate()
                .map(|(j, v)| v + 0.01 * n(j + 6))
                .collect();
            let (_, t) = real.frames(truth, &q)?;
            let p =
                t.translation.vector + Vector3::new(n(0), n(1), n(2)) * 1.7 * sim.noise_mm * 1e-3;
            Ok(if sim.position_only {
                Measurement::Position { q, p }
            } else {
                let r =
                    Rotation3::new(Vector3::new(n(3), n(4), n(5)) * 1.7 * sim.noise_mrad * 1e-3);
                Measurement::Pose {
                    q,
                    world_from_tool: Pose::from_parts(Translation3::from(p), r * t.rotation),
                }
            })
        })
        .collect()
}
