//! The reachability overlay and base placement in the app (issue 49), driven like a user:
//! the Show menu turns the overlay on and the map is computed; the slice slider changes which
//! voxels are drawn; pointing at a voxel of the slice and clicking it pins it; clicking one of its
//! directions in the panel moves the target there with every posture's ghost; a tasks file is
//! placed and the base moved to the best placement.
//!
//! Checked against what the test computes itself: the sample poses from the formulas
//! (Fibonacci directions, rolls, voxel centres), the index as the share of a voxel's samples
//! reached, the map against the library's own computation with the same settings, the ghosts by
//! forward kinematics onto the sample pose, the placement by solving each task at the new base.

use armlab::app::AppUi;
use armlab::app::action::Action;
use armlab::app::reachability::ReachabilityAction;
use armlab::app::state::AppState;
use armlab::app::state::reachability::MapSettings;
use armlab::app::viewport::scene_of;
use armlab::kinematics::Pose;
use armlab::reachability::{
    MapControl, MapOptions, ReachabilityMap, compute_reachability, solutions_at,
};
use armlab::scene::Scene;
use armlab::scene::reachability::{SLICE_ALPHA, index_color};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use nalgebra::{Matrix3, Vector3};

/// Small enough for a debug build: 20 cm voxels, 16 directions, 2 rolls.
const SMALL: MapSettings = MapSettings {
    voxel_m: 0.2,
    directions: 16,
    rolls: 2,
};

fn harness(app: AppUi) -> Harness<'static, AppUi> {
    // A computation finishing between two frames changes the panel (and starts egui's
    // animations of the widgets that appear): more frames to settle than the default 4.
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .with_max_steps(16)
        .build_ui_state(|ui, app: &mut AppUi| app.show(ui, None), app);
    h.run();
    h
}

/// The Puma with the overlay's settings at [`SMALL`].
fn puma() -> AppUi {
    let mut app = AppUi::new(AppState::from_spec("puma560").unwrap());
    app.ik.reach.map.settings = SMALL;
    app
}

/// Waits for the map being computed, then lays the window out again.
fn wait_for_map(h: &mut Harness<'static, AppUi>) {
    let app = h.state_mut();
    app.ik.reach.map.wait(&app.state, 0);
    h.run();
    assert!(h.state().ik.reach.map.result().is_some(), "a map came");
}

/// The 3D scene the app builds now (the arm, its ghosts and every overlay).
fn scene(h: &mut Harness<'static, AppUi>) -> Scene {
    let app = h.state_mut();
    scene_of(&mut app.state, (&app.tabs, &mut app.ik), 0, false)
}

/// The Fibonacci direction i of n.
fn fibonacci(i: usize, n: usize) -> Vector3<f64> {
    let z = 1.0 - (2 * i + 1) as f64 / n as f64;
    let rho = (1.0 - z * z).sqrt();
    let phi = i as f64 * std::f64::consts::PI * (3.0 - 5f64.sqrt());
    Vector3::new(rho * phi.cos(), rho * phi.sin(), z)
}

/// The sample pose: tool z along direction i of n, x the unit vector of e - (e.d) d
/// turned by roll j of r about d, the tool point at voxel (i, j, k)'s centre.
fn sample_pose(
    m: &ReachabilityMap,
    ijk: [usize; 3],
    (i, n): (usize, usize),
    (j, r): (usize, usize),
) -> Pose {
    let d = fibonacci(i, n);
    let e = if d.x.abs() > 0.9 {
        Vector3::y()
    } else {
        Vector3::x()
    };
    let x0 = (e - d * e.dot(&d)).normalize();
    let angle = 2.0 * std::f64::consts::PI * j as f64 / r as f64;
    let x = x0 * angle.cos() + d.cross(&x0) * angle.sin();
    let rot = Matrix3::from_columns(&[x, d.cross(&x), d]);
    let c = Vector3::from_fn(|a, _| m.grid.origin[a] + m.grid.voxel_m * ijk[a] as f64);
    Pose::from_parts(
        nalgebra::Translation3::from(c),
        nalgebra::Rotation3::from_matrix_unchecked(rot),
    )
}

