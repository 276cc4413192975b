//! Filling a map's cells from an exact point test, with the cells cut by an edge supersampled.

use rayon::prelude::*;

/// A cell cut by an edge: the class masks of a 4 x 4 grid of sub-samples inside it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct EdgeCell {
    /// Cell index (row-major from the top row).
    pub index: u32,
    /// Masks of the sub-samples, row-major from the top.
    pub sub: [u8; 16],
}

/// Centre of cell `(i, j)` (column, row from the top) of a raster over `bounds`.
#[inline]
pub(crate) fn centre(bounds: [f64; 4], dims: [usize; 2], i: usize, j: usize) -> [f64; 2] {
    sub_point(bounds, dims, i, j, 0.5, 0.5)
}

/// The point at fractions `(fu, fv)` of cell `(i, j)`.
#[inline]
fn sub_point(bounds: [f64; 4], dims: [usize; 2], i: usize, j: usize, fu: f64, fv: f64) -> [f64; 2] {
    let [x0, x1, y0, y1] = bounds;
    [
        x0 + (i as f64 + fu) / dims[0] as f64 * (x1 - x0),
        y1 - (j as f64 + fv) / dims[1] as f64 * (y1 - y0),
    ]
}

/// Masks at every cell centre, in parallel by rows.
pub(crate) fn fill(
    bounds: [f64; 4],
    dims: [usize; 2],
    test: &(dyn Fn([f64; 2]) -> u8 + Sync),
) -> Vec<u8> {
    fill_tiled(bounds, dims, test, Fill::Cells, &mut |_, _| {})
}

/// How [`fill_tiled`] decides the cells.
#[derive(Clone, Copy)]
pub(crate) enum Fill<'a> {
    /// Every cell by its own test.
    Cells,
    /// By blocks, as [`fill_blocks`] does.
    Blocks(Option<&'a (dyn Fn([f64; 2], f64) -> bool + Sync)>),
}

/// Rows of a tile of a map that forms progressively (a multiple of the block side).
pub const TILE_ROWS: usize = 8 * BLOCK;

/// Masks at every cell centre, [`TILE_ROWS`] rows at a time from the top, `tile(masks,
/// rows_done)` after each tile (the rows below `rows_done` are still 0). Each cell is decided
/// exactly as in one pass (a block never straddles two tiles), so the result does not depend on
/// the tiles.
pub(crate) fn fill_tiled(
    bounds: [f64; 4],
    dims: [usize; 2],
    test: &(dyn Fn([f64; 2]) -> u8 + Sync),
    how: Fill<'_>,
    tile: &mut dyn FnMut(&[u8], usize),
) -> Vec<u8> {
    let [w, h] = dims;
    let mut masks = vec![0u8; w * h];
    for j0 in (0..h).step_by(TILE_ROWS) {
        let j1 = (j0 + TILE_ROWS).min(h);
        fill_into(bounds, dims, test, how, j0, &mut masks[j0 * w..j1 * w]);
        tile(&masks, j1);
    }
    masks
}

/// The masks of rows `rows` of [`fill_tiled`]'s raster (the first a multiple of the block side),
/// decided as it decides them.
pub(crate) fn fill_rows(
    bounds: [f64; 4],
    dims: [usize; 2],
    test: &(dyn Fn([f64; 2]) -> u8 + Sync),
    how: Fill<'_>,
    rows: std::ops::Range<usize>,
) -> Vec<u8> {
    let mut masks = vec![0u8; dims[0] * rows.len()];
    fill_into(bounds, dims, test, how, rows.start, &mut masks);
    masks
}

/// Fills `rows` (whole rows from `j0`, a multiple of the block side) of the raster.
fn fill_into(
    bounds: [f64; 4],
    dims: [usize; 2],
    test: &(dyn Fn([f64; 2]) -> u8 + Sync),
    how: Fill<'_>,
    j0: usize,
    rows: &mut [u8],
) {
    match how {
        Fill::Cells => rows
            .par_chunks_mut(dims[0])
            .enumerate()
            .for_each(|(dj, row)| {
                for (i, m) in row.iter_mut().enumerate() {
                    *m = test(centre(bounds, dims, i, j0 + dj));
                }
            }),
        Fill::Blocks(uniform) => fill_blocks_rows(bounds, dims, test, uniform, j0, rows),
    }
}

