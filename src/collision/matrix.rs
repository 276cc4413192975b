//! The allowed-collision matrix: the link pairs never checked, and why. Built as MoveIt's
//! Setup Assistant builds it: adjacent links are never checked; random configurations within
//! the joint limits are sampled, and a pair that overlaps in nearly all of them ("always", at
//! least [`MatrixOptions::always_fraction`]) or already at the default configuration
//! ("default") is disabled, as is a pair that never overlaps in any sample ("never": checking
//! it would only cost time).

use super::geometry::RobotGeometry;
use super::obstacles::CellScene;
use super::{CollisionError, CollisionWorld, GeometryOptions};
use crate::kinematics::{KinematicsError, Robot};
use crate::workspace::rng::{Xoshiro256pp, uniform_q};
use rayon::prelude::*;
use serde::Serialize;
use std::collections::HashSet;

/// Why a pair is (or is not) checked; the words are MoveIt's SRDF reasons.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum PairReason {
    /// Joined by a joint: they touch by construction.
    Adjacent,
    /// Overlapping in at least [`MatrixOptions::always_fraction`] of the samples.
    Always,
    /// Overlapping at the default configuration (the ready pose, or zero).
    Default,
    /// Never overlapping in any sample.
    Never,
    /// Disabled by the user (an SRDF or the model file gave no reason MoveIt knows).
    User,
    /// Checked: they overlap in some samples and not in others.
    Checked,
}

impl PairReason {
    /// The SRDF `reason` attribute.
    pub fn as_str(self) -> &'static str {
        match self {
            PairReason::Adjacent => "Adjacent",
            PairReason::Always => "Always",
            PairReason::Default => "Default",
            PairReason::Never => "Never",
            PairReason::User => "User",
            PairReason::Checked => "Checked",
        }
    }

    /// A reason from its SRDF word (anything unknown is the user's).
    pub fn from_word(word: &str) -> PairReason {
        match word {
            "Adjacent" => PairReason::Adjacent,
            "Always" => PairReason::Always,
            "Default" => PairReason::Default,
            "Never" => PairReason::Never,
            _ => PairReason::User,
        }
    }

    /// Why, in words.
    pub fn explain(self) -> &'static str {
        match self {
            PairReason::Adjacent => "joined by a joint: they touch by construction",
            PairReason::Always => "overlap in nearly every sampled configuration",
            PairReason::Default => "overlap at the default configuration",
            PairReason::Never => "never overlap in any sampled configuration",
            PairReason::User => "disabled by the user",
            PairReason::Checked => "overlap in some configurations: checked",
        }
    }
}

/// One link pair of the matrix.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PairVerdict {
    /// The first link.
    pub a: String,
    /// The second link.
    pub b: String,
    /// Why it is disabled, or `Checked`.
    pub reason: PairReason,
    /// In how many samples they overlapped (0 when not sampled).
    pub collided: usize,
    /// How many samples were drawn (0 when not sampled).
    pub samples: usize,
}

/// The allowed-collision matrix: every link pair with its verdict; the pairs whose reason is
/// not `Checked` are never checked.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct AllowedCollisions {
    /// Every pair judged, in link order.
    pub pairs: Vec<PairVerdict>,
    #[serde(skip)]
    disabled: HashSet<(String, String)>,
}

/// How the matrix is sampled.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MatrixOptions {
    /// Random configurations drawn (MoveIt's default: 10,000). More finds rarer collisions
    /// (a pair that never overlapped is disabled) at proportional cost.
    pub samples: usize,
    /// The fraction of samples a pair must overlap in to be "always" colliding (MoveIt: 0.95).
    pub always_fraction: f64,
    /// Whether pairs that never overlap are disabled (MoveIt does; checking them costs time
    /// and finds only what sampling missed).
    pub disable_never: bool,
    /// The generator's seed (the same seed draws the same samples).
    pub seed: u64,
}

impl Default for MatrixOptions {
    fn default() -> Self {
        MatrixOptions {
            samples: 10_000,
            always_fraction: 0.95,
            disable_never: true,
            seed: 0x5EED_AC11,
        }
    }
}

