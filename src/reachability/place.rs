//! Base placement (issue 49): where on the floor to put an arm's base so that it reaches a set
//! of task poses, every task solved exactly by IK at every base position and yaw (never looked
//! up in a map).
//!
//! # The placements
//!
//! The floor grid covers the area `[x0, x1] x [y0, y1]` (m, world frame) at `step`:
//! `x_i = x0 + i step` for `i = 0..=floor((x1 - x0) / step + 1e-9)`, and the same in y. The grid
//! starts at `x0`; it ends at `x1` when the width is a whole number of steps (to 1e-9 of a step),
//! otherwise at the last step before `x1`. The yaws are `2 pi k / yaws`, `k = 0..yaws`.
//!
//! At placement `(x, y, yaw)` the robot's base is moved to
//! `world_from_base' = Trans(x, y, 0) Rz(yaw) world_from_base`: the robot's own base transform
//! (a pedestal's height, a mounting rotation) stays under the shift. A task pose
//! `world_from_tool` is reached when the unmoved robot reaches
//! `(Trans(x, y, 0) Rz(yaw))^-1 world_from_tool`, which is solved once per task and placement.
//!
//! # The solver
//!
//! Arms with a closed form ([`ClosedForm::detect`]) get every solution of
//! [`ClosedForm::solve_raw`], each revolute angle wrapped into its limits
//! ([`wrap_into_limits`]) and the solution kept when the joint vector lies within the limits (to
//! [`LIMIT_TOL`]): exact at the task, up to the closed form's rounding. The parts of the pose a
//! closed form sets are in [`TaskMatch`] (a position-only arm ignores the task's orientation).
//! A near-miss arm (a URDF rounded off its family's structure) is solved on its ideal structure
//! here; the solutions of [`PlacementMap::best`] and [`Placer::evaluate`] are polished on the
//! exact model. Arms without a closed form get the numerical solver (Levenberg-Marquardt within
//! the limits) from [`PlacementOptions::seeds`] starts, a solution counting when both errors are
//! below [`NUMERICAL_TOLERANCE`]; [`PlacementMap::solver`] says which solver ran.
//!
//! # Collisions
//!
//! With a [`CollisionWorld`], a solution counts only when [`CollisionWorld::in_collision`] is
//! false for the moved robot (its links against each other and against the obstacles; the
//! obstacles fixed in the world stay where the scene puts them, those attached to a link move
//! with it). A placement whose base (the links that no joint moves, and the obstacles attached
//! to them) overlaps an obstacle fixed in the world is blocked: it reaches nothing. Contacts the
//! unmoved robot's base already has (the floor it stands on) are its mounting and do not block.
//!
//! # Postures and the ranking
//!
//! Each (placement, task) holds a bit mask of the postures that reach it, in the family's
//! posture order, as the reachability map sets them ([`super::ReachabilityMap::postures`]): for
//! a closed form one bit per combination of its labels' two-way parts (shoulder right/left, elbow
//! up/down, extension, wrist no flip/flip or up/down), a degenerate part setting both members of
//! its pair; for the numerical solver one bit per class of [`PostureClassifier::class_names`].
//! [`PlacementMap::posture_names`] names the bits. The placements are ranked by
//! 1. the number of tasks reached;
//! 2. the number of IK solutions reaching them, summed over the tasks (a robustness proxy: more
//!    postures to choose from at each task);
//! 3. the steady neighbours: how many of the placement's six grid neighbours (x +- step,
//!    y +- step, yaw +- one yaw step, cyclic) reach at least as many tasks (a margin for placing
//!    the base slightly off);
//! 4. the grid order (i, then j, then k), so that the ranking is deterministic.
//!
//! [`PlacementMap::best`] keeps at most one placement per base position (its best yaw), and only
//! placements that reach at least one task.

use super::map::{NUMERICAL_TOLERANCE, PostureBits};
use crate::collision::CollisionWorld;
use crate::input::InputError;
use crate::kinematics::ik::SolutionPosture;
use crate::kinematics::ik::Target;
use crate::kinematics::ik::closed_form::{
    ClosedForm, Family, LIMIT_TOL, MAX_DOF, RawSolutions, wrap_into_limits,
};
use crate::kinematics::ik::numerical::{self, NumericalOptions, TaskMask};
use crate::kinematics::orientation::rotation_from_rpy;
use crate::kinematics::pose::{NotRigid, pose_from_matrix, rot_z};
use crate::kinematics::{JointKind, KinematicsError, Pose, Robot};
use crate::workspace::{PostureClassifier, UNCLASSIFIED};
use nalgebra::{Matrix4, Vector3};
use rayon::prelude::*;
use serde::Serialize;
use std::f64::consts::TAU;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use thiserror::Error;

/// Most IK evaluations (base positions x yaws x tasks) a placement runs without
/// [`PlacementOptions::force`]: 1e9 (the masks alone take 2 bytes each, 2 GB).
pub const MAX_EVALUATIONS: u64 = 1_000_000_000;

/// Numerical solutions closer than this (rad or m, every joint) are the same solution.
const NUMERICAL_DUPLICATE: f64 = 1e-6;

/// A closed-form solution with a larger error (m or rad) is polished by Newton steps on the
/// exact model before it is reported.
const POLISH_ABOVE: f64 = 1e-12;

