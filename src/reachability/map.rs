//! The six-dimensional reachability map: for every voxel centre of a grid over the arm's reach,
//! every approach direction of a Fibonacci sphere and every roll about it
//! ([`super::sampling`]), whether some IK solution within the joint limits (and, with a cell,
//! free of collision) puts the tool there, and which postures do.
//!
//! Arms with a closed form ([`ClosedForm`]) are solved exactly at every sample: all solutions,
//! each wrapped into the joint limits and kept if it is within them. Others (redundant arms,
//! chains without a closed form, end-effectors other than the first) use the numerical solver
//! from several seeds at each sample; [`MapSolver`] says which, and a sample the numerical solver
//! misses may still be reachable.
//!
//! The grid covers the arm's reach: the box of the tool points of 20,000 random configurations
//! widened by a margin, and every voxel farther from the box's middle than the reach (the farthest of
//! those points, refined by coordinate ascent, plus the margin) is skipped. The computation then
//! checks its own bound: when a reached sample lies within two voxels of the skipped shell or on
//! the grid's outer layer, the bound was too tight and the map is computed again with a doubled
//! margin (so nothing is lost to the bound).

use super::sampling::{VoxelGrid, fibonacci_directions, roll_angles, sample_rotation};
use crate::collision::CollisionWorld;
use crate::kinematics::ik::Target;
use crate::kinematics::ik::closed_form::{
    ClosedForm, Elbow, Extension, LIMIT_TOL, MAX_DOF, MAX_SOLUTIONS, Posture, RawSolutions,
    Shoulder, WristFlip, wrap_into_limits,
};
use crate::kinematics::ik::numerical::{self, NumericalOptions};
use crate::kinematics::{JointKind, Pose, Robot};
use crate::workspace::rng::Xoshiro256pp;
use crate::workspace::{PostureClassifier, UNCLASSIFIED};
use nalgebra::{Rotation3, Translation3, Vector3};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use thiserror::Error;

/// Most samples (voxels x directions x rolls) computed without [`MapOptions::force`].
pub const MAX_SAMPLES: u64 = 1_000_000_000;

/// Position tolerance of the numerical solver's samples (m); the orientation tolerance is the
/// same number in rad.
pub const NUMERICAL_TOLERANCE: f64 = 1e-9;

/// Bad input to a map, found before any work.
#[derive(Debug, Error, PartialEq)]
pub enum ReachabilityError {
    /// The voxel edge is zero, negative or not finite.
    #[error("the voxel edge must be a positive length in metres, got {voxel_m}")]
    BadVoxel {
        /// The edge given (m).
        voxel_m: f64,
    },
    /// No approach direction.
    #[error("the number of directions must be at least 1, got {directions}")]
    NoDirections {
        /// The count given.
        directions: usize,
    },
    /// No roll.
    #[error("the number of rolls must be at least 1, got {rolls}")]
    NoRolls {
        /// The count given.
        rolls: usize,
    },
    /// Too many samples without `force`.
    #[error(
        "{samples} samples ({voxels} voxels x {per_voxel} orientations) is over the limit of \
         {limit}: use a larger voxel, fewer directions or rolls, or force it"
    )]
    TooManySamples {
        /// Samples the map would have.
        samples: u64,
        /// Voxels of the grid.
        voxels: u64,
        /// Directions x rolls.
        per_voxel: u64,
        /// The limit ([`MAX_SAMPLES`]).
        limit: u64,
    },
    /// No such end-effector.
    #[error("end-effector {ee} does not exist (the robot has {count})")]
    NoEndEffector {
        /// The index asked for.
        ee: usize,
        /// End-effectors of the robot.
        count: usize,
    },
    /// The robot has no joint.
    #[error("the robot has no joint: nothing to map")]
    NoJoints,
    /// Stopped by the caller (Ctrl+C) before the end.
    #[error("stopped after {done} of {total} voxels")]
    Cancelled {
        /// Voxels finished.
        done: usize,
        /// Voxels in all.
        total: usize,
    },
}

/// How a map is sampled. Units: m, counts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapOptions {
    /// End-effector index (0: the first).
    pub ee: usize,
    /// Voxel edge (m).
    pub voxel_m: f64,
    /// Approach directions N of the Fibonacci sphere.
    pub directions: usize,
    /// Rolls R about each direction.
    pub rolls: usize,
    /// Compute even above [`MAX_SAMPLES`].
    pub force: bool,
    /// Seeds of the numerical solver per sample, for arms without a closed form.
    pub seeds: usize,
}

