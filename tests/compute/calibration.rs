//! Kinematic calibration (Sect. 2.11): Phi against finite differences, recovery of simulated
//! robots, identifiability of known rank deficiencies, observability indices, bad input.

use armlab::calibration::{
    CalibrationError, CalibrationOptions, Measurement, Observability, ParameterModel,
    SimulationOptions, Unidentifiable, calibrate, fit, identifiability, simulate,
};
use armlab::kinematics::models::built_in;
use armlab::kinematics::orientation::angle_axis_from_rotation;
use nalgebra::Vector3;

/// The pose change between two zeta, as the model's error convention measures it: [dp; dphi].
fn pose_difference(model: &ParameterModel, za: &[f64], zb: &[f64], q: &[f64]) -> [f64; 6] {
    let (_, ta) = model.frames(za, q).unwrap();
    let (_, tb) = model.frames(zb, q).unwrap();
    let dp = ta.translation.vector - tb.translation.vector;
    let aa = angle_axis_from_rotation(&(ta.rotation * tb.rotation.inverse()));
    let w = aa.axis.into_inner() * aa.angle;
    [dp.x, dp.y, dp.z, w.x, w.y, w.z]
}

#[test]
fn phi_matches_central_finite_differences() {
    for (name, q) in [
        ("puma560", vec![0.3, -0.7, 0.5, 1.1, -0.4, 0.9]),
        ("panda", vec![0.2, -0.4, 0.3, -2.0, 0.5, 1.7, -0.6]),
        ("stanford", vec![0.4, 0.9, 0.6, -0.3, 0.8, 0.2]),
        ("scara", vec![0.5, -0.9, 0.1, 0.4]),
    ] {
        let r = built_in(name).unwrap();
        let model = ParameterModel::new(&r).unwrap();
        let zeta = model.nominal();
        let phi = model.calibration_matrix(&zeta, &q, false).unwrap();
        let phi_pos = model.calibration_matrix(&zeta, &q, true).unwrap();
        let h = 1e-6;
        for k in 0..zeta.len() {
            let mut zp = zeta.clone();
            let mut zm = zeta.clone();
            zp[k] += h;
            zm[k] -= h;
            let d = pose_difference(&model, &zp, &zm, &q);
            for i in 0..6 {
                let fd = d[i] / (2.0 * h);
                assert!(
                    (phi[(i, k)] - fd).abs() < 1e-7,
                    "{name}: Phi[{i}, {}] = {} vs {fd}",
                    model.parameters()[k].name,
                    phi[(i, k)]
                );
                if i < 3 {
                    assert_eq!(phi_pos[(i, k)], phi[(i, k)]);
                }
            }
        }
    }
}

#[test]
fn phi_of_base_and_tool_parameters_matches_finite_differences_away_from_nominal() {
    let puma = built_in("puma560").unwrap();
    let model = ParameterModel::new(&puma).unwrap().with_base().with_tool();
    assert_eq!(model.parameters().len(), 36);
    let mut zeta = model.nominal();
    // Base and tool moved well away from identity, so the rotation-vector Jacobian matters.
    for (k, v) in [
        0.1, -0.2, 0.05, 0.3, -0.4, 0.2, 0.02, 0.03, -0.01, -0.5, 0.25, 0.6,
    ]
    .iter()
    .enumerate()
    {
        zeta[24 + k] = *v;
    }
    let q = [0.3, -0.7, 0.5, 1.1, -0.4, 0.9];
    let phi = model.calibration_matrix(&zeta, &q, false).unwrap();
    let h = 1e-6;
    for k in 0..zeta.len() {
        let (mut zp, mut zm) = (zeta.clone(), zeta.clone());
        zp[k] += h;
        zm[k] -= h;
        let d = pose_difference(&model, &zp, &zm, &q);
        for i in 0..6 {
            let fd = d[i] / (2.0 * h);
            assert!(
                (phi[(i, k)] - fd).abs() < 1e-7,
                "Phi[{i}, {}] = {} vs {fd}",
                model.parameters()[k].name,
                phi[(i, k)]
            );
        }
    }
    // The robot with those parameters is what the model predicts.
    let robot = model.robot_with(&zeta).unwrap();
    let (_, t) = model.frames(&zeta, &q).unwrap();
    assert!((robot.fk(&q).unwrap().to_homogeneous() - t.to_homogeneous()).amax() < 1e-12);
}

