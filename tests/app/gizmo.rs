//! The IK target gizmo's pure math: pixel rays, picking and dragging against a camera.

use armlab::app::gizmo::{
    Gizmo, GizmoOutput, GizmoSpace, Handle, PLANE_INNER, PLANE_OUTER, RING_RADIUS,
    metres_per_pixel, ray_from_pixel,
};
use armlab::camera::{Camera, Preset, Projection};
use armlab::kinematics::Pose;
use nalgebra::{Point3, Rotation3, Translation3, Vector2, Vector3};
use std::f64::consts::FRAC_PI_2;

const VP: [u32; 2] = [800, 600];

fn ortho(preset: Preset) -> Camera {
    let mut c = Camera {
        target: Point3::new(0.2, 0.0, 0.4),
        distance: 3.0,
        projection: Projection::Orthographic { height: 2.0 },
        ..Default::default()
    };
    c.set_preset(preset);
    c
}

fn persp(preset: Preset) -> Camera {
    let mut c = Camera {
        target: Point3::new(0.2, 0.0, 0.4),
        distance: 2.5,
        ..Default::default()
    };
    c.set_preset(preset);
    c
}

fn cameras() -> [Camera; 2] {
    [ortho(Preset::Iso), persp(Preset::Iso)]
}

/// A target with a generic orientation near the camera's target.
fn target() -> Pose {
    Pose::from_parts(
        Translation3::new(0.3, -0.1, 0.5),
        Rotation3::from_euler_angles(0.3, -0.4, 0.7),
    )
}

fn gizmo(space: GizmoSpace) -> Gizmo {
    Gizmo::new(space)
}

fn proj(c: &Camera, p: &Point3<f64>) -> Vector2<f64> {
    let q = c.project(&p.cast::<f32>(), VP[0], VP[1]).expect("in front");
    Vector2::new(q[0] as f64, q[1] as f64)
}

fn arr(v: Vector2<f64>) -> [f32; 2] {
    [v.x as f32, v.y as f32]
}

fn centre(p: &Pose) -> Point3<f64> {
    Point3::from(p.translation.vector)
}

/// World length of the arrows at the target.
fn arrow_len(g: &Gizmo, c: &Camera, p: &Pose) -> f64 {
    g.size_px as f64 * metres_per_pixel(c, VP, &centre(p)).unwrap()
}

fn assert_finite(p: &Pose) {
    assert!(p.to_homogeneous().iter().all(|v| v.is_finite()), "{p:?}");
}

#[test]
fn ray_from_pixel_round_trips_with_project() {
    for c in [
        ortho(Preset::Iso),
        persp(Preset::Iso),
        ortho(Preset::Top),
        persp(Preset::Front),
    ] {
        for pixel in [[400.0, 300.0], [10.0, 20.0], [790.0, 590.0], [123.4, 456.7]] {
            let (o, d) = ray_from_pixel(&c, VP, pixel);
            assert!((d.norm() - 1.0).abs() < 1e-9);
            for t in [0.5, 1.0, 2.5, 10.0] {
                let q = proj(&c, &(o + d * t));
                assert!(
                    (q - Vector2::new(pixel[0] as f64, pixel[1] as f64)).norm() < 2e-2,
                    "{c:?} {pixel:?} {t} {q}"
                );
            }
        }
        // The ray under a point's projection passes through the point.
        let p = Point3::new(0.5, 0.3, 0.1);
        let (o, d) = ray_from_pixel(&c, VP, arr(proj(&c, &p)));
        let off = p - o;
        assert!((off - d * off.dot(&d)).norm() < 1e-4, "{c:?}");
    }
    // Orthographic rays are parallel and metres per pixel is the visible height over the rows.
    let c = ortho(Preset::Iso);
    let (_, d1) = ray_from_pixel(&c, VP, [0.0, 0.0]);
    let (_, d2) = ray_from_pixel(&c, VP, [800.0, 600.0]);
    assert!((d1 - d2).norm() < 1e-9);
    let mpp = metres_per_pixel(&c, VP, &Point3::new(0.1, 0.2, 0.3)).unwrap();
    assert!((mpp - 2.0 / 600.0).abs() < 1e-9);
}

