//! What the app remembers across runs: the last model (a built-in name or a file), the view
//! toggles, projector mode and the angle unit. The window's size and place are remembered by
//! eframe itself. Stored as one JSON value in eframe's storage (`~/.local/share/armlab/app.ron`
//! on Linux); a value that cannot be read is ignored with a message, never a crash.

use super::layout::Layout;
use super::shell::AppUi;
use super::state::{AngleUnit, DisplayToggles, Level};
use serde::{Deserialize, Serialize};

/// The key of armlab's settings in eframe's storage.
pub const STORAGE_KEY: &str = "armlab.settings";

/// The remembered settings. Missing fields take their defaults, unknown ones are ignored, so
/// an older or newer settings file still reads.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Settings {
    /// The last model: a built-in name or an absolute path to a .toml/.urdf file.
    pub model: Option<String>,
    /// The view toggles.
    pub display: DisplayToggles,
    /// Large fonts and thick lines for a projector (read from older settings files; the
    /// layout below holds it now).
    pub projector: bool,
    /// The window's layout: projector mode and the side panels open in each mode.
    pub layout: Option<Layout>,
    /// Angles shown and typed in degrees (else radians).
    pub degrees: bool,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            model: None,
            display: DisplayToggles::default(),
            projector: false,
            layout: None,
            degrees: true,
        }
    }
}

impl Settings {
    /// What `app` shows now; a model file's path is made absolute so it opens from anywhere.
    /// In a browser a file the user handed over cannot be opened again: only a built-in model is
    /// remembered there.
    pub fn capture(app: &AppUi) -> Settings {
        let spec = app.state.spec();
        let model = if crate::kinematics::models::built_in(spec).is_some() {
            Some(spec.to_string())
        } else if cfg!(target_arch = "wasm32") {
            None
        } else {
            std::fs::canonicalize(spec)
                .map(|p| p.to_string_lossy().into_owned())
                .ok()
                .or_else(|| Some(spec.to_string()))
        };
        Settings {
            model,
            display: app.state.display,
            projector: app.layout.projector,
            layout: Some(app.layout),
            degrees: app.state.angle_unit() == AngleUnit::Degrees,
        }
    }

    /// Reads the stored text; `Err` says why it cannot be used.
    pub fn from_text(text: &str) -> Result<Settings, String> {
        serde_json::from_str(text).map_err(|e| format!("unreadable settings ({e})"))
    }

    /// The text to store.
    pub fn to_text(&self) -> String {
        serde_json::to_string(self).unwrap_or_default()
    }

    /// Applies the settings to `app`. The model is loaded unless `keep_model` (a model given on
    /// the command line wins); one that no longer loads leaves the current one and says why.
    pub fn apply(&self, app: &mut AppUi, keep_model: bool) {
        app.state.display = self.display;
        // A remembered layout can never open a broken window: it is validated (an older file's
        // projector flag alone gives the default panels of that mode).
        app.layout = Layout::validated(self.layout.or(Some(Layout {
            projector: self.projector,
            ..Layout::default()
        })));
        app.state.set_angle_unit(if self.degrees {
            AngleUnit::Degrees
        } else {
            AngleUnit::Radians
        });
        if let Some(model) = self.model.as_deref().filter(|_| !keep_model)
            && model != app.state.spec()
        {
            app.load(model);
        }
    }
}

/// Restores the settings stored under [`STORAGE_KEY`] (if any) into `app`; `settings_file` is
/// eframe's file, named in the message when it exists but gave nothing back (it could not be
/// parsed, and eframe starts from empty storage then).
pub fn restore(
    app: &mut AppUi,
    stored: Option<String>,
    settings_file: Option<&std::path::Path>,
    keep_model: bool,
) {
    match stored.map(|t| Settings::from_text(&t)) {
        Some(Ok(s)) => s.apply(app, keep_model),
        Some(Err(e)) => app
            .state
            .push_message(Level::Warning, format!("{e}; starting with the defaults")),
        None => {
            if let Some(f) = settings_file.filter(|f| f.is_file()) {
                app.state.push_message(
                    Level::Warning,
                    format!(
                        "the settings file {} could not be read; starting with the defaults",
                        f.display()
                    ),
                );
            }
        }
    }
}
