//! Every closed-form IK solution of a pose with its posture label (Sect. 2.12), and the
//! numerical solver for an arm that has no closed form.
//!
//! Run: `cargo run --release --example ik_all_solutions`.

use armlab::kinematics::ik::closed_form::{ClosedForm, Solutions, Verify};
use armlab::kinematics::ik::numerical::{self, NumericalOptions};
use armlab::kinematics::ik::{IkStatus, Target};
use armlab::kinematics::models::built_in;
use std::error::Error;

fn main() -> Result<(), Box<dyn Error>> {
    // The Puma 560: eight solutions for a generic pose.
    let puma = built_in("puma560").ok_or("no puma560")?;
    let target = Target::Pose(puma.fk(&[0.4, 0.6, -1.1, 0.5, 0.8, -0.3])?);
    let solver = ClosedForm::detect(&puma)?;
    println!("{}: {}", puma.name, solver.name());
    // Allocation-free: reuse `solutions` for every target of a loop.
    let mut solutions = Solutions::default();
    solver.solve_into(&puma, &target, Verify::Fk, &mut solutions)?;
    for s in &solutions {
        let e = s.errors.ok_or("verified solutions carry their errors")?;
        println!(
            "  {:<44} q = {:>7.3?}  {}  error {:.1e} m, {:.1e} rad",
            s.posture.to_string(),
            s.q(),
            if s.within_limits {
                "inside limits "
            } else {
                "outside limits"
            },
            e.position,
            e.orientation
        );
    }
    // A target outside the workspace is a status, not an error.
    let far = armlab::kinematics::Pose::translation(3.0, 0.0, 0.5);
    solver.solve_into(&puma, &Target::Pose(far), Verify::Limits, &mut solutions)?;
    if let IkStatus::Unreachable { distance } = solutions.status {
        println!("  a tool at (3, 0, 0.5) m is {distance:.3} m outside the workspace");
    }

    // The Panda has seven joints: no closed form, and the reason says why.
    let panda = built_in("panda").ok_or("no panda")?;
    if let Err(why) = ClosedForm::detect(&panda) {
        println!("{}: no closed form: {why}", panda.name);
    }
    let goal = Target::Pose(panda.fk(&[0.3, -0.5, 0.2, -2.0, 0.1, 1.8, 0.7])?);
    let seed = panda.config("ready").ok_or("no ready")?;
    let report = numerical::solve(&panda, 0, &goal, seed, &NumericalOptions::default())?;
    println!(
        "  numerical: converged {} after {} iterations ({} restarts), error {:.1e} m, q = {:.3?}",
        report.converged, report.iterations, report.restarts, report.position_error, report.q
    );
    Ok(())
}
