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
//! [[disable_collisions]]             # optional: the stored allowed-collision matrix
//! link1 = "link2"                    # "base", or "linkN": the link moving with joint N
//! link2 = "link4"
//! reason = "Never"                   # optional: Adjacent, Always, Default, Never, or your word
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
///
/// # Examples
///
/// The anthropomorphic arm of Table 2.4 written as a model file; at q = (0, 0, 0) it stretches
/// out along x0 to a2 + a3:
///
/// ```
/// use armlab::model_file::parse_model;
/// use std::path::Path;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let text = r#"
/// name = "anthropomorphic arm"
/// convention = "standard"
///
/// [[joints]]
/// type = "revolute"
/// a = 0.0
/// alpha = "pi/2"
/// d = 0.0
///
/// [[joints]]
/// type = "revolute"
/// a = 0.5
/// alpha = 0.0
/// d = 0.0
///
/// [[joints]]
/// type = "revolute"
/// a = 0.4
/// alpha = 0.0
/// d = 0.0
/// limits = ["-150deg", "150deg"]
///
/// [[configurations]]
/// name = "ready"
/// q = [0.0, "pi/4", "-pi/2"]
/// "#;
/// let arm = parse_model(text, Path::new("arm.toml"))?;
/// assert_eq!(arm.dof(), 3);
/// let p = arm.fk(&[0.0, 0.0, 0.0])?.translation.vector;
/// assert!((p.x - 0.9).abs() < 1e-15 && p.y.abs() < 1e-15 && p.z.abs() < 1e-15);
/// assert!((arm.dof_joint(2).limits[1] - 150f64.to_radians()).abs() < 1e-15);
/// assert_eq!(arm.config("ready"), Some(&[0.0, std::f64::consts::FRAC_PI_4, -std::f64::consts::FRAC_PI_2][..]));
/// # Ok(())
/// # }
/// ```
///
/// Errors name the field and where it is, line and column:
///
/// ```
/// use armlab::model_file::{ModelFileError, parse_model};
/// use std::path::Path;
///
/// let text = r#"name = "arm"
/// convention = "standard"
/// [[joints]]
/// type = "revolute"
/// a = 1.0
/// alpha = true
/// d = 0.0
/// "#;
/// let err = parse_model(text, Path::new("arm.toml")).unwrap_err();
/// assert!(matches!(err, ModelFileError::WrongType { .. }));
/// assert_eq!(err.field(), Some("joints[1].alpha"));
/// let at = err.location().expect("a position in the file");
/// assert_eq!((at.line, at.column), (6, 9));
/// println!("{err}"); // joints[1].alpha: expected a number or an angle string ... (arm.toml:6:9)
/// ```
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
///
/// # Examples
///
/// A two-joint URDF chain; the format is chosen by the name's extension:
///
/// ```
/// use armlab::model_file::parse_model_text;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let urdf = r#"<robot name="two_link">
///   <link name="base"/> <link name="upper"/> <link name="fore"/>
///   <joint name="shoulder" type="revolute">
///     <parent link="base"/> <child link="upper"/>
///     <axis xyz="0 0 1"/> <limit lower="-3" upper="3" effort="1" velocity="1"/>
///   </joint>
///   <joint name="elbow" type="revolute">
///     <parent link="upper"/> <child link="fore"/>
///     <origin xyz="0.4 0 0"/>
///     <axis xyz="0 0 1"/> <limit lower="-3" upper="3" effort="1" velocity="1"/>
///   </joint>
/// </robot>"#;
/// let robot = parse_model_text("two_link.urdf", urdf)?;
/// assert_eq!(robot.dof(), 2);
/// // The tool sits at the last joint's frame: the elbow, 0.4 m along the upper arm.
/// let p = robot.fk(&[std::f64::consts::FRAC_PI_2, 0.3])?.translation.vector;
/// assert!(p.x.abs() < 1e-15 && (p.y - 0.4).abs() < 1e-15);
/// // Anything else is refused by name.
/// assert!(parse_model_text("two_link.txt", urdf).is_err());
/// # Ok(())
/// # }
/// ```
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
///
/// # Examples
///
/// ```
/// use armlab::model_file::{LoadError, load_model};
///
/// let stanford = load_model("stanford").expect("a built-in model");
/// assert_eq!(stanford.dof(), 6);
/// // Neither a built-in name nor a model file: the error lists the built-in names.
/// let err = load_model("stanfrod").unwrap_err();
/// assert!(matches!(err, LoadError::Unknown { .. }));
/// assert!(err.to_string().contains("stanford"));
/// ```
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
