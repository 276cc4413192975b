//! `armlab calibrate`: kinematic calibration (Sect. 2.11) from a measurement file, or on
//! simulated data, with a readable report or JSON.

use super::{CliError, Format};
use crate::calibration::{
    CalibrationOptions, CalibrationReport, Criterion, Fit, Identifiability, JointColumns,
    Measurement, ParameterModel, ParsedFile, Setup, SetupScene, SimulationOptions,
    TargetCorrection, Unidentifiable, calibrate, correct_targets, dh_form, fit, nominal_examples,
    parse_setup, parse_targets, register_tracker, select_poses, simulate_setup, template,
    with_calibrated_origins, write_corrections, write_measurements,
};
use crate::kinematics::pose::Pose;
use serde_json::{Value, json};
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
    /// End-effector, by name or 0-based index (default: the tool of the longest arm). On a
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

fn read(
    path: &Path,
    joints: &JointColumns,
    setup: Setup,
    radius: Option<f64>,
) -> Result<ParsedFile, CliError> {
    let text = crate::input::read_data_text(path).map_err(|e| CliError::BadTarget {
        source_name: path.display().to_string(),
        reason: e.to_string(),
    })?;
    parse_setup(&text, &path.display().to_string(), joints, setup, radius).map_err(|e| {
        CliError::BadTarget {
            source_name: e.source_name.clone(),
            reason: format!("line {}: {}", e.line, e.problem),
        }
    })
}

fn calibration_error(e: crate::calibration::CalibrationError) -> CliError {
    CliError::BadTarget {
        source_name: "calibrate".into(),
        reason: e.to_string(),
    }
}

/// The data of a run.
struct Data {
    /// Measurements for the fit.
    ms: Vec<Measurement>,
    /// Held-out measurements.
    validation: Option<Vec<Measurement>>,
    /// The true zeta when simulated.
    truth: Option<Vec<f64>>,
    /// Quirks of the files accepted with a warning.
    warnings: Vec<String>,
}

/// The setup of a run: `--setup`, or full poses / positions as the file says.
fn setup_of(args: &CalibrateArgs) -> Setup {
    args.setup.map_or(Setup::Pose, SetupArg::setup)
}

fn data(
    args: &CalibrateArgs,
    model: &ParameterModel,
    opts: &CalibrationOptions,
) -> Result<Data, CliError> {
    let setup = setup_of(args);
    let radius = args.sphere_radius_mm.map(|r| r * 1e-3);
    if radius.is_some_and(|r| !(r > 0.0 && r.is_finite())) {
        return Err(CliError::Usage("--sphere-radius-mm must be positive"));
    }
    if !args.simulate {
        return measured(args, model, setup, radius);
    }
    simulated(args, model, setup, radius, opts)
}

/// The data of a run from `--measurements` (and `--validate`).
fn measured(
    args: &CalibrateArgs,
    model: &ParameterModel,
    setup: Setup,
    radius: Option<f64>,
) -> Result<Data, CliError> {
    let joints = JointColumns::of(model.nominal_robot());
    {
        let path = args
            .measurements
            .as_ref()
            .ok_or(CliError::Usage("give --measurements FILE, or --simulate"))?;
        let fit = read(path, &joints, setup, radius)?;
        let mut warnings: Vec<String> = fit
            .warnings
            .iter()
            .map(|w| format!("{}: {w}", path.display()))
            .collect();
        let validation = match &args.validate {
            Some(p) => {
                let v = read(p, &joints, setup, radius)?;
                warnings.extend(v.warnings.iter().map(|w| format!("{}: {w}", p.display())));
                Some(v.measurements)
            }
            None => None,
        };
        Ok(Data {
            ms: fit.measurements,
            validation,
            truth: None,
            warnings,
        })
    }
}

