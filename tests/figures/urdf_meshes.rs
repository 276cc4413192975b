//! URDF visuals: a vendored two-joint arm whose links are STL meshes (generated for the tests,
//! `tests/data/urdf_meshes/`) loads with its meshes, and rendering it puts each link's colour
//! where forward kinematics says the link is; a missing mesh is a warning naming the file and
//! the link falls back to the joint's body; `package://` paths resolve through the package
//! search list; large meshes are decimated within their budget.

use armlab::camera::{Camera, Preset, Projection};
use armlab::figure::Theme;
use armlab::figure::figures::{Figures, Scene3d};
use armlab::kinematics::visual::VisualGeometry;
use armlab::mesh::TriMesh;
use armlab::scene::{ArmStyle, arm_scene};
use armlab::urdf::{load_urdf, set_package_paths};
use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/urdf_meshes")
}

fn mesh_triangles(r: &armlab::kinematics::Robot) -> Vec<usize> {
    r.visuals
        .iter()
        .filter_map(|v| match &v.geometry {
            VisualGeometry::Mesh { mesh, coarse } => {
                assert!(coarse.triangles.len() <= mesh.triangles.len());
                Some(mesh.triangles.len())
            }
            _ => None,
        })
        .collect()
}

#[test]
fn meshes_are_drawn_where_forward_kinematics_puts_the_links() {
    let robot = load_urdf(&data().join("arm_with_meshes.urdf")).unwrap();
    assert!(robot.load_warnings.is_empty(), "{:?}", robot.load_warnings);
    assert_eq!(robot.visuals.len(), 3);
    assert_eq!(mesh_triangles(&robot), vec![12, 96]);
    let q = [0.6, 0.0];
    let style = ArmStyle {
        frames: false,
        grid: false,
        ..ArmStyle::default()
    };
    let scene = arm_scene(&robot, &q, &style).unwrap();
    assert_eq!(scene.custom_meshes.len(), 2);
    // The arm offers coarse copies for moving frames; a ghost (faded) is drawn with bodies.
    assert!(scene.custom_meshes.iter().all(|m| m.coarse.is_some()));
    let ghost = arm_scene(
        &robot,
        &q,
        &ArmStyle {
            alpha: 0.3,
            ..style
        },
    )
    .unwrap();
    assert!(ghost.custom_meshes.is_empty() && ghost.meshes.len() >= 3);
    let mut camera = Camera {
        projection: Projection::Orthographic { height: 1.6 },
        ..Camera::default()
    };
    camera.set_preset(Preset::Top);
    camera.target = nalgebra::Point3::new(0.0, 0.0, 0.4);
    camera.distance = 3.0;
    let fig = Scene3d {
        title: String::new(),
        subtitle: String::new(),
        scene: &scene,
        camera,
        legend: vec![],
        caption: String::new(),
    };
    let img = Figures::new()
        .unwrap_or_else(|e| panic!("{e}"))
        .scene([640, 640], Theme::Light, &fig)
        .unwrap();
    // Points in the links' frames, placed by the robot's own FK: the column's top face beside
    // the arm, the middle of the arm's cylinder, the tool sphere's top.
    let frames = robot.fk_frames(&q).unwrap();
    let at = |joint: usize, local: [f64; 3]| {
        let p = frames[joint] * nalgebra::Point3::from(local);
        camera
            .project(
                &nalgebra::Point3::new(p.x as f32, p.y as f32, p.z as f32),
                640,
                640,
            )
            .unwrap()
    };
    for (name, p, want) in [
        ("column", at(0, [-0.045, 0.0, 0.4]), [230, 25, 25]),
        ("upper arm", at(1, [0.25, 0.0, 0.05]), [25, 205, 25]),
        ("tool", at(2, [0.0, 0.0, 0.06]), [25, 25, 230]),
    ] {
        let px = img.get_pixel(p[0] as u32, p[1] as u32).0;
        let dominant = (0..3).max_by_key(|&k| want[k]).unwrap();
        assert!(
            (0..3).all(|k| k == dominant || px[dominant] as i32 > px[k] as i32 + 60),
            "{name} at {p:?}: {px:?}"
        );
    }
    // Turning joint 1 moves the arm: the old place of the cylinder's middle is background.
    let away = at(1, [0.25, 0.0, 0.05]);
    let scene = arm_scene(&robot, &[-1.0, 0.0], &style).unwrap();
    let img = Figures::new()
        .unwrap()
        .scene(
            [640, 640],
            Theme::Light,
            &Scene3d {
                scene: &scene,
                ..fig
            },
        )
        .unwrap();
    let px = img.get_pixel(away[0] as u32, away[1] as u32).0;
    assert!(px.iter().take(3).all(|&c| c > 200), "{px:?}");
}

