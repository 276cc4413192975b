//! `armlab self-motion`: the exact self-motion of a redundant arm holding its hand still.

use super::{CliError, Format};
use crate::kinematics::{Pose, Robot};
use crate::redundancy::motion::ExactSelfMotion;
use crate::redundancy::{BranchSolution, RedundancyError};
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
    #[arg(long, default_value_t = 360, value_parser = super::count)]
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

/// An exact self-motion (SRS arm angle, offset-elbow q7, planar phi), sampled.
fn exact(robot: &Robot, m: &ExactSelfMotion, n: usize) -> Motion {
    let p = m.target().translation.vector;
    Motion {
        parameter: m.parameter(),
        names: m.names().to_vec(),
        samples: grid(n).map(|v| (v, m.solutions(robot, v))).collect(),
        feasible: m.feasible().to_vec(),
        manifolds: m.manifolds(),
        singular: m.singular(),
        what: format!(
            "holding its hand at ({:.6}, {:.6}, {:.6}) m; {}",
            p.x,
            p.y,
            p.z,
            m.parameter_meaning()
        ),
    }
}

/// Any other redundant chain: numerical IK to the pose from the "ready" configuration (or
/// zero), then the drift-free numerical self-motion, sampled by arc length in joint space.
fn numerical(
    robot: &Robot,
    ee: usize,
    target: &Pose,
    n: usize,
    bad: &dyn Fn(String) -> CliError,
) -> Result<Motion, CliError> {
    use crate::kinematics::ik::numerical::{NumericalOptions, solve};
    use crate::redundancy::numerical::NullSpaceMotion;
    let red = crate::kinematics::redundancy::Redundancy::of(
        robot,
        crate::kinematics::redundancy::Task::Pose,
    );
    if red.degree() <= 0 {
        return Err(bad(format!(
            "{} is not redundant for a full pose ({red}): it has no self-motion",
            robot.name
        )));
    }
    let seed = robot
        .config("ready")
        .map_or_else(|| vec![0.0; robot.dof()], <[f64]>::to_vec);
    let rep = solve(
        robot,
        ee,
        &crate::kinematics::ik::Target::Pose(*target),
        &seed,
        &NumericalOptions::default(),
    )
    .map_err(|e| bad(e.to_string()))?;
    if !rep.converged {
        return Err(bad(format!(
            "numerical IK did not reach the pose (error {:.3e} m, {:.3e} rad)",
            rep.position_error, rep.orientation_error
        )));
    }
    let start = NullSpaceMotion::new(robot, ee, &rep.q, None).map_err(|e| bad(e.to_string()))?;
    let name = "self-motion".to_string();
    let h = std::f64::consts::TAU / n as f64;
    let sol = |m: &NullSpaceMotion| -> Result<BranchSolution, CliError> {
        let (pe, oe) = m.errors().map_err(|e| bad(e.to_string()))?;
        Ok(BranchSolution {
            name: name.clone(),
            q: m.q().to_vec(),
            within_limits: robot.within_limits(m.q(), 1e-12),
            position_error: pe,
            orientation_error: oe,
        })
    };
    let mut values = walk(&start, n, &sol)?;
    values.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Feasible stretches from the samples (not exact: the numerical case has no closed form).
    let mut feasible: Vec<[f64; 2]> = Vec::new();
    for (v, b) in &values {
        if b.first().is_some_and(|x| x.within_limits) {
            match feasible.last_mut() {
                Some(l) if (l[1] - (v - h)).abs() < 1e-9 => l[1] = *v,
                _ => feasible.push([*v, *v]),
            }
        }
    }
    let p = target.translation.vector;
    Ok(Motion {
        parameter: "arc length",
        names: vec![name.clone()],
        samples: values,
        feasible: vec![feasible],
        manifolds: 1,
        singular: false,
        what: format!(
            "holding its hand at ({:.6}, {:.6}, {:.6}) m (numerical: the curve through the IK \
             solution; feasible stretches from the samples)",
            p.x, p.y, p.z
        ),
    })
}

/// Samples of the numerical self-motion at `n` arc lengths covering [-pi, pi): from s = 0
/// forwards and backwards, in sub-steps of at most 0.01 rad; a sample past a singularity has no
/// branch.
fn walk(
    start: &crate::redundancy::numerical::NullSpaceMotion,
    n: usize,
    sol: &dyn Fn(
        &crate::redundancy::numerical::NullSpaceMotion,
    ) -> Result<BranchSolution, CliError>,
) -> Result<Vec<(f64, Vec<BranchSolution>)>, CliError> {
    let h = std::f64::consts::TAU / n as f64;
    let mut values: Vec<(f64, Vec<BranchSolution>)> = Vec::with_capacity(n);
    for dir in [1.0, -1.0] {
        let mut m = start.clone();
        let mut s = 0.0;
        let ks: Vec<usize> = if dir > 0.0 {
            (n / 2..n).collect()
        } else {
            (0..n / 2).rev().collect()
        };
        for k in ks {
            let value = -std::f64::consts::PI + h * k as f64;
            while (value - s).abs() > 1e-12 {
                let ds = (value - s).clamp(-0.01, 0.01);
                if m.step(ds).is_err() {
                    break;
                }
                s += ds;
            }
            let branch = if (value - s).abs() <= 1e-12 {
                vec![sol(&m)?]
            } else {
                Vec::new()
            };
            values.push((value, branch));
        }
    }
    Ok(values)
}

/// Whether the robot has the shape of an exact self-motion (so that a failure is the pose's, not
/// a reason to fall back on the numerical one).
fn exact_shape(robot: &Robot) -> bool {
    crate::redundancy::srs::SrsArm::detect(robot).is_some()
        || crate::redundancy::offset_elbow::OffsetElbowArm::detect(robot).is_some()
        || (crate::workspace::planar_frame(robot, 0).is_some() && matches!(robot.dof(), 2..=4))
}

/// Runs `self-motion`.
pub(super) fn run(args: &SelfMotionArgs, out: &mut dyn std::io::Write) -> Result<(), CliError> {
    let robot = super::load_model(&args.model)?;
    let ee = super::ik::end_effector(&robot, args.ee.as_deref())?;
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
    let mut motion = match ExactSelfMotion::new(&robot, &pose) {
        _ if ee != 0 => numerical(&robot, ee, &pose, args.samples, &bad)?,
        Ok(m) => exact(&robot, &m, args.samples),
        Err(RedundancyError::NotSupported(why)) if exact_shape(&robot) => return Err(bad(why)),
        Err(RedundancyError::NotSupported(_)) => numerical(&robot, 0, &pose, args.samples, &bad)?,
        Err(e) => return Err(bad(e.to_string())),
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