#[test]
fn picking_finds_each_arrow_plane_and_ring_and_nothing_far_away() {
    for c in cameras() {
        for space in [GizmoSpace::Local, GizmoSpace::World] {
            let g = gizmo(space);
            let pose = target();
            let (o, l) = (centre(&pose), arrow_len(&g, &c, &pose));
            let axes = g.axis_dirs(&pose);
            for i in 0..3 {
                let tip = arr(proj(&c, &(o + axes[i] * l * 0.97)));
                assert_eq!(
                    g.pick(&c, VP, &pose, tip),
                    Some(Handle::Axis(i)),
                    "{c:?} {space:?} tip {i}"
                );
                let mid = (PLANE_INNER + PLANE_OUTER) * 0.5 * l;
                let (a, b) = (axes[(i + 1) % 3], axes[(i + 2) % 3]);
                let sq = arr(proj(&c, &(o + (a + b) * mid)));
                assert_eq!(
                    g.pick(&c, VP, &pose, sq),
                    Some(Handle::Plane(i)),
                    "{c:?} {space:?} plane {i}"
                );
                // The ring on the side away from the arrows of its plane, found on its front half.
                let found = (0..12).any(|k| {
                    let phi = std::f64::consts::PI * (1.0 + k as f64 / 24.0);
                    let v = (a * phi.cos() + b * phi.sin()) * RING_RADIUS * l;
                    g.pick(&c, VP, &pose, arr(proj(&c, &(o + v)))) == Some(Handle::Ring(i))
                });
                assert!(found, "{c:?} {space:?} ring {i}");
            }
            // Far away and at the viewport's corners: nothing.
            let cp = proj(&c, &o);
            for far in [
                [0.0, 0.0],
                [799.0, 599.0],
                arr(cp + Vector2::new(200.0, 0.0)),
                arr(cp + Vector2::new(0.0, -180.0)),
            ] {
                assert_eq!(g.pick(&c, VP, &pose, far), None, "{far:?}");
            }
        }
    }
}

#[test]
fn every_point_of_a_visible_ring_picks_something() {
    let (c, g, pose) = (persp(Preset::Iso), gizmo(GizmoSpace::Local), target());
    let (o, l) = (centre(&pose), arrow_len(&g, &c, &pose));
    let axes = g.axis_dirs(&pose);
    for i in 0..3 {
        for k in 0..72 {
            let phi = std::f64::consts::TAU * k as f64 / 72.0;
            let v =
                (axes[(i + 1) % 3] * phi.cos() + axes[(i + 2) % 3] * phi.sin()) * RING_RADIUS * l;
            assert!(
                g.pick(&c, VP, &pose, arr(proj(&c, &(o + v)))).is_some(),
                "ring {i} at {k}"
            );
        }
    }
}

