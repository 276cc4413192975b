//! Which parameters a set of measurements identifies: the numerical rank of the scaled Phi, the
//! unidentifiable directions as combinations in words, and the observability indices.

use super::CalibrationError;
use super::model::{Kind, Measurement, ParameterModel};
use super::solve::{CalibrationOptions, check, column_scale, stacked};
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
    /// Free parameters (columns of the system).
    pub parameter_count: usize,
    /// Numerical rank of the column-scaled, weighted Phi.
    pub rank: usize,
    /// Singular values below `rank_threshold * sigma_max` count as zero.
    pub rank_threshold: f64,
    /// Per parameter of zeta: free and identifiable on its own.
    pub identifiable: Vec<bool>,
    /// Names of the free parameters that are not identifiable on their own.
    pub unidentifiable: Vec<String>,
    /// What can and cannot be identified, in words: "d2 and d3 only as d2 + d3 (axes 2 and 3 are
    /// parallel)", "theta6 cannot be identified: it does not change the measurements".
    pub combinations: Vec<String>,
    /// Singular values of the scaled system, largest first.
    pub singular_values: Vec<f64>,
    /// The observability indices.
    pub observability: Observability,
}

/// The identifiability of `model`'s free parameters at `zeta` for the measurements `ms`.
pub fn identifiability(
    model: &ParameterModel,
    zeta: &[f64],
    ms: &[Measurement],
    opts: &CalibrationOptions,
) -> Result<Identifiability, CalibrationError> {
    check(model, ms)?;
    identifiability_of(model, zeta, ms, opts)
}

pub(super) fn identifiability_of(
    model: &ParameterModel,
    zeta: &[f64],
    ms: &[Measurement],
    opts: &CalibrationOptions,
) -> Result<Identifiability, CalibrationError> {
    let free = model.free();
    let (phi, _) = stacked(model, zeta, ms, &free, opts)?;
    let scale = column_scale(&phi);
    let mut scaled = phi;
    for (j, mut c) in scaled.column_iter_mut().enumerate() {
        c /= scale[j];
    }
    let p = free.len();
    // A tall matrix gives all p right singular vectors; pad a short one with zero rows.
    if scaled.nrows() < p {
        scaled = scaled.resize_vertically(p, 0.0);
    }
    let svd = scaled.svd(false, true);
    let vt = svd.v_t.as_ref().expect("v_t requested");
    let mut order: Vec<usize> = (0..svd.singular_values.len()).collect();
    order.sort_by(|&a, &b| svd.singular_values[b].total_cmp(&svd.singular_values[a]));
    let sv: Vec<f64> = order.iter().map(|&k| svd.singular_values[k]).collect();
    let smax = sv.first().copied().unwrap_or(0.0);
    let rank = sv
        .iter()
        .filter(|&&s| s > opts.rank_tolerance * smax && s > 0.0)
        .count();
    // Null space basis (scaled coordinates), one row per null direction.
    let null: Vec<Vec<f64>> = order[rank..]
        .iter()
        .map(|&k| vt.row(k).iter().copied().collect())
        .collect();
    let names = model.parameters();
    let mut identifiable = vec![false; names.len()];
    let mut unidentifiable = Vec::new();
    for (c, &j) in free.iter().enumerate() {
        let weight: f64 = null.iter().map(|v| v[c] * v[c]).sum();
        identifiable[j] = weight.sqrt() < 1e-6;
        if !identifiable[j] {
            unidentifiable.push(names[j].name.clone());
        }
    }
    let combinations = describe(
        model,
        &free,
        &null,
        &scale.iter().copied().collect::<Vec<_>>(),
    );
    Ok(Identifiability {
        parameter_count: p,
        rank,
        rank_threshold: opts.rank_tolerance,
        identifiable,
        unidentifiable,
        combinations,
        observability: Observability::from_singular_values(
            &sv[..rank.max(1).min(sv.len())],
            ms.len(),
        ),
        singular_values: sv,
    })
}

/// The null directions in reduced row echelon form (each one a dependence among few parameters),
/// in parameter units, said in words.
fn describe(
    model: &ParameterModel,
    free: &[usize],
    null: &[Vec<f64>],
    scale: &[f64],
) -> Vec<String> {
    if null.is_empty() {
        return Vec::new();
    }
    let p = free.len();
    // Unscaled: a change dz = D^-1 y of the parameters along a null direction y.
    let mut m = DMatrix::from_fn(null.len(), p, |r, c| null[r][c] / scale[c]);
    rref(&mut m);
    let names = model.parameters();
    let mut out = Vec::new();
    for r in 0..m.nrows() {
        let terms: Vec<(usize, f64)> = (0..p)
            .filter(|&c| m[(r, c)].abs() > 1e-6)
            .map(|c| (c, m[(r, c)]))
            .collect();
        match terms.as_slice() {
            [] => {}
            [(c, _)] => out.push(format!(
                "{} cannot be identified: it does not change the measurements",
                names[free[*c]].name
            )),
            [(a, va), (b, vb)] => {
                // Changes along (va, vb) are invisible; va X + ... : the combination orthogonal
                // to it, vb X_a - va X_b, is what the data see.
                let (x, y) = (&names[free[*a]], &names[free[*b]]);
                let k = -va / vb;
                let combo = if (k - 1.0).abs() < 1e-6 {
                    format!("{} + {}", x.name, y.name)
                } else if (k + 1.0).abs() < 1e-6 {
                    format!("{} - {}", x.name, y.name)
                } else {
                    format!("{} {:+.6} * {}", x.name, k, y.name)
                };
                let why = parallel_reason(model, x.kind, x.joint, y.kind, y.joint);
                out.push(format!("{} and {} only as {combo}{why}", x.name, y.name));
            }
            many => {
                let list: Vec<&str> = many
                    .iter()
                    .map(|(c, _)| names[free[*c]].name.as_str())
                    .collect();
                out.push(format!(
                    "{} only in one combination (one direction of these changes leaves every \
                     measurement unchanged)",
                    list.join(", ")
                ));
            }
        }
    }
    out
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
            format!("; Hayati's beta{ja} instead of d{ja} (--hayati auto) removes the ambiguity")
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
