//! Collision checks (issue 48): every closed-form posture of a pose checked against the arm's
//! own links and a three-box cell. Goals: the Puma's 8 postures in at most 20 µs (primitive
//! shapes: the stick figure's capsules and cylinders), the UR5's 8 in at most 200 µs (the convex
//! hulls of its collision meshes, tests/data/collision_meshes). Both the full report (contacts,
//! depths, clearance) and the yes/no check are timed.
//! Run: `cargo bench --no-default-features --bench collision`.

use armlab::collision::{CellScene, CollisionWorld};
use armlab::kinematics::Robot;
use armlab::kinematics::ik::Target;
use armlab::kinematics::ik::numerical::NumericalOptions;
use armlab::kinematics::ik::solver::{SolverChoice, solve};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::path::Path;

/// Three boxes around an arm of `reach` metres: a table in front, a shelf to the side and a
/// post behind.
fn three_boxes(reach: f64) -> CellScene {
    let text = format!(
        "[[obstacle]]\nname = \"table\"\nshape = \"box\"\nsize = [{w}, {w}, 0.05]\nxyz = [{x}, 0, {z}]\n\n\
         [[obstacle]]\nname = \"shelf\"\nshape = \"box\"\nsize = [{s}, 0.3, {s}]\nxyz = [0, {y}, {x}]\n\n\
         [[obstacle]]\nname = \"post\"\nshape = \"box\"\nsize = [0.1, 0.1, {h}]\nxyz = [{b}, 0, 0]\n",
        w = reach * 0.8,
        x = reach * 0.6,
        z = -reach * 0.3,
        s = reach * 0.5,
        y = reach * 0.7,
        h = reach * 2.0,
        b = -reach * 0.7,
    );
    CellScene::parse(&text, Path::new("three_boxes.toml")).expect("a valid scene")
}

/// Every closed-form posture of the pose at `q`.
fn postures(robot: &Robot, q: &[f64]) -> Vec<Vec<f64>> {
    let target = Target::Pose(robot.fk(q).expect("fk"));
    let (result, _) = solve(
        robot,
        0,
        &target,
        None,
        SolverChoice::ClosedForm,
        &NumericalOptions::default(),
    )
    .expect("a closed form");
    result.solutions.into_iter().map(|s| s.q).collect()
}

fn bench_robot(c: &mut Criterion, name: &str, robot: &Robot, q: &[f64]) {
    let world =
        CollisionWorld::new(robot, &three_boxes(robot.longest_chain_length())).expect("a world");
    let qs = postures(robot, q);
    eprintln!(
        "{name}: {} postures, {} pairs checked",
        qs.len(),
        world.checked_pairs().len()
    );
    c.bench_function(
        &format!("{name}: every posture, report (contacts, clearance)"),
        |b| {
            b.iter(|| {
                for q in &qs {
                    black_box(world.check(robot, black_box(q)).expect("check"));
                }
            })
        },
    );
    c.bench_function(
        &format!("{name}: every posture, in collision or not"),
        |b| {
            b.iter(|| {
                for q in &qs {
                    black_box(world.in_collision(robot, black_box(q)).expect("check"));
                }
            })
        },
    );
}

fn collisions(c: &mut Criterion) {
    let puma = armlab::kinematics::models::puma560();
    bench_robot(
        c,
        "Puma 560 (primitives)",
        &puma,
        &[0.3, 0.5, -0.4, 0.6, 0.7, 0.2],
    );
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    armlab::urdf::set_package_paths(vec![root.join("tests/data/collision_meshes")]);
    let ur5 = armlab::urdf::load_urdf(&root.join("tests/data/urdf_corpus/ur5_robot.urdf"))
        .expect("the UR5");
    bench_robot(
        c,
        "UR5 (mesh hulls)",
        &ur5,
        &[0.3, -1.2, 1.0, -0.8, 0.7, 0.2],
    );
}

criterion_group!(benches, collisions);
criterion_main!(benches);
