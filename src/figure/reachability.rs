//! Reachability-map figures (issue 49): planes of voxels cut from a [`ReachabilityMap`] and
//! painted as 2D plots, PNG or SVG/PDF like the other figures.
//!
//! - **Index slices** ([`MapFigureKind::Index`]): each cell coloured by the reachability index
//!   (the fraction of the voxel's N x R sample orientations reached), with a colour bar.
//! - **Direction slices** ([`MapFigureKind::Direction`], "where the tool can point down"): the
//!   map's Fibonacci direction nearest to the one asked, each cell coloured by how many of the R
//!   rolls about it are reached; the title names the sample direction and its angle from the one
//!   asked.
//! - **Posture maps** ([`MapFigureKind::Postures`]): for that direction, one small panel per
//!   posture of the map's family, each cell coloured by how many rolls that posture reaches.
//!
//! Views: [`SliceView::Side`] is the x-z plane of the voxel layer at a given y (looking along
//! +y: x to the right, z up), by default the layer through the base; [`SliceView::Top`] is the
//! x-y plane of the layer at a given z, by default the layer where the figure's own quantity
//! (the index, or the rolls reached along the direction) adds up to the most. Coordinates are
//! the map's world frame, in metres; the base is marked, and the dashed circle is where the
//! plane cuts the sphere beyond which the map solved no voxel
//! ([`ReachabilityMap::reach_centre`], [`ReachabilityMap::reach_m`]).
//!
//! [`figure_data`] cuts the plane and reads its values off the map (no solving: the map holds
//! every sample); [`paint`] paints that data.

use super::figures::{Figures, PlotFrame, Scene3d};
use super::palette::{c32, sequential};
use super::plot2d::{Area, ColorBar, Curve, Plot2d};
use super::vector::VectorPage;
use super::{FigureError, Theme};
use crate::reachability::{ReachabilityMap, VoxelGrid};
use egui::Color32;
use thiserror::Error;

/// Which plane of voxels a figure cuts (world frame).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SliceView {
    /// The x-z plane of one voxel layer along y (x to the right, z up).
    #[default]
    Side,
    /// The x-y plane of one voxel layer along z (x to the right, y up).
    Top,
}

impl SliceView {
    /// The grid axes shown across and up, and the axis the plane is cut along (0 = x, 1 = y,
    /// 2 = z).
    fn axes(self) -> ([usize; 2], usize) {
        match self {
            SliceView::Side => ([0, 2], 1),
            SliceView::Top => ([0, 1], 2),
        }
    }
}

/// What a reachability figure shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MapFigureKind {
    /// The reachability index of each cell.
    #[default]
    Index,
    /// Where the tool can point along a direction: rolls reached about it per cell.
    Direction,
    /// Which postures reach each cell along a direction, one panel per posture.
    Postures,
}

/// What to cut from a map and how to show it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapFigureSpec {
    /// The figure.
    pub kind: MapFigureKind,
    /// The plane.
    pub view: SliceView,
    /// Where the plane is cut: y (side view) or z (top view) in m, world frame; the voxel layer
    /// whose cells hold it is shown. `None`: through the base (side view), or the layer where
    /// the figure's quantity adds up to the most (top view).
    pub slice_m: Option<f64>,
    /// The tool direction asked for (world frame, any length but zero) of the direction and
    /// posture figures: the map's nearest sample direction is shown.
    pub direction: [f64; 3],
}

impl Default for MapFigureSpec {
    /// The index in the side view through the base; the direction pointing down.
    fn default() -> Self {
        Self {
            kind: MapFigureKind::Index,
            view: SliceView::Side,
            slice_m: None,
            direction: [0.0, 0.0, -1.0],
        }
    }
}

