//! An exact self-motion in a cell: the stretches of each branch's feasible intervals where the
//! arm hits itself or an obstacle, found on a grid of the parameter and refined by bisection,
//! and the collision-free intervals that are left.

use super::BranchSolution;
use super::motion::ExactSelfMotion;
use crate::collision::CollisionWorld;
use crate::kinematics::Robot;
use std::f64::consts::{PI, TAU};

/// How the collision-free intervals are found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CellScanOptions {
    /// Grid step of the parameter over [-pi, pi] (rad): every branch is solved once per grid
    /// value and checked at those inside its feasible intervals (and at their ends). A
    /// colliding stretch shorter than the step can fall between two grid values and be missed;
    /// a smaller step finds shorter ones at proportional cost.
    pub step: f64,
    /// How close each end of a collision-free interval is to where the collision starts
    /// (rad): the bisection stops when its bracket is half this wide. Each halving costs one
    /// check.
    pub tolerance: f64,
}

impl Default for CellScanOptions {
    /// A quarter of a degree, ends to 1e-6 rad.
    fn default() -> Self {
        CellScanOptions {
            step: 0.25f64.to_radians(),
            tolerance: 1e-6,
        }
    }
}

/// A stretch of one branch's parameter where the arm hits something.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct CollidingStretch {
    /// The branch (index into the self-motion's names).
    pub branch: usize,
    /// Where it starts (rad; the first colliding value, to the tolerance).
    pub from: f64,
    /// Where it ends (rad).
    pub to: f64,
    /// The first body of the deepest contact at the grid point nearest the stretch's middle
    /// (a link).
    pub a: String,
    /// The second body (a link or an obstacle).
    pub b: String,
    /// That contact's depth (m).
    pub depth_m: f64,
}

/// The collision-free part of an exact self-motion.
#[derive(Debug, Clone, PartialEq)]
pub struct CollisionFreeMotion {
    /// Per branch, the intervals of the parameter (rad, pieces of [-pi, pi]) inside the joint
    /// limits where the arm hits nothing: sub-intervals of the feasible ones.
    pub free: Vec<Vec<[f64; 2]>>,
    /// Every colliding stretch inside the feasible intervals, branch by branch in order.
    pub colliding: Vec<CollidingStretch>,
    /// The options used.
    pub options: CellScanOptions,
}

/// One grid point of a branch: free, hitting something, or without a solution.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum State {
    Free,
    Hit,
    Missing,
}

impl ExactSelfMotion {
    /// The collision-free intervals of every branch in `world` (built for `robot` and a cell):
    /// each feasible interval is sampled every `options.step` and every change between free
    /// and colliding is refined by bisection to `options.tolerance`.
    ///
    /// ```
    /// use armlab::collision::{CellScene, CollisionWorld, Obstacle};
    /// use armlab::kinematics::models::built_in;
    /// use armlab::redundancy::collision::CellScanOptions;
    /// use armlab::redundancy::motion::ExactSelfMotion;
    ///
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// let arm = built_in("planar3").expect("a built-in model");
    /// let pose = arm.fk(&[0.3, 0.8, 0.6])?;
    /// let motion = ExactSelfMotion::new(&arm, &pose)?;
    /// // A post where the first branch's elbow is at phi = 1 rad.
    /// let at = &motion.solutions(&arm, 1.0)[0];
    /// let elbow = arm.fk_frames(&at.q)?[0].translation.vector;
    /// let cell = CellScene {
    ///     obstacles: vec![Obstacle::cuboid("post", [0.04, 0.04, 1.0], elbow.into())],
    ///     ..CellScene::default()
    /// };
    /// let world = CollisionWorld::new(&arm, &cell)?;
    /// let free = motion.collision_free(&arm, &world, CellScanOptions::default());
    /// // That branch hits the post around phi = 1, and is free elsewhere.
    /// let hit = free.colliding.iter().find(|s| s.from < 1.0 && 1.0 < s.to).expect("a stretch");
    /// assert_eq!((hit.branch, hit.b.as_str()), (0, "post"));
    /// assert!(world.in_collision(&arm, &at.q)?);
    /// assert!(!free.free[0].is_empty());
    /// // The free intervals lie inside the feasible ones.
    /// for (f, feasible) in free.free.iter().zip(motion.feasible()) {
    ///     for iv in f {
    ///         assert!(feasible.iter().any(|g| g[0] <= iv[0] && iv[1] <= g[1]));
    ///     }
    /// }
    /// # Ok(())
    /// # }
    /// ```
    pub fn collision_free(
        &self,
        robot: &Robot,
        world: &CollisionWorld,
        options: CellScanOptions,
    ) -> CollisionFreeMotion {
        let mut out = CollisionFreeMotion {
            free: vec![Vec::new(); self.names().len()],
            colliding: Vec::new(),
            options,
        };
        // One grid over the whole circle, every branch solved once per value.
        let n = ((TAU / options.step.max(1e-6)).ceil() as usize).max(8);
        let grid: Vec<(f64, Vec<BranchSolution>)> = (0..=n)
            .map(|k| {
                let t = -PI + TAU * k as f64 / n as f64;
                (t, self.solutions(robot, t))
            })
            .collect();
        for (b, intervals) in self.feasible().iter().enumerate() {
            let scan = Branch {
                motion: self,
                robot,
                world,
                branch: b,
            };
            for &[lo, hi] in intervals {
                scan.interval(lo, hi, &grid, options, &mut out);
            }
        }
        out
    }
}

