//! The figures of `armlab reachability` (issue 49): the flags (flattened into its arguments)
//! and the figures of a map, each written as PNG, SVG or PDF by its file's extension.
//!
//! `--figure FILE` may be repeated; `--figure-kind`, `--view`, `--slice-m` and `--direction`
//! are each given once for every figure, or once per `--figure` in the same order.

use super::CliError;
use super::figures::{Size, ThemeArg};
use crate::figure::reachability::{
    MapFigureError, MapFigureKind, MapFigureSpec, SliceView, figure_data, layer_at, paint,
    postures_size,
};
use crate::reachability::{ReachabilityMap, VoxelGrid};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// What a reachability figure shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum FigureKindArg {
    /// The reachability index of each cell (the fraction of its N x R orientations reached).
    Index,
    /// Where the tool can point along --direction: the rolls about the map's nearest sample
    /// direction reached in each cell.
    Direction,
    /// Which postures reach each cell along --direction: one panel per posture.
    Postures,
}

impl From<FigureKindArg> for MapFigureKind {
    fn from(k: FigureKindArg) -> Self {
        match k {
            FigureKindArg::Index => MapFigureKind::Index,
            FigureKindArg::Direction => MapFigureKind::Direction,
            FigureKindArg::Postures => MapFigureKind::Postures,
        }
    }
}

/// The plane a reachability figure cuts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum SliceViewArg {
    /// The x-z plane at y = --slice-m (default: through the base).
    Side,
    /// The x-y plane at z = --slice-m (default: the layer where the figure's quantity adds up
    /// to the most).
    Top,
}

impl From<SliceViewArg> for SliceView {
    fn from(v: SliceViewArg) -> Self {
        match v {
            SliceViewArg::Side => SliceView::Side,
            SliceViewArg::Top => SliceView::Top,
        }
    }
}

/// A direction `X,Y,Z` (world frame, any length but zero).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DirectionArg(pub [f64; 3]);

impl std::str::FromStr for DirectionArg {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let parts: Vec<&str> = s.split(',').map(str::trim).collect();
        let values: Vec<f64> = parts.iter().filter_map(|p| p.parse().ok()).collect();
        match values[..] {
            [x, y, z] if parts.len() == 3 && values.iter().all(|v| v.is_finite()) => {
                if x == 0.0 && y == 0.0 && z == 0.0 {
                    Err(format!("{s:?} has no length: give a nonzero X,Y,Z"))
                } else {
                    Ok(DirectionArg([x, y, z]))
                }
            }
            _ => Err(format!(
                "{s:?} is not X,Y,Z: three numbers separated by commas, e.g. 0,0,-1"
            )),
        }
    }
}

/// The figure flags of `armlab reachability` (flattened into its arguments).
#[derive(Debug, Default, clap::Args)]
pub struct MapFigureArgs {
    /// A figure of the map to write: PNG, or SVG / PDF (vectors, text as text) by its
    /// extension; repeat for several.
    #[arg(long = "figure", value_name = "FILE")]
    pub figure: Vec<PathBuf>,
    /// What each figure shows (once for all, or once per --figure) [default: index].
    #[arg(long = "figure-kind", value_enum, value_name = "KIND")]
    pub figure_kind: Vec<FigureKindArg>,
    /// The plane each figure cuts (once for all, or once per --figure) [default: side].
    #[arg(long, value_enum)]
    pub view: Vec<SliceViewArg>,
    /// Where the plane is cut, m in the world frame: y for the side view, z for the top view
    /// (once for all, or once per --figure) [default: through the base for the side view, the
    /// most reached layer for the top view].
    #[arg(long = "slice-m", value_name = "M", allow_hyphen_values = true)]
    pub slice_m: Vec<f64>,
    /// The tool direction of the direction and posture figures, world frame (once for all, or
    /// once per --figure); the map's nearest sample direction is shown [default: 0,0,-1,
    /// pointing down].
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub direction: Vec<DirectionArg>,
    /// Figure size in pixels, WIDTHxHEIGHT [default: 1200x900; a posture map 400x400 per panel
    /// under its header].
    #[arg(long = "figure-size", value_name = "WxH")]
    pub figure_size: Option<Size>,
    /// Figure colours.
    #[arg(long = "figure-theme", value_enum, default_value_t)]
    pub figure_theme: ThemeArg,
}

