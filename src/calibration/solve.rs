//! Iterative least squares (2.88)-(2.89) on the stacked, weighted, column-scaled system (2.87).

use super::CalibrationError;
use super::identify::{Identifiability, identifiability_of};
use super::model::{Measurement, Parameter, ParameterModel};
use super::setup::{Unknowns, linearise};
use nalgebra::{DMatrix, DVector};

/// What [`calibrate`] does with parameters the measurements cannot identify (found by the rank
/// analysis at the nominal parameters, before any iteration).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Unidentifiable {
    /// Keep one parameter of each unidentifiable combination at its nominal value (the first of
    /// the combination in the order of zeta) and estimate the rest: the written model stays
    /// physically sensible. The default.
    #[default]
    Nominal,
    /// Estimate every free parameter; each step is the minimum-norm solution over the numerical
    /// rank, but from the second iteration on, a direction that was exactly invisible at the
    /// nominal point may be weakly visible and drift (the lesson of plain DH on parallel axes).
    MinimumNorm,
}

/// Options of [`calibrate`]; every field with its unit and trade-off.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CalibrationOptions {
    /// Largest number of iterations of (2.88)-(2.89).
    pub max_iterations: usize,
    /// The iteration has converged when no parameter moves more than this (m or rad), or when
    /// the weighted residual changes by less than 1e-10 of itself between iterations.
    pub step_tolerance: f64,
    /// Singular values of the scaled system below `rank_tolerance * sigma_max` count as zero:
    /// the numerical rank. Larger hides weakly identifiable parameters; smaller lets noise into
    /// them.
    pub rank_tolerance: f64,
    /// Position measurement noise (m, one sigma): position rows are divided by it.
    pub position_sigma: f64,
    /// Orientation measurement noise (rad, one sigma): orientation rows are divided by it.
    pub orientation_sigma: f64,
    /// Levenberg–Marquardt damping of the scaled step (0 = plain (2.88)); damps the directions
    /// with singular values below about its square root.
    pub damping: f64,
    /// What happens to parameters the measurements cannot identify.
    pub unidentifiable: Unidentifiable,
}

impl Default for CalibrationOptions {
    /// 50 iterations, steps below 1e-12, rank tolerance 1e-9, 0.1 mm and 1 mrad noise, no
    /// damping, unidentifiable parameters kept at their nominal values.
    fn default() -> Self {
        Self {
            max_iterations: 50,
            step_tolerance: 1e-12,
            rank_tolerance: 1e-9,
            position_sigma: 1e-4,
            orientation_sigma: 1e-3,
            damping: 0.0,
            unidentifiable: Unidentifiable::Nominal,
        }
    }
}

/// Errors of a model against a set of measurements: position_rms = sqrt(mean |dp|^2), the
/// largest |dp|, and the same for the rotation angle of `R_measured R_model^T` (`None` for
/// position-only data). For the setups without a tracker, dp is the setup's residual in metres:
/// the distance error, the pivot point's offset, the distance to the plane or to the sphere.
#[derive(Debug, Clone, Copy, PartialEq)]
#[must_use]
pub struct Fit {
    /// RMS position error (m).
    pub position_rms: f64,
    /// Largest position error (m).
    pub position_max: f64,
    /// RMS orientation error (rad).
    pub orientation_rms: Option<f64>,
    /// Largest orientation error (rad).
    pub orientation_max: Option<f64>,
}

/// One iteration of the least squares.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Iteration {
    /// RMS position residual before the step (m).
    pub position_rms: f64,
    /// RMS orientation residual before the step (rad; 0 for position-only data).
    pub orientation_rms: f64,
    /// Largest parameter change of the step (m or rad).
    pub step_norm: f64,
    /// sigma_max / sigma_min over the numerical rank of the scaled system.
    pub condition: f64,
    /// Numerical rank of the scaled system.
    pub rank: usize,
}