/// The data of a `--simulate` run: a "real" arm, its measurements and held-out ones.
fn simulated(
    args: &CalibrateArgs,
    model: &ParameterModel,
    setup: Setup,
    radius: Option<f64>,
    opts: &CalibrationOptions,
) -> Result<Data, CliError> {
    if args.poses == 0 || args.poses > 100_000 {
        return Err(CliError::Usage("--poses must be between 1 and 100000"));
    }
    let select = if matches!(setup, Setup::Pose | Setup::Position) {
        args.select
    } else {
        Select::Random
    };
    let candidates = match select {
        Select::Random => args.poses,
        _ => 10 * args.poses,
    };
    let sim_opts = SimulationOptions {
        poses: candidates,
        validation_poses: args.poses,
        tolerance_mm: args.tolerance_mm,
        tolerance_deg: args.tolerance_deg,
        noise_mm: args.noise_mm,
        noise_mrad: args.noise_mrad,
        position_only: args.position_only || setup == Setup::Position,
        seed: args.seed,
    };
    let scene = SetupScene {
        setup: if args.position_only && setup == Setup::Pose {
            Setup::Position
        } else {
            setup
        },
        groups: args.groups,
        distance: args.distance_mm * 1e-3,
        radius: radius.unwrap_or(0.025),
        ..SetupScene::default()
    };
    let sim = simulate_setup(model, &scene, &sim_opts).map_err(calibration_error)?;
    let ms = match select {
        Select::Random => sim.measurements,
        Select::O1 | Select::O4 => {
            let c = if select == Select::O1 {
                Criterion::O1
            } else {
                Criterion::O4
            };
            let chosen = select_poses(model, &sim.measurements, args.poses, c, opts)
                .map_err(calibration_error)?;
            chosen
                .into_iter()
                .map(|i| sim.measurements[i].clone())
                .collect()
        }
    };
    if let Some(path) = &args.write_measurements {
        std::fs::write(path, write_measurements(&ms))?;
    }
    Ok(Data {
        ms,
        validation: Some(sim.validation),
        truth: Some(sim.truth),
        warnings: Vec::new(),
    })
}

/// The calibration model of `robot` with the run's options (the base estimated last, so that a
/// tracker's six parameters follow the others).
fn build_model(
    args: &CalibrateArgs,
    robot: &crate::kinematics::Robot,
    with_base: bool,
) -> Result<ParameterModel, CliError> {
    let mut model = ParameterModel::new(robot).map_err(calibration_error)?;
    if args.with_base && !with_base {
        model = model.with_base();
    }
    if args.with_tool {
        model = model.with_tool();
    }
    if args.hayati == Hayati::Auto && model.convention() == crate::kinematics::Convention::Standard
    {
        model = model.with_hayati().map_err(calibration_error)?;
    }
    if args.with_compliance {
        model = model.with_compliance().map_err(calibration_error)?;
    }
    if with_base {
        model = model.with_base();
    }
    if let Some(list) = &args.fix {
        let names: Vec<&str> = list
            .split(',')
            .map(str::trim)
            .filter(|s| !s.is_empty())
            .collect();
        model.fix(&names).map_err(calibration_error)?;
    }
    Ok(model)
}

/// The tracker setup: the model whose base starts at the registered tracker pose (its six base
/// parameters estimated), the truth extended by the true corrections when simulated, and the
/// registered `tracker_from_world`.
fn tracker_model(
    args: &CalibrateArgs,
    robot: &crate::kinematics::Robot,
    model: &ParameterModel,
    data: &mut Data,
) -> Result<(ParameterModel, Pose), CliError> {
    let registered =
        register_tracker(model, &model.nominal(), &data.ms).map_err(calibration_error)?;
    let mut moved = robot.clone();
    moved.base = registered * robot.base;
    let tracker = build_model(args, &moved, true)?;
    if let Some(t) = &mut data.truth {
        // The true base correction: Trans(t) Rot(r) registered = tracker_from_world (true).
        let truth = SetupScene::default().world_from_tracker.inverse() * registered.inverse();
        t.extend(truth.translation.vector.iter());
        t.extend(truth.rotation.scaled_axis().iter());
    }
    Ok((tracker, registered))
}

