//! The cell in the app: obstacles added from the Cell menu, moved by the gizmo and the panel's
//! drag values, drawn; a colliding ghost red and named in the 3D scene and in the solution
//! list; the status bar when the arm itself collides; scene files and lessons.
//!
//! Which posture collides is checked against distances computed here: points sampled along
//! the drawn stick figure's polyline (which the checker's capsules follow) against an
//! axis-aligned box, by the closed-form point-box distance.

use armlab::app::AppUi;
use armlab::app::cell::{self, ObstacleKind};
use armlab::app::state::{AppState, Ghost};
use armlab::app::viewport::{COLLISION_RED, build_scene};
use armlab::collision::{Obstacle, ObstacleShape};
use armlab::kinematics::Robot;
use armlab::kinematics::visual::{LINK_RADIUS_FRACTION, stick_body};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use nalgebra::Vector3;

fn harness(app: AppUi) -> Harness<'static, AppUi> {
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_ui_state(|ui, app: &mut AppUi| app.show(ui, None), app);
    h.run();
    h
}

/// Points every 5 mm along the drawn stick figure of `robot` at `q` (world, m).
fn stick_points(robot: &Robot, q: &[f64]) -> Vec<Vector3<f64>> {
    let frames = robot.fk_frames(q).unwrap();
    let mut out = Vec::new();
    for j in 0..robot.joints().len() {
        let body = stick_body(robot, &frames, q, j);
        for w in body.polyline.windows(2) {
            let n = ((w[1] - w[0]).norm() / 0.005).ceil().max(1.0) as usize;
            out.extend((0..=n).map(|k| w[0] + (w[1] - w[0]) * (k as f64 / n as f64)));
        }
    }
    out
}

/// Distance (m) from `p` to the axis-aligned box of full extents `size` centred at `c` (0
/// inside).
fn box_distance(p: &Vector3<f64>, c: &[f64; 3], size: &[f64; 3]) -> f64 {
    let d: Vector3<f64> = Vector3::from_fn(|k, _| ((p[k] - c[k]).abs() - size[k] / 2.0).max(0.0));
    d.norm()
}

/// Whether posture `q` surely hits (`Some(true)`) or surely misses (`Some(false)`) the box,
/// judged from the stick figure: a polyline point inside the box hits; every point farther than
/// the joints' bodies reach from the polyline (a revolute body: 1.9 link radii around, 0.035 L
/// along) misses; `None` in between.
fn sure_verdict(robot: &Robot, q: &[f64], c: &[f64; 3], size: &[f64; 3]) -> Option<bool> {
    let l = robot.longest_chain_length();
    let reach = ((1.9 * LINK_RADIUS_FRACTION * l).powi(2) + (0.035 * l).powi(2)).sqrt();
    let d = stick_points(robot, q)
        .iter()
        .map(|p| box_distance(p, c, size))
        .fold(f64::INFINITY, f64::min);
    if d == 0.0 {
        Some(true)
    } else if d > reach + 0.01 {
        Some(false)
    } else {
        None
    }
}

/// The Puma at `q`, the target on its tool (its postures listed), ghosts on.
fn puma_at(q: &[f64]) -> AppState {
    let mut state = AppState::from_spec("puma560").unwrap();
    state.set_q(q).unwrap();
    let tool = state.robot().fk(state.q()).unwrap();
    state.set_target(0, tool).unwrap();
    state.display.ghosts = true;
    state
}

/// The elbow (frame 2's origin, on the upper arm's end) of `robot` at `q` (world, m).
fn elbow(robot: &Robot, q: &[f64]) -> Vector3<f64> {
    robot.fk_frames(q).unwrap()[1].translation.vector
}

/// The Puma at the first of a few poses with an unselected posture within the limits whose
/// elbow is far from the arm (more than 0.25 m from every point of its stick figure): the
/// state, that posture's ghost and how far its elbow is.
fn puma_with_a_far_posture() -> (AppState, Ghost, f64) {
    let poses = [
        [0.3, 0.5, -1.2, 0.4, 0.8, -0.6],
        [0.0, -0.6, 0.4, 0.2, 0.7, 0.1],
        [0.5, -0.3, 0.2, 0.0, -0.9, 0.4],
        [0.0, 0.8, -0.2, 0.0, 0.5, 0.0],
        [0.2, 0.3, 0.6, 0.1, 0.6, 0.2],
    ];
    poses
        .iter()
        .find_map(|q| {
            let state = puma_at(q);
            let robot = state.robot();
            let arm = stick_points(robot, state.q());
            let (g, far) = state
                .ghosts(0)
                .into_iter()
                .filter(|g| !g.selected && g.within_limits)
                .map(|g| {
                    let e = elbow(robot, &g.q);
                    let d = arm
                        .iter()
                        .map(|p| (p - e).norm())
                        .fold(f64::INFINITY, f64::min);
                    (g, d)
                })
                .max_by(|a, b| a.1.total_cmp(&b.1))?;
            (far > 0.25).then_some((state, g, far))
        })
        .expect("a pose with a posture whose elbow is far from the arm")
}

