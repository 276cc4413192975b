//! `armlab rotation`: one rotation in every representation of Sect. 2.4 (with both Euler
//! solutions and the singular cases in words), or a composition of elementary rotations about
//! current and fixed axes printed step by step (Sect. 2.3). Angles typed in are degrees unless
//! `--rad`; the JSON is in radians.

use super::{CliError, Format};
use crate::kinematics::EulerKind;
use crate::kinematics::orientation::{
    AngleAxisCase, AngleAxisSolutions, Axis, EulerSolutions, Representations, Step, StepFrame,
    degrees, partial_products, quaternion, rotation_from_angle_axis,
};
use clap::ValueEnum;
use nalgebra::{Matrix3, Rotation3, Unit, UnitQuaternion, Vector3};
use serde_json::{Map, Value, json};
use std::io::Write;
use thiserror::Error;

/// Arguments of `armlab rotation`.
#[derive(Debug, clap::Args)]
pub struct RotationArgs {
    /// The rotation, as KIND:VALUES: `zyz:PHI,THETA,PSI`, `zxz:PHI,THETA,PSI`,
    /// `rpy:PHI,THETA,PSI` (R = Rz(phi) Ry(theta) Rx(psi)), `matrix:R11,R12,...,R33` (by rows;
    /// orthonormal to 1e-6, then re-orthonormalized), `quaternion:ETA,EX,EY,EZ` (normalized) or
    /// `axis-angle:THETA,X,Y,Z` (the axis normalized). Angles in degrees unless --rad.
    #[arg(long, allow_hyphen_values = true, value_name = "KIND:VALUES")]
    pub from: Option<String>,
    /// A sequence of elementary rotations, e.g. "current Rz(30) Ry(45); fixed Rx(10)": groups
    /// separated by ';', each starting with `current` (about the turned frame's axes:
    /// post-multiplied, (2.14)) or `fixed` (about the reference frame's axes: pre-multiplied,
    /// (2.16)), then Rx(A), Ry(A), Rz(A). Angles in degrees unless --rad. Each partial product is
    /// printed.
    #[arg(long, allow_hyphen_values = true, value_name = "SEQUENCE")]
    pub compose: Option<String>,
    /// The representations to print, comma-separated (default: all); the matrix is always
    /// printed.
    #[arg(long, value_enum, value_delimiter = ',')]
    pub to: Vec<Representation>,
    /// Read the angles of --from and --compose as radians (default: degrees).
    #[arg(long)]
    pub rad: bool,
    /// Output format; the JSON is in radians.
    #[arg(long, value_enum, default_value_t)]
    pub format: Format,
    /// Also draw the frame and its representations for a slide: PNG, or SVG / PDF (text as
    /// text) by the extension.
    #[arg(long, value_name = "FILE")]
    pub figure: Option<std::path::PathBuf>,
    /// The figure's size in pixels, WIDTHxHEIGHT.
    #[arg(long, default_value = "1200x900")]
    pub size: super::figures::Size,
}

/// A representation `--to` can ask for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Representation {
    /// The rotation matrix (always printed).
    Matrix,
    /// ZYZ Euler angles (2.18).
    Zyz,
    /// ZXZ Euler angles (Problem 2.1).
    Zxz,
    /// Roll-pitch-yaw angles (2.21).
    Rpy,
    /// Angle and axis (2.25).
    AxisAngle,
    /// Unit quaternion (2.33).
    Quaternion,
}

