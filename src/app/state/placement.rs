//! Base placement in the app (issue 49), free of any GUI type: the task poses (a tasks file, or
//! IK targets added one by one), the floor area and grid, the placement computed in the
//! background ([`crate::reachability::place()`], every task solved exactly by IK at every base
//! position and yaw), and moving the robot's base to the best placement
//! ([`AppState::set_base`], a model edit that Undo takes back).
//!
//! A placement keeps the base it was computed for: "move the base there" puts the base at
//! `Trans(x, y, 0) Rz(yaw) world_from_base` of that base, so it moves to the same place however
//! often it is pressed, and the heat map stays true after the move.
//!
//! Units: m and rad.

use super::AppState;
use crate::collision::CollisionWorld;
use crate::kinematics::{Pose, Robot};
use crate::reachability::{
    PlacementError, PlacementMap, PlacementOptions, PlacementTask, TaskFileError, floor_shift,
    parse_tasks, place,
};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

/// The floor grid of a placement (m, counts).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaceSettings {
    /// The floor area `[x0, x1, y0, y1]` searched for the base (m, world frame).
    pub area: [f64; 4],
    /// The grid step (m).
    pub step: f64,
    /// Yaw angles `2 pi k / yaws` of the base.
    pub yaws: usize,
}

impl PlaceSettings {
    /// The grid (5 cm, 36 yaws) over a square of twice the arm's longest chain each way
    /// around `robot`'s base: every place from which it may reach a task near its base.
    pub fn around(robot: &Robot) -> Self {
        let reach = robot.longest_chain_length().max(0.1);
        let b = robot.base.translation.vector;
        let r = |v: f64| (v * 20.0).round() / 20.0;
        Self {
            area: [
                r(b.x - reach),
                r(b.x + reach),
                r(b.y - reach),
                r(b.y + reach),
            ],
            step: 0.05,
            yaws: 36,
        }
    }

    /// The library's options of these settings.
    pub fn options(&self) -> PlacementOptions {
        PlacementOptions {
            area: self.area,
            step: self.step,
            yaws: self.yaws,
            ..PlacementOptions::default()
        }
    }
}

/// A finished placement with what it was computed from.
#[derive(Debug, Clone)]
pub struct PlaceResult {
    /// The placement.
    pub map: PlacementMap,
    /// `world_from_base` of the robot it was computed for (the shifts apply on its left).
    pub base: Pose,
    /// Seconds it took (`None` where there is no clock: a browser).
    pub seconds: Option<f64>,
}

impl PlaceResult {
    /// The base pose of the best placement (`Trans(x, y, 0) Rz(yaw) base`), if any placement
    /// reaches a task.
    pub fn best_base(&self) -> Option<Pose> {
        let b = self.map.best.first()?;
        Some(floor_shift(b.detail.x, b.detail.y, b.detail.yaw) * self.base)
    }
}

type Outcome = Result<PlaceResult, PlacementError>;

/// A placement being computed.
pub struct PlaceJob {
    cancel: Arc<AtomicBool>,
    done: Arc<AtomicUsize>,
    /// Base positions in all.
    pub total: usize,
    outcome: Arc<Mutex<Option<Outcome>>>,
}

impl PlaceJob {
    /// Starts placing `robot` for `tasks` with `settings`, in `world` when given: on a thread
    /// on the desktop, at once in a browser.
    pub fn start(
        robot: Robot,
        tasks: Vec<PlacementTask>,
        world: Option<CollisionWorld>,
        settings: PlaceSettings,
    ) -> Self {
        let options = settings.options();
        let total = crate::reachability::PlacementGrid::new(&options, tasks.len().max(1))
            .map_or(0, |g| g.positions());
        let job = Self {
            cancel: Arc::new(AtomicBool::new(false)),
            done: Arc::new(AtomicUsize::new(0)),
            total,
            outcome: Arc::new(Mutex::new(None)),
        };
        let (cancel, done, outcome) = (job.cancel.clone(), job.done.clone(), job.outcome.clone());
        let run = move || {
            let progress = |d: usize| done.store(d, Ordering::Relaxed);
            #[cfg(not(target_arch = "wasm32"))]
            let started = std::time::Instant::now();
            let placed = place(&robot, &tasks, world.as_ref(), &options, &cancel, &progress);
            #[cfg(not(target_arch = "wasm32"))]
            let seconds = Some(started.elapsed().as_secs_f64());
            #[cfg(target_arch = "wasm32")]
            let seconds = None;
            let result = placed.map(|map| PlaceResult {
                map,
                base: robot.base,
                seconds,
            });
            if let Ok(mut slot) = outcome.lock() {
                *slot = Some(result);
            }
        };
        if cfg!(target_arch = "wasm32") {
            run();
        } else {
            std::thread::spawn(run);
        }
        job
    }

