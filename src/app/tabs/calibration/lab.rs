//! The Calibration tab's state (no GUI types): simulation settings, the last run's report, the
//! two built-in lessons, measurement files and saving the calibrated model. Every failure is a
//! message; the previous result stays.

use crate::calibration::{
    AccuracyMap, CalibrationOptions, CalibrationReport, Criterion, Experiment, Fit, JointColumns,
    ModelOptions, NamedText, ParameterModel, Report, Selection, Setup, Simulation, Source,
    TargetCorrection, Unidentifiable, accuracy_map, correct_targets, measurement_template,
    parse_targets, write_corrections,
};
use crate::kinematics::Robot;
use crate::kinematics::pose::Pose;

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
    /// The arm calibrated when it is not a DH table (a URDF arm, calibrated through its
    /// derived table): a URDF is written back as this chain with its joint origins updated.
    pub chain: Option<Robot>,
    /// The nominal DH robot calibrated, with its own base (the chain's DH form for a URDF arm).
    pub nominal_robot: Robot,
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

/// The tab's last message, with its tone.
#[derive(Debug, Clone, PartialEq)]
pub enum Said {
    /// Something was written or is being downloaded.
    Done(String),
    /// Done, with a warning (a model saved with doubtful estimates), or not done on purpose.
    Warned(String),
    /// Why it could not be done.
    Failed(String),
}

impl Said {
    /// The words.
    pub fn text(&self) -> &str {
        match self {
            Said::Done(t) | Said::Warned(t) | Said::Failed(t) => t,
        }
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
    pub said: Option<Said>,
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
    /// What the lesson just run asks the class to look at (one sentence), until it ends.
    pub lesson: Option<&'static str>,
    /// The user's own settings while a lesson runs with its own: they come back when the
    /// lesson ends (a lesson is a sandbox).
    pub before_lesson: Option<LabSettings>,
    /// "Save calibrated model" was pressed on a model with doubtful estimates: the panel asks
    /// before writing it.
    pub confirm_save: bool,
}

fn options(s: &LabSettings) -> CalibrationOptions {
    CalibrationOptions {
        unidentifiable: if s.minimum_norm {
            Unidentifiable::MinimumNorm
        } else {
            Unidentifiable::Nominal
        },
        ..CalibrationOptions::default().with_noise(s.noise_mm, s.noise_mrad)
    }
}

/// The experiment of the settings on `robot` with the data of `source` (the library's
/// workflow, the one `armlab calibrate` runs).
fn experiment(s: &LabSettings, robot: &Robot, source: Source) -> Experiment {
    Experiment {
        robot: robot.clone(),
        setup: s.setup,
        model: ModelOptions {
            hayati: s.hayati,
            with_compliance: s.with_compliance,
            ..ModelOptions::default()
        },
        source,
        options: options(s),
        targets: None,
    }
}

/// The tab's result of a library report.
fn lab_result(title: String, r: Report) -> LabResult {
    LabResult {
        title,
        poses: r
            .measurements
            .iter()
            .flat_map(|m| m.joint_vectors())
            .map(<[f64]>::to_vec)
            .collect(),
        robot_base: r.tracker_from_base.map(|_| r.nominal_robot.base),
        chain: r.chain,
        nominal_robot: r.nominal_robot,
        model: r.model,
        report: r.calibration,
        truth: r.truth,
        validation: r.validation,
        setup: r.setup,
        warnings: r.warnings,
    }
}

impl CalibrationLab {
    /// Simulates a "real" `robot` with the settings, measures it, calibrates; `q_now` is the
    /// arm's configuration (the centre of the "alike" poses). Within a lesson, with the
    /// lesson's settings as changed since: the lesson goes on.
    pub fn run_simulated(&mut self, robot: &Robot, q_now: &[f64]) {
        match self.simulated(robot, q_now) {
            Ok(r) => self.install(r),
            Err(e) => self.fail(e),
        }
    }

