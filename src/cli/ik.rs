//! `armlab ik`: every closed-form solution with its posture, or the numerical solver.

use super::fk::fmt_vec;
use super::input::{parse_row, read_numbered_rows};
use super::{CliError, Format};
use crate::collision::CollisionReport;
use crate::kinematics::Robot;
use crate::kinematics::ik::numerical::{Method, NumericalOptions};
use crate::kinematics::ik::solver::{self, SolverChoice};
use crate::kinematics::ik::{IkResult, IkSolution, IkStatus, Target};
use crate::kinematics::pose::pose_from_matrix;
use clap::ValueEnum;
use nalgebra::{Matrix4, Vector3};
use serde_json::{Value, json};
use std::io::Write;
use std::path::PathBuf;

/// Layout of the targets in `--input`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum TargetKind {
    /// 16 numbers: a row-major 4x4 pose.
    Pose,
    /// x, y, z (m).
    Position,
    /// px, py, phi (m, m, rad).
    Planar,
}

/// Which solver.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum SolverArg {
    /// Closed form when the arm's structure has one, numerical otherwise.
    #[default]
    Auto,
    /// Closed form only.
    ClosedForm,
    /// Numerical only.
    Numerical,
}

/// Numerical update rule.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum MethodArg {
    /// Levenberg-Marquardt.
    #[default]
    Lm,
    /// Damped least squares.
    Dls,
    /// Pseudo-inverse.
    Pinv,
    /// Jacobian transpose.
    Transpose,
}

/// Arguments of `armlab ik`.
#[derive(Debug, clap::Args)]
#[command(group(clap::ArgGroup::new("target_source").required(true).args(["pose", "position", "planar", "input"])))]
pub struct IkArgs {
    /// Built-in name or path to a .toml / .urdf model.
    pub model: String,
    /// Target pose: 16 numbers, a row-major 4x4 homogeneous transform (m).
    #[arg(long, allow_hyphen_values = true)]
    pub pose: Option<String>,
    /// Target position x,y,z (m); the orientation is free. A planar arm's position has z = 0.
    #[arg(long, allow_hyphen_values = true)]
    pub position: Option<String>,
    /// Planar target px,py,phi (m, m, rad) for an arm in the x-y plane.
    #[arg(long, allow_hyphen_values = true)]
    pub planar: Option<String>,
    /// File with one target per line (comma-separated, # comments); `-` for stdin.
    #[arg(long, requires = "target")]
    pub input: Option<PathBuf>,
    /// Layout of the targets in --input.
    #[arg(long, value_enum)]
    pub target: Option<TargetKind>,
    /// Print every solution (default: the one closest to --seed-q, or to zero).
    #[arg(long)]
    pub all: bool,
    /// Print the solution with this posture (e.g. "shoulder right, elbow up, wrist no flip").
    #[arg(long, conflicts_with = "all")]
    pub posture: Option<String>,
    /// Joint vector that seeds the numerical solver and picks the closest solution.
    #[arg(long, allow_hyphen_values = true)]
    pub seed_q: Option<String>,
    /// End-effector, by name (any link of a URDF) or 0-based index (the humanoid has two hands).
    #[arg(long)]
    pub ee: Option<String>,
    /// Which solver.
    #[arg(long, value_enum, default_value_t)]
    pub solver: SolverArg,
    /// Numerical update rule.
    #[arg(long, value_enum, default_value_t)]
    pub method: MethodArg,
    /// The task, in the tool frame (Sect. 2.10.2): `position+axis` leaves the rotation about the
    /// approach axis free (laser cutting, r = 5). Tasks other than `pose` use the numerical
    /// solver with that mask.
    #[arg(long, value_enum, default_value_t)]
    pub task: TaskArg,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    pub format: Format,
    /// The nominal model of this arm (e.g. the model a calibrated one came from): every posture
    /// of its closed form, polished by Newton steps on MODEL to 1e-12 and labelled as the
    /// nominal model labels it. Full-pose targets.
    #[arg(long, conflicts_with = "solver")]
    pub nominal: Option<String>,
    /// A scene file of obstacles (TOML `[[obstacle]]` tables): each solution says what it hits
    /// there and its clearance. Without one, each solution still says whether the arm hits
    /// itself.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
}

