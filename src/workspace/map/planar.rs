//! Maps and statistics of two- and three-link planar arms from [`ExactPlanar`].

use super::raster;
use super::{
    CellValues, CurveRole, MapCurve, MapFill, MapRequest, MapValues, MapView, WorkspaceMap,
};
use crate::workspace::exact::{Arc, ExactPlanar, RegionSet};
use crate::workspace::{Aabb, ClassMeasure, GridMethod, WorkspaceStats};
use std::f64::consts::TAU;

/// The exact map of a planar arm over `bounds` (plane coordinates).
pub(super) fn map(e: &ExactPlanar, req: &MapRequest, bounds: [f64; 4]) -> WorkspaceMap {
    let dims = req.cells;
    let test = |p: [f64; 2]| e.mask(p);
    // A block far from every boundary candidate has one mask: the classes change only across
    // candidates.
    let uniform = |c: [f64; 2], r: f64| e.candidates().iter().all(|a| a.distance(c) > r);
    let masks = raster::fill_blocks(bounds, dims, &test, Some(&uniform));
    let edges = raster::edges(&masks, bounds, dims, &test);
    let step = 0.5
        * ((bounds[1] - bounds[0]) / dims[0] as f64).min((bounds[3] - bounds[2]) / dims[1] as f64);
    let values = match req.values {
        MapValues::Classes => None,
        MapValues::Dexterity => Some(dexterity(e, bounds, dims)),
        MapValues::Manipulability => Some(manipulability(e, bounds, dims)),
    };
    WorkspaceMap {
        view: MapView::Plane,
        bounds,
        width: dims[0],
        height: dims[1],
        masks,
        edges,
        class_names: e.class_names().to_vec(),
        values,
        curves: curves(e, step),
        fills: fills(e),
        method: if e.orientation_free() {
            "exact: closed-form IK with the orientation phi free (Sect. 2.12.1), decided between \
             the closed-form values of phi where a joint meets a limit"
                .into()
        } else {
            "exact: closed-form IK (Sect. 2.12.1) at each cell".into()
        },
        exact: true,
        collision: None,
    }
}

/// The exact regions to fill, each point in exactly one: the reachable set (one class); with two
/// classes, each class alone (its boundary plus the reversed boundary of the region both reach,
/// which lies inside it, so that the winding numbers are 1 only where the class alone reaches)
/// and the region both reach. With more classes the regions of several but not all classes have
/// no boundary here: none (a figure keeps the raster).
fn fills(e: &ExactPlanar) -> Vec<MapFill> {
    let arcs = |set: RegionSet| e.region(set).map(|r| r.arcs.clone());
    match e.class_names().len() {
        0 | 1 => arcs(RegionSet::Reachable)
            .map(|arcs| MapFill { mask: 1, arcs })
            .into_iter()
            .collect(),
        2 => {
            let both = arcs(RegionSet::AllClasses).unwrap_or_default();
            let reversed = both.iter().map(|a| Arc {
                start: a.start + a.sweep,
                sweep: -a.sweep,
                ..*a
            });
            let mut out: Vec<MapFill> = (0..2u8)
                .filter_map(|c| {
                    let mut own = arcs(RegionSet::Class(c))?;
                    own.extend(reversed.clone());
                    Some(MapFill {
                        mask: 1 << c,
                        arcs: own,
                    })
                })
                .collect();
            if !both.is_empty() {
                out.push(MapFill {
                    mask: 3,
                    arcs: both,
                });
            }
            out
        }
        _ => Vec::new(),
    }
}

/// The reachable boundary, the posture boundaries inside it, and the other candidates.
fn curves(e: &ExactPlanar, step: f64) -> Vec<MapCurve> {
    let outer = &e.regions()[0].arcs;
    let on_outer = |a: &Arc| {
        let m = a.at(a.start + 0.5 * a.sweep);
        outer.iter().any(|o| o.distance(m) < 1e-9)
    };
    let mut out: Vec<MapCurve> = outer
        .iter()
        .map(|a| MapCurve {
            points: a.polyline(step),
            role: CurveRole::Boundary,
            arc: Some(*a),
        })
        .collect();
    let mut inner: Vec<Arc> = Vec::new();
    for r in &e.regions()[1..] {
        for a in &r.arcs {
            let m = a.at(a.start + 0.5 * a.sweep);
            if !on_outer(a) && !inner.iter().any(|b| b.distance(m) < 1e-9) {
                inner.push(*a);
            }
        }
    }
    out.extend(inner.iter().map(|a| MapCurve {
        points: a.polyline(step),
        role: CurveRole::PostureBoundary,
        arc: Some(*a),
    }));
    out
}

