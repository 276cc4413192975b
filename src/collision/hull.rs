//! What the distance queries need of a convex hull beyond parry's `ConvexPolyhedron`: its
//! vertices' neighbours, for a support function that climbs from its last answer along the
//! hull's edges instead of scanning every vertex (GJK asks it a few dozen times per distance,
//! in directions that change little), and its box in its own frame (a placed box without
//! transforming every vertex). Measured on the UR5's mesh hulls: the vertex scans and the
//! per-placement boxes were 73 % of a full collision report.
//!
//! Climbing is exact on a convex polytope: a vertex whose neighbours are all no further along
//! a direction is the furthest of all (a linear function's local maximum on a polytope's
//! vertex graph is global, as the simplex method relies on).

use parry3d_f64::bounding_volume::Aabb;
use parry3d_f64::math::{Pose as PPose, Vector};
use parry3d_f64::shape::{ConvexPolyhedron, Shape, SupportMap};
use std::cell::Cell;
use std::collections::HashMap;
use std::sync::Arc;

/// A hull's vertex graph and its own box.
#[derive(Debug)]
pub(super) struct HullData {
    /// The box around the vertices, in the hull's frame.
    pub(super) local_aabb: Aabb,
    /// Vertex `v`'s neighbours are `next[start[v]..start[v + 1]]`.
    start: Vec<u32>,
    next: Vec<u32>,
    /// The vertices' address and count, to tell this hull from another one later at the
    /// same address.
    points: (usize, usize),
}

impl HullData {
    /// The graph of `hull`'s edges.
    fn of(hull: &ConvexPolyhedron) -> Self {
        let n = hull.points().len();
        let mut adjacent = vec![Vec::new(); n];
        for e in hull.edges() {
            let [a, b] = e.vertices;
            adjacent[a as usize].push(b);
            adjacent[b as usize].push(a);
        }
        let mut start = Vec::with_capacity(n + 1);
        let mut next = Vec::new();
        for list in &mut adjacent {
            list.sort_unstable();
            list.dedup();
            start.push(next.len() as u32);
            next.extend_from_slice(list);
        }
        start.push(next.len() as u32);
        Self {
            local_aabb: hull.local_aabb(),
            start,
            next,
            points: (hull.points().as_ptr() as usize, n),
        }
    }

    /// Whether this is `hull`'s data.
    fn describes(&self, hull: &ConvexPolyhedron) -> bool {
        self.points == (hull.points().as_ptr() as usize, hull.points().len())
    }
}

/// The hulls of a collision world, by the address of their shape.
#[derive(Debug, Clone, Default)]
pub(super) struct Hulls(HashMap<usize, Arc<HullData>>);

impl Hulls {
    /// Adds `shape` if it is a convex hull.
    pub(super) fn add(&mut self, shape: &dyn Shape) {
        if let Some(hull) = shape.as_convex_polyhedron() {
            self.0
                .entry(address(shape))
                .or_insert_with(|| Arc::new(HullData::of(hull)));
        }
    }

    /// `shape`'s data, if it is one of the hulls added.
    pub(super) fn get(&self, shape: &dyn Shape) -> Option<&HullData> {
        let hull = shape.as_convex_polyhedron()?;
        let data = self.0.get(&address(shape))?;
        data.describes(hull).then_some(data.as_ref())
    }
}

fn address(shape: &dyn Shape) -> usize {
    (shape as *const dyn Shape).cast::<u8>() as usize
}

/// A hull's support function by climbing, starting where the last call ended.
pub(super) struct Climb<'a> {
    points: &'a [Vector],
    data: &'a HullData,
    at: Cell<u32>,
}

impl<'a> Climb<'a> {
    /// Climbs on `hull` with its `data`.
    pub(super) fn new(hull: &'a ConvexPolyhedron, data: &'a HullData) -> Self {
        Self {
            points: hull.points(),
            data,
            at: Cell::new(0),
        }
    }
}

impl SupportMap for Climb<'_> {
    fn local_support_point(&self, dir: Vector) -> Vector {
        let (start, next) = (&self.data.start, &self.data.next);
        let mut v = self.at.get() as usize;
        let mut best = self.points[v].dot(dir);
        loop {
            let from = v;
            for &w in &next[start[from] as usize..start[from + 1] as usize] {
                let d = self.points[w as usize].dot(dir);
                if d > best {
                    best = d;
                    v = w as usize;
                }
            }
            if v == from {
                break;
            }
        }
        self.at.set(v as u32);
        self.points[v]
    }
}

