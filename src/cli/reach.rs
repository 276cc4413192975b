//! `armlab reach`: point queries against the workspace.

use super::{CliError, Format};
use crate::workspace::cell::{CellChecker, PostureVerdict};
use crate::workspace::{PointQuery, ReachAnswer, TrackedPoint};
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
    /// A scene file of obstacles (TOML `[[obstacle]]` tables): each posture that reaches a
    /// point is also checked against the arm itself and the obstacles, and the collision-free
    /// ones are listed (the others with what they hit).
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
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
    let cell = match &args.scene {
        Some(path) => Some(crate::collision::CellScene::read(path)?),
        None => None,
    };
    let checker = match &cell {
        Some(c) => Some(
            CellChecker::new(&robot, c, point).map_err(|e| CliError::BadTarget {
                source_name: args.model.clone(),
                reason: e.to_string(),
            })?,
        ),
        None => None,
    };
    let what = if query.dimension() == 2 {
        "coordinates (x,y)"
    } else {
        "coordinates (x,y,z)"
    };
    let rows = super::input::read_rows(&args.input, query.dimension(), what)?;
    let answers: Vec<_> = rows.iter().map(|p| query.query(p)).collect();
    let verdicts: Vec<Option<Vec<PostureVerdict>>> = rows
        .iter()
        .zip(&answers)
        .map(|(p, a)| checker.as_ref().map(|c| in_cell(c, &robot, p, a)))
        .collect();
    match args.format {
        Format::Json => {
            let v: Vec<serde_json::Value> = rows
                .iter()
                .zip(&answers)
                .zip(&verdicts)
                .map(|((p, a), cell)| {
                    let mut v = serde_json::json!({
                        "point": p,
                        "reachable": a.reachable,
                        "postures": a.postures,
                        "distance": a.distance,
                    });
                    if let Some(verdicts) = cell {
                        add_json(&mut v, verdicts);
                    }
                    v
                })
                .collect();
            serde_json::to_writer_pretty(&mut *out, &v).map_err(std::io::Error::from)?;
            writeln!(out)?;
        }
        Format::Text => write_text(&rows, &answers, &verdicts, query.distance_exact(), out)?,
    }
    Ok(())
}

/// The text answers: one line per point.
fn write_text(
    rows: &[Vec<f64>],
    answers: &[ReachAnswer],
    verdicts: &[Option<Vec<PostureVerdict>>],
    exact: bool,
    out: &mut dyn std::io::Write,
) -> Result<(), CliError> {
    for ((p, a), cell) in rows.iter().zip(answers).zip(verdicts) {
        let coords: Vec<String> = p.iter().map(|v| format!("{v}")).collect();
        let postures = if a.postures.is_empty() {
            String::new()
        } else {
            format!(" ({})", a.postures.join("; "))
        };
        writeln!(
            out,
            "{}: {}{postures}, distance to the boundary {:+.6} m{}{}",
            coords.join(","),
            if a.reachable {
                "reachable"
            } else {
                "not reachable"
            },
            a.distance,
            if exact { "" } else { " (estimated)" },
            cell.as_ref().map(|v| cell_text(v)).unwrap_or_default()
        )?;
    }
    Ok(())
}

/// The postures of `a` at point `p` (plane or world coordinates) checked in the cell: those
/// the query names, in its order.
fn in_cell(
    checker: &CellChecker<'_>,
    robot: &crate::kinematics::Robot,
    p: &[f64],
    a: &ReachAnswer,
) -> Vec<PostureVerdict> {
    let world = if p.len() == 2 {
        match crate::workspace::planar_frame(robot, 0) {
            Some(f) => f.to_world([p[0], p[1]]),
            None => return Vec::new(),
        }
    } else {
        [p[0], p[1], p[2]]
    };
    let all = checker.postures(world);
    a.postures
        .iter()
        .filter_map(|name| all.iter().find(|v| &v.name == name).cloned())
        .collect()
}

/// The keys a cell adds to a point's JSON: `collision_free_postures` (names) and
/// `colliding_postures` (`{"posture", "pairs": [{"a", "b", "depth_m", "at"}]}`).
fn add_json(v: &mut serde_json::Value, verdicts: &[PostureVerdict]) {
    let free: Vec<&str> = verdicts
        .iter()
        .filter(|x| x.free)
        .map(|x| x.name.as_str())
        .collect();
    let colliding: Vec<serde_json::Value> = verdicts
        .iter()
        .filter(|x| !x.free)
        .map(|x| serde_json::json!({"posture": x.name, "q": x.q, "pairs": x.contacts}))
        .collect();
    v["reachable_collision_free"] = serde_json::json!(!free.is_empty());
    v["collision_free_postures"] = serde_json::json!(free);
    v["colliding_postures"] = serde_json::json!(colliding);
}

/// "; collision-free: elbow up; elbow down hits: link3 hits table, 12 mm".
fn cell_text(verdicts: &[PostureVerdict]) -> String {
    let free: Vec<&str> = verdicts
        .iter()
        .filter(|x| x.free)
        .map(|x| x.name.as_str())
        .collect();
    let mut text = format!(
        "; collision-free: {}",
        if free.is_empty() {
            "none".to_string()
        } else {
            free.join("; ")
        }
    );
    for x in verdicts.iter().filter(|x| !x.free) {
        let hits: Vec<String> = x
            .contacts
            .iter()
            .map(|c| format!("{} hits {}, {:.1} mm", c.a, c.b, c.depth_m * 1000.0))
            .collect();
        text += &format!("; {}: {}", x.name, hits.join(", "));
    }
    text
}
