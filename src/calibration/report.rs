//! The report of an [`super::Experiment`]: what [`super::run`] found, printed as text
//! (`Display`, what `armlab calibrate` prints) and serialised (serde) with the keys of
//! `armlab calibrate --format json`. Lengths in m and angles in rad in the data; the text
//! prints mm, mrad and degrees as it says.

use super::experiment::Corrections;
use super::{
    CalibrationReport, Fit, Identifiability, Measurement, ParameterModel, Setup, TargetCorrection,
};
use crate::kinematics::Robot;
use crate::kinematics::pose::Pose;
use serde::Serialize;
use std::fmt;

/// What one calibration experiment found.
#[derive(Debug, Clone)]
#[must_use]
pub struct Report {
    /// The setup as reported: `pose` read from a file of positions is `position`.
    pub setup: Setup,
    /// Quirks of the measurement files accepted, each prefixed with its file's name; and the
    /// note that a chain that is not a DH table was calibrated through its derived one.
    pub warnings: Vec<String>,
    /// The measurements fitted.
    pub measurements: Vec<Measurement>,
    /// The parameter model calibrated (names, kinds, Hayati's rows; a tracker's base).
    pub model: ParameterModel,
    /// The calibration: estimate, identifiability at the nominal point and at the estimate,
    /// iterations, uncertainty, fit before and after.
    pub calibration: CalibrationReport,
    /// Errors on the held-out measurements, (nominal, calibrated), when there are any.
    pub validation: Option<(Fit, Fit)>,
    /// The real arm's zeta when simulated (a tracker's six base parameters: the true
    /// correction of the registered pose).
    pub truth: Option<Vec<f64>>,
    /// The nominal robot calibrated: the experiment's, or its derived DH table.
    pub nominal_robot: Robot,
    /// The experiment's robot when it is not a DH table (its joint origins carry the result).
    pub chain: Option<Robot>,
    /// The calibrated robot, with its own base (not a tracker's).
    pub calibrated: Robot,
    /// The tracker setup's estimated `tracker_from_base`.
    pub tracker_from_base: Option<Pose>,
    /// The target correction, when desired poses were given.
    pub corrections: Option<Corrections>,
}

/// `{"position_rms": .., "position_max": .., "orientation_rms": .., "orientation_max": ..}`.
#[derive(Serialize)]
struct FitJson {
    position_rms: f64,
    position_max: f64,
    orientation_rms: Option<f64>,
    orientation_max: Option<f64>,
}

impl From<&Fit> for FitJson {
    fn from(f: &Fit) -> Self {
        Self {
            position_rms: f.position_rms,
            position_max: f.position_max,
            orientation_rms: f.orientation_rms,
            orientation_max: f.orientation_max,
        }
    }
}

#[derive(Serialize)]
struct BeforeAfter {
    before: FitJson,
    after: FitJson,
}

impl BeforeAfter {
    fn of(before: &Fit, after: &Fit) -> Self {
        Self {
            before: before.into(),
            after: after.into(),
        }
    }
}

#[derive(Serialize)]
#[allow(non_snake_case)]
struct ObservabilityJson {
    O1: f64,
    O2: f64,
    O3: f64,
    O4: f64,
}

impl From<&Identifiability> for ObservabilityJson {
    fn from(n: &Identifiability) -> Self {
        let o = &n.observability;
        Self {
            O1: o.o1,
            O2: o.o2,
            O3: o.o3,
            O4: o.o4,
        }
    }
}

#[derive(Serialize)]
struct ParameterJson<'a> {
    name: &'a str,
    joint: usize,
    kind: &'static str,
    nominal: f64,
    estimate: f64,
    std: Option<f64>,
    identifiable: bool,
    fixed: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    fixed_because: Option<&'a str>,
    #[serde(rename = "true", skip_serializing_if = "Option::is_none")]
    truth: Option<f64>,
}

#[derive(Serialize)]
struct UnknownJson {
    name: String,
    estimate: f64,
    std: Option<f64>,
}