impl Default for MapOptions {
    /// The issue's defaults: 5 cm voxels, 200 directions, 8 rolls, end-effector 0, 4 seeds.
    fn default() -> Self {
        Self {
            ee: 0,
            voxel_m: 0.05,
            directions: 200,
            rolls: 8,
            force: false,
            seeds: 4,
        }
    }
}

/// Which solver decided the samples.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum MapSolver {
    /// Every solution in closed form: exact at every sample.
    ClosedForm {
        /// The closed-form family ("anthropomorphic arm with spherical wrist").
        family: String,
    },
    /// The numerical solver from several seeds: a sample it misses may be reachable.
    Numerical {
        /// Seeds tried per sample.
        seeds: usize,
        /// Position tolerance (m) and orientation tolerance (rad).
        tolerance: f64,
    },
    /// A map read from a file: the solver as the file describes it.
    Read {
        /// The file's description ([`MapSolver::describe`] of the map written).
        description: String,
    },
}

impl MapSolver {
    /// One line for files and reports: "closed form (anthropomorphic arm with spherical
    /// wrist)", "numerical, 4 seeds per sample, tolerance 1e-9 m and rad".
    pub fn describe(&self) -> String {
        match self {
            MapSolver::ClosedForm { family } => format!("closed form ({family})"),
            MapSolver::Numerical { seeds, tolerance } => format!(
                "numerical, {seeds} seeds per sample, tolerance {tolerance:e} m and rad (a \
                 sample it misses may be reachable)"
            ),
            MapSolver::Read { description } => description.clone(),
        }
    }
}

/// Start and progress of a map computation: a flag that stops it (Ctrl+C) and a callback told
/// of every voxel finished.
#[derive(Default, Clone, Copy)]
pub struct MapControl<'a> {
    /// Set to stop: the computation returns [`ReachabilityError::Cancelled`] soon after.
    pub cancel: Option<&'a AtomicBool>,
    /// Called with (voxels done, voxels in all), from any thread.
    pub progress: Option<&'a (dyn Fn(usize, usize) + Sync)>,
}

impl std::fmt::Debug for MapControl<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MapControl")
            .field("cancel", &self.cancel)
            .field("progress", &self.progress.is_some())
            .finish()
    }
}

/// A reachability map (see the module documentation). Sample arrays are flat in C order over
/// (nx, ny, nz, N, R): sample (i, j, k, d, r) is at
/// `((flat(i, j, k) * N) + d) * R + r`.
#[derive(Debug, Clone, PartialEq)]
pub struct ReachabilityMap {
    /// The voxel grid (m, world frame).
    pub grid: VoxelGrid,
    /// The approach directions (unit, world frame).
    pub directions: Vec<[f64; 3]>,
    /// The rolls about each direction (rad).
    pub rolls: Vec<f64>,
    /// Whether some solution reaches each sample.
    pub reachable: Vec<bool>,
    /// Bit p set when posture `posture_names[p]` reaches the sample.
    pub postures: Vec<u16>,
    /// Names of the posture bits, in the family's order.
    pub posture_names: Vec<String>,
    /// The end-effector's name.
    pub end_effector: String,
    /// The model's name.
    pub model: String,
    /// How the samples were decided.
    pub solver: MapSolver,
    /// Whether collisions with a cell (and the arm itself) were taken out.
    pub collisions: bool,
    /// The centre of the reach sphere (m, world frame): voxels farther than
    /// [`Self::reach_m`] from it are not solved (nothing there is reached).
    pub reach_centre: [f64; 3],
    /// The reach radius used to skip voxels (m, from [`Self::reach_centre`]).
    pub reach_m: f64,
}

impl ReachabilityMap {
    /// Orientations per voxel (N x R).
    pub fn per_voxel(&self) -> usize {
        self.directions.len() * self.rolls.len()
    }

    /// Flat index of sample (voxel, direction, roll), the voxel as a flat C-order index.
    pub fn sample_index(&self, voxel: usize, direction: usize, roll: usize) -> usize {
        (voxel * self.directions.len() + direction) * self.rolls.len() + roll
    }