/// Bad input to a placement, found before any work; or a placement stopped by its cancel flag.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum PlacementError {
    /// An area side that is empty: its upper bound is not above its lower bound.
    #[error("empty area: {axis}1 = {to} m is not above {axis}0 = {from} m (area x0,x1,y0,y1)")]
    EmptyArea {
        /// "x" or "y".
        axis: &'static str,
        /// The lower bound (m).
        from: f64,
        /// The upper bound (m).
        to: f64,
    },
    /// An area bound that is not a finite number.
    #[error("the area x0,x1,y0,y1 = {area:?} has a bound that is not a finite number (m)")]
    NonFiniteArea {
        /// The area as given (m).
        area: [f64; 4],
    },
    /// A grid step that is zero, negative or not finite.
    #[error("the step must be a positive length (m), got {step}")]
    BadStep {
        /// The step as given (m).
        step: f64,
    },
    /// No yaw angle.
    #[error("yaws must be at least 1 (the yaw angles are 2 pi k / yaws)")]
    NoYaws,
    /// No task pose.
    #[error("no task poses: give at least one")]
    NoTasks,
    /// More evaluations than [`MAX_EVALUATIONS`] without [`PlacementOptions::force`].
    #[error(
        "{positions} base positions x {yaws} yaws x {tasks} tasks = {evaluations:.3e} IK \
         evaluations, over the limit of {limit:.0e} (2 bytes of masks each): coarsen the step, \
         shrink the area, use fewer yaws, or force it"
    )]
    TooManyEvaluations {
        /// Base positions of the grid.
        positions: f64,
        /// Yaw angles.
        yaws: usize,
        /// Task poses.
        tasks: usize,
        /// Their product.
        evaluations: f64,
        /// The limit.
        limit: f64,
    },
    /// A robot with several end-effectors: its arm to one of them is placed
    /// ([`crate::kinematics::arm::arm_of`]).
    #[error(
        "the robot has {count} end-effectors: place the arm of one of them (its chain as a \
         robot of its own)"
    )]
    SeveralEndEffectors {
        /// How many it has.
        count: usize,
    },
    /// The cancel flag was raised: the placement stopped after `done` of `total` base positions.
    #[error("cancelled after {done} of {total} base positions")]
    Cancelled {
        /// Base positions done.
        done: usize,
        /// Base positions in the grid.
        total: usize,
    },
    /// The robot's kinematics rejected a configuration (a collision world for another robot).
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
}

/// A task file (poses people write by hand) that cannot be read; every message names the
/// source, its line and the field.
#[derive(Debug, Error)]
pub enum TaskFileError {
    /// A field that is not a finite number ([`InputError::NotANumber`]; the field number counts
    /// the name column).
    #[error(transparent)]
    Number(#[from] InputError),
    /// A data row with a wrong number of fields.
    #[error("{source_name}: expected {expected}, got {got} field(s)")]
    FieldCount {
        /// `file:line`.
        source_name: String,
        /// What the row needs, in words.
        expected: &'static str,
        /// Fields found.
        got: usize,
    },
    /// A header column that is not what the format allows.
    #[error(
        "{source_name}: read as a header (its first field is not a number): column {column} is \
         {found:?}, expected {expected}"
    )]
    Header {
        /// `file:line`.
        source_name: String,
        /// 1-based column.
        column: usize,
        /// The column's text.
        found: String,
        /// What it may be, in words.
        expected: &'static str,
    },
    /// A header with a wrong number of columns.
    #[error(
        "{source_name}: a header has [name,] x, y, z, roll_deg, pitch_deg, yaw_deg (6 columns) \
         or [name,] 16 columns of a row-major 4x4 pose; this one has {got} column(s)"
    )]
    HeaderCount {
        /// `file:line`.
        source_name: String,
        /// Columns found (the name column counted).
        got: usize,
    },
    /// A 4x4 pose that is not a rigid transform.
    #[error("{source_name}: the 4x4 pose is not rigid: {problem}")]
    NotRigid {
        /// `file:line`.
        source_name: String,
        /// Why.
        problem: NotRigid,
    },
    /// A named row whose name is empty.
    #[error("{source_name}: field 1 (the name) is empty")]
    EmptyName {
        /// `file:line`.
        source_name: String,
    },
    /// No task in the file.
    #[error("{source_name}: no task poses (blank lines, # comments and a header only)")]
    NoTasks {
        /// The file.
        source_name: String,
    },
}

/// One task pose of a placement.
#[derive(Debug, Clone, PartialEq)]
pub struct PlacementTask {
    /// Its name: the file's `name` column, else its 1-based number in the file.
    pub name: String,
    /// The pose the tool must reach, `world_from_tool` (world frame, m).
    pub world_from_tool: Pose,
    /// The 1-based line of the task file it came from (0: not from a file).
    pub line: usize,
}

impl PlacementTask {
    /// A task at `world_from_tool` (world frame, m), named `name`, not from a file.
    pub fn new(name: impl Into<String>, world_from_tool: Pose) -> Self {
        Self {
            name: name.into(),
            world_from_tool,
            line: 0,
        }
    }
}

/// The six columns of the position-and-angles layout, in order.
pub const TASK_COLUMNS: [&str; 6] = ["x", "y", "z", "roll_deg", "pitch_deg", "yaw_deg"];

/// How the rows of a task file are laid out (from its header, or each row's field count).
#[derive(Debug, Clone, Copy)]
struct Layout {
    /// The first field is the task's name.
    named: bool,
    /// 6 or 16 numbers per row; `None`: either (no header).
    numbers: Option<usize>,
}

/// Parses a task file's text (read by the caller); `source_name` names it in errors.
///
/// The format: one task per line, fields separated by commas (or by whitespace alone), `#`
/// starts a comment, blank lines are skipped. An optional header line (the first line whose
/// first field is not a number) names the columns:
/// - `x, y, z, roll_deg, pitch_deg, yaw_deg`: the tool's position (m, world frame) and its
///   orientation as fixed-axis roll-pitch-yaw in **degrees**, as in URDF:
///   `R = Rz(yaw) Ry(pitch) Rx(roll)`;
/// - 16 columns (any names, e.g. `t00 .. t33`): the row-major 4x4 `world_from_tool` (m), as
///   `armlab ik --pose` takes it; a rotation within 1e-5 of orthonormal is re-orthonormalised,
///   a worse one is an error;
/// - either, with a first column `name`: each row starts with the task's name.
///
/// Without a header each row holds 6 or 16 numbers (mixed rows are fine) and the tasks are named
/// by their number, 1-based. A file without tasks is an error.
///
/// # Examples
///
/// ```
/// use armlab::reachability::parse_tasks;
///
/// let text = "# shelf picks\nname, x, y, z, roll_deg, pitch_deg, yaw_deg\n\
///             top, 0.5, 0.1, 0.4, 180, 0, 90\nlow, 0.5, -0.1, 0.1, 180, 0, 0\n";
/// let tasks = parse_tasks(text, "poses.csv").expect("two tasks");
/// assert_eq!(tasks.len(), 2);
/// assert_eq!((tasks[0].name.as_str(), tasks[0].line), ("top", 3));
/// // roll 180 deg: the tool's z axis points down.
/// let z = tasks[0].world_from_tool.rotation.matrix().column(2).into_owned();
/// assert!((z.z + 1.0).abs() < 1e-12);
///
/// let bad = parse_tasks("1, 2, 3, 4, 5\n", "poses.csv").unwrap_err();
/// assert!(bad.to_string().starts_with("poses.csv:1: expected 6 numbers"));
/// ```
pub fn parse_tasks(text: &str, source_name: &str) -> Result<Vec<PlacementTask>, TaskFileError> {
    let mut layout: Option<Layout> = None;
    let mut tasks = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let data = line.split('#').next().unwrap_or("").trim();
        if data.is_empty() {
            continue;
        }
        let src = format!("{source_name}:{}", n + 1);
        let fields = split_fields(data);
        let first_is_number = fields[0].parse::<f64>().is_ok();
        let l = match layout {
            None if !first_is_number => {
                layout = Some(header_layout(&fields, &src)?);
                continue;
            }
            None => *layout.insert(Layout {
                named: false,
                numbers: None,
            }),
            Some(l) => l,
        };
        let number = tasks.len() + 1;
        tasks.push(task_row(&fields, l, &src, number, n + 1)?);
    }
    if tasks.is_empty() {
        return Err(TaskFileError::NoTasks {
            source_name: source_name.into(),
        });
    }
    Ok(tasks)
}

