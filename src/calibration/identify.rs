//! Which parameters a set of measurements identifies: the numerical rank of the scaled Phi, the
//! unidentifiable directions as combinations in words, and the observability indices.

use super::CalibrationError;
use super::model::{Kind, Measurement, ParameterModel};
use super::setup::Unknowns;
use super::solve::{CalibrationOptions, ScaledSvd, check, stacked};
use nalgebra::DMatrix;

/// Observability indices of a pose set, from the singular values sigma_1 >= ... >= sigma_L of
/// the column-scaled stacked Phi (not of Phi^T Phi), l poses. L is the numerical rank: the
/// indices describe the identifiable combinations (with an unidentifiable direction among them,
/// O2-O4 would be rounding noise, about 1e-16, whatever the poses).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Observability {
    /// O1 (Borm & Menq): (sigma_1 ... sigma_L)^(1/L) / sqrt(l).
    pub o1: f64,
    /// O2 (Driels & Pathre): sigma_L / sigma_1, the inverse condition number.
    pub o2: f64,
    /// O3 (Nahvi et al.): sigma_L.
    pub o3: f64,
    /// O4 (Nahvi & Hollerbach): sigma_L^2 / sigma_1, the noise amplification index.
    pub o4: f64,
}

impl Observability {
    /// The indices of singular values `s` (any order) for `poses` poses.
    pub fn from_singular_values(s: &[f64], poses: usize) -> Self {
        let l = s.len().max(1) as f64;
        let smax = s.iter().copied().fold(0.0, f64::max);
        let smin = s.iter().copied().fold(f64::INFINITY, f64::min);
        let log_mean = s.iter().map(|v| v.max(1e-300).ln()).sum::<f64>() / l;
        Self {
            o1: log_mean.exp() / (poses.max(1) as f64).sqrt(),
            o2: if smax > 0.0 { smin / smax } else { 0.0 },
            o3: smin,
            o4: if smax > 0.0 { smin * smin / smax } else { 0.0 },
        }
    }
}

/// The identifiability of the free parameters for a set of measurements.
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct Identifiability {
    /// Free parameters (columns of the system), the setup's unknowns included.
    pub parameter_count: usize,
    /// Numerical rank of the column-scaled, weighted Phi.
    pub rank: usize,
    /// Singular values below `rank_threshold * sigma_max` count as zero.
    pub rank_threshold: f64,
    /// Per parameter of zeta: free and identifiable on its own.
    pub identifiable: Vec<bool>,
    /// Per unknown of the setup (pivot points, planes, spheres): identifiable on its own.
    pub unknown_identifiable: Vec<bool>,
    /// Names of the free parameters (and unknowns) that are not identifiable on their own.
    pub unidentifiable: Vec<String>,
    /// Per entry of `combinations`: the index in zeta of the parameter that keeping at its
    /// value removes that unidentifiable direction (the first of the combination in the order
    /// of zeta), or None when the direction lies among the setup's unknowns alone.
    pub dependent: Vec<Option<usize>>,
    /// What can and cannot be identified, in words: "d2 and d3 only as d2 + d3 (axes 2 and 3 are
    /// parallel)", "theta6 cannot be identified: it does not change the measurements".
    pub combinations: Vec<String>,
    /// Singular values of the scaled system, largest first.
    pub singular_values: Vec<f64>,
    /// The observability indices.
    pub observability: Observability,
}

/// The identifiability of `model`'s free parameters at `zeta` for the measurements `ms` (with
/// the setup's unknowns started from the model's tool points).
pub fn identifiability(
    model: &ParameterModel,
    zeta: &[f64],
    ms: &[Measurement],
    opts: &CalibrationOptions,
) -> Result<Identifiability, CalibrationError> {
    check(model, ms)?;
    let s = Unknowns::initial(model, zeta, ms)?;
    identifiability_of(model, zeta, &s, ms, opts)
}

