//! `armlab calibrate`: kinematic calibration (Sect. 2.11) from a measurement file, or on
//! simulated data, with a readable report or JSON.

//!
//! The command parses its flags into a [`calibration::Experiment`], runs it in the library and
//! prints the [`Report`]; it writes the files the flags ask for.

use super::{CliError, Format};
use crate::calibration::{
    self, CalibrationError, CalibrationOptions, Criterion, Experiment, ExperimentError,
    JointColumns, ModelOptions, NamedText, ParameterModel, Report, Selection, Setup, Simulation,
    Source, Unidentifiable, measurement_template, with_calibrated_origins, write_corrections,
    write_measurements,
};
use std::io::Write;
use std::path::{Path, PathBuf};

/// How `--simulate` picks its poses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Default)]
pub enum Select {
    /// Uniformly random joint vectors.
    #[default]
    Random,
    /// The poses maximising O1 among 10x as many random candidates.
    O1,
    /// The poses maximising O4 among 10x as many random candidates.
    O4,
}

/// `--hayati`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Default)]
pub enum Hayati {
    /// Plain DH parameters (the lesson: d of parallel axes is ill-defined).
    Off,
    /// Hayati's beta for parallel consecutive axes (the default).
    #[default]
    Auto,
}

/// `--setup`: how the measurements were taken.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum SetupArg {
    /// Full tool poses in the robot's world frame.
    Pose,
    /// Tool points in the robot's world frame.
    Position,
    /// Tool points in a tracker's frame of unknown pose (estimated).
    Tracker,
    /// Pairs of joint vectors a known distance apart: `qa.., qb.., distance_m`.
    Distance,
    /// The tool held on fixed unknown points: `q..` in groups `# point K`.
    Pivot,
    /// A probe touching planes of unknown pose: `q..` (groups `# plane K`).
    Plane,
    /// A probe touching spheres of known radius: `q..` (groups `# sphere K`).
    Sphere,
}

impl SetupArg {
    fn setup(self) -> Setup {
        match self {
            SetupArg::Pose => Setup::Pose,
            SetupArg::Position => Setup::Position,
            SetupArg::Tracker => Setup::Tracker,
            SetupArg::Distance => Setup::Distance,
            SetupArg::Pivot => Setup::Pivot,
            SetupArg::Plane => Setup::Plane,
            SetupArg::Sphere => Setup::Sphere,
        }
    }
}

/// `--unidentifiable`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Default)]
pub enum UnidentifiableArg {
    /// Keep one parameter of each unidentifiable combination at its nominal value.
    #[default]
    Nominal,
    /// Estimate them all by minimum-norm steps (they may drift to absurd values).
    MinimumNorm,
}

