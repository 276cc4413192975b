//! What a workspace figure is drawn from, asked for and computed in one piece: the figure plans
//! its frame and says what it needs ([`FigureRequest`]: the statistics and, for a map, the cells
//! and data bounds of its own plot frame), the caller computes it here, on a thread or in a web
//! worker ([`compute_figure_data`]), and the figure paints the [`FigureData`] it is handed. Both
//! travel as JSON to a browser's worker.

use super::map::{
    MapForming, MapRequest, MapView, OneShot, WorkspaceMap, compute_map, compute_map_in,
    map_statistics,
};
use super::planar::{CurveKind, planar_boundary};
use super::rectangle::{JointRectangle, joint_rectangle};
use super::sample::{SampleOptions, sample};
use super::stats::{StatsOptions, WorkspaceStats};
use super::views::{PointCloud, point_cloud};
use super::{BoundaryOptions, GridOptions, TrackedPoint, WorkspaceError};
use crate::collision::CellScene;
use crate::kinematics::Robot;
use serde::{Deserialize, Serialize};

/// Grid cells per axis of a planar arm's statistics where no exact method applies.
pub const PLANAR_FIGURE_GRID: usize = 256;
/// Grid cells per axis of a spatial arm's statistics where no exact method applies.
pub const SPATIAL_FIGURE_GRID: usize = 48;
/// Orientations tried per cell of those grids (dexterity).
pub const FIGURE_GRID_ORIENTATIONS: usize = 16;
/// Most joint-space samples a figure draws.
pub const MAX_FIGURE_SAMPLES: usize = 200_000;

impl StatsOptions {
    /// The statistics options of a workspace figure: a grid of [`PLANAR_FIGURE_GRID`] or
    /// [`SPATIAL_FIGURE_GRID`] cells per axis, `samples` joint-space samples (at most
    /// [`MAX_FIGURE_SAMPLES`]) drawn with `seed`, for end-effector `end_effector`.
    pub fn for_figure(planar: bool, samples: usize, seed: u64, end_effector: usize) -> Self {
        let samples = samples.clamp(1, MAX_FIGURE_SAMPLES);
        Self {
            grid: GridOptions {
                resolution: if planar {
                    PLANAR_FIGURE_GRID
                } else {
                    SPATIAL_FIGURE_GRID
                },
                orientations: FIGURE_GRID_ORIENTATIONS,
                samples,
                seed,
                end_effector,
                ..GridOptions::default()
            },
            samples,
            boundary: BoundaryOptions::default(),
        }
    }
}

/// Everything a workspace figure needs computed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FigureRequest {
    /// The point whose workspace is shown (side and top views).
    pub point: TrackedPoint,
    /// Options of the statistics where no exact method applies.
    pub fallback: StatsOptions,
    /// What the figure's body shows.
    pub content: ContentRequest,
}

/// The body of a workspace figure, as asked for.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum ContentRequest {
    /// A map of the plane, top or side view at the plot frame's own cells and bounds.
    Map(MapRequest),
    /// A 3D point cloud from joint-space samples.
    Cloud(SampleOptions),
    /// The joint-space rectangle of a two-link arm (Fig. 2.29).
    JointRectangle,
}

/// What a workspace figure paints.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[must_use]
pub struct FigureData {
    /// Area or volume, bounds and reach.
    pub stats: WorkspaceStats,
    /// The body.
    pub content: Content,
    /// Fig. 2.30's marks, where the plane of a two-link arm with joint limits is shown.
    pub plane_marks: Option<PlaneMarks>,
}

/// The marks of Fig. 2.30 on the plane of a two-link arm with joint limits (arm plane, m).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct PlaneMarks {
    /// The letters A-G at the ends of the boundary arcs, then H where FD crosses BC.
    pub labels: Vec<(String, [f64; 2])>,
    /// The images of the singular lines (aligned links) as polylines.
    pub singular: Vec<Vec<[f64; 2]>>,
}

