//! A reachability map (issue 49) as draw lists: the voxels of a slice plane as flat squares
//! coloured by their reachability index, every other reached voxel as a dot, the outline of the
//! slice plane and of a voxel, the small sphere of a voxel's approach directions (reached or
//! not), and a base placement's heat map on the floor with the best placement marked. It paints
//! what it is handed: the map, the index and the placement come from the caller.

use super::{Dot, Label, Line, MeshInstance, Rgba, Scene, Shape};
use crate::reachability::VoxelGrid;

/// The index colour map's stops, from 0 (dark purple) through blue, teal and green to 1
/// (yellow): viridis at 0, 0.25, 0.5, 0.75 and 1, in linear RGB (the renderer's colours are
/// linear; viridis's sRGB values converted), readable on a projector and by the colour-blind.
const INDEX_STOPS: [[f32; 3]; 5] = [
    [0.0579, 0.0004, 0.0884],
    [0.0432, 0.0846, 0.2591],
    [0.0149, 0.2814, 0.2643],
    [0.1122, 0.5854, 0.1213],
    [0.9841, 0.7993, 0.0183],
];

/// The colour of a reachability index `f` in [0, 1] (clamped): viridis, opaque, linear RGB.
///
/// ```
/// use armlab::scene::reachability::index_color;
///
/// let (lo, hi) = (index_color(0.0), index_color(1.0));
/// assert!(hi[0] + hi[1] > lo[0] + lo[1]); // yellow is lighter than dark blue
/// assert_eq!(index_color(2.0), hi);
/// ```
pub fn index_color(f: f64) -> Rgba {
    let t = (f.clamp(0.0, 1.0) as f32) * (INDEX_STOPS.len() - 1) as f32;
    let k = (t.floor() as usize).min(INDEX_STOPS.len() - 2);
    let u = t - k as f32;
    let (a, b) = (INDEX_STOPS[k], INDEX_STOPS[k + 1]);
    [
        a[0] + (b[0] - a[0]) * u,
        a[1] + (b[1] - a[1]) * u,
        a[2] + (b[2] - a[2]) * u,
        1.0,
    ]
}

/// A direction reached at every roll shown: green (linear RGB, as every colour here).
pub const REACHED: Rgba = [0.007, 0.3515, 0.0452, 1.0];
/// A direction reached at some rolls only: orange.
pub const PARTLY_REACHED: Rgba = [0.8714, 0.3515, 0.007, 1.0];
/// A direction not reached: red.
pub const NOT_REACHED: Rgba = [0.6105, 0.0168, 0.013, 1.0];
/// The direction the target was moved to, and the best placement: blue.
pub const AIMED: Rgba = [0.013, 0.0802, 0.8714, 1.0];
/// Outlines (the slice plane, the voxel pointed at): near black.
const OUTLINE: Rgba = [0.0212, 0.0212, 0.0273, 1.0];
/// Opacity of the slice's squares: the arm behind them stays visible.
pub const SLICE_ALPHA: f32 = 0.9;

/// How the slice is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SliceStyle {
    /// Side of a square as a fraction of the voxel (a gap shows the grid).
    pub fill: f64,
    /// Opacity of the squares.
    pub alpha: f32,
    /// Diameter of the other voxels' dots (pixels; 0: not drawn).
    pub dots_px: f32,
}

impl Default for SliceStyle {
    fn default() -> Self {
        Self {
            fill: 0.9,
            alpha: SLICE_ALPHA,
            dots_px: 0.0,
        }
    }
}

fn f32x3(p: [f64; 3]) -> [f32; 3] {
    p.map(|v| v as f32)
}

