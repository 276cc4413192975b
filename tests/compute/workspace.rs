//! Workspace (Sect. 2.10.1, Example 2.6, Figs 2.29-2.30): areas against their closed forms,
//! deterministic parallel sampling, the exact planar boundary, posture classes against the
//! closed-form IK labels, the three-link arm of Problem 2.17 and spatial arms.

use armlab::kinematics::ik::Target;
use armlab::kinematics::ik::closed_form::ClosedForm;
use armlab::kinematics::models::built_in;
use armlab::kinematics::orientation::wrap_angle;
use armlab::kinematics::{JointKind, Robot};
use armlab::model_file::load_model_file;
use armlab::workspace::{
    CurveKind, GridMethod, GridOptions, MethodChoice, ReachTester, SampleOptions, Samples,
    StatsOptions, UNCLASSIFIED, View, analyze_grid, joint_rectangle, planar_boundary, point_cloud,
    project, sample, statistics,
};
use std::f64::consts::{FRAC_PI_2, PI, SQRT_2};
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

fn limited() -> Robot {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/robots/planar2_limited.toml");
    load_model_file(&path).unwrap_or_else(|e| panic!("{e}"))
}

fn robot(name: &str) -> Robot {
    built_in(name).expect("built-in model")
}

fn none(_: usize) {}

fn opts(samples: usize, seed: u64) -> SampleOptions {
    SampleOptions {
        samples,
        seed,
        keep_joints: true,
        ..SampleOptions::default()
    }
}

