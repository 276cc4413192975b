//! `armlab self-motion`: the exact self-motion of a redundant arm holding its hand still.

use super::{CliError, Format};
use crate::redundancy::PlanarSelfMotion;
use std::path::PathBuf;

/// Arguments of `armlab self-motion`.
#[derive(Debug, clap::Args)]
pub struct SelfMotionArgs {
    /// Built-in name or path to a .toml / .urdf model.
    pub model: String,
    /// The hand pose: 16 numbers, a row-major 4x4 homogeneous transform (m). A planar arm's
    /// position task uses its position in the arm plane.
    #[arg(long, allow_hyphen_values = true)]
    pub pose: String,
    /// End-effector name (robots with several).
    #[arg(long)]
    pub ee: Option<String>,
    /// Samples of the parameter over [-pi, pi).
    #[arg(long, default_value_t = 360)]
    pub samples: usize,
    /// Only this branch (e.g. "elbow up").
    #[arg(long)]
    pub branch: Option<String>,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    pub format: Format,
    /// Write the self-motion figure (every joint over the parameter, limit bands) to this PNG.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Runs `self-motion`.
pub(super) fn run(args: &SelfMotionArgs, out: &mut dyn std::io::Write) -> Result<(), CliError> {
    let robot = crate::model_file::load_model(&args.model)?;
    if args
        .ee
        .as_deref()
        .is_some_and(|e| e != "0" && robot.end_effectors().len() < 2)
    {
        return Err(CliError::UnknownEndEffector {
            name: args.ee.clone().unwrap_or_default(),
            available: "0".into(),
        });
    }
    if args.samples == 0 || args.samples > 1_000_000 {
        return Err(CliError::Usage("--samples must be between 1 and 1000000"));
    }
    let values =
        super::input::parse_row(&args.pose, "--pose", 16, "numbers (a row-major 4x4 pose)")?;
    let m = nalgebra::Matrix4::from_row_slice(&values);
    let pose = crate::kinematics::pose::pose_from_matrix(&m).map_err(|e| CliError::BadTarget {
        source_name: "--pose".into(),
        reason: e.to_string(),
    })?;
    let bad = |reason: String| CliError::BadTarget {
        source_name: args.model.clone(),
        reason,
    };
    let frame = crate::workspace::planar_frame(&robot, 0).ok_or_else(|| {
        bad(format!(
            "exact self-motion is available for three-link planar arms with a position task; {} \
             is not one (the SRS arm angle, the Panda's q7 and numerical self-motion are not \
             implemented yet)",
            robot.name
        ))
    })?;
    let p = pose.translation.vector;
    let xy = frame.to_plane([p.x, p.y, p.z]);
    let motion = PlanarSelfMotion::new(&robot, xy).map_err(|e| bad(e.to_string()))?;
    let names = motion.branch_names();
    if let Some(b) = &args.branch
        && !names.iter().any(|n| n == b)
    {
        return Err(bad(format!(
            "no branch {b:?} (the branches are: {})",
            names.join(", ")
        )));
    }
    let keep = |name: &str| args.branch.as_deref().is_none_or(|b| b == name);
    let n = args.samples;
    let samples: Vec<(f64, Vec<crate::redundancy::BranchSolution>)> = (0..n)
        .map(|k| {
            let phi = -std::f64::consts::PI + std::f64::consts::TAU * k as f64 / n as f64;
            let mut s = motion.solutions(&robot, phi);
            s.retain(|b| keep(&b.name));
            (phi, s)
        })
        .collect();
    let (feasible, _merges) = motion.feasible();
    let manifolds = motion.manifolds();
    if let Some(path) = &args.out {
        let img = crate::figure::self_motion::figure(&robot, &samples, &feasible, &names)?;
        crate::headless::write_png(&img, path)?;
    }
    match args.format {
        Format::Json => {
            let mut feas = serde_json::Map::new();
            for (b, name) in names.iter().enumerate() {
                if keep(name) {
                    feas.insert(name.clone(), serde_json::json!(feasible[b]));
                }
            }
            let v = serde_json::json!({
                "parameter": motion.parameter(),
                "samples": samples.iter().map(|(phi, s)| serde_json::json!({
                    "value": phi,
                    "branches": s.iter().map(|b| serde_json::json!({
                        "name": b.name,
                        "q": b.q,
                        "within_limits": b.within_limits,
                        "position_error": b.position_error,
                        "orientation_error": b.orientation_error,
                    })).collect::<Vec<_>>(),
                })).collect::<Vec<_>>(),
                "feasible": feas,
                "manifolds": manifolds,
                "singular": false,
            });
            serde_json::to_writer(&mut *out, &v).map_err(std::io::Error::from)?;
            writeln!(out)?;
        }
        Format::Text => {
            writeln!(
                out,
                "self-motion of the {} holding its hand at ({:.6}, {:.6}) m: parameter phi, {} \
                 disjoint self-motion curve(s) inside the limits",
                robot.name.to_lowercase(),
                xy[0],
                xy[1],
                manifolds
            )?;
            for (b, name) in names.iter().enumerate() {
                if keep(name) {
                    let iv: Vec<String> = feasible[b]
                        .iter()
                        .map(|i| format!("[{:.3}, {:.3}]", i[0].to_degrees(), i[1].to_degrees()))
                        .collect();
                    writeln!(out, "  {name}: feasible phi (deg) {}", iv.join(" "))?;
                }
            }
        }
    }
    Ok(())
}