    /// The reachability index of every voxel (C order over (nx, ny, nz)): the fraction of its
    /// N x R samples reached, in [0, 1].
    pub fn index(&self) -> Vec<f64> {
        let n = self.per_voxel();
        self.reachable
            .chunks(n.max(1))
            .map(|c| c.iter().filter(|&&b| b).count() as f64 / n as f64)
            .collect()
    }

    /// The tool pose of sample (voxel, direction, roll) (world frame, m).
    pub fn sample_pose(&self, voxel: usize, direction: usize, roll: usize) -> Pose {
        let c = self.grid.centre(self.grid.ijk(voxel));
        Pose::from_parts(
            Translation3::new(c[0], c[1], c[2]),
            sample_rotation(self.directions[direction], self.rolls[roll]),
        )
    }

    /// Samples reached (of all voxels).
    pub fn reached_count(&self) -> usize {
        self.reachable.iter().filter(|&&b| b).count()
    }
}

/// One solution behind a map sample: the posture bit it sets and its joint vector (rad or m,
/// within the limits).
#[derive(Debug, Clone, PartialEq)]
pub struct SampleSolution {
    /// Bits of [`ReachabilityMap::posture_names`] this solution sets (a degenerate posture sets
    /// the bits of the postures it borders).
    pub mask: u16,
    /// Its label ("shoulder left, elbow up, wrist flip"; the classifier's class name for the
    /// numerical solver).
    pub label: String,
    /// The joint vector (rad or m), wrapped into the limits.
    pub q: Vec<f64>,
}

/// The posture bits of a closed-form family: one bit per combination of its labels' two-way
/// parts (shoulder right/left, elbow up/down, extension forward/reversed, wrist no flip/flip or
/// up/down), shoulder most significant, and per branch number for the families whose solutions
/// are numbered. A degenerate part (shoulder on the axis, elbow stretched, wrist singular) sets
/// the bits of both members of its pair.
#[derive(Debug, Clone, PartialEq)]
struct PostureSlots {
    shoulder: bool,
    elbow: bool,
    extension: bool,
    wrist: bool,
    /// The wrist is labelled up/down (three parallel axes) rather than no flip/flip.
    wrist_up_down: bool,
    /// Branch numbers per combination of the parts (1 when the solutions are not numbered).
    branches: usize,
    names: Vec<String>,
}

impl PostureSlots {
    /// The slots of a family, read off the labels of its solutions at random configurations.
    fn of(robot: &Robot, cf: &ClosedForm) -> Self {
        let mut s = Self {
            shoulder: false,
            elbow: false,
            extension: false,
            wrist: false,
            wrist_up_down: false,
            branches: 1,
            names: Vec::new(),
        };
        let mut numbered = false;
        let mut raw = RawSolutions::default();
        let limits = robot.limits();
        let mut rng = Xoshiro256pp::stream(0x51_07, 0);
        for _ in 0..64 {
            let q: Vec<f64> = limits
                .iter()
                .map(|&[lo, hi]| {
                    let (lo, hi) = (lo.max(-3.0), hi.min(3.0));
                    lo + (hi - lo) * rng.next_f64()
                })
                .collect();
            let Ok(t) = robot.fk(&q) else { continue };
            if cf.solve_raw(&t, &mut raw).is_err() {
                continue;
            }
            for p in &raw.postures[..raw.len] {
                s.shoulder |= p.shoulder.is_some();
                s.elbow |= p.elbow.is_some();
                s.extension |= p.extension.is_some();
                s.wrist |= p.wrist.is_some();
                s.wrist_up_down |= matches!(p.wrist, Some(WristFlip::Up | WristFlip::Down));
                numbered |= p.branch.is_some();
            }
        }
        let parts = [s.shoulder, s.elbow, s.extension, s.wrist];
        let combos = 1usize << parts.iter().filter(|&&b| b).count();
        if numbered {
            s.branches = (MAX_SOLUTIONS / combos).max(1);
        }
        s.names = (0..combos * s.branches).map(|k| s.name(k)).collect();
        s
    }