    /// Says why something could not be done.
    pub fn fail(&mut self, why: String) {
        self.said = Some(Said::Failed(why));
    }

    /// Says what saving the calibrated model did: written (with a warning when it carries
    /// doubtful estimates), or why not.
    pub fn saved(&mut self, written: Result<String, String>) {
        let doubts = self.doubts();
        self.said = Some(match written {
            Ok(m) if doubts.is_empty() => Said::Done(m),
            Ok(m) => {
                let names: Vec<&str> = doubts.iter().map(|d| d.name.as_str()).collect();
                Said::Warned(format!(
                    "{m}, with a warning in its header: {} not to be trusted",
                    names.join(", ")
                ))
            }
            Err(e) => Said::Failed(e),
        });
    }

    /// The last message's words, if any.
    pub fn message(&self) -> Option<&str> {
        self.said.as_ref().map(Said::text)
    }

    /// A new result: what belonged to the old one goes.
    fn install(&mut self, r: LabResult) {
        self.result = Some(r);
        self.maps = None;
        self.said = None;
        self.corrections = None;
        self.confirm_save = false;
    }

    /// Starts a lesson with `settings`: the user's own are kept until it ends.
    fn start_lesson(&mut self, settings: LabSettings) {
        self.before_lesson.get_or_insert(self.settings);
        self.settings = settings;
    }

    /// Ends the lesson, if one runs: the user's settings come back and the lesson's result
    /// goes (nothing of it can be saved or corrected by mistake afterwards).
    pub fn end_lesson(&mut self) {
        if let Some(s) = self.before_lesson.take() {
            self.settings = s;
            self.result = None;
            self.maps = None;
            self.corrections = None;
            self.confirm_save = false;
        }
        self.lesson = None;
    }

    /// The estimates of the last result not to be trusted (see
    /// [`crate::calibration::doubtful_parameters`]).
    pub fn doubts(&self) -> Vec<crate::calibration::DoubtfulParameter> {
        self.result.as_ref().map_or_else(Vec::new, |r| {
            crate::calibration::doubtful_parameters(&r.report)
        })
    }

    /// The accuracy maps of the last result (`cells` per side, `samples` joint vectors): the
    /// nominal and the calibrated model against the real arm when simulated, the correction
    /// (calibrated against nominal) for measured data.
    pub fn compute_maps(&mut self, cells: usize, samples: usize) {
        let Some(r) = &self.result else {
            self.fail("run a calibration first".into());
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
            Err(e) => self.fail(e),
        }
    }

    fn simulated(&self, robot: &Robot, q_now: &[f64]) -> Result<LabResult, String> {
        let s = self.settings;
        let sim = Simulation {
            poses: s.poses,
            validation_poses: s.poses.max(10),
            selection: match s.choice {
                PoseChoice::Random => Selection::Random,
                PoseChoice::O1 => Selection::Best(Criterion::O1),
                PoseChoice::O4 => Selection::Best(Criterion::O4),
                PoseChoice::Alike => Selection::Alike(q_now.to_vec()),
            },
            tolerance_mm: s.tolerance_mm,
            tolerance_deg: s.tolerance_deg,
            noise_mm: s.noise_mm,
            noise_mrad: s.noise_mrad,
            position_only: s.position_only,
            seed: s.seed,
            groups: s.groups.max(1),
            distance: s.distance_mm * 1e-3,
            radius: s.radius_mm * 1e-3,
            bend: s.bend,
        };
        let e = experiment(&s, robot, Source::Simulated(sim));
        let r = crate::calibration::run(&e).map_err(|e| e.to_string())?;
        let title = if matches!(s.setup, Setup::Pose | Setup::Position) {
            format!(
                "simulated {}, {} {:?} poses",
                robot.name,
                r.measurements.len(),
                s.choice
            )
            .to_lowercase()
        } else {
            format!(
                "simulated {}, {} {} measurements",
                robot.name,
                r.measurements.len(),
                s.setup.name()
            )
        };
        Ok(lab_result(title, r))
    }

