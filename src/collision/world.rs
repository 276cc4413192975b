//! A robot, its cell and its allowed-collision matrix: what one configuration hits.

use super::CollisionError;
use super::geometry::{Body, BodyKind, GeometryOptions, RobotGeometry, StickPart};
use super::hull::{HullData, Hulls, support_distance, support_intersects};
use super::matrix::AllowedCollisions;
use super::obstacles::{CellScene, ObstacleFrame};
use crate::kinematics::{KinematicsError, Pose, Robot};
use parry3d_f64::bounding_volume::{Aabb, BoundingVolume};
use parry3d_f64::math::{Pose as PPose, Vec3};
use parry3d_f64::query;
use parry3d_f64::shape::{HalfSpace, Shape};
use serde::Serialize;

/// Penetration below this depth is touching, not a collision (m): a link resting on a table
/// top, or round-off of the contact query.
pub const TOUCH_TOLERANCE_M: f64 = 1e-7;

/// Two bodies in contact at one configuration.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Contact {
    /// The first body (a link: the one nearer the base).
    pub a: String,
    /// The second body (a link or an obstacle).
    pub b: String,
    /// How deep they overlap (m, > 0): the penetration depth of the deepest of their parts.
    pub depth_m: f64,
    /// Where (world frame, m): midway between the two deepest points.
    pub at: [f64; 3],
}

/// The pair of bodies nearest each other (or, in collision, the deepest pair).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ClosestPair {
    /// The first body.
    pub a: String,
    /// The second body.
    pub b: String,
}

/// What one configuration hits. Serialized as `{"in_collision", "pairs": [{"a", "b",
/// "depth_m", "at"}], "clearance_m", "closest": {"a", "b"}}`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CollisionReport {
    /// Whether any checked pair overlaps.
    pub in_collision: bool,
    /// Every pair in contact, deepest first.
    pub pairs: Vec<Contact>,
    /// The smallest distance between any two bodies that are checked (m): 0 in collision;
    /// `None` when nothing is checked (no obstacles and every link pair allowed).
    pub clearance_m: Option<f64>,
    /// The pair that gives the clearance (in collision: the deepest pair).
    pub closest: Option<ClosestPair>,
}

impl CollisionReport {
    /// "forearm hits table, 12 mm; upper_arm hits wrist_3, 3 mm", or "free, 45 mm clear".
    pub fn summary(&self) -> String {
        if self.in_collision {
            let each: Vec<String> = self
                .pairs
                .iter()
                .map(|c| format!("{} hits {}, {}", c.a, c.b, millimetres(c.depth_m)))
                .collect();
            return each.join("; ");
        }
        match self.clearance_m {
            Some(c) => format!("free, {} clear", millimetres(c)),
            None => "free".into(),
        }
    }
}

/// A length in millimetres as reports say it: "12 mm", "0.4 mm".
fn millimetres(m: f64) -> String {
    let mm = m * 1000.0;
    if mm >= 9.95 {
        format!("{mm:.0} mm")
    } else {
        format!("{mm:.1} mm")
    }
}

/// A robot's links and a cell's obstacles as collision bodies, with the pairs to check.
#[derive(Debug, Clone)]
pub struct CollisionWorld {
    /// The robot's links.
    pub geometry: RobotGeometry,
    /// The obstacles, parts in each obstacle's frame.
    pub obstacles: Vec<Body>,
    /// For each obstacle: the link body it moves with (`None`: the world) and
    /// `frame_from_obstacle`.
    attached: Vec<(Option<usize>, PPose)>,
    /// The pairs of bodies checked (indices: links first, then obstacles).
    pairs: Vec<(usize, usize)>,
    /// The hulls among the parts, with their vertex graphs (the distance queries' support).
    hulls: Hulls,
    /// The pairs never checked, and why.
    pub allowed: AllowedCollisions,
    /// What building it said: the robot's collision warnings, meshes left out, obstacles
    /// touching the fixed base (not checked against it).
    pub warnings: Vec<String>,
}

/// One convex part placed in the world.
struct Placed<'a> {
    pose: PPose,
    shape: &'a dyn Shape,
    aabb: Aabb,
    /// The shape's hull data, if it is a hull of the world.
    hull: Option<&'a HullData>,
}