    /// The label of slot `k`, as the IK labels it.
    fn name(&self, k: usize) -> String {
        let branch = k % self.branches;
        let mut bits = k / self.branches;
        let mut p = Posture::default();
        // Least significant part first (the wrist), as `mask` packs them.
        if self.wrist {
            p.wrist = Some(match (bits & 1 == 1, self.wrist_up_down) {
                (false, false) => WristFlip::NoFlip,
                (true, false) => WristFlip::Flip,
                (false, true) => WristFlip::Up,
                (true, true) => WristFlip::Down,
            });
            bits >>= 1;
        }
        if self.extension {
            p.extension = Some(if bits & 1 == 0 {
                Extension::Forward
            } else {
                Extension::Reversed
            });
            bits >>= 1;
        }
        if self.elbow {
            p.elbow = Some(if bits & 1 == 0 {
                Elbow::Up
            } else {
                Elbow::Down
            });
            bits >>= 1;
        }
        if self.shoulder {
            p.shoulder = Some(if bits & 1 == 0 {
                Shoulder::Right
            } else {
                Shoulder::Left
            });
        }
        if self.branches > 1 {
            p.branch = Some(branch as u8 + 1);
        }
        p.to_string()
    }

    /// The bits of a posture (see the type's documentation). Allocation-free: it runs for
    /// every solution of every sample.
    fn mask(&self, p: &Posture) -> u16 {
        // Each part: the set of its values' bits (1 = first, 2 = second, 3 = degenerate).
        let two = |first: bool, second: bool| -> u32 {
            match (first, second) {
                (true, _) => 1,
                (_, true) => 2,
                _ => 3,
            }
        };
        let (mut sets, mut n) = ([0u32; 4], 0);
        if self.shoulder {
            let s = p.shoulder;
            sets[n] = two(s == Some(Shoulder::Right), s == Some(Shoulder::Left));
            n += 1;
        }
        if self.elbow {
            sets[n] = two(p.elbow == Some(Elbow::Up), p.elbow == Some(Elbow::Down));
            n += 1;
        }
        if self.extension {
            let e = p.extension;
            sets[n] = two(
                e == Some(Extension::Forward),
                e == Some(Extension::Reversed),
            );
            n += 1;
        }
        if self.wrist {
            let w = p.wrist;
            sets[n] = two(
                matches!(w, Some(WristFlip::NoFlip | WristFlip::Up)),
                matches!(w, Some(WristFlip::Flip | WristFlip::Down)),
            );
            n += 1;
        }
        // Every combination of the parts' allowed values, most significant part first: bit c
        // of `combos` set when combination c is allowed.
        let mut combos: u32 = 1;
        for set in &sets[..n] {
            let mut next = 0u32;
            let mut rest = combos;
            while rest != 0 {
                let c = rest.trailing_zeros();
                rest &= rest - 1;
                next |= (set & 1) << (2 * c) | (set >> 1 & 1) << (2 * c + 1);
            }
            combos = next;
        }
        let branch = match (self.branches > 1, p.branch) {
            (true, Some(b)) => (b as usize).saturating_sub(1).min(self.branches - 1),
            _ => 0,
        };
        let mut mask = 0u16;
        let mut rest = combos;
        while rest != 0 {
            let c = rest.trailing_zeros() as usize;
            rest &= rest - 1;
            let slot = c * self.branches + branch;
            if slot < 16 {
                mask |= 1 << slot;
            }
        }
        mask
    }
}

/// The solver of every sample, built once.
enum SampleSolver<'a> {
    Closed {
        cf: Box<ClosedForm>,
        slots: PostureSlots,
    },
    Numerical {
        classifier: PostureClassifier,
        seeds: Vec<Vec<f64>>,
        options: NumericalOptions,
        robot: &'a Robot,
    },
}

/// What a map computation shares among its threads.
struct Context<'a> {
    robot: &'a Robot,
    ee: usize,
    solver: SampleSolver<'a>,
    world: Option<&'a CollisionWorld>,
    revolute: Vec<bool>,
    limits: Vec<[f64; 2]>,
    /// Sample rotations, direction-major.
    rotations: Vec<Rotation3<f64>>,
}

impl<'a> Context<'a> {
    fn new(
        robot: &'a Robot,
        opts: &MapOptions,
        world: Option<&'a CollisionWorld>,
        directions: &[[f64; 3]],
        rolls: &[f64],
    ) -> Self {
        let closed = if opts.ee == 0 {
            ClosedForm::detect(robot).ok()
        } else {
            None
        };
        let solver = match closed {
            Some(cf) => SampleSolver::Closed {
                slots: PostureSlots::of(robot, &cf),
                cf: Box::new(cf),
            },
            None => SampleSolver::Numerical {
                classifier: PostureClassifier::for_end_effector(robot, opts.ee),
                seeds: numerical_seeds(robot, opts.seeds.max(1)),
                options: NumericalOptions {
                    max_iterations: 60,
                    restarts: 0,
                    tolerance: NUMERICAL_TOLERANCE,
                    ..NumericalOptions::default()
                },
                robot,
            },
        };
        Self {
            robot,
            ee: opts.ee,
            solver,
            world,
            revolute: (0..robot.dof())
                .map(|k| robot.dof_joint(k).kind == JointKind::Revolute)
                .collect(),
            limits: robot.limits(),
            rotations: directions
                .iter()
                .flat_map(|&d| rolls.iter().map(move |&r| sample_rotation(d, r)))
                .collect(),
        }
    }

