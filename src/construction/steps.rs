//! The construction behind the closed-form solution the arm is in, step by step (what the app's
//! "Show the construction" draws): each step has a title, its equation, the formula with the
//! numbers substituted, and marks to draw (world frame, m). The geometry is read at the
//! configuration q from the joint axes (the Jacobian), so the numbers shown are those of the arm
//! on screen; the steps follow Sects. 2.12.1, 2.12.2, 2.12.4 and 2.12.5.

mod arms;
mod parallel3;

use super::{ConstructionError, TwoLinkConstruction, WristPoint};
use crate::kinematics::Robot;
use crate::kinematics::dh::Convention;
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
    let mut steps = family_steps(robot, q)?;
    for step in &mut steps {
        no_negative_zero(&mut step.title);
        no_negative_zero(&mut step.formula);
        for mark in &mut step.marks {
            match mark {
                Mark::Point { label, .. }
                | Mark::Segment { label, .. }
                | Mark::Arc { label, .. } => no_negative_zero(label),
            }
        }
    }
    Ok(steps)
}

/// "-0.000" (a rounded -1e-17) written as "0.000", wherever it appears in `text`.
fn no_negative_zero(text: &mut String) {
    let mut out = String::with_capacity(text.len());
    let mut rest = text.as_str();
    while let Some(pos) = rest.find("-0") {
        out.push_str(&rest[..pos]);
        // The number after the sign: digits and points.
        let after = &rest[pos + 1..];
        let end = after
            .find(|c: char| !(c.is_ascii_digit() || c == '.'))
            .unwrap_or(after.len());
        let number = &after[..end];
        // A sign, not a subtraction: nothing that ends an operand just before it.
        let is_sign = !out
            .chars()
            .next_back()
            .is_some_and(|c| c.is_alphanumeric() || c == ')' || c == ']');
        if !(is_sign && number.chars().all(|c| c == '0' || c == '.')) {
            out.push('-');
        }
        out.push_str(number);
        rest = &after[end..];
    }
    out.push_str(rest);
    *text = out;
}

/// The steps of the arm's family.
fn family_steps(robot: &Robot, q: &[f64]) -> Result<Vec<Step>, ConstructionError> {
    let cf = ClosedForm::detect(robot)?;
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
        Family::SphericalArm => arms::spherical(robot, q, None),
        Family::Decoupled6 {
            arm: ArmKind::Spherical,
        } => arms::spherical(robot, q, Some(WristPoint::of(robot, q)?)),
        Family::Cylindrical => arms::cylindrical(robot, q, None),
        Family::Decoupled6 {
            arm: ArmKind::Cylindrical,
        } => arms::cylindrical(robot, q, Some(WristPoint::of(robot, q)?)),
        Family::Cartesian => arms::cartesian(robot, q, None),
        Family::Decoupled6 {
            arm: ArmKind::Cartesian,
        } => arms::cartesian(robot, q, Some(WristPoint::of(robot, q)?)),
        Family::Scara => arms::scara(robot, q),
        Family::SphericalWrist => arms::wrist_alone(robot, q),
        Family::ThreeParallel => parallel3::steps(robot, q),
        Family::General6
        | Family::ThreeParallelGeneral
        | Family::Reversed6 { .. }
        | Family::Decoupled6 {
            arm: ArmKind::General3R,
        } => Err(ConstructionError::NotDrawn { family: cf.name() }),
    }
}

/// The plane geometry of a planar arm at q (world, m).
struct Plane {
    /// Shoulder (axis 1), elbow (axis 2), wrist point W (axis 3, or the tip of a two-link arm).
    o: Vector3<f64>,
    w: Vector3<f64>,
    /// The base frame's x, y and the plane normal z.
    xh: Vector3<f64>,
    yh: Vector3<f64>,
    n: Vector3<f64>,
    k: TwoLinkConstruction,
    /// The posture the arm is in (index into `k.postures`).
    shown: usize,
}

impl Plane {
    fn from2(&self, p: [f64; 2]) -> Vector3<f64> {
        self.o + self.xh * p[0] + self.yh * p[1]
    }

