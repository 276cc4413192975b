//! Maps of arms with no structure to use: occupancy of joint-space samples, then refinement:
//! every empty cell next to a reached one is tried with a position-only numerical IK started at
//! the neighbour's sample, so the rim of the region is decided by IK instead of being left
//! speckled. Each cell keeps the largest manipulability seen.

use super::{CellValues, MapRequest, MapValues, MapView, WorkspaceMap};
use crate::kinematics::Robot;
use crate::kinematics::ik::Target;
use crate::kinematics::ik::numerical::{self, MaskFrame, NumericalOptions, TaskMask};
use crate::workspace::{Aabb, SampleOptions, Samples, WorkspaceError, sample};
use nalgebra::{Point3, Vector3};
use rayon::prelude::*;

/// View coordinates of a world point: plane/top (x_b, y_b), side (r, z_b).
fn to_view(robot: &Robot, view: MapView, p: [f64; 3]) -> [f64; 2] {
    let l = robot
        .base
        .inverse_transform_point(&Point3::new(p[0], p[1], p[2]));
    match view {
        MapView::Plane | MapView::Top => [l.x, l.y],
        MapView::Side => [l.x.hypot(l.y), l.z],
    }
}

fn samples(
    robot: &Robot,
    n: usize,
    seed: u64,
    manip: bool,
    ee: usize,
) -> Result<Samples, WorkspaceError> {
    sample(
        robot,
        &SampleOptions {
            samples: n,
            seed,
            end_effector: ee,
            classes: false,
            manipulability: manip,
            keep_joints: true,
        },
        &|_| {},
    )
}

/// Extent of the samples' view coordinates (50 000 samples, seed 1).
pub(super) fn extent(robot: &Robot, view: MapView, ee: usize) -> Result<Aabb, WorkspaceError> {
    let s = samples(robot, 50_000, 1, false, ee)?;
    let mut b = Aabb::EMPTY;
    for p in &s.positions {
        let v = to_view(robot, view, *p);
        b.extend([v[0], v[1], 0.0]);
    }
    Ok(b)
}

/// A configuration test: whether a joint vector may count (collision-free in a cell).
pub(crate) type ConfigFilter<'a> = &'a (dyn Fn(&[f64]) -> bool + Sync);

/// The sampled map with refined rims (see the module documentation).
pub(super) fn map(
    robot: &Robot,
    req: &MapRequest,
    bounds: [f64; 4],
    forming: &mut dyn super::MapForming,
) -> Result<WorkspaceMap, WorkspaceError> {
    map_where(robot, req, bounds, forming, None).map(|(m, _)| m)
}

/// [`map`] counting only the samples (and the rim's IK solutions) that `keep` accepts; with a
/// filter, also the cells that only rejected samples fall in (1 each, else 0).
pub(super) fn map_where(
    robot: &Robot,
    req: &MapRequest,
    bounds: [f64; 4],
    forming: &mut dyn super::MapForming,
    keep: Option<ConfigFilter<'_>>,
) -> Result<(WorkspaceMap, Vec<u8>), WorkspaceError> {
    let [w, h] = req.cells;
    let s = samples(
        robot,
        req.samples.max(1),
        req.seed,
        req.values == MapValues::Manipulability,
        req.end_effector,
    )?;
    let (owner, best, rejected) = kept_occupancy(robot, req, &s, bounds, keep);
    let method = format!(
        "sampled: {} joint-space samples (seed {}), the rim refined by numerical IK",
        s.len(),
        req.seed
    );
    let partial = |masks: Vec<u8>| WorkspaceMap {
        view: req.view,
        bounds,
        width: w,
        height: h,
        masks,
        edges: Vec::new(),
        class_names: vec!["all".into()],
        values: None,
        fills: Vec::new(),
        curves: Vec::new(),
        method: method.clone(),
        exact: false,
        collision: None,
    };
    let mut masks: Vec<u8> = owner.iter().map(|&o| u8::from(o != u32::MAX)).collect();
    // The rim refined a tile at a time, the occupancy showing the rows not refined yet.
    for j0 in (0..h).step_by(super::TILE_ROWS) {
        let cells = j0 * w..(j0 + super::TILE_ROWS).min(h) * w;
        let refined = refine(robot, req, &s, &owner, bounds, cells.clone(), keep);
        for (m, r) in masks[cells.clone()].iter_mut().zip(refined) {
            *m |= u8::from(r);
        }
        if cells.end < w * h && forming.wants() {
            forming.partial(&partial(masks.clone()), h);
        }
    }
    let values = (req.values != MapValues::Classes).then(|| {
        let hi = best
            .iter()
            .copied()
            .filter(|v| v.is_finite())
            .fold(0.0f32, f32::max);
        CellValues {
            dims: [w, h],
            data: best,
            name: "largest manipulability of the samples in the cell".into(),
            unit: String::new(),
            range: [0.0, f64::from(hi).max(1e-12)],
            method: format!("{} joint-space samples", s.len()),
        }
    });
    let map = WorkspaceMap {
        values,
        ..partial(masks)
    };
    let rejected = rejected
        .iter()
        .zip(&map.masks)
        .map(|(r, m)| r & !m)
        .collect();
    Ok((map, rejected))
}