/// The scene the app builds for `state`: the ghost at `ghost_q` has a red body at its elbow
/// (the arm's own elbow has none), `contact` is marked with a red dot inside the box (centre
/// `c`, extents `size`) and named, and no label repeats a line.
fn assert_drawn_red(
    state: &AppState,
    ghost_q: &[f64],
    contact: &armlab::collision::Contact,
    (c, size): (&[f64; 3], &[f64; 3]),
) {
    let robot = state.robot();
    let scene = build_scene(state, 0, false);
    let red = |m: &armlab::scene::MeshInstance| {
        m.color[..3] == COLLISION_RED[..3] && m.color[3] < 1.0 && m.color[3] > 0.0
    };
    let at = |m: &armlab::scene::MeshInstance, p: &Vector3<f64>| {
        let t = m.world_from_unit[3];
        (Vector3::new(t[0] as f64, t[1] as f64, t[2] as f64) - p).norm() < 1e-4
    };
    assert!(
        scene
            .meshes
            .iter()
            .any(|m| red(m) && at(m, &elbow(robot, ghost_q))),
        "no red body at the colliding ghost's elbow"
    );
    let own = elbow(robot, state.q());
    assert!(scene.meshes.iter().any(|m| at(m, &own)));
    assert!(!scene.meshes.iter().any(|m| red(m) && at(m, &own)));
    let inside = |p: [f32; 3]| {
        let p = Vector3::new(p[0] as f64, p[1] as f64, p[2] as f64);
        box_distance(&p, c, size) < 0.03
    };
    assert!(inside(contact.at.map(|v| v as f32)), "{:?}", contact.at);
    assert!(
        scene
            .dots
            .iter()
            .any(|d| d.color == COLLISION_RED && inside(d.p)),
        "no red dot at the contact"
    );
    let name = format!("{} hits box", contact.a);
    assert!(
        scene.labels.iter().any(|l| l.text.contains(&name)),
        "no label \"{name}\" in {:?}",
        scene.labels.iter().map(|l| &l.text).collect::<Vec<_>>()
    );
    // Postures hitting the box at one spot (the wrist flips share the elbow) name it once.
    for l in &scene.labels {
        let lines: Vec<&str> = l.text.lines().collect();
        let mut unique = lines.clone();
        unique.sort();
        unique.dedup();
        assert_eq!(lines.len(), unique.len(), "a repeated line: {:?}", l.text);
    }
}