fn norm(p: &[f64; 3]) -> f64 {
    (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt()
}

fn rel(got: f64, want: f64) -> f64 {
    (got - want).abs() / want.abs()
}

/// Closed-form areas (m^2) of the two-link arm a1 = a2 = 1 with q1 in [-pi/2, pi/2] and
/// q2 in [-dm, dm] (here dm = 3 pi/4): (elbow down, elbow up, one posture only each, both, all).
///
/// Derivation. p = (c1 + c12, s1 + s12) = 2 cos(q2/2) (cos(q1 + q2/2), sin(q1 + q2/2)): for a fixed
/// q2 the reach is r = 2 cos(q2/2) and the direction angle theta = q1 + q2/2 sweeps an interval of
/// length pi (the span of q1). With d = |q2| in [0, dm] (dm < pi, so r decreases from 2 to
/// r_min = 2 cos(dm/2) one to one), elbow down (q2 = d > 0, s2 > 0) covers, at radius r(d),
/// theta in [-pi/2 + d/2, pi/2 + d/2] and elbow up (q2 = -d) theta in [-pi/2 - d/2, pi/2 - d/2]:
/// two intervals of length pi offset by d = 2 acos(r/2). In polar coordinates dA = r dr dtheta and
/// r dr = -sin(d) dd, so with an angular length L(d) at radius r(d) the area is
/// int_0^dm L(d) sin(d) dd:
/// - each posture: L = pi, A = pi (1 - cos dm) = pi (1 + sqrt2/2) = 5.36303;
/// - both postures: the intersection has L = pi - d (d <= pi), A = A_down - I with
///   I = int_0^dm d sin d dd = sin dm - dm cos dm = sqrt2/2 + 3 pi sqrt2/8 = 2.37319, so
///   A_both = 2.98985;
/// - one posture only: L = d for each, A = I = 2.37319;
/// - all reachable: the union has L = pi + d <= 2 pi (no wrap-around), A = A_down + I = 7.73622.
fn closed_form_areas() -> [f64; 5] {
    let dm = 3.0 * PI / 4.0;
    let each = PI * (1.0 - dm.cos());
    let i = dm.sin() - dm * dm.cos();
    assert!((each - PI * (1.0 + SQRT_2 / 2.0)).abs() < 1e-12);
    assert!((i - (SQRT_2 / 2.0 + 3.0 * PI * SQRT_2 / 8.0)).abs() < 1e-12);
    [each, each, i, each - i, each + i]
}

#[test]
fn two_link_areas_equal_their_closed_forms() {
    let r = limited();
    let [down, up, only, both, all] = closed_form_areas();
    let g = analyze_grid(
        &r,
        &GridOptions {
            resolution: 600,
            ..GridOptions::default()
        },
        &none,
    )
    .unwrap();
    assert!(matches!(g.method, GridMethod::ClosedForm { .. }));
    assert_eq!(g.class_names, ["elbow down", "elbow up"]);
    let checks = [
        ("all reachable", g.reachable_measure(), all),
        ("elbow down", g.class_measure(0), down),
        ("elbow up", g.class_measure(1), up),
        ("elbow down only", g.class_only_measure(0), only),
        ("elbow up only", g.class_only_measure(1), only),
        ("both postures", g.all_classes_measure(), both),
    ];
    for (what, got, want) in checks {
        println!("{what}: grid {got:.5} m^2, closed form {want:.5} m^2");
        assert!(rel(got, want) < 0.005, "{what}: {got} vs {want}");
    }
    // The posture loops ABCDA and EADFE of Fig. 2.30 give each posture's area by the shoelace
    // formula, exact up to the chord error.
    let b = planar_boundary(&r, &Default::default()).unwrap();
    for (class, want) in [(0, down), (1, up)] {
        let got = b.loop_area(class).unwrap();
        assert!(rel(got, want) < 1e-4, "loop area {class}: {got} vs {want}");
    }
    // The statistics carry the same numbers, and the exact reach 2 cos(3 pi / 8) .. 2.
    let s = statistics(
        &r,
        &StatsOptions {
            grid: GridOptions {
                resolution: 400,
                ..GridOptions::default()
            },
            ..StatsOptions::default()
        },
        &none,
    )
    .unwrap();
    assert!(s.planar && s.reach_exact);
    assert!(rel(s.area.unwrap(), all) < 0.005);
    assert!(rel(s.area_both_postures.unwrap(), both) < 0.005);
    assert!((s.max_reach - 2.0).abs() < 1e-9, "{}", s.max_reach);
    let r_min = 2.0 * (3.0 * PI / 8.0).cos();
    assert!((s.min_reach - r_min).abs() < 1e-5, "{}", s.min_reach);
    assert!(s.volume.is_none());
    // Bounding box: x from the folded elbow-up pose near q1 = -pi/2 ... to 2; y within +-2.
    assert!((s.bounds.max[0] - 2.0).abs() < 1e-9 && s.bounds.max[1] <= 2.0 + 1e-9);
}

#[test]
fn sampling_is_deterministic_whatever_the_thread_count() {
    let r = robot("planar3");
    let run = |threads: usize, seed: u64| -> Samples {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let o = SampleOptions {
                manipulability: true,
                ..opts(10_000, seed)
            };
            sample(&r, &o, &none).unwrap()
        })
    };
    let one = run(1, 7);
    for threads in [2, 3] {
        assert_eq!(one, run(threads, 7), "{threads} threads");
    }
    assert_ne!(
        one.positions,
        run(2, 8).positions,
        "another seed, other points"
    );
    assert_eq!(one.len(), 10_000);
    // Progress reaches the sample count.
    let done = AtomicUsize::new(0);
    let s = sample(&r, &opts(9_000, 1), &|d| {
        done.fetch_max(d, Ordering::Relaxed);
    })
    .unwrap();
    assert_eq!(done.load(Ordering::Relaxed), s.len());
}