/// The share of voxel v's samples reached, counted here.
fn share(m: &ReachabilityMap, v: usize) -> f64 {
    let n = m.directions.len() * m.rolls.len();
    m.reachable[v * n..(v + 1) * n]
        .iter()
        .filter(|&&b| b)
        .count() as f64
        / n as f64
}

/// The voxel ijk of flat index v, counted here (C order, k fastest).
fn ijk(m: &ReachabilityMap, v: usize) -> [usize; 3] {
    let [_, ny, nz] = m.grid.dims;
    [v / (ny * nz), (v / nz) % ny, v % nz]
}

/// The squares the scene draws for a slice across `axis` of voxels `voxel_m` wide: their voxel
/// (by their centre) and colour.
fn slice_squares(scene: &Scene, m: &ReachabilityMap, axis: usize) -> Vec<([usize; 3], [f32; 4])> {
    let v = m.grid.voxel_m as f32;
    scene
        .meshes
        .iter()
        .filter(|s| {
            s.shape == armlab::scene::Shape::Cube
                && (0..3).all(|a| {
                    let want = if a == axis { 0.1 * v } else { 0.9 * v };
                    (s.world_from_unit[a][a] - want).abs() < 1e-5
                })
        })
        .map(|s| {
            let t = s.world_from_unit[3];
            let ijk = [0, 1, 2].map(|a| {
                let k = (t[a] as f64 - m.grid.origin[a]) / m.grid.voxel_m;
                assert!(
                    (k - k.round()).abs() < 1e-4,
                    "a square off the voxel centres"
                );
                k.round() as usize
            });
            (ijk, s.color)
        })
        .collect()
}

/// The voxels of layer `layer` across `axis` with a reached sample, counted here, with their
/// colour.
fn expected_slice(m: &ReachabilityMap, axis: usize, layer: usize) -> Vec<([usize; 3], [f32; 4])> {
    (0..m.reachable.len() / (m.directions.len() * m.rolls.len()))
        .filter(|&v| ijk(m, v)[axis] == layer && share(m, v) > 0.0)
        .map(|v| {
            let mut c = index_color(share(m, v));
            c[3] = SLICE_ALPHA;
            (ijk(m, v), c)
        })
        .collect()
}

fn sorted(mut v: Vec<([usize; 3], [f32; 4])>) -> Vec<([usize; 3], [f32; 4])> {
    v.sort_by_key(|(k, _)| *k);
    v
}

#[test]
fn turning_the_overlay_on_computes_the_map_and_draws_its_slice() {
    // Seen from the front (along y), the first slice is across y: face on.
    let mut app = puma();
    app.apply(Action::CameraPreset(armlab::camera::Preset::Front));
    let mut h = harness(app);
    h.get_by_label("Show").click();
    h.run();
    h.get_by_label("Reachability").click();
    h.run();
    assert!(h.state().state.display.reachability);
    wait_for_map(&mut h);
    // The map is the library's for the panel's settings, without a cell (none is open).
    let robot = h.state().state.robot().clone();
    let options = MapOptions {
        voxel_m: SMALL.voxel_m,
        directions: SMALL.directions,
        rolls: SMALL.rolls,
        ..MapOptions::default()
    };
    let own = compute_reachability(&robot, &options, None, MapControl::default()).unwrap();
    let r = h.state().ik.reach.map.result().unwrap();
    assert_eq!(r.map.grid, own.grid);
    assert_eq!(r.map.reachable, own.reachable);
    assert!(!r.map.collisions && r.world.is_none());
    // The first slice is across y through the base (y = 0): the layer nearest to it.
    assert_eq!(h.state().ik.reach.map.slice.unwrap().axis, 1);
    let layer = (-own.grid.origin[1] / own.grid.voxel_m).round() as usize;
    let expected = expected_slice(&own, 1, layer);
    assert!(
        expected.len() > 5,
        "the slice through the base reaches voxels"
    );
    let drawn = slice_squares(&scene(&mut h), &own, 1);
    assert_eq!(sorted(drawn), sorted(expected));
    // The panel says what the map is.
    assert!(
        h.query_by_label_contains("16 directions x 2 rolls")
            .is_some(),
        "the panel describes the map"
    );
    // Off: nothing of it is drawn.
    h.get_by_label("Show").click();
    h.run();
    h.get_by_role_and_label(egui::accesskit::Role::CheckBox, "Reachability")
        .click();
    h.run();
    assert!(!h.state().state.display.reachability);
    assert!(slice_squares(&scene(&mut h), &own, 1).is_empty());
}