#[test]
fn base_and_tool_deviations_are_recovered_from_noise_free_poses() {
    let puma = built_in("puma560").unwrap();
    let model = ParameterModel::new(&puma).unwrap().with_base().with_tool();
    let sim = simulate(
        &model,
        &SimulationOptions {
            noise_mm: 0.0,
            noise_mrad: 0.0,
            poses: 60,
            ..Default::default()
        },
    )
    .unwrap();
    let report = calibrate(&model, &sim.measurements, &CalibrationOptions::default()).unwrap();
    assert!(report.converged, "{:?}", report.reason);
    let v = fit(&model, &report.estimate, &sim.validation).unwrap();
    assert!(
        v.position_max < 1e-9 && v.orientation_max.unwrap() < 1e-9,
        "{v:?}"
    );
    // With the base free, the first joint's theta and d lump with the base's rotation and height.
    let c = &report.nominal.combinations;
    assert!(
        c.iter()
            .any(|s| s.contains("theta1") && s.contains("base_rz")),
        "{c:?}"
    );
    assert!(
        c.iter().any(|s| s.contains("d1") && s.contains("base_z")),
        "{c:?}"
    );
}

#[test]
fn noise_free_data_recovers_the_robot_and_names_the_parallel_axes() {
    let puma = built_in("puma560").unwrap();
    let model = ParameterModel::new(&puma).unwrap();
    let sim = simulate(
        &model,
        &SimulationOptions {
            poses: 40,
            noise_mm: 0.0,
            noise_mrad: 0.0,
            seed: 7,
            ..SimulationOptions::default()
        },
    )
    .unwrap();
    // Minimum-norm steps: plain DH estimates d2 and d3 (only their sum is seen at the nominal
    // point); the default keeps d2 nominal (tests/compute/calibration_setups.rs).
    let opts = CalibrationOptions {
        unidentifiable: Unidentifiable::MinimumNorm,
        ..CalibrationOptions::default()
    };
    let report = calibrate(&model, &sim.measurements, &opts).unwrap();
    assert!(report.converged, "{:?}", report.reason);
    let v = fit(&model, &report.estimate, &sim.validation).unwrap();
    assert!(
        v.position_max < 1e-9 && v.orientation_max.unwrap() < 1e-9,
        "{v:?}"
    );
    let before = fit(&model, &model.nominal(), &sim.validation).unwrap();
    assert!(
        before.position_rms > 1e-4,
        "the deviations are visible: {before:?}"
    );
    // Every identifiable parameter is recovered to 1e-9.
    for (k, p) in model.parameters().iter().enumerate() {
        if report.at_estimate.identifiable[k] {
            assert!(
                (report.estimate[k] - sim.truth[k]).abs() < 1e-9,
                "{}: {} vs {}",
                p.name,
                report.estimate[k],
                sim.truth[k]
            );
        }
    }
    // Axes 2 and 3 of the Puma are parallel: only d2 + d3 is identifiable, and it is recovered.
    let ident = &report.nominal;
    assert!(
        ident
            .combinations
            .iter()
            .any(|c| c.starts_with("d2 and d3 only as d2 + d3") && c.contains("parallel")),
        "{:?}",
        ident.combinations
    );
    let idx = |n: &str| model.parameters().iter().position(|p| p.name == n).unwrap();
    let (d2, d3) = (idx("d2"), idx("d3"));
    assert!(!ident.identifiable[d2] && !ident.identifiable[d3]);
    let sum = report.estimate[d2] + report.estimate[d3];
    assert!((sum - (sim.truth[d2] + sim.truth[d3])).abs() < 1e-9);
    assert!(ident.rank < ident.parameter_count);
}