impl CollisionWorld {
    /// The robot in `scene`, meshes as hulls, with the robot's stored matrix (or, without one,
    /// a quick sampled one: adjacent pairs and pairs that always collide).
    pub fn new(robot: &Robot, scene: &CellScene) -> Result<CollisionWorld, CollisionError> {
        let geometry = RobotGeometry::of(robot, GeometryOptions::default());
        let allowed = AllowedCollisions::for_robot(robot, &geometry);
        CollisionWorld::with(robot, geometry, scene, GeometryOptions::default(), allowed)
    }

    /// The robot's `geometry` in `scene` with a given matrix.
    pub fn with(
        robot: &Robot,
        geometry: RobotGeometry,
        scene: &CellScene,
        options: GeometryOptions,
        allowed: AllowedCollisions,
    ) -> Result<CollisionWorld, CollisionError> {
        let mut warnings = robot.collision_warnings.clone();
        warnings.extend(geometry.warnings.iter().cloned());
        warnings.extend(scene.warnings.iter().cloned());
        let path = scene.path.clone().unwrap_or_else(|| "scene".into());
        let mut obstacles = Vec::new();
        let mut attached = Vec::new();
        for (k, o) in scene.obstacles.iter().enumerate() {
            let err = |problem: String| CollisionError::Obstacle {
                path: path.clone(),
                line: o.line,
                obstacle: o.name.clone(),
                problem,
            };
            let link = match &o.frame {
                ObstacleFrame::World => None,
                ObstacleFrame::Link(name) => Some(
                    geometry
                        .bodies
                        .iter()
                        .position(|b| &b.name == name)
                        .ok_or_else(|| {
                            let known: Vec<&str> =
                                geometry.bodies.iter().map(|b| b.name.as_str()).collect();
                            err(format!(
                                "frame \"{name}\" is neither \"world\" nor a link of {} ({})",
                                robot.name,
                                known.join(", ")
                            ))
                        })?,
                ),
            };
            if geometry.bodies.iter().any(|b| b.name == o.name) {
                return Err(err(format!(
                    "the name is a link of {}: obstacles need their own names",
                    robot.name
                )));
            }
            let parts = o.parts(options).map_err(err)?;
            obstacles.push(Body {
                name: o.name.clone(),
                kind: BodyKind::Obstacle(k),
                fixed: link.is_none_or(|b| geometry.bodies[b].fixed),
                parts,
                stick: false,
            });
            attached.push((link, o.parry_pose()));
        }
        let mut hulls = Hulls::default();
        for body in geometry.bodies.iter().chain(&obstacles) {
            for (_, shape) in &body.parts {
                hulls.add(shape.as_ref());
            }
        }
        let mut world = CollisionWorld {
            geometry,
            obstacles,
            attached,
            pairs: Vec::new(),
            hulls,
            allowed,
            warnings,
        };
        world.pairs = world.pairs_to_check(robot)?;
        Ok(world)
    }

    /// Every body: links first, then obstacles.
    pub fn bodies(&self) -> impl Iterator<Item = &Body> {
        self.geometry.bodies.iter().chain(&self.obstacles)
    }

    /// The body at index `i` of [`CollisionWorld::bodies`].
    fn body(&self, i: usize) -> &Body {
        let n = self.geometry.bodies.len();
        if i < n {
            &self.geometry.bodies[i]
        } else {
            &self.obstacles[i - n]
        }
    }

