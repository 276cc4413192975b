//! `armlab animate`: the motions are right (checked here against FK and matrices composed in
//! the test), and the files have the frames and timing asked for.

use armlab::animation::{Motion, plan};
use armlab::kinematics::Pose;
use armlab::kinematics::models::built_in;

fn build(name: &str) -> Result<armlab::kinematics::Robot, String> {
    built_in(name).ok_or_else(|| format!("no built-in {name}"))
}
use nalgebra::{Matrix4, Vector3};

fn mat(p: &Pose) -> Matrix4<f64> {
    p.to_homogeneous()
}

fn rot_z(t: f64) -> Matrix4<f64> {
    let (s, c) = t.sin_cos();
    Matrix4::new(
        c, -s, 0.0, 0.0, s, c, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
    )
}

fn rot_x(t: f64) -> Matrix4<f64> {
    let (s, c) = t.sin_cos();
    Matrix4::new(
        1.0, 0.0, 0.0, 0.0, 0.0, c, -s, 0.0, 0.0, s, c, 0.0, 0.0, 0.0, 0.0, 1.0,
    )
}

fn trans(x: f64, z: f64) -> Matrix4<f64> {
    Matrix4::new(
        1.0, 0.0, 0.0, x, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, z, 0.0, 0.0, 0.0, 1.0,
    )
}

/// The number after `key = ` in a caption.
fn value_after(caption: &str, key: &str) -> f64 {
    let start = caption
        .find(&format!("{key} = "))
        .unwrap_or_else(|| panic!("{key} in {caption}"))
        + key.len()
        + 3;
    caption[start..]
        .split([' ', ')'])
        .next()
        .unwrap()
        .parse()
        .unwrap()
}

#[test]
fn the_dh_build_composes_each_a_i_from_its_four_printed_motions() {
    for name in [
        "dlr",
        "puma560",
        "stanford",
        "anthropomorphic_spherical_wrist",
    ] {
        let robot = build(name).unwrap();
        let n = robot.dof();
        let anim = plan(&robot, Motion::DhFrames, 40 * n, 1.5 * n as f64).unwrap();
        let q = robot.config("ready").unwrap().to_vec();
        let world = robot.fk_frames(&q).unwrap();
        let mut seen = vec![false; n];
        for shot in &anim.shots {
            let Some(rest) = shot.caption.strip_prefix("A_") else {
                continue;
            };
            let i: usize = rest.split(' ').next().unwrap().parse().unwrap();
            if seen[i - 1] {
                continue;
            }
            seen[i - 1] = true;
            // (2.52): A_i = Rot(z, theta) Trans(z, d) Trans(x, a) Rot(x, alpha), from the
            // caption's numbers (0.1 deg, 1 mm).
            let c = &shot.caption;
            let theta = value_after(c, &format!(", theta{i}")).to_radians();
            let d = value_after(c, &format!(", d{i}"));
            let a = value_after(c, &format!(", a{i}"));
            let alpha = value_after(c, &format!(", alpha{i}")).to_radians();
            let a_i = rot_z(theta) * trans(0.0, d) * trans(a, 0.0) * rot_x(alpha);
            let prev = if i == 1 { robot.base } else { world[i - 2] };
            let expect = mat(&(prev.inverse() * world[i - 1]));
            let err = (a_i - expect).abs().max();
            assert!(
                err < 3e-3,
                "{name}: A_{i} from the caption is off by {err}:\n{c}"
            );
        }
        assert!(
            seen.iter().all(|s| *s),
            "{name}: every A_i is shown ({seen:?})"
        );
        // The frame carried by the last step ends on frame n, and the build ends with every
        // frame drawn.
        let last = anim.shots.last().unwrap();
        assert_eq!(last.frames.len(), n + 1, "{name}");
        let end = last.frames.last().unwrap().1;
        assert!((mat(&end) - mat(&world[n - 1])).abs().max() < 1e-12);
    }
}

#[test]
fn the_self_motion_holds_the_hand_and_sweeps_the_feasible_interval() {
    for name in ["dlr", "panda", "lwr4"] {
        let robot = build(name).unwrap();
        let q = robot.config("ready").unwrap().to_vec();
        let hand = robot.fk(&q).unwrap();
        let anim = plan(&robot, Motion::SelfMotion, 60, 2.0).unwrap();
        let mut spread = 0.0f64;
        for s in &anim.shots {
            let t = robot.fk(&s.q).unwrap();
            let e = (t.translation.vector - hand.translation.vector).norm()
                + (t.rotation.matrix() - hand.rotation.matrix()).abs().max();
            assert!(e < 1e-8, "{name}: the hand moved by {e} at {}", s.caption);
            spread = spread.max(
                (Vector3::from_iterator(s.q.iter().copied().take(3))
                    - Vector3::from_iterator(q.iter().copied().take(3)))
                .norm(),
            );
        }
        assert!(spread > 0.3, "{name}: the arm hardly moves ({spread} rad)");
        assert_eq!(anim.trace.len(), 60);
    }
}

