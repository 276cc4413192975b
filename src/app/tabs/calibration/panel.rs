//! The Calibration tab's widgets: settings, the lessons, files, and the report of the last run
//! (iterations, identifiability in words, O1-O4, the parameter table, held-out errors).

use super::lab::{CalibrationLab, LabResult, PoseChoice, Said};
use crate::app::file_picker::{FileKind, FilePicker};
use crate::calibration::{Fit, Setup};
use crate::kinematics::Robot;
use egui::{Color32, RichText};

/// The textures of the accuracy maps shown, and the generation of the maps they show.
#[derive(Default)]
pub struct MapTextures {
    generation: u64,
    textures: Vec<(crate::figure::plot2d::Plot2d, egui::TextureHandle)>,
}

impl std::fmt::Debug for MapTextures {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "MapTextures({} maps)", self.textures.len())
    }
}

/// The whole tab.
pub fn show(
    lab: &mut CalibrationLab,
    textures: &mut MapTextures,
    (robot, q): (&Robot, &[f64]),
    picker: &mut dyn FilePicker,
    ui: &mut egui::Ui,
) {
    egui::ScrollArea::vertical().show(ui, |ui| {
        ui.heading("Kinematic calibration (Sect. 2.11)");
        ui.label(
            RichText::new(
                "A simulated \"real\" arm (the model plus deviations) is measured with noise; \
                 iterative least squares (2.88)-(2.89) estimates its DH parameters.",
            )
            .small(),
        );
        if lab.before_lesson.is_some() {
            ui.horizontal_wrapped(|ui| {
                ui.label(
                    RichText::new(
                        "A lesson runs with its own settings: yours come back when it ends.",
                    )
                    .color(Color32::from_rgb(0, 70, 140)),
                );
                if ui.button("End lesson").clicked() {
                    lab.end_lesson();
                }
            });
        }
        settings(lab, ui);
        actions(lab, robot, q, ui);
        files(lab, robot, picker, ui);
        if let Some(l) = lab.lesson {
            ui.add(
                egui::Label::new(
                    RichText::new(l)
                        .strong()
                        .color(Color32::from_rgb(0, 70, 140)),
                )
                .wrap(),
            );
        }
        if let Some(m) = &lab.said {
            let color = match m {
                Said::Done(_) => Color32::from_rgb(0, 110, 0),
                Said::Warned(_) => Color32::from_rgb(170, 90, 0),
                Said::Failed(_) => Color32::from_rgb(190, 0, 0),
            };
            ui.add(egui::Label::new(RichText::new(m.text()).color(color)).wrap());
        }
        if lab.result.is_some() {
            ui.separator();
            ui.checkbox(
                &mut lab.show_poses,
                "Show the measured poses in the 3D view",
            );
            if ui
                .button("Accuracy map (before / after)")
                .on_hover_text("the position deviation against the real arm over the workspace")
                .clicked()
            {
                lab.compute_maps(160, 400_000);
            }
            maps(lab, textures, ui);
        }
        if lab.result.is_some() {
            corrections(lab, robot, picker, ui);
        }
        if let Some(r) = &lab.result {
            report(r, ui);
        }
    });
}

