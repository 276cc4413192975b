//! The flange workspace of arms whose full-range spherical wrist turns the tool in every
//! direction: the wrist-centre workspace grown by a sphere (exact), checked against computations
//! written here: closed-form balls and shells, dense forward kinematics of the tool point (never
//! outside the claimed region, and every claimed interior cell hit), and the reach.

use armlab::kinematics::pose::{rot_x, rot_y, rot_z};
use armlab::kinematics::{Convention, DhJoint, DhRow, JointKind, Pose, Robot, models::built_in};
use armlab::workspace::{
    MapRequest, MapValues, MapView, PostureClassifier, Section, TrackedPoint, UNCLASSIFIED,
    compute_map, map_statistics,
};
use std::f64::consts::{FRAC_PI_2, PI};

fn row(a: f64, alpha: f64, d: f64) -> DhRow {
    DhRow {
        a,
        alpha,
        d,
        theta: 0.0,
    }
}

/// An anthropomorphic arm with spherical wrist, a2, the elbow-to-wrist length d4 and a flange
/// offset d6; joints 2 and 3 limited when `limits` is given, every other joint full-range.
fn arm(a2: f64, a3: f64, d4: f64, d6: f64, limits: Option<[[f64; 2]; 2]>, tool: Pose) -> Robot {
    arm_q1(a2, a3, d4, d6, limits, None, tool)
}

/// [`arm`] with joint 1 limited to `q1` when given.
fn arm_q1(
    a2: f64,
    a3: f64,
    d4: f64,
    d6: f64,
    limits: Option<[[f64; 2]; 2]>,
    q1: Option<[f64; 2]>,
    tool: Pose,
) -> Robot {
    let full = |r: DhRow| DhJoint::new(JointKind::Revolute, r).unbounded();
    let mut j2 = full(row(a2, 0.0, 0.0));
    let mut j3 = full(row(a3, FRAC_PI_2, 0.0));
    if let Some([l2, l3]) = limits {
        j2 = j2.limits(l2[0], l2[1]);
        j3 = j3.limits(l3[0], l3[1]);
    }
    let mut j1 = full(row(0.0, FRAC_PI_2, 0.0));
    if let Some(l) = q1 {
        j1 = j1.limits(l[0], l[1]);
    }
    let rows = [
        j1,
        j2,
        j3,
        full(row(0.0, -FRAC_PI_2, d4)),
        full(row(0.0, FRAC_PI_2, 0.0)),
        full(row(0.0, 0.0, d6)),
    ];
    let base = Pose::translation(0.1, -0.2, 0.3) * rot_z(0.7);
    Robot::from_dh("test arm", Convention::Standard, &rows, base, tool).unwrap()
}

/// The limited arm: a2 = 0.5, a3 = 0.05, d4 = 0.35, d6 = 0.12 and a tool offset off the last
/// axis, q2 in [-0.5, 2.2], q3 in [-2.4, 0.9].
fn limited_arm() -> Robot {
    let tool = Pose::translation(0.03, -0.02, 0.04) * rot_y(0.3) * rot_x(-0.2);
    arm(
        0.5,
        0.05,
        0.35,
        0.12,
        Some([[-0.5, 2.2], [-2.4, 0.9]]),
        tool,
    )
}

