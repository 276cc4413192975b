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
}

impl Tab for CalibrationTab {
    fn title(&self) -> &'static str {
        "Calibration"
    }

    fn ui(&mut self, cx: &mut TabContext<'_>, ui: &mut egui::Ui, _out: &mut Actions) {
        panel::show(
            &mut self.lab,
            &mut self.maps,
            (cx.state.robot(), cx.state.q()),
            &mut *cx.picker,
            ui,
        );
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