/// The fields of a row: comma-separated when it has a comma, else whitespace-separated.
fn split_fields(data: &str) -> Vec<&str> {
    if data.contains(',') {
        data.split(',').map(str::trim).collect()
    } else {
        data.split_whitespace().collect()
    }
}

/// The layout a header line declares.
fn header_layout(fields: &[&str], src: &str) -> Result<Layout, TaskFileError> {
    let lower: Vec<String> = fields.iter().map(|f| f.to_ascii_lowercase()).collect();
    let named = lower[0] == "name";
    let columns = &lower[usize::from(named)..];
    match columns.len() {
        16 => Ok(Layout {
            named,
            numbers: Some(16),
        }),
        6 => {
            for (k, (c, want)) in columns.iter().zip(TASK_COLUMNS).enumerate() {
                if c != want {
                    let expected = match want {
                        "roll_deg" | "pitch_deg" | "yaw_deg" => {
                            "roll_deg, pitch_deg, yaw_deg in this order (the angles are in \
                             degrees, and the header says so)"
                        }
                        _ if k == 0 && !named => "name or x",
                        _ => "x, y, z in this order (m)",
                    };
                    return Err(TaskFileError::Header {
                        source_name: src.into(),
                        column: k + 1 + usize::from(named),
                        found: fields[k + usize::from(named)].into(),
                        expected,
                    });
                }
            }
            Ok(Layout {
                named,
                numbers: Some(6),
            })
        }
        _ if !named && lower[0] != "x" => Err(TaskFileError::Header {
            source_name: src.into(),
            column: 1,
            found: fields[0].into(),
            expected: "name or x (or a number: a data row)",
        }),
        _ => Err(TaskFileError::HeaderCount {
            source_name: src.into(),
            got: fields.len(),
        }),
    }
}

/// One data row as a task.
fn task_row(
    fields: &[&str],
    layout: Layout,
    src: &str,
    number: usize,
    line: usize,
) -> Result<PlacementTask, TaskFileError> {
    let skip = usize::from(layout.named);
    let expected = match (layout.named, layout.numbers) {
        (false, None) => {
            "6 numbers (x, y, z in m, roll_deg, pitch_deg, yaw_deg) or 16 (a row-major 4x4 pose)"
        }
        (false, Some(6)) => "6 numbers (x, y, z in m, roll_deg, pitch_deg, yaw_deg)",
        (false, Some(_)) => "16 numbers (a row-major 4x4 pose)",
        (true, Some(6)) => "a name and 6 numbers (x, y, z in m, roll_deg, pitch_deg, yaw_deg)",
        (true, _) => "a name and 16 numbers (a row-major 4x4 pose)",
    };
    let count = fields.len().saturating_sub(skip);
    let count_ok = match layout.numbers {
        Some(k) => count == k,
        None => count == 6 || count == 16,
    };
    let mut values = Vec::with_capacity(count);
    for (i, f) in fields.iter().enumerate().skip(skip) {
        match f.parse::<f64>() {
            Ok(v) if v.is_finite() => values.push(v),
            _ if i < skip + 16 => {
                return Err(TaskFileError::Number(InputError::NotANumber {
                    source_name: src.into(),
                    field: i + 1,
                    text: f.chars().take(40).collect(),
                }));
            }
            _ => break,
        }
    }
    if !count_ok {
        return Err(TaskFileError::FieldCount {
            source_name: src.into(),
            expected,
            got: fields.len(),
        });
    }
    let name = if layout.named {
        if fields[0].is_empty() {
            return Err(TaskFileError::EmptyName {
                source_name: src.into(),
            });
        }
        fields[0].to_string()
    } else {
        number.to_string()
    };
    let world_from_tool = if values.len() == 6 {
        let [x, y, z, roll, pitch, yaw] = std::array::from_fn(|k| values[k]);
        let r = rotation_from_rpy(&Vector3::new(
            yaw.to_radians(),
            pitch.to_radians(),
            roll.to_radians(),
        ));
        Pose::from_parts(nalgebra::Translation3::new(x, y, z), r)
    } else {
        pose_from_matrix(&Matrix4::from_row_slice(&values)).map_err(|problem| {
            TaskFileError::NotRigid {
                source_name: src.into(),
                problem,
            }
        })?
    };
    Ok(PlacementTask {
        name,
        world_from_tool,
        line,
    })
}

/// What a placement computes, and how finely.
#[derive(Debug, Clone, PartialEq)]
pub struct PlacementOptions {
    /// The floor area searched, `[x0, x1, y0, y1]` (m, world frame): the base positions' range.
    /// A larger area costs proportionally more.
    pub area: [f64; 4],
    /// The grid step (m). Halving it costs four times as much.
    pub step: f64,
    /// Number of yaw angles `2 pi k / yaws` (the base's rotation about the world z axis). Cost is
    /// proportional.
    pub yaws: usize,
    /// How many placements [`PlacementMap::best`] keeps (one per base position).
    pub best: usize,
    /// Run more than [`MAX_EVALUATIONS`] evaluations.
    pub force: bool,
    /// Starts of the numerical solver for arms without a closed form: the robot's "ready"
    /// configuration (or zero) and `seeds - 1` spread over the limits. More find more solutions
    /// at proportional cost; ignored by closed forms.
    pub seeds: usize,
}

