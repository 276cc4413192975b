//! The cell the arm works in: the obstacles (a scene file's, or added from the Cell menu), the
//! collision world built from them and the robot, and what the arm and every IK solution hit.
//!
//! The robot's collision bodies and its allowed-collision matrix are built once per model
//! (sampling the matrix takes tens of milliseconds); the world is rebuilt from them when the
//! scene changes (an obstacle added, moved, resized or deleted), never per frame. The reports
//! are computed when they change: a solution's when its target is solved, the arm's when q
//! changes, all of them when the scene or the model changes. A frame only reads them.

use super::{AppState, Ghost, Level};
use crate::collision::{
    AllowedCollisions, CellScene, CollisionReport, CollisionWorld, GeometryOptions, Obstacle,
    RobotGeometry,
};
use crate::kinematics::Pose;

/// The robot's collision bodies and allowed-collision matrix, for one model generation.
#[derive(Debug, Clone)]
struct RobotBodies {
    generation: u64,
    geometry: RobotGeometry,
    allowed: AllowedCollisions,
}

/// The cell: its scene, its collision world, and the reports of the arm and the solutions.
#[derive(Debug, Clone, Default)]
pub struct Cell {
    /// The obstacles (`None`: no cell; nothing is built or checked).
    scene: Option<CellScene>,
    /// Collisions are checked and shown.
    off: bool,
    bodies: Option<RobotBodies>,
    world: Option<CollisionWorld>,
    /// Why no world could be built for the current robot (an obstacle in the frame of a link
    /// the robot does not have): the obstacles are drawn, nothing is checked.
    problem: Option<String>,
    /// For each end-effector, the report of each solution of its last IK result (in order).
    solutions: Vec<Vec<CollisionReport>>,
    /// The arm at q.
    arm: Option<CollisionReport>,
    /// The obstacle the gizmo moves.
    selected: Option<usize>,
    /// Counts changes of the scene (caches of its drawing know when they are stale).
    epoch: u64,
}

impl AppState {
    /// The cell's obstacles, if there is a cell.
    pub fn cell_scene(&self) -> Option<&CellScene> {
        self.cell.scene.as_ref()
    }

    /// Counts the changes of the cell (obstacles added, moved, resized, deleted, a scene
    /// opened, the checks turned on or off).
    pub fn cell_epoch(&self) -> u64 {
        self.cell.epoch
    }

    /// Whether collisions are checked and shown (there is a cell and the checks are on).
    pub fn collisions_on(&self) -> bool {
        self.cell.scene.is_some() && !self.cell.off
    }

    /// The collision world of the robot in its cell (`None`: no cell, or it could not be built
    /// for this robot: see [`AppState::cell_problem`]).
    pub fn collision_world(&self) -> Option<&CollisionWorld> {
        self.cell.world.as_ref()
    }

    /// Why the cell is not checked for this robot, if it is not.
    pub fn cell_problem(&self) -> Option<&str> {
        self.cell.problem.as_deref()
    }

    /// What the arm hits at q (`None`: collisions off or nothing to check).
    pub fn arm_collision(&self) -> Option<&CollisionReport> {
        self.cell.arm.as_ref().filter(|_| self.collisions_on())
    }

    /// What each solution of the last IK result of `ee` hits, in the result's order (empty:
    /// collisions off, no result).
    pub fn solution_collisions(&self, ee: usize) -> &[CollisionReport] {
        match self.cell.solutions.get(ee) {
            Some(r) if self.collisions_on() => r,
            _ => &[],
        }
    }

    /// What the arm at `q` hits (`None`: collisions off, or `q` does not fit the robot).
    pub fn collision_at(&self, q: &[f64]) -> Option<CollisionReport> {
        let world = self.cell.world.as_ref().filter(|_| self.collisions_on())?;
        world.check(&self.robot, q).ok()
    }

    /// `world_from_obstacle` of every obstacle at the current q (m): from the collision world,
    /// or, where there is none, each obstacle's pose in its frame.
    pub fn obstacle_poses(&self) -> Vec<Pose> {
        let Some(scene) = &self.cell.scene else {
            return Vec::new();
        };
        if let Some(world) = &self.cell.world
            && let Ok(poses) = world.obstacle_poses(&self.robot, &self.q)
            && poses.len() == scene.obstacles.len()
        {
            return poses;
        }
        scene
            .obstacles
            .iter()
            .map(Obstacle::frame_from_obstacle)
            .collect()
    }

    /// The obstacle the gizmo moves, if one is selected.
    pub fn selected_obstacle(&self) -> Option<usize> {
        self.cell.selected
    }