#[test]
fn samples_lie_inside_the_exact_boundary_and_the_reach() {
    let r = limited();
    let b = planar_boundary(&r, &Default::default()).unwrap();
    let s = sample(&r, &opts(20_000, 3), &none).unwrap();
    let r_min = 2.0 * (3.0 * PI / 8.0).cos();
    let classes = s.classes.as_ref().unwrap();
    for (p, &c) in s.positions.iter().zip(classes) {
        let d = norm(p);
        assert!(d >= r_min - 1e-9 && d <= 2.0 + 1e-9, "{p:?}");
        assert!(p[2].abs() < 1e-12);
        // Tolerance above the chord error of the polylines, 2 m * (0.25 deg)^2 / 8 = 4.8e-6 m.
        let xy = [p[0], p[1]];
        assert_eq!(b.contains(xy, 1e-5), Some(true), "{p:?}");
        assert_eq!(b.class_contains(c, xy, 1e-5), Some(true), "{p:?} class {c}");
    }
    // Points outside: the base, behind the arm, beyond the reach.
    for p in [[0.0, 0.0], [-1.5, 0.0], [0.3, 0.0], [2.01, 0.0]] {
        assert_eq!(b.contains(p, 1e-6), Some(false), "{p:?}");
    }
    // The grid agrees with the boundary loops at cell centres away from the boundary.
    let tester = ReachTester::new(&r, 1).unwrap();
    for k in 0..400 {
        let p = [
            -2.0 + 4.0 * (k % 20) as f64 / 19.0,
            -2.0 + 4.0 * (k / 20) as f64 / 19.0,
        ];
        let near = b.curves.iter().any(|c| {
            c.points
                .iter()
                .any(|q| (q[0] - p[0]).hypot(q[1] - p[1]) < 0.01)
        });
        if !near {
            let reach = tester.test_plane(p).mask;
            for class in 0..2u8 {
                assert_eq!(
                    reach >> class & 1 == 1,
                    b.class_contains(class, p, 0.0).unwrap(),
                    "{p:?} class {class}"
                );
            }
        }
    }
}

/// The solution of `solve` equal to `q` (wrapped revolute angles), and its label.
fn label_of(robot: &Robot, cf: &ClosedForm, target: Target, q: &[f64]) -> Option<String> {
    let res = cf.solve(robot, &target).ok()?;
    res.solutions
        .iter()
        .find(|s| {
            s.q.iter().zip(q).enumerate().all(|(k, (a, b))| {
                let d = if robot.dof_joint(k).kind == JointKind::Revolute {
                    wrap_angle(a - b)
                } else {
                    a - b
                };
                d.abs() < 1e-6
            })
        })
        .map(|s| s.posture.to_string())
}

#[test]
fn posture_classes_agree_with_the_closed_form_labels() {
    for (name, r) in [
        ("planar2_limited", limited()),
        ("planar3", robot("planar3")),
        ("anthropomorphic3r", robot("anthropomorphic3r")),
        ("puma560", robot("puma560")),
        (
            "anthropomorphic_spherical_wrist",
            robot("anthropomorphic_spherical_wrist"),
        ),
        ("spherical_arm", robot("spherical_arm")),
    ] {
        let cf = ClosedForm::detect(&r).unwrap();
        let s = sample(&r, &opts(300, 11), &none).unwrap();
        let classes = s.classes.as_ref().unwrap();
        let mut checked = 0;
        for (i, &class) in classes.iter().enumerate() {
            let q = s.joint_vector(i).unwrap();
            let pose = r.fk(q).unwrap();
            let target = match r.dof() {
                2 => Target::Position(pose.translation.vector),
                _ if name.starts_with("anthropomorphic3r") || name == "spherical_arm" => {
                    Target::Position(pose.translation.vector)
                }
                _ => Target::Pose(pose),
            };
            let label = label_of(&r, &cf, target, q)
                .unwrap_or_else(|| panic!("{name}: q = {q:?} is not among the solutions"));
            assert_ne!(class, UNCLASSIFIED, "{name}: {q:?}");
            let class = &s.class_names[class as usize];
            assert!(
                label.starts_with(class.as_str()),
                "{name}: q = {q:?} labelled {label:?} but classed {class:?}"
            );
            checked += 1;
        }
        assert_eq!(checked, s.len());
    }
    // The planar rule is Siciliano's: s2 > 0 is elbow down.
    let r = limited();
    let s = sample(&r, &opts(1000, 5), &none).unwrap();
    for i in 0..s.len() {
        let q2 = s.joint_vector(i).unwrap()[1];
        let want = if q2 > 0.0 { "elbow down" } else { "elbow up" };
        assert_eq!(s.class_names[s.classes.as_ref().unwrap()[i] as usize], want);
    }
    // Arms without a closed form have the single class "all".
    let s = sample(&robot("panda"), &opts(100, 1), &none).unwrap();
    assert_eq!(s.class_names, ["all"]);
    assert!(s.classes.unwrap().iter().all(|&c| c == 0));
}

