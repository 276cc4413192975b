//! `armlab symbolic`: the direct kinematics in symbols, in the textbook's notation, or with
//! `--rotation` the matrix of a representation of orientation (Sects. 2.4-2.6).

use super::CliError;
use crate::kinematics::pose::pose_to_rows;
use crate::kinematics::symbolic::document::{self, position, strings, vector};
use crate::kinematics::symbolic::expr::{Style, number, write};
use crate::kinematics::symbolic::poly::Poly;
use crate::kinematics::symbolic::rotation::{Representation, SymbolicRotation, derive_rotation};
use crate::kinematics::symbolic::{Options, Source, SymbolicKinematics, derive};
use crate::kinematics::{JointKind, Pose};
use clap::ValueEnum;
use serde_json::{Value, json};
use std::io::Write;

/// Output format of `armlab symbolic`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum SymbolicFormat {
    /// The textbook's notation in plain text (`c1(a2c2 + a3c23)`).
    #[default]
    Text,
    /// LaTeX display equations (`bmatrix`).
    Latex,
    /// Markdown with `$$` LaTeX blocks.
    Markdown,
    /// JSON; each entry a string in the documented grammar (`c1*(a2*c2 + a3*c23)`).
    Json,
}

/// The representations `--rotation` writes (clap's names for
/// [`crate::kinematics::symbolic::rotation::Representation`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum RotationArg {
    /// Euler angles ZXZ, Rz(phi) Rx'(theta) Rz''(psi) (Problem 2.1).
    Zxz,
    /// Euler angles ZYZ, Rz(phi) Ry'(theta) Rz''(psi) (2.18).
    Zyz,
    /// Roll-pitch-yaw, Rz(phi) Ry(theta) Rx(psi) about fixed axes (2.21).
    Rpy,
    /// The rotation by theta about the unit axis r (2.25).
    AxisAngle,
    /// The unit quaternion (eta, epsilon) (2.33).
    Quaternion,
}

impl From<RotationArg> for Representation {
    fn from(r: RotationArg) -> Self {
        match r {
            RotationArg::Zxz => Representation::Zxz,
            RotationArg::Zyz => Representation::Zyz,
            RotationArg::Rpy => Representation::Rpy,
            RotationArg::AxisAngle => Representation::AxisAngle,
            RotationArg::Quaternion => Representation::Quaternion,
        }
    }
}

/// Arguments of `armlab symbolic`: exactly one of MODEL and `--rotation`.
#[derive(Debug, clap::Args)]
#[command(group(clap::ArgGroup::new("what").required(true).args(["model", "rotation"])))]
pub struct SymbolicArgs {
    /// Built-in name or path to a .toml / .urdf model; or --rotation instead.
    pub model: Option<String>,
    /// Write a rotation matrix instead of an arm: the Euler angles ZXZ (Problem 2.1) or ZYZ
    /// (2.18), roll-pitch-yaw (2.21), angle and axis (2.25) or the unit quaternion (2.33), in
    /// the textbook's symbols: c_phi, s_theta, r_x, eta, epsilon_x.
    #[arg(long, value_enum, value_name = "REPRESENTATION", conflicts_with_all = ["numbers", "ee"])]
    pub rotation: Option<RotationArg>,
    /// Substitute the lengths (a2, d4, ...) by their values in metres.
    #[arg(long)]
    pub numbers: bool,
    /// The end-effector whose chain is written (a name or an index; default: end-effector 0).
    #[arg(long)]
    pub ee: Option<String>,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    pub format: SymbolicFormat,
}

/// The grammar of the JSON strings, in one sentence (also in the JSON output).
pub const GRAMMAR: &str = "names: cK, sK = cos, sin of joint variable qK; c23, s23 = cos, sin of q2 + q3 (with 10 or more variables the indices are separated by '_': c1_2); aK, dK = constant DH lengths (m); dK = the prismatic variable qK where it is its row's DH length, qK otherwise (m); for rotations: c_phi, s_phi, c_theta, s_theta, c_psi, s_psi = cos, sin of the angles phi, theta, psi (rad), r_x, r_y, r_z = the unit axis' components, eta, epsilon_x, epsilon_y, epsilon_z = the unit quaternion's scalar and vector parts; numbers; + - * / ^ and parentheses";

