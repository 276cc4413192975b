//! The scriptable command line: subcommands, their arguments, and dispatch. `main.rs` only
//! parses and reports errors; everything here returns typed errors.

mod animate;
pub mod calibrate;
mod class;
mod class_demo;
mod collisions;
mod exercise;
mod export;
mod figures;
mod fk;
mod ik;
mod info;
mod lesson;
mod place;
pub use crate::input;
mod reach;
mod reachability;
pub mod reachability_figures;
pub mod reference;
mod rotation;
mod self_motion;
mod symbolic;
pub use symbolic::rotation_to_json as symbolic_rotation_json;
pub use symbolic::to_json as symbolic_json;
mod view;

use crate::kinematics::{KinematicsError, Robot};
use clap::{Parser, Subcommand, ValueEnum};
use std::path::PathBuf;
use thiserror::Error;

/// armlab: robot-manipulator kinematics (Siciliano et al., chapter 2).
#[derive(Debug, Parser)]
#[command(name = "armlab", version, about, long_about = None)]
pub struct Cli {
    /// What to do; without one, the app on the default robot.
    #[command(subcommand)]
    pub command: Option<Command>,
    /// Folders searched for a URDF's `package://` meshes (before ROS_PACKAGE_PATH); repeat the
    /// flag for several.
    #[arg(long = "package-path", global = true, value_name = "DIR")]
    pub package_path: Vec<PathBuf>,
}

/// Output format of a subcommand.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum Format {
    /// Human-readable text.
    #[default]
    Text,
    /// JSON (shortest round-trip doubles).
    Json,
}

/// Minimal orientation representation to print.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum EulerArg {
    /// ZYZ Euler angles (2.18).
    Zyz,
    /// Roll-pitch-yaw (2.21).
    Rpy,
    /// ZXZ Euler angles (Problem 2.1).
    Zxz,
}

impl From<EulerArg> for crate::kinematics::EulerKind {
    fn from(e: EulerArg) -> Self {
        match e {
            EulerArg::Zyz => Self::Zyz,
            EulerArg::Rpy => Self::Rpy,
            EulerArg::Zxz => Self::Zxz,
        }
    }
}

