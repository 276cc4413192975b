//! Workspace regions on a grid: which postures reach each cell (planar arms, plane coordinates,
//! m^2) or voxel (spatial arms, world frame, m^3), and the dexterous workspace (the fraction of
//! quantised orientations reached in each cell).
//!
//! With a closed form ([`ReachTester`]) a cell counts as reached with posture P when the P solution
//! for its centre exists and lies within the joint limits (Sect. 2.10.1 with the IK of Sect.
//! 2.12): exact at the centre, so the only error comes from the cells cut by the boundary, whose
//! centres fall on either side about equally often (well under perimeter x cell size). Without a closed form (or with [`MethodChoice::Sampling`]) a cell counts as reached
//! when a sample of [`super::sample()`]'s generator falls in it, which overestimates by up to a cell
//! along the boundary and underestimates where samples are sparse.
//!
//! The orientations are counted in the bins of [`super::reach`]: the angle phi in the plane for
//! planar arms, the approach direction a_e for spatial arms.

use super::posture::PostureClassifier;
use super::reach::{ORIENTATION_BINS, ReachTester, orientation_bin_of};
use super::rng::{Xoshiro256pp, uniform_q};
use super::sample::SAMPLE_CHUNK;
use super::{
    Aabb, PlanarFrame, Progress, WorkspaceError, check_ee, planar::BoundaryOptions,
    planar::planar_boundary, planar_frame,
};
use crate::kinematics::Robot;
use rayon::prelude::*;

/// How [`analyze_grid`] decides reachability.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub enum MethodChoice {
    /// The closed form when the arm has one that [`ReachTester`] supports, else sampling.
    #[default]
    Auto,
    /// Always by sampling.
    Sampling,
}

/// How a [`GridAnalysis`] was computed.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum GridMethod {
    /// Closed-form IK at every cell centre.
    ClosedForm {
        /// Name of the closed-form family.
        family: std::borrow::Cow<'static, str>,
        /// Orientations tried per cell (1 for position-only arms, which report the distinct
        /// orientation bins of their solutions instead).
        orientations: usize,
    },
    /// Occupancy of the samples.
    Sampling {
        /// Number of samples.
        samples: usize,
    },
}

/// Options of [`analyze_grid`].
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct GridOptions {
    /// Cells per axis (N x N for planar arms, N x N x N voxels for spatial arms).
    pub resolution: usize,
    /// Angles phi tried per cell for a three-link planar arm (the redundant position task is
    /// solved at each); ignored otherwise.
    pub orientations: usize,
    /// Samples: the bounding box pass of a spatial closed-form grid, or the whole sampling method.
    pub samples: usize,
    /// Seed of the sampler.
    pub seed: u64,
    /// Closed form or sampling.
    pub method: MethodChoice,
    /// End-effector index (closed forms only for end-effector 0 of single-tool robots).
    pub end_effector: usize,
}

impl Default for GridOptions {
    /// 128 cells per axis, 64 orientations, 200 000 samples, seed 1, automatic method, tool 0.
    fn default() -> Self {
        Self {
            resolution: 128,
            orientations: 64,
            samples: 200_000,
            seed: 1,
            method: MethodChoice::Auto,
            end_effector: 0,
        }
    }
}

/// A regular grid over a box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridSpec {
    /// Planar grid in plane coordinates (then `n[2] = 1` and z is unused), or a voxel grid in the
    /// world frame.
    pub planar: bool,
    /// Lower corner (m).
    pub min: [f64; 3],
    /// Upper corner (m).
    pub max: [f64; 3],
    /// Cells per axis; cell `(i, j, k)` has index `i + n[0] * (j + n[1] * k)`.
    pub n: [usize; 3],
}

impl GridSpec {
    /// Number of cells.
    pub fn len(&self) -> usize {
        self.n[0] * self.n[1] * self.n[2]
    }

    /// True for a grid without cells.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Cell size per axis (m); z is 0 for a planar grid.
    pub fn cell_size(&self) -> [f64; 3] {
        let mut s = [0, 1, 2].map(|k| (self.max[k] - self.min[k]) / self.n[k] as f64);
        if self.planar {
            s[2] = 0.0;
        }
        s
    }

    /// Area (m^2, planar) or volume (m^3) of one cell.
    pub fn cell_measure(&self) -> f64 {
        let s = self.cell_size();
        if self.planar {
            s[0] * s[1]
        } else {
            s[0] * s[1] * s[2]
        }
    }