#[test]
fn noisy_estimates_lie_within_four_sigma_and_validation_reaches_the_noise_floor() {
    let puma = built_in("puma560").unwrap();
    // With Hayati's beta on the parallel axes 2-3 (the default): every parameter identifiable.
    let model = ParameterModel::new(&puma).unwrap().with_hayati().unwrap();
    let (noise_mm, noise_mrad) = (0.02, 0.05);
    let sim = simulate(
        &model,
        &SimulationOptions {
            poses: 200,
            validation_poses: 100,
            noise_mm,
            noise_mrad,
            seed: 11,
            ..SimulationOptions::default()
        },
    )
    .unwrap();
    let opts = CalibrationOptions {
        position_sigma: noise_mm * 1e-3,
        orientation_sigma: noise_mrad * 1e-3,
        ..CalibrationOptions::default()
    };
    let report = calibrate(&model, &sim.measurements, &opts).unwrap();
    assert!(report.converged, "{:?}", report.reason);
    // The residual variance of the weighted system is about 1 when the noise is as stated.
    assert!(
        (0.7..1.4).contains(&report.sigma2),
        "sigma^2 = {}",
        report.sigma2
    );
    let mut checked = 0;
    for (k, p) in model.parameters().iter().enumerate() {
        if let Some(s) = report.std[k] {
            let err = (report.estimate[k] - sim.truth[k]).abs();
            assert!(
                err <= 4.0 * s,
                "{}: error {err:e} vs 4 sigma {:e}",
                p.name,
                4.0 * s
            );
            checked += 1;
        }
    }
    assert!(
        checked >= 20,
        "{checked} parameters with a standard deviation"
    );
    // Validation: the position error of a perfect model would be the noise, |n| ~ sqrt(3) sigma.
    let v = fit(&model, &report.estimate, &sim.validation).unwrap();
    let floor = 3f64.sqrt() * noise_mm * 1e-3;
    assert!(
        v.position_rms < 1.3 * floor,
        "{:e} vs floor {floor:e}",
        v.position_rms
    );
    let before = fit(&model, &model.nominal(), &sim.validation).unwrap();
    assert!(before.position_rms > 10.0 * v.position_rms);
}

#[test]
fn two_link_arm_with_positions_has_rank_six() {
    // Independently of the code: the tool point is the origin of frame 2, so alpha2 (a rotation
    // about x2 through that origin) never moves it; d1 and d2 both translate along parallel z
    // axes, so only d1 + d2 shows. The other six (a1, a2, alpha1, theta1, theta2 and d1 + d2)
    // move the point in independent ways: rank 8 - 2 = 6.
    let r = built_in("planar2").unwrap();
    let model = ParameterModel::new(&r).unwrap();
    let sim = simulate(
        &model,
        &SimulationOptions {
            position_only: true,
            poses: 20,
            noise_mm: 0.0,
            ..SimulationOptions::default()
        },
    )
    .unwrap();
    let ident = identifiability(
        &model,
        &model.nominal(),
        &sim.measurements,
        &CalibrationOptions::default(),
    )
    .unwrap();
    assert_eq!(ident.parameter_count, 8);
    assert_eq!(ident.rank, 6, "{:?}", ident.singular_values);
    let mut un = ident.unidentifiable.clone();
    un.sort();
    assert_eq!(un, ["alpha2", "d1", "d2"]);
    assert!(
        ident
            .combinations
            .iter()
            .any(|c| c.starts_with("alpha2 cannot be identified")),
        "{:?}",
        ident.combinations
    );
    assert!(
        ident
            .combinations
            .iter()
            .any(|c| c.starts_with("d1 and d2 only as d1 + d2")),
        "{:?}",
        ident.combinations
    );
}

#[test]
fn fixing_parameters_removes_them_from_the_estimate() {
    let puma = built_in("puma560").unwrap();
    let mut model = ParameterModel::new(&puma).unwrap();
    model.fix(&["d3", "theta6"]).unwrap();
    assert!(matches!(
        model.fix(&["q9"]),
        Err(CalibrationError::InvalidOption(_))
    ));
    let sim = simulate(
        &model,
        &SimulationOptions {
            noise_mm: 0.0,
            noise_mrad: 0.0,
            ..Default::default()
        },
    )
    .unwrap();
    let report = calibrate(&model, &sim.measurements, &CalibrationOptions::default()).unwrap();
    let idx = |n: &str| model.parameters().iter().position(|p| p.name == n).unwrap();
    assert_eq!(report.estimate[idx("d3")], model.nominal()[idx("d3")]);
    assert_eq!(sim.truth[idx("theta6")], model.nominal()[idx("theta6")]);
    // With d3 fixed, d2 alone carries the common offset and is identifiable.
    assert!(report.at_estimate.identifiable[idx("d2")]);
}