    fn map_solver(&self, opts: &MapOptions) -> MapSolver {
        match &self.solver {
            SampleSolver::Closed { cf, .. } => MapSolver::ClosedForm {
                family: cf.name().to_string(),
            },
            SampleSolver::Numerical { .. } => MapSolver::Numerical {
                seeds: opts.seeds.max(1),
                tolerance: NUMERICAL_TOLERANCE,
            },
        }
    }

    fn posture_names(&self) -> Vec<String> {
        match &self.solver {
            SampleSolver::Closed { slots, .. } => slots.names.clone(),
            SampleSolver::Numerical { classifier, .. } => classifier.class_names().to_vec(),
        }
    }

    /// Whether configuration `q` (within the limits) is free of collision.
    fn free(&self, q: &[f64]) -> bool {
        match self.world {
            Some(w) => !w.in_collision(self.robot, q).unwrap_or(true),
            None => true,
        }
    }

    /// Calls `visit(mask, label, q)` for every solution of `pose` within the limits (and free
    /// of collision); stops early when `visit` returns false.
    fn each_solution(&self, pose: &Pose, visit: &mut dyn FnMut(u16, &Posture, &[f64]) -> bool) {
        let n = self.limits.len();
        match &self.solver {
            SampleSolver::Closed { cf, slots } => {
                let mut raw = RawSolutions::default();
                if cf.solve_raw(pose, &mut raw).is_err() {
                    return;
                }
                let mut q = [0.0; MAX_DOF];
                for k in 0..raw.len {
                    for (j, v) in q.iter_mut().enumerate().take(n) {
                        *v = if self.revolute[j] {
                            wrap_into_limits(raw.q[k][j], self.limits[j])
                        } else {
                            raw.q[k][j]
                        };
                    }
                    if self.robot.within_limits(&q[..n], LIMIT_TOL)
                        && self.free(&q[..n])
                        && !visit(slots.mask(&raw.postures[k]), &raw.postures[k], &q[..n])
                    {
                        return;
                    }
                }
            }
            SampleSolver::Numerical {
                classifier,
                seeds,
                options,
                robot,
            } => {
                let target = Target::Pose(*pose);
                let mut found: Vec<Vec<f64>> = Vec::new();
                for seed in seeds {
                    let Ok(rep) = numerical::solve(robot, self.ee, &target, seed, options) else {
                        continue;
                    };
                    if !rep.converged
                        || !robot.within_limits(&rep.q, LIMIT_TOL)
                        || found.iter().any(|f| same_q(f, &rep.q, &self.revolute))
                        || !self.free(&rep.q)
                    {
                        continue;
                    }
                    let class = classifier.classify(&rep.q, pose);
                    let mask = if class == UNCLASSIFIED {
                        (1u16 << classifier.class_count().min(16)) - 1
                    } else {
                        1 << class
                    };
                    if !visit(mask, &Posture::default(), &rep.q) {
                        return;
                    }
                    found.push(rep.q);
                }
            }
        }
    }

    /// The posture bits of one sample (0: not reached) and whether it is reached.
    fn sample(&self, pose: &Pose) -> (bool, u16) {
        let mut mask = 0u16;
        let mut reached = false;
        self.each_solution(pose, &mut |m, _, _| {
            mask |= m;
            reached = true;
            true
        });
        (reached, mask)
    }
}