/// Arguments of `armlab calibrate`.
#[derive(Debug, clap::Args)]
pub struct CalibrateArgs {
    /// Built-in name or path to a .toml model (a serial DH chain).
    pub model: String,
    /// End-effector, by name (any link of a URDF) or 0-based index (default: the tool of the longest arm). On a
    /// robot with several, the command works on the chain from the root to it alone.
    #[arg(long)]
    pub ee: Option<String>,
    /// Measurement file, plain (SI units, see `--setup`) or a headered CSV (joint names and
    /// units in the header).
    #[arg(
        long,
        required_unless_present_any = ["simulate", "template"],
        conflicts_with = "simulate"
    )]
    pub measurements: Option<PathBuf>,
    /// How the measurements were taken (default: full poses or positions, as the file says).
    #[arg(long, value_enum)]
    pub setup: Option<SetupArg>,
    /// Write an annotated template of a measurement file for the setup (headered CSV, degrees
    /// and millimetres, example rows from the nominal model) and exit.
    #[arg(long, conflicts_with_all = ["measurements", "simulate"])]
    pub template: Option<PathBuf>,
    /// The sphere setup's contact radius: the sphere's radius plus the probe ball's (mm).
    #[arg(long)]
    pub sphere_radius_mm: Option<f64>,
    /// The simulated distance setup's artefact length (mm).
    #[arg(long, default_value_t = 300.0)]
    pub distance_mm: f64,
    /// Simulated pivot points, planes or spheres.
    #[arg(long, default_value_t = 3, value_parser = super::count)]
    pub groups: usize,
    /// What happens to parameters the measurements cannot identify.
    #[arg(long, value_enum, default_value_t)]
    pub unidentifiable: UnidentifiableArg,
    /// Held-out measurements, same format: errors before and after on poses not fitted.
    #[arg(long)]
    pub validate: Option<PathBuf>,
    /// Parameters to keep at their nominal values, e.g. "d1,theta6".
    #[arg(long)]
    pub fix: Option<String>,
    /// Also estimate the base transform (6 parameters).
    #[arg(long)]
    pub with_base: bool,
    /// Also estimate the tool transform (6 parameters).
    #[arg(long)]
    pub with_tool: bool,
    /// Also estimate one compliance per revolute joint (rad per N m), with gravity's torque from
    /// the links' masses (a URDF's inertials, or `mass` and `com` in the model file).
    #[arg(long)]
    pub with_compliance: bool,
    /// Hayati's parameter for parallel consecutive axes (auto: on every such pair).
    #[arg(long, value_enum, default_value_t)]
    pub hayati: Hayati,
    /// Write the calibrated robot: a TOML model file, or URDF when the name ends in `.urdf`.
    #[arg(long)]
    pub write_model: Option<PathBuf>,
    /// Write the calibrated robot as URDF (joint origins updated; FK equal to the TOML's).
    #[arg(long)]
    pub write_urdf: Option<PathBuf>,
    /// Desired tool poses (per line 16 numbers of the 4x4 world_from_tool, or a headered CSV
    /// with x, y, z and a quaternion, roll-pitch-yaw or rotation vector): for each pose and
    /// each posture of the nominal closed form, the joint vector that puts the calibrated arm's
    /// tool there, and the pose to send a controller that runs the nominal model.
    #[arg(long)]
    pub correct_targets: Option<PathBuf>,
    /// Where `--correct-targets` writes its table (CSV; default: the report only).
    #[arg(long, requires = "correct_targets")]
    pub out: Option<PathBuf>,
    /// Calibrate a simulated robot (the model plus seeded deviations) instead.
    #[arg(long)]
    pub simulate: bool,
    /// Simulated poses for the fit (as many again are held out).
    #[arg(long, default_value_t = 50, value_parser = super::count)]
    pub poses: usize,
    /// How the simulated poses are chosen.
    #[arg(long, value_enum, default_value_t)]
    pub select: Select,
    /// Simulated length deviations, uniform within +- this (mm).
    #[arg(long, default_value_t = 1.0)]
    pub tolerance_mm: f64,
    /// Simulated angle deviations, uniform within +- this (degrees).
    #[arg(long, default_value_t = 0.5)]
    pub tolerance_deg: f64,
    /// Position noise of the measurements (mm, one sigma); also the weight of position rows.
    #[arg(long, default_value_t = 0.05)]
    pub noise_mm: f64,
    /// Orientation noise (mrad, one sigma); also the weight of orientation rows.
    #[arg(long, default_value_t = 0.1)]
    pub noise_mrad: f64,
    /// Simulate position-only measurements.
    #[arg(long)]
    pub position_only: bool,
    /// Seed of the simulation.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Write the simulated measurements to this file.
    #[arg(long)]
    pub write_measurements: Option<PathBuf>,
    /// Draw the accuracy map (position deviation over the top view of the workspace) to this
    /// file (PNG, SVG or PDF by its extension): calibrated vs real when simulated (and nominal
    /// vs real to FILE-before.png, same extension), else the correction, calibrated vs nominal.
    #[arg(long)]
    pub accuracy_map: Option<PathBuf>,
    /// Cells of the accuracy map, "WxH" (16 to 8192 each).
    #[arg(long, default_value = "256x256")]
    pub map_cells: super::figures::Size,
    /// Joint vectors sampled for the accuracy map.
    #[arg(long, default_value_t = 1_000_000, value_parser = super::count)]
    pub map_samples: usize,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    pub format: Format,
}

/// The text of a file named on the command line, named by its path.
fn read_text(path: &Path) -> Result<NamedText, CliError> {
    let name = path.display().to_string();
    match crate::input::read_data_text(path) {
        Ok(text) => Ok(NamedText { name, text }),
        Err(e) => Err(CliError::BadTarget {
            source_name: name,
            reason: e.to_string(),
        }),
    }
}

fn calibration_error(e: CalibrationError) -> CliError {
    CliError::BadTarget {
        source_name: "calibrate".into(),
        reason: e.to_string(),
    }
}

fn experiment_error(e: ExperimentError) -> CliError {
    match e {
        ExperimentError::File(e) => CliError::BadTarget {
            source_name: e.source_name,
            reason: format!("line {}: {}", e.line, e.problem),
        },
        ExperimentError::Calibration(e) => calibration_error(e),
    }
}