    /// The end-effector's orientation phi in the plane (rad).
    fn phi(&self, t: &crate::kinematics::Pose) -> f64 {
        let x = t.rotation * Vector3::x();
        x.dot(&self.yh).atan2(x.dot(&self.xh))
    }
}

/// Sect. 2.12.1: the wrist point of the three-link arm (2.91)-(2.92), the triangle, theta2,
/// theta1 = alpha +- beta, theta3 (2.90).
fn planar(robot: &Robot, q: &[f64], three: bool) -> Result<Vec<Step>, ConstructionError> {
    let ax = axes(robot, q)?;
    let t = robot.fk(q)?;
    let r = robot.base.rotation;
    let (o, e) = (ax[0].0, ax[1].0);
    let w = if three { ax[2].0 } else { t.translation.vector };
    let (xh, yh) = (r * Vector3::x(), r * Vector3::y());
    let to2 = |v: Vector3<f64>| [(v - o).dot(&xh), (v - o).dot(&yh)];
    let k = TwoLinkConstruction::new((e - o).norm(), (w - e).norm(), to2(w))?;
    let e2 = to2(e);
    let dist = |p: [f64; 2]| (p[0] - e2[0]).hypot(p[1] - e2[1]);
    let shown = usize::from(dist(k.postures[1].elbow) < dist(k.postures[0].elbow));
    let g = Plane {
        o,
        w,
        xh,
        yh,
        n: r * Vector3::z(),
        k,
        shown,
    };
    let mut steps = Vec::new();
    if three {
        steps.push(planar_wrist(&g, &t));
    }
    steps.push(planar_triangle(&g));
    steps.push(planar_theta2(&g));
    steps.push(planar_theta1(&g));
    if three {
        steps.push(planar_theta3(&g, &t));
    }
    Ok(steps)
}

/// (2.91)-(2.92): W = p - a3 (c_phi, s_phi).
fn planar_wrist(g: &Plane, t: &crate::kinematics::Pose) -> Step {
    let p = t.translation.vector;
    let phi = g.phi(t);
    let a3 = (p - g.w).norm();
    let p2 = [(p - g.o).dot(&g.xh), (p - g.o).dot(&g.yh)];
    Step {
        title: "Wrist point W, the origin of frame 2".into(),
        equation: "(2.91), (2.92)".into(),
        formula: format!(
            "p_W = p - a3 (c_phi, s_phi) = ({:.3}, {:.3}) - {a3:.3} ({:.3}, {:.3}) = ({:.3}, \
             {:.3}) m, phi = {}",
            p2[0],
            p2[1],
            phi.cos(),
            phi.sin(),
            g.k.p[0],
            g.k.p[1],
            deg(phi)
        ),
        marks: vec![
            Mark::Point {
                p,
                label: "p".into(),
            },
            Mark::Segment {
                a: p,
                b: g.w,
                label: format!("a3 = {a3:.3} m"),
                dashed: false,
            },
            Mark::Point {
                p: g.w,
                label: "W".into(),
            },
        ],
    }
}

/// The triangle of a1, a2 and |p_W| by the cosine theorem, both postures.
fn planar_triangle(g: &Plane) -> Step {
    let k = &g.k;
    let mut marks = vec![Mark::Segment {
        a: g.o,
        b: g.w,
        label: format!("|p_W| = {:.3} m", k.distance),
        dashed: true,
    }];
    for (i, pos) in k.postures.iter().enumerate() {
        let el = g.from2(pos.elbow);
        marks.push(Mark::Segment {
            a: g.o,
            b: el,
            label: format!("a1 ({})", pos.name),
            dashed: i != g.shown,
        });
        marks.push(Mark::Segment {
            a: el,
            b: g.w,
            label: "a2".into(),
            dashed: i != g.shown,
        });
    }
    Step {
        title: "The triangle of links a1, a2 and |p_W|: cosine theorem".into(),
        equation: "Sect. 2.12.1, Fig. 2.31".into(),
        formula: format!(
            "c2 = (|p_W|^2 - a1^2 - a2^2) / (2 a1 a2) = ({:.3}^2 - {:.3}^2 - {:.3}^2) / (2 {:.3} \
             {:.3}) = {:.4}; two triangles: elbow up and elbow down",
            k.distance,
            k.a1,
            k.a2,
            k.a1,
            k.a2,
            k.c2 + 0.0
        ),
        marks,
    }
}

