//! The cell in the app: what the Cell menu, the cell panel and the 3D view's obstacle gizmo ask
//! for ([`CellAction`]), the obstacles the menu adds sized to the robot ([`ObstacleKind`]),
//! and scene files opened and saved (the file dialog where there is one, the typed path or the
//! in-app browser where there is none, a download in a browser). The shell hands every
//! [`CellAction`] to [`apply`]; what goes wrong is a message in the status bar, and the cell
//! stays as it was.

use super::AppUi;
use super::file_picker::FileKind;
use super::state::Level;
use crate::collision::{CellScene, Obstacle, ObstacleShape};
use crate::kinematics::orientation::rpy_from_rotation;
use crate::kinematics::{Pose, Robot};
use std::path::{Path, PathBuf};

/// The scene file proposed when saving, and the cell panel's path until one is typed.
pub const DEFAULT_SCENE_FILE: &str = "cell.toml";

/// An obstacle the Cell menu adds, sized and placed relative to the robot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ObstacleKind {
    /// The floor under the base's pedestal (a half-space).
    Floor,
    /// A table top in front of the robot, within its reach.
    Table,
    /// A box on the table's height, in front and to the left.
    Box,
    /// A wall behind the robot.
    Wall,
}

impl ObstacleKind {
    /// Every kind, in the menu's order.
    pub const ALL: [ObstacleKind; 4] = [
        ObstacleKind::Floor,
        ObstacleKind::Table,
        ObstacleKind::Box,
        ObstacleKind::Wall,
    ];

    /// The menu's word, and the obstacle's name.
    pub fn name(self) -> &'static str {
        match self {
            ObstacleKind::Floor => "floor",
            ObstacleKind::Table => "table",
            ObstacleKind::Box => "box",
            ObstacleKind::Wall => "wall",
        }
    }

    /// The obstacle for `robot`, in the world frame, placed in the base frame (x forward,
    /// z up) and sized by the arm's reach past its shoulder, `R` = the longest chain
    /// ([`Robot::longest_chain_length`]) less the shoulder's distance from the base (the
    /// shoulder: the first joint frame's origin at q = 0):
    ///
    /// - floor: the half-space under the base as it is drawn (a root link without a visual
    ///   of its own, a DH model's or a URDF's bare `world` link, is drawn as a pedestal two
    ///   link radii deep below the base frame, which for a DH model may be at the shoulder; a
    ///   root link with a visual stands on its frame), a hair (0.1 % of L) lower, so that it
    ///   does not touch the fixed base;
    /// - table: a top 0.5 R deep, 1.0 R wide and 0.04 R thick, from 0.3 R to 0.8 R in front of
    ///   the base, its top 0.3 R below the shoulder (never below the floor);
    /// - box: a cube of 0.15 R standing on the table's top, 0.5 R in front and 0.35 R to the
    ///   left;
    /// - wall: 0.04 R thick, 1.6 R wide, 1.4 R high, standing on the floor 0.6 R behind.
    pub fn obstacle(self, robot: &Robot) -> Obstacle {
        let l = robot.longest_chain_length().max(0.05);
        let stick_base = !robot.visuals.iter().any(|v| v.joint.is_none());
        let link_radius = f64::from(crate::scene::ArmStyle::default().link_radius) * l;
        // A hair (0.1 % of L) below what the base stands on: a floor touching the fixed base
        // would be said as a mounting contact.
        let floor = if stick_base { -2.0 * link_radius } else { 0.0 } - 1e-3 * l;
        // The shoulder in the base frame.
        let zero = vec![0.0; robot.dof()];
        let shoulder = robot
            .fk_frames(&zero)
            .ok()
            .and_then(|f| {
                f.first()
                    .map(|f| robot.base.inverse() * f.translation.vector)
            })
            .unwrap_or_else(nalgebra::Vector3::zeros);
        let r = (l - shoulder.norm()).max(0.5 * l);
        let top = (shoulder.z - 0.3 * r).max(floor);
        let (size, local) = match self {
            ObstacleKind::Floor => {
                let z = (robot.base * nalgebra::Point3::new(0.0, 0.0, floor)).z;
                return Obstacle::floor("floor", z);
            }
            ObstacleKind::Table => ([0.5 * r, r, 0.04 * r], [0.55 * r, 0.0, top - 0.02 * r]),
            ObstacleKind::Box => ([0.15 * r; 3], [0.5 * r, 0.35 * r, top + 0.075 * r]),
            ObstacleKind::Wall => (
                [0.04 * r, 1.6 * r, 1.4 * r],
                [-0.6 * r, 0.0, floor + 0.7 * r],
            ),
        };
        let world_from_obstacle = robot.base * Pose::translation(local[0], local[1], local[2]);
        let mut o = Obstacle::cuboid(self.name(), size, [0.0; 3]);
        set_pose(&mut o, &world_from_obstacle);
        o
    }
}