/// The setup of a run: `--setup`, or full poses / positions as the file says.
fn setup_of(args: &CalibrateArgs) -> Setup {
    args.setup.map_or(Setup::Pose, SetupArg::setup)
}

/// The arm the command calibrates (the model, or the chain to `--ee`).
fn arm(args: &CalibrateArgs) -> Result<crate::kinematics::Robot, CliError> {
    Ok(super::arm_robot(super::load_model(&args.model)?, args.ee.as_deref())?.0)
}

/// What the model estimates: `--with-base`, `--with-tool`, `--with-compliance`, `--hayati`,
/// `--fix`.
fn model_options(args: &CalibrateArgs) -> ModelOptions {
    ModelOptions {
        hayati: args.hayati == Hayati::Auto,
        with_base: args.with_base,
        with_tool: args.with_tool,
        with_compliance: args.with_compliance,
        fix: args.fix.as_deref().map_or(Vec::new(), |list| {
            list.split(',')
                .map(str::trim)
                .filter(|s| !s.is_empty())
                .map(String::from)
                .collect()
        }),
    }
}

/// The experiment the flags describe, its files read; `fit` replaces the text of
/// `--measurements` (Python's arrays).
pub fn experiment(args: &CalibrateArgs, fit: Option<NamedText>) -> Result<Experiment, CliError> {
    let robot = arm(args)?;
    let radius = args.sphere_radius_mm.map(|r| r * 1e-3);
    if radius.is_some_and(|r| !(r > 0.0 && r.is_finite())) {
        return Err(CliError::Usage("--sphere-radius-mm must be positive"));
    }
    let source = if args.simulate {
        if args.poses == 0 || args.poses > 100_000 {
            return Err(CliError::Usage("--poses must be between 1 and 100000"));
        }
        Source::Simulated(Simulation {
            poses: args.poses,
            validation_poses: args.poses,
            selection: match args.select {
                Select::Random => Selection::Random,
                Select::O1 => Selection::Best(Criterion::O1),
                Select::O4 => Selection::Best(Criterion::O4),
            },
            tolerance_mm: args.tolerance_mm,
            tolerance_deg: args.tolerance_deg,
            noise_mm: args.noise_mm,
            noise_mrad: args.noise_mrad,
            position_only: args.position_only,
            seed: args.seed,
            groups: args.groups,
            distance: args.distance_mm * 1e-3,
            radius: radius.unwrap_or(0.025),
            // The real arm bends when the model estimates how.
            bend: args.with_compliance,
        })
    } else {
        let fit = match fit {
            Some(f) => f,
            None => read_text(
                args.measurements
                    .as_ref()
                    .ok_or(CliError::Usage("give --measurements FILE, or --simulate"))?,
            )?,
        };
        let validation = args.validate.as_deref().map(read_text).transpose()?;
        Source::Measured {
            fit,
            validation,
            radius,
        }
    };
    let mut options = CalibrationOptions::default().with_noise(args.noise_mm, args.noise_mrad);
    if args.unidentifiable == UnidentifiableArg::MinimumNorm {
        options.unidentifiable = Unidentifiable::MinimumNorm;
    }
    Ok(Experiment {
        robot,
        setup: setup_of(args),
        model: model_options(args),
        source,
        options,
        targets: args.correct_targets.as_deref().map(read_text).transpose()?,
    })
}

/// Runs the experiment the flags describe (the library's [`calibration::run`]) and writes the
/// files they ask for (measurements, models, corrections, accuracy maps); `fit` as in
/// [`experiment`].
pub fn compute(args: &CalibrateArgs, fit: Option<NamedText>) -> Result<Report, CliError> {
    let e = experiment(args, fit)?;
    let report = calibration::run(&e).map_err(experiment_error)?;
    if let (true, Some(path)) = (args.simulate, &args.write_measurements) {
        std::fs::write(path, write_measurements(&report.measurements))?;
    }
    write_models(
        args,
        &report.calibrated,
        report.chain.as_ref().map(|c| (c, &report.nominal_robot)),
    )?;
    if let (Some(c), Some(out_path)) = (&report.corrections, &args.out) {
        let joints = JointColumns::of(&report.nominal_robot);
        std::fs::write(out_path, write_corrections(&c.rows, &joints))?;
    }
    if let Some(path) = &args.accuracy_map {
        accuracy_figures(
            args,
            &report.model,
            &report.calibration.estimate,
            report.truth.as_deref(),
            path,
        )?;
    }
    Ok(report)
}

