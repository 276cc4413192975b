//! Real rendering on whatever adapter wgpu finds (lavapipe on CI: `WGPU_BACKEND=vulkan`):
//! the same bytes twice, read-back of widths that are not a multiple of 64, 4x multisampling,
//! bad sizes and sample counts as errors, and a million dots. Without an adapter these tests
//! FAIL with the install instructions; they never skip.

use crate::common;

use common::render::*;

fn arm_demo_scene() -> (Scene, Camera) {
    let builtin = &armlab::kinematics::models::BUILT_INS[0];
    let robot = (builtin.build)();
    let q = robot.config("ready").expect("ready pose").to_vec();
    let mut scene = arm_scene(&robot, &q, &ArmStyle::default()).expect("scene");
    let ghost_q: Vec<f64> = q.iter().map(|v| v + 0.4).collect();
    scene.extend(
        arm_scene(
            &robot,
            &ghost_q,
            &ArmStyle {
                alpha: 0.35,
                grid: false,
                ..ArmStyle::default()
            },
        )
        .expect("ghost"),
    );
    scene
        .meshes
        .push(mesh(Shape::Cone, [0.3, 0.3, 0.0], [0.1, 0.1, 0.2], GREEN));
    scene.dots.extend((0..500).map(|i| {
        let t = i as f32 * 0.05;
        Dot {
            p: [t.cos() * 0.5, t.sin() * 0.5, t * 0.01],
            color: [0.9, 0.2, 0.6, if i % 2 == 0 { 1.0 } else { 0.5 }],
            size_px: 5.0,
        }
    }));
    let (c, r) = scene.bounds();
    let mut camera = Camera::default();
    camera.fit(c, r, 4.0 / 3.0);
    (scene, camera)
}

#[test]
fn rendering_twice_gives_identical_bytes_and_reuses_buffers() {
    let _serial = serial();
    let gpu = gpu();
    let (scene, camera) = arm_demo_scene();
    assert!(!scene.meshes.is_empty() && !scene.lines.is_empty() && !scene.dots.is_empty());
    let size = (256, 192);
    let settings = RenderSettings::default();
    let mut renderer = Renderer::new(gpu, 1).unwrap();
    let target = RenderTarget::new(gpu, size.0, size.1, 1).unwrap();
    let view = ViewUniforms::from_camera(&camera, size.0, size.1);
    renderer
        .render(gpu, &target, &scene, &view, &settings)
        .unwrap();
    let first = target.read_rgba(gpu).unwrap();
    let allocations = renderer.buffer_allocations();
    renderer
        .render(gpu, &target, &scene, &view, &settings)
        .unwrap();
    let second = target.read_rgba(gpu).unwrap();
    assert_eq!(
        renderer.buffer_allocations(),
        allocations,
        "same-size scene must not reallocate"
    );
    assert!(
        first.as_raw() == second.as_raw(),
        "two renders of one scene differ"
    );
    let fresh = render(&scene, &camera, size, 1, &settings);
    assert!(
        first.as_raw() == fresh.as_raw(),
        "a new renderer draws different bytes"
    );
    let bg = background(&settings);
    let drawn = first.pixels().filter(|p| p.0[..3] != bg[..]).count();
    assert!(drawn > 2000, "the arm covers only {drawn} pixels");
}

#[test]
fn a_width_that_is_not_a_multiple_of_64_reads_back_without_shear() {
    let _serial = serial();
    let settings = RenderSettings::unlit();
    let camera = front_camera(2.0);
    let size = (1000, 700);
    let scene = Scene {
        lines: vec![Line {
            a: [0.25, 0.0, -0.3],
            b: [0.25, 0.0, 0.3],
            color: GREEN,
            width_px: 3.0,
        }],
        dots: vec![Dot {
            p: [-0.3, 0.0, -0.3],
            color: BLUE,
            size_px: 7.0,
        }],
        ..Default::default()
    };
    let img = render(&scene, &camera, size, 1, &settings);
    let top = camera
        .project(&Point3::new(0.25, 0.0, 0.29), size.0, size.1)
        .unwrap();
    let bottom = camera
        .project(&Point3::new(0.25, 0.0, -0.29), size.0, size.1)
        .unwrap();
    assert!((top[0] - bottom[0]).abs() < 1e-3);
    let green = srgb3([GREEN[0], GREEN[1], GREEN[2]]);
    for y in (top[1].ceil() as u32..bottom[1] as u32).step_by(7) {
        let xs: Vec<u32> = (0..size.0)
            .filter(|&x| close(img.get_pixel(x, y), green, 2))
            .collect();
        assert!(
            !xs.is_empty() && xs.iter().all(|&x| x.abs_diff(top[0] as u32) <= 1),
            "row {y}: line pixels at {xs:?}, expected x = {}",
            top[0]
        );
    }
    let dot = camera
        .project(&Point3::new(-0.3, 0.0, -0.3), size.0, size.1)
        .unwrap();
    assert_pixel(
        &img,
        dot,
        srgb3([BLUE[0], BLUE[1], BLUE[2]]),
        2,
        "dot near the bottom",
    );
}

