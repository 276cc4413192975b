//! Workspace maps: what a workspace figure, the app and `armlab reach` need, computed at the
//! resolution asked for (pure computation; the figure layer only paints a map).
//!
//! A [`WorkspaceMap`] is a raster of cells over a rectangle of a view (the arm plane, a top view
//! or the (r, z) side view), each with the posture classes reaching its centre, decided by an
//! exact test where the arm has the structure for one:
//! - two- and three-link planar arms: [`super::ExactPlanar`] (closed-form membership with the
//!   orientation free, exact boundary arcs, areas by Green's theorem);
//! - arms with a closed-form positioning arm (anthropomorphic with or without shoulder offset,
//!   spherical, cylindrical; alone or with a spherical wrist, whose wrist centre is the tracked
//!   point): the side view from the closed form of the arm with joint 1 free (the position
//!   problem is planar in (r, z) after joint 1), the top view from the side view's radial extent
//!   and joint 1's range, the volume by Pappus from the section ([`Section`]); the flange of
//!   such an arm whose full-range wrist turns the tool in every direction is the wrist-centre
//!   workspace grown by a sphere, decided on the section's boundary arcs (`arcs`);
//! - any other arm: occupancy of joint-space samples.
//!
//! Cells along a region's edge are supersampled (4 x 4 exact tests) so that the painted edge is
//! antialiased and lies on the exact boundary. Continuous values (the fraction of orientations,
//! manipulability) come per cell with their name, unit and range.

mod arcs;
mod contour;
mod in_cell;
mod planar;
mod query;
mod raster;
mod sampled;
mod spatial;

pub use in_cell::compute_map_in;
pub use query::{PointQuery, ReachAnswer};
pub use spatial::Section;

pub use raster::{EdgeCell, TILE_ROWS};

use super::{Aabb, WorkspaceError, WorkspaceStats};
use crate::kinematics::Robot;

/// The view of a map.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum MapView {
    /// The arm plane of a planar arm, base-frame (x, y) (m).
    Plane,
    /// Top view, base-frame (x, y) (m).
    Top,
    /// Side view: (r, z) in the base frame, r the distance from the base z axis (m).
    Side,
}

/// Which point of the arm the workspace is of.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub enum TrackedPoint {
    /// The end-effector (tool or flange) position.
    #[default]
    Flange,
    /// The wrist centre of an arm with a spherical wrist ("the manipulator workspace without
    /// end-effector", Sect. 2.10.1); the flange for other arms.
    WristCentre,
}

/// Continuous values per cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub enum MapValues {
    /// Posture classes only.
    #[default]
    Classes,
    /// Fraction of the orientations with which the point is reached (the dexterous workspace).
    Dexterity,
    /// Largest manipulability sqrt(det(J J^T)) of the configurations reaching the cell.
    Manipulability,
}

/// What to compute.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct MapRequest {
    /// View.
    pub view: MapView,
    /// Tracked point.
    pub point: TrackedPoint,
    /// Values per cell.
    pub values: MapValues,
    /// Cells across and down.
    pub cells: [usize; 2],
    /// `[x_min, x_max, y_min, y_max]` of the view (m); `None`: [`map_extent`] padded by 6 %.
    pub bounds: Option<[f64; 4]>,
    /// Joint-space samples (sampled maps, manipulability).
    pub samples: usize,
    /// Sampler seed.
    pub seed: u64,
    /// End-effector (the exact methods need end-effector 0 of a single-tool robot).
    pub end_effector: usize,
}

impl Default for MapRequest {
    fn default() -> Self {
        Self {
            view: MapView::Plane,
            point: TrackedPoint::Flange,
            values: MapValues::Classes,
            cells: [800, 600],
            bounds: None,
            samples: 200_000,
            seed: 1,
            end_effector: 0,
        }
    }
}

/// Continuous values of the cells.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CellValues {
    /// Cells across and down of the values (the same rectangle as the map; may be coarser than
    /// the class cells).
    pub dims: [usize; 2],
    /// Per cell, row-major from the top row; NaN where the cell is not reached.
    pub data: Vec<f32>,
    /// What the value is, e.g. "fraction of orientations phi reached".
    pub name: String,
    /// Unit, e.g. "m^2" or "" for a fraction.
    pub unit: String,
    /// Smallest and largest value of the colour scale.
    pub range: [f64; 2],
    /// How the values were computed.
    pub method: String,
}

