//! `armlab self-motion`: the exact self-motion of a redundant arm holding its hand still.

use super::{CliError, Format};
use crate::kinematics::{Pose, Robot};
use crate::redundancy::sampler::{SelfMotionSamples, sample_self_motion_in};
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
    /// A scene file of obstacles (TOML `[[obstacle]]` tables): the feasible intervals lose
    /// the stretches where the arm hits itself or an obstacle (their ends refined by bisection
    /// to 1e-6 rad); each colliding stretch is given with the pair it hits.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
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
    let world = match &args.scene {
        Some(path) => {
            let cell = crate::collision::CellScene::read(path)?;
            Some(crate::collision::CollisionWorld::new(&robot, &cell)?)
        }
        None => None,
    };
    let mut motion = sample_self_motion_in(&robot, ee, &pose, args.samples, locked, world.as_ref())
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
    let mut v = serde_json::json!({
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
    if let Some(c) = &m.collisions {
        let mut free = serde_json::Map::new();
        let mut colliding = serde_json::Map::new();
        for (k, name) in m.names.iter().enumerate() {
            free.insert(name.clone(), serde_json::json!(c.free.get(k)));
            let stretches: Vec<serde_json::Value> = c
                .colliding
                .iter()
                .filter(|s| s.branch == k)
                .map(|s| {
                    serde_json::json!({
                        "from": s.from, "to": s.to, "a": s.a, "b": s.b, "depth_m": s.depth_m,
                    })
                })
                .collect();
            colliding.insert(name.clone(), serde_json::json!(stretches));
        }
        v["collision_free"] = serde_json::Value::Object(free);
        v["colliding"] = serde_json::Value::Object(colliding);
        v["collision_step"] = serde_json::json!(c.options.step);
        v["collision_tolerance"] = serde_json::json!(c.options.tolerance);
    }
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
    if let Some(c) = &m.collisions {
        write_cell_text(m, c, out)?;
    }
    Ok(())
}

/// The collision-free intervals and the colliding stretches, branch by branch.
fn write_cell_text(
    m: &SelfMotionSamples,
    c: &crate::redundancy::collision::CollisionFreeMotion,
    out: &mut dyn std::io::Write,
) -> Result<(), CliError> {
    writeln!(
        out,
        "in the cell (every {:.2} deg checked, ends refined by bisection to {:.0e} rad):",
        c.options.step.to_degrees(),
        c.options.tolerance
    )?;
    let deg = |x: f64| x.to_degrees();
    for (k, name) in m.names.iter().enumerate() {
        let free: Vec<String> = c.free[k]
            .iter()
            .map(|i| format!("[{:.4}, {:.4}]", deg(i[0]), deg(i[1])))
            .collect();
        writeln!(
            out,
            "  {name}: collision-free {} (deg) {}",
            m.parameter,
            if free.is_empty() {
                "none".to_string()
            } else {
                free.join(" ")
            }
        )?;
        for s in c.colliding.iter().filter(|s| s.branch == k) {
            writeln!(
                out,
                "    [{:.4}, {:.4}] deg: {} hits {}, {:.1} mm",
                deg(s.from),
                deg(s.to),
                s.a,
                s.b,
                s.depth_m * 1000.0
            )?;
        }
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
