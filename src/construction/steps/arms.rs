//! The constructions of the arms with a prismatic joint and of the wrist alone: the spherical arm
//! (Sect. 2.12.3, the Stanford manipulator with its wrist), the cylindrical arm (Problem 2.19),
//! the SCARA manipulator (Problem 2.20) and the spherical wrist (Sect. 2.12.5). As for the other
//! families, every drawn quantity is read from the arm's frames at q, and every formula is printed
//! with the numbers of the arm on screen.

use super::{
    Mark, Plane, Step, deg, planar_theta1, planar_theta2, planar_triangle, signed,
    wrist_point_step, wrist_step, wrist_steps,
};
use crate::construction::{ConstructionError, TwoLinkConstruction, WristPoint};
use crate::kinematics::orientation::wrap_angle;
use crate::kinematics::{Pose, Robot};
use nalgebra::Vector3;

/// A frame's origin and its x and z axes (world).
#[derive(Debug, Clone, Copy)]
struct Frame {
    o: Vector3<f64>,
    x: Vector3<f64>,
    z: Vector3<f64>,
}

impl Frame {
    fn of(pose: &Pose) -> Self {
        Self {
            o: pose.translation.vector,
            x: pose.rotation * Vector3::x(),
            z: pose.rotation * Vector3::z(),
        }
    }
}

/// The base frame and the frames of joints 1..=3 at q, and the point the arm positions (the
/// wrist point of a six-joint arm, the tool point of a three-joint one).
struct ArmFrames {
    base: Frame,
    f: [Frame; 3],
    p_w: Vector3<f64>,
}

impl ArmFrames {
    fn at(robot: &Robot, q: &[f64], wrist: bool) -> Result<Self, ConstructionError> {
        let frames = robot.fk_frames(q)?;
        let p_w = if wrist {
            WristPoint::of(robot, q)?.p_w
        } else {
            robot.fk(q)?.translation.vector
        };
        Ok(Self {
            base: Frame::of(&robot.base),
            f: [
                Frame::of(&frames[0]),
                Frame::of(&frames[1]),
                Frame::of(&frames[2]),
            ],
            p_w,
        })
    }

    /// p_W in the base frame (m): the textbook's (p_Wx, p_Wy, p_Wz).
    fn p_base(&self, robot: &Robot) -> Vector3<f64> {
        robot
            .base
            .inverse_transform_vector(&(self.p_w - self.base.o))
    }
}

/// The three quantities a positioning arm's construction draws (rad or m), at q or at q = 0.
type Drawn = [f64; 3];

/// The drawn quantities at q = 0: the constants between what is drawn and the joint values
/// (zero for the textbook's tables).
fn offsets(
    robot: &Robot,
    wrist: bool,
    drawn: fn(&ArmFrames) -> Drawn,
) -> Result<Drawn, ConstructionError> {
    Ok(drawn(&ArmFrames::at(
        robot,
        &vec![0.0; robot.dof()],
        wrist,
    )?))
}

/// A labelled straight mark.
fn seg(a: Vector3<f64>, b: Vector3<f64>, label: String, dashed: bool) -> Mark {
    Mark::Segment {
        a,
        b,
        label,
        dashed,
    }
}

/// Spherical arm: theta1 = angle x0 -> x1 about z0, theta2 = angle z0 -> z2 about z1, d3 = the
/// extension from frame 2's origin to p_W along z2.
fn spherical_drawn(g: &ArmFrames) -> Drawn {
    let [_, f2, _] = g.f;
    [
        signed(&g.base.x, &g.f[0].x, &g.base.z),
        signed(&g.base.z, &f2.z, &g.f[0].z),
        (g.p_w - f2.o).dot(&f2.z),
    ]
}

