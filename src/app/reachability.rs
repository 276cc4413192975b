//! The reachability overlay and base placement in the app (issue 49): what the Show menu, the
//! right panel's Reachability section and the 3D view ask for ([`ReachabilityAction`]), applied
//! in one place ([`apply`]), and the overlay's draw lists ([`add_to_scene`]).
//!
//! - The Show menu's "Reachability" turns the overlay on: the map of the current robot (in the
//!   cell, when one is open and checked) is computed in the background with the panel's
//!   settings, its progress shown and cancellable.
//! - The 3D view draws the voxels of a slice plane coloured by their index; the panel's slider
//!   scrubs the plane. Pointing at a voxel of the slice outlines it and shows its approach
//!   directions on a small sphere (and in the panel); clicking it pins it. Clicking one of its
//!   directions (on the sphere, or in the panel) moves the IK target to that sample with every
//!   posture's ghost, and lists the postures the map's computation finds there.
//! - Base placement: task poses from a tasks file or the IK target, placed over a floor area;
//!   the heat map is drawn on the floor with the best placement marked, and the base can be
//!   moved there.

use super::action::Action;
use super::shell::AppUi;
use super::state::placement::{PlaceSettings, PlacementOverlay};
use super::state::reachability::{DirectionReach, MapSettings, Ray, ReachabilityOverlay, Slice};
use super::state::{AppState, Level};
use crate::scene::Scene;
use crate::scene::reachability::{
    NOT_REACHED, PARTLY_REACHED, REACHED, SliceStyle, direction_sphere, floor_heat_map,
    placement_mark, slice_outline, slice_scene, voxel_outline,
};

/// What the overlay's controls and the 3D view ask for.
#[derive(Debug, Clone, PartialEq)]
pub enum ReachabilityAction {
    /// Show the overlay (its map computed when there is none), or hide it.
    Show(bool),
    /// Compute the map again with these settings (and show it).
    Compute(MapSettings),
    /// Stop the computation of the map.
    Cancel,
    /// The pointer looks along this ray into the 3D view (`None`: it left the view).
    Point(Option<Ray>),
    /// A click in the 3D view along `ray`; `ghost` is the posture a click there picks when it
    /// hits no direction of the pinned voxel.
    Click {
        /// Where the click looks (world).
        ray: Ray,
        /// The solution index of the ghost arm near the click, if any.
        ghost: Option<usize>,
    },
    /// Pin this voxel (flat index), or none.
    Pin(Option<usize>),
    /// Move the IK target to sample (voxel, direction, roll) of the map, with every posture.
    Aim {
        /// The voxel (flat C-order index).
        voxel: usize,
        /// The direction's index.
        direction: usize,
        /// The roll's index.
        roll: usize,
    },
    /// Read the task poses of a placement from this file.
    OpenTasks(String),
    /// Add the IK target as a task pose.
    AddTargetAsTask,
    /// Remove every task pose.
    ClearTasks,
    /// Place the base over this floor grid.
    Place(PlaceSettings),
    /// Stop the placement.
    CancelPlacement,
    /// Move the robot's base to the best placement.
    MoveBase,
}

/// Applies `action` to the app; what cannot be done is said in the status bar.
pub fn apply(app: &mut AppUi, action: ReachabilityAction) {
    let ee = app.ee();
    let (map, state) = (&mut app.ik.reach.map, &mut app.state);
    match action {
        ReachabilityAction::Show(true) => {
            state.display.reachability = true;
            if map.slice.is_none() {
                map.slice = Some(facing_slice(&app.tabs.view3d.camera, state));
            }
            if map.result().is_none() && !map.computing() {
                map.start(state, ee);
            }
            // The whole reach in view (and no more automatic framing that would move it).
            frame_reach(&mut app.tabs.view3d, state, ee);
        }
        ReachabilityAction::Show(false) => {
            state.display.reachability = false;
            map.cancel();
        }
        ReachabilityAction::Compute(settings) => {
            map.settings = settings;
            state.display.reachability = true;
            map.start(state, ee);
        }
        ReachabilityAction::Cancel => {
            map.cancel();
            state.push_message(Level::Info, "reachability map stopped");
        }
        ReachabilityAction::Point(ray) => {
            map.hovered = ray.and_then(|r| map.voxel_on_ray(&r));
            map.hovered_direction = ray.and_then(|r| map.direction_on_ray(&r));
        }
        ReachabilityAction::Click { ray, ghost } => click(app, ray, ghost),
        ReachabilityAction::Pin(v) => map.pinned = v,
        ReachabilityAction::Aim {
            voxel,
            direction,
            roll,
        } => aim(app, (voxel, direction, roll)),
        other => apply_placement(app, other),
    }
}

