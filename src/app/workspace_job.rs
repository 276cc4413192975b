//! The workspace of the current model, computed with progress: points for the 3D overlay
//! (coloured by posture) and the 2D figure for the workspace tab (the same figure
//! `armlab workspace` writes). On the desktop a background thread computes it; in a browser
//! (no threads) [`WorkspaceJob::step`] computes one slice per frame.

use crate::figure::Theme;
use crate::figure::figures::Figures;
use crate::figure::workspace::{ColorBy, WsFigureOptions, WsView, workspace_figure};
use crate::kinematics::Robot;
use crate::scene::Dot;
use crate::workspace::{SampleOptions, planar_frame, point_cloud, sample};
use crate::render::Gpu;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::{Arc, OnceLock};

/// Samples drawn for the overlay.
pub const OVERLAY_SAMPLES: usize = 100_000;

/// What the job produces.
pub struct WorkspaceData {
    /// Dots for the 3D view.
    pub dots: Vec<Dot>,
    /// The 2D figure (None if no GPU adapter could be opened for it).
    pub figure: Option<image::RgbaImage>,
}

/// A running or finished workspace computation.
pub struct WorkspaceJob {
    progress: Arc<AtomicU32>,
    done: Arc<OnceLock<Result<WorkspaceData, String>>>,
    /// The slices still to compute (browser only; `None` with a thread, or once done).
    slices: std::sync::Mutex<Option<Slices>>,
}

/// What a sliced job still has to do (the browser's way: one slice per frame).
struct Slices {
    robot: Robot,
    title: String,
    /// Overlay samples drawn so far, and their dots.
    drawn: usize,
    dots: Vec<Dot>,
}

/// Overlay samples per slice (a few milliseconds of work).
const SLICE: usize = crate::workspace::SAMPLE_CHUNK;

const CLASS_COLORS: [[f32; 4]; 4] = [
    [0.0, 0.17, 0.45, 1.0],
    [0.79, 0.34, 0.0, 1.0],
    [0.6, 0.19, 0.39, 1.0],
    [0.09, 0.46, 0.81, 1.0],
];

impl WorkspaceJob {
    /// Starts computing for `robot` (named `title` in the figure) on a background thread; where
    /// there are no threads (a browser), [`Self::step`] computes it a slice at a time.
    pub fn start(robot: Robot, title: String) -> Self {
        let progress = Arc::new(AtomicU32::new(0));
        let done = Arc::new(OnceLock::new());
        if cfg!(target_arch = "wasm32") {
            let slices = Slices {
                robot,
                title,
                drawn: 0,
                dots: Vec::with_capacity(OVERLAY_SAMPLES),
            };
            return Self {
                progress,
                done,
                slices: std::sync::Mutex::new(Some(slices)),
            };
        }
        let (p, d) = (progress.clone(), done.clone());
        std::thread::spawn(move || {
            let result = compute(&robot, &title, &p);
            let _ = d.set(result);
        });
        Self {
            progress,
            done,
            slices: std::sync::Mutex::new(None),
        }
    }

    /// Computes the next slice of a sliced job (nothing for a threaded or finished one): a
    /// chunk of overlay samples, then the figure, drawn on `gpu` (the window's device).
    pub fn step(&self, gpu: Option<&Gpu>) {
        let Ok(mut guard) = self.slices.lock() else {
            return;
        };
        let Some(s) = guard.as_mut() else { return };
        if s.drawn < OVERLAY_SAMPLES {
            let n = SLICE.min(OVERLAY_SAMPLES - s.drawn);
            // Each slice its own seed: the same distribution as the threaded job's one draw.
            match overlay_dots(&s.robot, n, 1 + (s.drawn / SLICE) as u64, &|_| {}) {
                Ok(d) => s.dots.extend(d),
                Err(e) => {
                    let _ = self.done.set(Err(e));
                    *guard = None;
                    return;
                }
            }
            s.drawn += n;
            let f = s.drawn as f32 / OVERLAY_SAMPLES as f32 * 500.0;
            self.progress.store(f as u32, Ordering::Relaxed);
            return;
        }
        let figure = gpu
            .and_then(|g| Figures::with_gpu(g.clone()).ok())
            .and_then(|mut f| figure(&mut f, &s.robot, &s.title, &self.progress));
        let dots = std::mem::take(&mut s.dots);
        let _ = self.done.set(Ok(WorkspaceData { dots, figure }));
        *guard = None;
    }