impl Default for PlacementOptions {
    /// A 2 m x 2 m floor around the origin at 5 cm, 36 yaws (10 degrees), 5 best, 8 seeds.
    fn default() -> Self {
        Self {
            area: [-1.0, 1.0, -1.0, 1.0],
            step: 0.05,
            yaws: 36,
            best: 5,
            force: false,
            seeds: 8,
        }
    }
}

/// The base positions and yaws of a placement.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlacementGrid {
    /// Base x positions (m, world frame), increasing.
    pub x: Vec<f64>,
    /// Base y positions (m, world frame), increasing.
    pub y: Vec<f64>,
    /// Yaw angles of the base about the world z axis (rad), `2 pi k / yaws`.
    pub yaw: Vec<f64>,
    /// The step of x and y (m).
    pub step: f64,
}

impl PlacementGrid {
    /// The grid of `options` for `tasks` task poses (see the module documentation), or why the
    /// options are bad (checked before anything is allocated).
    pub fn new(options: &PlacementOptions, tasks: usize) -> Result<Self, PlacementError> {
        let [x0, x1, y0, y1] = options.area;
        if options.area.iter().any(|v| !v.is_finite()) {
            return Err(PlacementError::NonFiniteArea { area: options.area });
        }
        for (axis, from, to) in [("x", x0, x1), ("y", y0, y1)] {
            if to <= from {
                return Err(PlacementError::EmptyArea { axis, from, to });
            }
        }
        let step = options.step;
        if !(step > 0.0 && step.is_finite()) {
            return Err(PlacementError::BadStep { step });
        }
        if options.yaws == 0 {
            return Err(PlacementError::NoYaws);
        }
        if tasks == 0 {
            return Err(PlacementError::NoTasks);
        }
        let count = |w: f64| (w / step + 1e-9).floor() + 1.0;
        let (nx, ny) = (count(x1 - x0), count(y1 - y0));
        let positions = nx * ny;
        let evaluations = positions * options.yaws as f64 * tasks as f64;
        if evaluations > MAX_EVALUATIONS as f64 && !options.force {
            return Err(PlacementError::TooManyEvaluations {
                positions,
                yaws: options.yaws,
                tasks,
                evaluations,
                limit: MAX_EVALUATIONS as f64,
            });
        }
        let axis = |from: f64, n: f64| (0..n as usize).map(|i| from + i as f64 * step).collect();
        Ok(Self {
            x: axis(x0, nx),
            y: axis(y0, ny),
            yaw: (0..options.yaws)
                .map(|k| TAU * k as f64 / options.yaws as f64)
                .collect(),
            step,
        })
    }

    /// Number of base positions (x times y).
    pub fn positions(&self) -> usize {
        self.x.len() * self.y.len()
    }

    /// Number of placements (positions times yaws).
    pub fn placements(&self) -> usize {
        self.positions() * self.yaw.len()
    }

    /// The index of placement `(i, j, k)` (x, y, yaw indices): `(i ny + j) nyaw + k`.
    pub fn index(&self, i: usize, j: usize, k: usize) -> usize {
        (i * self.y.len() + j) * self.yaw.len() + k
    }

    /// The placement indices `(i, j, k)` of index `p` ([`Self::index`] inverted).
    pub fn ijk(&self, p: usize) -> [usize; 3] {
        let nk = self.yaw.len();
        let ny = self.y.len();
        [p / nk / ny, (p / nk) % ny, p % nk]
    }

    /// The shift of placement `(i, j, k)`: `Trans(x_i, y_j, 0) Rz(yaw_k)`, which moves the base
    /// to `world_from_base' = shift world_from_base`.
    pub fn shift(&self, i: usize, j: usize, k: usize) -> Pose {
        floor_shift(self.x[i], self.y[j], self.yaw[k])
    }
}

/// `Trans(x, y, 0) Rz(yaw)` (m, rad, world frame): the shift a base placement applies on the left
/// of the robot's `world_from_base`.
pub fn floor_shift(x: f64, y: f64, yaw: f64) -> Pose {
    Pose::translation(x, y, 0.0) * rot_z(yaw)
}

/// Which solver a placement ran.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum PlacementSolver {
    /// The closed form ([`ClosedForm::describe`]: the family, and for a near miss how near).
    ClosedForm {
        /// The family in words.
        family: String,
    },
    /// Levenberg-Marquardt within the limits from several starts.
    Numerical {
        /// Starts per task and placement.
        seeds: usize,
        /// Position (m) and orientation (rad) tolerance of a solution.
        tolerance: f64,
    },
}

impl std::fmt::Display for PlacementSolver {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PlacementSolver::ClosedForm { family } => write!(f, "closed form ({family})"),
            PlacementSolver::Numerical { seeds, tolerance } => write!(
                f,
                "numerical (Levenberg-Marquardt from {seeds} starts, tolerance {tolerance:e})"
            ),
        }
    }
}

/// The parts of a task pose the solver sets (an arm with fewer than six joints cannot set all).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TaskMatch {
    /// Position and orientation.
    Pose,
    /// The position only (positioning arms: two-link planar, anthropomorphic, spherical,
    /// cylindrical, Cartesian).
    Position,
    /// The position in the arm's plane and the angle about its normal (three-link planar arm).
    PlanarPose,
    /// The position and the rotation about the vertical (SCARA).
    PositionAndRotationZ,
    /// The orientation only (a spherical wrist alone).
    Orientation,
}

impl TaskMatch {
    /// What a closed-form family sets.
    fn of_family(family: &Family) -> Self {
        match family {
            Family::Planar2
            | Family::Anthropomorphic
            | Family::SphericalArm
            | Family::Cylindrical
            | Family::Cartesian => TaskMatch::Position,
            Family::Planar3 => TaskMatch::PlanarPose,
            Family::Scara => TaskMatch::PositionAndRotationZ,
            Family::SphericalWrist => TaskMatch::Orientation,
            _ => TaskMatch::Pose,
        }
    }

    /// The IK target of a task pose in the unmoved robot's world.
    fn target(self, pose: &Pose) -> Target {
        match self {
            TaskMatch::Position => Target::Position(pose.translation.vector),
            _ => Target::Pose(*pose),
        }
    }
}