#[derive(Serialize)]
struct IdentifiabilityJson<'a> {
    parameter_count: usize,
    rank: usize,
    rank_threshold: f64,
    unidentifiable: &'a [String],
    combinations: &'a [String],
    observability: ObservabilityJson,
}

#[derive(Serialize)]
struct FixedJson<'a> {
    name: &'a str,
    because: &'a str,
}

#[derive(Serialize)]
struct TrackerJson {
    translation: [f64; 3],
    rotation_vector: [f64; 3],
}

#[derive(Serialize)]
struct CorrelationJson<'a> {
    parameters: [&'a str; 2],
    correlation: f64,
}

#[derive(Serialize)]
struct IterationJson {
    position_rms: f64,
    orientation_rms: f64,
    step_norm: f64,
    condition: f64,
    rank: usize,
}

#[derive(Serialize)]
struct SendJson {
    translation: [f64; 3],
    quaternion_wxyz: [f64; 4],
}

#[derive(Serialize)]
struct CorrectionRowJson<'a> {
    pose: usize,
    posture: String,
    posture_parts: crate::kinematics::ik::SolutionPosture,
    q: &'a [f64],
    within_limits: bool,
    send: SendJson,
    position_error: f64,
    orientation_error: f64,
    uncorrected_error: f64,
}

#[derive(Serialize)]
struct CorrectionsJson<'a> {
    file: &'a str,
    poses: usize,
    worst_error: f64,
    rows: Vec<CorrectionRowJson<'a>>,
}

/// The report's JSON, key for key as `armlab calibrate --format json` has printed it.
#[derive(Serialize)]
struct ReportJson<'a> {
    setup: &'static str,
    setup_cannot_see: &'static str,
    warnings: &'a [String],
    hayati_rows: Vec<usize>,
    parameters: Vec<ParameterJson<'a>>,
    unknowns: Vec<UnknownJson>,
    identifiability_at: &'static str,
    parameter_count: usize,
    rank: usize,
    rank_threshold: f64,
    unidentifiable: &'a [String],
    combinations: &'a [String],
    fixed_unidentifiable: Vec<FixedJson<'a>>,
    nominal_identifiability: IdentifiabilityJson<'a>,
    tracker_from_base: Option<TrackerJson>,
    correlations: Vec<CorrelationJson<'a>>,
    iterations: Vec<IterationJson>,
    converged: bool,
    reason: Option<&'a str>,
    sigma2: f64,
    observability: ObservabilityJson,
    fit: BeforeAfter,
    validation: Option<BeforeAfter>,
    target_correction: Option<CorrectionsJson<'a>>,
}

fn identifiability_json(n: &Identifiability) -> IdentifiabilityJson<'_> {
    IdentifiabilityJson {
        parameter_count: n.parameter_count,
        rank: n.rank,
        rank_threshold: n.rank_threshold,
        unidentifiable: &n.unidentifiable,
        combinations: &n.combinations,
        observability: n.into(),
    }
}

fn vec3(v: &nalgebra::Vector3<f64>) -> [f64; 3] {
    [v[0], v[1], v[2]]
}

/// The largest FK error of the corrected rows (m or rad).
fn worst_error(rows: &[TargetCorrection]) -> f64 {
    rows.iter()
        .map(|r| r.position_error.max(r.orientation_error))
        .fold(0.0, f64::max)
}

fn corrections_json(c: &Corrections) -> CorrectionsJson<'_> {
    CorrectionsJson {
        file: &c.name,
        poses: c.poses,
        worst_error: worst_error(&c.rows),
        rows: c
            .rows
            .iter()
            .map(|r| {
                let u = nalgebra::UnitQuaternion::from_rotation_matrix(&r.send.rotation);
                CorrectionRowJson {
                    pose: r.pose + 1,
                    posture: r.posture.to_string(),
                    posture_parts: r.posture,
                    q: &r.q,
                    within_limits: r.within_limits,
                    send: SendJson {
                        translation: vec3(&r.send.translation.vector),
                        quaternion_wxyz: [u.w, u.i, u.j, u.k],
                    },
                    position_error: r.position_error,
                    orientation_error: r.orientation_error,
                    uncorrected_error: r.uncorrected_error,
                }
            })
            .collect(),
    }
}