/// What [`calibrate`] found.
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct CalibrationReport {
    /// Every parameter (nominal value, fixed or not, the automatically fixed ones marked
    /// fixed), in the order of zeta.
    pub parameters: Vec<Parameter>,
    /// Parameters kept at their nominal values because the measurements cannot identify them
    /// (with [`Unidentifiable::Nominal`]): the name and the combination it belongs to.
    pub auto_fixed: Vec<(String, String)>,
    /// The setup's estimated unknowns (pivot points, planes, sphere centres).
    pub unknowns: Unknowns,
    /// Standard deviation of each unknown, in the order of [`Unknowns::values`].
    pub unknown_std: Vec<Option<f64>>,
    /// The estimate of zeta.
    pub estimate: Vec<f64>,
    /// Standard deviation of each estimated, identifiable parameter (m or rad).
    pub std: Vec<Option<f64>>,
    /// Identifiability at the nominal parameters, of every parameter free before the
    /// unidentifiable ones were fixed: where they were chosen.
    pub nominal: Identifiability,
    /// Identifiability at the estimate, of the parameters estimated: where the flags, the
    /// standard deviations and the correlations are computed.
    pub at_estimate: Identifiability,
    /// The iterations.
    pub iterations: Vec<Iteration>,
    /// Whether the step fell below the tolerance.
    pub converged: bool,
    /// Why not, when it did not converge.
    pub reason: Option<String>,
    /// Residual variance sigma^2 = |r|^2 / (rows - identifiable parameters) of the weighted
    /// system (1 when the noise is as stated).
    pub sigma2: f64,
    /// Pairs of identifiable parameters whose estimates correlate above 0.9.
    pub correlations: Vec<(String, String, f64)>,
    /// Errors of the nominal and of the calibrated model on the measurements.
    pub before: Fit,
    /// After.
    pub after: Fit,
}

/// The errors of the model with `zeta` on `ms`. The setup's unknowns (pivot points, planes,
/// spheres) are estimated first with the robot held at `zeta`, so that held-out data are judged
/// on the robot alone.
pub fn fit(
    model: &ParameterModel,
    zeta: &[f64],
    ms: &[Measurement],
) -> Result<Fit, CalibrationError> {
    let mut s = Unknowns::initial(model, zeta, ms)?;
    solve_unknowns(model, zeta, ms, &mut s)?;
    fit_with(model, zeta, &s, ms)
}

/// Gauss-Newton on the setup's unknowns alone, the robot held at `zeta` (at most 20 steps).
pub(super) fn solve_unknowns(
    model: &ParameterModel,
    zeta: &[f64],
    ms: &[Measurement],
    s: &mut Unknowns,
) -> Result<(), CalibrationError> {
    if s.is_empty() {
        return Ok(());
    }
    let rows: usize = ms.iter().map(Measurement::rows).sum();
    for _ in 0..20 {
        let mut a = DMatrix::zeros(rows, s.len());
        let mut b = DVector::zeros(rows);
        let mut at = 0;
        for m in ms {
            let l = linearise(model, zeta, s, m)?;
            for i in 0..m.rows() {
                b[at + i] = l.residual[i];
                for c in 0..s.len() {
                    a[(at + i, c)] = l.unknowns[(i, c)];
                }
            }
            at += m.rows();
        }
        let dx = a
            .svd(true, true)
            .solve(&b, 1e-12)
            .map_err(|e| CalibrationError::InvalidOption(e.into()))?;
        s.apply(dx.as_slice());
        if dx.amax() < 1e-13 {
            break;
        }
    }
    Ok(())
}

/// The errors of the model with `zeta` and the setup's unknowns `s` on `ms`.
pub(super) fn fit_with(
    model: &ParameterModel,
    zeta: &[f64],
    s: &Unknowns,
    ms: &[Measurement],
) -> Result<Fit, CalibrationError> {
    let (mut p2, mut pmax, mut o2, mut omax) = (0.0, 0.0f64, 0.0, 0.0f64);
    let pose = ms.first().is_some_and(|m| m.rows() == 6);
    for m in ms {
        let r = residual_of(model, zeta, s, m)?;
        let dp = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
        p2 += dp * dp;
        pmax = pmax.max(dp);
        if pose {
            let da = (r[3] * r[3] + r[4] * r[4] + r[5] * r[5]).sqrt();
            o2 += da * da;
            omax = omax.max(da);
        }
    }
    let l = ms.len().max(1) as f64;
    Ok(Fit {
        position_rms: (p2 / l).sqrt(),
        position_max: pmax,
        orientation_rms: pose.then(|| (o2 / l).sqrt()),
        orientation_max: pose.then_some(omax),
    })
}