/// A placed shape for [`support_distance`]: its pose, the shape, its hull data if it is a hull.
pub(super) type Side<'a> = (&'a PPose, &'a dyn Shape, Option<&'a HullData>);

/// One of parry's GJK queries on two support maps (`pos12`: the second's pose in the first's
/// frame).
trait Gjk {
    type Out;
    fn run<G1: ?Sized + SupportMap, G2: ?Sized + SupportMap>(
        pos12: &PPose,
        a: &G1,
        b: &G2,
    ) -> Self::Out;
}

/// The distance (m).
struct Distance;

impl Gjk for Distance {
    type Out = f64;
    fn run<G1: ?Sized + SupportMap, G2: ?Sized + SupportMap>(p: &PPose, a: &G1, b: &G2) -> f64 {
        parry3d_f64::query::details::distance_support_map_support_map(p, a, b)
    }
}

/// Whether they touch or overlap.
struct Intersects;

impl Gjk for Intersects {
    type Out = bool;
    fn run<G1: ?Sized + SupportMap, G2: ?Sized + SupportMap>(p: &PPose, a: &G1, b: &G2) -> bool {
        parry3d_f64::query::details::intersection_test_support_map_support_map(p, a, b)
    }
}

/// Query `Q` on two placed shapes, each hull climbed: `None` where neither is a hull with its
/// data, or one is not a support map (a half-space): parry's own query then.
fn climbed<Q: Gjk>((pose_a, a, ha): Side<'_>, (pose_b, b, hb): Side<'_>) -> Option<Q::Out> {
    fn climb<'a>(s: &'a dyn Shape, d: Option<&'a HullData>) -> Option<Climb<'a>> {
        Some(Climb::new(s.as_convex_polyhedron()?, d?))
    }
    let (ca, cb) = (climb(a, ha), climb(b, hb));
    let pos12 = pose_a.inv_mul(pose_b);
    Some(match (&ca, &cb) {
        (Some(ca), Some(cb)) => Q::run(&pos12, ca, cb),
        (Some(ca), None) => Q::run(&pos12, ca, b.as_support_map()?),
        (None, Some(cb)) => Q::run(&pos12, a.as_support_map()?, cb),
        (None, None) => return None,
    })
}

/// The distance between two placed shapes (m), each hull climbed; `None` as for [`climbed`].
pub(super) fn support_distance(a: Side<'_>, b: Side<'_>) -> Option<f64> {
    climbed::<Distance>(a, b)
}

/// Whether two placed shapes touch or overlap, each hull climbed; `None` as for [`climbed`].
pub(super) fn support_intersects(a: Side<'_>, b: Side<'_>) -> Option<bool> {
    climbed::<Intersects>(a, b)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A deterministic generator in [-1, 1).
    fn uniform(seed: &mut u64) -> f64 {
        *seed ^= *seed << 13;
        *seed ^= *seed >> 7;
        *seed ^= *seed << 17;
        (*seed >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    #[test]
    fn climbing_finds_the_furthest_vertex_of_every_direction() {
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        for cloud in 0..20 {
            // clouds of points, some long and thin as links are
            let stretch = Vector::new(1.0, 1.0 + cloud as f64, 0.2 + 0.1 * cloud as f64);
            let points: Vec<Vector> = (0..200)
                .map(|_| {
                    Vector::new(uniform(&mut seed), uniform(&mut seed), uniform(&mut seed))
                        * stretch
                })
                .collect();
            let hull = ConvexPolyhedron::from_convex_hull(&points).expect("a hull");
            let data = HullData::of(&hull);
            let climb = Climb::new(&hull, &data);
            for _ in 0..500 {
                let dir = Vector::new(uniform(&mut seed), uniform(&mut seed), uniform(&mut seed));
                // the brute force: every input point (the hull's vertices are among them)
                let best = points.iter().map(|p| p.dot(dir)).fold(f64::MIN, f64::max);
                let got = climb.local_support_point(dir).dot(dir);
                assert!(
                    (got - best).abs() <= 1e-12,
                    "cloud {cloud}: {got} vs {best}"
                );
            }
        }
    }
}