    /// The pairs checked at every configuration: link pairs the matrix does not allow, and
    /// link-obstacle pairs, except where both never move (a contact there is the mounting, said
    /// once as a warning when they touch).
    fn pairs_to_check(&mut self, robot: &Robot) -> Result<Vec<(usize, usize)>, KinematicsError> {
        let n = self.geometry.bodies.len();
        let total = n + self.obstacles.len();
        let has_parts = |w: &Self, i: usize| {
            let b = w.body(i);
            b.stick || !b.parts.is_empty()
        };
        let mut pairs = Vec::new();
        let mut mount = Vec::new();
        for i in 0..n {
            for j in i + 1..total {
                if !has_parts(self, i) || !has_parts(self, j) {
                    continue;
                }
                let (a, b) = (self.body(i), self.body(j));
                if j < n && self.allowed.is_allowed(&a.name, &b.name) {
                    continue;
                }
                if j >= n {
                    let attached_to = self.attached[j - n].0;
                    if attached_to == Some(i) || self.allowed.is_allowed(&a.name, &b.name) {
                        continue;
                    }
                    if a.fixed && b.fixed {
                        mount.push((i, j));
                        continue;
                    }
                }
                pairs.push((i, j));
            }
        }
        // Fixed bodies touching fixed obstacles: said once, never checked again.
        if !mount.is_empty() {
            let q = robot.ready_or_zero();
            let placed = self.place(robot, &q)?;
            let mut said = Vec::new();
            for (i, j) in mount {
                if let Some(depth) = self.pair_depth(&placed, i, j) {
                    said.push(format!(
                        "obstacle \"{}\" touches the fixed link \"{}\" ({}): the mounting, not \
                         checked",
                        self.body(j).name,
                        self.body(i).name,
                        millimetres(depth)
                    ));
                }
            }
            drop(placed);
            self.warnings.extend(said);
        }
        Ok(pairs)
    }

