//! The Orientation tab's four modes, each laid out in the tab's control column.

use super::lab::{self, Rep};
use super::{Changed, Mode, OrientationTab};
use crate::app::tabs::TabContext;
use crate::kinematics::EulerKind;
use crate::kinematics::orientation::{
    Axis, Representations, Step, StepFrame, commutator_norm, compose, rotation_angle_between,
    sum_comparison,
};
use egui::{Color32, RichText};
use nalgebra::{Rotation3, Vector3};

/// The warning colour (a singular case, an invalid value).
const WARN: Color32 = Color32::from_rgb(190, 90, 0);

/// Turn: the representation's values, the matrix, every representation, the singular case.
pub fn turn(tab: &mut OrientationTab, cx: &TabContext<'_>, ui: &mut egui::Ui) {
    ui.horizontal_wrapped(|ui| {
        ui.label("Edit:");
        for rep in Rep::ALL {
            if ui.selectable_label(tab.rep == rep, rep.name()).clicked() {
                tab.set_rep(rep);
            }
        }
    });
    let mut v = tab.values;
    let mut changed = false;
    for (k, (name, angle)) in tab.rep.fields().iter().enumerate() {
        let slider = if *angle {
            egui::Slider::new(&mut v[k], -180.0..=180.0).suffix("°")
        } else {
            egui::Slider::new(&mut v[k], -1.0..=1.0)
        };
        changed |= ui.add(slider.text(*name).max_decimals(4)).changed();
    }
    if changed {
        tab.set_values(v);
    }
    if let Some(why) = tab.invalid {
        ui.colored_label(Color32::from_rgb(190, 0, 0), why);
    }
    if let Rep::Euler(kind) = tab.rep {
        let all = Representations::of(&tab.rotation);
        let sols = all.euler(kind);
        if sols.solutions.len() == 2
            && ui
                .button("The other solution")
                .on_hover_text(
                    "The same matrix from the other inverse solution (theta of the other sign)",
                )
                .clicked()
        {
            let a = sols.solutions[1].map(f64::to_degrees);
            tab.values = [a[0], a[1], a[2], 0.0];
        }
    }
    if let Some(n) = tab.near_singular() {
        ui.label(RichText::new(n.message()).color(WARN));
        ui.label(
            RichText::new("The amber axes: the one phi turns about and the one psi turns about.")
                .color(WARN),
        );
    }
    ui.separator();
    matrix(ui, "R", &tab.rotation);
    for (name, text) in lab::readouts(&tab.rotation) {
        ui.label(RichText::new(name).strong());
        ui.add(egui::Label::new(text).wrap());
    }
    ui.separator();
    ui.checkbox(&mut tab.show_tool, "The arm's tool frame (e)");
    let tool = cx
        .state
        .target(cx.ee)
        .ok()
        .map(|t| t.world_from_tool.rotation);
    if let Some(t) = tool
        && ui.button("Take the tool's orientation").clicked()
    {
        tab.set_rotation(t);
    }
}

/// A rotation matrix in a grid, four decimals, under its name.
pub fn matrix(ui: &mut egui::Ui, name: &str, r: &Rotation3<f64>) {
    let m = r.matrix();
    let rows: Vec<String> = (0..3)
        .map(|i| format!("{:8.4} {:8.4} {:8.4}", m[(i, 0)], m[(i, 1)], m[(i, 2)]))
        .collect();
    ui.label(format!("{name} ="));
    ui.label(RichText::new(rows.join("\n")).monospace());
}

/// Compose: the sequence, its playback and the product written out.
pub fn compose_ui(tab: &mut OrientationTab, ui: &mut egui::Ui) {
    ui.label("Elementary rotations, in the order stated; each about the current frame (post-multiplied, 2.14) or the fixed one (pre-multiplied, 2.16).");
    step_list(tab, ui);
    playback(tab, ui);
    changes(tab, ui);
    let c = &tab.composition;
    let upto = &c.steps[..c.shown.min(c.steps.len())];
    ui.label(format!(
        "Step {} of {}",
        c.shown.min(c.steps.len()),
        c.steps.len()
    ));
    ui.label(RichText::new(lab::product_text(upto)).strong());
    matrix(ui, "R", &compose(upto));
    if let Some(b) = c.before {
        let apart = rotation_angle_between(&b.end, &compose(&c.steps));
        let what = match (b.reversed, b.switched) {
            (true, true) => "Reversed and switched",
            (true, false) => "Reversed",
            _ => "Switched",
        };
        let text = if apart < 1e-9 {
            format!("{what}: the frame ends where the stated sequence ended (b).")
        } else {
            format!(
                "{what}: the frame ends {:.1}° away from where the stated sequence ended (b).",
                apart.to_degrees()
            )
        };
        ui.label(RichText::new(text).color(WARN));
    }
    if ui
        .button("Turn this frame")
        .on_hover_text("Edit the result in the Turn mode's representations")
        .clicked()
    {
        let r = compose(upto);
        tab.mode = Mode::Turn;
        tab.set_rotation(r);
    }
}