    /// Centre of cell `i` (plane coordinates with z = 0, or world frame; m).
    pub fn centre(&self, i: usize) -> [f64; 3] {
        let c = [
            i % self.n[0],
            (i / self.n[0]) % self.n[1],
            i / (self.n[0] * self.n[1]),
        ];
        let s = self.cell_size();
        let mut p = [0, 1, 2].map(|k| self.min[k] + (c[k] as f64 + 0.5) * s[k]);
        if self.planar {
            p[2] = 0.0;
        }
        p
    }

    /// Index of the cell containing `p` (same coordinates as [`GridSpec::centre`]).
    pub fn index_of(&self, p: [f64; 3]) -> Option<usize> {
        let axes = if self.planar { 2 } else { 3 };
        let mut c = [0usize; 3];
        for k in 0..axes {
            let t = (p[k] - self.min[k]) / (self.max[k] - self.min[k]) * self.n[k] as f64;
            if !(t >= 0.0 && t <= self.n[k] as f64) {
                return None;
            }
            c[k] = (t as usize).min(self.n[k] - 1);
        }
        Some(c[0] + self.n[0] * (c[1] + self.n[1] * c[2]))
    }
}

/// The cells reached by each posture class, and the orientation coverage of each cell.
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct GridAnalysis {
    /// The grid (plane coordinates for a planar arm, else world frame).
    pub grid: GridSpec,
    /// The plane of a planar arm.
    pub frame: Option<PlanarFrame>,
    /// Names of the posture classes (bits of `masks`).
    pub class_names: Vec<String>,
    /// Per cell, bit k set when class k reaches it; 0 = unreachable.
    pub masks: Vec<u8>,
    /// Per cell, the fraction of orientations reached (0 to 1): the dexterity.
    pub orientation_fraction: Vec<f32>,
    /// How it was computed.
    pub method: GridMethod,
}

/// Cells reached with at least a given fraction of the orientations (the dexterous workspace),
/// kept apart from the reachable set.
#[derive(Debug, Clone, PartialEq)]
pub struct DexterousSet {
    /// The fraction used.
    pub threshold: f32,
    /// Cell indices.
    pub cells: Vec<usize>,
    /// Cell centres (world frame, m).
    pub centres: Vec<[f64; 3]>,
    /// Their area (m^2, planar) or volume (m^3).
    pub measure: f64,
}

impl GridAnalysis {
    fn count(&self, f: impl Fn(u8) -> bool) -> f64 {
        self.masks.iter().filter(|&&m| f(m)).count() as f64 * self.grid.cell_measure()
    }

    /// Area (m^2, planar) or volume (m^3) of the reachable cells.
    pub fn reachable_measure(&self) -> f64 {
        self.count(|m| m != 0)
    }

    /// Measure of the cells reached with class `class`.
    pub fn class_measure(&self, class: u8) -> f64 {
        self.count(|m| m >> class & 1 == 1)
    }

    /// Measure of the cells reached with class `class` and no other (e.g. elbow-up only).
    pub fn class_only_measure(&self, class: u8) -> f64 {
        self.count(|m| m == 1 << class)
    }

    /// Measure of the cells reached with every class ("both postures" for two classes).
    pub fn all_classes_measure(&self) -> f64 {
        let full = ((1u16 << self.class_names.len()) - 1) as u8;
        self.count(|m| m == full)
    }

    /// World position (m) of a cell centre.
    pub fn world_centre(&self, i: usize) -> [f64; 3] {
        let c = self.grid.centre(i);
        match (&self.frame, self.grid.planar) {
            (Some(f), true) => f.to_world([c[0], c[1]]),
            _ => c,
        }
    }

    /// The cells reached with at least `threshold` of the orientations.
    pub fn dexterous(&self, threshold: f32) -> DexterousSet {
        let cells: Vec<usize> = (0..self.masks.len())
            .filter(|&i| self.masks[i] != 0 && self.orientation_fraction[i] >= threshold)
            .collect();
        DexterousSet {
            threshold,
            centres: cells.iter().map(|&i| self.world_centre(i)).collect(),
            measure: cells.len() as f64 * self.grid.cell_measure(),
            cells,
        }
    }
}

