//! The orientation sheets of a class, drawn per student from the seed: the matrix (rows, four
//! decimals) or the sequence (degrees) in the question, radians in the key. Angles lie on a
//! 5-degree grid (15 for a sequence) so that a right answer is a round number; about one sheet
//! in five sits at a singular case (an Euler singularity, theta = 0 or pi for angle and axis
//! and the quaternion) and one in ten near it, where the answer is still well defined.

use super::grading::{angle_axis_matrix, product};
use super::{
    AxisAngleReference, ComposeReference, EulerConvention, EulerReference, QuaternionReference,
};
use crate::exercise::{
    ExerciseError, KEY_FORMAT, Key, KeyAnswer, Kind, Rng, Sheet, Tolerance, unsuitable,
};
use crate::kinematics::Pose;
use crate::kinematics::orientation::{Axis, Step, StepFrame, degrees};
use nalgebra::{Matrix3, Rotation3, Translation3, Vector3};
use std::f64::consts::PI;

/// What a sheet gives and asks.
struct Question {
    matrix: Option<Matrix3<f64>>,
    convention: Option<EulerConvention>,
    sequence: Option<Vec<Step>>,
    answer: KeyAnswer,
    markdown: String,
}

/// Makes one orientation sheet (`kind` euler, compose, axis-angle or quaternion) for `student`
/// of the class made with `seed`. It draws no arm; the figure shows the given frame.
pub(in crate::exercise) fn generate(
    kind: Kind,
    seed: u64,
    student: usize,
) -> Result<Sheet, ExerciseError> {
    let mut rng = Rng::new(seed, student);
    let q = match kind {
        Kind::Euler => euler(&mut rng),
        Kind::Compose => compose(&mut rng),
        Kind::AxisAngle => axis_angle(&mut rng),
        Kind::Quaternion => quaternion(&mut rng),
        _ => return Err(unsuitable(kind, "not an orientation exercise".into())),
    };
    let rows = |m: &Matrix3<f64>| [0, 1, 2].map(|i| [0, 1, 2].map(|j| m[(i, j)]));
    let key = Key {
        format: KEY_FORMAT.into(),
        kind,
        seed,
        student,
        robot: String::new(),
        model: String::new(),
        q: Vec::new(),
        matrix: q.matrix.as_ref().map(rows),
        convention: q.convention,
        sequence: q.sequence,
        answer: q.answer,
        tolerance: Tolerance::default(),
        question: q.markdown.clone(),
    };
    let target = q.matrix.map(|m| {
        Pose::from_parts(
            Translation3::identity(),
            Rotation3::from_matrix_unchecked(m),
        )
    });
    Ok(Sheet {
        markdown: q.markdown,
        key,
        robot: None,
        q: Vec::new(),
        frames: false,
        target,
        points: Vec::new(),
    })
}

/// One of `n` choices.
fn pick(rng: &mut Rng, n: usize) -> usize {
    (rng.uniform() * n as f64) as usize % n
}

/// An angle in degrees on the `step` grid in [lo, hi], never 0 (rad).
fn nonzero(rng: &mut Rng, lo: f64, hi: f64, step: f64) -> f64 {
    let d = rng.stepped(lo, hi, step);
    if d == 0.0 { step } else { d }.to_radians()
}

/// `a` or `b`, at even odds.
fn either(rng: &mut Rng, a: f64, b: f64) -> f64 {
    if rng.uniform() < 0.5 { a } else { b }
}