/// A box put around the elbow of one posture (one the arm is far from): that ghost is red in
/// the scene the app builds, its contact is marked and named there, the solution list names
/// the pair, and every posture whose verdict is sure from the stick figure gets that verdict.
/// Then the arm takes the colliding posture: a warning says so at once, and the IK panel keeps
/// saying it in words, with the free solutions.
#[test]
fn a_colliding_ghost_is_red_and_named() {
    let (mut state, g, far) = puma_with_a_far_posture();
    let robot = state.robot().clone();
    let c: [f64; 3] = elbow(&robot, &g.q).into();
    let size = [0.1; 3];
    assert!(
        sure_verdict(&robot, state.q(), &c, &size) == Some(false),
        "the box around the elbow ({far} m from the arm) must miss the arm"
    );
    state
        .add_obstacle(Obstacle::cuboid("box", size, c))
        .unwrap();

    // Every posture: the checker agrees with every sure verdict; the chosen one surely hits.
    let result = state.target(0).unwrap().result.clone().unwrap();
    let reports = state.solution_collisions(0).to_vec();
    assert_eq!(reports.len(), result.solutions.len());
    let mut hit = None;
    for (i, (s, r)) in result.solutions.iter().zip(&reports).enumerate() {
        if let Some(sure) = sure_verdict(&robot, &s.q, &c, &size) {
            assert_eq!(r.in_collision, sure, "solution {}: {}", i + 1, r.summary());
        }
        if s.q == g.q {
            assert!(r.in_collision, "the box is around this posture's elbow");
            assert!(r.pairs.iter().all(|p| p.b == "box"), "{}", r.summary());
            hit = Some(i);
        }
    }
    let hit = hit.expect("the chosen posture is a solution");
    assert!(!state.arm_collision().unwrap().in_collision);
    let contact = reports[hit].pairs[0].clone();
    assert_drawn_red(&state, &g.q, &contact, (&c, &size));

    // The solution list names the pair, and the free ones their clearance.
    let name = format!("{} hits box", contact.a);
    let mut h = harness(AppUi::new(state));
    let shown = |h: &Harness<'static, AppUi>, text: &str| {
        h.query_all_by_label_contains(text).next().is_some()
    };
    assert!(shown(&h, &name), "the list lacks \"{name}\"");
    assert!(shown(&h, "mm clear"));

    // The arm takes the colliding posture.
    h.state_mut().state.select_solution(0, hit).unwrap();
    h.run();
    let s = &h.state().state;
    let said = s.messages().iter().any(|m| {
        m.level == armlab::app::state::Level::Warning
            && m.text.contains("now in collision")
            && m.text.contains(&name)
    });
    assert!(said, "{:?}", s.messages());
    let warning = s.collision_warning(0).expect("the arm is in collision");
    assert!(
        warning.contains(&name) && warning.contains("free solutions"),
        "{warning}"
    );
    assert!(shown(&h, &format!("in collision: {name}")));
}

/// "Add table" from the Cell menu puts a table in front of the robot, all postures free;
/// dragging its height in the Cell section raises it into the arm's postures (the ones the
/// stick figure surely puts inside it collide); the gizmo moves it too.
#[test]
fn adding_a_table_from_the_menu_and_dragging_it_changes_what_collides() {
    let mut h = harness(AppUi::new(AppState::from_spec("puma560").unwrap()));
    h.get_by_label("Cell").click();
    h.run();
    h.get_by_label("Add table").click();
    h.run();
    let table = |h: &Harness<'static, AppUi>| -> Obstacle {
        let scene = h.state().state.cell_scene().expect("a cell").clone();
        assert_eq!(scene.obstacles.len(), 1);
        scene.obstacles[0].clone()
    };
    let t0 = table(&h);
    assert_eq!(t0.name, "table");
    assert_eq!(h.state().state.selected_obstacle(), Some(0));
    let colliding = |h: &Harness<'static, AppUi>| -> Vec<bool> {
        let s = &h.state().state;
        s.solution_collisions(0)
            .iter()
            .map(|r| r.in_collision)
            .collect()
    };
    assert!(!colliding(&h).is_empty());
    assert!(
        colliding(&h).iter().all(|c| !c),
        "the table is added clear of the arm"
    );

    // The panel's height field dragged 250 points to the right: 2 mm a point.
    let field = h.get_by_label("table z [mm]").rect().center();
    h.drag_at(field);
    h.step();
    for k in 1..=25 {
        h.hover_at(field + egui::vec2(10.0 * k as f32, 0.0));
        h.step();
    }
    h.drop_at(field + egui::vec2(250.0, 0.0));
    h.run();
    let t1 = table(&h);
    let rise = t1.xyz[2] - t0.xyz[2];
    assert!(rise > 0.4 && rise < 0.6, "the table rose by {rise} m");
    assert_eq!(t1.xyz[..2], t0.xyz[..2]);
    let after = colliding(&h);
    assert!(after.iter().any(|&c| c), "the raised table hits no posture");
    let s = &h.state().state;
    let result = s.target(0).unwrap().result.clone().unwrap();
    let ObstacleShape::Box { size } = t1.shape else {
        panic!("a table is a box")
    };
    let mut sure = 0;
    for (sol, &c) in result.solutions.iter().zip(&after) {
        if let Some(v) = sure_verdict(s.robot(), &sol.q, &t1.xyz, &size) {
            assert_eq!(c, v, "{:?}", sol.posture);
            sure += 1;
        }
    }
    assert!(sure > 0, "no posture has a sure verdict");

    // The gizmo, grabbed where a user would, moves the table.
    let grip = h.state().tabs.view3d.obstacle_grip(&h.state().state);
    let grip = grip.expect("the selected table's gizmo is shown");
    h.drag_at(grip);
    h.step();
    for k in 1..=5 {
        h.hover_at(grip + egui::vec2(-6.0 * k as f32, -8.0 * k as f32));
        h.step();
    }
    h.drop_at(grip + egui::vec2(-30.0, -40.0));
    h.run();
    let t2 = table(&h);
    let moved = (Vector3::from(t2.xyz) - Vector3::from(t1.xyz)).norm();
    assert!(moved > 1e-3, "the gizmo did not move the table");
    assert_eq!(t2.shape, t1.shape);
}