/// theta2 = +-acos(c2) of the posture shown.
fn planar_theta2(g: &Plane) -> Step {
    let pos = g.k.postures[g.shown];
    let el = g.from2(pos.elbow);
    Step {
        title: format!("theta2 of the {} posture", pos.name),
        equation: "Sect. 2.12.1".into(),
        formula: format!(
            "theta2 = {}acos({:.4}) = {} (elbow up: theta2 in (-pi, 0); elbow down: (0, pi))",
            if pos.theta2 < 0.0 { "-" } else { "+" },
            g.k.c2,
            deg(pos.theta2)
        ),
        marks: vec![Mark::Arc {
            center: el,
            from: (el - g.o).normalize(),
            normal: g.n,
            angle: pos.theta2,
            radius: 0.3 * g.k.a2,
            label: format!("θ2 = {}", deg(pos.theta2)),
        }],
    }
}

/// theta1 = alpha +- beta (Fig. 2.31).
fn planar_theta1(g: &Plane) -> Step {
    let (k, pos) = (&g.k, g.k.postures[g.shown]);
    let arc = |from, angle, radius, label| Mark::Arc {
        center: g.o,
        from,
        normal: g.n,
        angle,
        radius,
        label,
    };
    Step {
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
            arc(g.xh, k.alpha, 0.25 * k.a1, format!("α = {}", deg(k.alpha))),
            arc(
                (g.w - g.o).normalize(),
                pos.theta1 - k.alpha,
                0.4 * k.a1,
                format!("β = {}", deg(k.beta)),
            ),
            arc(
                g.xh,
                pos.theta1,
                0.55 * k.a1,
                format!("θ1 = {}", deg(pos.theta1)),
            ),
        ],
    }
}

/// theta3 = phi - theta1 - theta2 (2.90).
fn planar_theta3(g: &Plane, t: &crate::kinematics::Pose) -> Step {
    let pos = g.k.postures[g.shown];
    let el = g.from2(pos.elbow);
    let phi = g.phi(t);
    let t3 = crate::kinematics::orientation::wrap_angle(phi - pos.theta1 - pos.theta2);
    Step {
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
            center: g.w,
            from: (g.w - el).normalize(),
            normal: g.n,
            angle: t3,
            radius: 0.3 * g.k.a2,
            label: format!("θ3 = {}", deg(t3)),
        }],
    }
}

/// The arm geometry of an anthropomorphic arm at q (world, m).
struct ArmGeometry {
    /// Shoulder S and elbow E in the plane of links 2 and 3 (axes 1 and 2 meet at S; a lateral
    /// shoulder offset such as the Puma's moves both along axis 2 into that plane), wrist point.
    s: Vector3<f64>,
    e: Vector3<f64>,
    p_w: Vector3<f64>,
    /// Axes 1, 2, 3 (unit) and frame 1's x axis (horizontal).
    z0: Vector3<f64>,
    w2: Vector3<f64>,
    w3: Vector3<f64>,
    x1: Vector3<f64>,
    /// The point of axis 1 level with p_W, and p_W's horizontal offset from it.
    foot: Vector3<f64>,
    horizontal: Vector3<f64>,
    /// The lateral offset of p_W from the plane through S normal to axis 2 (m; 0 for the
    /// textbook's arms, the Puma's d3).
    h: f64,
    /// The drawn theta1, theta2, theta3 at q = 0: the constants between them and the joints.
    off: [f64; 3],
    /// p_W's horizontal components in the base frame.
    pw_xy: (f64, f64),
    /// What the DH table calls the lengths |E - S| and |p_W - E| ("a2"; "a3", "d4" or
    /// "sqrt(a3^2 + d4^2)" for an elbow offset such as the Puma's).
    names: [String; 2],
}