    /// Selects obstacle `k` (`None`: none; the gizmo moves the IK target again).
    pub fn select_obstacle(&mut self, k: Option<usize>) {
        let n = self.cell.scene.as_ref().map_or(0, |s| s.obstacles.len());
        self.cell.selected = k.filter(|&k| k < n);
    }

    /// Opens `scene` as the cell (`None`: no cell). The collision world is built at once; if it
    /// cannot be built (an obstacle in the frame of a link the robot does not have, or named
    /// as one of its links), the cell stays as it was and the error says why.
    pub fn set_scene(&mut self, scene: Option<CellScene>) -> Result<(), String> {
        let Some(scene) = scene else {
            self.cell.scene = None;
            self.cell.world = None;
            self.cell.problem = None;
            self.cell.selected = None;
            self.after_cell_change();
            return Ok(());
        };
        let world = self.build_world(&scene)?;
        for w in &world.warnings {
            let said = self
                .cell
                .world
                .as_ref()
                .is_some_and(|o| o.warnings.contains(w));
            if !said {
                self.push_message(Level::Warning, w.clone());
            }
        }
        self.cell.world = Some(world);
        self.cell.problem = None;
        let n = scene.obstacles.len();
        self.cell.scene = Some(scene);
        self.cell.selected = self.cell.selected.filter(|&k| k < n);
        self.after_cell_change();
        Ok(())
    }

    /// Turns the collision checks on or off; on without a cell opens an empty one (the arm
    /// against itself).
    pub fn set_collisions(&mut self, on: bool) {
        if on && self.cell.scene.is_none() {
            let _ = self.set_scene(Some(CellScene::default()));
        }
        self.cell.off = !on;
        self.after_cell_change();
    }

    /// Adds `obstacle` to the cell (one is opened if there is none), renamed if its name is
    /// taken, and selects it; returns its index.
    pub fn add_obstacle(&mut self, mut obstacle: Obstacle) -> Result<usize, String> {
        let mut scene = self.cell.scene.clone().unwrap_or_default();
        obstacle.name = self.free_obstacle_name(&scene, &obstacle.name);
        scene.obstacles.push(obstacle);
        let k = scene.obstacles.len() - 1;
        let was_off = std::mem::replace(&mut self.cell.off, false);
        if let Err(e) = self.set_scene(Some(scene)) {
            self.cell.off = was_off;
            return Err(e);
        }
        self.cell.selected = Some(k);
        Ok(k)
    }

    /// Replaces obstacle `k` (moved, resized); refused (the cell unchanged) where the world
    /// cannot be built with it.
    pub fn set_obstacle(&mut self, k: usize, obstacle: Obstacle) -> Result<(), String> {
        let mut scene = self.cell.scene.clone().ok_or("no cell is open")?;
        let slot = scene
            .obstacles
            .get_mut(k)
            .ok_or_else(|| format!("no obstacle {} in the cell", k + 1))?;
        if *slot == obstacle {
            return Ok(());
        }
        *slot = obstacle;
        self.set_scene(Some(scene))
    }

    /// Deletes obstacle `k` (the selection is cleared).
    pub fn remove_obstacle(&mut self, k: usize) -> Result<(), String> {
        let mut scene = self.cell.scene.clone().ok_or("no cell is open")?;
        if k >= scene.obstacles.len() {
            return Err(format!("no obstacle {} in the cell", k + 1));
        }
        let gone = scene.obstacles.remove(k);
        self.cell.selected = None;
        self.set_scene(Some(scene))?;
        self.push_message(Level::Info, format!("obstacle \"{}\" deleted", gone.name));
        Ok(())
    }

    /// `base`, or `base 2`, `base 3`, ... : a name no obstacle of `scene` and no link of the
    /// robot has.
    fn free_obstacle_name(&self, scene: &CellScene, base: &str) -> String {
        let links = self.cell.world.as_ref().map(|w| &w.geometry.bodies);
        let taken = |n: &str| {
            scene.obstacles.iter().any(|o| o.name == n)
                || links.is_some_and(|b| b.iter().any(|b| b.name == n))
        };
        if !taken(base) {
            return base.to_string();
        }
        (2..)
            .map(|i| format!("{base} {i}"))
            .find(|n| !taken(n))
            .unwrap_or_else(|| base.to_string())
    }