impl Report {
    /// The JSON view of the report (borrowed). Over 80 lines: one struct literal with a field
    /// per key of the JSON, in its order; splitting it would only scatter the keys.
    fn json(&self) -> ReportJson<'_> {
        let r = &self.calibration;
        let parameters = r
            .parameters
            .iter()
            .enumerate()
            .map(|(k, p)| ParameterJson {
                name: &p.name,
                joint: p.joint,
                kind: p.kind.as_str(),
                nominal: p.nominal,
                estimate: r.estimate[k],
                std: r.std[k],
                identifiable: r.at_estimate.identifiable[k],
                fixed: p.fixed,
                fixed_because: r
                    .auto_fixed
                    .iter()
                    .find(|(n, _)| *n == p.name)
                    .map(|(_, why)| why.as_str()),
                truth: self.truth.as_ref().map(|t| t[k]),
            })
            .collect();
        let unknowns = r
            .unknowns
            .values()
            .iter()
            .zip(r.unknowns.names())
            .zip(&r.unknown_std)
            .map(|((&estimate, name), &std)| UnknownJson {
                name,
                estimate,
                std,
            })
            .collect();
        let e = &r.at_estimate;
        ReportJson {
            setup: self.setup.name(),
            setup_cannot_see: self.setup.blind_spots(),
            warnings: &self.warnings,
            hayati_rows: self.model.hayati_rows(),
            parameters,
            unknowns,
            identifiability_at: "estimate",
            parameter_count: e.parameter_count,
            rank: e.rank,
            rank_threshold: e.rank_threshold,
            unidentifiable: &e.unidentifiable,
            combinations: &e.combinations,
            fixed_unidentifiable: r
                .auto_fixed
                .iter()
                .map(|(name, because)| FixedJson { name, because })
                .collect(),
            nominal_identifiability: identifiability_json(&r.nominal),
            tracker_from_base: self.tracker_from_base.map(|p| TrackerJson {
                translation: vec3(&p.translation.vector),
                rotation_vector: vec3(&p.rotation.scaled_axis()),
            }),
            correlations: r
                .correlations
                .iter()
                .map(|(a, b, c)| CorrelationJson {
                    parameters: [a.as_str(), b.as_str()],
                    correlation: *c,
                })
                .collect(),
            iterations: r
                .iterations
                .iter()
                .map(|i| IterationJson {
                    position_rms: i.position_rms,
                    orientation_rms: i.orientation_rms,
                    step_norm: i.step_norm,
                    condition: i.condition,
                    rank: i.rank,
                })
                .collect(),
            converged: r.converged,
            reason: r.reason.as_deref(),
            sigma2: r.sigma2,
            observability: e.into(),
            fit: BeforeAfter::of(&r.before, &r.after),
            validation: self.validation.as_ref().map(|(b, a)| BeforeAfter::of(b, a)),
            target_correction: self.corrections.as_ref().map(corrections_json),
        }
    }
}

impl Serialize for Report {
    /// The keys of `armlab calibrate --format json`: the setup, the warnings, the parameter
    /// table (nominal, estimate, std, identifiable, fixed, `true` when simulated), the
    /// identifiability at the estimate and at the nominal point, the iterations, the fits.
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.json().serialize(s)
    }
}