/// Figure flags that cannot be used, found before the map is computed where the flags alone
/// tell.
#[derive(Debug, Error)]
pub enum MapFigureFlagError {
    /// A per-figure flag given neither once nor once per `--figure`.
    #[error(
        "{flag} is given {given} times for {figures} --figure files: give it once for every \
         figure, or once per --figure in the same order"
    )]
    Counts {
        /// The flag.
        flag: &'static str,
        /// How many times it was given.
        given: usize,
        /// `--figure` files.
        figures: usize,
    },
    /// A figure flag without any `--figure`.
    #[error("{flag} is given without --figure: add --figure FILE (.png, .svg or .pdf)")]
    NoFigure {
        /// The flag.
        flag: &'static str,
    },
    /// A figure file of another format than PNG, SVG or PDF.
    #[error("--figure writes .png, .svg or .pdf files, not {}", path.display())]
    Extension {
        /// The file as given.
        path: PathBuf,
    },
    /// A figure that cannot be cut from the map (a slice outside the grid).
    #[error(transparent)]
    Figure(#[from] MapFigureError),
}

/// The value of a per-figure flag for figure `k` of `figures`: none given, one for all, or one
/// per figure.
fn pick<T: Copy>(
    values: &[T],
    k: usize,
    figures: usize,
    flag: &'static str,
) -> Result<Option<T>, MapFigureFlagError> {
    match values.len() {
        0 => Ok(None),
        1 => Ok(Some(values[0])),
        n if n == figures => Ok(Some(values[k])),
        given => Err(MapFigureFlagError::Counts {
            flag,
            given,
            figures,
        }),
    }
}

/// What figure `k` shows.
fn spec(args: &MapFigureArgs, k: usize) -> Result<MapFigureSpec, MapFigureFlagError> {
    let n = args.figure.len();
    let d = MapFigureSpec::default();
    Ok(MapFigureSpec {
        kind: pick(&args.figure_kind, k, n, "--figure-kind")?.map_or(d.kind, Into::into),
        view: pick(&args.view, k, n, "--view")?.map_or(d.view, Into::into),
        slice_m: pick(&args.slice_m, k, n, "--slice-m")?,
        direction: pick(&args.direction, k, n, "--direction")?.map_or(d.direction, |v| v.0),
    })
}

/// Whether `path` names a PNG, SVG or PDF file.
fn known_format(path: &Path) -> bool {
    let ext = path.extension().and_then(|e| e.to_str());
    ext.is_some_and(|e| ["png", "svg", "pdf"].contains(&e.to_ascii_lowercase().as_str()))
}

/// Checks the figure flags before any work: counts, formats, and, with the map's `grid`
/// (known before the map is computed: [`crate::reachability::plan_grid`]), every `--slice-m`.
///
/// # Errors
///
/// [`MapFigureFlagError`] naming the flag.
pub fn check_figure_args(
    args: &MapFigureArgs,
    grid: Option<&VoxelGrid>,
) -> Result<(), MapFigureFlagError> {
    if args.figure.is_empty() {
        let given = [
            ("--figure-kind", !args.figure_kind.is_empty()),
            ("--view", !args.view.is_empty()),
            ("--slice-m", !args.slice_m.is_empty()),
            ("--direction", !args.direction.is_empty()),
            ("--figure-size", args.figure_size.is_some()),
        ];
        if let Some((flag, _)) = given.iter().find(|(_, g)| *g) {
            return Err(MapFigureFlagError::NoFigure { flag });
        }
    }
    for (k, path) in args.figure.iter().enumerate() {
        if !known_format(path) {
            return Err(MapFigureFlagError::Extension { path: path.clone() });
        }
        let spec = spec(args, k)?;
        if let (Some(g), Some(at)) = (grid, spec.slice_m) {
            layer_at(g, spec.view, at)?;
        }
    }
    Ok(())
}

/// Draws and writes every `--figure` of `map` (PNG, SVG or PDF by extension); `base` is the
/// robot's base position (m, world frame: `robot.base.translation`), marked in the figures and
/// through which the side view is cut by default. Returns the files written, in order.
///
/// # Errors
///
/// Bad flags ([`check_figure_args`]), no graphics adapter, a file that cannot be written.
pub fn write_figures(
    map: &ReachabilityMap,
    base: [f64; 3],
    args: &MapFigureArgs,
) -> Result<Vec<PathBuf>, CliError> {
    check_figure_args(args, Some(&map.grid))?;
    let mut written = Vec::with_capacity(args.figure.len());
    for (k, path) in args.figure.iter().enumerate() {
        let spec = spec(args, k)?;
        let data = figure_data(map, base, &spec).map_err(MapFigureFlagError::from)?;
        let size = match (args.figure_size, spec.kind) {
            (Some(s), _) => s.0,
            (None, MapFigureKind::Postures) => postures_size(map),
            (None, _) => [1200, 900],
        };
        // A fresh renderer per file: the same figure is the same bytes whatever came before.
        let mut figs = crate::headless::figures_for(path)?;
        let fig = paint(&mut figs, map, &data, size, args.figure_theme.into())?;
        crate::headless::write_figure(&mut figs, &fig.image, path)?;
        written.push(path.clone());
    }
    Ok(written)
}
