//! Calibration without a tracker (issue 28): per setup (distance, pivot, plane, sphere, a
//! tracker of unknown pose), the identification Jacobian against finite differences of the
//! measurement written here from the robot's own FK, the rank derived by hand, recovery of a
//! simulated arm to its noise floor, and every identifiable parameter within 4 sigma of the truth.
//! Also the honest defaults on the Puma 560 (Hayati's beta, unidentifiable parameters kept
//! nominal, flags that agree with the rank analysis).

use armlab::calibration::{
    CalibrationOptions, CalibrationReport, Measurement, ParameterModel, PlaneUnknown, Setup,
    SetupScene, SimulationOptions, Unknowns, calibrate, fit, linearise, simulate_setup,
};
use armlab::kinematics::Robot;
use armlab::kinematics::models::built_in;
use armlab::kinematics::pose::Pose;
use nalgebra::{Rotation3, Translation3, Vector3};

/// The Puma 560 holding a tool 100 mm along z6, 50 mm along x6 and 30 mm along y6, so that
/// tool points see the wrist (with the tool point at the wrist centre, as the bare Puma has
/// it, they cannot; with no y offset, alpha6 and theta6 would both move it along y6 only).
fn puma_with_tool() -> Robot {
    let mut r = built_in("puma560").unwrap();
    r.set_tool(
        0,
        Pose::from_parts(Translation3::new(0.05, 0.03, 0.1), Rotation3::identity()),
    )
    .unwrap();
    r
}

/// The model calibrated by default: plain DH with Hayati's beta on the parallel axes 2-3.
fn hayati_model(robot: &Robot) -> ParameterModel {
    ParameterModel::new(robot).unwrap().with_hayati().unwrap()
}

/// The tool point of the robot with `zeta`, from the robot `robot_with` builds (its own FK, not
/// the calibration model's frames).
fn tool(model: &ParameterModel, zeta: &[f64], q: &[f64]) -> Vector3<f64> {
    let r = model.robot_with(zeta).unwrap();
    r.fk(q).unwrap().translation.vector
}

/// `f` of a measurement, written here from its definition: the distance, the pivot offset
/// `p - c`, the plane's `n . p - h`, the sphere's `|p - c|`.
fn f(model: &ParameterModel, zeta: &[f64], s: &Unknowns, m: &Measurement) -> Vec<f64> {
    match m {
        Measurement::Distance { qa, qb, .. } => {
            vec![(tool(model, zeta, qa) - tool(model, zeta, qb)).norm()]
        }
        Measurement::Pivot { q, point } => {
            let d = tool(model, zeta, q) - s.points[*point];
            vec![d.x, d.y, d.z]
        }
        Measurement::Plane { q, plane } => {
            let pl = &s.planes[*plane];
            let v = Vector3::new(pl.a, pl.b, 1.0);
            let n = pl.frame * (v / v.norm());
            vec![n.dot(&tool(model, zeta, q)) - pl.h]
        }
        Measurement::Sphere { q, sphere, .. } => {
            vec![(tool(model, zeta, q) - s.spheres[*sphere]).norm()]
        }
        _ => unreachable!("pose setups are checked in tests/compute/calibration.rs"),
    }
}