#[test]
fn msaa_4_renders_the_same_interior_and_smooths_edges() {
    let _serial = serial();
    let settings = RenderSettings::unlit();
    let mut camera = front_camera(2.0);
    camera.orbit(0.3, 0.2);
    let size = (320, 240);
    let centre = [0.0, 0.0, 0.0];
    let scene = Scene {
        meshes: vec![mesh(Shape::Sphere, centre, [0.3; 3], RED)],
        ..Default::default()
    };
    let img = render(&scene, &camera, size, 4, &settings);
    let p = camera
        .project(&Point3::from(centre), size.0, size.1)
        .unwrap();
    assert_pixel(
        &img,
        p,
        srgb3([RED[0], RED[1], RED[2]]),
        1,
        "sphere centre (MSAA)",
    );
    assert_pixel(&img, [3.0, 3.0], background(&settings), 0, "corner (MSAA)");
    let bg = background(&settings);
    let red = srgb3([RED[0], RED[1], RED[2]]);
    let blended = img
        .pixels()
        .filter(|px| !close(px, bg, 2) && !close(px, red, 2))
        .count();
    assert!(
        blended > 50,
        "MSAA should leave blended edge pixels, found {blended}"
    );
    // A renderer and a target with different sample counts are refused, not a panic.
    let gpu = gpu();
    let mut renderer = Renderer::new(gpu, 1).unwrap();
    let target = RenderTarget::new(gpu, 64, 64, 4).unwrap();
    let view = ViewUniforms::from_camera(&camera, 64, 64);
    let err = renderer
        .render(gpu, &target, &scene, &view, &settings)
        .unwrap_err();
    assert!(
        matches!(
            err,
            RenderError::SampleCountMismatch {
                renderer: 1,
                target: 4
            }
        ),
        "{err}"
    );
}

#[test]
fn bad_sizes_and_sample_counts_are_errors_not_panics() {
    let _serial = serial();
    let gpu = gpu();
    for (w, h) in [(0, 100), (100, 0), (0, 0)] {
        let err = RenderTarget::new(gpu, w, h, 1).unwrap_err();
        assert!(
            matches!(err, RenderError::InvalidSize { width, height, .. } if width == w && height == h),
            "{err}"
        );
    }
    let too_big = gpu.max_texture_side() + 1;
    assert!(matches!(
        RenderTarget::new(gpu, too_big, 16, 1),
        Err(RenderError::InvalidSize { .. })
    ));
    assert!(matches!(
        RenderTarget::new(gpu, 16, 16, 2),
        Err(RenderError::UnsupportedSampleCount { count: 2 })
    ));
    assert!(matches!(
        Renderer::new(gpu, 8),
        Err(RenderError::UnsupportedSampleCount { count: 8 })
    ));
}

