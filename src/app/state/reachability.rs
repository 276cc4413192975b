//! The reachability overlay's data (issue 49), free of any GUI type: the map's settings, the
//! computation running in the background (cancellable, with its progress), the finished map and
//! what the user looks at in it: the slice plane, the voxel pointed at or pinned, the roll shown
//! and the sample the target was moved to.
//!
//! On the desktop a thread computes the map ([`crate::reachability::compute_reachability`],
//! itself parallel); in a browser, which has no threads, [`MapJob::start`] computes it at once.
//! A map belongs to the model generation it was computed for ([`AppState::generation`]): a new
//! model, an edited DH table or a moved base makes it stale, and [`ReachabilityOverlay::poll`]
//! drops it (and starts again while the overlay is shown).
//!
//! Units: m and rad; the voxel index is a fraction in [0, 1].

use super::AppState;
use crate::collision::CollisionWorld;
use crate::kinematics::{Pose, Robot};
use crate::reachability::{
    MapControl, MapOptions, ReachabilityError, ReachabilityMap, SampleSolution,
    compute_reachability, solutions_at,
};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

/// How finely the overlay's map is sampled (m, counts).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapSettings {
    /// Voxel edge (m).
    pub voxel_m: f64,
    /// Approach directions N of the Fibonacci sphere.
    pub directions: usize,
    /// Rolls R about each direction.
    pub rolls: usize,
}

impl MapSettings {
    /// Fast enough to turn on in a lesson (a second or two for a six-joint arm on two cores):
    /// 10 cm voxels, 50 directions, 4 rolls.
    pub const FAST: MapSettings = MapSettings {
        voxel_m: 0.10,
        directions: 50,
        rolls: 4,
    };
    /// The map: 5 cm voxels, 200 directions, 8 rolls (under a minute for the UR5 on two
    /// cores).
    pub const FULL: MapSettings = MapSettings {
        voxel_m: 0.05,
        directions: 200,
        rolls: 8,
    };

    /// The map options of these settings for end-effector `ee`.
    pub fn options(&self, ee: usize) -> MapOptions {
        MapOptions {
            ee,
            voxel_m: self.voxel_m,
            directions: self.directions,
            rolls: self.rolls,
            ..MapOptions::default()
        }
    }
}

impl Default for MapSettings {
    fn default() -> Self {
        Self::FAST
    }
}

/// A ray in the world (m): where the pointer looks into the 3D view.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Its start (the camera's eye, or the near plane) (m, world frame).
    pub origin: [f64; 3],
    /// Its direction (unit, world frame).
    pub dir: [f64; 3],
}

/// A finished map with what it was computed from.
#[derive(Debug, Clone)]
pub struct ReachResult {
    /// The map.
    pub map: ReachabilityMap,
    /// The options it was computed with (for [`solutions_at`]).
    pub options: MapOptions,
    /// The cell's collision world it was computed in (`None`: no cell, or its checks off).
    pub world: Option<CollisionWorld>,
    /// The reachability index of every voxel ([`ReachabilityMap::index`]).
    pub index: Vec<f64>,
    /// Voxels with an index above 0.
    pub reached_voxels: usize,
    /// The model generation it belongs to.
    pub generation: u64,
    /// Seconds it took (`None` where there is no clock: a browser).
    pub seconds: Option<f64>,
}

type Outcome = Result<ReachResult, ReachabilityError>;

/// A map being computed.
pub struct MapJob {
    cancel: Arc<AtomicBool>,
    done: Arc<AtomicUsize>,
    total: Arc<AtomicUsize>,
    outcome: Arc<Mutex<Option<Outcome>>>,
    /// The settings it computes.
    pub settings: MapSettings,
    /// The model generation it computes for.
    pub generation: u64,
}

