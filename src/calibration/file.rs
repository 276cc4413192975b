//! Measurement files: one pose per line, comma-separated, `#` comments and blank lines ignored;
//! the n joint values (rad, m), then 3 numbers (measured tool point x, y, z in m) or 16 (the
//! measured `world_from_tool`, row-major 4x4). Every line of a file has the same kind.

use super::model::Measurement;
use crate::kinematics::pose::pose_from_matrix;
use nalgebra::{Matrix4, Vector3};
use std::fmt::Write as _;
use thiserror::Error;

/// A bad measurement file, located at `source:line`.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{source_name}:{line}: {problem}")]
pub struct MeasurementFileError {
    /// The file (or `-`).
    pub source_name: String,
    /// 1-based line (0 for the file as a whole).
    pub line: usize,
    /// What is wrong.
    pub problem: String,
}

/// Parses a measurement file's text for a robot with `dof` joints.
pub fn parse_measurements(
    text: &str,
    source_name: &str,
    dof: usize,
) -> Result<Vec<Measurement>, MeasurementFileError> {
    let err = |line: usize, problem: String| MeasurementFileError {
        source_name: source_name.into(),
        line,
        problem,
    };
    let mut out = Vec::new();
    let mut kind: Option<(usize, usize)> = None;
    for (n, raw) in text.lines().enumerate() {
        let line = n + 1;
        let data = raw.split('#').next().unwrap_or("").trim();
        if data.is_empty() {
            continue;
        }
        let values = numbers(data).map_err(|p| err(line, p))?;
        let extra = values
            .len()
            .checked_sub(dof)
            .filter(|e| *e == 3 || *e == 16);
        let Some(extra) = extra else {
            return Err(err(
                line,
                format!(
                    "{} values: expected {dof} joint values then 3 (a measured position) or 16 (a \
                     measured 4x4 pose), i.e. {} or {}",
                    values.len(),
                    dof + 3,
                    dof + 16
                ),
            ));
        };
        match kind {
            None => kind = Some((extra, line)),
            Some((k, first)) if k != extra => {
                let name = |e: usize| if e == 3 { "position" } else { "pose" };
                return Err(err(
                    line,
                    format!(
                        "a {} measurement, but line {first} is a {}: all lines of a file must be \
                         of one kind",
                        name(extra),
                        name(k)
                    ),
                ));
            }
            _ => {}
        }
        let q = values[..dof].to_vec();
        let rest = &values[dof..];
        out.push(if extra == 3 {
            Measurement::Position {
                q,
                p: Vector3::new(rest[0], rest[1], rest[2]),
            }
        } else {
            let m = Matrix4::from_row_slice(rest);
            let pose = pose_from_matrix(&m)
                .map_err(|e| err(line, format!("the measured pose is not rigid: {e}")))?;
            Measurement::Pose {
                q,
                world_from_tool: pose,
            }
        });
    }
    if out.is_empty() {
        return Err(err(
            0,
            "no measurements (blank lines and # comments only)".into(),
        ));
    }
    Ok(out)
}

/// The comma-separated finite numbers of one line, or what is wrong.
fn numbers(data: &str) -> Result<Vec<f64>, String> {
    data.split(',')
        .map(str::trim)
        .enumerate()
        .map(|(i, f)| match f.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(format!("value {} ({f:?}) is not a finite number", i + 1)),
        })
        .collect()
}

/// Writes measurements in the file format above (shortest round-trip numbers).
pub fn write_measurements(ms: &[Measurement]) -> String {
    let mut s = String::from(
        "# armlab measurements: joint values (rad, m), then the measured position (m) or the \
         4x4 world_from_tool, row-major\n",
    );
    for m in ms {
        let mut fields: Vec<f64> = m.q().to_vec();
        match m {
            Measurement::Position { p, .. } => fields.extend(p.iter()),
            Measurement::Pose {
                world_from_tool, ..
            } => {
                let h = world_from_tool.to_homogeneous();
                for r in 0..4 {
                    for c in 0..4 {
                        fields.push(h[(r, c)]);
                    }
                }
            }
        }
        let row: Vec<String> = fields.iter().map(|v| format!("{v:?}")).collect();
        let _ = writeln!(s, "{}", row.join(", "));
    }
    s
}
