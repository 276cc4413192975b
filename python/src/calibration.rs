//! The calibration: Python's keywords made into the library's [`Experiment`] (typed, no
//! command line in between), run once by [`armlab::calibration::run`]; the one report comes back
//! as its JSON (the keys of `armlab calibrate --format json`) and its text.

use crate::errors::{CalibrationError, value_error};
use crate::robot::CoreRobot;
use armlab::calibration::{
    CalibrationOptions, Criterion, Experiment, ModelOptions, NamedText, Selection, Setup,
    Simulation, Source, Unidentifiable,
};
use pyo3::prelude::*;
use std::path::Path;

/// The text of a file the caller named (measurements, held-out data, desired poses), named by
/// its path in every error and warning.
fn read_named(path: &str, keyword: &str) -> PyResult<NamedText> {
    armlab::input::read_data_text(Path::new(path))
        .map(|text| NamedText {
            name: path.to_string(),
            text,
        })
        .map_err(|e| CalibrationError::new_err(format!("{keyword}: {e}")))
}

/// A keyword's value among `names` (the error lists them).
fn one_of<T: Clone>(keyword: &str, value: &str, names: &[(&str, T)]) -> PyResult<T> {
    names
        .iter()
        .find(|(n, _)| *n == value)
        .map(|(_, v)| v.clone())
        .ok_or_else(|| {
            let list: Vec<&str> = names.iter().map(|(n, _)| *n).collect();
            value_error(format!(
                "{keyword} must be one of {}; got {value:?}",
                list.join(", ")
            ))
        })
}

/// A non-negative, finite keyword (noise, tolerances; units in its name).
fn non_negative(keyword: &str, value: f64) -> PyResult<f64> {
    if value >= 0.0 && value.is_finite() {
        Ok(value)
    } else {
        Err(value_error(format!(
            "{keyword} must be 0 or more; got {value}"
        )))
    }
}

/// A positive, finite length keyword (units in its name).
fn positive(keyword: &str, value: f64) -> PyResult<f64> {
    if value > 0.0 && value.is_finite() {
        Ok(value)
    } else {
        Err(value_error(format!(
            "{keyword} must be positive; got {value}"
        )))
    }
}

/// Calibrates `robot` (the library's experiment, run once): measurements from the file
/// `measurements` or the text `measurements_text` (Python's `(Q, Y)` arrays, named "(Q, Y)"), or
/// a simulated arm when `simulate`. Units as the keywords name them (mm, mrad, degrees); the
/// experiment is SI. Returns `(JSON, text)` of the one report. A bad file raises
/// `CalibrationError` naming the file and line; a bad keyword raises `ValueError` naming it.
#[pyfunction]
#[pyo3(signature = (
    robot, *, measurements=None, measurements_text=None, setup=None, validate=None,
    simulate=false, poses=50, select="random", tolerance_mm=1.0, tolerance_deg=0.5,
    noise_mm=0.05, noise_mrad=0.1, position_only=false, seed=1, groups=3, distance_mm=300.0,
    sphere_radius_mm=None, with_base=false, with_tool=false, with_compliance=false,
    fix=Vec::new(), hayati="auto", unidentifiable="nominal", correct_targets=None,
))]
#[allow(clippy::too_many_arguments)] // one keyword per option of the experiment, as Python calls it
pub fn calibrate(
    py: Python<'_>,
    robot: &CoreRobot,
    measurements: Option<String>,
    measurements_text: Option<String>,
    setup: Option<String>,
    validate: Option<String>,
    simulate: bool,
    poses: usize,
    select: &str,
    tolerance_mm: f64,
    tolerance_deg: f64,
    noise_mm: f64,
    noise_mrad: f64,
    position_only: bool,
    seed: u64,
    groups: usize,
    distance_mm: f64,
    sphere_radius_mm: Option<f64>,
    with_base: bool,
    with_tool: bool,
    with_compliance: bool,
    fix: Vec<String>,
    hayati: &str,
    unidentifiable: &str,
    correct_targets: Option<String>,
) -> PyResult<(String, String)> {
    let setups: Vec<(&str, Setup)> = Setup::ALL.iter().map(|s| (s.name(), *s)).collect();
    let setup = match setup.as_deref() {
        Some(name) => one_of("setup", name, &setups)?,
        None => Setup::Pose,
    };
    let radius = sphere_radius_mm
        .map(|r| positive("sphere_radius_mm", r).map(|r| r * 1e-3))
        .transpose()?;
    let noise_mm = non_negative("noise_mm", noise_mm)?;
    let noise_mrad = non_negative("noise_mrad", noise_mrad)?;
    let source = if simulate {
        if poses == 0 || poses > 100_000 {
            return Err(value_error(format!(
                "poses must be between 1 and 100000; got {poses}"
            )));
        }
        if groups == 0 {
            return Err(value_error("groups must be at least 1"));
        }
        let selection = one_of(
            "select",
            select,
            &[
                ("random", Selection::Random),
                ("o1", Selection::Best(Criterion::O1)),
                ("o4", Selection::Best(Criterion::O4)),
            ],
        )?;
        Source::Simulated(Simulation {
            poses,
            validation_poses: poses,
            selection,
            tolerance_mm: non_negative("tolerance_mm", tolerance_mm)?,
            tolerance_deg: non_negative("tolerance_deg", tolerance_deg)?,
            noise_mm,
            noise_mrad,
            position_only,
            seed,
            groups,
            distance: positive("distance_mm", distance_mm)? * 1e-3,
            radius: radius.unwrap_or(0.025),
            // The real arm bends when the model estimates how (as `armlab calibrate`).
            bend: with_compliance,
        })
    } else {
        let fit = match (measurements, measurements_text) {
            (Some(path), None) => read_named(&path, "measurements")?,
            (None, Some(text)) => NamedText {
                name: "(Q, Y)".into(),
                text,
            },
            (Some(_), Some(_)) => {
                return Err(value_error(
                    "give measurements or measurements_text, not both",
                ));
            }
            (None, None) => {
                return Err(value_error(
                    "give measurements (a file or (Q, Y) arrays), or simulate=True",
                ));
            }
        };
        Source::Measured {
            fit,
            validation: validate.map(|p| read_named(&p, "validate")).transpose()?,
            radius,
        }
    };
    let mut options = CalibrationOptions::default().with_noise(noise_mm, noise_mrad);
    options.unidentifiable = one_of(
        "unidentifiable",
        unidentifiable,
        &[
            ("nominal", options.unidentifiable),
            ("minimum-norm", Unidentifiable::MinimumNorm),
        ],
    )?;
    let experiment = Experiment {
        robot: robot.robot.clone(),
        setup,
        model: ModelOptions {
            hayati: one_of("hayati", hayati, &[("auto", true), ("off", false)])?,
            with_base,
            with_tool,
            with_compliance,
            fix: fix
                .iter()
                .map(|s| s.trim().to_string())
                .filter(|s| !s.is_empty())
                .collect(),
        },
        source,
        options,
        targets: correct_targets
            .map(|p| read_named(&p, "correct_targets"))
            .transpose()?,
    };
    let report = py
        .detach(|| armlab::calibration::run(&experiment))
        .map_err(|e| CalibrationError::new_err(e.to_string()))?;
    let json = serde_json::to_string_pretty(&report)
        .map_err(|e| CalibrationError::new_err(e.to_string()))?;
    Ok((json, report.to_string()))
}
