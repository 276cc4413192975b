//! The Orientation tab (Sects. 2.2-2.6, Problems 2.1-2.10, 2.15, 2.16): a frame turned in 3D
//! over the reference frame. **Turn**: sliders or typed values for one representation (ZYZ,
//! ZXZ, RPY, angle-axis, quaternion) with the matrix and every other representation live beside
//! it, the singular cases said in words and drawn. **Compose**: elementary rotations about the
//! current or the fixed frame, played step by step with the intermediate frames as ghosts and
//! the product written out. **2.15**: the sum of two sets of angles in both orders. **2.16**:
//! the commutator of two elementary rotations against the angle. The tab owns its state and
//! its own 3D view (camera), and paints the scene [`OrientationTab::scene`] makes.

pub mod lab;
mod modes;

use super::super::action::Actions;
use super::super::state::AppState;
use super::super::viewport::{TextureRegistry, Viewport3d, ViewportImage};
use super::view3d::View3d;
use super::{Tab, TabContext};
use crate::kinematics::orientation::{Axis, Step, StepFrame};
use crate::lesson::{OrientationMode, OrientationStep, SequenceStep};
use crate::scene::Scene;
use crate::scene::orientation::{AxisMark, FrameMark, OrientationPicture, orientation_scene};
use lab::{NearSingular, Rep};
use nalgebra::{Rotation3, Vector3};

/// What the tab shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// One representation edited, every other one shown.
    Turn,
    /// A sequence of elementary rotations, step by step.
    Compose,
    /// Problem 2.15: a sum of minimal representations in both orders.
    Sum,
    /// Problem 2.16: the commutator of two rotations against the angle.
    Small,
}

impl Mode {
    const ALL: [(Mode, &'static str); 4] = [
        (Mode::Turn, "Turn"),
        (Mode::Compose, "Compose"),
        (Mode::Sum, "2.15: sums"),
        (Mode::Small, "2.16: small turns"),
    ];
}

/// The composition builder's state.
#[derive(Debug, Clone, PartialEq)]
pub struct Composition {
    /// The sequence, in the order it is stated.
    pub steps: Vec<Step>,
    /// How many steps are applied (0: the reference frame).
    pub shown: usize,
    /// Playing: the time (s) the last step was shown.
    pub playing: Option<f64>,
    /// The end of the sequence as it was stated, while it is shown reversed or switched.
    pub before: Option<Changed>,
}

impl Default for Composition {
    fn default() -> Self {
        let deg = f64::to_radians;
        let step = |frame, axis, angle: f64| Step {
            frame,
            axis,
            angle: deg(angle),
        };
        let steps = vec![
            step(StepFrame::Current, Axis::Z, 30.0),
            step(StepFrame::Current, Axis::Y, 45.0),
            step(StepFrame::Fixed, Axis::X, 10.0),
        ];
        Self {
            shown: steps.len(),
            steps,
            playing: None,
            before: None,
        }
    }
}

/// The sequence as stated, and how the shown one differs from it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Changed {
    /// Where the stated sequence ends.
    pub end: Rotation3<f64>,
    /// The order is reversed.
    pub reversed: bool,
    /// Current and fixed are switched.
    pub switched: bool,
}

/// The Orientation tab.
pub struct OrientationTab {
    /// What is shown.
    pub mode: Mode,
    /// The representation edited in Turn.
    pub rep: Rep,
    /// Its values (degrees where they are angles).
    pub values: [f64; 4],
    /// The rotation the values give (the last valid one).
    pub rotation: Rotation3<f64>,
    /// Why the values give no rotation (a zero axis or quaternion).
    pub invalid: Option<&'static str>,
    /// Draw the arm's tool frame too.
    pub show_tool: bool,
    /// The composition builder.
    pub composition: Composition,
    /// Problem 2.15: the convention and the two angle sets (degrees).
    pub sum: (crate::kinematics::EulerKind, [f64; 3], [f64; 3]),
    /// Problem 2.16: the two axes.
    pub small: (Axis, Axis),
    /// The tab's own 3D view (its camera, its labels).
    pub view: View3d,
    /// The view's size and camera when it was last framed.
    fitted_at: Option<([u32; 2], crate::camera::Camera)>,
}

impl Default for OrientationTab {
    fn default() -> Self {
        let rep = Rep::Euler(crate::kinematics::EulerKind::Zyz);
        let values = [30.0, 45.0, 60.0, 0.0];
        Self {
            mode: Mode::Turn,
            rep,
            values,
            rotation: rep.rotation_of(values).unwrap_or_default(),
            invalid: None,
            show_tool: false,
            composition: Composition::default(),
            sum: (
                crate::kinematics::EulerKind::Rpy,
                [0.0, 0.0, 90.0],
                [0.0, 90.0, 0.0],
            ),
            small: (Axis::X, Axis::Y),
            view: View3d::default(),
            fitted_at: None,
        }
    }
}