/// What `armlab rotation` rejects, each naming the flag and what was expected.
#[derive(Debug, Error)]
pub enum RotationError {
    /// Neither or both of --from and --compose.
    #[error("give exactly one of --from KIND:VALUES or --compose SEQUENCE (got {got})")]
    Usage {
        /// What was given, in words.
        got: &'static str,
    },
    /// `--from` without the `KIND:` prefix, or with a kind that does not exist.
    #[error(
        "--from: unknown representation {kind:?} (expected zyz, zxz, rpy, matrix, quaternion or axis-angle, written KIND:VALUES, e.g. zyz:30,45,60)"
    )]
    UnknownKind {
        /// The text before ':' (or the whole argument).
        kind: String,
    },
    /// A matrix that is not orthonormal to 1e-6.
    #[error(
        "--from matrix: not a rotation matrix: the largest entry of R^T R - I is {error:.3e} (tolerance {tolerance:e}); give the 9 entries by rows"
    )]
    NotOrthonormal {
        /// max |R^T R - I|.
        error: f64,
        /// The tolerance.
        tolerance: f64,
    },
    /// An orthonormal matrix with determinant -1.
    #[error("--from matrix: a reflection (det R = {det:.6}), not a rotation (det R = +1)")]
    Reflection {
        /// The determinant.
        det: f64,
    },
    /// A quaternion or an axis of zero length.
    #[error("--from {kind}: {what} is zero; it must have a non-zero length to be normalized")]
    Zero {
        /// "quaternion" or "axis-angle".
        kind: &'static str,
        /// What is zero.
        what: &'static str,
    },
    /// `--compose` that is empty or has an empty group.
    #[error(
        "--compose: group {group} is empty (groups are separated by ';', e.g. \"current Rz(30) Ry(45); fixed Rx(10)\")"
    )]
    EmptyGroup {
        /// 1-based group number.
        group: usize,
    },
    /// A group that does not start with `current` or `fixed`.
    #[error("--compose: group {group} starts with {got:?}; expected `current` or `fixed`")]
    Frame {
        /// 1-based group number.
        group: usize,
        /// The first word.
        got: String,
    },
    /// A group with no rotation after its frame word.
    #[error(
        "--compose: group {group} ({frame}) has no rotation; expected Rx(A), Ry(A) or Rz(A) after it"
    )]
    NoStep {
        /// 1-based group number.
        group: usize,
        /// Its frame word.
        frame: StepFrame,
    },
    /// Text that is not an elementary rotation.
    #[error(
        "--compose: group {group}, rotation {position}: expected Rx(A), Ry(A) or Rz(A), got {got:?}"
    )]
    Step {
        /// 1-based group number.
        group: usize,
        /// 1-based rotation number in the group.
        position: usize,
        /// The text found there.
        got: String,
    },
    /// An angle that is not a finite number.
    #[error(
        "--compose: group {group}, rotation {position}: the angle {text:?} is not a finite number"
    )]
    Angle {
        /// 1-based group number.
        group: usize,
        /// 1-based rotation number in the group.
        position: usize,
        /// The angle's text.
        text: String,
    },
}

/// Tolerance on `max |R^T R - I|` of a typed matrix.
const ORTHONORMAL_TOLERANCE: f64 = 1e-6;

/// Runs `armlab rotation`.
pub(super) fn run(args: &RotationArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let unit = if args.rad {
        AngleUnit::Rad
    } else {
        AngleUnit::Deg
    };
    let to = Selection::new(&args.to);
    match (&args.from, &args.compose) {
        (Some(from), None) => {
            let r = parse_from(from, unit)?;
            figure(args, &r, &format!("R from {from}"), out)?;
            let reps = Representations::of(&r);
            match args.format {
                Format::Json => write_json(out, representations_json(&reps, &to)),
                Format::Text => {
                    writeln!(out, "{}", unit.note("--from"))?;
                    write_representations(out, &reps, &to)
                }
            }
        }
        (None, Some(sequence)) => {
            let steps = parse_compose(sequence, unit)?;
            let partial = partial_products(&steps);
            let r = partial.last().copied().unwrap_or_else(Rotation3::identity);
            let title = crate::animation::rotation::product_text(&steps);
            figure(args, &r, &title, out)?;
            let reps = Representations::of(&r);
            match args.format {
                Format::Json => {
                    let mut v = representations_json(&reps, &to);
                    v.insert("steps".into(), steps_json(&steps, &partial));
                    write_json(out, v)
                }
                Format::Text => {
                    writeln!(out, "{}", unit.note("--compose"))?;
                    write_steps(out, &steps, &partial)?;
                    writeln!(out)?;
                    write_representations(out, &reps, &to)
                }
            }
        }
        (None, None) => Err(RotationError::Usage { got: "neither" }.into()),
        (Some(_), Some(_)) => Err(RotationError::Usage { got: "both" }.into()),
    }
}

/// The unit of typed angles.
#[derive(Debug, Clone, Copy, PartialEq)]
enum AngleUnit {
    Deg,
    Rad,
}

impl AngleUnit {
    /// The first line of the text output: how the typed angles were read.
    fn note(self, flag: &str) -> String {
        match self {
            AngleUnit::Deg => format!("(the angles of {flag} read in degrees; --rad for radians)"),
            AngleUnit::Rad => format!("(the angles of {flag} read in radians)"),
        }
    }