/// Sect. 2.12.3: theta1 from the third row of (2.94), d3, theta2; with a spherical wrist, the
/// wrist point (2.93) first and the wrist's ZYZ angles last (the Stanford manipulator).
pub(super) fn spherical(
    robot: &Robot,
    q: &[f64],
    wrist: Option<WristPoint>,
) -> Result<Vec<Step>, ConstructionError> {
    let g = ArmFrames::at(robot, q, wrist.is_some())?;
    let off = offsets(robot, wrist.is_some(), spherical_drawn)?;
    let drawn = spherical_drawn(&g);
    let label = |k: usize| drawn[k] - off[k];
    let p = g.p_base(robot);
    let [f1, f2, _] = g.f;
    // The lateral offset d2: p_W's z coordinate in frame 1, the third row of (2.94).
    let d2 = (g.p_w - f1.o).dot(&f1.z);
    let mut steps = Vec::new();
    if let Some(w) = &wrist {
        steps.push(wrist_point_step(w));
    }
    let (t1, t2) = (label(0), label(1));
    let scale = robot.characteristic_length();
    steps.push(spherical_theta1(&g, p, d2, [drawn[0], t1], scale));
    let (a, b) = (
        p.x * t1.cos() + p.y * t1.sin(),
        (g.p_w - g.base.o).dot(&g.base.z),
    );
    steps.push(Step {
        title: "d3: the distance from the shoulder to p_W".into(),
        equation: "(2.94), Sect. 2.12.3".into(),
        formula: format!(
            "d3 = sqrt((p_Wx c1 + p_Wy s1)^2 + p_Wz^2) = sqrt({a:.3}^2 + {b:.3}^2) = {:.3} m (d3 \
             >= 0; the same d3 serves both theta1)",
            label(2)
        ),
        marks: vec![
            seg(f1.o, f2.o, format!("d2 = {d2:.3} m"), true),
            seg(f2.o, g.p_w, format!("d3 = {:.3} m", label(2)), false),
            Mark::Point {
                p: g.p_w,
                label: "p_W".into(),
            },
        ],
    });
    steps.push(Step {
        title: "theta2: the direction of the prismatic axis".into(),
        equation: "Sect. 2.12.3".into(),
        formula: if label(2).abs() < 1e-9 * scale {
            "d3 = 0: p_W is on axis 2, so theta2 is not determined".into()
        } else {
            format!(
                "theta2 = Atan2(p_Wx c1 + p_Wy s1, p_Wz) = Atan2({a:.3}, {b:.3}) = {}",
                deg(t2)
            )
        },
        marks: vec![Mark::Arc {
            center: f2.o,
            from: g.base.z,
            normal: f1.z,
            angle: drawn[1],
            radius: 0.25 * label(2).abs().max(0.2 * scale),
            label: format!("θ2 = {}", deg(t2)),
        }],
    });
    wrist_steps(robot, q, wrist.as_ref(), &mut steps)?;
    Ok(steps)
}

/// theta1 of the spherical arm from the third row of (2.94), both roots; `[drawn, t1]` are the
/// drawn angle and the joint value (rad).
fn spherical_theta1(
    g: &ArmFrames,
    p: Vector3<f64>,
    d2: f64,
    [drawn, t1]: [f64; 2],
    scale: f64,
) -> Step {
    let f1 = g.f[0];
    let root = |sign: f64| {
        2.0 * (-p.x + sign * (p.x * p.x + p.y * p.y - d2 * d2).max(0.0).sqrt()).atan2(d2 + p.y)
    };
    let foot = g.base.o + g.base.z * g.base.z.dot(&(g.p_w - g.base.o));
    let corner = foot + f1.z * d2;
    Step {
        title: "theta1: the lateral offset d2 fixes the vertical plane of the arm".into(),
        equation: "(2.94), Sect. 2.12.3".into(),
        formula: format!(
            "-p_Wx s1 + p_Wy c1 = d2 = {d2:.3} m; with t = tan(theta1/2): theta1 = 2 Atan2(-p_Wx \
             +- sqrt(p_Wx^2 + p_Wy^2 - d2^2), d2 + p_Wy) = 2 Atan2({:.3} +- {:.3}, {:.3}) = {} \
             or {}; the arm is at theta1 = {}",
            -p.x,
            (p.x * p.x + p.y * p.y - d2 * d2).max(0.0).sqrt(),
            d2 + p.y,
            deg(wrap_angle(root(1.0))),
            deg(wrap_angle(root(-1.0))),
            deg(t1)
        ),
        marks: vec![
            seg(
                foot,
                g.p_w,
                format!("sqrt(p_Wx^2 + p_Wy^2) = {:.3} m", p.x.hypot(p.y)),
                true,
            ),
            seg(foot, corner, format!("d2 = {d2:.3} m"), false),
            seg(corner, g.p_w, String::new(), true),
            Mark::Arc {
                center: foot,
                from: g.base.x,
                normal: g.base.z,
                angle: drawn,
                radius: 0.2 * scale,
                label: format!("θ1 = {}", deg(t1)),
            },
        ],
    }
}