/// A deterministic uniform generator on [0, 1).
fn rng(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The default robot's flange: the ball of radius a2 + d4 = 1 m about the shoulder grown by
/// d6 = 0.1 m is the ball of radius 1.1 m; exact reach 0-1.1 m, volume 4/3 pi 1.1^3.
#[test]
fn default_robot_flange_is_the_ball_of_radius_1_1() {
    let r = built_in("anthropomorphic_spherical_wrist").unwrap();
    let s = Section::new(&r, TrackedPoint::Flange).unwrap();
    assert!(s.exact(), "the full-range wrist must give the exact method");
    let stats = map_statistics(&r, TrackedPoint::Flange, &Default::default()).unwrap();
    assert!(stats.reach_exact);
    assert!(stats.min_reach.abs() < 1e-12, "{}", stats.min_reach);
    assert!((stats.max_reach - 1.1).abs() < 1e-12, "{}", stats.max_reach);
    let ball = 4.0 / 3.0 * PI * 1.1f64.powi(3);
    let v = stats.volume.unwrap();
    assert!((v - ball).abs() / ball < 2e-4, "{v} vs {ball}");
    // Membership against |p| <= 1.1 on a grid of the side view.
    for i in 0..60 {
        for j in 0..120 {
            let (rr, z) = (i as f64 * 0.02 + 0.005, j as f64 * 0.02 - 1.2 + 0.005);
            let d = rr.hypot(z);
            if (d - 1.1).abs() < 1e-9 {
                continue;
            }
            assert_eq!(s.side_mask(rr, z) != 0, d < 1.1, "({rr}, {z})");
        }
    }
    let map = compute_map(
        &r,
        &MapRequest {
            view: MapView::Top,
            point: TrackedPoint::Flange,
            values: MapValues::Classes,
            cells: [200, 200],
            bounds: Some([-1.2, 1.2, -1.2, 1.2]),
            samples: 0,
            seed: 1,
            end_effector: 0,
        },
    )
    .unwrap();
    assert!(map.exact);
    assert!(map.method.starts_with("exact"), "{}", map.method);
}

/// A shell: a2 = 0.5, d4 = 0.3 reach the shell 0.2-0.8 m about the shoulder (at the base
/// origin); d6 = 0.1 makes it 0.1-0.9 m (the hole stays), d6 = 0.3 fills it (0-1.1 m).
#[test]
fn shells_grow_by_the_flange_offset_and_holes_close() {
    for (d6, inner, outer) in [(0.1, 0.1, 0.9), (0.3, 0.0, 1.1)] {
        let r = arm(0.5, 0.0, 0.3, d6, None, Pose::identity());
        let s = Section::new(&r, TrackedPoint::Flange).unwrap();
        assert!(s.exact());
        let stats = s.statistics();
        assert!(stats.reach_exact);
        assert!(
            (stats.min_reach - inner).abs() < 1e-12,
            "{}",
            stats.min_reach
        );
        assert!(
            (stats.max_reach - outer).abs() < 1e-12,
            "{}",
            stats.max_reach
        );
        let v = stats.volume.unwrap();
        let shell = 4.0 / 3.0 * PI * (outer.powi(3) - f64::powi(inner, 3));
        assert!((v - shell).abs() / shell < 1e-3, "d6 {d6}: {v} vs {shell}");
        // Side view in the base frame (the base is at (0.1, -0.2, 0.3), turned about z).
        for i in 0..50 {
            for j in 0..100 {
                let (rr, z) = (i as f64 * 0.023 + 0.004, j as f64 * 0.023 - 1.15 + 0.004);
                let d = rr.hypot(z);
                if (d - inner).abs() < 1e-9 || (d - outer).abs() < 1e-9 {
                    continue;
                }
                let want = d > inner && d < outer;
                assert_eq!(
                    s.side_mask(rr, z) != 0,
                    want,
                    "d6 {d6}: ({rr}, {z}), |p| {d}"
                );
            }
        }
    }
}

/// The limited arm: the tool points of dense random configurations always lie in the claimed
/// region with their own posture class; the reach brackets the samples.
#[test]
fn limited_arm_flange_against_dense_forward_kinematics() {
    let r = limited_arm();
    let s = Section::new(&r, TrackedPoint::Flange).unwrap();
    assert!(s.exact(), "joints 2-3 limited, the wrist full: still exact");
    let classifier = PostureClassifier::new(&r);
    let lim = r.limits();
    let mut next = rng(7);
    let mut far: f64 = 0.0;
    for _ in 0..60_000 {
        let q: Vec<f64> = lim
            .iter()
            .map(|l| {
                let (lo, hi) = if l[0].is_finite() {
                    (l[0], l[1])
                } else {
                    (-PI, PI)
                };
                lo + (hi - lo) * next()
            })
            .collect();
        let t = r.fk(&q).unwrap();
        let p = r.base.inverse_transform_point(&t.translation.vector.into());
        let (rr, z) = (p.x.hypot(p.y), p.z);
        far = far.max(p.coords.norm());
        let class = classifier.classify(&q, &t);
        let mask = s.side_mask(rr, z);
        assert_ne!(
            mask, 0,
            "q {q:?}: tool point ({rr}, {z}) outside the claimed region"
        );
        if class != UNCLASSIFIED {
            assert_ne!(
                mask & (1 << class),
                0,
                "q {q:?}: class {class} not claimed, mask {mask:b}"
            );
        }
    }
    let stats = s.statistics();
    assert!(stats.reach_exact);
    assert!(
        far <= stats.max_reach + 1e-12,
        "{far} > {}",
        stats.max_reach
    );
    assert!(far > stats.max_reach - 0.02, "{far} vs {}", stats.max_reach);
}

/// The top view is the side view turned about the axis: a radius is reached with a class exactly
/// when some height is (checked on a fine column of heights).
#[test]
fn limited_arm_top_view_is_the_side_view_turned() {
    let r = limited_arm();
    let s = Section::new(&r, TrackedPoint::Flange).unwrap();
    let map = compute_map(
        &r,
        &MapRequest {
            view: MapView::Top,
            point: TrackedPoint::Flange,
            values: MapValues::Classes,
            cells: [120, 1],
            bounds: Some([0.0, 1.2, -0.001, 0.001]),
            samples: 0,
            seed: 1,
            end_effector: 0,
        },
    )
    .unwrap();
    assert!(map.exact);
    for i in 0..120 {
        let rr = (i as f64 + 0.5) * 0.01;
        let column = (0..2000).fold(0u8, |m, k| {
            m | s.side_mask(rr.hypot(0.0), -0.9 + k as f64 * 0.0011)
        });
        let top = map.masks[i];
        // The column may miss a sliver the exact radii catch, never the reverse.
        assert_eq!(column & !top, 0, "r {rr}: column {column:b}, top {top:b}");
        if top != column {
            let near = [-0.004, 0.004].iter().any(|dr| {
                let m = (0..2000).fold(0u8, |m, k| {
                    m | s.side_mask(rr + dr, -0.9 + k as f64 * 0.0011)
                });
                m == top
            });
            assert!(near, "r {rr}: column {column:b}, top {top:b}");
        }
    }
}

/// Arms outside the exact method keep the approach scan and say so: a limited wrist (Stanford),
/// and joint 1 limited.
#[test]
fn limited_wrists_keep_the_approach_scan() {
    let stanford = built_in("stanford").unwrap();
    let s = Section::new(&stanford, TrackedPoint::Flange).unwrap();
    assert!(!s.exact());
    let r = arm_q1(
        0.5,
        0.05,
        0.35,
        0.12,
        Some([[-0.5, 2.2], [-2.4, 0.9]]),
        Some([-2.0, 2.0]),
        Pose::identity(),
    );
    assert!(!Section::new(&r, TrackedPoint::Flange).unwrap().exact());
}

/// Classes reaching the side-view point (rr, z) (base frame) found by brute force: the wrist
/// centre put at distance d from it along `n` x `2n` directions, each solved by the positioning
/// arm's closed form and kept within the limits of joints 2 and 3.
fn brute_mask(r: &Robot, rr: f64, z: f64, n: usize) -> u8 {
    use armlab::kinematics::ik::closed_form::{ClosedForm, RawSolutions};
    let cf = ClosedForm::detect(r).unwrap();
    let classifier = PostureClassifier::new(r);
    let d = cf.wrist_centre_in_tool().unwrap().norm();
    let lim = r.limits();
    let p = r.base * nalgebra::Point3::new(rr, 0.0, z);
    let mut raw = RawSolutions::default();
    let mut m = 0u8;
    for i in 0..n {
        let th = PI * (i as f64 + 0.5) / n as f64;
        for j in 0..2 * n {
            let ph = PI * j as f64 / n as f64;
            let dir = nalgebra::Vector3::new(th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos());
            if cf
                .solve_position_raw(&(p.coords - d * dir), &mut raw)
                .is_err()
            {
                continue;
            }
            for k in 0..raw.len {
                let fits = (1..3).all(|j| {
                    let v = raw.q[k][j];
                    let v = v + ((lim[j][0] - v) / (2.0 * PI)).ceil() * 2.0 * PI;
                    v <= lim[j][1]
                });
                if fits {
                    m |= classifier.posture_mask(&raw.postures[k]);
                }
            }
        }
    }
    m
}

/// The limited arm against a brute-force search over the sphere of directions: the classes
/// found are always claimed, and at points whose 8 neighbours a cell away carry the same claim
/// (away from every edge) the search finds every class claimed.
#[test]
fn limited_arm_flange_against_a_brute_force_search() {
    let r = limited_arm();
    let s = Section::new(&r, TrackedPoint::Flange).unwrap();
    let n = 24;
    let (r_max, z_lo, z_hi) = (1.2, -0.9, 1.3);
    let h = [r_max / n as f64, (z_hi - z_lo) / n as f64];
    let (mut interior, mut outside) = (0, 0);
    for j in 0..n {
        for i in 0..n {
            let c = [(i as f64 + 0.5) * h[0], z_lo + (j as f64 + 0.5) * h[1]];
            let claimed = s.side_mask(c[0], c[1]);
            let found = brute_mask(&r, c[0], c[1], 60);
            assert_eq!(
                found & !claimed,
                0,
                "{c:?}: found {found:b}, claimed {claimed:b}"
            );
            let same = [
                (-1, -1),
                (-1, 0),
                (-1, 1),
                (0, -1),
                (0, 1),
                (1, -1),
                (1, 0),
                (1, 1),
            ]
            .iter()
            .all(|&(di, dj)| {
                let p = [c[0] + di as f64 * h[0], c[1] + dj as f64 * h[1]];
                p[0] >= 0.0 && s.side_mask(p[0], p[1]) == claimed
            });
            if same {
                assert_eq!(
                    found, claimed,
                    "{c:?}: found {found:b}, claimed {claimed:b}"
                );
                if claimed != 0 {
                    interior += 1;
                } else {
                    outside += 1;
                }
            }
        }
    }
    println!("{interior} interior and {outside} outside points agree");
    assert!(interior > 100 && outside > 50, "{interior} {outside}");
}

/// An arm whose elbow at q3 = 0 folds the wrist centre back onto joint 2's axis (a2 = d4, joint 3
/// offset by -90 degrees): the section's arcs are still found (the shoulder's circle from another
/// q3), and the flange is exact: the default robot's ball of radius 1.1 m.
#[test]
fn an_arm_folded_at_zero_still_has_its_arcs() {
    let full = |r: DhRow| DhJoint::new(JointKind::Revolute, r).unbounded();
    let rows = [
        full(row(0.0, FRAC_PI_2, 0.0)),
        full(row(0.5, 0.0, 0.0)),
        full(row(0.0, FRAC_PI_2, 0.0)).offset(-FRAC_PI_2),
        full(row(0.0, -FRAC_PI_2, 0.5)),
        full(row(0.0, FRAC_PI_2, 0.0)),
        full(row(0.0, 0.0, 0.1)),
    ];
    let r = Robot::from_dh(
        "folded at zero",
        Convention::Standard,
        &rows,
        Pose::identity(),
        Pose::identity(),
    )
    .unwrap();
    // q3 = 0 puts the wrist centre on the shoulder.
    let mut q = [0.0; 6];
    q[1] = 0.7;
    let t = r.fk(&q).unwrap();
    let w = t.translation.vector - (t.rotation * nalgebra::Vector3::z()) * 0.1;
    assert!(w.norm() < 1e-12, "{w:?}");
    let s = Section::new(&r, TrackedPoint::Flange).unwrap();
    assert!(s.exact());
    let stats = s.statistics();
    assert!(stats.reach_exact);
    assert!(stats.min_reach.abs() < 1e-12 && (stats.max_reach - 1.1).abs() < 1e-12);
}

/// The scan's pruned solve (`solve_raw_where`, the wrist solved only for the positioning
/// solutions a predicate keeps) gives exactly the solutions of the full `solve_raw` whose first
/// three joints the predicate keeps, in the same order, on Stanford and the Puma over poses made
/// by the forward kinematics and poses out of reach.
#[test]
fn the_pruned_solve_is_the_full_solve_filtered() {
    use armlab::kinematics::ik::closed_form::{ClosedForm, RawSolutions};
    for name in ["stanford", "puma560"] {
        let robot = built_in(name).unwrap();
        let cf = ClosedForm::detect(&robot).unwrap();
        let keep = |a: &[f64; 3]| a[1] > -0.5 && a[2] < 0.6;
        let (mut full, mut pruned) = (RawSolutions::default(), RawSolutions::default());
        let mut kept_some = 0;
        for i in 0..200 {
            let t = i as f64;
            let q: Vec<f64> = (0..6)
                .map(|j| (0.37 * t + 1.3 * j as f64).sin() * 1.5)
                .collect();
            let mut pose = robot.fk(&q).unwrap();
            if i % 10 == 0 {
                pose.translation.vector *= 5.0;
            }
            let n_full = cf.solve_raw(&pose, &mut full).unwrap();
            let n = cf.solve_raw_where(&pose, &mut pruned, keep).unwrap();
            let expected: Vec<_> = (0..n_full)
                .filter(|&k| keep(&[full.q[k][0], full.q[k][1], full.q[k][2]]))
                .collect();
            assert_eq!(n, expected.len(), "{name} pose {i}");
            for (m, &k) in expected.iter().enumerate() {
                assert_eq!(pruned.q[m], full.q[k], "{name} pose {i}");
                assert_eq!(pruned.postures[m], full.postures[k], "{name} pose {i}");
            }
            kept_some += usize::from(n > 0 && n < n_full);
        }
        assert!(
            kept_some > 10,
            "{name}: the predicate never cut: {kept_some}"
        );
    }
}

/// Classes reaching the base-frame point (x, y) at any of `heights` (m), by brute force: 40 x 80
/// approach directions at each, each solved in closed form, joints 1 to 5
/// within their limits (the last joint rolls the tool about its approach, which leaves the
/// flange in place: any value in its range serves).
fn brute_top_mask(r: &Robot, x: f64, y: f64, heights: &[f64]) -> u8 {
    use armlab::kinematics::ik::closed_form::{ClosedForm, RawSolutions};
    use nalgebra::{Rotation3, Translation3, Vector3};
    let cf = ClosedForm::detect(r).unwrap();
    let classifier = PostureClassifier::new(r);
    let lim = r.limits();
    let revolute: Vec<bool> = (0..6)
        .map(|j| r.dof_joint(j).kind == JointKind::Revolute)
        .collect();
    let fits = |q: &[f64; 6]| {
        (0..5).all(|j| {
            let v = q[j];
            if !revolute[j] {
                return v >= lim[j][0] - 1e-9 && v <= lim[j][1] + 1e-9;
            }
            let v = v + ((lim[j][0] - v) / (2.0 * PI)).ceil() * 2.0 * PI;
            v <= lim[j][1] + 1e-9
        })
    };
    let mut raw = RawSolutions::default();
    let mut m = 0u8;
    let n = 40;
    for &z in heights {
        let p = r.base * nalgebra::Point3::new(x, y, z);
        for i in 0..n {
            let th = PI * (i as f64 + 0.5) / n as f64;
            for j in 0..2 * n {
                let ph = PI * j as f64 / n as f64;
                let a = Vector3::new(th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos());
                let rot = Rotation3::rotation_between(&Vector3::z(), &a).unwrap();
                let pose = Pose::from_parts(Translation3::from(p.coords), rot);
                if cf.solve_raw(&pose, &mut raw).is_err() {
                    continue;
                }
                for s in 0..raw.len {
                    if fits(&raw.q[s]) {
                        m |= classifier.posture_mask(&raw.postures[s]);
                    }
                }
            }
        }
    }
    m
}

/// Stanford's top view (the approach scan: its wrist is limited) against the brute force above:
/// every class claimed at a cell is found there, and inside the rim every class found is
/// claimed. The scan once kept only the first eight (class, q1) pairs of a radius and height,
/// and checked the roll joint against its limits at an arbitrary roll: it claimed "shoulder
/// left only" and "shoulder right only" patches at (-0.39, 0.09) and (0.39, -0.03) where both
/// shoulders reach.
#[test]
fn stanford_top_view_against_a_brute_force_search() {
    let r = built_in("stanford").unwrap();
    // Cells of 4 mm, about the size of the 1200 x 900 figure's pixels, where the patches were.
    let (cells, half) = (600usize, 1.2);
    let map = compute_map(
        &r,
        &MapRequest {
            view: MapView::Top,
            point: TrackedPoint::Flange,
            values: MapValues::Classes,
            cells: [cells, cells],
            bounds: Some([-half, half, -half, half]),
            samples: 0,
            seed: 1,
            end_effector: 0,
        },
    )
    .unwrap();
    assert!(!map.exact);
    let cell = 2.0 * half / cells as f64;
    let at = |x: f64, y: f64| {
        let i = ((x + half) / cell).floor() as usize;
        let j = ((half - y) / cell).floor() as usize;
        let centre = (
            -half + (i as f64 + 0.5) * cell,
            half - (j as f64 + 0.5) * cell,
        );
        (map.masks[j * cells + i], centre)
    };
    let points = [
        (-0.4, 0.08),
        (0.4, -0.02),
        (0.0, 0.6),
        (0.6, 0.6),
        (-0.6, -0.6),
        (0.21, -0.33),
        (-0.85, 0.2),
        (0.1, 0.95),
        (1.09, -0.17),
        (-1.0, 0.5),
    ];
    for (x, y) in points {
        let (claimed, (cx, cy)) = at(x, y);
        let heights: Vec<f64> = (0..41).map(|k| -1.2 + 0.06 * k as f64).collect();
        let found = brute_top_mask(&r, cx, cy, &heights);
        assert_eq!(
            claimed & !found,
            0,
            "({cx}, {cy}): claimed {claimed:b}, found {found:b}"
        );
        if cx.hypot(cy) < 1.0 {
            assert_eq!(
                claimed, found,
                "({cx}, {cy}): claimed {claimed:b}, found {found:b}"
            );
        }
    }
}

/// Stanford's point query (`Section::point_mask`, the approach scan at the point) against the
/// brute force above at single points: what it claims is found (its 64 directions may miss a
/// class that a narrow set of approaches reaches: at (-0.4, 0.08, 0) the right shoulder, which
/// the top view finds at other heights), and most points get every class found.
#[test]
fn stanford_point_query_against_a_brute_force_search() {
    let r = built_in("stanford").unwrap();
    let s = Section::new(&r, TrackedPoint::Flange).unwrap();
    let mut same = 0;
    for (x, y, z) in [
        (-0.4, 0.08, 0.0),
        (0.4, -0.02, 0.0),
        (0.3, 0.5, 0.4),
        (-0.7, -0.2, -0.3),
        (0.05, -0.9, 0.2),
    ] {
        let w = r.base * nalgebra::Point3::new(x, y, z);
        let claimed = s.point_mask([w.x, w.y, w.z]);
        let found = brute_top_mask(&r, x, y, &[z]);
        assert_eq!(
            claimed & !found,
            0,
            "({x}, {y}, {z}): claimed {claimed:b}, found {found:b}"
        );
        assert_ne!(claimed, 0, "({x}, {y}, {z}): found {found:b}");
        same += usize::from(claimed == found);
    }
    assert!(same >= 4, "only {same} of 5 points complete");
}
