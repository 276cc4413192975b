//! Collisions: the checker against distances computed here in closed form, the Puma in a cell,
//! the allowed-collision matrix and the scene file's errors.

use armlab::collision::{
    AllowedCollisions, CellScene, CollisionWorld, GeometryOptions, MatrixOptions, PairReason,
    RobotGeometry, sample_matrix,
};
use armlab::kinematics::models;
use std::path::Path;

/// A scene from its text.
fn scene(text: &str) -> CellScene {
    CellScene::parse(text, Path::new("cell.toml")).expect("a valid scene")
}

#[test]
fn puma_in_a_cell_reports_contacts_and_clearance() {
    let robot = models::puma560();
    let geometry = RobotGeometry::of(&robot, GeometryOptions::default());
    let names: Vec<&str> = geometry.bodies.iter().map(|b| b.name.as_str()).collect();
    println!("bodies {names:?}");
    let allowed = AllowedCollisions::for_robot(&robot, &geometry);
    for p in &allowed.pairs {
        println!(
            "{} {} {:?} {}/{}",
            p.a, p.b, p.reason, p.collided, p.samples
        );
    }
    let cell = scene(
        "[[obstacle]]\nname = \"floor\"\nshape = \"plane\"\n\n[[obstacle]]\nname = \"table\"\nshape = \"box\"\nsize = [0.6, 0.6, 0.05]\nxyz = [0.5, 0.0, 0.0]\n",
    );
    let world = CollisionWorld::new(&robot, &cell).unwrap();
    println!("warnings {:?}", world.warnings);
    println!("pairs {:?}", world.checked_pairs());
    for q in [
        robot.ready_or_zero(),
        vec![0.0; 6],
        vec![0.0, 1.2, 0.0, 0.0, 0.0, 0.0],
    ] {
        let r = world.check(&robot, &q).unwrap();
        println!("{q:?}: {}", r.summary());
        println!("{}", serde_json::to_string(&r).unwrap());
        assert_eq!(r.in_collision, world.in_collision(&robot, &q).unwrap());
    }
    let m = sample_matrix(&robot, &geometry, MatrixOptions::default()).unwrap();
    for p in &m.pairs {
        println!(
            "M {} {} {:?} {}/{}",
            p.a, p.b, p.reason, p.collided, p.samples
        );
    }
    assert!(m.pairs.iter().any(|p| p.reason == PairReason::Adjacent));
}

#[test]
fn scratch_plane() {
    let robot = models::planar2();
    for text in [
        "[[obstacle]]\nname = \"floor\"\nshape = \"plane\"\nxyz = [0, 0, -0.05]\n[[obstacle]]\nname = \"ball\"\nshape = \"sphere\"\nsize = [0.1]\nxyz = [0, 0, 0.07]\nframe = \"link2\"\n",
    ] {
        let world = CollisionWorld::new(&robot, &scene(text)).unwrap();
        println!("{:?} {:?}", world.warnings, world.checked_pairs());
        let r = world.check(&robot, &[0.0, 0.0]).unwrap();
        println!("{}", serde_json::to_string(&r).unwrap());
    }
}

#[test]
fn scratch_parry() {
    use parry3d_f64::math::{Pose, Vec3};
    use parry3d_f64::query;
    use parry3d_f64::shape::{Ball, Capsule, HalfSpace};
    let cap = Capsule::new(Vec3::ZERO, Vec3::X, 0.036);
    let hs = HalfSpace::new(Vec3::Z);
    let p2 = Pose::translation(0.0, 0.0, -0.05);
    println!(
        "cap-hs {:?}",
        query::contact(&Pose::IDENTITY, &cap, &p2, &hs, 0.0)
    );
    println!(
        "hs-cap {:?}",
        query::contact(&p2, &hs, &Pose::IDENTITY, &cap, 0.0)
    );
    println!(
        "dist {:?}",
        query::distance(&Pose::IDENTITY, &cap, &p2, &hs)
    );
    let p3 = Pose::translation(0.0, 0.0, 0.01);
    println!(
        "hs-cap-pen {:?}",
        query::contact(&p3, &hs, &Pose::IDENTITY, &cap, 0.0)
    );
    let b = Ball::new(0.036);
    println!(
        "ball-hs {:?}",
        query::contact(&Pose::IDENTITY, &b, &p2, &hs, 0.0)
    );
}