#[test]
fn observability_indices_of_known_singular_values() {
    // sigma = (2, 1, 0.5), 4 poses: O1 = (2 * 1 * 0.5)^(1/3) / sqrt(4) = 0.5, O2 = 0.25,
    // O3 = 0.5, O4 = 0.25 / 2 = 0.125.
    let o = Observability::from_singular_values(&[1.0, 2.0, 0.5], 4);
    assert!((o.o1 - 0.5).abs() < 1e-15 && (o.o2 - 0.25).abs() < 1e-15);
    assert!((o.o3 - 0.5).abs() < 1e-15 && (o.o4 - 0.125).abs() < 1e-15);
}

#[test]
fn bad_measurements_are_typed_errors() {
    let puma = built_in("puma560").unwrap();
    let model = ParameterModel::new(&puma).unwrap();
    let opts = CalibrationOptions::default();
    let pos = |q: Vec<f64>, x: f64| Measurement::Position {
        q,
        p: Vector3::new(x, 0.0, 1.0),
    };
    let e = calibrate(&model, &[pos(vec![0.0; 5], 0.5)], &opts).unwrap_err();
    assert!(
        matches!(
            e,
            CalibrationError::JointCount {
                index: 0,
                expected: 6,
                got: 5
            }
        ),
        "{e}"
    );
    let e = calibrate(&model, &[pos(vec![0.0; 6], f64::NAN)], &opts).unwrap_err();
    assert!(matches!(e, CalibrationError::NonFinite { index: 0 }), "{e}");
    let pose = Measurement::Pose {
        q: vec![0.0; 6],
        world_from_tool: puma.fk(&[0.0; 6]).unwrap(),
    };
    let e = calibrate(&model, &[pose, pos(vec![0.0; 6], 0.5)], &opts).unwrap_err();
    assert!(
        matches!(e, CalibrationError::MixedKinds { index: 1, .. }),
        "{e}"
    );
    let few: Vec<Measurement> = (0..3).map(|i| pos(vec![0.1 * i as f64; 6], 0.5)).collect();
    let e = calibrate(&model, &few, &opts).unwrap_err();
    assert!(
        e.to_string()
            .contains("9 equations from 3 poses for 24 free parameters"),
        "{e}"
    );
    let bad = CalibrationOptions {
        position_sigma: 0.0,
        ..opts
    };
    assert!(calibrate(&model, &few, &bad).is_err());
    // A robot that is not a serial DH chain.
    assert!(ParameterModel::new(&built_in("humanoid").unwrap()).is_err());
}

#[test]
fn the_calibrated_model_is_a_robot_that_reloads_from_its_model_file() {
    let puma = built_in("puma560").unwrap();
    let model = ParameterModel::new(&puma).unwrap();
    let sim = simulate(&model, &SimulationOptions::default()).unwrap();
    let robot = model.robot_with(&sim.truth).unwrap();
    let text = armlab::model_file::to_toml(&robot).unwrap();
    let back =
        armlab::model_file::parse_model(&text, std::path::Path::new("calibrated.toml")).unwrap();
    for m in &sim.validation {
        let (_, t) = model.frames(&sim.truth, m.q()).unwrap();
        for r in [&robot, &back] {
            let f = r.fk(m.q()).unwrap();
            assert!((f.to_homogeneous() - t.to_homogeneous()).amax() < 1e-12);
        }
    }
}