/// The residual `y - f` of one measurement (its rows; the rest zero).
fn residual_of(
    model: &ParameterModel,
    zeta: &[f64],
    s: &Unknowns,
    m: &Measurement,
) -> Result<[f64; 6], CalibrationError> {
    let mut r = [0.0; 6];
    match m {
        Measurement::Pose { .. } | Measurement::Position { .. } => {
            model.residual(zeta, m, &mut r)?
        }
        _ => r = linearise(model, zeta, s, m)?.residual,
    }
    Ok(r)
}

/// Checks the measurements: joint counts, finite numbers, one kind, positive distances and
/// radii.
pub(super) fn check(model: &ParameterModel, ms: &[Measurement]) -> Result<(), CalibrationError> {
    let dof = model.nominal_robot().dof();
    let first = ms.first().map_or("pose", Measurement::kind);
    for (index, m) in ms.iter().enumerate() {
        for q in m.joint_vectors() {
            if q.len() != dof {
                return Err(CalibrationError::JointCount {
                    index,
                    expected: dof,
                    got: q.len(),
                });
            }
        }
        let finite = m
            .joint_vectors()
            .iter()
            .all(|q| q.iter().all(|v| v.is_finite()))
            && match m {
                Measurement::Pose {
                    world_from_tool, ..
                } => world_from_tool
                    .to_homogeneous()
                    .iter()
                    .all(|v| v.is_finite()),
                Measurement::Position { p, .. } => p.iter().all(|v| v.is_finite()),
                Measurement::Distance { distance: v, .. }
                | Measurement::Sphere { radius: v, .. } => v.is_finite() && *v > 0.0,
                Measurement::Pivot { .. } | Measurement::Plane { .. } => true,
            };
        if !finite {
            return Err(CalibrationError::NonFinite { index });
        }
        if m.kind() != first {
            return Err(CalibrationError::MixedKinds {
                index,
                first,
                found: m.kind(),
            });
        }
    }
    Ok(())
}

/// The weighted stacked system (2.87) over the free parameters and the setup's unknowns: Phi
/// (rows x (free + unknowns)) and the residual. Position-like rows (positions, distances,
/// plane and sphere contacts) are divided by the position noise, orientation rows by the
/// orientation noise.
pub(super) fn stacked(
    model: &ParameterModel,
    zeta: &[f64],
    s: &Unknowns,
    ms: &[Measurement],
    free: &[usize],
    opts: &CalibrationOptions,
) -> Result<(DMatrix<f64>, DVector<f64>), CalibrationError> {
    let rows: usize = ms.iter().map(Measurement::rows).sum();
    let mut phi = DMatrix::zeros(rows, free.len() + s.len());
    let mut res = DVector::zeros(rows);
    let mut at = 0;
    for m in ms {
        let k = m.rows();
        let l = linearise(model, zeta, s, m)?;
        for i in 0..k {
            let w = if i < 3 {
                1.0 / opts.position_sigma
            } else {
                1.0 / opts.orientation_sigma
            };
            res[at + i] = l.residual[i] * w;
            for (c, &j) in free.iter().enumerate() {
                phi[(at + i, c)] = l.robot[(i, j)] * w;
            }
            for c in 0..s.len() {
                phi[(at + i, free.len() + c)] = l.unknowns[(i, c)] * w;
            }
        }
        at += k;
    }
    Ok((phi, res))
}

