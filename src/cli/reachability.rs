//! `armlab reachability`: the six-dimensional reachability map of an arm (issue 49), every
//! sample solved in closed form, written as a NumPy `.npz` and drawn as figures; `--map` reads a
//! map written before, to draw it again. Ctrl+C stops a map cleanly and writes nothing.

use super::{CliError, Format};
use crate::collision::CollisionWorld;
use crate::kinematics::Robot;
use crate::npz::{NpzData, NpzFile, NpzSlice, write_npz};
use crate::reachability::{
    MapControl, MapOptions, MapSolver, ReachabilityError, ReachabilityMap, VoxelGrid,
    compute_reachability, plan_grid,
};
use serde_json::json;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

/// Arguments of `armlab reachability`.
#[derive(Debug, clap::Args)]
pub struct ReachabilityArgs {
    /// Built-in name or path to a .toml / .urdf model.
    pub model: String,
    /// The end-effector (a name, any link of a URDF, or an index; default: the first).
    #[arg(long)]
    pub ee: Option<String>,
    /// Voxel edge (m); the grid covers the arm's reach.
    #[arg(long, default_value_t = 0.05)]
    pub voxel: f64,
    /// Approach directions per voxel (a Fibonacci sphere).
    #[arg(long, default_value_t = 200)]
    pub directions: usize,
    /// Rolls about each direction (2 pi j / R).
    #[arg(long, default_value_t = 8)]
    pub rolls: usize,
    /// A scene file of obstacles (TOML, as `armlab collisions --scene`): a solution counts only
    /// when it hits neither the arm itself nor the cell.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
    /// Compute even above 1e9 samples.
    #[arg(long)]
    pub force: bool,
    /// Seeds of the numerical solver per sample, for arms without a closed form.
    #[arg(long, default_value_t = 4, value_parser = super::count)]
    pub seeds: usize,
    /// The map file to write (NumPy .npz: `numpy.load` opens it).
    #[arg(long, value_name = "FILE", required_unless_present_any = ["map", "figure"])]
    pub out: Option<PathBuf>,
    /// Read this map (written by `armlab reachability --out`) instead of computing one, to
    /// draw its figures or print its summary.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["scene", "out", "force"])]
    pub map: Option<PathBuf>,
    /// Output format of the summary.
    #[arg(long, value_enum, default_value_t)]
    pub format: Format,
    /// Figures of the map (PNG, SVG or PDF by extension).
    #[command(flatten)]
    pub figures: super::reachability_figures::MapFigureArgs,
}

/// The Ctrl+C flag, installed once per process.
pub(super) fn interrupted() -> &'static AtomicBool {
    static FLAG: OnceLock<&'static AtomicBool> = OnceLock::new();
    FLAG.get_or_init(|| {
        let flag: &'static AtomicBool = Box::leak(Box::new(AtomicBool::new(false)));
        // Without a handler (another library holds the signal) Ctrl+C ends the process as
        // usual, which writes nothing either.
        let _ = ctrlc::set_handler(move || flag.store(true, Ordering::SeqCst));
        flag
    })
}

/// Runs `armlab reachability`.
pub(super) fn run(args: &ReachabilityArgs, out: &mut dyn Write) -> Result<(), CliError> {
    super::reachability_figures::check_figure_args(&args.figures, None)?;
    let mut robot = super::load_model(&args.model)?;
    let ee = super::ik::end_effector(&mut robot, args.ee.as_deref())?;
    let opts = MapOptions {
        ee,
        voxel_m: args.voxel,
        directions: args.directions,
        rolls: args.rolls,
        force: args.force,
        seeds: args.seeds,
    };
    let started = Instant::now();
    let map = match &args.map {
        Some(path) => read_map(path)?,
        None => compute(&robot, &opts, args)?,
    };
    let seconds = started.elapsed().as_secs_f64();
    if let Some(path) = &args.out {
        write_map(&map, path)?;
    }
    let b = robot.base.translation.vector;
    let figures = super::reachability_figures::write_figures(&map, [b.x, b.y, b.z], &args.figures)?;
    summary(&map, args, seconds, &figures, out)
}

/// Computes the map, with a progress bar and Ctrl+C; the options are checked first.
fn compute(
    robot: &Robot,
    opts: &MapOptions,
    args: &ReachabilityArgs,
) -> Result<ReachabilityMap, CliError> {
    let grid = plan_grid(robot, opts)?;
    if let Some(out) = &args.out {
        writable(out)?;
    }
    super::reachability_figures::check_figure_args(&args.figures, Some(&grid))?;
    let world = match &args.scene {
        Some(path) => Some(super::collisions::world_for(robot, Some(path))?),
        None => None,
    };
    let bar = crate::headless::Progress::new(grid.len() as u64, "reachability");
    let progress = |done: usize, _total: usize| bar.set(done as u64);
    let control = MapControl {
        cancel: Some(interrupted()),
        progress: Some(&progress),
    };
    let map = compute_reachability(
        robot,
        opts,
        world.as_ref().map(|w: &CollisionWorld| w),
        control,
    );
    bar.finish();
    if let Err(ReachabilityError::Cancelled { .. }) = &map {
        eprintln!("armlab reachability: stopped by Ctrl+C; no file written");
    }
    Ok(map?)
}

