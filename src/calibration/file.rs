//! Measurement files, in two forms.
//!
//! **Plain** (what `--write-measurements` writes): comma-separated numbers per line, `#`
//! comments and blank lines ignored, SI units (rad, m). Per setup:
//! - pose, position, tracker: the n joint values, then 3 numbers (the measured tool point x, y,
//!   z) or 16 (the measured `world_from_tool`, row-major 4x4);
//! - distance: `qa1..qan, qb1..qbn, distance_m`;
//! - pivot, plane, sphere: `q1..qn`, in groups that a comment line `# point K`, `# plane K` or
//!   `# sphere K` starts (one group when there is none); `# radius_m R` sets the sphere's
//!   contact radius (sphere plus probe ball, m) for the lines after it.
//!
//! **Headered CSV** (what a cell's logger writes): the first line that is not all numbers names
//! the columns, each with an optional unit as `name [unit]`, `name (unit)` or `name_unit`
//! (`rad`, `deg`, `m`, `mm`):
//! - joints by the robot's joint names, or numbered `q1`, `j1`, `joint1`, `joint_1`, `axis1`,
//!   `a1` (`_a` / `_b` after the name for the two joint vectors of a distance);
//! - the tool point `x, y, z`;
//! - an orientation as a quaternion `qw, qx, qy, qz`, as roll-pitch-yaw `roll, pitch, yaw`
//!   (`Rz(yaw) Ry(pitch) Rx(roll)`, (2.21)), as a rotation vector `rx, ry, rz`, or the 16
//!   numbers `t11..t44` of the 4x4 matrix;
//! - `distance`; a group column `point`, `plane` or `sphere`; `radius`.
//!
//! Other columns are ignored with a warning that names them; a column without a unit is read
//! in SI units with a warning.

use super::model::Measurement;
use super::setup::Setup;
use crate::kinematics::orientation::rotation_from_rpy;
use crate::kinematics::pose::{Pose, pose_from_matrix};
use crate::kinematics::robot::{Drive, JointKind, Robot};
use nalgebra::{Matrix4, Rotation3, Translation3, UnitQuaternion, Vector3};
use std::collections::HashMap;
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

/// The robot's joint variables as files name them: per q index, the joint's name and whether
/// it is an angle (revolute) or a length (prismatic).
#[derive(Debug, Clone, PartialEq)]
pub struct JointColumns {
    /// Joint names, in the order of q.
    pub names: Vec<String>,
    /// Whether each variable is an angle.
    pub angular: Vec<bool>,
}

impl JointColumns {
    /// The actuated joints of `robot`, in the order of q.
    pub fn of(robot: &Robot) -> Self {
        let mut names = vec![String::new(); robot.dof()];
        let mut angular = vec![true; robot.dof()];
        for j in robot.joints() {
            if let Drive::Actuated(k) = j.drive {
                names[k] = j.name.clone();
                angular[k] = j.kind != JointKind::Prismatic;
            }
        }
        Self { names, angular }
    }

    /// `q1..qn`, all angles.
    pub fn numbered(dof: usize) -> Self {
        Self {
            names: (1..=dof).map(|k| format!("q{k}")).collect(),
            angular: vec![true; dof],
        }
    }

    pub(super) fn dof(&self) -> usize {
        self.names.len()
    }
}

/// A parsed file: its measurements and what was accepted with a warning.
#[derive(Debug, Clone, PartialEq)]
pub struct ParsedFile {
    /// The measurements, in file order.
    pub measurements: Vec<Measurement>,
    /// Quirks accepted (ignored columns, columns without units, ...), each naming the column.
    pub warnings: Vec<String>,
    /// Whether the file had a header line.
    pub headered: bool,
}

/// Parses a plain pose or position file for a robot with `dof` joints.
pub fn parse_measurements(
    text: &str,
    source_name: &str,
    dof: usize,
) -> Result<Vec<Measurement>, MeasurementFileError> {
    parse_setup(
        text,
        source_name,
        &JointColumns::numbered(dof),
        Setup::Pose,
        None,
    )
    .map(|f| f.measurements)
}

