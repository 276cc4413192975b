//! armlab's typed errors as Python exceptions, with the same messages.
//!
//! Every exception derives from `armlab.ArmlabError`; one subclass per layer, so that a notebook
//! can catch a model file's error apart from an unreachable target's.

use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyValueError};
use pyo3::prelude::*;

create_exception!(
    armlab,
    ArmlabError,
    PyException,
    "Base class of armlab's errors (the Rust library's typed errors, same messages)."
);
create_exception!(
    armlab,
    ModelError,
    ArmlabError,
    "A model (built-in name, TOML model file or URDF) that cannot be loaded; the message names \
     the file, line and field."
);
create_exception!(
    armlab,
    KinematicsError,
    ArmlabError,
    "Forward kinematics or a Jacobian refused its input (e.g. the wrong number of joints)."
);
create_exception!(
    armlab,
    IkError,
    ArmlabError,
    "Inverse kinematics refused its input (no closed form, a target this solver cannot take)."
);
create_exception!(
    armlab,
    WorkspaceError,
    ArmlabError,
    "A workspace computation or point query this arm does not support; the message says why."
);
create_exception!(
    armlab,
    FigureError,
    ArmlabError,
    "A figure could not be drawn (e.g. no graphics adapter: install Mesa's lavapipe)."
);
create_exception!(
    armlab,
    CalibrationError,
    ArmlabError,
    "A calibration that could not run (bad measurement file, unknown option); the message names \
     the file and line."
);

create_exception!(
    armlab,
    CollisionError,
    ArmlabError,
    "A scene file (or scene text) the collision checker cannot use; the message names the \
     file, the line and the obstacle."
);

/// A `ValueError` with `message` (bad shapes, NaN, bad option values).
pub fn value_error(message: impl Into<String>) -> PyErr {
    PyValueError::new_err(message.into())
}

/// Maps a library error of one layer into its Python exception.
pub trait IntoPy<T> {
    /// The error as a Python exception.
    fn py_err(self) -> PyResult<T>;
}

macro_rules! layer {
    ($rust:ty, $python:ty) => {
        impl<T> IntoPy<T> for Result<T, $rust> {
            fn py_err(self) -> PyResult<T> {
                self.map_err(|e| <$python>::new_err(e.to_string()))
            }
        }
    };
}

layer!(armlab::model_file::LoadError, ModelError);
layer!(armlab::kinematics::KinematicsError, KinematicsError);
layer!(armlab::kinematics::ik::IkError, IkError);
layer!(armlab::kinematics::ik::closed_form::NoClosedForm, IkError);
layer!(armlab::workspace::WorkspaceError, WorkspaceError);
layer!(armlab::figure::FigureError, FigureError);
layer!(armlab::headless::HeadlessError, FigureError);
layer!(armlab::redundancy::RedundancyError, IkError);
layer!(armlab::collision::CollisionError, CollisionError);