/// Cylindrical arm: theta1 = angle x0 -> the horizontal arm about z0, d2 = the rise along z1
/// from frame 1's origin, d3 = the extension from frame 2's origin to p_W along z2.
fn cylindrical_drawn(g: &ArmFrames) -> Drawn {
    let [f1, f2, _] = g.f;
    let arm = f2.z - g.base.z * g.base.z.dot(&f2.z);
    [
        signed(&g.base.x, &arm, &g.base.z),
        (f2.o - f1.o).dot(&f1.z),
        (g.p_w - f2.o).dot(&f2.z),
    ]
}

/// Problem 2.19: d2 from the height, theta1 from the horizontal direction, d3 from the horizontal
/// distance; with a spherical wrist, the wrist point first and the wrist last.
pub(super) fn cylindrical(
    robot: &Robot,
    q: &[f64],
    wrist: Option<WristPoint>,
) -> Result<Vec<Step>, ConstructionError> {
    let g = ArmFrames::at(robot, q, wrist.is_some())?;
    let off = offsets(robot, wrist.is_some(), cylindrical_drawn)?;
    let drawn = cylindrical_drawn(&g);
    let label = |k: usize| drawn[k] - off[k];
    let p = g.p_base(robot);
    let [f1, f2, _] = g.f;
    let d1 = (f1.o - g.base.o).dot(&g.base.z);
    let mut steps = Vec::new();
    if let Some(w) = &wrist {
        steps.push(wrist_point_step(w));
    }
    steps.push(Step {
        title: "d2 from the height of p_W".into(),
        equation: "Problem 2.19".into(),
        formula: format!("d2 = p_Wz - d1 = {:.3} - {d1:.3} = {:.3} m", p.z, label(1)),
        marks: vec![
            seg(g.base.o, f1.o, format!("d1 = {d1:.3} m"), true),
            seg(f1.o, f2.o, format!("d2 = {:.3} m", label(1)), false),
        ],
    });
    let scale = robot.characteristic_length();
    steps.push(Step {
        title: "theta1: the vertical plane through p_W".into(),
        equation: "Problem 2.19".into(),
        formula: format!(
            "theta1 = Atan2(p_Wy, p_Wx) = Atan2({:.3}, {:.3}) = {}",
            p.y,
            p.x,
            deg(label(0))
        ),
        marks: vec![Mark::Arc {
            center: f2.o,
            from: g.base.x,
            normal: g.base.z,
            angle: drawn[0],
            radius: 0.2 * scale,
            label: format!("θ1 = {}", deg(label(0))),
        }],
    });
    steps.push(Step {
        title: "d3: the horizontal distance to p_W".into(),
        equation: "Problem 2.19".into(),
        formula: format!(
            "d3 = sqrt(p_Wx^2 + p_Wy^2) = sqrt({:.3}^2 + {:.3}^2) = {:.3} m",
            p.x,
            p.y,
            label(2)
        ),
        marks: vec![
            seg(f2.o, g.p_w, format!("d3 = {:.3} m", label(2)), false),
            Mark::Point {
                p: g.p_w,
                label: "p_W".into(),
            },
        ],
    });
    wrist_steps(robot, q, wrist.as_ref(), &mut steps)?;
    Ok(steps)
}

