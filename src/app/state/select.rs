//! Choosing among IK solutions (by index or posture label), the posture lock, and what the UI
//! reads back: ghosts and readouts.

use super::{AppState, Ghost, GhostLabel, Level, Reach, Readouts, StateError};
use crate::kinematics::ik::IkSolution;
use crate::kinematics::jacobian::analyze;

impl AppState {
    /// Moves the arm to the next solution of the last IK result of `ee` (the first where none
    /// is selected); nothing where there is no solution.
    pub fn select_next_solution(&mut self, ee: usize) -> Result<(), StateError> {
        if let Ok(t) = self.target(ee)
            && let Some(r) = &t.result
            && !r.solutions.is_empty()
        {
            let next = t.selected.map_or(0, |s| (s + 1) % r.solutions.len());
            self.select_solution(ee, next)?;
        }
        Ok(())
    }

    /// Moves the arm to solution `index` of the last IK result of `ee` and selects its posture.
    /// Refused for a solution outside the joint limits.
    pub fn select_solution(&mut self, ee: usize, index: usize) -> Result<(), StateError> {
        let t = self.target(ee)?;
        let sols: &[IkSolution] = t.result.as_ref().map_or(&[], |r| &r.solutions);
        let s = sols.get(index).ok_or(StateError::NoSuchSolution {
            index,
            count: sols.len(),
        })?;
        if !s.within_limits {
            return Err(StateError::SolutionOutsideLimits {
                index,
                posture: s.posture.to_string(),
            });
        }
        let (q, label) = (s.q.clone(), s.posture);
        let t = &mut self.targets[ee];
        t.selected = Some(index);
        t.posture = Some(label);
        t.reach = Reach::Reached;
        self.apply_q(q, Some(ee));
        self.push_message(Level::Info, format!("posture \"{label}\" selected"));
        Ok(())
    }

    /// Selects the solution whose posture label is `label` (case-insensitive; words may be
    /// separated by spaces, commas, dashes or underscores).
    pub fn select_posture(&mut self, ee: usize, label: &str) -> Result<(), StateError> {
        let t = self.target(ee)?;
        let sols: &[IkSolution] = t.result.as_ref().map_or(&[], |r| &r.solutions);
        let index = crate::kinematics::ik::solver::by_posture(sols, label)
            .and_then(|s| sols.iter().position(|x| std::ptr::eq(x, s)))
            .ok_or_else(|| StateError::NoSuchPosture {
                label: label.to_string(),
                available: sols
                    .iter()
                    .map(|s| s.posture.to_string())
                    .collect::<Vec<_>>()
                    .join("; "),
            })?;
        self.select_solution(ee, index)
    }

    /// Turns the posture lock on or off. While on, moving a target keeps the selected posture
    /// (see "Targets and the posture lock" in the [module doc](super)).
    pub fn set_lock(&mut self, on: bool) {
        if on == self.lock {
            return;
        }
        self.lock = on;
        let labels: Vec<String> = self
            .targets
            .iter()
            .filter_map(|t| t.posture.map(|p| p.to_string()))
            .collect();
        let msg = if on {
            format!("posture lock on ({})", labels.join("; "))
        } else {
            "posture lock off".to_string()
        };
        self.push_message(Level::Info, msg);
    }

    /// Every solution of the last IK result of `ee`, to draw as ghosts (empty when there is none
    /// or `ee` is out of range).
    pub fn ghosts(&self, ee: usize) -> Vec<Ghost> {
        let Some(t) = self.targets.get(ee) else {
            return Vec::new();
        };
        let Some(r) = &t.result else {
            return Vec::new();
        };
        let reports = self.solution_collisions(ee);
        r.solutions
            .iter()
            .enumerate()
            .map(|(i, s)| Ghost {
                q: s.q.clone(),
                posture: GhostLabel::Solution(s.posture),
                within_limits: s.within_limits,
                selected: t.selected == Some(i),
                class: self.posture_class(&s.posture),
                collision: reports.get(i).cloned(),
            })
            .collect()
    }

    /// T, p, phi, rank, manipulability, smallest singular value and the singularity warning of
    /// end-effector `ee` at the current q.
    pub fn readouts(&self, ee: usize) -> Result<Readouts, StateError> {
        self.target(ee)?;
        let t = self.robot.fk_ee(&self.q, ee)?;
        let a = analyze(&self.analyzer.task_jacobian(&self.robot, &self.q, ee)?);
        let r = self.analyzer.task_rank(ee);
        let sv = a.singular_values.as_slice();
        let orientation = self.orientation.from_rotation(&t.rotation);
        Ok(Readouts {
            t: t.to_homogeneous(),
            p: t.translation.vector,
            phi: orientation.angles,
            phi_kind: self.orientation,
            phi_singular: orientation.singular,
            rank: a.rank,
            task_rank: r,
            manipulability: sv.iter().take(r).product(),
            min_sv: if r == 0 {
                0.0
            } else {
                sv.get(r - 1).copied().unwrap_or(0.0)
            },
            singularity: self.analyzer.classify(&self.robot, &self.q, ee)?,
        })
    }
}