#[test]
fn missing_meshes_warn_and_package_paths_resolve() {
    let dir = std::env::temp_dir().join(format!("armlab-meshes-{}", std::process::id()));
    let pkgs = dir.join("pkgs");
    std::fs::create_dir_all(pkgs.join("armlab_test/meshes")).unwrap();
    for f in ["column.stl", "arm.stl"] {
        std::fs::copy(
            data().join("armlab_test/meshes").join(f),
            pkgs.join("armlab_test/meshes").join(f),
        )
        .unwrap();
    }
    let text = std::fs::read_to_string(data().join("arm_with_meshes.urdf"))
        .unwrap()
        .replace("armlab_test/meshes/column.stl", "meshes/no_such_file.stl");
    let urdf = dir.join("elsewhere/arm.urdf");
    std::fs::create_dir_all(urdf.parent().unwrap()).unwrap();
    std::fs::write(&urdf, text).unwrap();
    // Neither mesh is found: two warnings naming the files; the robot loads anyway.
    set_package_paths(vec![]);
    let r = load_urdf(&urdf).unwrap();
    assert_eq!(r.load_warnings.len(), 2, "{:?}", r.load_warnings);
    assert!(
        r.load_warnings[0].contains("no_such_file.stl"),
        "{:?}",
        r.load_warnings
    );
    assert!(r.load_warnings[1].contains("package \"armlab_test\" not found"));
    assert_eq!(r.visuals.len(), 1);
    // The links without their mesh keep the joint's body (two cylinders of the generic arm).
    let scene = arm_scene(&r, &[0.0, 0.0], &ArmStyle::default()).unwrap();
    assert!(scene.custom_meshes.is_empty() && scene.meshes.len() > 3);
    // With the package folder on the search list the arm's mesh is found.
    set_package_paths(vec![pkgs.clone()]);
    let r = load_urdf(&urdf).unwrap();
    set_package_paths(vec![]);
    assert_eq!(r.load_warnings.len(), 1, "{:?}", r.load_warnings);
    assert_eq!(mesh_triangles(&r), vec![96]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A fine sphere (51,200 triangles) decimated to the budget: no more triangles than asked,
/// every vertex still within a grid cell of the sphere, no degenerate triangle.
#[test]
fn large_meshes_are_decimated_within_the_budget() {
    let (n, m) = (160u32, 160u32);
    let mut mesh = TriMesh::default();
    for i in 0..=n {
        for j in 0..m {
            let (t, p) = (
                std::f32::consts::PI * i as f32 / n as f32,
                std::f32::consts::TAU * j as f32 / m as f32,
            );
            mesh.positions
                .push([t.sin() * p.cos(), t.sin() * p.sin(), t.cos()]);
        }
    }
    let id = |i: u32, j: u32| i * m + j % m;
    for i in 0..n {
        for j in 0..m {
            mesh.triangles
                .push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            mesh.triangles
                .push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    assert_eq!(mesh.triangles.len(), 51_200);
    let small = mesh.decimated(armlab::urdf::MAX_TRIANGLES);
    assert!(small.triangles.len() <= armlab::urdf::MAX_TRIANGLES);
    assert!(small.triangles.len() > 1000, "{}", small.triangles.len());
    let cell = 2.0 * 3f32.sqrt() / 20.0;
    for p in &small.positions {
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        assert!((r - 1.0).abs() < cell, "{p:?}");
    }
    for t in &small.triangles {
        assert!(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
    }
    // Under the budget nothing changes.
    assert_eq!(small.decimated(armlab::urdf::MAX_TRIANGLES), small);
}

/// OBJ and COLLADA files (the same hand-written tetrahedron) load with their four triangles,
/// wound outward, scaled by the URDF's `scale`.
#[test]
fn obj_and_collada_meshes_load() {
    for file in ["tetra.obj", "tetra.dae"] {
        let text = format!(
            r#"<robot name="t"><link name="a"/><link name="b"><visual><geometry>
               <mesh filename="armlab_test/meshes/{file}" scale="2 2 2"/></geometry></visual></link>
               <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
               <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
               </robot>"#
        );
        let r = armlab::urdf::parse_urdf(&text, &data().join("t.urdf")).unwrap();
        assert!(r.load_warnings.is_empty(), "{file}: {:?}", r.load_warnings);
        let VisualGeometry::Mesh { mesh, .. } = &r.visuals[0].geometry else {
            panic!("{file}: not a mesh")
        };
        assert_eq!(mesh.triangles.len(), 4, "{file}");
        let far = mesh
            .positions
            .iter()
            .map(|p| p.iter().fold(0.0f32, |m, v| m.max(v.abs())))
            .fold(0.0, f32::max);
        assert!((far - 0.2).abs() < 1e-6, "{file}: scaled extent {far}");
        assert_eq!(mesh.winding(), armlab::mesh::Winding::Outward, "{file}");
    }
}

/// A mesh that is not a regular file (a device read forever) is refused with a warning, at once
/// (issue 16: found by reading the loader; /dev/zero has size 0 and never ends).
#[test]
fn a_mesh_that_is_a_device_is_refused() {
    let text = std::fs::read_to_string(data().join("arm_with_meshes.urdf"))
        .unwrap()
        .replace("armlab_test/meshes/column.stl", "/dev/zero");
    let start = std::time::Instant::now();
    let r = armlab::urdf::parse_urdf(&text, &data().join("arm_with_meshes.urdf")).unwrap();
    assert!(start.elapsed().as_secs() < 5);
    assert!(
        r.load_warnings
            .iter()
            .any(|w| w.contains("/dev/zero") && w.contains("not a regular file")),
        "{:?}",
        r.load_warnings
    );
}

/// The file quirks of issue 26, each a warning naming the element, never a refusal: upper-case
/// mesh extensions (`.DAE`, `.STL`) load; COLLADA `<unit meter="0.001">` scales millimetres to
/// metres; an `<up_axis>` other than Z_UP is ignored as RViz does, with a warning naming the
/// link and the file (once per file); a material defined twice with two colours is a warning
/// and the first colour is used; a xacro file gets a message saying how to expand it.
#[test]
fn file_quirks_are_warnings_naming_the_element() {
    let dir = std::env::temp_dir().join(format!("armlab_quirks_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let dae = std::fs::read_to_string(data().join("armlab_test/meshes/tetra.dae"))
        .unwrap()
        .replace(
            r#"<unit name="meter" meter="1"/>"#,
            r#"<unit name="millimeter" meter="0.001"/>"#,
        )
        .replace("<up_axis>Z_UP</up_axis>", "<up_axis>Y_UP</up_axis>")
        .replace(
            "0 0 0 0.1 0 0 0 0.1 0 0 0 0.1",
            "0 0 0 100 0 0 0 100 0 0 0 100",
        );
    std::fs::write(dir.join("TETRA_MM.DAE"), dae).unwrap();
    std::fs::copy(
        data().join("armlab_test/meshes/column.stl"),
        dir.join("COLUMN.STL"),
    )
    .unwrap();
    let text = r#"<robot name="q">
      <material name="grey"><color rgba="0.5 0.5 0.5 1"/></material>
      <material name="grey"><color rgba="1 0 0 1"/></material>
      <link name="a"><visual><geometry><mesh filename="COLUMN.STL"/></geometry>
        <material name="grey"/></visual></link>
      <link name="b"><visual><geometry><mesh filename="TETRA_MM.DAE"/></geometry></visual></link>
      <link name="c"><visual><geometry><mesh filename="TETRA_MM.DAE"/></geometry></visual></link>
      <joint name="j1" type="revolute"><parent link="a"/><child link="b"/>
        <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
      <joint name="j2" type="fixed"><parent link="b"/><child link="c"/></joint>
    </robot>"#;
    let r = armlab::urdf::parse_urdf(text, &dir.join("q.urdf")).unwrap();
    let w = &r.load_warnings;
    assert_eq!(mesh_triangles(&r).len(), 3, "all three meshes drawn: {w:?}");
    let tetra = r
        .visuals
        .iter()
        .find_map(|v| match &v.geometry {
            VisualGeometry::Mesh { mesh, .. } if mesh.triangles.len() == 4 => Some(mesh.clone()),
            _ => None,
        })
        .unwrap();
    let far = tetra
        .positions
        .iter()
        .map(|p| p.iter().fold(0.0f32, |m, v| m.max(v.abs())))
        .fold(0.0, f32::max);
    assert!((far - 0.1).abs() < 1e-6, "100 mm read as {far} m");
    let up: Vec<&String> = w.iter().filter(|m| m.contains("up_axis")).collect();
    assert_eq!(up.len(), 1, "once per file: {w:?}");
    assert!(
        up[0].contains("link \"b\"") && up[0].contains("TETRA_MM.DAE"),
        "{up:?}"
    );
    let grey: Vec<&String> = w
        .iter()
        .filter(|m| m.contains("material \"grey\""))
        .collect();
    assert_eq!(grey.len(), 1, "{w:?}");
    let col = r.visuals[0].color.unwrap();
    assert_eq!(col, [0.5, 0.5, 0.5, 1.0], "the first definition is used");
    assert_eq!(w.len(), 2, "{w:?}");
    // xacro: by its extension, and by its markup in a .urdf file.
    let e = armlab::model_file::load_model("robot.urdf.xacro")
        .unwrap_err()
        .to_string();
    assert!(e.contains("xacro robot.urdf.xacro > robot.urdf"), "{e}");
    let e = armlab::urdf::parse_urdf(
        r#"<robot name="x" xmlns:xacro="http://ros.org/wiki/xacro"><xacro:property name="l" value="1"/></robot>"#,
        Path::new("x.urdf"),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("expand it into URDF first"), "{e}");
    // xacro calls left in comments of an expanded file (TALOS's) are no xacro markup.
    let r = armlab::urdf::parse_urdf(
        r#"<robot name="x"><!-- <xacro:gripper name="g"/> --><link name="a"/><link name="b"/>
           <joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint></robot>"#,
        Path::new("x.urdf"),
    );
    assert!(r.is_ok(), "{r:?}");
    let _ = std::fs::remove_dir_all(&dir);
}
