//! Maps in a cell: the map of a request with the postures that collide taken out, decided on
//! collision cells of the map's own cells ([`crate::workspace::cell`]).

use super::{MapForming, MapRequest, MapValues, MapView, WorkspaceMap};
use crate::collision::CellScene;
use crate::kinematics::Robot;
use crate::workspace::cell::{
    COLLISION_CELLS, CellChecker, CollisionLayer, PointCheck, cut_map, obstacle_outlines,
};
use crate::workspace::{ExactPlanar, WorkspaceError};
use nalgebra::Point3;

/// Most heights a top view's column is checked at.
const MAX_HEIGHTS: usize = 128;

/// Computes the map of `req` in `cell` (with `cell = None`, [`super::compute_map_forming`]): a
/// point counts as reached by a posture only where that posture is within the joint limits
/// and hits neither itself nor the cell's obstacles. Where the map is decided by a closed form
/// (planar arms' planes, the side and top views of closed-form arms) the collisions are
/// decided on square blocks of its cells, at most [`COLLISION_CELLS`] along its longer side,
/// one point per posture each (the top view: a column of heights); sampled maps count only
/// the collision-free samples. The map's [`WorkspaceMap::collision`] says what was taken out,
/// how it was decided, and where the obstacles lie in the view.
///
/// # Examples
///
/// The two-link planar arm (a1 = a2 = 1 m) beside a wall 0.4 m thick at x = 1.4 m: cells
/// inside it are reached by no collision-free posture, cells far from it keep theirs.
///
/// ```
/// use armlab::collision::{CellScene, Obstacle};
/// use armlab::kinematics::models::built_in;
/// use armlab::workspace::{MapRequest, MapView, compute_map, compute_map_in, OneShot};
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let arm = built_in("planar2").expect("a built-in model");
/// let cell = CellScene {
///     obstacles: vec![Obstacle::cuboid("wall", [0.4, 4.0, 1.0], [1.4, 0.0, 0.0])],
///     ..CellScene::default()
/// };
/// let req = MapRequest {
///     view: MapView::Plane,
///     cells: [60, 60],
///     bounds: Some([-2.1, 2.1, -2.1, 2.1]),
///     ..MapRequest::default()
/// };
/// let free = compute_map_in(&arm, &req, Some(&cell), &mut OneShot)?;
/// let empty = compute_map(&arm, &req)?;
/// let layer = free.collision.as_ref().expect("a cell's map says what it took out");
/// assert_eq!(layer.obstacles[0].name, "wall");
/// // Inside the wall nothing reaches without a collision; it did without the wall.
/// let k = |x: f64, y: f64| {
///     let (i, j) = (((x + 2.1) / 4.2 * 60.0) as usize, ((2.1 - y) / 4.2 * 60.0) as usize);
///     j * 60 + i
/// };
/// assert!(empty.masks[k(1.4, 0.0)] != 0 && free.masks[k(1.4, 0.0)] == 0);
/// assert!(layer.blocked[k(1.4, 0.0)] != 0);
/// // Behind the base, far from the wall, every posture stays.
/// assert_eq!(free.masks[k(-1.0, 0.3)], empty.masks[k(-1.0, 0.3)]);
/// # Ok(())
/// # }
/// ```
pub fn compute_map_in(
    robot: &Robot,
    req: &MapRequest,
    cell: Option<&CellScene>,
    forming: &mut dyn MapForming,
) -> Result<WorkspaceMap, WorkspaceError> {
    let Some(cell) = cell else {
        return super::compute_map_forming(robot, req, forming);
    };
    let bounds = super::checked_bounds(robot, req)?;
    let checker = CellChecker::new(robot, cell, req.point)?;
    let closed_form = req.end_effector == 0
        && match req.view {
            MapView::Plane => ExactPlanar::new(robot).is_ok(),
            _ => {
                req.values != MapValues::Manipulability
                    && super::spatial::Section::new(robot, req.point).is_some()
            }
        };
    let plane_z = crate::workspace::planar_frame(robot, 0).map_or(0.0, |f| f.z);
    let cut = closed_form && checker.has_postures();
    let mut map = if cut {
        let mut map = super::compute_map_forming(robot, req, forming)?;
        cut_in_cell(robot, req, &checker, &mut map)?;
        map
    } else {
        sampled_in_cell(robot, req, bounds, &checker, forming)?
    };
    if let Some(layer) = &mut map.collision {
        // A sampled side view holds every azimuth: its obstacles are swept about the z axis.
        layer.obstacles = obstacle_outlines(cell, &robot.base, req.view, plane_z, map.bounds, !cut);
    }
    Ok(map)
}