/// `--task` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum TaskArg {
    /// Position and orientation.
    #[default]
    Pose,
    /// Position only.
    Position,
    /// Position and approach axis, free about the tool axis.
    #[value(name = "position+axis")]
    PositionAxis,
    /// Position in the plane.
    Planar,
    /// Position in the plane and phi.
    #[value(name = "planar+phi")]
    PlanarPhi,
}

impl From<TaskArg> for crate::kinematics::redundancy::Task {
    fn from(t: TaskArg) -> Self {
        use crate::kinematics::redundancy::Task;
        match t {
            TaskArg::Pose => Task::Pose,
            TaskArg::Position => Task::Position,
            TaskArg::PositionAxis => Task::PositionAxis,
            TaskArg::Planar => Task::Planar,
            TaskArg::PlanarPhi => Task::PlanarPhi,
        }
    }
}

fn target_from(values: &[f64], kind: TargetKind, source: &str) -> Result<Target, CliError> {
    Ok(match kind {
        TargetKind::Pose => {
            let m = Matrix4::from_row_slice(values);
            let p = pose_from_matrix(&m).map_err(|e| CliError::BadTarget {
                source_name: source.into(),
                reason: e.to_string(),
            })?;
            Target::Pose(p)
        }
        TargetKind::Position => Target::Position(Vector3::new(values[0], values[1], values[2])),
        TargetKind::Planar => Target::Planar {
            px: values[0],
            py: values[1],
            phi: values[2],
        },
    })
}

fn count(kind: TargetKind) -> usize {
    if kind == TargetKind::Pose { 16 } else { 3 }
}

fn targets(args: &IkArgs) -> Result<Vec<(String, Target)>, CliError> {
    let one =
        |text: &str, kind: TargetKind, flag: &str| -> Result<Vec<(String, Target)>, CliError> {
            let what = if kind == TargetKind::Pose {
                "numbers (a row-major 4x4 pose)"
            } else {
                "numbers"
            };
            let v = parse_row(text, flag, count(kind), what)?;
            Ok(vec![(flag.to_string(), target_from(&v, kind, flag)?)])
        };
    if let Some(t) = &args.pose {
        return one(t, TargetKind::Pose, "--pose");
    }
    if let Some(t) = &args.position {
        return one(t, TargetKind::Position, "--position");
    }
    if let Some(t) = &args.planar {
        return one(t, TargetKind::Planar, "--planar");
    }
    let (Some(path), Some(kind)) = (&args.input, args.target) else {
        return Err(CliError::Usage(
            "give a target with --pose, --position, --planar or --input with --target",
        ));
    };
    let what = if kind == TargetKind::Pose {
        "numbers (a row-major 4x4 pose)"
    } else {
        "numbers"
    };
    read_numbered_rows(path, count(kind), what)?
        .iter()
        .map(|(line, v)| {
            let src = format!("{}:{line}", path.display());
            Ok((src.clone(), target_from(v, kind, &src)?))
        })
        .collect()
}

/// The index of end-effector `spec` (a name or an index; the first without one). A name may
/// be any link of a robot description: a link that is no end-effector is made one
/// ([`Robot::end_effector_at`]). The error lists the end-effectors (the leaf-like links) first,
/// then the other links.
pub(super) fn end_effector(robot: &mut Robot, spec: Option<&str>) -> Result<usize, CliError> {
    let Some(s) = spec else { return Ok(0) };
    if let Ok(i) = s.parse::<usize>() {
        if i < robot.end_effectors().len() {
            return Ok(i);
        }
    } else if let Some(i) = robot.end_effector_at(s) {
        return Ok(i);
    }
    let ees: Vec<&str> = robot
        .end_effectors()
        .iter()
        .map(|e| e.name.as_str())
        .collect();
    let others: Vec<&str> = (robot.link_frames.iter())
        .map(|(l, _)| l.as_str())
        .filter(|l| !ees.contains(l))
        .collect();
    let mut available = ees.join(", ");
    if !others.is_empty() {
        available.push_str(&format!("; any other link: {}", others.join(", ")));
    }
    Err(CliError::UnknownEndEffector {
        name: s.into(),
        available,
    })
}

