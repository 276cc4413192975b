//! The app's files read and written: what a typed, dropped or picked file holds (a model, a
//! lesson, an exercise key), the answers of the file dialogs, and the model, lessons, pictures
//! and recordings written (or offered as downloads in a browser). Nothing here changes the app:
//! the shell applies what these functions return.

use super::file_browser::FileBrowser;
use super::file_picker::{FileKind, FilePicker};
use super::lesson::LessonPlayer;
use super::state::AppState;
use crate::lesson::Lesson;
use std::path::{Path, PathBuf};

/// What a file opened in the app turned out to be.
#[derive(Debug)]
pub enum Opening {
    /// A student's exercise sheet (`student-NN/sheet.json`) or a teacher's key
    /// (`keys/student-NN.json`), both written by `armlab exercise new`: its text.
    Exercise(String),
    /// A lesson, or why it could not be read.
    Lesson(Result<Lesson, String>),
    /// A cell's scene file (`[[obstacle]]` tables): its text.
    Scene(String),
    /// A model: its text where the file came as bytes (`None`: loaded by its name, a built-in
    /// model or a path).
    Model(Option<String>),
    /// Why the file cannot be opened.
    Unreadable(String),
}

/// What `spec` (a built-in model's name or a path) is: a lesson or a scene file (.toml) or an
/// exercise key (.json) by its contents, else a model.
pub fn open_path(spec: &str) -> Opening {
    lesson_or_key_text(spec).map_or(Opening::Model(None), |text| of_text(text, spec, false))
}

/// What a file handed over as bytes (a browser's, or dropped) is.
pub fn open_bytes(name: &str, bytes: &[u8]) -> Opening {
    match std::str::from_utf8(bytes) {
        Ok(text) => of_text(text.to_string(), name, true),
        Err(_) => Opening::Unreadable(format!(
            "{name}: not a text file (a model file is TOML or URDF text)"
        )),
    }
}

/// What `text`, the contents of the file `name`, holds (a model keeps its text with
/// `model_text`).
fn of_text(text: String, name: &str, model_text: bool) -> Opening {
    if text.contains(crate::exercise::KEY_FORMAT) || text.contains(crate::exercise::SHEET_FORMAT) {
        return Opening::Exercise(text);
    }
    if super::cell::is_scene_text(&text) {
        return Opening::Scene(text);
    }
    match Lesson::detect(&text, name) {
        Some(lesson) => Opening::Lesson(lesson),
        None => Opening::Model(model_text.then_some(text)),
    }
}

/// The text of `path` if it may be a lesson (.toml) or an exercise key (.json): a regular file
/// of at most 4 MB (never `/dev/zero` read to the end); `None` otherwise.
fn lesson_or_key_text(path: &str) -> Option<String> {
    let ext = Path::new(path).extension()?.to_str()?.to_ascii_lowercase();
    let meta = std::fs::metadata(path).ok()?;
    let small = meta.is_file() && meta.len() <= 4 << 20;
    (small && (ext == "toml" || ext == "json"))
        .then(|| std::fs::read_to_string(path).ok())
        .flatten()
}

/// The exercise sheet or key at `path` (the Exercise tab's "Open sheet"), whatever its
/// extension.
pub fn open_key(path: &str) -> Opening {
    match std::fs::read_to_string(path) {
        Ok(text) => Opening::Exercise(text),
        Err(e) => Opening::Unreadable(format!("{path}: {e}")),
    }
}

/// Writes an exam's answer to `path` (a download named as its file in a browser); the message
/// for the status bar.
pub fn write_answer(picker: &mut dyn FilePicker, path: &str, text: &str) -> Result<String, String> {
    if path.is_empty() {
        return Err("give the answer's file name (student-NN.toml or .txt)".into());
    }
    let name = Path::new(path)
        .file_name()
        .map_or("answer.txt".into(), |n| n.to_string_lossy().into_owned());
    if picker.download(&name, "text/plain", text.as_bytes()) {
        return Ok(format!("downloading {name}: hand it in"));
    }
    std::fs::write(path, text).map_err(|e| format!("cannot write {path}: {e}"))?;
    Ok(format!(
        "answer saved in {}: hand it in",
        full_path(Path::new(path)).display()
    ))
}

/// The paths of the files dropped onto the window in this frame (a file without a path, as a
/// browser hands it over, is read by the file picker instead).
pub fn dropped_paths(ctx: &egui::Context) -> Vec<String> {
    ctx.input(|i| {
        i.raw
            .dropped_files
            .iter()
            .map(|f| f.path().display().to_string())
            .filter(|p| !p.is_empty())
            .collect()
    })
}

