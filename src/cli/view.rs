//! `armlab view` (and `armlab` alone): the interactive app, or with `--screenshot` the whole
//! window rendered offscreen to PNG.

use super::CliError;
use super::figures::Size;
use super::input::parse_row;
use crate::app::screenshot::{ScreenshotOptions, screenshot};
use crate::app::state::AppState;
use crate::kinematics::models::DEFAULT_MODEL;
use std::path::PathBuf;

/// Arguments of `armlab view`.
#[derive(Debug, Default, clap::Args)]
pub struct ViewArgs {
    /// Built-in name or path to a .toml / .urdf model (default: the anthropomorphic arm with
    /// spherical wrist).
    pub model: Option<String>,
    /// Render the whole app window offscreen to this PNG and exit (no display needed).
    #[arg(long)]
    pub screenshot: Option<PathBuf>,
    /// Window size for --screenshot, WIDTHxHEIGHT.
    #[arg(long, default_value = "1280x800")]
    pub size: Size,
    /// Joint vector (rad, m) to show (in the window too, with the IK target on the tool).
    #[arg(long, allow_hyphen_values = true)]
    pub q: Option<String>,
    /// Put the IK target on the tool and show every closed-form solution.
    #[arg(long)]
    pub all_postures: bool,
    /// Move the IK target to this position x,y,z (m), e.g. outside the workspace.
    #[arg(long, allow_hyphen_values = true)]
    pub target_position: Option<String>,
    /// Projector mode (large fonts, high contrast).
    #[arg(long)]
    pub projector: bool,
    /// The end-effector the right panel, the gizmo and the readouts start on (a name or an
    /// index; default: the tool of the longest arm).
    #[arg(long)]
    pub ee: Option<String>,
    /// Open the window, drag the IK target for N frames, print the frame times and exit
    /// (vsync off; under `xvfb-run` on a machine without a display).
    #[arg(long, value_name = "N", conflicts_with = "screenshot", value_parser = super::count)]
    pub measure_frames: Option<usize>,
    /// A scene file of obstacles (TOML `[[obstacle]]` tables) to open as the cell: every
    /// posture is checked against them and against the arm itself.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
}

/// Runs `view`.
pub(super) fn run(args: &ViewArgs, out: &mut dyn std::io::Write) -> Result<(), CliError> {
    let spec = args.model.as_deref().unwrap_or(DEFAULT_MODEL);
    let mut robot = super::load_model(spec)?;
    let ee = super::ik::end_effector(&mut robot, args.ee.as_deref())?;
    let mut state = AppState::new(robot, spec);
    let scene = match &args.scene {
        Some(path) => Some(crate::collision::CellScene::read(path)?),
        None => None,
    };
    if let Some(s) = &scene {
        let cell = state.set_scene(Some(s.clone()));
        cell.map_err(|e| CliError::App(crate::app::AppError::Input(e)))?;
    }
    let dof = state.robot().dof();
    let q = match &args.q {
        Some(t) => Some(parse_row(t, "--q", dof, "joint values")?),
        None => None,
    };
    if args.measure_frames.is_some_and(|n| n == 0 || n > 100_000) {
        return Err(CliError::Usage(
            "--measure-frames must be between 1 and 100000",
        ));
    }
    let Some(path) = &args.screenshot else {
        let opts = crate::app::RunOptions {
            measure_frames: args.measure_frames,
            q,
            model_given: args.model.is_some(),
            ee,
            lesson: None,
            scene,
            class_teacher: None,
        };
        if let Some(report) = crate::app::run_with(spec, &opts).map_err(CliError::App)? {
            writeln!(out, "{report}")?;
        } else if opts.measure_frames.is_some() {
            return Err(CliError::App(crate::app::AppError::Window(
                "the window closed before the frames were measured".into(),
            )));
        }
        return Ok(());
    };
    let target_position = match &args.target_position {
        Some(t) => {
            let v = parse_row(t, "--target-position", 3, "numbers")?;
            Some([v[0], v[1], v[2]])
        }
        None => None,
    };
    let opts = ScreenshotOptions {
        q,
        all_postures: args.all_postures,
        target_position,
        projector: args.projector,
        ee,
    };
    let img = screenshot(state, args.size.0, &opts).map_err(CliError::App)?;
    crate::headless::write_png(&img, path)?;
    writeln!(
        out,
        "wrote {} ({}x{})",
        path.display(),
        img.width(),
        img.height()
    )?;
    Ok(())
}
