//! Direct kinematics of the built-in models against the Robotics Toolbox reference data
//! (tests/data/reference/fk_*.json, 500 configurations each), to 1e-12 per element.

use crate::common;
use armlab::kinematics::models::built_in;
use common::{mat4, max_diff, reference, vec_f64};

fn check(file: &str, model: &str) {
    let data = reference(file);
    let robot = built_in(model).expect("built-in");
    let qs = data["q"].as_array().unwrap();
    let ts = data["T"].as_array().unwrap();
    assert_eq!(qs.len(), 500);
    let mut worst: f64 = 0.0;
    for (q, t) in qs.iter().zip(ts) {
        let q = vec_f64(q);
        let pose = robot.fk(&q).unwrap();
        worst = worst.max(max_diff(&pose, &mat4(t)));
        // All-frames path agrees with the single-chain path.
        let frames = robot.fk_frames(&q).unwrap();
        let ee = robot.end_effectors()[0].clone();
        assert!(max_diff(&(frames[ee.parent] * ee.tool), &pose.to_homogeneous()) < 1e-15);
    }
    assert!(worst <= 1e-12, "{model}: worst element error {worst:e}");
    if let Some(flange) = data.get("T_flange") {
        // T_flange = T * inv(tool): the last DH frame.
        for (q, t) in qs.iter().zip(flange.as_array().unwrap()).take(100) {
            let frames = robot.fk_frames(&vec_f64(q)).unwrap();
            assert!(max_diff(frames.last().unwrap(), &mat4(t)) <= 1e-12);
        }
    }
}

#[test]
fn planar2() {
    check("fk_planar2.json", "planar2");
}
#[test]
fn planar3() {
    check("fk_planar3.json", "planar3");
}
#[test]
fn anthropomorphic3r() {
    check("fk_anthropomorphic3r.json", "anthropomorphic3r");
}
#[test]
fn spherical_arm() {
    check("fk_spherical_arm.json", "spherical_arm");
}
#[test]
fn puma560() {
    check("fk_puma560.json", "puma560");
}
#[test]
fn anthropomorphic_spherical_wrist() {
    check(
        "fk_anthropomorphic_spherical_wrist.json",
        "anthropomorphic_spherical_wrist",
    );
}
#[test]
fn panda_modified_dh_with_tool() {
    check("fk_panda.json", "panda");
}
#[test]
fn lwr4_with_tool() {
    check("fk_lwr4.json", "lwr4");
}

/// The reference models' tables, limits and tools match the built-ins row by row.
#[test]
fn tables_match_models_json() {
    let models = reference("models.json");
    for (key, m) in models["models"].as_object().unwrap() {
        let robot = built_in(key).unwrap_or_else(|| panic!("no built-in {key}"));
        let (_, rows) = robot.dh_table().expect("serial DH");
        let dh = m["dh"].as_array().unwrap();
        assert_eq!(rows.len(), dh.len(), "{key}");
        for (i, (r, ref_row)) in rows.iter().zip(dh).enumerate() {
            let f = |k: &str| ref_row[k].as_f64().unwrap();
            assert!((r.1.a - f("a")).abs() < 1e-12, "{key} row {i} a");
            assert!(
                (r.1.alpha - f("alpha")).abs() < 1e-12,
                "{key} row {i} alpha"
            );
            let lim = vec_f64(&ref_row["qlim"]);
            let ours = robot.limits()[i];
            assert!(
                (ours[0] - lim[0]).abs() < 1e-9 && (ours[1] - lim[1]).abs() < 1e-9,
                "{key} row {i} limits"
            );
        }
    }
}

/// The position-only path used by workspace sampling equals the full FK, every model and tool.
#[test]
fn position_only_fk_matches_full_fk() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
    for b in armlab::kinematics::models::BUILT_INS {
        let r = (b.build)();
        for _ in 0..100 {
            let q: Vec<f64> = r
                .limits()
                .iter()
                .map(|l| rng.random_range(l[0]..=l[1]))
                .collect();
            for ee in 0..r.end_effectors().len() {
                let p = r.fk_ee_position(&q, ee).unwrap();
                let t = r.fk_ee(&q, ee).unwrap().translation.vector;
                let d = (t - nalgebra::Vector3::from(p)).amax();
                assert!(d < 1e-14, "{} ee {ee}: {d:e}", b.name);
            }
        }
        assert!(r.fk_ee_position(&vec![f64::NAN; r.dof()], 0).is_err());
    }
}
