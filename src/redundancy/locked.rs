//! The exact self-motion of any seven-revolute arm, by locking one joint: the locked joint's
//! angle is the parameter, and each value is a six-revolute problem solved by elimination with
//! every branch ([`LockedArm`]). SRS arms keep the arm angle and the Panda keeps q7; this covers
//! the rest (a Kinova Gen3, a Baxter arm, an iiwa with offsets, a calibrated LWR).
//!
//! The parameter's whole turn [-pi, pi] is swept (values beyond the locked joint's limits keep
//! their solutions, flagged outside the limits); solutions at neighbouring values are joined
//! into arcs (a branch is an arc along which the parameter moves
//! monotonically); where an arc ends inside the range (a turning point, where two branches meet)
//! or leaves the joint limits, the end is refined by bisection to [`REFINE`] rad.

use super::geometry::{within, wrap_into};
use super::{BranchSolution, RedundancyError, checked, count_manifolds};
use crate::kinematics::ik::closed_form::{LockedArm, MAX_LOCKED_SOLUTIONS};
use crate::kinematics::{Pose, Robot};
use std::f64::consts::PI;

/// Samples of the parameter's range in the sweep.
const SWEEP: usize = 721;
/// Two solutions at neighbouring samples belong to one arc when no joint moved more than this
/// (rad).
const STEP_MATCH: f64 = 0.3;
/// Interval ends are refined to this (rad).
pub const REFINE: f64 = 1e-9;
/// The parameter's names, by locked joint.
const NAMES: [&str; 7] = [
    "q1 (locked)",
    "q2 (locked)",
    "q3 (locked)",
    "q4 (locked)",
    "q5 (locked)",
    "q6 (locked)",
    "q7 (locked)",
];
/// Joints tried in turn when armlab picks the one to lock (0-based): q3 first, as IKFast's free
/// joint and ssik.
const PREFERENCE: [usize; 7] = [2, 4, 1, 3, 5, 0, 6];

/// The parameter's name when joint `k` (0-based) is locked, e.g. "q3 (locked)".
pub fn parameter_name(k: usize) -> &'static str {
    NAMES[k.min(6)]
}

/// One branch: the parameter values (increasing) and the joint vectors along it.
#[derive(Debug, Clone, Default)]
struct Arc {
    values: Vec<f64>,
    qs: Vec<[f64; 7]>,
}

impl Arc {
    fn range(&self) -> [f64; 2] {
        [
            self.values[0],
            *self.values.last().unwrap_or(&self.values[0]),
        ]
    }

    /// The joint vector at `value` by linear interpolation of the samples.
    fn guess(&self, value: f64) -> [f64; 7] {
        let i = self.values.partition_point(|v| *v < value);
        if i == 0 {
            return self.qs[0];
        }
        if i >= self.values.len() {
            return self.qs[self.qs.len() - 1];
        }
        let (v0, v1) = (self.values[i - 1], self.values[i]);
        let t = if v1 > v0 {
            (value - v0) / (v1 - v0)
        } else {
            0.0
        };
        std::array::from_fn(|k| {
            let d = super::wrap(self.qs[i][k] - self.qs[i - 1][k]);
            self.qs[i - 1][k] + t * d
        })
    }
}

/// The largest joint difference, angles modulo 2 pi.
fn distance(a: &[f64; 7], b: &[f64; 7]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| super::wrap(x - y).abs())
        .fold(0.0, f64::max)
}

/// The exact self-motion of a seven-revolute arm with one joint locked.
#[derive(Debug, Clone)]
pub struct LockedSelfMotion {
    arm: LockedArm,
    /// The arm itself: every solution is checked (and polished) on its own kinematics.
    robot: Robot,
    target: Pose,
    limits: Vec<[f64; 2]>,
    arcs: Vec<Arc>,
    names: Vec<String>,
    feasible: Vec<Vec<[f64; 2]>>,
    manifolds: usize,
    why: String,
}

