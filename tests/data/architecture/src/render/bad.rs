//! The renderer naming the kinematics and egui (fixture).
use crate::kinematics::Robot;
fn paint(ui: &mut egui::Ui) {}