#[test]
fn the_slice_slider_changes_which_voxels_are_drawn() {
    let mut app = puma();
    app.apply(Action::Reachability(ReachabilityAction::Show(true)));
    let mut h = harness(app);
    wait_for_map(&mut h);
    // Across z: a horizontal plane.
    h.get_by_label("slice across z").click();
    h.run();
    let m = h.state().ik.reach.map.result().unwrap().map.clone();
    let rail = h
        .get_by_role_and_label(egui::accesskit::Role::Slider, "z of the slice [m]")
        .rect();
    let mut seen = Vec::new();
    for f in [0.05, 0.5, 0.7, 0.95] {
        let at = egui::pos2(rail.left() + f * rail.width(), rail.center().y);
        h.drag_at(at);
        h.run();
        h.drop_at(at);
        h.run();
        let slice = h.state().ik.reach.map.slice.unwrap();
        assert_eq!(slice.axis, 2);
        let layer = ((slice.at_m - m.grid.origin[2]) / m.grid.voxel_m).round() as usize;
        let drawn = sorted(slice_squares(&scene(&mut h), &m, 2));
        assert_eq!(drawn, sorted(expected_slice(&m, 2, layer)), "layer {layer}");
        assert!(drawn.iter().all(|(k, _)| k[2] == layer));
        seen.push((layer, drawn));
    }
    // The slider scrubbed through different layers, drawn differently.
    assert!(
        seen.first().unwrap().0 < seen.last().unwrap().0,
        "{:?}",
        seen.iter().map(|s| s.0).collect::<Vec<_>>()
    );
    assert!(seen.windows(2).any(|w| w[0].1 != w[1].1));
}

/// Where world point `p` is in the window (points), if in front of the camera.
fn on_screen(app: &AppUi, p: [f64; 3]) -> Option<egui::Pos2> {
    let v = &app.tabs.view3d;
    let [w, hp] = v.viewport_px;
    let ppp = w as f32 / v.viewport_rect.width();
    let px = v.camera.project(
        &nalgebra::Point3::new(p[0] as f32, p[1] as f32, p[2] as f32),
        w,
        hp,
    )?;
    Some(v.viewport_rect.min + egui::vec2(px[0], px[1]) / ppp)
}

/// Presses and releases the primary button at `at`.
fn click_at(h: &mut Harness<'static, AppUi>, at: egui::Pos2) {
    h.hover_at(at);
    h.run();
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton {
            pos: at,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: egui::Modifiers::NONE,
        });
        h.run();
    }
}

/// A voxel of the slice (flat index) whose centre shows in the 3D view far from the target's
/// gizmo and from every ghost arm's joints, and where it shows.
fn clickable_voxel(h: &Harness<'static, AppUi>) -> (usize, egui::Pos2) {
    let app = h.state();
    let r = app.ik.reach.map.result().unwrap();
    let rect = app.tabs.view3d.viewport_rect.shrink(30.0);
    let robot = app.state.robot();
    let target = app
        .state
        .target(0)
        .unwrap()
        .world_from_tool
        .translation
        .vector;
    let gizmo = on_screen(app, target.into()).unwrap();
    let joints: Vec<egui::Pos2> = (app.state.ghosts(0).iter())
        .flat_map(|g| robot.fk_frames(&g.q).unwrap())
        .filter_map(|f| on_screen(app, f.translation.vector.into()))
        .collect();
    app.ik
        .reach
        .map
        .slice_voxels()
        .into_iter()
        .filter_map(|v| Some((v, on_screen(app, r.map.grid.centre(ijk(&r.map, v)))?)))
        .find(|(_, p)| {
            rect.contains(*p)
                && (*p - gizmo).length() > 170.0
                && joints.iter().all(|j| (*j - *p).length() > 60.0)
        })
        .expect("a voxel of the slice clear of the gizmo and the ghosts")
}