/// What a curve of a map is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum CurveRole {
    /// Boundary of the reachable set.
    Boundary,
    /// Boundary between posture regions (inside the reachable set).
    PostureBoundary,
    /// A boundary candidate that is not on the boundary (a singular or limit arc inside).
    Candidate,
}

/// A curve of a map in view coordinates (m).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct MapCurve {
    /// Points (view coordinates, m).
    pub points: Vec<[f64; 2]>,
    /// What it is.
    pub role: CurveRole,
    /// The same curve as one exact circular arc, where it is one (planar arms' exact maps);
    /// vector figures write it as an arc. Not serialized.
    #[serde(skip)]
    pub arc: Option<crate::workspace::exact::Arc>,
}

/// A region of an exact map as its exact boundary: the points whose class mask is `mask`, the
/// points where the circular arcs' winding numbers sum to 1 (0 elsewhere; each closed loop of
/// arcs has its inside on its left).
#[derive(Debug, Clone, PartialEq)]
pub struct MapFill {
    /// Class bits the region's points all have (e.g. 1 for class 0, 3 for both classes).
    pub mask: u8,
    /// Its boundary (view coordinates, m).
    pub arcs: Vec<crate::workspace::exact::Arc>,
}

/// A workspace map (see the module documentation).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[must_use]
pub struct WorkspaceMap {
    /// View.
    pub view: MapView,
    /// `[x_min, x_max, y_min, y_max]` covered by the cells (m).
    pub bounds: [f64; 4],
    /// Cells across.
    pub width: usize,
    /// Cells down.
    pub height: usize,
    /// Class mask at each cell centre, row-major from the top row (bit k: class k reaches it).
    pub masks: Vec<u8>,
    /// Cells cut by an edge, with 4 x 4 sub-samples.
    pub edges: Vec<EdgeCell>,
    /// Names of the classes.
    pub class_names: Vec<String>,
    /// Values per cell, if asked for.
    pub values: Option<CellValues>,
    /// Curves to draw (exact boundaries where known).
    pub curves: Vec<MapCurve>,
    /// How the regions were decided, in words.
    pub method: String,
    /// Whether the regions are exact (decided by an exact test at each cell) rather than sampled.
    pub exact: bool,
    /// The regions as exact boundaries where known (planar arms): the reachable set with one
    /// class, else each class alone and the region both classes reach, disjoint. Vector figures
    /// fill these instead of the cells. Not serialized.
    #[serde(skip)]
    pub fills: Vec<MapFill>,
    /// What a cell's obstacles took from the map, and the obstacles in its view
    /// ([`compute_map_in`] with a cell); `None` in empty space.
    #[serde(default)]
    pub collision: Option<Box<crate::workspace::cell::CollisionLayer>>,
}

impl WorkspaceMap {
    /// Centre of cell `(i, j)` (column, row from the top), view coordinates (m).
    pub fn centre(&self, i: usize, j: usize) -> [f64; 2] {
        raster::centre(self.bounds, [self.width, self.height], i, j)
    }

    /// Fraction of cell `k` covered by each mask value: `(mask, fraction)` pairs.
    pub fn coverage(&self, k: usize) -> Vec<(u8, f32)> {
        match self.edges.binary_search_by_key(&(k as u32), |e| e.index) {
            Ok(e) => {
                let mut out: Vec<(u8, f32)> = Vec::new();
                for &m in &self.edges[e].sub {
                    match out.iter_mut().find(|x| x.0 == m) {
                        Some(x) => x.1 += 1.0 / 16.0,
                        None => out.push((m, 1.0 / 16.0)),
                    }
                }
                out
            }
            Err(_) => vec![(self.masks[k], 1.0)],
        }
    }
}

/// What a figure needs of a map view before the map is computed: where the view lies and, for an
/// arm with a spherical wrist, which of its points the map follows (the figure's title says it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapFrame {
    /// The view's extent ([`map_extent`]; m, base frame, r-z for the side view).
    pub extent: Aabb,
    /// For a six-joint arm with a spherical wrist, in the top and side views: the point followed
    /// (the wrist centre or the flange). `None` for other arms and for the plane of a planar arm,
    /// which have one point only.
    pub wrist_point: Option<TrackedPoint>,
}

