//! The Calibration tab's state (no GUI types): simulation settings, the last run's report, the
//! two built-in lessons, measurement files and saving the calibrated model. Every failure is a
//! message; the previous result stays.

use crate::calibration::{
    AccuracyMap, CalibrationOptions, CalibrationReport, Criterion, Fit, JointColumns, Measurement,
    ParameterModel, Setup, SetupScene, SimulationOptions, TargetCorrection, Unidentifiable,
    accuracy_map, calibrate, correct_targets, fit, nominal_examples, parse_setup, parse_targets,
    register_tracker, select_poses, simulate, simulate_setup, template, write_corrections,
};
use crate::kinematics::Robot;
use crate::kinematics::pose::Pose;
use nalgebra::{Rotation3, Translation3, Vector3};

/// How the simulated poses are chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PoseChoice {
    /// Uniformly random in the joint limits.
    Random,
    /// Maximising O1 among 10x as many random poses.
    O1,
    /// Maximising O4 among 10x as many random poses.
    O4,
    /// All within 0.02 rad of the arm's current configuration (the lesson "converged is not
    /// accurate").
    Alike,
}

/// The settings of a simulated calibration (units as named).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LabSettings {
    /// Measured poses (as many again are held out).
    pub poses: usize,
    /// Length deviations of the "real" arm, +- mm.
    pub tolerance_mm: f64,
    /// Angle deviations, +- degrees.
    pub tolerance_deg: f64,
    /// Position noise, mm (one sigma).
    pub noise_mm: f64,
    /// Orientation noise, mrad (one sigma).
    pub noise_mrad: f64,
    /// Position-only measurements.
    pub position_only: bool,
    /// Pose choice.
    pub choice: PoseChoice,
    /// Hayati's beta on parallel axes (the default).
    pub hayati: bool,
    /// Estimate unidentifiable parameters by minimum-norm steps instead of keeping them at
    /// their nominal values (the parallel-axes lesson shows what that does).
    pub minimum_norm: bool,
    /// How the measurements are taken (simulated, and how a measurement file is read).
    pub setup: Setup,
    /// Pivot points, planes or spheres of a simulated setup.
    pub groups: usize,
    /// The distance setup's artefact length (mm).
    pub distance_mm: f64,
    /// The sphere setup's contact radius, sphere plus probe ball (mm).
    pub radius_mm: f64,
    /// The simulated real arm's joints bend under gravity (a compliance each, up to
    /// [`crate::calibration::SIMULATED_COMPLIANCE`]); needs the arm's masses.
    pub bend: bool,
    /// Estimate a compliance per joint with the geometry.
    pub with_compliance: bool,
    /// Seed of the simulation.
    pub seed: u64,
}

impl Default for LabSettings {
    fn default() -> Self {
        Self {
            poses: 50,
            tolerance_mm: 1.0,
            tolerance_deg: 0.5,
            noise_mm: 0.02,
            noise_mrad: 0.05,
            position_only: false,
            choice: PoseChoice::Random,
            hayati: true,
            minimum_norm: false,
            setup: Setup::Pose,
            groups: 3,
            distance_mm: 300.0,
            radius_mm: 25.0,
            bend: false,
            with_compliance: false,
            seed: 1,
        }
    }
}

/// What one run produced.
#[derive(Debug, Clone)]
pub struct LabResult {
    /// What was calibrated, in words ("simulated Puma 560, 50 random poses", a file name).
    pub title: String,
    /// The parameter model used (names, kinds, which rows use Hayati's beta).
    pub model: ParameterModel,
    /// The report.
    pub report: CalibrationReport,
    /// The true parameters, when simulated.
    pub truth: Option<Vec<f64>>,
    /// Errors on held-out poses before and after, when there are any.
    pub validation: Option<(Fit, Fit)>,
    /// The joint vectors of the measured poses (drawn as ghosts).
    pub poses: Vec<Vec<f64>>,
    /// The setup of the measurements.
    pub setup: Setup,
    /// Quirks of the measurement file accepted with a warning.
    pub warnings: Vec<String>,
    /// The robot's own base when the model's base is a tracker's pose (the tracker setup): the
    /// calibrated robot gets it back.
    pub robot_base: Option<Pose>,
}