pub(super) fn identifiability_of(
    model: &ParameterModel,
    zeta: &[f64],
    s: &Unknowns,
    ms: &[Measurement],
    opts: &CalibrationOptions,
) -> Result<Identifiability, CalibrationError> {
    let free = model.free();
    let (phi, _) = stacked(model, zeta, s, ms, &free, opts)?;
    let p = free.len() + s.len();
    let scaled = ScaledSvd::new(&phi, false, opts);
    let svd = &scaled.svd;
    let mut order: Vec<usize> = (0..svd.singular_values.len()).collect();
    order.sort_by(|&a, &b| svd.singular_values[b].total_cmp(&svd.singular_values[a]));
    let sv: Vec<f64> = order.iter().map(|&k| svd.singular_values[k]).collect();
    let rank = sv.iter().filter(|&&s| scaled.counts(s)).count();
    // Null space basis (scaled coordinates), one row per null direction.
    let null: Vec<Vec<f64>> = order[rank..]
        .iter()
        .map(|&k| scaled.v(k).iter().copied().collect())
        .collect();
    let scale = &scaled.scale;
    let names = model.parameters();
    let columns = Columns::new(model, &free, s);
    let mut identifiable = vec![false; names.len()];
    let mut unknown_identifiable = vec![false; s.len()];
    let mut unidentifiable = Vec::new();
    for c in 0..p {
        let weight: f64 = null.iter().map(|v| v[c] * v[c]).sum();
        let seen = weight.sqrt() < 1e-6;
        match free.get(c) {
            Some(&j) => identifiable[j] = seen,
            None => unknown_identifiable[c - free.len()] = seen,
        }
        if !seen {
            unidentifiable.push(columns.names[c].clone());
        }
    }
    let (combinations, pivots) = describe(
        model,
        &columns,
        &null,
        &scale.iter().copied().collect::<Vec<_>>(),
    );
    let dependent = pivots.iter().map(|&c| free.get(c).copied()).collect();
    Ok(Identifiability {
        parameter_count: p,
        rank,
        rank_threshold: opts.rank_tolerance,
        identifiable,
        unknown_identifiable,
        unidentifiable,
        dependent,
        combinations,
        observability: Observability::from_singular_values(
            &sv[..rank.max(1).min(sv.len())],
            ms.len(),
        ),
        singular_values: sv,
    })
}

/// The columns of the stacked system: the free parameters, then the setup's unknowns.
struct Columns {
    names: Vec<String>,
    /// (kind, 1-based joint) of a parameter column; None for an unknown.
    params: Vec<Option<(Kind, usize)>>,
}

impl Columns {
    fn new(model: &ParameterModel, free: &[usize], s: &Unknowns) -> Self {
        let ps = model.parameters();
        let mut names: Vec<String> = free.iter().map(|&j| ps[j].name.clone()).collect();
        let mut params: Vec<_> = free
            .iter()
            .map(|&j| Some((ps[j].kind, ps[j].joint)))
            .collect();
        names.extend(s.names());
        params.resize(names.len(), None);
        Self { names, params }
    }
}

