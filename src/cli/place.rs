//! `armlab place`: base placement (issue 49). Where on the floor to bolt an arm so that it
//! reaches a set of task poses: every task solved exactly by IK at every base position and yaw
//! of a grid, the best placements ranked, each task's postures there, and a heat map figure.
//! Ctrl+C stops it cleanly and writes nothing.

use super::fk::fmt_vec;
use super::{CliError, Format};
use crate::kinematics::Robot;
use crate::kinematics::pose::pose_to_rows;
use crate::reachability::{
    BestPlacement, PlacementError, PlacementGrid, PlacementMap, PlacementOptions, PlacementTask,
    TaskMatch, parse_tasks, place,
};
use serde_json::{Value, json};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `armlab place`.
#[derive(Debug, clap::Args)]
pub struct PlaceArgs {
    /// Built-in name or path to a .toml / .urdf model.
    pub model: String,
    /// The task poses, one per line (`-` for stdin): `x, y, z, roll_deg, pitch_deg, yaw_deg`
    /// (m, world frame; fixed-axis roll-pitch-yaw in degrees, as in URDF) or 16 numbers (a
    /// row-major 4x4 world_from_tool pose); commas or whitespace, `#` comments, an optional
    /// header line (`name, x, y, z, roll_deg, pitch_deg, yaw_deg` names each row).
    #[arg(long, value_name = "FILE")]
    pub tasks: PathBuf,
    /// The floor area searched for the base: x0,x1,y0,y1 (m, world frame).
    #[arg(long, value_name = "X0,X1,Y0,Y1", allow_hyphen_values = true)]
    pub area: String,
    /// The grid step (m): base positions x0, x0 + step, ... up to x1 (included when the width is
    /// a whole number of steps), the same in y.
    #[arg(long, default_value_t = 0.05, allow_hyphen_values = true)]
    pub step: f64,
    /// How many yaw angles of the base about the world z axis: 2 pi k / yaws, k = 0..yaws.
    #[arg(long, default_value_t = 36, value_parser = super::count)]
    pub yaws: usize,
    /// A scene file of obstacles (TOML, as `armlab collisions --scene`), fixed in the world (or
    /// attached to a link, moving with the robot): a solution counts only when it hits neither
    /// the arm itself nor the cell, and a base that hits an obstacle reaches nothing.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
    /// The end-effector (a name, any link of a URDF, or an index; default: the tool of the
    /// longest arm). On a robot with several, the chain from the root to it is placed alone.
    #[arg(long)]
    pub ee: Option<String>,
    /// The heat map figure to write: .png, .svg or .pdf (per base position the best fraction of
    /// the tasks over the yaws, the tasks and the best placement marked).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// How many of the best placements to list (one per base position).
    #[arg(long, default_value_t = 5, value_parser = super::count)]
    pub best: usize,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    pub format: Format,
    /// Compute even above 1e9 IK evaluations (base positions x yaws x tasks).
    #[arg(long)]
    pub force: bool,
    /// Starts of the numerical solver per task and placement, for arms without a closed form.
    #[arg(long, default_value_t = 8, value_parser = super::count)]
    pub seeds: usize,
}

/// The flag a placement error is about, for its message.
fn flag_of(e: &PlacementError) -> &'static str {
    match e {
        PlacementError::EmptyArea { .. } | PlacementError::NonFiniteArea { .. } => "--area",
        PlacementError::BadStep { .. } => "--step",
        PlacementError::NoYaws => "--yaws",
        PlacementError::NoTasks => "--tasks",
        PlacementError::TooManyEvaluations { .. } => "--step, --area, --yaws (or --force)",
        PlacementError::SeveralEndEffectors { .. } => "--ee",
        _ => "armlab place",
    }
}

fn placement_error(e: PlacementError) -> CliError {
    CliError::Placement {
        flag: flag_of(&e),
        source: e,
    }
}