/// The frame of a map view: its extent ([`map_extent`]) and the point it follows.
pub fn map_frame(
    robot: &Robot,
    view: MapView,
    point: TrackedPoint,
    end_effector: usize,
) -> Result<MapFrame, WorkspaceError> {
    let extent = map_extent(robot, view, point, end_effector)?;
    let wrist = view != MapView::Plane
        && matches!(
            crate::kinematics::ik::ClosedForm::detect(robot).map(|c| *c.family()),
            Ok(crate::kinematics::ik::Family::Decoupled6 { .. })
        );
    Ok(MapFrame {
        extent,
        wrist_point: wrist.then_some(point),
    })
}

/// The extent of a view of the workspace (m): exact for planar arms and closed-form sections,
/// else from samples.
pub fn map_extent(
    robot: &Robot,
    view: MapView,
    point: TrackedPoint,
    end_effector: usize,
) -> Result<Aabb, WorkspaceError> {
    super::check_ee(robot, end_effector)?;
    if end_effector > 0 {
        return sampled::extent(robot, view, end_effector);
    }
    if let (MapView::Plane, Ok(e)) = (view, super::ExactPlanar::new(robot)) {
        return Ok(e.bounds());
    }
    if let Some(s) = spatial::Section::new(robot, point) {
        return Ok(s.extent(view));
    }
    sampled::extent(&tracking(robot, point), view, 0)
}

/// The robot whose flange is the tracked point, for the sampled maps (which sample the flange):
/// asked for the wrist centre of an arm with a spherical wrist but no closed-form section (a
/// gantry, whose joint 1 is prismatic), the robot with its tool moved to the wrist centre;
/// otherwise the robot itself. (Before, such a figure was titled "wrist centre" and showed the
/// flange.)
fn tracking(robot: &Robot, point: TrackedPoint) -> std::borrow::Cow<'_, Robot> {
    use std::borrow::Cow;
    if point != TrackedPoint::WristCentre || robot.end_effectors().len() != 1 {
        return Cow::Borrowed(robot);
    }
    let centre = crate::kinematics::ik::ClosedForm::detect(robot)
        .ok()
        .and_then(|cf| cf.wrist_centre_in_tool());
    let Some(c) = centre else {
        return Cow::Borrowed(robot);
    };
    let mut r = robot.clone();
    let tool = r.end_effectors()[0].tool * nalgebra::Translation3::from(c);
    match r.set_tool(0, tool) {
        Ok(()) => Cow::Owned(r),
        Err(_) => Cow::Borrowed(robot),
    }
}

/// Pads `[x0, x1, y0, y1]` of a box by `pad` times its larger side.
pub fn padded(b: &Aabb, pad: f64) -> [f64; 4] {
    let (x0, x1, y0, y1) = (b.min[0], b.max[0], b.min[1], b.max[1]);
    let m = ((x1 - x0).max(y1 - y0) * pad).max(1e-3);
    [x0 - m, x1 + m, y0 - m, y1 + m]
}

/// Receives a map while it forms, before [`compute_map_forming`] returns the finished one.
pub trait MapForming {
    /// Whether to build and hand over a partial map now (a receiver that paints throttles here;
    /// asked after each tile).
    fn wants(&mut self) -> bool;
    /// A partial map: the rows above `rows_done` (from the top) are decided, the others are not
    /// yet (mask 0), or all of them when `rows_done` is the height but a later pass still
    /// refines them; no edge cells, no curves, no values.
    fn partial(&mut self, map: &WorkspaceMap, rows_done: usize);
}

/// A [`MapForming`] that wants nothing: the one-shot map.
pub struct OneShot;

impl MapForming for OneShot {
    fn wants(&mut self) -> bool {
        false
    }
    fn partial(&mut self, _: &WorkspaceMap, _: usize) {}
}

