//! Orientation exercises (Sects. 2.2-2.5, Problems 2.1-2.8): the kinds `euler` (the angles of a
//! given matrix in a named convention, ZYZ, ZXZ or RPY), `compose` (the matrix of a described
//! sequence of elementary rotations, each about the current or the fixed frame), `axis-angle`
//! and `quaternion` (of a given matrix).
//!
//! A key carries its question at the top level: the given `matrix` (rows), the `convention` of
//! an euler sheet, the `sequence` of a compose sheet. Grading derives the answer from them again
//! and compares rotations, not numbers, so every correct answer gets full marks: either Euler
//! solution, any member of a singular family, Q and -Q, (theta, r) and (-theta, -r), any axis at
//! theta = 0. A wrong answer is tried against the named single mistakes, each the wrong
//! computation done on the key (the transpose, the other convention, the fixed axes for the
//! current ones, degrees read as radians, ...): the first that gives the answer is named.
//!
//! Answer files are one line (`phi theta psi`, `theta x y z`, `eta ex ey ez`) or three (the
//! rows of the matrix), numbers separated by commas or spaces, `#` comments; angles in radians,
//! or in degrees with a first line `# deg` ([`parse_answer`]).

mod grading;
mod sheets;

pub(super) use grading::grade;
pub(super) use sheets::generate;

use super::{ExerciseError, Kind};
use crate::kinematics::EulerKind;
use crate::kinematics::orientation::{Combination, euler_solutions};
use nalgebra::{Matrix3, Rotation3, Vector3};
use serde::{Deserialize, Serialize};
use std::fmt;

/// The Euler-angle convention an `euler` sheet names: `"zyz"`, `"zxz"` or `"rpy"` in a key.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum EulerConvention {
    /// ZYZ: `R = Rz(phi) Ry(theta) Rz(psi)`, (2.18).
    Zyz,
    /// ZXZ: `R = Rz(phi) Rx(theta) Rz(psi)`, Problem 2.1.
    Zxz,
    /// Roll-pitch-yaw: `R = Rz(phi) Ry(theta) Rx(psi)`, (2.21).
    Rpy,
}

impl EulerConvention {
    /// The three conventions, in the order ZYZ, ZXZ, RPY.
    pub const ALL: [EulerConvention; 3] = [
        EulerConvention::Zyz,
        EulerConvention::Zxz,
        EulerConvention::Rpy,
    ];

    /// The library's representation of the same convention.
    ///
    /// # Examples
    ///
    /// ```
    /// use armlab::exercise::orientation::EulerConvention;
    /// use armlab::kinematics::EulerKind;
    ///
    /// assert_eq!(EulerConvention::Zxz.kind(), EulerKind::Zxz);
    /// ```
    pub fn kind(self) -> EulerKind {
        match self {
            EulerConvention::Zyz => EulerKind::Zyz,
            EulerConvention::Zxz => EulerKind::Zxz,
            EulerConvention::Rpy => EulerKind::Rpy,
        }
    }

    /// The rotation matrix of the angles `[phi, theta, psi]` (rad): (2.18), Problem 2.1 or
    /// (2.21).
    ///
    /// # Examples
    ///
    /// ```
    /// use armlab::exercise::orientation::EulerConvention;
    /// use std::f64::consts::FRAC_PI_2;
    ///
    /// // ZXZ with theta = 90 degrees turns z0 onto -y0: the third column is (0, -1, 0).
    /// let r = EulerConvention::Zxz.rotation([0.0, FRAC_PI_2, 0.0]);
    /// assert!((r[(1, 2)] + 1.0).abs() < 1e-15 && r[(0, 2)].abs() < 1e-15);
    /// ```
    pub fn rotation(self, angles: [f64; 3]) -> Matrix3<f64> {
        self.kind().to_rotation(&Vector3::from(angles)).into_inner()
    }

    /// The product as a sheet writes it: `Rz(phi) Ry(theta) Rz(psi)`.
    ///
    /// # Examples
    ///
    /// ```
    /// use armlab::exercise::orientation::EulerConvention;
    ///
    /// assert_eq!(EulerConvention::Rpy.product(), "Rz(phi) Ry(theta) Rx(psi)");
    /// ```
    pub fn product(self) -> &'static str {
        match self {
            EulerConvention::Zyz => "Rz(phi) Ry(theta) Rz(psi)",
            EulerConvention::Zxz => "Rz(phi) Rx(theta) Rz(psi)",
            EulerConvention::Rpy => "Rz(phi) Ry(theta) Rx(psi)",
        }
    }
}

