//! Workspace statistics (Sect. 2.10.1): area (planar arms, m^2) or volume (m^3), the measures of
//! the posture regions (Fig. 2.30: elbow-down only, elbow-up only, both), bounding box and reach.

use super::grid::{GridMethod, GridOptions, analyze_grid};
use super::planar::{BoundaryOptions, planar_boundary};
use super::reach::ReachTester;
use super::sample::{SampleOptions, sample};
use super::{Aabb, WorkspaceError};
use crate::kinematics::Robot;

/// Options of [`statistics`].
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StatsOptions {
    /// The grid of the area or volume and of the posture regions.
    pub grid: GridOptions,
    /// Samples for the bounding box and the reach of arms without an exact planar boundary.
    pub samples: usize,
    /// Polyline resolution of the exact planar boundary.
    pub boundary: BoundaryOptions,
}

impl Default for StatsOptions {
    /// Default grid (128 cells per axis), 200 000 samples, default boundary.
    fn default() -> Self {
        Self {
            grid: GridOptions::default(),
            samples: 200_000,
            boundary: BoundaryOptions::default(),
        }
    }
}

/// Measures of one posture class.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ClassMeasure {
    /// Class name, e.g. "elbow down".
    pub name: String,
    /// Area (m^2) or volume (m^3) reached with this class.
    pub with: f64,
    /// Area or volume reached with this class and no other.
    pub only: f64,
}

/// Summary of a workspace.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[must_use]
pub struct WorkspaceStats {
    /// Whether the arm is planar (then areas, else volumes).
    pub planar: bool,
    /// Reachable area (m^2), planar arms.
    pub area: Option<f64>,
    /// Area reached with both postures (m^2), planar arms with two classes (region BADHB of Fig.
    /// 2.30).
    pub area_both_postures: Option<f64>,
    /// Reachable volume (m^3), spatial arms.
    pub volume: Option<f64>,
    /// Area or volume reached with every class.
    pub measure_all_classes: f64,
    /// Per class: with it, and with it only.
    pub classes: Vec<ClassMeasure>,
    /// Area or volume of the dexterous cells (at least half of the orientations reached).
    pub dexterous_measure: f64,
    /// Bounding box of the reachable positions (world frame, m).
    pub bounds: Aabb,
    /// Smallest distance (m) from the base origin to a reachable position.
    pub min_reach: f64,
    /// Largest distance (m) from the base origin to a reachable position.
    pub max_reach: f64,
    /// True when bounds and reach come from the exact planar boundary, false when from samples
    /// (then the maximum is a lower bound and the minimum an upper bound).
    pub reach_exact: bool,
    /// Cell size of the grid (m; z = 0 for planar arms).
    pub cell_size: [f64; 3],
    /// Cells per axis.
    pub resolution: usize,
    /// Samples used for bounds and reach (0 when exact).
    pub samples: usize,
    /// How the grid was computed.
    pub method: GridMethod,
    /// How the area or volume was computed, in words (e.g. "exact: Green's theorem over the
    /// boundary arcs").
    pub measure_method: String,
    /// Estimated error of the area or volume (m^2 or m^3), when the method gives one.
    pub measure_error: Option<f64>,
}

/// Computes the statistics: the grid of [`analyze_grid`] for the measures, the exact boundary
/// ([`planar_boundary`]) for the bounds and reach of two- and three-link planar arms, and
/// `opts.samples` samples for the other arms. `progress` reports the grid's progress.
///
/// # Examples
///
/// The two-link planar arm with full joint ranges reaches the disc of radius a1 + a2 = 2 m,
/// area 4 pi m^2; a coarse grid (48 x 48 cells) estimates it within a few per cent, the reach
/// comes from the exact boundary.
///
/// ```
/// use armlab::kinematics::models::built_in;
/// use armlab::workspace::{GridOptions, StatsOptions, statistics};
/// use std::f64::consts::PI;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let arm = built_in("planar2").expect("a built-in model");
/// let opts = StatsOptions {
///     grid: GridOptions { resolution: 48, ..GridOptions::default() },
///     ..StatsOptions::default()
/// };
/// let stats = statistics(&arm, &opts, &|_| {})?;
/// assert!(stats.planar);
/// let area = stats.area.expect("a planar arm has an area");
/// assert!((area - 4.0 * PI).abs() < 0.05 * 4.0 * PI, "area {area}");
/// assert!(stats.reach_exact && (stats.max_reach - 2.0).abs() < 1e-9);
/// # Ok(())
/// # }
/// ```
pub fn statistics(
    robot: &Robot,
    opts: &StatsOptions,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<WorkspaceStats, WorkspaceError> {
    let grid = analyze_grid(robot, &opts.grid, progress)?;
    let planar = grid.grid.planar;
    let exact = if opts.grid.end_effector == 0 {
        planar_boundary(robot, &opts.boundary).ok()
    } else {
        None
    };
    let base = robot.base.translation.vector;
    let origin = [base.x, base.y, base.z];
    let (bounds, reach, samples) = match &exact {
        Some(b) => {
            let mut bounds = Aabb::EMPTY;
            for p in b.curves.iter().flat_map(|c| &c.points) {
                bounds.extend(b.frame.to_world(*p));
            }
            let mut reach = b.curve_reach();
            let tester = ReachTester::new(robot, opts.grid.orientations);
            if tester.is_some_and(|t| t.test_plane([0.0, 0.0]).mask != 0) {
                reach[0] = b.frame.z.abs();
            }
            (bounds, reach, 0)
        }
        None => {
            let s = sample(
                robot,
                &SampleOptions {
                    samples: opts.samples,
                    seed: opts.grid.seed,
                    end_effector: opts.grid.end_effector,
                    classes: false,
                    manipulability: false,
                    keep_joints: false,
                },
                &|_| {},
            )?;
            (s.bounds(), s.reach_range(origin), opts.samples)
        }
    };
    let classes = grid
        .class_names
        .iter()
        .enumerate()
        .map(|(k, name)| ClassMeasure {
            name: name.clone(),
            with: grid.class_measure(k as u8),
            only: grid.class_only_measure(k as u8),
        })
        .collect();
    let total = grid.reachable_measure();
    let all = grid.all_classes_measure();
    Ok(WorkspaceStats {
        planar,
        area: planar.then_some(total),
        area_both_postures: (planar && grid.class_names.len() == 2).then_some(all),
        volume: (!planar).then_some(total),
        measure_all_classes: all,
        classes,
        dexterous_measure: grid.dexterous(0.5).measure,
        bounds,
        min_reach: reach[0],
        max_reach: reach[1],
        reach_exact: exact.is_some(),
        cell_size: grid.grid.cell_size(),
        resolution: opts.grid.resolution,
        samples,
        measure_method: method_words(&grid.method, opts.grid.resolution),
        method: grid.method,
        measure_error: None,
    })
}

/// How a grid measure was computed, in words.
fn method_words(method: &GridMethod, resolution: usize) -> String {
    match method {
        GridMethod::ClosedForm { .. } => {
            format!("closed-form IK at the centres of a {resolution} grid")
        }
        GridMethod::Sampling { samples } => {
            format!("occupancy of {samples} joint-space samples on a {resolution} grid")
        }
    }
}