impl fmt::Display for Report {
    /// The report as `armlab calibrate` prints it: the setup and what it cannot see, the
    /// identifiability at the nominal point, the iterations, the identifiability at the
    /// estimate, the parameter table, the setup's unknowns, the correlations, the fits before
    /// and after, the target correction.
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        let r = &self.calibration;
        self.preamble(out)?;
        writeln!(
            out,
            "iteration  position rms [mm]  orientation rms [mrad]  step      condition  rank"
        )?;
        for (i, it) in r.iterations.iter().enumerate() {
            writeln!(
                out,
                "{i:>9}  {:>17.5}  {:>22.5}  {:<8.1e}  {:>9.3e}  {:>4}",
                it.position_rms * 1e3,
                it.orientation_rms * 1e3,
                it.step_norm,
                it.condition,
                it.rank
            )?;
        }
        match &r.reason {
            None => writeln!(out, "converged")?,
            Some(why) => writeln!(out, "not converged: {why}")?,
        }
        write_identifiability(
            out,
            &r.at_estimate,
            "the estimate (the table's flags, standard deviations and correlations)",
        )?;
        self.table(out)?;
        write_unknowns(out, r)?;
        if let Some(p) = self.tracker_from_base {
            let t = p.translation.vector * 1e3;
            let a = p.rotation.scaled_axis();
            writeln!(
                out,
                "tracker_from_base: translation ({:.4}, {:.4}, {:.4}) mm, rotation vector \
                 ({:.5}, {:.5}, {:.5}) deg",
                t[0],
                t[1],
                t[2],
                a[0].to_degrees(),
                a[1].to_degrees(),
                a[2].to_degrees()
            )?;
        }
        for (a, b, c) in &r.correlations {
            writeln!(out, "correlated: {a} and {b} ({c:+.4})")?;
        }
        writeln!(out, "fit: before {}", FitText(&r.before))?;
        writeln!(out, "fit: after  {}", FitText(&r.after))?;
        if let Some((b, a)) = &self.validation {
            writeln!(out, "validation: before {}", FitText(b))?;
            writeln!(out, "validation: after  {}", FitText(a))?;
        }
        if let Some(c) = &self.corrections {
            write_corrections(out, c)?;
        }
        Ok(())
    }
}

impl Report {
    /// The warnings, the setup, the Hayati rows, the identifiability at the nominal point and
    /// what was kept at its nominal value and why.
    fn preamble(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        for w in &self.warnings {
            writeln!(out, "warning: {w}")?;
        }
        writeln!(
            out,
            "setup: {} ({} measurements); what it cannot see: {}",
            self.setup.name(),
            self.measurements.len(),
            self.setup.blind_spots()
        )?;
        let hayati = self.model.hayati_rows();
        if !hayati.is_empty() {
            let list: Vec<String> = hayati
                .iter()
                .map(|r| format!("beta{r} instead of d{r}"))
                .collect();
            writeln!(
                out,
                "Hayati's parameter (parallel axes): {} (d kept at its nominal value: along \
                 parallel axes plain DH cannot place the common normal)",
                list.join(", ")
            )?;
        }
        write_identifiability(
            out,
            &self.calibration.nominal,
            "the nominal parameters (before the iterations)",
        )?;
        for (name, why) in &self.calibration.auto_fixed {
            writeln!(
                out,
                "kept at its nominal value: {name}, because {why} (--unidentifiable \
                 minimum-norm estimates it anyway)"
            )?;
        }
        Ok(())
    }

    /// The parameter table: nominal, true (simulated), estimate, standard deviation, flag.
    fn table(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        let r = &self.calibration;
        let truth = self.truth.as_deref();
        writeln!(
            out,
            "{:<9} {:>12} {:>12} {:>12} {:>10}  unit     identifiable",
            "parameter",
            "nominal",
            if truth.is_some() { "true" } else { "" },
            "estimate",
            "std"
        )?;
        for (k, p) in r.parameters.iter().enumerate() {
            let (scale, unit) = p.kind.display();
            let t = truth.map_or(String::new(), |t| format!("{:.5}", t[k] * scale));
            let std = r.std[k].map_or("-".into(), |s| format!("{:.2e}", s * scale));
            let flag = if r.auto_fixed.iter().any(|(n, _)| *n == p.name) {
                "NO (kept nominal)"
            } else if p.fixed {
                "fixed"
            } else if r.at_estimate.identifiable[k] {
                "yes"
            } else {
                "NO"
            };
            writeln!(
                out,
                "{:<9} {:>12.5} {:>12} {:>12.5} {:>10}  {unit:<7}  {flag}",
                p.name,
                p.nominal * scale,
                t,
                r.estimate[k] * scale,
                std
            )?;
        }
        Ok(())
    }
}

