//! `armlab calibrate`: kinematic calibration (Sect. 2.11) from a measurement file, or on
//! simulated data, with a readable report or JSON.

use super::{CliError, Format};
use crate::calibration::{
    CalibrationOptions, CalibrationReport, Criterion, Fit, Identifiability, Measurement,
    ParameterModel, SimulationOptions, calibrate, fit, parse_measurements, select_poses, simulate,
    write_measurements,
};
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
    /// Plain DH parameters.
    #[default]
    Off,
    /// Hayati's beta for nearly parallel consecutive axes.
    Auto,
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
    /// Measurement file: per line the joint values, then 3 (position) or 16 (4x4 pose) numbers.
    #[arg(
        long,
        required_unless_present = "simulate",
        conflicts_with = "simulate"
    )]
    pub measurements: Option<PathBuf>,
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
    /// Hayati's parameter for nearly parallel axes.
    #[arg(long, value_enum, default_value_t)]
    pub hayati: Hayati,
    /// Write the calibrated robot as a model file.
    #[arg(long)]
    pub write_model: Option<PathBuf>,
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
    /// PNG: calibrated vs real when simulated (and nominal vs real to FILE-before.png), else the
    /// correction, calibrated vs nominal.
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

fn read(path: &Path, dof: usize) -> Result<Vec<Measurement>, CliError> {
    let text = crate::input::read_data_text(path).map_err(|e| CliError::BadTarget {
        source_name: path.display().to_string(),
        reason: e.to_string(),
    })?;
    parse_measurements(&text, &path.display().to_string(), dof).map_err(|e| CliError::BadTarget {
        source_name: e.source_name.clone(),
        reason: format!("line {}: {}", e.line, e.problem),
    })
}

fn calibration_error(e: crate::calibration::CalibrationError) -> CliError {
    CliError::BadTarget {
        source_name: "calibrate".into(),
        reason: e.to_string(),
    }
}

/// The data of a run: fit measurements, held-out ones, the truth when simulated.
type Data = (Vec<Measurement>, Option<Vec<Measurement>>, Option<Vec<f64>>);

