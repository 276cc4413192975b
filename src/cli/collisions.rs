//! `armlab collisions`: what a configuration hits (the arm's own links and a cell's obstacles),
//! and the allowed-collision matrix, sampled as MoveIt's Setup Assistant samples it, read from
//! an SRDF, written as one or stored in a TOML model file.

use super::{CliError, Format, JointInput, joint_vectors};
use crate::collision::{
    AllowedCollisions, CellScene, CollisionReport, CollisionWorld, GeometryOptions, MatrixOptions,
    PairReason, RobotGeometry, parse_srdf, sample_matrix_with_progress, write_srdf,
};
use crate::kinematics::{DisabledPair, JointKind, Robot};
use serde_json::{Value, json};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Arguments of `armlab collisions`.
#[derive(Debug, clap::Args)]
pub struct CollisionsArgs {
    /// Built-in name or path to a .toml / .urdf model.
    pub model: String,
    /// The configurations to check (`--input`: one per line, every one answered).
    #[command(flatten)]
    pub joints: JointInput,
    /// A scene file of obstacles (TOML `[[obstacle]]` tables: box, cylinder, sphere, plane,
    /// mesh); without one only the arm's own links are checked.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
    /// Sample the allowed-collision matrix as MoveIt's Setup Assistant does and print every
    /// link pair with its verdict and why (adjacent pairs, pairs that always, never or by
    /// default collide are not checked).
    #[arg(long, conflicts_with_all = ["q", "q_deg", "config", "input", "srdf", "scene"])]
    pub matrix: bool,
    /// Random configurations within the joint limits the matrix samples (with --matrix;
    /// default 10,000, as MoveIt's Setup Assistant).
    #[arg(long, value_parser = super::count)]
    pub samples: Option<usize>,
    /// The seed of the matrix's random configurations (with --matrix; the same seed draws the
    /// same configurations).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Read the pairs never checked from a MoveIt SRDF (`<disable_collisions>`); adjacent
    /// links are never checked in any case.
    #[arg(long, value_name = "FILE")]
    pub srdf: Option<PathBuf>,
    /// Write the matrix (sampled with --matrix, read with --srdf, or stored in the model) as a
    /// MoveIt SRDF of `<disable_collisions>` elements.
    #[arg(long, value_name = "FILE")]
    pub write_srdf: Option<PathBuf>,
    /// Write the model as a TOML model file with the matrix (sampled with --matrix, or read
    /// with --srdf) stored in it as `[[disable_collisions]]` tables; later commands on that
    /// file check with it instead of sampling. Serial DH models only (a URDF: --write-srdf).
    #[arg(long, value_name = "FILE")]
    pub save_model: Option<PathBuf>,
    /// Split each mesh into convex pieces (a convex decomposition) instead of taking its hull:
    /// closer to a concave link, slower to build and to check.
    #[arg(long)]
    pub decompose: bool,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    pub format: Format,
}

/// Where the matrix in effect comes from.
#[derive(Debug, Clone, PartialEq)]
enum MatrixSource {
    /// Sampled now (`--matrix`).
    Sampled,
    /// Read from an SRDF (`--srdf`).
    Srdf(PathBuf),
    /// Stored in the model file (`[[disable_collisions]]`).
    Stored,
    /// Sampled quickly for the checks (the robot stores none; pairs that never collided stay
    /// checked): not worth writing.
    Quick,
}

impl MatrixSource {
    /// Where the matrix came from, in words.
    fn describe(&self, options: &MatrixOptions) -> String {
        match self {
            MatrixSource::Sampled => format!(
                "sampled over {} random configurations within the joint limits (seed {})",
                options.samples, options.seed
            ),
            MatrixSource::Srdf(path) => {
                format!("read from {} and the adjacent links", path.display())
            }
            MatrixSource::Stored => "stored in the model file".into(),
            MatrixSource::Quick => "sampled quickly over 1,000 configurations".into(),
        }
    }