#[test]
fn joint_rectangle_and_boundary_are_labelled_as_in_figs_2_29_and_2_30() {
    let r = limited();
    let rect = joint_rectangle(&r).unwrap();
    assert_eq!(rect.singular_q2, [0.0]);
    let q = |l: &str| rect.points.iter().find(|p| p.label == l).unwrap().q;
    let (m1, m2) = (FRAC_PI_2, 3.0 * PI / 4.0);
    assert_eq!(q("a"), [-m1, 0.0]);
    assert_eq!(q("b"), [-m1, m2]);
    assert_eq!(q("c"), [m1, m2]);
    assert_eq!(q("d"), [m1, 0.0]);
    assert_eq!(q("e"), [-m1, -m2]);
    assert_eq!(q("f"), [m1, -m2]);
    let labels: Vec<&str> = rect.segments.iter().map(|s| s.label.as_str()).collect();
    assert_eq!(labels, ["ab", "bc", "cd", "da", "ae", "ef", "fd"]);
    for s in &rect.segments {
        let singular = s.label == "da";
        assert_eq!(s.kind == CurveKind::Singular, singular, "{}", s.label);
        assert_eq!(s.class.is_none(), singular, "{}", s.label);
    }
    assert_eq!(rect.bands, [([-m2, 0.0], 1), ([0.0, m2], 0)]);
    let b = planar_boundary(&r, &Default::default()).unwrap();
    let labels: Vec<&str> = b.curves.iter().map(|c| c.label.as_str()).collect();
    assert_eq!(labels, ["AB", "BC", "CD", "DA", "AE", "EF", "FD"]);
    let loops: Vec<(&str, u8)> = b
        .loops
        .iter()
        .map(|l| (l.label.as_str(), l.class))
        .collect();
    assert_eq!(loops, [("EADFE", 1), ("ABCDA", 0)]);
    // A = FK(q1m, 0) = (0, -2); C = FK(pi/2, 3pi/4); arc DA is the outer circle r = 2.
    let ab = &b.curves[0];
    assert!(ab.points[0][0].abs() < 1e-12 && (ab.points[0][1] + 2.0).abs() < 1e-12);
    let c = b.curves[1].points.last().unwrap();
    let want_c = [
        (FRAC_PI_2).cos() + (FRAC_PI_2 + m2).cos(),
        (FRAC_PI_2).sin() + (FRAC_PI_2 + m2).sin(),
    ];
    assert!((c[0] - want_c[0]).abs() < 1e-12 && (c[1] - want_c[1]).abs() < 1e-12);
    assert!(
        b.curves[3]
            .points
            .iter()
            .all(|p| (p[0].hypot(p[1]) - 2.0).abs() < 1e-12)
    );
}

