//! `armlab render` (a snapshot of the arm) and `armlab workspace` (workspace figures): PNGs made
//! headlessly with the app's renderer.

use super::fk::fmt_vec;
use super::{CliError, JointInput, joint_vectors};
use crate::camera::{Camera, Preset, Projection};
use crate::figure::Theme;
use crate::figure::figures::Scene3d;
use crate::scene::{ArmStyle, arm_scene};
use clap::ValueEnum;
use std::path::PathBuf;

/// A figure size `WxH` in pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Size(pub [u32; 2]);

impl Default for Size {
    /// 1280x800, the app's default window.
    fn default() -> Self {
        Size([1280, 800])
    }
}

impl std::str::FromStr for Size {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let (w, h) = s
            .split_once(['x', 'X'])
            .ok_or_else(|| format!("{s:?} is not WIDTHxHEIGHT, e.g. 1600x1200"))?;
        let parse = |t: &str| {
            t.trim()
                .parse::<u32>()
                .ok()
                .filter(|v| (16..=8192).contains(v))
        };
        match (parse(w), parse(h)) {
            (Some(w), Some(h)) => Ok(Size([w, h])),
            _ => Err(format!(
                "{s:?}: width and height must be whole numbers from 16 to 8192"
            )),
        }
    }
}

/// Light or dark figure.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum ThemeArg {
    /// Dark on white.
    #[default]
    Light,
    /// Light on dark.
    Dark,
}

impl From<ThemeArg> for Theme {
    fn from(t: ThemeArg) -> Self {
        match t {
            ThemeArg::Light => Theme::Light,
            ThemeArg::Dark => Theme::Dark,
        }
    }
}

/// Viewpoint of a 3D snapshot.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum ViewpointArg {
    /// Isometric-like.
    #[default]
    Iso,
    /// From above.
    Top,
    /// From -y (the x-z plane).
    Front,
    /// From +x (the y-z plane).
    Side,
}

impl From<ViewpointArg> for Preset {
    fn from(v: ViewpointArg) -> Self {
        match v {
            ViewpointArg::Iso => Preset::Iso,
            ViewpointArg::Top => Preset::Top,
            ViewpointArg::Front => Preset::Front,
            ViewpointArg::Side => Preset::Side,
        }
    }
}

/// Arguments of `armlab render`.
#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// Built-in name or path to a .toml / .urdf model.
    pub model: String,
    /// End-effector, by name (any link of a URDF) or 0-based index (default: the tool of the longest arm): on a
    /// robot with several, only the frames of the chain to it are labelled (with --frames).
    #[arg(long)]
    pub ee: Option<String>,
    /// Joint vector (default: the "ready" configuration).
    #[command(flatten)]
    pub joints: JointInput,
    /// Output file: PNG, or SVG / PDF (vectors: exact arcs, text as text) by its extension.
    #[arg(long)]
    pub out: PathBuf,
    /// Image size in pixels, WIDTHxHEIGHT.
    #[arg(long, default_value = "1200x900")]
    pub size: Size,
    /// Draw the DH frames with labels.
    #[arg(long)]
    pub frames: bool,
    /// Viewpoint.
    #[arg(long, value_enum, default_value_t)]
    pub view: ViewpointArg,
    /// Orthographic instead of perspective projection.
    #[arg(long)]
    pub orthographic: bool,
    /// Colours.
    #[arg(long, value_enum, default_value_t)]
    pub theme: ThemeArg,
    /// A scene file of obstacles (TOML `[[obstacle]]` tables) to draw with the arm; the
    /// subtitle says what the configuration hits.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
}

/// A camera at `preset` framing `points` (leaving room for the title at the top).
pub(crate) fn framing_camera(
    preset: Preset,
    points: &[nalgebra::Point3<f32>],
    size: [u32; 2],
    orthographic: bool,
) -> Camera {
    let mut camera = Camera::default();
    if orthographic {
        camera.projection = Projection::Orthographic { height: 1.0 };
    }
    camera.set_preset(preset);
    camera.fit_points(points, size[0], size[1], 0.75);
    // Shift the picture down a little, below the title.
    camera.pan(0.0, 0.04);
    camera
}

