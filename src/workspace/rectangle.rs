//! The rectangle of admissible configurations of a two-link planar arm (Sect. 2.10.1, Example
//! 2.6, Fig. 2.29): corners a-f, the singular segment ad (aligned links, q2 = 0) that separates
//! the elbow-down band (q2 > 0) from the elbow-up band (q2 < 0), as data for a figure. Its image
//! in the arm plane is [`super::planar_boundary`] (Fig. 2.30).

use super::WorkspaceError;
use super::planar::{CurveKind, Eval, planar_arm, roots};
use super::posture::PostureClassifier;
use crate::kinematics::Robot;

/// A labelled point of the joint-space rectangle (Fig. 2.29).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RectPoint {
    /// Label ("a" ... "f" as in Fig. 2.29, or "l0", "r0", ... when q2 has several singular
    /// values inside its limits).
    pub label: String,
    /// (q1, q2) in rad.
    pub q: [f64; 2],
}

/// A labelled segment of the joint-space rectangle.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RectSegment {
    /// Label, e.g. "ab".
    pub label: String,
    /// Index of the start point in [`JointRectangle::points`].
    pub from: usize,
    /// Index of the end point.
    pub to: usize,
    /// Joint limit or singular line (aligned links).
    pub kind: CurveKind,
    /// Posture class of the band the segment bounds (`None` for a singular line between two
    /// bands).
    pub class: Option<u8>,
}

/// The rectangle of admissible configurations of a two-link arm (Fig. 2.29), as data for a figure.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[must_use]
pub struct JointRectangle {
    /// Limits of q1 (rad).
    pub q1: [f64; 2],
    /// Limits of q2 (rad).
    pub q2: [f64; 2],
    /// The singular values of q2 strictly inside its limits (rad), ascending.
    pub singular_q2: Vec<f64>,
    /// Corners and the ends of the singular lines.
    pub points: Vec<RectPoint>,
    /// Edges and singular lines, in the order of Example 2.6 (ab, bc, cd, da, ae, ef, fd).
    pub segments: Vec<RectSegment>,
    /// Posture bands: (q2 range, class), bottom to top.
    pub bands: Vec<([f64; 2], u8)>,
    /// Names of the posture classes.
    pub class_names: Vec<String>,
}

/// The joint-space rectangle of a two-link planar arm (Fig. 2.29): corners, the ends of the
/// singular lines q2 = 0 (aligned links, also q2 = +-pi when inside the limits), segments labelled
/// as in Example 2.6 and posture bands.
pub fn joint_rectangle(robot: &Robot) -> Result<JointRectangle, WorkspaceError> {
    let (frame, n) = planar_arm(robot)?;
    if n != 2 {
        return Err(WorkspaceError::NotPlanar {
            robot: robot.name.clone(),
            reason: format!(
                "has {n} links: the joint-space rectangle of Fig. 2.29 needs a two-link planar arm"
            ),
        });
    }
    let mut ev = Eval::new(robot, frame);
    let lim = robot.sampling_ranges();
    let (l1, l2) = (lim[0], lim[1]);
    let singular = roots(|x| ev.cross(&[l1[0], x], 0, 1), l2[0], l2[1]);
    let mut b = vec![l2[0]];
    b.extend(&singular);
    b.push(l2[1]);
    let m = b.len() - 1;
    let classifier = PostureClassifier::new(robot);
    let bands = posture_bands(robot, &classifier, l1, &b);
    let lower_only = m == 1 && l2[1] <= 0.0;
    let points = rect_points(l1, &b, lower_only);
    let segments = rect_segments(&points, &bands, lower_only);
    Ok(JointRectangle {
        q1: l1,
        q2: l2,
        singular_q2: singular,
        points,
        segments,
        bands,
        class_names: classifier.class_names().to_vec(),
    })
}