/// Target correction: desired poses in, a row per pose and posture out (what to command the
/// real arm, what to send a nominal controller), and saving the table.
fn corrections(
    lab: &mut CalibrationLab,
    robot: &Robot,
    picker: &mut dyn FilePicker,
    ui: &mut egui::Ui,
) {
    ui.separator();
    ui.strong("Target correction");
    ui.label(
        RichText::new(
            "Desired tool poses (16 numbers per line, or a headered CSV with x y z and a \
             quaternion or roll pitch yaw): every posture of the nominal closed form, polished on \
             the calibrated arm, and the pose to send a controller that runs the nominal model.",
        )
        .small(),
    );
    ui.horizontal(|ui| {
        let l = ui.label("desired poses");
        ui.add(
            egui::TextEdit::singleline(&mut lab.targets_path)
                .hint_text("targets.csv")
                .desired_width(200.0),
        )
        .labelled_by(l.id);
        if ui.button("Correct targets").clicked() {
            lab.correct(robot);
        }
        if lab.corrections.is_some() && ui.button("Save table").clicked() {
            let name = match lab.targets_path.trim() {
                "" => "corrected.csv".to_string(),
                n => format!("{}-corrected.csv", n.trim_end_matches(".csv")),
            };
            let text = lab.corrections_text(robot).unwrap_or_default();
            lab.said = Some(if picker.downloads() {
                if picker.download(&name, "text/csv", text.as_bytes()) {
                    Said::Done(format!("downloading the table as {name}"))
                } else {
                    Said::Failed(format!("the browser refused the download of {name}"))
                }
            } else {
                match std::fs::write(&name, text) {
                    Ok(()) => Said::Done(format!("saved the table to {name}")),
                    Err(e) => Said::Failed(format!("cannot write {name}: {e}")),
                }
            });
        }
    });
    let Some(rows) = &lab.corrections else {
        return;
    };
    egui::Grid::new("target corrections")
        .striped(true)
        .show(ui, |ui| {
            for h in [
                "pose",
                "posture",
                "off without [mm]",
                "send x, y, z [mm]",
                "limits",
            ] {
                ui.label(RichText::new(h).small().strong());
            }
            ui.end_row();
            for r in rows.iter().take(40) {
                let t = r.send.translation.vector * 1e3;
                ui.label((r.pose + 1).to_string());
                ui.label(r.posture.to_string());
                ui.label(format!("{:.4}", r.uncorrected_error * 1e3));
                ui.label(format!("{:.3}, {:.3}, {:.3}", t[0], t[1], t[2]));
                ui.label(if r.within_limits { "ok" } else { "outside" });
                ui.end_row();
            }
        });
    if rows.len() > 40 {
        ui.label(format!(
            "... {} rows in all (Save table writes them)",
            rows.len()
        ));
    }
}

/// The accuracy maps side by side, each with its colour bar.
fn maps(lab: &CalibrationLab, textures: &mut MapTextures, ui: &mut egui::Ui) {
    let Some((before, after)) = &lab.maps else {
        return;
    };
    if textures.generation != lab.maps_generation || textures.textures.is_empty() {
        textures.textures.clear();
        // One colour scale for both: the nominal's (before) largest deviation, so the after map
        // shows how much darker it is instead of rescaling to look alike.
        let shared = before.as_ref().map(|b| b.max);
        let list = [
            (before.as_ref(), "before calibration"),
            (Some(after), "after calibration"),
        ];
        for (m, what) in list {
            let Some(m) = m else { continue };
            let (plot, img) =
                crate::figure::accuracy::accuracy_plot(m, &format!("Accuracy {what}"), shared);
            let tex = ui.ctx().load_texture(
                format!("accuracy {what}"),
                img,
                egui::TextureOptions::NEAREST,
            );
            textures.textures.push((plot, tex));
        }
        textures.generation = lab.maps_generation;
    }
    if let Some(b) = before {
        ui.label(format!(
            "Both maps share one colour scale, 0 to {:.3} mm: the nominal model's largest \
             deviation. After calibration the largest is {:.4} mm.",
            b.max * 1e3,
            after.max * 1e3
        ));
    }
    let w = ui.available_width() / textures.textures.len().max(1) as f32;
    ui.horizontal(|ui| {
        for (plot, tex) in &textures.textures {
            ui.allocate_ui(egui::vec2(w - 8.0, 420.0), |ui| {
                ui.set_min_size(egui::vec2(w - 8.0, 420.0));
                ui.vertical(|ui| {
                    crate::figure::plot2d::show(ui, plot, Some(tex.id()));
                });
            });
        }
    });
}