impl fmt::Display for EulerConvention {
    /// "ZYZ", "ZXZ" or "RPY".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            EulerConvention::Zyz => "ZYZ",
            EulerConvention::Zxz => "ZXZ",
            EulerConvention::Rpy => "RPY",
        })
    }
}

/// The combination of phi and psi a singular matrix determines (`"phi+psi"` or `"phi-psi"`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Determined {
    /// phi + psi (ZYZ and ZXZ at theta = 0, RPY at theta = -pi/2).
    #[serde(rename = "phi+psi")]
    PhiPlusPsi,
    /// phi - psi (ZYZ and ZXZ at theta = pi, RPY at theta = pi/2).
    #[serde(rename = "phi-psi")]
    PhiMinusPsi,
}

/// An euler key's reference answer, for the teacher reading the key (grading derives it again
/// from the key's matrix and convention).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EulerReference {
    /// The solutions `[phi, theta, psi]` (rad): both where the convention is regular, one
    /// representative (phi = 0) where it is singular.
    pub solutions: Vec<[f64; 3]>,
    /// Whether the matrix is at the convention's singularity (Problems 2.2, 2.3).
    pub singular: bool,
    /// Where singular: the combination of phi and psi that is determined.
    pub determined: Option<Determined>,
    /// Where singular: its value (rad, in (-pi, pi]).
    pub value: Option<f64>,
}

impl EulerReference {
    /// The reference answer of `matrix` (rows of a rotation) in `convention`.
    ///
    /// # Examples
    ///
    /// ```
    /// use armlab::exercise::orientation::{Determined, EulerConvention, EulerReference};
    ///
    /// let deg = |d: f64| d.to_radians();
    /// let c = EulerConvention::Zyz;
    /// let regular = EulerReference::of(&c.rotation([deg(30.0), deg(45.0), deg(60.0)]), c);
    /// assert_eq!(regular.solutions.len(), 2);
    /// let flat = EulerReference::of(&c.rotation([deg(30.0), 0.0, deg(45.0)]), c);
    /// assert_eq!(flat.determined, Some(Determined::PhiPlusPsi));
    /// assert!((flat.value.unwrap() - deg(75.0)).abs() < 1e-12);
    /// ```
    pub fn of(matrix: &Matrix3<f64>, convention: EulerConvention) -> Self {
        let s = euler_solutions(
            convention.kind(),
            &Rotation3::from_matrix_unchecked(*matrix),
        );
        Self {
            solutions: s.solutions.iter().map(|a| [a[0], a[1], a[2]]).collect(),
            singular: s.family.is_some(),
            determined: s.family.map(|f| match f.combination {
                Combination::PhiPlusPsi => Determined::PhiPlusPsi,
                Combination::PhiMinusPsi => Determined::PhiMinusPsi,
            }),
            value: s.family.map(|f| f.value),
        }
    }
}

/// A compose key's reference answer: the product of the sequence (rows).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ComposeReference {
    /// Rows of R, the final frame in the reference frame.
    pub product: [[f64; 3]; 3],
}

/// An axis-angle key's reference answer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AxisAngleReference {
    /// theta (rad, in [0, pi]); (-theta, -r) is as right.
    pub angle: f64,
    /// The unit axis r; `None` at theta = 0, where any axis serves.
    pub axis: Option<[f64; 3]>,
}

/// A quaternion key's reference answer, with eta >= 0 (-Q is as right).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QuaternionReference {
    /// eta = cos(theta/2), (2.30).
    pub eta: f64,
    /// epsilon = sin(theta/2) r, (2.30).
    pub epsilon: [f64; 3],
}

/// An orientation answer as read from its file (angles in rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum OrientationAnswer {
    /// `phi theta psi` (rad).
    Euler([f64; 3]),
    /// The matrix, rows.
    Matrix([[f64; 3]; 3]),
    /// `theta x y z`: the angle (rad) and the axis as given.
    AxisAngle {
        /// theta (rad).
        angle: f64,
        /// r as given (a unit vector, if right).
        axis: [f64; 3],
    },
    /// `eta ex ey ez`, as given.
    Quaternion {
        /// eta.
        eta: f64,
        /// epsilon.
        epsilon: [f64; 3],
    },
}