    fn to_rad(self, v: f64) -> f64 {
        match self {
            AngleUnit::Deg => v.to_radians(),
            AngleUnit::Rad => v,
        }
    }
}

/// Which representations to print (all when none is named).
struct Selection(Vec<Representation>);

impl Selection {
    fn new(asked: &[Representation]) -> Self {
        Selection(asked.to_vec())
    }
    fn has(&self, r: Representation) -> bool {
        self.0.is_empty() || self.0.contains(&r)
    }
}

/// Parses `--from KIND:VALUES` into a rotation.
fn parse_from(text: &str, unit: AngleUnit) -> Result<Rotation3<f64>, CliError> {
    let Some((kind, values)) = text.split_once(':') else {
        return Err(RotationError::UnknownKind {
            kind: text.trim().chars().take(40).collect(),
        }
        .into());
    };
    let kind = kind.trim().to_ascii_lowercase();
    let euler = match kind.as_str() {
        "zyz" => Some(EulerKind::Zyz),
        "zxz" => Some(EulerKind::Zxz),
        "rpy" => Some(EulerKind::Rpy),
        _ => None,
    };
    if let Some(euler) = euler {
        let source = format!("--from {kind}");
        let a = crate::input::parse_row(values, &source, 3, "angles (phi, theta, psi)")?;
        let a = Vector3::new(unit.to_rad(a[0]), unit.to_rad(a[1]), unit.to_rad(a[2]));
        return Ok(euler.to_rotation(&a));
    }
    match kind.as_str() {
        "matrix" => {
            let v = crate::input::parse_row(values, "--from matrix", 9, "entries (by rows)")?;
            Ok(rotation_of_matrix(&Matrix3::from_row_slice(&v))?)
        }
        "quaternion" => {
            let v = crate::input::parse_row(
                values,
                "--from quaternion",
                4,
                "numbers (eta, ex, ey, ez)",
            )?;
            let (eta, eps) = (v[0], Vector3::new(v[1], v[2], v[3]));
            if eta == 0.0 && eps.norm() == 0.0 {
                return Err(RotationError::Zero {
                    kind: "quaternion",
                    what: "(eta, ex, ey, ez)",
                }
                .into());
            }
            Ok(quaternion(eta, eps).to_rotation_matrix())
        }
        "axis-angle" => {
            let v = crate::input::parse_row(
                values,
                "--from axis-angle",
                4,
                "numbers (theta, x, y, z)",
            )?;
            let axis = Vector3::new(v[1], v[2], v[3]);
            let Some(axis) = Unit::try_new(axis, 0.0) else {
                return Err(RotationError::Zero {
                    kind: "axis-angle",
                    what: "the axis (x, y, z)",
                }
                .into());
            };
            Ok(rotation_from_angle_axis(unit.to_rad(v[0]), &axis))
        }
        _ => Err(RotationError::UnknownKind { kind }.into()),
    }
}

/// A typed matrix as a rotation: orthonormal to [`ORTHONORMAL_TOLERANCE`] with determinant +1,
/// then re-orthonormalized (the nearest rotation, by the polar decomposition's Newton
/// iteration `X <- (X + X^-T)/2`).
fn rotation_of_matrix(m: &Matrix3<f64>) -> Result<Rotation3<f64>, RotationError> {
    let error = (m.transpose() * m - Matrix3::identity()).amax();
    if error.is_nan() || error > ORTHONORMAL_TOLERANCE {
        return Err(RotationError::NotOrthonormal {
            error,
            tolerance: ORTHONORMAL_TOLERANCE,
        });
    }
    let det = m.determinant();
    if det < 0.0 {
        return Err(RotationError::Reflection { det });
    }
    let mut x = *m;
    for _ in 0..4 {
        let Some(inv) = x.try_inverse() else { break };
        x = (x + inv.transpose()) * 0.5;
    }
    Ok(Rotation3::from_matrix_unchecked(x))
}

