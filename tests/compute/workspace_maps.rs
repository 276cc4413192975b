//! Workspace maps (the data the figures paint): filled cells against the drawn exact boundary,
//! the closed-form side views against forward kinematics, Pappus volumes against closed forms,
//! and point queries.

use armlab::kinematics::Robot;
use armlab::kinematics::models::built_in;
use armlab::workspace::{
    CurveRole, ExactPlanar, MapRequest, MapValues, MapView, PointQuery, RegionSet, TrackedPoint,
    compute_map, map_statistics,
};
use std::f64::consts::PI;

fn robot(name: &str) -> Robot {
    built_in(name).unwrap()
}

/// Distance from `p` to a polyline.
fn polyline_distance(p: [f64; 2], pts: &[[f64; 2]]) -> f64 {
    pts.windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let d = [b[0] - a[0], b[1] - a[1]];
            let l2 = d[0] * d[0] + d[1] * d[1];
            let t = if l2 > 0.0 {
                (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / l2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (p[0] - a[0] - t * d[0]).hypot(p[1] - a[1] - t * d[1])
        })
        .fold(f64::INFINITY, f64::min)
}

/// Problem 2.17 at 1600 x 1200 cells: no filled cell lies more than one cell outside the drawn
/// boundary curve, no empty cell more than one cell inside it (inside and outside told apart by
/// an even-odd test against the drawn polylines, independent of the membership test).
#[test]
fn filled_cells_and_drawn_boundary_agree() {
    let r = robot("planar3");
    let map = compute_map(
        &r,
        &MapRequest {
            view: MapView::Plane,
            cells: [1600, 1200],
            ..Default::default()
        },
    )
    .unwrap();
    assert!(map.exact);
    let boundary: Vec<&Vec<[f64; 2]>> = map
        .curves
        .iter()
        .filter(|c| c.role == CurveRole::Boundary)
        .map(|c| &c.points)
        .collect();
    assert!(!boundary.is_empty());
    let cell = ((map.bounds[1] - map.bounds[0]) / map.width as f64)
        .max((map.bounds[3] - map.bounds[2]) / map.height as f64);
    let crossings = |p: [f64; 2]| {
        // Rays to +x: count crossings with every boundary segment.
        boundary
            .iter()
            .flat_map(|c| c.windows(2))
            .filter(|w| {
                let (a, b) = (w[0], w[1]);
                (a[1] > p[1]) != (b[1] > p[1])
                    && p[0] < a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
            })
            .count()
    };
    let mut checked = 0;
    for j in (0..map.height).step_by(3) {
        for i in (0..map.width).step_by(3) {
            let p = map.centre(i, j);
            let d = boundary
                .iter()
                .map(|c| polyline_distance(p, c))
                .fold(f64::INFINITY, f64::min);
            if d <= cell {
                continue;
            }
            let inside = crossings(p) % 2 == 1;
            let filled = map.masks[j * map.width + i] != 0;
            assert_eq!(
                filled, inside,
                "cell ({i}, {j}) at {p:?}, {d} m from the boundary"
            );
            checked += 1;
        }
    }
    assert!(checked > 150_000, "{checked}");
}

/// The Puma 560's side view (wrist centre) against forward kinematics: the wrist centre of
/// random joint vectors within the limits is inside the map's class regions, and points farther
/// from the shoulder than a2 + |(a3, d4)| are out.
#[test]
fn puma_side_view_contains_the_wrist_centres_of_random_configurations() {
    let r = robot("puma560");
    let s = armlab::workspace::Section::new(&r, TrackedPoint::WristCentre).unwrap();
    let lim = r.limits();
    let mut state = 11u64;
    let mut next = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let frames_len = r.joints().len();
    let mut frames = vec![armlab::kinematics::Pose::identity(); frames_len];
    for _ in 0..2000 {
        let q: Vec<f64> = lim.iter().map(|l| l[0] + (l[1] - l[0]) * next()).collect();
        r.fk_frames_into(&q, &mut frames).unwrap();
        // The wrist centre: the origin of frame 4 (axes 4, 5, 6 meet there).
        let w = frames[3].translation.vector;
        let l = r.base.inverse_transform_point(&w.into());
        let (rr, z) = (l.x.hypot(l.y), l.z);
        assert_ne!(
            s.side_mask(rr, z),
            0,
            "q {q:?}: wrist centre ({rr}, {z}) not in the map"
        );
        assert_ne!(s.point_mask([w.x, w.y, w.z]), 0, "q {q:?}");
    }
    // Far points: |p - shoulder| > a2 + sqrt(a3^2 + d4^2) + offset.
    let reach = 0.4318 + (0.0203f64.powi(2) + 0.4318f64.powi(2)).sqrt() + 0.16;
    for k in 0..100 {
        let a = k as f64 / 100.0 * 2.0 * PI;
        let (rr, z) = (1.2 * reach * a.cos().abs(), 0.67183 + 1.2 * reach * a.sin());
        assert_eq!(s.side_mask(rr, z), 0, "({rr}, {z})");
    }
}