/// Runs `armlab place`: everything is read and checked before the computation starts.
pub(super) fn run(args: &PlaceArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let (robot, _) = super::arm_robot(super::load_model(&args.model)?, args.ee.as_deref())?;
    let area = super::input::parse_row(&args.area, "--area", 4, "numbers (x0,x1,y0,y1 in m)")?;
    let text = super::input::read_data_text(&args.tasks)?;
    let tasks = parse_tasks(&text, &args.tasks.display().to_string())?;
    if let Some(path) = &args.out {
        figure_kind(path)?;
    }
    let options = PlacementOptions {
        area: [area[0], area[1], area[2], area[3]],
        step: args.step,
        yaws: args.yaws,
        best: args.best,
        force: args.force,
        seeds: args.seeds.max(1),
    };
    let grid = PlacementGrid::new(&options, tasks.len()).map_err(placement_error)?;
    let world = match &args.scene {
        Some(path) => Some(super::collisions::world_for(&robot, Some(path))?),
        None => None,
    };
    let started = Instant::now();
    let bar = crate::headless::Progress::new(grid.positions() as u64, "placement");
    let cancel = super::reachability::interrupted();
    let map = place(&robot, &tasks, world.as_ref(), &options, cancel, &|done| {
        bar.set(done as u64)
    });
    bar.finish();
    if let Err(PlacementError::Cancelled { .. }) = &map {
        eprintln!("armlab place: stopped by Ctrl+C; nothing written");
    }
    let map = map.map_err(placement_error)?;
    let seconds = started.elapsed().as_secs_f64();
    if let Some(path) = &args.out {
        write_figure(&robot, &map, path)?;
    }
    match args.format {
        Format::Json => {
            let v = to_json(&robot, &map, args, options.area);
            serde_json::to_writer_pretty(&mut *out, &v).map_err(std::io::Error::from)?;
            writeln!(out)?;
        }
        Format::Text => write_text(&robot, &map, args, seconds, out)?,
    }
    Ok(())
}

/// Whether the figure file's extension is one the figures write.
fn figure_kind(path: &Path) -> Result<(), CliError> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    match ext.to_ascii_lowercase().as_str() {
        "png" | "svg" | "pdf" => Ok(()),
        _ => Err(CliError::Usage(
            "--out names the heat map figure: a .png, .svg or .pdf file",
        )),
    }
}

/// The heat map figure to `path` (PNG pixels, or SVG / PDF vectors).
fn write_figure(robot: &Robot, map: &PlacementMap, path: &Path) -> Result<(), CliError> {
    let mut figures = crate::headless::figures_for(path)?;
    let title = format!("Base placement of {}", robot.name);
    let img = crate::figure::placement::placement_figure(
        &mut figures,
        map,
        &title,
        [1200, 1100],
        crate::figure::Theme::Light,
    )?;
    crate::headless::write_figure(&mut figures, &img, path)?;
    Ok(())
}

/// What the tasks' poses mean to this arm, in words.
fn match_words(m: TaskMatch) -> &'static str {
    match m {
        TaskMatch::Pose => "the tasks' full poses",
        TaskMatch::Position => "the tasks' positions (this arm cannot set an orientation)",
        TaskMatch::PlanarPose => "the tasks' positions and angles in the arm's plane",
        TaskMatch::PositionAndRotationZ => "the tasks' positions and rotations about z",
        TaskMatch::Orientation => "the tasks' orientations (a wrist alone)",
    }
}

/// The text report: the setting, the ranking table, each task's postures at the best.
fn write_text(
    robot: &Robot,
    map: &PlacementMap,
    args: &PlaceArgs,
    seconds: f64,
    out: &mut dyn Write,
) -> std::io::Result<()> {
    let g = &map.grid;
    let ee = &robot.end_effectors()[0].name;
    writeln!(
        out,
        "Base placement of {} ({ee}): {} task(s), {} x {} base positions at {} m over x [{}, {}] \
         m, y [{}, {}] m, {} yaw(s) ({:.1} deg apart)",
        robot.name,
        map.tasks.len(),
        g.x.len(),
        g.y.len(),
        g.step,
        g.x[0],
        g.x[g.x.len() - 1],
        g.y[0],
        g.y[g.y.len() - 1],
        g.yaw.len(),
        360.0 / g.yaw.len() as f64
    )?;
    writeln!(
        out,
        "{} IK evaluations in {seconds:.2} s; {}; {}{}",
        g.placements() * map.tasks.len(),
        map.solver,
        match_words(map.task_match),
        match &args.scene {
            Some(p) => format!("; collisions checked in {}", p.display()),
            None => String::new(),
        }
    )?;
    writeln!(out, "postures: {}", map.posture_names.join("; "))?;
    writeln!(out)?;
    if map.best.is_empty() {
        writeln!(out, "no base position in the area reaches any task")?;
        return Ok(());
    }
    writeln!(
        out,
        "rank    x [m]    y [m]  yaw [deg]  fraction  tasks    solutions  steady"
    )?;
    for (r, b) in map.best.iter().enumerate() {
        writeln!(
            out,
            "{:>4} {:>8.3} {:>8.3} {:>10.1} {:>9.3}  {:>7}  {:>9}  {}/6",
            r + 1,
            b.detail.x,
            b.detail.y,
            b.detail.yaw.to_degrees(),
            b.fraction,
            format!("{}/{}", b.reached, map.tasks.len()),
            b.solutions,
            b.steady
        )?;
    }
    writeln!(out)?;
    write_best(robot, map, &map.best[0], out)
}