#[test]
fn position_only_data_at_the_wrist_centre_cannot_see_the_wrist_rotations() {
    // Independently of the code: the Puma's flange origin is its wrist centre (a4 = a5 = a6 = 0,
    // d5 = d6 = 0), and the axes z3, x4, z4, x5, z5, x6 all pass through it, so theta4, alpha4,
    // theta5, alpha5, theta6 and alpha6 rotate the measured point about itself: six parameters
    // that position-only data never see. The wrist centre is w = o2 + d3 z2 + (a3 x3 + d4 z3):
    // d2 and d3 lump (parallel axes 2, 3); the in-plane vector (a3, d4) at angle theta3 has two
    // degrees of freedom for three parameters (one combination of a3, d4, theta3 is invisible);
    // a small change of alpha3 tilts d4 z3 out of the plane by d4 * dalpha3 along z2, exactly
    // like d3, so only alpha3 + d3 / d4 shows. Rank 24 - 6 - 1 - 1 - 1 = 15.
    let puma = built_in("puma560").unwrap();
    let model = ParameterModel::new(&puma).unwrap();
    let sim = simulate(
        &model,
        &SimulationOptions {
            position_only: true,
            poses: 40,
            noise_mm: 0.0,
            ..SimulationOptions::default()
        },
    )
    .unwrap();
    let ident = identifiability(
        &model,
        &model.nominal(),
        &sim.measurements,
        &CalibrationOptions::default(),
    )
    .unwrap();
    assert_eq!(ident.rank, 15, "{:?}", ident.combinations);
    let c = &ident.combinations;
    let d4 = 0.4318;
    assert!(
        c.iter()
            .any(|s| s == &format!("alpha3 and d3 only as alpha3 {:+.6} * d3", 1.0 / d4)),
        "{c:?}"
    );
    assert!(
        c.iter()
            .any(|s| s.starts_with("a3, d4, theta3 only in one combination")),
        "{c:?}"
    );
    assert!(
        c.iter().any(|s| s.starts_with("d2 and d3 only as d2 + d3")),
        "{c:?}"
    );
    for name in ["theta4", "alpha4", "theta5", "alpha5", "theta6", "alpha6"] {
        assert!(
            ident.combinations.iter().any(|c| c
                == &format!("{name} cannot be identified: it does not change the measurements")),
            "{name}: {:?}",
            ident.combinations
        );
    }
}

