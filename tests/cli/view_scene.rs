//! Issue 48: `armlab view MODEL --scene FILE` opens the app with the scene file's obstacles as
//! its cell: a bad scene file is one line naming the file, the line and the obstacle (no window,
//! no picture); a good one is drawn (the window rendered offscreen differs where the obstacle
//! stands).

use std::process::Command;

fn armlab(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args(args)
        .env("WGPU_BACKEND", "vulkan")
        .output()
        .expect("run armlab")
}

#[test]
fn view_opens_a_scene_and_refuses_a_bad_one() {
    let dir = std::env::temp_dir().join(format!("armlab-view-scene-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.toml");
    std::fs::write(
        &bad,
        "[[obstacle]]\nname = \"table\"\nshape = \"box\"\nsize = [1, 1, 0.05]\n\n\
         [[obstacle]]\nname = \"post\"\nshape = \"box\"\nsize = [0.1, nan, 1]\n",
    )
    .unwrap();
    let shot = |name: &str| dir.join(name).to_string_lossy().into_owned();
    let o = armlab(&[
        "view",
        "puma560",
        "--scene",
        &bad.to_string_lossy(),
        "--screenshot",
        &shot("bad.png"),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(
        err.contains("bad.toml:6") && err.contains("\"post\""),
        "the error names the file, the line and the obstacle: {err}"
    );
    assert!(!dir.join("bad.png").exists());

    // A box a metre wide in front of the arm, at its shoulder: drawn.
    let good = dir.join("cell.toml");
    std::fs::write(
        &good,
        "[[obstacle]]\nname = \"crate\"\nshape = \"box\"\nsize = [0.4, 1.0, 0.6]\nxyz = [0.9, 0.0, 0.3]\n",
    )
    .unwrap();
    for (args, name) in [
        (vec!["--scene", good.to_str().unwrap()], "with.png"),
        (vec![], "without.png"),
    ] {
        let out = shot(name);
        let mut all = vec!["view", "puma560", "--screenshot", out.as_str()];
        all.extend(args);
        let o = armlab(&all);
        assert!(
            o.status.success(),
            "{all:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    let with = image::open(dir.join("with.png")).unwrap().to_rgba8();
    let without = image::open(dir.join("without.png")).unwrap().to_rgba8();
    assert_eq!(with.dimensions(), without.dimensions());
    let differ = with
        .pixels()
        .zip(without.pixels())
        .filter(|(a, b)| a.0.iter().zip(b.0).any(|(x, y)| x.abs_diff(y) > 24))
        .count();
    let share = differ as f64 / (with.width() * with.height()) as f64;
    assert!(share > 0.01, "the crate changed {share:.4} of the window");
    std::fs::remove_dir_all(&dir).ok();
}