/// Runs `render`.
pub(super) fn render(args: &RenderArgs, out: &mut dyn std::io::Write) -> Result<(), CliError> {
    let mut robot = super::load_model(&args.model)?;
    let ee = super::ik::end_effector(&mut robot, args.ee.as_deref())?;
    let fallback = if robot.config("ready").is_some() {
        "ready"
    } else {
        "zero"
    };
    let q = joint_vectors(&robot, &args.model, &args.joints, Some(fallback))?.remove(0);
    let style = ArmStyle {
        frames: args.frames,
        frame_labels: args.frames,
        ..ArmStyle::default()
    };
    let mut scene = arm_scene(&robot, &q, &style)?;
    if robot.end_effectors().len() > 1 {
        crate::scene::label_driven_chain_only(&mut scene, &robot, ee);
    }
    let mut framed = crate::scene::arm_points(&robot, &q)?;
    let hits = match &args.scene {
        Some(path) => Some(add_cell(&mut scene, &robot, &q, path, &mut framed)?),
        None => None,
    };
    let camera = framing_camera(args.view.into(), &framed, args.size.0, args.orthographic);
    let shown = super::q_for_display(&robot, &q);
    let fig = Scene3d {
        title: robot.name.clone(),
        subtitle: format!(
            "q = {} (deg; m for prismatic joints){}",
            fmt_vec(&shown).replace(".000000", ""),
            hits.map(|h| format!("; {h}")).unwrap_or_default()
        ),
        scene: &scene,
        camera,
        legend: Vec::new(),
        caption: String::new(),
    };
    let mut figures = crate::headless::figures_for(&args.out)?;
    let img = figures.scene(args.size.0, args.theme.into(), &fig)?;
    crate::headless::write_figure(&mut figures, &img, &args.out)?;
    writeln!(
        out,
        "wrote {} ({}x{})",
        args.out.display(),
        img.width(),
        img.height()
    )?;
    Ok(())
}

/// Adds the obstacles of the scene file `path` to `scene` (planes as squares the size of the
/// robot's reach) and the centres of the bounded ones to the points the camera frames; says
/// what configuration `q` hits ("link3 hits table, 12 mm", or "free, 45 mm clear").
fn add_cell(
    scene: &mut crate::scene::Scene,
    robot: &crate::kinematics::Robot,
    q: &[f64],
    path: &std::path::Path,
    framed: &mut Vec<nalgebra::Point3<f32>>,
) -> Result<String, CliError> {
    use crate::collision::ObstacleShape;
    use crate::scene::obstacles::{ObstacleStyle, add_obstacle};
    let cell = crate::collision::CellScene::read(path)?;
    let world = crate::collision::CollisionWorld::new(robot, &cell)?;
    let poses = world.obstacle_poses(robot, q)?;
    let solid = ObstacleStyle {
        plane_half_size: robot.longest_chain_length().max(0.5),
        ..ObstacleStyle::default()
    };
    // Planes lighter than the solids, so that a table on the floor stands out.
    let plane = ObstacleStyle {
        color: [0.8, 0.8, 0.83, 0.6],
        ..solid
    };
    for (o, pose) in cell.obstacles.iter().zip(&poses) {
        if o.shape == ObstacleShape::Plane {
            add_obstacle(scene, o, pose, &plane);
        } else {
            add_obstacle(scene, o, pose, &solid);
            // A box's corners, else its centre.
            let half = match o.shape {
                ObstacleShape::Box { size } => nalgebra::Vector3::from(size) * 0.5,
                _ => nalgebra::Vector3::zeros(),
            };
            for k in 0..8 {
                let s = |b: usize| if k >> b & 1 == 1 { 1.0 } else { -1.0 };
                let corner = nalgebra::Point3::new(s(0) * half.x, s(1) * half.y, s(2) * half.z);
                framed.push(crate::scene::point32(&(pose * corner).coords));
            }
        }
    }
    Ok(world.check(robot, q)?.summary())
}

/// Workspace view.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum WsViewArg {
    /// The arm plane (planar arms); top view otherwise.
    Plane,
    /// World x-y, from above.
    Top,
    /// World x-z, from the side.
    Side,
    /// 3D point cloud with the arm.
    #[value(name = "3d")]
    ThreeD,
    /// The joint-space rectangle of Fig. 2.29 (two-link arms).
    JointSpace,
}

/// Workspace colouring.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum ColorByArg {
    /// Regions reached by each posture, and by several.
    #[default]
    Posture,
    /// Manipulability.
    Manipulability,
    /// The dexterous workspace: fraction of orientations reachable.
    Dexterity,
    /// One colour.
    None,
}

/// Tracked point of the workspace views.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum PointArg {
    /// The wrist centre (the flange when the arm has no spherical wrist).
    #[default]
    WristCentre,
    /// The flange (end-effector).
    Flange,
}

