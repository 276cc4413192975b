//! The in-app file browser: where the desktop has no file dialog (no xdg-desktop-portal), "Open
//! file..." lists a folder's model files and sub-folders in a window of the app itself.

use std::path::{Path, PathBuf};

/// The browser's state.
#[derive(Debug, Default)]
pub struct FileBrowser {
    /// Shown.
    pub open: bool,
    /// The folder listed.
    pub dir: PathBuf,
    /// Its sub-folders and model files (.toml, .urdf), sorted, folders first.
    entries: Vec<(String, bool)>,
    /// Why the folder could not be listed.
    error: Option<String>,
    /// Choosing a cell's scene file rather than a model (the title and the hint say so; the
    /// choice is opened by its contents either way).
    pub scenes: bool,
}

/// Whether `name` is a model file armlab opens.
fn is_model(name: &str) -> bool {
    let lower = name.to_ascii_lowercase();
    lower.ends_with(".toml") || lower.ends_with(".urdf")
}

impl FileBrowser {
    /// Opens the browser on `dir` to choose a cell's scene file (.toml).
    pub fn show_scenes(&mut self, dir: &Path) {
        self.show_dir(dir);
        self.scenes = true;
    }

    /// Opens the browser on `dir` (the working directory when empty).
    pub fn show_dir(&mut self, dir: &Path) {
        self.scenes = false;
        self.dir = if dir.as_os_str().is_empty() {
            std::env::current_dir().unwrap_or_default()
        } else {
            dir.to_path_buf()
        };
        self.open = true;
        self.list();
    }

    /// Reads the folder.
    fn list(&mut self) {
        self.entries.clear();
        self.error = None;
        match std::fs::read_dir(&self.dir) {
            Ok(rd) => {
                for e in rd.flatten() {
                    let name = e.file_name().to_string_lossy().into_owned();
                    let is_dir = e.file_type().is_ok_and(|t| t.is_dir());
                    if name.starts_with('.') || !(is_dir || is_model(&name)) {
                        continue;
                    }
                    self.entries.push((name, is_dir));
                }
                self.entries
                    .sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
            }
            Err(e) => self.error = Some(format!("cannot list {}: {e}", self.dir.display())),
        }
    }

    /// The browser's window; returns the model file chosen, if one was.
    pub fn ui(&mut self, ctx: &egui::Context) -> Option<PathBuf> {
        if !self.open {
            return None;
        }
        let mut chosen = None;
        let mut go = None;
        let mut open = self.open;
        let (title, hint) = if self.scenes {
            (
                "Open a scene file",
                "No desktop file dialog here (it needs xdg-desktop-portal): choose a .toml scene \
                 file (the cell's obstacles).",
            )
        } else {
            (
                "Open a model file",
                "No desktop file dialog here (it needs xdg-desktop-portal): choose a .toml or \
                 .urdf file.",
            )
        };
        egui::Window::new(title)
            .id(egui::Id::unique("file browser"))
            .open(&mut open)
            .collapsible(false)
            .default_size([420.0, 360.0])
            .show(ctx, |ui| {
                ui.label(egui::RichText::new(hint).small());
                ui.horizontal(|ui| {
                    if ui.button("Up").clicked()
                        && let Some(p) = self.dir.parent()
                    {
                        go = Some(p.to_path_buf());
                    }
                    ui.monospace(self.dir.display().to_string());
                });
                if let Some(e) = &self.error {
                    ui.colored_label(egui::Color32::from_rgb(190, 0, 0), e);
                }
                egui::ScrollArea::vertical()
                    .max_height(280.0)
                    .show(ui, |ui| {
                        for (name, is_dir) in &self.entries {
                            let label = if *is_dir {
                                format!("{name}/")
                            } else {
                                name.clone()
                            };
                            if ui.selectable_label(false, label).clicked() {
                                let p = self.dir.join(name);
                                if *is_dir {
                                    go = Some(p);
                                } else {
                                    chosen = Some(p);
                                }
                            }
                        }
                        if self.entries.is_empty() && self.error.is_none() {
                            ui.label("(no folders or model files here)");
                        }
                    });
            });
        if let Some(dir) = go {
            self.dir = dir;
            self.list();
        }
        self.open = open && chosen.is_none();
        chosen
    }
}