#[test]
fn identification_jacobians_match_finite_differences_of_the_measurements() {
    let robot = puma_with_tool();
    let model = hayati_model(&robot);
    // Away from the nominal parameters, so that no term vanishes by symmetry.
    let zeta: Vec<f64> = model
        .nominal()
        .iter()
        .enumerate()
        .map(|(k, v)| v + 1e-3 * ((k as f64 * 1.7).sin()))
        .collect();
    let qa = [0.3, -0.7, 0.5, 1.1, -0.4, 0.9];
    let qb = [-0.6, 0.2, -0.9, 0.4, 0.8, -1.2];
    let mut s = Unknowns {
        points: vec![Vector3::new(0.4, 0.1, 0.5)],
        planes: vec![PlaneUnknown {
            frame: Rotation3::from_euler_angles(0.3, -0.2, 0.5),
            a: 0.05,
            b: -0.1,
            h: 0.3,
        }],
        spheres: vec![Vector3::new(0.2, -0.3, 0.6)],
    };
    let ms = [
        Measurement::Distance {
            qa: qa.to_vec(),
            qb: qb.to_vec(),
            distance: 0.3,
        },
        Measurement::Pivot {
            q: qa.to_vec(),
            point: 0,
        },
        Measurement::Plane {
            q: qb.to_vec(),
            plane: 0,
        },
        Measurement::Sphere {
            q: qa.to_vec(),
            sphere: 0,
            radius: 0.025,
        },
    ];
    let h = 1e-6;
    for m in &ms {
        let l = linearise(&model, &zeta, &s, m).unwrap();
        let rows = m.rows();
        for k in 0..zeta.len() {
            let (mut zp, mut zm) = (zeta.clone(), zeta.clone());
            zp[k] += h;
            zm[k] -= h;
            let (fp, fm) = (f(&model, &zp, &s, m), f(&model, &zm, &s, m));
            for i in 0..rows {
                let fd = (fp[i] - fm[i]) / (2.0 * h);
                assert!(
                    (l.robot[(i, k)] - fd).abs() < 1e-7,
                    "{}: d f{i} / d {} = {} vs {fd}",
                    m.kind(),
                    model.parameters()[k].name,
                    l.robot[(i, k)]
                );
            }
        }
        let base = s.values();
        for k in 0..s.len() {
            let mut step = vec![0.0; s.len()];
            step[k] = h;
            s.apply(&step);
            let fp = f(&model, &zeta, &s, m);
            step[k] = -2.0 * h;
            s.apply(&step);
            let fm = f(&model, &zeta, &s, m);
            step[k] = h;
            s.apply(&step);
            for i in 0..rows {
                let fd = (fp[i] - fm[i]) / (2.0 * h);
                assert!(
                    (l.unknowns[(i, k)] - fd).abs() < 1e-7,
                    "{}: d f{i} / d {} = {} vs {fd}",
                    m.kind(),
                    s.names()[k],
                    l.unknowns[(i, k)]
                );
            }
        }
        for (a, b) in s.values().iter().zip(&base) {
            assert!((a - b).abs() < 1e-15);
        }
        // The residual is y - f.
        let y = match m {
            Measurement::Distance { distance, .. } => vec![*distance],
            Measurement::Sphere { radius, .. } => vec![*radius],
            _ => vec![0.0; rows],
        };
        let fv = f(&model, &zeta, &s, m);
        for i in 0..rows {
            assert!(
                (l.residual[i] - (y[i] - fv[i])).abs() < 1e-12,
                "{}",
                m.kind()
            );
        }
    }
}

/// Simulates `setup` on the Puma with a tool (100 measurements, 0.02 mm noise) and calibrates;
/// `fixed` are kept at their nominal values in the model (and so in the simulated truth).
fn run(
    setup: Setup,
    groups: usize,
    seed: u64,
    fixed: &[&str],
) -> (
    ParameterModel,
    Vec<f64>,
    CalibrationReport,
    Vec<Measurement>,
) {
    let mut model = hayati_model(&puma_with_tool());
    model.fix(fixed).unwrap();
    let noise_mm = 0.02;
    let sim = simulate_setup(
        &model,
        &SetupScene {
            setup,
            groups,
            ..SetupScene::default()
        },
        &SimulationOptions {
            poses: 100,
            validation_poses: 60,
            noise_mm,
            seed,
            ..SimulationOptions::default()
        },
    )
    .unwrap();
    let opts = CalibrationOptions {
        position_sigma: noise_mm * 1e-3,
        ..CalibrationOptions::default()
    };
    let report = calibrate(&model, &sim.measurements, &opts).unwrap();
    (model, sim.truth, report, sim.validation)
}