/// Arguments of `armlab workspace`.
#[derive(Debug, clap::Args)]
pub struct WorkspaceArgs {
    /// Built-in name or path to a .toml / .urdf model.
    pub model: String,
    /// End-effector, by name (any link of a URDF) or 0-based index (default: the tool of the longest arm). On a
    /// robot with several, the command works on the chain from the root to it alone.
    #[arg(long)]
    pub ee: Option<String>,
    /// Output file: PNG, or SVG / PDF (vectors: exact arcs, text as text) by its extension.
    #[arg(long)]
    pub out: PathBuf,
    /// View (default: plane for planar arms, top otherwise).
    #[arg(long, value_enum)]
    pub view: Option<WsViewArg>,
    /// Colouring.
    #[arg(long, value_enum, default_value_t)]
    pub color_by: ColorByArg,
    /// Joint-space samples.
    #[arg(long, default_value_t = 200_000, value_parser = super::count)]
    pub samples: usize,
    /// Sampler seed: the same inputs give the same PNG bytes.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Image size in pixels, WIDTHxHEIGHT.
    #[arg(long, default_value = "1200x900")]
    pub size: Size,
    /// Colours.
    #[arg(long, value_enum, default_value_t)]
    pub theme: ThemeArg,
    /// The point whose workspace the side and top views show: the wrist centre of an arm with a
    /// spherical wrist ("the manipulator workspace without end-effector", exact), or the
    /// flange. Arms without a wrist have one point.
    #[arg(long, value_enum, default_value_t)]
    pub point: PointArg,
    /// Print the statistics as JSON (area, bounds, reach, ...) instead of a summary line.
    #[arg(long, value_enum, default_value_t)]
    pub format: super::Format,
    /// A scene file of obstacles (TOML `[[obstacle]]` tables): a point counts as reached by a
    /// posture only where that posture is within the limits and hits neither the arm itself
    /// nor an obstacle, decided cell by cell (the figure says at what resolution and how); the
    /// obstacles are drawn. Plane, top and side views.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
}

/// Runs `workspace`.
pub(super) fn workspace(
    args: &WorkspaceArgs,
    out: &mut dyn std::io::Write,
) -> Result<(), CliError> {
    use crate::figure::workspace::{ColorBy, WsFigureOptions, WsView};
    use crate::headless::workspace_figure_in;
    let (robot, _) = super::arm_robot(super::load_model(&args.model)?, args.ee.as_deref())?;
    if args.samples == 0 || args.samples > 100_000_000 {
        return Err(CliError::Usage("--samples must be between 1 and 100000000"));
    }
    let cell = workspace_cell(args)?;
    let planar = crate::workspace::planar_frame(&robot, 0).is_some();
    let view = match args.view {
        Some(WsViewArg::Plane) | None if planar => WsView::Plane,
        Some(WsViewArg::Plane) | Some(WsViewArg::Top) | None => WsView::Top,
        Some(WsViewArg::Side) => WsView::Side,
        Some(WsViewArg::ThreeD) => WsView::ThreeD,
        Some(WsViewArg::JointSpace) => WsView::JointSpace,
    };
    let opts = WsFigureOptions {
        view,
        color_by: match args.color_by {
            ColorByArg::Posture => ColorBy::Posture,
            ColorByArg::Manipulability => ColorBy::Manipulability,
            ColorByArg::Dexterity => ColorBy::Dexterity,
            ColorByArg::None => ColorBy::None,
        },
        samples: args.samples,
        seed: args.seed,
        size: args.size.0,
        theme: args.theme.into(),
        end_effector: 0,
        point: match args.point {
            PointArg::WristCentre => crate::workspace::TrackedPoint::WristCentre,
            PointArg::Flange => crate::workspace::TrackedPoint::Flange,
        },
        caption: String::new(),
        text_scale: 1.0,
    };
    let bar = crate::headless::Progress::new(1000, "workspace");
    let mut figures = crate::headless::figures_for(&args.out)?;
    let title = robot.name.to_lowercase();
    let fig = workspace_figure_in(&mut figures, &robot, &title, &opts, cell.as_ref(), &|f| {
        bar.set((f * 1000.0) as u64)
    })?;
    bar.finish();
    crate::headless::write_figure(&mut figures, &fig.image, &args.out)?;
    match args.format {
        super::Format::Json => {
            let v = stats_json(&robot, args, &fig.stats);
            serde_json::to_writer_pretty(&mut *out, &v).map_err(std::io::Error::from)?;
            writeln!(out)?;
        }
        super::Format::Text => {
            let s = &fig.stats;
            let measure = match (s.area, s.volume) {
                (Some(a), _) => format!("area {a:.6} m^2"),
                (_, Some(v)) => format!("volume {v:.6} m^3"),
                _ => String::new(),
            };
            writeln!(
                out,
                "wrote {}: {measure}, reach {:.4}-{:.4} m",
                args.out.display(),
                s.min_reach,
                s.max_reach
            )?;
        }
    }
    Ok(())
}