/// The displacements along the three prismatic axes of a Cartesian arm (m): frame i's origin
/// from frame i - 1's, along z_(i-1).
fn cartesian_drawn(g: &ArmFrames) -> Drawn {
    let [f1, f2, f3] = g.f;
    [
        (f1.o - g.base.o).dot(&g.base.z),
        (f2.o - f1.o).dot(&f1.z),
        (f3.o - f2.o).dot(&f2.z),
    ]
}

/// The Cartesian (gantry) arm: every rotation is constant, so `p_W = c + d1 z0 + d2 z1 + d3 z2`
/// with c the point at d = 0, a 3 x 3 linear system; each d drawn along its axis. With a
/// spherical wrist, the wrist point first and the wrist last.
pub(super) fn cartesian(
    robot: &Robot,
    q: &[f64],
    wrist: Option<WristPoint>,
) -> Result<Vec<Step>, ConstructionError> {
    let g = ArmFrames::at(robot, q, wrist.is_some())?;
    let off = offsets(robot, wrist.is_some(), cartesian_drawn)?;
    let drawn = cartesian_drawn(&g);
    let label = |k: usize| drawn[k] - off[k];
    let p = g.p_base(robot);
    let [f1, f2, f3] = g.f;
    let mut steps = Vec::new();
    if let Some(w) = &wrist {
        steps.push(wrist_point_step(w));
    }
    steps.push(Step {
        title: "d1, d2, d3: p_W along the three fixed prismatic axes".into(),
        equation: "a linear system: no rotation depends on the joints".into(),
        formula: format!(
            "p_W = c + d1 z0 + d2 z1 + d3 z2 = ({:.3}, {:.3}, {:.3}) m: d1 = {:.3} m, d2 = {:.3} \
             m, d3 = {:.3} m",
            p.x,
            p.y,
            p.z,
            label(0),
            label(1),
            label(2)
        ),
        marks: vec![
            seg(g.base.o, f1.o, format!("d1 = {:.3} m", label(0)), false),
            seg(f1.o, f2.o, format!("d2 = {:.3} m", label(1)), false),
            seg(f2.o, f3.o, format!("d3 = {:.3} m", label(2)), false),
            Mark::Point {
                p: g.p_w,
                label: "p_W".into(),
            },
        ],
    });
    wrist_steps(robot, q, wrist.as_ref(), &mut steps)?;
    Ok(steps)
}

/// Problem 2.20: theta1 and theta2 by the two-link triangle in the horizontal plane of the links
/// (Sect. 2.12.1), d3 from the height, theta4 from the rotation about the vertical.
pub(super) fn scara(robot: &Robot, q: &[f64]) -> Result<Vec<Step>, ConstructionError> {
    let frames = robot.fk_frames(q)?;
    let t = robot.fk(q)?;
    let base = Frame::of(&robot.base);
    let [f1, f2, f3, f4] = [0, 1, 2, 3].map(|k| Frame::of(&frames[k]));
    // The links' plane: the height of frame 1; axis 1, the elbow (axis 2) and axis 3 in it.
    let o = base.o + base.z * base.z.dot(&(f1.o - base.o));
    let (e, w) = (f1.o, f2.o);
    let (xh, yh) = (
        robot.base.rotation * Vector3::x(),
        robot.base.rotation * Vector3::y(),
    );
    let to2 = |v: Vector3<f64>| [(v - o).dot(&xh), (v - o).dot(&yh)];
    let k = TwoLinkConstruction::new((e - o).norm(), (w - e).norm(), to2(w))?;
    let e2 = to2(e);
    let dist = |p: [f64; 2]| (p[0] - e2[0]).hypot(p[1] - e2[1]);
    let shown = usize::from(dist(k.postures[1].elbow) < dist(k.postures[0].elbow));
    let plane = Plane {
        o,
        w,
        xh,
        yh,
        n: base.z,
        k,
        shown,
    };
    let mut steps = vec![
        planar_triangle(&plane),
        planar_theta2(&plane),
        planar_theta1(&plane),
    ];
    let p = t.translation.vector;
    let (d1, d4) = ((f2.o - base.o).dot(&base.z), (p - f3.o).dot(&f3.z));
    let off = offsets_scara(robot)?;
    let d3 = (f3.o - f2.o).dot(&f2.z) - off[0];
    let pz = (p - base.o).dot(&base.z);
    steps.push(Step {
        title: "d3 from the height of the tool".into(),
        equation: "Problem 2.20".into(),
        formula: format!(
            "the prismatic axis points {}: d3 = d1 - d4 - p_z = {d1:.3} - {d4:.3} - {pz:.3} = \
             {d3:.3} m",
            if f2.z.dot(&base.z) < 0.0 {
                "down"
            } else {
                "up (the signs turn)"
            }
        ),
        marks: vec![
            seg(f2.o, f3.o, format!("d3 = {d3:.3} m"), false),
            seg(f3.o, p, format!("d4 = {d4:.3} m"), true),
        ],
    });
    steps.push(scara_theta4(robot, &plane, (f3, f4), &t, off[1]));
    Ok(steps)
}