#[test]
fn three_link_arm_of_problem_2_17() {
    let r = robot("planar3");
    // Minimum reach by brute force over (q2, q3) (|p| does not depend on q1).
    let lim = r.limits();
    let mut brute = f64::INFINITY;
    let n = 600;
    for i in 0..=n {
        for j in 0..=n {
            let q2 = lim[1][0] + (lim[1][1] - lim[1][0]) * i as f64 / n as f64;
            let q3 = lim[2][0] + (lim[2][1] - lim[2][0]) * j as f64 / n as f64;
            let p = r.fk(&[0.0, q2, q3]).unwrap().translation.vector;
            brute = brute.min(p.norm());
        }
    }
    let s = statistics(
        &r,
        &StatsOptions {
            grid: GridOptions {
                resolution: 200,
                orientations: 180,
                ..GridOptions::default()
            },
            ..StatsOptions::default()
        },
        &none,
    )
    .unwrap();
    println!(
        "planar3: area {:.5} m^2, both {:.5} m^2, reach {:.5} .. {:.5} m (brute-force min {brute:.5})",
        s.area.unwrap(),
        s.area_both_postures.unwrap(),
        s.min_reach,
        s.max_reach
    );
    // q = 0 is inside the limits: the stretched arm reaches a1 + a2 + a3 = 1 m.
    assert!((s.max_reach - 1.0).abs() < 1e-12, "{}", s.max_reach);
    assert!(
        s.min_reach <= brute + 1e-9 && s.min_reach > brute - 1e-3,
        "{}",
        s.min_reach
    );
    // Samples within the reach; the closed-form area against the sampled occupancy (which
    // overestimates by boundary cells).
    let smp = sample(&r, &opts(50_000, 2), &none).unwrap();
    for p in &smp.positions {
        let d = norm(p);
        assert!(d >= s.min_reach - 1e-9 && d <= s.max_reach + 1e-9, "{p:?}");
    }
    let sampled = analyze_grid(
        &r,
        &GridOptions {
            resolution: 200,
            samples: 2_000_000,
            method: MethodChoice::Sampling,
            ..GridOptions::default()
        },
        &none,
    )
    .unwrap();
    let area = s.area.unwrap();
    let occ = sampled.reachable_measure();
    assert!(
        occ > area && rel(occ, area) < 0.05,
        "sampled {occ} vs {area}"
    );
    // Boundary: 12 edges of the joint box, face folds and the aligned-links arc.
    let b = planar_boundary(&r, &Default::default()).unwrap();
    assert_eq!(
        b.curves.iter().filter(|c| c.label.starts_with('E')).count(),
        12
    );
    assert!(b.curves.iter().any(|c| c.label.starts_with('S')));
    assert!(b.loops.is_empty() && b.contains([0.5, 0.0], 0.0).is_none());
    // Dexterity: near the middle of the reach many orientations phi are reached.
    let g = analyze_grid(
        &r,
        &GridOptions {
            resolution: 60,
            orientations: 72,
            ..GridOptions::default()
        },
        &none,
    )
    .unwrap();
    let dex = g.dexterous(0.25);
    assert!(dex.measure > 0.0 && dex.measure < g.reachable_measure());
}