/// Joint vectors: one of `--q`, `--q-deg`, `--config` or `--input`.
#[derive(Debug, Default, clap::Args)]
#[group(required = false, multiple = false)]
pub struct JointInput {
    /// Joint vector "q1,q2,..." in radians (revolute) and metres (prismatic).
    #[arg(long, allow_hyphen_values = true)]
    pub q: Option<String>,
    /// Joint vector with revolute joints in degrees (prismatic still in metres).
    #[arg(long, allow_hyphen_values = true)]
    pub q_deg: Option<String>,
    /// A named configuration of the model (e.g. zero, ready, figure).
    #[arg(long)]
    pub config: Option<String>,
    /// File with one joint vector per line (comma-separated, # comments); `-` for stdin.
    #[arg(long)]
    pub input: Option<PathBuf>,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Open the interactive app on a model (or render its window to PNG with --screenshot).
    View(view::ViewArgs),
    /// List the built-in models with their DOF and a line of description.
    Robots {
        /// Output format.
        #[arg(long, value_enum, default_value_t)]
        format: Format,
    },
    /// Describe a model: DH table, limits, configurations, and its pose, Jacobian rank and
    /// manipulability at one configuration.
    Info {
        /// Built-in name or path to a .toml / .urdf model (default: the anthropomorphic arm with
        /// spherical wrist).
        model: Option<String>,
        /// Joint vector to evaluate (default: the "ready" configuration).
        #[command(flatten)]
        joints: JointInput,
        /// Only this end-effector (a name, any link of a URDF, or an index; default: every one, the model-level
        /// lines about the tool of the longest arm).
        #[arg(long)]
        ee: Option<String>,
        /// Output format.
        #[arg(long, value_enum, default_value_t)]
        format: Format,
    },
    /// Direct kinematics: the end-effector pose of each joint vector, eq. (2.50).
    Fk {
        /// Built-in name or path to a .toml / .urdf model.
        model: String,
        /// Joint vectors.
        #[command(flatten)]
        joints: JointInput,
        /// Add every joint frame T_i^0.
        #[arg(long)]
        frames: bool,
        /// The end-effector whose pose is "T" (a name, any link of a URDF, or an index; default: the tool of the
        /// longest arm, end-effector 0).
        #[arg(long)]
        ee: Option<String>,
        /// Add the orientation phi in this representation.
        #[arg(long, value_enum)]
        euler: Option<EulerArg>,
        /// Output format.
        #[arg(long, value_enum, default_value_t)]
        format: Format,
    },
    /// Inverse kinematics: every closed-form solution with its posture (Sect. 2.12), or the
    /// numerical solver for arms without one.
    Ik(ik::IkArgs),
    /// Render a snapshot of the arm to PNG, headlessly, with the app's renderer.
    Render(figures::RenderArgs),
    /// Compute the workspace (Sect. 2.10.1) and draw it to PNG, headlessly.
    Workspace(figures::WorkspaceArgs),
    /// One of the excerpt's figures (Figs 2.29-2.33, Problem 2.17) to PNG, headlessly, with the
    /// textbook's labels.
    Figure(figures::FigureArgs),
    /// Which postures reach each point of a file, and its distance to the workspace boundary
    /// (positive inside, negative outside).
    Reach(reach::ReachArgs),
    /// The six-dimensional reachability map: at every voxel, approach direction and roll, which
    /// postures reach the pose within the joint limits (and free of collision with --scene),
    /// written as a NumPy .npz; Ctrl+C stops cleanly.
    Reachability(reachability::ReachabilityArgs),
    /// Base placement: where on the floor to put the arm's base so that it reaches a file of
    /// task poses. Every task is solved exactly by IK at every base position and yaw of a grid
    /// over the area; prints the best placements and each task's postures there, and draws the
    /// heat map (--out); Ctrl+C stops cleanly.
    Place(place::PlaceArgs),
    /// Exact self-motion of a redundant arm holding its hand still (Sect. 2.10.2): every branch
    /// over the free parameter, the feasible intervals inside the joint limits, the number of
    /// disjoint self-motion curves.
    SelfMotion(self_motion::SelfMotionArgs),
    /// Kinematic calibration (Sect. 2.11): estimate the DH parameters from measured poses (or a
    /// simulated robot), with what can and cannot be identified.
    Calibrate(Box<calibrate::CalibrateArgs>),
    /// A lesson (a TOML file of steps: robot, joints, target, view, overlays, caption) in the
    /// app with Previous and Next, or rendered to one PNG per step with --render DIR.
    Lesson(lesson::LessonArgs),
    /// Exercises checked automatically: sheets with figures and answer keys for a class
    /// (`new`), answers graded by equivalence with feedback in words (`check`), a class's
    /// folder of answers graded at once (`grade`).
    Exercise(exercise::ExerciseArgs),
    /// The direct kinematics in symbols, in the textbook's notation: each A_i^{i-1}, the
    /// product T_n^0 and, for an arm with a spherical wrist, the wrist point p_W (Sect. 2.9);
    /// or, with --rotation, the rotation matrix of Euler angles, RPY, angle and axis or a unit
    /// quaternion (Sects. 2.4-2.6).
    Symbolic(symbolic::SymbolicArgs),
    /// Write a model as URDF (same forward kinematics, limits, simple visuals) or as a TOML
    /// model file.
    Export(export::ExportArgs),
    /// One rotation in every representation of Sect. 2.4 (the matrix, ZYZ and ZXZ Euler angles,
    /// roll-pitch-yaw, angle and axis, the unit quaternion) with both Euler solutions and the
    /// singular cases in words, or a composition of elementary rotations about current and fixed
    /// axes, each partial product printed (Sect. 2.3).
    Rotation(rotation::RotationArgs),
    /// An animation to GIF or APNG: the self-motion, a morph through the postures, the DH
    /// build one elementary motion at a time, or a straight tool path with its joint rates.
    Animate(animate::AnimateArgs),
    /// What a configuration hits: the arm's own links and a scene's obstacles, each contact
    /// named with its depth, and the clearance; or (--matrix) the allowed-collision matrix
    /// sampled as MoveIt's Setup Assistant does, with every pair's verdict and why.
    Collisions(Box<collisions::CollisionsArgs>),
    /// The live classroom (`serve`; `demo` to rehearse alone): the teacher's arm on every
    /// student's screen, questions answered from the seats and graded on the server, everything
    /// kept in SQLite.
    Class(class::ClassArgs),
}

impl From<crate::model_file::LoadError> for CliError {
    fn from(e: crate::model_file::LoadError) -> Self {
        CliError::Model(Box::new(e))
    }
}