#[test]
fn clicking_a_direction_moves_the_target_there_with_every_posture() {
    // Seen from the front: the slice across y face on, the whole reach framed.
    let mut app = puma();
    app.apply(Action::CameraPreset(armlab::camera::Preset::Front));
    app.apply(Action::Reachability(ReachabilityAction::Show(true)));
    let mut h = harness(app);
    wait_for_map(&mut h);
    // Pointing at a voxel of the slice shows it; clicking pins it.
    let (v, at) = clickable_voxel(&h);
    h.hover_at(at);
    h.run();
    assert_eq!(
        h.state().ik.reach.map.hovered,
        Some(v),
        "the voxel under the pointer"
    );
    click_at(&mut h, at);
    assert_eq!(
        h.state().ik.reach.map.pinned,
        Some(v),
        "the voxel clicked is pinned"
    );
    // Its directions in the panel: click one that some roll reaches.
    h.run();
    let m = h.state().ik.reach.map.result().unwrap().map.clone();
    let (n, rolls) = (m.directions.len(), m.rolls.len());
    let reached = |d: usize, j: usize| m.reachable[(v * n + d) * rolls + j];
    let dots = h.state().ik.reach.dots.clone();
    assert_eq!(dots.len(), n, "a dot per direction");
    let (d, dot) = dots
        .iter()
        .copied()
        .filter(|&(d, _)| (0..rolls).any(|j| reached(d, j)))
        .find(|&(d, p)| dots.iter().all(|&(o, q)| o == d || (q - p).length() > 6.0))
        .expect("a reached direction with a dot of its own");
    click_at(&mut h, dot);
    // The target is on the sample (every roll shown: the first roll that reaches it).
    let roll = (0..rolls).find(|&j| reached(d, j)).unwrap();
    let pose = sample_pose(&m, ijk(&m, v), (d, n), (roll, rolls));
    let app = h.state();
    let target = app.state.target(0).unwrap().world_from_tool;
    let gap = (target.to_homogeneous() - pose.to_homogeneous()).amax();
    assert!(gap < 1e-9, "target {gap} off the sample");
    assert!(app.state.display.ghosts, "every posture shown");
    // Every ghost's q puts the tool on the sample, and those within the limits are the
    // solutions the map's computation finds there.
    let robot = app.state.robot();
    let ghosts = app.state.ghosts(0);
    for g in &ghosts {
        let t = robot.fk(&g.q).unwrap();
        let gap = (t.to_homogeneous() - pose.to_homogeneous()).amax();
        assert!(gap < 1e-9, "a ghost {gap} off the sample: {:?}", g.posture);
    }
    let r = app.ik.reach.map.result().unwrap();
    let solutions = solutions_at(robot, &r.map, &r.options, None, &pose);
    let usable = ghosts.iter().filter(|g| g.within_limits).count();
    assert_eq!(
        usable,
        solutions.len(),
        "ghosts within the limits against solutions_at"
    );
    assert!(!solutions.is_empty());
    let bits = solutions.iter().fold(0, |b, s| b | s.mask);
    assert_eq!(
        bits,
        m.postures[(v * n + d) * rolls + roll],
        "the map's posture bits"
    );
    let aimed = app.ik.reach.map.aimed.as_ref().unwrap();
    assert_eq!((aimed.voxel, aimed.direction, aimed.roll), (v, d, roll));
    assert_eq!(aimed.solutions.len(), solutions.len());
}

/// Whether a world point (m) is inside the box `obstacle`, read here from its size and pose.
fn inside_box(obstacle: &armlab::collision::Obstacle) -> impl Fn([f64; 3]) -> bool + use<> {
    let armlab::collision::ObstacleShape::Box { size } = obstacle.shape else {
        panic!("a box")
    };
    let box_from_world = obstacle.frame_from_obstacle().inverse();
    move |c: [f64; 3]| {
        let p = box_from_world * nalgebra::Point3::from(c);
        (0..3).all(|a| p[a].abs() < 0.5 * size[a])
    }
}