/// A figure that cannot be cut from the map (found before anything is painted).
#[derive(Debug, Error, PartialEq)]
pub enum MapFigureError {
    /// The plane asked for lies outside the map's grid.
    #[error(
        "the slice at {axis} = {at_m} m is outside the map's grid, whose cells span {axis} = \
         {lo_m:.3} to {hi_m:.3} m"
    )]
    SliceOutside {
        /// The axis the plane is cut along ('y' for the side view, 'z' for the top view).
        axis: char,
        /// The coordinate asked for (m).
        at_m: f64,
        /// The grid's first cell edge along that axis (m).
        lo_m: f64,
        /// Its last cell edge (m).
        hi_m: f64,
    },
    /// The direction asked for has no length (or is not finite).
    #[error(
        "the direction ({}, {}, {}) has no length: give a nonzero x,y,z",
        direction[0],
        direction[1],
        direction[2]
    )]
    ZeroDirection {
        /// The direction given.
        direction: [f64; 3],
    },
    /// The map has no voxel, direction or roll.
    #[error("the map is empty ({voxels} voxels, {directions} directions, {rolls} rolls)")]
    EmptyMap {
        /// Voxels of its grid.
        voxels: usize,
        /// Its directions.
        directions: usize,
        /// Its rolls.
        rolls: usize,
    },
}

/// The map's sample direction shown by a direction or posture figure.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChosenDirection {
    /// The direction asked for, made unit (world frame).
    pub asked: [f64; 3],
    /// The index k of the map's nearest direction d_k.
    pub index: usize,
    /// d_k (unit, world frame).
    pub sample: [f64; 3],
    /// The angle between d_k and the direction asked (rad).
    pub angle_rad: f64,
}

/// A plane of voxels: the cells of one voxel layer, row by row from the bottom.
#[derive(Debug, Clone, PartialEq)]
pub struct MapSlice {
    /// The plane.
    pub view: SliceView,
    /// The layer's index along the axis the plane is cut along (j for the side view, k for
    /// the top view).
    pub layer: usize,
    /// The layer's centre coordinate along that axis (m, world frame).
    pub plane_m: f64,
    /// Cells across (along x) and up (along z or y).
    pub dims: [usize; 2],
    /// The cells' outer edges `[x_min, x_max, up_min, up_max]` (m, world frame).
    pub bounds: [f64; 4],
    /// The flat C-order voxel index of each cell: cell (u, w), u across and w up, is entry
    /// `w * dims[0] + u`.
    pub voxels: Vec<usize>,
}

/// What a figure paints, read off a map by [`figure_data`]: per cell of the slice (in
/// [`MapSlice::voxels`] order).
#[derive(Debug, Clone, PartialEq)]
pub struct MapFigureData {
    /// The figure.
    pub kind: MapFigureKind,
    /// The plane.
    pub slice: MapSlice,
    /// The base's position (m, world frame), marked in the figure.
    pub base: [f64; 3],
    /// What the figure shows `[x_min, x_max, up_min, up_max]` (m, world frame): the cells of
    /// every voxel the map reaches in some orientation (in any layer, so that the slices of one
    /// view share it) and the base, with a voxel to spare.
    pub extent: [f64; 4],
    /// The sample direction of a direction or posture figure.
    pub direction: Option<ChosenDirection>,
    /// The reachability index of each cell, in [0, 1].
    pub index: Vec<f64>,
    /// Rolls reached along the chosen direction in each cell (empty for an index figure).
    pub along: Vec<u16>,
    /// Per posture bit, the rolls along the chosen direction that posture reaches in each cell
    /// (empty but for a posture figure).
    pub posture_rolls: Vec<Vec<u16>>,
}