fn settings(lab: &mut CalibrationLab, ui: &mut egui::Ui) {
    let s = &mut lab.settings;
    egui::Grid::new("calibration settings")
        .num_columns(4)
        .show(ui, |ui| {
            let named = |ui: &mut egui::Ui, name: &str, w: egui::DragValue<'_>| {
                let l = ui.label(name);
                ui.add(w).labelled_by(l.id);
            };
            named(
                ui,
                "poses",
                egui::DragValue::new(&mut s.poses).range(4..=500),
            );
            named(ui, "seed", egui::DragValue::new(&mut s.seed));
            ui.end_row();
            named(
                ui,
                "tolerance [mm]",
                egui::DragValue::new(&mut s.tolerance_mm)
                    .range(0.0..=50.0)
                    .speed(0.05),
            );
            named(
                ui,
                "tolerance [deg]",
                egui::DragValue::new(&mut s.tolerance_deg)
                    .range(0.0..=10.0)
                    .speed(0.01),
            );
            ui.end_row();
            named(
                ui,
                "noise [mm]",
                egui::DragValue::new(&mut s.noise_mm)
                    .range(0.0..=5.0)
                    .speed(0.001),
            );
            named(
                ui,
                "noise [mrad]",
                egui::DragValue::new(&mut s.noise_mrad)
                    .range(0.0..=50.0)
                    .speed(0.005),
            );
            ui.end_row();
        });
    ui.horizontal_wrapped(|ui| {
        ui.label("poses:");
        for (c, name) in [
            (PoseChoice::Random, "random"),
            (PoseChoice::O1, "best O1"),
            (PoseChoice::O4, "best O4"),
            (PoseChoice::Alike, "all alike"),
        ] {
            ui.selectable_value(&mut s.choice, c, name);
        }
        ui.checkbox(&mut s.position_only, "position only");
    });
    setup_settings(s, ui);
}

/// The setup, its scene, and the model's options.
fn setup_settings(s: &mut super::lab::LabSettings, ui: &mut egui::Ui) {
    ui.horizontal_wrapped(|ui| {
        ui.label("setup:");
        for setup in Setup::ALL {
            ui.selectable_value(&mut s.setup, setup, setup.name())
                .on_hover_text(setup.blind_spots());
        }
    });
    ui.horizontal_wrapped(|ui| {
        match s.setup {
            Setup::Pivot | Setup::Plane | Setup::Sphere => {
                let l = ui.label(match s.setup {
                    Setup::Pivot => "points",
                    Setup::Plane => "planes",
                    _ => "spheres",
                });
                ui.add(egui::DragValue::new(&mut s.groups).range(1..=10))
                    .labelled_by(l.id);
            }
            Setup::Distance => {
                let l = ui.label("artefact [mm]");
                ui.add(
                    egui::DragValue::new(&mut s.distance_mm)
                        .range(10.0..=2000.0)
                        .speed(1.0),
                )
                .labelled_by(l.id);
            }
            _ => {}
        }
        if s.setup == Setup::Sphere {
            let l = ui.label("contact radius [mm]");
            ui.add(
                egui::DragValue::new(&mut s.radius_mm)
                    .range(1.0..=500.0)
                    .speed(0.1),
            )
            .labelled_by(l.id);
        }
        ui.checkbox(&mut s.hayati, "Hayati's beta on parallel axes");
        ui.checkbox(&mut s.bend, "real joints bend under gravity");
        ui.checkbox(&mut s.with_compliance, "estimate joint compliance");
        ui.checkbox(
            &mut s.minimum_norm,
            "estimate unidentifiable parameters too",
        )
        .on_hover_text(
            "Off (the default): one parameter of each combination the measurements cannot \
                 see keeps its nominal value. On: minimum-norm steps, which may drift far.",
        );
    });
}