impl OrientationAnswer {
    /// The answer of `kind` from its numbers in the file's order (angles in rad): 3 for euler,
    /// 9 for compose (rows), 4 for axis-angle and quaternion.
    ///
    /// # Examples
    ///
    /// ```
    /// use armlab::exercise::Kind;
    /// use armlab::exercise::orientation::OrientationAnswer;
    ///
    /// let a = OrientationAnswer::from_numbers(Kind::AxisAngle, &[1.0, 0.0, 0.0, 1.0]).unwrap();
    /// assert_eq!(a, OrientationAnswer::AxisAngle { angle: 1.0, axis: [0.0, 0.0, 1.0] });
    /// assert!(OrientationAnswer::from_numbers(Kind::Euler, &[1.0, 2.0]).is_err());
    /// ```
    pub fn from_numbers(kind: Kind, v: &[f64]) -> Result<Self, ExerciseError> {
        let lines = answer_lines(kind);
        let want: usize = lines.iter().map(|l| l.len()).sum();
        if want == 0 || v.len() != want {
            let layout: Vec<String> = lines.iter().map(|l| l.join(" ")).collect();
            return Err(ExerciseError::Answer {
                reason: format!(
                    "a {} answer is {want} numbers (`{}`), not {}",
                    kind.name(),
                    layout.join("` / `"),
                    v.len()
                ),
            });
        }
        Ok(match kind {
            Kind::Euler => Self::Euler([v[0], v[1], v[2]]),
            Kind::Compose => {
                Self::Matrix([[v[0], v[1], v[2]], [v[3], v[4], v[5]], [v[6], v[7], v[8]]])
            }
            Kind::AxisAngle => Self::AxisAngle {
                angle: v[0],
                axis: [v[1], v[2], v[3]],
            },
            _ => Self::Quaternion {
                eta: v[0],
                epsilon: [v[1], v[2], v[3]],
            },
        })
    }
}

/// The lines of an answer file of `kind`, each the names of its fields in order; empty for the
/// kinds that are not orientations.
///
/// # Examples
///
/// ```
/// use armlab::exercise::Kind;
/// use armlab::exercise::orientation::answer_lines;
///
/// assert_eq!(answer_lines(Kind::Euler), &[&["phi", "theta", "psi"][..]]);
/// assert_eq!(answer_lines(Kind::Compose).len(), 3);
/// assert!(answer_lines(Kind::Fk).is_empty());
/// ```
pub fn answer_lines(kind: Kind) -> &'static [&'static [&'static str]] {
    match kind {
        Kind::Euler => &[&["phi", "theta", "psi"]],
        Kind::Compose => &[
            &["r11", "r12", "r13"],
            &["r21", "r22", "r23"],
            &["r31", "r32", "r33"],
        ],
        Kind::AxisAngle => &[&["theta", "x", "y", "z"]],
        Kind::Quaternion => &[&["eta", "ex", "ey", "ez"]],
        _ => &[],
    }
}

/// Whether an answer of `kind` holds angles (and so reads `# deg`): euler and axis-angle.
///
/// # Examples
///
/// ```
/// use armlab::exercise::Kind;
/// use armlab::exercise::orientation::takes_degrees;
///
/// assert!(takes_degrees(Kind::Euler) && takes_degrees(Kind::AxisAngle));
/// assert!(!takes_degrees(Kind::Quaternion) && !takes_degrees(Kind::Compose));
/// ```
pub fn takes_degrees(kind: Kind) -> bool {
    answer_lines(kind)
        .iter()
        .flat_map(|l| l.iter())
        .any(|f| is_angle(f))
}

/// The fields that are angles, in degrees under `# deg`.
fn is_angle(field: &str) -> bool {
    matches!(field, "phi" | "theta" | "psi")
}