/// The map's sample direction nearest to `asked` (largest dot product, the first on ties).
///
/// # Errors
///
/// [`MapFigureError::ZeroDirection`] when `asked` has no length; [`MapFigureError::EmptyMap`]
/// when the map has no direction.
pub fn nearest_direction(
    map: &ReachabilityMap,
    asked: [f64; 3],
) -> Result<ChosenDirection, MapFigureError> {
    let norm = asked.iter().map(|v| v * v).sum::<f64>().sqrt();
    if !(norm.is_finite() && norm > 0.0) {
        return Err(MapFigureError::ZeroDirection { direction: asked });
    }
    let unit = asked.map(|v| v / norm);
    let dot = |d: &[f64; 3]| d[0] * unit[0] + d[1] * unit[1] + d[2] * unit[2];
    let (index, best) = map
        .directions
        .iter()
        .enumerate()
        .fold(None, |acc: Option<(usize, f64)>, (k, d)| match acc {
            Some((_, b)) if b >= dot(d) => acc,
            _ => Some((k, dot(d))),
        })
        .ok_or_else(|| empty(map))?;
    Ok(ChosenDirection {
        asked: unit,
        index,
        sample: map.directions[index],
        angle_rad: best.clamp(-1.0, 1.0).acos(),
    })
}

fn empty(map: &ReachabilityMap) -> MapFigureError {
    MapFigureError::EmptyMap {
        voxels: map.grid.len(),
        directions: map.directions.len(),
        rolls: map.rolls.len(),
    }
}

/// Rolls reached along direction `d` in voxel `v`.
fn rolls_along(map: &ReachabilityMap, v: usize, d: usize) -> u16 {
    let start = map.sample_index(v, d, 0);
    let reached = map.reachable[start..start + map.rolls.len()]
        .iter()
        .filter(|&&b| b)
        .count();
    u16::try_from(reached).unwrap_or(u16::MAX)
}

/// Per posture bit, the rolls along direction `d` it reaches in voxel `v`.
fn posture_rolls_along(map: &ReachabilityMap, v: usize, d: usize) -> Vec<u16> {
    let start = map.sample_index(v, d, 0);
    let masks = &map.postures[start..start + map.rolls.len()];
    (0..map.posture_names.len())
        .map(|b| masks.iter().filter(|&&m| m >> b & 1 == 1).count() as u16)
        .collect()
}

/// Reads a figure's data off `map`: the plane `spec` asks for and, per cell, the index, the
/// rolls reached along the chosen direction and, for a posture figure, per posture. `base` is
/// the base's position (m, world frame), marked in the figure and through which the side view
/// is cut by default. Pure: the map already holds every sample.
///
/// # Errors
///
/// A plane outside the grid, a direction of no length, an empty map ([`MapFigureError`]).
///
/// # Examples
///
/// The Puma 560 at 25 cm, looking down on the layer where the tool points down at the most
/// rolls:
///
/// ```
/// use armlab::figure::reachability::{MapFigureKind, MapFigureSpec, SliceView, figure_data};
/// use armlab::kinematics::models::built_in;
/// use armlab::reachability::{MapControl, MapOptions, compute_reachability};
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let puma = built_in("puma560").expect("a built-in model");
/// let opts = MapOptions { voxel_m: 0.25, directions: 20, rolls: 2, ..MapOptions::default() };
/// let map = compute_reachability(&puma, &opts, None, MapControl::default())?;
/// let spec = MapFigureSpec {
///     kind: MapFigureKind::Direction,
///     view: SliceView::Top,
///     ..MapFigureSpec::default()
/// };
/// let data = figure_data(&map, [0.0; 3], &spec)?;
/// let [nx, ny, _] = map.grid.dims;
/// assert_eq!(data.slice.dims, [nx, ny]);
/// // The sample direction nearest to straight down is the last of the Fibonacci sphere.
/// assert_eq!(data.direction.expect("a direction figure").index, 19);
/// assert!(data.along.iter().any(|&r| r > 0));
/// # Ok(())
/// # }
/// ```
pub fn figure_data(
    map: &ReachabilityMap,
    base: [f64; 3],
    spec: &MapFigureSpec,
) -> Result<MapFigureData, MapFigureError> {
    if map.grid.is_empty() || map.per_voxel() == 0 {
        return Err(empty(map));
    }
    let direction = match spec.kind {
        MapFigureKind::Index => None,
        _ => Some(nearest_direction(map, spec.direction)?),
    };
    let index = map.index();
    let along_all = |v: usize| direction.map_or(0, |d| rolls_along(map, v, d.index));
    let weight = |v: usize| match direction {
        None => index[v],
        Some(_) => f64::from(along_all(v)),
    };
    let layer = choose_layer(map, spec, base, &weight)?;
    let slice = cut(map, spec.view, layer);
    let along = match direction {
        None => Vec::new(),
        Some(_) => slice.voxels.iter().map(|&v| along_all(v)).collect(),
    };
    let posture_rolls = match (spec.kind, direction) {
        (MapFigureKind::Postures, Some(d)) => {
            let per_cell: Vec<Vec<u16>> = slice
                .voxels
                .iter()
                .map(|&v| posture_rolls_along(map, v, d.index))
                .collect();
            (0..map.posture_names.len())
                .map(|b| per_cell.iter().map(|c| c[b]).collect())
                .collect()
        }
        _ => Vec::new(),
    };
    Ok(MapFigureData {
        kind: spec.kind,
        extent: extent(map, spec.view, &index, base),
        index: slice.voxels.iter().map(|&v| index[v]).collect(),
        slice,
        base,
        direction,
        along,
        posture_rolls,
    })
}

