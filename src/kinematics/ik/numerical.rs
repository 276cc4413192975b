//! Numerical inverse kinematics for any chain (Sect. 2.12 and 3.7): Levenberg–Marquardt on the
//! geometric Jacobian with joint limits, plus damped least squares, pseudo-inverse and Jacobian
//! transpose for teaching comparisons; task masks (functional redundancy, r < m), a null-space
//! secondary objective for redundant arms, and seeded random restarts.
//!
//! A solver that does not converge returns an [`IkReport`] with `converged = false`, not an error.

mod secondary;

use super::{IkError, Target, check_target};
use crate::kinematics::pose::Pose;
use crate::kinematics::robot::Robot;
use nalgebra::{DMatrix, DVector, Matrix6, Matrix6xX, Rotation3, Vector3, Vector6};
use secondary::improve_secondary;
use std::f64::consts::TAU;

/// The update rule.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Method {
    /// Levenberg–Marquardt: damped Gauss–Newton with the damping adapted each step (accept a
    /// step that lowers the error and relax the damping, otherwise raise it). Fast and robust.
    #[default]
    LevenbergMarquardt,
    /// Damped least squares with a fixed damping: `dq = J^T (J J^T + lambda^2 I)^-1 e`.
    DampedLeastSquares,
    /// Pseudo-inverse (Gauss–Newton): `dq = J^+ e`; diverges near singularities, (3.72).
    PseudoInverse,
    /// Jacobian transpose: `dq = alpha J^T e`, (3.78); slow but never inverts.
    Transpose,
}

/// The frame in which a [`TaskMask`] names its components.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MaskFrame {
    /// World axes: x, y, z and rotations about them.
    #[default]
    World,
    /// Tool axes at the current configuration: e.g. "free about the approach axis z_e", which a
    /// world-frame mask cannot say (Sect. 2.10.2's laser cutting).
    Tool,
}

/// Which components of the 6-vector error `[p; orientation]` the task constrains, and in which
/// frame (field 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TaskMask(pub [bool; 6], pub MaskFrame);

impl TaskMask {
    /// All six components (a full pose).
    pub const FULL: TaskMask = TaskMask([true; 6], MaskFrame::World);
    /// Position only (x, y, z).
    pub const POSITION: TaskMask =
        TaskMask([true, true, true, false, false, false], MaskFrame::World);
    /// Planar task (x, y and rotation about z).
    pub const PLANAR: TaskMask =
        TaskMask([true, true, false, false, false, true], MaskFrame::World);

    /// The mask of a task of Sect. 2.10.2, in the tool frame.
    pub fn of_task(task: crate::kinematics::redundancy::Task) -> Self {
        TaskMask(task.tool_components(), MaskFrame::Tool)
    }

    /// Number of constrained components r.
    pub fn count(&self) -> usize {
        self.0.iter().filter(|&&b| b).count()
    }
}

/// A secondary objective optimised in the null space of the task (redundant arms only).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Secondary {
    /// None.
    #[default]
    None,
    /// Stay away from joint limits: maximise `-1/(2n) sum ((q_i - mid_i)/range_i)^2`, (3.55);
    /// `gain` scales the gradient step (dimensionless, ~0.1–1).
    JointLimits {
        /// Step gain.
        gain: f64,
    },
    /// Maximise manipulability `sqrt(det(J J^T))`, (3.56), by a finite-difference gradient.
    Manipulability {
        /// Step gain.
        gain: f64,
    },
}