/// The SCARA's drawn d3 and theta4 at q = 0.
fn offsets_scara(robot: &Robot) -> Result<[f64; 2], ConstructionError> {
    let frames = robot.fk_frames(&vec![0.0; robot.dof()])?;
    let [f2, f3, f4] = [1, 2, 3].map(|k| Frame::of(&frames[k]));
    Ok([(f3.o - f2.o).dot(&f2.z), signed(&f3.x, &f4.x, &f3.z)])
}

/// theta4 = theta1 + theta2 - phi (the prismatic axis down) from the tool's rotation phi about
/// the vertical; `off4` is the drawn angle at q = 0 (rad).
fn scara_theta4(
    robot: &Robot,
    plane: &Plane,
    (f3, f4): (Frame, Frame),
    t: &Pose,
    off4: f64,
) -> Step {
    let pos = plane.k.postures[plane.shown];
    let n_e = t.rotation * Vector3::x();
    let phi = n_e.dot(&plane.yh).atan2(n_e.dot(&plane.xh));
    let drawn = signed(&f3.x, &f4.x, &f3.z);
    let t4 = wrap_angle(drawn - off4);
    let down = f3.z.dot(&plane.n) < 0.0;
    let formula = if down {
        format!(
            "phi = {}; theta4 = theta1 + theta2 - phi = {} + {} - {} = {}",
            deg(phi),
            deg(pos.theta1),
            deg(pos.theta2),
            deg(phi),
            deg(t4)
        )
    } else {
        format!(
            "phi = {}; theta4 = phi - theta1 - theta2 = {}",
            deg(phi),
            deg(t4)
        )
    };
    Step {
        title: "theta4 from the rotation about the vertical".into(),
        equation: "Problem 2.20".into(),
        formula,
        marks: vec![Mark::Arc {
            center: t.translation.vector,
            from: f3.x,
            normal: f3.z,
            angle: drawn,
            radius: 0.1 * robot.characteristic_length(),
            label: format!("θ4 = {}", deg(t4)),
        }],
    }
}

/// Sect. 2.12.5 for the wrist alone: R_6^3 is the tool's rotation in the base frame.
pub(super) fn wrist_alone(robot: &Robot, q: &[f64]) -> Result<Vec<Step>, ConstructionError> {
    let t = robot.fk(q)?;
    let r3 = robot.base.rotation.into_inner();
    let frames = robot.fk_frames(q)?;
    let p_w = frames[0].translation.vector;
    let mut step = wrist_step(
        &r3,
        &frames[0].rotation.into_inner(),
        &t.rotation.into_inner(),
        p_w,
        q[1],
        robot.characteristic_length(),
    );
    step.marks.push(Mark::Point {
        p: p_w,
        label: "W".into(),
    });
    Ok(vec![step])
}