/// One branch of a self-motion in a world.
struct Branch<'a> {
    motion: &'a ExactSelfMotion,
    robot: &'a Robot,
    world: &'a CollisionWorld,
    branch: usize,
}

impl Branch<'_> {
    /// The branch's solution at `t` (rad).
    fn solution(&self, t: f64) -> Option<BranchSolution> {
        let name = &self.motion.names()[self.branch];
        self.motion
            .solutions(self.robot, t)
            .into_iter()
            .find(|s| &s.name == name)
    }

    fn state(&self, t: f64) -> State {
        self.state_of(self.solution(t).as_ref())
    }

    /// Between a free `f` and a not-free `n` (either order), the change refined until the
    /// bracket is at most `tol / 2`: (last free, first not free).
    fn bisect(&self, mut f: f64, mut n: f64, tol: f64) -> (f64, f64) {
        while (f - n).abs() > 0.5 * tol {
            let m = 0.5 * (f + n);
            if self.state(m) == State::Free {
                f = m;
            } else {
                n = m;
            }
        }
        (f, n)
    }

    /// The state of a solution already found (or missing).
    fn state_of(&self, s: Option<&BranchSolution>) -> State {
        match s {
            None => State::Missing,
            Some(s) => match self.world.in_collision(self.robot, &s.q) {
                Ok(false) => State::Free,
                _ => State::Hit,
            },
        }
    }

    /// Scans the feasible interval `[lo, hi]` at its ends and the grid's values inside it (see
    /// [`ExactSelfMotion::collision_free`]).
    fn interval(
        &self,
        lo: f64,
        hi: f64,
        grid: &[(f64, Vec<BranchSolution>)],
        options: CellScanOptions,
        out: &mut CollisionFreeMotion,
    ) {
        let name = &self.motion.names()[self.branch];
        let mut points: Vec<(f64, State)> = vec![(lo, self.state(lo))];
        for (t, sols) in grid {
            if *t > lo && *t < hi {
                points.push((*t, self.state_of(sols.iter().find(|s| &s.name == name))));
            }
        }
        if hi > lo {
            points.push((hi, self.state(hi)));
        }
        let n = points.len() - 1;
        let t = |i: usize| points[i].0;
        // Runs of equal freedom: [first, last] indices.
        let mut i = 0;
        while i <= n {
            let free = points[i].1 == State::Free;
            let mut j = i;
            while j < n && (points[j + 1].1 == State::Free) == free {
                j += 1;
            }
            // The run's ends: the interval's own ends, else the bisected changes.
            let start = match (i, free) {
                (0, _) => lo,
                (_, true) => self.bisect(t(i), t(i - 1), options.tolerance).0,
                (_, false) => self.bisect(t(i - 1), t(i), options.tolerance).1,
            };
            let end = match (j == n, free) {
                (true, _) => hi,
                (false, true) => self.bisect(t(j), t(j + 1), options.tolerance).0,
                (false, false) => self.bisect(t(j + 1), t(j), options.tolerance).1,
            };
            if free {
                out.free[self.branch].push([start, end]);
            } else {
                let states: Vec<(f64, State)> = points[i..=j].to_vec();
                out.colliding.push(self.stretch(start, end, &states));
            }
            i = j + 1;
        }
    }

    /// A colliding stretch from `from` to `to` (rad) over its scanned values `states`, named
    /// by the deepest contact at the scanned value nearest its middle that hits.
    fn stretch(&self, from: f64, to: f64, states: &[(f64, State)]) -> CollidingStretch {
        let middle = 0.5 * (from + to);
        let at = states
            .iter()
            .filter(|(_, s)| *s == State::Hit)
            .min_by(|x, y| (x.0 - middle).abs().total_cmp(&(y.0 - middle).abs()))
            .map(|(t, _)| *t);
        let contact = at
            .and_then(|t| self.solution(t))
            .and_then(|s| self.world.check(self.robot, &s.q).ok())
            .and_then(|r| r.pairs.into_iter().next());
        let (a, b, depth_m) = match contact {
            Some(c) => (c.a, c.b, c.depth_m),
            None => ("no solution".into(), String::new(), 0.0),
        };
        CollidingStretch {
            branch: self.branch,
            from,
            to,
            a,
            b,
            depth_m,
        }
    }
}
