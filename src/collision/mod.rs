//! Collisions of an arm with itself and with a cell's obstacles, for any configuration: what
//! every closed-form posture, ghost, workspace cell and self-motion stretch hits.
//!
//! - [`RobotGeometry`]: the links as convex parts. A URDF's `<collision>` elements (box,
//!   cylinder, sphere, mesh as its convex hull or, when asked, a convex decomposition), a link's
//!   `<visual>` where it has no `<collision>`, and for a DH model (or a link whose meshes are
//!   missing) the links as they are drawn: capsules along the stick figure and the joints'
//!   bodies.
//! - [`CellScene`]: obstacles read from a TOML scene file (boxes, cylinders, spheres, a floor
//!   plane, meshes), each with a name and a pose.
//! - [`AllowedCollisions`]: the pairs never checked (adjacent links, and what a sampled matrix
//!   disables as MoveIt's Setup Assistant does: pairs that always collide, or never do).
//! - [`CollisionWorld`]: the three together; [`CollisionWorld::check`] answers one
//!   configuration with the pairs in contact, their depth and the clearance.
//!
//! Shapes and queries are dimforge's parry (`parry3d-f64`): contact (penetration depth),
//! distance and intersection tests between convex shapes, convex hulls and decomposition.
//!
//! ```
//! use armlab::collision::{CellScene, CollisionWorld};
//! use armlab::kinematics::models;
//!
//! let robot = models::puma560();
//! let scene = CellScene::parse(
//!     "[[obstacle]]\nname = \"table\"\nshape = \"box\"\nsize = [1.2, 0.8, 0.05]\nxyz = [0.6, 0.0, 0.375]\n",
//!     std::path::Path::new("cell.toml"),
//! )
//! .unwrap();
//! let world = CollisionWorld::new(&robot, &scene).unwrap();
//! let report = world.check(&robot, &robot.ready_or_zero()).unwrap();
//! assert!(report.clearance_m.is_some());
//! ```

mod geometry;
mod hull;
mod matrix;
mod obstacles;
mod srdf;
mod world;

pub use geometry::{Body, BodyKind, GeometryOptions, RobotGeometry};
pub use matrix::{
    AllowedCollisions, MatrixOptions, PairReason, PairVerdict, sample_matrix,
    sample_matrix_with_progress,
};
pub use obstacles::{CellScene, Obstacle, ObstacleFrame, ObstacleShape};
pub use srdf::{parse_srdf, write_srdf};
pub use world::{ClosestPair, CollisionReport, CollisionWorld, Contact};

use crate::kinematics::KinematicsError;
use std::path::PathBuf;
use thiserror::Error;

/// Errors of the collision layer: a scene file, an SRDF or a configuration that cannot be
/// used. Each names the file, the line and the element.
#[derive(Debug, Error)]
pub enum CollisionError {
    /// The scene file could not be read.
    #[error("cannot read the scene file: {source} ({path})")]
    Read {
        /// The file as given.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The scene file is not TOML, or a key has the wrong type.
    #[error("{path}:{line}:{column}: {message}")]
    Toml {
        /// The file as given.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What the TOML reader said.
        message: String,
    },
    /// One obstacle is wrong (a degenerate box, a NaN, a missing mesh, an unknown frame).
    #[error("{path}:{line}: obstacle \"{obstacle}\": {problem}")]
    Obstacle {
        /// The scene file as given.
        path: PathBuf,
        /// 1-based line of the obstacle's table.
        line: usize,
        /// The obstacle's name ("#3" when it has none).
        obstacle: String,
        /// What is wrong, in words.
        problem: String,
    },
    /// An SRDF file is not usable.
    #[error("{path}:{line}: {problem}")]
    Srdf {
        /// The file as given.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// What is wrong.
        problem: String,
    },
    /// The configuration does not fit the robot.
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
}

/// 1-based line and column of byte `offset` in `text`.
pub(crate) fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}