    /// Base positions done so far.
    pub fn done(&self) -> usize {
        self.done.load(Ordering::Relaxed)
    }

    /// Stops the placement soon.
    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }

    fn take(&self) -> Option<Outcome> {
        self.outcome.lock().ok().and_then(|mut o| o.take())
    }
}

impl Drop for PlaceJob {
    fn drop(&mut self) {
        self.cancel();
    }
}

/// The placement's data: the tasks, the grid, the computation and its result.
#[derive(Default)]
pub struct PlacementOverlay {
    /// The task poses (world frame).
    pub tasks: Vec<PlacementTask>,
    /// The grid of the next placement (`None` until the section is first shown: then around
    /// the robot).
    pub settings: Option<PlaceSettings>,
    job: Option<PlaceJob>,
    result: Option<Arc<PlaceResult>>,
    /// Why the last placement (or tasks file) gave nothing.
    pub error: Option<String>,
}

impl PlacementOverlay {
    /// A copy of what is shown (the result shared, no job): a screenshot's.
    pub fn snapshot(&self) -> Self {
        Self {
            tasks: self.tasks.clone(),
            settings: self.settings,
            job: None,
            result: self.result.clone(),
            error: self.error.clone(),
        }
    }

    /// Reads a tasks file's `text` (named `name` in errors), replacing the tasks; returns how
    /// many were read.
    ///
    /// # Errors
    ///
    /// What [`parse_tasks`] finds wrong (the file, the line and the field named); the tasks stay
    /// as they were.
    pub fn read_tasks(&mut self, text: &str, name: &str) -> Result<usize, TaskFileError> {
        let tasks = parse_tasks(text, name)?;
        self.tasks = tasks;
        self.result = None;
        Ok(self.tasks.len())
    }

    /// Adds a task at `world_from_tool` (m), named by its number.
    pub fn add_task(&mut self, world_from_tool: Pose) {
        let name = format!("task {}", self.tasks.len() + 1);
        self.tasks.push(PlacementTask::new(name, world_from_tool));
    }

    /// Starts placing `state`'s robot for the tasks (in the cell when one is open and
    /// checked); a running placement is cancelled.
    pub fn start(&mut self, state: &AppState) {
        self.cancel();
        self.error = None;
        let settings = *self
            .settings
            .get_or_insert_with(|| PlaceSettings::around(state.robot()));
        let world = state
            .collision_world()
            .filter(|_| state.collisions_on())
            .cloned();
        self.job = Some(PlaceJob::start(
            state.robot().clone(),
            self.tasks.clone(),
            world,
            settings,
        ));
    }

    /// Stops the running placement, if any.
    pub fn cancel(&mut self) {
        if let Some(job) = self.job.take() {
            job.cancel();
        }
    }

    /// The running placement, if any.
    pub fn job(&self) -> Option<&PlaceJob> {
        self.job.as_ref()
    }

    /// The placement shown, if any.
    pub fn result(&self) -> Option<&PlaceResult> {
        self.result.as_deref()
    }

    /// Takes a finished placement; returns whether one came.
    pub fn poll(&mut self) -> bool {
        let Some(outcome) = self.job.as_ref().and_then(PlaceJob::take) else {
            return false;
        };
        self.job = None;
        match outcome {
            Ok(r) => self.result = Some(Arc::new(r)),
            Err(PlacementError::Cancelled { .. }) => {}
            Err(e) => self.error = Some(e.to_string()),
        }
        true
    }

    /// Blocks until the running placement is done and takes it (tests).
    pub fn wait(&mut self) {
        while self.job.is_some() {
            if !self.poll() {
                std::thread::sleep(std::time::Duration::from_millis(5));
            }
        }
    }
}

impl AppState {
    /// Moves the robot's base to `world_from_base` (m, world frame): a model edit (Undo takes
    /// it back); the targets follow the tool, the cell is checked again.
    pub fn set_base(&mut self, world_from_base: Pose) {
        if self.robot.base == world_from_base {
            return;
        }
        let before = self.robot.clone();
        self.robot.base = world_from_base;
        self.undo.push(before);
        self.redo.clear();
        self.after_model_edit();
    }
}
