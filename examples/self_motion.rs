//! The self-motion of the DLR arm (Sect. 2.10.2): the hand held still while the elbow turns
//! about the shoulder-wrist line. Every branch of the arm angle psi in closed form, the
//! intervals of psi where each branch stays inside the joint limits, and a check of the hand.
//!
//! Run: `cargo run --release --example self_motion`.

use armlab::kinematics::models::built_in;
use armlab::redundancy::sampler::sample_self_motion;
use std::error::Error;

fn main() -> Result<(), Box<dyn Error>> {
    let dlr = built_in("dlr").ok_or("no dlr")?;
    let q = [0.3, 0.6, -0.2, 1.2, 0.4, -0.5, 0.2];
    let world_from_hand = dlr.fk(&q)?;
    // 72 values of psi over [-pi, pi): every branch at each.
    let motion = sample_self_motion(&dlr, 0, &world_from_hand, 72)?;
    println!(
        "{}: parameter {} ({}), exact: {}, {} self-motion curve(s) inside the limits",
        dlr.name, motion.parameter, motion.meaning, motion.exact, motion.manifolds
    );
    for (name, intervals) in motion.names.iter().zip(&motion.feasible) {
        let deg: Vec<String> = intervals
            .iter()
            .map(|[a, b]| format!("[{:.1}, {:.1}]", a.to_degrees(), b.to_degrees()))
            .collect();
        println!("  {name:<24} feasible psi (deg): {}", deg.join(" "));
    }
    // The hand never moves: the largest error over every sample and branch.
    let worst = motion
        .samples
        .iter()
        .flat_map(|(_, branches)| branches)
        .map(|b| b.position_error.max(b.orientation_error))
        .fold(0.0, f64::max);
    println!("largest hand error over the samples: {worst:.1e} (m and rad)");
    Ok(())
}