    /// Fraction done while running; `None` once finished.
    pub fn progress(&self) -> Option<f32> {
        if self.done.get().is_some() {
            None
        } else {
            Some(self.progress.load(Ordering::Relaxed) as f32 / 1000.0)
        }
    }

    /// The overlay dots, once done.
    pub fn dots(&self) -> Option<&[Dot]> {
        self.done
            .get()
            .and_then(|r| r.as_ref().ok())
            .map(|d| d.dots.as_slice())
    }

    /// The 2D figure, once done.
    pub fn figure(&self) -> Option<&image::RgbaImage> {
        self.done
            .get()
            .and_then(|r| r.as_ref().ok())
            .and_then(|d| d.figure.as_ref())
    }

    /// The error, if the computation failed.
    pub fn error(&self) -> Option<&str> {
        self.done
            .get()
            .and_then(|r| r.as_ref().err())
            .map(String::as_str)
    }

    /// Blocks until done (tests, screenshots).
    pub fn wait(&self) {
        while self.done.get().is_none() {
            if self.slices.lock().is_ok_and(|s| s.is_some()) {
                self.step(None);
            } else {
                std::thread::sleep(std::time::Duration::from_millis(5));
            }
        }
    }
}

fn compute(robot: &Robot, title: &str, progress: &AtomicU32) -> Result<WorkspaceData, String> {
    let n = OVERLAY_SAMPLES;
    let dots = overlay_dots(robot, n, 1, &|k| {
        progress.store((k as f32 / n as f32 * 500.0) as u32, Ordering::Relaxed)
    })?;
    let figure = Figures::new()
        .ok()
        .and_then(|mut f| figure(&mut f, robot, title, progress));
    Ok(WorkspaceData { dots, figure })
}

/// `n` overlay dots from samples drawn with `seed`, coloured by posture.
fn overlay_dots(
    robot: &Robot,
    n: usize,
    seed: u64,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Vec<Dot>, String> {
    let opts = SampleOptions {
        samples: n,
        seed,
        classes: true,
        ..SampleOptions::default()
    };
    let samples = sample(robot, &opts, progress).map_err(|e| e.to_string())?;
    let cloud = point_cloud(&samples);
    Ok(cloud
        .positions
        .iter()
        .zip(&cloud.classes)
        .map(|(p, &c)| Dot {
            p: *p,
            color: CLASS_COLORS
                .get(c as usize)
                .copied()
                .unwrap_or([0.3, 0.3, 0.35, 1.0]),
            size_px: 2.0,
        })
        .collect())
}

/// The workspace tab's figure (the second half of the progress bar).
fn figure(
    figs: &mut Figures,
    robot: &Robot,
    title: &str,
    progress: &AtomicU32,
) -> Option<image::RgbaImage> {
    let view = if planar_frame(robot, 0).is_some() {
        WsView::Plane
    } else {
        WsView::Top
    };
    let o = WsFigureOptions {
        view,
        color_by: ColorBy::Posture,
        samples: 200_000,
        seed: 1,
        size: [1200, 900],
        theme: Theme::Light,
        end_effector: 0,
        point: Default::default(),
        caption: String::new(),
    };
    workspace_figure(figs, robot, &title.replace('_', " "), &o, &|x| {
        progress.store(500 + (x * 500.0) as u32, Ordering::Relaxed)
    })
    .ok()
    .map(|w| w.image)
}
