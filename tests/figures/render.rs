//! Real rendering on whatever adapter wgpu finds (lavapipe on CI: `WGPU_BACKEND=vulkan`).
//! Without an adapter these tests FAIL with the install instructions; they never skip.
//!
//! The checks need no golden images: colours come from `RenderSettings::unlit()` (or a
//! lighting formula evaluated here), positions from `Camera::project`.
//!
//! This file: where things land and how they are lit, blended and depth-tested;
//! `render_target.rs` covers determinism, read-back, multisampling, bad sizes and a large cloud.

use crate::common;

use common::render::*;

#[test]
fn the_install_message_names_the_packages() {
    let e = RenderError::NoAdapter {
        source: wgpu::RequestAdapterError::EnvNotSet,
    };
    assert_eq!(
        e.to_string(),
        "no graphics adapter found: install Mesa's software Vulkan driver (apt-get install mesa-vulkan-drivers libvulkan1) and run with WGPU_BACKEND=vulkan"
    );
}

#[test]
fn a_cube_appears_where_the_camera_projects_it() {
    let _serial = serial();
    let settings = RenderSettings::unlit();
    let mut camera = Camera {
        target: Point3::new(0.1, 0.0, 0.2),
        distance: 2.5,
        ..Camera::default()
    };
    camera.set_preset(Preset::Iso);
    let centre = [0.4, 0.4, 0.4];
    let scene = Scene {
        meshes: vec![mesh(Shape::Cube, centre, [0.12; 3], RED)],
        ..Default::default()
    };
    let size = (320, 240);
    let img = render(&scene, &camera, size, 1, &settings);
    let p = camera
        .project(&Point3::from(centre), size.0, size.1)
        .unwrap();
    assert!(p[0] > 200.0, "the cube is right of the centre: {p:?}");
    assert_pixel(&img, p, srgb3([RED[0], RED[1], RED[2]]), 1, "cube centre");
    // Just outside the cube (0.06 m half side) and far away: background.
    let beside = camera
        .project(
            &Point3::new(centre[0] - 0.15, centre[1], centre[2]),
            size.0,
            size.1,
        )
        .unwrap();
    assert_pixel(&img, beside, background(&settings), 1, "beside the cube");
    for corner in [[2.0, 2.0], [317.0, 2.0], [2.0, 237.0], [317.0, 237.0]] {
        assert_pixel(&img, corner, background(&settings), 0, "image corner");
    }
    let red_pixels = img
        .pixels()
        .filter(|px| px.0[0] > 150 && px.0[1] < 100)
        .count();
    assert!(
        (200..5000).contains(&red_pixels),
        "the cube covers {red_pixels} pixels"
    );
}