/// `armlab calibrate`.
pub(super) fn run(args: &CalibrateArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let (original, _) = super::arm_robot(super::load_model(&args.model)?, args.ee.as_deref())?;
    let (robot, derived) = dh_robot(&original)?;
    let chain = derived.then_some(&original);
    let base_model = build_model(args, &robot, false)?;
    if let Some(path) = &args.template {
        return write_template(args, &base_model, path, out);
    }
    let mut opts = CalibrationOptions {
        position_sigma: (args.noise_mm * 1e-3).max(1e-9),
        orientation_sigma: (args.noise_mrad * 1e-3).max(1e-9),
        ..CalibrationOptions::default()
    };
    if args.unidentifiable == UnidentifiableArg::MinimumNorm {
        opts.unidentifiable = Unidentifiable::MinimumNorm;
    }
    let mut data = data(args, &base_model, &opts)?;
    if chain.is_some() {
        data.warnings.push(format!(
            "{} is not a DH table: calibrated through its derived standard DH table (same FK); \
             --write-urdf / --write-model FILE.urdf carry the result into its joint origins",
            original.name
        ));
    }
    let setup = setup_of(args);
    let (model, tracker) = if setup == Setup::Tracker {
        let (m, t) = tracker_model(args, &robot, &base_model, &mut data)?;
        (m, Some(t))
    } else {
        (base_model, None)
    };
    let report = calibrate(&model, &data.ms, &opts).map_err(calibration_error)?;
    let val = data
        .validation
        .as_ref()
        .map(|v| -> Result<(Fit, Fit), CliError> {
            let before = fit(&model, &model.nominal(), v).map_err(calibration_error)?;
            let after = fit(&model, &report.estimate, v).map_err(calibration_error)?;
            Ok((before, after))
        })
        .transpose()?;
    let mut calibrated = model
        .robot_with(&report.estimate)
        .map_err(calibration_error)?;
    let tracker_from_base = tracker.map(|_| calibrated.base);
    if tracker.is_some() {
        // The tracker's pose is the cell's, not the robot's: the written model keeps its base.
        calibrated.base = robot.base;
    }
    write_models(args, &calibrated, chain.map(|c| (c, &robot)))?;
    let corrections = args
        .correct_targets
        .as_ref()
        .map(|path| corrections(args, path, &robot, &calibrated))
        .transpose()?;
    if let Some(path) = &args.accuracy_map {
        accuracy_figures(args, &model, &report.estimate, data.truth.as_deref(), path)?;
    }
    let ctx = Context {
        setup: reported_setup(setup, &data.ms),
        hayati_rows: model.hayati_rows(),
        tracker_from_base,
        warnings: &data.warnings,
        measurements: data.ms.len(),
        corrections: corrections.as_ref(),
    };
    print_report(
        args.format,
        out,
        &report,
        val.as_ref(),
        data.truth.as_deref(),
        &ctx,
    )
}

/// The robot to calibrate: `original` itself, or, for a chain that is not a DH table (a URDF
/// arm), its derived standard DH table (true).
fn dh_robot(
    original: &crate::kinematics::Robot,
) -> Result<(crate::kinematics::Robot, bool), CliError> {
    match ParameterModel::new(original) {
        Err(crate::calibration::CalibrationError::NotSerialDh(_)) => {
            Ok((dh_form(original).map_err(calibration_error)?, true))
        }
        _ => Ok((original.clone(), false)),
    }
}

/// The setup the report names: `pose` read from a file of positions is `position`.
fn reported_setup(setup: Setup, ms: &[Measurement]) -> Setup {
    match ms.first() {
        Some(Measurement::Position { .. }) if setup == Setup::Pose => Setup::Position,
        _ => setup,
    }
}

/// The report as text or JSON.
fn print_report(
    format: Format,
    out: &mut dyn Write,
    report: &CalibrationReport,
    val: Option<&(Fit, Fit)>,
    truth: Option<&[f64]>,
    ctx: &Context,
) -> Result<(), CliError> {
    match format {
        Format::Json => {
            let v = to_json(report, val, truth, ctx);
            serde_json::to_writer_pretty(&mut *out, &v).map_err(std::io::Error::from)?;
            writeln!(out)?;
        }
        Format::Text => write_text(out, report, val, truth, ctx)?,
    }
    Ok(())
}