/// Each task's postures and joint vectors at one placement.
fn write_best(
    robot: &Robot,
    map: &PlacementMap,
    b: &BestPlacement,
    out: &mut dyn Write,
) -> std::io::Result<()> {
    writeln!(
        out,
        "At the best placement (x {:.3} m, y {:.3} m, yaw {:.1} deg):",
        b.detail.x,
        b.detail.y,
        b.detail.yaw.to_degrees()
    )?;
    for (task, reach) in map.tasks.iter().zip(&b.detail.tasks) {
        let at = if task.line > 0 {
            format!(" (line {})", task.line)
        } else {
            String::new()
        };
        if reach.mask == 0 {
            writeln!(out, "  task {:?}{at}: not reached", task.name)?;
            continue;
        }
        let postures = if reach.mask.count_ones() as usize == map.posture_names.len() {
            format!("all {}", map.posture_names.len())
        } else {
            map.names_of(reach.mask).join("; ")
        };
        writeln!(
            out,
            "  task {:?}{at}: {} solution(s); postures: {postures}",
            task.name,
            reach.solutions.len(),
        )?;
        for s in &reach.solutions {
            writeln!(
                out,
                "    {}: q = {} (deg, m)",
                s.posture,
                fmt_vec(&super::q_for_display(robot, &s.q))
            )?;
        }
    }
    Ok(())
}

/// A task as JSON: its name, line, position, RPY (degrees) and 4x4 pose.
fn task_json(t: &PlacementTask) -> Value {
    let p = t.world_from_tool.translation.vector;
    let rpy = crate::kinematics::orientation::rpy_from_rotation(&t.world_from_tool.rotation);
    json!({
        "name": t.name,
        "line": t.line,
        "position": [p.x, p.y, p.z],
        "rpy_deg": [rpy.angles[2].to_degrees(), rpy.angles[1].to_degrees(), rpy.angles[0].to_degrees()],
        "pose": pose_to_rows(&t.world_from_tool),
    })
}

/// One best placement as JSON.
fn best_json(robot: &Robot, map: &PlacementMap, rank: usize, b: &BestPlacement) -> Value {
    let tasks: Vec<Value> = map
        .tasks
        .iter()
        .zip(&b.detail.tasks)
        .map(|(t, reach)| {
            json!({
                "task": t.name,
                "reached": reach.mask != 0,
                "postures": map.names_of(reach.mask),
                "posture_mask": reach.mask,
                "solutions": reach.solutions.iter().map(|s| json!({
                    "posture": s.posture.to_string(),
                    "posture_parts": s.posture,
                    "postures": map.names_of(s.classes),
                    "q": s.q,
                    "q_display": super::q_for_display(robot, &s.q),
                    "position_error": s.position_error,
                    "orientation_error": s.orientation_error,
                })).collect::<Vec<_>>(),
            })
        })
        .collect();
    json!({
        "rank": rank,
        "x": b.detail.x,
        "y": b.detail.y,
        "yaw_deg": b.detail.yaw.to_degrees(),
        "index": b.index,
        "fraction": b.fraction,
        "reached": b.reached,
        "solutions": b.solutions,
        "steady": b.steady,
        "base_contacts": b.detail.base_contacts,
        "tasks": tasks,
    })
}

/// The whole result as JSON (keys in the guide's base placement section).
fn to_json(robot: &Robot, map: &PlacementMap, args: &PlaceArgs, area: [f64; 4]) -> Value {
    let g = &map.grid;
    let ny = g.y.len();
    let heat = map.heat();
    let best_yaw: Vec<Vec<f64>> = (0..g.x.len())
        .map(|i| {
            (0..ny)
                .map(|j| g.yaw[map.best_yaw(i, j).1].to_degrees())
                .collect()
        })
        .collect();
    json!({
        "model": robot.name,
        "end_effector": robot.end_effectors()[0].name,
        "tasks": map.tasks.iter().map(task_json).collect::<Vec<_>>(),
        "area": area,
        "step": g.step,
        "yaws": g.yaw.len(),
        "x": g.x,
        "y": g.y,
        "yaw_deg": g.yaw.iter().map(|y| y.to_degrees()).collect::<Vec<_>>(),
        "solver": map.solver,
        "task_match": map.task_match,
        "scene": args.scene.as_ref().map(|p| p.display().to_string()),
        "posture_names": map.posture_names,
        "evaluations": g.placements() * map.tasks.len(),
        "heat": heat.chunks(ny).collect::<Vec<_>>(),
        "heat_yaw_deg": best_yaw,
        "blocked_positions": (0..g.positions())
            .filter(|p| (0..g.yaw.len()).all(|k| map.blocked[p * g.yaw.len() + k]))
            .count(),
        "best": map.best.iter().enumerate().map(|(r, b)| best_json(robot, map, r + 1, b)).collect::<Vec<_>>(),
        "figure": args.out.as_ref().map(|p| p.display().to_string()),
    })
}