/// The null directions in reduced row echelon form (each one a dependence among few parameters),
/// in parameter units, said in words; with the pivot column of each (the first column of its
/// combination).
fn describe(
    model: &ParameterModel,
    columns: &Columns,
    null: &[Vec<f64>],
    scale: &[f64],
) -> (Vec<String>, Vec<usize>) {
    if null.is_empty() {
        return (Vec::new(), Vec::new());
    }
    let p = columns.names.len();
    // Unscaled: a change dz = D^-1 y of the parameters along a null direction y.
    let mut m = DMatrix::from_fn(null.len(), p, |r, c| null[r][c] / scale[c]);
    rref(&mut m);
    let names = &columns.names;
    let (mut out, mut pivots) = (Vec::new(), Vec::new());
    for r in 0..m.nrows() {
        let terms: Vec<(usize, f64)> = (0..p)
            .filter(|&c| m[(r, c)].abs() > 1e-6)
            .map(|c| (c, m[(r, c)]))
            .collect();
        let Some(&(first, _)) = terms.first() else {
            continue;
        };
        pivots.push(first);
        match terms.as_slice() {
            [] => {}
            [(c, _)] => out.push(format!(
                "{} cannot be identified: it does not change the measurements",
                names[*c]
            )),
            [(a, va), (b, vb)] => {
                // Changes along (va, vb) are invisible; va X + ... : the combination orthogonal
                // to it, vb X_a - va X_b, is what the data see.
                let (x, y) = (&names[*a], &names[*b]);
                let k = -va / vb;
                let combo = if (k - 1.0).abs() < 1e-6 {
                    format!("{x} + {y}")
                } else if (k + 1.0).abs() < 1e-6 {
                    format!("{x} - {y}")
                } else {
                    format!("{x} {k:+.6} * {y}")
                };
                let why = match (columns.params[*a], columns.params[*b]) {
                    (Some((ka, ja)), Some((kb, jb))) => parallel_reason(model, ka, ja, kb, jb),
                    _ => String::new(),
                };
                out.push(format!("{x} and {y} only as {combo}{why}"));
            }
            many => {
                let list: Vec<&str> = many.iter().map(|(c, _)| names[*c].as_str()).collect();
                out.push(format!(
                    "{} only in one combination (one direction of these changes leaves every \
                     measurement unchanged)",
                    list.join(", ")
                ));
            }
        }
    }
    (out, pivots)
}

/// "(axes i and i+1 are parallel)" for the d parameters of a pair of rows whose axes are
/// parallel, the classic trap of plain DH (Sect. 2.11).
fn parallel_reason(model: &ParameterModel, ka: Kind, ja: usize, kb: Kind, jb: usize) -> String {
    if ka != Kind::D || kb != Kind::D || jb != ja + 1 {
        return String::new();
    }
    let robot = model.nominal_robot();
    let Some((conv, table)) = robot.dh_table() else {
        return String::new();
    };
    // The twist between axes ja and jb: alpha_ja (standard) or alpha of row jb (modified).
    let alpha = match conv {
        crate::kinematics::Convention::Standard => table[ja - 1].1.alpha,
        crate::kinematics::Convention::Modified => table[jb - 1].1.alpha,
    };
    if alpha.sin().abs() < 1e-9 {
        let hint = if model.hayati_rows().contains(&ja) {
            String::new()
        } else {
            format!("; Hayati's beta{ja} instead of d{ja} removes the ambiguity")
        };
        format!(" (axes {ja} and {jb} are parallel: plain DH cannot place the common normal{hint})")
    } else {
        String::new()
    }
}

/// Reduced row echelon form in place, partial pivoting.
fn rref(m: &mut DMatrix<f64>) {
    let (rows, cols) = (m.nrows(), m.ncols());
    let mut lead = 0;
    for r in 0..rows {
        if lead >= cols {
            return;
        }
        // The column with the largest remaining entry from `lead` on.
        let mut found = None;
        while lead < cols {
            let (pr, pv) = (r..rows)
                .map(|i| (i, m[(i, lead)].abs()))
                .fold((r, 0.0), |b, x| if x.1 > b.1 { x } else { b });
            if pv > 1e-12 {
                found = Some(pr);
                break;
            }
            lead += 1;
        }
        let Some(pr) = found else { return };
        m.swap_rows(r, pr);
        let pivot = m[(r, lead)];
        for c in 0..cols {
            m[(r, c)] /= pivot;
        }
        for i in 0..rows {
            if i != r {
                let f = m[(i, lead)];
                for c in 0..cols {
                    let v = m[(r, c)];
                    m[(i, c)] -= f * v;
                }
            }
        }
        lead += 1;
    }
}