/// What is wrong with one field (or line) of an answer file.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FieldProblem {
    /// Not a number.
    #[error("{text:?} is not a number")]
    NotANumber {
        /// The field as written.
        text: String,
    },
    /// A number, but infinite or NaN.
    #[error("{text:?} is not a finite number")]
    NotFinite {
        /// The field as written.
        text: String,
    },
    /// The line stops before this field.
    #[error("missing (the line is `{}`)", .line.join(" "))]
    Missing {
        /// The line's fields.
        line: &'static [&'static str],
    },
    /// More numbers on the line than it has fields.
    #[error("{extra} number(s) too many after it (the line is `{}`)", .line.join(" "))]
    TooMany {
        /// How many too many.
        extra: usize,
        /// The line's fields.
        line: &'static [&'static str],
    },
    /// A line of numbers after the last the answer has.
    #[error("a line too many: the answer has {lines} line(s)")]
    ExtraLine {
        /// How many lines the answer has.
        lines: usize,
    },
}

/// Reads an orientation answer file of `kind` (`file` names it in errors): its lines as
/// [`answer_lines`] lists them, numbers separated by commas or spaces, `#` comments and blank
/// lines skipped; a first line `# deg` makes the angles (phi, theta, psi; theta of axis-angle)
/// degrees, turned into radians (a compose or quaternion answer has no angle). An error names
/// the file, the line and the field.
///
/// # Examples
///
/// ```
/// use armlab::exercise::Kind;
/// use armlab::exercise::orientation::{OrientationAnswer, parse_answer};
///
/// let a = parse_answer(Kind::Euler, "# deg\n90, 45 0  # my answer\n", "a.txt").unwrap();
/// let OrientationAnswer::Euler(angles) = a else { panic!() };
/// assert!((angles[0] - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
///
/// let e = parse_answer(Kind::AxisAngle, "0.5 0 x 1\n", "student-03.txt").unwrap_err();
/// assert_eq!(
///     e.to_string(),
///     "answer: student-03.txt: line 1, field y: \"x\" is not a number"
/// );
/// ```
pub fn parse_answer(
    kind: Kind,
    text: &str,
    file: &str,
) -> Result<OrientationAnswer, ExerciseError> {
    let lines = answer_lines(kind);
    let degrees = text.lines().next().is_some_and(|l| {
        l.trim()
            .trim_start_matches('#')
            .trim()
            .eq_ignore_ascii_case("deg")
    });
    let error = |line: usize, field: Option<&'static str>, problem: FieldProblem| {
        ExerciseError::AnswerField {
            file: file.to_string(),
            line,
            field,
            problem,
        }
    };
    let mut numbers = Vec::with_capacity(12);
    let (mut row, mut last) = (0, 0);
    for (i, line) in text.lines().enumerate() {
        let body = line.split('#').next().unwrap_or("").trim();
        if body.is_empty() {
            continue;
        }
        last = i + 1;
        let Some(names) = lines.get(row) else {
            let problem = FieldProblem::ExtraLine { lines: lines.len() };
            return Err(error(last, None, problem));
        };
        read_line(body, names, degrees, &mut numbers).map_err(|(f, p)| error(last, f, p))?;
        row += 1;
    }
    if let Some(names) = lines.get(row) {
        let problem = FieldProblem::Missing { line: names };
        return Err(error(last + 1, names.first().copied(), problem));
    }
    OrientationAnswer::from_numbers(kind, &numbers)
}

/// Reads the numbers of one line whose fields are `names` onto `numbers` (angles turned into
/// radians where `degrees`); else the field at fault and what is wrong with it.
fn read_line(
    body: &str,
    names: &'static [&'static str],
    degrees: bool,
    numbers: &mut Vec<f64>,
) -> Result<(), (Option<&'static str>, FieldProblem)> {
    let fields: Vec<&str> = body
        .split(|c: char| c == ',' || c.is_whitespace())
        .filter(|f| !f.is_empty())
        .collect();
    if fields.len() > names.len() {
        let extra = fields.len() - names.len();
        let problem = FieldProblem::TooMany { extra, line: names };
        return Err((names.last().copied(), problem));
    }
    for (name, text) in names.iter().zip(&fields) {
        let text = text.to_string();
        let v: f64 = match text.parse() {
            Ok(v) => v,
            Err(_) => return Err((Some(name), FieldProblem::NotANumber { text })),
        };
        if !v.is_finite() {
            return Err((Some(name), FieldProblem::NotFinite { text }));
        }
        numbers.push(if degrees && is_angle(name) {
            v.to_radians()
        } else {
            v
        });
    }
    match names.get(fields.len()) {
        Some(name) => Err((Some(name), FieldProblem::Missing { line: names })),
        None => Ok(()),
    }
}