/// A closed-form map cut by the cell (see [`compute_map_in`]).
fn cut_in_cell(
    robot: &Robot,
    req: &MapRequest,
    checker: &CellChecker<'_>,
    map: &mut WorkspaceMap,
) -> Result<(), WorkspaceError> {
    let block = map.width.max(map.height).div_ceil(COLLISION_CELLS).max(1);
    let base = robot.base;
    let world = |x: f64, y: f64, z: f64| {
        let w = base * Point3::new(x, y, z);
        [w.x, w.y, w.z]
    };
    let (view_words, heights) = match req.view {
        MapView::Plane => {
            let frame = crate::workspace::planar_frame(robot, 0);
            let z = frame.map_or(0.0, |f| f.z);
            (String::from("the arm plane"), vec![z])
        }
        MapView::Side => (
            String::from("the section y = 0, x >= 0 of the base frame"),
            vec![0.0],
        ),
        MapView::Top => {
            let e = super::map_extent(robot, MapView::Side, req.point, 0)?;
            let step = (map.bounds[1] - map.bounds[0]) / map.width as f64 * block as f64;
            let n = (((e.max[1] - e.min[1]) / step).ceil() as usize).clamp(1, MAX_HEIGHTS);
            let dz = (e.max[1] - e.min[1]) / n as f64;
            let heights: Vec<f64> = spread(n)
                .into_iter()
                .map(|k| e.min[1] + (k as f64 + 0.5) * dz)
                .collect();
            (
                format!(
                    "a posture counts where it is free at one of {n} heights {:.0} mm apart",
                    dz * 1000.0
                ),
                heights,
            )
        }
    };
    let test = |p: [f64; 2], want: u8, hint: &mut usize| -> PointCheck {
        let at = |z: f64| match req.view {
            MapView::Plane | MapView::Top => world(p[0], p[1], z),
            MapView::Side => world(p[0], 0.0, p[1]),
        };
        let mut out = PointCheck::default();
        let first = (*hint).min(heights.len() - 1);
        for k in std::iter::once(first).chain((0..heights.len()).filter(|&k| k != first)) {
            let here = checker.check_point(at(heights[k]), want & !out.free);
            out.reached |= here.reached;
            if here.free != 0 {
                *hint = k;
            }
            out.free |= here.free;
            if want & !out.free == 0 {
                break;
            }
        }
        out
    };
    cut_map(map, block, &test);
    if let Some(layer) = &mut map.collision {
        layer.method = cut_method(checker, layer, &view_words);
    }
    Ok(())
}

/// `0..n` in the order of a van der Corput sequence from the middle (the middle, the bottom,
/// the quarters, ...): a column scanned this way meets a long free stretch early.
fn spread(n: usize) -> Vec<usize> {
    let size = n.max(1).next_power_of_two();
    let bits = size.trailing_zeros();
    (0..size)
        .map(|k| {
            let r = if bits == 0 {
                0
            } else {
                k.reverse_bits() >> (usize::BITS - bits)
            };
            (r + size / 2) % size
        })
        .filter(|&k| k < n)
        .collect()
}

/// The caption of a cut map: how its collisions were decided.
fn cut_method(checker: &CellChecker<'_>, layer: &CollisionLayer, view: &str) -> String {
    format!(
        "collision-free: decided cell by cell on {} x {} cells of {}: each cell's centre checked \
         per posture with parry ({}); {view}",
        layer.cells[0],
        layer.cells[1],
        millimetres(layer.cell_size),
        checker.what_is_checked()
    )
}

/// "20 mm", or "20 x 15 mm" for cells that are not square.
fn millimetres([w, h]: [f64; 2]) -> String {
    let (w, h) = (w * 1000.0, h * 1000.0);
    if (w - h).abs() < 0.05 * w.max(h) {
        format!("{w:.0} mm")
    } else {
        format!("{w:.0} x {h:.0} mm")
    }
}

/// A sampled map of the collision-free samples (see [`compute_map_in`]).
fn sampled_in_cell(
    robot: &Robot,
    req: &MapRequest,
    bounds: [f64; 4],
    checker: &CellChecker<'_>,
    forming: &mut dyn MapForming,
) -> Result<WorkspaceMap, WorkspaceError> {
    let tracked = if req.end_effector == 0 {
        super::tracking(robot, req.point)
    } else {
        std::borrow::Cow::Borrowed(robot)
    };
    let keep = |q: &[f64]| checker.config_free(q);
    let (mut map, blocked) =
        super::sampled::map_where(&tracked, req, bounds, forming, Some(&keep))?;
    let (w, h) = (map.width, map.height);
    let cell_size = [
        (bounds[1] - bounds[0]) / w as f64,
        (bounds[3] - bounds[2]) / h as f64,
    ];
    map.collision = Some(Box::new(CollisionLayer {
        method: format!(
            "collision-free: decided cell by cell on the map's {w} x {h} cells of {}: a cell \
             counts where a joint-space sample that hits nothing falls in it (or the rim's IK \
             solution hits nothing), each checked with parry ({}){}",
            millimetres(cell_size),
            checker.what_is_checked(),
            if req.view == MapView::Side {
                "; the side view holds every azimuth, so obstacles are drawn swept about the \
                 base z axis"
            } else {
                ""
            }
        ),
        blocked,
        block: 1,
        cells: [w, h],
        cell_size,
        obstacles: Vec::new(),
    }));
    Ok(map)
}