/// Recovery to the noise floor on held-out data, and every identifiable parameter within 4
/// sigma of the truth.
fn check_recovery(
    setup: Setup,
    model: &ParameterModel,
    truth: &[f64],
    r: &CalibrationReport,
    val: &[Measurement],
    four_sigma: bool,
) {
    assert!(r.converged, "{}: {:?}", setup.name(), r.reason);
    // Noise floor of a one-row residual: sigma (0.02 mm); of a 3-D offset: sqrt(3) sigma.
    let floor = if val[0].rows() == 3 {
        0.02e-3 * 3f64.sqrt()
    } else {
        0.02e-3
    };
    let after = fit(model, &r.estimate, val).unwrap();
    let before = fit(model, &model.nominal(), val).unwrap();
    assert!(
        after.position_rms < 1.3 * floor && before.position_rms > 20.0 * floor,
        "{}: held out {:.5} mm (before {:.4} mm), floor {:.5} mm",
        setup.name(),
        after.position_rms * 1e3,
        before.position_rms * 1e3,
        floor * 1e3
    );
    for (k, p) in r.parameters.iter().enumerate().filter(|_| four_sigma) {
        if let Some(sd) = r.std[k] {
            assert!(
                (r.estimate[k] - truth[k]).abs() < 4.0 * sd,
                "{}: {} = {} vs true {} (std {sd})",
                setup.name(),
                p.name,
                r.estimate[k],
                truth[k]
            );
        }
    }
}

#[test]
fn distances_recover_everything_but_the_base_pose() {
    let (model, truth, r, val) = run(Setup::Distance, 1, 11, &[]);
    // Derived: 24 parameters (a, alpha, d, theta of 6 rows, d2 replaced by beta2).
    // - A tool point is one point: the last row's four parameters move it like a vector fixed
    //   in frame 6 turned about z5, which has three numbers: one combination of a6, alpha6, d6,
    //   theta6 is invisible to every point measurement (-1).
    // - A distance does not change when the whole arm moves, and of the six rigid motions a
    //   standard table can make two: theta1 turns everything about z0, d1 shifts it along z0
    //   (-2). Rank 24 - 3 = 21.
    assert_eq!(r.nominal.rank, 21);
    assert_eq!(r.nominal.parameter_count, 24);
    let fixed: Vec<&str> = r.auto_fixed.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(fixed, ["a6", "d1", "theta1"]);
    assert_eq!(r.at_estimate.parameter_count, 21);
    assert_eq!(r.at_estimate.rank, 21);
    check_recovery(Setup::Distance, &model, &truth, &r, &val, false);
    // With the truth in the parameters estimated (the fixed ones at their nominal values), every
    // identifiable parameter within 4 sigma of it.
    let (model, truth, r, val) = run(Setup::Distance, 1, 11, &fixed);
    assert!(r.auto_fixed.is_empty());
    check_recovery(Setup::Distance, &model, &truth, &r, &val, true);
}

#[test]
fn pivot_points_recover_the_shape_with_one_length_setting_the_scale() {
    let (model, truth, r, val) = run(Setup::Pivot, 4, 12, &[]);
    // Derived: 24 parameters + 3 per point (12).
    // - One combination of the last row is invisible to any point (-1, see the distances).
    // - d1 with the points' z: a shift along z0 of arm and points changes nothing (-1): rank 34
    //   at the nominal point.
    // - Two directions are invisible only at the solution, where the offsets p - c are noise:
    //   turning arm and points about z0 (theta1), and scaling arm and points (a2, the longest
    //   length). They are fixed on top: 36 - 4 = 32 estimated, all identifiable.
    assert_eq!(r.nominal.parameter_count, 36);
    assert_eq!(r.nominal.rank, 34);
    let fixed: Vec<&str> = r.auto_fixed.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(fixed, ["a6", "d1", "theta1", "a2"]);
    assert_eq!(r.at_estimate.parameter_count, 32);
    assert_eq!(r.at_estimate.rank, 32);
    // The held-out points are re-estimated with the robot held: the shape fits to the floor.
    check_recovery(Setup::Pivot, &model, &truth, &r, &val, false);
    let (model, truth, r, val) = run(Setup::Pivot, 4, 12, &fixed);
    check_recovery(Setup::Pivot, &model, &truth, &r, &val, true);
}

