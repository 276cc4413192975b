//! The workspace of the current model, computed with progress: points for the 3D overlay
//! (coloured by posture) and the Workspace tab's figure (the same figure `armlab workspace` or
//! `armlab figure` writes). On the desktop a background thread computes it; in a browser (no
//! threads) [`WorkspaceJob::step`] computes one slice per frame. A job is cancelled at once when
//! the model changes ([`WorkspaceJob::cancel`]): it stops at its next check, so the next model's
//! job never waits behind it.

use crate::figure::Theme;
use crate::figure::figures::{Figures, PlotFrame};
use crate::figure::workspace::{
    ColorBy, WsFigure, WsFigureOptions, WsPlan, WsView, paint, paint_forming, plan,
};
use crate::kinematics::Robot;
use crate::offload::{Answer, Offload, Request, Spread, SpreadStep};
use crate::render::{Gpu, PendingRead};
use crate::scene::Dot;
use crate::workspace::{SampleOptions, TrackedPoint, compute_figure_data, point_cloud, sample};
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

/// Samples drawn for the overlay.
pub const OVERLAY_SAMPLES: usize = 100_000;

/// Which figure a job makes.
#[derive(Debug, Clone, PartialEq)]
pub enum JobFigure {
    /// A workspace figure with these options.
    Workspace(WsFigureOptions),
    /// One of the excerpt's figures that is not a workspace figure (Figs 2.31-2.33), by name,
    /// with its text scale (see [`crate::figure::workspace::WsFigureOptions::text_scale`]).
    Textbook(&'static str, f32),
}

/// What the job produces.
pub struct WorkspaceData {
    /// Dots for the 3D view.
    pub dots: Vec<Dot>,
    /// The 2D figure (None if no GPU adapter could be opened for it).
    pub figure: Option<image::RgbaImage>,
    /// Where the figure's plot data lie in its pixels (2D workspace views).
    pub frame: Option<PlotFrame>,
    /// Why there is no figure.
    pub figure_error: Option<String>,
}

/// A running or finished workspace computation.
pub struct WorkspaceJob {
    progress: Arc<AtomicU32>,
    done: Arc<OnceLock<Result<WorkspaceData, String>>>,
    cancelled: Arc<AtomicBool>,
    /// Whether a thread is still computing (it stops soon after a cancel).
    running: Arc<AtomicBool>,
    figure: JobFigure,
    /// The slices still to compute (browser only; `None` with a thread, or once done).
    slices: std::sync::Mutex<Option<Slices>>,
    /// The figure as it forms: the latest picture not taken yet ([`Self::take_preview`]).
    preview: Arc<Preview>,
}

/// The pictures of a figure as it forms.
#[derive(Default)]
struct Preview {
    /// The latest one not taken yet.
    latest: Mutex<Option<image::RgbaImage>>,
    /// How many were painted.
    count: AtomicU32,
}

impl Preview {
    /// Puts a newly painted picture up.
    fn put(&self, image: image::RgbaImage) {
        if let Ok(mut slot) = self.latest.lock() {
            *slot = Some(image);
            self.count.fetch_add(1, Ordering::Relaxed);
        }
    }
}

/// How often a forming figure is painted again (the coarse first look at once).
pub const PREVIEW_EVERY: std::time::Duration = std::time::Duration::from_millis(250);

/// What a sliced job still has to do (the browser's way: one slice per frame).
struct Slices {
    robot: Robot,
    spec: String,
    title: String,
    /// Overlay samples drawn so far, and their dots.
    drawn: usize,
    dots: Vec<Dot>,
    /// The figure, planned (with workers at once, else once the overlay is drawn).
    figure: Option<FigureSlices>,
    /// The finished figure (or why not), waiting for the overlay.
    ready: Option<Result<Figure, String>>,
}

/// The figure of a sliced job: planned on the window's device, its data computed by the
/// [`Offload`] worker (where there is one and the robot can travel to it) or here in one slice,
/// then painted and read back, each over as many frames as it takes.
struct FigureSlices {
    figs: Figures,
    plan: Option<WsPlan>,
    /// Where the figure's data are being computed.
    asked: Asked,
    /// The painted figure's pixels on their way back from the GPU, and its frame.
    readback: Option<(PendingRead, Option<PlotFrame>)>,
    /// A picture of the figure as it forms on its way back.
    forming: Option<PendingRead>,
    /// When the last one was painted (s, the caller's clock).
    last_preview: Option<f64>,
}

/// Seconds between two pictures of a figure as it forms that a sliced job paints.
pub const PAGE_PREVIEW_EVERY: f64 = 0.5;

/// Where a sliced job's figure data are being computed.
enum Asked {
    /// Nowhere yet.
    No,
    /// All of it by the first web worker.
    Whole,
    /// Spread over the pool; which workers are busy.
    Spread {
        spread: Box<Spread>,
        busy: Vec<bool>,
    },
}

/// Hands `request` to `worker`.
fn submit(worker: &mut dyn Offload, request: &Request) -> Result<(), String> {
    let json = serde_json::to_string(request).map_err(|e| e.to_string())?;
    if worker.submit(json) {
        Ok(())
    } else {
        Err("the web worker took no request".into())
    }
}

/// A worker's answer, read.
fn read_answer(json: &str) -> Result<Answer, String> {
    serde_json::from_str(json).map_err(|e| format!("unreadable answer: {e}"))
}

/// Asks the pool for a figure's data (spread over it, or whole to one worker; here in one slice
/// without workers or for a robot that cannot travel), or takes what the workers answered:
/// `None` while nothing new came.
fn answers(
    asked: &mut Asked,
    (robot, spec, request): (&Robot, &str, &crate::workspace::FigureRequest),
    pool: &mut [Box<dyn Offload>],
    progress: &AtomicU32,
) -> Option<Result<SpreadStep, String>> {
    match asked {
        Asked::No => match Request::new(robot, spec, request.clone()) {
            // A pool of web workers: the work spread over it, or all of it to one.
            Ok(r) if !pool.is_empty() => {
                *asked = match Spread::new(robot, &r, pool.len()) {
                    Some(spread) => Asked::Spread {
                        spread: Box::new(spread),
                        busy: vec![false; pool.len()],
                    },
                    None => match submit(&mut *pool[0], &r) {
                        Ok(()) => Asked::Whole,
                        Err(e) => return Some(Err(e)),
                    },
                };
                progress.store(600, Ordering::Relaxed);
                None
            }
            // No worker, or a robot that cannot travel: here, in one slice.
            _ => Some(
                compute_figure_data(robot, request, &|_| {})
                    .map(|d| SpreadStep::Done(Box::new(d)))
                    .map_err(|e| e.to_string()),
            ),
        },
        Asked::Whole => match pool.first_mut() {
            None => Some(Err("the web worker went away".into())),
            Some(worker) => worker.poll().map(|a| match read_answer(&a)? {
                Answer::Partial { map, rows_done } => Ok(SpreadStep::Partial(map, rows_done)),
                Answer::Data(d) => Ok(SpreadStep::Done(d)),
                Answer::Error(e) => Err(e),
                _ => Err("an answer that fits no request".into()),
            }),
        },
        Asked::Spread { spread, busy } => spread_step(spread, busy, pool),
    }
}

/// Takes the answers of the busy workers of the pool and hands the idle ones the next parts;
/// the figure's data once all of it is in, else the latest map as it forms (`None`: nothing
/// new).
fn spread_step(
    spread: &mut Spread,
    busy: &mut [bool],
    pool: &mut [Box<dyn Offload>],
) -> Option<Result<SpreadStep, String>> {
    let mut latest = None;
    for (worker, busy) in pool.iter_mut().zip(busy.iter_mut()) {
        if *busy && let Some(answer) = worker.poll() {
            *busy = false;
            match read_answer(&answer).and_then(|a| spread.take(a)) {
                Ok(SpreadStep::Working) => {}
                Ok(step @ SpreadStep::Partial(..)) => latest = Some(step),
                Ok(done @ SpreadStep::Done(_)) => return Some(Ok(done)),
                Err(e) => return Some(Err(e)),
            }
        }
        if !*busy && let Some(part) = spread.next_part() {
            if let Err(e) = submit(&mut **worker, &part) {
                return Some(Err(e));
            }
            *busy = true;
        }
    }
    latest.map(Ok)
}

/// Seconds of overlay samples a sliced job computes per frame (at least one chunk).
pub const SLICE_BUDGET: f64 = 0.03;

/// Overlay samples per chunk (a few milliseconds of work).
const SLICE: usize = crate::workspace::SAMPLE_CHUNK;

const CLASS_COLORS: [[f32; 4]; 4] = [
    [0.0, 0.17, 0.45, 1.0],
    [0.79, 0.34, 0.0, 1.0],
    [0.6, 0.19, 0.39, 1.0],
    [0.09, 0.46, 0.81, 1.0],
];

/// Why a job stopped without a result.
const CANCELLED: &str = "cancelled: the model changed";

impl WorkspaceJob {
    /// The options of a workspace figure of `robot` in `view` at `size` pixels, coloured by
    /// posture; `textbook` names the excerpt's figure it is (for its caption).
    pub fn options_for(
        robot: &Robot,
        view: WsView,
        size: [u32; 2],
        textbook: Option<&str>,
    ) -> WsFigureOptions {
        let _ = robot;
        WsFigureOptions {
            view,
            color_by: ColorBy::Posture,
            samples: 200_000,
            seed: 1,
            size,
            theme: Theme::Light,
            end_effector: 0,
            point: if textbook.is_some() {
                TrackedPoint::WristCentre
            } else {
                TrackedPoint::default()
            },
            caption: textbook.map_or_else(String::new, |name| {
                let source = crate::construction::textbook::Subject::source(name);
                format!(
                    "after {source} of Siciliano et al., Robotics: Modelling, Planning and Control"
                )
            }),
            text_scale: 1.0,
        }
    }