    /// The word JSON gives it.
    fn word(&self) -> &'static str {
        match self {
            MatrixSource::Sampled => "sampled",
            MatrixSource::Srdf(_) => "srdf",
            MatrixSource::Stored => "model",
            MatrixSource::Quick => "quick",
        }
    }
}

/// Runs `armlab collisions`. Every input is read and checked (the configurations, the scene)
/// before anything is sampled or written.
pub(super) fn run(args: &CollisionsArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let robot = super::load_model(&args.model)?;
    let rows = refuse_early(&robot, args)?;
    let scene = match &args.scene {
        Some(path) => CellScene::read(path)?,
        None => CellScene::default(),
    };
    let options = GeometryOptions {
        decompose_meshes: args.decompose,
    };
    let geometry = RobotGeometry::of(&robot, options);
    let defaults = MatrixOptions::default();
    let matrix_options = MatrixOptions {
        samples: args.samples.unwrap_or(defaults.samples),
        seed: args.seed.unwrap_or(defaults.seed),
        ..defaults
    };
    let (matrix, source) = matrix_in_effect(&robot, &geometry, args, matrix_options)?;
    let described = source.describe(&matrix_options);
    // The checker before any file is written: a scene it refuses writes nothing.
    let world = match rows {
        Some(_) => Some(CollisionWorld::with(
            &robot,
            geometry.clone(),
            &scene,
            options,
            matrix.clone(),
        )?),
        None => None,
    };
    let written = write_matrix_files(&robot, &matrix, args)?;
    match (rows, world) {
        (Some(rows), Some(world)) => {
            warn(&world.warnings);
            let checks = Checks {
                robot: &robot,
                world: &world,
                scene: &scene,
                matrix: &described,
                single: args.joints.input.is_none(),
                degrees: args.joints.q_deg.is_some(),
            };
            write_checks(&checks, &rows, args.format, out)?;
        }
        _ => {
            warn(&robot.collision_warnings);
            warn(&geometry.warnings);
            write_matrix(&robot, &matrix, &source, &described, args.format, out)?;
        }
    }
    for path in written {
        match args.format {
            Format::Text => writeln!(out, "wrote {}", path.display())?,
            Format::Json => eprintln!("armlab: wrote {}", path.display()),
        }
    }
    Ok(())
}

/// The refusals that cost nothing (what to do is unclear, flags that do not go together, bad
/// joint values, a model a TOML file cannot hold), and the configurations to check (`None`: the
/// command is about the matrix).
fn refuse_early(robot: &Robot, args: &CollisionsArgs) -> Result<Option<Vec<Vec<f64>>>, CliError> {
    let j = &args.joints;
    let has_q = j.q.is_some() || j.q_deg.is_some() || j.config.is_some() || j.input.is_some();
    let writes = args.write_srdf.is_some() || args.save_model.is_some();
    if !has_q && !args.matrix && args.srdf.is_none() && !writes {
        return Err(CliError::Usage(
            "say what to check: a configuration (--q, --q-deg, --config or --input), or \
             --matrix to sample the allowed-collision matrix",
        ));
    }
    if !args.matrix && (args.samples.is_some() || args.seed.is_some()) {
        return Err(CliError::Usage(
            "--samples and --seed are how --matrix samples: add --matrix",
        ));
    }
    if !has_q && args.scene.is_some() {
        return Err(CliError::Usage(
            "--scene checks configurations: give one with --q, --q-deg, --config or --input",
        ));
    }
    if writes && !args.matrix && args.srdf.is_none() && robot.disabled_collisions.is_empty() {
        return Err(CliError::Usage(
            "no matrix to write: sample one with --matrix or read one with --srdf",
        ));
    }
    if args.save_model.is_some() && crate::model_file::to_toml(robot).is_none() {
        return Err(CliError::NotSerialDh {
            model: args.model.clone(),
        });
    }
    if !has_q {
        return Ok(None);
    }
    Ok(Some(joint_vectors(robot, &args.model, j, None)?))
}