#[test]
fn planes_recover_the_shape_with_one_length_setting_the_scale() {
    let (model, truth, r, val) = run(Setup::Plane, 3, 13, &[]);
    // Derived: 24 + 3 per plane (9); the last row's combination (-1); a plane moves with the
    // base: d1 with the offsets h, theta1 with the normals' tilts (-2): rank 30 at the nominal
    // point; then one length sets the scale: 33 - 4 = 29 estimated.
    assert_eq!(r.nominal.parameter_count, 33);
    assert_eq!(r.nominal.rank, 30);
    let fixed: Vec<&str> = r.auto_fixed.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(fixed, ["a6", "d1", "theta1", "a2"]);
    assert_eq!(r.at_estimate.rank, 29);
    check_recovery(Setup::Plane, &model, &truth, &r, &val, false);
    let (model, truth, r, val) = run(Setup::Plane, 3, 13, &fixed);
    check_recovery(Setup::Plane, &model, &truth, &r, &val, true);
}

#[test]
fn spheres_of_known_radius_recover_the_size_too() {
    let (model, truth, r, val) = run(Setup::Sphere, 3, 14, &[]);
    // Derived: 24 + 3 per centre (9); the last row's combination (-1); the centres move with
    // the base (d1 with their z, theta1 with their x, y: -2); the known radius fixes the scale:
    // rank 30.
    assert_eq!(r.nominal.parameter_count, 33);
    assert_eq!(r.nominal.rank, 30);
    let fixed: Vec<&str> = r.auto_fixed.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(fixed, ["a6", "d1", "theta1"]);
    assert_eq!(r.at_estimate.rank, 30);
    check_recovery(Setup::Sphere, &model, &truth, &r, &val, false);
    let (model, truth, r, val) = run(Setup::Sphere, 3, 14, &fixed);
    check_recovery(Setup::Sphere, &model, &truth, &r, &val, true);
}

#[test]
fn a_tracker_of_unknown_pose_is_registered_then_estimated_with_the_arm() {
    use armlab::calibration::register_tracker;
    let robot = puma_with_tool();
    let scene = SetupScene {
        setup: Setup::Tracker,
        ..SetupScene::default()
    };
    let opts = CalibrationOptions {
        position_sigma: 0.02e-3,
        ..CalibrationOptions::default()
    };
    // Twice: every parameter perturbed (ranks, recovery), then the truth with the parameters
    // the analysis keeps nominal at their nominal values (4 sigma).
    for fixed in [&[][..], &["a6", "d1", "theta1"][..]] {
        let mut model = hayati_model(&robot);
        model.fix(fixed).unwrap();
        let sim = simulate_setup(
            &model,
            &scene,
            &SimulationOptions {
                poses: 100,
                validation_poses: 60,
                noise_mm: 0.02,
                seed: 15,
                ..SimulationOptions::default()
            },
        )
        .unwrap();
        // Registration alone puts the tracker within the arm's deviations (millimetres) of
        // its true pose (2 m away, turned 90 degrees).
        let reg = register_tracker(&model, &model.nominal(), &sim.measurements).unwrap();
        let truth_pose = scene.world_from_tracker.inverse();
        assert!((reg.translation.vector - truth_pose.translation.vector).norm() < 0.02);
        let mut moved = robot.clone();
        moved.base = reg * robot.base;
        let mut tracker_model = hayati_model(&moved).with_base();
        tracker_model.fix(fixed).unwrap();
        let r = calibrate(&tracker_model, &sim.measurements, &opts).unwrap();
        assert!(r.converged);
        let after = fit(&tracker_model, &r.estimate, &sim.validation).unwrap();
        assert!(
            after.position_rms < 1.3 * 0.02e-3 * 3f64.sqrt(),
            "{}",
            after.position_rms
        );
        if fixed.is_empty() {
            // Derived: 24 + 6 base parameters; the last row's combination (-1); the base's
            // rotation about z0 and shift along z0 are theta1 and d1 again (-2): rank 27.
            assert_eq!(r.nominal.parameter_count, 30);
            assert_eq!(r.nominal.rank, 27);
            let names: Vec<&str> = r.auto_fixed.iter().map(|(n, _)| n.as_str()).collect();
            assert_eq!(names, ["a6", "d1", "theta1"]);
            continue;
        }
        assert!(r.auto_fixed.is_empty());
        assert_eq!(r.at_estimate.rank, 27);
        // The arm's parameters within 4 sigma of the truth; the base's six against the true
        // tracker pose relative to the registered one.
        let true_base = truth_pose * reg.inverse();
        let mut truth = sim.truth.clone();
        truth.extend(true_base.translation.vector.iter());
        truth.extend(true_base.rotation.scaled_axis().iter());
        for (k, p) in r.parameters.iter().enumerate() {
            if let Some(sd) = r.std[k] {
                assert!((r.estimate[k] - truth[k]).abs() < 4.0 * sd, "{}", p.name);
            }
        }
    }
}