/// Everything a subcommand can report (all are bad input: the binary exits with code 2).
#[derive(Debug, Error)]
pub enum CliError {
    /// A model that cannot be loaded (boxed: its located errors are large).
    #[error(transparent)]
    Model(Box<crate::model_file::LoadError>),
    /// A bad joint vector or input file.
    #[error(transparent)]
    Input(#[from] input::InputError),
    /// Input the kinematics rejected.
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
    /// An unknown named configuration.
    #[error("model {model:?} has no configuration {name:?} (it has: {available})")]
    UnknownConfig {
        /// Model name.
        model: String,
        /// Name asked for.
        name: String,
        /// The names it has.
        available: String,
    },
    /// Several input options where one is allowed, or none where one is needed.
    #[error("{0}")]
    Usage(&'static str),
    /// A target that is not usable (e.g. a pose that is not rigid).
    #[error("{source_name}: {reason}")]
    BadTarget {
        /// Where the target came from.
        source_name: String,
        /// What is wrong.
        reason: String,
    },
    /// Invalid input the IK solver rejected.
    #[error("{source_name}: {source}")]
    Ik {
        /// Where the target came from.
        source_name: String,
        /// The solver's error.
        source: crate::kinematics::ik::IkError,
    },
    /// A figure `armlab figure` does not know.
    #[error("no figure {name:?} (the figures are: {available})")]
    UnknownFigure {
        /// Name asked.
        name: String,
        /// The figures.
        available: String,
    },
    /// An end-effector the robot does not have.
    #[error("no end-effector {name:?} (the robot has: {available})")]
    UnknownEndEffector {
        /// Name or index asked for.
        name: String,
        /// Names it has.
        available: String,
    },
    /// Making a figure failed (no GPU adapter, device error).
    #[error(transparent)]
    Figure(#[from] crate::figure::FigureError),
    /// The app could not run.
    #[error(transparent)]
    App(crate::app::AppError),
    /// Writing a PNG failed.
    #[error(transparent)]
    Headless(#[from] crate::headless::HeadlessError),
    /// A model the asked format cannot hold, or a file that cannot be written.
    #[error("{0}")]
    Export(String),
    /// A rotation or a sequence `armlab rotation` cannot read.
    #[error(transparent)]
    Rotation(#[from] rotation::RotationError),
    /// Writing the output failed.
    #[error("cannot write output: {0}")]
    Output(#[from] std::io::Error),
    /// A scene file, an SRDF or a configuration the collision checker cannot use (the message
    /// names the file, the line and the obstacle).
    #[error(transparent)]
    Collision(#[from] crate::collision::CollisionError),
    /// Bad options of a reachability map, or a map stopped by Ctrl+C.
    #[error(transparent)]
    Reachability(#[from] crate::reachability::ReachabilityError),
    /// A .npz map file that cannot be written or read.
    #[error(transparent)]
    Npz(#[from] crate::npz::NpzError),
    /// Bad options of a base placement (named by their flag), or a placement stopped by Ctrl+C.
    #[error("{flag}: {source}")]
    Placement {
        /// The flag(s) at fault.
        flag: &'static str,
        /// What is wrong.
        source: crate::reachability::PlacementError,
    },
    /// A task file of `armlab place` that cannot be read (the message names the line and the
    /// field).
    #[error(transparent)]
    Tasks(#[from] crate::reachability::TaskFileError),
    /// An input file (an SRDF) that cannot be read.
    #[error("cannot read {what}: {source} ({})", path.display())]
    ReadFile {
        /// What the file is, in words ("the SRDF file").
        what: &'static str,
        /// The file as given.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// Figure flags of `armlab reachability` that cannot be used.
    #[error(transparent)]
    MapFigures(#[from] reachability_figures::MapFigureFlagError),
    /// An output file that cannot be written.
    #[error("cannot write the file: {source} ({})", path.display())]
    WriteFile {
        /// The file as given.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A model a TOML model file cannot hold (it holds one serial DH table).
    #[error(
        "{model}: a TOML model file holds one serial DH table with one variable per joint; this \
         model is a tree, a closed chain, coupled, or given by URDF origins: write its matrix \
         with --write-srdf instead"
    )]
    NotSerialDh {
        /// The model as given.
        model: String,
    },
    /// The class server could not start (the address is taken, the data file cannot be
    /// opened) or stopped on an error.
    #[error(transparent)]
    ClassServer(#[from] crate::class_server::ServerError),
}

/// Loads a model for a command; what loading skipped (a mesh file that could not be read) is
/// said on stderr as a warning, the command goes on.
pub(crate) fn load_model(spec: &str) -> Result<Robot, CliError> {
    let robot = crate::model_file::load_model(spec)?;
    for w in &robot.load_warnings {
        eprintln!("armlab: warning: {w}");
    }
    Ok(robot)
}

/// The robot a one-arm command works on: with one end-effector the robot itself and the index
/// `spec` names; with several, the arm of end-effector `spec` (default: the tool of the longest
/// arm, end-effector 0) as a robot of its own ([`crate::kinematics::arm`]), its joints off the
/// chain at the "ready" configuration (or zero), and index 0.
pub(crate) fn arm_robot(mut robot: Robot, spec: Option<&str>) -> Result<(Robot, usize), CliError> {
    let ee = ik::end_effector(&mut robot, spec)?;
    if robot.end_effectors().len() == 1 {
        return Ok((robot, ee));
    }
    let q = robot.ready_or_zero();
    let arm = crate::kinematics::arm::arm_of(&robot, ee, &q).map_err(|e| CliError::BadTarget {
        source_name: format!("--ee {}", robot.end_effectors()[ee].name),
        reason: e.to_string(),
    })?;
    Ok((arm.robot, 0))
}

/// Runs the command line; output goes to `out`.
pub fn run(cli: Cli, out: &mut dyn std::io::Write) -> Result<(), CliError> {
    crate::urdf::set_package_paths(cli.package_path);
    match cli.command {
        None => view::run(&view::ViewArgs::default(), out),
        Some(Command::View(args)) => view::run(&args, out),
        Some(Command::Robots { format }) => info::robots(format, out),
        Some(Command::Info {
            model,
            joints,
            ee,
            format,
        }) => info::run(model.as_deref(), &joints, ee.as_deref(), format, out),
        Some(Command::Fk {
            model,
            joints,
            frames,
            ee,
            euler,
            format,
        }) => fk::run(
            &model,
            &joints,
            frames,
            ee.as_deref(),
            euler.map(Into::into),
            format,
            out,
        ),
        Some(Command::Workspace(args)) => figures::workspace(&args, out),
        Some(Command::Render(args)) => figures::render(&args, out),
        Some(Command::Figure(args)) => figures::figure(&args, out),
        Some(Command::Ik(args)) => ik::run(&args, out),
        Some(Command::Calibrate(args)) => calibrate::run(&args, out),
        Some(Command::Reach(args)) => reach::run(&args, out),
        Some(Command::Reachability(args)) => reachability::run(&args, out),
        Some(Command::Place(args)) => place::run(&args, out),
        Some(Command::SelfMotion(args)) => self_motion::run(&args, out),
        Some(Command::Export(args)) => export::run(&args, out),
        Some(Command::Symbolic(args)) => symbolic::run(&args, out),
        Some(Command::Exercise(args)) => exercise::run(&args, out),
        Some(Command::Lesson(args)) => lesson::run(&args, out),
        Some(Command::Animate(args)) => animate::run(&args, out),
        Some(Command::Rotation(args)) => rotation::run(&args, out),
        Some(Command::Collisions(args)) => collisions::run(&args, out),
        Some(Command::Class(args)) => class::run(&args, out),
    }
}

/// The joint vectors an input option asks for; `fallback` names a configuration used when no
/// option is given (None: an error).
pub(crate) fn joint_vectors(
    robot: &Robot,
    model: &str,
    j: &JointInput,
    fallback: Option<&str>,
) -> Result<Vec<Vec<f64>>, CliError> {
    let n = robot.dof();
    if let Some(text) = &j.q {
        return Ok(vec![input::parse_row(text, "--q", n, "joint values")?]);
    }
    if let Some(text) = &j.q_deg {
        let mut q = input::parse_row(text, "--q-deg", n, "joint values")?;
        for (k, v) in q.iter_mut().enumerate() {
            if robot.dof_joint(k).kind == crate::kinematics::JointKind::Revolute {
                *v = v.to_radians();
            }
        }
        return Ok(vec![q]);
    }
    if let Some(path) = &j.input {
        return Ok(input::read_rows(path, n, "joint values")?);
    }
    let name = match (&j.config, fallback) {
        (Some(c), _) => c.as_str(),
        (None, Some(f)) => f,
        (None, None) => {
            return Err(CliError::Usage(
                "give the joint values with --q, --q-deg, --config or --input",
            ));
        }
    };
    let q = robot.config(name).ok_or_else(|| CliError::UnknownConfig {
        model: model.into(),
        name: name.into(),
        available: robot
            .configurations
            .iter()
            .map(|c| c.name.as_str())
            .collect::<Vec<_>>()
            .join(", "),
    })?;
    Ok(vec![q.to_vec()])
}

/// A joint vector as the CLI shows it to people: degrees for revolute joints, metres for
/// prismatic ones.
fn q_for_display(robot: &Robot, q: &[f64]) -> Vec<f64> {
    q.iter()
        .enumerate()
        .map(|(k, &v)| {
            if robot.dof_joint(k).kind == crate::kinematics::JointKind::Revolute {
                v.to_degrees()
            } else {
                v
            }
        })
        .collect()
}

/// Parses a count flag: a whole number written plainly (`200000`, `200_000`) or in scientific
/// notation (`2e5`); ranges are checked by each command with the flag's name in the message.
pub fn count(text: &str) -> Result<usize, String> {
    let plain = text.trim().replace('_', "");
    if let Ok(n) = plain.parse::<usize>() {
        return Ok(n);
    }
    match plain.parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 0.0 && v.fract() == 0.0 && v < 1e18 => Ok(v as usize),
        Ok(v) if v.is_finite() && v >= 1e18 => Err(format!("{text} is far too many")),
        _ => Err(format!("{text:?} is not a whole number")),
    }
}