    /// Calibrates `robot` from the measurement file typed in `measurements_path` (a lesson
    /// running ends first: real data are read with the user's own settings).
    pub fn run_file(&mut self, robot: &Robot) {
        self.end_lesson();
        let path = self.measurements_path.trim().to_string();
        if path.is_empty() {
            self.fail("type the path of a measurement file (or Browse...)".into());
            return;
        }
        match crate::input::read_data_text(std::path::Path::new(&path)) {
            Ok(text) => self.run_text(robot, &path, &text),
            Err(e) => self.fail(e.to_string()),
        }
    }

    /// Calibrates `robot` from a measurement file handed over as bytes (a browser's file
    /// picker), or says that it is no text.
    pub fn run_bytes(&mut self, robot: &Robot, name: &str, bytes: &[u8]) {
        self.end_lesson();
        match std::str::from_utf8(bytes) {
            Ok(text) => {
                self.measurements_path = name.to_string();
                self.run_text(robot, name, text);
            }
            Err(_) => self.fail(format!("{name}: not a text file")),
        }
    }

    /// Calibrates `robot` from the text of a measurement file named `name` (errors name it),
    /// read as the setup of the settings says (plain or headered CSV).
    pub fn run_text(&mut self, robot: &Robot, name: &str, text: &str) {
        let s = self.settings;
        let source = Source::Measured {
            fit: NamedText {
                name: name.to_string(),
                text: text.to_string(),
            },
            validation: None,
            radius: Some(s.radius_mm * 1e-3),
        };
        let result = crate::calibration::run(&experiment(&s, robot, source))
            .map(|r| lab_result(name.to_string(), r))
            .map_err(|e| e.to_string());
        match result {
            Ok(r) => self.install(r),
            Err(e) => self.fail(e),
        }
    }

    /// The calibrated robot as the text of a model file, its doubtful estimates (if any) named
    /// in a header: a URDF for a name ending in `.urdf` (a URDF arm is written back as its own
    /// chain with the calibrated joint origins, as `armlab calibrate --write-urdf` does), else
    /// TOML.
    pub fn calibrated_text(&self) -> Result<String, String> {
        let Some(r) = &self.result else {
            return Err("run a calibration first".into());
        };
        let robot = r.calibrated_robot()?;
        let urdf = std::path::Path::new(self.save_path.trim())
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("urdf"));
        let header = crate::calibration::doubt_header(&self.doubts(), urdf);
        if !urdf {
            return crate::model_file::to_toml(&robot)
                .map(|t| header + &t)
                .ok_or_else(|| "the calibrated robot is not a DH model file".to_string());
        }
        let carried = match &r.chain {
            Some(chain) => {
                let nominal = &r.nominal_robot;
                let c = crate::calibration::with_calibrated_origins(chain, nominal, &robot);
                Some(c.map_err(|e| e.to_string())?)
            }
            None => None,
        };
        let text =
            crate::urdf::to_urdf(carried.as_ref().unwrap_or(&robot)).map_err(|e| e.to_string())?;
        // the warning goes after the XML declaration, which must come first
        Ok(match text.split_once('\n') {
            Some((decl, rest)) if decl.starts_with("<?xml") => format!("{decl}\n{header}{rest}"),
            _ => header + &text,
        })
    }

    /// "Save calibrated model": writes at once when every estimate is to be trusted; else asks
    /// first (`confirm_save`, answered by [`Self::save_model`] or [`Self::cancel_save`]).
    pub fn request_save(&mut self) -> bool {
        if self.result.is_some() && !self.doubts().is_empty() && !self.confirm_save {
            self.confirm_save = true;
            return false;
        }
        self.confirm_save = false;
        true
    }

