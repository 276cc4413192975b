//! The workspace of the two-link arm with joint limits (Example 2.6, Figs 2.29-2.30): its area,
//! the area reached with each posture and with both, and the exact boundary arcs.
//!
//! Run: `cargo run --release --example workspace_area`.

use armlab::model_file::load_model;
use armlab::workspace::{BoundaryOptions, StatsOptions, planar_boundary, statistics};
use std::error::Error;

fn main() -> Result<(), Box<dyn Error>> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/robots/planar2_limited.toml"
    );
    let robot = load_model(path)?;
    // Areas from the closed-form IK at the centre of every cell of a grid (no progress bar).
    let stats = statistics(&robot, &StatsOptions::default(), &|_| {})?;
    println!("{}", robot.name);
    println!(
        "  reachable area {:.4} m^2 on a {} x {} grid",
        stats.area.unwrap_or(f64::NAN),
        stats.resolution,
        stats.resolution
    );
    for c in &stats.classes {
        println!(
            "  {:<11} {:.4} m^2 ({:.4} m^2 with it only)",
            c.name, c.with, c.only
        );
    }
    // The exact boundary: arcs of circles, each labelled as in Fig. 2.30.
    let boundary = planar_boundary(&robot, &BoundaryOptions::default())?;
    for curve in &boundary.curves {
        println!("  arc {:<3} {}", curve.label, curve.description);
    }
    for (class, name) in boundary.class_names.iter().enumerate() {
        if let Some(a) = boundary.loop_area(class as u8) {
            println!("  area enclosed by the {name} loop (exact boundary): {a:.6} m^2");
        }
    }
    Ok(())
}
