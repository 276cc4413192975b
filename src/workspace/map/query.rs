//! Point queries (`armlab reach`): whether a point is reached, with which postures, and its
//! distance to the workspace boundary.

use super::TrackedPoint;
use super::spatial::Section;
use crate::kinematics::Robot;
use crate::workspace::{ExactPlanar, WorkspaceError};

/// The answer for one point.
#[derive(Debug, Clone, PartialEq)]
pub struct ReachAnswer {
    /// Reached with some posture within the joint limits.
    pub reachable: bool,
    /// Names of the posture classes that reach it.
    pub postures: Vec<String>,
    /// Distance (m) to the workspace boundary: positive inside, negative outside.
    pub distance: f64,
}

enum Kind {
    Planar(Box<ExactPlanar>),
    Spatial(Box<Section>),
}

/// Answers point queries for one robot.
///
/// # Examples
///
/// Which postures reach a point, and how far it is from the workspace boundary (what
/// `armlab reach` prints). The two-link planar arm (a1 = a2 = 1 m, full ranges) reaches
/// (1, 1) m with both elbows, 2 - sqrt(2) m inside the circle of radius 2 m:
///
/// ```
/// use armlab::kinematics::models::built_in;
/// use armlab::workspace::{PointQuery, TrackedPoint};
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let arm = built_in("planar2").expect("a built-in model");
/// let query = PointQuery::new(&arm, TrackedPoint::Flange)?;
/// assert_eq!(query.dimension(), 2); // plane coordinates
/// let inside = query.query(&[1.0, 1.0]);
/// assert!(inside.reachable);
/// assert_eq!(inside.postures, ["elbow down", "elbow up"]);
/// assert!((inside.distance - (2.0 - 2f64.sqrt())).abs() < 1e-12);
/// let outside = query.query(&[3.0, 0.0]);
/// assert!(!outside.reachable && (outside.distance + 1.0).abs() < 1e-12);
/// # Ok(())
/// # }
/// ```
///
/// A spatial arm takes world points. The spherical arm of Fig. 2.22 (d2 = 0.5 m,
/// 0.25 <= d3 <= 1 m, (2.65)) reaches the points between the spheres of radii
/// sqrt(d2^2 + 0.25^2) and sqrt(d2^2 + 1) at least d2 from the z axis:
///
/// ```
/// use armlab::kinematics::models::built_in;
/// use armlab::workspace::{PointQuery, TrackedPoint};
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let arm = built_in("spherical_arm").expect("a built-in model");
/// let query = PointQuery::new(&arm, TrackedPoint::Flange)?;
/// assert_eq!(query.dimension(), 3);
/// let a = query.query(&[0.8, 0.0, 0.0]);
/// assert!(a.reachable);
/// // The nearest boundary is the inner sphere.
/// let inner = (0.5f64.powi(2) + 0.25f64.powi(2)).sqrt();
/// assert!((a.distance - (0.8 - inner)).abs() < 1e-6, "{}", a.distance);
/// assert!(!query.query(&[0.0, 0.0, 0.8]).reachable); // on the z axis: closer than d2
/// // An arm without the structure for exact queries is an error that says why.
/// let lwr = built_in("lwr4").expect("a built-in model");
/// assert!(PointQuery::new(&lwr, TrackedPoint::Flange).is_err());
/// # Ok(())
/// # }
/// ```
pub struct PointQuery {
    kind: Kind,
    scale: f64,
}

/// Directions of the distance search of spatial arms: the 26 neighbours of a cube's centre.
fn directions() -> Vec<[f64; 3]> {
    let mut out = Vec::new();
    for i in -1i32..=1 {
        for j in -1i32..=1 {
            for k in -1i32..=1 {
                if (i, j, k) != (0, 0, 0) {
                    let n = f64::from(i * i + j * j + k * k).sqrt();
                    out.push([f64::from(i) / n, f64::from(j) / n, f64::from(k) / n]);
                }
            }
        }
    }
    out
}

