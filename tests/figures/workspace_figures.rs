//! Workspace figures rendered headlessly: golden images (tolerance in tests/common/golden.rs),
//! colour fractions checked against the closed-form areas, and the CLI's statistics. Need a
//! graphics adapter (Mesa's lavapipe on machines without a GPU); they fail without one.

use crate::common;
use armlab::figure::Theme;
use armlab::figure::figures::Figures;
use armlab::figure::workspace::{ColorBy, WsFigureOptions, WsView};
use armlab::headless::workspace_figure;
use armlab::kinematics::Robot;
use armlab::kinematics::models::built_in;
use armlab::workspace::TrackedPoint;
use common::golden::assert_golden;
use std::f64::consts::PI;

fn limited_two_link() -> Robot {
    armlab::model_file::load_model(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/robots/planar2_limited.toml"
    ))
    .unwrap()
}

fn figure(robot: &Robot, view: WsView, samples: usize) -> armlab::figure::workspace::WsFigure {
    sized(robot, view, samples, [800, 600])
}

fn sized(
    robot: &Robot,
    view: WsView,
    samples: usize,
    size: [u32; 2],
) -> armlab::figure::workspace::WsFigure {
    let mut f = Figures::new().unwrap_or_else(|e| panic!("{e}"));
    let opts = WsFigureOptions {
        view,
        color_by: ColorBy::Posture,
        samples,
        seed: 1,
        size,
        theme: Theme::Light,
        end_effector: 0,
        point: TrackedPoint::WristCentre,
        caption: String::new(),
        text_scale: 1.0,
    };
    workspace_figure(&mut f, robot, &robot.name.to_lowercase(), &opts, &|_| {}).unwrap()
}

/// Closed forms of the limited two-link arm (a1 = a2 = 1, |q1| <= pi/2, |q2| <= 3pi/4): each
/// posture pi (1 + sqrt2/2), one posture only sqrt2/2 + 3 pi sqrt2 / 8 (see tests/compute/workspace.rs).
fn closed_forms() -> (f64, f64) {
    let s2 = 2f64.sqrt();
    let only = s2 / 2.0 + 3.0 * PI * s2 / 8.0;
    let each = PI * (1.0 + s2 / 2.0);
    (only, each - only)
}

#[test]
fn two_link_with_limits_coloured_by_posture() {
    let fig = figure(&limited_two_link(), WsView::Plane, 50_000);
    assert_golden("workspace_planar2_limited_posture", &fig.image);
    // Colour fractions: pixels nearest to each legend colour, against the closed-form areas.
    let palette = [[0u8, 114, 178], [230, 159, 0], [0, 158, 115]];
    let mut counts = [0usize; 3];
    for p in fig.image.pixels() {
        for (k, c) in palette.iter().enumerate() {
            if p.0.iter().zip(c).all(|(a, b)| a.abs_diff(*b) <= 30) {
                counts[k] += 1;
            }
        }
    }
    let total: usize = counts.iter().sum();
    let (only, both) = closed_forms();
    let all = 2.0 * only + both;
    let fractions = counts.map(|c| c as f64 / total as f64);
    assert!((fractions[0] - only / all).abs() < 0.02, "{fractions:?}");
    assert!((fractions[1] - only / all).abs() < 0.02, "{fractions:?}");
    assert!((fractions[2] - both / all).abs() < 0.02, "{fractions:?}");
    // Exact areas (Green's theorem over the boundary arcs) equal the closed forms.
    let area = fig.stats.area.unwrap();
    assert!((area - all).abs() / all < 1e-10, "area {area} vs {all}");
    let both_measured = fig.stats.area_both_postures.unwrap();
    assert!(
        (both_measured - both).abs() / both < 1e-10,
        "both {both_measured} vs {both}"
    );
    assert!(fig.stats.measure_method.starts_with("exact"));
}

#[test]
fn three_link_arm_of_problem_2_17() {
    let fig = figure(&built_in("planar3").unwrap(), WsView::Plane, 50_000);
    assert_golden("workspace_planar3_problem_2_17", &fig.image);
    assert!((fig.stats.max_reach - 1.0).abs() < 1e-9);
    // Print size: the same exact regions at 2400 x 1800.
    let big = sized(
        &built_in("planar3").unwrap(),
        WsView::Plane,
        50_000,
        [2400, 1800],
    );
    assert_golden("workspace_planar3_problem_2_17_2400x1800", &big.image);
}

