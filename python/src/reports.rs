//! The reports: workspace figures with their statistics, point queries, self-motions and the
//! symbolic kinematics, each computed by the library and handed to Python as plain data (JSON
//! for the nested ones; the Python layer makes objects of them); and `run_cli`, the command line's own
//! driver for `armlab info`, in process.

use crate::arrays::{checked, pose_of};
use crate::errors::{ArmlabError, IntoPy, ModelError, value_error};
use crate::figures::{Drawn, draw, size, theme, workspace_options};
use crate::robot::CoreRobot;
use armlab::figure::workspace::{paint, plan};
use armlab::kinematics::Robot;
use armlab::redundancy::sampler::{SelfMotionSamples, sample_self_motion_locked};
use armlab::workspace::compute_figure_data;
use armlab::workspace::{PointQuery, TrackedPoint, WorkspaceStats};
use clap::Parser;
use numpy::PyReadonlyArrayDyn;
use pyo3::prelude::*;
use rayon::prelude::*;
use serde_json::json;
use std::sync::OnceLock;

/// The statistics of a workspace figure (the keys of `armlab workspace --format json`).
fn stats_json(s: &WorkspaceStats, point: &str, samples: usize, seed: u64) -> serde_json::Value {
    let mut v = json!({
        "samples": samples,
        "seed": seed,
        "bbox": { "min": s.bounds.min, "max": s.bounds.max },
        "max_reach": s.max_reach,
        "min_reach": s.min_reach,
        "reach_exact": s.reach_exact,
        "resolution": s.resolution,
        "cell_size": s.cell_size,
        "dexterous": s.dexterous_measure,
        "classes": s.classes.iter().map(|c| json!({"name": c.name, "with": c.with, "only": c.only})).collect::<Vec<_>>(),
        "measure_method": s.measure_method,
        "point": point,
    });
    for (key, value) in [
        ("area", s.area),
        ("area_both_postures", s.area_both_postures),
        ("volume", s.volume),
        ("measure_error", s.measure_error),
    ] {
        if let Some(x) = value {
            v[key] = json!(x);
        }
    }
    v
}

/// A workspace figure and its statistics: `(stats JSON, png, svg)`.
#[pyfunction]
#[pyo3(signature = (robot, view=None, point="wrist-centre", color_by="posture", samples=200_000, seed=1, width=1200, height=900, theme="light"))]
#[allow(clippy::too_many_arguments)]
pub fn workspace(
    py: Python<'_>,
    robot: &Bound<'_, CoreRobot>,
    view: Option<&str>,
    point: &str,
    color_by: &str,
    samples: usize,
    seed: u64,
    width: u32,
    height: u32,
    theme: &str,
) -> PyResult<(String, Vec<u8>, String)> {
    let r = robot.get();
    let (size, theme) = (size(width, height)?, self::theme(theme)?);
    let opts = workspace_options(r, view, point, color_by, samples, seed, size, theme)?;
    let title = r.robot.name.to_lowercase();
    // Computed once, painted twice (pixels, then vectors).
    let data = OnceLock::new();
    let stats = OnceLock::new();
    let (png, svg) = draw(py, |figs| {
        let plan = plan(figs, &r.robot, &title, &opts)?;
        let data = match data.get() {
            Some(d) => d,
            None => {
                let d = compute_figure_data(&r.robot, &plan.request, &|_| {})?;
                data.get_or_init(|| d)
            }
        };
        let f = paint(figs, &r.robot, &plan, data)?;
        let _ = stats.set(f.stats);
        Ok(f.image)
    })?;
    let point = match opts.point {
        TrackedPoint::WristCentre => "wrist centre",
        TrackedPoint::Flange => "flange",
    };
    let stats = stats.into_inner().expect("set by the figure");
    Ok((
        stats_json(&stats, point, samples, seed).to_string(),
        png,
        svg,
    ))
}

/// Point queries against the exact workspace: per row of `points` (N, 2) for planar arms or
/// (N, 3) otherwise, `(reachable, distance to the boundary (m, positive inside), postures)`,
/// and whether the distances are exact.
#[pyfunction]
#[pyo3(signature = (robot, points, point="wrist-centre"))]
#[allow(clippy::type_complexity)]
pub fn reach(
    py: Python<'_>,
    robot: &Bound<'_, CoreRobot>,
    points: PyReadonlyArrayDyn<'_, f64>,
    point: &str,
) -> PyResult<(Vec<bool>, Vec<f64>, Vec<Vec<String>>, bool, usize)> {
    let r = robot.get();
    let tracked = match point {
        "wrist-centre" | "wrist_centre" | "wrist-center" | "wrist_center" => {
            TrackedPoint::WristCentre
        }
        "flange" => TrackedPoint::Flange,
        other => {
            return Err(value_error(format!(
                "point = {other:?}: use \"wrist-centre\" or \"flange\""
            )));
        }
    };
    let query = PointQuery::new(&r.robot, tracked).py_err()?;
    let d = query.dimension();
    let what = if d == 2 {
        "x, y in the arm's plane (m)"
    } else {
        "x, y, z (m)"
    };
    let data = checked(&points, "points", &[None, Some(d)], what)?;
    let data: &[f64] = &data;
    let answers: Vec<_> = py.detach(|| data.par_chunks(d).map(|p| query.query(p)).collect());
    let exact = query.distance_exact();
    let mut reachable = Vec::with_capacity(answers.len());
    let mut distance = Vec::with_capacity(answers.len());
    let mut postures = Vec::with_capacity(answers.len());
    for a in answers {
        reachable.push(a.reachable);
        distance.push(a.distance);
        postures.push(a.postures);
    }
    Ok((reachable, distance, postures, exact, d))
}