/// A fit in words: "position rms .. mm, max .. mm[, orientation rms .. mrad, max .. mrad]".
struct FitText<'a>(&'a Fit);

impl fmt::Display for FitText<'_> {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        let f = self.0;
        write!(
            out,
            "position rms {:.4} mm, max {:.4} mm",
            f.position_rms * 1e3,
            f.position_max * 1e3
        )?;
        if let (Some(r), Some(m)) = (f.orientation_rms, f.orientation_max) {
            write!(
                out,
                ", orientation rms {:.4} mrad, max {:.4} mrad",
                r * 1e3,
                m * 1e3
            )?;
        }
        Ok(())
    }
}

fn write_identifiability(
    out: &mut fmt::Formatter<'_>,
    n: &Identifiability,
    at: &str,
) -> fmt::Result {
    writeln!(
        out,
        "identifiability at {at}: rank {} of {} (singular values below {:e} of the largest count \
         as zero)",
        n.rank, n.parameter_count, n.rank_threshold
    )?;
    for c in &n.combinations {
        writeln!(out, "  {c}")?;
    }
    let o = n.observability;
    writeln!(
        out,
        "  observability: O1 {:.3e}, O2 {:.3e}, O3 {:.3e}, O4 {:.3e}",
        o.o1, o.o2, o.o3, o.o4
    )
}

/// The setup's unknowns (pivot points, planes, sphere centres) in mm (a plane's normal without
/// unit).
fn write_unknowns(out: &mut fmt::Formatter<'_>, r: &CalibrationReport) -> fmt::Result {
    let u = &r.unknowns;
    for (k, c) in u.points.iter().enumerate() {
        writeln!(
            out,
            "point {}: ({:.4}, {:.4}, {:.4}) mm",
            k + 1,
            c[0] * 1e3,
            c[1] * 1e3,
            c[2] * 1e3
        )?;
    }
    for (k, pl) in u.planes.iter().enumerate() {
        let n = pl.normal();
        writeln!(
            out,
            "plane {}: normal ({:.6}, {:.6}, {:.6}), offset {:.4} mm",
            k + 1,
            n[0],
            n[1],
            n[2],
            pl.h * 1e3
        )?;
    }
    for (k, c) in u.spheres.iter().enumerate() {
        writeln!(
            out,
            "sphere {}: centre ({:.4}, {:.4}, {:.4}) mm",
            k + 1,
            c[0] * 1e3,
            c[1] * 1e3,
            c[2] * 1e3
        )?;
    }
    Ok(())
}

/// The target correction's summary and its first 20 rows.
fn write_corrections(out: &mut fmt::Formatter<'_>, c: &Corrections) -> fmt::Result {
    let rows = &c.rows;
    let off: Vec<f64> = rows
        .iter()
        .map(|r| r.uncorrected_error)
        .filter(|v| v.is_finite())
        .collect();
    let rms = (off.iter().map(|v| v * v).sum::<f64>() / off.len().max(1) as f64).sqrt();
    writeln!(
        out,
        "target correction ({}): {} poses, {} pose-posture rows; calibrated FK error at the \
         corrected q at most {:.1e} (m, rad); uncorrected, the real tool would be off by {:.4} \
         mm rms",
        c.name,
        c.poses,
        rows.len(),
        worst_error(rows),
        rms * 1e3
    )?;
    writeln!(
        out,
        "{:>5}  {:<42} {:>10}  send x, y, z [mm]",
        "pose", "posture", "off [mm]"
    )?;
    for r in rows.iter().take(20) {
        let t = r.send.translation.vector * 1e3;
        writeln!(
            out,
            "{:>5}  {:<42} {:>10.4}  {:.4}, {:.4}, {:.4}",
            r.pose + 1,
            r.posture,
            r.uncorrected_error * 1e3,
            t[0],
            t[1],
            t[2]
        )?;
    }
    if rows.len() > 20 {
        writeln!(
            out,
            "  ... {} rows in all (--out FILE writes them)",
            rows.len()
        )?;
    }
    Ok(())
}