#[test]
fn spatial_arms_volume_and_classes() {
    // Anthropomorphic arm a2 = a3 = 1, limits [-pi, pi]: the ball of radius 2 reached by all four
    // postures.
    let r = robot("anthropomorphic3r");
    let g = analyze_grid(
        &r,
        &GridOptions {
            resolution: 40,
            samples: 100_000,
            ..GridOptions::default()
        },
        &none,
    )
    .unwrap();
    let ball = 4.0 / 3.0 * PI * 8.0;
    let v = g.reachable_measure();
    println!("anthropomorphic3r: volume {v:.4} m^3 (ball {ball:.4})");
    assert!(rel(v, ball) < 0.03, "{v} vs {ball}");
    assert_eq!(g.class_names.len(), 4);
    assert!(g.all_classes_measure() > 0.95 * v);
    // Anthropomorphic arm with spherical wrist: wrist centre in the ball of radius a2 + d4 = 1,
    // tool point 0.1 m further: reachable |p| <= 1.1, every approach direction where |p| <= 0.9.
    let r = robot("anthropomorphic_spherical_wrist");
    let g = analyze_grid(
        &r,
        &GridOptions {
            resolution: 20,
            samples: 50_000,
            ..GridOptions::default()
        },
        &none,
    )
    .unwrap();
    let v = g.reachable_measure();
    let outer = 4.0 / 3.0 * PI * 1.1f64.powi(3);
    println!("anthropomorphic_spherical_wrist: volume {v:.4} m^3 (ball of 1.1 m: {outer:.4})");
    assert!(v < outer * 1.05 && v > 4.0 / 3.0 * PI, "{v}");
    let t = ReachTester::new(&r, 1).unwrap();
    let reach = t.test_world([0.3, 0.2, 0.1]);
    assert_eq!((reach.mask, reach.reached, reach.tried), (0b1111, 64, 64));
    assert_eq!(t.test_world([0.0, 0.0, 1.2]).mask, 0);
    let dex = g.dexterous(1.0);
    assert!(
        dex.measure > 0.5 * 4.0 / 3.0 * PI * 0.9f64.powi(3),
        "{}",
        dex.measure
    );
    assert!(dex.centres.iter().all(|p| norm(p) < 1.0));
    // Puma 560 with its limits: volume and sampled reach plausible, four classes present.
    let r = robot("puma560");
    let s = statistics(
        &r,
        &StatsOptions {
            grid: GridOptions {
                resolution: 16,
                samples: 50_000,
                ..GridOptions::default()
            },
            samples: 50_000,
            ..StatsOptions::default()
        },
        &none,
    )
    .unwrap();
    println!("puma560: {s:#?}");
    assert!(!s.planar && !s.reach_exact && s.area.is_none());
    assert!(s.max_reach < 0.67183 + 0.4318 + 0.4318 + 0.0203 + 0.15005);
    assert!(s.volume.unwrap() > 1.0 && s.classes.iter().all(|c| c.with > 0.0));
    // A robot without a closed form: the sampling method.
    let g = analyze_grid(
        &robot("panda"),
        &GridOptions {
            resolution: 16,
            samples: 50_000,
            ..GridOptions::default()
        },
        &none,
    )
    .unwrap();
    assert!(matches!(g.method, GridMethod::Sampling { .. }));
    assert_eq!(g.class_names, ["all"]);
    assert!(g.reachable_measure() > 0.0);
}

#[test]
fn manipulability_views_and_point_cloud() {
    // Two-link arm: sqrt(det(J J^T)) = |det J| = a1 a2 |sin q2| (Sect. 3.9).
    let r = limited();
    let s = sample(
        &r,
        &SampleOptions {
            manipulability: true,
            ..opts(2000, 9)
        },
        &none,
    )
    .unwrap();
    let m = s.manipulability.as_ref().unwrap();
    for (i, &mi) in m.iter().enumerate() {
        let q2 = s.joint_vector(i).unwrap()[1];
        assert!((mi as f64 - q2.sin().abs()).abs() < 1e-5, "{q2}: {}", mi);
    }
    let top = project(&r, &s, View::Top);
    let side = project(&r, &s, View::SideRZ);
    assert_eq!(top.points.len(), s.len());
    for ((t, sd), p) in top.points.iter().zip(&side.points).zip(&s.positions) {
        assert_eq!(*t, [p[0], p[1]]);
        assert!((sd[0] - p[0].hypot(p[1])).abs() < 1e-12 && sd[1] == p[2]);
    }
    let cloud = point_cloud(&s);
    assert_eq!(cloud.positions.len(), s.len());
    assert_eq!(cloud.classes, *s.classes.as_ref().unwrap());
    // Bad options are errors, not panics.
    assert!(
        sample(
            &r,
            &SampleOptions {
                end_effector: 3,
                ..opts(10, 1)
            },
            &none
        )
        .is_err()
    );
    let bad = GridOptions {
        resolution: 0,
        ..GridOptions::default()
    };
    assert!(analyze_grid(&r, &bad, &none).is_err());
    assert!(planar_boundary(&robot("puma560"), &Default::default()).is_err());
    assert!(joint_rectangle(&robot("planar3")).is_err());
}

