//! TOML model files: every asset loads, the reference models reproduce the reference forward
//! kinematics, `humanoid.toml` reproduces the built-in humanoid, `to_toml` round-trips every
//! serial built-in, and every malformed file in `tests/data/bad_models` gives the promised error.

use armlab::kinematics::Robot;
use armlab::kinematics::models::{BUILT_INS, built_in};
use armlab::model_file::{LoadError, ModelFileError, load_model, load_model_file, to_toml};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::{Path, PathBuf};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn files_in(dir: &Path, ext: &str) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("directory entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == ext))
        .collect();
    v.sort();
    v
}

fn random_q(robot: &Robot, rng: &mut ChaCha8Rng) -> Vec<f64> {
    robot
        .limits()
        .iter()
        .map(|&[lo, hi]| {
            if lo < hi {
                rng.random_range(lo..=hi)
            } else {
                lo
            }
        })
        .collect()
}

fn assert_same_fk(a: &Robot, b: &Robot, rng: &mut ChaCha8Rng, tol: f64, what: &str) {
    assert_eq!(a.dof(), b.dof(), "{what}: dof");
    assert_eq!(a.end_effectors().len(), b.end_effectors().len(), "{what}");
    for _ in 0..25 {
        let q = random_q(a, rng);
        for ee in 0..a.end_effectors().len() {
            let ta = a.fk_ee(&q, ee).expect("fk").to_homogeneous();
            let tb = b.fk_ee(&q, ee).expect("fk").to_homogeneous();
            let err = (ta - tb).amax();
            assert!(
                err <= tol,
                "{what}: end-effector {ee} differs by {err:e} at q = {q:?}"
            );
        }
    }
}

#[test]
fn every_asset_loads() {
    let dir = root().join("assets/robots");
    let mut n = 0;
    for ext in ["toml", "urdf"] {
        for path in files_in(&dir, ext) {
            let spec = path.to_str().expect("UTF-8 path");
            let robot = load_model(spec).unwrap_or_else(|e| panic!("{e}"));
            assert!(robot.dof() > 0, "{spec}");
            for c in &robot.configurations {
                assert_eq!(c.q.len(), robot.dof(), "{spec}: configuration {}", c.name);
                robot.fk(&c.q).expect("fk of a named configuration");
            }
            n += 1;
        }
    }
    assert!(n >= 11, "only {n} model files found");
}

const REFERENCE_MODELS: [&str; 8] = [
    "planar2",
    "planar3",
    "anthropomorphic3r",
    "spherical_arm",
    "puma560",
    "anthropomorphic_spherical_wrist",
    "panda",
    "lwr4",
];

#[derive(serde::Deserialize)]
struct FkData {
    q: Vec<Vec<f64>>,
    #[serde(rename = "T")]
    t: Vec<[[f64; 4]; 4]>,
}

#[test]
fn reference_models_match_reference_fk() {
    for model in REFERENCE_MODELS {
        let path = root().join(format!("assets/robots/{model}.toml"));
        let robot = load_model_file(&path).unwrap_or_else(|e| panic!("{e}"));
        let json = root().join(format!("tests/data/reference/fk_{model}.json"));
        let text = std::fs::read_to_string(&json).expect("reference file");
        let data: FkData = serde_json::from_str(&text).expect("reference JSON");
        assert!(data.q.len() >= 50 && data.t.len() >= 50, "{model}");
        for (q, t) in data.q.iter().zip(&data.t).take(50) {
            let m = robot.fk(q).expect("fk").to_homogeneous();
            for (r, row) in t.iter().enumerate() {
                for (c, &want) in row.iter().enumerate() {
                    let got = m[(r, c)];
                    assert!(
                        (got - want).abs() <= 1e-12,
                        "{model}: T[{r}][{c}] = {got} but the reference has {want} at q = {q:?}"
                    );
                }
            }
        }
        // The file also equals the built-in model of the same name.
        let built = built_in(model).expect("built-in");
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        assert_same_fk(&built, &robot, &mut rng, 1e-12, model);
        assert_eq!(built.name, robot.name, "{model}");
    }
}

#[test]
fn humanoid_file_equals_built_in() {
    let path = root().join("assets/robots/humanoid.toml");
    let file = load_model_file(&path).unwrap_or_else(|e| panic!("{e}"));
    let built = built_in("humanoid").expect("built-in humanoid");
    assert_eq!(file.dof(), 17);
    let names = |r: &Robot| -> Vec<String> { r.joints().iter().map(|j| j.name.clone()).collect() };
    assert_eq!(names(&file), names(&built));
    let ees =
        |r: &Robot| -> Vec<String> { r.end_effectors().iter().map(|e| e.name.clone()).collect() };
    assert_eq!(ees(&file), ees(&built));
    for (a, b) in file.joints().iter().zip(built.joints()) {
        assert_eq!(a.drive, b.drive, "{}", a.name);
        assert_eq!(a.parent, b.parent, "{}", a.name);
        for k in 0..2 {
            assert!((a.limits[k] - b.limits[k]).abs() < 1e-15, "{}", a.name);
        }
    }
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    assert_same_fk(&built, &file, &mut rng, 1e-12, "humanoid");
    for name in ["ready", "figure"] {
        let (a, b) = (
            file.config(name).expect(name),
            built.config(name).expect(name),
        );
        assert!(
            a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-15),
            "{name}"
        );
    }
}