    /// The robot's collision bodies and matrix for the current model (built the first time).
    fn robot_bodies(&mut self) -> &RobotBodies {
        let stale = self
            .cell
            .bodies
            .as_ref()
            .is_none_or(|b| b.generation != self.generation);
        if stale {
            let geometry = RobotGeometry::of(&self.robot, GeometryOptions::default());
            let allowed = AllowedCollisions::for_robot(&self.robot, &geometry);
            self.cell.bodies = Some(RobotBodies {
                generation: self.generation,
                geometry,
                allowed,
            });
        }
        self.cell.bodies.as_ref().expect("built above")
    }

    /// The collision world of the robot in `scene`.
    fn build_world(&mut self, scene: &CellScene) -> Result<CollisionWorld, String> {
        let b = self.robot_bodies().clone();
        CollisionWorld::with(
            &self.robot,
            b.geometry,
            scene,
            GeometryOptions::default(),
            b.allowed,
        )
        .map_err(|e| e.to_string())
    }

    /// The model changed: the world is built again for the new robot (an obstacle in the frame
    /// of a link it lacks leaves the cell unchecked, said once), every report is redone.
    pub(super) fn cell_model_changed(&mut self) {
        let Some(scene) = self.cell.scene.clone() else {
            return;
        };
        match self.build_world(&scene) {
            Ok(world) => {
                self.cell.world = Some(world);
                self.cell.problem = None;
            }
            Err(e) => {
                self.cell.world = None;
                let m = format!("the cell is not checked for {}: {e}", self.robot.name);
                self.push_message(Level::Warning, m.clone());
                self.cell.problem = Some(m);
            }
        }
        self.recheck_all();
    }

    /// The scene or the checks changed: counted, every report redone.
    fn after_cell_change(&mut self) {
        self.cell.epoch += 1;
        self.recheck_all();
    }

    /// Every report redone: the arm's and every target's solutions.
    fn recheck_all(&mut self) {
        self.recheck_arm();
        for ee in 0..self.targets.len() {
            self.recheck_solutions(ee);
        }
    }

    /// The arm's report at q, redone (after q changed). Moving into a collision is said at once
    /// in a warning naming the pairs (what stays in collision the status bar keeps saying, see
    /// [`AppState::collision_warning`]).
    pub(super) fn recheck_arm(&mut self) {
        let was = self.cell.arm.as_ref().is_some_and(|r| r.in_collision);
        self.cell.arm = self.collision_at(&self.q);
        if let Some(r) = self.cell.arm.as_ref().filter(|r| r.in_collision && !was) {
            let pairs: Vec<String> = r
                .pairs
                .iter()
                .map(|c| format!("{} hits {}", c.a, c.b))
                .collect();
            let m = format!("the arm is now in collision: {}", pairs.join("; "));
            self.push_message(Level::Warning, m);
        }
    }

    /// The reports of target `ee`'s solutions, redone (after its IK result changed).
    pub(super) fn recheck_solutions(&mut self, ee: usize) {
        let reports: Vec<CollisionReport> = match (self.cell.world.as_ref(), self.targets.get(ee)) {
            (Some(world), Some(t)) if self.collisions_on() => t
                .result
                .iter()
                .flat_map(|r| &r.solutions)
                .map_while(|s| world.check(&self.robot, &s.q).ok())
                .collect(),
            _ => Vec::new(),
        };
        if self.cell.solutions.len() <= ee {
            self.cell
                .solutions
                .resize(self.targets.len().max(ee + 1), Vec::new());
        }
        self.cell.solutions[ee] = reports;
    }

    /// While the arm is in collision, what it hits, in words, and the way out: the solutions of
    /// `ee` that are free (counted from 1, as the list does), or that the posture lock keeps
    /// this one. `None` while it is free or collisions are off.
    pub fn collision_warning(&self, ee: usize) -> Option<String> {
        let report = self.arm_collision().filter(|r| r.in_collision)?;
        let mut text = format!("in collision: {}", report.summary());
        let free: Vec<String> = self
            .target(ee)
            .ok()
            .and_then(|t| t.result.as_ref())
            .map(|r| {
                let reports = self.solution_collisions(ee);
                (r.solutions.iter().zip(reports).enumerate())
                    .filter(|(_, (s, c))| s.within_limits && !c.in_collision)
                    .map(|(i, _)| (i + 1).to_string())
                    .collect()
            })
            .unwrap_or_default();
        if self.lock {
            text += "; the posture lock keeps this posture";
        }
        if !free.is_empty() {
            text += &format!("; free solutions: {}", free.join(", "));
        }
        Some(text)
    }

    /// `ghost` with what its posture hits (where collisions are on).
    pub(super) fn with_collision(&self, mut ghost: Ghost) -> Ghost {
        ghost.collision = self.collision_at(&ghost.q);
        ghost
    }
}