#[test]
fn the_default_puma_run_writes_a_sensible_model_with_flags_that_match_the_text() {
    // The run: 60 full poses, 0.02 mm noise, defaults (Hayati's beta on axes 2-3,
    // unidentifiable parameters kept nominal).
    let model = hayati_model(&built_in("puma560").unwrap());
    let sim = simulate_setup(
        &model,
        &SetupScene::default(),
        &SimulationOptions {
            poses: 60,
            validation_poses: 60,
            noise_mm: 0.02,
            noise_mrad: 0.1,
            seed: 3,
            ..SimulationOptions::default()
        },
    )
    .unwrap();
    let opts = CalibrationOptions {
        position_sigma: 0.02e-3,
        orientation_sigma: 0.1e-3,
        ..CalibrationOptions::default()
    };
    let r = calibrate(&model, &sim.measurements, &opts).unwrap();
    assert!(r.auto_fixed.is_empty());
    for (k, p) in r.parameters.iter().enumerate() {
        if p.fixed {
            assert_eq!(r.estimate[k], p.nominal, "{}", p.name);
            continue;
        }
        let sd = r.std[k].expect("every free parameter is identifiable");
        assert!(sd < 1e-4, "{}: std {sd}", p.name);
        assert!(
            (r.estimate[k] - sim.truth[k]).abs() < 5.0 * sd,
            "{}",
            p.name
        );
        // The flag agrees with the analysis at the estimate, where it is reported.
        assert!(r.at_estimate.identifiable[k]);
        assert!(!r.at_estimate.unidentifiable.contains(&p.name));
    }
}

#[test]
fn plain_dh_keeps_d2_nominal_by_default_and_minimum_norm_shows_the_lesson() {
    use armlab::calibration::{SimulationOptions as S, Unidentifiable, simulate};
    let plain = ParameterModel::new(&built_in("puma560").unwrap()).unwrap();
    let sim = simulate(
        &plain,
        &S {
            poses: 60,
            noise_mm: 0.02,
            seed: 3,
            ..S::default()
        },
    )
    .unwrap();
    let opts = CalibrationOptions {
        position_sigma: 0.02e-3,
        orientation_sigma: 0.1e-3,
        ..CalibrationOptions::default()
    };
    let r = calibrate(&plain, &sim.measurements, &opts).unwrap();
    let d2 = plain
        .parameters()
        .iter()
        .position(|p| p.name == "d2")
        .unwrap();
    let d3 = d2 + 1;
    assert_eq!(r.auto_fixed.len(), 1);
    assert_eq!(r.auto_fixed[0].0, "d2");
    assert!(r.auto_fixed[0].1.contains("only as d2 + d3"));
    assert_eq!(r.estimate[d2], 0.0);
    // d3 carries d2 + d3 of the truth.
    assert!((r.estimate[d3] - (sim.truth[d2] + sim.truth[d3])).abs() < 5.0 * r.std[d3].unwrap());
    assert!(!r.at_estimate.identifiable[d2]);
    assert!(r.at_estimate.identifiable[d3]);
    // Every parameter of the written model stays within a few millimetres / degrees of nominal.
    for (k, p) in r.parameters.iter().enumerate() {
        let tol = if p.kind.is_angle() { 0.05 } else { 0.005 };
        assert!((r.estimate[k] - p.nominal).abs() < tol, "{}", p.name);
    }
    // Minimum-norm steps: d2 and d3 drift far (the lesson), with a standard deviation to match,
    // and the flags agree with the analysis at the estimate.
    let free = calibrate(
        &plain,
        &sim.measurements,
        &CalibrationOptions {
            unidentifiable: Unidentifiable::MinimumNorm,
            ..opts
        },
    )
    .unwrap();
    assert!((free.estimate[d2] - sim.truth[d2]).abs() > 0.01);
    assert!(free.std[d2].unwrap() > 0.01);
    for (k, p) in free.parameters.iter().enumerate() {
        assert_eq!(
            free.at_estimate.identifiable[k],
            !p.fixed && !free.at_estimate.unidentifiable.contains(&p.name)
        );
    }
}