impl PointQuery {
    /// The query of a two- or three-link planar arm (exact), or of an arm with a closed-form
    /// positioning arm (`point` chooses wrist centre or flange). Other arms: an error saying why.
    pub fn new(robot: &Robot, point: TrackedPoint) -> Result<Self, WorkspaceError> {
        let scale = robot.characteristic_length();
        match ExactPlanar::new(robot) {
            Ok(e) => Ok(Self {
                kind: Kind::Planar(Box::new(e)),
                scale,
            }),
            Err(planar) => match Section::new(robot, point) {
                Some(s) => Ok(Self {
                    kind: Kind::Spatial(Box::new(s)),
                    scale,
                }),
                None => Err(WorkspaceError::NotPlanar {
                    robot: robot.name.clone(),
                    reason: format!(
                        "has neither a two- or three-link planar arm nor a closed-form \
                         positioning arm whose joint 1 turns about the base z axis, which point \
                         queries need ({planar})"
                    ),
                }),
            },
        }
    }

    /// Coordinates per point: 2 (plane x, y: the base frame's) for planar arms, 3 (world x, y, z)
    /// otherwise.
    pub fn dimension(&self) -> usize {
        match self.kind {
            Kind::Planar(_) => 2,
            Kind::Spatial(_) => 3,
        }
    }

    /// Whether the distances are exact (planar arms) or estimated (spatial arms: the nearest
    /// membership change along 26 directions, found by bisection to 1e-9 m).
    pub fn distance_exact(&self) -> bool {
        matches!(self.kind, Kind::Planar(_))
    }

    fn names(&self, mask: u8) -> Vec<String> {
        let names = match &self.kind {
            Kind::Planar(e) => e.class_names(),
            Kind::Spatial(s) => s.class_names(),
        };
        names
            .iter()
            .enumerate()
            .filter(|(k, _)| mask >> k & 1 == 1)
            .map(|(_, n)| n.clone())
            .collect()
    }

    fn spatial_mask(s: &Section, p: [f64; 3]) -> u8 {
        s.point_mask(p)
    }

    /// Answers for one point (`dimension()` coordinates, m; plane or world frame).
    pub fn query(&self, p: &[f64]) -> ReachAnswer {
        match &self.kind {
            Kind::Planar(e) => {
                let xy = [p[0], p[1]];
                let mask = e.mask(xy);
                ReachAnswer {
                    reachable: mask != 0,
                    postures: self.names(mask),
                    distance: e.signed_distance(xy),
                }
            }
            Kind::Spatial(s) => {
                let q = [p[0], p[1], p[2]];
                let mask = Self::spatial_mask(s, q);
                let inside = mask != 0;
                let d = directions()
                    .iter()
                    .map(|u| self.first_change(s, q, *u, inside))
                    .fold(f64::INFINITY, f64::min);
                ReachAnswer {
                    reachable: inside,
                    postures: self.names(mask),
                    distance: if inside { d } else { -d },
                }
            }
        }
    }

    /// Distance along `u` to the first change of membership (steps of 1/64 of the arm's size,
    /// then bisection), or the arm's size if none.
    fn first_change(&self, s: &Section, p: [f64; 3], u: [f64; 3], inside: bool) -> f64 {
        let at = |t: f64| [p[0] + t * u[0], p[1] + t * u[1], p[2] + t * u[2]];
        let step = self.scale / 64.0;
        let mut lo = 0.0;
        for k in 1..=128 {
            let t = k as f64 * step;
            if (Self::spatial_mask(s, at(t)) != 0) != inside {
                let mut hi = t;
                while hi - lo > 1e-9 {
                    let m = 0.5 * (lo + hi);
                    if (Self::spatial_mask(s, at(m)) != 0) == inside {
                        lo = m;
                    } else {
                        hi = m;
                    }
                }
                return 0.5 * (lo + hi);
            }
            lo = t;
        }
        2.0 * self.scale
    }
}

impl Section {
    /// Class mask of a world point (m): the postures reaching its (r, z) in the base frame whose
    /// joint 1 fits its azimuth.
    pub fn point_mask(&self, p: [f64; 3]) -> u8 {
        let l = self.base_from_world(p);
        self.mask_at(l[0].hypot(l[1]), l[2], l[1].atan2(l[0]))
    }
}