/// Parses a measurement file (plain or headered) of `setup` for the joints `joints`;
/// `radius` is the sphere setup's contact radius (m) unless the file gives it.
pub fn parse_setup(
    text: &str,
    source_name: &str,
    joints: &JointColumns,
    setup: Setup,
    radius: Option<f64>,
) -> Result<ParsedFile, MeasurementFileError> {
    if super::yaml::looks_like_yaml(text) {
        if !matches!(setup, Setup::Pose | Setup::Tracker) {
            return Err(MeasurementFileError {
                source_name: source_name.into(),
                line: 0,
                problem: format!(
                    "a robot_cal_tools YAML file holds full poses: read it with the pose or tracker setup, not {}",
                    setup.name()
                ),
            });
        }
        return super::yaml::parse_rct_yaml(text, source_name, joints.dof());
    }
    let mut p = Parser {
        source_name,
        joints,
        setup,
        radius,
        group: None,
        groups: HashMap::new(),
        header: None,
        first_line: None,
        out: ParsedFile {
            measurements: Vec::new(),
            warnings: Vec::new(),
            headered: false,
        },
    };
    for (n, raw) in text.lines().enumerate() {
        p.line(n + 1, raw)?;
    }
    if p.out.measurements.is_empty() {
        return Err(p.err(
            0,
            "no measurements (blank lines and # comments only)".into(),
        ));
    }
    Ok(p.out)
}

/// One column of a headered file.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Col {
    /// Joint variable: q index, which joint vector (0, or 1 for a distance's second), scale.
    Joint(usize, usize, f64),
    /// Tool point coordinate 0..2, scale to m.
    Point(usize, f64),
    /// Quaternion component: 0 = w, 1..3 = x, y, z.
    Quat(usize),
    /// Roll, pitch, yaw (0, 1, 2), scale to rad.
    Rpy(usize, f64),
    /// Rotation vector component, scale to rad.
    RotVec(usize, f64),
    /// Matrix element (row, column), 0-based; translations scaled to m.
    Matrix(usize, usize, f64),
    /// The known distance, scale to m.
    Distance(f64),
    /// The contact radius, scale to m.
    Radius(f64),
    /// The group label.
    Group,
    /// Ignored.
    Ignored,
}

struct Parser<'a> {
    source_name: &'a str,
    joints: &'a JointColumns,
    setup: Setup,
    radius: Option<f64>,
    /// The current group (from a `# point K` line).
    group: Option<usize>,
    /// Group labels seen, to their indices.
    groups: HashMap<String, usize>,
    header: Option<Vec<Col>>,
    /// The line of the first measurement.
    first_line: Option<usize>,
    out: ParsedFile,
}