/// Fig. 2.30's marks of a two-link planar arm with joint limits; `None` for any other arm.
pub fn plane_marks(robot: &Robot) -> Option<PlaneMarks> {
    let e = planar_boundary(robot, &BoundaryOptions::default()).ok()?;
    e.rectangle.as_ref()?;
    let mut marks = PlaneMarks::default();
    for c in &e.curves {
        if let (Some(first), Some(last)) = (c.points.first(), c.points.last()) {
            let name = c.label.chars().collect::<Vec<_>>();
            if name.len() == 2 && name.iter().all(char::is_ascii_uppercase) {
                marks.labels.push((name[0].to_string(), *first));
                marks.labels.push((name[1].to_string(), *last));
            }
        }
        if c.kind == CurveKind::Singular {
            marks.singular.push(c.points.clone());
        }
    }
    marks.labels.sort_by(|a, b| a.0.cmp(&b.0));
    marks.labels.dedup_by(|a, b| a.0 == b.0);
    if let Some(h) = e.crossing("FD", "BC") {
        marks.labels.push(("H".into(), h));
    }
    Some(marks)
}

/// The body of a workspace figure, computed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Content {
    /// The map.
    Map(WorkspaceMap),
    /// The point cloud.
    Cloud(PointCloud),
    /// The joint-space rectangle.
    JointRectangle(JointRectangle),
}

/// Computes what `request` asks for. `progress(fraction)` is called as the work proceeds (the
/// statistics are the first 30 %).
pub fn compute_figure_data(
    robot: &Robot,
    request: &FigureRequest,
    progress: &(dyn Fn(f32) + Sync),
) -> Result<FigureData, WorkspaceError> {
    compute_figure_data_forming(robot, request, progress, &mut OneShot)
}

/// Cells of a map's coarse first look: one in `COARSE` per side.
pub const COARSE: usize = 8;

/// [`compute_figure_data`], handing `forming` the map while it forms: a coarse first look (one
/// cell in [`COARSE`] per side, one joint-space sample in [`COARSE`], upsampled to the map's
/// cells; `rows_done` 0), then the map refined tile by tile (the rows not decided yet from the
/// coarse look), all before the statistics. The data returned are the one-shot data, whatever
/// `forming` wants.
pub fn compute_figure_data_forming(
    robot: &Robot,
    request: &FigureRequest,
    progress: &(dyn Fn(f32) + Sync),
    forming: &mut dyn MapForming,
) -> Result<FigureData, WorkspaceError> {
    compute_figure_data_in(robot, request, None, progress, forming)
}

/// [`compute_figure_data_forming`] in a cell: the map made with [`compute_map_in`] (a point
/// counts as reached by a posture only where it is within the limits and collision-free; the
/// map carries the obstacles in its view). The statistics stay those without the obstacles.
/// A cell is for maps: a point cloud or a joint-space rectangle with one is
/// [`WorkspaceError::InvalidOption`].
pub fn compute_figure_data_in(
    robot: &Robot,
    request: &FigureRequest,
    cell: Option<&CellScene>,
    progress: &(dyn Fn(f32) + Sync),
    forming: &mut dyn MapForming,
) -> Result<FigureData, WorkspaceError> {
    if cell.is_some() && !matches!(request.content, ContentRequest::Map(_)) {
        return Err(WorkspaceError::InvalidOption {
            option: "scene",
            value: "with a 3D or joint-space view".into(),
            expected: "a scene is drawn in the plane, top and side views",
        });
    }
    let mut map = None;
    if let ContentRequest::Map(req) = &request.content
        && forming.wants()
    {
        let coarse = coarse_map(robot, req)?;
        forming.partial(&coarse, 0);
        progress(0.1);
        let mut merge = Merge {
            coarse: &coarse,
            to: forming,
            progress,
            tiles: 0,
        };
        map = Some(compute_map_in(robot, req, cell, &mut merge)?);
    }
    let (stats, plane) = figure_stats(robot, request)?;
    progress(if map.is_some() { 0.8 } else { 0.3 });
    let content = match &request.content {
        ContentRequest::Map(req) => match map {
            Some(map) => Content::Map(map),
            None => Content::Map(compute_map_in(robot, req, cell, &mut OneShot)?),
        },
        ContentRequest::Cloud(opts) => {
            let n = opts.samples.max(1);
            let samples = sample(robot, opts, &|done| {
                progress(0.3 + 0.6 * done as f32 / n as f32);
            })?;
            Content::Cloud(point_cloud(&samples))
        }
        ContentRequest::JointRectangle => Content::JointRectangle(joint_rectangle(robot)?),
    };
    progress(0.9);
    Ok(FigureData {
        stats,
        content,
        plane_marks: plane,
    })
}

