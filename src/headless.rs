//! Headless output: PNG files written deterministically (same pixels, same bytes) and a
//! progress bar shown only when standard output is a terminal.

use std::io::IsTerminal;
use std::path::Path;
use thiserror::Error;

/// Writing a figure failed.
#[derive(Debug, Error)]
pub enum HeadlessError {
    /// The PNG could not be encoded or written.
    #[error("cannot write {}: {source}", path.display())]
    Write {
        /// Output file.
        path: std::path::PathBuf,
        /// The cause.
        source: image::ImageError,
    },
}

/// Writes `img` as an 8-bit RGBA PNG (fast compression, no timestamps or metadata, so the same
/// pixels always give the same bytes).
pub fn write_png(img: &image::RgbaImage, path: &Path) -> Result<(), HeadlessError> {
    let wrap = |source| HeadlessError::Write {
        path: path.to_path_buf(),
        source,
    };
    let file = std::fs::File::create(path).map_err(|e| wrap(image::ImageError::IoError(e)))?;
    crate::figure::encode_png(img, std::io::BufWriter::new(file)).map_err(wrap)
}

/// A progress bar on stderr when stdout is a terminal; a no-op otherwise.
pub struct Progress(Option<indicatif::ProgressBar>);

impl Progress {
    /// A bar of `total` steps with a message.
    pub fn new(total: u64, message: &str) -> Self {
        if !std::io::stdout().is_terminal() {
            return Self(None);
        }
        let bar = indicatif::ProgressBar::new(total);
        if let Ok(style) =
            indicatif::ProgressStyle::with_template("{msg} [{bar:40}] {percent:>3}% {elapsed}")
        {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_message(message.to_string());
        Self(Some(bar))
    }

    /// Sets the position.
    pub fn set(&self, pos: u64) {
        if let Some(b) = &self.0 {
            b.set_position(pos);
        }
    }

    /// Removes the bar.
    pub fn finish(&self) {
        if let Some(b) = &self.0 {
            b.finish_and_clear();
        }
    }
}
