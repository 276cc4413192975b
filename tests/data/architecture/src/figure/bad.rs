//! A figure that computes (fixture).
fn sample_count() -> usize { 3 }
fn solve_into_label() {}
fn figure(robot: &Robot) {
    solver.solve_into(robot, &target, Verify::Fk, &mut solutions);
    let s = workspace::sample(robot, &opts, &|_| {});
    let n = sample_count();
    let wrist = ClosedForm::detect(robot).is_ok();
}
use crate::app::AppUi;
fn write(out: impl std::io::Write) {}