#[test]
fn top_view_of_the_anthropomorphic_arm_with_spherical_wrist() {
    let fig = figure(
        &built_in("anthropomorphic_spherical_wrist").unwrap(),
        WsView::Top,
        100_000,
    );
    assert_golden("workspace_anthropomorphic_spherical_wrist_top", &fig.image);
    // The wrist centre reaches a2 + d4 = 1 m from the shoulder.
    assert!(
        fig.stats.max_reach <= 1.0 + 1e-2 && fig.stats.max_reach > 0.98,
        "{}",
        fig.stats.max_reach
    );
}

#[test]
fn side_view_of_the_puma_560() {
    let fig = figure(&built_in("puma560").unwrap(), WsView::Side, 1000);
    assert_golden("workspace_puma560_side", &fig.image);
    assert!(fig.stats.measure_method.starts_with("Pappus"));
    // Decided exactly at every cell (no "too few samples to tell" left to paint grey).
    let map = armlab::workspace::compute_map(
        &built_in("puma560").unwrap(),
        &armlab::workspace::MapRequest {
            view: armlab::workspace::MapView::Side,
            point: TrackedPoint::WristCentre,
            cells: [400, 300],
            ..Default::default()
        },
    )
    .unwrap();
    assert!(
        map.exact && map.method.starts_with("exact"),
        "{}",
        map.method
    );
}

#[test]
fn joint_space_rectangle() {
    let fig = figure(&limited_two_link(), WsView::JointSpace, 1000);
    assert_golden("workspace_joint_space_rectangle", &fig.image);
}

#[test]
fn same_inputs_same_png_bytes() {
    let dir = std::env::temp_dir().join(format!("armlab-ws-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let run = |name: &str| {
        let out = dir.join(name);
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_armlab"))
            .args([
                "workspace",
                "planar2",
                "--out",
                out.to_str().unwrap(),
                "--samples",
                "20000",
                "--size",
                "640x480",
                "--format",
                "json",
                "--color-by",
                "none",
            ])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        (std::fs::read(out).unwrap(), v)
    };
    let (a, va) = run("a.png");
    let (b, _) = run("b.png");
    assert!(a == b, "PNG bytes differ between identical runs");
    // Full-range two-link arm: the disc of radius 2, both postures everywhere.
    let area = va["area"].as_f64().unwrap();
    assert!((area - 4.0 * PI).abs() / (4.0 * PI) < 0.005, "{area}");
    for key in [
        "area_both_postures",
        "bbox",
        "max_reach",
        "min_reach",
        "samples",
    ] {
        assert!(va.get(key).is_some(), "missing {key}");
    }
}

/// The dexterous workspace, shown apart from the reachable one: for the anthropomorphic arm with
/// spherical wrist every approach direction is reachable well inside (the wrist centre within
/// a2 + d4 of the shoulder), few near the outer rim (the last d6 = 0.1 m).
#[test]
fn dexterous_workspace_is_shown() {
    let robot = built_in("anthropomorphic_spherical_wrist").unwrap();
    let mut f = Figures::new().unwrap_or_else(|e| panic!("{e}"));
    let opts = WsFigureOptions {
        view: WsView::Side,
        color_by: ColorBy::Dexterity,
        samples: 5000,
        seed: 1,
        size: [640, 480],
        theme: Theme::Light,
        end_effector: 0,
        point: TrackedPoint::Flange,
        caption: String::new(),
        text_scale: 1.0,
    };
    let fig = workspace_figure(&mut f, &robot, "arm", &opts, &|_| {}).unwrap();
    let yellow = fig
        .image
        .pixels()
        .filter(|p| p.0[0] > 220 && p.0[1] > 200 && p.0[2] < 80)
        .count();
    let dark = fig
        .image
        .pixels()
        .filter(|p| p.0[0] < 90 && p.0[1] < 60 && p.0[2] > 60 && p.0[2] < 130)
        .count();
    assert!(yellow > 10_000, "dexterous core missing ({yellow} px)");
    assert!(dark > 200, "low-dexterity rim missing ({dark} px)");
    assert!(fig.stats.dexterous_measure > 0.0);
}