/// Writes `--write-srdf` and `--save-model`; returns the files written.
fn write_matrix_files(
    robot: &Robot,
    matrix: &AllowedCollisions,
    args: &CollisionsArgs,
) -> Result<Vec<PathBuf>, CliError> {
    let mut written = Vec::new();
    if let Some(path) = &args.write_srdf {
        write_file(path, &write_srdf(matrix, &robot.name))?;
        written.push(path.clone());
    }
    if let Some(path) = &args.save_model {
        write_file(path, &model_with_matrix(robot, matrix, &args.model)?)?;
        written.push(path.clone());
    }
    Ok(written)
}

/// The matrix the command works with, and where it comes from: sampled (`--matrix`), read
/// (`--srdf`), stored in the model, or (none of those) a quick one for the checks.
fn matrix_in_effect(
    robot: &Robot,
    geometry: &RobotGeometry,
    args: &CollisionsArgs,
    options: MatrixOptions,
) -> Result<(AllowedCollisions, MatrixSource), CliError> {
    if args.matrix {
        if options.samples == 0 {
            return Err(CliError::Usage(
                "--samples must be at least 1 (MoveIt's Setup Assistant draws 10,000)",
            ));
        }
        let bar = crate::headless::Progress::new(options.samples as u64, "matrix");
        let matrix = sample_matrix_with_progress(robot, geometry, options, &|n| bar.set(n as u64))?;
        bar.finish();
        return Ok((matrix, MatrixSource::Sampled));
    }
    if let Some(path) = &args.srdf {
        let text = crate::input::read_text(path, crate::input::MAX_MODEL_BYTES, "an SRDF file")
            .map_err(|source| CliError::ReadFile {
                what: "the SRDF file",
                path: path.clone(),
                source,
            })?;
        let names: Vec<&str> = geometry.bodies.iter().map(|b| b.name.as_str()).collect();
        let mut matrix = AllowedCollisions::adjacent(robot, geometry);
        for (a, b, reason) in parse_srdf(&text, path, &names)? {
            // An SRDF's "Adjacent" pair that is not adjacent here is still the user's choice.
            matrix.add(&a, &b, reason);
        }
        with_checked_pairs(&mut matrix, geometry);
        return Ok((matrix, MatrixSource::Srdf(path.clone())));
    }
    let mut matrix = AllowedCollisions::for_robot(robot, geometry);
    if robot.disabled_collisions.is_empty() {
        return Ok((matrix, MatrixSource::Quick));
    }
    with_checked_pairs(&mut matrix, geometry);
    Ok((matrix, MatrixSource::Stored))
}

/// Adds every link pair a read matrix does not disable, as checked, so that the matrix lists
/// every pair.
fn with_checked_pairs(matrix: &mut AllowedCollisions, geometry: &RobotGeometry) {
    let names: Vec<&str> = geometry.bodies.iter().map(|b| b.name.as_str()).collect();
    for (i, a) in names.iter().enumerate() {
        for b in &names[i + 1..] {
            if !matrix.is_allowed(a, b) {
                matrix.add(a, b, PairReason::Checked);
            }
        }
    }
}

/// The model's TOML model file with `matrix` stored in it (every pair not checked).
fn model_with_matrix(
    robot: &Robot,
    matrix: &AllowedCollisions,
    model: &str,
) -> Result<String, CliError> {
    let mut robot = robot.clone();
    robot.disabled_collisions = matrix
        .disabled()
        .map(|p| DisabledPair {
            link1: p.a.clone(),
            link2: p.b.clone(),
            reason: p.reason.as_str().to_string(),
        })
        .collect();
    crate::model_file::to_toml(&robot).ok_or_else(|| CliError::NotSerialDh {
        model: model.to_string(),
    })
}