/// A pair's key, the names in order.
fn key(a: &str, b: &str) -> (String, String) {
    if a <= b {
        (a.to_string(), b.to_string())
    } else {
        (b.to_string(), a.to_string())
    }
}

impl AllowedCollisions {
    /// A matrix of these verdicts.
    pub fn from_pairs(pairs: Vec<PairVerdict>) -> AllowedCollisions {
        let disabled = pairs
            .iter()
            .filter(|p| p.reason != PairReason::Checked)
            .map(|p| key(&p.a, &p.b))
            .collect();
        AllowedCollisions { pairs, disabled }
    }

    /// Whether the pair of bodies named `a` and `b` is never checked.
    pub fn is_allowed(&self, a: &str, b: &str) -> bool {
        self.disabled.contains(&key(a, b))
    }

    /// The adjacent link pairs of `robot` (parent and child bodies).
    pub fn adjacent(robot: &Robot, geometry: &RobotGeometry) -> AllowedCollisions {
        let pairs = adjacent_pairs(robot, geometry)
            .into_iter()
            .map(|(i, j)| PairVerdict {
                a: geometry.bodies[i].name.clone(),
                b: geometry.bodies[j].name.clone(),
                reason: PairReason::Adjacent,
                collided: 0,
                samples: 0,
            })
            .collect();
        AllowedCollisions::from_pairs(pairs)
    }

    /// The matrix a robot is checked with: its stored one (a model file's
    /// `[[disable_collisions]]`, with the adjacent pairs added), or else a quick one sampled
    /// now (1,000 samples; adjacent, always and default pairs; never-colliding pairs stay
    /// checked).
    pub fn for_robot(robot: &Robot, geometry: &RobotGeometry) -> AllowedCollisions {
        let mut m = AllowedCollisions::adjacent(robot, geometry);
        if !robot.disabled_collisions.is_empty() {
            for d in &robot.disabled_collisions {
                m.add(&d.link1, &d.link2, PairReason::from_word(&d.reason));
            }
            return m;
        }
        let options = MatrixOptions {
            samples: 1000,
            disable_never: false,
            ..MatrixOptions::default()
        };
        sample_matrix(robot, geometry, options).unwrap_or(m)
    }

    /// Disables the pair `a`, `b` for `reason` (a pair already judged takes the new reason).
    pub fn add(&mut self, a: &str, b: &str, reason: PairReason) {
        let k = key(a, b);
        if let Some(p) = self.pairs.iter_mut().find(|p| key(&p.a, &p.b) == k) {
            p.reason = reason;
        } else {
            self.pairs.push(PairVerdict {
                a: a.to_string(),
                b: b.to_string(),
                reason,
                collided: 0,
                samples: 0,
            });
        }
        if reason == PairReason::Checked {
            self.disabled.remove(&k);
        } else {
            self.disabled.insert(k);
        }
    }

    /// The disabled pairs (not `Checked`).
    pub fn disabled(&self) -> impl Iterator<Item = &PairVerdict> {
        self.pairs
            .iter()
            .filter(|p| p.reason != PairReason::Checked)
    }
}

/// Body index pairs joined by a joint: each link body and the body of its nearest ancestor
/// joint's child (skipping joints whose links have no geometry).
fn adjacent_pairs(robot: &Robot, geometry: &RobotGeometry) -> Vec<(usize, usize)> {
    let has = |slot: usize| {
        let b = &geometry.bodies[slot];
        b.stick || !b.parts.is_empty()
    };
    let mut out = Vec::new();
    for j in 0..robot.joints().len() {
        let child = j + 1;
        if !has(child) {
            continue;
        }
        let mut parent = robot.joints()[j].parent;
        // A parent link without geometry passes adjacency on to its own parent.
        while let Some(p) = parent
            && !has(p + 1)
        {
            parent = robot.joints()[p].parent;
        }
        let p = parent.map_or(0, |p| p + 1);
        if has(p) {
            out.push((p.min(child), p.max(child)));
        }
    }
    out
}