/// The solver and its options from `--solver`, `--method` and `--task`.
fn solver_setup(args: &IkArgs) -> Result<(SolverChoice, NumericalOptions), CliError> {
    let task: crate::kinematics::redundancy::Task = args.task.into();
    let choice = match (args.solver, args.task) {
        (SolverArg::ClosedForm, t) if t != TaskArg::Pose => {
            return Err(CliError::Usage(
                "the closed form solves whole targets; a --task other than pose needs the \
                 numerical solver",
            ));
        }
        (_, t) if t != TaskArg::Pose => SolverChoice::Numerical,
        (SolverArg::Auto, _) => SolverChoice::Auto,
        (SolverArg::ClosedForm, _) => SolverChoice::ClosedForm,
        (SolverArg::Numerical, _) => SolverChoice::Numerical,
    };
    let method = match args.method {
        MethodArg::Lm => Method::LevenbergMarquardt,
        MethodArg::Dls => Method::DampedLeastSquares,
        MethodArg::Pinv => Method::PseudoInverse,
        MethodArg::Transpose => Method::Transpose,
    };
    let opts = NumericalOptions {
        method,
        mask: if task == crate::kinematics::redundancy::Task::Pose {
            crate::kinematics::ik::numerical::TaskMask::FULL
        } else {
            crate::kinematics::ik::numerical::TaskMask::of_task(task)
        },
        ..Default::default()
    };
    Ok((choice, opts))
}

/// Runs `ik`. All targets are parsed before anything is solved or printed; each solution
/// printed is checked for collisions (the arm's own links, and the obstacles of `--scene`).
pub(super) fn run(args: &IkArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let mut robot = super::load_model(&args.model)?;
    let targets = targets(args)?;
    let ee = end_effector(&mut robot, args.ee.as_deref())?;
    let seed = match &args.seed_q {
        Some(t) => Some(parse_row(t, "--seed-q", robot.dof(), "joint values")?),
        None => None,
    };
    let (choice, opts) = solver_setup(args)?;
    let reference = seed.clone().unwrap_or_else(|| vec![0.0; robot.dof()]);
    let nominal = args.nominal.as_deref().map(super::load_model).transpose()?;
    let world = super::collisions::world_for(&robot, args.scene.as_deref())?;
    let mut answers = Vec::with_capacity(targets.len());
    for (src, t) in &targets {
        let solved = match &nominal {
            Some(n) => solver::solve_from_reference(&robot, n, t, &opts),
            None => solver::solve(&robot, ee, t, seed.as_deref(), choice, &opts),
        };
        let (result, used) = solved.map_err(|e| CliError::Ik {
            source_name: src.clone(),
            source: e,
        })?;
        let (picked, note) = pick(&robot, &result, args, &reference);
        let collisions = picked
            .iter()
            .map(|s| world.check(&robot, &s.q))
            .collect::<Result<Vec<_>, _>>()?;
        answers.push(Answer {
            target: t,
            result,
            used: used.to_string(),
            picked,
            note,
            collisions,
        });
    }
    match args.format {
        Format::Json => {
            let arr: Vec<Value> = answers.iter().map(answer_json).collect();
            serde_json::to_writer_pretty(&mut *out, &arr).map_err(std::io::Error::from)?;
            writeln!(out)?;
        }
        Format::Text => {
            for (i, a) in answers.iter().enumerate() {
                if i > 0 {
                    writeln!(out)?;
                }
                write_answer(&robot, a, out)?;
            }
        }
    }
    Ok(())
}

/// One target's answer: the solver's result, the solutions printed and what each hits.
struct Answer<'t> {
    target: &'t Target,
    result: IkResult,
    used: String,
    picked: Vec<IkSolution>,
    note: Option<String>,
    /// What each picked solution hits (same order as `picked`).
    collisions: Vec<CollisionReport>,
}

/// One target's JSON object.
fn answer_json(a: &Answer<'_>) -> Value {
    let mut o = json!({
        "status": status_name(&a.result.status),
        "solutions": a.picked.iter().zip(&a.collisions).map(|(s, c)| solution_json(s, c)).collect::<Vec<_>>(),
        "solver": a.used,
        "target": target_json(a.target),
    });
    if let IkStatus::Unreachable { distance } = a.result.status {
        o["distance"] = if distance.is_finite() {
            json!(distance)
        } else {
            Value::Null
        };
    }
    o["solution_count"] = json!(a.result.solutions.len());
    if let Some(n) = &a.note {
        o["note"] = json!(n);
    }
    o
}

