//! Frame timing of the real window (`armlab view --measure-frames N`): the IK target is dragged
//! along a small circle, one step per frame, with repaints requested back to back, and the
//! wall-clock time between frames is recorded (layout, IK, 3D view, egui paint and present).

use crate::kinematics::Pose;
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// Frames skipped before timing starts (window mapping, first shader compilation).
const WARM_UP: usize = 10;

/// The target of drag step `k` around `start`: a circle of 30 mm radius in the world y-z
/// plane through the start position, 0.05 rad per step.
pub fn drag_step(start: &Pose, k: u32) -> Pose {
    let a = k as f64 * 0.05;
    let mut t = *start;
    t.translation.vector.y += 0.03 * a.sin();
    t.translation.vector.z += 0.03 * (1.0 - a.cos());
    t
}

/// What `--measure-frames` prints.
#[derive(Debug, Clone, PartialEq)]
pub struct FrameReport {
    /// Frames timed.
    pub frames: usize,
    /// Median frame time (ms).
    pub median_ms: f64,
    /// 95th percentile (ms).
    pub p95_ms: f64,
    /// Mean (ms).
    pub mean_ms: f64,
    /// Window size (physical pixels).
    pub size_px: [u32; 2],
    /// The graphics adapter (name and driver).
    pub adapter: String,
}

impl std::fmt::Display for FrameReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} frames at {}x{} on {}: median {:.1} ms, p95 {:.1} ms, mean {:.1} ms",
            self.frames,
            self.size_px[0],
            self.size_px[1],
            self.adapter,
            self.median_ms,
            self.p95_ms,
            self.mean_ms
        )
    }
}

/// Drives and times the live app for a number of frames, then closes the window.
pub struct FrameProbe {
    frames: usize,
    seen: usize,
    times_ms: Vec<f64>,
    last: Option<Instant>,
    start: Option<Pose>,
    /// Where the report goes when the run is over.
    pub report: Arc<Mutex<Option<FrameReport>>>,
    /// The adapter, for the report.
    pub adapter: String,
}

impl FrameProbe {
    /// A probe timing `frames` frames after the warm-up.
    pub fn new(frames: usize) -> Self {
        Self {
            frames: frames.max(1),
            seen: 0,
            times_ms: Vec::with_capacity(frames),
            last: None,
            start: None,
            report: Arc::new(Mutex::new(None)),
            adapter: String::new(),
        }
    }

    /// Called at the start of every frame: records the time since the previous one and moves
    /// the target of end-effector 0 one step. Returns true once enough frames are timed (the
    /// report is written then).
    pub fn frame(&mut self, state: &mut super::state::AppState, size_px: [u32; 2]) -> bool {
        if self.times_ms.len() >= self.frames {
            return true;
        }
        let now = Instant::now();
        if let Some(last) = self.last.replace(now)
            && self.seen > WARM_UP
        {
            self.times_ms.push((now - last).as_secs_f64() * 1e3);
        }
        self.seen += 1;
        let start = match (self.start, state.target(0)) {
            (Some(s), _) => s,
            (None, Ok(t)) => *self.start.insert(t.world_from_tool),
            (None, Err(_)) => return true,
        };
        let _ = state.set_target(0, drag_step(&start, self.seen as u32));
        if self.times_ms.len() < self.frames {
            return false;
        }
        let mut t = self.times_ms.clone();
        t.sort_by(f64::total_cmp);
        let pick = |q: f64| t[((t.len() - 1) as f64 * q).round() as usize];
        let report = FrameReport {
            frames: t.len(),
            median_ms: pick(0.5),
            p95_ms: pick(0.95),
            mean_ms: t.iter().sum::<f64>() / t.len() as f64,
            size_px,
            adapter: self.adapter.clone(),
        };
        if let Ok(mut r) = self.report.lock() {
            *r = Some(report);
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_drag_path_is_a_small_closed_circle() {
        let start = Pose::identity();
        let p = |k| drag_step(&start, k).translation.vector;
        assert!(p(0).norm() < 1e-15);
        let steps = (std::f64::consts::TAU / 0.05).round() as u32;
        for k in 0..steps {
            assert!((p(k) - nalgebra::Vector3::new(0.0, 0.0, 0.03)).norm() - 0.03 < 1e-12);
            assert!((p(k + 1) - p(k)).norm() <= 0.03 * 0.05 + 1e-12);
        }
    }
}