/// The matrix as the sheet prints it: rows of four decimals, indented (a Markdown code block).
fn matrix_text(m: &Matrix3<f64>) -> String {
    (0..3)
        .map(|i| {
            let row: Vec<String> = (0..3)
                .map(|j| {
                    let v = m[(i, j)];
                    format!("{:8.4}", if v.abs() < 5e-5 { 0.0 } else { v })
                })
                .collect();
            format!("    [{} ]", row.join(""))
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// What every sheet says about handing in.
const HAND_IN: &str = "then hand it in: the app's Exercise tab saves it under your sheet's \
                       name (`student-NN.txt`).";

/// An euler sheet: a convention drawn among ZYZ, ZXZ and RPY, and angles whose matrix is given.
fn euler(rng: &mut Rng) -> Question {
    let c = EulerConvention::ALL[pick(rng, 3)];
    let case = rng.uniform();
    let theta = match c {
        EulerConvention::Rpy if case < 0.2 => either(rng, 90.0, -90.0).to_radians(),
        EulerConvention::Rpy if case < 0.3 => either(rng, 85.0, -85.0).to_radians(),
        EulerConvention::Rpy => nonzero(rng, -75.0, 75.0, 5.0),
        _ if case < 0.2 => either(rng, 0.0, 180.0).to_radians(),
        _ if case < 0.3 => either(rng, 5.0, 175.0).to_radians(),
        _ => nonzero(rng, 15.0, 165.0, 5.0),
    };
    let phi = nonzero(rng, -175.0, 180.0, 5.0);
    let psi = nonzero(rng, -175.0, 180.0, 5.0);
    let m = c.rotation([phi, theta, psi]);
    let markdown = format!(
        "# Euler angles of a rotation matrix\n\nA frame is turned from the reference frame by \
         the rotation matrix (rows)\n\n{}\n\nFind its {c} angles (phi, theta, psi): R = {} \
         ({}). Either solution is right; where only a combination of phi and psi is \
         determined, any phi and psi that give it are right.\n\nAnswer with one line \
         `phi theta psi` in radians, or in degrees with a first line `# deg`; {HAND_IN}\n",
        matrix_text(&m),
        c.product(),
        match c {
            EulerConvention::Zyz => "2.18",
            EulerConvention::Zxz => "Problem 2.1",
            EulerConvention::Rpy => "2.21",
        }
    );
    Question {
        matrix: Some(m),
        convention: Some(c),
        sequence: None,
        answer: KeyAnswer::Euler(EulerReference::of(&m, c)),
        markdown,
    }
}

/// A compose sheet: two to four elementary rotations about different successive axes, all about
/// the current frame, all about the fixed frame, or mixed.
fn compose(rng: &mut Rng) -> Question {
    let n = 2 + pick(rng, 3);
    let pattern = pick(rng, 3);
    let mut steps: Vec<Step> = Vec::with_capacity(n);
    for _ in 0..n {
        let mut axis = Axis::ALL[pick(rng, 3)];
        while steps.last().is_some_and(|s| s.axis == axis) {
            axis = Axis::ALL[pick(rng, 3)];
        }
        let frame = match pattern {
            0 => StepFrame::Current,
            1 => StepFrame::Fixed,
            _ if rng.uniform() < 0.5 => StepFrame::Current,
            _ => StepFrame::Fixed,
        };
        let angle = nonzero(rng, -180.0, 180.0, 15.0);
        steps.push(Step { frame, axis, angle });
    }
    if pattern == 2 && steps.iter().all(|s| s.frame == steps[0].frame) {
        let last = steps.len() - 1;
        steps[last].frame = match steps[0].frame {
            StepFrame::Current => StepFrame::Fixed,
            StepFrame::Fixed => StepFrame::Current,
        };
    }
    let list: Vec<String> = steps
        .iter()
        .enumerate()
        .map(|(i, s)| {
            format!(
                "{}. by {}° about the {} axis of the {} frame",
                i + 1,
                degrees(s.angle),
                s.axis,
                s.frame
            )
        })
        .collect();
    let markdown = format!(
        "# Composition of rotations\n\nA frame starts aligned with the fixed reference frame \
         and turns, in this order:\n\n{}\n\nWrite the rotation matrix R of the final frame \
         with respect to the reference frame (Sect. 2.3: a turn about an axis of the current \
         frame, or of the fixed frame).\n\nAnswer with three lines, the rows of R \
         (`r11 r12 r13`, `r21 r22 r23`, `r31 r32 r33`); {HAND_IN}\n",
        list.join("\n")
    );
    let r = product(&steps);
    let rows = [0, 1, 2].map(|i| [0, 1, 2].map(|j| r[(i, j)]));
    Question {
        matrix: None,
        convention: None,
        sequence: Some(steps),
        answer: KeyAnswer::Compose(ComposeReference { product: rows }),
        markdown,
    }
}

/// The axes drawn: integer directions of integer length, permuted and signed at random.
const AXES: [[f64; 4]; 7] = [
    [1.0, 2.0, 2.0, 3.0],
    [2.0, 3.0, 6.0, 7.0],
    [1.0, 4.0, 8.0, 9.0],
    [0.0, 3.0, 4.0, 5.0],
    [2.0, 6.0, 9.0, 11.0],
    [4.0, 4.0, 7.0, 9.0],
    [0.0, 0.0, 1.0, 1.0],
];

/// A rotation for axis-angle and quaternion sheets: theta (rad, in [0, pi]) and a unit axis.
/// Cases: a half turn (one in ten), no turn (one in twenty), theta of 5 or 175 degrees (one in
/// ten), else theta in [10, 170] degrees.
fn turn(rng: &mut Rng) -> (f64, Vector3<f64>) {
    let case = rng.uniform();
    let theta = if case < 0.1 {
        PI
    } else if case < 0.15 {
        0.0
    } else if case < 0.25 {
        either(rng, 5.0, 175.0).to_radians()
    } else {
        nonzero(rng, 10.0, 170.0, 5.0)
    };
    let [a, b, c, n] = AXES[pick(rng, AXES.len())];
    let perms = [
        [a, b, c],
        [a, c, b],
        [b, a, c],
        [b, c, a],
        [c, a, b],
        [c, b, a],
    ];
    let p = perms[pick(rng, 6)];
    let mut r = Vector3::new(p[0], p[1], p[2]) / n;
    for k in 0..3 {
        if rng.uniform() < 0.5 {
            r[k] = -r[k];
        }
    }
    (theta, r)
}

/// The text of a sheet that gives the matrix `m` and asks for `what`, answered on one `line`
/// (`units` says how).
fn given_matrix(title: &str, m: &Matrix3<f64>, what: &str, line: &str, units: &str) -> String {
    format!(
        "# {title}\n\nA frame is turned from the reference frame by the rotation matrix (rows)\
         \n\n{}\n\n{what}\n\nAnswer with one line `{line}` ({units}); {HAND_IN}\n",
        matrix_text(m)
    )
}

/// An axis-angle sheet: the matrix of a turn; theta and r asked.
fn axis_angle(rng: &mut Rng) -> Question {
    let (theta, r) = turn(rng);
    let m = angle_axis_matrix(theta, &r);
    let markdown = given_matrix(
        "Angle and axis of a rotation matrix",
        &m,
        "Find an angle theta and a unit axis r with R = R(theta, r), (2.25), by (2.27)-(2.28) \
         or, where sin(theta) = 0, by their special cases (Problem 2.5). (theta, r) and \
         (-theta, -r) are both right; at theta = 0 any axis is.",
        "theta x y z",
        "theta in radians, or in degrees with a first line `# deg`; r a unit vector",
    );
    Question {
        matrix: Some(m),
        convention: None,
        sequence: None,
        answer: KeyAnswer::AxisAngle(AxisAngleReference {
            angle: theta,
            axis: (theta != 0.0).then(|| [r.x, r.y, r.z]),
        }),
        markdown,
    }
}

/// A quaternion sheet: the matrix of a turn; eta and epsilon asked.
fn quaternion(rng: &mut Rng) -> Question {
    let (theta, r) = turn(rng);
    let m = angle_axis_matrix(theta, &r);
    let markdown = given_matrix(
        "Unit quaternion of a rotation matrix",
        &m,
        "Find the unit quaternion Q = {eta, epsilon} of R, (2.34)-(2.35). Q and -Q are both \
         right.",
        "eta ex ey ez",
        "eta first, then the three components of epsilon",
    );
    let (s, c) = (theta / 2.0).sin_cos();
    Question {
        matrix: Some(m),
        convention: None,
        sequence: None,
        answer: KeyAnswer::Quaternion(QuaternionReference {
            eta: c,
            epsilon: [s * r.x, s * r.y, s * r.z],
        }),
        markdown,
    }
}
