//! A cell's obstacles as a workspace map's view shows them: the section of each by the view's
//! plane (the arm plane, the side view's half-plane y = 0), its outline seen from above (the
//! top view), or for a side view of every azimuth its shape swept about the base z axis, in
//! view coordinates clipped to the map's bounds.

use crate::collision::{CellScene, Obstacle, ObstacleFrame, ObstacleShape};
use crate::kinematics::Pose;
use crate::workspace::MapView;
use nalgebra::{Point3, Vector3};
use std::f64::consts::TAU;

/// How an outline was made from its obstacle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum OutlineKind {
    /// The obstacle cut by the view's plane.
    Section,
    /// The obstacle seen from above, along the base z axis.
    FromAbove,
    /// The side view's (r, z) of every point of the obstacle: what a side view of every
    /// azimuth (a sampled map's) shows.
    Swept,
}

impl OutlineKind {
    /// "its section", "seen from above", "swept about the base z axis".
    pub fn words(self) -> &'static str {
        match self {
            OutlineKind::Section => "its section",
            OutlineKind::FromAbove => "seen from above",
            OutlineKind::Swept => "swept about the base z axis",
        }
    }
}

/// One obstacle in a map's view.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ObstacleOutline {
    /// The obstacle's name.
    pub name: String,
    /// Section, seen from above, or swept.
    pub kind: OutlineKind,
    /// Its boundary (view coordinates, m; it closes itself); empty where the obstacle misses
    /// the view (or fills all of it: see `whole_view`). Convex and clipped to the map's bounds
    /// but for a swept outline, which may be neither.
    pub ring: Vec<[f64; 2]>,
    /// The region inside `ring` as convex pieces clipped to the map's bounds (one for a
    /// section or an outline from above, strips for a swept one), to fill.
    pub pieces: Vec<Vec<[f64; 2]>>,
    /// The obstacle covers the whole view (a floor seen from above): drawn as nothing but
    /// named.
    pub whole_view: bool,
    /// Where its name goes (view coordinates, m): the pieces' vertex mean.
    pub label_at: [f64; 2],
}

/// The view's plane in the base frame: view coordinates `(a, b)` are `x . u` and `x . v`; a
/// section keeps the points with `x . n = c`, a projection looks along `n`.
struct ViewCut {
    u: Vector3<f64>,
    v: Vector3<f64>,
    n: Vector3<f64>,
    c: f64,
    section: bool,
}

impl ViewCut {
    fn of(view: MapView, plane_z: f64) -> ViewCut {
        let (x, y, z) = (Vector3::x(), Vector3::y(), Vector3::z());
        match view {
            MapView::Plane => ViewCut {
                u: x,
                v: y,
                n: z,
                c: plane_z,
                section: true,
            },
            MapView::Top => ViewCut {
                u: x,
                v: y,
                n: z,
                c: 0.0,
                section: false,
            },
            MapView::Side => ViewCut {
                u: x,
                v: z,
                n: y,
                c: 0.0,
                section: true,
            },
        }
    }

    fn to_view(&self, p: &Vector3<f64>) -> [f64; 2] {
        [p.dot(&self.u), p.dot(&self.v)]
    }
}