/// The sequence's rows (about which frame, which axis, by how much; Remove) and Add; any
/// change shows the whole new sequence and forgets the stated one's ghost.
fn step_list(tab: &mut OrientationTab, ui: &mut egui::Ui) {
    let c = &mut tab.composition;
    let mut remove = None;
    let mut changed = false;
    for (k, s) in c.steps.iter_mut().enumerate() {
        // wrapped: the row is longer than the column in projector mode
        ui.horizontal_wrapped(|ui| {
            ui.label(format!("{}.", k + 1));
            changed |= choose(
                ui,
                (("frame", k), "about"),
                &mut s.frame,
                &[(StepFrame::Current, "current"), (StepFrame::Fixed, "fixed")],
            );
            changed |= choose(
                ui,
                (("axis", k), "axis"),
                &mut s.axis,
                &[(Axis::X, "x"), (Axis::Y, "y"), (Axis::Z, "z")],
            );
            let mut deg = s.angle.to_degrees();
            let label = ui.label("by");
            if ui
                .add(
                    egui::DragValue::new(&mut deg)
                        .suffix("°")
                        .range(-360.0..=360.0),
                )
                .labelled_by(label.id)
                .changed()
            {
                s.angle = deg.to_radians();
                changed = true;
            }
            if ui.button("Remove").clicked() {
                remove = Some(k);
            }
        });
    }
    if let Some(k) = remove {
        c.steps.remove(k);
        changed = true;
    }
    if ui.button("Add a rotation").clicked() {
        c.steps.push(Step {
            frame: StepFrame::Current,
            axis: Axis::Z,
            angle: 30f64.to_radians(),
        });
        changed = true;
    }
    if changed {
        c.shown = c.steps.len();
        c.before = None;
    }
}

/// The playback buttons (first, back, forward, play, all) and the playing clock.
fn playback(tab: &mut OrientationTab, ui: &mut egui::Ui) {
    let c = &mut tab.composition;
    let n = c.steps.len();
    ui.horizontal_wrapped(|ui| {
        if ui.button("First").clicked() {
            c.shown = 0;
            c.playing = None;
        }
        if ui.button("< Step").clicked() {
            c.shown = c.shown.saturating_sub(1);
        }
        if ui.button("Step >").clicked() {
            c.shown = (c.shown + 1).min(n);
        }
        let label = if c.playing.is_some() { "Pause" } else { "Play" };
        if ui.button(label).clicked() {
            c.playing = match c.playing {
                Some(_) => None,
                None => {
                    if c.shown >= n {
                        c.shown = 0;
                    }
                    Some(ui.input(|i| i.time))
                }
            };
        }
        if ui.button("All").clicked() {
            c.shown = n;
            c.playing = None;
        }
    });
    if let Some(t0) = c.playing {
        let now = ui.input(|i| i.time);
        if now - t0 > 0.9 {
            c.shown = (c.shown + 1).min(n);
            c.playing = (c.shown < n).then_some(now);
        }
        ui.ctx()
            .request_repaint_after(std::time::Duration::from_millis(100));
    }
}

/// Reverse the order, switch current and fixed: the stated sequence's end stays as a ghost
/// until both are undone.
fn changes(tab: &mut OrientationTab, ui: &mut egui::Ui) {
    let c = &mut tab.composition;
    let (mut reverse, mut switch) = (false, false);
    ui.horizontal_wrapped(|ui| {
        reverse = ui.button("Reverse the order").clicked();
        switch = ui.button("Switch current and fixed").clicked();
    });
    if !(reverse || switch) {
        return;
    }
    let end = compose(&c.steps);
    let b = c.before.get_or_insert(Changed {
        end,
        reversed: false,
        switched: false,
    });
    if reverse {
        c.steps.reverse();
        b.reversed ^= true;
    }
    if switch {
        for s in &mut c.steps {
            s.frame = match s.frame {
                StepFrame::Current => StepFrame::Fixed,
                StepFrame::Fixed => StepFrame::Current,
            };
        }
        b.switched ^= true;
    }
    if !(b.reversed || b.switched) {
        c.before = None;
    }
    c.shown = c.steps.len();
}

/// A combo box choosing one of `options`, named by `label` (shown before it); true when it
/// changed.
fn choose<T: Copy + PartialEq>(
    ui: &mut egui::Ui,
    (id, label): ((&str, usize), &str),
    value: &mut T,
    options: &[(T, &str)],
) -> bool {
    let before = *value;
    let text = options
        .iter()
        .find(|(v, _)| v == value)
        .map_or("", |(_, t)| *t);
    let l = ui.label(label);
    let r = egui::ComboBox::from_id_salt(id)
        .selected_text(text)
        .width(64.0)
        .show_ui(ui, |ui| {
            for (v, t) in options {
                ui.selectable_value(value, *v, *t);
            }
        });
    r.response.labelled_by(l.id);
    *value != before
}

/// The rotations of Problem 2.15: `R(phi1) R(phi2)`, `R(phi2) R(phi1)` and `R(phi1 + phi2)`.
pub fn sum_rotations(tab: &OrientationTab) -> (Rotation3<f64>, Rotation3<f64>, Rotation3<f64>) {
    let (kind, a, b) = tab.sum;
    let (a, b) = (
        Vector3::from(a).map(f64::to_radians),
        Vector3::from(b).map(f64::to_radians),
    );
    let (ra, rb) = (kind.to_rotation(&a), kind.to_rotation(&b));
    (ra * rb, rb * ra, kind.to_rotation(&(a + b)))
}

