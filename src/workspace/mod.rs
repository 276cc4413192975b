//! The workspace of a manipulator (Sect. 2.10.1): pure computation, no graphics, no I/O.
//!
//! The reachable workspace is the set of end-effector positions `p_e = p_e(q)` with every
//! joint inside its mechanical limits, `q_im <= q_i <= q_iM` (Sect. 2.10.1). This module offers:
//!
//! - [`sample()`]: positions of joint vectors drawn uniformly in the joint-limit box, in parallel and
//!   deterministic for a seed, optionally with a posture class and the manipulability;
//! - [`PostureClassifier`]: the posture of a configuration (elbow up/down for planar arms,
//!   shoulder right/left x elbow up/down for anthropomorphic arms), named as the closed-form IK
//!   labels its solutions;
//! - [`planar_boundary`] and [`joint_rectangle`]: for two- and three-link planar arms the exact
//!   boundary candidates (images of the joint-limit edges and of the aligned-links segments) as
//!   labelled polylines, and the joint-space rectangle of Fig. 2.29 whose image is Fig. 2.30;
//! - [`analyze_grid`]: the cells (planar arms, m^2) or voxels (spatial arms, m^3) reachable with
//!   each posture, from the closed-form IK at cell centres (or by sampling when there is no closed
//!   form), and per cell the fraction of quantised orientations reached (the dexterous
//!   workspace);
//! - [`statistics`]: area or volume, areas by posture, bounding box, minimum and maximum reach;
//! - [`views`]: 2D projections (plane, top, side) and 3D point clouds as plain data.
//!
//! Frames and units: positions are in the world frame (m) unless a function says "plane
//! coordinates", which are the x-y coordinates of the robot's base frame for an arm that moves in
//! that plane ([`PlanarFrame`]). Angles are in rad.

pub mod cell;
pub mod exact;
pub mod figure_data;
pub mod grid;
pub mod map;
pub mod planar;
pub mod posture;
pub mod reach;
pub mod rectangle;
pub(crate) mod rng;
pub mod sample;
pub mod stats;
pub mod views;

pub use exact::{Arc, ExactPlanar, ExactRegion, Membership, RegionSet};
pub use figure_data::{
    COARSE, Content, ContentRequest, FigureData, FigureRequest, compute_figure_data,
    compute_figure_data_forming, compute_figure_data_in,
};
pub use grid::{
    DexterousSet, GridAnalysis, GridMethod, GridOptions, GridSpec, MethodChoice, analyze_grid,
};
pub use map::{
    CellValues, CurveRole, MapCurve, MapForming, MapFrame, MapRequest, MapValues, MapView, OneShot,
    PointQuery, ReachAnswer, Section, TILE_ROWS, TiledMap, TrackedPoint, WorkspaceMap, compute_map,
    compute_map_forming, compute_map_in, map_extent, map_frame, map_statistics,
};
pub use planar::{
    BoundaryCurve, BoundaryOptions, CurveKind, PlanarBoundary, PostureLoop, planar_boundary,
};
pub use posture::{PostureClassifier, UNCLASSIFIED};
pub use reach::{ORIENTATION_BINS, Reach, ReachTester, approach_bin, approach_bin_centre, phi_bin};
pub use rectangle::{JointRectangle, RectPoint, RectSegment, joint_rectangle};
pub use sample::{SAMPLE_CHUNK, SampleOptions, Samples, sample};
pub use stats::{ClassMeasure, StatsOptions, WorkspaceStats, statistics};
pub use views::{PointCloud, Projection, View, point_cloud, project};

use crate::kinematics::{KinematicsError, Pose, Robot};
use nalgebra::{Point3, Vector3};
use thiserror::Error;

/// Why a workspace computation could not run.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum WorkspaceError {
    /// The end-effector index does not exist.
    #[error("end-effector {index} does not exist (the robot has {count})")]
    NoSuchEndEffector {
        /// The index asked for.
        index: usize,
        /// How many end-effectors the robot has.
        count: usize,
    },
    /// An option is out of range (e.g. a zero grid resolution).
    #[error("invalid workspace option: {option} {value}: {expected}")]
    InvalidOption {
        /// The option, e.g. "grid resolution".
        option: &'static str,
        /// The value given, in words.
        value: String,
        /// What it must be.
        expected: &'static str,
    },
    /// The computation needs a planar arm of a given kind, and the robot is not one.
    #[error("{robot} {reason}")]
    NotPlanar {
        /// The robot's name.
        robot: String,
        /// What it lacks, e.g. "is not a two- or three-link planar arm".
        reason: String,
    },
    /// The dexterous workspace needs orientations, and the arm controls position only.
    #[error("the {family} controls position only: the dexterous workspace needs a wrist")]
    PositionOnly {
        /// The closed-form family's name.
        family: String,
    },
    /// Forward kinematics failed.
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
    /// The cell's obstacles could not be used with the robot (an obstacle named after a link,
    /// or in the frame of a link it does not have).
    #[error(transparent)]
    Collision(#[from] crate::collision::CollisionError),
}