fn data(
    args: &CalibrateArgs,
    model: &ParameterModel,
    opts: &CalibrationOptions,
) -> Result<Data, CliError> {
    let dof = model.nominal_robot().dof();
    if !args.simulate {
        let path = args
            .measurements
            .as_ref()
            .ok_or(CliError::Usage("give --measurements FILE, or --simulate"))?;
        let ms = read(path, dof)?;
        let val = args.validate.as_ref().map(|p| read(p, dof)).transpose()?;
        return Ok((ms, val, None));
    }
    if args.poses == 0 || args.poses > 100_000 {
        return Err(CliError::Usage("--poses must be between 1 and 100000"));
    }
    let candidates = match args.select {
        Select::Random => args.poses,
        _ => 10 * args.poses,
    };
    let sim = simulate(
        model,
        &SimulationOptions {
            poses: candidates,
            validation_poses: args.poses,
            tolerance_mm: args.tolerance_mm,
            tolerance_deg: args.tolerance_deg,
            noise_mm: args.noise_mm,
            noise_mrad: args.noise_mrad,
            position_only: args.position_only,
            seed: args.seed,
        },
    )
    .map_err(calibration_error)?;
    let ms = match args.select {
        Select::Random => sim.measurements,
        Select::O1 | Select::O4 => {
            let c = if args.select == Select::O1 {
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
    Ok((ms, Some(sim.validation), Some(sim.truth)))
}

/// `armlab calibrate`.
pub(super) fn run(args: &CalibrateArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let (robot, _) = super::arm_robot(super::load_model(&args.model)?, args.ee.as_deref())?;
    let mut model = ParameterModel::new(&robot).map_err(calibration_error)?;
    if args.with_base {
        model = model.with_base();
    }
    if args.with_tool {
        model = model.with_tool();
    }
    if args.hayati == Hayati::Auto {
        model = model.with_hayati().map_err(calibration_error)?;
    }
    if let Some(list) = &args.fix {
        let names: Vec<&str> = list
            .split(',')
            .map(str::trim)
            .filter(|s| !s.is_empty())
            .collect();
        model.fix(&names).map_err(calibration_error)?;
    }
    let opts = CalibrationOptions {
        position_sigma: (args.noise_mm * 1e-3).max(1e-9),
        orientation_sigma: (args.noise_mrad * 1e-3).max(1e-9),
        ..CalibrationOptions::default()
    };
    let (ms, validation, truth) = data(args, &model, &opts)?;
    let report = calibrate(&model, &ms, &opts).map_err(calibration_error)?;
    let val = validation
        .map(|v| -> Result<(Fit, Fit), CliError> {
            let before = fit(&model, &model.nominal(), &v).map_err(calibration_error)?;
            let after = fit(&model, &report.estimate, &v).map_err(calibration_error)?;
            Ok((before, after))
        })
        .transpose()?;
    if let Some(path) = &args.write_model {
        let r = model
            .robot_with(&report.estimate)
            .map_err(calibration_error)?;
        let text = crate::model_file::to_toml(&r).ok_or(CliError::Usage(
            "the calibrated robot cannot be written as a DH model file",
        ))?;
        std::fs::write(path, text)?;
    }
    if let Some(path) = &args.accuracy_map {
        accuracy_figures(args, &model, &report.estimate, truth.as_deref(), path)?;
    }
    match args.format {
        Format::Json => {
            let mut v = to_json(&report, val.as_ref(), truth.as_deref());
            v["hayati_rows"] = json!(model.hayati_rows());
            serde_json::to_writer_pretty(&mut *out, &v).map_err(std::io::Error::from)?;
            writeln!(out)?;
        }
        Format::Text => {
            let rows = model.hayati_rows();
            if !rows.is_empty() {
                let list: Vec<String> = rows
                    .iter()
                    .map(|r| format!("beta{r} instead of d{r}"))
                    .collect();
                writeln!(
                    out,
                    "Hayati's parameter (parallel axes): {}",
                    list.join(", ")
                )?;
            }
            write_text(out, &report, val.as_ref(), truth.as_deref())?
        }
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
            let before = path.with_file_name(format!("{stem}-before.png"));
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
    let mut figures = crate::figure::figures::Figures::new()?;
    for (file, a, b, title) in maps {
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
        crate::headless::write_png(&img, &file)?;
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

fn to_json(r: &CalibrationReport, val: Option<&(Fit, Fit)>, truth: Option<&[f64]>) -> Value {
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
            if let Some(t) = truth {
                o["true"] = json!(t[k]);
            }
            o
        })
        .collect();
    let n = &r.nominal;
    let o = &n.observability;
    json!({
        "parameters": params,
        "parameter_count": n.parameter_count,
        "rank": n.rank,
        "rank_threshold": n.rank_threshold,
        "unidentifiable": n.unidentifiable,
        "combinations": n.combinations,
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
    })
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

fn write_identifiability(out: &mut dyn Write, n: &Identifiability) -> std::io::Result<()> {
    writeln!(
        out,
        "identifiability at the nominal parameters: rank {} of {} (singular values below {:e} of \
         the largest count as zero)",
        n.rank, n.parameter_count, n.rank_threshold
    )?;
    for c in &n.combinations {
        writeln!(out, "  {c}")?;
    }
    let o = n.observability;
    writeln!(
        out,
        "observability: O1 {:.3e}, O2 {:.3e}, O3 {:.3e}, O4 {:.3e}",
        o.o1, o.o2, o.o3, o.o4
    )
}

fn write_text(
    out: &mut dyn Write,
    r: &CalibrationReport,
    val: Option<&(Fit, Fit)>,
    truth: Option<&[f64]>,
) -> std::io::Result<()> {
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
    write_identifiability(out, &r.nominal)?;
    writeln!(
        out,
        "{:<9} {:>12} {:>12} {:>12} {:>10}  unit  identifiable",
        "parameter",
        "nominal",
        if truth.is_some() { "true" } else { "" },
        "estimate",
        "std"
    )?;
    for (k, p) in r.parameters.iter().enumerate() {
        let (scale, unit) = if p.kind.is_angle() {
            (180.0 / std::f64::consts::PI, "deg")
        } else {
            (1e3, "mm")
        };
        let t = truth.map_or(String::new(), |t| format!("{:.5}", t[k] * scale));
        let std = r.std[k].map_or("-".into(), |s| format!("{:.2e}", s * scale));
        let flag = if p.fixed {
            "fixed"
        } else if r.at_estimate.identifiable[k] {
            "yes"
        } else {
            "NO"
        };
        writeln!(
            out,
            "{:<9} {:>12.5} {:>12} {:>12.5} {:>10}  {unit:<4}  {flag}",
            p.name,
            p.nominal * scale,
            t,
            r.estimate[k] * scale,
            std
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
    Ok(())
}