/// The voxel layer of plane `view` whose cells hold `at_m` (y for the side view, z for the top
/// view; m, world frame).
///
/// # Errors
///
/// [`MapFigureError::SliceOutside`] when no layer of `grid` holds it.
pub fn layer_at(grid: &VoxelGrid, view: SliceView, at_m: f64) -> Result<usize, MapFigureError> {
    let (_, normal) = view.axes();
    let n = grid.dims[normal];
    let t = ((at_m - grid.origin[normal]) / grid.voxel_m + 0.5).floor();
    if t >= 0.0 && t < n as f64 {
        return Ok(t as usize);
    }
    let edge = |k: f64| grid.origin[normal] + grid.voxel_m * (k - 0.5);
    Err(MapFigureError::SliceOutside {
        axis: ['x', 'y', 'z'][normal],
        at_m,
        lo_m: edge(0.0),
        hi_m: edge(n as f64),
    })
}

/// The layer a figure cuts: the one holding `spec.slice_m`, else through the base (side view)
/// or where `weight` adds up to the most (top view).
fn choose_layer(
    map: &ReachabilityMap,
    spec: &MapFigureSpec,
    base: [f64; 3],
    weight: &dyn Fn(usize) -> f64,
) -> Result<usize, MapFigureError> {
    let g = &map.grid;
    if let Some(at) = spec.slice_m {
        return layer_at(g, spec.view, at);
    }
    let (_, normal) = spec.view.axes();
    let n = g.dims[normal];
    if spec.view == SliceView::Side {
        let t = ((base[normal] - g.origin[normal]) / g.voxel_m + 0.5).floor();
        return Ok(t.clamp(0.0, (n - 1) as f64) as usize);
    }
    let mut sums = vec![0.0; n];
    for v in 0..g.len() {
        sums[g.ijk(v)[normal]] += weight(v);
    }
    Ok(sums
        .iter()
        .enumerate()
        .fold(0, |best, (k, &s)| if s > sums[best] { k } else { best }))
}

/// The box of the reached voxels' cells and the base in plane `view`, a voxel to spare (the
/// whole grid when nothing is reached).
fn extent(map: &ReachabilityMap, view: SliceView, index: &[f64], base: [f64; 3]) -> [f64; 4] {
    let g = &map.grid;
    let ([across, up], _) = view.axes();
    let mut b = [base[across], base[across], base[up], base[up]];
    let mut any = false;
    for (v, _) in index.iter().enumerate().filter(|(_, x)| **x > 0.0) {
        let c = g.centre(g.ijk(v));
        b = [
            b[0].min(c[across]),
            b[1].max(c[across]),
            b[2].min(c[up]),
            b[3].max(c[up]),
        ];
        any = true;
    }
    if !any {
        return cut(map, view, 0).bounds;
    }
    let m = 1.5 * g.voxel_m;
    [b[0] - m, b[1] + m, b[2] - m, b[3] + m]
}