/// The voxels `voxels` (flat C-order indices of `grid`) of the slice across `axis` as flat
/// squares in the slice plane, coloured by `index` (one per voxel of the grid); with
/// `style.dots_px` above 0 every other voxel with an index above 0 as a dot of its colour.
///
/// ```
/// use armlab::reachability::VoxelGrid;
/// use armlab::scene::reachability::{SliceStyle, slice_scene};
///
/// let grid = VoxelGrid { origin: [0.0; 3], voxel_m: 0.1, dims: [2, 2, 2] };
/// let index = vec![0.5, 0.0, 1.0, 0.25, 0.0, 0.0, 0.0, 0.75];
/// // The slice x = 0 (i = 0): voxels 0..4, of which 0, 2 and 3 are reached.
/// let scene = slice_scene(&grid, &index, 0, &[0, 2, 3], &SliceStyle::default());
/// assert_eq!(scene.meshes.len(), 3);
/// // Flat across x: a tenth of a voxel thin, 0.9 of a voxel wide.
/// let m = scene.meshes[1].world_from_unit;
/// assert!((m[0][0] - 0.01).abs() < 1e-6 && (m[1][1] - 0.09).abs() < 1e-6);
/// ```
pub fn slice_scene(
    grid: &VoxelGrid,
    index: &[f64],
    axis: usize,
    voxels: &[usize],
    style: &SliceStyle,
) -> Scene {
    let mut scene = Scene::default();
    let v = grid.voxel_m;
    let mut size = [v * style.fill; 3];
    size[axis] = 0.1 * v;
    for &k in voxels {
        let c = grid.centre(grid.ijk(k));
        let mut color = index_color(index[k]);
        color[3] = style.alpha;
        scene.meshes.push(MeshInstance {
            shape: Shape::Cube,
            world_from_unit: [
                [size[0] as f32, 0.0, 0.0, 0.0],
                [0.0, size[1] as f32, 0.0, 0.0],
                [0.0, 0.0, size[2] as f32, 0.0],
                [c[0] as f32, c[1] as f32, c[2] as f32, 1.0],
            ],
            color,
        });
    }
    if style.dots_px > 0.0 {
        let layer = voxels.first().map(|&k| grid.ijk(k)[axis]);
        for (k, &f) in index.iter().enumerate() {
            let ijk = grid.ijk(k);
            if f > 0.0 && Some(ijk[axis]) != layer {
                scene.dots.push(Dot {
                    p: f32x3(grid.centre(ijk)),
                    color: index_color(f),
                    size_px: style.dots_px,
                });
            }
        }
    }
    scene
}

/// The outline of the slice plane across `axis` at layer `layer` of `grid`: the rectangle
/// around its voxels' cells, labelled with the plane's coordinate ("y = 0.10 m").
pub fn slice_outline(grid: &VoxelGrid, axis: usize, layer: usize) -> Scene {
    let v = grid.voxel_m;
    let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
    let plane = grid.origin[axis] + v * layer as f64;
    let corner = |sa: f64, sb: f64| {
        let mut p = [0.0; 3];
        p[axis] = plane;
        p[a] = if sa < 0.0 {
            grid.origin[a] - 0.5 * v
        } else {
            grid.origin[a] + v * (grid.dims[a] as f64 - 0.5)
        };
        p[b] = if sb < 0.0 {
            grid.origin[b] - 0.5 * v
        } else {
            grid.origin[b] + v * (grid.dims[b] as f64 - 0.5)
        };
        f32x3(p)
    };
    let c = [
        corner(-1.0, -1.0),
        corner(1.0, -1.0),
        corner(1.0, 1.0),
        corner(-1.0, 1.0),
    ];
    let mut scene = Scene::default();
    for k in 0..4 {
        scene.lines.push(Line {
            a: c[k],
            b: c[(k + 1) % 4],
            color: OUTLINE,
            width_px: 1.5,
        });
    }
    scene.labels.push(Label {
        p: c[2],
        text: format!("{} = {plane:.2} m", ["x", "y", "z"][axis]),
        color: OUTLINE,
        movable: true,
    });
    scene
}

/// The twelve edges of the cell of voxel `ijk` of `grid`, `width_px` wide.
pub fn voxel_outline(grid: &VoxelGrid, ijk: [usize; 3], width_px: f32) -> Vec<Line> {
    let c = grid.centre(ijk);
    let h = 0.5 * grid.voxel_m;
    let corner = |k: usize| -> [f32; 3] {
        f32x3([0, 1, 2].map(|a| c[a] + if k >> a & 1 == 1 { h } else { -h }))
    };
    let mut out = Vec::with_capacity(12);
    for k in 0..8usize {
        for a in 0..3 {
            if k >> a & 1 == 0 {
                out.push(Line {
                    a: corner(k),
                    b: corner(k | 1 << a),
                    color: OUTLINE,
                    width_px,
                });
            }
        }
    }
    out
}