/// Runs `armlab symbolic`.
pub(super) fn run(args: &SymbolicArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let model = match (&args.model, args.rotation) {
        (None, Some(rotation)) => return run_rotation(rotation.into(), args.format, out),
        (Some(model), None) => model,
        // clap refuses both and neither before this runs
        _ => return Err(CliError::Usage("give either a MODEL or --rotation")),
    };
    let mut robot = super::load_model(model)?;
    let ee = super::ik::end_effector(&mut robot, args.ee.as_deref())?;
    let options = Options {
        numbers: args.numbers,
    };
    let sk = derive(&robot, ee, &options).map_err(|e| CliError::BadTarget {
        source_name: model.clone(),
        reason: e.to_string(),
    })?;
    match args.format {
        SymbolicFormat::Text => write!(out, "{}", document::text(&sk, args.numbers))?,
        SymbolicFormat::Latex => write!(out, "{}", document::latex(&sk))?,
        SymbolicFormat::Markdown => write!(out, "{}", document::markdown(&sk, args.numbers))?,
        SymbolicFormat::Json => write_json(&to_json(&sk), out)?,
    }
    Ok(())
}

/// `armlab symbolic --rotation R`.
fn run_rotation(
    representation: Representation,
    format: SymbolicFormat,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let r = derive_rotation(representation);
    match format {
        SymbolicFormat::Text => write!(out, "{}", document::rotation_text(&r))?,
        SymbolicFormat::Latex => write!(out, "{}", document::rotation_latex(&r))?,
        SymbolicFormat::Markdown => write!(out, "{}", document::rotation_markdown(&r))?,
        SymbolicFormat::Json => write_json(&rotation_to_json(&r), out)?,
    }
    Ok(())
}

/// Pretty JSON and a newline.
fn write_json(v: &Value, out: &mut dyn Write) -> Result<(), CliError> {
    serde_json::to_writer_pretty(&mut *out, v).map_err(std::io::Error::from)?;
    writeln!(out)?;
    Ok(())
}

/// The JSON document of a rotation: `rotation` (the flag's value), `equation`, `formula`,
/// `variables` (name and unit), `symbols` (each name the entries use, with its meaning),
/// `constraint` (the unit norm, or null), `R` (3x3 strings, rows) and `grammar`, the same as
/// the arms'.
pub fn rotation_to_json(r: &SymbolicRotation) -> Value {
    let rep = r.representation;
    let variables: Vec<Value> = rep
        .variables()
        .iter()
        .map(|s| json!({"name": s.name(), "unit": if s.is_angle() { "rad" } else { "1" }}))
        .collect();
    let symbols: serde_json::Map<String, Value> = r
        .symbols()
        .iter()
        .filter_map(|f| {
            let name = write(&Poly::factor(f.clone()), Style::Json, false);
            Some((name, Value::from(document::meaning(f)?)))
        })
        .collect();
    json!({
        "rotation": rep.name(),
        "equation": rep.equation(),
        "formula": rep.formula(),
        "variables": variables,
        "symbols": symbols,
        "constraint": rep.constraint().map(|p| format!("{} = 1", write(&p, Style::Json, false))),
        "R": strings(&r.matrix, Style::Json, false),
        "grammar": GRAMMAR,
    })
}

/// A constant transform as strings of numbers (the same grammar).
fn constant_strings(p: &Pose) -> Value {
    let rows = pose_to_rows(p);
    json!(
        rows.iter()
            .map(|r| r.iter().map(|v| number(*v)).collect::<Vec<_>>())
            .collect::<Vec<_>>()
    )
}

/// The JSON document: `model`, `convention`, `symbols`, `A`, `T`, `p_W` (the keys), and
/// `variables`, `p`, `base`, `tool`, `grammar` besides.
pub fn to_json(sk: &SymbolicKinematics) -> Value {
    let sep = sk.separate_indices;
    let a: Vec<Value> = sk
        .links
        .iter()
        .map(|l| {
            json!({
                "from": l.from,
                "to": l.to,
                "joint": l.joint,
                "matrix": strings(&l.matrix, Style::Json, sep),
            })
        })
        .collect();
    let variables: Vec<Value> = sk
        .variables
        .iter()
        .map(|v| {
            let (q, passive) = match v.source {
                Source::Actuated(k) => (Some(k), false),
                Source::Passive(_) => (None, true),
            };
            json!({
                "index": v.index,
                "joint": v.joint,
                "kind": match v.kind { JointKind::Prismatic => "prismatic", _ => "revolute" },
                "q_index": q,
                "passive": passive,
            })
        })
        .collect();
    let t = sk.t();
    json!({
        "model": sk.model,
        "convention": sk.convention,
        "dh_derived": sk.derived_dh,
        "rounded_m": sk.rounded,
        "symbols": sk.symbols,
        "variables": variables,
        "A": a,
        "T": strings(&t, Style::Json, sep),
        "p": position(&t, Style::Json, sep),
        "p_W": sk.wrist.as_ref().map(|(_, w)| vector(w, Style::Json, sep)),
        "base": constant_strings(&sk.base),
        "tool": constant_strings(&sk.tool),
        "grammar": GRAMMAR,
    })
}