    /// Starts computing for `robot` (opened as `spec`, named `title` in the figure) on a
    /// background thread; where there are no threads (a browser), [`Self::step`] computes it a
    /// slice at a time.
    pub fn start(robot: Robot, spec: String, title: String, figure: JobFigure) -> Self {
        if cfg!(target_arch = "wasm32") {
            return Self::start_sliced(robot, spec, title, figure);
        }
        let progress = Arc::new(AtomicU32::new(0));
        let done = Arc::new(OnceLock::new());
        let cancelled = Arc::new(AtomicBool::new(false));
        let running = Arc::new(AtomicBool::new(true));
        let preview = Arc::new(Preview::default());
        let (p, d, c, f, r, v) = (
            progress.clone(),
            done.clone(),
            cancelled.clone(),
            figure.clone(),
            running.clone(),
            preview.clone(),
        );
        std::thread::spawn(move || {
            // A cancelled computation unwinds out of the progress callback (see
            // [`stop_if_cancelled`]); it is caught here and reported as cancelled.
            let run = std::panic::AssertUnwindSafe(|| compute(&robot, &title, &f, &p, &c, &v));
            let result = match std::panic::catch_unwind(run) {
                Ok(r) => r,
                Err(payload) if payload.is::<Cancelled>() => Err(CANCELLED.into()),
                Err(payload) => std::panic::resume_unwind(payload),
            };
            let _ = d.set(result);
            r.store(false, Ordering::Relaxed);
        });
        Self {
            progress,
            done,
            cancelled,
            running,
            figure,
            slices: std::sync::Mutex::new(None),
            preview,
        }
    }