/// The small sphere of approach directions at `centre` (m, world frame): a dot at
/// `centre + radius_m d_k` for every direction `d_k`, coloured by `colors[k]`; the dot of
/// `aimed` larger and blue.
pub fn direction_sphere(
    centre: [f64; 3],
    radius_m: f64,
    directions: &[[f64; 3]],
    colors: &[Rgba],
    aimed: Option<usize>,
) -> Vec<Dot> {
    directions
        .iter()
        .zip(colors)
        .enumerate()
        .map(|(k, (d, &color))| {
            let aim = aimed == Some(k);
            Dot {
                p: f32x3([0, 1, 2].map(|a| centre[a] + radius_m * d[a])),
                color: if aim { AIMED } else { color },
                size_px: if aim { 14.0 } else { 8.0 },
            }
        })
        .collect()
}

/// A base placement's heat map on the floor plane `z` (m): a square per base position
/// (`x[i]`, `y[j]`) whose best fraction `heat[i * ny + j]` over the yaws is above 0, coloured by
/// it, and the area's outline.
pub fn floor_heat_map(x: &[f64], y: &[f64], heat: &[f64], z: f64, step: f64) -> Scene {
    let mut scene = Scene::default();
    let s = (0.92 * step) as f32;
    // A hair above the floor (the ground grid's lines), thin.
    let z = z as f32 + 0.002;
    for (i, &xi) in x.iter().enumerate() {
        for (j, &yj) in y.iter().enumerate() {
            let f = heat[i * y.len() + j];
            if f <= 0.0 {
                continue;
            }
            scene.meshes.push(MeshInstance {
                shape: Shape::Cube,
                world_from_unit: [
                    [s, 0.0, 0.0, 0.0],
                    [0.0, s, 0.0, 0.0],
                    [0.0, 0.0, 0.003, 0.0],
                    [xi as f32, yj as f32, z, 1.0],
                ],
                color: index_color(f),
            });
        }
    }
    if let (Some(&x0), Some(&x1), Some(&y0), Some(&y1)) = (x.first(), x.last(), y.first(), y.last())
    {
        let h = 0.5 * step;
        let c = [
            [x0 - h, y0 - h],
            [x1 + h, y0 - h],
            [x1 + h, y1 + h],
            [x0 - h, y1 + h],
        ]
        .map(|[a, b]| [a as f32, b as f32, z]);
        for k in 0..4 {
            scene.lines.push(Line {
                a: c[k],
                b: c[(k + 1) % 4],
                color: OUTLINE,
                width_px: 1.5,
            });
        }
    }
    scene
}

/// The best placement's mark: a vertical post at (`x`, `y`) from the floor `z` (m), `height_m`
/// high, an arrow along the base's x axis turned by `yaw` (rad) on the floor, and `label`.
pub fn placement_mark([x, y, z]: [f64; 3], yaw: f64, height_m: f64, label: String) -> Scene {
    let mut scene = Scene::default();
    let p = |a: f64, b: f64, c: f64| [a as f32, b as f32, c as f32];
    let (s, c) = yaw.sin_cos();
    let len = 0.5 * height_m;
    let tip = (x + c * len, y + s * len);
    let head = 0.25 * len;
    for (a, b) in [
        (p(x, y, z), p(x, y, z + height_m)),
        (p(x, y, z + 0.004), p(tip.0, tip.1, z + 0.004)),
        (
            p(tip.0, tip.1, z + 0.004),
            p(
                tip.0 - head * (c - s * 0.6),
                tip.1 - head * (s + c * 0.6),
                z + 0.004,
            ),
        ),
        (
            p(tip.0, tip.1, z + 0.004),
            p(
                tip.0 - head * (c + s * 0.6),
                tip.1 - head * (s - c * 0.6),
                z + 0.004,
            ),
        ),
    ] {
        scene.lines.push(Line {
            a,
            b,
            color: AIMED,
            width_px: 4.0,
        });
    }
    scene.dots.push(Dot {
        p: p(x, y, z + height_m),
        color: AIMED,
        size_px: 12.0,
    });
    scene.labels.push(Label {
        p: p(x, y, z + height_m),
        text: label,
        color: AIMED,
        movable: true,
    });
    scene
}
