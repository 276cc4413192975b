//! Replays every input kept from fuzzing (`tests/data/fuzz/<target>/`: crashes found and fixed,
//! and seeds) through the same checks the cargo-fuzz targets run (`fuzz/src/checks.rs`), so the
//! stable suite keeps them fixed. How to fuzz: the guide, docs/src/architecture.md, "Fuzzing".

#[path = "../../fuzz/src/checks.rs"]
mod checks;

use std::path::Path;

fn replay(target: &str, check: fn(&[u8])) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/fuzz")
        .join(target);
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.unwrap().path();
        let data = std::fs::read(&path).unwrap();
        let outcome = std::panic::catch_unwind(|| check(&data));
        assert!(outcome.is_ok(), "{} fails its check", path.display());
        n += 1;
    }
    assert!(n > 0, "no inputs kept in {}", dir.display());
}

#[test]
fn model_toml_inputs() {
    replay("model_toml", checks::model_toml);
}

#[test]
fn urdf_inputs() {
    replay("urdf", checks::urdf);
}

#[test]
fn rows_inputs() {
    replay("rows", checks::rows);
}

#[test]
fn measurements_inputs() {
    replay("measurements", checks::measurements);
}

#[test]
fn angle_inputs() {
    replay("angle", checks::angle);
}

#[test]
fn mesh_inputs() {
    replay("mesh", checks::mesh);
}

#[test]
fn lesson_inputs() {
    replay("lesson", checks::lesson);
}

#[test]
fn exercise_inputs() {
    replay("exercise", checks::exercise);
}

#[test]
fn calibration_files_inputs() {
    replay("calibration_files", checks::calibration_files);
}

#[test]
fn class_message_inputs() {
    replay("class_message", checks::class_message);
}