#[test]
fn corrected_targets_put_the_real_arm_on_the_desired_poses_in_every_posture() {
    use armlab::calibration::correct_targets;
    use armlab::kinematics::ik::Target;
    use armlab::kinematics::ik::numerical::NumericalOptions;
    use armlab::kinematics::ik::solver::{SolverChoice, solve};
    let puma = built_in("puma560").unwrap();
    let model = hayati_model(&puma);
    let sim = simulate_setup(
        &model,
        &SetupScene::default(),
        &SimulationOptions {
            poses: 100,
            noise_mm: 0.02,
            noise_mrad: 0.05,
            seed: 21,
            ..SimulationOptions::default()
        },
    )
    .unwrap();
    let opts = CalibrationOptions {
        position_sigma: 0.02e-3,
        orientation_sigma: 0.05e-3,
        ..CalibrationOptions::default()
    };
    let r = calibrate(&model, &sim.measurements, &opts).unwrap();
    let calibrated = model.robot_with(&r.estimate).unwrap();
    let real = model.robot_with(&sim.truth).unwrap();
    // Desired poses: the nominal arm's tool at joint vectors well inside the workspace.
    let targets: Vec<Pose> = (0..20)
        .map(|k| {
            let q: Vec<f64> = (0..6)
                .map(|j| 0.9 * ((k * 6 + j) as f64 * 1.3).sin())
                .collect();
            puma.fk(&q).unwrap()
        })
        .collect();
    let rows = correct_targets(&puma, &calibrated, &targets).unwrap();
    let (mut worst, mut off) = (0.0f64, Vec::new());
    let numerical = NumericalOptions::default();
    for (k, t) in targets.iter().enumerate() {
        let nominal = solve(
            &puma,
            0,
            &Target::Pose(*t),
            None,
            SolverChoice::ClosedForm,
            &numerical,
        )
        .unwrap()
        .0;
        let mine: Vec<_> = rows.iter().filter(|r| r.pose == k).collect();
        // Every solution the calibrated arm has, found independently by Newton from 300 random
        // starts (near the shoulder boundary a real arm may lack a pair the nominal one has).
        let all = brute_force(&calibrated, t, 300, k as u64);
        assert_eq!(mine.len(), all.len(), "pose {k}");
        for a in &all {
            assert!(
                mine.iter().any(|r| same_q(&r.q, a)),
                "pose {k}: missed {a:?}"
            );
        }
        assert!(mine.len() <= nominal.solutions.len());
        for row in &mine {
            assert!(nominal.solutions.iter().any(|s| s.posture == row.posture));
            // FK-checked on the calibrated arm, independently here.
            let e = calibrated.fk(&row.q).unwrap();
            let dp = (e.translation.vector - t.translation.vector).norm();
            let dr = nalgebra::UnitQuaternion::from_rotation_matrix(
                &(e.rotation.inverse() * t.rotation),
            )
            .angle();
            assert!(dp < 1e-12 && dr < 1e-12, "{dp:e} {dr:e}");
            // The real arm at q is on the desired pose to the calibration's accuracy.
            let p = real.fk(&row.q).unwrap();
            worst = worst.max((p.translation.vector - t.translation.vector).norm());
            off.push(row.uncorrected_error);
            // Target filtering: the nominal controller, sent `send`, picks q in that posture.
            let back = solve(
                &puma,
                0,
                &Target::Pose(row.send),
                None,
                SolverChoice::ClosedForm,
                &numerical,
            )
            .unwrap()
            .0;
            let same = back
                .solutions
                .iter()
                .find(|s| s.posture == row.posture)
                .unwrap();
            let dq = same
                .q
                .iter()
                .zip(&row.q)
                .map(|(a, b)| armlab::kinematics::orientation::wrap_angle(a - b).abs())
                .fold(0.0, f64::max);
            assert!(dq < 1e-9, "{}: {dq:e}", row.posture);
        }
    }
    // The noise floor of the calibration: 0.02 mm per axis over 100 poses; the corrected tool
    // lands within a few hundredths of a millimetre, the uncorrected one millimetres off.
    assert!(worst < 0.05e-3, "corrected: {worst:e} m");
    let rms = (off.iter().map(|v| v * v).sum::<f64>() / off.len() as f64).sqrt();
    assert!(rms > 1e-3, "uncorrected: {rms:e} m");
}