fn actions(lab: &mut CalibrationLab, robot: &Robot, q: &[f64], ui: &mut egui::Ui) {
    ui.horizontal_wrapped(|ui| {
        if ui.button("Run").clicked() {
            lab.run_simulated(robot, q);
        }
        if ui
            .button("Lesson: converged is not accurate")
            .on_hover_text("40 poses all alike: a small residual, a bad validation, O1 near zero")
            .clicked()
        {
            lab.lesson_alike(robot, q);
        }
        if ui
            .button("Lesson: parallel axes")
            .on_hover_text("Plain DH on parallel axes (the Puma's 2 and 3): d2 and d3 run off")
            .clicked()
        {
            lab.lesson_parallel(robot, q, false);
        }
        if ui
            .button("... with Hayati's beta")
            .on_hover_text("beta instead of d on the parallel pair: every parameter identifiable")
            .clicked()
        {
            lab.lesson_parallel(robot, q, true);
        }
        if ui
            .button("Lesson: joints that bend")
            .on_hover_text("gravity bends the joints: the error no DH parameter can absorb")
            .clicked()
        {
            lab.lesson_compliance(robot, q, false);
        }
        if ui
            .button("... with compliance")
            .on_hover_text("one compliance per joint, estimated with the geometry")
            .clicked()
        {
            lab.lesson_compliance(robot, q, true);
        }
    });
}

/// The measurement file (typed, or chosen in the file dialog) and where to save the result.
fn files(lab: &mut CalibrationLab, robot: &Robot, picker: &mut dyn FilePicker, ui: &mut egui::Ui) {
    ui.label(
        RichText::new(
            "Measurement files: plain (SI units) or a headered CSV (joint names, units in \
             brackets, x y z and a quaternion / roll pitch yaw); read as the setup above says.",
        )
        .small(),
    );
    ui.horizontal(|ui| {
        let l = ui.label("measurements");
        ui.add(
            egui::TextEdit::singleline(&mut lab.measurements_path)
                .hint_text("measurements.csv")
                .desired_width(200.0),
        )
        .labelled_by(l.id);
        if ui.button("Calibrate from file").clicked() {
            lab.run_file(robot);
        }
        if ui
            .add_enabled(picker.available(), egui::Button::new("Browse..."))
            .on_hover_text("Choose the measurement file in a file dialog")
            .on_disabled_hover_text("No file dialog here: type the path")
            .clicked()
            && let Some(p) = picker.open(FileKind::Measurements)
        {
            lab.measurements_path = p.to_string_lossy().into_owned();
            lab.run_file(robot);
        }
    });
    template(lab, robot, picker, ui);
    ui.horizontal(|ui| {
        let l = ui.label("save as");
        ui.add(
            egui::TextEdit::singleline(&mut lab.save_path)
                .hint_text("calibrated.toml")
                .desired_width(200.0),
        )
        .labelled_by(l.id);
        if ui.button("Save calibrated model").clicked() && lab.request_save() {
            save_calibrated(lab, picker);
        }
    });
    if lab.confirm_save {
        confirm_save(lab, picker, ui);
    }
}

/// Writes the calibrated model (a download in a browser).
fn save_calibrated(lab: &mut CalibrationLab, picker: &mut dyn FilePicker) {
    if !picker.downloads() {
        return lab.save_model();
    }
    lab.confirm_save = false;
    let name = match lab.save_path.trim() {
        "" => "calibrated.toml".to_string(),
        n => n.to_string(),
    };
    let written = lab.calibrated_text().and_then(|t| {
        if picker.download(&name, "application/toml", t.as_bytes()) {
            Ok(format!("downloading the calibrated model as {name}"))
        } else {
            Err(format!("the browser refused the download of {name}"))
        }
    });
    lab.saved(written);
}

/// The question before saving a model with doubtful estimates: each named with its reason.
fn confirm_save(lab: &mut CalibrationLab, picker: &mut dyn FilePicker, ui: &mut egui::Ui) {
    let red = Color32::from_rgb(190, 0, 0);
    egui::Frame::group(ui.style()).show(ui, |ui| {
        ui.label(
            RichText::new("These estimates are not to be trusted:")
                .strong()
                .color(red),
        );
        for d in lab.doubts() {
            ui.add(egui::Label::new(RichText::new(d.to_string()).color(red)).wrap());
        }
        ui.label("Save the model anyway? Its file will name them in a warning at the top.");
        ui.horizontal(|ui| {
            if ui.button("Save with the warning").clicked() {
                save_calibrated(lab, picker);
            }
            if ui.button("Don't save").clicked() {
                lab.cancel_save();
            }
        });
    });
}