/// Refuses, before any work, an output file whose folder does not exist.
fn writable(path: &Path) -> Result<(), CliError> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if dir.is_dir() {
        return Ok(());
    }
    Err(CliError::WriteFile {
        path: path.to_path_buf(),
        source: std::io::Error::new(
            std::io::ErrorKind::NotFound,
            format!("the folder {} does not exist", dir.display()),
        ),
    })
}

/// Writes the map as a compressed .npz with the arrays (and `size`, `solver`,
/// `collisions`).
pub(super) fn write_map(map: &ReachabilityMap, path: &Path) -> Result<(), CliError> {
    let [nx, ny, nz] = map.grid.dims;
    let (n, r) = (map.directions.len(), map.rolls.len());
    let index = map.index();
    let directions: Vec<f64> = map.directions.iter().flatten().copied().collect();
    let size: Vec<f64> = map
        .grid
        .dims
        .iter()
        .map(|&d| d as f64 * map.grid.voxel_m)
        .collect();
    let text = |s: &str| vec![s.to_string()];
    let (ee, model, version, solver) = (
        text(&map.end_effector),
        text(&map.model),
        text(env!("CARGO_PKG_VERSION")),
        text(&map.solver.describe()),
    );
    let arrays: Vec<(&str, Vec<usize>, NpzSlice<'_>)> = vec![
        (
            "reachable",
            vec![nx, ny, nz, n, r],
            NpzSlice::Bool(&map.reachable),
        ),
        (
            "postures",
            vec![nx, ny, nz, n, r],
            NpzSlice::U16(&map.postures),
        ),
        (
            "posture_names",
            vec![map.posture_names.len()],
            NpzSlice::Text(&map.posture_names),
        ),
        ("index", vec![nx, ny, nz], NpzSlice::F64(&index)),
        ("origin", vec![3], NpzSlice::F64(&map.grid.origin)),
        (
            "voxel",
            vec![],
            NpzSlice::F64(std::slice::from_ref(&map.grid.voxel_m)),
        ),
        ("size", vec![3], NpzSlice::F64(&size)),
        ("directions", vec![n, 3], NpzSlice::F64(&directions)),
        ("rolls", vec![r], NpzSlice::F64(&map.rolls)),
        ("end_effector", vec![], NpzSlice::Text(&ee)),
        ("model", vec![], NpzSlice::Text(&model)),
        ("version", vec![], NpzSlice::Text(&version)),
        ("solver", vec![], NpzSlice::Text(&solver)),
        (
            "collisions",
            vec![],
            NpzSlice::Bool(std::slice::from_ref(&map.collisions)),
        ),
        ("reach_centre", vec![3], NpzSlice::F64(&map.reach_centre)),
        (
            "reach",
            vec![],
            NpzSlice::F64(std::slice::from_ref(&map.reach_m)),
        ),
    ];
    Ok(write_npz(path, &arrays)?)
}

/// Reads a map written by [`write_map`].
pub(super) fn read_map(path: &Path) -> Result<ReachabilityMap, CliError> {
    let mut f = NpzFile::open(path)?;
    let bad = |what: String| CliError::BadTarget {
        source_name: path.display().to_string(),
        reason: what,
    };
    let floats = |f: &mut NpzFile, name: &str| -> Result<(Vec<usize>, Vec<f64>), CliError> {
        match f.read(name, "float64")? {
            (s, NpzData::F64(d)) => Ok((s, d)),
            _ => unreachable!("read returns the type asked for"),
        }
    };
    let texts = |f: &mut NpzFile, name: &str| -> Result<Vec<String>, CliError> {
        match f.read(name, "text")? {
            (_, NpzData::Text(d)) => Ok(d),
            _ => unreachable!("read returns the type asked for"),
        }
    };
    let (shape, reachable) = match f.read("reachable", "bool")? {
        (s, NpzData::Bool(d)) => (s, d),
        _ => unreachable!("read returns the type asked for"),
    };
    let postures = match f.read("postures", "uint16")? {
        (s, NpzData::U16(d)) if s == shape => d,
        (s, _) => {
            return Err(bad(format!(
                "postures has shape {s:?}, reachable {shape:?}"
            )));
        }
    };
    let collisions =
        matches!(f.read("collisions", "bool")?, (_, NpzData::Bool(d)) if d.first() == Some(&true));
    let (_, origin) = floats(&mut f, "origin")?;
    let (_, voxel) = floats(&mut f, "voxel")?;
    let (dshape, directions) = floats(&mut f, "directions")?;
    let (_, rolls) = floats(&mut f, "rolls")?;
    let (_, reach) = floats(&mut f, "reach")?;
    let (_, centre) = floats(&mut f, "reach_centre")?;
    if shape.len() != 5
        || origin.len() != 3
        || voxel.len() != 1
        || centre.len() != 3
        || dshape != [shape[3], 3]
        || rolls.len() != shape[4]
    {
        return Err(bad(format!(
            "the arrays do not agree: reachable {shape:?}, directions {dshape:?}, rolls {}",
            rolls.len()
        )));
    }
    let one = |v: Vec<String>| v.into_iter().next().unwrap_or_default();
    Ok(ReachabilityMap {
        grid: VoxelGrid {
            origin: [origin[0], origin[1], origin[2]],
            voxel_m: voxel[0],
            dims: [shape[0], shape[1], shape[2]],
        },
        directions: directions.chunks(3).map(|c| [c[0], c[1], c[2]]).collect(),
        rolls,
        reachable,
        postures,
        posture_names: texts(&mut f, "posture_names")?,
        end_effector: one(texts(&mut f, "end_effector")?),
        model: one(texts(&mut f, "model")?),
        solver: MapSolver::Read {
            description: one(texts(&mut f, "solver")?),
        },
        collisions,
        reach_centre: [centre[0], centre[1], centre[2]],
        reach_m: reach.first().copied().unwrap_or(f64::NAN),
    })
}