/// Revolute joint vectors equal up to 2 pi, to 1e-6 rad.
fn same_q(a: &[f64], b: &[f64]) -> bool {
    a.iter()
        .zip(b)
        .all(|(x, y)| armlab::kinematics::orientation::wrap_angle(x - y).abs() < 1e-6)
}

/// Every distinct IK solution of `robot` at `t` that Levenberg-Marquardt finds from `starts`
/// random joint vectors (no limits).
fn brute_force(robot: &Robot, t: &Pose, starts: usize, seed: u64) -> Vec<Vec<f64>> {
    use armlab::kinematics::ik::Target;
    use armlab::kinematics::ik::numerical::{NumericalOptions, solve};
    let o = NumericalOptions {
        restarts: 0,
        enforce_limits: false,
        tolerance: 1e-13,
        max_iterations: 200,
        ..NumericalOptions::default()
    };
    let mut state = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut found: Vec<Vec<f64>> = Vec::new();
    for _ in 0..starts {
        let s: Vec<f64> = (0..robot.dof())
            .map(|_| (next() * 2.0 - 1.0) * std::f64::consts::PI)
            .collect();
        let rep = solve(robot, 0, &Target::Pose(*t), &s, &o).unwrap();
        if rep.converged && !found.iter().any(|f| same_q(f, &rep.q)) {
            found.push(rep.q);
        }
    }
    found
}

/// The torque of gravity on each revolute joint of the Puma at q, written here from its
/// definition: sum over the links after joint i of `z_{i-1} . ((p_com - o_{i-1}) x m g)`.
fn puma_gravity_torques(robot: &Robot, q: &[f64]) -> Vec<f64> {
    let frames = robot.fk_frames(q).unwrap();
    let g = Vector3::new(0.0, 0.0, -9.80665);
    (0..6)
        .map(|i| {
            let before = if i == 0 { robot.base } else { frames[i - 1] };
            let (z, o) = (before.rotation * Vector3::z(), before.translation.vector);
            robot
                .masses
                .iter()
                .filter(|m| m.joint.unwrap() >= i)
                .map(|m| {
                    let p = frames[m.joint.unwrap()] * nalgebra::Point3::from(m.com);
                    z.dot(&(p.coords - o).cross(&(g * m.mass)))
                })
                .sum()
        })
        .collect()
}