/// What the Cell menu, the cell panel and the obstacle gizmo ask for.
#[derive(Debug, Clone, PartialEq)]
pub enum CellAction {
    /// Add an obstacle of this kind, sized to the robot, and select it.
    Add(ObstacleKind),
    /// Replace obstacle `k` (moved by the gizmo, resized or moved in the panel).
    Set(usize, Obstacle),
    /// Delete obstacle `k`.
    Delete(usize),
    /// Select an obstacle (the gizmo moves it), or none (the gizmo moves the IK target).
    Select(Option<usize>),
    /// Check collisions (and show them), or not.
    Check(bool),
    /// Open a scene file: this path, or where the file dialog says (`None`).
    Open(Option<String>),
    /// Save the cell as a scene file: to this path, or where the file dialog says (`None`).
    Save(Option<String>),
    /// Use this scene as the cell (a lesson step's), or none.
    Use(Option<Box<CellScene>>),
}

/// Applies `action` to the app; the status bar says what was done, or why not (the cell is
/// unchanged then).
pub fn apply(app: &mut AppUi, action: CellAction) {
    let s = &mut app.state;
    let done: Result<Option<String>, String> = match action {
        CellAction::Add(kind) => {
            let o = kind.obstacle(s.robot());
            s.add_obstacle(o).map(|k| {
                let name = &s.cell_scene().expect("just added").obstacles[k].name;
                Some(format!(
                    "added \"{name}\": drag the gizmo to move it, or set its size in the Cell \
                     section of the right panel"
                ))
            })
        }
        CellAction::Set(k, o) => s.set_obstacle(k, o).map(|()| None),
        CellAction::Delete(k) => s.remove_obstacle(k).map(|()| None),
        CellAction::Select(k) => {
            s.select_obstacle(k);
            Ok(None)
        }
        CellAction::Check(on) => {
            s.set_collisions(on);
            let m = if on {
                "collisions checked"
            } else {
                "collisions not checked"
            };
            Ok(Some(m.to_string()))
        }
        CellAction::Use(scene) => s.set_scene(scene.map(|b| *b)).map(|()| None),
        CellAction::Open(Some(path)) => open_path(app, &path),
        CellAction::Open(None) => open_dialog(app),
        CellAction::Save(path) => save(app, path),
    };
    match done {
        Ok(Some(m)) => app.state.push_message(Level::Info, m),
        Ok(None) => {}
        Err(e) => app.state.push_message(Level::Error, e),
    }
}

/// Opens the scene file `name` from its `text` (dropped, typed, picked in the browser); on an
/// error the cell stays as it was and the status bar says why, naming the file, the line and
/// the obstacle.
pub fn open_text(app: &mut AppUi, name: &str, text: &str) {
    let opened = CellScene::parse(text, Path::new(name))
        .map_err(|e| e.to_string())
        .and_then(|scene| use_scene(app, scene, name));
    match opened {
        Ok(m) => app.state.push_message(Level::Info, m),
        Err(e) => app.state.push_message(Level::Error, e),
    }
}

/// Whether `text` is a scene file rather than a model or a lesson: a TOML table with a list
/// of `[[obstacle]]` tables and no lesson steps.
pub fn is_scene_text(text: &str) -> bool {
    toml::from_str::<toml::Table>(text).is_ok_and(|t| {
        t.get("obstacle").is_some_and(toml::Value::is_array) && !t.contains_key("steps")
    })
}

/// Reads the scene file at `path` and makes it the cell.
fn open_path(app: &mut AppUi, path: &str) -> Result<Option<String>, String> {
    let scene = CellScene::read(Path::new(path)).map_err(|e| e.to_string())?;
    app.ik.cell.path = path.to_string();
    use_scene(app, scene, path).map(Some)
}

/// Makes `scene` (read from `name`) the cell; the message says what it holds.
fn use_scene(app: &mut AppUi, scene: CellScene, name: &str) -> Result<String, String> {
    let n = scene.obstacles.len();
    let warnings = scene.warnings.clone();
    app.state.set_scene(Some(scene))?;
    app.state.set_collisions(true);
    for w in warnings {
        app.state.push_message(Level::Warning, w);
    }
    Ok(format!("cell {name}: {n} obstacle(s)"))
}

/// "Open scene...": the file dialog's choice; where there is no dialog, the in-app file browser
/// (its choice is opened like a typed path, which knows a scene file by its contents).
fn open_dialog(app: &mut AppUi) -> Result<Option<String>, String> {
    let picker = app.file_picker.as_mut();
    if cfg!(target_arch = "wasm32") {
        // The browser's picker hands the file over later (opened by its contents).
        let _ = picker.open(FileKind::Scene);
        return Ok(None);
    }
    let typed_dir = Path::new(&app.ik.cell.path)
        .parent()
        .unwrap_or(Path::new(""))
        .to_path_buf();
    if !picker.available() {
        app.browser.show_scenes(&typed_dir);
        return Ok(None);
    }
    let asked = std::time::Instant::now();
    match picker.open(FileKind::Scene) {
        Some(path) => open_path(app, &path.to_string_lossy()),
        None if asked.elapsed() < std::time::Duration::from_millis(300) => {
            app.browser.show_scenes(&typed_dir);
            Ok(Some(
                "no desktop file dialog answered (it needs xdg-desktop-portal): choose the \
                 scene file here"
                    .into(),
            ))
        }
        None => Ok(None),
    }
}