#[test]
fn the_cells_obstacles_take_their_samples_out_of_the_map() {
    use armlab::app::cell::{CellAction, ObstacleKind};
    let mut app = AppUi::new(AppState::from_spec("puma560").unwrap());
    app.ik.reach.map.settings = MapSettings {
        voxel_m: 0.1,
        directions: 8,
        rolls: 1,
    };
    app.apply(Action::Cell(CellAction::Add(ObstacleKind::Table)));
    assert!(app.state.collisions_on());
    app.apply(Action::Reachability(ReachabilityAction::Show(true)));
    let mut h = harness(app);
    wait_for_map(&mut h);
    let app = h.state();
    let r = app.ik.reach.map.result().unwrap();
    assert!(
        r.map.collisions && r.world.is_some(),
        "computed in the cell"
    );
    // No voxel centre inside the table is reached, while without the cell some are.
    let inside = inside_box(&app.state.cell_scene().unwrap().obstacles[0]);
    let options = r.options;
    let free =
        compute_reachability(app.state.robot(), &options, None, MapControl::default()).unwrap();
    assert_eq!(free.grid, r.map.grid);
    let in_table: Vec<usize> = (0..r.map.grid.len())
        .filter(|&v| inside(r.map.grid.centre(ijk(&r.map, v))))
        .collect();
    assert!(
        in_table.iter().any(|&v| share(&free, v) > 0.0),
        "the table is within reach"
    );
    assert!(
        in_table.iter().all(|&v| share(&r.map, v) == 0.0),
        "nothing inside the table"
    );
    // The cell only takes samples away.
    assert!(
        r.map
            .reachable
            .iter()
            .zip(&free.reachable)
            .all(|(&c, &f)| !c || f)
    );
    assert!(r.map.reached_count() < free.reached_count());
    // At a reached sample, the ghosts within the limits and free of the table are the
    // solutions the map's computation finds there.
    let n = r.map.per_voxel();
    // A sample where the table takes a posture away (its ghost red), if there is one.
    let s = (0..r.map.reachable.len())
        .find(|&s| r.map.reachable[s] && r.map.postures[s] != free.postures[s])
        .or_else(|| r.map.reachable.iter().position(|&b| b))
        .unwrap();
    let (v, d) = (s / n, s % n);
    h.state_mut()
        .apply(Action::Reachability(ReachabilityAction::Aim {
            voxel: v,
            direction: d,
            roll: 0,
        }));
    let app = h.state();
    let r = app.ik.reach.map.result().unwrap();
    let pose = sample_pose(&r.map, ijk(&r.map, v), (d, 8), (0, 1));
    let solutions = solutions_at(
        app.state.robot(),
        &r.map,
        &r.options,
        r.world.as_ref(),
        &pose,
    );
    let ghosts = app.state.ghosts(0);
    let free_ghosts = ghosts
        .iter()
        .filter(|g| g.within_limits && !g.collision.as_ref().is_some_and(|c| c.in_collision))
        .count();
    assert_eq!(free_ghosts, solutions.len());
    assert!(!solutions.is_empty());
}

/// Three tasks the Puma reaches from where it stands (the tool at three configurations), as a
/// tasks file a user writes (name, position in m, roll-pitch-yaw in degrees), and their poses.
fn three_tasks(robot: &armlab::kinematics::Robot) -> (String, Vec<Pose>) {
    let mut csv = String::from("name, x, y, z, roll_deg, pitch_deg, yaw_deg\n");
    let mut tasks = Vec::new();
    for (k, q) in [
        [0.3, 0.5, -1.2, 0.4, 0.8, -0.6],
        [-0.4, 0.2, -0.5, 0.0, 0.9, 0.3],
        [0.1, 0.7, -0.9, -0.3, 0.5, 0.2],
    ]
    .iter()
    .enumerate()
    {
        let t = robot.fk(q).unwrap();
        let p = t.translation.vector;
        let (roll, pitch, yaw) = t.rotation.euler_angles();
        csv += &format!(
            "t{k}, {}, {}, {}, {}, {}, {}\n",
            p.x,
            p.y,
            p.z,
            roll.to_degrees(),
            pitch.to_degrees(),
            yaw.to_degrees()
        );
        tasks.push(t);
    }
    (csv, tasks)
}