impl Parser<'_> {
    fn err(&self, line: usize, problem: String) -> MeasurementFileError {
        MeasurementFileError {
            source_name: self.source_name.into(),
            line,
            problem,
        }
    }

    fn group_index(&mut self, label: &str) -> usize {
        let next = self.groups.len();
        *self.groups.entry(label.trim().to_string()).or_insert(next)
    }

    fn line(&mut self, line: usize, raw: &str) -> Result<(), MeasurementFileError> {
        let (data, comment) = match raw.split_once('#') {
            Some((d, c)) => (d.trim(), Some(c.trim())),
            None => (raw.trim(), None),
        };
        if let Some(c) = comment.filter(|_| data.is_empty()) {
            return self.directive(line, c);
        }
        if data.is_empty() {
            return Ok(());
        }
        let fields: Vec<&str> = data.split([',', ';', '\t']).map(str::trim).collect();
        // A header: before any data, a field that is not a number at all ("nan" is a number,
        // rejected below as not finite).
        let text = |f: &&str| f.trim().trim_matches('"').parse::<f64>().is_err();
        if self.header.is_none() && self.out.measurements.is_empty() && fields.iter().any(text) {
            let cols = self.header(line, &fields)?;
            self.header = Some(cols);
            self.out.headered = true;
            return Ok(());
        }
        let m = match self.header.clone() {
            Some(cols) => self.headered_row(line, &cols, &fields)?,
            None => self.plain_row(line, &fields)?,
        };
        match (self.out.measurements.first(), self.first_line) {
            (Some(first), Some(at)) if first.kind() != m.kind() => {
                return Err(self.err(
                    line,
                    format!(
                        "a {} measurement, but line {at} is a {}: all lines of a file must be of \
                         one kind",
                        m.kind(),
                        first.kind()
                    ),
                ));
            }
            (None, _) => self.first_line = Some(line),
            _ => {}
        }
        self.out.measurements.push(m);
        Ok(())
    }

    /// `# point K`, `# plane K`, `# sphere K`, `# radius_m R`; other comments are ignored.
    fn directive(&mut self, line: usize, c: &str) -> Result<(), MeasurementFileError> {
        let mut words = c.split_whitespace();
        let (Some(key), rest) = (words.next(), words.collect::<Vec<_>>().join(" ")) else {
            return Ok(());
        };
        let key = key.trim_end_matches(':').to_ascii_lowercase();
        if key == "radius_m" || key == "radius" {
            let v = number(rest.trim()).filter(|v| *v > 0.0).ok_or_else(|| {
                self.err(line, format!("radius {rest:?} is not a positive number"))
            })?;
            self.radius = Some(v);
        } else if Some(key.as_str()) == group_word(self.setup) {
            self.group = Some(self.group_index(&rest));
        }
        Ok(())
    }

    fn plain_row(
        &mut self,
        line: usize,
        fields: &[&str],
    ) -> Result<Measurement, MeasurementFileError> {
        let values: Vec<f64> = fields
            .iter()
            .enumerate()
            .map(|(i, f)| {
                number(f).ok_or_else(|| {
                    self.err(
                        line,
                        format!("value {} ({f:?}) is not a finite number", i + 1),
                    )
                })
            })
            .collect::<Result<_, _>>()?;
        let n = self.joints.dof();
        let expect =
            |what: String| self.err(line, format!("{} values: expected {what}", values.len()));
        match self.setup {
            Setup::Pose | Setup::Position | Setup::Tracker => {
                let extra = values.len().checked_sub(n).filter(|e| *e == 3 || *e == 16);
                let Some(extra) = extra else {
                    return Err(expect(format!(
                        "{n} joint values then 3 (a measured position) or 16 (a measured 4x4 \
                         pose), i.e. {} or {}",
                        n + 3,
                        n + 16
                    )));
                };
                let q = values[..n].to_vec();
                if extra == 3 {
                    let p = Vector3::new(values[n], values[n + 1], values[n + 2]);
                    return self.position(line, q, p, None);
                }
                let m = Matrix4::from_row_slice(&values[n..]);
                let pose = pose_from_matrix(&m)
                    .map_err(|e| self.err(line, format!("the measured pose is not rigid: {e}")))?;
                self.position(line, q, pose.translation.vector, Some(pose.rotation))
            }
            Setup::Distance => {
                if values.len() != 2 * n + 1 {
                    return Err(expect(format!(
                        "qa1..qa{n}, qb1..qb{n}, distance_m: {}",
                        2 * n + 1
                    )));
                }
                self.distance(
                    line,
                    values[..n].to_vec(),
                    values[n..2 * n].to_vec(),
                    values[2 * n],
                )
            }
            Setup::Pivot | Setup::Plane | Setup::Sphere => {
                if values.len() != n {
                    return Err(expect(format!("the {n} joint values")));
                }
                self.grouped(line, values, None)
            }
        }
    }

    fn position(
        &self,
        line: usize,
        q: Vec<f64>,
        p: Vector3<f64>,
        r: Option<Rotation3<f64>>,
    ) -> Result<Measurement, MeasurementFileError> {
        match (self.setup, r) {
            (Setup::Pose | Setup::Tracker, Some(r)) => Ok(Measurement::Pose {
                q,
                world_from_tool: Pose::from_parts(Translation3::from(p), r),
            }),
            (Setup::Pose | Setup::Position | Setup::Tracker, _) => {
                Ok(Measurement::Position { q, p })
            }
            _ => Err(self.err(line, "unreachable: not a pose setup".into())),
        }
    }

    fn distance(
        &self,
        line: usize,
        qa: Vec<f64>,
        qb: Vec<f64>,
        distance: f64,
    ) -> Result<Measurement, MeasurementFileError> {
        if distance <= 0.0 {
            return Err(self.err(line, format!("distance {distance} m: must be positive")));
        }
        Ok(Measurement::Distance { qa, qb, distance })
    }

    fn grouped(
        &mut self,
        line: usize,
        q: Vec<f64>,
        label: Option<&str>,
    ) -> Result<Measurement, MeasurementFileError> {
        let group = match label {
            Some(l) => self.group_index(l),
            None => match self.group {
                Some(g) => g,
                None => self.group_index(""),
            },
        };
        Ok(match self.setup {
            Setup::Pivot => Measurement::Pivot { q, point: group },
            Setup::Plane => Measurement::Plane { q, plane: group },
            _ => {
                let radius = self.radius.ok_or_else(|| {
                    self.err(
                        line,
                        "a sphere touch needs the contact radius (sphere plus probe ball): give \
                         --sphere-radius-mm, a `# radius_m R` line or a radius column"
                            .into(),
                    )
                })?;
                Measurement::Sphere {
                    q,
                    sphere: group,
                    radius,
                }
            }
        })
    }
}