/// Column norms of `phi`, for the scaling. A column that is zero up to rounding (below 1e-12 of
/// the largest: a parameter that does not move the measured pose at all) keeps the largest
/// norm as its scale, so that it stays a zero column instead of being blown up into noise.
pub(super) fn column_scale(phi: &DMatrix<f64>) -> DVector<f64> {
    let norms: Vec<f64> = phi.column_iter().map(|c| c.norm()).collect();
    let largest = norms.iter().copied().fold(0.0, f64::max);
    let floor = 1e-12 * largest;
    DVector::from_iterator(
        norms.len(),
        norms.iter().map(|&n| {
            if n > floor {
                n
            } else if largest > 0.0 {
                largest
            } else {
                1.0
            }
        }),
    )
}

fn validate(opts: &CalibrationOptions) -> Result<(), CalibrationError> {
    let positive = [
        ("position_sigma", opts.position_sigma),
        ("orientation_sigma", opts.orientation_sigma),
        ("rank_tolerance", opts.rank_tolerance),
        ("step_tolerance", opts.step_tolerance),
    ];
    for (name, v) in positive {
        if !(v > 0.0 && v.is_finite()) {
            return Err(CalibrationError::InvalidOption(format!(
                "{name} must be positive and finite, got {v}"
            )));
        }
    }
    if !(opts.damping >= 0.0 && opts.damping.is_finite()) {
        return Err(CalibrationError::InvalidOption(format!(
            "damping must be >= 0, got {}",
            opts.damping
        )));
    }
    Ok(())
}

/// The column-scaled system and its SVD, shared by the step, the identifiability and the
/// uncertainty: D = diag(column norms of Phi) ([`column_scale`]), the SVD of `Phi D^-1` (padded
/// with zero rows to at least as many rows as columns, so that every right singular vector
/// comes back), and which singular values count for the numerical rank.
pub(super) struct ScaledSvd {
    /// The column scale D.
    pub scale: DVector<f64>,
    /// The SVD of the scaled system (U only when asked for).
    pub svd: nalgebra::SVD<f64, nalgebra::Dyn, nalgebra::Dyn>,
    /// The largest singular value.
    pub smax: f64,
    /// Singular values at or below `rank_tolerance * smax` count as zero.
    rank_tolerance: f64,
}

impl ScaledSvd {
    /// The SVD of `phi` scaled by its column norms; `with_u`: compute U as well.
    pub fn new(phi: &DMatrix<f64>, with_u: bool, opts: &CalibrationOptions) -> Self {
        let scale = column_scale(phi);
        let mut scaled = phi.clone();
        for (j, mut c) in scaled.column_iter_mut().enumerate() {
            c /= scale[j];
        }
        let columns = scaled.ncols();
        if scaled.nrows() < columns {
            scaled = scaled.resize_vertically(columns, 0.0);
        }
        let svd = scaled.svd(with_u, true);
        let smax = svd.singular_values.iter().copied().fold(0.0, f64::max);
        Self {
            scale,
            svd,
            smax,
            rank_tolerance: opts.rank_tolerance,
        }
    }

    /// Whether the singular value `s` counts for the numerical rank.
    pub fn counts(&self, s: f64) -> bool {
        s > self.rank_tolerance * self.smax && s > 0.0
    }

    /// Row `k` of V^T (a right singular vector, scaled coordinates).
    pub fn v(&self, k: usize) -> DVector<f64> {
        self.svd
            .v_t
            .as_ref()
            .expect("v_t computed")
            .row(k)
            .transpose()
    }
}

/// One scaled, rank-revealing least-squares step: the change of the free parameters, the
/// rank and the condition number.
fn step(
    phi: &DMatrix<f64>,
    res: &DVector<f64>,
    opts: &CalibrationOptions,
) -> (DVector<f64>, usize, f64) {
    let s = ScaledSvd::new(phi, true, opts);
    let u = s.svd.u.as_ref().expect("u requested");
    let smax = s.smax;
    let mut y = DVector::zeros(phi.ncols());
    let mut rank = 0;
    let mut smin = smax;
    for (k, &sv) in s.svd.singular_values.iter().enumerate() {
        if !s.counts(sv) {
            continue;
        }
        rank += 1;
        smin = smin.min(sv);
        let lambda = opts.damping * smax * smax;
        // The padding rows of U (a short system) are zero where sv > 0.
        let coef = u.column(k).rows(0, res.len()).dot(res) * sv / (sv * sv + lambda);
        y += s.v(k) * coef;
    }
    let dz = y.component_div(&s.scale);
    let cond = if rank > 0 { smax / smin } else { f64::INFINITY };
    (dz, rank, cond)
}