/// Headlight only: a face seen head-on shows its base colour, so the outside is drawn (culling
/// and winding agree) and normals survive non-uniform and mirroring scales.
#[test]
fn lighting_uses_correct_normals_under_non_uniform_and_mirroring_scale() {
    let _serial = serial();
    let settings = RenderSettings {
        ambient_sky: 0.0,
        ambient_ground: 0.0,
        key_intensity: 0.0,
        headlight: 1.0,
        specular: 0.0,
        ..RenderSettings::default()
    };
    let mut camera = front_camera(10.0);
    camera.projection = Projection::Orthographic { height: 1.2 };
    let base = [0.2, 0.7, 0.9, 1.0];
    let (a, c) = (0.4, 0.1); // ellipsoid semi-axes along x and y (z = c too)
    let scene = Scene {
        meshes: vec![
            mesh(Shape::Sphere, [0.0, 0.0, 0.25], [a, c, c], base),
            mesh(Shape::Sphere, [0.0, 0.0, -0.25], [-0.1, 0.1, 0.1], base),
            mesh(
                Shape::Cylinder,
                [-0.35, 0.0, -0.25],
                [0.05, -0.05, 0.1],
                base,
            ),
        ],
        ..Default::default()
    };
    let size = (400, 400);
    let img = render(&scene, &camera, size, 1, &settings);
    let eye = camera.eye();
    // On the ellipsoid at x = a/2, z = 0.25: surface y and the true normal (gradient).
    let x = a * 0.5;
    let y = -c * (1.0f32 - 0.25).sqrt();
    let n = nalgebra::Vector3::new(x / (a * a), y / (c * c), 0.0).normalize();
    let p = Point3::new(x, y, 0.25);
    let v = (eye - p).normalize();
    let shade = n.dot(&v);
    assert!(shade > 0.95, "test geometry: {shade}");
    let expect = srgb3([base[0] * shade, base[1] * shade, base[2] * shade]);
    assert_pixel(
        &img,
        camera.project(&p, size.0, size.1).unwrap(),
        expect,
        6,
        "ellipsoid at x = a/2",
    );
    let head_on = srgb3([base[0], base[1], base[2]]);
    let mirrored = camera
        .project(&Point3::new(0.0, -0.1, -0.25), size.0, size.1)
        .unwrap();
    assert_pixel(&img, mirrored, head_on, 3, "mirrored sphere, centre");
    let cyl = camera
        .project(&Point3::new(-0.35, -0.05, -0.25), size.0, size.1)
        .unwrap();
    assert_pixel(&img, cyl, head_on, 3, "mirrored cylinder, centre");
}

#[test]
fn lines_and_dots_land_where_projected() {
    let _serial = serial();
    let settings = RenderSettings::unlit();
    let camera = Camera {
        target: Point3::new(0.0, 0.0, 0.1),
        distance: 2.0,
        ..Camera::default()
    };
    let size = (480, 360);
    let (a, b) = ([-0.4, 0.1, 0.3], [0.3, -0.2, 0.25]);
    let dot = [0.15, 0.1, -0.2];
    let scene = Scene {
        lines: vec![Line {
            a,
            b,
            color: GREEN,
            width_px: 3.0,
        }],
        dots: vec![Dot {
            p: dot,
            color: BLUE,
            size_px: 9.0,
        }],
        ..Default::default()
    };
    let img = render(&scene, &camera, size, 1, &settings);
    let proj = |p: [f32; 3]| camera.project(&Point3::from(p), size.0, size.1).unwrap();
    let green = srgb3([GREEN[0], GREEN[1], GREEN[2]]);
    for t in [0.1f32, 0.5, 0.9] {
        let p = [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) * t);
        assert_pixel(&img, proj(p), green, 2, &format!("line at t = {t}"));
    }
    // 6 px across the line: background.
    let (pa, pb) = (proj(a), proj(b));
    let (dx, dy) = (pb[0] - pa[0], pb[1] - pa[1]);
    let len = (dx * dx + dy * dy).sqrt();
    let mid = proj([0, 1, 2].map(|k| (a[k] + b[k]) * 0.5));
    let off = [mid[0] - dy / len * 6.0, mid[1] + dx / len * 6.0];
    assert_pixel(&img, off, background(&settings), 1, "6 px beside the line");
    let pd = proj(dot);
    assert_pixel(
        &img,
        pd,
        srgb3([BLUE[0], BLUE[1], BLUE[2]]),
        2,
        "dot centre",
    );
    assert_pixel(
        &img,
        [pd[0] + 3.0, pd[1]],
        srgb3([BLUE[0], BLUE[1], BLUE[2]]),
        2,
        "3 px inside the dot",
    );
    assert_pixel(
        &img,
        [pd[0] + 7.0, pd[1]],
        background(&settings),
        1,
        "7 px right of the dot",
    );
    // Round, not square: the corner of its 9 px box is background.
    assert_pixel(
        &img,
        [pd[0] + 5.0, pd[1] + 5.0],
        background(&settings),
        1,
        "dot's bounding-box corner",
    );
}

