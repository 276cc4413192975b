//! Base placement (issue 49): 12 task poses over a 2 m x 2 m floor at 5 cm and 36 yaws
//! (41 x 41 positions x 36 yaws x 12 tasks = 726,192 closed-form solves), goal at most 10 s on
//! two cores; the UR5 (tests/data/urdf_corpus) and the Puma 560. Also one placement (12 tasks)
//! alone, and the same floor with a three-box cell (every solution checked for collisions).
//! Run: `cargo bench --no-default-features --bench placement`.

use armlab::collision::{CellScene, CollisionWorld};
use armlab::kinematics::Robot;
use armlab::kinematics::arm::arm_of;
use armlab::kinematics::models::built_in;
use armlab::reachability::{PlacementOptions, PlacementTask, Placer, floor_shift, place};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::path::Path;
use std::sync::atomic::AtomicBool;

/// The UR5 of the test corpus, as the arm to its first end-effector (tool0).
fn ur5() -> Robot {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/urdf_corpus/ur5_robot.urdf");
    let robot =
        armlab::model_file::load_model(path.to_str().expect("a UTF-8 path")).expect("the UR5 URDF");
    arm_of(&robot, 0, &robot.ready_or_zero())
        .expect("the arm of tool0")
        .robot
}

/// Twelve task poses the arm reaches from base position (0.3, -0.2) m at yaw 40 degrees: its
/// tool at twelve configurations spread over the joints, seen from that placement.
fn tasks(robot: &Robot) -> Vec<PlacementTask> {
    let shift = floor_shift(0.3, -0.2, 40f64.to_radians());
    (0..12)
        .map(|k| {
            let t = k as f64;
            let mut q = vec![0.0; robot.dof()];
            let pattern = [
                0.5 * (t * 0.7).sin(),
                -0.9 + 0.3 * (t * 1.3).cos(),
                1.2 + 0.4 * (t * 0.9).sin(),
                -1.5 + 0.5 * (t * 1.7).cos(),
                -1.4 + 0.6 * (t * 0.5).sin(),
                0.8 * t,
            ];
            for (v, p) in q.iter_mut().zip(pattern) {
                *v = p;
            }
            let tool = robot.fk(&q).expect("fk");
            PlacementTask::new(format!("task {}", k + 1), shift * tool)
        })
        .collect()
}

/// Three boxes: a table in front of the tasks, a wall to one side and a post.
fn cell() -> CellScene {
    let text = "[[obstacle]]\nname = \"table\"\nshape = \"box\"\nsize = [0.6, 0.8, 0.05]\n\
                xyz = [0.9, -0.2, 0.0]\n\n\
                [[obstacle]]\nname = \"wall\"\nshape = \"box\"\nsize = [2.0, 0.1, 1.5]\n\
                xyz = [0.0, 1.2, 0.75]\n\n\
                [[obstacle]]\nname = \"post\"\nshape = \"box\"\nsize = [0.1, 0.1, 2.0]\n\
                xyz = [-0.6, -0.6, 1.0]\n";
    CellScene::parse(text, Path::new("cell.toml")).expect("a valid scene")
}

fn bench_floor(c: &mut Criterion, name: &str, robot: &Robot) {
    let tasks = tasks(robot);
    let options = PlacementOptions::default();
    let cancel = AtomicBool::new(false);
    let map = place(robot, &tasks, None, &options, &cancel, &|_| {}).expect("a placement");
    eprintln!(
        "{name}: {} placements x {} tasks, best fraction {:.3} at ({:.2}, {:.2}) m, yaw {:.0} deg",
        map.grid.placements(),
        tasks.len(),
        map.best.first().map_or(0.0, |b| b.fraction),
        map.best.first().map_or(f64::NAN, |b| b.detail.x),
        map.best.first().map_or(f64::NAN, |b| b.detail.y),
        map.best
            .first()
            .map_or(f64::NAN, |b| b.detail.yaw.to_degrees()),
    );
    let mut group = c.benchmark_group("placement");
    group.sample_size(10);
    group.bench_function(
        format!("{name}: 12 tasks, 2 m x 2 m at 5 cm, 36 yaws"),
        |b| {
            b.iter(|| {
                black_box(place(robot, &tasks, None, &options, &cancel, &|_| {}).expect("ok"))
            })
        },
    );
    group.finish();
    let placer = Placer::new(robot, &tasks, None, 1).expect("a placer");
    c.bench_function(
        &format!("{name}: one placement, 12 tasks, every solution"),
        |b| b.iter(|| black_box(placer.evaluate(black_box(0.3), -0.2, 0.7))),
    );
}

fn bench_cell(c: &mut Criterion, robot: &Robot) {
    let tasks = tasks(robot);
    let world = CollisionWorld::new(robot, &cell()).expect("a world");
    let options = PlacementOptions {
        step: 0.1,
        yaws: 12,
        ..PlacementOptions::default()
    };
    let cancel = AtomicBool::new(false);
    let mut group = c.benchmark_group("placement with a cell");
    group.sample_size(10);
    group.bench_function(
        "ur5: 12 tasks, 2 m x 2 m at 10 cm, 12 yaws, three boxes",
        |b| {
            b.iter(|| {
                black_box(
                    place(robot, &tasks, Some(&world), &options, &cancel, &|_| {}).expect("ok"),
                )
            })
        },
    );
    group.finish();
}

fn benches(c: &mut Criterion) {
    let ur5 = ur5();
    bench_floor(c, "ur5", &ur5);
    bench_floor(
        c,
        "puma560",
        &built_in("puma560").expect("a built-in model"),
    );
    bench_cell(c, &ur5);
}

criterion_group!(placement, benches);
criterion_main!(placement);