/// Parses `--compose`: groups separated by ';', each `current|fixed` then `Rx(a)`, `Ry(a)`,
/// `Rz(a)` separated by spaces (or commas or `*`).
fn parse_compose(text: &str, unit: AngleUnit) -> Result<Vec<Step>, RotationError> {
    let mut steps = Vec::new();
    let groups: Vec<&str> = text.split(';').collect();
    for (g, group) in groups.iter().enumerate() {
        let group_no = g + 1;
        let group = group.trim();
        if group.is_empty() {
            // A trailing ';' ends the list; an empty group elsewhere is a slip.
            if g + 1 == groups.len() && g > 0 {
                break;
            }
            return Err(RotationError::EmptyGroup { group: group_no });
        }
        let (word, rest) = group
            .split_once(|c: char| c.is_whitespace() || c == ':')
            .unwrap_or((group, ""));
        let frame = match word.to_ascii_lowercase().as_str() {
            "current" => StepFrame::Current,
            "fixed" => StepFrame::Fixed,
            _ => {
                return Err(RotationError::Frame {
                    group: group_no,
                    got: word.chars().take(40).collect(),
                });
            }
        };
        let before = steps.len();
        parse_group(rest, frame, group_no, unit, &mut steps)?;
        if steps.len() == before {
            return Err(RotationError::NoStep {
                group: group_no,
                frame,
            });
        }
    }
    Ok(steps)
}

/// The elementary rotations of one group, appended to `steps`.
fn parse_group(
    text: &str,
    frame: StepFrame,
    group: usize,
    unit: AngleUnit,
    steps: &mut Vec<Step>,
) -> Result<(), RotationError> {
    let mut rest = text.trim_start_matches(|c: char| c.is_whitespace() || c == ',' || c == '*');
    let mut position = 1;
    while !rest.is_empty() {
        let bad = || RotationError::Step {
            group,
            position,
            got: rest
                .split(|c: char| c.is_whitespace())
                .next()
                .unwrap_or(rest)
                .chars()
                .take(40)
                .collect(),
        };
        let mut chars = rest.chars();
        let axis = match (chars.next(), chars.next().map(|c| c.to_ascii_lowercase())) {
            (Some('R' | 'r'), Some('x')) => Axis::X,
            (Some('R' | 'r'), Some('y')) => Axis::Y,
            (Some('R' | 'r'), Some('z')) => Axis::Z,
            _ => return Err(bad()),
        };
        let after = chars.as_str().trim_start();
        let Some(inner) = after.strip_prefix('(') else {
            return Err(bad());
        };
        let Some((angle_text, tail)) = inner.split_once(')') else {
            return Err(bad());
        };
        let angle = match angle_text.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => unit.to_rad(v),
            _ => {
                return Err(RotationError::Angle {
                    group,
                    position,
                    text: angle_text.trim().chars().take(40).collect(),
                });
            }
        };
        steps.push(Step { frame, axis, angle });
        position += 1;
        rest = tail.trim_start_matches(|c: char| c.is_whitespace() || c == ',' || c == '*');
    }
    Ok(())
}

fn write_json(out: &mut dyn Write, v: Map<String, Value>) -> Result<(), CliError> {
    serde_json::to_writer_pretty(&mut *out, &Value::Object(v)).map_err(std::io::Error::from)?;
    writeln!(out)?;
    Ok(())
}

fn rows(m: &Matrix3<f64>) -> Value {
    json!(
        (0..3)
            .map(|i| [m[(i, 0)], m[(i, 1)], m[(i, 2)]])
            .collect::<Vec<_>>()
    )
}

fn euler_json(s: &EulerSolutions) -> Value {
    json!({
        "solutions": s.solutions.iter().map(|a| [a[0], a[1], a[2]]).collect::<Vec<_>>(),
        "singular": s.singular(),
        "determined": s.family.map(|f| f.combination.as_str()),
        "value": s.family.map(|f| f.value),
    })
}

fn axis_angle_json(aa: &AngleAxisSolutions) -> Value {
    let v = |a: &Unit<Vector3<f64>>| [a[0], a[1], a[2]];
    json!({
        "angle": aa.angle,
        "axis": aa.axes.first().map(v),
        "axes": aa.axes.iter().map(v).collect::<Vec<_>>(),
        "case": match aa.case {
            AngleAxisCase::Regular => "regular",
            AngleAxisCase::AnyAxis => "any-axis",
            AngleAxisCase::HalfTurn => "half-turn",
        },
    })
}

fn quaternion_json(q: &UnitQuaternion<f64>) -> Value {
    json!({"eta": q.w, "epsilon": [q.i, q.j, q.k]})
}