/// The word that starts a group of a setup's lines: `# point K`, `# plane K`, `# sphere K`.
fn group_word(setup: Setup) -> Option<&'static str> {
    match setup {
        Setup::Pivot => Some("point"),
        Setup::Plane => Some("plane"),
        Setup::Sphere => Some("sphere"),
        _ => None,
    }
}

/// A finite number, or None.
fn number(f: &str) -> Option<f64> {
    f.trim().parse::<f64>().ok().filter(|v| v.is_finite())
}

/// Writes measurements in the plain format above (shortest round-trip numbers), with the group
/// and radius lines of the setups that need them.
pub fn write_measurements(ms: &[Measurement]) -> String {
    let mut s = String::from(
        "# armlab measurements (SI units: rad, m). Per line: joint values (rad, m), then the \
         measured position (m) or the 4x4 world_from_tool, row-major; or qa, qb and the distance \
         (m); or the joint values of a touch, in groups that `# point K`, `# plane K` or \
         `# sphere K` start\n",
    );
    let mut group = None;
    let mut radius = None;
    for m in ms {
        let mut fields: Vec<f64> = m.q().to_vec();
        let marker = match m {
            Measurement::Pivot { point, .. } => Some(("point", *point)),
            Measurement::Plane { plane, .. } => Some(("plane", *plane)),
            Measurement::Sphere { sphere, .. } => Some(("sphere", *sphere)),
            _ => None,
        };
        if let Measurement::Sphere { radius: r, .. } = m
            && radius != Some(*r)
        {
            radius = Some(*r);
            let _ = writeln!(s, "# radius_m {r:?}");
        }
        if marker.is_some() && marker != group {
            group = marker;
            let (name, k) = marker.unwrap_or(("point", 0));
            let _ = writeln!(s, "# {name} {}", k + 1);
        }
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
            Measurement::Distance { qb, distance, .. } => {
                fields.extend(qb.iter());
                fields.push(*distance);
            }
            Measurement::Pivot { .. } | Measurement::Plane { .. } | Measurement::Sphere { .. } => {}
        }
        let row: Vec<String> = fields.iter().map(|v| format!("{v:?}")).collect();
        let _ = writeln!(s, "{}", row.join(", "));
    }
    s
}

/// A unit's factor to SI and whether it is an angle unit.
fn unit(u: &str) -> Option<(f64, bool)> {
    match u.trim().to_ascii_lowercase().as_str() {
        "rad" | "radian" | "radians" => Some((1.0, true)),
        "deg" | "degree" | "degrees" | "°" => Some((std::f64::consts::PI / 180.0, true)),
        "m" | "metre" | "meter" | "metres" | "meters" => Some((1.0, false)),
        "mm" | "millimetre" | "millimeter" | "millimetres" | "millimeters" => Some((1e-3, false)),
        _ => None,
    }
}

/// A header field split into its name and unit: `x [mm]`, `x (mm)`, `x_mm`.
fn split_unit(field: &str) -> (String, Option<(f64, bool)>, bool) {
    let f = field.trim().trim_matches('"').trim();
    for (open, close) in [('[', ']'), ('(', ')')] {
        if let (Some(a), true) = (f.find(open), f.ends_with(close)) {
            let name = f[..a].trim().to_ascii_lowercase();
            let u = unit(&f[a + 1..f.len() - 1]);
            return (name, u, u.is_some());
        }
    }
    if let Some((name, u)) = f.rsplit_once('_')
        && let Some(u) = unit(u)
    {
        return (name.to_ascii_lowercase(), Some(u), true);
    }
    (f.to_ascii_lowercase(), None, false)
}