/// One target's answer as text: the status line, then each solution.
fn write_answer(robot: &Robot, a: &Answer<'_>, out: &mut dyn Write) -> std::io::Result<()> {
    let status = match a.result.status {
        IkStatus::Unreachable { distance } => format!(
            "unreachable: outside the workspace by {distance:.6} (m, or rad for an orientation)"
        ),
        s => status_name(&s).to_string(),
    };
    writeln!(
        out,
        "{status}; {}; {} solution(s)",
        a.used,
        a.result.solutions.len()
    )?;
    if let Some(n) = &a.note {
        writeln!(out, "  {n}")?;
    }
    for (s, c) in a.picked.iter().zip(&a.collisions) {
        write_solution(robot, s, out)?;
        writeln!(out, "    collision: {}", super::collisions::report_line(c))?;
    }
    Ok(())
}

fn pick(
    robot: &Robot,
    result: &IkResult,
    args: &IkArgs,
    reference: &[f64],
) -> (Vec<IkSolution>, Option<String>) {
    if args.all {
        return (result.solutions.clone(), None);
    }
    if let Some(name) = &args.posture {
        return match solver::by_posture(&result.solutions, name) {
            Some(s) => (vec![s.clone()], None),
            None if result.solutions.is_empty() => (Vec::new(), None),
            None => {
                let have: Vec<String> = result
                    .solutions
                    .iter()
                    .map(|s| s.posture.to_string())
                    .collect();
                (
                    Vec::new(),
                    Some(format!(
                        "no solution with posture {name:?}; postures here: {}",
                        have.join("; ")
                    )),
                )
            }
        };
    }
    (
        solver::closest(robot, &result.solutions, reference)
            .into_iter()
            .cloned()
            .collect(),
        None,
    )
}

fn status_name(s: &IkStatus) -> &'static str {
    match s {
        IkStatus::Ok => "ok",
        IkStatus::Unreachable { .. } => "unreachable",
        IkStatus::Singular => "singular",
    }
}

/// One solution's JSON object; `collision` is null or the contacts `{a, b, depth_m, at}`, and
/// `clearance_m` the smallest distance between bodies checked (0 in collision).
fn solution_json(s: &IkSolution, c: &CollisionReport) -> Value {
    json!({
        "q": s.q,
        "posture": s.posture.to_string(),
        "posture_parts": s.posture,
        "within_limits": s.within_limits,
        "position_error": s.position_error,
        "orientation_error": s.orientation_error,
        "free_joints": s.free_joints.iter().map(|f| json!({"index": f.index, "reason": f.reason})).collect::<Vec<_>>(),
        "collision": if c.in_collision { json!(c.pairs) } else { Value::Null },
        "clearance_m": c.clearance_m,
    })
}

fn target_json(t: &Target) -> Value {
    match t {
        Target::Pose(p) => json!({ "pose": crate::kinematics::pose::pose_to_rows(p) }),
        Target::Position(p) => json!({ "position": p.as_slice() }),
        Target::Planar { px, py, phi } => json!({ "planar": [px, py, phi] }),
    }
}

fn write_solution(robot: &Robot, s: &IkSolution, out: &mut dyn Write) -> std::io::Result<()> {
    let deg = super::q_for_display(robot, &s.q);
    let limits = if s.within_limits {
        "within limits"
    } else {
        "OUTSIDE the joint limits"
    };
    writeln!(out, "  {}: {limits}", s.posture)?;
    writeln!(out, "    q = {} (rad, m)", fmt_vec(&s.q))?;
    writeln!(out, "    q = {} (deg, m)", fmt_vec(&deg))?;
    writeln!(
        out,
        "    errors: position {:.2e} m, orientation {:.2e} rad",
        s.position_error, s.orientation_error
    )?;
    for f in &s.free_joints {
        writeln!(out, "    joint {} is free: {}", f.index + 1, f.reason)?;
    }
    Ok(())
}