/// The statistics a figure shows and, for the plane of a two-link arm with joint limits, Fig.
/// 2.30's marks.
pub fn figure_stats(
    robot: &Robot,
    request: &FigureRequest,
) -> Result<(WorkspaceStats, Option<PlaneMarks>), WorkspaceError> {
    let stats = map_statistics(robot, request.point, &request.fallback)?;
    let plane = match &request.content {
        ContentRequest::Map(req) if req.view == MapView::Plane => plane_marks(robot),
        _ => None,
    };
    Ok((stats, plane))
}

/// The coarse first look at the map `req`: computed at one cell in [`COARSE`] per side (one
/// joint-space sample in [`COARSE`]) and upsampled to its cells.
pub fn coarse_map(robot: &Robot, req: &MapRequest) -> Result<WorkspaceMap, WorkspaceError> {
    let coarse = MapRequest {
        cells: [req.cells[0].div_ceil(COARSE), req.cells[1].div_ceil(COARSE)],
        samples: (req.samples / COARSE).max(1),
        ..req.clone()
    };
    Ok(upsampled(&compute_map(robot, &coarse)?, req.cells))
}

/// A map at `cells` (the same bounds) whose every cell takes the mask of the cell of `coarse`
/// that holds its centre: the coarse look at the figure's own cells.
fn upsampled(coarse: &WorkspaceMap, cells: [usize; 2]) -> WorkspaceMap {
    let ([w, h], [cw, ch]) = (cells, [coarse.width, coarse.height]);
    let masks = (0..w * h)
        .map(|k| {
            // The coarse cell holding the centre of fine cell (i, j).
            let (i, j) = (
                (2 * (k % w) + 1) * cw / (2 * w),
                (2 * (k / w) + 1) * ch / (2 * h),
            );
            coarse.masks[j * cw + i]
        })
        .collect();
    WorkspaceMap {
        width: w,
        height: h,
        masks,
        edges: Vec::new(),
        values: None,
        curves: Vec::new(),
        fills: Vec::new(),
        ..coarse.clone()
    }
}

/// Hands partial maps on with the rows not decided yet taken from the coarse look, and reports
/// progress after each tile.
struct Merge<'a> {
    coarse: &'a WorkspaceMap,
    to: &'a mut dyn MapForming,
    progress: &'a (dyn Fn(f32) + Sync),
    /// Tiles done so far.
    tiles: usize,
}

impl MapForming for Merge<'_> {
    fn wants(&mut self) -> bool {
        self.tiles += 1;
        let done = (self.tiles * super::TILE_ROWS) as f32 / self.coarse.height.max(1) as f32;
        (self.progress)(0.1 + 0.6 * done.min(1.0));
        self.to.wants()
    }

    fn partial(&mut self, map: &WorkspaceMap, rows_done: usize) {
        if rows_done >= map.height || self.coarse.masks.len() != map.masks.len() {
            return self.to.partial(map, rows_done);
        }
        let mut merged = map.clone();
        let k = rows_done * map.width;
        merged.masks[k..].copy_from_slice(&self.coarse.masks[k..]);
        self.to.partial(&merged, rows_done);
    }
}
