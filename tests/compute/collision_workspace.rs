//! Issue 48: workspaces in a cell. The side view of the anthropomorphic arm (a2 = a3 = 1 m,
//! full ranges) with a table and a floor, each collision cell one map cell, checked against an
//! IK written here (joint 1 from the azimuth, then the two-link arm in the arm's plane, each
//! solution checked by forward kinematics) and `CollisionWorld::in_collision`:
//!
//! - at every cell, the classes the map keeps are those with a configuration that hits nothing;
//!   the classes it takes out because they collide are in its `blocked` layer;
//! - a point under the table top that a posture reaches without the table is not reached by it
//!   with the table; a point far from every obstacle keeps all its postures;
//! - the checker `reach` uses says the same per posture;
//! - the top view keeps a class only where one height of the cell's column is free for it.

use armlab::collision::{CellScene, CollisionWorld, Obstacle};
use armlab::kinematics::Robot;
use armlab::kinematics::models::built_in;
use armlab::workspace::cell::CellChecker;
use armlab::workspace::{
    MapRequest, MapView, OneShot, PostureClassifier, TrackedPoint, compute_map, compute_map_in,
};
use std::f64::consts::PI;

fn cell() -> CellScene {
    CellScene {
        obstacles: vec![
            Obstacle::cuboid("table", [1.0, 1.2, 0.06], [1.1, 0.0, 0.4]),
            Obstacle::floor("floor", -0.7),
        ],
        ..CellScene::default()
    }
}

/// The configurations reaching base point (x, 0, z) (x > 0): joint 1 at 0 or pi, then the
/// two-link arm (a2 = a3 = 1 m) in the plane, elbow on either side; each checked by forward
/// kinematics. Empty out of reach (or within 1e-6 of its rim, where the test stays silent).
fn own_ik(robot: &Robot, x: f64, z: f64) -> Vec<Vec<f64>> {
    let mut out = Vec::new();
    for (q1, r) in [(0.0, x), (PI, -x)] {
        let c3 = (r * r + z * z - 2.0) / 2.0;
        if c3.abs() > 1.0 - 1e-6 {
            return Vec::new();
        }
        for s3 in [(1.0 - c3 * c3).sqrt(), -(1.0 - c3 * c3).sqrt()] {
            let q3 = s3.atan2(c3);
            let q2 = z.atan2(r) - s3.atan2(1.0 + c3);
            let wrap = |a: f64| (a + PI).rem_euclid(2.0 * PI) - PI;
            let q = vec![q1, wrap(q2), wrap(q3)];
            let p = robot.fk(&q).expect("fk").translation.vector;
            assert!(
                (p.x - x).abs() < 1e-9 && p.y.abs() < 1e-9 && (p.z - z).abs() < 1e-9,
                "own IK: {q:?} reaches {p:?}, not ({x}, 0, {z})"
            );
            out.push(q);
        }
    }
    out
}

/// Class bits of the configurations reaching (x, 0, z): all of them, and those hitting nothing.
fn own_classes(robot: &Robot, world: &CollisionWorld, x: f64, z: f64) -> Option<(u8, u8)> {
    let classifier = PostureClassifier::new(robot);
    let qs = own_ik(robot, x, z);
    if qs.is_empty() {
        return None;
    }
    let (mut all, mut free) = (0u8, 0u8);
    for q in qs {
        let bit = 1 << classifier.classify(&q, &robot.fk(&q).expect("fk"));
        all |= bit;
        if !world.in_collision(robot, &q).expect("a configuration") {
            free |= bit;
        }
    }
    Some((all, free))
}

