//! The right panel's Reachability section (issue 49), shown while the overlay is on: the map's
//! settings, Compute and Cancel with the progress, the slice plane (axis and a slider in
//! metres), the index's colour legend, the directions of the voxel pointed at or pinned (two
//! discs, the halves of the sphere pointing up and down, seen from above; a click moves the
//! target there), the postures the map finds at the target, and base placement (tasks, area,
//! grid, the best placement, moving the base there).
//!
//! It paints what it is handed: the map and the placement are computed in the background
//! ([`crate::app::state::reachability`], [`crate::app::state::placement`]), started and stopped
//! through [`ReachabilityAction`]s.

use super::super::action::{Action, Actions};
use super::super::reachability::{ReachabilityAction, add_to_scene};
use super::super::state::placement::{PlaceSettings, PlacementOverlay};
use super::super::state::reachability::{DirectionReach, MapSettings, ReachabilityOverlay, Slice};
use super::super::state::{AppState, format_number};
use crate::scene::reachability::{NOT_REACHED, PARTLY_REACHED, REACHED, index_color};
use crate::scene::{Rgba, Scene};
use egui::{Color32, RichText};

/// The tasks file proposed until one is typed.
pub const DEFAULT_TASKS_FILE: &str = "tasks.csv";

/// The Reachability section's state: the overlay's data, the placement's, the tasks file's
/// name, and where the directions' dots were drawn.
pub struct ReachabilityPanel {
    /// The map, its computation and what is looked at in it.
    pub map: ReachabilityOverlay,
    /// The base placement.
    pub placement: PlacementOverlay,
    /// The tasks file's name typed.
    pub tasks_path: String,
    /// Where each direction's dot was drawn last (its index, its centre in window points).
    pub dots: Vec<(usize, egui::Pos2)>,
}

impl Default for ReachabilityPanel {
    fn default() -> Self {
        Self {
            map: ReachabilityOverlay::default(),
            placement: PlacementOverlay::default(),
            tasks_path: DEFAULT_TASKS_FILE.to_string(),
            dots: Vec::new(),
        }
    }
}

/// Whether the overlay is on and allowed (an exercise sheet that hides the workspace or the IK
/// solutions hides it too).
pub fn shown(state: &AppState) -> bool {
    state.display.reachability && !(state.hidden.workspace || state.hidden.solutions)
}

/// The egui colour of a scene colour (linear RGB, as the renderer takes it): the panel's dots
/// and legend show what the 3D view shows.
fn color32(c: Rgba) -> Color32 {
    Color32::from(egui::Rgba::from_rgb(c[0], c[1], c[2]))
}

/// A number field named `name` (screen readers, UI tests).
fn named<T: egui::emath::Numeric>(
    ui: &mut egui::Ui,
    v: &mut T,
    range: std::ops::RangeInclusive<T>,
    speed: f64,
    name: &str,
) -> egui::Response {
    let r = ui.add(egui::DragValue::new(v).range(range).speed(speed));
    let value = v.to_f64();
    r.widget_info(|| {
        let mut info = egui::WidgetInfo::labeled(egui::Role::SpinButton, r.enabled(), name);
        info.value = Some(value);
        info
    });
    r
}

impl ReachabilityPanel {
    /// A copy of what is shown (no computation): a screenshot's.
    pub fn snapshot(&self) -> Self {
        Self {
            map: self.map.snapshot(),
            placement: self.placement.snapshot(),
            tasks_path: self.tasks_path.clone(),
            dots: Vec::new(),
        }
    }

    /// Takes what the computations finished (a map of another model is dropped, and computed
    /// again while shown); returns whether something changed.
    pub fn poll(&mut self, state: &AppState, ee: usize) -> bool {
        let shown = state.display.reachability;
        let map = self.map.poll(state, ee, shown);
        map | self.placement.poll()
    }

    /// Whether a map or a placement is being computed.
    pub fn computing(&self) -> bool {
        self.map.computing() || self.placement.job().is_some()
    }

