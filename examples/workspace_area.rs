//! The workspace of the two-link arm with joint limits (Example 2.6, Figs 2.29-2.30): its exact
//! area, the areas reached with each posture and with both (region BADHB), and the boundary
//! arcs labelled as in Fig. 2.30.
//!
//! Run: `cargo run --release --example workspace_area`.

use armlab::kinematics::models::built_in;
use armlab::workspace::{
    BoundaryOptions, StatsOptions, TrackedPoint, map_statistics, planar_boundary,
};
use std::error::Error;

fn main() -> Result<(), Box<dyn Error>> {
    let robot = built_in("planar2_fig2_30").ok_or("no planar2_fig2_30")?;
    // Exact: areas by Green's theorem over the boundary arcs (no grid, no sampling).
    let stats = map_statistics(&robot, TrackedPoint::Flange, &StatsOptions::default())?;
    println!("{} ({})", robot.name, stats.measure_method);
    println!(
        "  reachable area {:.6} m^2, reached with both postures {:.6} m^2",
        stats.area.unwrap_or(f64::NAN),
        stats.area_both_postures.unwrap_or(f64::NAN)
    );
    for c in &stats.classes {
        println!(
            "  {:<11} {:.6} m^2 ({:.6} m^2 with it only)",
            c.name, c.with, c.only
        );
    }
    // The boundary: arcs of circles, each the image of a segment of Fig. 2.29.
    let boundary = planar_boundary(&robot, &BoundaryOptions::default())?;
    for curve in &boundary.curves {
        println!("  arc {:<3} {}", curve.label, curve.description);
    }
    if let Some(h) = boundary.crossing("FD", "BC") {
        println!("  H, where FD cuts BC: ({:.6}, {:.6}) m", h[0], h[1]);
    }
    Ok(())
}