/// Every world-frame obstacle of `cell` in a map's view over `bounds` (`[x0, x1, y0, y1]`, m),
/// for a robot at `world_from_base`: the section by the arm plane (base z = `plane_z`) or by the
/// side view's half-plane (base y = 0), or the outline seen from above; with `swept_side`, a
/// side view shows each obstacle swept about the base z axis instead (the view of a map whose
/// side view holds every azimuth). Obstacles that move with a link are left out (a map has no
/// configuration to place them at).
///
/// ```
/// use armlab::collision::{CellScene, Obstacle};
/// use armlab::kinematics::Pose;
/// use armlab::workspace::MapView;
/// use armlab::workspace::cell::{ObstacleOutline, obstacle_outlines};
///
/// let cell = CellScene {
///     obstacles: vec![
///         Obstacle::floor("floor", 0.0),
///         Obstacle::cuboid("table", [1.2, 0.8, 0.05], [0.6, 0.0, 0.375]),
///     ],
///     ..CellScene::default()
/// };
/// let span = |o: &ObstacleOutline, k: usize| {
///     o.ring.iter().map(|p| p[k]).fold([f64::MAX, f64::MIN], |a, v| [a[0].min(v), a[1].max(v)])
/// };
/// let bounds = [-0.1, 1.1, -1.1, 1.1];
/// let side = obstacle_outlines(&cell, &Pose::identity(), MapView::Side, 0.0, bounds, false);
/// // The floor's section is the band below z = 0, the table's a 1.2 x 0.05 m rectangle.
/// assert_eq!(span(&side[0], 1), [-1.1, 0.0]);
/// let [z0, z1] = span(&side[1], 1);
/// assert!((z0 - 0.35).abs() < 1e-12 && (z1 - 0.4).abs() < 1e-12);
/// // Swept about the z axis, the table reaches out to the corner of its top, 1.2^2 + 0.4^2.
/// let swept = obstacle_outlines(&cell, &Pose::identity(), MapView::Side, 0.0, [-0.1, 2.0, -1.1, 1.1], true);
/// let [r0, r1] = span(&swept[1], 0);
/// assert!(r0.abs() < 1e-12 && (r1 - 1.6f64.sqrt()).abs() < 1e-9);
/// let top = obstacle_outlines(&cell, &Pose::identity(), MapView::Top, 0.0, [-1.1, 1.1, -1.1, 1.1], false);
/// assert!(top[0].whole_view && top[0].ring.is_empty()); // the floor, from above
/// ```
pub fn obstacle_outlines(
    cell: &CellScene,
    world_from_base: &Pose,
    view: MapView,
    plane_z: f64,
    bounds: [f64; 4],
    swept_side: bool,
) -> Vec<ObstacleOutline> {
    let cut = ViewCut::of(view, plane_z);
    let base_from_world = world_from_base.inverse();
    let swept = swept_side && view == MapView::Side;
    cell.obstacles
        .iter()
        .filter(|o| o.frame == ObstacleFrame::World)
        .map(|o| {
            let base_from_obstacle = base_from_world * o.frame_from_obstacle();
            if swept {
                swept_outline(o, &base_from_obstacle, bounds)
            } else {
                outline(o, &base_from_obstacle, &cut, bounds)
            }
        })
        .collect()
}

/// One obstacle's outline; `base_from_obstacle` places it.
fn outline(
    o: &Obstacle,
    base_from_obstacle: &Pose,
    cut: &ViewCut,
    bounds: [f64; 4],
) -> ObstacleOutline {
    let kind = if cut.section {
        OutlineKind::Section
    } else {
        OutlineKind::FromAbove
    };
    let (polygon, whole_view) = match &o.shape {
        ObstacleShape::Plane => half_space(base_from_obstacle, cut, bounds),
        ObstacleShape::Sphere { radius } => {
            let centre = base_from_obstacle.translation.vector;
            let d = centre.dot(&cut.n) - cut.c;
            let r = if cut.section {
                (radius * radius - d * d).max(0.0).sqrt()
            } else {
                *radius
            };
            let poly = if r > 0.0 {
                circle(cut.to_view(&centre), r)
            } else {
                Vec::new()
            };
            (clip_to(&poly, bounds), false)
        }
        shape => {
            let (points, edges) = convex_points(shape);
            let placed: Vec<Vector3<f64>> = points
                .iter()
                .map(|p| (base_from_obstacle * Point3::from(*p)).coords)
                .collect();
            let flat: Vec<[f64; 2]> = if cut.section {
                section_points(&placed, &edges, cut)
            } else {
                placed.iter().map(|p| cut.to_view(p)).collect()
            };
            (clip_to(&hull(flat), bounds), false)
        }
    };
    let pieces = if polygon.is_empty() {
        Vec::new()
    } else {
        vec![polygon.clone()]
    };
    finish(o, kind, polygon, pieces, whole_view)
}

/// An outline from its ring and pieces, labelled at the pieces' vertex mean.
fn finish(
    o: &Obstacle,
    kind: OutlineKind,
    ring: Vec<[f64; 2]>,
    pieces: Vec<Vec<[f64; 2]>>,
    whole_view: bool,
) -> ObstacleOutline {
    let all: Vec<&[f64; 2]> = pieces.iter().flatten().collect();
    let label_at = if all.is_empty() {
        [f64::NAN; 2]
    } else {
        let s = all
            .iter()
            .fold([0.0, 0.0], |a, p| [a[0] + p[0], a[1] + p[1]]);
        [s[0] / all.len() as f64, s[1] / all.len() as f64]
    };
    ObstacleOutline {
        name: o.name.clone(),
        kind,
        ring,
        pieces,
        whole_view,
        label_at,
    }
}