impl LockedSelfMotion {
    /// The joint armlab locks for `robot` (0-based) and why; `None` when the robot is not a
    /// serial arm of seven revolute joints or no lock leaves a six-joint arm the elimination
    /// solves (tried at a generic configuration inside the limits: the ready or zero one is
    /// often singular, an arm stretched out).
    pub fn pick(robot: &Robot) -> Option<(usize, String)> {
        if robot.dof() != 7 {
            return None;
        }
        const FRACTION: [f64; 7] = [0.31, -0.43, 0.27, 0.52, -0.37, 0.46, 0.22];
        let limits = robot.limits();
        let q7: [f64; 7] = std::array::from_fn(|i| {
            let (lo, hi) = (limits[i][0].max(-PI), limits[i][1].min(PI));
            0.5 * (lo + hi) + FRACTION[i] * (hi - lo)
        });
        let pose = robot.fk(&q7).ok()?;
        PREFERENCE.iter().find_map(|&k| {
            let arm = LockedArm::new(robot, k)?;
            let mut out = [[0.0; 7]; MAX_LOCKED_SOLUTIONS];
            let n = arm.solve_exact(robot, &pose, q7[k], &mut out).ok()?;
            let found = out[..n].iter().any(|s| distance(s, &q7) < 1e-6);
            found.then(|| {
                let why = if k == 2 {
                    "q3 locked: the upper arm's rotation, the usual choice for seven-joint arms \
                     (IKFast's free joint, ssik); the six-joint arm left is solved by elimination, \
                     every branch"
                        .to_string()
                } else {
                    format!(
                        "q{} locked: locking q3 left a six-joint arm the elimination cannot solve; \
                         q{} leaves one it solves, every branch",
                        k + 1,
                        k + 1
                    )
                };
                (k, why)
            })
        })
    }

    /// The self-motion of `robot` holding its tool at `target` (world, m), with joint `locked`
    /// (0-based; `None`: armlab picks, see [`Self::pick`]) as the parameter.
    pub fn new(
        robot: &Robot,
        target: &Pose,
        locked: Option<usize>,
    ) -> Result<Self, RedundancyError> {
        let not = || RedundancyError::NoExactSelfMotion {
            robot: robot.name.clone(),
        };
        let (k, why) = match locked {
            Some(k) => (k, format!("q{} locked: chosen by the user", k + 1)),
            None => Self::pick(robot).ok_or_else(not)?,
        };
        let arm = LockedArm::new(robot, k).ok_or_else(not)?;
        let limits = robot.limits();
        // The whole turn of the locked joint, as the arm angle and q7 are swept: values beyond
        // its own limits keep their solutions, flagged outside the limits by `feasible`.
        let (lo, hi) = (-PI, PI);
        let mut m = Self {
            arm,
            robot: robot.clone(),
            target: *target,
            limits,
            arcs: Vec::new(),
            names: Vec::new(),
            feasible: Vec::new(),
            manifolds: 0,
            why,
        };
        m.sweep(lo, hi);
        if m.arcs.is_empty() {
            if let Some(value) = fixed_by_pose(robot, target, k) {
                return Err(RedundancyError::LockedJointFixedByPose {
                    parameter: NAMES[k],
                    value_deg: value.to_degrees(),
                });
            }
            return Err(RedundancyError::OutOfReachForEveryValue {
                parameter: NAMES[k],
            });
        }
        m.names = (1..=m.arcs.len()).map(|i| format!("branch {i}")).collect();
        m.feasible = (0..m.arcs.len()).map(|a| m.feasible_of(a)).collect();
        m.manifolds = m.count();
        Ok(m)
    }

    /// Every solution at `value`, the joints wrapped into their limits where they fit.
    fn solve(&self, value: f64) -> Vec<[f64; 7]> {
        let mut out = [[0.0; 7]; MAX_LOCKED_SOLUTIONS];
        let n = self
            .arm
            .solve_exact(&self.robot, &self.target, value, &mut out)
            .unwrap_or(0);
        out[..n]
            .iter()
            .map(|q| wrap_into(*q, &self.limits))
            .collect()
    }

