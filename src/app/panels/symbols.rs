//! The Symbols section of the right panel: the direct kinematics in the textbook's notation
//! ([`crate::kinematics::symbolic`]), a step through the product A_1 A_2 ... A_n with the
//! partial product's frame highlighted in the 3D view, and "copy as LaTeX". It only paints
//! what the symbolic layer hands it (cached per robot and end-effector).

use super::super::state::AppState;
use crate::kinematics::Joint;
use crate::kinematics::symbolic::document::{self, span, strings};
use crate::kinematics::symbolic::expr::Style;
use crate::kinematics::symbolic::{Options, SymMatrix, SymbolicKinematics, derive, eval_matrix};
use crate::scene::{Label, Line, Scene, point32};
use egui::text::{LayoutJob, TextFormat};
use egui::{FontId, RichText};
use nalgebra::Vector3;

/// Colour of the partial product's frame and of the links it spans.
const HIGHLIGHT: [f32; 4] = [0.85, 0.35, 0.0, 1.0];

/// What the cache was computed for: the joints (their geometry, drives, offsets), the
/// end-effector and whether lengths are numbers.
type CacheKey = (Vec<Joint>, usize, bool);

/// The Symbols section's own state.
#[derive(Default)]
pub struct SymbolsPanel {
    /// Show the section's matrices and the highlighted frame.
    pub shown: bool,
    /// The partial product shown: T_{step+1}^0 (0-based step).
    pub step: usize,
    /// Substitute the lengths by their values.
    pub numbers: bool,
    cache: Option<(CacheKey, Result<SymbolicKinematics, String>)>,
}

impl SymbolsPanel {
    /// The symbolic kinematics of the current robot's chain to `ee` (derived once per robot).
    fn kinematics(&mut self, state: &AppState, ee: usize) -> Result<&SymbolicKinematics, String> {
        let key: CacheKey = (state.robot().joints().to_vec(), ee, self.numbers);
        if self.cache.as_ref().is_none_or(|(k, _)| *k != key) {
            let options = Options {
                numbers: self.numbers,
            };
            let result = derive(state.robot(), ee, &options).map_err(|e| e.to_string());
            self.cache = Some((key, result));
        }
        match &self.cache {
            Some((_, Ok(sk))) => Ok(sk),
            Some((_, Err(e))) => Err(e.clone()),
            None => Err("not derived".into()),
        }
    }

    /// The Symbols section of the right panel.
    pub fn ui(&mut self, state: &AppState, ui: &mut egui::Ui, ee: usize) {
        ui.heading("Symbols");
        if state.hidden.dh_table {
            ui.label("Off while the exercise is answered");
            return;
        }
        ui.checkbox(&mut self.shown, "Show the kinematics in symbols");
        if !self.shown {
            return;
        }
        ui.checkbox(&mut self.numbers, "Lengths as numbers");
        let step = self.step;
        let sk = match self.kinematics(state, ee) {
            Ok(sk) => sk.clone(),
            Err(e) => {
                ui.label(RichText::new(format!("No symbolic form: {e}.")).small());
                return;
            }
        };
        let n = sk.links.len();
        if n == 0 {
            ui.label("The chain has no joints.");
            return;
        }
        let step = step.min(n - 1);
        ui.horizontal(|ui| {
            if ui.button("< Previous").clicked() {
                self.step = step.saturating_sub(1);
            }
            ui.label(format!("step {} of {n}", step + 1));
            if ui.button("Next >").clicked() {
                self.step = (step + 1).min(n - 1);
            }
        });
        self.step = self.step.min(n - 1);
        product_step(ui, &sk, self.step);
    }

    /// Adds the frame of the partial product shown, and the links up to it, to the scene.
    pub fn decorate(&mut self, state: &AppState, ee: usize, scene: &mut Scene) {
        if !self.shown || state.hidden.dh_table {
            return;
        }
        let step = self.step;
        let Ok(sk) = self.kinematics(state, ee) else {
            return;
        };
        let Ok(values) = sk.variable_values(state.robot(), state.q()) else {
            return;
        };
        let lengths = &sk.symbols;
        let v = crate::kinematics::symbolic::poly::Values {
            variables: &values,
            first: sk.first,
            lengths,
        };
        let world = |m: &SymMatrix| sk.base.to_homogeneous() * eval_matrix(m, &v);
        let step = step.min(sk.partials.len().saturating_sub(1));
        let mut origins = vec![sk.base.translation.vector];
        for m in &sk.partials[..=step] {
            let t = world(m);
            origins.push(Vector3::new(t[(0, 3)], t[(1, 3)], t[(2, 3)]));
        }
        for w in origins.windows(2) {
            scene.lines.push(Line {
                a: point32(&w[0]).into(),
                b: point32(&w[1]).into(),
                color: HIGHLIGHT,
                width_px: 4.0,
            });
        }
        let t = world(&sk.partials[step]);
        let o = Vector3::new(t[(0, 3)], t[(1, 3)], t[(2, 3)]);
        let len = 0.2 * state.robot().characteristic_length().max(0.05);
        let colors = [
            [0.9, 0.1, 0.1, 1.0],
            [0.1, 0.7, 0.1, 1.0],
            [0.1, 0.3, 0.95, 1.0],
        ];
        for (axis, color) in colors.iter().enumerate() {
            let dir = Vector3::new(t[(0, axis)], t[(1, axis)], t[(2, axis)]);
            scene.lines.push(Line {
                a: point32(&o).into(),
                b: point32(&(o + dir * len)).into(),
                color: *color,
                width_px: 5.0,
            });
        }
        scene.labels.push(Label {
            p: point32(&o).into(),
            text: format!("frame {}", sk.links[step].to),
            color: HIGHLIGHT,
            movable: true,
        });
    }
}