#[test]
fn side_view_keeps_at_each_cell_the_postures_that_hit_nothing() {
    let arm = built_in("anthropomorphic3r").expect("a built-in model");
    let cell = cell();
    let world = CollisionWorld::new(&arm, &cell).expect("a world");
    let req = MapRequest {
        view: MapView::Side,
        point: TrackedPoint::Flange,
        cells: [110, 110],
        bounds: Some([-0.1, 2.1, -1.1, 1.1]),
        ..MapRequest::default()
    };
    let empty = compute_map(&arm, &req).expect("a map");
    let map = compute_map_in(&arm, &req, Some(&cell), &mut OneShot).expect("a map in the cell");
    let layer = map.collision.as_ref().expect("the cell's layer");
    assert_eq!(layer.block, 1, "one map cell per collision cell here");
    let names: Vec<&str> = layer.obstacles.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names, ["table", "floor"]);
    let (mut compared, mut under_table, mut far) = (0, 0, 0);
    for j in 0..map.height {
        for i in 0..map.width {
            let [x, z] = map.centre(i, j);
            let k = j * map.width + i;
            let Some((all, free)) = (x > 0.02)
                .then(|| own_classes(&arm, &world, x, z))
                .flatten()
            else {
                continue;
            };
            assert_eq!(empty.masks[k], all, "({x}, {z}): the empty map's postures");
            assert_eq!(
                map.masks[k], free,
                "({x}, {z}): the postures that hit nothing"
            );
            assert_eq!(
                layer.blocked[k],
                all & !free,
                "({x}, {z}): the colliding postures"
            );
            compared += 1;
            // Under the table top, over it in x: a posture that reached it collides now.
            if (0.7..1.5).contains(&x) && (-0.6..0.3).contains(&z) && all & !free != 0 {
                under_table += 1;
            }
            // Far from both (20 cm of clearance at every configuration): all postures stay.
            let clear = own_ik(&arm, x, z).iter().all(|q| {
                world
                    .check(&arm, q)
                    .expect("a configuration")
                    .clearance_m
                    .is_some_and(|c| c > 0.2)
            });
            if clear {
                assert_eq!(
                    map.masks[k], empty.masks[k],
                    "({x}, {z}) is far from everything"
                );
                far += 1;
            }
        }
    }
    assert!(compared > 3000, "{compared} cells compared");
    assert!(
        under_table > 20,
        "{under_table} cells under the table lost a posture"
    );
    assert!(far > 20, "{far} cells far from every obstacle");
}

#[test]
fn reach_checker_names_the_postures_that_collide_under_the_table() {
    let arm = built_in("anthropomorphic3r").expect("a built-in model");
    let cell = cell();
    let world = CollisionWorld::new(&arm, &cell).expect("a world");
    let checker = CellChecker::new(&arm, &cell, TrackedPoint::Flange).expect("a checker");
    let names = PostureClassifier::new(&arm).class_names().to_vec();
    let mut collided = 0;
    for (x, z) in [(1.0, 0.2), (1.2, 0.0), (0.9, -0.3), (0.4, 0.9), (1.3, 0.8)] {
        let (all, free) = own_classes(&arm, &world, x, z).expect("in reach");
        let verdicts = checker.postures([x, 0.0, z]);
        let reached: u8 = verdicts.iter().fold(0, |m, v| m | 1 << v.class);
        assert_eq!(reached, all, "({x}, {z})");
        for v in &verdicts {
            assert_eq!(v.name, names[v.class]);
            assert_eq!(v.free, free >> v.class & 1 == 1, "({x}, {z}) {}", v.name);
            assert_eq!(v.free, v.contacts.is_empty(), "({x}, {z}) {}", v.name);
            if !v.free {
                assert!(v.contacts.iter().any(|c| c.b == "table" || c.b == "floor"));
                collided += 1;
            }
        }
    }
    assert!(collided >= 2, "{collided} postures collided");
}

#[test]
fn top_view_keeps_a_posture_only_where_a_height_of_its_column_is_free() {
    let arm = built_in("anthropomorphic3r").expect("a built-in model");
    let cell = cell();
    let world = CollisionWorld::new(&arm, &cell).expect("a world");
    let req = MapRequest {
        view: MapView::Top,
        point: TrackedPoint::Flange,
        cells: [60, 60],
        bounds: Some([-2.1, 2.1, -2.1, 2.1]),
        ..MapRequest::default()
    };
    let map = compute_map_in(&arm, &req, Some(&cell), &mut OneShot).expect("a map");
    let classifier = PostureClassifier::new(&arm);
    let mut checked = 0;
    for j in (0..60).step_by(3) {
        for i in (0..60).step_by(3) {
            let k = j * 60 + i;
            if map.masks[k] == 0 {
                continue;
            }
            let [x, y] = map.centre(i, j);
            let (r, psi) = (x.hypot(y), y.atan2(x));
            // Some height of the column (the arm's reach, 2 m, up and down), on a 5 mm grid,
            // where the class hits nothing.
            let mut free = 0u8;
            for h in 0..=800 {
                if map.masks[k] & !free == 0 {
                    break;
                }
                let z = -2.0 + 0.005 * h as f64;
                for q in own_ik(&arm, r, z) {
                    let q = vec![q[0] + psi, q[1], q[2]];
                    if !world.in_collision(&arm, &q).expect("a configuration") {
                        free |= 1 << classifier.classify(&q, &arm.fk(&q).expect("fk"));
                    }
                }
            }
            assert_eq!(
                map.masks[k] & !free,
                0,
                "({x}, {y}): kept a posture no height frees (free {free:#b}, {:?})",
                map.class_names
            );
            checked += 1;
        }
    }
    assert!(checked > 50, "{checked} top cells checked");
}