#[test]
fn a_tasks_file_is_placed_and_the_base_moved_to_the_best_placement() {
    use armlab::app::state::placement::PlaceSettings;
    let mut app = puma();
    app.apply(Action::Reachability(ReachabilityAction::Show(true)));
    let (csv, tasks) = three_tasks(app.state.robot());
    let path = std::env::temp_dir().join(format!("armlab-tasks-{}.csv", std::process::id()));
    std::fs::write(&path, csv).unwrap();
    app.ik.reach.tasks_path = path.to_string_lossy().into_owned();
    app.ik.reach.placement.settings = Some(PlaceSettings {
        area: [-0.3, 0.3, -0.3, 0.3],
        step: 0.1,
        yaws: 8,
    });
    let mut h = harness(app);
    wait_for_map(&mut h);
    h.get_by_label("Open tasks").click();
    h.run();
    assert_eq!(h.state().ik.reach.placement.tasks.len(), 3);
    h.get_by_label("Place the base").click();
    h.run();
    h.state_mut().ik.reach.placement.wait();
    h.run();
    let p = h.state().ik.reach.placement.result().expect("a placement");
    let (nx, ny, nk) = (p.map.grid.x.len(), p.map.grid.y.len(), p.map.grid.yaw.len());
    assert_eq!((nx, ny, nk), (7, 7, 8));
    // The heat map: a square on the floor at every position some yaw of which reaches a task.
    let best_of = |i: usize, j: usize| (0..nk).map(|k| p.map.reached[(i * ny + j) * nk + k]).max();
    let reaching = (0..nx)
        .flat_map(|i| (0..ny).map(move |j| (i, j)))
        .filter(|&(i, j)| best_of(i, j).unwrap() > 0)
        .count();
    let scene = scene(&mut h);
    let floor = scene
        .meshes
        .iter()
        .filter(|m| (m.world_from_unit[2][2] - 0.003).abs() < 1e-6)
        .count();
    assert_eq!(floor, reaching);
    // The base where it stands (x = y = 0, yaw 0) reaches all three: so does the best.
    let best = h.state().ik.reach.placement.result().unwrap().map.best[0].clone();
    assert_eq!(best.reached, 3);
    h.get_by_label("Move the base there").click();
    h.run();
    let app = h.state_mut();
    let b = app.state.robot().base;
    let want = armlab::reachability::floor_shift(best.detail.x, best.detail.y, best.detail.yaw);
    assert!((b.to_homogeneous() - want.to_homogeneous()).amax() < 1e-12);
    // Every task is reached by the app's own IK at the new base.
    for t in &tasks {
        let reach = app.state.set_target(0, *t).unwrap();
        assert!(
            reach.is_reached(),
            "a task not reached at the best placement: {reach:?}"
        );
    }
    app.apply(Action::Undo);
    assert_eq!(app.state.robot().base, Pose::identity());
    std::fs::remove_file(path).ok();
}

/// The overlay as the class sees it: the Puma's map at the fast settings, the slice across y
/// seen from the front, a voxel pinned with its sphere of directions, the target on one of them
/// with every posture's ghost. A golden image (looked at before it was accepted).
#[test]
fn the_overlay_in_the_window() {
    use crate::common::golden::assert_golden;
    use armlab::app::screenshot::{ScreenshotOptions, screenshot_with};
    let mut app = AppUi::new(AppState::from_spec("puma560").unwrap());
    app.apply(Action::CameraPreset(armlab::camera::Preset::Front));
    app.apply(Action::Reachability(ReachabilityAction::Show(true)));
    app.ik.reach.map.wait(&app.state, 0);
    let r = app.ik.reach.map.result().unwrap();
    let m = &r.map;
    // The slice voxel at (0.4, 0, 0.3) m, and its first direction reached at roll 0.
    let v = m.grid.flat(m.grid.voxel_at([0.4, 0.0, 0.3]).unwrap());
    let d = (0..m.directions.len())
        .find(|&d| m.reachable[m.sample_index(v, d, 0)] && m.directions[d][2] < -0.3)
        .expect("a direction pointing down reached there");
    app.apply(Action::Reachability(ReachabilityAction::Aim {
        voxel: v,
        direction: d,
        roll: 0,
    }));
    app.state.clear_trails();
    let img = screenshot_with(&app, [1280, 800], &ScreenshotOptions::default()).unwrap();
    assert_golden("app_puma560_reachability", &img);
}