#[test]
fn a_line_through_the_camera_draws_only_its_visible_part() {
    let _serial = serial();
    let settings = RenderSettings::unlit();
    let camera = front_camera(2.0); // eye at (0, -2, 0), looking along +y
    let size = (320, 240);
    let scene = Scene {
        lines: vec![Line {
            a: [0.2, 0.0, 0.0],
            b: [0.2, -4.0, 0.0],
            color: GREEN,
            width_px: 4.0,
        }],
        ..Default::default()
    };
    let img = render(&scene, &camera, size, 1, &settings);
    let green = srgb3([GREEN[0], GREEN[1], GREEN[2]]);
    let near = camera
        .project(&Point3::new(0.2, -1.0, 0.0), size.0, size.1)
        .unwrap();
    assert_pixel(&img, near, green, 2, "visible part of the line");
    assert_pixel(
        &img,
        camera
            .project(&Point3::new(0.2, 0.0, 0.0), size.0, size.1)
            .unwrap(),
        green,
        2,
        "far end",
    );
    // Unclipped, the end behind the eye would project to the mirror side (x < centre).
    let mirror = [160.0 - (near[0] - 160.0), 120.0];
    assert_pixel(
        &img,
        mirror,
        background(&settings),
        1,
        "mirror side of the screen",
    );
    let left_half_coloured = (0..240)
        .flat_map(|y| (0..150).map(move |x| (x, y)))
        .filter(|&(x, y)| img.get_pixel(x, y).0[1] > 100 && img.get_pixel(x, y).0[0] < 100)
        .count();
    assert_eq!(left_half_coloured, 0, "no line pixels left of centre");
}

#[test]
fn depth_bias_shows_lines_on_a_surface_and_hides_lines_behind_it() {
    let _serial = serial();
    let settings = RenderSettings::unlit();
    let camera = front_camera(2.0);
    let size = (320, 240);
    // Cube face at y = -0.2 faces the camera; one line on it, one behind the cube.
    let scene = Scene {
        meshes: vec![mesh(Shape::Cube, [0.0, 0.0, 0.0], [0.4; 3], BLUE)],
        lines: vec![
            Line {
                a: [-0.15, -0.2, 0.05],
                b: [0.15, -0.2, 0.05],
                color: GREEN,
                width_px: 3.0,
            },
            Line {
                a: [-0.15, 0.1, -0.05],
                b: [0.15, 0.1, -0.05],
                color: RED,
                width_px: 3.0,
            },
        ],
        ..Default::default()
    };
    let img = render(&scene, &camera, size, 1, &settings);
    let on = camera
        .project(&Point3::new(0.0, -0.2, 0.05), size.0, size.1)
        .unwrap();
    assert_pixel(
        &img,
        on,
        srgb3([GREEN[0], GREEN[1], GREEN[2]]),
        2,
        "line on the front face",
    );
    let behind = camera
        .project(&Point3::new(0.0, -0.2, -0.05), size.0, size.1)
        .unwrap();
    assert_pixel(
        &img,
        behind,
        srgb3([BLUE[0], BLUE[1], BLUE[2]]),
        1,
        "line behind the cube is hidden",
    );
}