/// Estimates the free parameters of `model` from the measurements by (2.88)-(2.89) iterated:
/// each step solves the weighted, column-scaled stacked system (2.87) by SVD over its numerical
/// rank, until no parameter moves more than `opts.step_tolerance`. The setup's unknowns (pivot
/// points, planes, spheres) are estimated with the robot.
///
/// First, the rank analysis at the nominal parameters finds what the measurements cannot
/// identify; with [`Unidentifiable::Nominal`] (the default) one parameter of each such
/// combination is kept at its nominal value (reported in `auto_fixed`).
pub fn calibrate(
    model: &ParameterModel,
    ms: &[Measurement],
    opts: &CalibrationOptions,
) -> Result<CalibrationReport, CalibrationError> {
    validate(opts)?;
    check(model, ms)?;
    let nominal = model.nominal();
    let mut s = Unknowns::initial(model, &nominal, ms)?;
    enough_equations(ms, model.free().len() + s.len())?;
    solve_unknowns(model, &nominal, ms, &mut s)?;
    let at_nominal = identifiability_of(model, &nominal, &s, ms, opts)?;
    let user_fixed: Vec<usize> = (0..model.parameters().len())
        .filter(|&k| model.parameters()[k].fixed)
        .collect();
    let mut model = model.clone();
    let mut auto_fixed = Vec::new();
    if opts.unidentifiable == Unidentifiable::Nominal {
        for (dep, why) in at_nominal.dependent.iter().zip(&at_nominal.combinations) {
            if let Some(j) = *dep {
                let name = model.parameters()[j].name.clone();
                model.fix(&[name.as_str()])?;
                auto_fixed.push((name, why.clone()));
            }
        }
    }
    auto_fixed.extend(fix_gauges(&mut model, &user_fixed, ms)?);
    let free = model.free();
    let mut zeta = nominal.clone();
    let before = fit_with(&model, &zeta, &s, ms)?;
    let (iterations, converged, reason) = iterate(&model, ms, &free, opts, &mut zeta, &mut s)?;
    let after = fit_with(&model, &zeta, &s, ms)?;
    let at_estimate = identifiability_of(&model, &zeta, &s, ms, opts)?;
    let u = uncertainty(&model, &zeta, &s, ms, &free, opts, &at_estimate)?;
    Ok(CalibrationReport {
        parameters: model.parameters().to_vec(),
        auto_fixed,
        unknowns: s,
        unknown_std: u.unknown_std,
        estimate: zeta,
        std: u.std,
        nominal: at_nominal,
        at_estimate,
        iterations,
        converged,
        reason,
        sigma2: u.sigma2,
        correlations: u.correlations,
        before,
        after,
    })
}