/// One IK solution at a placement.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlacedSolution {
    /// The joint vector (rad or m), within the limits.
    pub q: Vec<f64>,
    /// The closed form's posture of the solution (or the numerical solver's).
    pub posture: SolutionPosture,
    /// Bit k set when the solution is in posture class k ([`PlacementMap::posture_names`]).
    pub classes: u16,
    /// Position error of the tool at `q` on the moved robot (m).
    pub position_error: f64,
    /// Orientation error (rad; 0 for a position-only arm).
    pub orientation_error: f64,
}

/// What reaches one task at one placement.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TaskReach {
    /// Bit k set when posture class k reaches the task.
    pub mask: u16,
    /// Every solution reaching it (within the limits, collision free), closed-form order.
    pub solutions: Vec<PlacedSolution>,
}

/// Everything at one placement: each task's solutions.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlacementDetail {
    /// Base x (m, world frame).
    pub x: f64,
    /// Base y (m, world frame).
    pub y: f64,
    /// Base yaw about the world z axis (rad).
    pub yaw: f64,
    /// The base's contacts with obstacles fixed in the world (fixed body, obstacle): when there
    /// are any the placement is blocked and reaches nothing.
    pub base_contacts: Vec<(String, String)>,
    /// One entry per task, in the tasks' order.
    pub tasks: Vec<TaskReach>,
}

impl PlacementDetail {
    /// Number of tasks reached.
    pub fn reached(&self) -> usize {
        self.tasks.iter().filter(|t| t.mask != 0).count()
    }
}

/// One of the best placements.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BestPlacement {
    /// Grid indices `[i, j, k]` (x, y, yaw).
    pub index: [usize; 3],
    /// Tasks reached.
    pub reached: usize,
    /// Fraction of the tasks reached (0 to 1).
    pub fraction: f64,
    /// IK solutions reaching the tasks, summed over the tasks.
    pub solutions: u32,
    /// Grid neighbours (of 6) that reach at least as many tasks.
    pub steady: u8,
    /// Each task's solutions there, polished.
    pub detail: PlacementDetail,
}

/// The result of a placement: every (placement, task) posture mask, each placement's counts,
/// and the best placements with each task's solutions.
#[derive(Debug, Clone, PartialEq)]
pub struct PlacementMap {
    /// Base positions and yaws.
    pub grid: PlacementGrid,
    /// The tasks, in order.
    pub tasks: Vec<PlacementTask>,
    /// The names of the posture bits, in bit order (see the module documentation).
    pub posture_names: Vec<String>,
    /// Which solver ran.
    pub solver: PlacementSolver,
    /// The parts of each task pose the solver sets.
    pub task_match: TaskMatch,
    /// Whether solutions were checked for collisions.
    pub collisions: bool,
    /// Posture masks, index `grid.index(i, j, k) * tasks + t`.
    pub masks: Vec<u16>,
    /// Tasks reached per placement (index [`PlacementGrid::index`]).
    pub reached: Vec<u32>,
    /// IK solutions reaching the tasks per placement, summed over the tasks.
    pub solutions: Vec<u32>,
    /// Placements whose base hits an obstacle fixed in the world (they reach nothing).
    pub blocked: Vec<bool>,
    /// The best placements, best first (see the module documentation).
    pub best: Vec<BestPlacement>,
}

impl PlacementMap {
    /// The posture mask of task `t` at placement `(i, j, k)`.
    pub fn mask(&self, i: usize, j: usize, k: usize, t: usize) -> u16 {
        self.masks[self.grid.index(i, j, k) * self.tasks.len() + t]
    }

    /// The fraction of the tasks reached at placement `(i, j, k)` (0 to 1).
    pub fn fraction(&self, i: usize, j: usize, k: usize) -> f64 {
        self.reached[self.grid.index(i, j, k)] as f64 / self.tasks.len() as f64
    }

    /// At base position `(i, j)`: the best fraction over the yaws and the yaw index giving it
    /// (ranked as the placements are: tasks, then solutions, then the lowest k).
    pub fn best_yaw(&self, i: usize, j: usize) -> (f64, usize) {
        let k = (0..self.grid.yaw.len())
            .max_by_key(|&k| {
                let p = self.grid.index(i, j, k);
                (self.reached[p], self.solutions[p], std::cmp::Reverse(k))
            })
            .unwrap_or(0);
        (self.fraction(i, j, k), k)
    }

    /// The heat map: per base position the best fraction over the yaws, index `i ny + j`.
    pub fn heat(&self) -> Vec<f64> {
        let ny = self.grid.y.len();
        (0..self.grid.positions())
            .map(|p| self.best_yaw(p / ny, p % ny).0)
            .collect()
    }

    /// The names of the posture classes set in `mask`.
    pub fn names_of(&self, mask: u16) -> Vec<&str> {
        (self.posture_names.iter().enumerate())
            .filter(|(k, _)| mask >> k & 1 == 1)
            .map(|(_, n)| n.as_str())
            .collect()
    }
}

/// How tasks are solved: the closed form, or the numerical solver from several starts.
#[derive(Debug, Clone)]
enum Engine {
    Closed {
        cf: Box<ClosedForm>,
        bits: PostureBits,
    },
    Numerical {
        opts: NumericalOptions,
        seeds: Vec<Vec<f64>>,
        classifier: PostureClassifier,
    },
}

/// Evaluates placements of one robot for a set of tasks (what [`place()`] runs at every grid
/// point); [`Placer::evaluate`] gives every solution at any one placement.
#[derive(Debug, Clone)]
pub struct Placer<'a> {
    robot: &'a Robot,
    tasks: &'a [PlacementTask],
    world: Option<&'a CollisionWorld>,
    engine: Engine,
    limits: Vec<[f64; 2]>,
    revolute: Vec<bool>,
    task_match: TaskMatch,
    /// The unmoved base's contacts with world obstacles: its mounting.
    mounting: Vec<(String, String)>,
}

/// A solution found by the engines: its classes, q, and posture.
type Visit<'v> = dyn FnMut(u16, &[f64], SolutionPosture) + 'v;

