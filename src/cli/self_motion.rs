//! `armlab self-motion`: the exact self-motion of a redundant arm holding its hand still.

use super::{CliError, Format};
use crate::kinematics::{Pose, Robot};
use crate::redundancy::srs::SrsArm;
use crate::redundancy::{BranchSolution, PlanarSelfMotion};
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

/// A computed self-motion, whatever the arm.
struct Motion {
    parameter: &'static str,
    names: Vec<String>,
    samples: Vec<(f64, Vec<BranchSolution>)>,
    feasible: Vec<Vec<[f64; 2]>>,
    manifolds: usize,
    singular: bool,
    what: String,
}

/// The parameter values: `n` samples covering [-pi, pi) evenly.
fn grid(n: usize) -> impl Iterator<Item = f64> {
    (0..n).map(move |k| -std::f64::consts::PI + std::f64::consts::TAU * k as f64 / n as f64)
}

/// The SRS arm angle of a 7R arm.
fn srs(robot: &Robot, arm: &SrsArm, target: &Pose, n: usize) -> Motion {
    let p = target.translation.vector;
    Motion {
        parameter: "arm angle",
        names: SrsArm::branch_names().to_vec(),
        samples: grid(n)
            .map(|psi| (psi, arm.branch_solutions(robot, target, psi)))
            .collect(),
        feasible: arm.feasible_intervals(target).to_vec(),
        manifolds: arm.manifolds(target),
        singular: arm.singular(target),
        what: format!("holding its hand at ({:.6}, {:.6}, {:.6}) m", p.x, p.y, p.z),
    }
}

/// The orientation phi of a three-link planar arm with a position task.
fn planar(
    robot: &Robot,
    target: &Pose,
    n: usize,
    bad: &dyn Fn(String) -> CliError,
) -> Result<Motion, CliError> {
    let frame = crate::workspace::planar_frame(robot, 0).ok_or_else(|| {
        bad(format!(
            "exact self-motion is available for SRS 7R arms (arm angle) and three-link planar \
             arms (phi); {} is neither (the Panda's q7 and numerical self-motion are not \
             implemented yet)",
            robot.name
        ))
    })?;
    let p = target.translation.vector;
    let xy = frame.to_plane([p.x, p.y, p.z]);
    let motion = PlanarSelfMotion::new(robot, xy).map_err(|e| bad(e.to_string()))?;
    let (feasible, _) = motion.feasible();
    Ok(Motion {
        parameter: "phi",
        names: motion.branch_names().to_vec(),
        samples: grid(n)
            .map(|phi| (phi, motion.solutions(robot, phi)))
            .collect(),
        feasible: feasible.to_vec(),
        manifolds: motion.manifolds(robot),
        singular: false,
        what: format!("holding its hand at ({:.6}, {:.6}) m", xy[0], xy[1]),
    })
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
    let mut motion = match SrsArm::detect(&robot) {
        Some(arm) => {
            if arm.solve(&pose, 0.0).is_empty() && !arm.singular(&pose) {
                return Err(bad("the pose's wrist centre is out of reach".into()));
            }
            srs(&robot, &arm, &pose, args.samples)
        }
        None => planar(&robot, &pose, args.samples, &bad)?,
    };
    if let Some(b) = &args.branch {
        let Some(k) = motion.names.iter().position(|n| n == b) else {
            return Err(bad(format!(
                "no branch {b:?} (the branches are: {})",
                motion.names.join("; ")
            )));
        };
        for (_, s) in &mut motion.samples {
            s.retain(|x| &x.name == b);
        }
        motion.names = vec![motion.names[k].clone()];
        motion.feasible = vec![motion.feasible[k].clone()];
    }
    if let Some(path) = &args.out {
        let img = crate::figure::self_motion::figure(
            &robot,
            motion.parameter,
            &motion.samples,
            &motion.feasible,
            &motion.names,
        )?;
        crate::headless::write_png(&img, path)?;
    }
    match args.format {
        Format::Json => write_json(&motion, out),
        Format::Text => write_text(&robot, &motion, out),
    }
}

fn write_json(m: &Motion, out: &mut dyn std::io::Write) -> Result<(), CliError> {
    let mut feas = serde_json::Map::new();
    for (name, iv) in m.names.iter().zip(&m.feasible) {
        feas.insert(name.clone(), serde_json::json!(iv));
    }
    let v = serde_json::json!({
        "parameter": m.parameter,
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

fn write_text(robot: &Robot, m: &Motion, out: &mut dyn std::io::Write) -> Result<(), CliError> {
    writeln!(
        out,
        "self-motion of the {} {}: parameter {}, {} disjoint self-motion curve(s) inside the \
         limits{}",
        robot.name.to_lowercase(),
        m.what,
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