    /// Adds the overlay to the 3D scene while it is on (after taking what finished).
    pub fn decorate(&mut self, state: &AppState, ee: usize, scene: &mut Scene) {
        self.poll(state, ee);
        if shown(state) {
            let scale = state.robot().longest_chain_length();
            add_to_scene((&self.map, &self.placement), scale, scene);
        }
    }

    /// The section.
    pub fn ui(&mut self, state: &AppState, ee: usize, ui: &mut egui::Ui, out: &mut Actions) {
        self.poll(state, ee);
        if self.computing() {
            ui.ctx()
                .request_repaint_after(std::time::Duration::from_millis(100));
        }
        ui.heading("Reachability");
        self.settings_rows(ui, out);
        self.status(ui);
        if self.map.result().is_some() {
            self.slice_rows(ui);
            legend(ui);
            self.voxel_rows(ui, out);
        }
        ui.separator();
        self.placement_ui(state, ee, ui, out);
    }

    /// The settings, Compute and Cancel.
    fn settings_rows(&mut self, ui: &mut egui::Ui, out: &mut Actions) {
        let s = &mut self.map.settings;
        ui.horizontal_wrapped(|ui| {
            if ui
                .button("Fast: 10 cm, 50 x 4")
                .on_hover_text("10 cm voxels, 50 directions, 4 rolls: a second or two")
                .clicked()
            {
                *s = MapSettings::FAST;
            }
            if ui
                .button("Fine: 5 cm, 200 x 8")
                .on_hover_text("The issue's map: 5 cm voxels, 200 directions, 8 rolls")
                .clicked()
            {
                *s = MapSettings::FULL;
            }
        });
        ui.horizontal_wrapped(|ui| {
            let mut cm = s.voxel_m * 100.0;
            ui.label("voxel [cm]");
            if named(ui, &mut cm, 1.0..=50.0, 0.1, "voxel [cm]").changed() {
                s.voxel_m = cm / 100.0;
            }
            ui.label("directions");
            named(ui, &mut s.directions, 1..=2000, 1.0, "directions");
            ui.label("rolls");
            named(ui, &mut s.rolls, 1..=72, 0.1, "rolls");
        });
        let settings = *s;
        ui.horizontal(|ui| {
            if ui
                .button("Compute the map")
                .on_hover_text("Every sample solved by IK, in the cell when one is open")
                .clicked()
            {
                out.push(Action::Reachability(ReachabilityAction::Compute(settings)));
            }
            if self.map.computing() && ui.button("Cancel").clicked() {
                out.push(Action::Reachability(ReachabilityAction::Cancel));
            }
        });
        if let Some(job) = self.map.job() {
            let (done, total) = job.progress();
            let f = done as f32 / total.max(1) as f32;
            progress(ui, f, format!("voxels {done} of {total}"));
        }
    }

    /// What the map is, or why there is none.
    fn status(&self, ui: &mut egui::Ui) {
        if let Some(e) = &self.map.error {
            ui.colored_label(Color32::from_rgb(190, 0, 0), e);
        }
        let Some(r) = self.map.result() else {
            if !self.map.computing() {
                ui.label(RichText::new("no map yet: Compute the map").small());
            }
            return;
        };
        let m = &r.map;
        let [nx, ny, nz] = m.grid.dims;
        let time = r.seconds.map_or(String::new(), |s| format!(", {s:.1} s"));
        let cell = if m.collisions { ", in the cell" } else { "" };
        let text = format!(
            "{} voxels of {:.0} cm ({nx} x {ny} x {nz}), {} directions x {} rolls: {} reached; \
             {}{cell}{time}",
            m.grid.len(),
            m.grid.voxel_m * 100.0,
            m.directions.len(),
            m.rolls.len(),
            r.reached_voxels,
            m.solver.describe(),
        );
        ui.label(RichText::new(text).small());
    }

