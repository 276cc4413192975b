//! Reachability maps from Python (issue 49): `Robot.reachability(...)` returns the arrays of
//! `armlab reachability --out map.npz`, key by key, as NumPy arrays and plain values.
//!
//! The map is computed with the GIL released, on every core. Bad options (a zero voxel, no
//! directions or rolls, too many samples without `force`, a missing end-effector) raise
//! `ValueError` with the library's message before any work; a scene that cannot be used raises
//! `CollisionError`. Ctrl+C is not watched during the computation (no other call of the
//! package watches it either).

use crate::arrays::to_numpy;
use crate::errors::value_error;
use crate::robot::CoreRobot;
use armlab::reachability::{MapControl, MapOptions, ReachabilityMap, compute_reachability};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The reachability map of `robot`'s end-effector `ee` (an index) as a dict with the keys of
/// the `.npz` file: `reachable` (nx, ny, nz, N, R) bool, `postures` (nx, ny, nz, N, R) uint16,
/// `posture_names` (list of str), `index` (nx, ny, nz) float64, `origin` (3,) m, `voxel` m,
/// `size` (3,) m, `directions` (N, 3), `rolls` (R,) rad, `end_effector`, `model`, `version`,
/// `solver` (str), `collisions` (bool), `reach_centre` (3,) m and `reach` (m): voxels farther
/// than `reach` from `reach_centre` were not solved. With `scene_path` (a scene file) or
/// `scene_text` (its TOML), a solution counts only when it hits neither the arm nor the scene.
#[pyfunction]
#[pyo3(signature = (robot, voxel=0.05, directions=200, rolls=8, ee=0, seeds=4, force=false, scene_path=None, scene_text=None))]
#[allow(clippy::too_many_arguments)]
pub fn reachability<'py>(
    py: Python<'py>,
    robot: &Bound<'py, CoreRobot>,
    voxel: f64,
    directions: usize,
    rolls: usize,
    ee: usize,
    seeds: usize,
    force: bool,
    scene_path: Option<&str>,
    scene_text: Option<&str>,
) -> PyResult<Bound<'py, PyDict>> {
    let core = robot.get();
    let opts = MapOptions {
        ee,
        voxel_m: voxel,
        directions,
        rolls,
        force,
        seeds,
    };
    let world = match (scene_path, scene_text) {
        (None, None) => None,
        _ => Some(crate::collision::world(core, scene_path, scene_text)?),
    };
    let map = py
        .detach(|| {
            compute_reachability(&core.robot, &opts, world.as_deref(), MapControl::default())
        })
        .map_err(|e| value_error(e.to_string()))?;
    to_dict(py, map)
}

/// The map's arrays and values under the `.npz` file's keys (the sample arrays moved, not
/// copied).
fn to_dict(py: Python<'_>, map: ReachabilityMap) -> PyResult<Bound<'_, PyDict>> {
    let [nx, ny, nz] = map.grid.dims;
    let (n, r) = (map.directions.len(), map.rolls.len());
    let index = map.index();
    let size: Vec<f64> = map
        .grid
        .dims
        .iter()
        .map(|&d| d as f64 * map.grid.voxel_m)
        .collect();
    let directions: Vec<f64> = map.directions.iter().flatten().copied().collect();
    let out = PyDict::new(py);
    out.set_item(
        "reachable",
        to_numpy(py, map.reachable, &[nx, ny, nz, n, r])?,
    )?;
    out.set_item("postures", to_numpy(py, map.postures, &[nx, ny, nz, n, r])?)?;
    out.set_item("posture_names", map.posture_names)?;
    out.set_item("index", to_numpy(py, index, &[nx, ny, nz])?)?;
    out.set_item("origin", to_numpy(py, map.grid.origin.to_vec(), &[3])?)?;
    out.set_item("voxel", map.grid.voxel_m)?;
    out.set_item("size", to_numpy(py, size, &[3])?)?;
    out.set_item("directions", to_numpy(py, directions, &[n, 3])?)?;
    out.set_item("rolls", to_numpy(py, map.rolls, &[r])?)?;
    out.set_item("end_effector", map.end_effector)?;
    out.set_item("model", map.model)?;
    out.set_item("version", env!("CARGO_PKG_VERSION"))?;
    out.set_item("solver", map.solver.describe())?;
    out.set_item("collisions", map.collisions)?;
    out.set_item(
        "reach_centre",
        to_numpy(py, map.reach_centre.to_vec(), &[3])?,
    )?;
    out.set_item("reach", map.reach_m)?;
    Ok(out)
}