/// Frames the box the tool of `ee` sweeps ([`crate::reachability::reach_estimate`]: where the
/// map's voxels are) in the 3D view, and keeps the camera there.
fn frame_reach(view: &mut super::tabs::view3d::View3d, state: &AppState, ee: usize) {
    let reach = crate::reachability::reach_estimate(state.robot(), ee);
    let (lo, hi) = (reach.lo, reach.hi);
    let corners: Vec<nalgebra::Point3<f32>> = (0..8)
        .map(|c| {
            let at = |a: usize| if c >> a & 1 == 0 { lo[a] } else { hi[a] } as f32;
            nalgebra::Point3::new(at(0), at(1), at(2))
        })
        .collect();
    let [w, h] = view.viewport_px;
    let mut camera = view.camera;
    camera.fit_points(&corners, w.max(16), h.max(16), 0.9);
    view.set_camera(camera);
}

/// The first slice: through the base, across the world axis the camera looks along most (the
/// slice seen face on).
fn facing_slice(camera: &crate::camera::Camera, state: &AppState) -> Slice {
    let look = camera.target - camera.eye();
    let axis = (0..3)
        .max_by(|&a, &b| look[a].abs().total_cmp(&look[b].abs()))
        .unwrap_or(1);
    let base = state.robot().base.translation.vector;
    Slice {
        axis,
        at_m: base[axis],
    }
}

/// A click in the 3D view: a direction of the pinned voxel's sphere moves the target there;
/// else the ghost arm there is selected; else the voxel of the slice there is pinned (clicking
/// the pinned one, or nothing, unpins).
fn click(app: &mut AppUi, ray: Ray, ghost: Option<usize>) {
    let map = &mut app.ik.reach.map;
    if let (Some(voxel), Some(direction)) = (map.pinned, map.direction_on_ray(&ray)) {
        let roll = map.roll_for(voxel, direction);
        return aim(app, (voxel, direction, roll));
    }
    if let Some(index) = ghost {
        let ee = app.ee();
        return app.apply(Action::SelectSolution(ee, index));
    }
    let hit = map.voxel_on_ray(&ray);
    map.pinned = if hit == map.pinned { None } else { hit };
}

/// Moves the IK target of the map's end-effector to a sample of the map, ghosts on; the status
/// bar says how many postures the map's computation finds there.
fn aim(app: &mut AppUi, sample: (usize, usize, usize)) {
    let map = &mut app.ik.reach.map;
    let Some(ee) = map.result().map(|r| r.options.ee) else {
        return;
    };
    let Some(pose) = map.aim(app.state.robot(), sample) else {
        return app
            .state
            .push_message(Level::Warning, "no such sample in the map");
    };
    map.pinned = Some(sample.0);
    let n = map.aimed.as_ref().map_or(0, |a| a.solutions.len());
    app.state.display.ghosts = true;
    if let Err(e) = app.state.set_target(ee, pose) {
        return app.state.push_message(Level::Warning, e.to_string());
    }
    let what = match n {
        0 => "no posture reaches it (the map's sample is not reached)".to_string(),
        1 => "1 posture reaches it".to_string(),
        n => format!("{n} postures reach it"),
    };
    let (voxel, direction, roll) = sample;
    app.state.push_message(
        Level::Info,
        format!("target on voxel {voxel}, direction {direction}, roll {roll}: {what}"),
    );
}

/// The placement's actions.
fn apply_placement(app: &mut AppUi, action: ReachabilityAction) {
    let (placement, state) = (&mut app.ik.reach.placement, &mut app.state);
    let ee = app.ik.ee.min(state.targets().len().saturating_sub(1));
    let done: Result<Option<String>, String> = match action {
        ReachabilityAction::OpenTasks(path) => read_tasks(placement, &path).map(Some),
        ReachabilityAction::AddTargetAsTask => match state.target(ee) {
            Ok(t) => {
                placement.add_task(t.world_from_tool);
                Ok(Some(format!("{} task pose(s)", placement.tasks.len())))
            }
            Err(e) => Err(e.to_string()),
        },
        ReachabilityAction::ClearTasks => {
            placement.tasks.clear();
            Ok(None)
        }
        ReachabilityAction::Place(settings) => {
            placement.settings = Some(settings);
            placement.start(state);
            Ok(None)
        }
        ReachabilityAction::CancelPlacement => {
            placement.cancel();
            Ok(Some("placement stopped".into()))
        }
        ReachabilityAction::MoveBase => match placement.result().and_then(|r| r.best_base()) {
            Some(base) => {
                state.set_base(base);
                let t = base.translation.vector;
                Ok(Some(format!(
                    "base moved to x = {:.3} m, y = {:.3} m (Undo takes it back)",
                    t.x, t.y
                )))
            }
            None => Err("no placement reaches a task: nowhere to move the base".into()),
        },
        _ => Ok(None),
    };
    match done {
        Ok(Some(m)) => state.push_message(Level::Info, m),
        Ok(None) => {}
        Err(e) => state.push_message(Level::Error, e),
    }
}

