//! File dialogs: the desktop's native one in the window (the `rfd` crate: the XDG desktop
//! portal on Linux, the system dialogs on macOS and Windows), none in tests and screenshots.
//! Typing a path stays possible everywhere.

use std::path::PathBuf;

/// What a dialog is for: it sets the title and the file-type filter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileKind {
    /// A robot model to open (.toml or .urdf).
    Model,
    /// A model to save (.toml, or .urdf by the name's extension).
    ModelToSave,
    /// A measurement file (calibration).
    Measurements,
    /// A cell's scene file to open (.toml).
    Scene,
    /// A cell's scene file to save (.toml).
    SceneToSave,
    /// A live class's answers to save (.csv).
    ClassCsv,
}

#[cfg(feature = "app")]
impl FileKind {
    fn title(self) -> &'static str {
        match self {
            FileKind::Model => "Open a robot model",
            FileKind::ModelToSave => "Save the model as",
            FileKind::Measurements => "Open a measurement file",
            FileKind::Scene => "Open a scene file (the cell's obstacles)",
            FileKind::SceneToSave => "Save the cell as a scene file",
            FileKind::ClassCsv => "Save the class's answers as CSV",
        }
    }

    fn filters(self) -> &'static [(&'static str, &'static [&'static str])] {
        match self {
            FileKind::Model => &[("Robot models", &["toml", "urdf"])],
            FileKind::ModelToSave => &[("TOML model file", &["toml"]), ("URDF", &["urdf"])],
            FileKind::Measurements => &[("Measurements", &["csv", "txt"]), ("All files", &["*"])],
            FileKind::Scene | FileKind::SceneToSave => &[("Scene files", &["toml"])],
            FileKind::ClassCsv => &[("CSV", &["csv"])],
        }
    }
}

/// Asks the user for a file. `None`: cancelled, or no dialog on this platform.
pub trait FilePicker {
    /// Whether a dialog can be shown at all (the buttons say so when not).
    fn available(&self) -> bool;
    /// A file to open.
    fn open(&mut self, kind: FileKind) -> Option<PathBuf>;
    /// A file to write, `suggested` as the proposed name.
    fn save(&mut self, kind: FileKind, suggested: &str) -> Option<PathBuf>;
    /// Where files are not paths (the browser): a file the user picked since the last call, as
    /// its name and contents. `open` starts such a pick and answers `None`.
    fn poll_opened(&mut self) -> Option<(FileKind, String, Vec<u8>)> {
        None
    }
    /// Where files are not paths (the browser): hands `bytes` to the user as a download named
    /// `name`; `false` where there are no downloads (the desktop writes files instead).
    fn download(&mut self, _name: &str, _mime: &str, _bytes: &[u8]) -> bool {
        false
    }
    /// Where files are not paths (the browser): starts reading a file dropped onto the window,
    /// to be handed over by [`Self::poll_opened`]; `false`: open it by its path.
    fn take_dropped(&mut self, _file: &egui::DroppedFileHandle) -> bool {
        false
    }
    /// Whether saving means a download (the browser) rather than writing a path.
    fn downloads(&self) -> bool {
        false
    }
}

/// No dialogs (tests, screenshots): every request answers `None`.
#[derive(Debug, Default)]
pub struct NoDialogs;

impl FilePicker for NoDialogs {
    fn available(&self) -> bool {
        false
    }
    fn open(&mut self, _kind: FileKind) -> Option<PathBuf> {
        None
    }
    fn save(&mut self, _kind: FileKind, _suggested: &str) -> Option<PathBuf> {
        None
    }
}

/// The desktop's native file dialog (blocking while it is open, as egui apps do).
#[cfg(feature = "app")]
#[derive(Debug, Default)]
pub struct NativeDialogs;

#[cfg(feature = "app")]
impl NativeDialogs {
    fn dialog(kind: FileKind) -> rfd::FileDialog {
        let mut d = rfd::FileDialog::new().set_title(kind.title());
        for (name, ext) in kind.filters() {
            d = d.add_filter(*name, ext);
        }
        if let Ok(dir) = std::env::current_dir() {
            d = d.set_directory(dir);
        }
        d
    }
}

#[cfg(feature = "app")]
impl FilePicker for NativeDialogs {
    fn available(&self) -> bool {
        true
    }
    fn open(&mut self, kind: FileKind) -> Option<PathBuf> {
        Self::dialog(kind).pick_file()
    }
    fn save(&mut self, kind: FileKind, suggested: &str) -> Option<PathBuf> {
        Self::dialog(kind).set_file_name(suggested).save_file()
    }
}
