//! The construction behind the closed-form solution the arm is in, step by step (what the app's
//! "Show the construction" draws): each step has a title, its equation, the formula with the
//! numbers substituted, and marks to draw (world frame, m). The geometry is read at the
//! configuration q from the joint axes (the Jacobian), so the numbers shown are those of the arm
//! on screen; the steps follow Sects. 2.12.1, 2.12.2, 2.12.4 and 2.12.5.

use super::{ConstructionError, TwoLinkConstruction, WristPoint};
use crate::kinematics::Robot;
use crate::kinematics::ik::closed_form::{ArmKind, ClosedForm, Family};
use nalgebra::{Matrix3, Vector3};

/// Something a step draws (world frame, m).
#[derive(Debug, Clone, PartialEq)]
pub enum Mark {
    /// A labelled point.
    Point {
        /// Where.
        p: Vector3<f64>,
        /// Its name, e.g. "p_W".
        label: String,
    },
    /// A labelled segment.
    Segment {
        /// From.
        a: Vector3<f64>,
        /// To.
        b: Vector3<f64>,
        /// Its name (side length, vector), or empty.
        label: String,
        /// Dashed: a construction line or the posture not shown.
        dashed: bool,
    },
    /// An angle: the arc from direction `from` by `angle` about `normal` (right-hand rule).
    Arc {
        /// The vertex.
        center: Vector3<f64>,
        /// Start direction (unit).
        from: Vector3<f64>,
        /// Rotation axis (unit).
        normal: Vector3<f64>,
        /// Signed angle (rad).
        angle: f64,
        /// Radius (m).
        radius: f64,
        /// e.g. "θ2 = 45.0°".
        label: String,
    },
}

/// One step of a construction.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    /// What the step finds, e.g. "Wrist point".
    pub title: String,
    /// The equation or section it implements, e.g. "(2.93)".
    pub equation: String,
    /// The formula with the numbers substituted.
    pub formula: String,
    /// What to draw.
    pub marks: Vec<Mark>,
}

/// A joint axis: a point on it and its unit direction (world, m).
type Axis = (Vector3<f64>, Vector3<f64>);

/// Each joint axis at q.
fn axes(robot: &Robot, q: &[f64]) -> Result<Vec<Axis>, ConstructionError> {
    let pe = robot.fk(q)?.translation.vector;
    let jac = robot.jacobian(q, 0)?;
    Ok(jac
        .column_iter()
        .map(|c| {
            let w = Vector3::new(c[3], c[4], c[5]);
            let n = w.norm();
            let w = if n > 0.0 { w / n } else { w };
            (pe + w.cross(&Vector3::new(c[0], c[1], c[2])), w)
        })
        .collect())
}

/// Degrees with one decimal.
fn deg(a: f64) -> String {
    format!("{:.1}°", a.to_degrees())
}

/// The signed angle from `u` to `v` about `n` (rad).
fn signed(u: &Vector3<f64>, v: &Vector3<f64>, n: &Vector3<f64>) -> f64 {
    n.dot(&u.cross(v)).atan2(u.dot(v))
}

/// The construction of the closed-form solution at `q`, or why there is none.
pub fn construction(robot: &Robot, q: &[f64]) -> Result<Vec<Step>, ConstructionError> {
    let cf = ClosedForm::detect(robot)
        .map_err(|e| ConstructionError::NoConstruction(format!("no closed form: {e}")))?;
    match cf.family() {
        Family::Planar2 => planar(robot, q, false),
        Family::Planar3 => planar(robot, q, true),
        Family::Anthropomorphic => anthropomorphic(robot, q, None),
        Family::Decoupled6 {
            arm: ArmKind::Anthropomorphic,
        } => {
            let w = WristPoint::of(robot, q)?;
            anthropomorphic(robot, q, Some(w))
        }
        other => Err(ConstructionError::NoConstruction(format!(
            "the construction of the {} is not drawn yet (the two- and three-link planar arms \
             and the anthropomorphic arm, with or without spherical wrist, are)",
            other.name()
        ))),
    }
}