/// The cells of layer `layer` of the plane `view`.
fn cut(map: &ReachabilityMap, view: SliceView, layer: usize) -> MapSlice {
    let g = &map.grid;
    let ([across, up], normal) = view.axes();
    let dims = [g.dims[across], g.dims[up]];
    let mut voxels = Vec::with_capacity(dims[0] * dims[1]);
    for w in 0..dims[1] {
        for u in 0..dims[0] {
            let mut ijk = [0; 3];
            ijk[across] = u;
            ijk[up] = w;
            ijk[normal] = layer;
            voxels.push(g.flat(ijk));
        }
    }
    let half = 0.5 * g.voxel_m;
    let lo = |a: usize| g.origin[a] - half;
    let hi = |a: usize| g.origin[a] + g.voxel_m * (g.dims[a] - 1) as f64 + half;
    MapSlice {
        view,
        layer,
        plane_m: g.origin[normal] + g.voxel_m * layer as f64,
        dims,
        bounds: [lo(across), hi(across), lo(up), hi(up)],
        voxels,
    }
}

/// A painted reachability figure.
pub struct MapFigure {
    /// The pixels.
    pub image: image::RgbaImage,
    /// Where each plot's data lie in the image (one plot, or one per posture panel in bit
    /// order), the rectangles in pixels of the whole image.
    pub frames: Vec<PlotFrame>,
}

/// Colour of a cell reached only in other orientations than the ones shown.
pub const ELSEWHERE: [u8; 3] = [214, 214, 214];
/// Colour of a cell reached along the direction by other postures only (posture panels).
pub const OTHER_POSTURES: [u8; 3] = [150, 150, 150];
/// Name of the colour map of the index and of the rolls.
pub const COLOR_MAP: &str = "viridis";

/// The colour of an index cell: the colour map, transparent where nothing is reached.
pub fn index_color(index: f64) -> Option<[u8; 3]> {
    (index > 0.0).then(|| sequential(index as f32))
}

/// The colour of a cell where `rolls` of `of` rolls are reached along the direction:
/// the colour map at `rolls / of`, else [`ELSEWHERE`] when the voxel is reached in other
/// orientations (`index > 0`), else transparent.
pub fn rolls_color(rolls: u16, of: usize, index: f64) -> Option<[u8; 3]> {
    if rolls > 0 {
        Some(sequential(f32::from(rolls) / of.max(1) as f32))
    } else {
        (index > 0.0).then_some(ELSEWHERE)
    }
}

/// Paints `data` (read off `map` by [`figure_data`]) at `size` pixels: one plot for the index
/// and direction figures, a header and one panel per posture for the posture map.
pub fn paint(
    figs: &mut Figures,
    map: &ReachabilityMap,
    data: &MapFigureData,
    size: [u32; 2],
    theme: Theme,
) -> Result<MapFigure, FigureError> {
    if data.kind == MapFigureKind::Postures && !map.posture_names.is_empty() {
        return paint_postures(figs, map, data, size, theme);
    }
    let (plot, raster) = single_plot(map, data);
    let (image, frame) = figs.plot_at(size, theme, &plot, Some((raster, data.slice.bounds)))?;
    Ok(MapFigure {
        image,
        frames: vec![frame],
    })
}

