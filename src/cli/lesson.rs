//! `armlab lesson FILE`: a lesson in the app, or (`--render DIR`) one PNG per step.

use super::CliError;
use super::figures::Size;
use crate::app::state::AppState;
use crate::lesson::{Lesson, RobotSource, resolve_spec};
use std::io::Write;
use std::path::PathBuf;

/// Arguments of `armlab lesson`.
#[derive(Debug, clap::Args)]
pub struct LessonArgs {
    /// The lesson file (TOML).
    pub file: PathBuf,
    /// Write one PNG per step (the app window as the class sees it) into this folder instead
    /// of opening the window.
    #[arg(long)]
    pub render: Option<PathBuf>,
    /// Window size of the rendered steps, WIDTHxHEIGHT.
    #[arg(long, default_value = "1280x800")]
    pub size: Size,
    /// A scene file of obstacles (TOML `[[obstacle]]` tables) to open as the cell before the
    /// first step (a step that carries its own `scene` replaces it).
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
}

/// Runs `armlab lesson`.
pub(super) fn run(args: &LessonArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let name = args.file.display().to_string();
    let text = std::fs::read_to_string(&args.file)
        .map_err(|e| CliError::Export(format!("{name}: {e}")))?;
    let lesson = Lesson::parse(&text, &name).map_err(|e| CliError::Export(e.to_string()))?;
    let bad = |e: String| CliError::Export(format!("{name}: robot: {e}"));
    let state = match lesson.robot_source().map_err(bad)? {
        RobotSource::Spec(spec) => AppState::from_spec(&resolve_spec(&spec, &args.file)),
        RobotSource::Embedded(model) => {
            let robot = crate::model_file::parse_model_text("lesson robot.toml", &model)
                .map_err(|e| bad(e.to_string()))?;
            Ok(AppState::new(robot, "lesson robot.toml"))
        }
    }
    .map_err(|e| bad(e.to_string()))?;
    let mut state = state;
    let scene = match &args.scene {
        Some(path) => Some(crate::collision::CellScene::read(path)?),
        None => None,
    };
    if let Some(s) = &scene {
        let cell = state.set_scene(Some(s.clone()));
        cell.map_err(|e| CliError::App(crate::app::AppError::Input(e)))?;
    }
    let Some(dir) = &args.render else {
        let spec = state.spec().to_string();
        let opts = crate::app::RunOptions {
            model_given: true,
            lesson: Some((lesson, name)),
            scene,
            ..Default::default()
        };
        crate::app::run_with(&spec, &opts).map_err(CliError::App)?;
        return Ok(());
    };
    let frames = crate::app::screenshot::lesson_frames(state, lesson, &name, args.size.0)
        .map_err(CliError::App)?;
    std::fs::create_dir_all(dir)
        .map_err(|e| CliError::Export(format!("{}: {e}", dir.display())))?;
    for (i, img) in frames.iter().enumerate() {
        let path = dir.join(format!("step-{:02}.png", i + 1));
        crate::headless::write_png(img, &path)?;
        writeln!(
            out,
            "wrote {} ({}x{})",
            path.display(),
            img.width(),
            img.height()
        )?;
    }
    Ok(())
}