/// Options of the numerical solver. Every field documents its unit and trade-off.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NumericalOptions {
    /// The update rule.
    pub method: Method,
    /// Iterations per attempt. Raising it helps slow methods (transpose) converge, at more cost
    /// per failure.
    pub max_iterations: usize,
    /// Random restarts after the first attempt fails (0 = none). More restarts raise the success
    /// rate on hard targets; unreachable targets cost `(1 + restarts) * max_iterations`.
    pub restarts: usize,
    /// Convergence threshold on the position error (m) and on the orientation error (rad).
    pub tolerance: f64,
    /// Initial damping of Levenberg–Marquardt, or the fixed lambda of damped least squares (m,
    /// rad scale). Larger is more robust near singularities and slower to converge.
    pub damping: f64,
    /// Gain alpha of the Jacobian-transpose method (1/s in the continuous form; here per step).
    pub transpose_gain: f64,
    /// Largest joint step per iteration (rad or m); keeps far-off starts from overshooting.
    pub max_step: f64,
    /// Which error components count.
    pub mask: TaskMask,
    /// Secondary objective in the null space.
    pub secondary: Secondary,
    /// Clamp every iterate into the joint limits.
    pub enforce_limits: bool,
    /// Seed of the random restarts: the same seed gives the same answer.
    pub seed: u64,
}

impl Default for NumericalOptions {
    fn default() -> Self {
        Self {
            method: Method::LevenbergMarquardt,
            max_iterations: 100,
            restarts: 50,
            tolerance: 1e-10,
            damping: 1e-2,
            transpose_gain: 0.5,
            max_step: 0.5,
            mask: TaskMask::FULL,
            secondary: Secondary::None,
            enforce_limits: true,
            seed: 0x5EED,
        }
    }
}

/// What the numerical solver did.
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct IkReport {
    /// Final joint vector (the best found when not converged).
    pub q: Vec<f64>,
    /// Whether both errors are below the tolerance.
    pub converged: bool,
    /// Iterations over all attempts.
    pub iterations: usize,
    /// Restarts used.
    pub restarts: usize,
    /// Position error |p_d - p| over the masked components (m).
    pub position_error: f64,
    /// Orientation error over the masked components (rad).
    pub orientation_error: f64,
}

/// SplitMix64: a small deterministic generator for restarts and simulated data (no dependency,
/// no global state).
#[derive(Debug, Clone)]
pub(crate) struct SplitMix(pub(crate) u64);

