//! `armlab animate MODEL --what self-motion|postures|dh-frames|path`, or `armlab animate --what
//! rotation --compose "current Rz(30) Ry(45); fixed Rx(10)"`: an animation to GIF or APNG (by
//! the extension of `--out`).

use super::CliError;
use super::figures::{Size, ThemeArg};
use crate::animation::{Motion, plan};
use std::io::Write;
use std::path::PathBuf;

/// What to animate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum WhatArg {
    /// The hand held still while the elbow sweeps the feasible interval (redundant arms).
    SelfMotion,
    /// A morph between the closed-form postures of one hand pose, with the ghosts.
    Postures,
    /// The DH build: each A_i as Rot(z, theta) Trans(z, d) Trans(x, a) Rot(x, alpha).
    DhFrames,
    /// A straight tool path with the joint rates plotted beside it.
    Path,
    /// A composition of elementary rotations (`--compose`), step by step (no model).
    Rotation,
}

/// The sequence `--what rotation` plays when `--compose` is not given (the example).
pub const DEFAULT_SEQUENCE: &str = "current Rz(30) Ry(45); fixed Rx(10)";

/// Arguments of `armlab animate`.
#[derive(Debug, clap::Args)]
pub struct AnimateArgs {
    /// Built-in name, model file (.toml) or URDF (not for `--what rotation`).
    pub model: Option<String>,
    /// What to animate.
    #[arg(long, value_enum)]
    pub what: WhatArg,
    /// Output file: .gif (256 colours a frame) or .apng / .png (animated PNG, lossless).
    #[arg(long, default_value = "animation.gif")]
    pub out: PathBuf,
    /// Frame size, WIDTHxHEIGHT.
    #[arg(long, default_value = "800x600")]
    pub size: Size,
    /// Frames per second (1 to 60).
    #[arg(long, default_value_t = 30)]
    pub fps: u32,
    /// Length (s); default 5 s, for the DH build 1.5 s per joint.
    #[arg(long)]
    pub seconds: Option<f64>,
    /// Light or dark.
    #[arg(long, value_enum, default_value_t = ThemeArg::Light)]
    pub theme: ThemeArg,
    /// For `--what rotation`: the sequence, as `armlab rotation --compose` reads it (default
    /// "current Rz(30) Ry(45); fixed Rx(10)").
    #[arg(long, allow_hyphen_values = true, value_name = "SEQUENCE")]
    pub compose: Option<String>,
    /// Read the angles of --compose in radians (default: degrees).
    #[arg(long)]
    pub rad: bool,
}

/// Runs `armlab animate`.
pub(super) fn run(args: &AnimateArgs, out: &mut dyn Write) -> Result<(), CliError> {
    if !(1..=60).contains(&args.fps) {
        return Err(CliError::Usage("--fps must be between 1 and 60"));
    }
    let ext = output_extension(&args.out)?;
    let motion = match args.what {
        WhatArg::SelfMotion => Motion::SelfMotion,
        WhatArg::Postures => Motion::Postures,
        WhatArg::DhFrames => Motion::DhFrames,
        WhatArg::Path => Motion::Path,
        WhatArg::Rotation => return rotation(args, &ext, out),
    };
    let Some(model) = &args.model else {
        return Err(CliError::Usage(
            "name a model (a built-in, a .toml or a URDF); only --what rotation needs none",
        ));
    };
    if args.compose.is_some() {
        return Err(CliError::Usage("--compose goes with --what rotation"));
    }
    let (robot, _) = super::arm_robot(super::load_model(model)?, None)?;
    let seconds = args.seconds.unwrap_or(match motion {
        Motion::DhFrames => 1.5 * robot.dof() as f64,
        _ => 5.0,
    });
    check_seconds(seconds)?;
    let frames = ((seconds * f64::from(args.fps)).round() as usize).max(2);
    let bad = |reason: String| CliError::BadTarget {
        source_name: model.clone(),
        reason,
    };
    let anim = plan(&robot, motion, frames, seconds).map_err(|e| bad(e.to_string()))?;
    let mut figs = crate::figure::figures::Figures::new()?;
    let images =
        crate::figure::animation::frames(&mut figs, &robot, &anim, args.size.0, args.theme.into())?;
    encode(&images, args, &ext)?;
    writeln!(
        out,
        "wrote {} ({} frames, {}x{}, {} fps, {seconds:.2} s): {}",
        args.out.display(),
        images.len(),
        args.size.0[0],
        args.size.0[1],
        args.fps,
        anim.title
    )?;
    Ok(())
}

/// The lower-case extension of `--out`, checked: gif, apng or png.
fn output_extension(path: &std::path::Path) -> Result<String, CliError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default();
    if !matches!(ext.as_str(), "gif" | "apng" | "png") {
        return Err(CliError::Usage(
            "--out must end in .gif, .apng or .png (MP4 is not written: no maintained \
             pure-Rust encoder)",
        ));
    }
    Ok(ext)
}

/// Writes `images` to `--out` as GIF or APNG (by `ext`).
fn encode(images: &[image::RgbaImage], args: &AnimateArgs, ext: &str) -> Result<(), CliError> {
    let file = std::fs::File::create(&args.out)
        .map_err(|e| CliError::Export(format!("{}: {e}", args.out.display())))?;
    let w = std::io::BufWriter::new(file);
    let encoded = if ext == "gif" {
        crate::figure::animation::encode_gif(images, args.fps, w)
    } else {
        crate::figure::animation::encode_apng(images, args.fps, w)
    };
    encoded.map_err(|e| CliError::Export(format!("{}: {e}", args.out.display())))
}

/// `--what rotation`: the sequence of `--compose` played step by step (Sect. 2.3).
fn rotation(args: &AnimateArgs, ext: &str, out: &mut dyn Write) -> Result<(), CliError> {
    if args.model.is_some() {
        return Err(CliError::Usage(
            "--what rotation turns a frame, not an arm: give no model",
        ));
    }
    let text = args.compose.as_deref().unwrap_or(DEFAULT_SEQUENCE);
    let steps = super::rotation::sequence_of(text, args.rad)?;
    let seconds = args.seconds.unwrap_or(1.5 * steps.len().max(1) as f64);
    check_seconds(seconds)?;
    let frames = ((seconds * f64::from(args.fps)).round() as usize).max(2);
    let shots = crate::animation::rotation::rotation_shots(&steps, frames);
    let title = format!(
        "Composition: {}",
        crate::animation::rotation::product_text(&steps)
    );
    let mut figs = crate::figure::figures::Figures::new()?;
    let images = crate::figure::orientation::rotation_frames(
        &mut figs,
        &shots,
        &title,
        args.size.0,
        args.theme.into(),
    )?;
    encode(&images, args, ext)?;
    writeln!(
        out,
        "wrote {} ({} frames, {}x{}, {} fps, {seconds:.2} s): {title}",
        args.out.display(),
        images.len(),
        args.size.0[0],
        args.size.0[1],
        args.fps,
    )?;
    Ok(())
}

/// `--seconds` must be more than 0 and at most 600.
fn check_seconds(seconds: f64) -> Result<(), CliError> {
    if seconds > 0.0 && seconds <= 600.0 {
        Ok(())
    } else {
        Err(CliError::Usage(
            "--seconds must be more than 0 and at most 600",
        ))
    }
}