impl OrientationTab {
    /// Edits `rep` from now on, starting from the current rotation's values.
    pub fn set_rep(&mut self, rep: Rep) {
        self.rep = rep;
        self.values = rep.values_of(&self.rotation);
        self.invalid = None;
    }

    /// Sets the edited values (degrees where angles) and the rotation they give.
    pub fn set_values(&mut self, values: [f64; 4]) {
        self.values = values;
        match self.rep.rotation_of(values) {
            Ok(r) => {
                self.rotation = r;
                self.invalid = None;
            }
            Err(e) => self.invalid = Some(e),
        }
    }

    /// Sets the rotation (from the tool, a composition) and the edited values from it.
    pub fn set_rotation(&mut self, r: Rotation3<f64>) {
        self.rotation = r;
        self.values = self.rep.values_of(&r);
        self.invalid = None;
    }

    /// The edited Euler angles' nearness to their singular case (Turn only).
    pub fn near_singular(&self) -> Option<NearSingular> {
        match (self.mode, self.rep) {
            (Mode::Turn, Rep::Euler(kind)) => {
                let a = Vector3::new(self.values[0], self.values[1], self.values[2]);
                NearSingular::of(kind, &a.map(f64::to_radians))
            }
            _ => None,
        }
    }

    /// The frame the tab turns now: Turn's rotation, the composition's partial product, the
    /// first order of the sum.
    pub fn turned(&self) -> Rotation3<f64> {
        match self.mode {
            Mode::Turn | Mode::Small => self.rotation,
            Mode::Compose => {
                let c = &self.composition;
                let upto = &c.steps[..c.shown.min(c.steps.len())];
                crate::kinematics::orientation::compose(upto)
            }
            Mode::Sum => modes::sum_rotations(self).0,
        }
    }

    /// The 3D picture of the current mode (`tool`: the arm's tool orientation, drawn if asked).
    pub fn picture(&self, tool: Option<Rotation3<f64>>, projector: bool) -> OrientationPicture {
        let mut marks = Vec::new();
        let mut axes = Vec::new();
        match self.mode {
            Mode::Compose => {
                let c = &self.composition;
                let partial = crate::kinematics::orientation::partial_products(&c.steps);
                for (k, r) in partial.iter().enumerate().take(c.shown.saturating_sub(1)) {
                    marks.push(mark(*r, &(k + 1).to_string(), 0.35));
                }
                if let Some(b) = c.before {
                    marks.push(mark(b.end, "b", 0.6));
                }
            }
            Mode::Sum => {
                let (_, ba, naive) = modes::sum_rotations(self);
                marks.push(mark(ba, "21", 0.7));
                marks.push(mark(naive, "+", 0.3));
            }
            Mode::Turn | Mode::Small => {
                if let Some(n) = self.near_singular() {
                    axes.push(AxisMark {
                        direction: n.axes[0],
                        label: "phi".into(),
                    });
                    axes.push(AxisMark {
                        direction: n.axes[1],
                        label: "psi".into(),
                    });
                }
            }
        }
        if let Some(t) = tool.filter(|_| self.show_tool) {
            marks.push(mark(t, "e", 0.8));
        }
        OrientationPicture {
            rotation: self.turned(),
            suffix: match self.mode {
                Mode::Sum => "12".into(),
                _ => "'".into(),
            },
            marks,
            axes,
            body: true,
            projector,
        }
    }

    /// Renders the tab's scene with its own camera into the viewport (`vp`, its texture
    /// registry, dark or light); returns the image to show.
    pub fn render(
        &mut self,
        state: &AppState,
        ee: usize,
        projector: bool,
        (vp, registry, dark): (&mut Viewport3d, &mut dyn TextureRegistry, bool),
    ) -> Result<ViewportImage, String> {
        let scene = self.scene(state, ee, projector);
        self.view.render(vp, registry, scene, dark)
    }

    /// The scene the tab's 3D view renders.
    pub fn scene(&self, state: &AppState, ee: usize, projector: bool) -> Scene {
        let tool = state.target(ee).ok().map(|t| t.world_from_tool.rotation);
        orientation_scene(&self.picture(tool, projector))
    }