/// Computes a map.
///
/// # Examples
///
/// A coarse map (40 x 40 cells) of the two-link planar arm of Example 2.6, whose joint limits
/// leave points reached with one posture only (Fig. 2.30):
///
/// ```
/// use armlab::kinematics::models::built_in;
/// use armlab::workspace::{MapRequest, MapView, compute_map};
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let arm = built_in("planar2_fig2_30").expect("a built-in model");
/// let req = MapRequest {
///     view: MapView::Plane,
///     cells: [40, 40],
///     bounds: Some([-2.2, 2.2, -2.2, 2.2]),
///     ..MapRequest::default()
/// };
/// let map = compute_map(&arm, &req)?;
/// assert!(map.exact); // decided by the closed form at every cell, not sampled
/// assert_eq!((map.width, map.height, map.masks.len()), (40, 40, 1600));
/// // The corner cell is outside the disc of radius 2 m.
/// let corner = map.centre(0, 0);
/// assert!(corner[0].hypot(corner[1]) > 2.0 && map.masks[0] == 0);
/// // Some cells are reached with both postures (mask 0b11), some with one only.
/// assert!(map.masks.contains(&0b11));
/// assert!(map.masks.iter().any(|&m| m == 0b01 || m == 0b10));
/// println!("{}: classes {:?}", map.method, map.class_names);
/// # Ok(())
/// # }
/// ```
pub fn compute_map(robot: &Robot, req: &MapRequest) -> Result<WorkspaceMap, WorkspaceError> {
    compute_map_forming(robot, req, &mut OneShot)
}

/// Computes a map, handing `forming` partial maps as its tiles are decided (side and top views
/// of the closed-form arms: [`TILE_ROWS`] rows at a time; sampled maps: the rim refinement tile
/// by tile). The finished map is the one [`compute_map`] returns, whatever `forming` wants.
pub fn compute_map_forming(
    robot: &Robot,
    req: &MapRequest,
    forming: &mut dyn MapForming,
) -> Result<WorkspaceMap, WorkspaceError> {
    let bounds = checked_bounds(robot, req)?;
    if req.end_effector == 0 {
        if req.view == MapView::Plane {
            if let Ok(e) = super::ExactPlanar::new(robot) {
                return Ok(planar::map(&e, req, bounds));
            }
        } else if let Some(s) = spatial::Section::new(robot, req.point) {
            return s.map(robot, req, bounds, forming);
        }
        return sampled::map(&tracking(robot, req.point), req, bounds, forming);
    }
    sampled::map(robot, req, bounds, forming)
}

/// A map made in tiles by several workers (a browser's pool of web workers): prepared by each
/// ([`Self::new`]), its rows decided in tiles in any order and anywhere ([`Self::rows`]), then
/// finished from all the masks ([`Self::finish`]): the map [`compute_map`] returns. For the side
/// and top views of the closed-form arms.
pub struct TiledMap {
    section: spatial::Section,
    prepared: spatial::Prepared,
    req: MapRequest,
    bounds: [f64; 4],
}

impl TiledMap {
    /// The map of `req` prepared for tiles; `None` where it is not made that way (the exact
    /// maps of planar arms, sampled maps, manipulability values, end-effectors other than 0).
    pub fn new(robot: &Robot, req: &MapRequest) -> Result<Option<Self>, WorkspaceError> {
        let bounds = checked_bounds(robot, req)?;
        if !Self::applies(robot, req) {
            return Ok(None);
        }
        Ok(spatial::Section::new(robot, req.point).map(|section| {
            let prepared = section.prepare(req, bounds);
            Self {
                section,
                prepared,
                req: req.clone(),
                bounds,
            }
        }))
    }

    /// Whether the map of `req` is made in tiles (cheap: nothing is prepared).
    pub fn applies(robot: &Robot, req: &MapRequest) -> bool {
        req.end_effector == 0
            && req.view != MapView::Plane
            && req.values != MapValues::Manipulability
            && spatial::Section::new(robot, req.point).is_some()
    }

    /// The masks of the rows `rows` (from the top; the first a multiple of [`TILE_ROWS`]),
    /// row-major.
    pub fn rows(&self, rows: std::ops::Range<usize>) -> Result<Vec<u8>, WorkspaceError> {
        if !rows.start.is_multiple_of(TILE_ROWS)
            || rows.start > rows.end
            || rows.end > self.req.cells[1]
        {
            return Err(WorkspaceError::InvalidOption {
                option: "map tile",
                value: format!("rows {}..{} of {}", rows.start, rows.end, self.req.cells[1]),
                expected: "rows within the map, starting at a multiple of the tile height",
            });
        }
        Ok(self
            .section
            .rows(&self.req, self.bounds, &self.prepared, rows))
    }