    /// Every body's parts placed in the world at `q`.
    fn place<'a>(&'a self, robot: &Robot, q: &[f64]) -> Result<Placement<'a>, KinematicsError> {
        let frames = robot.fk_frames(q)?;
        let world_from = |slot: usize| -> Pose {
            if slot == 0 {
                robot.base
            } else {
                frames[slot - 1]
            }
        };
        // sized once: a stick body has a few capsules (growing it was 6 % of a Puma report)
        let mut sticks: Vec<(usize, PPose, StickPart)> =
            Vec::with_capacity(4 * self.geometry.bodies.len());
        let mut scratch = Vec::with_capacity(8);
        for (slot, b) in self.geometry.bodies.iter().enumerate() {
            if b.stick {
                scratch.clear();
                self.geometry
                    .stick_parts(robot, &frames, q, slot.checked_sub(1), &mut scratch);
                sticks.extend(scratch.drain(..).map(|(p, s)| (slot, p, s)));
            }
        }
        let mut link_poses = Vec::with_capacity(self.geometry.bodies.len());
        for slot in 0..self.geometry.bodies.len() {
            link_poses.push(super::geometry::to_parry(&world_from(slot)));
        }
        Ok(Placement {
            world: self,
            link_poses,
            sticks,
        })
    }

    /// The deepest penetration between bodies `i` and `j` (m), if they overlap.
    fn pair_depth(&self, placement: &Placement<'_>, i: usize, j: usize) -> Option<f64> {
        let (a, b) = (placement.parts(i), placement.parts(j));
        self.deepest(&a, &b).map(|(d, _)| d)
    }

    /// The deepest overlap between two bodies' placed parts: depth (m) and where.
    fn deepest(&self, a: &[Placed<'_>], b: &[Placed<'_>]) -> Option<(f64, [f64; 3])> {
        let mut best: Option<(f64, [f64; 3])> = None;
        for pa in a {
            for pb in b {
                if !pa.aabb.intersects(&pb.aabb) {
                    continue;
                }
                if intersects(pa, pb)
                    && let Some((depth, at)) = penetration(pa, pb)
                    && best.is_none_or(|(d, _)| depth > d)
                {
                    best = Some((depth, at));
                }
            }
        }
        best
    }

    /// Whether configuration `q` hits anything checked (faster than [`CollisionWorld::check`]:
    /// no depths, no clearance).
    pub fn in_collision(&self, robot: &Robot, q: &[f64]) -> Result<bool, KinematicsError> {
        let placement = self.place(robot, q)?;
        let parts: Vec<Vec<Placed<'_>>> =
            (0..self.body_count()).map(|i| placement.parts(i)).collect();
        let boxes: Vec<Option<Aabb>> = parts.iter().map(|p| union(p)).collect();
        for &(i, j) in &self.pairs {
            let (Some(bi), Some(bj)) = (&boxes[i], &boxes[j]) else {
                continue;
            };
            if !bi.intersects(bj) {
                continue;
            }
            for pa in &parts[i] {
                for pb in &parts[j] {
                    if pa.aabb.intersects(&pb.aabb) && overlap(pa, pb) {
                        return Ok(true);
                    }
                }
            }
        }
        Ok(false)
    }

    /// The base's contacts with the obstacles fixed in the world, with the base where
    /// `robot.base` puts it: each `(body, obstacle)` where the body moves with no joint (a fixed
    /// link, or an obstacle attached to one) and overlaps a world obstacle, allowed pairs left
    /// out. [`CollisionWorld::in_collision`] never checks these (fixed against fixed is the
    /// mounting); a base placement that moves the whole robot asks them here.
    pub fn base_contacts(&self, robot: &Robot) -> Result<Vec<(String, String)>, KinematicsError> {
        let placement = self.place(robot, &robot.ready_or_zero())?;
        let n = self.geometry.bodies.len();
        let with_base = |i: usize| match i.checked_sub(n) {
            None => self.geometry.bodies[i].fixed,
            Some(k) => self.attached[k].0.is_some_and(|l| self.body(l).fixed),
        };
        let mut out = Vec::new();
        for i in (0..self.body_count()).filter(|&i| with_base(i)) {
            let a = placement.parts(i);
            for k in (0..self.obstacles.len()).filter(|&k| self.attached[k].0.is_none()) {
                let (an, bn) = (&self.body(i).name, &self.obstacles[k].name);
                if a.is_empty() || self.allowed.is_allowed(an, bn) {
                    continue;
                }
                if self.deepest(&a, &placement.parts(n + k)).is_some() {
                    out.push((an.clone(), bn.clone()));
                }
            }
        }
        Ok(out)
    }

    /// How many bodies there are (links and obstacles).
    fn body_count(&self) -> usize {
        self.geometry.bodies.len() + self.obstacles.len()
    }

    /// What configuration `q` hits: every pair in contact with its depth, and the clearance.
    pub fn check(&self, robot: &Robot, q: &[f64]) -> Result<CollisionReport, KinematicsError> {
        let placement = self.place(robot, q)?;
        let parts: Vec<Vec<Placed<'_>>> =
            (0..self.body_count()).map(|i| placement.parts(i)).collect();
        let boxes: Vec<Option<Aabb>> = parts.iter().map(|p| union(p)).collect();
        let mut contacts = Vec::new();
        // Pairs not in contact, with a lower bound on their distance (their boxes' gap).
        let mut apart: Vec<(f64, usize, usize)> = Vec::new();
        for &(i, j) in &self.pairs {
            let (Some(bi), Some(bj)) = (&boxes[i], &boxes[j]) else {
                continue;
            };
            let gap = aabb_gap(bi, bj);
            if gap <= 0.0
                && let Some((depth, at)) = self.deepest(&parts[i], &parts[j])
            {
                contacts.push(Contact {
                    a: self.body(i).name.clone(),
                    b: self.body(j).name.clone(),
                    depth_m: depth,
                    at,
                });
                continue;
            }
            apart.push((gap, i, j));
        }
        contacts.sort_by(|x, y| y.depth_m.total_cmp(&x.depth_m));
        if let Some(deepest) = contacts.first() {
            return Ok(CollisionReport {
                in_collision: true,
                closest: Some(ClosestPair {
                    a: deepest.a.clone(),
                    b: deepest.b.clone(),
                }),
                pairs: contacts,
                clearance_m: Some(0.0),
            });
        }
        // Branch and bound: exact distances in order of the boxes' gaps, until a gap exceeds
        // the best distance found.
        apart.sort_by(|x, y| x.0.total_cmp(&y.0));
        let mut best: Option<(f64, usize, usize)> = None;
        for (gap, i, j) in apart {
            if best.is_some_and(|(d, _, _)| gap >= d) {
                break;
            }
            let bound = best.map_or(f64::INFINITY, |(d, _, _)| d);
            if let Some(d) = min_distance(&parts[i], &parts[j], bound)
                && d < bound
            {
                best = Some((d, i, j));
            }
        }
        Ok(CollisionReport {
            in_collision: false,
            pairs: Vec::new(),
            clearance_m: best.map(|(d, _, _)| d.max(0.0)),
            closest: best.map(|(_, i, j)| ClosestPair {
                a: self.body(i).name.clone(),
                b: self.body(j).name.clone(),
            }),
        })
    }

    /// The names of the pairs checked at every configuration.
    pub fn checked_pairs(&self) -> Vec<(String, String)> {
        self.pairs
            .iter()
            .map(|&(i, j)| (self.body(i).name.clone(), self.body(j).name.clone()))
            .collect()
    }

    /// For the matrix: whether each link pair `(i, j)` (body indices) overlaps at `q`.
    pub(super) fn link_pairs_overlap(
        &self,
        robot: &Robot,
        q: &[f64],
        pairs: &[(usize, usize)],
    ) -> Result<Vec<bool>, KinematicsError> {
        let placement = self.place(robot, q)?;
        let n = self.geometry.bodies.len();
        let parts: Vec<Vec<Placed<'_>>> = (0..n).map(|i| placement.parts(i)).collect();
        Ok(pairs
            .iter()
            .map(|&(i, j)| self.deepest(&parts[i], &parts[j]).is_some())
            .collect())
    }

    /// The obstacle a ray from `origin` along the unit vector `dir` (world, m) meets first at
    /// `q`: its index in the scene and the distance (m). Planes are left out unless `planes`
    /// (a floor would catch every click below the horizon). What a click in a 3D view picks.
    pub fn obstacle_on_ray(
        &self,
        robot: &Robot,
        q: &[f64],
        (origin, dir): ([f64; 3], [f64; 3]),
        planes: bool,
    ) -> Result<Option<(usize, f64)>, KinematicsError> {
        use parry3d_f64::query::Ray;
        let placement = self.place(robot, q)?;
        let n = self.geometry.bodies.len();
        let ray = Ray::new(
            Vec3::new(origin[0], origin[1], origin[2]),
            Vec3::new(dir[0], dir[1], dir[2]),
        );
        let mut best: Option<(usize, f64)> = None;
        for k in 0..self.obstacles.len() {
            for p in placement.parts(n + k) {
                if !planes && p.shape.as_shape::<HalfSpace>().is_some() {
                    continue;
                }
                if let Some(t) = p.shape.cast_ray(&p.pose, &ray, f64::MAX, true)
                    && best.is_none_or(|(_, b)| t < b)
                {
                    best = Some((k, t));
                }
            }
        }
        Ok(best)
    }

    /// World poses of every obstacle at `q` (`world_from_obstacle`), for drawing.
    pub fn obstacle_poses(&self, robot: &Robot, q: &[f64]) -> Result<Vec<Pose>, KinematicsError> {
        let frames = robot.fk_frames(q)?;
        Ok(self
            .attached
            .iter()
            .map(|(link, p)| {
                let world_from_frame = match link {
                    None => Pose::identity(),
                    Some(0) => robot.base,
                    Some(slot) => frames[slot - 1],
                };
                world_from_frame * super::geometry::from_parry(p)
            })
            .collect())
    }
}

