//! `armlab export MODEL --urdf OUT.urdf [--toml OUT.toml]`: a model written as URDF (any chain
//! whose couplings URDF can say) or as armlab's TOML model file (serial DH tables).

use super::CliError;
use std::io::Write;
use std::path::PathBuf;

/// Arguments of `armlab export`.
#[derive(Debug, clap::Args)]
pub struct ExportArgs {
    /// Built-in name or path to a .toml / .urdf model.
    pub model: String,
    /// Write the model as URDF here: joint origins and axes with the same forward kinematics,
    /// the joint limits, simple visuals.
    #[arg(long)]
    pub urdf: Option<PathBuf>,
    /// Write the model as a TOML model file here (a serial DH table).
    #[arg(long)]
    pub toml: Option<PathBuf>,
    /// Export only the arm of this end-effector (a name or an index): the chain from the root
    /// to it; as TOML, a chain given by URDF origins is written as the DH table derived from
    /// its axes (same forward kinematics).
    #[arg(long)]
    pub ee: Option<String>,
}

/// Runs `armlab export`.
pub(super) fn run(args: &ExportArgs, out: &mut dyn Write) -> Result<(), CliError> {
    if args.urdf.is_none() && args.toml.is_none() {
        return Err(CliError::Usage(
            "say what to write: --urdf OUT.urdf and/or --toml OUT.toml",
        ));
    }
    let mut robot = super::load_model(&args.model)?;
    if args.ee.is_some() {
        robot = super::arm_robot(robot, args.ee.as_deref())?.0;
        if args.toml.is_some()
            && crate::model_file::to_toml(&robot).is_none()
            && let Ok(d) = crate::kinematics::dh_derive::derive_dh(
                &robot,
                0,
                crate::kinematics::Convention::Standard,
            )
            && let Ok(dh) = d.robot(&robot.name)
        {
            robot = dh;
        }
    }
    // Every text first, so that a model one format cannot say writes nothing.
    let urdf = match &args.urdf {
        Some(path) => Some((
            path,
            crate::urdf::to_urdf(&robot).map_err(|e| CliError::Export(e.to_string()))?,
        )),
        None => None,
    };
    let toml = match &args.toml {
        Some(path) => Some((
            path,
            crate::model_file::to_toml(&robot).ok_or_else(|| {
                CliError::Export(
                    "a TOML model file holds one serial DH table with one variable per joint; \
                     this model is a tree, a closed chain, coupled, or given by URDF origins \
                     (export it with --urdf)"
                        .into(),
                )
            })?,
        )),
        None => None,
    };
    for (path, text) in urdf.iter().chain(toml.iter()) {
        std::fs::write(path, text)
            .map_err(|e| CliError::Export(format!("cannot write {}: {e}", path.display())))?;
        writeln!(out, "wrote {}", path.display())?;
    }
    Ok(())
}