impl LabResult {
    /// The calibrated robot (its own base, not a tracker's).
    pub fn calibrated_robot(&self) -> Result<Robot, String> {
        let mut r = self
            .model
            .robot_with(&self.report.estimate)
            .map_err(|e| e.to_string())?;
        if let Some(b) = self.robot_base {
            r.base = b;
        }
        Ok(r)
    }
}

/// The Calibration tab.
#[derive(Debug, Clone, Default)]
pub struct CalibrationLab {
    /// Simulation settings.
    pub settings: LabSettings,
    /// The last successful run.
    pub result: Option<LabResult>,
    /// The last message (an error, or what was saved).
    pub message: Option<String>,
    /// Path typed for measurement files.
    pub measurements_path: String,
    /// Path typed for saving the calibrated model.
    pub save_path: String,
    /// Path typed for the measurement-file template.
    pub template_path: String,
    /// Path typed for the desired poses of the target correction.
    pub targets_path: String,
    /// The target correction of the last result, when computed.
    pub corrections: Option<Vec<TargetCorrection>>,
    /// The accuracy maps of the last result, when computed: (before, after) against the real
    /// arm when simulated; (none, correction) for measured data.
    pub maps: Option<(Option<AccuracyMap>, AccuracyMap)>,
    /// Counts the maps computed (the panel re-uploads its textures when it changes).
    pub maps_generation: u64,
    /// Draw the measured poses of the last run in the 3D view (tool points, some as ghosts).
    pub show_poses: bool,
    /// What the lesson just run asks the class to look at (one sentence), until another run.
    pub lesson: Option<&'static str>,
}

fn options(s: &LabSettings) -> CalibrationOptions {
    CalibrationOptions {
        position_sigma: (s.noise_mm * 1e-3).max(1e-9),
        orientation_sigma: (s.noise_mrad * 1e-3).max(1e-9),
        unidentifiable: if s.minimum_norm {
            Unidentifiable::MinimumNorm
        } else {
            Unidentifiable::Nominal
        },
        ..CalibrationOptions::default()
    }
}

fn model_of(robot: &Robot, hayati: bool) -> Result<ParameterModel, String> {
    let m = ParameterModel::new(robot).map_err(|e| e.to_string())?;
    if hayati {
        m.with_hayati().map_err(|e| e.to_string())
    } else {
        Ok(m)
    }
}

/// Poses within 0.02 rad (or m) of `q0`, measured on the true parameters with the stated noise
/// (deterministic).
fn alike(
    model: &ParameterModel,
    truth: &[f64],
    q0: &[f64],
    s: &LabSettings,
) -> Result<Vec<Measurement>, String> {
    (0..s.poses)
        .map(|k| {
            let n = |i: usize| ((k * 13 + i * 5) % 17) as f64 / 8.0 - 1.0;
            let q: Vec<f64> = q0
                .iter()
                .enumerate()
                .map(|(j, v)| v + 0.01 * n(j + 6))
                .collect();
            let (_, t) = model.frames(truth, &q).map_err(|e| e.to_string())?;
            let p = t.translation.vector + Vector3::new(n(0), n(1), n(2)) * 1.7 * s.noise_mm * 1e-3;
            Ok(if s.position_only {
                Measurement::Position { q, p }
            } else {
                let r = Rotation3::new(Vector3::new(n(3), n(4), n(5)) * 1.7 * s.noise_mrad * 1e-3);
                Measurement::Pose {
                    q,
                    world_from_tool: Pose::from_parts(Translation3::from(p), r * t.rotation),
                }
            })
        })
        .collect()
}

impl CalibrationLab {
    /// Simulates a "real" `robot` with the settings, measures it, calibrates; `q_now` is the
    /// arm's configuration (the centre of the "alike" poses).
    pub fn run_simulated(&mut self, robot: &Robot, q_now: &[f64]) {
        match self.simulated(robot, q_now) {
            Ok(r) => {
                self.result = Some(r);
                self.maps = None;
                self.message = None;
                self.lesson = None;
                self.corrections = None;
            }
            Err(e) => self.message = Some(e),
        }
    }

