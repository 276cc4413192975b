//! Pose selection: choose l poses out of candidates to maximise an observability index, by a
//! DETMAX-style exchange (add the candidate that raises the index most, then drop the pose whose
//! removal lowers it least, while that improves the set).

use super::CalibrationError;
use super::identify::Observability;
use super::model::{Measurement, ParameterModel};
use super::setup::Unknowns;
use super::solve::{CalibrationOptions, stacked};
use nalgebra::DMatrix;

/// Which index [`select_poses`] maximises.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Criterion {
    /// O1: the geometric mean of the singular values (D-optimality).
    O1,
    /// O4: the noise amplification index sigma_min^2 / sigma_max.
    O4,
}

/// The index of the poses `set` (indices into the candidates' Phi blocks).
fn index(blocks: &[DMatrix<f64>], set: &[usize], criterion: Criterion, rank_tolerance: f64) -> f64 {
    let cols = blocks[0].ncols();
    let rows: usize = set.iter().map(|&i| blocks[i].nrows()).sum();
    let mut phi = DMatrix::zeros(rows.max(cols), cols);
    let mut at = 0;
    for &i in set {
        let b = &blocks[i];
        phi.view_mut((at, 0), (b.nrows(), cols)).copy_from(b);
        at += b.nrows();
    }
    // Column scaling over the whole set, as the identifiability uses.
    for mut c in phi.column_iter_mut() {
        let n = c.norm();
        if n > 0.0 {
            c /= n;
        }
    }
    let all = phi.singular_values();
    let smax = all.max();
    // Over the numerical rank, as the identifiability report computes them.
    let s: Vec<f64> = all
        .iter()
        .copied()
        .filter(|&v| v > rank_tolerance * smax)
        .collect();
    if s.is_empty() {
        return 0.0;
    }
    let o = Observability::from_singular_values(&s, set.len());
    match criterion {
        Criterion::O1 => o.o1,
        Criterion::O4 => o.o4,
    }
}

/// Chooses `count` of the candidate measurements (only their joint values matter) that maximise
/// `criterion` for the free parameters of `model` at its nominal values; returns their indices.
/// Starts from the first `count` candidates (give them in random order for a random start).
pub fn select_poses(
    model: &ParameterModel,
    candidates: &[Measurement],
    count: usize,
    criterion: Criterion,
    opts: &CalibrationOptions,
) -> Result<Vec<usize>, CalibrationError> {
    if count == 0 || count > candidates.len() {
        return Err(CalibrationError::InvalidOption(format!(
            "cannot choose {count} poses out of {} candidates",
            candidates.len()
        )));
    }
    let zeta = model.nominal();
    let free = model.free();
    let blocks: Vec<DMatrix<f64>> = candidates
        .iter()
        .map(|m| {
            stacked(
                model,
                &zeta,
                &Unknowns::default(),
                std::slice::from_ref(m),
                &free,
                opts,
            )
            .map(|(phi, _)| phi)
        })
        .collect::<Result<_, _>>()?;
    let mut set: Vec<usize> = (0..count).collect();
    let mut best = index(&blocks, &set, criterion, opts.rank_tolerance);
    for _ in 0..4 * count {
        // Add the candidate that helps most.
        let mut add = None;
        let mut with = f64::NEG_INFINITY;
        let outside: Vec<usize> = (0..candidates.len()).filter(|c| !set.contains(c)).collect();
        for c in outside {
            set.push(c);
            let v = index(&blocks, &set, criterion, opts.rank_tolerance);
            set.pop();
            if v > with {
                with = v;
                add = Some(c);
            }
        }
        let Some(add) = add else { break };
        set.push(add);
        // Drop the pose whose removal hurts least.
        let (drop, without) = (0..set.len())
            .map(|k| {
                let removed = set.remove(k);
                let v = index(&blocks, &set, criterion, opts.rank_tolerance);
                set.insert(k, removed);
                (k, v)
            })
            .fold((0, f64::NEG_INFINITY), |b, x| if x.1 > b.1 { x } else { b });
        let dropped = set.remove(drop);
        if dropped == add || without <= best * (1.0 + 1e-12) {
            // No exchange improves the set.
            if dropped != add {
                set.retain(|&c| c != add);
                set.push(dropped);
            }
            break;
        }
        best = without;
    }
    set.sort_unstable();
    Ok(set)
}