/// Directions that are invisible only at the solution, where the residuals are noise, so that
/// the rank analysis at the nominal point (with millimetre residuals) cannot find them:
/// - pivot points and planes see the arm's shape, not its size: scaling every length of the
///   arm and of the scene together scales every residual, and the least squares would shrink
///   the arm. The longest free length keeps its nominal value and sets the scale (unless the
///   caller keeps a length over 1 mm fixed already).
/// - pivot points turn with the arm: turning the whole arm and the points about the first
///   joint's axis turns every offset `p - c` without changing its length. The first joint's
///   offset (theta1 of a revolute joint) and the base's rotations keep their values.
fn fix_gauges(
    model: &mut ParameterModel,
    user_fixed: &[usize],
    ms: &[Measurement],
) -> Result<Vec<(String, String)>, CalibrationError> {
    use super::model::Kind;
    let mut out = Vec::new();
    let Some(first) = ms.first() else {
        return Ok(out);
    };
    let pivot = matches!(first, Measurement::Pivot { .. });
    if pivot {
        let turning: Vec<String> = model
            .parameters()
            .iter()
            .filter(|p| {
                !p.fixed
                    && ((p.kind == Kind::Theta && p.joint == 1)
                        || matches!(p.kind, Kind::BaseRotation(_)))
            })
            .map(|p| p.name.clone())
            .collect();
        for name in turning {
            model.fix(&[name.as_str()])?;
            let why = format!(
                "pivot points turn with the arm: turning both changes no offset's length, and the \
                 offsets are noise at the solution; {name} keeps its value"
            );
            out.push((name, why));
        }
    }
    // A length the caller keeps at a non-zero value already sets the scale; d1 does not (it
    // shifts the whole arm along the first axis, which the scene absorbs).
    let scaled = user_fixed.iter().any(|&k| {
        let p = &model.parameters()[k];
        matches!(p.kind, Kind::A | Kind::D)
            && p.nominal.abs() > 1e-3
            && !(p.kind == Kind::D && p.joint == 1)
    });
    if (pivot || matches!(first, Measurement::Plane { .. })) && !scaled {
        // The longest free length (the first of equal ones).
        let longest = model
            .parameters()
            .iter()
            .filter(|p| !p.fixed && matches!(p.kind, Kind::A | Kind::D))
            .fold(None::<&super::model::Parameter>, |best, p| match best {
                Some(b) if b.nominal.abs() >= p.nominal.abs() => Some(b),
                _ => Some(p),
            })
            .map(|p| p.name.clone());
        if let Some(name) = longest {
            model.fix(&[name.as_str()])?;
            let why = format!(
                "{} measurements see the arm's shape, not its size (scaling every length and the \
                 scene together leaves them unchanged at the solution); {name}, the longest free \
                 length, sets the scale (add distance or sphere measurements to measure it)",
                first.kind()
            );
            out.push((name, why));
        }
    }
    Ok(out)
}

/// At least as many equations as unknowns (the free parameters and the setup's unknowns).
fn enough_equations(ms: &[Measurement], unknowns: usize) -> Result<(), CalibrationError> {
    let equations: usize = ms.iter().map(Measurement::rows).sum();
    if equations < unknowns {
        let per = ms.first().map_or(6, Measurement::rows);
        return Err(CalibrationError::TooFewEquations {
            equations,
            poses: ms.len(),
            parameters: unknowns,
            needed: unknowns.div_ceil(per),
        });
    }
    Ok(())
}

/// RMS of the position and orientation rows of a weighted residual, in m and rad.
fn residual_rms(res: &DVector<f64>, ms: &[Measurement], opts: &CalibrationOptions) -> (f64, f64) {
    let (mut p2, mut o2, mut at) = (0.0, 0.0, 0);
    for m in ms {
        for i in 0..m.rows() {
            if i < 3 {
                p2 += (res[at + i] * opts.position_sigma).powi(2);
            } else {
                o2 += (res[at + i] * opts.orientation_sigma).powi(2);
            }
        }
        at += m.rows();
    }
    let l = ms.len().max(1) as f64;
    ((p2 / l).sqrt(), (o2 / l).sqrt())
}

