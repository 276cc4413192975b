//! The construction of the Universal Robots family: six revolute joints, axes 2, 3 and 4
//! parallel, axes 4-5 and 5-6 meeting, no spherical wrist. There is no wrist centre to decouple
//! (2.93) on; instead the point o5 where axes 5 and 6 meet gives theta1, the direction of the
//! parallel axes against the approach gives theta5 and theta6, and what is left after joint 1 is
//! the three-link planar arm of Sect. 2.12.1 in the plane normal to axes 2-4: the point W where
//! axes 4 and 5 meet plays the wrist point (2.91)-(2.92), the triangle gives theta3 and theta2,
//! and theta4 = phi - theta2 - theta3 (2.90).
//!
//! As for the other families, every drawn quantity is read from the joint axes at q (world
//! frame), so the URDF of a UR arm draws the same as its DH table. Each drawn angle is measured
//! about its joint's axis between a direction fixed in the link before it and one fixed in the
//! link after it, so it differs from the joint by a constant, read at q = 0; the labels print the
//! joint.

use super::{Mark, Step, axes, deg, signed};
use crate::construction::{ConstructionError, meet};
use crate::kinematics::Robot;
use crate::kinematics::ik::closed_form::{Elbow, Posture, Shoulder, WristFlip};
use crate::kinematics::ik::{ClosedForm, Target};
use crate::kinematics::orientation::wrap_angle;
use nalgebra::Vector3;

/// The arm's geometry at q (world, m; directions unit).
struct Geometry {
    /// Axis 1's direction, and its point level with o5.
    z0: Vector3<f64>,
    foot: Vector3<f64>,
    /// The base frame's x axis, normal to axis 1.
    x0: Vector3<f64>,
    /// The direction of the parallel axes 2-4 ("z1").
    n: Vector3<f64>,
    /// The directions of axes 5 and 6 (axis 6 along the tool's approach).
    w5: Vector3<f64>,
    w6: Vector3<f64>,
    /// The tool point and the tool's x axis (normal to axis 6).
    p: Vector3<f64>,
    x_e: Vector3<f64>,
    /// o5: where axes 5 and 6 meet; W: where axes 4 and 5 meet.
    o5: Vector3<f64>,
    w: Vector3<f64>,
    /// S and E: where axes 2 and 3 cross the plane through o5 normal to them.
    s: Vector3<f64>,
    e: Vector3<f64>,
}

/// `v` made normal to the unit `axis` and unit length; `None` when along it.
fn across(v: Vector3<f64>, axis: &Vector3<f64>) -> Option<Vector3<f64>> {
    let u = v - axis * axis.dot(&v);
    let len = u.norm();
    (len > 1e-9).then(|| u / len)
}

impl Geometry {
    /// The geometry at q, or `NotDrawn` where the axes are not those of the family.
    fn at(robot: &Robot, q: &[f64]) -> Result<Self, ConstructionError> {
        let not = || ConstructionError::NotDrawn {
            family: "three parallel axes (its axes 4-5 or 5-6 do not meet at this configuration)",
        };
        let ax = axes(robot, q)?;
        let t = robot.fk(q)?;
        let tol = 1e-9 * robot.characteristic_length().max(1e-3);
        let (o5, gap56) = meet(&ax[4].0, &ax[4].1, &ax[5].0, &ax[5].1);
        let (w, gap45) = meet(&ax[3].0, &ax[3].1, &ax[4].0, &ax[4].1);
        if gap56 > tol || gap45 > tol {
            return Err(not());
        }
        let z0 = ax[0].1;
        let n = ax[1].1;
        let approach = t.rotation * Vector3::z();
        let w6 = if ax[5].1.dot(&approach) < 0.0 {
            -ax[5].1
        } else {
            ax[5].1
        };
        let on_plane = |a: &Vector3<f64>| a + n * n.dot(&(o5 - a));
        let x_e = across(t.rotation * Vector3::x(), &w6)
            .or_else(|| across(t.rotation * Vector3::y(), &w6))
            .ok_or_else(not)?;
        Ok(Self {
            z0,
            foot: ax[0].0 + z0 * z0.dot(&(o5 - ax[0].0)),
            x0: across(robot.base.rotation * Vector3::x(), &z0)
                .or_else(|| across(robot.base.rotation * Vector3::y(), &z0))
                .ok_or_else(not)?,
            n,
            w5: ax[4].1,
            w6,
            p: t.translation.vector,
            x_e,
            o5,
            w,
            s: on_plane(&ax[1].0),
            e: on_plane(&ax[2].0),
        })
    }

