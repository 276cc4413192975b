//! The exact workspace of a two- or three-link planar arm with joint limits (Sect. 2.10.1,
//! Example 2.6, Problem 2.17), in plane coordinates ([`PlanarFrame`], m).
//!
//! - **Membership** of a point and its posture classes come from the closed-form inverse
//!   kinematics of Sect. 2.12.1 with the orientation phi left free: the feasible values of phi of
//!   each elbow branch change only where a joint reaches a limit or the branches merge, and each
//!   of those is a root of `|A - B e^{i phi}| = R` in closed form, so a handful of tests between
//!   consecutive roots decide the point exactly (no scan of phi on a grid).
//! - **Boundary**: the boundary of the image of the joint box lies on the images of its edges, of
//!   the fold curves of its faces and of the interior singular lines; on each of them one joint
//!   moves, so each image is a circular arc. The arcs are split where they meet and a piece is
//!   kept where the region lies on exactly one side of it (exact membership just inside and just
//!   outside), oriented with the region on its left.
//! - **Areas** by Green's theorem over those arcs, in closed form per arc; the estimated error is
//!   the closure gap of the loops times the perimeter (rounding only, for a closed boundary).

mod arcs;
pub(crate) mod chain;

pub use arcs::Arc;
pub use chain::Membership;

use super::{Aabb, PlanarFrame, WorkspaceError};
use crate::kinematics::Robot;
use chain::PlanarChain;

/// Which set of points a boundary or an area is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RegionSet {
    /// Reached with some posture.
    Reachable,
    /// Reached with posture class k.
    Class(u8),
    /// Reached with every posture class (region BADHB of Fig. 2.30).
    AllClasses,
}

impl RegionSet {
    /// Whether a membership mask belongs to the set, for `classes` posture classes.
    #[inline]
    pub fn contains(self, mask: u8, classes: usize) -> bool {
        match self {
            RegionSet::Reachable => mask != 0,
            RegionSet::Class(k) => mask & (1 << k) != 0,
            RegionSet::AllClasses => {
                let all = ((1u16 << classes) - 1) as u8;
                mask & all == all
            }
        }
    }
}

/// An exact boundary and the area it encloses.
#[derive(Debug, Clone, PartialEq)]
pub struct ExactRegion {
    /// The set.
    pub set: RegionSet,
    /// Boundary arcs, the region on the left of each (plane coordinates).
    pub arcs: Vec<Arc>,
    /// Area (m^2), Green's theorem over `arcs`.
    pub area: f64,
    /// Estimated error of the area (m^2): the largest gap between consecutive arcs times the
    /// perimeter, plus rounding.
    pub error: f64,
}

/// The exact workspace of a two- or three-link planar arm.
#[derive(Debug, Clone)]
pub struct ExactPlanar {
    chain: PlanarChain,
    frame: PlanarFrame,
    class_names: Vec<String>,
    candidates: Vec<Arc>,
    regions: Vec<ExactRegion>,
}

impl ExactPlanar {
    /// Builds the exact workspace of end-effector 0 of a two- or three-link planar arm (closed-form
    /// family; revolute joints). Errors say why another arm is not supported.
    pub fn new(robot: &Robot) -> Result<Self, WorkspaceError> {
        let (chain, frame) = PlanarChain::from_robot(robot)?;
        let class_names = super::PostureClassifier::new(robot).class_names().to_vec();
        let candidates = chain.candidates();
        let mut me = Self {
            chain,
            frame,
            class_names,
            candidates,
            regions: Vec::new(),
        };
        let mut sets = vec![RegionSet::Reachable];
        if me.class_names.len() > 1 {
            sets.extend((0..me.class_names.len() as u8).map(RegionSet::Class));
            sets.push(RegionSet::AllClasses);
        }
        me.regions = sets.into_iter().map(|s| me.region_of(s)).collect();
        Ok(me)
    }

    fn region_of(&self, set: RegionSet) -> ExactRegion {
        let k = self.class_names.len();
        let inside = |p: [f64; 2]| set.contains(self.chain.mask(p), k);
        let arcs = arcs::boundary(&self.candidates, self.chain.scale, &inside);
        let area: f64 = arcs.iter().map(Arc::green).sum();
        let perimeter: f64 = arcs.iter().map(Arc::length).sum();
        let error = arcs::closure_gap(&arcs) * perimeter + 1e-14 * area.abs().max(1e-30);
        ExactRegion {
            set,
            arcs,
            area,
            error,
        }
    }