/// What the report says besides the calibration itself.
struct Context<'a> {
    setup: Setup,
    hayati_rows: Vec<usize>,
    tracker_from_base: Option<Pose>,
    warnings: &'a [String],
    measurements: usize,
    /// `--correct-targets`: the file, the number of desired poses, the rows.
    corrections: Option<&'a (String, usize, Vec<TargetCorrection>)>,
}

/// `--correct-targets` (and `--out`): the nominal robot's postures on the calibrated one.
fn corrections(
    args: &CalibrateArgs,
    path: &Path,
    robot: &crate::kinematics::Robot,
    calibrated: &crate::kinematics::Robot,
) -> Result<(String, usize, Vec<TargetCorrection>), CliError> {
    let targets = read_targets(path)?;
    let rows = correct_targets(robot, calibrated, &targets).map_err(calibration_error)?;
    if let Some(out_path) = &args.out {
        std::fs::write(out_path, write_corrections(&rows, &JointColumns::of(robot)))?;
    }
    Ok((path.display().to_string(), targets.len(), rows))
}

/// The desired poses of `--correct-targets`.
fn read_targets(path: &Path) -> Result<Vec<Pose>, CliError> {
    let text = crate::input::read_data_text(path).map_err(|e| CliError::BadTarget {
        source_name: path.display().to_string(),
        reason: e.to_string(),
    })?;
    parse_targets(&text, &path.display().to_string()).map_err(|e| CliError::BadTarget {
        source_name: e.source_name.clone(),
        reason: format!("line {}: {}", e.line, e.problem),
    })
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

/// `--template FILE`: an annotated measurement file for the setup, with example rows from the
/// nominal model (simulated without deviations or noise).
fn write_template(
    args: &CalibrateArgs,
    model: &ParameterModel,
    path: &Path,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let setup = setup_of(args);
    let scene = SetupScene {
        setup,
        groups: 2,
        distance: args.distance_mm * 1e-3,
        radius: args.sphere_radius_mm.map_or(0.025, |r| r * 1e-3),
        world_from_tracker: Pose::identity(),
    };
    let examples = nominal_examples(model, &scene, 4, args.seed).map_err(calibration_error)?;
    let joints = JointColumns::of(model.nominal_robot());
    std::fs::write(path, template(&joints, setup, &examples))?;
    writeln!(
        out,
        "wrote {} (setup {}: {} example rows from the nominal model; replace them with yours)",
        path.display(),
        setup.name(),
        examples.len()
    )?;
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

fn fit_json(f: &Fit) -> Value {
    json!({
        "position_rms": f.position_rms,
        "position_max": f.position_max,
        "orientation_rms": f.orientation_rms,
        "orientation_max": f.orientation_max,
    })
}

/// The setup's unknowns as JSON objects: name, estimate and standard deviation.
fn unknowns_json(r: &CalibrationReport) -> Vec<Value> {
    let names = r.unknowns.names();
    r.unknowns
        .values()
        .iter()
        .zip(&names)
        .zip(&r.unknown_std)
        .map(|((v, n), s)| json!({"name": n, "estimate": v, "std": s}))
        .collect()
}

fn identifiability_json(n: &Identifiability) -> Value {
    let o = &n.observability;
    json!({
        "parameter_count": n.parameter_count,
        "rank": n.rank,
        "rank_threshold": n.rank_threshold,
        "unidentifiable": n.unidentifiable,
        "combinations": n.combinations,
        "observability": {"O1": o.o1, "O2": o.o2, "O3": o.o3, "O4": o.o4},
    })
}

fn to_json(
    r: &CalibrationReport,
    val: Option<&(Fit, Fit)>,
    truth: Option<&[f64]>,
    ctx: &Context,
) -> Value {
    let params: Vec<Value> = r
        .parameters
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let mut o = json!({
                "name": p.name,
                "joint": p.joint,
                "kind": p.kind.as_str(),
                "nominal": p.nominal,
                "estimate": r.estimate[k],
                "std": r.std[k],
                "identifiable": r.at_estimate.identifiable[k],
                "fixed": p.fixed,
            });
            if let Some((_, why)) = r.auto_fixed.iter().find(|(n, _)| *n == p.name) {
                o["fixed_because"] = json!(why);
            }
            if let Some(t) = truth {
                o["true"] = json!(t[k]);
            }
            o
        })
        .collect();
    let e = &r.at_estimate;
    let o = &e.observability;
    json!({
        "setup": ctx.setup.name(),
        "setup_cannot_see": ctx.setup.blind_spots(),
        "warnings": ctx.warnings,
        "hayati_rows": ctx.hayati_rows,
        "parameters": params,
        "unknowns": unknowns_json(r),
        "identifiability_at": "estimate",
        "parameter_count": e.parameter_count,
        "rank": e.rank,
        "rank_threshold": e.rank_threshold,
        "unidentifiable": e.unidentifiable,
        "combinations": e.combinations,
        "fixed_unidentifiable": r.auto_fixed.iter().map(|(n, why)| json!({"name": n, "because": why})).collect::<Vec<_>>(),
        "nominal_identifiability": identifiability_json(&r.nominal),
        "tracker_from_base": ctx.tracker_from_base.map(|p| json!({
            "translation": p.translation.vector.as_slice(),
            "rotation_vector": p.rotation.scaled_axis().as_slice(),
        })),
        "correlations": r.correlations.iter().map(|(a, b, c)| json!({"parameters": [a, b], "correlation": c})).collect::<Vec<_>>(),
        "iterations": r.iterations.iter().map(|i| json!({
            "position_rms": i.position_rms,
            "orientation_rms": i.orientation_rms,
            "step_norm": i.step_norm,
            "condition": i.condition,
            "rank": i.rank,
        })).collect::<Vec<_>>(),
        "converged": r.converged,
        "reason": r.reason,
        "sigma2": r.sigma2,
        "observability": {"O1": o.o1, "O2": o.o2, "O3": o.o3, "O4": o.o4},
        "fit": {"before": fit_json(&r.before), "after": fit_json(&r.after)},
        "validation": val.map(|(b, a)| json!({"before": fit_json(b), "after": fit_json(a)})),
        "target_correction": ctx.corrections.map(corrections_json),
    })
}