/// Writes `text` to `path`.
fn write_file(path: &Path, text: &str) -> Result<(), CliError> {
    std::fs::write(path, text).map_err(|source| CliError::WriteFile {
        path: path.to_path_buf(),
        source,
    })
}

/// Says each warning on stderr (each names the link, obstacle or file it is about).
pub(super) fn warn(warnings: &[String]) {
    for w in warnings {
        eprintln!("armlab: warning: {w}");
    }
}

/// The checker for a command that reports collisions next to something else (`ik`): the
/// robot's own links (with its stored matrix, or a quick sampled one) and, with `scene`, the
/// scene file's obstacles. Its warnings are said on stderr.
pub(super) fn world_for(robot: &Robot, scene: Option<&Path>) -> Result<CollisionWorld, CliError> {
    let scene = match scene {
        Some(path) => CellScene::read(path)?,
        None => CellScene::default(),
    };
    let world = CollisionWorld::new(robot, &scene)?;
    warn(&world.warnings);
    Ok(world)
}

/// What a report says after its summary in text: the nearest pair when free, or that nothing
/// is checked.
pub(super) fn report_line(report: &CollisionReport) -> String {
    let summary = report.summary();
    match (&report.closest, report.in_collision, report.clearance_m) {
        (_, _, None) => format!("{summary} (no pair of bodies is checked)"),
        (Some(c), false, _) => format!("{summary} (nearest: {} and {})", c.a, c.b),
        _ => summary,
    }
}

/// What the configurations are checked with.
struct Checks<'a> {
    robot: &'a Robot,
    world: &'a CollisionWorld,
    scene: &'a CellScene,
    /// Where the allowed-collision matrix comes from, in words.
    matrix: &'a str,
    /// One configuration (a JSON object) rather than a file of them (a JSON list).
    single: bool,
    /// Whether the configurations were given in degrees (`--q-deg`): they are shown so.
    degrees: bool,
}

/// Checks every configuration and prints the reports: in JSON one report (a single
/// configuration) or a list of them (`--input`); in text a line saying what is checked, then one
/// line per configuration.
fn write_checks(
    c: &Checks<'_>,
    rows: &[Vec<f64>],
    format: Format,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let (robot, world, scene, single) = (c.robot, c.world, c.scene, c.single);
    let reports = rows
        .iter()
        .map(|q| world.check(robot, q))
        .collect::<Result<Vec<_>, _>>()?;
    match format {
        Format::Json => {
            let v = if single {
                serde_json::to_value(&reports[0])
            } else {
                serde_json::to_value(&reports)
            }
            .map_err(std::io::Error::from)?;
            serde_json::to_writer_pretty(&mut *out, &v).map_err(std::io::Error::from)?;
            writeln!(out)?;
        }
        Format::Text => {
            let obstacles = match (&scene.path, scene.obstacles.len()) {
                (Some(p), n) => format!(" and {n} obstacle(s) of {}", p.display()),
                (None, _) => String::new(),
            };
            writeln!(
                out,
                "{}: its own links{obstacles}; {} pairs of bodies checked (matrix {})",
                robot.name,
                world.checked_pairs().len(),
                c.matrix
            )?;
            for (q, r) in rows.iter().zip(&reports) {
                writeln!(out, "{}: {}", q_text(robot, q, c.degrees), report_line(r))?;
            }
        }
    }
    Ok(())
}

/// A joint vector as it was given: "q = [0, 1.5708, -0.5] (rad)", or with `degrees`
/// "q = [0, 90, -45.5] (deg)"; prismatic joints in m.
fn q_text(robot: &Robot, q: &[f64], degrees: bool) -> String {
    let mut prismatic = false;
    let items: Vec<String> = q
        .iter()
        .enumerate()
        .map(|(k, &v)| {
            let (v, decimals) = match robot.dof_joint(k).kind {
                JointKind::Revolute if degrees => (v.to_degrees(), 3),
                JointKind::Revolute => (v, 6),
                _ => {
                    prismatic = true;
                    (v, 6)
                }
            };
            let s = format!("{:.*}", decimals, super::fk::tidy(v));
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        })
        .collect();
    let angles = if degrees { "deg" } else { "rad" };
    let units = if prismatic {
        format!("{angles}, m")
    } else {
        angles.to_string()
    };
    format!("q = [{}] ({units})", items.join(", "))
}

