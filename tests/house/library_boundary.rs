//! The library without default features is graphics-free: no graphics crate in its normal
//! dependency tree (`cargo tree --no-default-features -e normal`), and the app's modules are
//! behind the `app` feature. Runs in both feature configurations.

use std::process::Command;

/// Crates of the graphics, windowing and figure side, and the CLI's, that the library must not
/// pull in without the `app` feature.
const FORBIDDEN: &[&str] = &[
    "wgpu",
    "wgpu-core",
    "wgpu-hal",
    "naga",
    "egui",
    "egui-wgpu",
    "egui_plot",
    "eframe",
    "winit",
    "epaint",
    "image",
    "png",
    "indicatif",
    "clap",
    "anyhow",
    "pollster",
    "ash",
    "glow",
    "x11rb",
    "wayland-client",
];

/// The crates the library may depend on directly without default features.
const ALLOWED_DIRECT: &[&str] = &[
    "nalgebra",
    "serde",
    "toml",
    "urdf-rs",
    "mesh-loader",
    "thiserror",
    "rayon",
    // robot_cal_tools' calibration files (pure Rust, no graphics).
    "yaml-rust2",
    // The line and column of a URDF that is not well-formed XML (already under mesh-loader).
    "roxmltree",
    // The exercise sheets students open and the keys (JSON; pure Rust, no graphics).
    "serde_json",
    // Collision geometry and queries (dimforge's parry, f64; its math is glam, no graphics).
    "parry3d-f64",
];

fn cargo_tree(args: &[&str]) -> String {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(cargo)
        .args([
            "tree",
            "--manifest-path",
            concat!(env!("CARGO_MANIFEST_DIR"), "/Cargo.toml"),
        ])
        .args([
            "--no-default-features",
            "-e",
            "normal",
            "--prefix",
            "none",
            "--format",
            "{p}",
        ])
        .args(args)
        .output()
        .expect("cargo tree runs (cargo is on PATH when tests run under cargo)");
    assert!(
        out.status.success(),
        "cargo tree failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("utf-8")
}

fn names(tree: &str) -> Vec<String> {
    tree.lines()
        .filter_map(|l| l.split_whitespace().next())
        .map(str::to_string)
        .collect()
}

#[test]
fn no_graphics_crate_without_default_features() {
    let all = names(&cargo_tree(&[]));
    assert!(
        all.iter().any(|n| n == "nalgebra"),
        "unexpected tree: {all:?}"
    );
    let bad: Vec<&String> = all
        .iter()
        .filter(|n| FORBIDDEN.contains(&n.as_str()))
        .collect();
    assert!(
        bad.is_empty(),
        "graphics or CLI crates without default features: {bad:?}"
    );
    let direct = names(&cargo_tree(&["--depth", "1"]));
    for d in direct.iter().filter(|n| n.as_str() != "armlab") {
        assert!(
            ALLOWED_DIRECT.contains(&d.as_str()),
            "unexpected direct dependency of the library: {d}"
        );
    }
}
