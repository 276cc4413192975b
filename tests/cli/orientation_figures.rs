//! The orientation lab's pictures from the command line: `armlab animate --what rotation` (a
//! composition step by step, to GIF or APNG) and `armlab rotation --figure` (a frame and its
//! representations for a slide, PNG or SVG). The animation's frames are checked against
//! rotations multiplied out here from hand-written elementary matrices.

use armlab::animation::rotation::rotation_shots;
use armlab::kinematics::orientation::{Axis, Step, StepFrame};
use nalgebra::Matrix3;
use std::process::{Command, Output};

fn armlab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args(args)
        .output()
        .expect("run armlab")
}

fn rz(d: f64) -> Matrix3<f64> {
    let (s, c) = d.to_radians().sin_cos();
    Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}
fn ry(d: f64) -> Matrix3<f64> {
    let (s, c) = d.to_radians().sin_cos();
    Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c)
}
fn rx(d: f64) -> Matrix3<f64> {
    let (s, c) = d.to_radians().sin_cos();
    Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c)
}

/// The shots of current Rz(30) Ry(45), fixed Rx(10): the first frame is the reference, the
/// frame at the end of each step is the hand-multiplied product (post-multiplied for current
/// axes, pre-multiplied for fixed ones), and halfway through step 2 the frame has turned 22.5°
/// about the current y axis (smoothstep easing: half the time, half the angle).
#[test]
fn the_rotation_animation_follows_the_composition() {
    let s = |frame, axis, d: f64| Step {
        frame,
        axis,
        angle: d.to_radians(),
    };
    let steps = [
        s(StepFrame::Current, Axis::Z, 30.0),
        s(StepFrame::Current, Axis::Y, 45.0),
        s(StepFrame::Fixed, Axis::X, 10.0),
    ];
    // 3 steps over 61 frames: frame 20 ends step 1, frame 30 is halfway through step 2
    let shots = rotation_shots(&steps, 61);
    let at = |f: usize| *shots[f].rotation.matrix();
    assert!((at(0) - Matrix3::identity()).amax() < 1e-12);
    assert!((at(20) - rz(30.0)).amax() < 1e-12);
    assert!((at(30) - rz(30.0) * ry(22.5)).amax() < 1e-12);
    assert!((at(40) - rz(30.0) * ry(45.0)).amax() < 1e-12);
    assert!((at(60) - rx(10.0) * rz(30.0) * ry(45.0)).amax() < 1e-12);
    assert_eq!(shots[30].done.len(), 1);
    assert!(
        shots[30].caption.contains("R = Rz(30°) Ry(22°)"),
        "{}",
        shots[30].caption
    );
    assert!(shots[60].caption.contains("R = Rx(10°) Rz(30°) Ry(45°)"));
}

/// The command writes a GIF with the frames asked for (fps x seconds), with no model; a model
/// or a bad sequence is refused with one line.
#[test]
fn animate_what_rotation_writes_the_gif() {
    let dir = std::env::temp_dir().join(format!("armlab-rot-anim-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let gif = dir.join("r.gif");
    let o = armlab(&[
        "animate",
        "--what",
        "rotation",
        "--compose",
        "current Rz(90) Rx(90)",
        "--fps",
        "5",
        "--seconds",
        "2",
        "--size",
        "320x240",
        "--out",
        gif.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains("10 frames") && out.contains("R = Rz(90°) Rx(90°)"),
        "{out}"
    );
    let bytes = std::fs::read(&gif).unwrap();
    assert_eq!(&bytes[..6], b"GIF89a");
    let mut decoder = gif::DecodeOptions::new()
        .read_info(std::io::Cursor::new(bytes))
        .unwrap();
    let mut frames = 0;
    while decoder.read_next_frame().unwrap().is_some() {
        frames += 1;
    }
    assert_eq!(frames, 10);
    for (args, needle) in [
        (
            vec!["animate", "puma560", "--what", "rotation"],
            "give no model",
        ),
        (
            vec![
                "animate",
                "--what",
                "rotation",
                "--compose",
                "sideways Rz(3)",
            ],
            "--compose",
        ),
        (vec!["animate", "--what", "postures"], "name a model"),
    ] {
        let mut a = args.clone();
        let bad = dir.join("bad.gif");
        a.extend(["--out", bad.to_str().unwrap()]);
        let o = armlab(&a);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{a:?}: {err}");
        assert!(err.contains(needle), "{a:?}: {err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--figure` writes a PNG of the asked size, and an SVG whose text carries the singular case in
/// words.
#[test]
fn rotation_figure_for_a_slide() {
    let dir = std::env::temp_dir().join(format!("armlab-rot-fig-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let png = dir.join("f.png");
    let o = armlab(&[
        "rotation",
        "--from",
        "zyz:30,0,45",
        "--figure",
        png.to_str().unwrap(),
        "--size",
        "640x480",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let img = image::open(&png).unwrap();
    assert_eq!((img.width(), img.height()), (640, 480));
    let svg = dir.join("f.svg");
    let o = armlab(&[
        "rotation",
        "--from",
        "zyz:30,0,45",
        "--figure",
        svg.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(
        text.contains("only phi + psi is determined: 75°"),
        "the words in the SVG"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