    /// The slice's axis, its slider (m) and "all voxels".
    fn slice_rows(&mut self, ui: &mut egui::Ui) {
        let Some(mut slice) = self.map.slice else {
            return;
        };
        ui.horizontal(|ui| {
            ui.label("slice across");
            for (k, name) in ["x", "y", "z"].into_iter().enumerate() {
                let r = ui.selectable_label(slice.axis == k, name);
                let named = format!("slice across {name}");
                r.widget_info(|| {
                    let t = egui::Role::Button;
                    egui::WidgetInfo::selected(t, true, slice.axis == k, &named)
                });
                if r.clicked() && slice.axis != k {
                    let at_m = self
                        .map
                        .slice_range(k)
                        .map_or(0.0, |(lo, hi)| 0.5 * (lo + hi));
                    slice = Slice { axis: k, at_m };
                }
            }
        });
        if let Some((lo, hi)) = self.map.slice_range(slice.axis) {
            let step = self.map.result().map_or(0.01, |r| r.map.grid.voxel_m);
            let name = format!("{} of the slice [m]", ["x", "y", "z"][slice.axis]);
            let label = ui.label(name);
            ui.scope(|ui| {
                // As long as the panel allows (a voxel's step is a few points on a short
                // slider), leaving room for the value's box.
                let s = ui.spacing();
                let room = 2.0 * s.interact_size.x + s.item_spacing.x;
                ui.spacing_mut().slider_width = (ui.available_width() - room).max(100.0);
                ui.add(
                    egui::Slider::new(&mut slice.at_m, lo..=hi.max(lo))
                        .step_by(step)
                        .custom_formatter(|v, _| format_number(v, 3)),
                )
                .labelled_by(label.id);
            });
        }
        if Some(slice) != self.map.slice {
            self.map.set_slice(slice);
        }
        ui.checkbox(&mut self.map.all_voxels, "Every reached voxel as a dot")
            .on_hover_text("Besides the slice, every voxel reached at all, coloured by its index");
    }

    /// The voxel shown, its directions and the target's postures.
    fn voxel_rows(&mut self, ui: &mut egui::Ui, out: &mut Actions) {
        let Some(r) = self.map.result() else { return };
        let Some(v) = self.map.shown_voxel() else {
            ui.label("Point at a voxel of the slice: its directions show; click it to keep them.");
            self.dots.clear();
            return;
        };
        let m = &r.map;
        let ijk = m.grid.ijk(v);
        let c = m.grid.centre(ijk).map(|x| x * 1e3);
        let reached = (m.reachable[v * m.per_voxel()..(v + 1) * m.per_voxel()].iter())
            .filter(|&&b| b)
            .count();
        ui.label(format!(
            "voxel {ijk:?} at ({:.0}, {:.0}, {:.0}) mm{}: index {:.2} ({reached} of {} \
             orientations)",
            c[0],
            c[1],
            c[2],
            if self.map.pinned == Some(v) {
                ", pinned"
            } else {
                ""
            },
            r.index[v],
            m.per_voxel(),
        ));
        let rolls = m.rolls.clone();
        ui.horizontal(|ui| {
            let label = ui.label("roll");
            let text = |k: Option<usize>| {
                k.map_or("every roll".to_string(), |k| {
                    format!("{:.0} deg", rolls[k].to_degrees())
                })
            };
            egui::ComboBox::from_id_salt("reachability roll")
                .selected_text(text(self.map.roll))
                .show_ui(ui, |ui| {
                    for k in std::iter::once(None).chain((0..rolls.len()).map(Some)) {
                        ui.selectable_value(&mut self.map.roll, k, text(k));
                    }
                })
                .response
                .labelled_by(label.id);
        });
        self.direction_discs(ui, v, out);
        self.aimed_rows(ui);
    }

