//! Numerical inverse kinematics for any chain (Sect. 2.12 and 3.7): Levenberg–Marquardt on the
//! geometric Jacobian with joint limits, plus damped least squares, pseudo-inverse and Jacobian
//! transpose for teaching comparisons; task masks (functional redundancy, r < m), a null-space
//! secondary objective for redundant arms, and seeded random restarts.
//!
//! A solver that does not converge returns an [`IkReport`] with `converged = false`, not an error.

use super::{IkError, Target, check_target};
use crate::kinematics::pose::Pose;
use crate::kinematics::robot::Robot;
use nalgebra::{DMatrix, DVector, Matrix6, Matrix6xX, Rotation3, Vector3, Vector6};

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

/// Which components of the 6-vector error `[p; orientation]` (world frame) the task constrains.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TaskMask(pub [bool; 6]);

impl TaskMask {
    /// All six components (a full pose).
    pub const FULL: TaskMask = TaskMask([true; 6]);
    /// Position only (x, y, z).
    pub const POSITION: TaskMask = TaskMask([true, true, true, false, false, false]);
    /// Planar task (x, y and rotation about z).
    pub const PLANAR: TaskMask = TaskMask([true, true, false, false, false, true]);

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

/// SplitMix64: a small deterministic generator for restarts (no dependency, no global state).
#[derive(Debug, Clone)]
struct SplitMix(u64);

impl SplitMix {
    fn next_f64(&mut self) -> f64 {
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
    let and = |m: TaskMask| TaskMask(std::array::from_fn(|i| m.0[i] && mask.0[i]));
    match *target {
        Target::Pose(p) => (p, mask),
        Target::Position(p) => (Pose::translation(p.x, p.y, p.z), and(TaskMask::POSITION)),
        Target::Planar { px, py, phi } => (
            Pose::translation(px, py, 0.0) * crate::kinematics::pose::rot_z(phi),
            and(TaskMask::PLANAR),
        ),
    }
}

/// Error `[p_d - p; r theta]` with `R_d R^T = Rot(r, theta)` (world frame), masked.
fn error(d: &Pose, t: &Pose, mask: &TaskMask) -> Vector6<f64> {
    let ep = d.translation.vector - t.translation.vector;
    let re: Rotation3<f64> = d.rotation * t.rotation.inverse();
    // (2.26)-(2.27) through the robust atan2 form (nalgebra's angle() uses acos, which loses
    // half the digits near zero).
    let aa = crate::kinematics::orientation::angle_axis_from_rotation(&re);
    let eo = aa.axis.into_inner() * aa.angle;
    let mut e = Vector6::new(ep.x, ep.y, ep.z, eo.x, eo.y, eo.z);
    for (i, on) in mask.0.iter().enumerate() {
        if !on {
            e[i] = 0.0;
        }
    }
    e
}

fn split_norms(e: &Vector6<f64>) -> (f64, f64) {
    (e.fixed_rows::<3>(0).norm(), e.fixed_rows::<3>(3).norm())
}

/// Scratch buffers of one solve, allocated once.
struct Scratch {
    frames: Vec<Pose>,
    jac: Matrix6xX<f64>,
    trial: Vec<f64>,
    dq: DVector<f64>,
}

/// Solves IK numerically for end-effector `ee` from `seed_q`. Invalid input (NaN target, wrong
/// seed length) is an error; failure to converge is a report with `converged = false`.
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
    let limits = robot.limits();
    let mut s = Scratch {
        frames: vec![Pose::identity(); robot.joints().len()],
        jac: Matrix6xX::zeros(n),
        trial: vec![0.0; n],
        dq: DVector::zeros(n),
    };
    let mut rng = SplitMix(opts.seed);
    let mut q: Vec<f64> = seed_q.to_vec();
    if opts.enforce_limits {
        clamp(&mut q, &limits);
    }
    let mut best: Option<(f64, Vec<f64>, Vector6<f64>)> = None;
    let mut iterations = 0;
    for attempt in 0..=opts.restarts {
        if attempt > 0 {
            for (v, l) in q.iter_mut().zip(&limits) {
                *v = l[0] + (l[1] - l[0]) * rng.next_f64();
            }
        }
        let (it, e) = attempt_solve(robot, ee, &goal, &mask, opts, &limits, &mut q, &mut s)?;
        iterations += it;
        let (pe, oe) = split_norms(&e);
        let cost = pe.max(oe);
        if best.as_ref().is_none_or(|b| cost < b.0) {
            best = Some((cost, q.clone(), e));
        }
        if pe <= opts.tolerance && oe <= opts.tolerance {
            let (q, e, it) = if opts.secondary != Secondary::None && n > mask.count() {
                improve_secondary(robot, ee, &goal, &mask, opts, &limits, q, e, &mut s)?
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

fn clamp(q: &mut [f64], limits: &[[f64; 2]]) {
    for (v, l) in q.iter_mut().zip(limits) {
        *v = v.clamp(l[0], l[1]);
    }
}

/// `(J J^T + lambda I)^-1 e` for the masked rows (unmasked rows get a unit diagonal), then
/// `J^T` of it: the damped least-squares step, allocation-free.
fn dls_step(
    jac: &Matrix6xX<f64>,
    e: &Vector6<f64>,
    lambda: f64,
    mask: &TaskMask,
    dq: &mut DVector<f64>,
) -> bool {
    let mut a: Matrix6<f64> = jac * jac.transpose();
    for i in 0..6 {
        if mask.0[i] {
            a[(i, i)] += lambda;
        } else {
            a.row_mut(i).fill(0.0);
            a.column_mut(i).fill(0.0);
            a[(i, i)] = 1.0;
        }
    }
    let Some(ch) = a.cholesky() else { return false };
    let y = ch.solve(e);
    dq.gemv_tr(1.0, jac, &y, 0.0);
    true
}

#[allow(clippy::too_many_arguments)]
fn attempt_solve(
    robot: &Robot,
    ee: usize,
    goal: &Pose,
    mask: &TaskMask,
    opts: &NumericalOptions,
    limits: &[[f64; 2]],
    q: &mut [f64],
    s: &mut Scratch,
) -> Result<(usize, Vector6<f64>), IkError> {
    let mut lambda = opts.damping;
    let t = robot.jacobian_into(q, ee, &mut s.frames, &mut s.jac)?;
    let mut e = error(goal, &t, mask);
    let mut cost = e.norm_squared();
    for (i, l) in mask.0.iter().enumerate() {
        if !l {
            s.jac.row_mut(i).fill(0.0);
        }
    }
    for it in 1..=opts.max_iterations {
        let (pe, oe) = split_norms(&e);
        if pe <= opts.tolerance && oe <= opts.tolerance {
            return Ok((it - 1, e));
        }
        let ok = match opts.method {
            Method::LevenbergMarquardt => dls_step(&s.jac, &e, lambda, mask, &mut s.dq),
            Method::DampedLeastSquares => {
                dls_step(&s.jac, &e, opts.damping * opts.damping, mask, &mut s.dq)
            }
            Method::PseudoInverse => pinv_step(&s.jac, &e, &mut s.dq),
            Method::Transpose => {
                s.dq.gemv_tr(opts.transpose_gain, &s.jac, &e, 0.0);
                true
            }
        };
        if !ok {
            return Ok((it, e));
        }
        let norm = s.dq.amax();
        if norm > opts.max_step {
            s.dq *= opts.max_step / norm;
        }
        for ((t, &v), d) in s.trial.iter_mut().zip(q.iter()).zip(s.dq.iter()) {
            *t = v + d;
        }
        if opts.enforce_limits {
            clamp(&mut s.trial, limits);
        }
        let t_trial = robot.fk_ee(&s.trial, ee)?;
        let e_trial = error(goal, &t_trial, mask);
        let c_trial = e_trial.norm_squared();
        let accept = opts.method != Method::LevenbergMarquardt || c_trial < cost;
        if accept {
            q.copy_from_slice(&s.trial);
            let t = robot.jacobian_into(q, ee, &mut s.frames, &mut s.jac)?;
            e = error(goal, &t, mask);
            cost = e.norm_squared();
            for (i, l) in mask.0.iter().enumerate() {
                if !l {
                    s.jac.row_mut(i).fill(0.0);
                }
            }
            lambda = (lambda * 0.1).max(1e-12);
        } else {
            lambda *= 10.0;
            if lambda > 1e8 {
                return Ok((it, e));
            }
        }
        if !cost.is_finite() {
            return Ok((it, e));
        }
    }
    Ok((opts.max_iterations, e))
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

/// Value of the secondary objective (larger is better).
fn objective(
    robot: &Robot,
    ee: usize,
    q: &[f64],
    mask: &TaskMask,
    secondary: Secondary,
    limits: &[[f64; 2]],
) -> f64 {
    match secondary {
        Secondary::None => 0.0,
        Secondary::JointLimits { .. } => {
            let n = q.len() as f64;
            -q.iter()
                .zip(limits)
                .map(|(&v, l)| ((v - 0.5 * (l[0] + l[1])) / (l[1] - l[0]).max(1e-9)).powi(2))
                .sum::<f64>()
                / (2.0 * n)
        }
        Secondary::Manipulability { .. } => manipulability(robot, ee, q, mask),
    }
}

fn manipulability(robot: &Robot, ee: usize, q: &[f64], mask: &TaskMask) -> f64 {
    robot.jacobian(q, ee).map_or(0.0, |mut j| {
        for (i, l) in mask.0.iter().enumerate() {
            if !l {
                j.row_mut(i).fill(0.0);
            }
        }
        let mut m = j.clone() * j.transpose();
        for i in 0..6 {
            if !mask.0[i] {
                m[(i, i)] = 1.0;
            }
        }
        m.determinant().max(0.0).sqrt()
    })
}

/// Second phase for redundant arms: step along the null-space projection of the objective's
/// gradient, (3.54), then re-converge the task with LM; keep a step only if the task still
/// converges and the objective improved.
#[allow(clippy::too_many_arguments)]
fn improve_secondary(
    robot: &Robot,
    ee: usize,
    goal: &Pose,
    mask: &TaskMask,
    opts: &NumericalOptions,
    limits: &[[f64; 2]],
    mut q: Vec<f64>,
    mut e: Vector6<f64>,
    s: &mut Scratch,
) -> Result<(Vec<f64>, Vector6<f64>, usize), IkError> {
    let mut best = objective(robot, ee, &q, mask, opts.secondary, limits);
    let mut iterations = 0;
    let inner = NumericalOptions {
        method: Method::LevenbergMarquardt,
        max_iterations: 30,
        ..*opts
    };
    for _ in 0..opts.max_iterations {
        robot.jacobian_into(&q, ee, &mut s.frames, &mut s.jac)?;
        for (i, l) in mask.0.iter().enumerate() {
            if !l {
                s.jac.row_mut(i).fill(0.0);
            }
        }
        s.dq.fill(0.0);
        add_null_space(
            robot,
            ee,
            &q,
            &s.jac,
            mask,
            1e-9,
            opts.secondary,
            limits,
            &mut s.dq,
        );
        let norm = s.dq.amax();
        if norm < 1e-9 {
            break;
        }
        if norm > opts.max_step {
            s.dq *= opts.max_step / norm;
        }
        let mut trial: Vec<f64> = q.iter().zip(s.dq.iter()).map(|(a, b)| a + b).collect();
        if opts.enforce_limits {
            clamp(&mut trial, limits);
        }
        let (it, e_trial) = attempt_solve(robot, ee, goal, mask, &inner, limits, &mut trial, s)?;
        iterations += it;
        let (pe, oe) = split_norms(&e_trial);
        let value = objective(robot, ee, &trial, mask, opts.secondary, limits);
        if pe <= opts.tolerance && oe <= opts.tolerance && value > best + 1e-12 {
            best = value;
            q = trial;
            e = e_trial;
        } else {
            break;
        }
    }
    Ok((q, e, iterations))
}

/// Adds `(I - J^# J) k grad w` to `dq`, (3.54).
#[allow(clippy::too_many_arguments)]
fn add_null_space(
    robot: &Robot,
    ee: usize,
    q: &[f64],
    jac: &Matrix6xX<f64>,
    mask: &TaskMask,
    lambda: f64,
    secondary: Secondary,
    limits: &[[f64; 2]],
    dq: &mut DVector<f64>,
) {
    let n = q.len();
    let (gain, grad) = match secondary {
        Secondary::None => return,
        Secondary::JointLimits { gain } => {
            let g = DVector::from_iterator(
                n,
                q.iter().zip(limits).map(|(&v, l)| {
                    let range = (l[1] - l[0]).max(1e-9);
                    -(v - 0.5 * (l[0] + l[1])) / (n as f64 * range * range)
                }),
            );
            (gain, g)
        }
        Secondary::Manipulability { gain } => {
            let w = |q: &[f64]| manipulability(robot, ee, q, mask);
            let h = 1e-6;
            let mut qq = q.to_vec();
            let g = DVector::from_iterator(
                n,
                (0..n).map(|k| {
                    qq[k] = q[k] + h;
                    let wp = w(&qq);
                    qq[k] = q[k] - h;
                    let wm = w(&qq);
                    qq[k] = q[k];
                    (wp - wm) / (2.0 * h)
                }),
            );
            (gain, g)
        }
    };
    // J^# J grad = J^T (J J^T + lambda I)^-1 J grad
    let jg: Vector6<f64> = jac * &grad;
    let mut proj = DVector::zeros(n);
    if dls_step(jac, &jg, lambda, mask, &mut proj) {
        *dq += (grad - proj) * gain;
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
