//! "Show the construction": the geometry behind the closed-form solution the arm is in (Sect.
//! 2.12), drawn in the 3D view one step at a time, with each step's formula and numbers in the
//! side panel. The steps come from [`crate::construction::steps::construction`] at
//! the current q, so the overlay follows the target while it is dragged.

use super::super::state::AppState;
use crate::construction::steps::{Mark, Step, construction};
use crate::scene::{Dot, Label, Line, Scene, point32};
use egui::RichText;
use nalgebra::{Rotation3, Unit, Vector3};

/// Colour of the current step's marks.
const CURRENT: [f32; 4] = [0.85, 0.2, 0.05, 1.0];
/// Colour of the earlier steps' marks.
const EARLIER: [f32; 4] = [0.3, 0.3, 0.35, 1.0];

/// The construction overlay's own state: shown or not, and the step shown.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct ConstructionPanel {
    /// Draw the construction behind the closed-form solution (Sect. 2.12).
    pub shown: bool,
    /// The step shown (0-based; the steps before it stay drawn).
    pub step: usize,
    /// The step last scrolled into view (`None` while hidden): the panel scrolls to the steps
    /// when they appear and when the step changes, instead of leaving them below the fold.
    seen: Option<usize>,
}

impl ConstructionPanel {
    /// The Construction section of the right panel.
    pub fn ui(&mut self, state: &AppState, ui: &mut egui::Ui) {
        ui.heading("Construction");
        ui.checkbox(&mut self.shown, "Show the construction (C)");
        if !self.shown {
            self.seen = None;
            return;
        }
        let steps = match construction(state.robot(), state.q()) {
            Ok(s) => s,
            Err(e) => {
                ui.label(RichText::new(format!("No construction: {e}.")).small());
                return;
            }
        };
        self.step = self.step.min(steps.len().saturating_sub(1));
        ui.horizontal(|ui| {
            if ui.button("< Previous (B)").clicked() {
                self.step = self.step.saturating_sub(1);
            }
            ui.label(format!("step {} of {}", self.step + 1, steps.len()));
            if ui.button("Next (N) >").clicked() {
                self.step = (self.step + 1).min(steps.len() - 1);
            }
        });
        for (k, s) in steps.iter().enumerate() {
            let text = RichText::new(format!("{}. {} {}", k + 1, s.title, s.equation));
            let text = if k == self.step {
                text.strong()
            } else {
                text.small()
            };
            if ui.selectable_label(k == self.step, text).clicked() {
                self.step = k;
            }
        }
        let s = &steps[self.step];
        let formula = ui.label(RichText::new(&s.formula).monospace().small());
        if self.seen != Some(self.step) {
            formula.scroll_to_me(Some(egui::Align::Max));
            self.seen = Some(self.step);
        }
    }

    /// Adds the construction of the current configuration, up to the step shown, to `scene`.
    pub fn decorate(&self, state: &AppState, scene: &mut Scene) {
        if self.shown
            && let Ok(steps) = construction(state.robot(), state.q())
        {
            add_to_scene(scene, &steps, self.step.min(steps.len().saturating_sub(1)));
        }
    }
}

/// Adds the marks of steps 1..=`current` to the scene: the current step in red, the earlier ones
/// in grey, dashed construction lines as dashes, angles as arcs with their labels.
fn add_to_scene(scene: &mut Scene, steps: &[Step], current: usize) {
    for (k, step) in steps.iter().enumerate().take(current + 1) {
        let color = if k == current { CURRENT } else { EARLIER };
        for m in &step.marks {
            add_mark(scene, m, color, k == current);
        }
    }
}

fn add_mark(scene: &mut Scene, m: &Mark, color: [f32; 4], labelled: bool) {
    let mut label = |p: &Vector3<f64>, text: &str| {
        if labelled && !text.is_empty() {
            scene.labels.push(Label {
                p: point32(p).into(),
                text: text.to_string(),
                color,
                movable: true,
            });
        }
    };
    match m {
        Mark::Point { p, label: text } => {
            label(p, text);
            scene.dots.push(Dot {
                p: point32(p).into(),
                color,
                size_px: 9.0,
            });
        }
        Mark::Segment {
            a,
            b,
            label: text,
            dashed,
        } => {
            label(&(0.5 * (a + b)), text);
            let n = if *dashed { 16 } else { 1 };
            for i in 0..n {
                if *dashed && i % 2 == 1 {
                    continue;
                }
                let (t0, t1) = (i as f64 / n as f64, (i + 1) as f64 / n as f64);
                scene.lines.push(Line {
                    a: point32(&(a + (b - a) * t0)).into(),
                    b: point32(&(a + (b - a) * t1)).into(),
                    color,
                    width_px: 2.5,
                });
            }
        }
        Mark::Arc {
            center,
            from,
            normal,
            angle,
            radius,
            label: text,
        } => {
            let axis = Unit::new_normalize(*normal);
            let at = |t: f64| center + Rotation3::from_axis_angle(&axis, t) * (from * *radius);
            label(&at(0.5 * angle), text);
            let n = 24;
            for i in 0..n {
                let (t0, t1) = (
                    angle * i as f64 / n as f64,
                    angle * (i + 1) as f64 / n as f64,
                );
                scene.lines.push(Line {
                    a: point32(&at(t0)).into(),
                    b: point32(&at(t1)).into(),
                    color,
                    width_px: 2.0,
                });
            }
        }
    }
}
