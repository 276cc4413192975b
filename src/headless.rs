//! Headless figures: each figure planned, its data computed by the compute layers and painted,
//! in one call ([`workspace_figure`], [`textbook_figure`]); PNG files written deterministically
//! (same pixels, same bytes) and, with the command line, a progress bar shown only when standard
//! output is a terminal.

use crate::collision::CellScene;
use crate::figure::figures::{Figures, PlotFrame};
use crate::figure::workspace::{WsFigure, WsFigureOptions, WsPlan, paint, paint_forming, plan};
use crate::figure::{FigureError, Theme};
use crate::kinematics::Robot;
use crate::workspace::{
    MapForming, OneShot, WorkspaceMap, compute_figure_data_forming, compute_figure_data_in,
};
use std::path::Path;
use thiserror::Error;

/// A workspace figure of `robot` (named `title` in it), planned, computed here and painted.
/// `progress(fraction)` is called as work proceeds.
pub fn workspace_figure(
    figs: &mut Figures,
    robot: &Robot,
    title: &str,
    opts: &WsFigureOptions,
    progress: &(dyn Fn(f32) + Sync),
) -> Result<WsFigure, FigureError> {
    workspace_figure_in(figs, robot, title, opts, None, progress)
}

/// [`workspace_figure`] in a cell (`None`: empty space): a point counts as reached by a
/// posture only where that posture is within the limits and hits neither the arm nor the
/// cell's obstacles, decided cell by cell at a resolution the figure states; the obstacles are
/// drawn in the view ([`crate::workspace::compute_figure_data_in`]). Plane, top and side views.
pub fn workspace_figure_in(
    figs: &mut Figures,
    robot: &Robot,
    title: &str,
    opts: &WsFigureOptions,
    cell: Option<&CellScene>,
    progress: &(dyn Fn(f32) + Sync),
) -> Result<WsFigure, FigureError> {
    figs.text_scale = opts.text_scale;
    let plan = plan(figs, robot, title, opts)?;
    let data = compute_figure_data_in(robot, &plan.request, cell, progress, &mut OneShot)?;
    let figure = paint(figs, robot, &plan, &data)?;
    progress(1.0);
    Ok(figure)
}

/// [`workspace_figure`], showing the figure as it forms: the map's coarse first look and then,
/// at most one every `every`, the map refined so far, each painted and handed to `shown` with
/// its plot frame (a 3D or joint-space figure shows nothing before it is done). The figure
/// returned is the one [`workspace_figure`] makes.
pub fn workspace_figure_forming(
    figs: &mut Figures,
    robot: &Robot,
    title: &str,
    opts: &WsFigureOptions,
    progress: &(dyn Fn(f32) + Sync),
    every: std::time::Duration,
    shown: &mut dyn FnMut(image::RgbaImage, PlotFrame),
) -> Result<WsFigure, FigureError> {
    figs.text_scale = opts.text_scale;
    let plan = plan(figs, robot, title, opts)?;
    let mut painter = Painter {
        figs,
        plan: &plan,
        every,
        last: None,
        shown,
    };
    let data = compute_figure_data_forming(robot, &plan.request, progress, &mut painter)?;
    let figure = paint(figs, robot, &plan, &data)?;
    progress(1.0);
    Ok(figure)
}

/// Paints the partial maps of a forming figure, throttled.
struct Painter<'a> {
    figs: &'a mut Figures,
    plan: &'a WsPlan,
    every: std::time::Duration,
    /// When the last partial map was painted.
    last: Option<std::time::Instant>,
    shown: &'a mut dyn FnMut(image::RgbaImage, PlotFrame),
}

impl MapForming for Painter<'_> {
    fn wants(&mut self) -> bool {
        self.last.is_none_or(|t| t.elapsed() >= self.every)
    }

    fn partial(&mut self, map: &WorkspaceMap, rows_done: usize) {
        // A preview that cannot be painted is skipped: the finished figure reports the error.
        if let Ok((image, frame)) = paint_forming(self.figs, self.plan, map, rows_done) {
            (self.shown)(image, frame);
        }
        self.last = Some(std::time::Instant::now());
    }
}

/// Figure `name` of the excerpt ([`crate::construction::textbook::FIGURES`]) at `size` pixels.
pub fn textbook_figure(
    figs: &mut Figures,
    name: &str,
    size: [u32; 2],
    theme: Theme,
) -> Result<image::RgbaImage, FigureError> {
    let subject = crate::construction::textbook::subject(name)?;
    match crate::figure::textbook::workspace_options(&subject, name, size, theme) {
        Some((robot, title, opts)) => {
            Ok(workspace_figure(figs, robot, title, &opts, &|_| {})?.image)
        }
        None => crate::figure::textbook::paint(figs, &subject, size, theme),
    }
}

/// Figures for an output file: with vector capture on when `path` ends in `.svg` or `.pdf`.
pub fn figures_for(path: &Path) -> Result<Figures, FigureError> {
    let mut figs = Figures::new()?;
    figs.capture_vectors(vector_format(path).is_some());
    Ok(figs)
}

/// The vector format an output path asks for, by its extension (`svg`, `pdf`).
pub fn vector_format(path: &Path) -> Option<&'static str> {
    match path.extension()?.to_str()?.to_ascii_lowercase().as_str() {
        "svg" => Some("svg"),
        "pdf" => Some("pdf"),
        _ => None,
    }
}

#[cfg(feature = "app")]
/// Writes the figure just made with `figs` to `path`: PNG pixels (`img`), or, for `.svg` and
/// `.pdf`, what `figs` captured as vectors ([`figures_for`]).
pub fn write_figure(
    figs: &mut Figures,
    img: &image::RgbaImage,
    path: &Path,
) -> Result<(), HeadlessError> {
    let Some(format) = vector_format(path) else {
        return write_png(img, path);
    };
    let page = figs.take_vector().ok_or_else(|| HeadlessError::NoVector {
        path: path.to_path_buf(),
    })?;
    let svg = crate::figure::vector::to_svg(&page);
    let bytes = if format == "svg" {
        svg.into_bytes()
    } else {
        crate::figure::vector::svg_to_pdf(&svg).map_err(|source| HeadlessError::Pdf {
            path: path.to_path_buf(),
            source,
        })?
    };
    std::fs::write(path, bytes).map_err(|source| HeadlessError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Writing a figure failed.
#[derive(Debug, Error)]
pub enum HeadlessError {
    /// A vector file could not be written.
    #[error("cannot write {}: {source}", path.display())]
    Io {
        /// Output file.
        path: std::path::PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The PDF could not be made.
    #[cfg(feature = "app")]
    #[error("cannot write {}: {source}", path.display())]
    Pdf {
        /// Output file.
        path: std::path::PathBuf,
        /// The cause.
        source: crate::figure::vector::PdfError,
    },
    /// The figure was not captured as vectors (a bug: the figure bypassed [`figures_for`]).
    #[error("cannot write {}: the figure was not captured as vectors", path.display())]
    NoVector {
        /// Output file.
        path: std::path::PathBuf,
    },
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
#[cfg(feature = "app")]
pub struct Progress(Option<indicatif::ProgressBar>);

#[cfg(feature = "app")]
impl Progress {
    /// A bar of `total` steps with a message.
    pub fn new(total: u64, message: &str) -> Self {
        use std::io::IsTerminal;
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