impl<'a> Placer<'a> {
    /// A placer of `robot` (one end-effector) for `tasks`, checking collisions in `world` (built
    /// for this robot) when given; `seeds` starts for the numerical solver.
    pub fn new(
        robot: &'a Robot,
        tasks: &'a [PlacementTask],
        world: Option<&'a CollisionWorld>,
        seeds: usize,
    ) -> Result<Self, PlacementError> {
        if robot.end_effectors().len() != 1 {
            return Err(PlacementError::SeveralEndEffectors {
                count: robot.end_effectors().len(),
            });
        }
        if tasks.is_empty() {
            return Err(PlacementError::NoTasks);
        }
        let (engine, task_match) = match ClosedForm::detect(robot) {
            Ok(cf) if cf.dof() == robot.dof() && robot.dof() <= MAX_DOF => {
                let m = TaskMatch::of_family(cf.family());
                let bits = PostureBits::of(robot, &cf);
                let cf = Box::new(cf);
                (Engine::Closed { cf, bits }, m)
            }
            _ => numerical_engine(robot, seeds),
        };
        let mounting = match world {
            Some(w) => w.base_contacts(robot)?,
            None => Vec::new(),
        };
        Ok(Self {
            robot,
            tasks,
            world,
            engine,
            limits: robot.limits(),
            revolute: (0..robot.dof())
                .map(|k| robot.dof_joint(k).kind == JointKind::Revolute)
                .collect(),
            task_match,
            mounting,
        })
    }

    /// Which solver runs.
    pub fn solver(&self) -> PlacementSolver {
        match &self.engine {
            Engine::Closed { cf, .. } => PlacementSolver::ClosedForm {
                family: cf.describe(),
            },
            Engine::Numerical { seeds, opts, .. } => PlacementSolver::Numerical {
                seeds: seeds.len(),
                tolerance: opts.tolerance,
            },
        }
    }

    /// The parts of a task pose the solver sets.
    pub fn task_match(&self) -> TaskMatch {
        self.task_match
    }

    /// The names of the posture bits, in bit order.
    pub fn posture_names(&self) -> &[String] {
        match &self.engine {
            Engine::Closed { bits, .. } => bits.names(),
            Engine::Numerical { classifier, .. } => classifier.class_names(),
        }
    }

    /// Moves the robot in `scratch` (a clone made on first use) by `shift`, for the collision
    /// checks; without a world `scratch` stays `None`.
    fn moved(&self, shift: &Pose, scratch: &mut Option<Robot>) {
        if self.world.is_some() {
            let r = scratch.get_or_insert_with(|| self.robot.clone());
            r.base = shift * self.robot.base;
        }
    }

    /// The base's contacts at `moved` that are not its mounting.
    fn blocking(&self, moved: &Robot) -> Vec<(String, String)> {
        let Some(w) = self.world else {
            return Vec::new();
        };
        match w.base_contacts(moved) {
            Ok(c) => c
                .into_iter()
                .filter(|p| !self.mounting.contains(p))
                .collect(),
            Err(_) => vec![("base".into(), "?".into())],
        }
    }

    /// Calls `visit` for every solution of task `t` at `shift` (moved robot `moved` for the
    /// collision checks) within the limits and free of collision.
    fn solve_task(
        &self,
        shift_inv: &Pose,
        t: usize,
        moved: Option<&Robot>,
        raw: &mut RawSolutions,
        visit: &mut Visit<'_>,
    ) {
        let target = shift_inv * self.tasks[t].world_from_tool;
        let free = |q: &[f64]| match (self.world, moved) {
            (Some(w), Some(m)) => !w.in_collision(m, q).unwrap_or(true),
            _ => true,
        };
        match &self.engine {
            Engine::Closed { cf, bits } => {
                if cf.solve_raw(&target, raw).is_err() {
                    return;
                }
                let n = self.limits.len();
                let mut q = [0.0; MAX_DOF];
                for k in 0..raw.len {
                    if self.valid(&raw.q[k], &mut q) && free(&q[..n]) {
                        let p = raw.postures[k];
                        visit(bits.mask(&p), &q[..n], SolutionPosture::ClosedForm(p));
                    }
                }
            }
            Engine::Numerical {
                opts,
                seeds,
                classifier,
            } => {
                let free: &dyn Fn(&[f64]) -> bool = &free;
                self.solve_numerical(&target, (opts, seeds, classifier), free, visit);
            }
        }
    }

    /// The numerical engine at one target: each converged start within the limits, once.
    fn solve_numerical(
        &self,
        target: &Pose,
        (opts, seeds, classifier): (&NumericalOptions, &[Vec<f64>], &PostureClassifier),
        free: &dyn Fn(&[f64]) -> bool,
        visit: &mut Visit<'_>,
    ) {
        let goal = self.task_match.target(target);
        let mut found: Vec<Vec<f64>> = Vec::new();
        for seed in seeds {
            let Ok(rep) = numerical::solve(self.robot, 0, &goal, seed, opts) else {
                continue;
            };
            let same = |a: &Vec<f64>| {
                a.iter()
                    .zip(&rep.q)
                    .all(|(x, y)| (x - y).abs() < NUMERICAL_DUPLICATE)
            };
            if !rep.converged
                || !self.robot.within_limits(&rep.q, LIMIT_TOL)
                || found.iter().any(same)
                || !free(&rep.q)
            {
                continue;
            }
            let classes = match self.robot.fk(&rep.q) {
                Ok(t) => match classifier.classify(&rep.q, &t) {
                    UNCLASSIFIED => (1u16 << classifier.class_count()) - 1,
                    c => 1 << c,
                },
                Err(_) => continue,
            };
            visit(
                classes,
                &rep.q,
                SolutionPosture::Numerical { converged: true },
            );
            found.push(rep.q);
        }
    }

    /// Wraps a raw solution into the limits (revolute joints, modulo 2 pi) and checks them.
    #[inline]
    fn valid(&self, raw: &[f64; MAX_DOF], q: &mut [f64; MAX_DOF]) -> bool {
        let n = self.limits.len();
        for k in 0..n {
            if !raw[k].is_finite() {
                return false;
            }
            q[k] = if self.revolute[k] {
                wrap_into_limits(raw[k], self.limits[k])
            } else {
                raw[k]
            };
        }
        self.robot.within_limits(&q[..n], LIMIT_TOL)
    }