#[test]
fn dragging_an_arrow_moves_along_its_axis_by_the_pointer_motion() {
    let c = ortho(Preset::Iso);
    for space in [GizmoSpace::Local, GizmoSpace::World] {
        let g = gizmo(space);
        let pose = target();
        let o = centre(&pose);
        for (i, &a) in g.axis_dirs(&pose).iter().enumerate() {
            // Pixels per metre along the axis (orthographic: exact and constant).
            let q = proj(&c, &(o + a)) - proj(&c, &o);
            let start = proj(&c, &(o + a * 0.2));
            for n in [-37.0, 25.0, 120.0] {
                let now = start + q.normalize() * n;
                let p = g.drag_pose(&c, VP, &pose, Handle::Axis(i), arr(start), arr(now));
                let d = p.translation.vector - pose.translation.vector;
                let expect = a * (n / q.norm());
                assert!(
                    (d - expect).norm() < 1e-5,
                    "{space:?} {i} {n}: {d} vs {expect}"
                );
                assert!((p.rotation.matrix() - pose.rotation.matrix()).norm() < 1e-12);
                // Perpendicular motion does not move the target.
                let side = start + Vector2::new(-q.y, q.x).normalize() * n;
                let p = g.drag_pose(&c, VP, &pose, Handle::Axis(i), arr(start), arr(side));
                assert!(
                    (p.translation.vector - pose.translation.vector).norm() < 1e-5,
                    "{space:?} {i} {n}"
                );
            }
        }
    }
    // Perspective: the grabbed point of the arrow stays under the pointer along the axis line.
    let c = persp(Preset::Iso);
    let g = gizmo(GizmoSpace::Local);
    let pose = target();
    let o = centre(&pose);
    for (i, &a) in g.axis_dirs(&pose).iter().enumerate() {
        let grab = o + a * 0.05;
        let (s, far) = (proj(&c, &grab), proj(&c, &(o + a * 0.1)));
        let now = s + (far - s).normalize() * 60.0;
        let p = g.drag_pose(&c, VP, &pose, Handle::Axis(i), arr(s), arr(now));
        let moved = p * (pose.inverse() * grab);
        assert!((proj(&c, &moved) - now).norm() < 0.05, "{i}");
        let d = p.translation.vector - pose.translation.vector;
        assert!(d.cross(&a).norm() < 1e-9 && d.dot(&a) > 0.0, "{i}");
    }
}

#[test]
fn plane_drag_stays_in_the_plane_and_follows_the_pointer() {
    for c in cameras() {
        for space in [GizmoSpace::Local, GizmoSpace::World] {
            let g = gizmo(space);
            let pose = target();
            let o = centre(&pose);
            let axes = g.axis_dirs(&pose);
            for i in 0..3 {
                let (a, b) = (axes[(i + 1) % 3], axes[(i + 2) % 3]);
                let grab = o + (a + b) * 0.03;
                let s = proj(&c, &grab);
                let now = s + Vector2::new(33.0, -21.0);
                let p = g.drag_pose(&c, VP, &pose, Handle::Plane(i), arr(s), arr(now));
                let d = p.translation.vector - pose.translation.vector;
                assert!(d.norm() > 1e-3, "{i} moved");
                assert!(d.dot(&axes[i]).abs() < 1e-9, "{c:?} {space:?} {i}: {d}");
                // The grabbed point of the plane stays under the pointer.
                let moved = grab + d;
                assert!(
                    (proj(&c, &moved) - now).norm() < 0.05,
                    "{c:?} {space:?} {i}"
                );
            }
        }
    }
}

#[test]
fn a_quarter_turn_on_a_ring_rotates_ninety_degrees_with_the_right_sign() {
    let start = Pose::from_parts(Translation3::new(0.2, 0.0, 0.4), Rotation3::identity());
    let quarter = |c: &Camera, g: &Gizmo, pose: &Pose, axis: usize| {
        let cp = proj(c, &centre(pose));
        let from = cp + Vector2::new(50.0, 0.0);
        let to = cp + Vector2::new(0.0, -50.0); // right -> up: counter-clockwise on screen
        g.drag_pose(c, VP, pose, Handle::Ring(axis), arr(from), arr(to))
    };
    let close = |a: &Rotation3<f64>, b: &Rotation3<f64>| (a.matrix() - b.matrix()).norm() < 1e-6;
    for c in [ortho(Preset::Top), persp(Preset::Top)] {
        // Seen from above (+z towards the camera) counter-clockwise is +90 deg about z: x -> y.
        let p = quarter(&c, &gizmo(GizmoSpace::World), &start, 2);
        assert!(close(
            &p.rotation,
            &Rotation3::from_axis_angle(&Vector3::z_axis(), FRAC_PI_2)
        ));
        assert_eq!(p.translation, start.translation);
    }
    for c in [ortho(Preset::Front), persp(Preset::Front)] {
        // Seen from -y (+y away from the camera), counter-clockwise takes x to z: -90 deg about y.
        let p = quarter(&c, &gizmo(GizmoSpace::World), &start, 1);
        assert!(close(
            &p.rotation,
            &Rotation3::from_axis_angle(&Vector3::y_axis(), -FRAC_PI_2)
        ));
        assert!((p.rotation * Vector3::x() - Vector3::z()).norm() < 1e-6);
    }
    // Local space: about the target's own axis, r' = r * rot(e_i, +-90 deg).
    let c = persp(Preset::Top);
    let r0 = Rotation3::from_axis_angle(&Vector3::y_axis(), 0.4);
    let tilted = Pose::from_parts(start.translation, r0);
    let p = quarter(&c, &gizmo(GizmoSpace::Local), &tilted, 2);
    // The local z still points up enough to face the camera: counter-clockwise is positive.
    assert!(close(
        &p.rotation,
        &(r0 * Rotation3::from_axis_angle(&Vector3::z_axis(), FRAC_PI_2))
    ));
    let w = quarter(&c, &gizmo(GizmoSpace::World), &tilted, 2);
    assert!(close(
        &w.rotation,
        &(Rotation3::from_axis_angle(&Vector3::z_axis(), FRAC_PI_2) * r0)
    ));
}