/// Every body's placement at one configuration.
struct Placement<'a> {
    world: &'a CollisionWorld,
    /// `world_from_link` for each link body.
    link_poses: Vec<PPose>,
    /// The stick bodies' parts in the world: (body, pose, shape).
    sticks: Vec<(usize, PPose, StickPart)>,
}

impl Placement<'_> {
    /// Body `i`'s parts placed in the world, with their boxes.
    fn parts(&self, i: usize) -> Vec<Placed<'_>> {
        let w = self.world;
        let n = w.geometry.bodies.len();
        fn placed<'a>(hulls: &'a Hulls, pose: PPose, shape: &'a dyn Shape) -> Placed<'a> {
            let hull = hulls.get(shape);
            Placed {
                // a hull's own box placed (not every vertex moved): a little looser, which a
                // bound allows
                aabb: hull.map_or_else(
                    || shape.compute_aabb(&pose),
                    |h| h.local_aabb.transform_by(&pose),
                ),
                pose,
                shape,
                hull,
            }
        }
        if i < n {
            let b = &w.geometry.bodies[i];
            if b.stick {
                return self
                    .sticks
                    .iter()
                    .filter(|(k, _, _)| *k == i)
                    .map(|(_, p, s)| placed(&w.hulls, *p, s.shape()))
                    .collect();
            }
            let world_from_link = self.link_poses[i];
            return b
                .parts
                .iter()
                .map(|(p, s)| placed(&w.hulls, world_from_link * *p, s.as_ref()))
                .collect();
        }
        let (link, frame_from_obstacle) = w.attached[i - n];
        let world_from_frame = link.map_or(PPose::IDENTITY, |l| self.link_poses[l]);
        let world_from_obstacle = world_from_frame * frame_from_obstacle;
        w.obstacles[i - n]
            .parts
            .iter()
            .map(|(p, s)| placed(&w.hulls, world_from_obstacle * *p, s.as_ref()))
            .collect()
    }
}