/// `armlab calibrate`: the report as text or JSON.
pub(super) fn run(args: &CalibrateArgs, out: &mut dyn Write) -> Result<(), CliError> {
    if let Some(path) = &args.template {
        return write_template(args, path, out);
    }
    let report = compute(args, None)?;
    match args.format {
        Format::Json => {
            serde_json::to_writer_pretty(&mut *out, &report).map_err(std::io::Error::from)?;
            writeln!(out)?;
        }
        Format::Text => write!(out, "{report}")?,
    }
    Ok(())
}

/// `--template FILE`: an annotated measurement file for the setup, with example rows from the
/// nominal model (simulated without deviations or noise).
fn write_template(args: &CalibrateArgs, path: &Path, out: &mut dyn Write) -> Result<(), CliError> {
    let setup = setup_of(args);
    let (text, rows) = measurement_template(
        &arm(args)?,
        &model_options(args),
        setup,
        args.distance_mm * 1e-3,
        args.sphere_radius_mm.map_or(0.025, |r| r * 1e-3),
        args.seed,
    )
    .map_err(calibration_error)?;
    std::fs::write(path, text)?;
    writeln!(
        out,
        "wrote {} (setup {}: {rows} example rows from the nominal model; replace them with yours)",
        path.display(),
        setup.name(),
    )?;
    Ok(())
}

/// `--write-model` (TOML, or URDF by the extension) and `--write-urdf`; `chain` is the original
/// chain and its nominal DH form when the calibration ran on a derived table (the URDF then
/// keeps the chain's joints, their origins updated).
fn write_models(
    args: &CalibrateArgs,
    calibrated: &crate::kinematics::Robot,
    chain: Option<(&crate::kinematics::Robot, &crate::kinematics::Robot)>,
) -> Result<(), CliError> {
    let urdf = |path: &Path| -> Result<(), CliError> {
        let carried = chain
            .map(|(original, nominal)| with_calibrated_origins(original, nominal, calibrated))
            .transpose()
            .map_err(calibration_error)?;
        let robot = carried.as_ref().unwrap_or(calibrated);
        let text = crate::urdf::to_urdf(robot).map_err(|e| CliError::BadTarget {
            source_name: path.display().to_string(),
            reason: e.to_string(),
        })?;
        std::fs::write(path, text)?;
        Ok(())
    };
    if let Some(path) = &args.write_model {
        if path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("urdf"))
        {
            urdf(path)?;
        } else {
            let text = crate::model_file::to_toml(calibrated).ok_or(CliError::Usage(
                "the calibrated robot cannot be written as a DH model file",
            ))?;
            std::fs::write(path, text)?;
        }
    }
    if let Some(path) = &args.write_urdf {
        urdf(path)?;
    }
    Ok(())
}

/// The accuracy map(s) of `--accuracy-map`.
fn accuracy_figures(
    args: &CalibrateArgs,
    model: &ParameterModel,
    estimate: &[f64],
    truth: Option<&[f64]>,
    path: &Path,
) -> Result<(), CliError> {
    let cells = [args.map_cells.0[0] as usize, args.map_cells.0[1] as usize];
    let nominal = model.nominal();
    let name = &model.nominal_robot().name;
    let mut maps = Vec::new();
    match truth {
        Some(t) => {
            maps.push((
                path.to_path_buf(),
                estimate,
                t,
                format!("Accuracy of the calibrated {name}"),
            ));
            let stem = path
                .file_stem()
                .and_then(|s| s.to_str())
                .unwrap_or("accuracy");
            let ext = path.extension().and_then(|s| s.to_str()).unwrap_or("png");
            let before = path.with_file_name(format!("{stem}-before.{ext}"));
            maps.push((
                before,
                &nominal[..],
                t,
                format!("Accuracy of the nominal {name}"),
            ));
        }
        None => maps.push((
            path.to_path_buf(),
            estimate,
            &nominal[..],
            format!("Correction of the {name} by the calibration"),
        )),
    }
    for (file, a, b, title) in maps {
        let mut figures = crate::headless::figures_for(&file)?;
        if args.map_samples == 0 || args.map_samples > 100_000_000 {
            return Err(CliError::Usage(
                "--map-samples must be between 1 and 100000000",
            ));
        }
        let map = crate::calibration::accuracy_map(model, a, b, cells, args.map_samples, args.seed)
            .map_err(calibration_error)?;
        let img = crate::figure::accuracy::accuracy_figure(
            &mut figures,
            &map,
            &title,
            [1200, 1000],
            crate::figure::Theme::Light,
        )?;
        crate::headless::write_figure(&mut figures, &img, &file)?;
    }
    Ok(())
}
