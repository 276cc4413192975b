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
}

/// Runs `armlab export`.
pub(super) fn run(args: &ExportArgs, out: &mut dyn Write) -> Result<(), CliError> {
    if args.urdf.is_none() && args.toml.is_none() {
        return Err(CliError::Usage(
            "say what to write: --urdf OUT.urdf and/or --toml OUT.toml",
        ));
    }
    let robot = super::load_model(&args.model)?;
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