/// [`occupancy`] of the samples `keep` accepts (all without a filter), and with a filter the
/// cells (1 each) that only rejected samples fall in.
fn kept_occupancy(
    robot: &Robot,
    req: &MapRequest,
    s: &Samples,
    bounds: [f64; 4],
    keep: Option<ConfigFilter<'_>>,
) -> (Vec<u32>, Vec<f32>, Vec<u8>) {
    let Some(f) = keep else {
        let (owner, best) = occupancy(robot, req, s, bounds, None);
        return (owner, best, Vec::new());
    };
    let kept: Vec<bool> = (0..s.len())
        .into_par_iter()
        .map(|k| s.joint_vector(k).is_none_or(f))
        .collect();
    let (owner, best) = occupancy(robot, req, s, bounds, Some(&kept));
    let (all, _) = occupancy(robot, req, s, bounds, None);
    let rejected = all
        .iter()
        .zip(&owner)
        .map(|(a, o)| u8::from(*a != u32::MAX && *o == u32::MAX))
        .collect();
    (owner, best, rejected)
}

/// Per cell, the last sample in it (`u32::MAX` for none) and the largest manipulability of its
/// samples (NaN for none, or when not sampled).
fn occupancy(
    robot: &Robot,
    req: &MapRequest,
    s: &Samples,
    bounds: [f64; 4],
    kept: Option<&[bool]>,
) -> (Vec<u32>, Vec<f32>) {
    let [w, h] = req.cells;
    let cell_of = |v: [f64; 2]| -> Option<usize> {
        let u = (v[0] - bounds[0]) / (bounds[1] - bounds[0]) * w as f64;
        let t = (bounds[3] - v[1]) / (bounds[3] - bounds[2]) * h as f64;
        (u >= 0.0 && t >= 0.0 && u < w as f64 && t < h as f64).then(|| t as usize * w + u as usize)
    };
    let mut owner = vec![u32::MAX; w * h];
    let mut best = vec![f32::NAN; w * h];
    for (k, p) in s.positions.iter().enumerate() {
        if kept.is_some_and(|kept| !kept[k]) {
            continue;
        }
        if let Some(c) = cell_of(to_view(robot, req.view, *p)) {
            owner[c] = k as u32;
            if let Some(m) = &s.manipulability {
                best[c] = if best[c].is_nan() {
                    m[k]
                } else {
                    best[c].max(m[k])
                };
            }
        }
    }
    (owner, best)
}

/// Of the cells `cells`: the empty ones with a reached 8-neighbour, tried by position IK from
/// that neighbour's sample.
fn refine(
    robot: &Robot,
    req: &MapRequest,
    s: &Samples,
    owner: &[u32],
    bounds: [f64; 4],
    cells: std::ops::Range<usize>,
    keep: Option<ConfigFilter<'_>>,
) -> Vec<bool> {
    let (view, [w, h]) = (req.view, req.cells);
    let opts = NumericalOptions {
        max_iterations: 40,
        restarts: 0,
        tolerance: 1e-9,
        mask: match view {
            MapView::Top => TaskMask([true, true, false, false, false, false], MaskFrame::World),
            _ => TaskMask::POSITION,
        },
        ..NumericalOptions::default()
    };
    cells
        .into_par_iter()
        .map(|c| {
            if owner[c] != u32::MAX {
                return false;
            }
            let (i, j) = ((c % w) as isize, (c / w) as isize);
            let nbr = (-1..=1)
                .flat_map(|dj| (-1..=1).map(move |di| (i + di, j + dj)))
                .filter(|&(x, y)| x >= 0 && y >= 0 && (x as usize) < w && (y as usize) < h)
                .map(|(x, y)| owner[y as usize * w + x as usize])
                .find(|&o| o != u32::MAX);
            let Some(o) = nbr else {
                return false;
            };
            let q0 = s.joint_vector(o as usize).unwrap_or(&[]);
            let v = super::raster::centre(bounds, [w, h], c % w, c / w);
            let target = world_target(robot, view, v, s.positions[o as usize]);
            numerical::solve(
                robot,
                req.end_effector,
                &Target::Position(target),
                q0,
                &opts,
            )
            .is_ok_and(|r| r.converged && keep.is_none_or(|f| f(&r.q)))
        })
        .collect()
}

/// The world point of view coordinates `v`, at the height (top view) or azimuth (side view) of
/// the neighbour's sample `near`.
fn world_target(robot: &Robot, view: MapView, v: [f64; 2], near: [f64; 3]) -> Vector3<f64> {
    let l = robot
        .base
        .inverse_transform_point(&Point3::new(near[0], near[1], near[2]));
    let local = match view {
        MapView::Plane | MapView::Top => Point3::new(v[0], v[1], l.z),
        MapView::Side => {
            let psi = l.y.atan2(l.x);
            Point3::new(v[0] * psi.cos(), v[0] * psi.sin(), v[1])
        }
    };
    (robot.base * local).coords
}