#[test]
fn a_million_dots_at_1600x1200() {
    let _serial = serial();
    let gpu = gpu();
    let size = (1600, 1200);
    // Deterministic pseudo-random points in a 1 m cube.
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    let dots: Vec<Dot> = (0..1_000_000)
        .map(|_| {
            let p = [next() - 0.5, next() - 0.5, next() - 0.5];
            Dot {
                p,
                color: [p[0] + 0.5, 0.3, p[2] + 0.5, 1.0],
                size_px: 3.0,
            }
        })
        .collect();
    let scene = Scene {
        dots,
        ..Default::default()
    };
    let mut camera = Camera {
        target: Point3::origin(),
        ..Camera::default()
    };
    camera.fit(Point3::origin(), 0.87, 4.0 / 3.0);
    let settings = RenderSettings::default();
    let mut renderer = Renderer::new(gpu, 1).unwrap();
    let target = RenderTarget::new(gpu, size.0, size.1, 1).unwrap();
    let view = ViewUniforms::from_camera(&camera, size.0, size.1);
    // Warm-up frame (first use compiles the pipelines' shaders in the driver).
    renderer
        .render(gpu, &target, &scene, &view, &settings)
        .unwrap();
    gpu.device
        .poll(wgpu::PollType::wait_indefinitely())
        .unwrap();
    // Best of three frames: the machine is shared, and one slow frame says little.
    let (mut draw, mut cpu) = (std::time::Duration::MAX, std::time::Duration::MAX);
    for _ in 0..3 {
        let start = Instant::now();
        renderer
            .render(gpu, &target, &scene, &view, &settings)
            .unwrap();
        let submitted = start.elapsed();
        gpu.device
            .poll(wgpu::PollType::wait_indefinitely())
            .unwrap();
        if start.elapsed() < draw {
            (draw, cpu) = (start.elapsed(), submitted);
        }
    }
    let start = Instant::now();
    let img = target.read_rgba(gpu).unwrap();
    let readback = start.elapsed();
    println!(
        "1,000,000 dots at 1600x1200 on {} ({:?}): draw {:.0} ms (CPU side {:.0} ms), read-back {:.0} ms",
        gpu.adapter_info.name,
        gpu.adapter_info.backend,
        draw.as_secs_f64() * 1e3,
        cpu.as_secs_f64() * 1e3,
        readback.as_secs_f64() * 1e3
    );
    let bg = background(&settings);
    let covered = img.pixels().filter(|p| p.0[..3] != bg[..]).count();
    assert!(covered > 300_000, "dots cover only {covered} pixels");
    // 0.5-0.7 s on 2 quiet cores (lavapipe's per-triangle setup is the floor; the time is
    // measured in the performance chapter, not here). The tests of this crate share the cores
    // (4.7 s was seen with other builds running), so this is only a guard against a regression to
    // one draw per dot, which takes minutes.
    assert!(draw.as_secs_f64() < 30.0, "1M dots took {draw:?}");
}

/// Devices that cannot view the sRGB colour texture as `Rgba8Unorm` (WebGL2) get a copy
/// re-encoded after every frame (`shaders/encode.wgsl`). Its bytes must be the colour texture's
/// own: once, on the web, the 3D view came out too dark (linear values shown as sRGB). Checked
/// against the sRGB texture's bytes (the independent path: the GPU's own encoding on write),
/// at 1x and at 4x MSAA.
#[test]
fn the_reencoded_copy_has_the_colour_textures_bytes() {
    let _serial = serial();
    let gpu = gpu();
    let (scene, camera) = arm_demo_scene();
    let settings = RenderSettings::default();
    for samples in [1, 4] {
        let size = (200, 150);
        let mut renderer = Renderer::new(gpu, samples).unwrap();
        let target = RenderTarget::with_encoded_copy(gpu, size.0, size.1, samples).unwrap();
        let view = ViewUniforms::from_camera(&camera, size.0, size.1);
        renderer
            .render(gpu, &target, &scene, &view, &settings)
            .unwrap();
        let srgb = target.read_rgba(gpu).unwrap();
        let copy = target.read_egui_rgba(gpu).unwrap();
        let worst = srgb
            .as_raw()
            .iter()
            .zip(copy.as_raw())
            .map(|(a, b)| a.abs_diff(*b))
            .max()
            .unwrap();
        // One step of 8-bit rounding between the GPU's encoder and the shader's formula.
        assert!(
            worst <= 1,
            "{samples}x: the copy differs by up to {worst}/255"
        );
        let bg = background(&settings);
        let drawn = copy.pixels().filter(|p| p.0[..3] != bg[..]).count();
        assert!(
            drawn > 2000,
            "{samples}x: the copy shows only {drawn} drawn pixels"
        );
    }
}