/// How deep two placed parts overlap (m, beyond [`TOUCH_TOLERANCE_M`]) and where (midway
/// between the deepest points, world frame), or `None`.
fn penetration(pa: &Placed<'_>, pb: &Placed<'_>) -> Option<(f64, [f64; 3])> {
    // parry 0.31.1 gets a convex shape against a half-space wrong in that order (a capsule 14
    // mm above a floor reads 86 mm deep; the test `a_half_space_second_is_measured_right`
    // holds it); the half-space first is right, and the contact is symmetric.
    if let Some(found) = rounded_penetration(pa, pb) {
        return found;
    }
    let (first, second) = half_space_first(pa, pb);
    let c = query::contact(&first.pose, first.shape, &second.pose, second.shape, 0.0)
        .ok()
        .flatten()?;
    let depth = -c.dist;
    (depth > TOUCH_TOLERANCE_M).then(|| {
        let m = (c.point1 + c.point2) * 0.5;
        (depth, [m.x, m.y, m.z])
    })
}

/// A part's core and rounding: a capsule is its segment and radius, anything else itself and 0.
fn core<'a>(p: &'a Placed<'_>) -> (&'a dyn Shape, f64) {
    match p.shape.as_capsule() {
        Some(c) => (&c.segment, c.radius),
        None => (p.shape, 0.0),
    }
}

/// For a pair with a capsule: the overlap measured between the cores (a segment's contact is
/// a closed form or a short GJK; two capsules through EPA cost ten times more). `None` when no
/// capsule is involved, or the cores themselves overlap (then the shapes are asked).
#[allow(clippy::option_option)]
fn rounded_penetration(pa: &Placed<'_>, pb: &Placed<'_>) -> Option<Option<(f64, [f64; 3])>> {
    let ((sa, ra), (sb, rb)) = (core(pa), core(pb));
    let rounding = ra + rb;
    if rounding == 0.0 {
        return None;
    }
    let ((s1, p1, r1), (s2, p2, r2)) = if sb.as_shape::<HalfSpace>().is_some() {
        ((sb, &pb.pose, rb), (sa, &pa.pose, ra))
    } else {
        ((sa, &pa.pose, ra), (sb, &pb.pose, rb))
    };
    let c = match query::contact(p1, s1, p2, s2, rounding) {
        Ok(Some(c)) => c,
        Ok(None) => return Some(None),
        Err(_) => return None,
    };
    if c.dist <= 0.0 {
        return None;
    }
    let depth = rounding - c.dist;
    Some((depth > TOUCH_TOLERANCE_M).then(|| {
        let m = (c.point1 + c.normal1 * r1 + c.point2 + c.normal2 * r2) * 0.5;
        (depth, [m.x, m.y, m.z])
    }))
}

/// The distance between two placed parts that do not overlap (m). A capsule is measured as
/// its segment less its radius: parry has the segments' distance in closed form, where two
/// capsules would go through GJK (five times slower on the Puma's links).
fn part_distance(pa: &Placed<'_>, pb: &Placed<'_>) -> Option<f64> {
    let ((sa, ra), (sb, rb)) = (core(pa), core(pb));
    // A hull is its own core: its vertex graph climbs (see `super::hull`).
    fn hull<'a>(s: &dyn Shape, p: &Placed<'a>) -> Option<&'a HullData> {
        p.hull.filter(|_| s.as_convex_polyhedron().is_some())
    }
    if let Some(d) = support_distance((&pa.pose, sa, hull(sa, pa)), (&pb.pose, sb, hull(sb, pb))) {
        return Some(d - ra - rb);
    }
    let (first, second) = if sb.as_shape::<HalfSpace>().is_some() {
        ((sb, &pb.pose), (sa, &pa.pose))
    } else {
        ((sa, &pa.pose), (sb, &pb.pose))
    };
    let d = query::distance(first.1, first.0, second.1, second.0).ok()?;
    Some(d.distance - ra - rb)
}

/// Whether two placed parts overlap deeper than [`TOUCH_TOLERANCE_M`] (an intersection test
/// first: no penetration depth is computed for parts apart).
fn overlap(pa: &Placed<'_>, pb: &Placed<'_>) -> bool {
    intersects(pa, pb) && penetration(pa, pb).is_some()
}