    /// The postures the map's computation finds at the target's sample.
    fn aimed_rows(&self, ui: &mut egui::Ui) {
        let (Some(a), Some(r)) = (&self.map.aimed, self.map.result()) else {
            return;
        };
        let d = r.map.directions[a.direction];
        ui.label(format!(
            "target: direction {} ({:.2}, {:.2}, {:.2}), roll\u{a0}{:.0}\u{a0}deg: {} posture(s)",
            a.direction,
            d[0],
            d[1],
            d[2],
            r.map.rolls[a.roll].to_degrees(),
            a.solutions.len()
        ));
        for s in &a.solutions {
            ui.label(RichText::new(format!("  {}", s.label)).small());
        }
    }

    /// The two discs of directions of voxel `v`; a click on a dot aims the target there.
    fn direction_discs(&mut self, ui: &mut egui::Ui, v: usize, out: &mut Actions) {
        let Some(r) = self.map.result() else { return };
        let reach = self.map.directions_of(v);
        let dirs = &r.map.directions;
        let w = ui.available_width().min(460.0);
        let d = ((w - 16.0) / 2.0).clamp(60.0, 220.0);
        let text_h = ui.text_style_height(&egui::TextStyle::Small) + 4.0;
        let (rect, response) =
            ui.allocate_exact_size(egui::vec2(w, d + text_h), egui::Sense::click());
        response.widget_info(|| {
            egui::WidgetInfo::labeled(egui::Role::Canvas, true, "directions of the voxel")
        });
        let centres = [
            rect.left_top() + egui::vec2(d / 2.0 + 2.0, d / 2.0),
            rect.left_top() + egui::vec2(1.5 * d + 14.0, d / 2.0),
        ];
        // Room for the ring around the aimed dot.
        let radius = d / 2.0 - 8.0;
        let spacing = radius * (2.0 * std::f32::consts::PI / dirs.len().max(1) as f32).sqrt();
        let dot = (0.35 * spacing).clamp(2.5, 9.0);
        let painter = ui.painter_at(rect);
        let ink = ui.visuals().text_color();
        let font = egui::FontId::proportional(ui.text_style_height(&egui::TextStyle::Small));
        for (c, name) in centres.iter().zip(["pointing up", "pointing down"]) {
            painter.circle_stroke(*c, radius, egui::Stroke::new(1.0, ink));
            let at = egui::pos2(c.x, rect.bottom() - 2.0);
            painter.text(at, egui::Align2::CENTER_BOTTOM, name, font.clone(), ink);
        }
        self.dots = dirs
            .iter()
            .enumerate()
            .map(|(k, d)| (k, disc_position(*d, centres, radius)))
            .collect();
        let aimed = self.map.aimed.as_ref().filter(|a| a.voxel == v);
        for &(k, p) in &self.dots {
            let color = match reach[k] {
                DirectionReach::All => REACHED,
                DirectionReach::Some => PARTLY_REACHED,
                DirectionReach::None => NOT_REACHED,
            };
            painter.circle_filled(p, dot, color32(color));
            if aimed.is_some_and(|a| a.direction == k) {
                painter.circle_stroke(p, dot + 3.0, egui::Stroke::new(2.5, Color32::BLUE));
            }
        }
        let pick = (0.6 * spacing).max(dot + 2.0);
        if let Some(k) = disc_input(&self.dots, &response, (&reach, dirs), pick) {
            let roll = self.map.roll_for(v, k);
            out.push(Action::Reachability(ReachabilityAction::Aim {
                voxel: v,
                direction: k,
                roll,
            }));
        }
    }