impl Parser<'_> {
    /// The columns of a header line.
    fn header(&mut self, line: usize, fields: &[&str]) -> Result<Vec<Col>, MeasurementFileError> {
        let mut cols = Vec::with_capacity(fields.len());
        for f in fields {
            let (name, u, has_unit) = split_unit(f);
            let col = self.column(&name, u);
            let angular = match col {
                Col::Joint(k, _, _) => Some(self.joints.angular[k]),
                Col::Rpy(..) | Col::RotVec(..) => Some(true),
                Col::Point(..) | Col::Distance(_) | Col::Radius(_) => Some(false),
                Col::Matrix(_, c, _) => (c == 3).then_some(false),
                _ => None,
            };
            if let (Some(want), Some((_, is_angle))) = (angular, u)
                && want != is_angle
            {
                return Err(self.err(
                    line,
                    format!(
                        "column {f:?}: a unit of {} for {}",
                        if is_angle { "angle" } else { "length" },
                        if want { "an angle" } else { "a length" }
                    ),
                ));
            }
            if col == Col::Ignored {
                self.out
                    .warnings
                    .push(format!("column {f:?} is not one armlab reads: ignored"));
            } else if angular.is_some() && !has_unit {
                let si = if angular == Some(true) { "rad" } else { "m" };
                self.out
                    .warnings
                    .push(format!("column {f:?} has no unit: read in {si}"));
            }
            cols.push(col);
        }
        self.check_columns(line, &cols)?;
        Ok(cols)
    }

    /// What a column name (lower case, unit removed) means.
    fn column(&self, name: &str, u: Option<(f64, bool)>) -> Col {
        let scale = u.map_or(1.0, |(s, _)| s);
        let (base, side) = match name
            .strip_suffix("_a")
            .or_else(|| name.strip_suffix(".a"))
            .map(|b| (b, 0))
            .or_else(|| {
                name.strip_suffix("_b")
                    .or_else(|| name.strip_suffix(".b"))
                    .map(|b| (b, 1))
            }) {
            Some((b, s)) if self.setup == Setup::Distance => (b, s),
            _ => (name, 0),
        };
        if let Some(k) = self.joint_index(base) {
            return Col::Joint(k, side, scale);
        }
        let xyz = |c: &str| ["x", "y", "z"].iter().position(|v| *v == c);
        // FIGAROH's marker columns: x1, y1, z1 and phix1, phiy1, phiz1 (roll-pitch-yaw, (2.21));
        // markers 2.. are not read.
        let name = match name {
            "x1" | "y1" | "z1" => &name[..1],
            "phix1" => "roll",
            "phiy1" => "pitch",
            "phiz1" => "yaw",
            _ => name,
        };
        match name {
            "x" | "y" | "z" => Col::Point(xyz(name).unwrap_or(0), scale),
            "qw" | "qx" | "qy" | "qz" => Col::Quat(
                ["qw", "qx", "qy", "qz"]
                    .iter()
                    .position(|v| *v == name)
                    .unwrap_or(0),
            ),
            "roll" | "pitch" | "yaw" => Col::Rpy(
                ["roll", "pitch", "yaw"]
                    .iter()
                    .position(|v| *v == name)
                    .unwrap_or(0),
                scale,
            ),
            "rx" | "ry" | "rz" => Col::RotVec(xyz(&name[1..]).unwrap_or(0), scale),
            "distance" => Col::Distance(scale),
            "radius" => Col::Radius(scale),
            "point" | "plane" | "sphere" | "group" => Col::Group,
            _ => matrix_element(name).map_or(Col::Ignored, |(r, c)| Col::Matrix(r, c, scale)),
        }
    }

    /// The q index of a joint column: the robot's joint name, or q1..qn.
    fn joint_index(&self, name: &str) -> Option<usize> {
        self.joints
            .names
            .iter()
            .position(|n| n.to_ascii_lowercase() == name)
            .or_else(|| {
                let digits = ["joint_", "joint", "axis_", "axis", "q", "j", "a"]
                    .iter()
                    .find_map(|p| name.strip_prefix(p))?;
                let k: usize = digits.parse().ok()?;
                (1..=self.joints.dof()).contains(&k).then(|| k - 1)
            })
    }

    /// Every joint present (twice for a distance), and what the setup needs.
    fn check_columns(&self, line: usize, cols: &[Col]) -> Result<(), MeasurementFileError> {
        let sides = if self.setup == Setup::Distance { 2 } else { 1 };
        for side in 0..sides {
            for k in 0..self.joints.dof() {
                if !cols
                    .iter()
                    .any(|c| matches!(c, Col::Joint(j, s, _) if *j == k && *s == side))
                {
                    let suffix = ["_a", "_b"][side];
                    return Err(self.err(
                        line,
                        format!(
                            "no column for joint {} ({}{}): the header names {:?}",
                            k + 1,
                            self.joints.names[k],
                            if sides == 2 { suffix } else { "" },
                            self.joints.names
                        ),
                    ));
                }
            }
        }
        let has = |f: &dyn Fn(&Col) -> bool| cols.iter().any(f);
        let point = has(&|c| matches!(c, Col::Point(..))) || has(&|c| matches!(c, Col::Matrix(..)));
        let need = match self.setup {
            Setup::Pose | Setup::Position | Setup::Tracker if !point => {
                Some("the measured tool point: columns x, y, z (or t11..t44)")
            }
            Setup::Distance if !has(&|c| matches!(c, Col::Distance(_))) => {
                Some("the known distance: a column `distance [mm]`")
            }
            _ => None,
        };
        match need {
            Some(what) => Err(self.err(line, format!("the header lacks {what}"))),
            None => Ok(()),
        }
    }

    /// One data row of a headered file.
    fn headered_row(
        &mut self,
        line: usize,
        cols: &[Col],
        fields: &[&str],
    ) -> Result<Measurement, MeasurementFileError> {
        if fields.len() < cols.len() {
            return Err(self.err(
                line,
                format!("{} values for {} columns", fields.len(), cols.len()),
            ));
        }
        let n = self.joints.dof();
        let mut q = [vec![0.0; n], vec![0.0; n]];
        let mut row = Row::default();
        let mut label = None;
        for (c, (col, f)) in cols.iter().zip(fields).enumerate() {
            if matches!(col, Col::Ignored) {
                continue;
            }
            if *col == Col::Group {
                label = Some(f.to_string());
                continue;
            }
            let v = number(f).ok_or_else(|| {
                self.err(
                    line,
                    format!("column {} ({f:?}) is not a finite number", c + 1),
                )
            })?;
            match *col {
                Col::Joint(k, side, s) => q[side][k] = v * s,
                other => row.put(other, v),
            }
        }
        if let Some(r) = row.radius {
            // As a `# radius_m R` line: a contact radius is positive.
            if r <= 0.0 {
                return Err(self.err(
                    line,
                    format!("radius {r} m: the contact radius must be positive"),
                ));
            }
            self.radius = Some(r);
        }
        let [qa, qb] = q;
        match self.setup {
            Setup::Pose | Setup::Position | Setup::Tracker => {
                let (p, r) = row.pose().map_err(|e| self.err(line, e))?;
                self.position(line, qa, p, r)
            }
            Setup::Distance => {
                let d = row.distance.unwrap_or(f64::NAN);
                self.distance(line, qa, qb, d)
            }
            _ => self.grouped(line, qa, label.as_deref()),
        }
    }
}