/// Classifies the cells of a grid over the workspace (see the module documentation).
///
/// Planar arms ([`planar_frame`]) get an N x N grid in plane coordinates over the bounding box of
/// the exact boundary ([`planar_boundary`], closed form) or of the samples; spatial arms an
/// N x N x N voxel grid over the samples' bounding box grown by 5 % per side. `progress` is
/// called with the number of cells (closed form) or samples (sampling) done.
pub fn analyze_grid(
    robot: &Robot,
    opts: &GridOptions,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<GridAnalysis, WorkspaceError> {
    let ee = opts.end_effector;
    check_ee(robot, ee)?;
    if opts.resolution == 0 || opts.resolution > 4096 {
        return Err(WorkspaceError::InvalidOption {
            option: "grid resolution",
            value: opts.resolution.to_string(),
            expected: "must be 1 to 4096",
        });
    }
    let frame = planar_frame(robot, ee);
    let tester = if opts.method == MethodChoice::Auto && ee == 0 {
        ReachTester::new(robot, opts.orientations)
    } else {
        None
    };
    let Some(tester) = tester else {
        return sampling_grid(robot, opts, frame, progress);
    };
    if opts.samples == 0 && tester.frame().is_none() {
        return Err(WorkspaceError::InvalidOption {
            option: "samples",
            value: opts.samples.to_string(),
            expected: "a spatial grid needs samples for its bounding box",
        });
    }
    let grid = closed_form_grid_spec(robot, opts, &tester)?;
    let (masks, frac) = test_cells(&grid, &tester, progress);
    Ok(GridAnalysis {
        grid,
        frame: tester.frame().copied(),
        class_names: tester.class_names().to_vec(),
        masks,
        orientation_fraction: frac,
        method: GridMethod::ClosedForm {
            family: tester.family().into(),
            orientations: tester.orientations(),
        },
    })
}

/// The closed-form method's grid: N x N in plane coordinates over the exact boundary's bounding
/// box (planar arms), else N x N x N voxels over the samples' bounding box grown by 5 % per side.
fn closed_form_grid_spec(
    robot: &Robot,
    opts: &GridOptions,
    tester: &ReachTester,
) -> Result<GridSpec, WorkspaceError> {
    let n = opts.resolution;
    Ok(match tester.frame() {
        Some(_) => {
            let b = planar_boundary(robot, &BoundaryOptions::default())?.bounds();
            let pad = 1e-6 * b.extent()[0].max(b.extent()[1]).max(1e-3);
            GridSpec {
                planar: true,
                min: [b.min[0] - pad, b.min[1] - pad, 0.0],
                max: [b.max[0] + pad, b.max[1] + pad, 0.0],
                n: [n, n, 1],
            }
        }
        None => {
            let b = sampled_bounds(robot, opts.end_effector, opts.samples, opts.seed, None)?;
            voxel_grid(b, n, 0.05)
        }
    })
}

/// Tests every cell centre with the closed form, one grid row per task: the posture mask and the
/// fraction of orientations reached, per cell.
fn test_cells(
    grid: &GridSpec,
    tester: &ReachTester,
    progress: &(dyn Fn(usize) + Sync),
) -> (Vec<u8>, Vec<f32>) {
    let mut masks = vec![0u8; grid.len()];
    let mut frac = vec![0f32; grid.len()];
    let row = grid.n[0];
    let prog = Progress::new(progress);
    masks
        .par_chunks_mut(row)
        .zip(frac.par_chunks_mut(row))
        .enumerate()
        .for_each(|(r, (m, f))| {
            for i in 0..m.len() {
                let c = grid.centre(r * row + i);
                let reach = if grid.planar {
                    tester.test_plane([c[0], c[1]])
                } else {
                    tester.test_world(c)
                };
                m[i] = reach.mask;
                f[i] = if reach.tried > 0 {
                    reach.reached as f32 / reach.tried as f32
                } else {
                    0.0
                };
            }
            prog.add(m.len());
        });
    (masks, frac)
}

/// A voxel grid over `b` grown by `grow` of the largest extent on every side.
fn voxel_grid(b: Aabb, n: usize, grow: f64) -> GridSpec {
    let e = b.extent();
    let pad = grow * e[0].max(e[1]).max(e[2]).max(1e-3);
    GridSpec {
        planar: false,
        min: [0, 1, 2].map(|k| b.min[k] - pad),
        max: [0, 1, 2].map(|k| b.max[k] + pad),
        n: [n, n, n],
    }
}

/// Bounding box of the sampled positions (world frame, or plane coordinates with z = 0).
fn sampled_bounds(
    robot: &Robot,
    ee: usize,
    samples: usize,
    seed: u64,
    frame: Option<&PlanarFrame>,
) -> Result<Aabb, WorkspaceError> {
    let limits = robot.sampling_ranges();
    (0..samples.div_ceil(SAMPLE_CHUNK))
        .into_par_iter()
        .map(|c| {
            let mut rng = Xoshiro256pp::stream(seed, c as u64);
            let mut q = vec![0.0; robot.dof()];
            let mut b = Aabb::EMPTY;
            for _ in 0..chunk_len(c, samples) {
                uniform_q(&mut rng, &limits, &mut q);
                let p = robot.fk_ee(&q, ee)?.translation.vector;
                b.extend(match frame {
                    Some(f) => {
                        let xy = f.to_plane([p.x, p.y, p.z]);
                        [xy[0], xy[1], 0.0]
                    }
                    None => [p.x, p.y, p.z],
                });
            }
            Ok(b)
        })
        .try_reduce(|| Aabb::EMPTY, |a, b| Ok(a.union(b)))
}

fn chunk_len(c: usize, samples: usize) -> usize {
    SAMPLE_CHUNK.min(samples - c * SAMPLE_CHUNK)
}

/// The sampling method: two passes over the same samples (bounding box, then occupancy).
fn sampling_grid(
    robot: &Robot,
    opts: &GridOptions,
    frame: Option<PlanarFrame>,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<GridAnalysis, WorkspaceError> {
    let (ee, n, samples) = (opts.end_effector, opts.resolution, opts.samples);
    if samples == 0 {
        return Err(WorkspaceError::InvalidOption {
            option: "samples",
            value: opts.samples.to_string(),
            expected: "the sampling method needs at least one sample",
        });
    }
    let b = sampled_bounds(robot, ee, samples, opts.seed, frame.as_ref())?;
    let grid = match frame {
        Some(_) => {
            let e = b.extent();
            let pad = 1e-9 * e[0].max(e[1]).max(1e-3);
            GridSpec {
                planar: true,
                min: [b.min[0] - pad, b.min[1] - pad, 0.0],
                max: [b.max[0] + pad, b.max[1] + pad, 0.0],
                n: [n, n, 1],
            }
        }
        None => voxel_grid(b, n, 1e-9),
    };
    let classifier = PostureClassifier::for_end_effector(robot, ee);
    let (bins, masks) = bin_samples(robot, opts, &grid, frame.as_ref(), &classifier, progress)?;
    Ok(GridAnalysis {
        grid,
        frame,
        class_names: classifier.class_names().to_vec(),
        masks,
        orientation_fraction: bins
            .iter()
            .map(|b| b.count_ones() as f32 / ORIENTATION_BINS as f32)
            .collect(),
        method: GridMethod::Sampling { samples },
    })
}

/// The sampling method's second pass: per cell, the orientation bins and the posture classes of
/// the samples that fall in it (a degenerate posture marks every class).
fn bin_samples(
    robot: &Robot,
    opts: &GridOptions,
    grid: &GridSpec,
    frame: Option<&PlanarFrame>,
    classifier: &PostureClassifier,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<(Vec<u64>, Vec<u8>), WorkspaceError> {
    let (ee, samples) = (opts.end_effector, opts.samples);
    let limits = robot.sampling_ranges();
    let prog = Progress::new(progress);
    let cells = grid.len();
    let all = ((1u16 << classifier.class_count()) - 1) as u8;
    let chunks = samples.div_ceil(SAMPLE_CHUNK);
    // Few accumulators (each holds the whole grid); OR-merging makes the result independent of
    // how the chunks are split.
    let min_len = (chunks / (4 * rayon::current_num_threads())).max(1);
    (0..chunks)
        .into_par_iter()
        .with_min_len(min_len)
        .try_fold(
            || (vec![0u64; cells], vec![0u8; cells]),
            |(mut bins, mut masks), c| {
                let mut rng = Xoshiro256pp::stream(opts.seed, c as u64);
                let mut q = vec![0.0; robot.dof()];
                let len = chunk_len(c, samples);
                for _ in 0..len {
                    uniform_q(&mut rng, &limits, &mut q);
                    let t = robot.fk_ee(&q, ee)?;
                    let p = t.translation.vector;
                    let key = match frame {
                        Some(f) => {
                            let xy = f.to_plane([p.x, p.y, p.z]);
                            [xy[0], xy[1], 0.0]
                        }
                        None => [p.x, p.y, p.z],
                    };
                    if let Some(i) = grid.index_of(key) {
                        bins[i] |= 1 << orientation_bin_of(&t, frame);
                        let class = classifier.classify(&q, &t);
                        // A degenerate posture borders every class.
                        masks[i] |= if class < 8 { 1 << class } else { all };
                    }
                }
                prog.add(len);
                Ok::<_, WorkspaceError>((bins, masks))
            },
        )
        .try_reduce(
            || (vec![0u64; cells], vec![0u8; cells]),
            |(mut b1, mut m1), (b2, m2)| {
                b1.iter_mut().zip(&b2).for_each(|(a, b)| *a |= b);
                m1.iter_mut().zip(&m2).for_each(|(a, b)| *a |= b);
                Ok((b1, m1))
            },
        )
}