/// Reads the tasks file at `path` into `placement`.
fn read_tasks(placement: &mut PlacementOverlay, path: &str) -> Result<String, String> {
    if cfg!(target_arch = "wasm32") {
        return Err("a browser cannot open a file by its path: add the target as a task".into());
    }
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read {path}: {e}"))?;
    let n = placement
        .read_tasks(&text, path)
        .map_err(|e| e.to_string())?;
    Ok(format!("{n} task pose(s) from {path}"))
}

/// The colour of a direction's dot.
fn reach_color(r: DirectionReach) -> crate::scene::Rgba {
    match r {
        DirectionReach::All => REACHED,
        DirectionReach::Some => PARTLY_REACHED,
        DirectionReach::None => NOT_REACHED,
    }
}

/// Adds the overlay to `scene`: the slice's voxels and outline (every reached voxel as a dot
/// when asked), the voxel pointed at and the pinned one outlined, the shown voxel's sphere of
/// directions; the task poses, and the placement's heat map with its best placement. `scale`
/// (m) is the robot's size (its longest chain): the marks are sized by it.
pub fn add_to_scene(
    (map, placement): (&ReachabilityOverlay, &PlacementOverlay),
    scale: f64,
    scene: &mut Scene,
) {
    if let (Some(r), Some(s), Some(layer)) = (map.result(), map.slice, map.slice_layer()) {
        let grid = &r.map.grid;
        let style = SliceStyle {
            dots_px: if map.all_voxels { 5.0 } else { 0.0 },
            ..SliceStyle::default()
        };
        let voxels = map.slice_voxels();
        scene.extend(slice_scene(grid, &r.index, s.axis, &voxels, &style));
        scene.extend(slice_outline(grid, s.axis, layer));
        for (v, width) in [(map.hovered, 2.0), (map.pinned, 3.5)] {
            if let Some(v) = v {
                scene.lines.extend(voxel_outline(grid, grid.ijk(v), width));
            }
        }
        if let (Some(v), Some(radius)) = (map.shown_voxel(), map.sphere_radius()) {
            let colors: Vec<_> = map.directions_of(v).into_iter().map(reach_color).collect();
            let aimed = map
                .aimed
                .as_ref()
                .filter(|a| a.voxel == v)
                .map(|a| a.direction);
            let centre = grid.centre(grid.ijk(v));
            let mut dots = direction_sphere(centre, radius, &r.map.directions, &colors, aimed);
            if let Some(d) = map.hovered_direction.and_then(|d| dots.get_mut(d)) {
                d.size_px *= 1.6;
            }
            scene.dots.extend(dots);
        }
    }
    let scale = scale.max(0.1);
    for t in &placement.tasks {
        add_task(scene, &t.world_from_tool, &t.name, 0.08 * scale);
    }
    if let Some(p) = placement.result() {
        let g = &p.map.grid;
        scene.extend(floor_heat_map(&g.x, &g.y, &p.map.heat(), 0.0, g.step));
        if let Some(b) = p.map.best.first() {
            let label = format!(
                "best: {} of {} tasks, yaw {:.0} deg",
                b.reached,
                p.map.tasks.len(),
                b.detail.yaw.to_degrees()
            );
            let at = [b.detail.x, b.detail.y, 0.0];
            scene.extend(placement_mark(at, b.detail.yaw, 0.4 * scale, label));
        }
    }
}

/// A task pose: its three axes (x red, y green, z blue, `len` m) and its name.
fn add_task(scene: &mut Scene, world_from_tool: &crate::kinematics::Pose, name: &str, len: f64) {
    let o = world_from_tool.translation.vector;
    let o32 = [o.x as f32, o.y as f32, o.z as f32];
    for (k, color) in crate::scene::AXIS_COLORS.iter().enumerate() {
        let tip = o + world_from_tool.rotation * nalgebra::Vector3::ith(k, len);
        scene.lines.push(crate::scene::Line {
            a: o32,
            b: [tip.x as f32, tip.y as f32, tip.z as f32],
            color: *color,
            width_px: 3.0,
        });
    }
    scene.labels.push(crate::scene::Label {
        p: o32,
        text: name.to_string(),
        color: [0.2, 0.2, 0.25, 1.0],
        movable: true,
    });
}