/// Sect. 2.12.1: the wrist point of the three-link arm (2.91)-(2.92), the triangle, theta2,
/// theta1 = alpha +- beta, theta3 (2.90).
fn planar(robot: &Robot, q: &[f64], three: bool) -> Result<Vec<Step>, ConstructionError> {
    let ax = axes(robot, q)?;
    let t = robot.fk(q)?;
    let (xh, yh, n) = (
        robot.base.rotation * Vector3::x(),
        robot.base.rotation * Vector3::y(),
        robot.base.rotation * Vector3::z(),
    );
    let o = ax[0].0;
    let e = ax[1].0;
    let w = if three { ax[2].0 } else { t.translation.vector };
    let to2 = |v: Vector3<f64>| [(v - o).dot(&xh), (v - o).dot(&yh)];
    let from2 = |p: [f64; 2]| o + xh * p[0] + yh * p[1];
    let (a1, a2) = ((e - o).norm(), (w - e).norm());
    let k = TwoLinkConstruction::new(a1, a2, to2(w))?;
    let e2 = to2(e);
    let shown = (0..2)
        .min_by(|&i, &j| {
            let dist = |p: [f64; 2]| (p[0] - e2[0]).hypot(p[1] - e2[1]);
            dist(k.postures[i].elbow).total_cmp(&dist(k.postures[j].elbow))
        })
        .unwrap_or(0);
    let mut steps = Vec::new();
    if three {
        let p = t.translation.vector;
        let x = t.rotation * Vector3::x();
        let phi = x.dot(&yh).atan2(x.dot(&xh));
        let a3 = (p - w).norm();
        steps.push(Step {
            title: "Wrist point W, the origin of frame 2".into(),
            equation: "(2.91), (2.92)".into(),
            formula: format!(
                "p_W = p - a3 (c_phi, s_phi) = ({:.3}, {:.3}) - {a3:.3} ({:.3}, {:.3}) = ({:.3}, \
                 {:.3}) m, phi = {}",
                to2(p)[0],
                to2(p)[1],
                phi.cos(),
                phi.sin(),
                k.p[0],
                k.p[1],
                deg(phi)
            ),
            marks: vec![
                Mark::Point {
                    p,
                    label: "p".into(),
                },
                Mark::Segment {
                    a: p,
                    b: w,
                    label: format!("a3 = {a3:.3} m"),
                    dashed: false,
                },
                Mark::Point {
                    p: w,
                    label: "W".into(),
                },
            ],
        });
    }
    let mut triangle = vec![Mark::Segment {
        a: o,
        b: w,
        label: format!("|p_W| = {:.3} m", k.distance),
        dashed: true,
    }];
    for (i, pos) in k.postures.iter().enumerate() {
        let el = from2(pos.elbow);
        triangle.push(Mark::Segment {
            a: o,
            b: el,
            label: format!("a1 ({})", pos.name),
            dashed: i != shown,
        });
        triangle.push(Mark::Segment {
            a: el,
            b: w,
            label: "a2".into(),
            dashed: i != shown,
        });
    }
    steps.push(Step {
        title: "The triangle of links a1, a2 and |p_W|: cosine theorem".into(),
        equation: "Sect. 2.12.1, Fig. 2.31".into(),
        formula: format!(
            "c2 = (|p_W|^2 - a1^2 - a2^2) / (2 a1 a2) = ({:.3}^2 - {a1:.3}^2 - {a2:.3}^2) / (2 \
             {a1:.3} {a2:.3}) = {:.4}; two triangles: elbow up and elbow down",
            k.distance, k.c2
        ),
        marks: triangle,
    });
    let pos = k.postures[shown];
    let el = from2(pos.elbow);
    steps.push(Step {
        title: format!("theta2 of the {} posture", pos.name),
        equation: "Sect. 2.12.1".into(),
        formula: format!(
            "theta2 = {}acos({:.4}) = {} (elbow up: theta2 in (-pi, 0); elbow down: (0, pi))",
            if pos.theta2 < 0.0 { "-" } else { "+" },
            k.c2,
            deg(pos.theta2)
        ),
        marks: vec![Mark::Arc {
            center: el,
            from: (el - o).normalize(),
            normal: n,
            angle: pos.theta2,
            radius: 0.3 * a2,
            label: format!("θ2 = {}", deg(pos.theta2)),
        }],
    });
    let w_dir = (w - o).normalize();
    steps.push(Step {
        title: "theta1 = alpha +- beta".into(),
        equation: "Sect. 2.12.1, Fig. 2.31".into(),
        formula: format!(
            "alpha = Atan2(p_Wy, p_Wx) = Atan2({:.3}, {:.3}) = {}; beta = acos((|p_W|^2 + a1^2 - \
             a2^2) / (2 a1 |p_W|)) = {}; theta1 = alpha {} beta = {}",
            k.p[1],
            k.p[0],
            deg(k.alpha),
            deg(k.beta),
            if pos.theta2 < 0.0 { "+" } else { "-" },
            deg(pos.theta1)
        ),
        marks: vec![
            Mark::Arc {
                center: o,
                from: xh,
                normal: n,
                angle: k.alpha,
                radius: 0.25 * a1,
                label: format!("α = {}", deg(k.alpha)),
            },
            Mark::Arc {
                center: o,
                from: w_dir,
                normal: n,
                angle: pos.theta1 - k.alpha,
                radius: 0.4 * a1,
                label: format!("β = {}", deg(k.beta)),
            },
            Mark::Arc {
                center: o,
                from: xh,
                normal: n,
                angle: pos.theta1,
                radius: 0.55 * a1,
                label: format!("θ1 = {}", deg(pos.theta1)),
            },
        ],
    });
    if three {
        let x = t.rotation * Vector3::x();
        let phi = x.dot(&yh).atan2(x.dot(&xh));
        let t3 = crate::kinematics::orientation::wrap_angle(phi - pos.theta1 - pos.theta2);
        steps.push(Step {
            title: "theta3 from the orientation".into(),
            equation: "(2.90)".into(),
            formula: format!(
                "theta3 = phi - theta1 - theta2 = {} - {} - {} = {}",
                deg(phi),
                deg(pos.theta1),
                deg(pos.theta2),
                deg(t3)
            ),
            marks: vec![Mark::Arc {
                center: w,
                from: (w - el).normalize(),
                normal: n,
                angle: t3,
                radius: 0.3 * a2,
                label: format!("θ3 = {}", deg(t3)),
            }],
        });
    }
    Ok(steps)
}