/// Prints the matrix: every pair with its verdict and why, in words or as JSON.
fn write_matrix(
    robot: &Robot,
    matrix: &AllowedCollisions,
    source: &MatrixSource,
    described: &str,
    format: Format,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let disabled = matrix.disabled().count();
    let checked = matrix.pairs.len() - disabled;
    match format {
        Format::Json => {
            let pairs: Vec<Value> = matrix
                .pairs
                .iter()
                .map(|p| {
                    json!({
                        "a": p.a,
                        "b": p.b,
                        "reason": p.reason,
                        "collided": p.collided,
                        "samples": p.samples,
                        "why": p.reason.explain(),
                    })
                })
                .collect();
            let v = json!({
                "robot": robot.name,
                "source": source.word(),
                "samples": matrix.pairs.iter().map(|p| p.samples).max().unwrap_or(0),
                "pairs": pairs,
                "disabled": disabled,
                "checked": checked,
            });
            serde_json::to_writer_pretty(&mut *out, &v).map_err(std::io::Error::from)?;
            writeln!(out)?;
        }
        Format::Text => {
            writeln!(
                out,
                "Allowed-collision matrix of {}: {described}",
                robot.name
            )?;
            writeln!(
                out,
                "{} link pairs: {disabled} never checked ({}), {checked} checked",
                matrix.pairs.len(),
                reason_counts(matrix)
            )?;
            write_matrix_rows(matrix, out)?;
        }
    }
    Ok(())
}

/// "4 Adjacent, 2 Never" over the disabled pairs.
fn reason_counts(matrix: &AllowedCollisions) -> String {
    let reasons = [
        PairReason::Adjacent,
        PairReason::Always,
        PairReason::Default,
        PairReason::Never,
        PairReason::User,
    ];
    let parts: Vec<String> = reasons
        .iter()
        .filter_map(|&r| {
            let n = matrix.pairs.iter().filter(|p| p.reason == r).count();
            (n > 0).then(|| format!("{n} {}", r.as_str()))
        })
        .collect();
    if parts.is_empty() {
        "none".into()
    } else {
        parts.join(", ")
    }
}

/// One aligned line per pair: the links, whether they are checked, and why (with how often
/// they collided where the matrix was sampled).
fn write_matrix_rows(matrix: &AllowedCollisions, out: &mut dyn Write) -> std::io::Result<()> {
    let wa = matrix.pairs.iter().map(|p| p.a.len()).max().unwrap_or(0);
    let wb = matrix.pairs.iter().map(|p| p.b.len()).max().unwrap_or(0);
    writeln!(out)?;
    for p in &matrix.pairs {
        let count = format!("{} of {} samples", p.collided, p.samples);
        let why = match p.reason {
            PairReason::Checked if p.samples > 0 => format!("checked      collided in {count}"),
            PairReason::Checked => "checked      (not disabled)".to_string(),
            PairReason::Always | PairReason::Default if p.samples > 0 => format!(
                "not checked  {}: {} (collided in {count})",
                p.reason.as_str(),
                p.reason.explain()
            ),
            PairReason::Never if p.samples > 0 => format!(
                "not checked  Never: {} ({} samples)",
                p.reason.explain(),
                p.samples
            ),
            r => format!("not checked  {}: {}", r.as_str(), r.explain()),
        };
        writeln!(out, "  {:<wa$}  {:<wb$}  {why}", p.a, p.b)?;
    }
    Ok(())
}