#[test]
fn hayati_beta_removes_the_parallel_axis_trap() {
    let puma = built_in("puma560").unwrap();
    let plain = ParameterModel::new(&puma).unwrap();
    assert_eq!(plain.parallel_rows(), vec![2]);
    let hayati = ParameterModel::new(&puma).unwrap().with_hayati().unwrap();
    assert_eq!(hayati.hayati_rows(), vec![2]);
    let names: Vec<&str> = hayati
        .parameters()
        .iter()
        .map(|p| p.name.as_str())
        .collect();
    assert_eq!(names.last(), Some(&"beta2"));
    // Phi of beta against finite differences, away from beta = 0.
    let mut zeta = hayati.nominal();
    *zeta.last_mut().unwrap() = 0.05;
    let q = [0.3, -0.7, 0.5, 1.1, -0.4, 0.9];
    let phi = hayati.calibration_matrix(&zeta, &q, false).unwrap();
    let k = zeta.len() - 1;
    let h = 1e-6;
    let (mut zp, mut zm) = (zeta.clone(), zeta.clone());
    zp[k] += h;
    zm[k] -= h;
    let d = pose_difference(&hayati, &zp, &zm, &q);
    for i in 0..6 {
        assert!((phi[(i, k)] - d[i] / (2.0 * h)).abs() < 1e-7, "row {i}");
    }
    // The robot with beta is a robot (Ry(beta) in the next joint's `pre`) that a model file
    // keeps.
    let robot = hayati.robot_with(&zeta).unwrap();
    let text = armlab::model_file::to_toml(&robot).unwrap();
    assert!(text.contains("pre = "), "{text}");
    let back = armlab::model_file::parse_model(&text, std::path::Path::new("h.toml")).unwrap();
    let (_, t) = hayati.frames(&zeta, &q).unwrap();
    for r in [&robot, &back] {
        assert!((r.fk(&q).unwrap().to_homogeneous() - t.to_homogeneous()).amax() < 1e-12);
    }
    // The lesson: a real arm whose axes 2 and 3 are off parallel by a fraction of a degree,
    // measured with noise. Plain DH puts d2 and d3 far off; with beta every length stays near
    // its nominal value, and both fit the held-out poses at the noise level.
    let sim = simulate(
        &plain,
        &SimulationOptions {
            poses: 60,
            noise_mm: 0.02,
            noise_mrad: 0.05,
            ..Default::default()
        },
    )
    .unwrap();
    let opts = CalibrationOptions {
        position_sigma: 0.02e-3,
        orientation_sigma: 0.05e-3,
        ..CalibrationOptions::default()
    };
    let far = |m: &ParameterModel, z: &[f64]| {
        m.parameters()
            .iter()
            .zip(z)
            .filter(|(p, _)| !p.kind.is_angle())
            .map(|(p, v)| (v - p.nominal).abs())
            .fold(0.0, f64::max)
    };
    // The lesson: plain DH with minimum-norm steps (by default d2 would be kept nominal).
    let lesson = CalibrationOptions {
        unidentifiable: Unidentifiable::MinimumNorm,
        ..opts
    };
    let a = calibrate(&plain, &sim.measurements, &lesson).unwrap();
    let b = calibrate(&hayati, &sim.measurements, &opts).unwrap();
    assert_eq!(
        b.nominal.rank, b.nominal.parameter_count,
        "beta makes every parameter identifiable"
    );
    assert!(
        far(&plain, &a.estimate) > 0.05,
        "plain DH: {} m",
        far(&plain, &a.estimate)
    );
    assert!(
        far(&hayati, &b.estimate) < 0.005,
        "Hayati: {} m",
        far(&hayati, &b.estimate)
    );
    let floor = 3f64.sqrt() * 0.02e-3;
    for (m, r) in [(&plain, &a), (&hayati, &b)] {
        let v = fit(m, &r.estimate, &sim.validation).unwrap();
        assert!(v.position_rms < 1.3 * floor, "{:e}", v.position_rms);
    }
}

#[test]
fn converged_is_not_accurate_with_poses_that_are_all_alike() {
    // The lesson of Sect. 2.11 ("a sufficient number of poses" is not enough: they must differ):
    // 40 poses within 0.02 rad of one configuration fit their own data to the noise, but the
    // model is wrong elsewhere, and O1 says so.
    let puma = built_in("puma560").unwrap();
    let model = ParameterModel::new(&puma).unwrap();
    let sim = simulate(
        &model,
        &SimulationOptions {
            poses: 40,
            noise_mm: 0.01,
            noise_mrad: 0.02,
            seed: 3,
            ..Default::default()
        },
    )
    .unwrap();
    let base = [0.3, 0.5, -0.8, 0.4, 0.9, -0.2];
    let alike: Vec<Measurement> = (0..40)
        .map(|k| {
            let q: Vec<f64> = base
                .iter()
                .enumerate()
                .map(|(j, v)| v + 0.02 * (((k * 7 + j * 3) % 11) as f64 / 10.0 - 0.5))
                .collect();
            let (_, t) = model.frames(&sim.truth, &q).unwrap();
            // Measured with noise of the stated size (deterministic, +- 1.7 sigma).
            let n = |i: usize| ((k * 13 + i * 5) % 17) as f64 / 8.0 - 1.0;
            let dp = nalgebra::Vector3::new(n(0), n(1), n(2)) * 1.7 * 0.01e-3;
            let dr =
                nalgebra::Rotation3::new(nalgebra::Vector3::new(n(3), n(4), n(5)) * 1.7 * 0.02e-3);
            let measured = armlab::kinematics::Pose::from_parts(
                nalgebra::Translation3::from(t.translation.vector + dp),
                dr * t.rotation,
            );
            Measurement::Pose {
                q,
                world_from_tool: measured,
            }
        })
        .collect();
    let opts = CalibrationOptions {
        position_sigma: 0.01e-3,
        orientation_sigma: 0.02e-3,
        ..Default::default()
    };
    let narrow = calibrate(&model, &alike, &opts).unwrap();
    let broad = calibrate(&model, &sim.measurements, &opts).unwrap();
    assert!(narrow.converged);
    assert!(
        narrow.after.position_rms < 3e-5, // its own poses, to the noise level
        "{:?}",
        narrow.after
    );
    let on_random = fit(&model, &narrow.estimate, &sim.validation).unwrap();
    let good = fit(&model, &broad.estimate, &sim.validation).unwrap();
    assert!(
        on_random.position_rms > 20.0 * good.position_rms, // and far off elsewhere
        "{on_random:?} vs {good:?}"
    );
    assert!(narrow.nominal.observability.o1 < 0.1 * broad.nominal.observability.o1);
    // Not rank deficient, ill-conditioned: the condition number says what the residual hides.
    let cond = |r: &armlab::calibration::CalibrationReport| r.iterations.last().unwrap().condition;
    assert!(
        cond(&narrow) > 100.0 * cond(&broad),
        "{} vs {}",
        cond(&narrow),
        cond(&broad)
    );
}