    /// z0 x z1: the direction in the plane of the planar problem that joint 1 carries along, from
    /// which theta2 is measured.
    fn h(&self) -> Vector3<f64> {
        self.z0.cross(&self.n)
    }

    /// The drawn angles of joints 1-6 (rad), each about its own axis (see the module docs).
    fn drawn(&self) -> [f64; 6] {
        let (s, e, w) = (self.s, self.e, self.w);
        [
            signed(&self.x0, &self.n, &self.z0),
            signed(&self.h(), &(e - s), &self.n),
            signed(&(e - s), &(w - e), &self.n),
            signed(&(w - e), &self.w5, &self.n),
            signed(&self.n, &self.w6, &self.w5),
            signed(&self.w5, &self.x_e, &self.w6),
        ]
    }
}

/// The drawn angles, the joint values they show, and the names of the posture drawn and of the
/// other shoulder, elbow and wrist.
struct Angles {
    drawn: [f64; 6],
    joint: [f64; 6],
    /// e.g. ["shoulder left", "elbow up", "wrist down"].
    this: [String; 3],
    other: [String; 3],
}

/// The posture of the closed-form solution equal to q, if the closed form gives one there.
fn posture_at(robot: &Robot, q: &[f64]) -> Option<Posture> {
    let (Ok(cf), Ok(t)) = (ClosedForm::detect(robot), robot.fk(q)) else {
        return None;
    };
    let result = cf.solve(robot, &Target::Pose(t)).ok()?;
    let same = |a: &[f64]| {
        a.iter().zip(q).all(|(x, y)| {
            let d = (x - y).rem_euclid(std::f64::consts::TAU);
            d.min(std::f64::consts::TAU - d) < 1e-6
        })
    };
    let found = result.solutions.iter().find(|s| same(&s.q))?;
    found.posture.closed_form().copied()
}

/// The names of the shoulder, elbow and wrist of the posture drawn ("shoulder left", "elbow
/// up", "wrist down"; "this shoulder" where the posture has none, e.g. at a singularity) and of
/// the other member of each pair ("shoulder right", or "the other wrist" where the pair has no
/// opposite name).
fn part_names(posture: Option<Posture>) -> ([String; 3], [String; 3]) {
    // Parts read from the base (a reversed chain's are named from the tool: not these).
    let p = posture.filter(|p| !p.reversed).unwrap_or_default();
    let shoulder = match p.shoulder {
        Some(Shoulder::Right) => Some(Shoulder::Left),
        Some(Shoulder::Left) => Some(Shoulder::Right),
        _ => None,
    };
    let elbow = match p.elbow {
        Some(Elbow::Up) => Some(Elbow::Down),
        Some(Elbow::Down) => Some(Elbow::Up),
        _ => None,
    };
    let wrist = match p.wrist {
        Some(WristFlip::Up) => Some(WristFlip::Down),
        Some(WristFlip::Down) => Some(WristFlip::Up),
        _ => None,
    };
    let other = Posture {
        shoulder,
        elbow,
        wrist,
        ..Posture::default()
    };
    let name = |label: Option<&str>, fallback: &str| label.unwrap_or(fallback).to_string();
    (
        [
            name(p.shoulder_label(), "this shoulder"),
            name(p.elbow_label(), "this elbow"),
            name(p.wrist_label(), "this wrist"),
        ],
        [
            name(other.shoulder_label(), "the other shoulder"),
            name(other.elbow_label(), "the other elbow"),
            name(other.wrist_label(), "the other wrist"),
        ],
    )
}

/// The steps of the construction at q (module docs).
pub(super) fn steps(robot: &Robot, q: &[f64]) -> Result<Vec<Step>, ConstructionError> {
    let g = Geometry::at(robot, q)?;
    let zero = Geometry::at(robot, &vec![0.0; robot.dof()])?;
    let (drawn, at_zero) = (g.drawn(), zero.drawn());
    let (this, other) = part_names(posture_at(robot, q));
    let a = Angles {
        drawn,
        joint: std::array::from_fn(|k| wrap_angle(drawn[k] - at_zero[k])),
        this,
        other,
    };
    let scale = robot.characteristic_length();
    Ok(vec![
        o5_step(&g),
        theta1_step(&g, &a, scale),
        theta5_step(&g, &a, scale),
        theta6_step(&g, &a, scale),
        plane_step(&g, &a),
        triangle_step(&g, &a),
        theta2_step(&g, &a),
        theta4_step(&g, &a),
    ])
}