impl ArmGeometry {
    /// The geometry at q; `off` is zero when `at_zero`, else the drawn angles at q = 0.
    fn at(robot: &Robot, q: &[f64], wrist: bool, at_zero: bool) -> Result<Self, ConstructionError> {
        let ax = axes(robot, q)?;
        let p_w = if wrist {
            WristPoint::of(robot, q)?.p_w
        } else {
            robot.fk(q)?.translation.vector
        };
        let (s, _) = super::meet(&ax[0].0, &ax[0].1, &ax[1].0, &ax[1].1);
        let (o3, w3) = ax[2];
        let (z0, w2) = (ax[0].1, ax[1].1);
        let h = w2.dot(&(p_w - s));
        let foot = s + z0 * z0.dot(&(p_w - s));
        let b = robot.base.rotation;
        let mut g = ArmGeometry {
            s: s + w2 * h,
            e: o3 + w3 * w3.dot(&(s - o3)) + w2 * h,
            p_w,
            z0,
            w2,
            w3,
            x1: robot.fk_frames(q)?[0].rotation * Vector3::x(),
            foot,
            horizontal: p_w - foot,
            h,
            off: [0.0; 3],
            pw_xy: (
                (p_w - foot).dot(&(b * Vector3::x())),
                (p_w - foot).dot(&(b * Vector3::y())),
            ),
            names: link_names(robot, wrist),
        };
        if !at_zero {
            let zero = Self::at(robot, &vec![0.0; robot.dof()], wrist, true)?;
            g.off = zero.drawn(robot.base.rotation * Vector3::x());
        }
        Ok(g)
    }

    /// The drawn theta1 (x0 to x1 about axis 1), theta2 (x1 to link 2 about axis 2) and theta3
    /// (link 2 to link 3 about axis 3) (rad).
    fn drawn(&self, x0: Vector3<f64>) -> [f64; 3] {
        [
            signed(&x0, &self.x1, &self.z0),
            signed(&self.x1, &(self.e - self.s), &self.w2),
            signed(&(self.e - self.s), &(self.p_w - self.e), &self.w3),
        ]
    }
}

/// The DH table's names for the upper arm |E - S| and the forearm |p_W - E| of an
/// anthropomorphic arm (standard DH: a2; a3 and, with a wrist, d4); the forearm named by the
/// parameters that make it, "sqrt(a3^2 + d4^2)" when both do. Generic names where the table is
/// in another convention.
fn link_names(robot: &Robot, wrist: bool) -> [String; 2] {
    let generic = ["|E - S|".to_string(), "|p_W - E|".to_string()];
    let Some((Convention::Standard, rows)) = robot.dh_table() else {
        return generic;
    };
    let (Some(r3), r4) = (rows.get(2), rows.get(3)) else {
        return generic;
    };
    let mut parts = vec![("a3", r3.1.a)];
    if wrist && let Some(r4) = r4 {
        parts.push(("d4", r4.1.d));
    }
    let named: Vec<&str> = parts
        .iter()
        .filter(|(_, v)| v.abs() > 1e-12)
        .map(|(n, _)| *n)
        .collect();
    let forearm = match named.as_slice() {
        [one] => (*one).to_string(),
        [] => generic[1].clone(),
        many => format!(
            "sqrt({})",
            many.iter()
                .map(|n| format!("{n}^2"))
                .collect::<Vec<_>>()
                .join(" + ")
        ),
    };
    ["a2".to_string(), forearm]
}

/// Sects. 2.12.2, 2.12.4, 2.12.5: the wrist point (2.93), theta1 (2.109)-(2.110), the arm plane's
/// triangle and theta3 (2.99)-(2.101), theta2 (2.105)-(2.108), the wrist's ZYZ angles
/// (2.111)-(2.112).
fn anthropomorphic(
    robot: &Robot,
    q: &[f64],
    wrist: Option<WristPoint>,
) -> Result<Vec<Step>, ConstructionError> {
    let g = ArmGeometry::at(robot, q, wrist.is_some(), false)?;
    let scale = robot.characteristic_length();
    let mut steps = Vec::new();
    if let Some(w) = wrist {
        steps.push(wrist_point_step(&w));
    }
    steps.push(arm_theta1(&g, robot.base.rotation * Vector3::x(), scale));
    steps.push(arm_triangle(&g));
    steps.push(arm_theta2(&g));
    wrist_steps(robot, q, wrist.as_ref(), &mut steps)?;
    Ok(steps)
}