#[test]
fn translucent_meshes_blend_back_to_front_over_opaque_ones() {
    let _serial = serial();
    let settings = RenderSettings::unlit();
    let camera = front_camera(3.0);
    let size = (320, 240);
    let half_red = [1.0, 0.0, 0.0, 0.5];
    let half_green = [0.0, 1.0, 0.0, 0.5];
    let scene = Scene {
        meshes: vec![
            // Listed near first: sorting must still draw the far one first.
            mesh(Shape::Cube, [-0.3, -0.5, 0.0], [0.3; 3], half_red),
            mesh(
                Shape::Cube,
                [-0.3, 0.0, 0.0],
                [0.2, 0.2, 0.2],
                [0.0, 0.0, 1.0, 1.0],
            ),
            mesh(Shape::Cube, [-0.3, 0.5, 0.0], [0.2, 0.2, 0.2], half_green),
            mesh(Shape::Cube, [0.35, -0.2, 0.0], [0.2; 3], half_red),
            mesh(Shape::Cube, [0.35, 0.4, 0.05], [0.4; 3], half_green),
        ],
        ..Default::default()
    };
    let img = render(&scene, &camera, size, 1, &settings);
    let bg = settings.clear;
    let px = |p: [f32; 3]| camera.project(&Point3::from(p), size.0, size.1).unwrap();
    // Red (near, translucent) over opaque blue: 0.5 red + 0.5 blue; the translucent green cube
    // behind the blue one is hidden by the depth test.
    assert_pixel(
        &img,
        px([-0.3, -0.6, 0.0]),
        srgb3([0.5, 0.0, 0.5]),
        2,
        "red over blue",
    );
    // Red over background only (above the blue cube, below the green one's top).
    assert_pixel(
        &img,
        px([-0.3, -0.6, -0.13]),
        srgb3([0.5 + 0.5 * bg[0], 0.5 * bg[1], 0.5 * bg[2]]),
        2,
        "red over background",
    );
    // Red (near) over green (far) over background, whatever the scene order.
    let over = [0.5, 0.5 * (0.5 + 0.5 * bg[1]), 0.5 * 0.5 * bg[2]];
    let over = [0.5 + 0.25 * bg[0], over[1], over[2]];
    assert_pixel(
        &img,
        px([0.35, -0.3, 0.0]),
        srgb3(over),
        2,
        "red over green",
    );
}

/// A workspace cloud never hides the arm: dots of the underlay in front of a mesh are covered
/// by it (they once were drawn with the depth test and a dense cloud hid the arm), while the
/// same dot among the ordinary dots covers the mesh. Beside the mesh the underlay shows.
#[test]
fn underlay_dots_never_cover_a_mesh() {
    let _serial = serial();
    let settings = RenderSettings::unlit();
    let mut camera = Camera {
        target: Point3::new(0.0, 0.0, 0.0),
        distance: 2.0,
        ..Camera::default()
    };
    camera.set_preset(Preset::Iso);
    let centre = [0.0, 0.0, 0.0];
    // A point between the eye and the cube, on the ray through the cube's centre.
    let eye = camera.eye();
    let towards = [eye.x * 0.5, eye.y * 0.5, eye.z * 0.5];
    let dot = |p: [f32; 3]| Dot {
        p,
        color: [0.0, 1.0, 0.0, 1.0],
        size_px: 30.0,
    };
    let size = (320, 240);
    let at = camera
        .project(&Point3::from(centre), size.0, size.1)
        .unwrap();
    let red = srgb3([RED[0], RED[1], RED[2]]);
    let green = srgb3([0.0, 1.0, 0.0]);
    let under = Scene {
        meshes: vec![mesh(Shape::Cube, centre, [0.3; 3], RED)],
        underlay: vec![dot(towards)],
        ..Default::default()
    };
    let img = render(&under, &camera, size, 1, &settings);
    assert_pixel(
        &img,
        at,
        red,
        1,
        "the cube over the underlay dot in front of it",
    );
    let over = Scene {
        meshes: vec![mesh(Shape::Cube, centre, [0.3; 3], RED)],
        dots: vec![dot(towards)],
        ..Default::default()
    };
    let img = render(&over, &camera, size, 1, &settings);
    assert_pixel(
        &img,
        at,
        green,
        1,
        "an ordinary dot in front of the cube covers it",
    );
    let beside = Scene {
        underlay: vec![dot(towards)],
        ..Default::default()
    };
    let img = render(&beside, &camera, size, 1, &settings);
    assert_pixel(&img, at, green, 1, "the underlay dot alone shows");
}