impl SplitMix {
    /// Uniform in [0, 1).
    pub(crate) fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The desired pose and the mask a target implies (the mask of `opts` is intersected with it).
fn desired(target: &Target, mask: TaskMask) -> (Pose, TaskMask) {
    let and = |m: TaskMask| TaskMask(std::array::from_fn(|i| m.0[i] && mask.0[i]), mask.1);
    match *target {
        Target::Pose(p) => (p, mask),
        Target::Position(p) => (Pose::translation(p.x, p.y, p.z), and(TaskMask::POSITION)),
        Target::Planar { px, py, phi } => (
            Pose::translation(px, py, 0.0) * crate::kinematics::pose::rot_z(phi),
            and(TaskMask::PLANAR),
        ),
    }
}

/// Error `[p_d - p; r theta]` with `R_d R^T = Rot(r, theta)` (world frame; rotated into the
/// tool frame `R^T` for a tool-frame mask), masked.
pub(crate) fn error(d: &Pose, t: &Pose, mask: &TaskMask) -> Vector6<f64> {
    let ep = d.translation.vector - t.translation.vector;
    let re: Rotation3<f64> = d.rotation * t.rotation.inverse();
    // (2.26)-(2.27) through the robust atan2 form (nalgebra's angle() uses acos, which loses
    // half the digits near zero).
    let aa = crate::kinematics::orientation::angle_axis_from_rotation(&re);
    let eo = aa.axis.into_inner() * aa.angle;
    let (ep, eo) = match mask.1 {
        MaskFrame::World => (ep, eo),
        MaskFrame::Tool => {
            let r = t.rotation.inverse();
            (r * ep, r * eo)
        }
    };
    let mut e = Vector6::new(ep.x, ep.y, ep.z, eo.x, eo.y, eo.z);
    for (i, on) in mask.0.iter().enumerate() {
        if !on {
            e[i] = 0.0;
        }
    }
    e
}

/// The Jacobian's rows in the mask's frame (`diag(R^T, R^T) J` for a tool-frame mask, R the
/// tool's rotation at the same configuration), the rows the mask leaves out zeroed.
pub(crate) fn mask_rows(jac: &mut Matrix6xX<f64>, t: &Pose, mask: &TaskMask) {
    if mask.1 == MaskFrame::Tool {
        let r = t.rotation.inverse();
        for c in 0..jac.ncols() {
            let mut col = jac.column_mut(c);
            let lin = r * Vector3::new(col[0], col[1], col[2]);
            let ang = r * Vector3::new(col[3], col[4], col[5]);
            col.copy_from_slice(&[lin.x, lin.y, lin.z, ang.x, ang.y, ang.z]);
        }
    }
    for (i, l) in mask.0.iter().enumerate() {
        if !l {
            jac.row_mut(i).fill(0.0);
        }
    }
}

/// Position (m) and orientation (rad) errors of `actual` from `desired` over the components
/// the task constrains (in the mask's frame): what a partial task holds.
pub fn task_errors(desired: &Pose, actual: &Pose, mask: &TaskMask) -> (f64, f64) {
    split_norms(&error(desired, actual, mask))
}

fn split_norms(e: &Vector6<f64>) -> (f64, f64) {
    (e.fixed_rows::<3>(0).norm(), e.fixed_rows::<3>(3).norm())
}

/// The joint limits as the solver uses them, gathered once per solve.
struct Bounds {
    /// `[lower, upper]` per joint (infinite = open).
    limits: Vec<[f64; 2]>,
    /// Whether each joint is revolute (shifted by 2 pi before clamping).
    revolute: Vec<bool>,
    /// Finite ranges the restarts draw from ([`Robot::sampling_range`]).
    sample: Vec<[f64; 2]>,
}

impl Bounds {
    fn of(robot: &Robot) -> Self {
        Self {
            limits: robot.limits(),
            revolute: (0..robot.dof())
                .map(|k| robot.dof_joint(k).kind == crate::kinematics::JointKind::Revolute)
                .collect(),
            sample: robot.sampling_ranges(),
        }
    }