fn corrections_json((file, poses, rows): &(String, usize, Vec<TargetCorrection>)) -> Value {
    let worst = rows
        .iter()
        .map(|r| r.position_error.max(r.orientation_error))
        .fold(0.0, f64::max);
    json!({
        "file": file,
        "poses": poses,
        "worst_error": worst,
        "rows": rows.iter().map(|r| {
            let u = nalgebra::UnitQuaternion::from_rotation_matrix(&r.send.rotation);
            json!({
                "pose": r.pose + 1,
                "posture": r.posture.to_string(),
                "q": r.q,
                "within_limits": r.within_limits,
                "send": {
                    "translation": r.send.translation.vector.as_slice(),
                    "quaternion_wxyz": [u.w, u.i, u.j, u.k],
                },
                "position_error": r.position_error,
                "orientation_error": r.orientation_error,
                "uncorrected_error": r.uncorrected_error,
            })
        }).collect::<Vec<_>>(),
    })
}

/// The target correction's summary and its first rows.
fn print_corrections(
    out: &mut dyn Write,
    (file, poses, rows): &(String, usize, Vec<TargetCorrection>),
) -> std::io::Result<()> {
    let worst = rows
        .iter()
        .map(|r| r.position_error.max(r.orientation_error))
        .fold(0.0, f64::max);
    let off: Vec<f64> = rows
        .iter()
        .map(|r| r.uncorrected_error)
        .filter(|v| v.is_finite())
        .collect();
    let rms = (off.iter().map(|v| v * v).sum::<f64>() / off.len().max(1) as f64).sqrt();
    writeln!(
        out,
        "target correction ({file}): {poses} poses, {} pose-posture rows; calibrated FK error at \
         the corrected q at most {worst:.1e} (m, rad); uncorrected, the real tool would be off by \
         {:.4} mm rms",
        rows.len(),
        rms * 1e3
    )?;
    writeln!(
        out,
        "{:>5}  {:<42} {:>10}  send x, y, z [mm]",
        "pose", "posture", "off [mm]"
    )?;
    for r in rows.iter().take(20) {
        let t = r.send.translation.vector * 1e3;
        writeln!(
            out,
            "{:>5}  {:<42} {:>10.4}  {:.4}, {:.4}, {:.4}",
            r.pose + 1,
            r.posture.to_string(),
            r.uncorrected_error * 1e3,
            t[0],
            t[1],
            t[2]
        )?;
    }
    if rows.len() > 20 {
        writeln!(
            out,
            "  ... {} rows in all (--out FILE writes them)",
            rows.len()
        )?;
    }
    Ok(())
}