/// `t11..t44` (1-based) or `m00..m33` (0-based): the (row, column) of a 4x4 matrix element.
fn matrix_element(name: &str) -> Option<(usize, usize)> {
    let d: Vec<usize> = name
        .get(1..)?
        .chars()
        .map(|c| c.to_digit(10).map(|v| v as usize))
        .collect::<Option<_>>()?;
    let [r, c] = d[..] else { return None };
    match name.as_bytes()[0] {
        b't' if (1..=4).contains(&r) && (1..=4).contains(&c) => Some((r - 1, c - 1)),
        b'm' if r < 4 && c < 4 => Some((r, c)),
        _ => None,
    }
}

/// The non-joint values of one headered row, in SI units.
#[derive(Default)]
struct Row {
    point: [Option<f64>; 3],
    quat: [Option<f64>; 4],
    rpy: [Option<f64>; 3],
    rotvec: [Option<f64>; 3],
    matrix: [[Option<f64>; 4]; 4],
    distance: Option<f64>,
    radius: Option<f64>,
}

impl Row {
    fn put(&mut self, col: Col, v: f64) {
        match col {
            Col::Point(i, s) => self.point[i] = Some(v * s),
            Col::Quat(i) => self.quat[i] = Some(v),
            Col::Rpy(i, s) => self.rpy[i] = Some(v * s),
            Col::RotVec(i, s) => self.rotvec[i] = Some(v * s),
            Col::Matrix(r, c, s) => self.matrix[r][c] = Some(if c == 3 { v * s } else { v }),
            Col::Distance(s) => self.distance = Some(v * s),
            Col::Radius(s) => self.radius = Some(v * s),
            Col::Joint(..) | Col::Group | Col::Ignored => {}
        }
    }