/// The keys, in radians: `matrix` always, the others as selected.
fn representations_json(reps: &Representations, to: &Selection) -> Map<String, Value> {
    let mut v = Map::new();
    v.insert("matrix".into(), rows(reps.matrix.matrix()));
    for (sel, key, kind) in [
        (Representation::Zyz, "zyz", EulerKind::Zyz),
        (Representation::Zxz, "zxz", EulerKind::Zxz),
        (Representation::Rpy, "rpy", EulerKind::Rpy),
    ] {
        if to.has(sel) {
            v.insert(key.into(), euler_json(reps.euler(kind)));
        }
    }
    if to.has(Representation::AxisAngle) {
        v.insert("axis_angle".into(), axis_angle_json(&reps.axis_angle));
    }
    if to.has(Representation::Quaternion) {
        v.insert("quaternion".into(), quaternion_json(&reps.quaternion));
    }
    v
}

fn steps_json(steps: &[Step], partial: &[Rotation3<f64>]) -> Value {
    json!(
        steps
            .iter()
            .zip(partial)
            .map(|(s, r)| json!({
                "frame": s.frame,
                "axis": s.axis,
                "angle": s.angle,
                "matrix": rows(r.matrix()),
            }))
            .collect::<Vec<_>>()
    )
}

/// A number for six-decimal text: rounding noise (and -0) below the last digit shown as 0.
fn shown(v: f64) -> f64 {
    if v.abs() < 5e-7 { 0.0 } else { v }
}

/// `(0.130820, 0.488227, 0.862856)`.
fn vector_text(v: &Vector3<f64>) -> String {
    format!(
        "({:.6}, {:.6}, {:.6})",
        shown(v[0]),
        shown(v[1]),
        shown(v[2])
    )
}

/// The matrix, one row a line, indented.
fn write_matrix(out: &mut dyn Write, m: &Matrix3<f64>) -> std::io::Result<()> {
    for i in 0..3 {
        let (a, b, c) = (shown(m[(i, 0)]), shown(m[(i, 1)]), shown(m[(i, 2)]));
        writeln!(out, "  [{a:>10.6} {b:>10.6} {c:>10.6} ]")?;
    }
    Ok(())
}

/// `(30°, 45°, 60°) = (0.523599, 0.785398, 1.047198) rad`.
fn triple(a: &Vector3<f64>) -> String {
    format!(
        "({}°, {}°, {}°) = {} rad",
        degrees(a[0]),
        degrees(a[1]),
        degrees(a[2]),
        vector_text(a)
    )
}

fn write_euler(out: &mut dyn Write, s: &EulerSolutions) -> std::io::Result<()> {
    let (name, formula) = match s.kind {
        EulerKind::Zyz => ("ZYZ Euler angles", "R = Rz(phi) Ry(theta) Rz(psi), (2.18)"),
        EulerKind::Zxz => (
            "ZXZ Euler angles",
            "R = Rz(phi) Rx(theta) Rz(psi), Problem 2.1",
        ),
        EulerKind::Rpy => (
            "roll-pitch-yaw angles",
            "R = Rz(phi) Ry(theta) Rx(psi), (2.21)",
        ),
    };
    writeln!(out, "{name} (phi, theta, psi), {formula}:")?;
    match &s.family {
        None => {
            for (i, a) in s.solutions.iter().enumerate() {
                writeln!(out, "  solution {}: {}", i + 1, triple(a))?;
            }
        }
        Some(family) => {
            let theta = s.solutions.first().map_or(0.0, |a| a[1]);
            writeln!(
                out,
                "  singular (theta = {}°): {} ({:.6} rad); phi and psi turn about the same axis",
                degrees(theta),
                family,
                family.value
            )?;
            for a in &s.solutions {
                writeln!(out, "  with phi = 0: {}", triple(a))?;
            }
        }
    }
    Ok(())
}

fn write_axis_angle(out: &mut dyn Write, aa: &AngleAxisSolutions) -> std::io::Result<()> {
    writeln!(
        out,
        "angle and axis (theta, r), (2.27)-(2.28), r a unit vector:"
    )?;
    let v = |a: &Unit<Vector3<f64>>| vector_text(a);
    let theta = format!("theta = {}° ({:.6} rad)", degrees(aa.angle), aa.angle);
    match (aa.case, aa.axes.as_slice()) {
        (AngleAxisCase::Regular, [r, ..]) => {
            writeln!(out, "  {theta}, r = {} (or -theta about -r)", v(r))
        }
        (AngleAxisCase::HalfTurn, [r, minus, ..]) => writeln!(
            out,
            "  {theta}: a half turn (sin(theta) = 0); r = {} and -r = {} give the same matrix",
            v(r),
            v(minus)
        ),
        _ => writeln!(
            out,
            "  {theta}: no rotation (sin(theta) = 0); any axis serves"
        ),
    }
}