/// The template's path and its button.
fn template(
    lab: &mut CalibrationLab,
    robot: &Robot,
    picker: &mut dyn FilePicker,
    ui: &mut egui::Ui,
) {
    ui.horizontal(|ui| {
        let l = ui.label("template");
        ui.add(
            egui::TextEdit::singleline(&mut lab.template_path)
                .hint_text("measurements.csv")
                .desired_width(200.0),
        )
        .labelled_by(l.id);
        if ui
            .button("Write template")
            .on_hover_text("an annotated file for this setup and arm, with example rows")
            .clicked()
        {
            if picker.downloads() {
                let name = match lab.template_path.trim() {
                    "" => "measurements.csv",
                    n => n,
                };
                lab.said = Some(match lab.template_text(robot) {
                    Ok(t) if picker.download(name, "text/csv", t.as_bytes()) => {
                        Said::Done(format!("downloading the template as {name}"))
                    }
                    Ok(_) => Said::Failed(format!("the browser refused the download of {name}")),
                    Err(e) => Said::Failed(e),
                });
            } else {
                lab.save_template(robot);
            }
        }
    });
}

fn fit_line(name: &str, f: &Fit) -> String {
    let o = f.orientation_rms.map_or(String::new(), |r| {
        format!(", orientation rms {:.4} mrad", r * 1e3)
    });
    format!(
        "{name}: position rms {:.4} mm, max {:.4} mm{o}",
        f.position_rms * 1e3,
        f.position_max * 1e3
    )
}

/// The run's title, setup, file warnings, Hayati rows and what was kept nominal and why.
fn header(r: &LabResult, ui: &mut egui::Ui) {
    ui.strong(&r.title);
    let wrap = |ui: &mut egui::Ui, t: RichText| ui.add(egui::Label::new(t).wrap());
    wrap(
        ui,
        RichText::new(format!(
            "setup: {}; what it cannot see: {}",
            r.setup.name(),
            r.setup.blind_spots()
        ))
        .small(),
    );
    for w in &r.warnings {
        wrap(
            ui,
            RichText::new(format!("warning: {w}")).color(Color32::from_rgb(170, 60, 0)),
        );
    }
    let rows = r.model.hayati_rows();
    if !rows.is_empty() {
        ui.label(format!("Hayati's beta instead of d on rows {rows:?}"));
    }
    for (name, why) in &r.report.auto_fixed {
        wrap(
            ui,
            RichText::new(format!("kept at its nominal value: {name}, because {why}"))
                .color(Color32::from_rgb(0, 70, 140)),
        );
    }
}

fn report(r: &LabResult, ui: &mut egui::Ui) {
    let rep = &r.report;
    header(r, ui);
    egui::Grid::new("calibration iterations")
        .striped(true)
        .show(ui, |ui| {
            for h in [
                "iteration",
                "position rms [mm]",
                "orientation rms [mrad]",
                "step",
                "condition",
                "rank",
            ] {
                ui.label(RichText::new(h).small().strong());
            }
            ui.end_row();
            for (i, it) in rep.iterations.iter().enumerate() {
                ui.label(i.to_string());
                ui.label(format!("{:.5}", it.position_rms * 1e3));
                ui.label(format!("{:.5}", it.orientation_rms * 1e3));
                ui.label(format!("{:.1e}", it.step_norm));
                ui.label(format!("{:.2e}", it.condition));
                ui.label(it.rank.to_string());
                ui.end_row();
            }
        });
    ui.label(match &rep.reason {
        None => "converged".to_string(),
        Some(why) => format!("not converged: {why}"),
    });
    let n = &rep.nominal;
    ui.label(format!(
        "identifiable at the nominal parameters: rank {} of {}; at the estimate (the table's \
         flags): rank {} of {}",
        n.rank, n.parameter_count, rep.at_estimate.rank, rep.at_estimate.parameter_count
    ));
    for c in &n.combinations {
        ui.add(egui::Label::new(RichText::new(c).color(Color32::from_rgb(170, 60, 0))).wrap());
    }
    let o = n.observability;
    ui.label(format!(
        "O1 {:.3e}   O2 {:.3e}   O3 {:.3e}   O4 {:.3e}",
        o.o1, o.o2, o.o3, o.o4
    ));
    let line = |ui: &mut egui::Ui, t: RichText| ui.add(egui::Label::new(t).wrap());
    line(ui, RichText::new(fit_line("fit before", &rep.before)));
    line(ui, RichText::new(fit_line("fit after", &rep.after)));
    if let Some((b, a)) = &r.validation {
        line(ui, RichText::new(fit_line("held-out before", b)));
        line(ui, RichText::new(fit_line("held-out after", a)).strong());
    }
    parameters(r, ui);
    unknowns(r, ui);
}