    /// The tool point and, if the row has one, the orientation.
    fn pose(&self) -> Result<(Vector3<f64>, Option<Rotation3<f64>>), String> {
        let all = |v: &[Option<f64>]| v.iter().copied().collect::<Option<Vec<f64>>>();
        let any = |v: &[Option<f64>]| v.iter().any(Option::is_some);
        let flat: Vec<Option<f64>> = self.matrix.iter().flatten().copied().collect();
        if any(&flat) {
            let m = all(&flat).ok_or("the 4x4 matrix needs all 16 columns t11..t44")?;
            let pose = pose_from_matrix(&Matrix4::from_row_slice(&m))
                .map_err(|e| format!("the measured pose is not rigid: {e}"))?;
            return Ok((pose.translation.vector, Some(pose.rotation)));
        }
        let p = all(&self.point).ok_or("the tool point needs x, y and z")?;
        let p = Vector3::new(p[0], p[1], p[2]);
        let r = if any(&self.quat) {
            let q = all(&self.quat).ok_or("a quaternion needs qw, qx, qy and qz")?;
            let quat = nalgebra::Quaternion::new(q[0], q[1], q[2], q[3]);
            let norm = quat.norm();
            if !(norm > 0.5 && norm < 2.0) {
                return Err(format!("the quaternion has norm {norm}: not a rotation"));
            }
            Some(UnitQuaternion::from_quaternion(quat).to_rotation_matrix())
        } else if any(&self.rpy) {
            let a = all(&self.rpy).ok_or("roll-pitch-yaw needs roll, pitch and yaw")?;
            // (2.21): R = Rz(phi) Ry(theta) Rx(psi) with phi = yaw, theta = pitch, psi = roll.
            Some(rotation_from_rpy(&Vector3::new(a[2], a[1], a[0])))
        } else if any(&self.rotvec) {
            let a = all(&self.rotvec).ok_or("a rotation vector needs rx, ry and rz")?;
            let v = Vector3::new(a[0], a[1], a[2]);
            if !v.norm().is_finite() {
                return Err("the rotation vector's length is not a finite angle".into());
            }
            Some(Rotation3::new(v))
        } else {
            None
        };
        Ok((p, r))
    }
}

/// An annotated headered template for `setup` (degrees and millimetres), with `examples` as
/// its rows: what `armlab calibrate MODEL --template FILE` writes.
pub fn template(joints: &JointColumns, setup: Setup, examples: &[Measurement]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# armlab calibration measurements, setup `{}` (armlab calibrate MODEL --setup {} \
         --measurements THIS_FILE)",
        setup.name(),
        setup.name()
    );
    let what = match setup {
        Setup::Pose => {
            "per row: the joint readings, then the measured tool pose (x, y, z and a \
                        unit quaternion qw, qx, qy, qz; roll, pitch, yaw or rx, ry, rz work too)"
        }
        Setup::Position | Setup::Tracker => {
            "per row: the joint readings, then the measured tool point"
        }
        Setup::Distance => {
            "per row: the joint readings at socket a and at socket b (`_a`, `_b`), \
                            then the artefact's calibrated distance between the two tool points"
        }
        Setup::Pivot => {
            "per row: the joint readings with the tool tip in a fixed socket; the \
                         `point` column says which socket"
        }
        Setup::Plane => {
            "per row: the joint readings with the probe touching a plane; the `plane` \
                         column says which"
        }
        Setup::Sphere => {
            "per row: the joint readings with the probe touching a sphere; `radius` is \
                          the sphere's radius plus the probe ball's"
        }
    };
    let _ = writeln!(s, "# {what}.");
    let _ = writeln!(
        s,
        "# Units go in brackets: [deg] or [rad] for angles, [mm] or [m] for lengths. Columns \
         armlab does not know are ignored (with a warning); `#` starts a comment."
    );
    let _ = writeln!(s, "# What this setup cannot see: {}.", setup.blind_spots());
    let unit = |k: usize| if joints.angular[k] { "deg" } else { "mm" };
    let jcols = |suffix: &str| -> Vec<String> {
        (0..joints.dof())
            .map(|k| format!("{}{suffix} [{}]", joints.names[k], unit(k)))
            .collect()
    };
    let mut header = match setup {
        Setup::Distance => [jcols("_a"), jcols("_b")].concat(),
        _ => jcols(""),
    };
    header.extend(
        match setup {
            Setup::Pose => &["x [mm]", "y [mm]", "z [mm]", "qw", "qx", "qy", "qz"][..],
            Setup::Position | Setup::Tracker => &["x [mm]", "y [mm]", "z [mm]"][..],
            Setup::Distance => &["distance [mm]"][..],
            Setup::Pivot => &["point"][..],
            Setup::Plane => &["plane"][..],
            Setup::Sphere => &["sphere", "radius [mm]"][..],
        }
        .iter()
        .map(|c| c.to_string()),
    );
    let _ = writeln!(s, "{}", header.join(", "));
    for m in examples {
        let _ = writeln!(s, "{}", template_row(joints, m).join(", "));
    }
    s
}

