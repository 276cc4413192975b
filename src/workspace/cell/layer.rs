//! A workspace map cut by a cell's obstacles, decided block by block of its cells.

use super::PointCheck;
use super::outline::ObstacleOutline;
use crate::workspace::WorkspaceMap;
use rayon::prelude::*;

/// Most collision cells along a map's longer side: each is a square block of the map's own
/// cells, checked at one point per posture, so that a figure's collisions take about a second.
pub const COLLISION_CELLS: usize = 160;

/// What the obstacles take from a map (see [`cut_map`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CollisionLayer {
    /// Per map cell (row-major from the top), the posture classes that reach it within the
    /// limits only through a collision at its collision cell (taken out of the map's masks).
    pub blocked: Vec<u8>,
    /// Map cells per side of a collision cell.
    pub block: usize,
    /// Collision cells across and down.
    pub cells: [usize; 2],
    /// Size of a collision cell (view units, m): across, down.
    pub cell_size: [f64; 2],
    /// How the collisions were decided, in words (what is checked, where, at what
    /// resolution).
    pub method: String,
    /// The obstacles in the map's view.
    pub obstacles: Vec<ObstacleOutline>,
}

/// One collision cell's verdict: bit k is posture class k.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct BlockVerdict {
    /// Classes collision-free at the cell's point.
    pub free: u8,
    /// Classes that reach the cell's point only through a collision.
    pub colliding: u8,
}

/// Cuts `map` by a cell's obstacles, decided per collision cell: square blocks of `block` x
/// `block` map cells. In each, every posture class the map shows there is checked with `test`
/// (view point (m), classes wanted, a hint the test may keep between calls on one row) at the
/// block's middle cell, or where that cell does not have the class, at the first cell of the
/// block that has it. A class stays where it is free there and is taken out elsewhere (into
/// [`CollisionLayer::blocked`] where it collides; silently where `test` does not reach the
/// point at all). The exact fills are dropped (no longer the regions); the curves stay (the
/// boundaries without the obstacles).
pub fn cut_map(
    map: &mut WorkspaceMap,
    block: usize,
    test: &(dyn Fn([f64; 2], u8, &mut usize) -> PointCheck + Sync),
) -> Vec<BlockVerdict> {
    let (w, h) = (map.width, map.height);
    let block = block.max(1);
    let (bw, bh) = (w.div_ceil(block), h.div_ceil(block));
    let present = |k: usize| present(map, k);
    let verdicts: Vec<BlockVerdict> = (0..bh)
        .into_par_iter()
        .flat_map_iter(|bj| {
            let mut hint = 0usize;
            let row: Vec<BlockVerdict> = (0..bw)
                .map(|bi| block_verdict(map, [bi, bj], block, test, &mut hint))
                .collect();
            row
        })
        .collect();
    let block_of = |k: usize| verdicts[(k / w / block) * bw + (k % w) / block];
    let mut blocked = vec![0u8; w * h];
    for (k, b) in blocked.iter_mut().enumerate() {
        let v = block_of(k);
        *b = present(k) & v.colliding & !v.free;
    }
    for (k, m) in map.masks.iter_mut().enumerate() {
        *m &= block_of(k).free;
    }
    for e in &mut map.edges {
        let free = block_of(e.index as usize).free;
        for s in &mut e.sub {
            *s &= free;
        }
    }
    map.fills.clear();
    map.collision = Some(Box::new(CollisionLayer {
        blocked,
        block,
        cells: [bw, bh],
        cell_size: [
            (map.bounds[1] - map.bounds[0]) / w as f64 * block as f64,
            (map.bounds[3] - map.bounds[2]) / h as f64 * block as f64,
        ],
        method: String::new(),
        obstacles: Vec::new(),
    }));
    verdicts
}

/// The classes of map cell `k`: its centre's, and its sub-samples' where it is an edge cell.
fn present(map: &WorkspaceMap, k: usize) -> u8 {
    let sub = match map.edges.binary_search_by_key(&(k as u32), |e| e.index) {
        Ok(e) => map.edges[e].sub.iter().fold(0, |a, b| a | b),
        Err(_) => 0,
    };
    map.masks[k] | sub
}

/// The verdict of collision cell `[bi, bj]` (see [`cut_map`]).
fn block_verdict(
    map: &WorkspaceMap,
    [bi, bj]: [usize; 2],
    block: usize,
    test: &(dyn Fn([f64; 2], u8, &mut usize) -> PointCheck + Sync),
    hint: &mut usize,
) -> BlockVerdict {
    let (w, h) = (map.width, map.height);
    let (i0, j0) = (bi * block, bj * block);
    let (i1, j1) = ((i0 + block).min(w), (j0 + block).min(h));
    let cells = (j0..j1).flat_map(|j| (i0..i1).map(move |i| j * w + i));
    let middle = ((j0 + j1) / 2) * w + (i0 + i1) / 2;
    let mut verdict = BlockVerdict::default();
    let mut left = cells.clone().fold(0u8, |a, k| a | present(map, k));
    while left != 0 {
        // The middle cell for the classes it has, else the first cell whose centre has the
        // lowest class left (else one of its sub-samples).
        let c = left & left.wrapping_neg();
        let at = if map.masks[middle] & c != 0 {
            middle
        } else {
            cells
                .clone()
                .find(|&k| map.masks[k] & c != 0)
                .or_else(|| cells.clone().find(|&k| present(map, k) & c != 0))
                .unwrap_or(middle)
        };
        let want = left & (map.masks[at] | c);
        let got = test(map.centre(at % w, at / w), want, hint);
        verdict.free |= got.free & want;
        verdict.colliding |= got.colliding() & want;
        left &= !want;
    }
    verdict
}