    /// The browser's way on any platform: nothing runs until [`Self::step`] is called, once a
    /// frame.
    pub fn start_sliced(robot: Robot, spec: String, title: String, figure: JobFigure) -> Self {
        let slices = Slices {
            robot,
            spec,
            title,
            drawn: 0,
            dots: Vec::with_capacity(OVERLAY_SAMPLES),
            figure: None,
            ready: None,
        };
        Self {
            progress: Arc::new(AtomicU32::new(0)),
            done: Arc::new(OnceLock::new()),
            cancelled: Arc::new(AtomicBool::new(false)),
            running: Arc::new(AtomicBool::new(false)),
            figure,
            slices: std::sync::Mutex::new(Some(slices)),
            preview: Arc::default(),
        }
    }

    /// Stops the job: a thread stops at its next check (between samples chunks and before the
    /// figure), a sliced job at once.
    pub fn cancel(&self) {
        self.cancelled.store(true, Ordering::Relaxed);
        if let Ok(mut guard) = self.slices.lock() {
            *guard = None;
        }
        let _ = self.done.set(Err(CANCELLED.into()));
    }

    /// Computes the next slice of a sliced job (nothing for a threaded or finished one): chunks
    /// of overlay samples for at most [`SLICE_BUDGET`] seconds of `clock` (seconds); then the
    /// figure, drawn on `gpu` (the window's device), its data computed by the `pool` of web
    /// workers while frames go on, or here when there is none. Returns whether it worked here
    /// (then the next frame should come at once); `false` for a threaded or finished job, or
    /// while the workers compute.
    pub fn step(
        &self,
        gpu: Option<&Gpu>,
        pool: &mut [Box<dyn Offload>],
        clock: &dyn Fn() -> f64,
    ) -> bool {
        let now = clock();
        let Ok(mut guard) = self.slices.lock() else {
            return false;
        };
        let Some(s) = guard.as_mut() else {
            return false;
        };
        // With workers, the figure is asked for first, so that they compute it while the page
        // draws the overlay a slice at a time (and paints the figure as it forms).
        let with_workers = !pool.is_empty() && matches!(self.figure, JobFigure::Workspace(_));
        if with_workers
            && s.ready.is_none()
            && let Some(gpu) = gpu
            && (s.figure.is_none() || s.drawn < OVERLAY_SAMPLES)
        {
            let asked = s.figure.is_some();
            s.ready = s.figure_step(gpu, &self.figure, pool, &self.progress, &self.preview, now);
            if !asked {
                self.progress.store(0, Ordering::Relaxed);
                return true;
            }
        }
        if s.drawn < OVERLAY_SAMPLES {
            if let Err(e) = s.draw_overlay(clock, now) {
                let _ = self.done.set(Err(e));
                *guard = None;
                return false;
            }
            if s.figure.is_none() {
                let f = s.drawn as f32 / OVERLAY_SAMPLES as f32 * 500.0;
                self.progress.store(f as u32, Ordering::Relaxed);
            }
            return true;
        }
        let waiting = s
            .figure
            .as_ref()
            .is_some_and(|f| !matches!(f.asked, Asked::No));
        let finished = match (s.ready.take(), gpu) {
            (Some(ready), _) => Some(ready),
            (None, Some(gpu)) => {
                s.figure_step(gpu, &self.figure, pool, &self.progress, &self.preview, now)
            }
            (None, None) => Some(Err("no graphics device for the figure".into())),
        };
        if let Some(figure) = finished {
            let dots = std::mem::take(&mut s.dots);
            let (figure, frame, figure_error) = match figure {
                Ok((f, frame)) => (Some(f), frame, None),
                Err(e) => (None, None, Some(e)),
            };
            let data = WorkspaceData {
                dots,
                figure,
                frame,
                figure_error,
            };
            let _ = self.done.set(Ok(data));
            *guard = None;
        }
        !waiting
    }

