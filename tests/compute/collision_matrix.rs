//! The allowed-collision matrix against checks written here: on the UR5 and Panda corpus files,
//! no pair the sampled matrix marks "Never" collides in configurations this test draws with its
//! own generator and seed (checked with every pair enabled), and pairs marked "Always" collide
//! in nearly all of them; and the matrix stored in a TOML model file reads back to the same
//! pairs, with errors naming the field, line and link.

use armlab::collision::{
    AllowedCollisions, CellScene, CollisionWorld, GeometryOptions, MatrixOptions, PairReason,
    RobotGeometry, sample_matrix,
};
use armlab::kinematics::models;
use armlab::model_file::{ModelFileError, parse_model, to_toml};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// A pair's key, names in order.
fn key(a: &str, b: &str) -> (String, String) {
    if a <= b {
        (a.into(), b.into())
    } else {
        (b.into(), a.into())
    }
}

#[test]
fn never_pairs_never_collide_in_configurations_drawn_here() {
    for file in ["ur5_robot.urdf", "panda.urdf"] {
        let robot = armlab::model_file::load_model(&format!("tests/data/urdf_corpus/{file}"))
            .expect("a corpus file");
        let geometry = RobotGeometry::of(&robot, GeometryOptions::default());
        let matrix = sample_matrix(&robot, &geometry, MatrixOptions::default()).unwrap();
        let reasons: BTreeMap<(String, String), PairReason> = matrix
            .pairs
            .iter()
            .map(|p| (key(&p.a, &p.b), p.reason))
            .collect();
        // Every pair checked: the matrix under test plays no part in what is found here.
        let world = CollisionWorld::with(
            &robot,
            geometry.clone(),
            &CellScene::default(),
            GeometryOptions::default(),
            AllowedCollisions::default(),
        )
        .unwrap();
        // Uniform within the limits (a joint without limits: one turn), another generator and
        // another seed than the matrix's.
        let ranges: Vec<[f64; 2]> = robot
            .limits()
            .into_iter()
            .map(|[lo, hi]| {
                if lo.is_finite() && hi.is_finite() {
                    [lo, hi]
                } else {
                    [-std::f64::consts::PI, std::f64::consts::PI]
                }
            })
            .collect();
        let mut rng = ChaCha8Rng::seed_from_u64(20_240_601);
        let draws = 2000;
        let mut hits: BTreeMap<(String, String), usize> = BTreeMap::new();
        for _ in 0..draws {
            let q: Vec<f64> = ranges
                .iter()
                .map(|[lo, hi]| rng.random_range(*lo..=*hi))
                .collect();
            let report = world.check(&robot, &q).unwrap();
            let mut seen = BTreeSet::new();
            for c in &report.pairs {
                let k = key(&c.a, &c.b);
                assert_ne!(
                    reasons.get(&k),
                    Some(&PairReason::Never),
                    "{file}: {} and {} collide at q = {q:?} ({} m deep) but the matrix says never",
                    c.a,
                    c.b,
                    c.depth_m
                );
                if seen.insert(k.clone()) {
                    *hits.entry(k).or_default() += 1;
                }
            }
        }
        let mut always = 0;
        for (k, r) in &reasons {
            if *r == PairReason::Always {
                always += 1;
                let n = hits.get(k).copied().unwrap_or(0);
                assert!(
                    n as f64 >= 0.9 * draws as f64,
                    "{file}: {k:?} is 'always' but collided in {n} of {draws}"
                );
            }
        }
        let never = reasons
            .values()
            .filter(|r| **r == PairReason::Never)
            .count();
        println!(
            "{file}: {never} never, {always} always, {} pairs",
            reasons.len()
        );
        assert!(
            never > 0,
            "{file}: no pair marked never: the test would prove nothing"
        );
    }
}

