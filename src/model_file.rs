//! TOML model files: read a robot from text (with precise, typed errors) and write one back.
//!
//! # Schema
//!
//! Lengths in metres, angles in radians. Keys not listed are errors.
//!
//! ```toml
//! name = "Puma 560"
//! description = "..."                # optional
//! convention = "standard"            # or "modified"
//! base = [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]  # optional world_from_base, row-major, rigid
//! tool = [[...]]                     # optional flange_from_tool of the default end-effector
//! [[joints]]
//! type = "revolute"                  # or "prismatic" or "fixed"
//! a = 0.0                            # m
//! alpha = "pi/2"                     # a number (rad) or an angle string, see parse_angle
//! d = 0.672                          # m; required for revolute and fixed joints
//! offset = 0.0                       # optional: theta = q + offset (revolute), d = q + offset
//! theta = 0.0                        # optional constant theta of prismatic and fixed joints
//! limits = [-2.79, 2.79]             # optional for revolute ([-pi, pi]), required for prismatic
//! name = "waist"                     # optional, default "q1", "q2", ...; unique
//! parent = "torso4"                  # optional: an earlier joint's name or "base"
//! pre = [[...]]                      # optional constant transform before the DH row
//! couple = [[2, -1.0], [3, -1.0]]    # optional: value = sum factor * q of those joints (1-based)
//! [[end_effectors]]                  # optional; default: "tool" on the last joint with `tool`
//! name = "right hand"
//! parent = "r7"
//! tool = [[...]]                     # optional
//! [[configurations]]                 # optional named joint vectors, one value per dof
//! name = "ready"
//! q = [0.0, "pi/2"]
//! ```
//!
//! A revolute joint's `theta` and a prismatic joint's `d` are its variable: they may be written
//! only as 0. Fixed joints take no `offset`, `limits` or `couple`. Error messages look like
//! `joints[3].alpha: expected a number or an angle string like "pi/2" or "-90deg", found boolean
//! true (robots/arm.toml:14:9)`: the field (array elements numbered from 1), what is wrong, then
//! the file, line and column (1-based).

mod angle;
mod build;
mod error;
mod value;
mod writer;

pub use angle::parse_angle;
pub use error::{CoupleProblem, Location, ModelFileError, NameKind};
pub use writer::to_toml;

use crate::kinematics::Robot;
use crate::kinematics::models::{BUILT_INS, built_in};
use crate::urdf::{UrdfError, load_urdf};
use std::path::Path;
use thiserror::Error;

/// Reads a robot from the text of a TOML model file.
///
/// `path` is only used in error messages. The robot's joints are in file order, its `q`
/// components are the actuated (not fixed, not coupled) joints in file order, and it has the
/// configuration "zero" plus those of the file.
pub fn parse_model(text: &str, path: &Path) -> Result<Robot, ModelFileError> {
    build::build(&value::Ctx { text, path })
}

/// Reads a robot from a TOML model file (see [`parse_model`]); also reports unreadable files.
pub fn load_model_file(path: &Path) -> Result<Robot, ModelFileError> {
    let text = crate::input::read_text(path, crate::input::MAX_MODEL_BYTES, "a model file")
        .map_err(|source| ModelFileError::Read {
            path: path.to_path_buf(),
            source,
        })?;
    parse_model(&text, path)
}

/// Why [`load_model`] could not produce a robot.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum LoadError {
    /// A `.toml` model file that could not be read or is invalid.
    #[error(transparent)]
    ModelFile(#[from] ModelFileError),
    /// A `.urdf` file that could not be read or converted.
    #[error(transparent)]
    Urdf(#[from] UrdfError),
    /// Neither a built-in name nor a `.toml`/`.urdf` path.
    #[error(
        "unknown robot model \"{name}\": not a built-in model and not a path ending in .toml or .urdf; built-in models: {built_ins}"
    )]
    Unknown {
        /// The name given.
        name: String,
        /// The built-in names, comma-separated.
        built_ins: String,
    },
    /// A `.xacro` file: macros that must be expanded into URDF first.
    #[error(
        "{name}: a xacro file (URDF with macros, properties and includes): expand it into URDF \
         first, e.g. `xacro {name} > robot.urdf` (ROS 2: `ros2 run xacro xacro {name} > \
         robot.urdf`; ROS 1: `rosrun xacro xacro {name} > robot.urdf`; without ROS: `pip install \
         xacro`), then open robot.urdf"
    )]
    Xacro {
        /// The file's name.
        name: String,
    },
    /// A file handed over by name and text whose name does not end in .toml or .urdf.
    #[error("{name}: not a model file (the name of a model file ends in .toml or .urdf)")]
    NotAModelFile {
        /// The file's name.
        name: String,
    },
}

/// A robot from the text of a model file named `name` (`.toml` or `.urdf`, by the extension,
/// case-insensitively), e.g. a file the browser handed over. Errors name `name` like a path. A
/// URDF's meshes are looked up next to `name` (there are none in a browser: each is a warning).
pub fn parse_model_text(name: &str, text: &str) -> Result<Robot, LoadError> {
    let path = Path::new(name);
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("toml") => Ok(parse_model(text, path)?),
        Some("urdf") => Ok(crate::urdf::parse_urdf(text, path)?),
        Some("xacro") => Err(LoadError::Xacro {
            name: name.to_string(),
        }),
        _ => Err(LoadError::NotAModelFile {
            name: name.to_string(),
        }),
    }
}

/// A robot from a built-in name (see [`BUILT_INS`]) or from a path ending in `.toml` (model
/// file) or `.urdf` (see [`crate::urdf`]); the extension is matched case-insensitively.
pub fn load_model(spec: &str) -> Result<Robot, LoadError> {
    let ext = Path::new(spec)
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("toml") => Ok(load_model_file(Path::new(spec))?),
        Some("urdf") => Ok(load_urdf(Path::new(spec))?),
        Some("xacro") => Err(LoadError::Xacro {
            name: spec.to_string(),
        }),
        _ => built_in(spec).ok_or_else(|| LoadError::Unknown {
            name: spec.to_string(),
            built_ins: BUILT_INS
                .iter()
                .map(|b| b.name)
                .collect::<Vec<_>>()
                .join(", "),
        }),
    }
}