    /// The tab's setup as a lesson step saves it.
    pub fn lesson_step(&self) -> OrientationStep {
        let c = &self.composition;
        OrientationStep {
            mode: match self.mode {
                Mode::Turn => OrientationMode::Turn,
                Mode::Compose => OrientationMode::Compose,
                Mode::Sum => OrientationMode::Sum,
                Mode::Small => OrientationMode::Small,
            },
            edit: Some(lab::lesson_rep(self.rep)),
            values: Some(self.values[..self.rep.fields().len()].to_vec()),
            sequence: Some(
                c.steps
                    .iter()
                    .map(|s| SequenceStep {
                        frame: s.frame,
                        axis: s.axis,
                        angle_deg: s.angle.to_degrees(),
                    })
                    .collect(),
            ),
            shown: Some(c.shown.min(c.steps.len())),
        }
    }

    /// Sets the tab up as a lesson step says (what it leaves out stays as it is).
    pub fn apply_lesson(&mut self, o: &OrientationStep) {
        self.mode = match o.mode {
            OrientationMode::Turn => Mode::Turn,
            OrientationMode::Compose => Mode::Compose,
            OrientationMode::Sum => Mode::Sum,
            OrientationMode::Small => Mode::Small,
        };
        if let Some(rep) = o.edit {
            self.set_rep(lab::tab_rep(rep));
        }
        if let Some(v) = &o.values {
            let mut values = [0.0; 4];
            for (slot, x) in values.iter_mut().zip(v) {
                *slot = *x;
            }
            self.set_values(values);
        }
        let c = &mut self.composition;
        if let Some(seq) = &o.sequence {
            c.steps = seq
                .iter()
                .map(|s| Step {
                    frame: s.frame,
                    axis: s.axis,
                    angle: s.angle_deg.to_radians(),
                })
                .collect();
            c.shown = c.steps.len();
            c.before = None;
        }
        if let Some(k) = o.shown {
            c.shown = k.min(c.steps.len());
        }
        c.playing = None;
    }

    /// Frames the unit ball once the view has its size (as the orientation figures do).
    fn fit(&mut self) {
        let camera = crate::figure::orientation::camera(self.view.viewport_px);
        self.view.set_camera(camera);
        self.fitted_at = Some((self.view.viewport_px, camera));
    }
}

fn mark(rotation: Rotation3<f64>, suffix: &str, weight: f32) -> FrameMark {
    FrameMark {
        rotation,
        suffix: suffix.into(),
        weight,
    }
}

impl Tab for OrientationTab {
    fn title(&self) -> &'static str {
        "Orientation"
    }

    fn ui(&mut self, cx: &mut TabContext<'_>, ui: &mut egui::Ui, out: &mut Actions) {
        if cx.state.hidden.exam {
            ui.label(
                "The Orientation tab is closed during an exam: it would compute the answer. \
                 It opens again when the sheet is closed.",
            );
            return;
        }
        ui.horizontal(|ui| {
            for (m, name) in Mode::ALL {
                if ui.selectable_label(self.mode == m, name).clicked() {
                    self.mode = m;
                }
            }
        });
        // The 3D view keeps the larger share, the controls the rest (scrolled).
        let avail = ui.available_rect_before_wrap();
        let split = avail.left()
            + (avail.width() * 0.55)
                .max(avail.width() - 520.0)
                .min(avail.width() * 0.7);
        let view = egui::Rect::from_min_max(avail.min, egui::pos2(split, avail.bottom()));
        let controls = egui::Rect::from_min_max(egui::pos2(split + 8.0, avail.top()), avail.max);
        self.view.set_rect(ui, view);
        // Framed when first shown and again when the view's size changes, unless the user has
        // turned or zoomed it since.
        let resized = self
            .fitted_at
            .is_some_and(|(px, cam)| px != self.view.viewport_px && cam == self.view.camera);
        if (self.fitted_at.is_none() || resized) && view.width() > 50.0 {
            self.fit();
        }
        let font = egui::FontId::proportional(13.0 * cx.layout.text_scale());
        let response = self.view.paint(ui, cx.image.as_ref(), &font, &[]);
        self.view.navigate(ui, &response, view, false);
        if response.double_clicked() {
            self.fit();
        }
        let mut child = ui.new_child(egui::UiBuilder::new().max_rect(controls));
        egui::ScrollArea::vertical()
            .id_salt("orientation controls")
            .auto_shrink([false, false])
            .show(&mut child, |ui| match self.mode {
                Mode::Turn => modes::turn(self, cx, ui),
                Mode::Compose => modes::compose_ui(self, ui),
                Mode::Sum => modes::sum(self, ui),
                Mode::Small => modes::small(self, ui),
            });
        let _ = out;
    }

    fn model_changed(&mut self) {}
}
