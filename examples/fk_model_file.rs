//! Forward kinematics of a robot read from a model file (TOML DH table or URDF), eq. (2.50).
//!
//! Run: `cargo run --example fk_model_file -- assets/robots/puma560.toml 0.1,0.8,-1.2,0.3,0.5,0.2`
//! (no arguments: the Puma 560 file at its "ready" configuration).

use armlab::kinematics::JointGeometry;
use armlab::model_file::load_model;
use std::error::Error;

fn main() -> Result<(), Box<dyn Error>> {
    let mut args = std::env::args().skip(1);
    let path = args.next().unwrap_or_else(|| {
        concat!(env!("CARGO_MANIFEST_DIR"), "/assets/robots/puma560.toml").into()
    });
    // A path, or a built-in name such as "stanford".
    let robot = load_model(&path)?;
    let q: Vec<f64> = match args.next() {
        Some(list) => list
            .split(',')
            .map(|v| v.trim().parse::<f64>())
            .collect::<Result<_, _>>()?,
        None => robot
            .config("ready")
            .map_or_else(|| vec![0.0; robot.dof()], <[f64]>::to_vec),
    };
    println!("{} ({} DOF)", robot.name, robot.dof());
    for j in robot.joints() {
        if let JointGeometry::Dh { row, .. } = &j.geometry {
            println!("  {:<8} {:<9} {row}", j.name, j.kind.as_str());
        }
    }
    // `fk` checks the length of q and that every value is finite: a typed error, no panic.
    let world_from_tool = robot.fk(&q)?;
    println!("q = {q:?}");
    println!("world_from_tool = {}", world_from_tool.to_homogeneous());
    println!("p = {:?} m", world_from_tool.translation.vector.as_slice());
    Ok(())
}