    /// The accuracy maps of the last result (`cells` per side, `samples` joint vectors): the
    /// nominal and the calibrated model against the real arm when simulated, the correction
    /// (calibrated against nominal) for measured data.
    pub fn compute_maps(&mut self, cells: usize, samples: usize) {
        let Some(r) = &self.result else {
            self.message = Some("run a calibration first".into());
            return;
        };
        let nominal = r.model.nominal();
        let map = |a: &[f64], b: &[f64]| {
            accuracy_map(&r.model, a, b, [cells, cells], samples, 7).map_err(|e| e.to_string())
        };
        let maps = match &r.truth {
            Some(t) => {
                map(&nominal, t).and_then(|before| Ok((Some(before), map(&r.report.estimate, t)?)))
            }
            None => map(&r.report.estimate, &nominal).map(|after| (None, after)),
        };
        match maps {
            Ok(m) => {
                self.maps = Some(m);
                self.maps_generation += 1;
            }
            Err(e) => self.message = Some(e),
        }
    }

    fn simulated(&self, robot: &Robot, q_now: &[f64]) -> Result<LabResult, String> {
        let s = self.settings;
        if !matches!(s.setup, Setup::Pose | Setup::Position) {
            return self.simulated_setup(robot);
        }
        // The real arm (bending under gravity or not) and the model calibrated (with compliance
        // or not); compliances come last in zeta, so the geometric truth is a prefix.
        let geometric = model_of(robot, s.hayati)?;
        let bending = |m: ParameterModel| m.with_compliance().map_err(|e| e.to_string());
        let real = if s.bend {
            bending(geometric.clone())?
        } else {
            geometric.clone()
        };
        let model = if s.with_compliance {
            bending(geometric)?
        } else {
            geometric
        };
        let opts = options(&s);
        let candidates = match s.choice {
            PoseChoice::O1 | PoseChoice::O4 => 10 * s.poses,
            _ => s.poses,
        };
        let sim = simulate(
            &real,
            &SimulationOptions {
                poses: candidates,
                validation_poses: s.poses.max(10),
                tolerance_mm: s.tolerance_mm,
                tolerance_deg: s.tolerance_deg,
                noise_mm: s.noise_mm,
                noise_mrad: s.noise_mrad,
                position_only: s.position_only || s.setup == Setup::Position,
                seed: s.seed,
            },
        )
        .map_err(|e| e.to_string())?;
        let ms = match s.choice {
            PoseChoice::Random => sim.measurements,
            PoseChoice::Alike => alike(&model, &sim.truth, q_now, &s)?,
            PoseChoice::O1 | PoseChoice::O4 => {
                let c = if s.choice == PoseChoice::O1 {
                    Criterion::O1
                } else {
                    Criterion::O4
                };
                let chosen = select_poses(&model, &sim.measurements, s.poses, c, &opts)
                    .map_err(|e| e.to_string())?;
                chosen
                    .into_iter()
                    .map(|i| sim.measurements[i].clone())
                    .collect()
            }
        };
        let title = format!(
            "simulated {}, {} {:?} poses",
            robot.name,
            ms.len(),
            s.choice
        )
        .to_lowercase();
        let setup = if s.position_only {
            Setup::Position
        } else {
            s.setup
        };
        let mut truth = sim.truth;
        truth.resize(model.parameters().len(), 0.0);
        let data = RunData {
            ms: &ms,
            validation: Some(&sim.validation),
            truth: Some(truth),
            title,
            setup,
            warnings: Vec::new(),
            robot_base: None,
        };
        finish(model, data, &opts)
    }