    fn clamp(&self, q: &mut [f64]) {
        clamp(q, &self.limits, &self.revolute);
    }
}

/// Scratch buffers of one solve, allocated once.
struct Scratch {
    frames: Vec<Pose>,
    jac: Matrix6xX<f64>,
    trial: Vec<f64>,
    dq: DVector<f64>,
    /// Geodesic acceleration of the Levenberg–Marquardt step.
    acc: DVector<f64>,
    /// The iterate of the try without limits.
    free: Vec<f64>,
}

/// Solves IK numerically for end-effector `ee` from `seed_q`. Invalid input (NaN target, wrong
/// seed length) is an error; failure to converge is a report with `converged = false`.
///
/// # Examples
///
/// The four-link planar arm is redundant for a planar task (x, y, phi) (Sect. 2.10.2): one of
/// its infinitely many solutions, from the seed.
///
/// ```
/// use armlab::kinematics::ik::Target;
/// use armlab::kinematics::ik::numerical::{NumericalOptions, solve};
/// use armlab::kinematics::models::built_in;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let arm = built_in("planar4").expect("a built-in model");
/// let (px, py, phi) = (0.5, 0.4, 1.0);
/// let target = Target::Planar { px, py, phi };
/// let report = solve(&arm, 0, &target, &arm.ready_or_zero(), &NumericalOptions::default())?;
/// assert!(report.converged);
/// let t = arm.fk(&report.q)?;
/// assert!((t.translation.vector.x - px).abs() < 1e-9 && (t.translation.vector.y - py).abs() < 1e-9);
/// // The tool's orientation in the plane is the sum of the joint angles.
/// let sum: f64 = report.q.iter().sum();
/// assert!((armlab::kinematics::orientation::wrap_angle(sum - phi)).abs() < 1e-9);
/// # Ok(())
/// # }
/// ```
///
/// A target out of reach is not an error: the report says it did not converge, and how far
/// the best configuration found is from the target.
///
/// ```
/// use armlab::kinematics::ik::Target;
/// use armlab::kinematics::ik::numerical::{Method, NumericalOptions, solve};
/// use armlab::kinematics::models::built_in;
/// use armlab::nalgebra::Vector3;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let arm = built_in("planar2").expect("a built-in model"); // reaches 2 m
/// let opts = NumericalOptions { method: Method::DampedLeastSquares, restarts: 2, ..Default::default() };
/// let far = Target::Position(Vector3::new(3.0, 0.0, 0.0));
/// let report = solve(&arm, 0, &far, &[0.2, 0.3], &opts)?;
/// assert!(!report.converged);
/// // The target is 3 m from the base and the arm reaches 2 m: at best 1 m off.
/// assert!(report.position_error >= 1.0 - 1e-12);
/// // Bad input is an error: a seed of the wrong length.
/// assert!(solve(&arm, 0, &far, &[0.0], &opts).is_err());
/// # Ok(())
/// # }
/// ```
pub fn solve(
    robot: &Robot,
    ee: usize,
    target: &Target,
    seed_q: &[f64],
    opts: &NumericalOptions,
) -> Result<IkReport, IkError> {
    check_target(target)?;
    robot.check_q(seed_q)?;
    robot.fk_ee(seed_q, ee)?;
    let (goal, mask) = desired(target, opts.mask);
    let n = robot.dof();
    let bounds = Bounds::of(robot);
    let mut s = Scratch {
        frames: vec![Pose::identity(); robot.joints().len()],
        jac: Matrix6xX::zeros(n),
        trial: vec![0.0; n],
        dq: DVector::zeros(n),
        acc: DVector::zeros(n),
        free: Vec::with_capacity(n),
    };
    let mut rng = SplitMix(opts.seed);
    let mut q: Vec<f64> = seed_q.to_vec();
    if opts.enforce_limits {
        bounds.clamp(&mut q);
    }
    let mut best: Option<(f64, Vec<f64>, Vector6<f64>)> = None;
    let mut iterations = 0;
    for attempt in 0..=opts.restarts {
        if attempt > 0 {
            for (v, l) in q.iter_mut().zip(&bounds.sample) {
                *v = l[0] + (l[1] - l[0]) * rng.next_f64();
            }
        }
        let (it, e) = if opts.enforce_limits && opts.method == Method::LevenbergMarquardt {
            // A non-redundant arm whose unlimited answer lies outside the limits goes on to the
            // next restart at once: its limited try rarely succeeds (measured on the Puma 560).
            // Without restarts (the app's tracking) the limited try from the seed still runs, so
            // that the arm gets as close as its limits allow.
            let free_only = (attempt > 0 || opts.restarts > 0) && n <= mask.count();
            limited_attempt(
                robot, ee, &goal, &mask, opts, &bounds, free_only, &mut q, &mut s,
            )?
        } else {
            descend(robot, ee, &goal, &mask, opts, &bounds, &mut q, &mut s)?
        };
        iterations += it;
        let (pe, oe) = split_norms(&e);
        let cost = pe.max(oe);
        if best.as_ref().is_none_or(|b| cost < b.0) {
            best = Some((cost, q.clone(), e));
        }
        if pe <= opts.tolerance && oe <= opts.tolerance {
            let (q, e, it) = if opts.secondary != Secondary::None && n > mask.count() {
                improve_secondary(robot, ee, &goal, &mask, opts, &bounds, q, e, &mut s)?
            } else {
                (q, e, 0)
            };
            let (pe, oe) = split_norms(&e);
            return Ok(IkReport {
                q,
                converged: true,
                iterations: iterations + it,
                restarts: attempt,
                position_error: pe,
                orientation_error: oe,
            });
        }
    }
    let (_, q, e) = best.unwrap_or((f64::INFINITY, seed_q.to_vec(), Vector6::zeros()));
    let (pe, oe) = split_norms(&e);
    Ok(IkReport {
        q,
        converged: false,
        iterations,
        restarts: opts.restarts,
        position_error: pe,
        orientation_error: oe,
    })
}

/// Keeps every joint inside its limits: a revolute angle outside is first shifted by a multiple
/// of 2 pi into the range where one fits (the same configuration), then clamped; open bounds
/// (infinite) clamp nothing.
fn clamp(q: &mut [f64], limits: &[[f64; 2]], revolute: &[bool]) {
    for ((v, l), &rev) in q.iter_mut().zip(limits).zip(revolute) {
        if *v >= l[0] && *v <= l[1] {
            continue;
        }
        if rev {
            let k_lo = ((l[0] - *v) / TAU).ceil();
            if k_lo.is_finite() && *v + k_lo * TAU <= l[1] {
                *v += k_lo * TAU;
                continue;
            }
            let k_hi = ((l[1] - *v) / TAU).floor();
            if k_hi.is_finite() && *v + k_hi * TAU >= l[0] {
                *v += k_hi * TAU;
                continue;
            }
        }
        *v = v.clamp(l[0], l[1]);
    }
}

/// One attempt under joint limits, in two tries from the same start: first without the limits
/// (Levenberg–Marquardt converges in a few steps where the limits would stop it at a local
/// minimum against a bound), and if the answer lies inside the limits after shifting revolute
/// joints by 2 pi, that is the solution; otherwise the limited attempt from the start. Measured
/// on the Puma 560 and the Panda from the zero and "ready" seeds, this removes most restarts.
#[allow(clippy::too_many_arguments)]
fn limited_attempt(
    robot: &Robot,
    ee: usize,
    goal: &Pose,
    mask: &TaskMask,
    opts: &NumericalOptions,
    bounds: &Bounds,
    free_only: bool,
    q: &mut [f64],
    s: &mut Scratch,
) -> Result<(usize, Vector6<f64>), IkError> {
    let mut free = std::mem::take(&mut s.free);
    free.clear();
    free.extend_from_slice(q);
    let unlimited = NumericalOptions {
        enforce_limits: false,
        ..*opts
    };
    let (it_free, e_free) = descend(robot, ee, goal, mask, &unlimited, bounds, &mut free, s)?;
    let (pe, oe) = split_norms(&e_free);
    if pe <= opts.tolerance && oe <= opts.tolerance {
        bounds.clamp(&mut free);
        if free
            .iter()
            .zip(&bounds.limits)
            .all(|(v, l)| *v >= l[0] && *v <= l[1])
        {
            let e = error(goal, &robot.fk_ee(&free, ee)?, mask);
            let (pe, oe) = split_norms(&e);
            if pe <= opts.tolerance && oe <= opts.tolerance {
                q.copy_from_slice(&free);
                s.free = free;
                return Ok((it_free, e));
            }
        }
    }
    s.free = free;
    if free_only {
        // Report the start's error so that the best-so-far bookkeeping stays honest.
        let e = error(goal, &robot.fk_ee(q, ee)?, mask);
        return Ok((it_free, e));
    }
    let (it, e) = descend(robot, ee, goal, mask, opts, bounds, q, s)?;
    Ok((it_free + it, e))
}

/// The Jacobian at `q` with the rows the mask leaves out zeroed, and the error there.
fn masked_jacobian(
    robot: &Robot,
    ee: usize,
    goal: &Pose,
    mask: &TaskMask,
    q: &[f64],
    s: &mut Scratch,
) -> Result<Vector6<f64>, IkError> {
    let t = robot.jacobian_into(q, ee, &mut s.frames, &mut s.jac)?;
    mask_rows(&mut s.jac, &t, mask);
    Ok(error(goal, &t, mask))
}

/// `J J^T` (6 x 6) summed column by column: the generic product of a dynamic-width matrix goes
/// through a packing GEMM that allocates on every call (measured: a tenth of an LM solve).
#[inline]
fn gram(jac: &Matrix6xX<f64>) -> Matrix6<f64> {
    let mut a = Matrix6::zeros();
    for c in jac.column_iter() {
        for j in 0..6 {
            for i in j..6 {
                a[(i, j)] += c[i] * c[j];
            }
        }
    }
    for j in 0..6 {
        for i in 0..j {
            a[(i, j)] = a[(j, i)];
        }
    }
    a
}

/// `(J J^T + lambda I)` for the masked rows (a unit diagonal for the others), factored.
fn damped_factor(
    jac: &Matrix6xX<f64>,
    lambda: f64,
    mask: &TaskMask,
) -> Option<nalgebra::Cholesky<f64, nalgebra::U6>> {
    let mut a: Matrix6<f64> = gram(jac);
    for i in 0..6 {
        if mask.0[i] {
            a[(i, i)] += lambda;
        } else {
            a.row_mut(i).fill(0.0);
            a.column_mut(i).fill(0.0);
            a[(i, i)] = 1.0;
        }
    }
    a.cholesky()
}

/// Iterations over which Levenberg–Marquardt must at least halve the error (when the error is
/// above `sqrt(STALL_COST)`), or the attempt ends and a restart follows.
const STALL_WINDOW: usize = 10;
/// Squared error (m^2 + rad^2; 1e-4 as a norm) below which an attempt is never called stalled: close to the goal,
/// slow progress is the convergence near a singularity, not a local minimum.
const STALL_COST: f64 = 1e-8;

/// Largest ratio |a| / |v| of the geodesic acceleration to the velocity for which the
/// second-order step is taken (Transtrum & Sethna's alpha).
const ACCELERATION_RATIO: f64 = 0.75;
/// Finite-difference step (a fraction of the step) for the second directional derivative.
const ACCELERATION_PROBE: f64 = 0.1;

/// How an attempt fared over the last [`STALL_WINDOW`] iterations.
enum Progress {
    /// The error at least halved.
    Good,
    /// Far from the goal and the error not even halved: a local minimum (at a joint limit,
    /// most often), and a restart is cheaper than crawling.
    Stalled,
    /// Slow beside the goal: the valley of a near-singular goal, where every step needs the
    /// curvature correction; it goes on.
    Crawling,
}

fn progress(cost: f64, cost_before: f64) -> Progress {
    if cost <= 0.25 * cost_before {
        Progress::Good
    } else if cost > STALL_COST {
        Progress::Stalled
    } else {
        Progress::Crawling
    }
}

/// Adds half the geodesic acceleration to the step `s.dq` (Transtrum & Sethna 2012): the second
/// directional derivative of the error along the step, by one extra forward kinematics, and the
/// same damped solve; skipped when it is not small against the step (the model is too poor).
#[allow(clippy::too_many_arguments)]
fn accelerate(
    robot: &Robot,
    ee: usize,
    goal: &Pose,
    mask: &TaskMask,
    q: &[f64],
    e: &Vector6<f64>,
    jv: &Vector6<f64>,
    ch: &nalgebra::Cholesky<f64, nalgebra::U6>,
    s: &mut Scratch,
) -> Result<(), IkError> {
    let h = ACCELERATION_PROBE;
    for ((t, &v), d) in s.trial.iter_mut().zip(q.iter()).zip(s.dq.iter()) {
        *t = v + h * d;
    }
    let e_probe = error(goal, &robot.fk_ee(&s.trial, ee)?, mask);
    // e(q + h v) = e - h J v - h^2/2 e'': the second directional derivative, sign as J v.
    let second = ((e - e_probe) / h - jv) * (2.0 / h);
    s.acc.gemv_tr(-1.0, &s.jac, &ch.solve(&second), 0.0);
    if s.acc.norm() <= ACCELERATION_RATIO * s.dq.norm() {
        s.dq.axpy(0.5, &s.acc, 1.0);
    }
    Ok(())
}

/// One attempt from `q`, the one iteration loop of every method: a step (see [`Method`]),
/// capped at `max_step`, clamped into the limits when they are enforced, and the trial's error.
///
/// For Levenberg–Marquardt the step is the damped Gauss–Newton step
/// `v = J^T (J J^T + lambda I)^-1 e`, with its geodesic acceleration whenever the previous step
/// fitted the linear model poorly (Transtrum & Sethna 2012: the second directional derivative of
/// the error along v, by one extra forward kinematics, corrects the step for the curvature of the
/// solution's valley, which is what makes plain LM crawl beside singular goals); a trial is kept
/// only if it lowers the error, with Nielsen's damping update from the ratio of actual to
/// predicted decrease, and the attempt ends early when the error stalls far from the goal
/// ([`STALL_WINDOW`]). The other methods take every step.
#[allow(clippy::too_many_arguments)]
fn descend(
    robot: &Robot,
    ee: usize,
    goal: &Pose,
    mask: &TaskMask,
    opts: &NumericalOptions,
    bounds: &Bounds,
    q: &mut [f64],
    s: &mut Scratch,
) -> Result<(usize, Vector6<f64>), IkError> {
    let lm = opts.method == Method::LevenbergMarquardt;
    let mut damping = Damping {
        lambda: opts.damping,
        nu: 2.0,
    };
    let mut e = masked_jacobian(robot, ee, goal, mask, q, s)?;
    let mut cost = e.norm_squared();
    let mut cost_before = cost;
    let mut poor_fit = true;
    let mut crawling = false;
    for it in 1..=opts.max_iterations {
        let (pe, oe) = split_norms(&e);
        if pe <= opts.tolerance && oe <= opts.tolerance {
            return Ok((it - 1, e));
        }
        if lm && it % STALL_WINDOW == 0 {
            match progress(cost, cost_before) {
                Progress::Stalled => return Ok((it, e)),
                Progress::Crawling => crawling = true,
                Progress::Good => {}
            }
            cost_before = cost;
        }
        let Some(factor) = take_step(opts, damping.lambda, mask, &e, s) else {
            return Ok((it, e));
        };
        let jv: Vector6<f64> = &s.jac * &s.dq;
        if let (true, Some(ch)) = (lm && (poor_fit || crawling), &factor) {
            // The last step's decrease fell short of the linear model's: correct for the
            // curvature (once the model fits, plain steps converge quadratically).
            accelerate(robot, ee, goal, mask, q, &e, &jv, ch, s)?;
        }
        set_trial(q, opts, bounds, s);
        let c_trial = if lm {
            error(goal, &robot.fk_ee(&s.trial, ee)?, mask).norm_squared()
        } else {
            0.0
        };
        if !lm || c_trial < cost {
            if lm {
                let predicted = cost - (e - jv).norm_squared();
                let rho = if predicted > 0.0 {
                    (cost - c_trial) / predicted
                } else {
                    1.0
                };
                damping.accepted(rho);
                poor_fit = rho < 0.25;
            }
            q.copy_from_slice(&s.trial);
            e = masked_jacobian(robot, ee, goal, mask, q, s)?;
            cost = e.norm_squared();
        } else {
            poor_fit = true;
            if !damping.rejected() {
                return Ok((it, e));
            }
        }
        if !cost.is_finite() {
            return Ok((it, e));
        }
    }
    Ok((opts.max_iterations, e))
}

/// Levenberg–Marquardt's damping lambda and the factor nu it grows by after a rejected step.
struct Damping {
    lambda: f64,
    nu: f64,
}

impl Damping {
    /// Nielsen's update after an accepted step whose actual decrease was `rho` times the
    /// predicted one.
    fn accepted(&mut self, rho: f64) {
        self.lambda =
            (self.lambda * (1.0 / 3.0f64).max(1.0 - (2.0 * rho - 1.0).powi(3))).max(1e-14);
        self.nu = 2.0;
    }