    /// The solution at `value` continuing from `q`, if one is within [`STEP_MATCH`]: the
    /// nearest of the elimination's, else Newton's continuation from `q` (on a nearly special
    /// arm, an ill-conditioned eliminant can miss a branch at one value that it found at
    /// another; the continuation keeps it).
    fn continue_from(&self, q: &[f64; 7], value: f64) -> Option<[f64; 7]> {
        self.solve(value)
            .into_iter()
            .map(|s| (distance(&s, q), s))
            .filter(|(d, _)| *d < STEP_MATCH)
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, s)| s)
            .or_else(|| self.newton_step(q, value))
    }

    /// Newton's continuation of `q` to `value`, kept if it moved less than [`STEP_MATCH`].
    fn newton_step(&self, q: &[f64; 7], value: f64) -> Option<[f64; 7]> {
        let s = self
            .arm
            .continue_at(&self.robot, &self.target, q, value)
            .map(|s| wrap_into(s, &self.limits))?;
        (distance(&s, q) < STEP_MATCH).then_some(s)
    }

    /// The sweep: arcs from the samples, with their ends inside the range refined.
    fn sweep(&mut self, lo: f64, hi: f64) {
        let mut active: Vec<usize> = Vec::new();
        let mut prev = lo;
        for i in 0..SWEEP {
            let v = lo + (hi - lo) * i as f64 / (SWEEP - 1) as f64;
            let sols = self.solve(v);
            // Greedy matching, nearest pairs first.
            let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
            for &a in &active {
                let last = self.arcs[a].qs.last().copied().unwrap_or_default();
                for (s, q) in sols.iter().enumerate() {
                    let d = distance(&last, q);
                    if d < STEP_MATCH {
                        pairs.push((d, a, s));
                    }
                }
            }
            pairs.sort_by(|x, y| x.0.total_cmp(&y.0));
            let (mut arc_done, mut sol_done) = (Vec::new(), vec![false; sols.len()]);
            let mut next = Vec::new();
            for (_, a, s) in pairs {
                if arc_done.contains(&a) || sol_done[s] {
                    continue;
                }
                arc_done.push(a);
                sol_done[s] = true;
                self.arcs[a].values.push(v);
                self.arcs[a].qs.push(sols[s]);
                next.push(a);
            }
            // An arc the elimination lost at this value goes on by continuation, unless that
            // lands on another arc's solution.
            let mut taken: Vec<[f64; 7]> = next
                .iter()
                .map(|&a| self.arcs[a].qs[self.arcs[a].qs.len() - 1])
                .collect();
            for &a in &active {
                if arc_done.contains(&a) {
                    continue;
                }
                let last = *self.arcs[a].qs.last().unwrap_or(&[0.0; 7]);
                match self.newton_step(&last, v) {
                    Some(s) if taken.iter().all(|t| distance(t, &s) > 1e-6) => {
                        self.arcs[a].values.push(v);
                        self.arcs[a].qs.push(s);
                        taken.push(s);
                        next.push(a);
                    }
                    _ => self.refine_end(a, prev, v),
                }
            }
            for (s, q) in sols.iter().enumerate() {
                if sol_done[s] {
                    continue;
                }
                let mut arc = Arc::default();
                if i > 0
                    && let Some((v0, q0)) = self.refine_start(q, prev, v)
                {
                    arc.values.push(v0);
                    arc.qs.push(q0);
                }
                arc.values.push(v);
                arc.qs.push(*q);
                self.arcs.push(arc);
                next.push(self.arcs.len() - 1);
            }
            active = next;
            prev = v;
        }
    }

    /// Bisection for where arc `a` (alive at `alive`) ends before `dead`.
    fn refine_end(&mut self, a: usize, alive: f64, dead: f64) {
        let mut q = *self.arcs[a].qs.last().unwrap_or(&[0.0; 7]);
        let (mut lo, mut hi) = (alive, dead);
        while (hi - lo).abs() > REFINE {
            let mid = 0.5 * (lo + hi);
            match self.continue_from(&q, mid) {
                Some(s) => (lo, q) = (mid, s),
                None => hi = mid,
            }
        }
        if lo != alive {
            self.arcs[a].values.push(lo);
            self.arcs[a].qs.push(q);
        }
    }

    /// Bisection for where an arc alive at `alive` (solution `q`) starts after `dead`.
    fn refine_start(&self, q: &[f64; 7], dead: f64, alive: f64) -> Option<(f64, [f64; 7])> {
        let mut q = *q;
        let (mut lo, mut hi) = (dead, alive);
        while (hi - lo).abs() > REFINE {
            let mid = 0.5 * (lo + hi);
            match self.continue_from(&q, mid) {
                Some(s) => (hi, q) = (mid, s),
                None => lo = mid,
            }
        }
        (hi != alive).then_some((hi, q))
    }

    /// The pieces of arc `a` inside the joint limits, their ends refined by bisection.
    fn feasible_of(&self, a: usize) -> Vec<[f64; 2]> {
        let arc = &self.arcs[a];
        let ok = |q: &[f64; 7]| within(q, &self.limits);
        let mut pieces = Vec::new();
        let mut start: Option<f64> = ok(&arc.qs[0]).then_some(arc.values[0]);
        for i in 1..arc.values.len() {
            let (was, is) = (ok(&arc.qs[i - 1]), ok(&arc.qs[i]));
            if was == is {
                continue;
            }
            // Bisect the crossing between samples i - 1 and i.
            let (mut lo, mut hi, mut q) = (arc.values[i - 1], arc.values[i], arc.qs[i - 1]);
            while hi - lo > REFINE {
                let mid = 0.5 * (lo + hi);
                let Some(s) = self.continue_from(&q, mid) else {
                    break;
                };
                if ok(&s) == was {
                    (lo, q) = (mid, s);
                } else {
                    hi = mid;
                }
            }
            if was {
                pieces.push([start.take().unwrap_or(lo), lo]);
            } else {
                start = Some(hi);
            }
        }
        if let Some(s) = start {
            pieces.push([s, arc.range()[1]]);
        }
        pieces
    }

    /// Connected curves inside the limits: pieces joined where two arcs meet (a turning point).
    fn count(&self) -> usize {
        let ends: Vec<f64> = self.arcs.iter().flat_map(|a| a.range()).collect();
        let same = |a: usize, b: usize, v: f64| {
            let end_at = |arc: &Arc| {
                let [s, e] = arc.range();
                if (s - v).abs() < 1e-7 {
                    Some(arc.qs[0])
                } else if (e - v).abs() < 1e-7 {
                    arc.qs.last().copied()
                } else {
                    None
                }
            };
            match (end_at(&self.arcs[a]), end_at(&self.arcs[b])) {
                (Some(x), Some(y)) => distance(&x, &y) < 1e-3,
                _ => false,
            }
        };
        count_manifolds(&self.feasible, &ends, &same)
    }

    /// The parameter's name, e.g. "q3 (locked)".
    pub fn parameter(&self) -> &'static str {
        NAMES[self.arm.locked()]
    }

    /// The locked joint (0-based).
    pub fn locked(&self) -> usize {
        self.arm.locked()
    }

    /// Which joint is locked and why, in words.
    pub fn why(&self) -> &str {
        &self.why
    }

    /// Branch names ("branch 1", ...).
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// Feasible intervals of each branch (rad), inside the joint limits.
    pub fn feasible(&self) -> &[Vec<[f64; 2]>] {
        &self.feasible
    }

    /// Disjoint self-motion curves inside the limits.
    pub fn manifolds(&self) -> usize {
        self.manifolds
    }

    /// Every branch alive at `value` (rad), FK-checked against the target.
    pub fn solutions(&self, robot: &Robot, value: f64) -> Vec<BranchSolution> {
        let sols = self.solve(value);
        let mut out = Vec::new();
        for (a, arc) in self.arcs.iter().enumerate() {
            let [s, e] = arc.range();
            if value < s - REFINE || value > e + REFINE {
                continue;
            }
            let guess = arc.guess(value);
            if let Some(q) = sols
                .iter()
                .min_by(|x, y| distance(x, &guess).total_cmp(&distance(y, &guess)))
            {
                out.push(checked(
                    robot,
                    &self.target,
                    self.names[a].clone(),
                    q,
                    &self.limits,
                ));
            }
        }
        out
    }
}