    /// A simulated setup without a tracker (or a tracker of unknown pose): random joint vectors
    /// placed where the setup needs the tool.
    fn simulated_setup(&self, robot: &Robot) -> Result<LabResult, String> {
        let s = self.settings;
        let model = model_of(robot, s.hayati)?;
        let scene = SetupScene {
            setup: s.setup,
            groups: s.groups.max(1),
            distance: s.distance_mm * 1e-3,
            radius: s.radius_mm * 1e-3,
            ..SetupScene::default()
        };
        let sim = simulate_setup(
            &model,
            &scene,
            &SimulationOptions {
                poses: s.poses,
                validation_poses: s.poses.max(10),
                tolerance_mm: s.tolerance_mm,
                tolerance_deg: s.tolerance_deg,
                noise_mm: s.noise_mm,
                noise_mrad: s.noise_mrad,
                position_only: false,
                seed: s.seed,
            },
        )
        .map_err(|e| e.to_string())?;
        let (model, robot_base, mut truth) = if s.setup == Setup::Tracker {
            let (m, base) = tracker_model(robot, s.hayati, &sim.measurements)?;
            // The true base correction against the registered pose: not part of the arm's truth.
            let mut t = sim.truth.clone();
            t.resize(m.parameters().len(), f64::NAN);
            (m, Some(base), t)
        } else {
            (model, None, sim.truth.clone())
        };
        truth.truncate(model.parameters().len());
        let title = format!(
            "simulated {}, {} {} measurements",
            robot.name,
            sim.measurements.len(),
            s.setup.name()
        );
        let data = RunData {
            ms: &sim.measurements,
            validation: Some(&sim.validation),
            truth: Some(truth),
            title,
            setup: s.setup,
            warnings: Vec::new(),
            robot_base,
        };
        finish(model, data, &options(&s))
    }

    /// Calibrates `robot` from the measurement file typed in `measurements_path`.
    pub fn run_file(&mut self, robot: &Robot) {
        let path = self.measurements_path.trim().to_string();
        if path.is_empty() {
            self.message = Some("type the path of a measurement file (or Browse...)".into());
            return;
        }
        match crate::input::read_data_text(std::path::Path::new(&path)) {
            Ok(text) => self.run_text(robot, &path, &text),
            Err(e) => self.message = Some(e.to_string()),
        }
    }

    /// Calibrates `robot` from a measurement file handed over as bytes (a browser's file
    /// picker), or says that it is no text.
    pub fn run_bytes(&mut self, robot: &Robot, name: &str, bytes: &[u8]) {
        match std::str::from_utf8(bytes) {
            Ok(text) => {
                self.measurements_path = name.to_string();
                self.run_text(robot, name, text);
            }
            Err(_) => self.message = Some(format!("{name}: not a text file")),
        }
    }

    /// Calibrates `robot` from the text of a measurement file named `name` (errors name it),
    /// read as the setup of the settings says (plain or headered CSV).
    pub fn run_text(&mut self, robot: &Robot, name: &str, text: &str) {
        let s = self.settings;
        let radius = Some(s.radius_mm * 1e-3);
        let result = parse_setup(text, name, &JointColumns::of(robot), s.setup, radius)
            .map_err(|e| e.to_string())
            .and_then(|file| {
                let ms = &file.measurements;
                let (model, robot_base) = if s.setup == Setup::Tracker {
                    let (m, b) = tracker_model(robot, s.hayati, ms)?;
                    (m, Some(b))
                } else {
                    (model_of(robot, s.hayati)?, None)
                };
                let kind = ms.first().map_or("pose", Measurement::kind);
                let data = RunData {
                    ms,
                    validation: None,
                    truth: None,
                    title: name.to_string(),
                    setup: if s.setup == Setup::Pose && kind == "position" {
                        Setup::Position
                    } else {
                        s.setup
                    },
                    warnings: file.warnings.clone(),
                    robot_base,
                };
                finish(model, data, &options(&s))
            });
        match result {
            Ok(r) => {
                self.result = Some(r);
                self.maps = None;
                self.message = None;
                self.corrections = None;
            }
            Err(e) => self.message = Some(e),
        }
    }