/// o5 = p - d6 z6: where axes 5 and 6 meet.
fn o5_step(g: &Geometry) -> Step {
    let d6 = g.w6.dot(&(g.p - g.o5));
    let off = (g.p - g.o5 - g.w6 * d6).norm();
    let (p, o5, z6) = (g.p, g.o5, g.w6);
    let formula = if off > 1e-9 {
        format!(
            "o5 is where axes 5 and 6 meet: ({:.3}, {:.3}, {:.3}) m (the tool point is {off:.3} \
             m off axis 6, so p - d6 z6 misses it)",
            o5.x, o5.y, o5.z
        )
    } else {
        format!(
            "o5 = p - d6 z6 = ({:.3}, {:.3}, {:.3}) - {d6:.3} ({:.3}, {:.3}, {:.3}) = ({:.3}, \
             {:.3}, {:.3}) m: axes 5 and 6 meet there; unlike a spherical wrist's centre it still \
             moves with joints 2-4",
            p.x, p.y, p.z, z6.x, z6.y, z6.z, o5.x, o5.y, o5.z
        )
    };
    Step {
        title: "The point o5 where axes 5 and 6 meet".into(),
        equation: "(2.93) for this family".into(),
        formula,
        marks: vec![
            Mark::Point {
                p,
                label: "p".into(),
            },
            Mark::Segment {
                a: p,
                b: o5,
                label: format!("-d6 z6 (d6 = {d6:.3} m)"),
                dashed: false,
            },
            Mark::Point {
                p: o5,
                label: "o5".into(),
            },
        ],
    }
}

/// theta1: o5 lies D from axis 1 along the parallel axes, so the arm's plane is one of the two
/// vertical planes at distance D from axis 1 through o5 (two shoulders).
fn theta1_step(g: &Geometry, a: &Angles, scale: f64) -> Step {
    let radial = g.o5 - g.foot;
    let r = radial.norm();
    let d = g.n.dot(&radial);
    // The other plane: n reflected across the direction to o5 keeps n . (o5 - foot) = D.
    let u = radial / r.max(f64::MIN_POSITIVE);
    let n_other = u * (2.0 * g.n.dot(&u)) - g.n;
    let other = wrap_angle(a.joint[0] + signed(&g.n, &n_other, &g.z0));
    let (corner, corner_other) = (g.foot + g.n * d, g.foot + n_other * d);
    let seg = |a, b, label: String, dashed| Mark::Segment {
        a,
        b,
        label,
        dashed,
    };
    Step {
        title: format!(
            "theta1: the vertical plane at distance D from axis 1 through o5 ({}), or the other \
             one ({})",
            a.this[0], a.other[0]
        ),
        equation: "Sect. 2.12.1, the shoulder offset of (2.109)-(2.110)".into(),
        formula: format!(
            "axes 2-4 and o5 lie D = d2 + d3 + d4 = {d:.3} m along z1 from axis 1, and o5 lies \
             r = {r:.3} m from it: r sin(theta1 - Atan2(o5y, o5x)) = D, two planes {} apart; \
             theta1 = {} ({}) or {} ({}); none where r < |D|",
            deg(std::f64::consts::PI - 2.0 * (d / r.max(f64::MIN_POSITIVE)).clamp(-1.0, 1.0).asin()),
            deg(a.joint[0]),
            a.this[0],
            deg(other),
            a.other[0]
        ),
        marks: vec![
            seg(g.foot, g.o5, format!("r = {r:.3} m"), true),
            seg(g.foot, corner, format!("D = {d:.3} m"), false),
            seg(corner, g.o5, String::new(), false),
            seg(g.foot, corner_other, a.other[0].clone(), true),
            seg(corner_other, g.o5, String::new(), true),
            Mark::Arc {
                center: g.foot,
                from: g.x0,
                normal: g.z0,
                angle: a.drawn[0],
                radius: 0.2 * scale,
                label: format!("θ1 = {}", deg(a.joint[0])),
            },
        ],
    }
}