impl MapJob {
    /// Starts computing the map of `robot` (model generation `generation`) with `options`, in
    /// `world` when given: on a thread on the desktop, at once in a browser.
    pub fn start(
        robot: Robot,
        world: Option<CollisionWorld>,
        options: MapOptions,
        settings: MapSettings,
        generation: u64,
    ) -> Self {
        let job = Self {
            cancel: Arc::new(AtomicBool::new(false)),
            done: Arc::new(AtomicUsize::new(0)),
            total: Arc::new(AtomicUsize::new(0)),
            outcome: Arc::new(Mutex::new(None)),
            settings,
            generation,
        };
        let (cancel, done, total, outcome) = (
            job.cancel.clone(),
            job.done.clone(),
            job.total.clone(),
            job.outcome.clone(),
        );
        let run = move || {
            let progress = |d: usize, t: usize| {
                done.store(d, Ordering::Relaxed);
                total.store(t, Ordering::Relaxed);
            };
            let control = MapControl {
                cancel: Some(&cancel),
                progress: Some(&progress),
            };
            #[cfg(not(target_arch = "wasm32"))]
            let started = std::time::Instant::now();
            let computed = compute_reachability(&robot, &options, world.as_ref(), control);
            #[cfg(not(target_arch = "wasm32"))]
            let seconds = Some(started.elapsed().as_secs_f64());
            #[cfg(target_arch = "wasm32")]
            let seconds = None;
            let result = computed.map(|map| {
                let index = map.index();
                ReachResult {
                    reached_voxels: index.iter().filter(|&&f| f > 0.0).count(),
                    index,
                    map,
                    options,
                    world,
                    generation,
                    seconds,
                }
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

    /// Stops the computation soon (it ends with [`ReachabilityError::Cancelled`]).
    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }

    /// (voxels done, voxels in all) so far; (0, 0) before the first voxel.
    pub fn progress(&self) -> (usize, usize) {
        (
            self.done.load(Ordering::Relaxed),
            self.total.load(Ordering::Relaxed),
        )
    }

    /// The outcome once it is there (taken: a second call gives `None`).
    fn take(&self) -> Option<Outcome> {
        self.outcome.lock().ok().and_then(|mut o| o.take())
    }
}

impl Drop for MapJob {
    /// A job nobody holds any more stops computing.
    fn drop(&mut self) {
        self.cancel();
    }
}

/// The slice plane: voxels whose centre has coordinate `at_m` along `axis` (nearest layer).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slice {
    /// 0 = x, 1 = y, 2 = z (world axes).
    pub axis: usize,
    /// Where the plane cuts the axis (m, world frame); the nearest layer of voxels is shown.
    pub at_m: f64,
}

/// The sample the target was moved to, and the postures the map's computation gives there.
#[derive(Debug, Clone, PartialEq)]
pub struct Aimed {
    /// The voxel (flat C-order index).
    pub voxel: usize,
    /// The direction's index.
    pub direction: usize,
    /// The roll's index.
    pub roll: usize,
    /// Every solution behind the sample ([`solutions_at`]), within the limits and free of
    /// collision in the map's cell.
    pub solutions: Vec<SampleSolution>,
}

/// How one direction of a voxel is reached over the rolls shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DirectionReach {
    /// Every roll shown is reached.
    All,
    /// Some rolls are reached, not all (only when every roll is shown).
    Some,
    /// No roll shown is reached.
    None,
}

/// The overlay's data (see the module documentation).
#[derive(Default)]
pub struct ReachabilityOverlay {
    /// The settings of the next computation.
    pub settings: MapSettings,
    job: Option<MapJob>,
    result: Option<Arc<ReachResult>>,
    /// Why the last computation gave no map.
    pub error: Option<String>,
    /// The slice plane shown (`None` until a map came: then through the base, across y).
    pub slice: Option<Slice>,
    /// Draw every reached voxel as a dot, besides the slice.
    pub all_voxels: bool,
    /// The voxel under the pointer (on the slice).
    pub hovered: Option<usize>,
    /// The voxel clicked (its directions stay shown while the pointer moves away).
    pub pinned: Option<usize>,
    /// The direction of the pinned voxel's sphere under the pointer.
    pub hovered_direction: Option<usize>,
    /// The roll whose directions are shown (`None`: every roll).
    pub roll: Option<usize>,
    /// The sample the target was last moved to.
    pub aimed: Option<Aimed>,
}

impl ReachabilityOverlay {
    /// A copy of what is shown (the map shared, no job): a screenshot's.
    pub fn snapshot(&self) -> Self {
        Self {
            settings: self.settings,
            job: None,
            result: self.result.clone(),
            error: self.error.clone(),
            slice: self.slice,
            all_voxels: self.all_voxels,
            hovered: self.hovered,
            pinned: self.pinned,
            hovered_direction: self.hovered_direction,
            roll: self.roll,
            aimed: self.aimed.clone(),
        }
    }

    /// Starts computing the map of `state`'s robot for end-effector `ee` with the current
    /// settings, in the cell when one is open and checked (a running computation is cancelled).
    pub fn start(&mut self, state: &AppState, ee: usize) {
        self.cancel();
        let world = state
            .collision_world()
            .filter(|_| state.collisions_on())
            .cloned();
        let options = self.settings.options(ee);
        self.error = None;
        self.job = Some(MapJob::start(
            state.robot().clone(),
            world,
            options,
            self.settings,
            state.generation(),
        ));
    }

