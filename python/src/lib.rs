//! `armlab._core`: the extension module behind the `armlab` Python package.
//!
//! It wraps the graphics-free library (FK, Jacobians, labelled closed-form and numerical IK,
//! point queries, self-motions, symbolic kinematics, rotation conversions, collisions,
//! reachability maps) and the headless figures, NumPy in and out, SI units and radians. The
//! Python layer (`armlab/__init__.py`, `armlab/rotation.py`) turns its plain results into
//! documented objects; everything that computes is here or in the armlab crate.
//!
//! Batch calls (`fk_batch`, `ik_batch`, `rotation_to`, `rotation_from`) release the GIL and
//! spread the rows over every core (rayon). Inputs are checked here (shape, NaN); a bad one
//! raises `ValueError` naming the argument and the offending index, never a panic.

use pyo3::prelude::*;

mod arrays;
mod batch;
mod calibration;
mod collision;
mod errors;
mod figures;
mod reachability;
mod reports;
mod robot;
mod rotation;

/// The module `armlab._core`.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("ArmlabError", py.get_type::<errors::ArmlabError>())?;
    m.add("ModelError", py.get_type::<errors::ModelError>())?;
    m.add("KinematicsError", py.get_type::<errors::KinematicsError>())?;
    m.add("IkError", py.get_type::<errors::IkError>())?;
    m.add("WorkspaceError", py.get_type::<errors::WorkspaceError>())?;
    m.add("FigureError", py.get_type::<errors::FigureError>())?;
    m.add(
        "CalibrationError",
        py.get_type::<errors::CalibrationError>(),
    )?;
    m.add("CollisionError", py.get_type::<errors::CollisionError>())?;
    m.add_class::<robot::CoreRobot>()?;
    m.add_function(wrap_pyfunction!(collision::collisions, m)?)?;
    m.add_function(wrap_pyfunction!(reachability::reachability, m)?)?;
    m.add_function(wrap_pyfunction!(batch::fk_batch, m)?)?;
    m.add_function(wrap_pyfunction!(batch::ik_batch, m)?)?;
    m.add_function(wrap_pyfunction!(batch::ik_batch_numerical, m)?)?;
    m.add_function(wrap_pyfunction!(figures::render, m)?)?;
    m.add_function(wrap_pyfunction!(reports::workspace, m)?)?;
    m.add_function(wrap_pyfunction!(reports::reach, m)?)?;
    m.add_function(wrap_pyfunction!(reports::self_motion, m)?)?;
    m.add_function(wrap_pyfunction!(reports::symbolic, m)?)?;
    m.add_function(wrap_pyfunction!(calibration::calibrate, m)?)?;
    m.add_function(wrap_pyfunction!(reports::run_cli, m)?)?;
    m.add_function(wrap_pyfunction!(figures::svg_to_pdf, m)?)?;
    m.add_function(wrap_pyfunction!(figures::textbook_figure, m)?)?;
    m.add_function(wrap_pyfunction!(rotation::rotation_to, m)?)?;
    m.add_function(wrap_pyfunction!(rotation::rotation_from, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