/// The cells whose mask differs from a 4-neighbour's, each supersampled 4 x 4 with `test`.
pub(crate) fn edges(
    masks: &[u8],
    bounds: [f64; 4],
    dims: [usize; 2],
    test: &(dyn Fn([f64; 2]) -> u8 + Sync),
) -> Vec<EdgeCell> {
    let [w, h] = dims;
    let cut = |k: usize| {
        let (i, j) = (k % w, k / w);
        let m = masks[k];
        (i > 0 && masks[k - 1] != m)
            || (i + 1 < w && masks[k + 1] != m)
            || (j > 0 && masks[k - w] != m)
            || (j + 1 < h && masks[k + w] != m)
    };
    (0..w * h)
        .into_par_iter()
        .filter(|&k| cut(k))
        .map(|k| {
            let (i, j) = (k % w, k / w);
            let mut sub = [0u8; 16];
            for (s, m) in sub.iter_mut().enumerate() {
                let (fu, fv) = ((s % 4) as f64 * 0.25 + 0.125, (s / 4) as f64 * 0.25 + 0.125);
                *m = test(sub_point(bounds, dims, i, j, fu, fv));
            }
            EdgeCell {
                index: k as u32,
                sub,
            }
        })
        .collect()
}

/// Values at every cell centre (NaN where `f` gives none), in parallel by rows.
pub(crate) fn values(
    bounds: [f64; 4],
    dims: [usize; 2],
    f: &(dyn Fn([f64; 2]) -> Option<f32> + Sync),
) -> Vec<f32> {
    let w = dims[0];
    let mut out = vec![f32::NAN; w * dims[1]];
    out.par_chunks_mut(w).enumerate().for_each(|(j, row)| {
        for (i, v) in row.iter_mut().enumerate() {
            *v = f(centre(bounds, dims, i, j)).unwrap_or(f32::NAN);
        }
    });
    out
}

/// Side of the blocks of [`fill_blocks`] (cells).
const BLOCK: usize = 8;

/// Masks at every cell centre, block by block: a block of 8 x 8 cells for which `uniform(centre,
/// radius)` says no edge comes within `radius` (m) of its centre takes the mask of its centre
/// cell; the others are tested cell by cell. With `uniform = None`, a block is taken as uniform
/// when its centre cell and its four corner cells agree (a heuristic, for tests that are not
/// exact anyway).
pub(crate) fn fill_blocks(
    bounds: [f64; 4],
    dims: [usize; 2],
    test: &(dyn Fn([f64; 2]) -> u8 + Sync),
    uniform: Option<&(dyn Fn([f64; 2], f64) -> bool + Sync)>,
) -> Vec<u8> {
    fill_tiled(bounds, dims, test, Fill::Blocks(uniform), &mut |_, _| {})
}

/// [`fill_blocks`] on the rows from `j0` (a multiple of the block side) that `rows` holds.
fn fill_blocks_rows(
    bounds: [f64; 4],
    dims: [usize; 2],
    test: &(dyn Fn([f64; 2]) -> u8 + Sync),
    uniform: Option<&(dyn Fn([f64; 2], f64) -> bool + Sync)>,
    j0: usize,
    rows: &mut [u8],
) {
    let w = dims[0];
    let h = j0 + rows.len() / w;
    let (bw, bh) = (w.div_ceil(BLOCK), (h - j0).div_ceil(BLOCK));
    let cell = [
        (bounds[1] - bounds[0]) / w as f64,
        (bounds[3] - bounds[2]) / dims[1] as f64,
    ];
    let blocks: Vec<(usize, Vec<u8>)> = (0..bw * bh)
        .into_par_iter()
        .map(|b| {
            let (i0, j0) = ((b % bw) * BLOCK, j0 + (b / bw) * BLOCK);
            let (i1, j1) = ((i0 + BLOCK).min(w), (j0 + BLOCK).min(h));
            let (ic, jc) = ((i0 + i1) / 2, (j0 + j1) / 2);
            let c = centre(bounds, dims, ic, jc);
            let m = test(c);
            let same = match uniform {
                Some(u) => {
                    let reach = [
                        (ic - i0).max(i1 - ic) as f64 * cell[0],
                        (jc - j0).max(j1 - jc) as f64 * cell[1],
                    ];
                    u(c, reach[0].hypot(reach[1]))
                }
                None => [(i0, j0), (i1 - 1, j0), (i0, j1 - 1), (i1 - 1, j1 - 1)]
                    .iter()
                    .all(|&(i, j)| test(centre(bounds, dims, i, j)) == m),
            };
            let cells = (j0..j1)
                .flat_map(|j| (i0..i1).map(move |i| (i, j)))
                .map(|(i, j)| {
                    if same {
                        m
                    } else {
                        test(centre(bounds, dims, i, j))
                    }
                })
                .collect();
            (b, cells)
        })
        .collect();
    for (b, cells) in blocks {
        let (i0, dj0) = ((b % bw) * BLOCK, (b / bw) * BLOCK);
        let iw = (i0 + BLOCK).min(w) - i0;
        for (k, m) in cells.into_iter().enumerate() {
            rows[(dj0 + k / iw) * w + i0 + k % iw] = m;
        }
    }
}