/// Sects. 2.12.2, 2.12.4, 2.12.5: the wrist point (2.93), theta1 (2.109)-(2.110), the arm plane's
/// triangle and theta3 (2.99)-(2.101), theta2 (2.105)-(2.108), the wrist's ZYZ angles
/// (2.111)-(2.112).
fn anthropomorphic(
    robot: &Robot,
    q: &[f64],
    wrist: Option<WristPoint>,
) -> Result<Vec<Step>, ConstructionError> {
    let ax = axes(robot, q)?;
    let t = robot.fk(q)?;
    let p_w = wrist.map_or(t.translation.vector, |w| w.p_w);
    let z0 = ax[0].1;
    let (s, _) = super::meet(&ax[0].0, &ax[0].1, &ax[1].0, &ax[1].1);
    let (o3, w3) = ax[2];
    let e = o3 + w3 * w3.dot(&(s - o3));
    let mut steps = Vec::new();
    if let Some(w) = wrist {
        steps.push(Step {
            title: "Wrist point: the kinematic decoupling".into(),
            equation: "(2.93)".into(),
            formula: format!(
                "p_W = p_e - d6 a_e = ({:.3}, {:.3}, {:.3}) - {:.3} ({:.3}, {:.3}, {:.3}) = \
                 ({:.3}, {:.3}, {:.3}) m",
                w.p_e.x, w.p_e.y, w.p_e.z, w.d6, w.a_e.x, w.a_e.y, w.a_e.z, p_w.x, p_w.y, p_w.z
            ),
            marks: vec![
                Mark::Point {
                    p: w.p_e,
                    label: "p_e".into(),
                },
                Mark::Segment {
                    a: w.p_e,
                    b: p_w,
                    label: format!("-d6 a_e (d6 = {:.3} m)", w.d6),
                    dashed: false,
                },
                Mark::Point {
                    p: p_w,
                    label: "p_W".into(),
                },
            ],
        });
    }
    // theta1: the horizontal direction of p_W in the base frame.
    let base = robot.base.rotation;
    let (x0, y0) = (base * Vector3::x(), base * Vector3::y());
    let foot = s + z0 * z0.dot(&(p_w - s));
    let horizontal = p_w - foot;
    let r = horizontal.norm();
    let (pwx, pwy) = (horizontal.dot(&x0), horizontal.dot(&y0));
    let theta1 = pwy.atan2(pwx);
    let twin = (-pwy).atan2(-pwx);
    let scale = robot.characteristic_length();
    steps.push(Step {
        title: "theta1: the vertical plane through p_W (shoulder right), or the opposite one \
                (shoulder left)"
            .into(),
        equation: "(2.109), (2.110)".into(),
        formula: format!(
            "theta1 = Atan2(p_Wy, p_Wx) = Atan2({pwy:.3}, {pwx:.3}) = {}, or Atan2(-p_Wy, -p_Wx) \
             = {}; undefined where p_Wx = p_Wy = 0",
            deg(theta1),
            deg(twin)
        ),
        marks: vec![
            Mark::Segment {
                a: foot,
                b: p_w,
                label: format!("horizontal distance {r:.3} m"),
                dashed: true,
            },
            Mark::Segment {
                a: foot,
                b: foot - horizontal,
                label: "shoulder left: theta1 + pi".into(),
                dashed: true,
            },
            Mark::Arc {
                center: foot,
                from: x0,
                normal: z0,
                angle: theta1,
                radius: 0.2 * scale,
                label: format!("θ1 = {}", deg(theta1)),
            },
        ],
    });
    let (a2, a3, d) = ((e - s).norm(), (p_w - e).norm(), (p_w - s).norm());
    let c3 = (d * d - a2 * a2 - a3 * a3) / (2.0 * a2 * a3);
    // The other elbow: E reflected across the line S-W in the arm plane.
    let u = (p_w - s) / d;
    let e_rel = e - s;
    let e_other = s + u * (2.0 * u.dot(&e_rel)) - e_rel;
    let theta3 = signed(&(e - s), &(p_w - e), &w3);
    // The drawn angles are geometric; the joint values differ from them by the constant the
    // DH table puts between them (the forearm along z3 in Table 2.7 turns theta3 by pi/2).
    let (off2, off3) = geometric_offsets(robot, wrist.is_some())?;
    steps.push(Step {
        title: "The triangle in the arm plane: c3, and the two elbows".into(),
        equation: "(2.99)-(2.101)".into(),
        formula: format!(
            "c3 = (|p_W - S|^2 - a2^2 - a3^2) / (2 a2 a3) = ({d:.3}^2 - {a2:.3}^2 - {a3:.3}^2) / \
             (2 {a2:.3} {a3:.3}) = {c3:.4}; the angle between the links +-acos(c3) = {}, so \
             theta3 = {}{} (elbow up / down)",
            deg(theta3),
            deg(theta3 - off3),
            if off3.abs() > 1e-9 {
                format!(" (the DH frames put {} between them)", deg(off3))
            } else {
                String::new()
            }
        ),
        marks: vec![
            Mark::Segment {
                a: s,
                b: e,
                label: format!("a2 = {a2:.3} m"),
                dashed: false,
            },
            Mark::Segment {
                a: e,
                b: p_w,
                label: format!("a3 = {a3:.3} m"),
                dashed: false,
            },
            Mark::Segment {
                a: s,
                b: p_w,
                label: format!("{d:.3} m"),
                dashed: true,
            },
            Mark::Segment {
                a: s,
                b: e_other,
                label: "the other elbow".into(),
                dashed: true,
            },
            Mark::Segment {
                a: e_other,
                b: p_w,
                label: String::new(),
                dashed: true,
            },
            Mark::Arc {
                center: e,
                from: (e - s).normalize(),
                normal: w3,
                angle: theta3,
                radius: 0.25 * a3,
                label: format!("θ3 = {}", deg(theta3 - off3)),
            },
        ],
    });
    let w2 = ax[1].1;
    let level = (horizontal / r.max(1e-12))
        * if theta1_is_twin(q[0], theta1) {
            -1.0
        } else {
            1.0
        };
    let theta2 = signed(&level, &(e - s), &w2);
    steps.push(Step {
        title: "theta2 from the triangle".into(),
        equation: "(2.105)-(2.108)".into(),
        formula: format!(
            "theta2 = Atan2((a2 + a3 c3) p_Wz -+ a3 s3 sqrt(p_Wx^2 + p_Wy^2), ...) = {}",
            deg(theta2 - off2)
        ),
        marks: vec![Mark::Arc {
            center: s,
            from: level,
            normal: w2,
            angle: theta2,
            radius: 0.3 * a2,
            label: format!("θ2 = {}", deg(theta2 - off2)),
        }],
    });
    if wrist.is_some() {
        steps.push(wrist_step(robot, q, &t.rotation.into_inner(), p_w, scale)?);
    }
    Ok(steps)
}