/// The plot and raster of an index or direction figure.
fn single_plot(map: &ReachabilityMap, data: &MapFigureData) -> (Plot2d, egui::ColorImage) {
    let r = map.rolls.len();
    let (title, colors, bar): (String, Vec<Option<[u8; 3]>>, ColorBar) = match data.direction {
        None => (
            format!(
                "Reachability index of the {}, {}",
                map.model,
                view_words(data.slice.view)
            ),
            data.index.iter().map(|&x| index_color(x)).collect(),
            ColorBar {
                label: format!(
                    "reachability index: fraction of the N x R = {} orientations reached \
                     (colour map: {COLOR_MAP})",
                    map.per_voxel()
                ),
                min: 0.0,
                max: 1.0,
                colors: ramp(),
            },
        ),
        Some(d) => (
            format!(
                "Where the {} can point {}, {}",
                map.model,
                direction_words(&d),
                view_words(data.slice.view)
            ),
            data.along
                .iter()
                .zip(&data.index)
                .map(|(&k, &x)| rolls_color(k, r, x))
                .collect(),
            ColorBar {
                label: format!(
                    "rolls reached about d_{} (of R = {r}; colour map: {COLOR_MAP})",
                    d.index
                ),
                min: 0.0,
                max: r as f64,
                colors: ramp(),
            },
        ),
    };
    let mut plot = base_plot(map, data, title);
    plot.subtitle = format!("{}; {}", slice_words(&data.slice), sampling_words(map));
    plot.colorbar = Some(bar);
    if data.direction.is_some() && colors.contains(&Some(ELSEWHERE)) {
        plot.legend
            .push(("reached in other directions only".into(), c32(ELSEWHERE)));
    }
    let raster = raster(&data.slice, &colors);
    (plot, raster)
}

/// The colour map sampled for a colour bar.
fn ramp() -> Vec<Color32> {
    (0..64).map(|k| c32(sequential(k as f32 / 63.0))).collect()
}

/// The plot every figure starts from: axes, bounds, the base and the reach bound.
fn base_plot(map: &ReachabilityMap, data: &MapFigureData, title: String) -> Plot2d {
    let s = &data.slice;
    let (x_label, y_label) = match s.view {
        SliceView::Side => ("x [m] (world frame)", "z [m] (world frame)"),
        SliceView::Top => ("x [m] (world frame)", "y [m] (world frame)"),
    };
    let mut plot = Plot2d {
        title,
        x_label: x_label.into(),
        y_label: y_label.into(),
        bounds: data.extent,
        equal_aspect: true,
        ..Plot2d::default()
    };
    add_base(&mut plot, map, data);
    plot
}

/// The base (a filled triangle with its tip on the base's origin, labelled) and the circle
/// where the plane cuts the sphere beyond which the map solved no voxel (dashed).
fn add_base(plot: &mut Plot2d, map: &ReachabilityMap, data: &MapFigureData) {
    let s = &data.slice;
    let ([across, up], normal) = s.view.axes();
    let (bx, by) = (data.base[across], data.base[up]);
    let e = data.extent;
    let h = 0.035 * (e[1] - e[0]).max(e[3] - e[2]);
    plot.areas.push(Area {
        name: "base".into(),
        points: vec![[bx, by], [bx - 0.6 * h, by - h], [bx + 0.6 * h, by - h]],
        fill: Color32::from_rgb(200, 40, 40),
    });
    let c = map.reach_centre;
    let (cx, cy) = (c[across], c[up]);
    let off = s.plane_m - c[normal];
    let r2 = map.reach_m * map.reach_m - off * off;
    if r2.is_finite() && r2 > 0.0 {
        let r = r2.sqrt();
        plot.curves.push(Curve {
            name: Some("reach bound (no voxel solved beyond)".into()),
            points: (0..=180)
                .map(|k| {
                    let t = std::f64::consts::TAU * k as f64 / 180.0;
                    [cx + r * t.cos(), cy + r * t.sin()]
                })
                .collect(),
            color: Color32::from_gray(120),
            width: 1.0,
            dashed: true,
            ..Curve::default()
        });
    }
}