/// Fraction of the orientations phi reached (exact measure of the feasible set, Sect. 2.10.1's
/// dexterous workspace).
fn dexterity(e: &ExactPlanar, bounds: [f64; 4], dims: [usize; 2]) -> CellValues {
    let free = e.orientation_free();
    let f = |p: [f64; 2]| {
        let m = e.membership(p);
        (m.mask != 0).then_some(if free {
            (m.orientations / TAU) as f32
        } else {
            0.0
        })
    };
    CellValues {
        dims,
        data: raster::values(bounds, dims, &f),
        name: "fraction of the orientations phi reached".into(),
        unit: String::new(),
        range: [0.0, 1.0],
        method: if free {
            "exact: the measure of the feasible phi intervals at each cell".into()
        } else {
            "a two-link arm reaches each point with one orientation per posture (measure 0)".into()
        },
    }
}

/// Largest position manipulability sqrt(det(J_P J_P^T)) (m^2) at each cell: over both postures
/// of a two-link arm (exact), over 96 orientations and the midpoints of the feasible intervals
/// for three links.
fn manipulability(e: &ExactPlanar, bounds: [f64; 4], dims: [usize; 2]) -> CellValues {
    let f = |p: [f64; 2]| e.max_manipulability(p).map(|v| v as f32);
    let data = raster::values(bounds, dims, &f);
    let hi = data
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .fold(0.0f32, f32::max);
    CellValues {
        dims,
        data,
        name: "largest manipulability sqrt(det(J_P J_P^T))".into(),
        unit: "m²".into(),
        range: [0.0, f64::from(hi).max(1e-12)],
        method: if e.orientation_free() {
            "largest over 96 orientations phi and the feasible intervals' midpoints".into()
        } else {
            "exact: both postures at each cell".into()
        },
    }
}

/// Exact statistics: areas by Green's theorem, bounds and reach from the boundary arcs.
pub(super) fn statistics(e: &ExactPlanar) -> WorkspaceStats {
    let area = |s: RegionSet| e.region(s).map(|r| (r.area, r.error));
    let (total, err) = area(RegionSet::Reachable).unwrap_or((0.0, 0.0));
    let both = area(RegionSet::AllClasses).map(|x| x.0);
    let n = e.class_names().len();
    let classes = e
        .class_names()
        .iter()
        .enumerate()
        .map(|(k, name)| {
            let with = if n > 1 {
                area(RegionSet::Class(k as u8)).map_or(0.0, |x| x.0)
            } else {
                total
            };
            // With two classes, "only this one" = with it - both; with one, everything.
            let only = match (n, both) {
                (2, Some(b)) => with - b,
                (1, _) => total,
                _ => with,
            };
            ClassMeasure {
                name: name.clone(),
                with,
                only,
            }
        })
        .collect();
    let mut bounds = Aabb::EMPTY;
    for a in &e.regions()[0].arcs {
        for p in a.polyline(1e-3 * e.bounds().extent()[0].max(1e-3)) {
            bounds.extend(e.frame().to_world(p));
        }
    }
    let reach = e.reach();
    WorkspaceStats {
        planar: true,
        area: Some(total),
        area_both_postures: (n == 2).then_some(both.unwrap_or(0.0)),
        volume: None,
        measure_all_classes: both.unwrap_or(total),
        classes,
        dexterous_measure: dexterous_area(e),
        bounds,
        min_reach: reach[0],
        max_reach: reach[1],
        reach_exact: true,
        cell_size: [0.0; 3],
        resolution: 0,
        samples: 0,
        method: GridMethod::ClosedForm {
            family: if e.orientation_free() {
                "three-link planar arm".into()
            } else {
                "two-link planar arm".into()
            },
            orientations: 0,
        },
        measure_method: "exact: Green's theorem over the boundary arcs".into(),
        measure_error: Some(err),
    }
}

/// Area (m^2) where at least half of the orientations are reached, on a 256 x 256 grid of exact
/// tests (0 for a two-link arm).
fn dexterous_area(e: &ExactPlanar) -> f64 {
    if !e.orientation_free() {
        return 0.0;
    }
    let b = e.bounds();
    let bounds = [b.min[0], b.max[0], b.min[1], b.max[1]];
    let dims = [256, 256];
    let half = |p: [f64; 2]| u8::from(e.membership(p).orientations >= 0.5 * TAU);
    let cells = raster::fill(bounds, dims, &half);
    let cell = (bounds[1] - bounds[0]) * (bounds[3] - bounds[2]) / (256.0 * 256.0);
    cells.iter().filter(|&&m| m != 0).count() as f64 * cell
}