/// The wrist step of a six-joint arm with spherical wrist (joints 4-6), if it has one.
fn wrist_steps(
    robot: &Robot,
    q: &[f64],
    wrist: Option<&WristPoint>,
    steps: &mut Vec<Step>,
) -> Result<(), ConstructionError> {
    if let Some(w) = wrist {
        let frames = robot.fk_frames(q)?;
        let (r3, r4) = (
            frames[2].rotation.into_inner(),
            frames[3].rotation.into_inner(),
        );
        let r_e = robot.fk(q)?.rotation.into_inner();
        let scale = robot.characteristic_length();
        steps.push(wrist_step(&r3, &r4, &r_e, w.p_w, q[4], scale));
    }
    Ok(())
}

/// (2.93): p_W = p_e - d6 a_e.
fn wrist_point_step(w: &WristPoint) -> Step {
    let p_w = w.p_w;
    Step {
        title: "Wrist point: the kinematic decoupling".into(),
        equation: "(2.93)".into(),
        formula: format!(
            "p_W = p_e - d6 a_e = ({:.3}, {:.3}, {:.3}) - {:.3} ({:.3}, {:.3}, {:.3}) = ({:.3}, \
             {:.3}, {:.3}) m",
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
    }
}

/// theta1 (2.109) and its twin (2.110): the vertical plane through p_W; with a lateral shoulder
/// offset h, the plane of the links passes h beside axis 1 and theta1 turns by Atan2(h, R).
fn arm_theta1(g: &ArmGeometry, x0: Vector3<f64>, scale: f64) -> Step {
    let (pwx, pwy) = g.pw_xy;
    let drawn = signed(&x0, &g.x1, &g.z0);
    let label = format!("θ1 = {}", deg(drawn - g.off[0]));
    let arc = Mark::Arc {
        center: g.foot,
        from: x0,
        normal: g.z0,
        angle: drawn,
        radius: 0.2 * scale,
        label,
    };
    if g.h.abs() > 1e-9 * scale {
        return arm_theta1_offset(g, drawn, arc);
    }
    let theta1 = pwy.atan2(pwx);
    let twin = (-pwy).atan2(-pwx);
    Step {
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
                a: g.foot,
                b: g.p_w,
                label: format!("horizontal distance {:.3} m", g.horizontal.norm()),
                dashed: true,
            },
            Mark::Segment {
                a: g.foot,
                b: g.foot - g.horizontal,
                label: "shoulder left: theta1 + pi".into(),
                dashed: true,
            },
            arc,
        ],
    }
}

/// theta1 with a lateral shoulder offset (the Puma's d3): the right triangle of R and h in the
/// horizontal plane.
fn arm_theta1_offset(g: &ArmGeometry, drawn: f64, arc: Mark) -> Step {
    let (pwx, pwy) = g.pw_xy;
    // p_W - foot = r x1 + h' (z0 x x1): the right triangle in the horizontal plane.
    let r = g.x1.dot(&g.horizontal);
    let side = g.z0.cross(&g.x1);
    let h = side.dot(&g.horizontal);
    let corner = g.foot + g.x1 * r;
    Step {
        title: "theta1: the plane of the links passes the shoulder offset beside axis 1 \
                (shoulder right or left)"
            .into(),
        equation: "(2.109), (2.110) with a shoulder offset".into(),
        formula: format!(
            "R = +-sqrt(p_Wx^2 + p_Wy^2 - h^2) = {r:.3} m (h = {h:.3} m); theta1 = \
             Atan2(p_Wy, p_Wx) - Atan2(h, R) = {} - {} = {}",
            deg(pwy.atan2(pwx)),
            deg(h.atan2(r)),
            deg(drawn - g.off[0])
        ),
        marks: vec![
            Mark::Segment {
                a: g.foot,
                b: g.p_w,
                label: format!("horizontal distance {:.3} m", g.horizontal.norm()),
                dashed: true,
            },
            Mark::Segment {
                a: g.foot,
                b: corner,
                label: format!("R = {r:.3} m"),
                dashed: false,
            },
            Mark::Segment {
                a: corner,
                b: g.p_w,
                label: format!("h = {h:.3} m"),
                dashed: false,
            },
            arc,
        ],
    }
}