/// theta5: the angle between the parallel axes and z6 (two wrists).
fn theta5_step(g: &Geometry, a: &Angles, scale: f64) -> Step {
    let c = g.n.dot(&g.w6);
    let len = 0.15 * scale;
    Step {
        title: format!(
            "theta5: z6 against the parallel axes ({}, or {})",
            a.this[2], a.other[2]
        ),
        equation: "third row of R_6^1".into(),
        formula: format!(
            "cos theta5 = +-z1 . z6 = +-{c:.4}: z6 makes {} with axes 2-4, turned about axis 5 one \
             way ({}) or the other ({}); theta5 = {} here; z6 parallel to axes 2-4 (theta5 = 0 \
             or pi) is the wrist singularity",
            deg(c.clamp(-1.0, 1.0).acos()),
            a.this[2],
            a.other[2],
            deg(a.joint[4])
        ),
        marks: vec![
            Mark::Segment {
                a: g.o5,
                b: g.o5 + g.n * len,
                label: "z1 (axes 2-4)".into(),
                dashed: true,
            },
            Mark::Segment {
                a: g.o5,
                b: g.o5 + g.w6 * len,
                label: "z6".into(),
                dashed: true,
            },
            Mark::Arc {
                center: g.o5,
                from: g.n,
                normal: g.w5,
                angle: a.drawn[4],
                radius: 0.6 * len,
                label: format!("θ5 = {}", deg(a.joint[4])),
            },
        ],
    }
}

/// Axis 5 = z1 x z6 / |z1 x z6|, and theta6 from it to x6.
fn theta6_step(g: &Geometry, a: &Angles, scale: f64) -> Step {
    let len = 0.15 * scale;
    Step {
        title: "Axis 5 normal to both, then theta6".into(),
        equation: "third row of R_6^1".into(),
        formula: format!(
            "axis 5 is normal to axes 2-4 and to z6: z4 = +-z1 x z6 / |z1 x z6| (undefined at \
             the wrist singularity, where theta6 is free); theta6 turns x6 about z6 from it: \
             theta6 = {}",
            deg(a.joint[5])
        ),
        marks: vec![
            Mark::Segment {
                a: g.o5 - g.w5 * len,
                b: g.o5 + g.w5 * len,
                label: "axis 5 = z1 x z6".into(),
                dashed: false,
            },
            Mark::Arc {
                center: g.p,
                from: g.w5,
                normal: g.w6,
                angle: a.drawn[5],
                radius: 0.5 * len,
                label: format!("θ6 = {}", deg(a.joint[5])),
            },
        ],
    }
}

/// The planar three-link problem after joint 1: W = o5 - d5 z4 and phi.
fn plane_step(g: &Geometry, a: &Angles) -> Step {
    let d5 = g.w5.dot(&(g.o5 - g.w));
    let phi = wrap_angle(a.joint[1] + a.joint[2] + a.joint[3]);
    let ws = (g.w - g.s).norm();
    Step {
        title: "After joint 1, a three-link planar arm in the plane normal to axes 2-4".into(),
        equation: "Sect. 2.12.1, (2.91)-(2.92)".into(),
        formula: format!(
            "W = o5 - d5 z4 = ({:.3}, {:.3}, {:.3}) m (d5 = {d5:.3} m) plays the wrist point: \
             links a2, a3 from S on axis 2 reach it, |W - S| = {ws:.3} m, and phi = theta2 + \
             theta3 + theta4 = {} is read off the direction of axis 5 in the plane",
            g.w.x,
            g.w.y,
            g.w.z,
            deg(phi)
        ),
        marks: vec![
            Mark::Point {
                p: g.s,
                label: "S (axis 2)".into(),
            },
            Mark::Segment {
                a: g.o5,
                b: g.w,
                label: format!("d5 = {d5:.3} m"),
                dashed: false,
            },
            Mark::Point {
                p: g.w,
                label: "W (axis 4)".into(),
            },
            Mark::Segment {
                a: g.s,
                b: g.w,
                label: format!("|W - S| = {ws:.3} m"),
                dashed: true,
            },
        ],
    }
}