    /// Stops the running computation, if any (the map shown stays).
    pub fn cancel(&mut self) {
        if let Some(job) = self.job.take() {
            job.cancel();
        }
    }

    /// The running computation, if any.
    pub fn job(&self) -> Option<&MapJob> {
        self.job.as_ref()
    }

    /// Whether a computation is running.
    pub fn computing(&self) -> bool {
        self.job.is_some()
    }

    /// The map shown, if any.
    pub fn result(&self) -> Option<&ReachResult> {
        self.result.as_deref()
    }

    /// Takes a finished computation; drops a map (and a computation) of another model
    /// generation than `state`'s, and starts again when `shown` and the map was stale. Returns
    /// whether something changed.
    pub fn poll(&mut self, state: &AppState, ee: usize, shown: bool) -> bool {
        let generation = state.generation();
        let mut changed = false;
        if self
            .job
            .as_ref()
            .is_some_and(|j| j.generation != generation)
        {
            self.cancel();
            changed = true;
        }
        let stale = self
            .result
            .as_ref()
            .is_some_and(|r| r.generation != generation);
        if stale {
            self.drop_map();
            changed = true;
            if shown {
                self.start(state, ee);
            }
        }
        let Some(outcome) = self.job.as_ref().and_then(MapJob::take) else {
            return changed;
        };
        self.job = None;
        match outcome {
            Ok(r) => self.install(r, state),
            Err(ReachabilityError::Cancelled { .. }) => {}
            Err(e) => self.error = Some(e.to_string()),
        }
        true
    }

    /// Blocks until the running computation is done and takes it (tests, screenshots).
    pub fn wait(&mut self, state: &AppState, ee: usize) {
        while self.job.is_some() {
            if !self.poll(state, ee, false) {
                std::thread::sleep(std::time::Duration::from_millis(5));
            }
        }
    }

    fn drop_map(&mut self) {
        self.result = None;
        self.hovered = None;
        self.pinned = None;
        self.hovered_direction = None;
        self.aimed = None;
    }

    /// Shows a finished map: the slice kept (clamped into the grid) or, the first time, across
    /// y through the base; the roll shown kept when the map has it.
    fn install(&mut self, r: ReachResult, state: &AppState) {
        self.drop_map();
        let base = state.robot().base.translation.vector;
        let slice = self.slice.unwrap_or(Slice {
            axis: 1,
            at_m: base.y,
        });
        self.roll = self.roll.filter(|&k| k < r.map.rolls.len());
        self.result = Some(Arc::new(r));
        self.set_slice(slice);
    }

    /// Sets the slice plane, clamped into the grid (no map: kept as asked).
    pub fn set_slice(&mut self, slice: Slice) {
        let axis = slice.axis.min(2);
        let at_m = match self.slice_range(axis) {
            Some((lo, hi)) => slice.at_m.clamp(lo, hi),
            None => slice.at_m,
        };
        self.slice = Some(Slice { axis, at_m });
        // What was pointed at may have left the slice.
        self.hovered = None;
    }

    /// The centres of the first and last layers of voxels along `axis` (m), if there is a map.
    pub fn slice_range(&self, axis: usize) -> Option<(f64, f64)> {
        let g = &self.result.as_ref()?.map.grid;
        let lo = g.origin[axis];
        Some((lo, lo + g.voxel_m * g.dims[axis].saturating_sub(1) as f64))
    }

    /// The layer of the slice (voxel index along its axis), if there is a map.
    pub fn slice_layer(&self) -> Option<usize> {
        let (g, s) = (&self.result.as_ref()?.map.grid, self.slice?);
        let k = ((s.at_m - g.origin[s.axis]) / g.voxel_m).round();
        Some((k.max(0.0) as usize).min(g.dims[s.axis].saturating_sub(1)))
    }

    /// The voxels of the slice with an index above 0 (flat C-order indices).
    pub fn slice_voxels(&self) -> Vec<usize> {
        let (Some(r), Some(s), Some(layer)) = (self.result(), self.slice, self.slice_layer())
        else {
            return Vec::new();
        };
        (0..r.map.grid.len())
            .filter(|&v| r.index[v] > 0.0 && r.map.grid.ijk(v)[s.axis] == layer)
            .collect()
    }

    /// The voxel whose directions are shown: the one pinned, else the one pointed at.
    pub fn shown_voxel(&self) -> Option<usize> {
        self.pinned.or(self.hovered)
    }