/// Whether two placed parts touch or overlap (parry's intersection test, the half-space
/// first; an unsupported pair counts as touching, so that the contact query decides).
fn intersects(pa: &Placed<'_>, pb: &Placed<'_>) -> bool {
    if let Some(found) = rounded_penetration(pa, pb) {
        return found.is_some();
    }
    if let Some(hit) =
        support_intersects((&pa.pose, pa.shape, pa.hull), (&pb.pose, pb.shape, pb.hull))
    {
        return hit;
    }
    let (first, second) = half_space_first(pa, pb);
    query::intersection_test(&first.pose, first.shape, &second.pose, second.shape)
        .map_or(true, |i| i.intersecting)
}

/// The two parts with a half-space first (see [`penetration`]).
fn half_space_first<'a, 'b>(
    pa: &'a Placed<'b>,
    pb: &'a Placed<'b>,
) -> (&'a Placed<'b>, &'a Placed<'b>) {
    if pb.shape.as_shape::<HalfSpace>().is_some() {
        (pb, pa)
    } else {
        (pa, pb)
    }
}

/// The box around a body's parts (`None`: no parts).
fn union(parts: &[Placed<'_>]) -> Option<Aabb> {
    let mut it = parts.iter();
    let first = it.next()?.aabb;
    Some(it.fold(first, |acc, p| acc.merged(&p.aabb)))
}

/// The gap between two boxes (m; 0 when they overlap): a lower bound on the distance between
/// what they hold.
fn aabb_gap(a: &Aabb, b: &Aabb) -> f64 {
    let d = Vec3::ZERO.max(a.mins - b.maxs).max(b.mins - a.maxs);
    d.length()
}

/// The smallest distance between two bodies' parts, skipping part pairs whose boxes are at
/// least `bound` apart (m); `None` when every pair was skipped.
fn min_distance(a: &[Placed<'_>], b: &[Placed<'_>], bound: f64) -> Option<f64> {
    let mut best: Option<f64> = None;
    for pa in a {
        for pb in b {
            let limit = best.unwrap_or(bound);
            if aabb_gap(&pa.aabb, &pb.aabb) >= limit {
                continue;
            }
            if let Some(d) = part_distance(pa, pb)
                && best.is_none_or(|x| d < x)
            {
                best = Some(d);
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// The UR5's clearance as the report gives it (boxes pruning, hulls climbed) against the
    /// smallest distance of every checked pair's every two parts by parry's own query (its
    /// vertex scans, nothing pruned), at configurations drawn over the joint ranges.
    #[test]
    fn the_reports_clearance_is_the_smallest_distance_of_all_pairs() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        crate::urdf::set_package_paths(vec![root.join("tests/data/collision_meshes")]);
        let robot = crate::urdf::load_urdf(&root.join("tests/data/urdf_corpus/ur5_robot.urdf"));
        crate::urdf::set_package_paths(Vec::new());
        let robot = robot.expect("the UR5");
        let world = CollisionWorld::new(&robot, &CellScene::default()).expect("a world");
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        let mut free = 0;
        for _ in 0..60 {
            let q: Vec<f64> = (0..6)
                .map(|_| {
                    seed ^= seed << 13;
                    seed ^= seed >> 7;
                    seed ^= seed << 17;
                    ((seed >> 11) as f64 / (1u64 << 52) as f64 - 1.0) * std::f64::consts::PI
                })
                .collect();
            let report = world.check(&robot, &q).expect("a report");
            if report.in_collision {
                continue;
            }
            free += 1;
            let placement = world.place(&robot, &q).expect("placed");
            let mut nearest = f64::INFINITY;
            for &(i, j) in &world.pairs {
                for pa in placement.parts(i) {
                    for pb in placement.parts(j) {
                        let d = query::distance(&pa.pose, pa.shape, &pb.pose, pb.shape);
                        nearest = nearest.min(d.expect("a distance").distance);
                    }
                }
            }
            let got = report.clearance_m.expect("a clearance");
            assert!((got - nearest).abs() < 1e-9, "q {q:?}: {got} vs {nearest}");
        }
        assert!(free >= 15, "{free} free configurations");
    }
}