fn fit_text(f: &Fit) -> String {
    let o = match (f.orientation_rms, f.orientation_max) {
        (Some(r), Some(m)) => format!(
            ", orientation rms {:.4} mrad, max {:.4} mrad",
            r * 1e3,
            m * 1e3
        ),
        _ => String::new(),
    };
    format!(
        "position rms {:.4} mm, max {:.4} mm{o}",
        f.position_rms * 1e3,
        f.position_max * 1e3
    )
}

fn write_identifiability(
    out: &mut dyn Write,
    n: &Identifiability,
    at: &str,
) -> std::io::Result<()> {
    writeln!(
        out,
        "identifiability at {at}: rank {} of {} (singular values below {:e} of the largest count \
         as zero)",
        n.rank, n.parameter_count, n.rank_threshold
    )?;
    for c in &n.combinations {
        writeln!(out, "  {c}")?;
    }
    let o = n.observability;
    writeln!(
        out,
        "  observability: O1 {:.3e}, O2 {:.3e}, O3 {:.3e}, O4 {:.3e}",
        o.o1, o.o2, o.o3, o.o4
    )
}

/// The setup, the warnings, the Hayati rows and what was kept at its nominal value and why.
fn write_preamble(
    out: &mut dyn Write,
    r: &CalibrationReport,
    ctx: &Context,
) -> std::io::Result<()> {
    for w in ctx.warnings {
        writeln!(out, "warning: {w}")?;
    }
    writeln!(
        out,
        "setup: {} ({} measurements); what it cannot see: {}",
        ctx.setup.name(),
        ctx.measurements,
        ctx.setup.blind_spots()
    )?;
    if !ctx.hayati_rows.is_empty() {
        let list: Vec<String> = ctx
            .hayati_rows
            .iter()
            .map(|r| format!("beta{r} instead of d{r}"))
            .collect();
        writeln!(
            out,
            "Hayati's parameter (parallel axes): {} (d kept at its nominal value: along parallel \
             axes plain DH cannot place the common normal)",
            list.join(", ")
        )?;
    }
    write_identifiability(
        out,
        &r.nominal,
        "the nominal parameters (before the iterations)",
    )?;
    for (name, why) in &r.auto_fixed {
        writeln!(
            out,
            "kept at its nominal value: {name}, because {why} (--unidentifiable minimum-norm \
             estimates it anyway)"
        )?;
    }
    Ok(())
}
fn write_text(
    out: &mut dyn Write,
    r: &CalibrationReport,
    val: Option<&(Fit, Fit)>,
    truth: Option<&[f64]>,
    ctx: &Context,
) -> std::io::Result<()> {
    write_preamble(out, r, ctx)?;
    writeln!(
        out,
        "iteration  position rms [mm]  orientation rms [mrad]  step      condition  rank"
    )?;
    for (i, it) in r.iterations.iter().enumerate() {
        writeln!(
            out,
            "{i:>9}  {:>17.5}  {:>22.5}  {:<8.1e}  {:>9.3e}  {:>4}",
            it.position_rms * 1e3,
            it.orientation_rms * 1e3,
            it.step_norm,
            it.condition,
            it.rank
        )?;
    }
    match &r.reason {
        None => writeln!(out, "converged")?,
        Some(why) => writeln!(out, "not converged: {why}")?,
    }
    write_identifiability(
        out,
        &r.at_estimate,
        "the estimate (the table's flags, standard deviations and correlations)",
    )?;
    write_table(out, r, truth)?;
    write_unknowns(out, r)?;
    if let Some(p) = ctx.tracker_from_base {
        let t = p.translation.vector * 1e3;
        let a = p.rotation.scaled_axis();
        writeln!(
            out,
            "tracker_from_base: translation ({:.4}, {:.4}, {:.4}) mm, rotation vector ({:.5}, \
             {:.5}, {:.5}) deg",
            t[0],
            t[1],
            t[2],
            a[0].to_degrees(),
            a[1].to_degrees(),
            a[2].to_degrees()
        )?;
    }
    for (a, b, c) in &r.correlations {
        writeln!(out, "correlated: {a} and {b} ({c:+.4})")?;
    }
    writeln!(out, "fit: before {}", fit_text(&r.before))?;
    writeln!(out, "fit: after  {}", fit_text(&r.after))?;
    if let Some((b, a)) = val {
        writeln!(out, "validation: before {}", fit_text(b))?;
        writeln!(out, "validation: after  {}", fit_text(a))?;
    }
    if let Some(c) = ctx.corrections {
        print_corrections(out, c)?;
    }
    Ok(())
}