/// Two joint vectors equal within 1e-6 (angles wrapped).
fn same_q(a: &[f64], b: &[f64], revolute: &[bool]) -> bool {
    a.iter().zip(b).zip(revolute).all(|((x, y), &r)| {
        let d = x - y;
        let d = if r {
            (d + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI
        } else {
            d
        };
        d.abs() < 1e-6
    })
}

/// Seeds of the numerical solver: the middle of the limits, then spread configurations.
fn numerical_seeds(robot: &Robot, n: usize) -> Vec<Vec<f64>> {
    let limits = robot.limits();
    let mut rng = Xoshiro256pp::stream(0x005E_ED49, 0);
    (0..n)
        .map(|k| {
            limits
                .iter()
                .map(|&[lo, hi]| {
                    let (lo, hi) = (lo.max(-3.1), hi.min(3.1));
                    if k == 0 {
                        0.5 * (lo + hi)
                    } else {
                        lo + (hi - lo) * rng.next_f64()
                    }
                })
                .collect()
        })
        .collect()
}

/// Where an arm reaches, estimated from inside: the box its tool point sweeps (m, world frame),
/// a centre (the box's middle) and the largest distance of the tool point from that centre (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReachEstimate {
    /// Lowest corner of the box (m, world frame).
    pub lo: [f64; 3],
    /// Highest corner (m, world frame).
    pub hi: [f64; 3],
    /// The middle of the box (m, world frame).
    pub centre: [f64; 3],
    /// The farthest tool point from `centre` (m).
    pub radius_m: f64,
}

/// Estimates the reach of end-effector `ee` from 20,000 random configurations within the
/// limits, the farthest point from the box's middle refined by coordinate ascent. An estimate
/// from inside: the map widens it and checks it (see the module documentation).
pub fn reach_estimate(robot: &Robot, ee: usize) -> ReachEstimate {
    let limits = robot.limits();
    let mut rng = Xoshiro256pp::stream(0xBA5E, 0);
    let point = |q: &[f64]| robot.fk_ee(q, ee).ok().map(|t| t.translation.vector);
    let mut points: Vec<(Vector3<f64>, Vec<f64>)> = Vec::with_capacity(20_000);
    let mut q = vec![0.0; limits.len()];
    for _ in 0..20_000 {
        for (v, &[l, h]) in q.iter_mut().zip(&limits) {
            *v = l + (h - l) * rng.next_f64();
        }
        if let Some(p) = point(&q) {
            points.push((p, q.clone()));
        }
    }
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for (p, _) in &points {
        for a in 0..3 {
            lo[a] = lo[a].min(p[a]);
            hi[a] = hi[a].max(p[a]);
        }
    }
    if points.is_empty() {
        let b: [f64; 3] = robot.base.translation.vector.into();
        return ReachEstimate {
            lo: b,
            hi: b,
            centre: b,
            radius_m: 0.0,
        };
    }
    let centre = Vector3::from([0, 1, 2].map(|a| 0.5 * (lo[a] + hi[a])));
    let (mut far, mut best) = points
        .iter()
        .map(|(p, q)| ((p - centre).norm(), q.clone()))
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .unwrap_or((0.0, q));
    // Coordinate ascent on the distance from the centre; the box grows with what it visits.
    let mut step = 0.2;
    while step > 1e-4 {
        let mut moved = false;
        for j in 0..best.len() {
            for s in [-step, step] {
                let mut t = best.clone();
                t[j] = (t[j] + s).clamp(limits[j][0], limits[j][1]);
                let Some(p) = point(&t) else { continue };
                for a in 0..3 {
                    lo[a] = lo[a].min(p[a]);
                    hi[a] = hi[a].max(p[a]);
                }
                let r = (p - centre).norm();
                if r > far {
                    (far, best, moved) = (r, t, true);
                }
            }
        }
        if !moved {
            step *= 0.5;
        }
    }
    ReachEstimate {
        lo,
        hi,
        centre: centre.into(),
        radius_m: far,
    }
}

/// The grid, skip centre and reach radius of a map with margin `margin_m` (m) around the
/// estimate.
fn plan(robot: &Robot, opts: &MapOptions, margin_m: f64) -> (VoxelGrid, [f64; 3], f64) {
    let e = reach_estimate(robot, opts.ee);
    let r = e.radius_m + margin_m;
    let lo = [0, 1, 2].map(|a| (e.lo[a] - margin_m).max(e.centre[a] - r));
    let hi = [0, 1, 2].map(|a| (e.hi[a] + margin_m).min(e.centre[a] + r));
    (VoxelGrid::covering(lo, hi, opts.voxel_m), e.centre, r)
}