/// "Save scene": the cell written as a scene file to `path`, or where the file dialog says;
/// where no dialog answers, to the path typed in the cell panel; a download in a browser.
fn save(app: &mut AppUi, path: Option<String>) -> Result<Option<String>, String> {
    let scene = app
        .state
        .cell_scene()
        .ok_or("no cell to save: add an obstacle from the Cell menu first")?;
    let text = scene.to_toml();
    let picker = app.file_picker.as_mut();
    let typed = app.ik.cell.path.trim().to_string();
    if picker.downloads() {
        let name = path.unwrap_or(typed);
        let name = Path::new(&name)
            .file_name()
            .map_or(DEFAULT_SCENE_FILE.into(), |n| {
                n.to_string_lossy().into_owned()
            });
        return if picker.download(&name, "application/toml", text.as_bytes()) {
            Ok(Some(format!("downloading {name}")))
        } else {
            Err(format!("the browser refused the download of {name}"))
        };
    }
    let (path, note) = match path {
        Some(p) => (p, ""),
        None if !picker.available() => (typed, ""),
        None => {
            let asked = std::time::Instant::now();
            let suggested = Path::new(&typed)
                .file_name()
                .map_or(DEFAULT_SCENE_FILE.to_string(), |n| {
                    n.to_string_lossy().into_owned()
                });
            match picker.save(FileKind::SceneToSave, &suggested) {
                Some(p) => (with_toml(p).to_string_lossy().into_owned(), ""),
                None if asked.elapsed() < std::time::Duration::from_millis(300) => (
                    typed,
                    " (no desktop file dialog answered: the name typed in the Cell section)",
                ),
                None => return Ok(None),
            }
        }
    };
    if path.is_empty() {
        return Err("type the scene file's name in the Cell section (e.g. cell.toml)".into());
    }
    std::fs::write(&path, text).map_err(|e| format!("cannot write {path}: {e}"))?;
    app.ik.cell.path = path.clone();
    let full = super::files::full_path(Path::new(&path));
    Ok(Some(format!("cell saved in {}{note}", full.display())))
}

/// A path without an extension gets `.toml`.
fn with_toml(path: PathBuf) -> PathBuf {
    if path.extension().is_none() {
        path.with_extension("toml")
    } else {
        path
    }
}

/// Sets `o`'s pose in its frame to `frame_from_obstacle` (m; the angles as URDF's fixed-axis
/// roll, pitch, yaw).
pub fn set_pose(o: &mut Obstacle, frame_from_obstacle: &Pose) {
    let t = frame_from_obstacle.translation.vector;
    o.xyz = [t.x, t.y, t.z];
    // rpy_from_rotation's angles are about z, y, x (R = Rz Ry Rx); the file's are x, y, z.
    let a = rpy_from_rotation(&frame_from_obstacle.rotation).angles;
    o.rpy = [a.z, a.y, a.x];
}

/// Obstacle `o`, whose world pose is `world_from_old`, moved to the world pose `world_from_new`
/// (the gizmo's): its pose in its own frame (the world, or the link it moves with) changed.
pub fn moved(o: &Obstacle, world_from_old: &Pose, world_from_new: &Pose) -> Obstacle {
    let world_from_frame = world_from_old * o.frame_from_obstacle().inverse();
    let mut out = o.clone();
    set_pose(&mut out, &(world_from_frame.inverse() * world_from_new));
    out
}

/// The sizes of a shape the panel edits (m), with their names: a box's x, y, z; a cylinder's
/// radius and length; a sphere's radius; none for a plane or a mesh.
pub fn sizes(shape: &ObstacleShape) -> Vec<(&'static str, f64)> {
    match shape {
        ObstacleShape::Box { size } => vec![("x", size[0]), ("y", size[1]), ("z", size[2])],
        ObstacleShape::Cylinder { radius, length } => {
            vec![("radius", *radius), ("length", *length)]
        }
        ObstacleShape::Sphere { radius } => vec![("radius", *radius)],
        ObstacleShape::Plane | ObstacleShape::Mesh { .. } => Vec::new(),
    }
}

/// `shape` with its sizes (m, as [`sizes`] lists them) replaced, each kept at least 1 mm.
pub fn with_sizes(shape: &ObstacleShape, v: &[f64]) -> ObstacleShape {
    let at = |k: usize, old: f64| v.get(k).copied().unwrap_or(old).max(1e-3);
    match shape {
        ObstacleShape::Box { size } => ObstacleShape::Box {
            size: [at(0, size[0]), at(1, size[1]), at(2, size[2])],
        },
        ObstacleShape::Cylinder { radius, length } => ObstacleShape::Cylinder {
            radius: at(0, *radius),
            length: at(1, *length),
        },
        ObstacleShape::Sphere { radius } => ObstacleShape::Sphere {
            radius: at(0, *radius),
        },
        other => other.clone(),
    }
}