    /// Base placement: the tasks, the grid, Place, the best placement and moving the base.
    fn placement_ui(&mut self, state: &AppState, ee: usize, ui: &mut egui::Ui, out: &mut Actions) {
        ui.heading("Base placement");
        ui.horizontal(|ui| {
            let label = ui.label("tasks file");
            ui.add(
                egui::TextEdit::singleline(&mut self.tasks_path)
                    .desired_width((ui.available_width() - 100.0).max(60.0)),
            )
            .labelled_by(label.id);
            if ui
                .button("Open tasks")
                .on_hover_text(
                    "A CSV of task poses: name, x, y, z, roll_deg, pitch_deg, yaw_deg (or 16 \
                     numbers of a 4x4 pose) per line",
                )
                .clicked()
            {
                let path = self.tasks_path.trim().to_string();
                out.push(Action::Reachability(ReachabilityAction::OpenTasks(path)));
            }
        });
        let p = &mut self.placement;
        ui.horizontal_wrapped(|ui| {
            if ui
                .button("Add the target")
                .on_hover_text("The IK target's pose as one more task")
                .clicked()
            {
                out.push(Action::Reachability(ReachabilityAction::AddTargetAsTask));
            }
            if ui.button("Clear tasks").clicked() {
                out.push(Action::Reachability(ReachabilityAction::ClearTasks));
            }
            ui.label(format!("{} task(s)", p.tasks.len()));
        });
        task_buttons(p, ee, ui, out);
        let settings = p
            .settings
            .get_or_insert_with(|| PlaceSettings::around(state.robot()));
        grid_rows(settings, ui);
        let settings = *settings;
        placement_result(p, settings, ui, out);
    }
}

/// Where direction `d` (unit, world) is drawn: on the first disc (centre `centres[0]`) when it
/// points up, else on the second, both seen from above (x right, y up), by the equal-area
/// azimuthal projection of its hemisphere onto a disc of `radius` points.
pub fn disc_position(d: [f64; 3], centres: [egui::Pos2; 2], radius: f32) -> egui::Pos2 {
    let (c, z) = if d[2] >= 0.0 {
        (centres[0], d[2])
    } else {
        (centres[1], -d[2])
    };
    let polar = z.clamp(-1.0, 1.0).acos();
    let rho = std::f64::consts::SQRT_2 * (0.5 * polar).sin();
    let h = d[0].hypot(d[1]);
    let (x, y) = if h > 1e-12 {
        (d[0] / h, d[1] / h)
    } else {
        (0.0, 0.0)
    };
    c + egui::vec2((x * rho) as f32, -(y * rho) as f32) * radius
}

/// The discs' hover text (the direction under the pointer and how it is reached) and the
/// direction clicked, if any: the dot (of `dots`, drawn for `dirs` reached as `reach` says)
/// nearest the pointer within `pick` points.
fn disc_input(
    dots: &[(usize, egui::Pos2)],
    response: &egui::Response,
    (reach, dirs): (&[DirectionReach], &[[f64; 3]]),
    pick: f32,
) -> Option<usize> {
    let nearest = |at: egui::Pos2| {
        (dots.iter())
            .map(|&(k, p)| (k, (p - at).length()))
            .filter(|&(_, dist)| dist < pick)
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(k, _)| k)
    };
    if let Some(k) = response.hover_pos().and_then(nearest) {
        let how = match reach[k] {
            DirectionReach::All => "reached",
            DirectionReach::Some => "reached at some rolls",
            DirectionReach::None => "not reached",
        };
        let d = dirs[k];
        let tip = format!(
            "direction {k}: ({:.2}, {:.2}, {:.2}), {how}; click: the target goes there",
            d[0], d[1], d[2]
        );
        response.clone().on_hover_text(tip);
    }
    if response.clicked() {
        response.interact_pointer_pos().and_then(nearest)
    } else {
        None
    }
}

/// A button per task: the IK target of `ee` goes to it (the arm shows whether and how it
/// reaches the task from where the base is).
fn task_buttons(p: &PlacementOverlay, ee: usize, ui: &mut egui::Ui, out: &mut Actions) {
    if p.tasks.is_empty() {
        return;
    }
    ui.horizontal_wrapped(|ui| {
        ui.label("target to");
        for t in &p.tasks {
            if ui
                .small_button(&t.name)
                .on_hover_text("The IK target goes to this task")
                .clicked()
            {
                out.push(Action::SetTarget(ee, t.world_from_tool));
            }
        }
    });
}

