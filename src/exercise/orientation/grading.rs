//! Grading an orientation answer: the key's question gives the rotation, the answer is read as
//! the rotation it describes, and a wrong one is tried against the named single mistakes, each
//! the wrong computation done on the key.

use super::{Determined, EulerConvention, EulerReference, OrientationAnswer};
use crate::exercise::{Answer, ExerciseError, Grade, Item, Key, Kind, Mistake};
use crate::kinematics::orientation::{Step, StepFrame, compose};
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::PI;

/// A key without the question field its kind needs.
fn missing(key: &Key, field: &'static str) -> ExerciseError {
    ExerciseError::KeyField {
        kind: key.kind.name(),
        field,
    }
}

/// The key's given matrix.
fn given(key: &Key) -> Result<Matrix3<f64>, ExerciseError> {
    key.matrix
        .map(|m| matrix(&m))
        .ok_or_else(|| missing(key, "matrix"))
}

/// A matrix from its rows.
fn matrix(rows: &[[f64; 3]; 3]) -> Matrix3<f64> {
    Matrix3::from_fn(|i, j| rows[i][j])
}

/// Grades an orientation answer (`Answer::Orientation`, or `Answer::Rows` of numbers in rad)
/// against `key`: one item, right when the answer describes the key's rotation.
pub(in crate::exercise) fn grade(key: &Key, answer: &Answer) -> Result<Grade, ExerciseError> {
    let answer = match answer {
        Answer::Orientation(a) => *a,
        Answer::Rows(rows) => OrientationAnswer::from_numbers(key.kind, &rows.concat())?,
        _ => {
            return Err(ExerciseError::Answer {
                reason: format!(
                    "a {} answer is numbers, not a model file or names",
                    key.kind.name()
                ),
            });
        }
    };
    let tol = key.tolerance.angle;
    let item = match (key.kind, answer) {
        (Kind::Euler, OrientationAnswer::Euler(a)) => {
            let c = key.convention.ok_or_else(|| missing(key, "convention"))?;
            grade_euler(&given(key)?, c, a, tol)
        }
        (Kind::Compose, OrientationAnswer::Matrix(m)) => {
            let steps = key
                .sequence
                .as_ref()
                .ok_or_else(|| missing(key, "sequence"))?;
            grade_compose(steps, &matrix(&m), tol)
        }
        (Kind::AxisAngle, OrientationAnswer::AxisAngle { angle, axis }) => {
            grade_axis_angle(&given(key)?, angle, Vector3::from(axis), tol)
        }
        (Kind::Quaternion, OrientationAnswer::Quaternion { eta, epsilon }) => {
            let [x, y, z] = epsilon;
            grade_quaternion(&given(key)?, [eta, x, y, z], tol)
        }
        (kind, _) => {
            return Err(ExerciseError::Answer {
                reason: format!("this answer is not one of a {} sheet", kind.name()),
            });
        }
    };
    Ok(Grade::of(vec![item]))
}

/// Two matrices equal entry by entry within `tol` (false where a number is not finite).
fn same(a: &Matrix3<f64>, b: &Matrix3<f64>, tol: f64) -> bool {
    a.iter().zip(b.iter()).all(|(x, y)| (x - y).abs() <= tol)
}