/// The geometric angles of link 2 (from the horizontal) and between links 2 and 3 at q = 0:
/// the constants between the drawn angles and the joint values.
fn geometric_offsets(robot: &Robot, wrist: bool) -> Result<(f64, f64), ConstructionError> {
    let q0 = vec![0.0; robot.dof()];
    let ax = axes(robot, &q0)?;
    let p_w = if wrist {
        WristPoint::of(robot, &q0)?.p_w
    } else {
        robot.fk(&q0)?.translation.vector
    };
    let (s, _) = super::meet(&ax[0].0, &ax[0].1, &ax[1].0, &ax[1].1);
    let (o3, w3) = ax[2];
    let e = o3 + w3 * w3.dot(&(s - o3));
    let z0 = ax[0].1;
    let h = {
        let v = (e - s) - z0 * z0.dot(&(e - s));
        let x = robot.base.rotation * Vector3::x();
        if v.norm() > 1e-9 { v.normalize() } else { x }
    };
    Ok((
        signed(&h, &(e - s), &ax[1].1),
        signed(&(e - s), &(p_w - e), &w3),
    ))
}

/// Whether the arm's theta1 (`q1`) is the pi-shifted twin of `theta1` (shoulder left).
fn theta1_is_twin(q1: f64, theta1: f64) -> bool {
    crate::kinematics::orientation::wrap_angle(q1 - theta1).abs() > std::f64::consts::FRAC_PI_2
}

