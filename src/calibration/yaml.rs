//! robot_cal_tools' kinematic measurement files (YAML): a map from an observation's key (often a
//! timestamp) to `target_joints` (the arm's joint values, rad), `camera_joints` (a camera's own
//! chain; armlab needs it empty or absent: the camera is fixed) and `pose` (`x y z qw qx qy qz`:
//! the target as the camera sees it, m). Each observation is a full pose of the tool in the
//! camera's frame: calibrate it with `--setup tracker` (the camera's pose estimated) or as
//! `pose` when the camera frame is the robot's world frame.

use super::file::{MeasurementFileError, ParsedFile};
use super::model::Measurement;
use crate::kinematics::pose::Pose;
use nalgebra::{Quaternion, Translation3, UnitQuaternion};
use yaml_rust2::{Yaml, YamlLoader};

/// Whether a text looks like YAML of this kind: its first line that is not blank or a comment
/// is a map key alone (`'1593701755':`, `obs_1:`).
pub(super) fn looks_like_yaml(text: &str) -> bool {
    text.lines()
        .map(str::trim_end)
        .find(|l| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
        .is_some_and(|l| !l.starts_with(' ') && l.ends_with(':') && !l.contains(','))
}

/// Parses a robot_cal_tools measurement file for an arm of `dof` joints. Errors name the
/// observation and its line.
pub(super) fn parse_rct_yaml(
    text: &str,
    source_name: &str,
    dof: usize,
) -> Result<ParsedFile, MeasurementFileError> {
    let err = |line: usize, problem: String| MeasurementFileError {
        source_name: source_name.into(),
        line,
        problem,
    };
    let docs = YamlLoader::load_from_str(text).map_err(|e| {
        let problem = format!("not YAML: {} (column {})", e.info(), e.marker().col() + 1);
        err(text_line(text, e.marker().line()), problem)
    })?;
    let Some(Yaml::Hash(map)) = docs.first() else {
        return Err(err(
            0,
            "expected a map of observations (key: {target_joints, pose})".into(),
        ));
    };
    let mut out = ParsedFile {
        measurements: Vec::with_capacity(map.len()),
        warnings: Vec::new(),
        headered: false,
    };
    for (key, obs) in map {
        let name = match key {
            Yaml::String(s) => s.clone(),
            Yaml::Integer(i) => i.to_string(),
            other => format!("{other:?}"),
        };
        let line = line_of(text, &name);
        let bad = |problem: String| err(line, format!("observation {name:?}: {problem}"));
        let q = numbers(&obs["target_joints"])
            .ok_or_else(|| bad("`target_joints` is not a list of numbers".into()))?;
        if q.len() != dof {
            return Err(bad(format!("{} target_joints, the arm has {dof}", q.len())));
        }
        match numbers(&obs["camera_joints"]) {
            Some(c) if !c.is_empty() => {
                return Err(bad(
                    "`camera_joints` is not empty: a camera on a moving chain is not supported \
                     (armlab calibrates one arm against a fixed camera or tracker)"
                        .into(),
                ));
            }
            _ => {}
        }
        let pose = &obs["pose"];
        let mut v = [0.0; 7];
        for (slot, k) in v.iter_mut().zip(["x", "y", "z", "qw", "qx", "qy", "qz"]) {
            *slot = number(&pose[k])
                .ok_or_else(|| bad(format!("`pose.{k}` is missing or not a finite number")))?;
        }
        let quat = Quaternion::new(v[3], v[4], v[5], v[6]);
        let norm = quat.norm();
        if !(norm > 0.5 && norm < 2.0) {
            return Err(bad(format!(
                "the pose's quaternion has norm {norm}: not a rotation"
            )));
        }
        let r = UnitQuaternion::from_quaternion(quat).to_rotation_matrix();
        out.measurements.push(Measurement::Pose {
            q,
            world_from_tool: Pose::from_parts(Translation3::new(v[0], v[1], v[2]), r),
        });
    }
    if out.measurements.is_empty() {
        return Err(err(0, "no observations".into()));
    }
    Ok(out)
}

/// A finite number (YAML reals and integers).
fn number(y: &Yaml) -> Option<f64> {
    match y {
        Yaml::Real(s) => s.parse::<f64>().ok(),
        Yaml::Integer(i) => Some(*i as f64),
        _ => None,
    }
    .filter(|v| v.is_finite())
}

/// A list of finite numbers (None if it is not one; an absent key is an empty list).
fn numbers(y: &Yaml) -> Option<Vec<f64>> {
    match y {
        Yaml::Array(a) => a.iter().map(number).collect(),
        Yaml::BadValue | Yaml::Null => Some(Vec::new()),
        _ => None,
    }
}

/// The line of `text`, as `str::lines` counts them (the line numbers of every other error),
/// where YAML's line `yaml_line` starts (1-based; YAML also breaks lines at a lone `\r`).
fn text_line(text: &str, yaml_line: usize) -> usize {
    let (mut yaml, mut line) = (1, 1);
    let bytes = text.as_bytes();
    for (i, &c) in bytes.iter().enumerate() {
        if yaml >= yaml_line {
            break;
        }
        match c {
            b'\n' => {
                yaml += 1;
                line += 1;
            }
            b'\r' if bytes.get(i + 1) != Some(&b'\n') => yaml += 1,
            _ => {}
        }
    }
    line
}

/// The 1-based line where an observation's key starts (0 when not found).
fn line_of(text: &str, key: &str) -> usize {
    text.lines()
        .position(|l| {
            let t = l.trim_start_matches(['\'', '"']);
            !l.starts_with(' ') && t.starts_with(key) && l.trim_end().ends_with(':')
        })
        .map_or(0, |i| i + 1)
}