/// The cell of `armlab workspace --scene FILE`, for the views that draw one.
fn workspace_cell(args: &WorkspaceArgs) -> Result<Option<crate::collision::CellScene>, CliError> {
    let Some(path) = &args.scene else {
        return Ok(None);
    };
    if matches!(args.view, Some(WsViewArg::ThreeD | WsViewArg::JointSpace)) {
        return Err(CliError::Usage(
            "--scene draws the plane, top and side views (not --view 3d or joint-space)",
        ));
    }
    Ok(Some(crate::collision::CellScene::read(path)?))
}

/// The statistics of `armlab workspace --format json`.
fn stats_json(
    robot: &crate::kinematics::Robot,
    args: &WorkspaceArgs,
    s: &crate::workspace::WorkspaceStats,
) -> serde_json::Value {
    let mut v = serde_json::json!({
        "model": robot.name,
        "out": args.out.display().to_string(),
        "samples": args.samples,
        "seed": args.seed,
        "bbox": { "min": s.bounds.min, "max": s.bounds.max },
        "max_reach": s.max_reach,
        "min_reach": s.min_reach,
        "reach_exact": s.reach_exact,
        "resolution": s.resolution,
        "cell_size": s.cell_size,
        "dexterous": s.dexterous_measure,
        "classes": s.classes.iter().map(|c| serde_json::json!({"name": c.name, "with": c.with, "only": c.only})).collect::<Vec<_>>(),
        "measure_method": s.measure_method,
        "point": match args.point {
            PointArg::WristCentre => "wrist centre",
            PointArg::Flange => "flange",
        },
    });
    if let Some(path) = &args.scene {
        v["scene"] = serde_json::json!(path.display().to_string());
    }
    for (key, value) in [
        ("area", s.area),
        ("area_both_postures", s.area_both_postures),
        ("volume", s.volume),
        ("measure_error", s.measure_error),
    ] {
        if let Some(x) = value {
            v[key] = serde_json::json!(x);
        }
    }
    v
}

/// Arguments of `armlab figure`.
#[derive(Debug, clap::Args)]
pub struct FigureArgs {
    /// The figure: 2.29, 2.30, 2.31, 2.32, 2.33 or problem-2.17 (`--list` shows them).
    pub name: Option<String>,
    /// List the figures and what each shows.
    #[arg(long)]
    pub list: bool,
    /// Output file: PNG, or SVG / PDF (vectors: exact arcs, text as text) by its extension.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Image size in pixels, WIDTHxHEIGHT.
    #[arg(long, default_value = "1200x900")]
    pub size: Size,
    /// Colours.
    #[arg(long, value_enum, default_value_t)]
    pub theme: ThemeArg,
}

/// Runs `figure`.
pub(super) fn figure(args: &FigureArgs, out: &mut dyn std::io::Write) -> Result<(), CliError> {
    use crate::construction::textbook::FIGURES;
    use crate::headless::textbook_figure;
    if args.list {
        for (name, what) in FIGURES {
            writeln!(out, "{name:<13} {what}")?;
        }
        return Ok(());
    }
    let Some(name) = args.name.as_deref() else {
        return Err(CliError::Usage(
            "name a figure (2.29, 2.30, 2.31, 2.32, 2.33, problem-2.17) or pass --list",
        ));
    };
    if !FIGURES.iter().any(|f| f.0 == name) {
        return Err(CliError::UnknownFigure {
            name: name.into(),
            available: FIGURES.map(|f| f.0).join(", "),
        });
    }
    let Some(path) = &args.out else {
        return Err(CliError::Usage("--out FILE.png is required"));
    };
    let mut figures = crate::headless::figures_for(path)?;
    let img = textbook_figure(&mut figures, name, args.size.0, args.theme.into())?;
    crate::headless::write_figure(&mut figures, &img, path)?;
    writeln!(
        out,
        "wrote {} ({}x{}): Fig. {name}",
        path.display(),
        img.width(),
        img.height()
    )?;
    Ok(())
}