/// The posture bands between consecutive q2 boundaries `b` (limits and singular values): each
/// band's q2 range and the posture class at its centre (class 0 where forward kinematics fails).
fn posture_bands(
    robot: &Robot,
    classifier: &PostureClassifier,
    l1: [f64; 2],
    b: &[f64],
) -> Vec<([f64; 2], u8)> {
    (0..b.len() - 1)
        .map(|i| {
            let q = [0.5 * (l1[0] + l1[1]), 0.5 * (b[i] + b[i + 1])];
            let c = robot
                .fk(&q)
                .map(|t| classifier.classify(&q, &t))
                .unwrap_or(0);
            ([b[i], b[i + 1]], c)
        })
        .collect()
}

/// The labelled ends of every q2 line `b` on the left (q1 = q1m, even indices) and right (q1 =
/// q1M, odd indices) edges, bottom to top. `lower_only`: one band, below q2 = 0.
fn rect_points(l1: [f64; 2], b: &[f64], lower_only: bool) -> Vec<RectPoint> {
    let m = b.len() - 1;
    // Labels of Fig. 2.29: left edge (q1 = q1m) e, a, b and right edge f, d, c, bottom to top.
    let (left, right): (Vec<String>, Vec<String>) = match m {
        2 => (
            ["e", "a", "b"].map(String::from).to_vec(),
            ["f", "d", "c"].map(String::from).to_vec(),
        ),
        1 if lower_only => (
            ["e", "a"].map(String::from).to_vec(),
            ["f", "d"].map(String::from).to_vec(),
        ),
        1 => (
            ["a", "b"].map(String::from).to_vec(),
            ["d", "c"].map(String::from).to_vec(),
        ),
        _ => (
            (0..=m).map(|i| format!("l{i}")).collect(),
            (0..=m).map(|i| format!("r{i}")).collect(),
        ),
    };
    let mut points = Vec::new();
    for i in 0..=m {
        points.push(RectPoint {
            label: left[i].clone(),
            q: [l1[0], b[i]],
        });
        points.push(RectPoint {
            label: right[i].clone(),
            q: [l1[1], b[i]],
        });
    }
    points
}

/// The segments of the rectangle in the order of Example 2.6: the top band's perimeter (ab, bc,
/// cd, da), then each lower band's (ae, ef, fd); the perimeter alone when `lower_only`.
fn rect_segments(
    points: &[RectPoint],
    bands: &[([f64; 2], u8)],
    lower_only: bool,
) -> Vec<RectSegment> {
    let m = bands.len();
    let (li, ri) = (|i: usize| 2 * i, |i: usize| 2 * i + 1);
    let mut segments = Vec::new();
    let mut seg = |from: usize, to: usize, kind, class| {
        segments.push(RectSegment {
            label: format!("{}{}", points[from].label, points[to].label),
            from,
            to,
            kind,
            class,
        });
    };
    let line_kind = |i: usize| {
        if i == 0 || i == m {
            CurveKind::JointLimit
        } else {
            CurveKind::Singular
        }
    };
    let line_class = |i: usize, band: usize| (i == 0 || i == m).then_some(bands[band].1);
    let lim_kind = CurveKind::JointLimit;
    if lower_only {
        let c = Some(bands[0].1);
        seg(li(1), li(0), lim_kind, c);
        seg(li(0), ri(0), lim_kind, c);
        seg(ri(0), ri(1), lim_kind, c);
        seg(ri(1), li(1), lim_kind, c);
    } else {
        // Top band first: ab, bc, cd, da; then each lower band: ae, ef, fd.
        let t = m - 1;
        let c = Some(bands[t].1);
        seg(li(t), li(m), lim_kind, c);
        seg(li(m), ri(m), lim_kind, c);
        seg(ri(m), ri(t), lim_kind, c);
        seg(ri(t), li(t), line_kind(t), line_class(t, t));
        for i in (0..t).rev() {
            let c = Some(bands[i].1);
            seg(li(i + 1), li(i), lim_kind, c);
            if i == 0 {
                seg(li(0), ri(0), lim_kind, c);
            } else {
                seg(li(i), ri(i), line_kind(i), line_class(i, i));
            }
            seg(ri(i), ri(i + 1), lim_kind, c);
        }
    }
    segments
}