/// Throughput of the sampler (run with `--ignored --nocapture`; the release figure is the
/// `workspace` bench).
#[test]
#[ignore]
fn sampling_throughput() {
    for (name, classes) in [("planar3", false), ("planar3", true), ("puma560", false)] {
        let r = robot(name);
        let o = SampleOptions {
            samples: 2_000_000,
            classes,
            ..SampleOptions::default()
        };
        let _warm_up = sample(&r, &o, &none).unwrap();
        let t = std::time::Instant::now();
        let s = sample(&r, &o, &none).unwrap();
        let dt = t.elapsed().as_secs_f64();
        println!(
            "{name} (classes {classes}): {:.2} M positions/s on {} threads",
            s.len() as f64 / dt / 1e6,
            rayon::current_num_threads()
        );
    }
}

#[test]
fn full_range_two_link_arm_reaches_the_disk_with_both_postures() {
    // planar2: a1 = a2 = 1, limits [-pi, pi]: the disk of radius 2, every point with both
    // postures (the arcs of the q1 = +-pi edges are traversed twice and cancel in the loops).
    let r = robot("planar2");
    let disk = 4.0 * PI;
    let b = planar_boundary(&r, &Default::default()).unwrap();
    for class in 0..2 {
        let a = b.loop_area(class).unwrap();
        assert!(rel(a, disk) < 1e-4, "{class}: {a}");
    }
    let g = analyze_grid(
        &r,
        &GridOptions {
            resolution: 300,
            ..GridOptions::default()
        },
        &none,
    )
    .unwrap();
    assert!(rel(g.reachable_measure(), disk) < 0.005);
    assert!(rel(g.all_classes_measure(), disk) < 0.005);
    // The sampling method is deterministic whatever the thread count too.
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            analyze_grid(
                &r,
                &GridOptions {
                    resolution: 50,
                    samples: 40_000,
                    method: MethodChoice::Sampling,
                    ..GridOptions::default()
                },
                &none,
            )
            .unwrap()
        })
    };
    let one = run(1);
    assert_eq!(one, run(2));
    assert!(one.reachable_measure() > 0.9 * disk);
}

/// Point H of Fig. 2.30: with the figure's limits (|q1| <= pi/2, -3pi/4 <= q2 <= pi/2) arc FD
/// (q1 = pi/2, q2 from -3pi/4 to 0) crosses arc BC (q2 = pi/2) where the two postures
/// (q1, q2) = (pi/2, -pi/2) and (0, pi/2) reach the same point, (1, 1) m by the two-link forward
/// kinematics written out here; with symmetric limits the arcs meet only at F (no H).
#[test]
fn point_h_is_where_arc_fd_crosses_arc_bc() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/robots/example_2_6.toml");
    let r = load_model_file(&path).unwrap();
    let b = planar_boundary(&r, &Default::default()).unwrap();
    let fk = |q1: f64, q2: f64| [q1.cos() + (q1 + q2).cos(), q1.sin() + (q1 + q2).sin()];
    let (h1, h2) = (fk(FRAC_PI_2, -FRAC_PI_2), fk(0.0, FRAC_PI_2));
    assert!((h1[0] - h2[0]).abs() < 1e-15 && (h1[1] - h2[1]).abs() < 1e-15);
    let h = b.crossing("FD", "BC").expect("H");
    assert!((h[0] - h1[0]).hypot(h[1] - h1[1]) < 1e-9, "{h:?} vs {h1:?}");
    assert_eq!(
        b.crossing("BC", "FD").map(|p| p.map(|v| (v * 1e6).round())),
        Some([1e6, 1e6])
    );
    // H is reached with both postures and lies on the boundary of the reachable set.
    assert_eq!(b.class_contains(0, h, 1e-6), Some(true));
    assert_eq!(b.class_contains(1, h, 1e-6), Some(true));
    assert!(b.crossing("AB", "EF").is_none());
    assert!(limited_boundary_has_no_h());
}

fn limited_boundary_has_no_h() -> bool {
    let b = planar_boundary(&limited(), &Default::default()).unwrap();
    b.crossing("FD", "BC").is_none()
}