/// Every selected representation, in text with the unit of every number.
fn write_representations(
    out: &mut dyn Write,
    reps: &Representations,
    to: &Selection,
) -> Result<(), CliError> {
    writeln!(out, "rotation matrix R (rows; dimensionless):")?;
    write_matrix(out, reps.matrix.matrix())?;
    for (sel, kind) in [
        (Representation::Zyz, EulerKind::Zyz),
        (Representation::Zxz, EulerKind::Zxz),
        (Representation::Rpy, EulerKind::Rpy),
    ] {
        if to.has(sel) {
            write_euler(out, reps.euler(kind))?;
        }
    }
    if to.has(Representation::AxisAngle) {
        write_axis_angle(out, &reps.axis_angle)?;
    }
    if to.has(Representation::Quaternion) {
        let q = &reps.quaternion;
        writeln!(
            out,
            "unit quaternion Q = {{eta, epsilon}}, (2.34)-(2.35), eta >= 0 (dimensionless):"
        )?;
        writeln!(
            out,
            "  eta = {:.6}, epsilon = {}",
            shown(q.w),
            vector_text(&q.imag())
        )?;
    }
    Ok(())
}

/// The elementary rotation of a step in the textbook's notation, `Rz(30°)`.
fn elementary_name(s: &Step) -> String {
    format!("R{}({}°)", s.axis, degrees(s.angle))
}

/// Each step with the product so far, then the whole product in symbols.
fn write_steps(
    out: &mut dyn Write,
    steps: &[Step],
    partial: &[Rotation3<f64>],
) -> Result<(), CliError> {
    writeln!(
        out,
        "composition of {} elementary rotations (angles shown in degrees):",
        steps.len()
    )?;
    for (i, (s, r)) in steps.iter().zip(partial).enumerate() {
        let (n, e) = (i + 1, elementary_name(s));
        let product = match s.frame {
            StepFrame::Current if i > 0 => format!("R{i} {e}"),
            StepFrame::Fixed if i > 0 => format!("{e} R{i}"),
            _ => e,
        };
        let rule = match s.frame {
            StepFrame::Current => "about the current axis: post-multiplied, (2.14)",
            StepFrame::Fixed => "about the fixed axis: pre-multiplied, (2.16)",
        };
        writeln!(out, "step {n}: {s}, {rule}")?;
        writeln!(out, "R{n} = {product} =")?;
        write_matrix(out, r.matrix())?;
    }
    // The product in symbols: fixed steps in reverse order on the left, current ones in order
    // on the right.
    let fixed = steps
        .iter()
        .rev()
        .filter(|s| s.frame == StepFrame::Fixed)
        .map(elementary_name);
    let current = steps
        .iter()
        .filter(|s| s.frame == StepFrame::Current)
        .map(elementary_name);
    let symbols: Vec<String> = fixed.chain(current).collect();
    writeln!(out, "R = {}", symbols.join(" "))?;
    Ok(())
}

/// A `--compose` sequence for another subcommand (`armlab animate --what rotation`): angles in
/// degrees, or radians with `rad`.
pub(super) fn sequence_of(text: &str, rad: bool) -> Result<Vec<Step>, CliError> {
    let unit = if rad { AngleUnit::Rad } else { AngleUnit::Deg };
    Ok(parse_compose(text, unit)?)
}

/// `--figure`: the frame turned by `r` with its representations, titled `title`, written to
/// the file (PNG, SVG or PDF); says so on stderr-free `out` only in text mode.
fn figure(
    args: &RotationArgs,
    r: &Rotation3<f64>,
    title: &str,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let Some(path) = &args.figure else {
        return Ok(());
    };
    let mut figs = crate::headless::figures_for(path)?;
    let img = crate::figure::orientation::frame_figure(
        &mut figs,
        r,
        title,
        args.size.0,
        crate::figure::Theme::Light,
    )?;
    crate::headless::write_figure(&mut figs, &img, path)?;
    if args.format == Format::Text {
        writeln!(
            out,
            "wrote {} ({}x{})",
            path.display(),
            img.width(),
            img.height()
        )?;
    }
    Ok(())
}