/// Problem 2.15: two angle sets, their sums in both orders and how far apart they end.
pub fn sum(tab: &mut OrientationTab, ui: &mut egui::Ui) {
    ui.label("Problem 2.15: the sum of two orientations phi1 (+) phi2 is the representation of R(phi1) R(phi2). It depends on the order, and it is not phi1 + phi2.");
    let (kind, a, b) = &mut tab.sum;
    choose(
        ui,
        (("sum kind", 0), "Convention"),
        kind,
        &[
            (EulerKind::Zyz, "ZYZ"),
            (EulerKind::Zxz, "ZXZ"),
            (EulerKind::Rpy, "RPY"),
        ],
    );
    for (name, v) in [("phi1", a), ("phi2", b)] {
        ui.horizontal(|ui| {
            ui.label(name);
            for (k, part) in ["phi", "theta", "psi"].iter().enumerate() {
                let l = ui.label(*part);
                ui.add(
                    egui::DragValue::new(&mut v[k])
                        .suffix("°")
                        .range(-180.0..=180.0),
                )
                .labelled_by(l.id);
            }
        });
    }
    let (kind, a, b) = tab.sum;
    let c = sum_comparison(
        kind,
        &Vector3::from(a).map(f64::to_radians),
        &Vector3::from(b).map(f64::to_radians),
    );
    let deg = |v: &Vector3<f64>| {
        format!(
            "({:.1}°, {:.1}°, {:.1}°)",
            v[0].to_degrees(),
            v[1].to_degrees(),
            v[2].to_degrees()
        )
    };
    ui.label(format!(
        "phi1 (+) phi2 = {} (frame x12 y12 z12)",
        deg(&c.sum)
    ));
    ui.label(format!(
        "phi2 (+) phi1 = {} (frame x21 y21 z21)",
        deg(&c.reversed)
    ));
    ui.label(format!(
        "phi1 + phi2 as numbers = {} (frame x+ y+ z+)",
        deg(&(Vector3::from(a) + Vector3::from(b)).map(f64::to_radians))
    ));
    ui.label(
        RichText::new(format!(
            "The two orders end {:.1}° apart; the numbers added end {:.1}° from phi1 (+) phi2.",
            c.order_angle.to_degrees(),
            c.naive_angle.to_degrees()
        ))
        .strong(),
    );
    let (ab, ba, _) = sum_rotations(tab);
    matrix(ui, "R(phi1) R(phi2)", &ab);
    matrix(ui, "R(phi2) R(phi1)", &ba);
}

/// Problem 2.16: the commutator of two elementary rotations against the angle, with the
/// second-order law it follows.
pub fn small(tab: &mut OrientationTab, ui: &mut egui::Ui) {
    ui.label("Problem 2.16: finite rotations do not commute, infinitesimal ones do. |Ra Rb - Rb Ra| shrinks as the angle squared: to first order the two orders agree.");
    let (a, b) = &mut tab.small;
    let axes = [(Axis::X, "x"), (Axis::Y, "y"), (Axis::Z, "z")];
    ui.horizontal(|ui| {
        choose(ui, (("small a", 0), "Axes: a ="), a, &axes);
        choose(ui, (("small b", 0), "b ="), b, &axes);
    });
    let (a, b) = tab.small;
    let curve: Vec<[f64; 2]> = (0..=90)
        .map(|k| {
            let deg = f64::from(k) * 0.5;
            [deg, commutator_norm(a, b, deg.to_radians())]
        })
        .collect();
    let law: Vec<[f64; 2]> = curve
        .iter()
        .map(|p| {
            [
                p[0],
                if a == b {
                    0.0
                } else {
                    2f64.sqrt() * p[0].to_radians().powi(2)
                },
            ]
        })
        .collect();
    let first: Vec<[f64; 2]> = curve.iter().map(|p| [p[0], p[0].to_radians()]).collect();
    egui_plot::Plot::new("commutator")
        .height(ui.available_height().clamp(180.0, 320.0))
        .x_axis_label("angle (deg)")
        .y_axis_label("|Ra Rb - Rb Ra|")
        .legend(egui_plot::Legend::default())
        .show(ui, |p| {
            p.line(egui_plot::Line::new("|Ra Rb - Rb Ra|", curve).width(2.5));
            p.line(
                egui_plot::Line::new("sqrt(2) angle^2", law)
                    .style(egui_plot::LineStyle::dashed_loose()),
            );
            p.line(egui_plot::Line::new("angle (first order)", first).color(Color32::GRAY));
        });
    for deg in [1.0f64, 10.0, 45.0] {
        let t = deg.to_radians();
        let c = commutator_norm(a, b, t);
        ui.label(format!(
            "{deg}°: |Ra Rb - Rb Ra| = {c:.2e}, divided by angle^2: {:.3}",
            c / (t * t)
        ));
    }
}
