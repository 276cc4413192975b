//! Boundary curves of a map whose regions come from an exact point test but that has no closed
//! form of its boundary (the closed-form side and top views): marching squares over the cell
//! centres, every crossing located by bisection with the exact test (so each vertex lies on the
//! exact boundary to 1e-9 of a cell), the segments chained into polylines.

use super::raster::centre;
use super::{CurveRole, MapCurve};
use std::collections::HashMap;

/// Bisection steps per crossing (a cell / 2^30).
const STEPS: usize = 30;

/// Key of the grid edge between cell centres `a` and `b` (cell indices, a < b).
type EdgeKey = (u32, u32);

/// Curves where `same(mask_a, mask_b)` fails between neighbouring cells: the reachable boundary
/// (`role` Boundary, `same` = both reached or both not) or the posture boundaries.
pub(super) fn contours(
    masks: &[u8],
    bounds: [f64; 4],
    dims: [usize; 2],
    test: &(dyn Fn([f64; 2]) -> u8 + Sync),
    role: CurveRole,
) -> Vec<MapCurve> {
    let [w, h] = dims;
    let differ = |a: u8, b: u8| match role {
        CurveRole::Boundary => (a != 0) != (b != 0),
        _ => a != 0 && b != 0 && a != b,
    };
    let point = |k: usize| centre(bounds, dims, k % w, k / w);
    // The crossing on the edge between cells a and b, by bisection.
    let crossing = |a: usize, b: usize| {
        let (pa, pb) = (point(a), point(b));
        let ma = masks[a];
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..STEPS {
            let t = 0.5 * (lo + hi);
            let m = test([pa[0] + t * (pb[0] - pa[0]), pa[1] + t * (pb[1] - pa[1])]);
            if differ(ma, m) {
                hi = t;
            } else {
                lo = t;
            }
        }
        let t = 0.5 * (lo + hi);
        [pa[0] + t * (pb[0] - pa[0]), pa[1] + t * (pb[1] - pa[1])]
    };
    let mut points: HashMap<EdgeKey, [f64; 2]> = HashMap::new();
    let mut links: HashMap<EdgeKey, Vec<EdgeKey>> = HashMap::new();
    for j in 0..h.saturating_sub(1) {
        for i in 0..w.saturating_sub(1) {
            let c = [
                j * w + i,
                j * w + i + 1,
                (j + 1) * w + i + 1,
                (j + 1) * w + i,
            ];
            let mut cut: Vec<EdgeKey> = Vec::new();
            for e in 0..4 {
                let (a, b) = (c[e], c[(e + 1) % 4]);
                if differ(masks[a], masks[b]) {
                    let key = (a.min(b) as u32, a.max(b) as u32);
                    points.entry(key).or_insert_with(|| crossing(a, b));
                    cut.push(key);
                }
            }
            // Two crossings: one segment; four (a saddle): pair them around the square.
            for pair in cut.chunks(2).filter(|p| p.len() == 2) {
                links.entry(pair[0]).or_default().push(pair[1]);
                links.entry(pair[1]).or_default().push(pair[0]);
            }
        }
    }
    chain(&points, &mut links, role)
}

/// Walks the segment graph into polylines (open chains from their ends first, then loops).
fn chain(
    points: &HashMap<EdgeKey, [f64; 2]>,
    links: &mut HashMap<EdgeKey, Vec<EdgeKey>>,
    role: CurveRole,
) -> Vec<MapCurve> {
    let mut starts: Vec<EdgeKey> = links
        .iter()
        .filter(|(_, v)| v.len() == 1)
        .map(|(k, _)| *k)
        .collect();
    let mut rest: Vec<EdgeKey> = links.keys().copied().collect();
    starts.sort_unstable();
    rest.sort_unstable();
    starts.extend(rest);
    let mut out = Vec::new();
    for s in starts {
        if links.get(&s).is_none_or(Vec::is_empty) {
            continue;
        }
        let mut line = vec![points[&s]];
        let mut at = s;
        while let Some(next) = links.get_mut(&at).and_then(Vec::pop) {
            if let Some(back) = links.get_mut(&next)
                && let Some(k) = back.iter().position(|x| *x == at)
            {
                back.swap_remove(k);
            }
            line.push(points[&next]);
            at = next;
        }
        if line.len() > 1 {
            out.push(MapCurve {
                points: line,
                role,
                arc: None,
            });
        }
    }
    out
}