/// "Open file...": the model file chosen in the desktop's file dialog, or `None`. Where there
/// is none (no xdg-desktop-portal answers at once, or none is built in) the in-app `browser`
/// opens, on the folder of `load_path` (the path typed last); in a web page the picker answers
/// later ([`FilePicker::poll_opened`]). The message says why no dialog showed.
pub fn ask_to_open(
    picker: &mut dyn FilePicker,
    browser: &mut FileBrowser,
    load_path: &str,
) -> (Option<String>, Option<&'static str>) {
    if !picker.available() {
        if cfg!(target_arch = "wasm32") {
            return (
                None,
                Some("no file dialog here: drop a model file on the page"),
            );
        }
        let dir = Path::new(load_path).parent().unwrap_or(Path::new(""));
        browser.show_dir(dir);
        return (None, None);
    }
    if cfg!(target_arch = "wasm32") {
        let _ = picker.open(FileKind::Model);
        return (None, None);
    }
    let asked = std::time::Instant::now();
    match picker.open(FileKind::Model) {
        Some(path) => (Some(path.to_string_lossy().into_owned()), None),
        // A dialog that closed before anyone could answer it was never shown.
        None if asked.elapsed() < std::time::Duration::from_millis(300) => {
            browser.show_dir(Path::new(""));
            let m = "no desktop file dialog answered (it needs xdg-desktop-portal): choose the \
                     file here";
            (None, Some(m))
        }
        None => (None, None),
    }
}

/// Asks the save dialog where to write the model of the robot `robot_name` (a path without an
/// extension gets `.toml`); `None`: cancelled.
pub fn ask_to_save(picker: &mut dyn FilePicker, robot_name: &str) -> Option<String> {
    let suggested = suggested_model_name(robot_name);
    let path = picker.save(FileKind::ModelToSave, &suggested)?;
    Some(with_model_extension(path).to_string_lossy().into_owned())
}

/// "Save model as..." in a browser: the edited robot of `state` offered as a download named
/// `save_path` (TOML, or URDF for a name ending in .urdf; the robot's name where it is empty);
/// the message for the status bar.
pub fn download_model(
    picker: &mut dyn FilePicker,
    state: &AppState,
    save_path: &str,
) -> Result<String, String> {
    let name = match save_path.trim() {
        "" => suggested_model_name(&state.robot().name),
        n => n.to_string(),
    };
    let mime = if name.to_ascii_lowercase().ends_with(".urdf") {
        "application/xml"
    } else {
        "application/toml"
    };
    let text = state.model_text(&name)?;
    if picker.download(&name, mime, text.as_bytes()) {
        Ok(format!("downloading {name}"))
    } else {
        Err(format!("the browser refused the download of {name}"))
    }
}

/// Writes the lesson of `player` to its file (a download in a browser); the message for the
/// status bar.
pub fn write_lesson(picker: &mut dyn FilePicker, player: &LessonPlayer) -> Result<String, String> {
    let text = player.lesson.to_toml();
    let name = Path::new(&player.file)
        .file_name()
        .map_or("lesson.toml".into(), |n| n.to_string_lossy().into_owned());
    if picker.download(&name, "application/toml", text.as_bytes()) {
        return Ok(format!("downloading {name}"));
    }
    let file = &player.file;
    std::fs::write(file, text).map_err(|e| format!("cannot write {file}: {e}"))?;
    Ok(format!(
        "step {} saved in {}",
        player.lesson.steps.len(),
        full_path(Path::new(file)).display()
    ))
}

/// The file name proposed for saving a robot: its name in lower case, spaces as `_`, `.toml`.
pub fn suggested_model_name(robot_name: &str) -> String {
    let stem: String = robot_name
        .chars()
        .map(|c| {
            if c.is_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect();
    format!("{}.toml", stem.trim_matches('_'))
}

/// A path from a save dialog without an extension gets `.toml`.
pub fn with_model_extension(path: PathBuf) -> PathBuf {
    if path.extension().is_none() {
        path.with_extension("toml")
    } else {
        path
    }
}

/// Writes `img` as `armlab-<stem>-<n>.png` (the first free n) in the working directory, or
/// offers it as the download `armlab-<stem>.png` where files are downloads (a browser); the
/// message names the file's full path.
pub fn deliver_png(
    picker: &mut dyn FilePicker,
    img: &image::RgbaImage,
    stem: &str,
) -> Result<String, String> {
    let mut png = Vec::new();
    crate::figure::encode_png(img, &mut png).map_err(|e| e.to_string())?;
    deliver_bytes(picker, &png, stem, ("png", "image/png"))
}

/// Saves `bytes` as `armlab-<stem>-<n>.<ext>` (the first free n) in the current folder, or
/// offers them as a download in a browser; returns the message for the status bar.
pub fn deliver_bytes(
    picker: &mut dyn FilePicker,
    bytes: &[u8],
    stem: &str,
    (ext, mime): (&str, &str),
) -> Result<String, String> {
    let name = format!("armlab-{stem}.{ext}");
    if picker.download(&name, mime, bytes) {
        return Ok(format!("downloading {name}"));
    }
    let path = (1..1000)
        .map(|n| PathBuf::from(format!("armlab-{stem}-{n}.{ext}")))
        .find(|p| !p.exists())
        .ok_or_else(|| "no free file name".to_string())?;
    std::fs::write(&path, bytes).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    Ok(format!("saved {}", full_path(&path).display()))
}

/// `path` made absolute (against the working directory) for messages.
pub fn full_path(path: &Path) -> PathBuf {
    std::fs::canonicalize(path).unwrap_or_else(|_| {
        std::env::current_dir()
            .map(|d| d.join(path))
            .unwrap_or_else(|_| path.to_path_buf())
    })
}