/// One row of the template: joints in degrees or millimetres, lengths in millimetres.
fn template_row(joints: &JointColumns, m: &Measurement) -> Vec<String> {
    let q = |q: &[f64]| -> Vec<String> {
        q.iter()
            .enumerate()
            .map(|(k, v)| {
                let v = if joints.angular[k] {
                    v.to_degrees()
                } else {
                    v * 1e3
                };
                format!("{v:.4}")
            })
            .collect()
    };
    let mm = |v: f64| format!("{:.4}", v * 1e3);
    let mut row = q(m.q());
    match m {
        Measurement::Pose {
            world_from_tool, ..
        } => {
            row.extend(world_from_tool.translation.vector.iter().map(|v| mm(*v)));
            let u = UnitQuaternion::from_rotation_matrix(&world_from_tool.rotation);
            row.extend([u.w, u.i, u.j, u.k].iter().map(|v| format!("{v:.9}")));
        }
        Measurement::Position { p, .. } => row.extend(p.iter().map(|v| mm(*v))),
        Measurement::Distance { qb, distance, .. } => {
            row.extend(q(qb));
            row.push(mm(*distance));
        }
        Measurement::Pivot { point: g, .. } | Measurement::Plane { plane: g, .. } => {
            row.push(format!("{}", g + 1))
        }
        Measurement::Sphere { sphere, radius, .. } => {
            row.push(format!("{}", sphere + 1));
            row.push(mm(*radius));
        }
    }
    row
}

/// Desired tool poses: per line the 16 numbers of a 4x4 `world_from_tool` (plain), or a
/// headered CSV with `x, y, z` and an orientation (quaternion, roll-pitch-yaw, rotation vector or
/// `t11..t44`), as the measurement files.
pub fn parse_targets(text: &str, source_name: &str) -> Result<Vec<Pose>, MeasurementFileError> {
    let none = JointColumns {
        names: Vec::new(),
        angular: Vec::new(),
    };
    let file = parse_setup(text, source_name, &none, Setup::Pose, None)?;
    file.measurements
        .into_iter()
        .map(|m| match m {
            Measurement::Pose {
                world_from_tool, ..
            } => Ok(world_from_tool),
            _ => Err(MeasurementFileError {
                source_name: source_name.into(),
                line: 0,
                problem: "a desired pose needs an orientation (16 numbers, or x, y, z with a \
                          quaternion, roll-pitch-yaw or rotation vector)"
                    .into(),
            }),
        })
        .collect()
}

/// The table of a target correction as a headered CSV in SI units (what
/// `armlab calibrate --correct-targets ... --out` writes): pose, posture (quoted), within the
/// limits, the joint vector, the pose to send (position and quaternion w x y z), the errors.
pub fn write_corrections(
    rows: &[super::correct::TargetCorrection],
    joints: &JointColumns,
) -> String {
    let mut s = String::from(
        "# armlab target correction: per desired pose and posture, the joint vector that puts the \
         calibrated arm's tool there (q), and the pose to send a controller that runs the nominal \
         model (send_*, quaternion w x y z); errors of the calibrated FK at q, and of the \
         uncorrected nominal solution, in m\n",
    );
    let mut header = vec!["pose".to_string(), "posture".into(), "within_limits".into()];
    for (name, angle) in joints.names.iter().zip(&joints.angular) {
        header.push(format!("{name} [{}]", if *angle { "rad" } else { "m" }));
    }
    for c in [
        "send_x [m]",
        "send_y [m]",
        "send_z [m]",
        "send_qw",
        "send_qx",
        "send_qy",
        "send_qz",
        "position_error [m]",
        "orientation_error [rad]",
        "uncorrected_error [m]",
    ] {
        header.push(c.into());
    }
    s.push_str(&header.join(", "));
    s.push('\n');
    for r in rows {
        let u = nalgebra::UnitQuaternion::from_rotation_matrix(&r.send.rotation);
        let mut f = vec![
            (r.pose + 1).to_string(),
            format!("\"{}\"", r.posture),
            r.within_limits.to_string(),
        ];
        f.extend(r.q.iter().map(|v| format!("{v:?}")));
        f.extend(r.send.translation.vector.iter().map(|v| format!("{v:?}")));
        f.extend([u.w, u.i, u.j, u.k].iter().map(|v| format!("{v:?}")));
        f.extend(
            [r.position_error, r.orientation_error, r.uncorrected_error]
                .iter()
                .map(|v| format!("{v:e}")),
        );
        s.push_str(&f.join(", "));
        s.push('\n');
    }
    s
}