/// One pixel per cell (the top image row is the top cell row), transparent where `None`.
fn raster(s: &MapSlice, colors: &[Option<[u8; 3]>]) -> egui::ColorImage {
    let [w, h] = s.dims;
    let mut img = egui::ColorImage::new([w, h], vec![Color32::TRANSPARENT; w * h]);
    for (c, color) in colors.iter().enumerate() {
        if let Some([r, g, b]) = color {
            let (u, row) = (c % w, c / w);
            img.pixels[(h - 1 - row) * w + u] = Color32::from_rgb(*r, *g, *b);
        }
    }
    img
}

/// "side view" / "top view".
fn view_words(view: SliceView) -> &'static str {
    match view {
        SliceView::Side => "side view",
        SliceView::Top => "top view",
    }
}

/// "x-z plane at y = 0.000 m (layer 5 of 11)".
fn slice_words(s: &MapSlice) -> String {
    let (plane, axis) = match s.view {
        SliceView::Side => ("x-z", 'y'),
        SliceView::Top => ("x-y", 'z'),
    };
    format!("{plane} plane at {axis} = {:.3} m", s.plane_m)
}

/// The map's end-effector, resolution and solver, as figures say them.
fn sampling_words(map: &ReachabilityMap) -> String {
    let cell = if map.collisions {
        "; collision-free in the cell"
    } else {
        ""
    };
    format!(
        "end-effector {}; voxel {} m, N = {} directions x R = {} rolls; {}{cell}",
        map.end_effector,
        map.grid.voxel_m,
        map.directions.len(),
        map.rolls.len(),
        map.solver.describe()
    )
}

/// "down along d_199 = (0.05, 0.03, -1.00), 2.9° from straight down" and the like.
fn direction_words(d: &ChosenDirection) -> String {
    let asked = match d.asked {
        [x, y, z] if x == 0.0 && y == 0.0 && z < 0.0 => "straight down".to_string(),
        [x, y, z] if x == 0.0 && y == 0.0 && z > 0.0 => "straight up".to_string(),
        [x, y, z] => format!("({x:.2}, {y:.2}, {z:.2})"),
    };
    let [x, y, z] = d.sample;
    format!(
        "along d_{} = ({x:.2}, {y:.2}, {z:.2}), {:.1}° from {asked}",
        d.index,
        d.angle_rad.to_degrees()
    )
}

/// Panels across of a posture map of `n` postures.
fn panel_columns(n: usize) -> usize {
    match n {
        0..=3 => n.max(1),
        4 => 2,
        _ => 4,
    }
}

/// The size a posture map of `map` is drawn at by default: panels of 400 x 400 pixels under a
/// header.
pub fn postures_size(map: &ReachabilityMap) -> [u32; 2] {
    let n = map.posture_names.len().max(1);
    let cols = panel_columns(n);
    let rows = n.div_ceil(cols);
    let w = cols as u32 * 400;
    [w, header_height(w) + rows as u32 * 400]
}

/// Header pixels of a posture map `width` pixels wide.
fn header_height(width: u32) -> u32 {
    (f64::from(width) * 150.0 / 800.0).round() as u32
}