/// The triangle S, E, W: c3 and the two elbows.
fn triangle_step(g: &Geometry, a: &Angles) -> Step {
    let (s, e, w) = (g.s, g.e, g.w);
    let (a2, a3, d) = ((e - s).norm(), (w - e).norm(), (w - s).norm());
    let c3 = (d * d - a2 * a2 - a3 * a3) / (2.0 * a2 * a3);
    // The other elbow: E reflected across the line S-W in the plane.
    let u = (w - s) / d.max(f64::MIN_POSITIVE);
    let e_other = s + u * (2.0 * u.dot(&(e - s))) - (e - s);
    let seg = |a, b, label: String, dashed| Mark::Segment {
        a,
        b,
        label,
        dashed,
    };
    Step {
        title: format!(
            "The triangle: c3, and the two elbows ({}, or {})",
            a.this[1], a.other[1]
        ),
        equation: "Sect. 2.12.1, Fig. 2.31".into(),
        formula: format!(
            "c3 = (|W - S|^2 - a2^2 - a3^2) / (2 a2 a3) = ({d:.3}^2 - {a2:.3}^2 - {a3:.3}^2) / \
             (2 {a2:.3} {a3:.3}) = {:.4}; theta3 = +-acos(c3): theta3 = {} here",
            c3 + 0.0,
            deg(a.joint[2])
        ),
        marks: vec![
            seg(s, e, format!("a2 = {a2:.3} m"), false),
            seg(e, w, format!("a3 = {a3:.3} m"), false),
            seg(s, e_other, a.other[1].clone(), true),
            seg(e_other, w, String::new(), true),
            Mark::Arc {
                center: e,
                from: (e - s).normalize(),
                normal: g.n,
                angle: a.drawn[2],
                radius: 0.25 * a3,
                label: format!("θ3 = {}", deg(a.joint[2])),
            },
        ],
    }
}

/// theta2 = alpha -+ beta (Fig. 2.31).
fn theta2_step(g: &Geometry, a: &Angles) -> Step {
    let (s, e, w) = (g.s, g.e, g.w);
    let alpha = signed(&g.h(), &(w - s), &g.n);
    let beta = signed(&(w - s), &(e - s), &g.n);
    let a2 = (e - s).norm();
    Step {
        title: "theta2 from alpha and beta".into(),
        equation: "Sect. 2.12.1, Fig. 2.31".into(),
        formula: format!(
            "alpha = the direction of W - S from z0 x z1 = {}, beta = the angle at S from W - S \
             to link a2 = {} (its sign is the elbow's): alpha + beta = {}, so theta2 = {}{}",
            deg(alpha),
            deg(beta),
            deg(wrap_angle(alpha + beta)),
            deg(a.joint[1]),
            offset_note(a.drawn[1] - a.joint[1])
        ),
        marks: vec![
            Mark::Arc {
                center: s,
                from: g.h(),
                normal: g.n,
                angle: alpha,
                radius: 0.2 * a2,
                label: format!("α = {}", deg(alpha)),
            },
            Mark::Arc {
                center: s,
                from: g.h(),
                normal: g.n,
                angle: a.drawn[1],
                radius: 0.35 * a2,
                label: format!("θ2 = {}", deg(a.joint[1])),
            },
        ],
    }
}

/// " (the DH frames put X between ...)" where the drawn angle and the joint differ by `off`.
fn offset_note(off: f64) -> String {
    let off = wrap_angle(off);
    if off.abs() > 1e-9 {
        format!(
            " (the DH frames put {} between the drawn angle and the joint)",
            deg(off)
        )
    } else {
        String::new()
    }
}

/// Degrees as a term after a minus sign: "(-18.9°)" for a negative angle.
fn term(a: f64) -> String {
    if deg(a).starts_with('-') {
        format!("({})", deg(a))
    } else {
        deg(a)
    }
}

/// theta4 = phi - theta2 - theta3 (2.90).
fn theta4_step(g: &Geometry, a: &Angles) -> Step {
    let phi = wrap_angle(a.joint[1] + a.joint[2] + a.joint[3]);
    let a3 = (g.w - g.e).norm();
    Step {
        title: "theta4 from phi".into(),
        equation: "(2.90)".into(),
        formula: format!(
            "theta4 = phi - theta2 - theta3 = {} - {} - {} = {}",
            deg(phi),
            term(a.joint[1]),
            term(a.joint[2]),
            deg(a.joint[3])
        ),
        marks: vec![Mark::Arc {
            center: g.w,
            from: (g.w - g.e).normalize(),
            normal: g.n,
            angle: a.drawn[3],
            radius: 0.3 * a3,
            label: format!("θ4 = {}", deg(a.joint[3])),
        }],
    }
}