    /// After a rejected step: damp more; `false` once the damping is past any use (1e8).
    fn rejected(&mut self) -> bool {
        self.lambda *= self.nu;
        self.nu *= 2.0;
        self.lambda <= 1e8
    }
}

/// The factor of `J J^T + lambda I` that a damped step was made with.
type Factor = nalgebra::Cholesky<f64, nalgebra::U6>;

/// The step of `opts.method` from the error `e` into `s.dq`: damped least squares with `lambda`
/// (Levenberg–Marquardt) or `damping^2` (DLS), the pseudo-inverse, or the scaled transpose.
/// `Some(factor)` when a step was made (the factor for LM and DLS, `None` for the others);
/// `None` when none could be (a factorization or the pseudo-inverse failed).
fn take_step(
    opts: &NumericalOptions,
    lambda: f64,
    mask: &TaskMask,
    e: &Vector6<f64>,
    s: &mut Scratch,
) -> Option<Option<Factor>> {
    match opts.method {
        Method::LevenbergMarquardt | Method::DampedLeastSquares => {
            let damping = if opts.method == Method::LevenbergMarquardt {
                lambda
            } else {
                opts.damping * opts.damping
            };
            let ch = damped_factor(&s.jac, damping, mask)?;
            s.dq.gemv_tr(1.0, &s.jac, &ch.solve(e), 0.0);
            Some(Some(ch))
        }
        Method::PseudoInverse => pinv_step(&s.jac, e, &mut s.dq).then_some(None),
        Method::Transpose => {
            s.dq.gemv_tr(opts.transpose_gain, &s.jac, e, 0.0);
            Some(None)
        }
    }
}

/// `s.trial = q + s.dq`, the step first capped at `max_step` (its largest component) and the
/// trial then clamped into the limits when they are enforced.
fn set_trial(q: &[f64], opts: &NumericalOptions, bounds: &Bounds, s: &mut Scratch) {
    let norm = s.dq.amax();
    if norm > opts.max_step {
        s.dq *= opts.max_step / norm;
    }
    for ((t, &v), d) in s.trial.iter_mut().zip(q.iter()).zip(s.dq.iter()) {
        *t = v + d;
    }
    if opts.enforce_limits {
        bounds.clamp(&mut s.trial);
    }
}

fn pinv_step(jac: &Matrix6xX<f64>, e: &Vector6<f64>, dq: &mut DVector<f64>) -> bool {
    let j = DMatrix::from_column_slice(6, jac.ncols(), jac.as_slice());
    match j.pseudo_inverse(1e-12) {
        Ok(p) => {
            let ev = DVector::from_column_slice(e.as_slice());
            dq.copy_from(&(p * ev));
            true
        }
        Err(_) => false,
    }
}

/// Distances of a report from the target, for callers that polish closed-form answers.
pub fn pose_errors(
    robot: &Robot,
    ee: usize,
    q: &[f64],
    target: &Target,
) -> Result<(f64, f64), IkError> {
    let t = robot.fk_ee(q, ee)?;
    Ok(match target {
        Target::Pose(d) => {
            let e = error(d, &t, &TaskMask::FULL);
            split_norms(&e)
        }
        Target::Position(p) => ((p - t.translation.vector).norm(), 0.0),
        Target::Planar { px, py, phi } => {
            let p = t.translation.vector;
            let dp = Vector3::new(px - p.x, py - p.y, 0.0).norm();
            let ang = t.rotation.matrix()[(1, 0)].atan2(t.rotation.matrix()[(0, 0)]);
            (
                dp,
                crate::kinematics::orientation::wrap_angle(phi - ang).abs(),
            )
        }
    })
}