    /// The masks of every task at one placement into `masks` (one per task), with the tasks
    /// reached, the solutions counted and whether the base is blocked.
    fn fill(
        &self,
        shift: &Pose,
        masks: &mut [u16],
        scratch: &mut (Option<Robot>, RawSolutions),
    ) -> (u32, u32, bool) {
        let (robot, raw) = scratch;
        self.moved(shift, robot);
        let moved = robot.as_ref();
        if let Some(m) = moved
            && !self.blocking(m).is_empty()
        {
            masks.fill(0);
            return (0, 0, true);
        }
        let shift_inv = shift.inverse();
        let (mut reached, mut count) = (0, 0);
        for (t, out) in masks.iter_mut().enumerate() {
            let mut mask = 0u16;
            self.solve_task(&shift_inv, t, moved, raw, &mut |c, _, _| {
                mask |= c;
                count += 1;
            });
            *out = mask;
            reached += u32::from(mask != 0);
        }
        (reached, count, false)
    }

    /// Every solution of every task at placement `(x, y, yaw)` (m, m, rad): the same masks as
    /// [`place()`] computes there, each solution polished on the exact model when its error
    /// exceeds 1e-12 (near singularities, or a near-miss arm) and its errors measured.
    pub fn evaluate(&self, x: f64, y: f64, yaw: f64) -> PlacementDetail {
        let shift = floor_shift(x, y, yaw);
        let mut robot = None;
        self.moved(&shift, &mut robot);
        let moved = robot.as_ref();
        let mut detail = PlacementDetail {
            x,
            y,
            yaw,
            base_contacts: moved.map(|m| self.blocking(m)).unwrap_or_default(),
            tasks: Vec::with_capacity(self.tasks.len()),
        };
        let shift_inv = shift.inverse();
        let mut raw = RawSolutions::default();
        for t in 0..self.tasks.len() {
            let mut reach = TaskReach {
                mask: 0,
                solutions: Vec::new(),
            };
            if detail.base_contacts.is_empty() {
                self.solve_task(&shift_inv, t, moved, &mut raw, &mut |c, q, posture| {
                    reach.mask |= c;
                    reach.solutions.push(PlacedSolution {
                        q: q.to_vec(),
                        posture,
                        classes: c,
                        position_error: f64::NAN,
                        orientation_error: f64::NAN,
                    });
                });
            }
            let goal = self
                .task_match
                .target(&(shift_inv * self.tasks[t].world_from_tool));
            for s in &mut reach.solutions {
                self.polish(&goal, s);
            }
            detail.tasks.push(reach);
        }
        detail
    }

    /// Measures a solution's errors and, above [`POLISH_ABOVE`], runs Newton steps on the
    /// exact model from it, keeping the result when it is closer and still within the limits.
    fn polish(&self, goal: &Target, s: &mut PlacedSolution) {
        let errors = |q: &[f64]| numerical::pose_errors(self.robot, 0, q, goal).ok();
        let Some((pe, oe)) = errors(&s.q) else {
            return;
        };
        (s.position_error, s.orientation_error) = (pe, oe);
        if pe.max(oe) <= POLISH_ABOVE || !matches!(self.engine, Engine::Closed { .. }) {
            return;
        }
        let opts = NumericalOptions {
            restarts: 0,
            max_iterations: 30,
            enforce_limits: false,
            tolerance: POLISH_ABOVE / 10.0,
            damping: 1e-6,
            mask: match self.task_match {
                TaskMatch::Position => TaskMask::POSITION,
                _ => TaskMask::FULL,
            },
            ..NumericalOptions::default()
        };
        let Ok(rep) = numerical::solve(self.robot, 0, goal, &s.q, &opts) else {
            return;
        };
        if let Some((p2, o2)) = errors(&rep.q)
            && p2.max(o2) < pe.max(oe)
            && self.robot.within_limits(&rep.q, LIMIT_TOL)
        {
            (s.q, s.position_error, s.orientation_error) = (rep.q, p2, o2);
        }
    }
}

/// The numerical engine of an arm without a closed form: LM within the limits from the
/// "ready" configuration and `seeds - 1` starts spread over the limits.
fn numerical_engine(robot: &Robot, seeds: usize) -> (Engine, TaskMatch) {
    let task_match = if robot.dof() >= 6 {
        TaskMatch::Pose
    } else {
        TaskMatch::Position
    };
    let ranges = robot.sampling_ranges();
    let mut starts = vec![robot.ready_or_zero()];
    let mut rng = crate::workspace::rng::Xoshiro256pp::stream(0x91ACE, 0);
    for _ in 1..seeds.max(1) {
        let mut q = vec![0.0; robot.dof()];
        crate::workspace::rng::uniform_q(&mut rng, &ranges, &mut q);
        starts.push(q);
    }
    let opts = NumericalOptions {
        restarts: 0,
        max_iterations: 60,
        tolerance: NUMERICAL_TOLERANCE,
        enforce_limits: true,
        mask: match task_match {
            TaskMatch::Position => TaskMask::POSITION,
            _ => TaskMask::FULL,
        },
        ..NumericalOptions::default()
    };
    let classifier = PostureClassifier::new(robot);
    (
        Engine::Numerical {
            opts,
            seeds: starts,
            classifier,
        },
        task_match,
    )
}