/// The iterations of (2.88)-(2.89) from `zeta` (updated in place): the record, whether they
/// converged, and why not.
fn iterate(
    model: &ParameterModel,
    ms: &[Measurement],
    free: &[usize],
    opts: &CalibrationOptions,
    zeta: &mut [f64],
    s: &mut Unknowns,
) -> Result<(Vec<Iteration>, bool, Option<String>), CalibrationError> {
    let mut iterations = Vec::new();
    let mut last_cost = f64::INFINITY;
    for _ in 0..opts.max_iterations {
        let (phi, res) = stacked(model, zeta, s, ms, free, opts)?;
        // The weighted residual no longer changes (to 1e-10 relative): the least-squares fixed
        // point is reached even where an ill-conditioned direction keeps the step above the
        // tolerance with rounding noise.
        let cost = res.norm_squared();
        if cost > 0.0 && (last_cost - cost).abs() <= 1e-10 * cost {
            return Ok((iterations, true, None));
        }
        last_cost = cost;
        let (dz, rank, condition) = step(&phi, &res, opts);
        let (position_rms, orientation_rms) = residual_rms(&res, ms, opts);
        // The largest change of a robot parameter (the unknowns are lengths of the scene).
        let step_norm = dz.rows(0, free.len()).amax().max(if s.is_empty() {
            0.0
        } else {
            dz.rows(free.len(), s.len()).amax()
        });
        iterations.push(Iteration {
            position_rms,
            orientation_rms,
            step_norm,
            condition,
            rank,
        });
        if !step_norm.is_finite() {
            let why = "the step is not finite (the system is singular)".to_string();
            return Ok((iterations, false, Some(why)));
        }
        for (c, &j) in free.iter().enumerate() {
            zeta[j] += dz[c];
        }
        s.apply(&dz.as_slice()[free.len()..]);
        if step_norm <= opts.step_tolerance {
            return Ok((iterations, true, None));
        }
    }
    let why = format!(
        "the step was still above {} after {} iterations",
        opts.step_tolerance, opts.max_iterations
    );
    Ok((iterations, false, Some(why)))
}

/// The uncertainty of an estimate.
struct Uncertainty {
    std: Vec<Option<f64>>,
    unknown_std: Vec<Option<f64>>,
    sigma2: f64,
    correlations: Vec<(String, String, f64)>,
}

/// sigma^2 = |r|^2 / (rows - rank), the covariance `sigma^2 (Phi^T Phi)^+` over the identifiable
/// subspace (in parameter units), the standard deviations and the correlations above 0.9.
fn uncertainty(
    model: &ParameterModel,
    zeta: &[f64],
    s: &Unknowns,
    ms: &[Measurement],
    free: &[usize],
    opts: &CalibrationOptions,
    ident: &Identifiability,
) -> Result<Uncertainty, CalibrationError> {
    let (phi, res) = stacked(model, zeta, s, ms, free, opts)?;
    let svd = ScaledSvd::new(&phi, false, opts);
    let scale = &svd.scale;
    let p = free.len() + s.len();
    let mut cov = DMatrix::zeros(p, p);
    let mut rank = 0;
    for (k, &sv) in svd.svd.singular_values.iter().enumerate() {
        if svd.counts(sv) {
            rank += 1;
            let v = svd.v(k);
            cov += &v * v.transpose() / (sv * sv);
        }
    }
    let dof = res.len().saturating_sub(rank).max(1);
    let sigma2 = res.norm_squared() / dof as f64;
    for i in 0..p {
        for j in 0..p {
            cov[(i, j)] *= sigma2 / (scale[i] * scale[j]);
        }
    }
    let mut std = vec![None; model.parameters().len()];
    for (c, &j) in free.iter().enumerate() {
        if ident.identifiable[j] {
            std[j] = Some(cov[(c, c)].max(0.0).sqrt());
        }
    }
    let unknown_std = (0..s.len())
        .map(|k| {
            let c = free.len() + k;
            ident.unknown_identifiable[k].then(|| cov[(c, c)].max(0.0).sqrt())
        })
        .collect();
    let mut correlations = Vec::new();
    for (a, &ja) in free.iter().enumerate() {
        for (b, &jb) in free.iter().enumerate().skip(a + 1) {
            if let (Some(sa), Some(sb)) = (std[ja], std[jb])
                && sa > 0.0
                && sb > 0.0
            {
                let r = cov[(a, b)] / (sa * sb);
                if r.abs() > 0.9 {
                    let names = model.parameters();
                    correlations.push((names[ja].name.clone(), names[jb].name.clone(), r));
                }
            }
        }
    }
    Ok(Uncertainty {
        std,
        unknown_std,
        sigma2,
        correlations,
    })
}
