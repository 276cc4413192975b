//! `armlab self-motion`: the exact self-motion of a redundant arm holding its hand still.

use super::{CliError, Format};
use crate::kinematics::{Pose, Robot};
use crate::redundancy::sampler::{SelfMotionSamples, sample_self_motion_locked};
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
    /// End-effector, by name (any link of a URDF) or 0-based index (default: the tool of the longest arm); on a
    /// robot with several, the self-motion of the chain from the root to it alone.
    #[arg(long)]
    pub ee: Option<String>,
    /// Samples of the parameter over [-pi, pi).
    #[arg(long, default_value_t = 360, value_parser = super::count)]
    pub samples: usize,
    /// Only this branch (e.g. "elbow up").
    #[arg(long)]
    pub branch: Option<String>,
    /// Lock this joint (1-based) of a seven-joint arm and use its angle as the parameter,
    /// instead of the one armlab picks (q3 for most arms; the arm angle of an SRS arm, q7 of the
    /// Panda).
    #[arg(long, value_parser = clap::value_parser!(u8).range(1..=7))]
    pub lock: Option<u8>,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    pub format: Format,
    /// Write the self-motion figure (every joint over the parameter, limit bands) to this file
    /// (PNG, SVG or PDF by its extension).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Runs `self-motion`.
pub(super) fn run(args: &SelfMotionArgs, out: &mut dyn std::io::Write) -> Result<(), CliError> {
    let (robot, ee) = super::arm_robot(super::load_model(&args.model)?, args.ee.as_deref())?;
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
    if args.lock.is_some() && robot.dof() != 7 {
        return Err(CliError::Usage(
            "--lock needs an arm of seven joints (a joint of it is locked)",
        ));
    }
    let locked = args.lock.map(|k| usize::from(k) - 1);
    let mut motion = sample_self_motion_locked(&robot, ee, &pose, args.samples, locked)
        .map_err(|e| bad(e.to_string()))?;
    if let Some(b) = &args.branch {
        motion.keep_branch(b).map_err(|e| bad(e.to_string()))?;
    }
    if let Some(path) = &args.out {
        let mut figs = crate::headless::figures_for(path)?;
        let img = crate::figure::self_motion::figure(&mut figs, &robot, &motion)?;
        crate::headless::write_figure(&mut figs, &img, path)?;
    }
    match args.format {
        Format::Json => write_json(&motion, out),
        Format::Text => write_text(&robot, &pose, &motion, out),
    }
}

fn write_json(m: &SelfMotionSamples, out: &mut dyn std::io::Write) -> Result<(), CliError> {
    let mut feas = serde_json::Map::new();
    for (name, iv) in m.names.iter().zip(&m.feasible) {
        feas.insert(name.clone(), serde_json::json!(iv));
    }
    let v = serde_json::json!({
        "parameter": m.parameter,
        "parameter_meaning": m.meaning,
        "samples": m.samples.iter().map(|(value, s)| serde_json::json!({
            "value": value,
            "branches": s.iter().map(|b| serde_json::json!({
                "name": b.name,
                "q": b.q,
                "within_limits": b.within_limits,
                "position_error": b.position_error,
                "orientation_error": b.orientation_error,
            })).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
        "feasible": feas,
        "manifolds": m.manifolds,
        "singular": m.singular,
    });
    serde_json::to_writer(&mut *out, &v).map_err(std::io::Error::from)?;
    writeln!(out)?;
    Ok(())
}

fn write_text(
    robot: &Robot,
    pose: &Pose,
    m: &SelfMotionSamples,
    out: &mut dyn std::io::Write,
) -> Result<(), CliError> {
    writeln!(
        out,
        "self-motion of the {} {}: parameter {}, {} disjoint self-motion curve(s) inside the \
         limits{}",
        robot.name.to_lowercase(),
        holding(pose, m),
        m.parameter,
        m.manifolds,
        if m.singular {
            " (algorithmic singularity: the shoulder-wrist line is along axis 1)"
        } else {
            ""
        }
    )?;
    for (name, iv) in m.names.iter().zip(&m.feasible) {
        let iv: Vec<String> = iv
            .iter()
            .map(|i| format!("[{:.3}, {:.3}]", i[0].to_degrees(), i[1].to_degrees()))
            .collect();
        writeln!(
            out,
            "  {name}: feasible {} (deg) {}",
            m.parameter,
            iv.join(" ")
        )?;
    }
    Ok(())
}

/// "holding its hand at (x, y, z) m; <what the parameter is>".
fn holding(pose: &Pose, m: &SelfMotionSamples) -> String {
    let p = pose.translation.vector;
    format!(
        "holding its hand at ({:.6}, {:.6}, {:.6}) m; {}",
        p.x, p.y, p.z, m.meaning
    )
}