/// The posture map: a header (title, what the colours mean) and one panel per posture.
fn paint_postures(
    figs: &mut Figures,
    map: &ReachabilityMap,
    data: &MapFigureData,
    size: [u32; 2],
    theme: Theme,
) -> Result<MapFigure, FigureError> {
    let n = map.posture_names.len();
    let cols = panel_columns(n);
    let rows = n.div_ceil(cols);
    let head = header_height(size[0]).min(size[1] / 3);
    let panel = [
        (size[0] / cols as u32).max(16),
        ((size[1] - head) / rows as u32).max(16),
    ];
    let background = match theme {
        Theme::Light => image::Rgba([255, 255, 255, 255]),
        Theme::Dark => image::Rgba([5, 6, 7, 255]),
    };
    let mut out = image::RgbaImage::from_pixel(size[0], size[1], background);
    let mut pages = Vec::new();
    let scale = figs.text_scale;
    figs.text_scale = 0.75;
    let header = header(figs, map, data, [size[0], head], theme);
    figs.text_scale = (800.0 / panel[0] as f32).clamp(1.0, 3.0);
    let mut frames = Vec::with_capacity(n);
    let result = header.and_then(|img| {
        image::imageops::overlay(&mut out, &img, 0, 0);
        pages.extend(figs.take_vector().map(|p| ([0, 0], p)));
        for b in 0..n {
            let at = [
                (b % cols) as u32 * panel[0],
                head + (b / cols) as u32 * panel[1],
            ];
            let (plot, raster) = posture_panel(map, data, b);
            let (img, mut frame) =
                figs.plot_at(panel, theme, &plot, Some((raster, data.slice.bounds)))?;
            image::imageops::overlay(&mut out, &img, i64::from(at[0]), i64::from(at[1]));
            pages.extend(figs.take_vector().map(|p| (at, p)));
            let [l, t, r, bt] = frame.rect_px;
            let (dx, dy) = (at[0] as f32, at[1] as f32);
            frame.rect_px = [l + dx, t + dy, r + dx, bt + dy];
            frames.push(frame);
        }
        Ok(())
    });
    figs.text_scale = scale;
    result?;
    if figs.capturing() {
        figs.set_composite(VectorPage::compose(size, pages));
    }
    Ok(MapFigure { image: out, frames })
}

/// The posture map's header: title, the map's sampling, and a legend of the cells' colours.
fn header(
    figs: &mut Figures,
    map: &ReachabilityMap,
    data: &MapFigureData,
    size: [u32; 2],
    theme: Theme,
) -> Result<image::RgbaImage, FigureError> {
    let r = map.rolls.len();
    let d = data.direction.as_ref();
    let scene = crate::scene::Scene::default();
    figs.scene(
        size,
        theme,
        &Scene3d {
            title: format!(
                "Postures of the {} pointing {}",
                map.model,
                d.map(direction_words).unwrap_or_default()
            ),
            subtitle: format!(
                "{}, {}; {}",
                view_words(data.slice.view),
                slice_words(&data.slice),
                sampling_words(map)
            ),
            scene: &scene,
            camera: crate::camera::Camera::default(),
            legend: vec![
                (format!("all {r} rolls"), c32(sequential(1.0))),
                ("1 roll".into(), c32(sequential(1.0 / r.max(1) as f32))),
                ("other postures only".into(), c32(OTHER_POSTURES)),
                ("other directions only".into(), c32(ELSEWHERE)),
            ],
            caption: String::new(),
        },
    )
}

/// The panel of posture bit `b`: the rolls it reaches along the direction per cell.
fn posture_panel(
    map: &ReachabilityMap,
    data: &MapFigureData,
    b: usize,
) -> (Plot2d, egui::ColorImage) {
    let r = map.rolls.len();
    let rolls = &data.posture_rolls[b];
    let colors: Vec<Option<[u8; 3]>> = rolls
        .iter()
        .zip(&data.along)
        .zip(&data.index)
        .map(|((&mine, &any), &x)| match (mine, any) {
            (0, 0) => (x > 0.0).then_some(ELSEWHERE),
            (0, _) => Some(OTHER_POSTURES),
            (k, _) => rolls_color(k, r, x),
        })
        .collect();
    let cells = rolls.iter().filter(|&&k| k > 0).count();
    let mut plot = base_plot(map, data, map.posture_names[b].clone());
    plot.subtitle = format!(
        "reaches d_{} in {cells} cells of the slice",
        data.direction.map_or(0, |d| d.index)
    );
    // The panels share the header's legend.
    for a in &mut plot.areas {
        a.name.clear();
    }
    for c in &mut plot.curves {
        c.name = None;
    }
    let raster = raster(&data.slice, &colors);
    (plot, raster)
}