    /// Fraction done while running; `None` once finished (or cancelled).
    pub fn progress(&self) -> Option<f32> {
        if self.done.get().is_some() {
            None
        } else {
            Some(self.progress.load(Ordering::Relaxed) as f32 / 1000.0)
        }
    }

    /// The figure as it forms, while the job runs: the latest picture painted since the last
    /// call (`None` if there is no new one, or once the job is done).
    pub fn take_preview(&self) -> Option<image::RgbaImage> {
        if self.done.get().is_some() {
            return None;
        }
        self.preview.latest.lock().ok()?.take()
    }

    /// How many pictures of the figure as it formed were painted so far.
    pub fn previews(&self) -> u32 {
        self.preview.count.load(Ordering::Relaxed)
    }

    /// The finished data.
    fn data(&self) -> Option<&WorkspaceData> {
        self.done.get().and_then(|r| r.as_ref().ok())
    }

    /// The overlay dots, once done.
    pub fn dots(&self) -> Option<&[Dot]> {
        self.data().map(|d| d.dots.as_slice())
    }

    /// Why there is no 2D figure, once done without one.
    pub fn figure_error(&self) -> Option<&str> {
        self.data().and_then(|d| d.figure_error.as_deref())
    }

    /// The 2D figure, once done.
    pub fn figure(&self) -> Option<&image::RgbaImage> {
        self.data().and_then(|d| d.figure.as_ref())
    }

    /// Where the figure's data lie in its pixels, once done (2D workspace views).
    pub fn frame(&self) -> Option<PlotFrame> {
        self.data().and_then(|d| d.frame)
    }