    /// The arm's plane.
    pub fn frame(&self) -> &PlanarFrame {
        &self.frame
    }

    /// Names of the posture classes (bits of [`Membership::mask`]).
    pub fn class_names(&self) -> &[String] {
        &self.class_names
    }

    /// Whether the orientation of the end-effector is free (three links): then
    /// [`Membership::orientations`] is meaningful.
    pub fn orientation_free(&self) -> bool {
        self.chain.n == 3
    }

    /// Exact membership of a point (plane coordinates, m). Allocation-free.
    #[inline]
    pub fn membership(&self, p: [f64; 2]) -> Membership {
        self.chain.membership(p)
    }

    /// The class mask of [`Self::membership`] alone: faster, it stops once every class is found.
    #[inline]
    pub fn mask(&self, p: [f64; 2]) -> u8 {
        self.chain.mask(p)
    }

    /// Largest position manipulability sqrt(det(J_P J_P^T)) (m^2) of the configurations
    /// reaching `p` (plane coordinates): both postures of a two-link arm; for three links both
    /// postures at 96 orientations phi and at the midpoint of each feasible interval. `None`
    /// when `p` is not reached.
    pub fn max_manipulability(&self, p: [f64; 2]) -> Option<f64> {
        self.chain.max_manipulability(p)
    }

    /// Every boundary candidate (arcs of the images of the box's edges, face folds and singular
    /// lines), the boundary of each region is made of pieces of them.
    pub fn candidates(&self) -> &[Arc] {
        &self.candidates
    }

    /// The regions: reachable first, then each class, then all classes (when there are
    /// several classes).
    pub fn regions(&self) -> &[ExactRegion] {
        &self.regions
    }

    /// The region of a set, if computed.
    pub fn region(&self, set: RegionSet) -> Option<&ExactRegion> {
        self.regions.iter().find(|r| r.set == set)
    }

    /// Signed distance (m) from a point to the boundary of the reachable set: positive inside,
    /// negative outside.
    pub fn signed_distance(&self, p: [f64; 2]) -> f64 {
        let d = self.regions[0]
            .arcs
            .iter()
            .map(|a| a.distance(p))
            .fold(f64::INFINITY, f64::min);
        if self.mask(p) != 0 { d } else { -d }
    }

    /// Bounding box of the reachable set in plane coordinates (z = 0), from the boundary arcs
    /// (their extreme points included).
    pub fn bounds(&self) -> Aabb {
        let mut b = Aabb::EMPTY;
        for a in &self.regions[0].arcs {
            for p in [a.first(), a.last()] {
                b.extend([p[0], p[1], 0.0]);
            }
            let (lo, span) = if a.sweep >= 0.0 {
                (a.start, a.sweep)
            } else {
                (a.start + a.sweep, -a.sweep)
            };
            for k in 0..4 {
                let t = k as f64 * std::f64::consts::FRAC_PI_2;
                if (t - lo).rem_euclid(std::f64::consts::TAU) <= span {
                    let p = a.at(t);
                    b.extend([p[0], p[1], 0.0]);
                }
            }
        }
        b
    }

    /// Smallest and largest distance (m) from the base origin (3D, the plane's z included) over
    /// the reachable set.
    pub fn reach(&self) -> [f64; 2] {
        let z2 = self.frame.z * self.frame.z;
        let mut lo = f64::INFINITY;
        let mut hi: f64 = 0.0;
        for a in &self.regions[0].arcs {
            let d = a.centre[0].hypot(a.centre[1]);
            // Nearest and farthest points of the circle from the origin, if on the arc.
            let dir = a.centre[1].atan2(a.centre[0]);
            let mut cands = vec![a.first(), a.last()];
            for t in [dir, dir + std::f64::consts::PI] {
                let probe = a.at(t);
                if a.distance(probe) < 1e-12 * (d + a.radius) {
                    cands.push(probe);
                }
            }
            for p in cands {
                let r = (p[0] * p[0] + p[1] * p[1] + z2).sqrt();
                lo = lo.min(r);
                hi = hi.max(r);
            }
        }
        if self.membership([0.0, 0.0]).mask != 0 {
            lo = self.frame.z.abs();
        }
        [lo, hi]
    }
}