/// What the summary reports, counted once for text and JSON.
struct Counts {
    samples: usize,
    reached: usize,
    per_posture: Vec<usize>,
    voxels_reached: usize,
    file_bytes: Option<u64>,
}

/// Prints what the map holds: text or JSON.
fn summary(
    map: &ReachabilityMap,
    args: &ReachabilityArgs,
    seconds: f64,
    figures: &[PathBuf],
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let c = Counts {
        samples: map.reachable.len(),
        reached: map.reached_count(),
        per_posture: (0..map.posture_names.len())
            .map(|b| map.postures.iter().filter(|&&m| m >> b & 1 == 1).count())
            .collect(),
        voxels_reached: map.index().iter().filter(|&&x| x > 0.0).count(),
        file_bytes: args
            .out
            .as_ref()
            .and_then(|p| std::fs::metadata(p).ok())
            .map(|m| m.len()),
    };
    match args.format {
        Format::Json => summary_json(map, args, seconds, figures, &c, out),
        Format::Text => summary_text(map, args, seconds, figures, &c, out),
    }
}

/// The summary as one JSON object.
fn summary_json(
    map: &ReachabilityMap,
    args: &ReachabilityArgs,
    seconds: f64,
    figures: &[PathBuf],
    c: &Counts,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let postures: Vec<_> = map
        .posture_names
        .iter()
        .zip(&c.per_posture)
        .map(|(name, &n)| json!({"name": name, "samples": n}))
        .collect();
    let v = json!({
        "model": map.model,
        "end_effector": map.end_effector,
        "solver": map.solver.describe(),
        "collisions": map.collisions,
        "origin": map.grid.origin,
        "voxel": map.grid.voxel_m,
        "dims": map.grid.dims,
        "directions": map.directions.len(),
        "rolls": map.rolls.len(),
        "samples": c.samples,
        "reached": c.reached,
        "voxels_reached": c.voxels_reached,
        "postures": postures,
        "seconds": seconds,
        "out": args.out,
        "file_bytes": c.file_bytes,
        "figures": figures,
    });
    writeln!(
        out,
        "{}",
        serde_json::to_string_pretty(&v).unwrap_or_default()
    )?;
    Ok(())
}

/// The summary in words.
fn summary_text(
    map: &ReachabilityMap,
    args: &ReachabilityArgs,
    seconds: f64,
    figures: &[PathBuf],
    c: &Counts,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let [nx, ny, nz] = map.grid.dims;
    writeln!(
        out,
        "{} ({}): {}",
        map.model,
        map.end_effector,
        map.solver.describe()
    )?;
    writeln!(
        out,
        "grid {nx} x {ny} x {nz} voxels of {} m from ({:.3}, {:.3}, {:.3}) m, {} directions x {} rolls: {} samples{}",
        map.grid.voxel_m,
        map.grid.origin[0],
        map.grid.origin[1],
        map.grid.origin[2],
        map.directions.len(),
        map.rolls.len(),
        c.samples,
        if map.collisions {
            ", collisions taken out"
        } else {
            ""
        }
    )?;
    writeln!(
        out,
        "reached: {} samples ({:.2} %), in {} voxels; {seconds:.1} s",
        c.reached,
        100.0 * c.reached as f64 / c.samples.max(1) as f64,
        c.voxels_reached
    )?;
    for (name, n) in map.posture_names.iter().zip(&c.per_posture) {
        writeln!(out, "  {name:<45} {n:>12} samples")?;
    }
    if let (Some(p), Some(b)) = (&args.out, c.file_bytes) {
        writeln!(out, "wrote {} ({:.1} MB)", p.display(), b as f64 / 1e6)?;
    }
    for p in figures {
        writeln!(out, "wrote {}", p.display())?;
    }
    Ok(())
}