/// Checks the options (before any work) and returns the grid a map of them would have.
///
/// # Errors
///
/// A bad voxel, no directions or rolls, a missing end-effector, or more than [`MAX_SAMPLES`]
/// samples without [`MapOptions::force`].
pub fn plan_grid(robot: &Robot, opts: &MapOptions) -> Result<VoxelGrid, ReachabilityError> {
    check_options(robot, opts)?;
    let (grid, _, _) = plan(robot, opts, first_margin(opts));
    check_size(&grid, opts)?;
    Ok(grid)
}

fn first_margin(opts: &MapOptions) -> f64 {
    opts.voxel_m * 2.0
}

fn check_options(robot: &Robot, opts: &MapOptions) -> Result<(), ReachabilityError> {
    if !(opts.voxel_m.is_finite() && opts.voxel_m > 0.0) {
        return Err(ReachabilityError::BadVoxel {
            voxel_m: opts.voxel_m,
        });
    }
    if opts.directions == 0 {
        return Err(ReachabilityError::NoDirections { directions: 0 });
    }
    if opts.rolls == 0 {
        return Err(ReachabilityError::NoRolls { rolls: 0 });
    }
    if opts.ee >= robot.end_effectors().len() {
        return Err(ReachabilityError::NoEndEffector {
            ee: opts.ee,
            count: robot.end_effectors().len(),
        });
    }
    if robot.dof() == 0 {
        return Err(ReachabilityError::NoJoints);
    }
    Ok(())
}

fn check_size(grid: &VoxelGrid, opts: &MapOptions) -> Result<(), ReachabilityError> {
    let voxels = grid.dims.iter().map(|&d| d as u64).product::<u64>();
    let per_voxel = (opts.directions as u64).saturating_mul(opts.rolls as u64);
    let samples = voxels.saturating_mul(per_voxel);
    if samples > MAX_SAMPLES && !opts.force {
        return Err(ReachabilityError::TooManySamples {
            samples,
            voxels,
            per_voxel,
            limit: MAX_SAMPLES,
        });
    }
    Ok(())
}

/// Computes the reachability map of `robot` (see the module documentation), in parallel; with
/// `world`, a solution counts only when it hits neither the arm itself nor the cell.
///
/// # Errors
///
/// Bad options ([`plan_grid`]'s errors), found before any work, and
/// [`ReachabilityError::Cancelled`] when `control.cancel` is set.
///
/// # Examples
///
/// The Puma 560 at 25 cm with 20 directions and 2 rolls: every posture bit of a sample is a
/// solution that puts the tool on the sample's pose.
///
/// ```
/// use armlab::kinematics::models::built_in;
/// use armlab::reachability::{MapControl, MapOptions, compute_reachability, solutions_at};
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let puma = built_in("puma560").expect("a built-in model");
/// let opts = MapOptions { voxel_m: 0.25, directions: 20, rolls: 2, ..MapOptions::default() };
/// let map = compute_reachability(&puma, &opts, None, MapControl::default())?;
/// assert_eq!(map.posture_names.len(), 8);
/// let s = map.reachable.iter().position(|&b| b).expect("something is reached");
/// let (voxel, d, r) = (s / 40, s / 2 % 20, s % 2);
/// let pose = map.sample_pose(voxel, d, r);
/// let mut bits = 0;
/// for sol in solutions_at(&puma, &map, &opts, None, &pose) {
///     let gap = (puma.fk(&sol.q)?.to_homogeneous() - pose.to_homogeneous()).amax();
///     assert!(gap < 1e-9);
///     bits |= sol.mask;
/// }
/// assert_eq!(bits, map.postures[s]);
/// # Ok(())
/// # }
/// ```
pub fn compute_reachability(
    robot: &Robot,
    opts: &MapOptions,
    world: Option<&CollisionWorld>,
    control: MapControl<'_>,
) -> Result<ReachabilityMap, ReachabilityError> {
    check_options(robot, opts)?;
    let directions = fibonacci_directions(opts.directions);
    let rolls = roll_angles(opts.rolls);
    let ctx = Context::new(robot, opts, world, &directions, &rolls);
    let mut margin = first_margin(opts);
    loop {
        let (grid, centre, reach) = plan(robot, opts, margin);
        check_size(&grid, opts)?;
        let (reachable, postures) = sweep(&ctx, &grid, centre, reach, control)?;
        let map = ReachabilityMap {
            grid,
            directions: directions.clone(),
            rolls: rolls.clone(),
            reachable,
            postures,
            posture_names: ctx.posture_names(),
            end_effector: robot.end_effectors()[opts.ee].name.clone(),
            model: robot.name.clone(),
            solver: ctx.map_solver(opts),
            collisions: world.is_some(),
            reach_centre: centre,
            reach_m: reach,
        };
        if !touches_bound(&map) || margin > 1.0 {
            return Ok(map);
        }
        margin *= 2.0;
    }
}

