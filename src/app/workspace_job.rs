//! The workspace of the current model, computed on a background thread with progress: points
//! for the 3D overlay (coloured by posture) and the 2D figure for the workspace tab (the same
//! figure `armlab workspace` writes).

use crate::figure::Theme;
use crate::figure::figures::Figures;
use crate::figure::workspace::{ColorBy, WsFigureOptions, WsView, workspace_figure};
use crate::kinematics::Robot;
use crate::scene::Dot;
use crate::workspace::{SampleOptions, planar_frame, point_cloud, sample};
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
}

const CLASS_COLORS: [[f32; 4]; 4] = [
    [0.0, 0.17, 0.45, 1.0],
    [0.79, 0.34, 0.0, 1.0],
    [0.6, 0.19, 0.39, 1.0],
    [0.09, 0.46, 0.81, 1.0],
];

impl WorkspaceJob {
    /// Starts computing for `robot` (named `title` in the figure).
    pub fn start(robot: Robot, title: String) -> Self {
        let progress = Arc::new(AtomicU32::new(0));
        let done = Arc::new(OnceLock::new());
        let (p, d) = (progress.clone(), done.clone());
        std::thread::spawn(move || {
            let result = compute(&robot, &title, &p);
            let _ = d.set(result);
        });
        Self { progress, done }
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
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
    }
}

fn compute(robot: &Robot, title: &str, progress: &AtomicU32) -> Result<WorkspaceData, String> {
    let n = OVERLAY_SAMPLES;
    let opts = SampleOptions {
        samples: n,
        seed: 1,
        classes: true,
        ..SampleOptions::default()
    };
    let samples = sample(robot, &opts, &|k| {
        progress.store((k as f32 / n as f32 * 500.0) as u32, Ordering::Relaxed)
    })
    .map_err(|e| e.to_string())?;
    let cloud = point_cloud(&samples);
    let dots = cloud
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
        .collect();
    let view = if planar_frame(robot, 0).is_some() {
        WsView::Plane
    } else {
        WsView::Top
    };
    let figure = Figures::new().ok().and_then(|mut f| {
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
        workspace_figure(&mut f, robot, &title.replace('_', " "), &o, &|x| {
            progress.store(500 + (x * 500.0) as u32, Ordering::Relaxed)
        })
        .ok()
        .map(|w| w.image)
    });
    Ok(WorkspaceData { dots, figure })
}