/// Joint `k`'s value where the pose fixes it: the pose is reached (a numerical solution from
/// a few starts) and the Jacobian's null space there leaves joint `k` still (its component of
/// the null vector below 1e-9 of the vector), so the self-motion keeps `q[k]` (an SRS arm's
/// elbow). `None` when the pose is not reached or joint `k` moves with the self-motion.
fn fixed_by_pose(robot: &Robot, target: &Pose, k: usize) -> Option<f64> {
    use crate::kinematics::ik::Target;
    use crate::kinematics::ik::numerical::{NumericalOptions, solve};
    let starts = [
        robot.ready_or_zero(),
        vec![0.3; robot.dof()],
        vec![-0.6; robot.dof()],
    ];
    let q = starts.iter().find_map(|seed| {
        let opts = NumericalOptions::default();
        let rep = solve(robot, 0, &Target::Pose(*target), seed, &opts).ok()?;
        rep.converged.then_some(rep.q)
    })?;
    let j = robot.jacobian(&q, 0).ok()?;
    let jm = nalgebra::DMatrix::from_fn(6, j.ncols(), |r, c| j[(r, c)]);
    // the null vector: the eigenvector of J^T J of the smallest eigenvalue
    let e = (jm.transpose() * &jm).symmetric_eigen();
    let i = e.eigenvalues.argmin().0;
    let null = e.eigenvectors.column(i);
    (null[k].abs() < 1e-9 * null.norm()).then_some(q[k])
}
