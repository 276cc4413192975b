//! The secondary objective of a redundant arm's numerical IK (Sect. 3.5.1 of Siciliano et al.):
//! once the task converges, steps along the null-space projection of the objective's gradient,
//! (3.54), each followed by the task's re-convergence, while the objective improves.

use super::{
    Bounds, IkError, Method, NumericalOptions, Pose, Robot, Scratch, Secondary, TaskMask,
    damped_factor, descend, mask_rows, split_norms,
};
use nalgebra::{DVector, Matrix6xX, Vector6};

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
                .filter(|(_, l)| l[0].is_finite() && l[1].is_finite())
                .map(|(&v, l)| ((v - 0.5 * (l[0] + l[1])) / (l[1] - l[0]).max(1e-9)).powi(2))
                .sum::<f64>()
                / (2.0 * n)
        }
        Secondary::Manipulability { .. } => manipulability(robot, ee, q, mask),
    }
}

fn manipulability(robot: &Robot, ee: usize, q: &[f64], mask: &TaskMask) -> f64 {
    let Ok(t) = robot.fk_ee(q, ee) else {
        return 0.0;
    };
    robot.jacobian(q, ee).map_or(0.0, |mut j| {
        mask_rows(&mut j, &t, mask);
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
pub(super) fn improve_secondary(
    robot: &Robot,
    ee: usize,
    goal: &Pose,
    mask: &TaskMask,
    opts: &NumericalOptions,
    bounds: &Bounds,
    mut q: Vec<f64>,
    mut e: Vector6<f64>,
    s: &mut Scratch,
) -> Result<(Vec<f64>, Vector6<f64>, usize), IkError> {
    let limits = &bounds.limits;
    let mut best = objective(robot, ee, &q, mask, opts.secondary, limits);
    let mut iterations = 0;
    let inner = NumericalOptions {
        method: Method::LevenbergMarquardt,
        max_iterations: 30,
        ..*opts
    };
    for _ in 0..opts.max_iterations {
        let t = robot.jacobian_into(&q, ee, &mut s.frames, &mut s.jac)?;
        mask_rows(&mut s.jac, &t, mask);
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
            bounds.clamp(&mut trial);
        }
        let (it, e_trial) = descend(robot, ee, goal, mask, &inner, bounds, &mut trial, s)?;
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
                    if !(l[0].is_finite() && l[1].is_finite()) {
                        return 0.0;
                    }
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
    if let Some(ch) = damped_factor(jac, lambda, mask) {
        let proj = jac.tr_mul(&ch.solve(&jg));
        *dq += (grad - proj) * gain;
    }
}