    /// The workspace figure's view and tracked point (`None` for a drawing of the excerpt).
    pub fn view(&self) -> Option<(WsView, TrackedPoint)> {
        match &self.figure {
            JobFigure::Workspace(o) => Some((o.view, o.point)),
            JobFigure::Textbook(..) => None,
        }
    }

    /// The error, if the computation failed (or was cancelled).
    pub fn error(&self) -> Option<&str> {
        self.done
            .get()
            .and_then(|r| r.as_ref().err())
            .map(String::as_str)
    }

    /// Whether a background thread is still computing (a cancelled one stops after the chunk
    /// of samples it is on; a sliced job computes only in [`Self::step`]).
    pub fn computing(&self) -> bool {
        self.running.load(Ordering::Relaxed)
    }

    /// Whether the job was cancelled.
    pub fn is_cancelled(&self) -> bool {
        self.cancelled.load(Ordering::Relaxed)
    }

    /// Blocks until done (tests, screenshots).
    pub fn wait(&self) {
        while self.done.get().is_none() {
            if self.slices.lock().is_ok_and(|s| s.is_some()) {
                self.step(None, &mut [], &native_clock);
            } else {
                std::thread::sleep(std::time::Duration::from_millis(5));
            }
        }
    }
}

impl Drop for WorkspaceJob {
    /// A job nobody holds any more stops computing.
    fn drop(&mut self) {
        self.cancelled.store(true, Ordering::Relaxed);
    }
}

/// A finished figure: its pixels and, for the 2D workspace views, its frame.
type Figure = (image::RgbaImage, Option<PlotFrame>);

impl Slices {
    /// Overlay samples in chunks until the frame's budget is spent (`clock` in seconds, the
    /// frame begun at `now`): a frame costs more than a chunk of a simple arm's samples (on a
    /// software rasterizer, 50-100 ms against a few).
    fn draw_overlay(&mut self, clock: &dyn Fn() -> f64, now: f64) -> Result<(), String> {
        while self.drawn < OVERLAY_SAMPLES {
            let n = SLICE.min(OVERLAY_SAMPLES - self.drawn);
            // Each chunk its own seed: the same distribution as the threaded job's one draw.
            let seed = 1 + (self.drawn / SLICE) as u64;
            self.dots
                .extend(overlay_dots(&self.robot, n, seed, &|_| {})?);
            self.drawn += n;
            if clock() - now >= SLICE_BUDGET {
                break;
            }
        }
        Ok(())
    }

    /// One slice of the figure; `Some(figure or why not)` once it is finished.
    fn figure_step(
        &mut self,
        gpu: &Gpu,
        which: &JobFigure,
        pool: &mut [Box<dyn Offload>],
        progress: &AtomicU32,
        preview: &Preview,
        now: f64,
    ) -> Option<Result<Figure, String>> {
        if self.figure.is_none() {
            match self.plan_figure(gpu, which) {
                Ok(f) => self.figure = Some(f),
                Err(e) => return Some(Err(e)),
            }
        }
        let f = self.figure.as_mut()?;
        if let Some((read, frame)) = &f.readback {
            return read
                .poll(&gpu.device)
                .map(|r| r.map(|img| (img, *frame)).map_err(|e| e.to_string()));
        }
        let Some(plan) = &f.plan else {
            // A drawing of the excerpt: made here, in one slice.
            let JobFigure::Textbook(name, text_scale) = which else {
                return Some(Err("no figure planned".into()));
            };
            f.figs.text_scale = *text_scale;
            return Some(
                crate::headless::textbook_figure(&mut f.figs, name, [1200, 900], Theme::Light)
                    .map(|img| (img, None))
                    .map_err(|e| e.to_string()),
            );
        };
        // The figure as it forms: a picture on its way back is shown before the next answers
        // are taken.
        if let Some(read) = &f.forming {
            let r = read.poll(&gpu.device)?;
            f.forming = None;
            if let Ok(img) = r {
                preview.put(img);
            }
        }
        let answers = answers(
            &mut f.asked,
            (&self.robot, &self.spec, &plan.request),
            pool,
            progress,
        );
        let data = match answers? {
            Ok(SpreadStep::Done(d)) => *d,
            Ok(SpreadStep::Partial(map, rows_done)) => {
                // At most one picture every PAGE_PREVIEW_EVERY seconds: each is painted by the
                // page (on a software rasterizer, the CPU the workers compute on).
                let due = f.last_preview.is_none_or(|t| now - t >= PAGE_PREVIEW_EVERY);
                if due && paint_forming(&mut f.figs, plan, &map, rows_done).is_ok() {
                    f.forming = f.figs.take_deferred();
                    f.last_preview = Some(now);
                }
                return None;
            }
            Ok(SpreadStep::Working) => return None,
            Err(e) => return Some(Err(e)),
        };
        let frame = match paint(&mut f.figs, &self.robot, plan, &data) {
            Ok(w) => w.frame,
            Err(e) => return Some(Err(e.to_string())),
        };
        f.readback = f.figs.take_deferred().map(|r| (r, frame));
        progress.store(950, Ordering::Relaxed);
        f.readback
            .is_none()
            .then(|| Err("the figure was not read back".to_string()))
    }