/// The gizmo's world pose becomes the obstacle's pose in its own frame, with the file's
/// fixed-axis roll, pitch, yaw: read back through the collision layer's own pose.
#[test]
fn a_moved_obstacle_keeps_the_urdf_angles() {
    let mut o = Obstacle::cuboid("b", [0.1, 0.2, 0.3], [0.4, -0.1, 0.2]);
    o.rpy = [0.3, -0.4, 1.1];
    let old = o.frame_from_obstacle();
    let rot = nalgebra::Rotation3::from_axis_angle(&Vector3::x_axis(), 0.7)
        * nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), -0.2);
    let new = armlab::kinematics::Pose::from_parts(
        nalgebra::Translation3::new(0.1, 0.5, 0.9),
        rot * old.rotation,
    );
    let m = cell::moved(&o, &old, &new);
    let back = m.frame_from_obstacle();
    assert!((back.to_homogeneous() - new.to_homogeneous()).amax() < 1e-12);
    // R = Rz(yaw) Ry(pitch) Rx(roll), written out.
    let [r, p, y] = m.rpy;
    let (cr, sr, cp, sp, cy, sy) = (r.cos(), r.sin(), p.cos(), p.sin(), y.cos(), y.sin());
    let expected = nalgebra::Matrix3::new(
        cy * cp,
        cy * sp * sr - sy * cr,
        cy * sp * cr + sy * sr,
        sy * cp,
        sy * sp * sr + cy * cr,
        sy * sp * cr - cy * sr,
        -sp,
        cp * sr,
        cp * cr,
    );
    assert!((new.rotation.matrix() - expected).amax() < 1e-12);
}

/// Every obstacle the menu adds, for a DH arm standing on its base (the Puma), one whose base
/// is at its shoulder (the anthropomorphic arm) and a URDF (the UR5): the floor is under the
/// base as drawn (within the pedestal's depth below the base frame), the table's
/// top is below the shoulder and in front, within reach, and the DH arms at their opening pose
/// touch none of them (the UR5's opening pose hangs its wrist below its mounting plane: it
/// hits the floor, as it would).
#[test]
fn the_menus_obstacles_fit_the_robot() {
    let ur5 = format!(
        "{}/tests/data/urdf_corpus/ur5_robot.urdf",
        env!("CARGO_MANIFEST_DIR")
    );
    for spec in ["puma560", "anthropomorphic_spherical_wrist", ur5.as_str()] {
        let mut state = AppState::from_spec(spec).unwrap();
        let robot = state.robot().clone();
        let l = robot.longest_chain_length();
        let base = robot.base.translation.vector;
        for kind in ObstacleKind::ALL {
            state.add_obstacle(kind.obstacle(&robot)).unwrap();
        }
        let scene = state.cell_scene().unwrap().clone();
        let floor = &scene.obstacles[0];
        assert_eq!(floor.shape, ObstacleShape::Plane);
        let pedestal = 2.0 * LINK_RADIUS_FRACTION * l;
        assert!(
            floor.xyz[2] <= base.z + 1e-9,
            "{spec}: the floor is above the base"
        );
        assert!(
            floor.xyz[2] >= base.z - pedestal - 2e-3 * l,
            "{spec}: the floor hangs"
        );
        let table = &scene.obstacles[1];
        let ObstacleShape::Box { size } = table.shape else {
            panic!("a box")
        };
        let shoulder = robot.fk_frames(&vec![0.0; robot.dof()]).unwrap()[0]
            .translation
            .vector;
        let top = table.xyz[2] + size[2] / 2.0;
        assert!(
            top < shoulder.z && top >= floor.xyz[2] - 1e-9,
            "{spec}: top {top}"
        );
        let near = table.xyz[0] - size[0] / 2.0;
        assert!(
            near > base.x && near < base.x + l,
            "{spec}: the table starts at {near}"
        );
        // The floor clears the fixed base: no "mounting" contact said (it once was, 0.0 mm).
        let mounting = state
            .messages()
            .iter()
            .find(|m| m.text.contains("mounting"));
        assert!(mounting.is_none(), "{spec}: {mounting:?}");
        let report = state.arm_collision().expect("checked");
        if spec == ur5 {
            let tool = robot.fk(state.q()).unwrap().translation.vector;
            assert!(tool.z < base.z, "the UR5's tool is above its base: {tool}");
            assert!(report.pairs.iter().any(|p| p.b == "floor"));
        } else {
            assert!(!report.in_collision, "{spec}: {}", report.summary());
        }
    }
}