/// An axis-aligned box `[min, max]` (m), in the frame stated by whoever returns it.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Aabb {
    /// Smallest coordinates (m).
    pub min: [f64; 3],
    /// Largest coordinates (m).
    pub max: [f64; 3],
}

impl Aabb {
    /// The empty box (min = +inf, max = -inf).
    pub const EMPTY: Aabb = Aabb {
        min: [f64::INFINITY; 3],
        max: [f64::NEG_INFINITY; 3],
    };

    /// Grows the box to contain `p`.
    #[inline]
    pub fn extend(&mut self, p: [f64; 3]) {
        for ((lo, hi), v) in self.min.iter_mut().zip(self.max.iter_mut()).zip(p) {
            *lo = lo.min(v);
            *hi = hi.max(v);
        }
    }

    /// The smallest box containing both.
    pub fn union(mut self, other: Aabb) -> Aabb {
        self.extend(other.min);
        self.extend(other.max);
        self
    }

    /// True when no point has been added.
    pub fn is_empty(&self) -> bool {
        (0..3).any(|k| self.min[k] > self.max[k])
    }

    /// `max - min` per axis (m); zeros for an empty box.
    pub fn extent(&self) -> [f64; 3] {
        if self.is_empty() {
            return [0.0; 3];
        }
        [0, 1, 2].map(|k| self.max[k] - self.min[k])
    }
}

/// The plane of a planar arm: every end-effector position has the same z in the base frame.
///
/// Plane coordinates `(x, y)` are the base-frame x and y (m); the world point is
/// `world_from_base * (x, y, z)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarFrame {
    /// `world_from_base` of the robot.
    pub world_from_base: Pose,
    /// The constant base-frame z of the end-effector (m).
    pub z: f64,
}

impl PlanarFrame {
    /// Plane coordinates (m) of a world point (its base-frame x, y).
    #[inline]
    pub fn to_plane(&self, p: [f64; 3]) -> [f64; 2] {
        let l = self
            .world_from_base
            .inverse_transform_point(&Point3::new(p[0], p[1], p[2]));
        [l.x, l.y]
    }

    /// World point (m) of plane coordinates.
    #[inline]
    pub fn to_world(&self, xy: [f64; 2]) -> [f64; 3] {
        let w = self.world_from_base * Point3::new(xy[0], xy[1], self.z);
        [w.x, w.y, w.z]
    }

    /// The world position of the base origin (m).
    pub fn origin(&self) -> [f64; 3] {
        let t = self.world_from_base.translation.vector;
        [t.x, t.y, t.z]
    }
}

/// The plane of end-effector `ee` if the robot is planar: the base-frame z of the end-effector is
/// the same (within 1e-9 times the arm's size) at the zero configuration and at 16 pseudo-random
/// configurations inside the limits. `None` for spatial arms and for arms that move in another
/// plane (they are treated as spatial).
pub fn planar_frame(robot: &Robot, ee: usize) -> Option<PlanarFrame> {
    let base = robot.base;
    let z_of = |q: &[f64]| -> Option<Vector3<f64>> {
        let t = robot.fk_ee(q, ee).ok()?;
        Some(
            base.inverse_transform_point(&Point3::from(t.translation.vector))
                .coords,
        )
    };
    let limits = robot.sampling_ranges();
    let zero: Vec<f64> = limits.iter().map(|l| 0f64.clamp(l[0], l[1])).collect();
    let p0 = z_of(&zero)?;
    let mut rng = rng::Xoshiro256pp::stream(0x5EED, 0);
    let mut q = vec![0.0; robot.dof()];
    let mut pts = Vec::with_capacity(16);
    for _ in 0..16 {
        rng::uniform_q(&mut rng, &limits, &mut q);
        pts.push(z_of(&q)?);
    }
    let scale = pts
        .iter()
        .map(|p| (p - p0).norm())
        .fold(p0.norm(), f64::max)
        .max(1e-3);
    pts.iter()
        .all(|p| (p.z - p0.z).abs() <= 1e-9 * scale)
        .then_some(PlanarFrame {
            world_from_base: base,
            z: p0.z,
        })
}

/// Checks that end-effector `ee` exists.
pub(crate) fn check_ee(robot: &Robot, ee: usize) -> Result<(), WorkspaceError> {
    let count = robot.end_effectors().len();
    if ee < count {
        Ok(())
    } else {
        Err(WorkspaceError::NoSuchEndEffector { index: ee, count })
    }
}

/// Calls `progress` from the workers: a shared counter of finished items.
pub(crate) struct Progress<'a> {
    done: std::sync::atomic::AtomicUsize,
    f: &'a (dyn Fn(usize) + Sync),
}

impl<'a> Progress<'a> {
    pub(crate) fn new(f: &'a (dyn Fn(usize) + Sync)) -> Self {
        Self {
            done: std::sync::atomic::AtomicUsize::new(0),
            f,
        }
    }

    pub(crate) fn add(&self, n: usize) {
        let d = self.done.fetch_add(n, std::sync::atomic::Ordering::Relaxed) + n;
        (self.f)(d);
    }
}