    /// The figure's device and, for a workspace figure, its plan.
    fn plan_figure(&self, gpu: &Gpu, which: &JobFigure) -> Result<FigureSlices, String> {
        let mut figs = Figures::with_gpu(gpu.clone()).map_err(|e| e.to_string())?;
        figs.defer_readback();
        let plan = match which {
            JobFigure::Workspace(o) => {
                Some(plan(&mut figs, &self.robot, &self.title, o).map_err(|e| e.to_string())?)
            }
            JobFigure::Textbook(..) => None,
        };
        Ok(FigureSlices {
            figs,
            plan,
            asked: Asked::No,
            readback: None,
            forming: None,
            last_preview: None,
        })
    }
}

fn compute(
    robot: &Robot,
    title: &str,
    which: &JobFigure,
    progress: &AtomicU32,
    cancelled: &AtomicBool,
    preview: &Preview,
) -> Result<WorkspaceData, String> {
    // The figure first, so that it starts forming at once; the overlay's dots show with it.
    let figure = Figures::new()
        .map_err(|e| e.to_string())
        .and_then(|mut figs| {
            let on_progress = |x: f32| {
                stop_if_cancelled(cancelled);
                progress.store((x * 500.0) as u32, Ordering::Relaxed)
            };
            match which {
                JobFigure::Workspace(o) => crate::headless::workspace_figure_forming(
                    &mut figs,
                    robot,
                    title,
                    o,
                    &on_progress,
                    PREVIEW_EVERY,
                    &mut |image, _| preview.put(image),
                )
                .map(|WsFigure { image, frame, .. }| (image, frame))
                .map_err(|e| e.to_string()),
                JobFigure::Textbook(name, text_scale) => {
                    figs.text_scale = *text_scale;
                    crate::headless::textbook_figure(&mut figs, name, [1200, 900], Theme::Light)
                        .map(|img| (img, None))
                        .map_err(|e| e.to_string())
                }
            }
        });
    if cancelled.load(Ordering::Relaxed) {
        return Err(CANCELLED.into());
    }
    let n = OVERLAY_SAMPLES;
    let dots = overlay_dots(robot, n, 1, &|k| {
        stop_if_cancelled(cancelled);
        progress.store(
            500 + (k as f32 / n as f32 * 500.0) as u32,
            Ordering::Relaxed,
        )
    })?;
    let (figure, frame, figure_error) = match figure {
        Ok((f, frame)) => (Some(f), frame, None),
        Err(e) => (None, None, Some(e)),
    };
    Ok(WorkspaceData {
        dots,
        figure,
        frame,
        figure_error,
    })
}

/// Seconds since the first call: the clock of a sliced job run natively (tests, screenshots;
/// a browser hands in its own).
pub fn native_clock() -> f64 {
    static START: OnceLock<std::time::Instant> = OnceLock::new();
    START
        .get_or_init(std::time::Instant::now)
        .elapsed()
        .as_secs_f64()
}

/// The payload a cancelled threaded job unwinds with.
struct Cancelled;

/// Stops a threaded job's computation at once when it was cancelled: called from the progress
/// callbacks, which the compute layers call after every chunk of work (also from rayon's
/// workers, which hand the unwinding on to the job's thread). `resume_unwind` runs no panic
/// hook, so nothing is printed; the job's thread catches it (salsa cancels queries the same
/// way). The compute layers stay free of any notion of cancellation.
fn stop_if_cancelled(cancelled: &AtomicBool) {
    if cancelled.load(Ordering::Relaxed) {
        std::panic::resume_unwind(Box::new(Cancelled));
    }
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