/// A bad scene file is a message naming the file, the line and the obstacle, and the cell
/// stays as it was; a scene file typed as a path opens as the cell.
#[test]
fn a_bad_scene_file_changes_nothing_and_a_good_one_opens() {
    let mut app = AppUi::new(AppState::from_spec("puma560").unwrap());
    app.state
        .add_obstacle(ObstacleKind::Table.obstacle(app.state.robot()))
        .unwrap();
    let before = app.state.cell_scene().unwrap().clone();
    let q = app.state.q().to_vec();
    let bad = "[[obstacle]]\nname = \"crate\"\nshape = \"box\"\nsize = [0.2, 0.0, 0.1]\n";
    cell::open_text(&mut app, "bad.toml", bad);
    let m = app.state.last_message().unwrap().text.clone();
    assert!(
        m.contains("bad.toml:1") && m.contains("crate") && m.contains("degenerate"),
        "{m}"
    );
    assert_eq!(app.state.cell_scene().unwrap(), &before);
    assert_eq!(app.state.q(), &q[..]);

    let dir = std::env::temp_dir().join(format!("armlab-cell-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("cell.toml");
    let good = "[[obstacle]]\nname = \"pillar\"\nshape = \"cylinder\"\nsize = [0.05, 1.0]\nxyz = [0.0, -0.6, 0.5]\n";
    std::fs::write(&path, good).unwrap();
    app.load(&path.to_string_lossy());
    let scene = app.state.cell_scene().unwrap();
    assert_eq!(scene.obstacles.len(), 1);
    assert_eq!(scene.obstacles[0].name, "pillar");
    assert_eq!(app.state.robot().name, "Puma 560", "the model stays");
    // Saved and read back: the same obstacles.
    let saved = dir.join("again.toml");
    cell::apply(
        &mut app,
        cell::CellAction::Save(Some(saved.to_string_lossy().into_owned())),
    );
    let back = armlab::collision::CellScene::read(&saved).unwrap();
    let unlined = |s: &armlab::collision::CellScene| -> Vec<Obstacle> {
        let mut o = s.obstacles.clone();
        o.iter_mut().for_each(|o| o.line = 0);
        o
    };
    assert_eq!(unlined(&back), unlined(app.state.cell_scene().unwrap()));
    std::fs::remove_dir_all(&dir).ok();
}

/// A lesson step carries the cell (the scene file's obstacles written in the step): replaying
/// it restores the cell after the user moved an obstacle; "Save as lesson" writes the app's
/// cell into the step, and it reads back the same.
#[test]
fn a_lesson_step_restores_its_cell() {
    let text = "title = \"cell\"\nrobot = \"puma560\"\n[[steps]]\ncaption = \"a table\"\n\
                [[steps.scene.obstacle]]\nname = \"table\"\nshape = \"box\"\n\
                size = [0.5, 1.0, 0.04]\nxyz = [0.55, 0.0, 0.3]\n";
    let lesson = armlab::lesson::Lesson::parse(text, "lesson.toml").unwrap();
    let mut app = AppUi::new(AppState::from_spec("planar2").unwrap());
    app.open_lesson(lesson, "lesson.toml").unwrap();
    let scene = app.state.cell_scene().expect("the step's cell").clone();
    assert_eq!(scene.obstacles.len(), 1);
    assert_eq!(scene.obstacles[0].xyz, [0.55, 0.0, 0.3]);
    let mut moved = scene.obstacles[0].clone();
    moved.xyz[2] = 0.9;
    app.state.set_obstacle(0, moved).unwrap();
    app.go_to_step(0);
    assert_eq!(app.state.cell_scene().unwrap().obstacles[0].xyz[2], 0.3);

    let bad = text.replace("0.04]", "-0.04]");
    let bad = armlab::lesson::Lesson::parse(&bad, "bad-lesson.toml").unwrap();
    let mut other = AppUi::new(AppState::from_spec("puma560").unwrap());
    other.open_lesson(bad, "bad-lesson.toml").unwrap();
    assert!(other.state.cell_scene().is_none());
    let said = other
        .state
        .messages()
        .iter()
        .any(|m| m.text.contains("bad-lesson.toml: step 1") && m.text.contains("\"table\""));
    assert!(said, "{:?}", other.state.messages());

    let step = armlab::app::lesson::current_step(
        &app.state,
        0,
        &armlab::app::lesson::Seen::of(&app.tabs, app.tab, &app.ik.construction),
        "",
    );
    let mut saved = app.lesson.clone().unwrap().lesson;
    saved.steps = vec![step];
    let again = armlab::lesson::Lesson::parse(&saved.to_toml(), "again.toml").unwrap();
    let Some(Ok(armlab::lesson::SceneSource::Inline(t))) = again.step_scene(0) else {
        panic!("the saved step has no scene: {}", saved.to_toml());
    };
    let back = armlab::collision::CellScene::parse(&t, std::path::Path::new("x")).unwrap();
    let (a, b) = (
        &back.obstacles[0],
        &app.state.cell_scene().unwrap().obstacles[0],
    );
    assert_eq!(
        (&a.name, &a.shape, a.xyz, a.rpy),
        (&b.name, &b.shape, b.xyz, b.rpy)
    );
}

/// The self-motion slider of the planar three-link arm in a cell: a ball put around the elbow
/// at one value of phi makes a red stretch there on that branch; a value where the whole arm is
/// far from the ball stays free. (The stretches are found when the drag ends: not while one is
/// under way.)
#[test]
fn the_self_motion_slider_shows_where_the_arm_collides() {
    use armlab::kinematics::redundancy::Task;
    let mut state = AppState::from_spec("planar3").unwrap();
    state.set_task(Task::Planar).unwrap();
    state.set_q(&[0.3, 0.8, 0.6]).unwrap();
    let view = state.self_motion(0).expect("an exact self-motion");
    assert!(view.exact && view.colliding.is_empty());
    let robot = state.robot().clone();
    let branch = view.branch;
    let name = view.names[branch].clone();
    let feasible = view.feasible[branch].clone();
    let inside = |t: f64| feasible.iter().any(|iv| iv[0] + 0.2 < t && t < iv[1] - 0.2);
    // The branch's postures over phi, from the tab's samples.
    let postures: Vec<(f64, Vec<f64>)> = view
        .samples
        .iter()
        .filter_map(|(t, sols)| {
            let s = sols.iter().find(|s| s.name == name && s.within_limits)?;
            Some((*t, s.q.clone()))
        })
        .collect();
    let elbow = |q: &[f64]| robot.fk_frames(q).unwrap()[0].translation.vector;
    let (t_hit, q_hit) = postures
        .iter()
        .filter(|(t, _)| inside(*t))
        .max_by(|a, b| {
            let d = |q: &[f64]| (elbow(q) - elbow(state.q())).norm();
            d(&a.1).total_cmp(&d(&b.1))
        })
        .cloned()
        .expect("a value inside a feasible interval");
    let c = elbow(&q_hit);
    let radius = 0.04;
    let mut ball = Obstacle::cuboid("ball", [0.1; 3], c.into());
    ball.shape = ObstacleShape::Sphere { radius };
    state.add_obstacle(ball).unwrap();

    state.dragging = true;
    let during = state.self_motion(0).unwrap();
    assert!(during.colliding.is_empty(), "found during a drag");
    state.dragging = false;
    let view = state.self_motion(0).unwrap();
    let here: Vec<_> = view
        .colliding
        .iter()
        .filter(|s| s.branch == branch)
        .collect();
    assert!(
        here.iter()
            .any(|s| s.from <= t_hit && t_hit <= s.to && s.b == "ball"),
        "phi = {t_hit}: the elbow is in the ball, but the stretches are {here:?}"
    );
    // Far from the ball everywhere along the stick figure: free.
    let l = robot.longest_chain_length();
    let clear = radius + 2.0 * LINK_RADIUS_FRACTION * l + 0.02;
    let mut free_checked = 0;
    for (t, q) in &postures {
        let far = stick_points(&robot, q)
            .iter()
            .all(|p| (p - c).norm() > clear);
        if far && inside(*t) {
            assert!(
                !here.iter().any(|s| s.from <= *t && *t <= s.to),
                "phi = {t} is far from the ball but in a stretch"
            );
            free_checked += 1;
        }
    }
    assert!(
        free_checked > 10,
        "only {free_checked} values far from the ball"
    );
}
