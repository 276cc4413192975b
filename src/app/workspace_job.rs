//! The workspace of the current model, computed with progress: points for the 3D overlay
//! (coloured by posture) and the 2D figure for the workspace tab (the same figure
//! `armlab workspace` writes). On the desktop a background thread computes it; in a browser
//! (no threads) [`WorkspaceJob::step`] computes one slice per frame.

use crate::figure::Theme;
use crate::figure::figures::Figures;
use crate::figure::workspace::{ColorBy, WsFigureOptions, WsPlan, WsView, paint, plan};
use crate::kinematics::Robot;
use crate::offload::{Answer, Offload, Request};
use crate::render::{Gpu, PendingRead};
use crate::scene::Dot;
use crate::workspace::{SampleOptions, compute_figure_data, planar_frame, point_cloud, sample};
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
    /// Why there is no figure.
    pub figure_error: Option<String>,
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
    /// Once the overlay is drawn: the figure, made again as results come in.
    figure: Option<FigureSlices>,
}

/// The figure of a sliced job: planned on the window's device, its data computed by the
/// [`Offload`] worker (where there is one and the robot can travel to it) or here in one slice,
/// then painted and read back, each over as many frames as it takes.
struct FigureSlices {
    figs: Figures,
    plan: WsPlan,
    /// A request is with the worker.
    asked: bool,
    /// The painted figure's pixels on their way back from the GPU.
    readback: Option<PendingRead>,
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
        if cfg!(target_arch = "wasm32") {
            return Self::start_sliced(robot, title);
        }
        let progress = Arc::new(AtomicU32::new(0));
        let done = Arc::new(OnceLock::new());
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

    /// The browser's way on any platform: nothing runs until [`Self::step`] is called, once a
    /// frame.
    pub fn start_sliced(robot: Robot, title: String) -> Self {
        let slices = Slices {
            robot,
            title,
            drawn: 0,
            dots: Vec::with_capacity(OVERLAY_SAMPLES),
            figure: None,
        };
        Self {
            progress: Arc::new(AtomicU32::new(0)),
            done: Arc::new(OnceLock::new()),
            slices: std::sync::Mutex::new(Some(slices)),
        }
    }

    /// Computes the next slice of a sliced job (nothing for a threaded or finished one): a
    /// chunk of overlay samples; then the figure, drawn on `gpu` (the window's device), its
    /// statistics and map computed by `offload` (a web worker) while frames go on, or here
    /// when there is none.
    /// Returns whether it worked here (then the next frame should come at once); `false` for
    /// a threaded or finished job, or while the worker computes.
    pub fn step(&self, gpu: Option<&Gpu>, offload: Option<&mut (dyn Offload + 'static)>) -> bool {
        let Ok(mut guard) = self.slices.lock() else {
            return false;
        };
        let Some(s) = guard.as_mut() else {
            return false;
        };
        if s.drawn < OVERLAY_SAMPLES {
            let n = SLICE.min(OVERLAY_SAMPLES - s.drawn);
            // Each slice its own seed: the same distribution as the threaded job's one draw.
            match overlay_dots(&s.robot, n, 1 + (s.drawn / SLICE) as u64, &|_| {}) {
                Ok(d) => s.dots.extend(d),
                Err(e) => {
                    let _ = self.done.set(Err(e));
                    *guard = None;
                    return false;
                }
            }
            s.drawn += n;
            let f = s.drawn as f32 / OVERLAY_SAMPLES as f32 * 500.0;
            self.progress.store(f as u32, Ordering::Relaxed);
            return true;
        }
        let waiting = s.figure.as_ref().is_some_and(|f| f.asked);
        let finished = match gpu {
            Some(gpu) => s.figure_step(gpu, offload, &self.progress),
            None => Some(Err("no graphics device for the figure".into())),
        };
        if let Some(figure) = finished {
            let dots = std::mem::take(&mut s.dots);
            let (figure, figure_error) = match figure {
                Ok(f) => (Some(f), None),
                Err(e) => (None, Some(e)),
            };
            let data = WorkspaceData {
                dots,
                figure,
                figure_error,
            };
            let _ = self.done.set(Ok(data));
            *guard = None;
        }
        !waiting
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

    /// Why there is no 2D figure, once done without one.
    pub fn figure_error(&self) -> Option<&str> {
        self.done
            .get()
            .and_then(|r| r.as_ref().ok())
            .and_then(|d| d.figure_error.as_deref())
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
                self.step(None, None);
            } else {
                std::thread::sleep(std::time::Duration::from_millis(5));
            }
        }
    }
}