/// The triangle S, E, p_W in the arm plane: c3 (2.99), theta3 (2.100)-(2.101), the other elbow.
fn arm_triangle(g: &ArmGeometry) -> Step {
    let (s, e, p_w) = (g.s, g.e, g.p_w);
    let (a2, a3, d) = ((e - s).norm(), (p_w - e).norm(), (p_w - s).norm());
    let c3 = (d * d - a2 * a2 - a3 * a3) / (2.0 * a2 * a3);
    // The other elbow: E reflected across the line S-W in the arm plane.
    let u = (p_w - s) / d;
    let e_other = s + u * (2.0 * u.dot(&(e - s))) - (e - s);
    let theta3 = signed(&(e - s), &(p_w - e), &g.w3);
    let off3 = g.off[2];
    // The forearm by its DH name; one letter in the formula where it is a root of two.
    let (f, with) = if g.names[1].starts_with("sqrt") {
        ("L3", format!(" with L3 = {}", g.names[1]))
    } else {
        (g.names[1].as_str(), String::new())
    };
    let seg = |a, b, label: String, dashed| Mark::Segment {
        a,
        b,
        label,
        dashed,
    };
    Step {
        title: "The triangle in the arm plane: c3, and the two elbows".into(),
        equation: "(2.99)-(2.101)".into(),
        formula: format!(
            "c3 = (|p_W - S|^2 - a2^2 - {f}^2) / (2 a2 {f}){with} = ({d:.3}^2 - {a2:.3}^2 - \
             {a3:.3}^2) / (2 {a2:.3} {a3:.3}) = {c3:.4}; the angle between the links +-acos(c3) \
             = {}, so theta3 = {}{} (elbow up / down)",
            deg(theta3),
            deg(theta3 - off3),
            if off3.abs() > 1e-9 {
                format!(" (the DH frames put {} between them)", deg(off3))
            } else {
                String::new()
            }
        ),
        marks: vec![
            seg(s, e, format!("{} = {a2:.3} m", g.names[0]), false),
            seg(e, p_w, format!("{} = {a3:.3} m", g.names[1]), false),
            seg(s, p_w, format!("{d:.3} m"), true),
            seg(s, e_other, "the other elbow".into(), true),
            seg(e_other, p_w, String::new(), true),
            Mark::Arc {
                center: e,
                from: (e - s).normalize(),
                normal: g.w3,
                angle: theta3,
                radius: 0.25 * a3,
                label: format!("θ3 = {}", deg(theta3 - off3)),
            },
        ],
    }
}

/// theta2 (2.105)-(2.108): link 2 from the horizontal of the arm plane (frame 1's x axis).
fn arm_theta2(g: &ArmGeometry) -> Step {
    let theta2 = signed(&g.x1, &(g.e - g.s), &g.w2);
    let a2 = (g.e - g.s).norm();
    Step {
        title: "theta2 from the triangle".into(),
        equation: "(2.105)-(2.108)".into(),
        formula: format!(
            "theta2 = Atan2((a2 + a3 c3) p_Wz -+ a3 s3 sqrt(p_Wx^2 + p_Wy^2), ...) = {}",
            deg(theta2 - g.off[1])
        ),
        marks: vec![Mark::Arc {
            center: g.s,
            from: g.x1,
            normal: g.w2,
            angle: theta2,
            radius: 0.3 * a2,
            label: format!("θ2 = {}", deg(theta2 - g.off[1])),
        }],
    }
}

/// The wrist step's formula: the ZYZ angles with the numbers, or what is free at theta5 = 0.
fn wrist_formula(
    a: &Vector3<f64>,
    nx: f64,
    sx: f64,
    (t4, t5, t6): (f64, f64, f64),
    flip: bool,
    singular: bool,
) -> String {
    if singular {
        return format!(
            "theta5 = 0: axes 4 and 6 are aligned, so only theta4 + theta6 = {} is determined; \
             theta4 is kept where it was and theta6 follows",
            deg(sx.atan2(nx))
        );
    }
    let m = if flip { "-" } else { "" };
    format!(
        "a^3 = ({:.3}, {:.3}, {:.3}); theta4 = Atan2({m}a_y, {m}a_x) = {}, theta5 = \
         Atan2({m}sqrt(a_x^2 + a_y^2), a_z) = {}, theta6 = Atan2({m}s_z, {}n_z) = {} ({})",
        a.x,
        a.y,
        a.z,
        deg(t4),
        deg(t5),
        if flip { "" } else { "-" },
        deg(t6),
        if flip {
            "wrist flip, theta5 in (-pi, 0): (2.112)"
        } else {
            "wrist no flip, theta5 in (0, pi): (2.111)"
        }
    )
}

