//! Every example that the README, the guide or the crate docs name exists and runs: `cargo test`
//! builds the examples, and this test runs each one (exit status 0, something printed). A deleted
//! or broken example fails here.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Example names written as `--example NAME` or `examples/NAME.rs` in `text`.
fn named_in(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for (marker, end) in [("--example ", None), ("examples/", Some(".rs"))] {
        for (i, _) in text.match_indices(marker) {
            let rest = &text[i + marker.len()..];
            let name: String = rest
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            let after = &rest[name.len()..];
            if !name.is_empty() && name != "NAME" && end.is_none_or(|e| after.starts_with(e)) {
                out.push(name);
            }
        }
    }
    out
}

/// The documents that name examples: README.md, the guide's chapters, src/lib.rs.
fn documents() -> Vec<PathBuf> {
    let mut docs = vec![root().join("README.md"), root().join("src/lib.rs")];
    if let Ok(dir) = std::fs::read_dir(root().join("docs/src")) {
        let mut chapters: Vec<PathBuf> = dir
            .filter_map(Result::ok)
            .map(|e| e.path())
            .filter(|p| p.extension().is_some_and(|e| e == "md"))
            .collect();
        chapters.sort();
        docs.extend(chapters);
    }
    docs
}

/// Every example file in examples/.
fn example_files() -> BTreeSet<String> {
    std::fs::read_dir(root().join("examples"))
        .expect("examples/ exists")
        .filter_map(Result::ok)
        .filter_map(|e| {
            let p = e.path();
            if p.extension()? != "rs" {
                return None;
            }
            Some(p.file_stem()?.to_string_lossy().into_owned())
        })
        .collect()
}

/// The built example binary (cargo test builds examples next to the test's own deps folder).
fn binary(name: &str) -> PathBuf {
    let exe = std::env::current_exe().expect("test executable");
    let profile_dir = exe
        .parent()
        .and_then(Path::parent)
        .expect("target/<profile>/deps/..");
    profile_dir
        .join("examples")
        .join(format!("{name}{}", std::env::consts::EXE_SUFFIX))
}

#[test]
fn the_scanner_finds_example_names() {
    let text = "run `cargo run --release --example calibration` or see examples/self_motion.rs; \
                `--example NAME` is a placeholder, examples/ a folder";
    assert_eq!(named_in(text), ["calibration", "self_motion"]);
}

#[test]
fn every_named_example_exists() {
    let files = example_files();
    let mut named = BTreeSet::new();
    for doc in documents() {
        let text = std::fs::read_to_string(&doc).unwrap_or_default();
        for name in named_in(&text) {
            assert!(
                files.contains(&name),
                "{} names the example {name:?}, but there is no examples/{name}.rs",
                doc.display()
            );
            named.insert(name);
        }
    }
    assert!(
        !named.is_empty(),
        "the README, the guide or the crate docs name at least one example"
    );
}

#[test]
fn every_example_runs() {
    let mut failures = Vec::new();
    for name in example_files() {
        let bin = binary(&name);
        assert!(
            bin.exists(),
            "{} was not built (cargo test builds the examples; run this test through cargo test)",
            bin.display()
        );
        let start = Instant::now();
        let out = Command::new(&bin)
            .current_dir(root())
            .output()
            .unwrap_or_else(|e| panic!("{}: {e}", bin.display()));
        let took = start.elapsed();
        let stdout = String::from_utf8_lossy(&out.stdout);
        if !out.status.success() || stdout.trim().is_empty() {
            failures.push(format!(
                "example {name} ({}): stdout:\n{stdout}\nstderr:\n{}",
                out.status,
                String::from_utf8_lossy(&out.stderr)
            ));
        }
        assert!(
            took < Duration::from_secs(120),
            "example {name} took {took:?} (a debug build; keep examples quick)"
        );
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}