/// The placement's area, step and yaws.
fn grid_rows(s: &mut PlaceSettings, ui: &mut egui::Ui) {
    ui.horizontal_wrapped(|ui| {
        ui.label("area x [m]");
        named(ui, &mut s.area[0], -50.0..=50.0, 0.01, "area x from [m]");
        named(ui, &mut s.area[1], -50.0..=50.0, 0.01, "area x to [m]");
        ui.label("y [m]");
        named(ui, &mut s.area[2], -50.0..=50.0, 0.01, "area y from [m]");
        named(ui, &mut s.area[3], -50.0..=50.0, 0.01, "area y to [m]");
    });
    ui.horizontal_wrapped(|ui| {
        let mut cm = s.step * 100.0;
        ui.label("step [cm]");
        if named(ui, &mut cm, 0.5..=100.0, 0.1, "step [cm]").changed() {
            s.step = cm / 100.0;
        }
        ui.label("yaws");
        named(ui, &mut s.yaws, 1..=360, 0.2, "yaws");
    });
}

/// Place and Cancel with the progress, the best placement and "Move the base there".
fn placement_result(
    p: &PlacementOverlay,
    settings: PlaceSettings,
    ui: &mut egui::Ui,
    out: &mut Actions,
) {
    ui.horizontal(|ui| {
        if ui
            .add_enabled(!p.tasks.is_empty(), egui::Button::new("Place the base"))
            .on_hover_text("Every task solved by IK at every base position and yaw")
            .on_disabled_hover_text("Open a tasks file or add the target first")
            .clicked()
        {
            out.push(Action::Reachability(ReachabilityAction::Place(settings)));
        }
        if p.job().is_some() && ui.button("Cancel placement").clicked() {
            out.push(Action::Reachability(ReachabilityAction::CancelPlacement));
        }
    });
    if let Some(job) = p.job() {
        let f = job.done() as f32 / job.total.max(1) as f32;
        progress(
            ui,
            f,
            format!("base positions {} of {}", job.done(), job.total),
        );
    }
    if let Some(e) = &p.error {
        ui.colored_label(Color32::from_rgb(190, 0, 0), e);
    }
    let Some(r) = p.result() else { return };
    let time = r.seconds.map_or(String::new(), |s| format!(" in {s:.1} s"));
    let Some(b) = r.map.best.first() else {
        ui.label(format!("no base position reaches a task{time}"));
        return;
    };
    ui.label(format!(
        "best: x = {:.3} m, y = {:.3} m, yaw {:.0} deg: {} of {} tasks, {} solutions{time}",
        b.detail.x,
        b.detail.y,
        b.detail.yaw.to_degrees(),
        b.reached,
        r.map.tasks.len(),
        b.solutions,
    ));
    if ui
        .button("Move the base there")
        .on_hover_text("The robot's base to the best placement (Undo takes it back)")
        .clicked()
    {
        out.push(Action::Reachability(ReachabilityAction::MoveBase));
    }
}

/// A progress bar on a row of its own, as wide as the panel (never wider: a wider one would
/// widen the panel and shrink the 3D view).
fn progress(ui: &mut egui::Ui, f: f32, text: String) {
    let w = ui.available_width();
    ui.add(egui::ProgressBar::new(f).desired_width(w).text(text));
}

/// The index's colour legend: a bar from 0 to 1.
fn legend(ui: &mut egui::Ui) {
    ui.horizontal(|ui| {
        ui.label("index 0");
        let (rect, _) = ui.allocate_exact_size(egui::vec2(120.0, 12.0), egui::Sense::hover());
        let n = 24;
        for k in 0..n {
            let x0 = rect.left() + rect.width() * k as f32 / n as f32;
            let x1 = rect.left() + rect.width() * (k + 1) as f32 / n as f32;
            let r = egui::Rect::from_x_y_ranges(x0..=x1, rect.y_range());
            let c = index_color((k as f64 + 0.5) / n as f64);
            ui.painter().rect_filled(r, 0.0, color32(c));
        }
        ui.label("1 (share of orientations reached)");
    });
}