    /// The finished map from the masks of all its rows (row-major from the top).
    pub fn finish(&self, masks: Vec<u8>) -> Result<WorkspaceMap, WorkspaceError> {
        if masks.len() != self.req.cells[0] * self.req.cells[1] {
            return Err(WorkspaceError::InvalidOption {
                option: "map masks",
                value: format!("{} masks", masks.len()),
                expected: "one per cell of the map",
            });
        }
        self.section
            .finish(&self.req, self.bounds, &self.prepared, masks)
    }
}

/// The bounds of a map request (its own, or the padded extent), checked with its cells.
fn checked_bounds(robot: &Robot, req: &MapRequest) -> Result<[f64; 4], WorkspaceError> {
    if req.cells[0] == 0 || req.cells[1] == 0 || req.cells[0] * req.cells[1] > 64_000_000 {
        return Err(WorkspaceError::InvalidOption {
            option: "map size",
            value: format!("{}x{} cells", req.cells[0], req.cells[1]),
            expected: "each side must be at least 1, at most 64 million cells",
        });
    }
    let bounds = match req.bounds {
        Some(b) => b,
        None => padded(
            &map_extent(robot, req.view, req.point, req.end_effector)?,
            0.06,
        ),
    };
    if !(bounds[1] > bounds[0] && bounds[3] > bounds[2] && bounds.iter().all(|v| v.is_finite())) {
        return Err(WorkspaceError::InvalidOption {
            option: "map bounds",
            value: format!("{bounds:?}"),
            expected: "must be finite and not empty",
        });
    }
    super::check_ee(robot, req.end_effector)?;
    Ok(bounds)
}

/// Statistics of the workspace with the exact method where there is one: exact areas for planar
/// arms, Pappus volumes for closed-form sections (end-effector 0), the grid of
/// [`super::statistics`] with `fallback` otherwise.
///
/// # Examples
///
/// Exact values against the geometry: a two-link arm with a1 = 1 m, a2 = 0.5 m and full joint
/// ranges reaches the annulus between radii 0.5 m and 1.5 m, area pi (1.5^2 - 0.5^2) = 2 pi m^2;
/// the Puma's wrist centre sweeps a solid of revolution whose volume Pappus gives from its section.
///
/// ```
/// use armlab::kinematics::models::built_in;
/// use armlab::kinematics::{Convention, DhJoint, DhRow, Pose, Robot};
/// use armlab::workspace::{StatsOptions, TrackedPoint, map_statistics};
/// use std::f64::consts::PI;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let link = |a: f64| DhJoint::revolute(DhRow { a, ..DhRow::default() }).limits(-PI, PI);
/// let arm = Robot::from_dh(
///     "annulus arm",
///     Convention::Standard,
///     &[link(1.0), link(0.5)],
///     Pose::identity(),
///     Pose::identity(),
/// )?;
/// let stats = map_statistics(&arm, TrackedPoint::Flange, &StatsOptions::default())?;
/// assert!((stats.area.expect("planar") - 2.0 * PI).abs() < 1e-9);
/// assert!((stats.min_reach - 0.5).abs() < 1e-9 && (stats.max_reach - 1.5).abs() < 1e-9);
///
/// let puma = built_in("puma560").expect("a built-in model");
/// let wrist = map_statistics(&puma, TrackedPoint::WristCentre, &StatsOptions::default())?;
/// assert!(wrist.volume.expect("a spatial arm") > 0.0);
/// println!("{} m^3 by {}", wrist.volume.unwrap_or_default(), wrist.measure_method);
/// # Ok(())
/// # }
/// ```
pub fn map_statistics(
    robot: &Robot,
    point: TrackedPoint,
    fallback: &super::StatsOptions,
) -> Result<WorkspaceStats, WorkspaceError> {
    if fallback.grid.end_effector == 0 {
        if let Ok(e) = super::ExactPlanar::new(robot) {
            return Ok(planar::statistics(&e));
        }
        if let Some(s) = spatial::Section::new(robot, point) {
            return Ok(s.statistics());
        }
        return super::statistics(&tracking(robot, point), fallback, &|_| {});
    }
    super::statistics(robot, fallback, &|_| {})
}