#[test]
fn the_posture_morph_visits_every_closed_form_posture() {
    let robot = build("puma560").unwrap();
    let anim = plan(&robot, Motion::Postures, 80, 4.0).unwrap();
    let ghosts = &anim.shots[0].ghosts;
    assert_eq!(ghosts.len(), 8);
    let target = robot.fk(&ghosts[0]).unwrap();
    for g in ghosts {
        let t = robot.fk(g).unwrap();
        assert!((t.translation.vector - target.translation.vector).norm() < 1e-9);
        assert!(
            anim.shots.iter().any(|s| s.q == *g),
            "posture {g:?} is held in some frame"
        );
    }
}

#[test]
fn the_tool_path_is_straight_at_constant_speed_with_fixed_orientation() {
    let robot = build("puma560").unwrap();
    let anim = plan(&robot, Motion::Path, 50, 2.0).unwrap();
    let tools: Vec<Pose> = anim.shots.iter().map(|s| robot.fk(&s.q).unwrap()).collect();
    let (p0, p1) = (tools[0].translation.vector, tools[49].translation.vector);
    assert!((p1 - p0).norm() > 0.05);
    for (k, t) in tools.iter().enumerate() {
        let want = p0 + (p1 - p0) * (k as f64 / 49.0);
        assert!((t.translation.vector - want).norm() < 1e-6, "sample {k}");
        assert!(
            (t.rotation.matrix() - tools[0].rotation.matrix())
                .abs()
                .max()
                < 1e-6
        );
    }
    let rates = anim.rates.as_ref().unwrap();
    assert_eq!(rates.qdot.len(), 50);
    // The rates are the joint motion's derivative: their integral returns the last joint vector.
    let dt = 2.0 / 50.0;
    for j in 0..6 {
        let moved = anim.shots[49].q[j] - anim.shots[0].q[j];
        let integral: f64 = (0..49)
            .map(|k| 0.5 * (rates.qdot[k][j] + rates.qdot[k + 1][j]) * dt)
            .sum();
        assert!(
            (integral - moved).abs() < 0.05 * moved.abs().max(0.05),
            "joint {j}: {integral} vs {moved}"
        );
    }
}

#[test]
fn an_arm_without_a_dh_table_or_redundancy_is_told_why() {
    let robot = build("puma560").unwrap();
    let e = plan(&robot, Motion::SelfMotion, 10, 1.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("no exact self-motion"), "{e}");
    assert!(plan(&robot, Motion::DhFrames, 1, 1.0).is_err());
}

#[cfg(feature = "app")]
mod files {
    use std::process::Command;

    fn animate(args: &[&str]) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("armlab-animate-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.join(args[0]);
        let o = Command::new(env!("CARGO_BIN_EXE_armlab"))
            .arg("animate")
            .args(&args[1..])
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        out
    }

    #[test]
    fn a_gif_has_the_frames_and_timing_asked_for() {
        let out = animate(&[
            "dlr.gif",
            "dlr",
            "--what",
            "self-motion",
            "--size",
            "320x240",
            "--fps",
            "15",
            "--seconds",
            "2",
        ]);
        let mut opts = gif::DecodeOptions::new();
        opts.set_color_output(gif::ColorOutput::Indexed);
        let mut dec = opts.read_info(std::fs::File::open(&out).unwrap()).unwrap();
        assert_eq!((dec.width(), dec.height()), (320, 240));
        let (mut frames, mut centis) = (0, 0u32);
        while let Some(f) = dec.read_next_frame().unwrap() {
            frames += 1;
            centis += u32::from(f.delay);
        }
        assert_eq!(frames, 30);
        assert_eq!(centis, 200, "2 s in hundredths");
    }

    #[test]
    fn an_apng_has_the_frames_and_timing_asked_for() {
        let out = animate(&[
            "puma.apng",
            "puma560",
            "--what",
            "postures",
            "--size",
            "320x240",
            "--fps",
            "12",
            "--seconds",
            "1",
        ]);
        let dec = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&out).unwrap()));
        let reader = dec.read_info().unwrap();
        let info = reader.info();
        let actl = info.animation_control().expect("an animated PNG");
        assert_eq!(actl.num_frames, 12);
        let fctl = info.frame_control().expect("frame timing");
        assert_eq!((fctl.delay_num, fctl.delay_den), (1, 12));
        assert_eq!((info.width, info.height), (320, 240));
    }
}