/// The setup's estimated points, planes and spheres.
fn unknowns(r: &LabResult, ui: &mut egui::Ui) {
    let u = &r.report.unknowns;
    for (k, c) in u.points.iter().enumerate() {
        ui.label(format!(
            "point {}: ({:.3}, {:.3}, {:.3}) mm",
            k + 1,
            c[0] * 1e3,
            c[1] * 1e3,
            c[2] * 1e3
        ));
    }
    for (k, p) in u.planes.iter().enumerate() {
        let n = p.normal();
        ui.label(format!(
            "plane {}: normal ({:.5}, {:.5}, {:.5}), offset {:.3} mm",
            k + 1,
            n[0],
            n[1],
            n[2],
            p.h * 1e3
        ));
    }
    for (k, c) in u.spheres.iter().enumerate() {
        ui.label(format!(
            "sphere {}: centre ({:.3}, {:.3}, {:.3}) mm",
            k + 1,
            c[0] * 1e3,
            c[1] * 1e3,
            c[2] * 1e3
        ));
    }
}

fn parameters(r: &LabResult, ui: &mut egui::Ui) {
    let rep = &r.report;
    let doubts = crate::calibration::doubtful_parameters(rep);
    let correlated = |name: &str| {
        rep.correlations
            .iter()
            .any(|(a, b, _)| a == name || b == name)
    };
    egui::Grid::new("calibration parameters")
        .striped(true)
        .show(ui, |ui| {
            for h in ["parameter", "nominal", "true", "estimate", "std", ""] {
                ui.label(RichText::new(h).small().strong());
            }
            ui.end_row();
            for (k, p) in rep.parameters.iter().enumerate() {
                let (scale, unit) = p.kind.display();
                let kept = rep.auto_fixed.iter().any(|(n, _)| *n == p.name);
                let doubt = doubts.iter().find(|d| d.index == k);
                let state = if kept {
                    (
                        "kept nominal: not identifiable".to_string(),
                        Color32::from_rgb(0, 70, 140),
                    )
                } else if p.fixed {
                    ("fixed".into(), Color32::GRAY)
                } else if let Some(d) = doubt {
                    (d.reason(), Color32::from_rgb(190, 0, 0))
                } else if correlated(&p.name) {
                    ("correlated > 0.9".into(), Color32::from_rgb(200, 110, 0))
                } else {
                    (String::new(), Color32::GRAY)
                };
                ui.label(format!("{} [{unit}]", p.name));
                ui.label(format!("{:.4}", p.nominal * scale));
                ui.label(
                    r.truth
                        .as_ref()
                        .and_then(|t| t.get(k))
                        .filter(|v| v.is_finite())
                        .map_or("-".into(), |t| format!("{:.4}", t * scale)),
                );
                ui.label(format!("{:.4}", rep.estimate[k] * scale));
                ui.label(rep.std[k].map_or("-".into(), |s| format!("{:.2e}", s * scale)));
                ui.add(egui::Label::new(RichText::new(state.0).color(state.1)).wrap());
                ui.end_row();
            }
        });
}