/// The arm of end-effector `ee` alone (the robot itself when it has one).
fn arm(robot: &Robot, ee: usize) -> PyResult<Robot> {
    if robot.end_effectors().len() == 1 {
        return Ok(robot.clone());
    }
    armlab::kinematics::arm::arm_of(robot, ee, &robot.ready_or_zero())
        .map(|a| a.robot)
        .map_err(|e| value_error(format!("ee = {ee}: {e}")))
}

/// The self-motion's JSON (the keys of `armlab self-motion --format json`).
fn self_motion_json(m: &SelfMotionSamples) -> serde_json::Value {
    let mut feas = serde_json::Map::new();
    for (name, iv) in m.names.iter().zip(&m.feasible) {
        feas.insert(name.clone(), json!(iv));
    }
    json!({
        "parameter": m.parameter,
        "parameter_meaning": m.meaning,
        "exact": m.exact,
        "branch_names": m.names,
        "samples": m.samples.iter().map(|(value, s)| json!({
            "value": value,
            "branches": s.iter().map(|b| json!({
                "name": b.name,
                "q": b.q,
                "within_limits": b.within_limits,
                "position_error": b.position_error,
                "orientation_error": b.orientation_error,
            })).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
        "feasible": feas,
        "manifolds": m.manifolds,
        "singular": m.singular,
    })
}

/// The self-motion of a redundant arm holding `T` (4x4): its JSON and, with `figure`, the
/// figure of every joint over the parameter `(png, svg)`.
#[pyfunction]
#[pyo3(signature = (robot, target, samples=360, lock=None, branch=None, ee=0, figure=false))]
#[allow(clippy::too_many_arguments)]
pub fn self_motion(
    py: Python<'_>,
    robot: &Bound<'_, CoreRobot>,
    target: PyReadonlyArrayDyn<'_, f64>,
    samples: usize,
    lock: Option<usize>,
    branch: Option<&str>,
    ee: usize,
    figure: bool,
) -> PyResult<(String, Option<Drawn>)> {
    let r = robot.get();
    let m = checked(&target, "T", &[Some(4), Some(4)], "a homogeneous transform")?;
    let pose = pose_of(&m, "T")?;
    if samples == 0 || samples > 1_000_000 {
        return Err(value_error("samples must be between 1 and 1000000"));
    }
    let arm = arm(&r.robot, r.ee(ee)?)?;
    let locked = match lock {
        Some(k) if arm.dof() != 7 || !(1..=7).contains(&k) => {
            return Err(value_error(format!(
                "lock = {k}: give a joint 1 to 7 of a seven-joint arm ({} has {})",
                arm.name,
                arm.dof()
            )));
        }
        Some(k) => Some(k - 1),
        None => None,
    };
    let mut motion = py
        .detach(|| sample_self_motion_locked(&arm, 0, &pose, samples, locked))
        .py_err()?;
    if let Some(b) = branch {
        motion
            .keep_branch(b)
            .map_err(|e| value_error(format!("branch = {b:?}: {e}")))?;
    }
    let drawn = if figure {
        Some(draw(py, |figs| {
            armlab::figure::self_motion::figure(figs, &arm, &motion)
        })?)
    } else {
        None
    };
    Ok((self_motion_json(&motion).to_string(), drawn))
}

/// The direct kinematics in the textbook's symbols: `(text, latex, markdown)`.
#[pyfunction]
#[pyo3(signature = (robot, numbers=false, ee=0))]
pub fn symbolic(
    robot: &Bound<'_, CoreRobot>,
    numbers: bool,
    ee: usize,
) -> PyResult<(String, String, String)> {
    use armlab::kinematics::symbolic::{Options, derive, document};
    let r = robot.get();
    let sk = derive(&r.robot, r.ee(ee)?, &Options { numbers })
        .map_err(|e| ArmlabError::new_err(e.to_string()))?;
    Ok((
        document::text(&sk, numbers),
        document::latex(&sk),
        document::markdown(&sk, numbers),
    ))
}

/// Runs the command line `armlab ARGS...` in this process and returns what it printed (for
/// `armlab info`); an error becomes `error` ("model": `ModelError`, else `ArmlabError`) with
/// the command line's message.
#[pyfunction]
#[pyo3(signature = (args, error="armlab"))]
pub fn run_cli(py: Python<'_>, args: Vec<String>, error: &str) -> PyResult<String> {
    let raise = |message: String| match error {
        "model" => ModelError::new_err(message),
        _ => ArmlabError::new_err(message),
    };
    let cli = armlab::cli::Cli::try_parse_from(std::iter::once("armlab".to_string()).chain(args))
        .map_err(|e| value_error(e.to_string()))?;
    let mut out = Vec::new();
    py.detach(|| armlab::cli::run(cli, &mut out))
        .map_err(|e| raise(e.to_string()))?;
    String::from_utf8(out).map_err(|e| raise(format!("the output is not UTF-8: {e}")))
}