#[test]
fn degenerate_views_give_finite_poses() {
    let pose = Pose::from_parts(Translation3::new(0.2, 0.0, 0.4), Rotation3::identity());
    let handles = (0..3).flat_map(|i| [Handle::Axis(i), Handle::Plane(i), Handle::Ring(i)]);
    for c in [
        ortho(Preset::Top),
        persp(Preset::Top),
        ortho(Preset::Side),
        persp(Preset::Front),
    ] {
        let g = gizmo(GizmoSpace::World);
        let cp = proj(&c, &centre(&pose));
        for h in handles.clone() {
            for (s, n) in [
                (cp, cp),
                (cp, cp + Vector2::new(0.0, -40.0)),
                (
                    cp + Vector2::new(3.0, 0.0),
                    cp + Vector2::new(-250.0, 180.0),
                ),
                (cp, Vector2::new(1e6, -1e6)),
                (Vector2::new(0.0, 0.0), Vector2::new(800.0, 600.0)),
            ] {
                let p = g.drag_pose(&c, VP, &pose, h, arr(s), arr(n));
                assert_finite(&p);
                let moved = (p.translation.vector - pose.translation.vector).norm();
                assert!(moved < 100.0, "{h:?} moved {moved}");
            }
        }
    }
    // z pointing at the camera: dragging the z arrow falls back to pixels times metres per pixel,
    // upwards on screen along the (tiny) projection of +z or screen up.
    let c = ortho(Preset::Top);
    let g = gizmo(GizmoSpace::World);
    let cp = proj(&c, &centre(&pose));
    let p = g.drag_pose(
        &c,
        VP,
        &pose,
        Handle::Axis(2),
        arr(cp),
        arr(cp + Vector2::new(0.0, -30.0)),
    );
    let dz = p.translation.z - pose.translation.z;
    assert!((dz.abs() - 30.0 * 2.0 / 600.0).abs() < 1e-6, "{dz}");
    // A target behind the camera, or a bad handle index: the start pose.
    let c = persp(Preset::Top);
    let behind = Pose::translation(0.2, 0.0, 40.0);
    let p = g.drag_pose(&c, VP, &behind, Handle::Axis(0), [0.0, 0.0], [100.0, 100.0]);
    assert_eq!(p, behind);
    assert_eq!(g.pick(&c, VP, &behind, [400.0, 300.0]), None);
    let p = g.drag_pose(&c, VP, &pose, Handle::Ring(7), [0.0, 0.0], [100.0, 100.0]);
    assert_eq!(p, pose);
}

/// One egui frame (no GPU) with the gizmo over an 800 x 600 viewport filling the screen: the
/// gizmo's output and the number of shapes painted.
fn frame(
    ctx: &egui::Context,
    g: &mut Gizmo,
    c: &Camera,
    pose: &Pose,
    events: Vec<egui::Event>,
) -> (GizmoOutput, usize) {
    let input = egui::RawInput {
        screen_rect: Some(egui::Rect::from_min_size(
            egui::Pos2::ZERO,
            egui::vec2(800.0, 600.0),
        )),
        events,
        ..Default::default()
    };
    let mut out = GizmoOutput::default();
    let full = ctx.run_ui(input, |ui| {
        let rect = ui.max_rect();
        let response = ui.allocate_rect(rect, egui::Sense::click_and_drag());
        out = g.ui(ui, &response, rect, c, pose, true);
    });
    let shapes = full.shapes.len();
    full.drop_without_applying_deltas();
    (out, shapes)
}

