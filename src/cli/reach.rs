//! `armlab reach`: point queries against the workspace.

use super::{CliError, Format};
use crate::workspace::{PointQuery, TrackedPoint};
use std::path::PathBuf;

/// Arguments of `armlab reach`.
#[derive(Debug, clap::Args)]
pub struct ReachArgs {
    /// Built-in name or path to a .toml / .urdf model.
    pub model: String,
    /// End-effector, by name (any link of a URDF) or 0-based index (default: the tool of the longest arm). On a
    /// robot with several, the command works on the chain from the root to it alone.
    #[arg(long)]
    pub ee: Option<String>,
    /// Points, one per line: `x,y` (plane coordinates, m) for planar arms, `x,y,z` (world
    /// frame, m) otherwise; `#` comments and blank lines ignored; `-` for stdin.
    #[arg(long)]
    pub input: PathBuf,
    /// The tracked point of an arm with a spherical wrist.
    #[arg(long, value_enum, default_value_t)]
    pub point: super::figures::PointArg,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    pub format: Format,
}

/// Runs `reach`.
pub(super) fn run(args: &ReachArgs, out: &mut dyn std::io::Write) -> Result<(), CliError> {
    let (robot, _) = super::arm_robot(super::load_model(&args.model)?, args.ee.as_deref())?;
    let point = match args.point {
        super::figures::PointArg::WristCentre => TrackedPoint::WristCentre,
        super::figures::PointArg::Flange => TrackedPoint::Flange,
    };
    let query = PointQuery::new(&robot, point).map_err(|e| CliError::BadTarget {
        source_name: args.model.clone(),
        reason: e.to_string(),
    })?;
    let what = if query.dimension() == 2 {
        "coordinates (x,y)"
    } else {
        "coordinates (x,y,z)"
    };
    let rows = super::input::read_rows(&args.input, query.dimension(), what)?;
    let answers: Vec<_> = rows.iter().map(|p| query.query(p)).collect();
    match args.format {
        Format::Json => {
            let v: Vec<serde_json::Value> = rows
                .iter()
                .zip(&answers)
                .map(|(p, a)| {
                    serde_json::json!({
                        "point": p,
                        "reachable": a.reachable,
                        "postures": a.postures,
                        "distance": a.distance,
                    })
                })
                .collect();
            serde_json::to_writer_pretty(&mut *out, &v).map_err(std::io::Error::from)?;
            writeln!(out)?;
        }
        Format::Text => {
            for (p, a) in rows.iter().zip(&answers) {
                let coords: Vec<String> = p.iter().map(|v| format!("{v}")).collect();
                let postures = if a.postures.is_empty() {
                    String::new()
                } else {
                    format!(" ({})", a.postures.join("; "))
                };
                writeln!(
                    out,
                    "{}: {}{postures}, distance to the boundary {:+.6} m{}",
                    coords.join(","),
                    if a.reachable {
                        "reachable"
                    } else {
                        "not reachable"
                    },
                    a.distance,
                    if query.distance_exact() {
                        ""
                    } else {
                        " (estimated)"
                    }
                )?;
            }
        }
    }
    Ok(())
}
