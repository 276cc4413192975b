//! The Calibration tab (Sect. 2.11): a simulated or measured calibration of the current arm,
//! its report (identifiability in words, the parameter table, held-out errors) and accuracy maps,
//! with two lessons. [`lab`] holds the computations' state, [`panel`] the widgets.

pub mod lab;
pub mod panel;

use super::super::action::Actions;
use super::super::state::AppState;
use super::{Tab, TabContext};
use crate::scene::Scene;

/// The Calibration tab's state.
#[derive(Default)]
pub struct CalibrationTab {
    /// The calibration runs, settings and results.
    pub lab: lab::CalibrationLab,
    /// The accuracy maps' textures.
    maps: panel::MapTextures,
    /// The arm calibrated on a robot with several end-effectors, for (model generation,
    /// end-effector).
    arm: Option<((u64, usize), Result<crate::kinematics::arm::Arm, String>)>,
}

impl Tab for CalibrationTab {
    fn title(&self) -> &'static str {
        "Calibration"
    }

    fn ui(&mut self, cx: &mut TabContext<'_>, ui: &mut egui::Ui, _out: &mut Actions) {
        let robot = cx.state.robot();
        if robot.end_effectors().len() <= 1 {
            let arm = (robot, cx.state.q());
            return panel::show(&mut self.lab, &mut self.maps, arm, &mut *cx.picker, ui);
        }
        // A robot with several arms (Baxter): the arm of the chosen end-effector, calibrated
        // as `armlab calibrate --ee` does (a URDF chain through its derived DH table).
        let key = (cx.state.generation(), cx.ee);
        if self.arm.as_ref().is_none_or(|(k, _)| *k != key) {
            let arm = crate::kinematics::arm::arm_of(robot, cx.ee, cx.state.q());
            self.arm = Some((key, arm.map_err(|e| e.to_string())));
        }
        match &self.arm {
            Some((_, Ok(arm))) => {
                let q: Vec<f64> = arm.free.iter().map(|&k| cx.state.q()[k]).collect();
                let pair = (&arm.robot, q.as_slice());
                panel::show(&mut self.lab, &mut self.maps, pair, &mut *cx.picker, ui);
            }
            Some((_, Err(e))) => {
                ui.label(format!("This end-effector's arm cannot be calibrated: {e}"));
            }
            None => {}
        }
    }

    fn model_changed(&mut self) {
        // a lesson never outlives its arm (the user's settings come back), nor a message
        self.lab.end_lesson();
        self.lab.said = None;
        self.arm = None;
    }

    fn decorate(&self, state: &AppState, scene: &mut Scene) {
        if self.lab.show_poses
            && let Some(r) = &self.lab.result
            && r.model.nominal_robot().dof() == state.robot().dof()
        {
            super::super::viewport::add_measured_poses(scene, state.robot(), &r.poses);
        }
    }
}