    /// The question about doubtful estimates is answered no.
    pub fn cancel_save(&mut self) {
        self.confirm_save = false;
        self.said = Some(Said::Warned("not saved".into()));
    }

    /// Writes the calibrated robot to `save_path` as a model file (with the doubts' header).
    pub fn save_model(&mut self) {
        self.confirm_save = false;
        let path = self.save_path.trim().to_string();
        if path.is_empty() {
            self.fail("type a file name for the calibrated model (e.g. calibrated.toml)".into());
            return;
        }
        // The full path, so the message says where the file went.
        let path = std::path::absolute(&path).map_or(path, |p| p.display().to_string());
        let written = self.calibrated_text().and_then(|t| {
            std::fs::write(&path, t).map_err(|e| format!("cannot write {path}: {e}"))
        });
        self.saved(written.map(|()| format!("saved the calibrated model to {path}")));
    }

    /// An annotated measurement-file template for the settings' setup and `robot` (headered CSV,
    /// degrees and millimetres, four example rows from the nominal model).
    pub fn template_text(&self, robot: &Robot) -> Result<String, String> {
        let s = self.settings;
        let model = ModelOptions {
            hayati: s.hayati,
            ..ModelOptions::default()
        };
        let (text, _) = measurement_template(
            robot,
            &model,
            s.setup,
            s.distance_mm * 1e-3,
            s.radius_mm * 1e-3,
            s.seed,
        )
        .map_err(|e| e.to_string())?;
        Ok(text)
    }

    /// Writes the template to `template_path`.
    pub fn save_template(&mut self, robot: &Robot) {
        let path = self.template_path.trim().to_string();
        if path.is_empty() {
            self.fail("type a file name for the template (e.g. measurements.csv)".into());
            return;
        }
        let written = self.template_text(robot).and_then(|t| {
            std::fs::write(&path, t).map_err(|e| format!("cannot write {path}: {e}"))
        });
        let setup = self.settings.setup.name();
        self.said = Some(match written {
            Ok(()) => Said::Done(format!("saved the {setup} template to {path}")),
            Err(e) => Said::Failed(e),
        });
    }

    /// The target correction of the poses in the file typed in `targets_path` on the last
    /// result's calibrated arm, through `robot`'s (the nominal model's) closed form.
    pub fn correct(&mut self, robot: &Robot) {
        let path = self.targets_path.trim().to_string();
        if path.is_empty() {
            self.fail("type the path of a file of desired tool poses".into());
            return;
        }
        let text = match crate::input::read_data_text(std::path::Path::new(&path)) {
            Ok(t) => t,
            Err(e) => {
                self.fail(e.to_string());
                return;
            }
        };
        self.correct_text(robot, &path, &text);
    }

    /// The target correction of the desired poses in `text` (named `name` in errors).
    pub fn correct_text(&mut self, robot: &Robot, name: &str, text: &str) {
        let Some(r) = &self.result else {
            self.fail("run a calibration first".into());
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
                self.said = None;
            }
            Err(e) => self.fail(e),
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
        self.start_lesson(LabSettings {
            choice: PoseChoice::Alike,
            poses: 40,
            ..LabSettings::default()
        });
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
        self.start_lesson(LabSettings {
            poses: 120,
            noise_mm: 0.002,
            noise_mrad: 0.005,
            bend: true,
            with_compliance: estimate,
            ..LabSettings::default()
        });
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
        self.start_lesson(LabSettings {
            poses: 60,
            hayati,
            // Plain DH with every parameter estimated: what the default protects against.
            minimum_norm: !hayati,
            ..LabSettings::default()
        });
        self.run_simulated(robot, q_now);
        self.lesson = Some(if hayati {
            "Look at the parameter table: with Hayati's beta on the parallel pair every \
             parameter is marked identifiable and lands near its true value."
        } else {
            "Look at the parameter table: with plain DH on parallel axes, d2 and d3 are marked \
             red, not identifiable, and run far from their true values, though the fit is good."
        });
    }
}