impl Slices {
    /// One slice of the figure; `Some(figure or why not)` once it is finished.
    fn figure_step(
        &mut self,
        gpu: &Gpu,
        offload: Option<&mut (dyn Offload + 'static)>,
        progress: &AtomicU32,
    ) -> Option<Result<image::RgbaImage, String>> {
        if self.figure.is_none() {
            let planned = Figures::with_gpu(gpu.clone()).and_then(|mut figs| {
                figs.defer_readback();
                let plan = plan(
                    &mut figs,
                    &self.robot,
                    &figure_title(&self.title),
                    &options(&self.robot),
                )?;
                Ok(FigureSlices {
                    figs,
                    plan,
                    asked: false,
                    readback: None,
                })
            });
            match planned {
                Ok(f) => self.figure = Some(f),
                Err(e) => return Some(Err(e.to_string())),
            }
        }
        let f = self.figure.as_mut()?;
        if let Some(read) = &f.readback {
            return read.poll(&gpu.device).map(|r| r.map_err(|e| e.to_string()));
        }
        let data = match (f.asked, offload) {
            (true, Some(offload)) => {
                let answer = offload.poll()?;
                match serde_json::from_str::<Answer>(&answer) {
                    Ok(Answer::Data(d)) => *d,
                    Ok(Answer::Error(e)) => return Some(Err(e)),
                    Err(e) => return Some(Err(format!("unreadable answer: {e}"))),
                }
            }
            (true, None) => return Some(Err("the web worker went away".into())),
            (false, Some(offload))
                if let Ok(r) = Request::new(&self.robot, &self.title, f.plan.request.clone()) =>
            {
                let json = serde_json::to_string(&r).map_err(|e| e.to_string());
                match json.map(|j| offload.submit(j)) {
                    Ok(true) => {}
                    Ok(false) => return Some(Err("the web worker took no request".into())),
                    Err(e) => return Some(Err(e)),
                }
                f.asked = true;
                progress.store(600, Ordering::Relaxed);
                return None;
            }
            // No worker, or a robot that cannot travel: here, in one slice.
            (false, _) => match compute_figure_data(&self.robot, &f.plan.request, &|_| {}) {
                Ok(d) => d,
                Err(e) => return Some(Err(e.to_string())),
            },
        };
        if let Err(e) = paint(&mut f.figs, &self.robot, &f.plan, &data) {
            return Some(Err(e.to_string()));
        }
        f.readback = f.figs.take_deferred();
        progress.store(950, Ordering::Relaxed);
        f.readback
            .is_none()
            .then(|| Err("the figure was not read back".to_string()))
    }
}

fn compute(robot: &Robot, title: &str, progress: &AtomicU32) -> Result<WorkspaceData, String> {
    let n = OVERLAY_SAMPLES;
    let dots = overlay_dots(robot, n, 1, &|k| {
        progress.store((k as f32 / n as f32 * 500.0) as u32, Ordering::Relaxed)
    })?;
    let figure = Figures::new()
        .map_err(|e| e.to_string())
        .and_then(|mut figs| {
            let on_progress = |x: f32| progress.store(500 + (x * 500.0) as u32, Ordering::Relaxed);
            crate::headless::workspace_figure(
                &mut figs,
                robot,
                &figure_title(title),
                &options(robot),
                &on_progress,
            )
            .map(|w| w.image)
            .map_err(|e| e.to_string())
        });
    let (figure, figure_error) = match figure {
        Ok(f) => (Some(f), None),
        Err(e) => (None, Some(e)),
    };
    Ok(WorkspaceData {
        dots,
        figure,
        figure_error,
    })
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

/// The robot's name in the workspace tab's figure.
fn figure_title(title: &str) -> String {
    title.replace('_', " ")
}

/// The workspace tab's figure: the arm's plane (planar arms) or the top view, coloured by
/// posture, 1200 x 900 pixels.
fn options(robot: &Robot) -> WsFigureOptions {
    let view = if planar_frame(robot, 0).is_some() {
        WsView::Plane
    } else {
        WsView::Top
    };
    WsFigureOptions {
        view,
        color_by: ColorBy::Posture,
        samples: 200_000,
        seed: 1,
        size: [1200, 900],
        theme: Theme::Light,
        end_effector: 0,
        point: Default::default(),
        caption: String::new(),
    }
}