#[test]
fn joint_compliance_turns_each_joint_by_gravity_and_its_jacobian_matches() {
    let puma = built_in("puma560").unwrap();
    assert_eq!(puma.masses.len(), 5, "the Puma's link masses");
    let model = hayati_model(&puma).with_compliance().unwrap();
    let names: Vec<&str> = model
        .parameters()
        .iter()
        .filter(|p| p.kind == armlab::calibration::Kind::Compliance)
        .map(|p| p.name.as_str())
        .collect();
    assert_eq!(names, ["c1", "c2", "c3", "c4", "c5", "c6"]);
    let mut zeta = model.nominal();
    for (k, p) in model.parameters().iter().enumerate() {
        if p.kind == armlab::calibration::Kind::Compliance {
            zeta[k] = 1e-6 * (1.0 + p.joint as f64);
        }
    }
    let q = [0.3, -0.7, 0.5, 1.1, -0.4, 0.9];
    // The model's pose equals the geometric arm at q + c tau(q), tau computed here.
    let tau = puma_gravity_torques(&puma, &q);
    assert!(tau[1].abs() > 10.0, "the shoulder carries the arm: {tau:?}");
    assert!(
        tau[0].abs() < 1e-9,
        "a vertical first axis feels no gravity torque"
    );
    let bent: Vec<f64> = (0..6)
        .map(|i| q[i] + 1e-6 * (2.0 + i as f64) * tau[i])
        .collect();
    let geometric = model.robot_with(&zeta).unwrap();
    let (_, t) = model.frames(&zeta, &q).unwrap();
    let e = geometric.fk(&bent).unwrap();
    assert!((t.to_homogeneous() - e.to_homogeneous()).abs().max() < 1e-14);
    // The compliance columns of Phi against central differences of the pose.
    let phi = model.calibration_matrix(&zeta, &q, false).unwrap();
    let h = 1e-7;
    for (k, p) in model.parameters().iter().enumerate() {
        if p.kind != armlab::calibration::Kind::Compliance {
            continue;
        }
        let (mut zp, mut zm) = (zeta.clone(), zeta.clone());
        zp[k] += h;
        zm[k] -= h;
        let (_, tp) = model.frames(&zp, &q).unwrap();
        let (_, tm) = model.frames(&zm, &q).unwrap();
        let dp = (tp.translation.vector - tm.translation.vector) / (2.0 * h);
        let w =
            nalgebra::UnitQuaternion::from_rotation_matrix(&(tp.rotation * tm.rotation.inverse()))
                .scaled_axis()
                / (2.0 * h);
        for i in 0..3 {
            assert!(
                (phi[(i, k)] - dp[i]).abs() < 1e-6 * (1.0 + dp[i].abs()),
                "{}",
                p.name
            );
            assert!(
                (phi[(3 + i, k)] - w[i]).abs() < 1e-6 * (1.0 + w[i].abs()),
                "{}",
                p.name
            );
        }
    }
}

#[test]
fn joint_compliance_is_what_no_dh_parameter_absorbs_and_is_recovered() {
    let puma = built_in("puma560").unwrap();
    let with = hayati_model(&puma).with_compliance().unwrap();
    let sim = simulate_setup(
        &with,
        &SetupScene::default(),
        &SimulationOptions {
            poses: 120,
            validation_poses: 60,
            noise_mm: 0.002,
            noise_mrad: 0.005,
            seed: 41,
            ..SimulationOptions::default()
        },
    )
    .unwrap();
    let opts = CalibrationOptions {
        position_sigma: 0.002e-3,
        orientation_sigma: 0.005e-3,
        ..CalibrationOptions::default()
    };
    // Geometry alone: the DH parameters absorb part of gravity's bending (it varies with the
    // configuration much as offsets do), not all of it; with a precise tracker (2 um) the rest
    // stays well above the noise floor.
    let geometric = hayati_model(&puma);
    let g = calibrate(&geometric, &sim.measurements, &opts).unwrap();
    let floor = 3f64.sqrt() * 0.002e-3;
    let g_val = fit(&geometric, &g.estimate, &sim.validation).unwrap();
    assert!(
        g_val.position_rms > 3.0 * floor,
        "geometry alone: {:e}",
        g_val.position_rms
    );
    // With compliance: the noise floor, and each identifiable compliance within 4 sigma.
    let r = calibrate(&with, &sim.measurements, &opts).unwrap();
    assert!(r.converged);
    let val = fit(&with, &r.estimate, &sim.validation).unwrap();
    assert!(
        val.position_rms < 1.3 * floor,
        "with compliance: {:e}",
        val.position_rms
    );
    for (k, p) in r.parameters.iter().enumerate() {
        if let Some(sd) = r.std[k] {
            assert!(
                (r.estimate[k] - sim.truth[k]).abs() < 4.0 * sd,
                "{}",
                p.name
            );
        }
    }
    // c1 (vertical axis: no torque) cannot be identified and is said so; c6's torque is that
    // of the 0.09 kg wrist flange, too small to see, or lumped.
    assert!(
        r.auto_fixed
            .iter()
            .any(|(n, why)| n == "c1" && why.contains("c1")),
        "{:?}",
        r.auto_fixed
    );
}