    /// The calibrated robot as the text of a TOML model file.
    pub fn calibrated_text(&self) -> Result<String, String> {
        let Some(r) = &self.result else {
            return Err("run a calibration first".into());
        };
        r.calibrated_robot().and_then(|robot| {
            crate::model_file::to_toml(&robot)
                .ok_or_else(|| "the calibrated robot is not a DH model file".to_string())
        })
    }

    /// Writes the calibrated robot to `save_path` as a model file.
    pub fn save_model(&mut self) {
        let path = self.save_path.trim().to_string();
        if path.is_empty() {
            self.message =
                Some("type a file name for the calibrated model (e.g. calibrated.toml)".into());
            return;
        }
        // The full path, so the message says where the file went.
        let path = std::path::absolute(&path).map_or(path, |p| p.display().to_string());
        self.message = Some(
            match self.calibrated_text().and_then(|t| {
                std::fs::write(&path, t).map_err(|e| format!("cannot write {path}: {e}"))
            }) {
                Ok(()) => format!("saved the calibrated model to {path}"),
                Err(e) => e,
            },
        );
    }

    /// An annotated measurement-file template for the settings' setup and `robot` (headered CSV,
    /// degrees and millimetres, four example rows from the nominal model).
    pub fn template_text(&self, robot: &Robot) -> Result<String, String> {
        let s = self.settings;
        let model = model_of(robot, s.hayati)?;
        let scene = SetupScene {
            setup: s.setup,
            groups: 2,
            distance: s.distance_mm * 1e-3,
            radius: s.radius_mm * 1e-3,
            world_from_tracker: Pose::identity(),
        };
        let examples = nominal_examples(&model, &scene, 4, s.seed).map_err(|e| e.to_string())?;
        Ok(template(&JointColumns::of(robot), s.setup, &examples))
    }

    /// Writes the template to `template_path`.
    pub fn save_template(&mut self, robot: &Robot) {
        let path = self.template_path.trim().to_string();
        if path.is_empty() {
            self.message = Some("type a file name for the template (e.g. measurements.csv)".into());
            return;
        }
        self.message = Some(
            match self.template_text(robot).and_then(|t| {
                std::fs::write(&path, t).map_err(|e| format!("cannot write {path}: {e}"))
            }) {
                Ok(()) => format!(
                    "saved the {} template to {path}",
                    self.settings.setup.name()
                ),
                Err(e) => e,
            },
        );
    }

    /// The target correction of the poses in the file typed in `targets_path` on the last
    /// result's calibrated arm, through `robot`'s (the nominal model's) closed form.
    pub fn correct(&mut self, robot: &Robot) {
        let path = self.targets_path.trim().to_string();
        if path.is_empty() {
            self.message = Some("type the path of a file of desired tool poses".into());
            return;
        }
        let text = match crate::input::read_data_text(std::path::Path::new(&path)) {
            Ok(t) => t,
            Err(e) => {
                self.message = Some(e.to_string());
                return;
            }
        };
        self.correct_text(robot, &path, &text);
    }

    /// The target correction of the desired poses in `text` (named `name` in errors).
    pub fn correct_text(&mut self, robot: &Robot, name: &str, text: &str) {
        let Some(r) = &self.result else {
            self.message = Some("run a calibration first".into());
            return;
        };
        let rows = parse_targets(text, name)
            .map_err(|e| e.to_string())
            .and_then(|targets| {
                let calibrated = r.calibrated_robot()?;
                correct_targets(robot, &calibrated, &targets).map_err(|e| e.to_string())
            });
        match rows {
            Ok(rows) => {
                self.corrections = Some(rows);
                self.message = None;
            }
            Err(e) => self.message = Some(e),
        }
    }

    /// The target correction as CSV (what `armlab calibrate --correct-targets --out` writes).
    pub fn corrections_text(&self, robot: &Robot) -> Option<String> {
        self.corrections
            .as_ref()
            .map(|rows| write_corrections(rows, &JointColumns::of(robot)))
    }

