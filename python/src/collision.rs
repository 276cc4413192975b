//! Collisions from Python: what a configuration hits (the arm's own links and a scene's
//! obstacles), as `armlab collisions --format json` reports it, and the checker `ik` uses for
//! its solutions' collision fields.

use crate::arrays::checked;
use crate::errors::IntoPy;
use crate::robot::CoreRobot;
use armlab::collision::{CellScene, CollisionReport, CollisionWorld, GeometryOptions};
use numpy::{PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use std::borrow::Cow;
use std::path::Path;

/// The name a scene given as text has in messages (meshes in it are read relative to the
/// working directory).
const SCENE_TEXT_NAME: &str = "<scene text>";

/// The scene `path` names or `text` holds (neither: no obstacles).
fn scene(path: Option<&str>, text: Option<&str>) -> PyResult<CellScene> {
    match (path, text) {
        (Some(p), _) => CellScene::read(Path::new(p)).py_err(),
        (None, Some(t)) => CellScene::parse(t, Path::new(SCENE_TEXT_NAME)).py_err(),
        (None, None) => Ok(CellScene::default()),
    }
}

/// The checker of `core`'s robot in a scene: its own links with the robot's matrix (built
/// once per robot and kept) and the scene's obstacles; with no scene the kept checker itself.
pub fn world<'a>(
    core: &'a CoreRobot,
    path: Option<&str>,
    text: Option<&str>,
) -> PyResult<Cow<'a, CollisionWorld>> {
    let own = core.self_world()?;
    if path.is_none() && text.is_none() {
        return Ok(Cow::Borrowed(own));
    }
    let scene = scene(path, text)?;
    let world = CollisionWorld::with(
        &core.robot,
        own.geometry.clone(),
        &scene,
        GeometryOptions::default(),
        own.allowed.clone(),
    )
    .py_err()?;
    Ok(Cow::Owned(world))
}

/// A report as JSON, `armlab collisions --format json`'s object.
pub fn report_json(report: &CollisionReport) -> String {
    // A report is plain data (strings, numbers): it always serialises.
    serde_json::to_string(report).unwrap_or_default()
}

/// What configuration `q` (dof,) hits, or each row of `Q` (N, dof): the reports as JSON (one
/// object, or a list), and what building the checker said (a link checked with its visual, an
/// obstacle touching the fixed base), each naming the link or obstacle. `scene_path` is a
/// scene file; `scene_text` the text of one.
#[pyfunction]
#[pyo3(signature = (robot, q, scene_path=None, scene_text=None))]
pub fn collisions(
    robot: &Bound<'_, CoreRobot>,
    q: PyReadonlyArrayDyn<'_, f64>,
    scene_path: Option<&str>,
    scene_text: Option<&str>,
) -> PyResult<(String, Vec<String>)> {
    let core = robot.get();
    let n = core.robot.dof();
    let batch = q.shape().len() == 2;
    let shape: &[Option<usize>] = if batch { &[None, Some(n)] } else { &[Some(n)] };
    let data = checked(&q, "q", shape, "one value per joint, rad or m")?;
    let world = world(core, scene_path, scene_text)?;
    let mut reports = Vec::new();
    for row in data.chunks_exact(n) {
        reports.push(world.check(&core.robot, row).py_err()?);
    }
    let json = if batch {
        serde_json::to_string(&reports).unwrap_or_default()
    } else {
        reports.first().map(report_json).unwrap_or_default()
    };
    Ok((json, world.warnings.clone()))
}