/// Heights a swept outline is sliced at.
const SWEEP_LEVELS: usize = 48;

/// The obstacle swept about the base z axis, in the side view's (r, z): at each of
/// [`SWEEP_LEVELS`] heights, the radii from its horizontal slice's nearest point to the axis to
/// its farthest; a half-space's swept region is a half-plane of (r, z).
fn swept_outline(o: &Obstacle, base_from_obstacle: &Pose, bounds: [f64; 4]) -> ObstacleOutline {
    let kind = OutlineKind::Swept;
    // Per level: (z, r_min, r_max).
    let levels: Vec<(f64, f64, f64)> = match &o.shape {
        ObstacleShape::Plane => {
            let n = base_from_obstacle.rotation * Vector3::z();
            let d = n.dot(&base_from_obstacle.translation.vector);
            // Some azimuth puts (r, z) inside when -r |n_xy| + n_z z <= d.
            let piece = clip(&rectangle(bounds), [-n.xy().norm(), n.z], d);
            let piece = clip_to(&piece, bounds);
            let pieces = if piece.is_empty() {
                Vec::new()
            } else {
                vec![piece.clone()]
            };
            return finish(o, kind, piece, pieces, false);
        }
        ObstacleShape::Sphere { radius } => {
            let c = base_from_obstacle.translation.vector;
            let d = c.xy().norm();
            (0..=SWEEP_LEVELS)
                .map(|i| {
                    let z = c.z - radius + 2.0 * radius * i as f64 / SWEEP_LEVELS as f64;
                    let rho = (radius * radius - (z - c.z).powi(2)).max(0.0).sqrt();
                    (z, (d - rho).max(0.0), d + rho)
                })
                .collect()
        }
        shape => {
            let (points, edges) = convex_points(shape);
            let placed: Vec<Vector3<f64>> = points
                .iter()
                .map(|p| (base_from_obstacle * Point3::from(*p)).coords)
                .collect();
            let (lo, hi) = placed
                .iter()
                .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.z), b.max(p.z)));
            (0..=SWEEP_LEVELS)
                .filter_map(|i| {
                    let z = lo + (hi - lo) * i as f64 / SWEEP_LEVELS as f64;
                    let level = ViewCut::of(MapView::Plane, z);
                    let slice = section_points(&placed, &edges, &level);
                    let far = slice
                        .iter()
                        .map(|p| p[0].hypot(p[1]))
                        .fold(f64::MIN, f64::max);
                    (!slice.is_empty())
                        .then(|| (z, distance_to_axis(&hull(slice.clone()), &slice), far))
                })
                .collect()
        }
    };
    let mut pieces = Vec::new();
    for w in levels.windows(2) {
        let ((z0, a0, b0), (z1, a1, b1)) = (w[0], w[1]);
        let piece = clip_to(&[[a0, z0], [b0, z0], [b1, z1], [a1, z1]], bounds);
        if !piece.is_empty() {
            pieces.push(piece);
        }
    }
    let ring: Vec<[f64; 2]> = levels
        .iter()
        .map(|&(z, _, b)| [b, z])
        .chain(levels.iter().rev().map(|&(z, a, _)| [a, z]))
        .collect();
    finish(o, kind, ring, pieces, false)
}

/// The distance (m) from the origin of the plane to a convex polygon (counter-clockwise; 0
/// inside); for fewer than three vertices, to the nearest of `points`.
fn distance_to_axis(poly: &[[f64; 2]], points: &[[f64; 2]]) -> f64 {
    if poly.len() < 3 {
        return points
            .iter()
            .map(|p| p[0].hypot(p[1]))
            .fold(f64::MAX, f64::min);
    }
    let edge = |a: [f64; 2], b: [f64; 2]| {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let t = (-(a[0] * dx + a[1] * dy) / (dx * dx + dy * dy).max(1e-300)).clamp(0.0, 1.0);
        ((a[0] + t * dx).hypot(a[1] + t * dy), a[0] * dy - a[1] * dx)
    };
    let mut inside = true;
    let mut best = f64::MAX;
    for k in 0..poly.len() {
        let (d, cross) = edge(poly[k], poly[(k + 1) % poly.len()]);
        // The origin is left of every edge of a counter-clockwise polygon that holds it.
        inside &= cross >= 0.0;
        best = best.min(d);
    }
    if inside { 0.0 } else { best }
}