/// Samples the matrix as MoveIt's Setup Assistant does (see the module documentation); every
/// link pair gets a verdict.
pub fn sample_matrix(
    robot: &Robot,
    geometry: &RobotGeometry,
    options: MatrixOptions,
) -> Result<AllowedCollisions, CollisionError> {
    sample_matrix_with_progress(robot, geometry, options, &|_| {})
}

/// [`sample_matrix`], calling `progress` with the number of configurations sampled so far
/// (from any thread, every 256 configurations), for a progress bar.
///
/// ```
/// use armlab::collision::{
///     GeometryOptions, MatrixOptions, PairReason, RobotGeometry, sample_matrix_with_progress,
/// };
/// use armlab::kinematics::models;
/// use std::sync::atomic::{AtomicUsize, Ordering};
///
/// let robot = models::puma560();
/// let geometry = RobotGeometry::of(&robot, GeometryOptions::default());
/// let options = MatrixOptions { samples: 600, ..MatrixOptions::default() };
/// let most = AtomicUsize::new(0);
/// let m = sample_matrix_with_progress(&robot, &geometry, options, &|n| {
///     most.fetch_max(n, Ordering::Relaxed);
/// })
/// .unwrap();
/// // Every configuration was counted, and every pair not adjacent was judged on all of them.
/// assert_eq!(most.load(Ordering::Relaxed), 600);
/// assert!(m.pairs.iter().all(|p| p.reason == PairReason::Adjacent || p.samples == 600));
/// ```
pub fn sample_matrix_with_progress(
    robot: &Robot,
    geometry: &RobotGeometry,
    options: MatrixOptions,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<AllowedCollisions, CollisionError> {
    let done = std::sync::atomic::AtomicUsize::new(0);
    let adjacent = AllowedCollisions::adjacent(robot, geometry);
    let everything = AllowedCollisions::default();
    let world = CollisionWorld::with(
        robot,
        geometry.clone(),
        &CellScene::default(),
        GeometryOptions::default(),
        everything,
    )?;
    let n = geometry.bodies.len();
    let has = |i: usize| geometry.bodies[i].stick || !geometry.bodies[i].parts.is_empty();
    let mut candidates = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            if has(i)
                && has(j)
                && !adjacent.is_allowed(&geometry.bodies[i].name, &geometry.bodies[j].name)
            {
                candidates.push((i, j));
            }
        }
    }
    let at_default = world.link_pairs_overlap(robot, &robot.ready_or_zero(), &candidates)?;
    let limits = robot.sampling_ranges();
    let chunks = options.samples.div_ceil(256);
    let counts = (0..chunks)
        .into_par_iter()
        .map(|c| -> Result<Vec<usize>, KinematicsError> {
            let mut rng = Xoshiro256pp::stream(options.seed, c as u64);
            let mut q = vec![0.0; robot.dof()];
            let mut counts = vec![0usize; candidates.len()];
            let here = 256.min(options.samples - c * 256);
            for _ in 0..here {
                uniform_q(&mut rng, &limits, &mut q);
                for (k, hit) in world
                    .link_pairs_overlap(robot, &q, &candidates)?
                    .into_iter()
                    .enumerate()
                {
                    counts[k] += usize::from(hit);
                }
            }
            progress(done.fetch_add(here, std::sync::atomic::Ordering::Relaxed) + here);
            Ok(counts)
        })
        .try_reduce(
            || vec![0usize; candidates.len()],
            |mut a, b| {
                a.iter_mut().zip(b).for_each(|(x, y)| *x += y);
                Ok(a)
            },
        )?;
    let mut matrix = adjacent;
    for (k, &(i, j)) in candidates.iter().enumerate() {
        let fraction = counts[k] as f64 / options.samples.max(1) as f64;
        let reason = if options.samples > 0 && fraction >= options.always_fraction {
            PairReason::Always
        } else if at_default[k] {
            PairReason::Default
        } else if counts[k] == 0 && options.disable_never && options.samples > 0 {
            PairReason::Never
        } else {
            PairReason::Checked
        };
        matrix.add(&geometry.bodies[i].name, &geometry.bodies[j].name, reason);
        if let Some(p) = matrix.pairs.last_mut() {
            p.collided = counts[k];
            p.samples = options.samples;
        }
    }
    Ok(matrix)
}
