//! Which singularity an arm is at, named from its geometry: the wrist, elbow and shoulder
//! singularities of the Puma 560 (Sect. 3.3 of Siciliano et al.), found from the Jacobian's
//! conditioning and the positions of the joint axes.
//!
//! Run: `cargo run --release --example singularity`.

use armlab::kinematics::models::built_in;
use armlab::kinematics::singularity::SingularityAnalyzer;
use std::error::Error;

fn main() -> Result<(), Box<dyn Error>> {
    let puma = built_in("puma560").ok_or("no puma560")?;
    let analyzer = SingularityAnalyzer::new(&puma);
    for (what, q) in [
        ("a generic pose", [0.3, 0.8, -1.0, 0.4, 0.6, 0.2]),
        (
            "theta5 = 0 (axes 4 and 6 aligned)",
            [0.3, 0.8, -1.0, 0.4, 0.0, 0.2],
        ),
        ("the zero configuration", [0.0; 6]),
    ] {
        match analyzer.classify(&puma, &q, 0)? {
            Some(report) => println!("{what}: {}", report.message()),
            None => println!(
                "{what}: no singularity (conditioning {:.3})",
                analyzer.conditioning(&puma, &q, 0)?
            ),
        }
    }
    Ok(())
}