/// A half-space obstacle (below its frame's x-y plane) in the view: a half-plane of the view
/// clipped to the bounds, everything, or nothing.
fn half_space(base_from_obstacle: &Pose, cut: &ViewCut, bounds: [f64; 4]) -> (Vec<[f64; 2]>, bool) {
    let normal = base_from_obstacle.rotation * Vector3::z();
    let origin = base_from_obstacle.translation.vector;
    let (a, b) = (normal.dot(&cut.u), normal.dot(&cut.v));
    if a.hypot(b) < 1e-12 {
        // The view's plane is parallel to the obstacle's: inside it or not at all. From above,
        // a tilted or level half-space covers the whole view.
        let inside = !cut.section || normal.dot(&(cut.n * cut.c - origin)) <= 0.0;
        return (Vec::new(), inside);
    }
    if !cut.section && normal.dot(&cut.n).abs() > 1e-12 {
        return (Vec::new(), true);
    }
    // Points a u + b v (+ c n) with normal . (x - origin) <= 0.
    let rhs = normal.dot(&origin)
        - if cut.section {
            cut.c * normal.dot(&cut.n)
        } else {
            0.0
        };
    let rect = rectangle(bounds);
    (clip(&rect, [a, b], rhs), false)
}

/// A convex obstacle's points (its frame, m) and the edges between them whose crossings with a
/// plane span its section: a box's corners and edges, a cylinder's rims, a mesh's hull.
fn convex_points(shape: &ObstacleShape) -> (Vec<Vector3<f64>>, Vec<[usize; 2]>) {
    match shape {
        ObstacleShape::Box { size } => {
            let h = Vector3::from(*size) * 0.5;
            let points: Vec<Vector3<f64>> = (0..8)
                .map(|k| {
                    let s = |bit: usize| if k >> bit & 1 == 1 { 1.0 } else { -1.0 };
                    Vector3::new(s(0) * h.x, s(1) * h.y, s(2) * h.z)
                })
                .collect();
            let edges = (0..8usize)
                .flat_map(|a| (0..3).map(move |bit| [a, a ^ (1 << bit)]))
                .filter(|[a, b]| a < b)
                .collect();
            (points, edges)
        }
        ObstacleShape::Cylinder { radius, length } => {
            let n = 64;
            let mut points = Vec::with_capacity(2 * n);
            for z in [-0.5 * length, 0.5 * length] {
                for k in 0..n {
                    let t = TAU * k as f64 / n as f64;
                    points.push(Vector3::new(radius * t.cos(), radius * t.sin(), z));
                }
            }
            let mut edges = Vec::with_capacity(3 * n);
            for k in 0..n {
                edges.push([k, (k + 1) % n]);
                edges.push([n + k, n + (k + 1) % n]);
                edges.push([k, n + k]);
            }
            (points, edges)
        }
        ObstacleShape::Mesh { mesh, .. } => mesh_hull(mesh),
        ObstacleShape::Sphere { .. } | ObstacleShape::Plane => (Vec::new(), Vec::new()),
    }
}

