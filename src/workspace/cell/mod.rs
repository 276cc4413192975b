//! Workspaces in a cell: which postures reach a point within the joint limits without the arm
//! hitting itself or the cell's obstacles ([`CellChecker`]), and a workspace map cut by them,
//! decided cell by cell at a resolution the map states ([`CollisionLayer`]), with the
//! obstacles' outlines in the map's view ([`ObstacleOutline`]).
//!
//! The postures at a point come from the closed-form IK ([`ReachTester::visit_world`]): every
//! solution within the limits, over the scanned orientations of an arm that scans them; a
//! posture class counts as collision-free at the point when one of its configurations is.
//! For the wrist centre of an arm with a spherical wrist, the orientation is free: the links up
//! to the wrist centre are checked (the wrist joints at [`ReachTester::wrist_reference`]); the
//! wrist's and the tool's links, whose pose the view leaves free, are not.

mod layer;
mod outline;

pub use layer::{BlockVerdict, COLLISION_CELLS, CollisionLayer, cut_map};
pub use outline::{ObstacleOutline, OutlineKind, obstacle_outlines};

use super::map::TrackedPoint;
use super::reach::ReachTester;
use super::{PostureClassifier, WorkspaceError};
use crate::collision::{
    AllowedCollisions, CellScene, CollisionWorld, Contact, GeometryOptions, PairReason,
    RobotGeometry,
};
use crate::kinematics::Robot;

/// Orientations a three-link planar arm's posture check scans (angles phi, 1 degree apart: a
/// point near the workspace's edge is reached on a narrow range of phi only).
pub const CHECK_ORIENTATIONS: usize = 360;

/// What the postures do at one point: bit k of each mask is posture class k.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PointCheck {
    /// Classes with a configuration within the joint limits there (of those the scan met
    /// before it stopped: every class asked for, at least).
    pub reached: u8,
    /// Classes with such a configuration that hits nothing.
    pub free: u8,
}

impl PointCheck {
    /// Classes that reach the point only through a collision.
    pub fn colliding(&self) -> u8 {
        self.reached & !self.free
    }
}

/// One posture class at a point, checked.
#[derive(Debug, Clone, PartialEq)]
pub struct PostureVerdict {
    /// The class's index (its bit in the masks).
    pub class: usize,
    /// Its name, e.g. "shoulder right, elbow up".
    pub name: String,
    /// Whether some configuration of the class within the limits hits nothing.
    pub free: bool,
    /// That configuration (rad, m), or when there is none the first one tried.
    pub q: Vec<f64>,
    /// What `q` hits (empty when free), deepest first.
    pub contacts: Vec<Contact>,
}

/// A robot in its cell: which postures reach a point within the limits without a collision.
///
/// ```
/// use armlab::collision::{CellScene, Obstacle};
/// use armlab::kinematics::models::built_in;
/// use armlab::workspace::TrackedPoint;
/// use armlab::workspace::cell::CellChecker;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let arm = built_in("anthropomorphic3r").expect("a built-in model");
/// // A box that fills the space in front of the arm, below z = 0.
/// let cell = CellScene {
///     obstacles: vec![Obstacle::cuboid("block", [2.0, 2.0, 1.0], [1.5, 0.0, -0.6])],
///     ..CellScene::default()
/// };
/// let checker = CellChecker::new(&arm, &cell, TrackedPoint::Flange)?;
/// // Inside the block nothing is free; above it every posture that reaches is.
/// let inside = checker.check_point([0.9, 0.0, -0.5], 0xff);
/// assert!(inside.reached != 0 && inside.free == 0);
/// let above = checker.check_point([0.0, 0.6, 0.5], 0xff);
/// assert!(above.reached != 0 && above.free == above.reached);
/// # Ok(())
/// # }
/// ```
#[derive(Debug, Clone)]
pub struct CellChecker<'a> {
    robot: &'a Robot,
    world: CollisionWorld,
    tester: Option<ReachTester<'a>>,
    class_names: Vec<String>,
    /// Bodies left out of every check (the wrist and tool of a wrist-centre check).
    unchecked: Vec<String>,
}

impl<'a> CellChecker<'a> {
    /// The checker of `robot` (end-effector 0) in `cell` for the tracked `point`. Without a
    /// closed form whose postures it can enumerate it still checks configurations
    /// ([`Self::config_free`]), and [`Self::has_postures`] is false.
    pub fn new(
        robot: &'a Robot,
        cell: &CellScene,
        point: TrackedPoint,
    ) -> Result<Self, WorkspaceError> {
        let tester = ReachTester::tracking(robot, CHECK_ORIENTATIONS, point);
        let geometry = RobotGeometry::of(robot, GeometryOptions::default());
        let mut allowed = AllowedCollisions::for_robot(robot, &geometry);
        let unchecked = match &tester {
            Some(t) if t.wrist_centre() => hand_bodies(robot, &geometry),
            _ => Vec::new(),
        };
        if !unchecked.is_empty() {
            let names: Vec<String> = geometry
                .bodies
                .iter()
                .map(|b| b.name.clone())
                .chain(cell.obstacles.iter().map(|o| o.name.clone()))
                .collect();
            for hand in &unchecked {
                for other in &names {
                    if other != hand {
                        allowed.add(hand, other, PairReason::User);
                    }
                }
            }
        }
        let world =
            CollisionWorld::with(robot, geometry, cell, GeometryOptions::default(), allowed)?;
        Ok(CellChecker {
            robot,
            world,
            class_names: PostureClassifier::new(robot).class_names().to_vec(),
            tester,
            unchecked,
        })
    }

