//! Collisions: the checker's distances and depths against closed forms written here (spheres,
//! boxes, capsules) and a brute-force search over points sampled on a mesh's surface; the scene
//! file's errors and round trip; the UR5 with the convex hulls of its own collision meshes.

use armlab::collision::{CellScene, CollisionError, CollisionWorld};
use armlab::kinematics::models;
use armlab::urdf::parse_urdf;
use std::path::{Path, PathBuf};

/// A scene from its text.
fn scene(text: &str) -> CellScene {
    CellScene::parse(text, Path::new("cell.toml")).expect("a valid scene")
}

/// A one-joint URDF: a prismatic joint along x (limits +-1 m) carrying `geometry` at the child
/// link's origin; the base link has no geometry.
fn one_link(geometry: &str) -> armlab::kinematics::Robot {
    let text = format!(
        r#"<robot name="probe">
  <link name="base_link"/>
  <link name="probe"><collision><geometry>{geometry}</geometry></collision></link>
  <joint name="slide" type="prismatic">
    <parent link="base_link"/><child link="probe"/>
    <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
</robot>"#
    );
    parse_urdf(&text, Path::new("probe.urdf")).expect("a valid URDF")
}

/// The distance from `p` to the box of `half` extents centred at `c` (axis-aligned), 0 inside.
fn point_box_distance(p: [f64; 3], c: [f64; 3], half: [f64; 3]) -> f64 {
    (0..3)
        .map(|k| ((p[k] - c[k]).abs() - half[k]).max(0.0).powi(2))
        .sum::<f64>()
        .sqrt()
}