/// Evaluates every placement of the floor grid of `options` for `tasks`: for each base position
/// and yaw, which posture classes reach each task, solved exactly by IK, free of collision in
/// `world` when given (see the module documentation for the frames, the solver and the
/// ranking). Runs in parallel (rayon); checks `cancel` before each base position and calls
/// `progress` with the number of base positions done (from any thread).
///
/// Bad options are an error before any work; a raised `cancel` ends it with
/// [`PlacementError::Cancelled`].
///
/// # Examples
///
/// The two-link planar arm (a1 = a2 = 1 m) reaches 2 m around its base. Two tasks 3.9 m apart:
/// only base positions within 0.05 m of the middle line between them, and at most 0.44 m off
/// the line joining them, reach both.
///
/// ```
/// use armlab::kinematics::Pose;
/// use armlab::kinematics::models::built_in;
/// use armlab::reachability::{PlacementOptions, PlacementTask, place};
/// use std::sync::atomic::AtomicBool;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let arm = built_in("planar2").expect("a built-in model");
/// let tasks = [
///     PlacementTask::new("left", Pose::translation(-1.95, 0.0, 0.0)),
///     PlacementTask::new("right", Pose::translation(1.95, 0.0, 0.0)),
/// ];
/// let options = PlacementOptions {
///     area: [-1.0, 1.0, -1.0, 1.0],
///     step: 0.1,
///     yaws: 4,
///     ..PlacementOptions::default()
/// };
/// let map = place(&arm, &tasks, None, &options, &AtomicBool::new(false), &|_| {})?;
/// assert_eq!(map.grid.x.len(), 21); // -1.0, -0.9, ..., 1.0: both ends
/// let best = &map.best[0];
/// assert_eq!(best.reached, 2);
/// assert!(best.detail.x.abs() < 1e-12 && best.detail.y.abs() < 0.45);
/// // On y = 0, every base position off x = 0 reaches one task at most.
/// for (i, x) in map.grid.x.iter().enumerate() {
///     let (fraction, _) = map.best_yaw(i, 10);
///     assert_eq!(fraction == 1.0, x.abs() < 1e-9, "x = {x}");
/// }
/// # Ok(())
/// # }
/// ```
pub fn place(
    robot: &Robot,
    tasks: &[PlacementTask],
    world: Option<&CollisionWorld>,
    options: &PlacementOptions,
    cancel: &AtomicBool,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<PlacementMap, PlacementError> {
    let grid = PlacementGrid::new(options, tasks.len())?;
    let placer = Placer::new(robot, tasks, world, options.seeds)?;
    let sweep = sweep(&placer, &grid, cancel, progress)?;
    let mut map = PlacementMap {
        posture_names: placer.posture_names().to_vec(),
        solver: placer.solver(),
        task_match: placer.task_match(),
        collisions: world.is_some(),
        tasks: tasks.to_vec(),
        masks: sweep.masks,
        reached: sweep.reached,
        solutions: sweep.solutions,
        blocked: sweep.blocked,
        best: Vec::new(),
        grid,
    };
    map.best = rank(&map, options.best)
        .into_iter()
        .map(|(p, steady)| best_at(&placer, &map, p, steady))
        .collect();
    Ok(map)
}

/// The arrays of a sweep over the grid.
struct Sweep {
    masks: Vec<u16>,
    reached: Vec<u32>,
    solutions: Vec<u32>,
    blocked: Vec<bool>,
}

/// Every placement of `grid`, one base position (all its yaws) per parallel item.
fn sweep(
    placer: &Placer<'_>,
    grid: &PlacementGrid,
    cancel: &AtomicBool,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Sweep, PlacementError> {
    let (nt, nk, ny) = (placer.tasks.len(), grid.yaw.len(), grid.y.len());
    let n = grid.placements();
    let mut out = Sweep {
        masks: vec![0; n * nt],
        reached: vec![0; n],
        solutions: vec![0; n],
        blocked: vec![false; n],
    };
    let done = AtomicUsize::new(0);
    out.masks
        .par_chunks_mut(nk * nt)
        .zip(out.reached.par_chunks_mut(nk))
        .zip(out.solutions.par_chunks_mut(nk))
        .zip(out.blocked.par_chunks_mut(nk))
        .enumerate()
        .for_each_init(
            || (None, RawSolutions::default()),
            |scratch, (p, (((masks, reached), solutions), blocked))| {
                if cancel.load(Ordering::Relaxed) {
                    return;
                }
                let (i, j) = (p / ny, p % ny);
                for k in 0..nk {
                    let shift = grid.shift(i, j, k);
                    let m = &mut masks[k * nt..(k + 1) * nt];
                    (reached[k], solutions[k], blocked[k]) = placer.fill(&shift, m, scratch);
                }
                progress(done.fetch_add(1, Ordering::Relaxed) + 1);
            },
        );
    if cancel.load(Ordering::Relaxed) {
        return Err(PlacementError::Cancelled {
            done: done.load(Ordering::Relaxed),
            total: grid.positions(),
        });
    }
    Ok(out)
}

/// How many of placement `p`'s six grid neighbours reach at least as many tasks.
fn steady(map: &PlacementMap, p: usize) -> u8 {
    let g = &map.grid;
    let [i, j, k] = g.ijk(p);
    let (nx, ny, nk) = (g.x.len(), g.y.len(), g.yaw.len());
    let mut neighbours = Vec::with_capacity(6);
    if i > 0 {
        neighbours.push(g.index(i - 1, j, k));
    }
    if i + 1 < nx {
        neighbours.push(g.index(i + 1, j, k));
    }
    if j > 0 {
        neighbours.push(g.index(i, j - 1, k));
    }
    if j + 1 < ny {
        neighbours.push(g.index(i, j + 1, k));
    }
    if nk > 1 {
        neighbours.push(g.index(i, j, (k + 1) % nk));
        if nk > 2 {
            neighbours.push(g.index(i, j, (k + nk - 1) % nk));
        }
    }
    neighbours
        .iter()
        .filter(|&&q| map.reached[q] >= map.reached[p])
        .count() as u8
}

/// The best `count` placements (index, steady neighbours), one per base position, each
/// reaching at least one task.
fn rank(map: &PlacementMap, count: usize) -> Vec<(usize, u8)> {
    let g = &map.grid;
    let key = |p: usize, s: u8| (map.reached[p], map.solutions[p], s);
    let mut per_position: Vec<(usize, u8)> = (0..g.positions())
        .filter_map(|pos| {
            (0..g.yaw.len())
                .map(|k| {
                    let p = pos * g.yaw.len() + k;
                    (p, steady(map, p))
                })
                .filter(|&(p, _)| map.reached[p] > 0)
                // The first of equal keys wins: max_by_key keeps the last, so compare reversed.
                .min_by(|a, b| key(b.0, b.1).cmp(&key(a.0, a.1)))
        })
        .collect();
    per_position.sort_by(|a, b| key(b.0, b.1).cmp(&key(a.0, a.1)).then(a.0.cmp(&b.0)));
    per_position.truncate(count);
    per_position
}

/// A best placement with its detail.
fn best_at(placer: &Placer<'_>, map: &PlacementMap, p: usize, steady: u8) -> BestPlacement {
    let [i, j, k] = map.grid.ijk(p);
    let detail = placer.evaluate(map.grid.x[i], map.grid.y[j], map.grid.yaw[k]);
    BestPlacement {
        index: [i, j, k],
        reached: map.reached[p] as usize,
        fraction: map.reached[p] as f64 / map.tasks.len() as f64,
        solutions: map.solutions[p],
        steady,
        detail,
    }
}