    /// The collision world the checks use.
    pub fn world(&self) -> &CollisionWorld {
        &self.world
    }

    /// Names of the posture classes (bits of the masks).
    pub fn class_names(&self) -> &[String] {
        &self.class_names
    }

    /// Whether the postures of a point can be enumerated (a closed form the checker knows).
    pub fn has_postures(&self) -> bool {
        self.tester.is_some()
    }

    /// The bodies never checked: the wrist's and tool's links of a wrist-centre check.
    pub fn unchecked(&self) -> &[String] {
        &self.unchecked
    }

    /// Whether configuration `q` hits nothing that is checked (the limits are not looked at).
    /// A configuration that cannot be placed (wrong length) counts as hitting.
    pub fn config_free(&self, q: &[f64]) -> bool {
        self.world.in_collision(self.robot, q).is_ok_and(|hit| !hit)
    }

    /// The classes reaching world point `p` (m) within the limits and, of the classes in
    /// `want`, those that do without a collision. Stops as soon as every class of `want` is
    /// known to be free.
    pub fn check_point(&self, p: [f64; 3], want: u8) -> PointCheck {
        let mut out = PointCheck::default();
        let Some(tester) = &self.tester else {
            return out;
        };
        tester.visit_world(p, &mut |mask, q| {
            out.reached |= mask;
            if mask & want & !out.free != 0 && self.config_free(q) {
                out.free |= mask;
            }
            want & !out.free == 0
        });
        out
    }

    /// [`Self::check_point`] over several points (a column of heights): a class counts as
    /// free when it is free at one of them, reached when it reaches one.
    pub fn check_points(&self, points: &mut dyn Iterator<Item = [f64; 3]>, want: u8) -> PointCheck {
        let mut out = PointCheck::default();
        for p in points {
            let here = self.check_point(p, want & !out.free);
            out.reached |= here.reached;
            out.free |= here.free;
            if want & !out.free == 0 {
                break;
            }
        }
        out
    }

    /// Every posture class reaching world point `p` (m) within the limits, checked: free when
    /// one of its configurations hits nothing; otherwise what the first one hits.
    pub fn postures(&self, p: [f64; 3]) -> Vec<PostureVerdict> {
        let mut first: Vec<Option<Vec<f64>>> = vec![None; 8];
        let mut free: Vec<Option<Vec<f64>>> = vec![None; 8];
        if let Some(tester) = &self.tester {
            tester.visit_world(p, &mut |mask, q| {
                let k = (mask.trailing_zeros() as usize).min(7);
                if first[k].is_none() {
                    first[k] = Some(q.to_vec());
                }
                if free[k].is_none() && self.config_free(q) {
                    free[k] = Some(q.to_vec());
                }
                false
            });
        }
        let mut out = Vec::new();
        for (k, (f, q0)) in free.into_iter().zip(first).enumerate() {
            let Some(q0) = q0 else { continue };
            let name = self
                .class_names
                .get(k)
                .cloned()
                .unwrap_or_else(|| format!("class {k}"));
            let verdict = match f {
                Some(q) => PostureVerdict {
                    class: k,
                    name,
                    free: true,
                    q,
                    contacts: Vec::new(),
                },
                None => PostureVerdict {
                    class: k,
                    name,
                    free: false,
                    contacts: self
                        .world
                        .check(self.robot, &q0)
                        .map(|r| r.pairs)
                        .unwrap_or_default(),
                    q: q0,
                },
            };
            out.push(verdict);
        }
        out
    }

    /// What is checked, in words: "the links against each other and the obstacles", or for a
    /// wrist-centre check "the links up to the wrist centre against ...".
    pub fn what_is_checked(&self) -> String {
        if self.unchecked.is_empty() {
            "the links against each other and the obstacles".into()
        } else {
            format!(
                "the links up to the wrist centre against each other and the obstacles; the \
                 wrist's links, {}, are free in this view and not checked",
                self.unchecked.join(" and ")
            )
        }
    }
}

/// The bodies that the wrist joints (joints 5 and 6, and any after) move: their pose depends
/// on the tool's orientation, which a wrist-centre workspace leaves free.
fn hand_bodies(robot: &Robot, geometry: &RobotGeometry) -> Vec<String> {
    let wrist: Vec<usize> = robot.actuated_joints().iter().skip(4).copied().collect();
    geometry
        .bodies
        .iter()
        .filter(|b| match b.kind {
            crate::collision::BodyKind::Link(Some(j)) => {
                wrist.contains(&j) || robot.chain_to(j).iter().any(|k| wrist.contains(k))
            }
            _ => false,
        })
        .map(|b| b.name.clone())
        .collect()
}