/// Pappus volumes against closed forms: the full-range anthropomorphic arm (a2 = a3 = 1 m)
/// reaches the ball of radius 2 with every posture; the anthropomorphic arm with spherical
/// wrist's wrist centre reaches the ball of radius a2 + d4 = 1 m.
#[test]
fn pappus_volumes_equal_the_closed_forms() {
    let s = map_statistics(
        &robot("anthropomorphic3r"),
        TrackedPoint::WristCentre,
        &Default::default(),
    )
    .unwrap();
    let ball = 4.0 / 3.0 * PI * 8.0;
    let v = s.volume.unwrap();
    println!(
        "anthropomorphic3r: {v} (closed form {ball}), est. error {:?}",
        s.measure_error
    );
    assert!((v - ball).abs() / ball < 2e-4, "{v} vs {ball}");
    assert!(s.measure_error.unwrap() < 1e-3 * ball);
    for c in &s.classes {
        assert!(
            (c.with - ball).abs() / ball < 2e-3,
            "{}: {}",
            c.name,
            c.with
        );
    }
    let s = map_statistics(
        &robot("anthropomorphic_spherical_wrist"),
        TrackedPoint::WristCentre,
        &Default::default(),
    )
    .unwrap();
    let ball = 4.0 / 3.0 * PI;
    let v = s.volume.unwrap();
    assert!((v - ball).abs() / ball < 2e-4, "{v} vs {ball}");
    assert!(s.measure_method.starts_with("Pappus"));
}

#[test]
fn point_queries_match_the_exact_workspace() {
    let r = robot("planar3");
    let q = PointQuery::new(&r, TrackedPoint::Flange).unwrap();
    assert_eq!(q.dimension(), 2);
    assert!(q.distance_exact());
    let e = ExactPlanar::new(&r).unwrap();
    // Stretched arm along x reaches 1 m: (0.9, 0) is 0.1 m inside, reached with both postures.
    let a = q.query(&[0.9, 0.0]);
    assert!(a.reachable);
    assert_eq!(a.postures, ["elbow down", "elbow up"]);
    assert!((a.distance - 0.1).abs() < 1e-12, "{}", a.distance);
    let far = q.query(&[2.0, 0.0]);
    assert!(!far.reachable && (far.distance + 1.0).abs() < 1e-12);
    // Class answers equal the exact regions' membership.
    for p in [[0.3, 0.5], [0.3, -0.5], [0.7, 0.2], [-0.2, 0.4]] {
        let a = q.query(&p);
        let m = e.mask(p);
        assert_eq!(a.reachable, m != 0);
        let want: Vec<&str> = ["elbow down", "elbow up"]
            .iter()
            .enumerate()
            .filter(|(k, _)| m >> k & 1 == 1)
            .map(|(_, n)| *n)
            .collect();
        assert_eq!(a.postures, want, "{p:?}");
        // Inside a posture's exact region exactly when that posture is listed.
        let d0 = e.region(RegionSet::Class(0)).unwrap();
        let near = d0
            .arcs
            .iter()
            .map(|x| x.distance(p))
            .fold(f64::INFINITY, f64::min);
        assert!(near > 1e-6, "{p:?} too close to a boundary for the check");
    }
    // A spatial arm: three coordinates, estimated distances.
    let q = PointQuery::new(
        &robot("anthropomorphic_spherical_wrist"),
        TrackedPoint::WristCentre,
    )
    .unwrap();
    assert_eq!(q.dimension(), 3);
    let base = robot("anthropomorphic_spherical_wrist")
        .base
        .translation
        .vector;
    let a = q.query(&[base.x + 0.5, base.y, base.z]);
    assert!(a.reachable);
    // The wrist centre reaches the ball of radius 1 about the shoulder: 0.5 m inside.
    assert!((a.distance - 0.5).abs() < 1e-3, "{}", a.distance);
    // Arms without structure are refused with a reason.
    let err = PointQuery::new(&robot("dlr"), TrackedPoint::Flange)
        .err()
        .unwrap();
    assert!(err.to_string().contains("point queries need"), "{err}");
}

#[test]
fn dexterity_of_the_spherical_wrist_arm_is_a_continuous_map() {
    let r = robot("anthropomorphic_spherical_wrist");
    let t = std::time::Instant::now();
    let map = compute_map(
        &r,
        &MapRequest {
            view: MapView::Side,
            point: TrackedPoint::Flange,
            values: MapValues::Dexterity,
            cells: [128, 128],
            ..Default::default()
        },
    )
    .unwrap();
    println!("dexterity 128 x 128: {:?}", t.elapsed());
    let v = map.values.unwrap();
    assert!(v.dims[0] >= 128);
    let finite: Vec<f32> = v.data.iter().copied().filter(|x| x.is_finite()).collect();
    assert!(finite.contains(&1.0), "a dexterous core");
    assert!(
        finite.iter().any(|&x| x > 0.0 && x < 0.5),
        "a low-dexterity rim"
    );
}

/// Traced boundaries of a closed-form view lie on the exact boundary: the wrist centre of the
/// anthropomorphic arm with spherical wrist (a2 = d4 = 0.5 m, full joint 1) reaches the ball of
/// radius 1 m about the shoulder on the base axis, so the top view's boundary is the unit circle.
#[test]
fn traced_boundary_of_a_closed_form_view_is_on_the_exact_boundary() {
    let r = robot("anthropomorphic_spherical_wrist");
    let map = compute_map(
        &r,
        &MapRequest {
            view: MapView::Top,
            point: TrackedPoint::WristCentre,
            cells: [300, 300],
            ..Default::default()
        },
    )
    .unwrap();
    let pts: Vec<[f64; 2]> = map
        .curves
        .iter()
        .filter(|c| c.role == CurveRole::Boundary)
        .flat_map(|c| c.points.iter().copied())
        .collect();
    assert!(pts.len() > 500, "{}", pts.len());
    for p in pts {
        let rho = p[0].hypot(p[1]);
        assert!((rho - 1.0).abs() < 1e-6, "{p:?} at {rho}");
    }
}