/// Sect. 2.12.5: R_6^3 = (R_3^0)^T R_e and its ZYZ angles (2.111) or (2.112); `r3` and `r4`
/// are the rotations of frames 3 and 4 (world), `theta5` the wrist's middle joint value (rad).
/// The wrist of Table 2.5 (alpha4 = -pi/2, alpha5 = pi/2) turns by Ry(theta5) between its
/// z rotations; one with the twists reversed (the Puma 560's) by Ry(-theta5), read from the
/// frames as sigma = -sin(alpha4), so theta5 = sigma times the Euler angle.
fn wrist_step(
    r3: &Matrix3<f64>,
    r4: &Matrix3<f64>,
    r_e: &Matrix3<f64>,
    p_w: Vector3<f64>,
    theta5: f64,
    scale: f64,
) -> Step {
    let r63 = r3.transpose() * r_e;
    let (n, s, a) = (r63.column(0), r63.column(1), r63.column(2));
    let sin_alpha4 = (r3 * Vector3::z())
        .cross(&(r4 * Vector3::z()))
        .dot(&(r4 * Vector3::x()));
    let sigma = if sin_alpha4 > 0.0 { -1.0 } else { 1.0 };
    let sin5 = a.x.hypot(a.y);
    let flip = sigma * theta5.sin() < 0.0;
    let sg = if flip { -1.0 } else { 1.0 };
    let t4 = (sg * a.y).atan2(sg * a.x);
    let t5 = sigma * (sg * sin5).atan2(a.z);
    let t6 = (sg * s.z).atan2(-sg * n.z);
    let mut formula = wrist_formula(
        &a.into_owned(),
        n.x,
        s.x,
        (t4, sigma * t5, t6),
        flip,
        sin5 < 1e-9,
    );
    if sigma < 0.0 {
        formula.push_str(
            "; this wrist's twists are Table 2.5's reversed, R_6^3 = Rz(theta4) Ry(-theta5) \
             Rz(theta6), so theta5 is minus that Euler angle",
        );
    }
    let z3 = r3 * Vector3::z();
    let a_e = r_e * Vector3::z();
    let len = 0.25 * scale;
    let mut step = Step {
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
    };
    if sin5 >= 1e-9 {
        step.marks.extend(wrist_arcs(r3, r_e, p_w, (t4, t6), len));
    }
    step
}

/// theta4 about z3 from x3 (2.111)/(2.112), and theta6 about a_e ending at n_e.
fn wrist_arcs(
    r3: &Matrix3<f64>,
    r_e: &Matrix3<f64>,
    p_w: Vector3<f64>,
    (t4, t6): (f64, f64),
    len: f64,
) -> [Mark; 2] {
    let a_e = r_e * Vector3::z();
    [
        Mark::Arc {
            center: p_w,
            from: r3 * Vector3::x(),
            normal: r3 * Vector3::z(),
            angle: t4,
            radius: 0.4 * len,
            label: format!("θ4 = {}", deg(t4)),
        },
        Mark::Arc {
            center: p_w + a_e * len,
            from: r_e * Vector3::new(t6.cos(), -t6.sin(), 0.0),
            normal: a_e,
            angle: t6,
            radius: 0.3 * len,
            label: format!("θ6 = {}", deg(t6)),
        },
    ]
}

#[cfg(test)]
mod tests {
    #[test]
    fn negative_zero_loses_its_sign_and_nothing_else_does() {
        let mut t = "d6 = -0.000 m, -0.0004 m, -0.5°, (-0.0, 3-0.000) x-0".to_string();
        super::no_negative_zero(&mut t);
        assert_eq!(t, "d6 = 0.000 m, -0.0004 m, -0.5°, (0.0, 3-0.000) x-0");
    }
}