    /// The lesson "converged is not accurate": poses all alike around the current configuration.
    pub fn lesson_alike(&mut self, robot: &Robot, q_now: &[f64]) {
        self.settings = LabSettings {
            choice: PoseChoice::Alike,
            poses: 40,
            ..LabSettings::default()
        };
        self.run_simulated(robot, q_now);
        self.lesson = Some(
            "Look at the validation line against the fit line: 40 poses all alike fit with a small \
             residual, yet the arm is no more accurate over the workspace, and O1 (the smallest \
             singular value) is near zero.",
        );
    }

    /// The lesson "joint compliance": a real arm whose joints bend under gravity, measured with
    /// a precise tracker (2 um), calibrated with the geometry alone (`estimate` false: the
    /// held-out error stays above the noise, what no DH parameter can absorb), then with a
    /// compliance per joint.
    pub fn lesson_compliance(&mut self, robot: &Robot, q_now: &[f64], estimate: bool) {
        self.settings = LabSettings {
            poses: 120,
            noise_mm: 0.002,
            noise_mrad: 0.005,
            bend: true,
            with_compliance: estimate,
            ..LabSettings::default()
        };
        self.run_simulated(robot, q_now);
        if self.result.is_some() {
            self.lesson = Some(if estimate {
                "Look at the held-out line: with a compliance per joint it falls to the noise, \
                 and the table gives each joint's compliance (c1 of a vertical axis feels no \
                 gravity and is kept nominal)."
            } else {
                "Look at the held-out line against the fit line: the joints bend under gravity, \
                 and no DH parameter absorbs all of it; the error stays above the tracker's 2 um. \
                 Now run it with compliance."
            });
        }
    }

    /// The lesson "parallel axes": plain DH on an arm with parallel axes (the Puma's 2 and 3);
    /// switch `hayati` on to see what beta does.
    pub fn lesson_parallel(&mut self, robot: &Robot, q_now: &[f64], hayati: bool) {
        self.settings = LabSettings {
            poses: 60,
            hayati,
            // Plain DH with every parameter estimated: what the default protects against.
            minimum_norm: !hayati,
            ..LabSettings::default()
        };
        self.run_simulated(robot, q_now);
        self.lesson = Some(if hayati {
            "Look at the parameter table: with Hayati's beta on the parallel pair every \
             parameter is marked identifiable and lands near its true value."
        } else {
            "Look at the parameter table: with plain DH on parallel axes, d2 and d3 are marked \
             not identifiable and run far from their true values, though the fit is good."
        });
    }
}

/// What a run calibrates, besides the model: where the data came from.
struct RunData<'a> {
    ms: &'a [Measurement],
    validation: Option<&'a [Measurement]>,
    truth: Option<Vec<f64>>,
    title: String,
    setup: Setup,
    warnings: Vec<String>,
    robot_base: Option<Pose>,
}

fn finish(
    model: ParameterModel,
    d: RunData<'_>,
    opts: &CalibrationOptions,
) -> Result<LabResult, String> {
    let report = calibrate(&model, d.ms, opts).map_err(|e| e.to_string())?;
    let validation = match d.validation {
        Some(v) => Some((
            fit(&model, &model.nominal(), v).map_err(|e| e.to_string())?,
            fit(&model, &report.estimate, v).map_err(|e| e.to_string())?,
        )),
        None => None,
    };
    Ok(LabResult {
        title: d.title,
        poses: d
            .ms
            .iter()
            .flat_map(|m| m.joint_vectors())
            .map(<[f64]>::to_vec)
            .collect(),
        model,
        report,
        truth: d.truth,
        validation,
        setup: d.setup,
        warnings: d.warnings,
        robot_base: d.robot_base,
    })
}

/// The tracker setup's model: the base started at the tracker pose registered from the
/// measurements, its six parameters estimated; with the robot's own base.
fn tracker_model(
    robot: &Robot,
    hayati: bool,
    ms: &[Measurement],
) -> Result<(ParameterModel, Pose), String> {
    let plain = model_of(robot, hayati)?;
    let reg = register_tracker(&plain, &plain.nominal(), ms).map_err(|e| e.to_string())?;
    let mut moved = robot.clone();
    moved.base = reg * robot.base;
    Ok((model_of(&moved, hayati)?.with_base(), robot.base))
}