fn moved(p: Vector2<f64>) -> egui::Event {
    egui::Event::PointerMoved(egui::pos2(p.x as f32, p.y as f32))
}

fn button(p: Vector2<f64>, pressed: bool) -> egui::Event {
    egui::Event::PointerButton {
        pos: egui::pos2(p.x as f32, p.y as f32),
        button: egui::PointerButton::Primary,
        pressed,
        modifiers: Default::default(),
    }
}

#[test]
fn ui_hovers_drags_and_releases_without_a_gpu() {
    let ctx = egui::Context::default();
    let (c, pose) = (persp(Preset::Iso), target());
    let mut g = gizmo(GizmoSpace::Local);
    let (o, a) = (centre(&pose), g.axis_dirs(&pose)[0]);
    let tip = proj(&c, &(o + a * arrow_len(&g, &c, &pose) * 0.9));
    let along = (proj(&c, &(o + a * 0.1)) - proj(&c, &o)).normalize();
    let empty = Vector2::new(20.0, 20.0);
    let (out, _) = frame(&ctx, &mut g, &c, &pose, vec![moved(empty)]);
    assert!(!out.active);
    let (out, shapes) = frame(&ctx, &mut g, &c, &pose, vec![moved(tip)]);
    assert!(out.active && out.new_pose.is_none());
    assert_eq!(g.hovered(), Some(Handle::Axis(0)));
    assert!(shapes > 20, "the gizmo is painted: {shapes} shapes");
    // Press on the arrow: the drag starts at once; moving returns drag_pose's pose.
    let (out, _) = frame(&ctx, &mut g, &c, &pose, vec![button(tip, true)]);
    assert!(out.active && g.dragging() == Some(Handle::Axis(0)));
    let now = tip + along * 40.0;
    let (out, _) = frame(&ctx, &mut g, &c, &pose, vec![moved(now)]);
    let expect = g.drag_pose(&c, VP, &pose, Handle::Axis(0), arr(tip), arr(now));
    let got = out.new_pose.expect("dragging");
    assert!((got.translation.vector - expect.translation.vector).norm() < 1e-9);
    assert!((got.translation.vector - pose.translation.vector).dot(&a) > 0.0);
    let (out, _) = frame(&ctx, &mut g, &c, &got, vec![button(now, false)]);
    assert!(out.released && g.dragging().is_none());
    // Escape cancels a drag with the start pose.
    frame(&ctx, &mut g, &c, &pose, vec![moved(tip)]);
    frame(&ctx, &mut g, &c, &pose, vec![button(tip, true)]);
    frame(&ctx, &mut g, &c, &pose, vec![moved(now)]);
    let key = egui::Event::Key {
        key: egui::Key::Escape,
        physical_key: None,
        pressed: true,
        repeat: false,
        modifiers: Default::default(),
    };
    let (out, _) = frame(&ctx, &mut g, &c, &pose, vec![key]);
    assert!(out.released && out.new_pose == Some(pose) && g.dragging().is_none());
    frame(&ctx, &mut g, &c, &pose, vec![button(now, false)]);
    // A drag begun on empty space (an orbit) passing over the gizmo does not activate it.
    frame(&ctx, &mut g, &c, &pose, vec![moved(empty)]);
    frame(&ctx, &mut g, &c, &pose, vec![button(empty, true)]);
    let (out, _) = frame(&ctx, &mut g, &c, &pose, vec![moved(tip)]);
    assert!(!out.active && out.new_pose.is_none() && g.dragging().is_none());
    let (out, _) = frame(&ctx, &mut g, &c, &pose, vec![button(tip, false)]);
    assert!(!out.released);
}