#[test]
fn sphere_against_sphere_and_box_matches_the_closed_forms() {
    let robot = one_link(r#"<sphere radius="0.1"/>"#);
    let cell = scene(
        "[[obstacle]]\nname = \"ball\"\nshape = \"sphere\"\nsize = [0.2]\nxyz = [0.6, 0.3, 0.1]\n\n\
         [[obstacle]]\nname = \"crate\"\nshape = \"box\"\nsize = [0.4, 0.2, 0.6]\nxyz = [-0.7, -0.22, 0.0]\n",
    );
    let world = CollisionWorld::new(&robot, &cell).unwrap();
    for x in [-0.9, -0.6, -0.45, -0.2, 0.0, 0.2, 0.45, 0.6, 0.9] {
        let p = [x, 0.0, 0.0];
        let to_ball = ((x - 0.6f64).powi(2) + 0.09 + 0.01).sqrt() - 0.1 - 0.2;
        let to_box = point_box_distance(p, [-0.7, -0.22, 0.0], [0.2, 0.1, 0.3]) - 0.1;
        let report = world.check(&robot, &[x]).unwrap();
        let nearest = to_ball.min(to_box);
        if nearest > 0.0 {
            assert!(!report.in_collision, "x = {x}: {}", report.summary());
            let c = report.clearance_m.unwrap();
            assert!(
                (c - nearest).abs() < 1e-9,
                "x = {x}: clearance {c}, closed form {nearest}"
            );
            let closest = report.closest.unwrap();
            let expected = if to_ball < to_box { "ball" } else { "crate" };
            assert_eq!(closest.b, expected);
        } else {
            assert!(report.in_collision, "x = {x}");
            let depth = report.pairs[0].depth_m;
            assert!(
                (depth + nearest).abs() < 1e-6,
                "x = {x}: depth {depth}, closed form {}",
                -nearest
            );
            assert_eq!(report.pairs[0].a, "probe");
        }
        assert_eq!(
            report.in_collision,
            world.in_collision(&robot, &[x]).unwrap()
        );
    }
}

#[test]
fn box_against_box_is_their_gap() {
    let robot = one_link(r#"<box size="0.2 0.2 0.2"/>"#);
    let cell = scene(
        "[[obstacle]]\nname = \"wall\"\nshape = \"box\"\nsize = [0.1, 2, 2]\nxyz = [0.5, 0, 0]\n",
    );
    let world = CollisionWorld::new(&robot, &cell).unwrap();
    for x in [-0.5, 0.0, 0.2, 0.3, 0.34, 0.36, 0.5] {
        // The probe's face at x + 0.1, the wall's at 0.45.
        let gap = 0.45 - (x + 0.1);
        let r = world.check(&robot, &[x]).unwrap();
        if gap > 0.0 {
            assert!(
                (r.clearance_m.unwrap() - gap).abs() < 1e-9,
                "x = {x}: {:?}",
                r.clearance_m
            );
        } else {
            assert!(r.in_collision);
            assert!(
                (r.pairs[0].depth_m + gap).abs() < 1e-6,
                "x = {x}: {:?}",
                r.pairs
            );
        }
    }
}

/// The distance from `p` to the segment `a`-`b`.
fn point_segment_distance(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let ab: Vec<f64> = (0..3).map(|k| b[k] - a[k]).collect();
    let ap: Vec<f64> = (0..3).map(|k| p[k] - a[k]).collect();
    let t = (ap.iter().zip(&ab).map(|(x, y)| x * y).sum::<f64>()
        / ab.iter().map(|x| x * x).sum::<f64>())
    .clamp(0.0, 1.0);
    (0..3)
        .map(|k| (p[k] - (a[k] + t * ab[k])).powi(2))
        .sum::<f64>()
        .sqrt()
}

#[test]
fn a_stick_link_is_a_capsule_of_the_drawn_radius() {
    // The two-link planar arm (1 m links) is checked as drawn: capsules of 0.018 x 2 m along
    // its links. A ball beside the second link at q = (30°, 45°).
    let robot = models::planar2();
    let (q1, q2) = (30f64.to_radians(), 45f64.to_radians());
    let elbow = [q1.cos(), q1.sin(), 0.0];
    let hand = [elbow[0] + (q1 + q2).cos(), elbow[1] + (q1 + q2).sin(), 0.0];
    let mid = [(elbow[0] + hand[0]) / 2.0, (elbow[1] + hand[1]) / 2.0, 0.0];
    // 0.25 m from the link's middle, at right angles in the plane.
    let normal = [-(q1 + q2).sin(), (q1 + q2).cos(), 0.0];
    let centre: Vec<f64> = (0..3).map(|k| mid[k] + 0.25 * normal[k]).collect();
    let cell = scene(&format!(
        "[[obstacle]]\nname = \"ball\"\nshape = \"sphere\"\nsize = [0.05]\nxyz = [{}, {}, {}]\n",
        centre[0], centre[1], centre[2]
    ));
    let world = CollisionWorld::new(&robot, &cell).unwrap();
    let r = world.check(&robot, &[q1, q2]).unwrap();
    let link_radius = 0.018 * 2.0;
    let expected =
        point_segment_distance([centre[0], centre[1], centre[2]], elbow, hand) - link_radius - 0.05;
    let c = r.clearance_m.unwrap();
    assert!(
        (c - expected).abs() < 1e-9,
        "clearance {c}, closed form {expected}"
    );
    assert_eq!(r.closest.unwrap().a, "link2");
    // A 0.1 m box whose near face is 0.02 m off the link's axis overlaps the capsule by 0.036 - 0.02.
    let off: Vec<f64> = (0..3).map(|k| mid[k] + 0.07 * normal[k]).collect();
    let cell = scene(&format!(
        "[[obstacle]]\nname = \"block\"\nshape = \"box\"\nsize = [0.1, 0.1, 0.1]\nxyz = [{}, {}, {}]\nrpy_deg = [0, 0, {}]\n",
        off[0],
        off[1],
        off[2],
        (q1 + q2).to_degrees()
    ));
    let world = CollisionWorld::new(&robot, &cell).unwrap();
    let r = world.check(&robot, &[q1, q2]).unwrap();
    assert!(r.in_collision);
    let depth = r.pairs[0].depth_m;
    assert!((depth - (link_radius - 0.02)).abs() < 1e-9, "depth {depth}");
    assert!(world.in_collision(&robot, &[q1, q2]).unwrap());
}

#[test]
fn a_half_space_second_is_measured_right() {
    // parry 0.31.1 measures a convex shape against a half-space wrongly in that order (a
    // capsule 14 mm above a floor read 86 mm deep); armlab asks with the half-space first.
    let robot = one_link(r#"<sphere radius="0.036"/>"#);
    for (floor, expected_gap) in [(-0.05, 0.014), (0.01, -0.046)] {
        let cell = scene(&format!(
            "[[obstacle]]\nname = \"floor\"\nshape = \"plane\"\nxyz = [0, 0, {floor}]\n"
        ));
        let world = CollisionWorld::new(&robot, &cell).unwrap();
        let r = world.check(&robot, &[0.3]).unwrap();
        if expected_gap > 0.0 {
            assert!(!r.in_collision, "{}", r.summary());
            assert!((r.clearance_m.unwrap() - expected_gap).abs() < 1e-9);
        } else {
            assert!(
                (r.pairs[0].depth_m + expected_gap).abs() < 1e-9,
                "{:?}",
                r.pairs
            );
        }
    }
}

/// A closed octahedron of "radius" `r` about `c` as ASCII STL.
fn octahedron_stl(c: [f64; 3], r: f64) -> String {
    let v = |k: usize, s: f64| {
        let mut p = c;
        p[k] += s * r;
        p
    };
    let mut out = String::from("solid octa\n");
    for sx in [1.0, -1.0] {
        for sy in [1.0, -1.0] {
            for sz in [1.0, -1.0] {
                let (a, b, cc) = (v(0, sx), v(1, sy), v(2, sz));
                // Outward winding: flip when the octant's orientation is negative.
                let tri = if sx * sy * sz > 0.0 {
                    [a, b, cc]
                } else {
                    [a, cc, b]
                };
                out += "facet normal 0 0 0\nouter loop\n";
                for p in tri {
                    out += &format!("vertex {} {} {}\n", p[0], p[1], p[2]);
                }
                out += "endloop\nendfacet\n";
            }
        }
    }
    out + "endsolid octa\n"
}

/// A fresh folder under the target directory for this test's files.
fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn a_mesh_obstacle_agrees_with_points_sampled_on_its_surface() {
    let dir = scratch("collision_mesh");
    std::fs::write(dir.join("octa.stl"), octahedron_stl([0.5, 0.2, 0.1], 0.3)).unwrap();
    std::fs::write(
        dir.join("cell.toml"),
        "[[obstacle]]\nname = \"fixture\"\nshape = \"mesh\"\nmesh = \"octa.stl\"\n",
    )
    .unwrap();
    let cell = CellScene::read(&dir.join("cell.toml")).unwrap();
    assert!(cell.warnings.is_empty(), "{:?}", cell.warnings);
    let robot = one_link(r#"<sphere radius="0.05"/>"#);
    let world = CollisionWorld::new(&robot, &cell).unwrap();
    // Brute force: points on every face of the octahedron on a fine barycentric grid.
    let (c, r) = ([0.5, 0.2, 0.1], 0.3);
    let mut surface = Vec::new();
    let n = 120;
    for sx in [1.0, -1.0] {
        for sy in [1.0, -1.0] {
            for sz in [1.0, -1.0] {
                for i in 0..=n {
                    for j in 0..=n - i {
                        let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
                        let w = 1.0 - u - v;
                        surface.push([c[0] + sx * r * u, c[1] + sy * r * v, c[2] + sz * r * w]);
                    }
                }
            }
        }
    }
    for x in [-0.8, -0.4, -0.1, 0.05] {
        let p = [x, 0.0, 0.0];
        let brute = surface
            .iter()
            .map(|s| ((s[0] - p[0]).powi(2) + (s[1] - p[1]).powi(2) + (s[2] - p[2]).powi(2)).sqrt())
            .fold(f64::INFINITY, f64::min)
            - 0.05;
        let report = world.check(&robot, &[x]).unwrap();
        let got = report.clearance_m.unwrap();
        // The grid's points lie on the surface: the true distance is at most the brute force's,
        // and no less than it minus the grid's spacing (0.3 m * sqrt(2) / 120).
        // Mesh files hold f32 vertices: 1e-7 m of round-off.
        assert!(
            got <= brute + 1e-6 && got >= brute - 0.004,
            "x = {x}: {got} vs {brute}"
        );
    }
    // Inside: the octahedron holds (0.5, 0.2, 0.1).
    assert!(world.in_collision(&robot, &[0.5]).unwrap());
}

/// The error of a scene file's text, as a message.
fn scene_error(text: &str, dir: &Path) -> String {
    let e = CellScene::parse(text, &dir.join("cell.toml")).expect_err("a bad scene");
    e.to_string()
}

#[test]
fn bad_scenes_are_errors_naming_the_file_the_line_and_the_obstacle() {
    let dir = scratch("collision_bad");
    std::fs::write(dir.join("empty.stl"), "solid e\nendsolid e\n").unwrap();
    let table = "[[obstacle]]\nname = \"table\"\nshape = \"box\"\nsize = [1, 1, 0.05]\n\n";
    let cases = [
        (
            "[[obstacle]]\nname = \"flat\"\nshape = \"box\"\nsize = [1, 0, 0.05]\n",
            "flat",
            "degenerate",
        ),
        (
            "[[obstacle]]\nname = \"nan\"\nshape = \"sphere\"\nsize = [0.1]\nxyz = [nan, 0, 0]\n",
            "nan",
            "not finite",
        ),
        (
            "[[obstacle]]\nname = \"gone\"\nshape = \"mesh\"\nmesh = \"nowhere.stl\"\n",
            "gone",
            "cannot be read",
        ),
        (
            "[[obstacle]]\nname = \"hollow\"\nshape = \"mesh\"\nmesh = \"empty.stl\"\n",
            "hollow",
            "empty.stl",
        ),
        (
            "[[obstacle]]\nname = \"blob\"\nshape = \"torus\"\n",
            "blob",
            "unknown shape",
        ),
    ];
    for (body, name, words) in cases {
        let text = format!("{table}{body}");
        let msg = scene_error(&text, &dir);
        assert!(msg.contains("cell.toml:6:"), "{msg}");
        assert!(msg.contains(&format!("obstacle \"{name}\"")), "{msg}");
        assert!(msg.contains(words), "{msg}");
    }
    // A frame the robot does not have: found when the scene meets the robot.
    let text = format!(
        "{table}[[obstacle]]\nname = \"tool\"\nshape = \"sphere\"\nsize = [0.1]\nframe = \"flange\"\n"
    );
    let cell = CellScene::parse(&text, &dir.join("cell.toml")).unwrap();
    let robot = models::puma560();
    let e = CollisionWorld::new(&robot, &cell).expect_err("unknown frame");
    assert!(matches!(e, CollisionError::Obstacle { line: 6, .. }), "{e}");
    assert!(e.to_string().contains("frame \"flange\""), "{e}");
    // A TOML error has its line and column.
    let msg = scene_error("[[obstacle]]\nname = \"x\nshape = \"box\"\n", &dir);
    assert!(msg.contains("cell.toml:2:"), "{msg}");
}

#[test]
fn an_open_mesh_is_a_warning_and_its_hull_is_checked() {
    let dir = scratch("collision_open");
    // The octahedron without its last face.
    let stl = octahedron_stl([0.0, 0.0, 0.0], 0.2);
    let cut = stl.rfind("facet normal").unwrap();
    std::fs::write(
        dir.join("open.stl"),
        format!("{}endsolid octa\n", &stl[..cut]),
    )
    .unwrap();
    let cell = CellScene::parse(
        "[[obstacle]]\nname = \"open\"\nshape = \"mesh\"\nmesh = \"open.stl\"\nxyz = [0.5, 0, 0]\n",
        &dir.join("cell.toml"),
    )
    .unwrap();
    assert_eq!(cell.warnings.len(), 1, "{:?}", cell.warnings);
    assert!(
        cell.warnings[0].contains("obstacle \"open\"") && cell.warnings[0].contains("not closed")
    );
    let robot = one_link(r#"<sphere radius="0.05"/>"#);
    let world = CollisionWorld::new(&robot, &cell).unwrap();
    // The hull is still the full octahedron: its vertex at x = 0.3.
    let r = world.check(&robot, &[0.0]).unwrap();
    assert!(
        (r.clearance_m.unwrap() - (0.3 - 0.05)).abs() < 1e-6,
        "{:?}",
        r.clearance_m
    );
}

#[test]
fn a_scene_survives_its_own_file() {
    let text = "[[obstacle]]\nname = \"table\"\nshape = \"box\"\nsize = [1.2, 0.8, 0.05]\nxyz = [0.6, 0.0, 0.375]\nrpy_deg = [0, 0, 30]\n\n\
                [[obstacle]]\nname = \"floor\"\nshape = \"plane\"\n\n\
                [[obstacle]]\nname = \"post\"\nshape = \"cylinder\"\nsize = [0.05, 1.0]\nxyz = [-0.4, 0.3, 0.5]\nframe = \"link1\"\n";
    let a = scene(text);
    let b = scene(&a.to_toml());
    assert_eq!(a.obstacles.len(), 3);
    for (x, y) in a.obstacles.iter().zip(&b.obstacles) {
        assert_eq!((&x.name, &x.shape, &x.frame), (&y.name, &y.shape, &y.frame));
        for k in 0..3 {
            assert!((x.xyz[k] - y.xyz[k]).abs() < 1e-9 && (x.rpy[k] - y.rpy[k]).abs() < 1e-9);
        }
    }
    assert!((a.obstacles[0].rpy[2] - 30f64.to_radians()).abs() < 1e-15);
}

#[test]
fn the_ur5_is_checked_with_the_hulls_of_its_own_meshes() {
    let meshes = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/collision_meshes");
    armlab::urdf::set_package_paths(vec![meshes]);
    let urdf = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/urdf_corpus/ur5_robot.urdf");
    let robot = armlab::urdf::load_urdf(&urdf).unwrap();
    armlab::urdf::set_package_paths(Vec::new());
    assert!(
        robot.collisions.len() >= 7,
        "{:?}",
        robot.collision_warnings
    );
    let world = CollisionWorld::new(&robot, &CellScene::default()).unwrap();
    let names: Vec<&str> = world.bodies().map(|b| b.name.as_str()).collect();
    assert!(names.contains(&"forearm_link"), "{names:?}");
    // Folded onto itself: the forearm back over the upper arm (q3 = 170°) hits.
    let mut q = vec![0.0, -1.57, 0.0, -1.57, 0.0, 0.0];
    let free = world.check(&robot, &q).unwrap();
    assert!(!free.in_collision, "{}", free.summary());
    q[2] = 170f64.to_radians();
    let folded = world.check(&robot, &q).unwrap();
    assert!(folded.in_collision, "{}", folded.summary());
}