/// Entries longer than this are listed one per line (n_x = ...) instead of in a grid.
const GRID_CELL: usize = 16;

/// A matrix as a grid of mathematics (subscripts lowered and smaller), or, where entries are
/// long (a 6R arm's T), as the textbook prints (2.70): n, s, a, p entry by entry, wrapped.
fn matrix_grid(ui: &mut egui::Ui, id: (&str, usize), m: &SymMatrix, separate: bool) {
    let cells = strings(m, Style::Text, separate);
    if cells.iter().flatten().any(|c| c.len() > GRID_CELL) {
        egui::Frame::group(ui.style()).show(ui, |ui| {
            for (j, col) in ["n", "s", "a", "p"].iter().enumerate() {
                for (i, axis) in ["x", "y", "z"].iter().enumerate() {
                    let text = format!("{col}_{axis} = {}", cells[i][j]);
                    ui.add(egui::Label::new(math(&text, ui)).wrap());
                }
            }
        });
        return;
    }
    egui::Frame::group(ui.style()).show(ui, |ui| {
        egui::Grid::new(id).spacing([14.0, 4.0]).show(ui, |ui| {
            for row in &cells {
                for c in row {
                    ui.label(math(c, ui));
                }
                ui.end_row();
            }
        });
    });
}

/// The textbook's notation as a layout: a letter's digits (`c23`, `a2`) and what follows an
/// underscore (`p_Wx`) as a lowered, smaller subscript, `c1_2`'s separator as a comma, what
/// follows `^` raised (`A_1^0`); numbers,
/// operators and parentheses as they are; a minus as U+2212.
pub fn math(text: &str, ui: &egui::Ui) -> LayoutJob {
    let size = egui::TextStyle::Body.resolve(ui.style()).size;
    // a subscript is smaller, but never under the projector's floor
    let floor = crate::app::layout::text_floor(ui.ctx());
    let color = ui.visuals().text_color();
    let normal = TextFormat {
        font_id: FontId::proportional(size),
        color,
        ..Default::default()
    };
    let sub = TextFormat {
        font_id: FontId::proportional((size * 0.7).max(floor)),
        color,
        valign: egui::Align::BOTTOM,
        ..Default::default()
    };
    let sup = TextFormat {
        valign: egui::Align::TOP,
        ..sub.clone()
    };
    #[derive(PartialEq)]
    enum Mode {
        Normal,
        AfterLetter,
        Digits,
        Underscore,
        Superscript,
    }
    let mut mode = Mode::Normal;
    let mut job = LayoutJob::default();
    for ch in text.chars() {
        let (shown, subscript): (String, bool) = match (&mode, ch) {
            (_, '^') => {
                mode = Mode::Superscript;
                (String::new(), false)
            }
            (Mode::Superscript, c) if c.is_ascii_alphanumeric() => {
                job.append(&ch.to_string(), 0.0, sup.clone());
                continue;
            }
            (Mode::AfterLetter | Mode::Digits, '0'..='9') => {
                mode = Mode::Digits;
                (ch.to_string(), true)
            }
            (Mode::Digits, '_') => (",".into(), true),
            (Mode::AfterLetter, '_') => {
                mode = Mode::Underscore;
                (String::new(), true)
            }
            (Mode::Underscore, c) if c.is_ascii_alphanumeric() => (ch.to_string(), true),
            (_, c) if c.is_ascii_alphabetic() => {
                mode = Mode::AfterLetter;
                (ch.to_string(), false)
            }
            (_, '-') => {
                mode = Mode::Normal;
                ("\u{2212}".into(), false)
            }
            _ => {
                mode = Mode::Normal;
                (ch.to_string(), false)
            }
        };
        let format = if subscript { &sub } else { &normal };
        job.append(&shown, 0.0, format.clone());
    }
    job
}

/// Step `step` of the product: A_i, the partial product T and what it highlights, the wrist
/// point, and the LaTeX buttons.
fn product_step(ui: &mut egui::Ui, sk: &SymbolicKinematics, step: usize) {
    let link = &sk.links[step];
    let (lo, _) = span(sk);
    ui.label(math(
        &format!(
            "A_{}^{}(q{}), joint {}:",
            link.to, link.from, link.to, link.joint
        ),
        ui,
    ));
    matrix_grid(ui, ("A", step), &link.matrix, sk.separate_indices);
    let product: Vec<String> = sk.links[..=step]
        .iter()
        .map(|l| format!("A_{}^{}", l.to, l.from))
        .collect();
    ui.label(math(
        &format!("T_{}^{lo} = {}:", link.to, product.join(" ")),
        ui,
    ));
    ui.label(
        RichText::new(format!(
            "frame {} highlighted in the 3D view, the links of the product in orange",
            link.to
        ))
        .small(),
    );
    matrix_grid(ui, ("T", step), &sk.partials[step], sk.separate_indices);
    if let Some((k, w)) = &sk.wrist {
        let p = document::vector(w, Style::Text, sk.separate_indices);
        ui.label(format!("wrist point p_W (origin of frame {k}):"));
        for (axis, e) in ["x", "y", "z"].iter().zip(p) {
            ui.label(math(&format!("p_W{axis} = {e}"), ui));
        }
    }
    ui.horizontal(|ui| {
        if ui.button("Copy as LaTeX").clicked() {
            ui.ctx().copy_text(document::latex(sk));
        }
        if ui.button("Copy this T as LaTeX").clicked() {
            ui.ctx().copy_text(document::latex_matrix(
                &sk.partials[step],
                sk.separate_indices,
            ));
        }
    });
}