#[test]
fn a_matrix_stored_in_a_model_file_reads_back_to_the_same_pairs() {
    let mut robot = models::puma560();
    let geometry = RobotGeometry::of(&robot, GeometryOptions::default());
    let options = MatrixOptions {
        samples: 300,
        ..MatrixOptions::default()
    };
    let matrix = sample_matrix(&robot, &geometry, options).unwrap();
    robot.disabled_collisions = matrix
        .disabled()
        .map(|p| armlab::kinematics::DisabledPair {
            link1: p.a.clone(),
            link2: p.b.clone(),
            reason: p.reason.as_str().to_string(),
        })
        .collect();
    assert!(!robot.disabled_collisions.is_empty());
    let text = to_toml(&robot).expect("a serial DH robot");
    let back = parse_model(&text, Path::new("puma.toml")).unwrap();
    assert_eq!(back.disabled_collisions, robot.disabled_collisions);
    // The checker reads it: exactly the same pairs allowed, for every pair of links.
    let stored = AllowedCollisions::for_robot(&back, &geometry);
    let names: Vec<&str> = geometry.bodies.iter().map(|b| b.name.as_str()).collect();
    for (i, a) in names.iter().enumerate() {
        for b in &names[i + 1..] {
            assert_eq!(stored.is_allowed(a, b), matrix.is_allowed(a, b), "{a} {b}");
        }
    }
}

/// A two-joint model file followed by `tail`.
fn model(tail: &str) -> String {
    format!(
        "name = \"arm\"\nconvention = \"standard\"\n\n[[joints]]\ntype = \"revolute\"\na = 0.5\nalpha = 0\nd = 0\n\n[[joints]]\ntype = \"revolute\"\na = 0.4\nalpha = 0\nd = 0\n{tail}"
    )
}

#[test]
fn disable_collisions_errors_name_the_field_the_line_and_the_link() {
    let ok = parse_model(
        &model("\n[[disable_collisions]]\nlink1 = \"base\"\nlink2 = \"link2\"\n"),
        Path::new("arm.toml"),
    )
    .unwrap();
    assert_eq!(ok.disabled_collisions.len(), 1);
    assert_eq!(ok.disabled_collisions[0].reason, "User");
    // The table's header is on line 16, its `link2` on line 18.
    let cases: [(&str, &str, usize, &[&str]); 4] = [
        (
            "\n[[disable_collisions]]\nlink1 = \"link1\"\nlink2 = \"link9\"\nreason = \"Never\"\n",
            "disable_collisions[1].link2",
            18,
            &["link9", "base, link1, link2"],
        ),
        (
            "\n[[disable_collisions]]\nlink1 = \"link1\"\nlink2 = \"link1\"\n",
            "disable_collisions[1].link2",
            18,
            &["itself"],
        ),
        (
            "\n[[disable_collisions]]\nlink1 = \"link1\"\nlink_2 = \"link2\"\n",
            "disable_collisions[1].link_2",
            18,
            &["link_2"],
        ),
        (
            "\n[[disable_collisions]]\nlink1 = \"link1\"\nlink2 = 3\n",
            "disable_collisions[1].link2",
            18,
            &["string"],
        ),
    ];
    for (tail, field, line, needles) in cases {
        let err = parse_model(&model(tail), Path::new("arm.toml")).unwrap_err();
        assert_eq!(err.field(), Some(field), "{err}");
        assert_eq!(err.location().map(|l| l.line), Some(line), "{err}");
        let text = err.to_string();
        assert!(text.contains("arm.toml:"), "{text}");
        for n in needles {
            assert!(text.contains(n), "{n:?} not in {text}");
        }
    }
    let missing = parse_model(
        &model("\n[[disable_collisions]]\nlink2 = \"link1\"\n"),
        Path::new("arm.toml"),
    )
    .unwrap_err();
    assert!(
        matches!(missing, ModelFileError::Missing { .. }),
        "{missing}"
    );
    assert_eq!(missing.field(), Some("disable_collisions[1].link1"));
}