/// The largest difference of two matrices' entries.
fn off_by(a: &Matrix3<f64>, b: &Matrix3<f64>) -> f64 {
    a.iter()
        .zip(b.iter())
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// A named single mistake tried on an answer: whether its wrong computation on the key gives
/// the answer, and what it was in words (appended to the mistake's name).
struct Trial {
    mistake: Mistake,
    detail: String,
    fits: bool,
}

impl Trial {
    fn new(mistake: Mistake, detail: impl Into<String>, fits: bool) -> Self {
        Self {
            mistake,
            detail: detail.into(),
            fits,
        }
    }
}

/// The item: right (with `right`'s feedback), else the first mistake that fits, else `wrong`.
fn verdict(item: String, right: Option<String>, trials: Vec<Trial>, wrong: String) -> Item {
    if let Some(feedback) = right {
        return Item {
            item,
            correct: true,
            feedback,
            mistake: None,
        };
    }
    match trials.into_iter().find(|t| t.fits) {
        Some(t) => Item {
            item,
            correct: false,
            feedback: format!("{}{}", t.mistake, t.detail),
            mistake: Some(t.mistake),
        },
        None => Item {
            item,
            correct: false,
            feedback: wrong,
            mistake: None,
        },
    }
}

/// Grades Euler angles `a` (rad) of `given` in convention `c`. The mistakes tried, each a reading
/// of the answer that gives the matrix: degrees as radians and the converse, the angles of the
/// transpose, another convention's angles, the angles in the reversed order, one angle's sign.
fn grade_euler(given: &Matrix3<f64>, c: EulerConvention, a: [f64; 3], tol: f64) -> Item {
    let fits = |angles: [f64; 3], target: &Matrix3<f64>| same(&c.rotation(angles), target, tol);
    let right = fits(a, given).then(|| match EulerReference::of(given, c).determined {
        Some(d) => format!(
            "right: only {} is determined here; any phi and psi that give it are right",
            match d {
                Determined::PhiPlusPsi => "phi + psi",
                Determined::PhiMinusPsi => "phi - psi",
            }
        ),
        None => "right".to_string(),
    });
    let scaled = |k: f64| a.map(|v| v * k);
    let mut trials = vec![
        Trial::new(
            Mistake::DegreesAsRadians,
            ": the numbers are degrees; write `# deg` as the first line, or give radians",
            fits(scaled(PI / 180.0), given),
        ),
        Trial::new(
            Mistake::RadiansAsDegrees,
            ": the file says `# deg` but the numbers are radians",
            fits(scaled(180.0 / PI), given),
        ),
        Trial::new(
            Mistake::Transpose,
            format!(": these are the {c} angles of R^T, the rotation back"),
            fits(a, &given.transpose()),
        ),
    ];
    for other in EulerConvention::ALL.into_iter().filter(|o| *o != c) {
        trials.push(Trial::new(
            Mistake::OtherConvention,
            format!(" ({c} given, {other} answered)"),
            same(&other.rotation(a), given, tol),
        ));
    }
    trials.push(Trial::new(
        Mistake::ReversedOrder,
        ": psi, theta, phi: the angles in the reversed order",
        fits([a[2], a[1], a[0]], given),
    ));
    for (k, name) in ["phi", "theta", "psi"].into_iter().enumerate() {
        let mut b = a;
        b[k] = -b[k];
        let detail = format!(": {name} has the wrong sign");
        trials.push(Trial::new(Mistake::AngleSign, detail, fits(b, given)));
    }
    let wrong = format!(
        "wrong: {} of these angles is not the given matrix (off by up to {:.3})",
        c.product(),
        off_by(&c.rotation(a), given)
    );
    verdict(format!("the {c} angles"), right, trials, wrong)
}

/// The product of a sequence of elementary rotations, (2.14) and (2.16).
pub(super) fn product(steps: &[Step]) -> Matrix3<f64> {
    compose(steps).into_inner()
}

/// `steps` with the frame of every step about `from` changed to the other frame.
fn swapped(steps: &[Step], from: StepFrame) -> Vec<Step> {
    let to = match from {
        StepFrame::Current => StepFrame::Fixed,
        StepFrame::Fixed => StepFrame::Current,
    };
    steps
        .iter()
        .map(|s| Step {
            frame: if s.frame == from { to } else { s.frame },
            ..*s
        })
        .collect()
}

/// The steps (1-based) about `frame`, as "1, 3".
fn steps_about(steps: &[Step], frame: StepFrame) -> Vec<String> {
    (1..=steps.len())
        .filter(|&i| steps[i - 1].frame == frame)
        .map(|i| i.to_string())
        .collect()
}

/// Grades the matrix `m` of the sequence `steps`. The mistakes tried, each a wrong product of
/// the sequence: the current steps pre-multiplied (as about the fixed axes) and the converse,
/// the steps in the reversed order (for a mixed sequence; for one of a single frame it is the
/// frames swapped), the transpose, the degrees put into sin and cos as radians, one angle's
/// sign.
fn grade_compose(steps: &[Step], m: &Matrix3<f64>, tol: f64) -> Item {
    let r = product(steps);
    let fits = |wrong: &[Step]| same(&product(wrong), m, tol);
    let current = steps_about(steps, StepFrame::Current);
    let fixed = steps_about(steps, StepFrame::Fixed);
    let mixed = !current.is_empty() && !fixed.is_empty();
    let which = |list: &[String]| {
        if mixed {
            format!(" (step {})", list.join(", "))
        } else {
            String::new()
        }
    };
    let mut trials = Vec::new();
    if !current.is_empty() {
        let fit = fits(&swapped(steps, StepFrame::Current));
        trials.push(Trial::new(Mistake::FixedForCurrent, which(&current), fit));
    }
    if !fixed.is_empty() {
        let fit = fits(&swapped(steps, StepFrame::Fixed));
        trials.push(Trial::new(Mistake::CurrentForFixed, which(&fixed), fit));
    }
    if mixed {
        let reversed: Vec<Step> = steps.iter().rev().copied().collect();
        trials.push(Trial::new(
            Mistake::ReversedOrder,
            ": the steps multiplied in the reversed order",
            fits(&reversed),
        ));
    }
    trials.push(Trial::new(
        Mistake::Transpose,
        ": R^T, the rotation back to the reference frame",
        same(&r.transpose(), m, tol),
    ));
    let degrees: Vec<Step> = steps
        .iter()
        .map(|s| Step {
            angle: s.angle.to_degrees(),
            ..*s
        })
        .collect();
    trials.push(Trial::new(
        Mistake::DegreesAsRadians,
        ": sin and cos took the sequence's degrees as radians",
        fits(&degrees),
    ));
    for (k, s) in steps.iter().enumerate() {
        let mut b = steps.to_vec();
        b[k].angle = -s.angle;
        let detail = format!(": step {} ({s}) turned the other way", k + 1);
        trials.push(Trial::new(Mistake::AngleSign, detail, fits(&b)));
    }
    let right = same(&r, m, tol).then(|| "right".to_string());
    let wrong = format!(
        "wrong: not the product of the sequence (off by up to {:.3})",
        off_by(&r, m)
    );
    verdict("the matrix".into(), right, trials, wrong)
}

/// `R(theta, r)` of (2.25) with `r` as given: a unit r gives the rotation, any other r no
/// rotation at all (except at theta = 0, where it is the identity for every r).
pub(super) fn angle_axis_matrix(theta: f64, r: &Vector3<f64>) -> Matrix3<f64> {
    let (s, c) = theta.sin_cos();
    let v = 1.0 - c;
    let (x, y, z) = (r.x, r.y, r.z);
    // (2.25)
    Matrix3::new(
        x * x * v + c,
        x * y * v - z * s,
        x * z * v + y * s,
        x * y * v + z * s,
        y * y * v + c,
        y * z * v - x * s,
        x * z * v - y * s,
        y * z * v + x * s,
        z * z * v + c,
    )
}

/// Grades `theta` (rad) and the axis `r` of `given`. Right: R(theta, r) is the matrix and r is
/// a unit vector, or theta = 0 (mod 2 pi) and the matrix the identity, with any axis. The
/// mistakes tried: r not a unit vector, degrees as radians and the converse, the transpose's
/// angle and axis, the half angle.
fn grade_axis_angle(given: &Matrix3<f64>, theta: f64, r: Vector3<f64>, tol: f64) -> Item {
    let fits = |t: f64, axis: &Vector3<f64>, target: &Matrix3<f64>| {
        same(&angle_axis_matrix(t, axis), target, tol)
    };
    let n = r.norm();
    let unit = (n - 1.0).abs() <= tol;
    let none = crate::kinematics::orientation::wrap_angle(theta).abs() <= tol;
    let right = (fits(theta, &r, given) && (unit || none)).then(|| {
        if none {
            "right: theta = 0, any axis".to_string()
        } else {
            "right".to_string()
        }
    });
    let trials = vec![
        Trial::new(
            Mistake::NonUnitAxis,
            format!(": |r| = {n:.4}; divide r by its length"),
            n > 0.0 && !unit && fits(theta, &(r / n), given),
        ),
        Trial::new(
            Mistake::DegreesAsRadians,
            ": theta is in degrees; write `# deg` as the first line, or give radians",
            fits(theta.to_radians(), &r, given),
        ),
        Trial::new(
            Mistake::RadiansAsDegrees,
            ": the file says `# deg` but theta is in radians",
            fits(theta.to_degrees(), &r, given),
        ),
        Trial::new(
            Mistake::Transpose,
            ": (theta, r) turns the other way; r = (r32 - r23, r13 - r31, r21 - r12) / (2 sin theta), (2.28)",
            fits(theta, &r, &given.transpose()),
        ),
        Trial::new(
            Mistake::HalfAngle,
            ": theta/2 (the quaternion's half angle) given for theta",
            fits(2.0 * theta, &r, given),
        ),
    ];
    let wrong = format!(
        "wrong: R(theta, r) of (2.25) is not the given matrix (off by up to {:.3})",
        off_by(&angle_axis_matrix(theta, &r), given)
    );
    verdict("the angle and axis".into(), right, trials, wrong)
}

/// `R(eta, epsilon)` of (2.33) with `q = [eta, ex, ey, ez]` as given (a non-unit q gives no
/// rotation).
fn quaternion_matrix(q: [f64; 4]) -> Matrix3<f64> {
    let [n, x, y, z] = q;
    // (2.33)
    Matrix3::new(
        2.0 * (n * n + x * x) - 1.0,
        2.0 * (x * y - n * z),
        2.0 * (x * z + n * y),
        2.0 * (x * y + n * z),
        2.0 * (n * n + y * y) - 1.0,
        2.0 * (y * z - n * x),
        2.0 * (x * z - n * y),
        2.0 * (y * z + n * x),
        2.0 * (n * n + z * z) - 1.0,
    )
}

/// Grades the quaternion `q = [eta, ex, ey, ez]` of `given`. Right: a unit q whose (2.33) is the
/// matrix (Q and -Q alike). The mistakes tried: q not unit, epsilon written before eta, the
/// conjugate (the transpose's quaternion), the whole angle where (2.30) takes half of it.
fn grade_quaternion(given: &Matrix3<f64>, q: [f64; 4], tol: f64) -> Item {
    let fits = |q: [f64; 4], target: &Matrix3<f64>| same(&quaternion_matrix(q), target, tol);
    let n = q.iter().map(|v| v * v).sum::<f64>().sqrt();
    let unit = (n - 1.0).abs() <= tol;
    let [eta, x, y, z] = q;
    let eps = Vector3::new(x, y, z);
    let full = {
        // the answer as {cos(theta), sin(theta) r}: the quaternion of theta is then
        // {cos(theta/2), sin(theta/2) r}
        let (theta, s) = (eps.norm().atan2(eta), eps.norm());
        let r = if s > 0.0 { eps / s } else { eps };
        let (sh, ch) = (theta / 2.0).sin_cos();
        [ch, sh * r.x, sh * r.y, sh * r.z]
    };
    let trials = vec![
        Trial::new(
            Mistake::NonUnitQuaternion,
            format!(": |Q| = {n:.4}; eta^2 + |epsilon|^2 = 1"),
            n > 0.0 && !unit && fits(q.map(|v| v / n), given),
        ),
        Trial::new(
            Mistake::EpsilonFirst,
            ": the answer is `eta ex ey ez`, eta first",
            fits([z, eta, x, y], given),
        ),
        Trial::new(
            Mistake::Transpose,
            ": epsilon with the wrong sign, {eta, -epsilon} is the rotation back",
            fits(q, &given.transpose()),
        ),
        Trial::new(
            Mistake::FullAngle,
            ": eta = cos(theta), epsilon = sin(theta) r; (2.30) takes theta/2",
            eps.norm() > tol && fits(full, given),
        ),
    ];
    let right = (unit && fits(q, given)).then(|| "right".to_string());
    let wrong = format!(
        "wrong: R(eta, epsilon) of (2.33) is not the given matrix (off by up to {:.3})",
        off_by(&quaternion_matrix(q), given)
    );
    verdict("the quaternion".into(), right, trials, wrong)
}