#[test]
fn accuracy_maps_of_known_deviations() {
    use armlab::calibration::accuracy_map;
    let puma = built_in("puma560").unwrap();
    let model = ParameterModel::new(&puma).unwrap().with_base();
    let a = model.nominal();
    let idx = |n: &str| model.parameters().iter().position(|p| p.name == n).unwrap();
    // The same model: no deviation anywhere.
    let same = accuracy_map(&model, &a, &a, [32, 32], 20_000, 1).unwrap();
    assert_eq!(same.max, 0.0);
    assert!(
        same.values
            .iter()
            .filter(|v| v.is_finite())
            .all(|&v| v == 0.0)
    );
    // The base raised by 5 mm: every tool point moves by exactly 5 mm.
    let mut b = a.clone();
    b[idx("base_z")] = 5e-3;
    let up = accuracy_map(&model, &a, &b, [32, 32], 20_000, 1).unwrap();
    assert!((up.max - 5e-3).abs() < 1e-12 && (up.rms - 5e-3).abs() < 1e-12);
    assert!(
        up.values
            .iter()
            .filter(|v| v.is_finite())
            .all(|v| (v - 5e-3).abs() < 1e-12)
    );
    // The base turned about z by delta: a point at distance r from the axis moves by
    // 2 r sin(delta / 2), so each cell's value lies between that of its nearest and farthest
    // corner (cells straddling the axis from 0).
    let delta = 0.01;
    let mut c = a.clone();
    c[idx("base_rz")] = delta;
    let m = accuracy_map(&model, &a, &c, [40, 40], 200_000, 2).unwrap();
    let [x0, x1, y0, y1] = m.bounds;
    let (dx, dy) = ((x1 - x0) / 40.0, (y1 - y0) / 40.0);
    let mut checked = 0;
    for j in 0..40 {
        for i in 0..40 {
            let v = m.values[j * 40 + i];
            if !v.is_finite() {
                continue;
            }
            let xs = [x0 + i as f64 * dx, x0 + (i + 1) as f64 * dx];
            let ys = [y0 + j as f64 * dy, y0 + (j + 1) as f64 * dy];
            let far = xs
                .iter()
                .flat_map(|x| ys.iter().map(move |y| x.hypot(*y)))
                .fold(0.0, f64::max);
            let near = if xs[0] <= 0.0 && xs[1] >= 0.0 && ys[0] <= 0.0 && ys[1] >= 0.0 {
                0.0
            } else {
                let cx = 0f64.clamp(xs[0], xs[1]);
                let cy = 0f64.clamp(ys[0], ys[1]);
                cx.hypot(cy)
            };
            let k = 2.0 * (delta / 2.0).sin();
            assert!(
                v >= k * near - 1e-12 && v <= k * far + 1e-12,
                "cell {i},{j}: {v} not in [{}, {}]",
                k * near,
                k * far
            );
            checked += 1;
        }
    }
    assert!(checked > 300, "{checked} cells");
    assert!(accuracy_map(&model, &a, &a, [0, 4], 10, 1).is_err());
}