/// Whether a reached voxel lies on the grid's outer layer or within two voxels of the skipped
/// shell: then the estimated reach may have cut reachable voxels off.
fn touches_bound(map: &ReachabilityMap) -> bool {
    let centre = Vector3::from(map.reach_centre);
    let n = map.per_voxel();
    let g = &map.grid;
    (0..g.len()).any(|v| {
        if !map.reachable[v * n..(v + 1) * n].iter().any(|&b| b) {
            return false;
        }
        let ijk = g.ijk(v);
        let edge = (0..3).any(|a| ijk[a] == 0 || ijk[a] + 1 == g.dims[a]);
        let c = Vector3::from(g.centre(ijk));
        edge || (c - centre).norm() > map.reach_m - 2.0 * g.voxel_m
    })
}

/// Every sample of every voxel within `reach` of `centre`, in parallel.
fn sweep(
    ctx: &Context<'_>,
    grid: &VoxelGrid,
    centre: [f64; 3],
    reach: f64,
    control: MapControl<'_>,
) -> Result<(Vec<bool>, Vec<u16>), ReachabilityError> {
    let per = ctx.rotations.len();
    let total = grid.len();
    let mut reachable = vec![false; total * per];
    let mut postures = vec![0u16; total * per];
    let done = AtomicUsize::new(0);
    let centre = Vector3::from(centre);
    let stopped = || control.cancel.is_some_and(|c| c.load(Ordering::Relaxed));
    reachable
        .par_chunks_mut(per)
        .zip(postures.par_chunks_mut(per))
        .enumerate()
        .for_each(|(v, (reach_out, post_out))| {
            if stopped() {
                return;
            }
            let c = grid.centre(grid.ijk(v));
            if (Vector3::from(c) - centre).norm() <= reach {
                let t = Translation3::new(c[0], c[1], c[2]);
                for (s, rot) in ctx.rotations.iter().enumerate() {
                    let (r, m) = ctx.sample(&Pose::from_parts(t, *rot));
                    reach_out[s] = r;
                    post_out[s] = m;
                }
            }
            let d = done.fetch_add(1, Ordering::Relaxed) + 1;
            if let Some(p) = control.progress {
                p(d, total);
            }
        });
    if stopped() {
        return Err(ReachabilityError::Cancelled {
            done: done.load(Ordering::Relaxed),
            total,
        });
    }
    Ok((reachable, postures))
}

/// Every solution behind a sample pose of `map` (as computed with `opts` and `world`): the
/// postures a map's bits stand for, with their joint vectors, for the app's ghosts and for
/// checking a map.
pub fn solutions_at(
    robot: &Robot,
    map: &ReachabilityMap,
    opts: &MapOptions,
    world: Option<&CollisionWorld>,
    world_from_tool: &Pose,
) -> Vec<SampleSolution> {
    let ctx = Context::new(robot, opts, world, &[], &[]);
    let mut out = Vec::new();
    ctx.each_solution(world_from_tool, &mut |mask, posture, q| {
        let label = match &ctx.solver {
            SampleSolver::Closed { .. } => posture.to_string(),
            SampleSolver::Numerical { .. } => (0..16)
                .filter(|b| mask >> b & 1 == 1)
                .filter_map(|b| map.posture_names.get(b))
                .cloned()
                .collect::<Vec<_>>()
                .join(" / "),
        };
        out.push(SampleSolution {
            mask,
            label,
            q: q.to_vec(),
        });
        true
    });
    out
}

/// The map's posture bits of a closed form, for base placement ([`super::place`]), so that its
/// masks read as the map's.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PostureBits(PostureSlots);

impl PostureBits {
    /// The bits of `cf`'s solutions on `robot`.
    pub(crate) fn of(robot: &Robot, cf: &ClosedForm) -> Self {
        Self(PostureSlots::of(robot, cf))
    }

    /// The bit names, in bit order.
    pub(crate) fn names(&self) -> &[String] {
        &self.0.names
    }

    /// The bits of one posture (a degenerate part sets both members of its pair).
    pub(crate) fn mask(&self, p: &Posture) -> u16 {
        self.0.mask(p)
    }
}
