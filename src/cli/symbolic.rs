//! `armlab symbolic`: the direct kinematics in symbols, in the textbook's notation.

use super::CliError;
use crate::kinematics::pose::pose_to_rows;
use crate::kinematics::symbolic::document::{self, position, strings, vector};
use crate::kinematics::symbolic::expr::{Style, number};
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

/// Arguments of `armlab symbolic`.
#[derive(Debug, clap::Args)]
pub struct SymbolicArgs {
    /// Built-in name or path to a .toml / .urdf model.
    pub model: String,
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
pub const GRAMMAR: &str = "names: cK, sK = cos, sin of joint variable qK; c23, s23 = cos, sin of q2 + q3 (with 10 or more variables the indices are separated by '_': c1_2); aK, dK = constant DH lengths (m); dK = the prismatic variable qK where it is its row's DH length, qK otherwise (m); numbers; + - * / ^ and parentheses";

/// Runs `armlab symbolic`.
pub(super) fn run(args: &SymbolicArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let mut robot = super::load_model(&args.model)?;
    let ee = super::ik::end_effector(&mut robot, args.ee.as_deref())?;
    let options = Options {
        numbers: args.numbers,
    };
    let sk = derive(&robot, ee, &options).map_err(|e| CliError::BadTarget {
        source_name: args.model.clone(),
        reason: e.to_string(),
    })?;
    match args.format {
        SymbolicFormat::Text => write!(out, "{}", document::text(&sk, args.numbers))?,
        SymbolicFormat::Latex => write!(out, "{}", document::latex(&sk))?,
        SymbolicFormat::Markdown => write!(out, "{}", document::markdown(&sk, args.numbers))?,
        SymbolicFormat::Json => {
            serde_json::to_writer_pretty(&mut *out, &to_json(&sk)).map_err(std::io::Error::from)?;
            writeln!(out)?;
        }
    }
    Ok(())
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