#[test]
fn to_toml_round_trips_every_serial_built_in() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let mut written = 0;
    for b in BUILT_INS {
        let robot = (b.build)();
        let Some(text) = to_toml(&robot) else {
            assert!(
                matches!(b.name, "parallelogram" | "slider_chain" | "humanoid"),
                "{} is serial DH but to_toml gave None",
                b.name
            );
            continue;
        };
        let back = armlab::model_file::parse_model(&text, Path::new("round-trip.toml"))
            .unwrap_or_else(|e| panic!("{}: {e}\n{text}", b.name));
        assert_same_fk(&robot, &back, &mut rng, 1e-12, b.name);
        assert_eq!(back.name, robot.name);
        assert_eq!(back.description, robot.description);
        assert_eq!(back.limits(), robot.limits(), "{}", b.name);
        assert_eq!(back.configurations, robot.configurations, "{}", b.name);
        for (x, y) in back.joints().iter().zip(robot.joints()) {
            assert_eq!((&x.name, x.kind, x.offset), (&y.name, y.kind, y.offset));
        }
        written += 1;
    }
    assert_eq!(written, BUILT_INS.len() - 3);
}

#[test]
fn load_model_resolves_names_and_paths() {
    assert_eq!(load_model("puma560").expect("built-in").dof(), 6);
    let err = load_model("puma561").expect_err("unknown name");
    let msg = err.to_string();
    assert!(matches!(err, LoadError::Unknown { .. }), "{msg}");
    for b in BUILT_INS {
        assert!(msg.contains(b.name), "{msg}");
    }
    let missing = root().join("assets/robots/no_such_robot.toml");
    let err = load_model(missing.to_str().expect("UTF-8")).expect_err("missing file");
    let msg = err.to_string();
    assert!(
        matches!(err, LoadError::ModelFile(ModelFileError::Read { .. })),
        "{msg}"
    );
    assert!(msg.contains("no_such_robot.toml"), "{msg}");
    let urdf = root().join("assets/robots/planar2.urdf");
    assert_eq!(
        load_model(urdf.to_str().expect("UTF-8"))
            .expect("urdf")
            .dof(),
        2
    );
}

/// `# expect: <substring>` and `# line: N` from the first two lines of a bad model.
fn expectations(text: &str, path: &Path) -> (String, usize) {
    let mut lines = text.lines();
    let expect = lines
        .next()
        .and_then(|l| l.strip_prefix("# expect: "))
        .unwrap_or_else(|| panic!("{}: first line must be `# expect: ...`", path.display()));
    let line = lines
        .next()
        .and_then(|l| l.strip_prefix("# line: "))
        .and_then(|n| n.trim().parse().ok())
        .unwrap_or_else(|| panic!("{}: second line must be `# line: N`", path.display()));
    (expect.to_string(), line)
}

#[test]
fn every_bad_model_gives_its_error() {
    let files = files_in(&root().join("tests/data/bad_models"), "toml");
    assert!(files.len() >= 20, "only {} bad models", files.len());
    for path in files {
        let text = std::fs::read_to_string(&path).expect("bad model");
        let (expect, line) = expectations(&text, &path);
        let result = std::panic::catch_unwind(|| load_model_file(&path));
        let Ok(result) = result else {
            panic!("{}: the loader panicked", path.display());
        };
        let err = match result {
            Ok(_) => panic!("{}: loaded without error", path.display()),
            Err(e) => e,
        };
        let msg = err.to_string();
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .expect("file name");
        assert!(msg.contains(&expect), "{name}: `{msg}` lacks `{expect}`");
        assert!(msg.contains(name), "{name}: `{msg}` does not name the file");
        let at = err
            .location()
            .unwrap_or_else(|| panic!("{name}: no location"));
        assert_eq!(at.line, line, "{name}: `{msg}` points to the wrong line");
        assert!(
            msg.contains(&format!(":{}:{})", at.line, at.column)),
            "{name}: {msg}"
        );
        assert!(at.column >= 1, "{name}");
        // The column points inside the reported line.
        let reported = text.lines().nth(line - 1).expect("line exists");
        assert!(at.column <= reported.chars().count() + 1, "{name}: {msg}");
    }
}

#[test]
fn unreadable_file_is_reported() {
    let path = root().join("tests/data/bad_models");
    let err = load_model_file(&path).expect_err("a directory is not a model file");
    assert!(matches!(err, ModelFileError::Read { .. }));
    assert!(err.to_string().contains("bad_models"), "{err}");
}

#[test]
fn joints_without_limits_load_write_and_reload() {
    let text = r#"
name = "free arm"
convention = "standard"
[[joints]]
type = "revolute"
a = 1.0
alpha = 0.0
d = 0.0
limits = "none"
[[joints]]
type = "prismatic"
a = 0.0
alpha = 0.0
theta = 0.0
limits = "none"
"#;
    let robot = armlab::model_file::parse_model(text, std::path::Path::new("free.toml")).unwrap();
    assert_eq!(robot.limits(), vec![armlab::kinematics::UNBOUNDED; 2]);
    // The sampling ranges are finite: one turn, and the arm's scale either side of 0.
    let [lo, hi] = robot.sampling_range(0);
    assert!((hi - lo - std::f64::consts::TAU).abs() < 1e-15);
    let [lo, hi] = robot.sampling_range(1);
    assert!(lo.is_finite() && hi.is_finite() && lo < 0.0 && hi > 0.0);
    let written = armlab::model_file::to_toml(&robot).unwrap();
    assert!(written.contains("limits = \"none\""), "{written}");
    let back =
        armlab::model_file::parse_model(&written, std::path::Path::new("back.toml")).unwrap();
    assert_eq!(back.limits(), robot.limits());
}