    /// The reached voxel of the slice where `ray` crosses the slice plane, if any.
    pub fn voxel_on_ray(&self, ray: &Ray) -> Option<usize> {
        let (r, s, layer) = (self.result()?, self.slice?, self.slice_layer()?);
        let g = &r.map.grid;
        let plane = g.origin[s.axis] + g.voxel_m * layer as f64;
        let d = ray.dir[s.axis];
        if d.abs() < 1e-12 {
            return None;
        }
        let t = (plane - ray.origin[s.axis]) / d;
        if t < 0.0 {
            return None;
        }
        let mut p = [0, 1, 2].map(|a| ray.origin[a] + t * ray.dir[a]);
        p[s.axis] = plane;
        let v = g.flat(g.voxel_at(p)?);
        (r.index[v] > 0.0).then_some(v)
    }

    /// The radius of the small sphere of directions drawn at a voxel (m): one and a half voxels.
    pub fn sphere_radius(&self) -> Option<f64> {
        Some(1.5 * self.result()?.map.grid.voxel_m)
    }

    /// The direction whose dot on the sphere of the pinned voxel `ray` passes nearest to
    /// (within half the dots' spacing), the one nearest the eye among those. A ray through the
    /// voxel's own cell (within 0.6 voxel of its centre) hits none: there a click unpins it
    /// (the dots in front of the centre are clicked in the panel).
    pub fn direction_on_ray(&self, ray: &Ray) -> Option<usize> {
        let r = self.result()?;
        let voxel = self.pinned?;
        let c = nalgebra::Vector3::from(r.map.grid.centre(r.map.grid.ijk(voxel)));
        let radius = self.sphere_radius()?;
        let n = r.map.directions.len() as f64;
        let tolerance = 0.5 * radius * (4.0 * std::f64::consts::PI / n).sqrt();
        let o = nalgebra::Vector3::from(ray.origin);
        let dir = nalgebra::Vector3::from(ray.dir).normalize();
        let off_centre = ((c - o) - dir * (c - o).dot(&dir)).norm();
        if off_centre < 0.6 * r.map.grid.voxel_m {
            return None;
        }
        let mut best: Option<(f64, usize)> = None;
        for (k, d) in r.map.directions.iter().enumerate() {
            let p = c + nalgebra::Vector3::from(*d) * radius;
            let along = (p - o).dot(&dir);
            let off = ((p - o) - dir * along).norm();
            if along > 0.0 && off < tolerance && best.is_none_or(|b| along < b.0) {
                best = Some((along, k));
            }
        }
        best.map(|(_, k)| k)
    }

    /// How each direction of `voxel` is reached at the roll shown (or over every roll).
    pub fn directions_of(&self, voxel: usize) -> Vec<DirectionReach> {
        let Some(r) = self.result() else {
            return Vec::new();
        };
        let m = &r.map;
        let rolls: Vec<usize> = match self.roll {
            Some(k) => vec![k],
            None => (0..m.rolls.len()).collect(),
        };
        (0..m.directions.len())
            .map(|d| {
                let hit = rolls
                    .iter()
                    .filter(|&&k| m.reachable[m.sample_index(voxel, d, k)])
                    .count();
                match hit {
                    0 => DirectionReach::None,
                    h if h == rolls.len() => DirectionReach::All,
                    _ => DirectionReach::Some,
                }
            })
            .collect()
    }

    /// The roll to aim at for `direction` of `voxel`: the one shown, else the first reached
    /// (else the first).
    pub fn roll_for(&self, voxel: usize, direction: usize) -> usize {
        if let Some(k) = self.roll {
            return k;
        }
        let Some(r) = self.result() else { return 0 };
        let m = &r.map;
        (0..m.rolls.len())
            .find(|&k| m.reachable[m.sample_index(voxel, direction, k)])
            .unwrap_or(0)
    }

    /// The tool pose of a sample of the map (m, world frame), with every solution the map's
    /// computation finds there (for `robot`, the robot the map was computed for).
    pub fn aim(
        &mut self,
        robot: &Robot,
        (voxel, direction, roll): (usize, usize, usize),
    ) -> Option<Pose> {
        let r = self.result.clone()?;
        let m = &r.map;
        if voxel >= m.grid.len() || direction >= m.directions.len() || roll >= m.rolls.len() {
            return None;
        }
        let pose = m.sample_pose(voxel, direction, roll);
        let solutions = solutions_at(robot, m, &r.options, r.world.as_ref(), &pose);
        self.aimed = Some(Aimed {
            voxel,
            direction,
            roll,
            solutions,
        });
        Some(pose)
    }
}