/// A mesh's convex hull (what the collision checks use) as points and edges; where no hull can
/// be made, its vertices with every pair as an edge (a few only: a degenerate mesh).
fn mesh_hull(mesh: &crate::mesh::TriMesh) -> (Vec<Vector3<f64>>, Vec<[usize; 2]>) {
    use parry3d_f64::math::Vec3;
    let pts: Vec<Vec3> = mesh
        .positions
        .iter()
        .map(|p| Vec3::new(p[0].into(), p[1].into(), p[2].into()))
        .collect();
    match parry3d_f64::transformation::try_convex_hull(&pts) {
        Ok((vertices, triangles)) => {
            let points = vertices
                .iter()
                .map(|v| Vector3::new(v.x, v.y, v.z))
                .collect();
            let mut edges: Vec<[usize; 2]> = triangles
                .iter()
                .flat_map(|t| {
                    let t = t.map(|i| i as usize);
                    [[t[0], t[1]], [t[1], t[2]], [t[2], t[0]]]
                })
                .map(|[a, b]| [a.min(b), a.max(b)])
                .collect();
            edges.sort_unstable();
            edges.dedup();
            (points, edges)
        }
        Err(_) => {
            let points: Vec<Vector3<f64>> = pts
                .iter()
                .take(64)
                .map(|v| Vector3::new(v.x, v.y, v.z))
                .collect();
            let n = points.len();
            let edges = (0..n)
                .flat_map(|a| (a + 1..n).map(move |b| [a, b]))
                .collect();
            (points, edges)
        }
    }
}

/// Where the edges cross the view's plane, in view coordinates (the section's vertices).
fn section_points(points: &[Vector3<f64>], edges: &[[usize; 2]], cut: &ViewCut) -> Vec<[f64; 2]> {
    let side = |p: &Vector3<f64>| p.dot(&cut.n) - cut.c;
    let mut out = Vec::new();
    for &[a, b] in edges {
        let (pa, pb) = (&points[a], &points[b]);
        let (sa, sb) = (side(pa), side(pb));
        if sa == 0.0 {
            out.push(cut.to_view(pa));
        }
        if sb == 0.0 {
            out.push(cut.to_view(pb));
        }
        if sa * sb < 0.0 {
            let t = sa / (sa - sb);
            out.push(cut.to_view(&(pa + (pb - pa) * t)));
        }
    }
    out
}

/// The convex hull of points, counter-clockwise (Andrew's monotone chain); fewer than three
/// distinct points give no polygon.
fn hull(mut pts: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    pts.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    pts.dedup();
    if pts.len() < 3 {
        return Vec::new();
    }
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut out: Vec<[f64; 2]> = Vec::with_capacity(2 * pts.len());
    for pass in 0..2 {
        let start = out.len();
        let iter: Box<dyn Iterator<Item = &[f64; 2]>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while out.len() >= start + 2 && cross(out[out.len() - 2], out[out.len() - 1], p) <= 0.0
            {
                out.pop();
            }
            out.push(p);
        }
        out.pop();
    }
    if out.len() < 3 { Vec::new() } else { out }
}

/// A circle as a polygon of 96 vertices.
fn circle(c: [f64; 2], r: f64) -> Vec<[f64; 2]> {
    (0..96)
        .map(|k| {
            let t = TAU * k as f64 / 96.0;
            [c[0] + r * t.cos(), c[1] + r * t.sin()]
        })
        .collect()
}

/// The bounds `[x0, x1, y0, y1]` as a counter-clockwise rectangle.
fn rectangle([x0, x1, y0, y1]: [f64; 4]) -> Vec<[f64; 2]> {
    vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
}

/// A convex polygon clipped to the bounds.
fn clip_to(poly: &[[f64; 2]], [x0, x1, y0, y1]: [f64; 4]) -> Vec<[f64; 2]> {
    let mut p = poly.to_vec();
    for (n, d) in [
        ([-1.0, 0.0], -x0),
        ([1.0, 0.0], x1),
        ([0.0, -1.0], -y0),
        ([0.0, 1.0], y1),
    ] {
        p = clip(&p, n, d);
    }
    if p.len() < 3 { Vec::new() } else { p }
}

/// A convex polygon clipped to the half-plane `n . p <= d` (Sutherland-Hodgman).
fn clip(poly: &[[f64; 2]], n: [f64; 2], d: f64) -> Vec<[f64; 2]> {
    let s = |p: [f64; 2]| n[0] * p[0] + n[1] * p[1] - d;
    let mut out = Vec::with_capacity(poly.len() + 1);
    for (k, &a) in poly.iter().enumerate() {
        let b = poly[(k + 1) % poly.len()];
        let (sa, sb) = (s(a), s(b));
        if sa <= 0.0 {
            out.push(a);
        }
        if sa * sb < 0.0 {
            let t = sa / (sa - sb);
            out.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
        }
    }
    out
}