/// Sect. 2.12.5: R_6^3 = (R_3^0)^T R_e and its ZYZ angles (2.111) or (2.112).
fn wrist_step(
    robot: &Robot,
    q: &[f64],
    r_e: &Matrix3<f64>,
    p_w: Vector3<f64>,
    scale: f64,
) -> Result<Step, ConstructionError> {
    let frames = robot.fk_frames(q)?;
    let r3 = frames[2].rotation.into_inner();
    let r63 = r3.transpose() * r_e;
    let (n, s, a) = (r63.column(0), r63.column(1), r63.column(2));
    let sin5 = a.x.hypot(a.y);
    let flip = q[4].sin() < 0.0;
    let sg = if flip { -1.0 } else { 1.0 };
    let t4 = (sg * a.y).atan2(sg * a.x);
    let t5 = (sg * sin5).atan2(a.z);
    let t6 = (sg * s.z).atan2(-sg * n.z);
    let singular = sin5 < 1e-9;
    let formula = if singular {
        format!(
            "theta5 = 0: axes 4 and 6 are aligned, so only theta4 + theta6 = {} is determined; \
             theta4 is kept where it was and theta6 follows",
            deg(s.x.atan2(n.x))
        )
    } else {
        format!(
            "a^3 = ({:.3}, {:.3}, {:.3}); theta4 = Atan2({}a_y, {}a_x) = {}, theta5 = \
             Atan2({}sqrt(a_x^2 + a_y^2), a_z) = {}, theta6 = Atan2({}s_z, {}n_z) = {} ({})",
            a.x,
            a.y,
            a.z,
            if flip { "-" } else { "" },
            if flip { "-" } else { "" },
            deg(t4),
            if flip { "-" } else { "" },
            deg(t5),
            if flip { "-" } else { "" },
            if flip { "" } else { "-" },
            deg(t6),
            if flip {
                "wrist flip, theta5 in (-pi, 0): (2.112)"
            } else {
                "wrist no flip, theta5 in (0, pi): (2.111)"
            }
        )
    };
    let z3 = r3 * Vector3::z();
    let a_e = r_e * Vector3::z();
    let len = 0.25 * scale;
    Ok(Step {
        title: "The spherical wrist: R_6^3 = (R_3^0)^T R_e as ZYZ Euler angles".into(),
        equation: if flip { "(2.112)" } else { "(2.111)" }.into(),
        formula,
        marks: vec![
            Mark::Segment {
                a: p_w,
                b: p_w + z3 * len,
                label: "z3".into(),
                dashed: true,
            },
            Mark::Segment {
                a: p_w,
                b: p_w + a_e * len,
                label: "a_e".into(),
                dashed: false,
            },
            Mark::Arc {
                center: p_w,
                from: z3,
                normal: {
                    let c = z3.cross(&a_e);
                    if c.norm() > 1e-12 {
                        c.normalize()
                    } else {
                        r3 * Vector3::y()
                    }
                },
                angle: z3.angle(&a_e),
                radius: 0.6 * len,
                label: format!("θ5 = {}", deg(t5)),
            },
        ],
    })
}