/// The parameter table: nominal, true (simulated), estimate, standard deviation, flag.
fn write_table(
    out: &mut dyn Write,
    r: &CalibrationReport,
    truth: Option<&[f64]>,
) -> std::io::Result<()> {
    writeln!(
        out,
        "{:<9} {:>12} {:>12} {:>12} {:>10}  unit     identifiable",
        "parameter",
        "nominal",
        if truth.is_some() { "true" } else { "" },
        "estimate",
        "std"
    )?;
    for (k, p) in r.parameters.iter().enumerate() {
        let (scale, unit) = p.kind.display();
        let t = truth.map_or(String::new(), |t| format!("{:.5}", t[k] * scale));
        let std = r.std[k].map_or("-".into(), |s| format!("{:.2e}", s * scale));
        let flag = if r.auto_fixed.iter().any(|(n, _)| *n == p.name) {
            "NO (kept nominal)"
        } else if p.fixed {
            "fixed"
        } else if r.at_estimate.identifiable[k] {
            "yes"
        } else {
            "NO"
        };
        writeln!(
            out,
            "{:<9} {:>12.5} {:>12} {:>12.5} {:>10}  {unit:<7}  {flag}",
            p.name,
            p.nominal * scale,
            t,
            r.estimate[k] * scale,
            std
        )?;
    }
    Ok(())
}

/// The setup's unknowns (pivot points, planes, sphere centres) in mm (a plane's tilts a, b
/// without unit).
fn write_unknowns(out: &mut dyn Write, r: &CalibrationReport) -> std::io::Result<()> {
    let u = &r.unknowns;
    for (k, c) in u.points.iter().enumerate() {
        writeln!(
            out,
            "point {}: ({:.4}, {:.4}, {:.4}) mm",
            k + 1,
            c[0] * 1e3,
            c[1] * 1e3,
            c[2] * 1e3
        )?;
    }
    for (k, pl) in u.planes.iter().enumerate() {
        let n = pl.normal();
        writeln!(
            out,
            "plane {}: normal ({:.6}, {:.6}, {:.6}), offset {:.4} mm",
            k + 1,
            n[0],
            n[1],
            n[2],
            pl.h * 1e3
        )?;
    }
    for (k, c) in u.spheres.iter().enumerate() {
        writeln!(
            out,
            "sphere {}: centre ({:.4}, {:.4}, {:.4}) mm",
            k + 1,
            c[0] * 1e3,
            c[1] * 1e3,
            c[2] * 1e3
        )?;
    }
    Ok(())
}
