//! Built-in models: the arms of chapter 2 of Siciliano et al., in SI units, each citing its
//! section, plus three industrial arms whose parameters come from the Robotics Toolbox.
//!
//! Where the excerpt gives no numbers, realistic ones were chosen; each model's description says
//! which. Every model has the configurations "zero" and "ready"; most have "figure" (the pose
//! drawn in the textbook figure, approximately where the figure shows no angles).

use super::dh::{Convention, DhRow};
use super::pose::{Pose, rot_x, rot_z, trans_x, trans_y, trans_z};
use super::robot::{DhJoint, Drive, EndEffector, Joint, JointGeometry, JointKind, Robot};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_3, FRAC_PI_4, FRAC_PI_6, PI};

/// Name of the robot used when none is given: the anthropomorphic arm with spherical wrist.
pub const DEFAULT_MODEL: &str = "anthropomorphic_spherical_wrist";

/// One catalogue entry: the CLI name, a one-line summary, and the constructor.
pub struct BuiltIn {
    /// Name accepted wherever a model is named.
    pub name: &'static str,
    /// One line for `armlab robots`.
    pub summary: &'static str,
    /// Builds the robot.
    pub build: fn() -> Robot,
}

/// Every built-in model, in the order of the textbook.
pub const BUILT_INS: &[BuiltIn] = &[
    BuiltIn {
        name: "planar2",
        summary: "two-link planar arm, a1 = a2 = 1 m (Sect. 2.12.1, Figs 2.29-2.31)",
        build: planar2,
    },
    BuiltIn {
        name: "planar2_fig2_30",
        summary: "two-link planar arm with the joint limits of Figs 2.29-2.30, so that point H exists (Sect. 2.10.1, Example 2.6)",
        build: planar2_fig2_30,
    },
    BuiltIn {
        name: "planar3",
        summary: "three-link planar arm of Problem 2.17, a = 0.5, 0.3, 0.2 m (Sect. 2.9.1, Fig. 2.20)",
        build: planar3,
    },
    BuiltIn {
        name: "planar4",
        summary: "four-link planar arm, a = 0.35, 0.3, 0.2, 0.15 m: intrinsically redundant for (x, y, phi) (Sect. 2.10.2)",
        build: planar4,
    },
    BuiltIn {
        name: "parallelogram",
        summary: "parallelogram arm, closed chain opened at joint 4 (Sect. 2.9.2, Fig. 2.21)",
        build: parallelogram,
    },
    BuiltIn {
        name: "slider_chain",
        summary: "four-link closed-chain planar arm with a prismatic joint, links 2' and 3' orthogonal (Problem 2.11, Fig. 2.34)",
        build: slider_chain,
    },
    BuiltIn {
        name: "spherical_arm",
        summary: "spherical arm R-R-P, d2 = 0.5 m (Sect. 2.9.3, Fig. 2.22)",
        build: spherical_arm,
    },
    BuiltIn {
        name: "anthropomorphic3r",
        summary: "anthropomorphic arm 3R, a2 = a3 = 1 m (Sect. 2.9.4, Fig. 2.23)",
        build: anthropomorphic3r,
    },
    BuiltIn {
        name: "spherical_wrist",
        summary: "spherical wrist, d6 = 0.1 m (Sect. 2.9.5, Fig. 2.24)",
        build: spherical_wrist,
    },
    BuiltIn {
        name: "stanford",
        summary: "Stanford manipulator: spherical arm + spherical wrist (Sect. 2.9.6, Fig. 2.25)",
        build: stanford,
    },
    BuiltIn {
        name: "anthropomorphic_spherical_wrist",
        summary: "anthropomorphic arm with spherical wrist, a2 = d4 = 0.5 m (Sect. 2.9.7, Fig. 2.26); the default",
        build: anthropomorphic_spherical_wrist,
    },
    BuiltIn {
        name: "dlr",
        summary: "DLR 7-DOF lightweight arm (Sect. 2.9.8, Fig. 2.27)",
        build: dlr,
    },
    BuiltIn {
        name: "humanoid",
        summary: "humanoid: 3-DOF torso with coupled chest joint and two DLR arms, 17 DOF (Sect. 2.9.9, Fig. 2.28)",
        build: humanoid,
    },
    BuiltIn {
        name: "scara",
        summary: "SCARA manipulator R-R-P-R (Problem 2.13, Fig. 2.36)",
        build: scara,
    },
    BuiltIn {
        name: "cylindrical",
        summary: "cylindrical arm R-P-P (Problem 2.12, Fig. 2.35)",
        build: cylindrical,
    },
    BuiltIn {
        name: "puma560",
        summary: "Unimation Puma 560: shoulder offset and spherical wrist (Robotics Toolbox parameters)",
        build: puma560,
    },
    BuiltIn {
        name: "lwr4",
        summary: "KUKA LWR-IV, 7-DOF industrial arm, standard DH (Robotics Toolbox parameters)",
        build: lwr4,
    },
    BuiltIn {
        name: "panda",
        summary: "Franka Emika Panda, 7-DOF industrial arm, modified DH (Robotics Toolbox parameters)",
        build: panda,
    },
];

/// Builds the built-in model called `name`, if there is one.
///
/// # Examples
///
/// ```
/// use armlab::kinematics::models::{BUILT_INS, built_in};
///
/// let scara = built_in("scara").expect("a built-in model");
/// assert_eq!(scara.dof(), 4);
/// assert!(built_in("no such arm").is_none());
/// // The catalogue, as `armlab robots` lists it.
/// for b in BUILT_INS {
///     let robot = (b.build)();
///     assert!(robot.dof() >= 2, "{}", b.name);
///     println!("{:<32} {} DOF  {}", b.name, robot.dof(), b.summary);
/// }
/// ```
pub fn built_in(name: &str) -> Option<Robot> {
    BUILT_INS
        .iter()
        .find(|b| b.name == name)
        .map(|b| (b.build)())
}

const R: JointKind = JointKind::Revolute;
const P: JointKind = JointKind::Prismatic;
const FULL: [f64; 2] = [-PI, PI];

type Row = DhJoint;

/// A row in the column order of the textbook's tables: a, alpha, d, theta, then the limits.
fn row(kind: JointKind, a: f64, alpha: f64, d: f64, theta: f64, [lo, hi]: [f64; 2]) -> Row {
    DhJoint::new(kind, DhRow { a, alpha, d, theta }).limits(lo, hi)
}

fn serial(name: &str, conv: Convention, rows: &[Row], tool: Pose, description: &str) -> Robot {
    match Robot::from_dh(name, conv, rows, Pose::identity(), tool) {
        Ok(r) => r.with_description(description),
        // The tables below are constants checked by the test suite.
        Err(e) => unreachable!("built-in model {name} is invalid: {e}"),
    }
}

fn deg(v: f64) -> f64 {
    v.to_radians()
}

/// The two-link arm of Example 2.6 as drawn in Figs 2.29-2.30 (Sect. 2.10.1), a1 = a2 = 1 m. The
/// excerpt gives no numbers; the limits -pi/2 <= q1 <= pi/2, -3pi/4 <= q2 <= pi/2 are chosen so
/// that the figures have every point the text names: with q2M < |q2m| the arc FD (q1 = q1M) cuts
/// the arc BC (q2 = q2M) at H = (1, 1) m, the outer contour is CDAEFHC and the region reached
/// with both postures is BADHB. The same arm as `assets/robots/example_2_6.toml`.
pub fn planar2_fig2_30() -> Robot {
    serial(
        "Two-link planar arm of Example 2.6",
        Convention::Standard,
        &[
            row(R, 1.0, 0.0, 0.0, 0.0, [-FRAC_PI_2, FRAC_PI_2]),
            row(R, 1.0, 0.0, 0.0, 0.0, [-3.0 * PI / 4.0, FRAC_PI_2]),
        ],
        Pose::identity(),
        "Two-link planar arm of Example 2.6 as drawn in Figs 2.29-2.30, a1 = a2 = 1 m, joint limits -pi/2 <= q1 <= pi/2, -3pi/4 <= q2 <= pi/2 (chosen so that point H exists).",
    )
    .with_config("ready", vec![FRAC_PI_4, FRAC_PI_4])
    .with_config("figure", vec![FRAC_PI_6, FRAC_PI_3])
}

/// Two-link planar arm, a1 = a2 = 1 m, joints within [-pi, pi] (Sect. 2.12.1, Figs 2.29–2.31).
pub fn planar2() -> Robot {
    serial(
        "Two-link planar arm",
        Convention::Standard,
        &[row(R, 1.0, 0.0, 0.0, 0.0, FULL), row(R, 1.0, 0.0, 0.0, 0.0, FULL)],
        Pose::identity(),
        "Two-link planar arm of Sect. 2.12.1 (Figs 2.29-2.31), a1 = a2 = 1 m, joint limits [-pi, pi].",
    )
    .with_config("ready", vec![FRAC_PI_4, FRAC_PI_2])
    .with_config("figure", vec![FRAC_PI_6, FRAC_PI_3])
}

/// Three-link planar arm with the data of Problem 2.17 (Table 2.1, Fig. 2.20).
pub fn planar3() -> Robot {
    serial(
        "Three-link planar arm",
        Convention::Standard,
        &[
            row(R, 0.5, 0.0, 0.0, 0.0, [-FRAC_PI_3, FRAC_PI_3]),
            row(R, 0.3, 0.0, 0.0, 0.0, [-2.0 * FRAC_PI_3, 2.0 * FRAC_PI_3]),
            row(R, 0.2, 0.0, 0.0, 0.0, [-FRAC_PI_2, FRAC_PI_2]),
        ],
        Pose::identity(),
        "Three-link planar arm (Table 2.1, Fig. 2.20) with the data of Problem 2.17: a = 0.5, 0.3, 0.2 m, \
         -pi/3 <= q1 <= pi/3, -2pi/3 <= q2 <= 2pi/3, -pi/2 <= q3 <= pi/2. Direct kinematics (2.63), x_e of (2.83).",
    )
    .with_config("ready", vec![FRAC_PI_6, FRAC_PI_3, -FRAC_PI_6])
    .with_config("figure", vec![FRAC_PI_6, FRAC_PI_4, FRAC_PI_4])
}

/// Four-link planar arm: the excerpt's example of intrinsic redundancy (Sect. 2.10.2, n = 4,
/// m = 3). Chosen numbers: a = 0.35, 0.3, 0.2, 0.15 m (1 m in all), every joint within
/// [-pi, pi].
pub fn planar4() -> Robot {
    serial(
        "Four-link planar arm",
        Convention::Standard,
        &[
            row(R, 0.35, 0.0, 0.0, 0.0, FULL),
            row(R, 0.3, 0.0, 0.0, 0.0, FULL),
            row(R, 0.2, 0.0, 0.0, 0.0, FULL),
            row(R, 0.15, 0.0, 0.0, 0.0, FULL),
        ],
        Pose::identity(),
        "Four-link planar arm (Sect. 2.10.2): intrinsically redundant for the planar task (x, y, phi), \
         n = 4, m = 3; a = 0.35, 0.3, 0.2, 0.15 m, joint limits [-pi, pi].",
    )
    .with_config("ready", vec![FRAC_PI_6, FRAC_PI_4, FRAC_PI_4, -FRAC_PI_6])
}

/// Parallelogram arm (Table 2.2, Fig. 2.21): the closed chain is opened at joint 4 and the
/// constraint is kept by couplings, theta2' = q1'' - q1' and theta3' = pi - theta2' (2.64).
///
/// Chosen numbers: crank a1' = a3' = 0.2 m, upper arm a1'' = a2' = 0.6 m, forearm extension
/// a4 = 0.5 m. Independent joints: q1' (crank) and q1'' (upper arm).
pub fn parallelogram() -> Robot {
    let (a1p, a1pp, a4) = (0.2, 0.6, 0.5);
    let dh = |a: f64| JointGeometry::Dh {
        row: DhRow {
            a,
            alpha: 0.0,
            d: 0.0,
            theta: 0.0,
        },
        convention: Convention::Standard,
    };
    let joints = vec![
        Joint {
            name: "q1'".into(),
            kind: R,
            parent: None,
            pre: Pose::identity(),
            geometry: dh(a1p),
            offset: 0.0,
            drive: Drive::Actuated(0),
            limits: [FRAC_PI_2, 3.0 * FRAC_PI_2],
        },
        Joint {
            name: "q1''".into(),
            kind: R,
            parent: None,
            pre: Pose::identity(),
            geometry: dh(a1pp),
            offset: 0.0,
            drive: Drive::Actuated(1),
            limits: [FRAC_PI_6, 5.0 * FRAC_PI_6],
        },
        Joint {
            name: "q2'".into(),
            kind: R,
            parent: Some(0),
            pre: Pose::identity(),
            geometry: dh(a1pp),
            offset: 0.0,
            drive: Drive::Coupled(vec![(1, 1.0), (0, -1.0)]),
            limits: FULL,
        },
        Joint {
            name: "q3'".into(),
            kind: R,
            parent: Some(2),
            pre: Pose::identity(),
            geometry: dh(a1p),
            offset: PI,
            drive: Drive::Coupled(vec![(0, 1.0), (1, -1.0)]),
            limits: FULL,
        },
    ];
    // T_4^3' of (2.64): frame 4 at the far end of the extension, x flipped.
    let ee = EndEffector {
        name: "tool".into(),
        parent: 3,
        tool: trans_x(a4) * rot_z(PI),
    };
    let r = Robot::new("Parallelogram arm", Pose::identity(), joints, vec![ee])
        .unwrap_or_else(|e| unreachable!("parallelogram: {e}"));
    r.with_description(
        "Parallelogram arm (Sect. 2.9.2, Table 2.2, Fig. 2.21): closed chain opened at joint 4, with \
         theta2' = q1'' - q1' and theta3' = pi - theta2' as couplings. Chosen lengths: a1' = a3' = 0.2 m, \
         a2' = a1'' = 0.6 m, a4 = 0.5 m. The parallelogram is singular where links 1' and 2' align.",
    )
    .with_config("ready", vec![PI, FRAC_PI_4])
    .with_config("figure", vec![5.0 * FRAC_PI_6, FRAC_PI_3])
}

/// The joints of [`slider_chain`]: crank and arm at the base, the revolute joint at the
/// crank's end and the prismatic joint along link 2', the last two driven by the loop.
fn slider_joints(mechanism: super::closure::SliderLoop) -> Vec<Joint> {
    use super::closure::{Closure, LoopOutput};
    let (a1p, a1pp) = (mechanism.a_crank, mechanism.a_arm);
    let dh = |a: f64, alpha: f64, theta: f64| JointGeometry::Dh {
        row: DhRow {
            a,
            alpha,
            d: 0.0,
            theta,
        },
        convention: Convention::Standard,
    };
    let closure = |output| Drive::Closure(Closure { mechanism, output });
    let joint = |name: &str, kind, parent, geometry, drive, offset, limits| Joint {
        name: name.into(),
        kind,
        parent,
        pre: Pose::identity(),
        geometry,
        offset,
        drive,
        limits,
    };
    // DH frames: frame 2' has z along link 2' (theta = q2' - pi/2, alpha = -pi/2), so the
    // prismatic joint slides along it; frame 3 (theta = pi, alpha = -pi/2) has x along link 3',
    // orthogonal to link 2', and z normal to the plane again.
    vec![
        joint(
            "q1'",
            R,
            None,
            dh(a1p, 0.0, 0.0),
            Drive::Actuated(0),
            0.0,
            FULL,
        ),
        joint(
            "q1''",
            R,
            None,
            dh(a1pp, 0.0, 0.0),
            Drive::Actuated(1),
            0.0,
            [FRAC_PI_6, 5.0 * FRAC_PI_6],
        ),
        joint(
            "q2'",
            R,
            Some(0),
            dh(0.0, -FRAC_PI_2, 0.0),
            closure(LoopOutput::Angle),
            -FRAC_PI_2,
            FULL,
        ),
        joint(
            "d2'",
            P,
            Some(2),
            dh(0.0, -FRAC_PI_2, PI),
            closure(LoopOutput::Slide),
            0.0,
            [0.0, 1.0],
        ),
    ]
}

/// Problem 2.11 (Fig. 2.34): the four-link closed-chain planar arm with a prismatic joint whose
/// two links are orthogonal, opened at the joint between link 3' and the arm (as the
/// parallelogram is opened at joint 4); the passive joints follow the loop in closed form
/// ([`crate::kinematics::closure`]).
///
/// The excerpt has the problem's sentence but not its figure, so the geometry is ours, the
/// parallelogram of Fig. 2.21 with one revolute joint made prismatic: the crank 1' (a1' = 0.2 m)
/// and the arm 1'' (a1'' = 0.6 m) turn about the base axis (the independent joints, motors at the
/// base as in Sect. 2.9.2); link 2' is pinned at the crank's end A; link 3' slides along link
/// 2' (the prismatic joint d2') standing orthogonal to it, and is pinned to the arm's end C at
/// c = 0.25 m from the slider; the end-effector is on link 3', a4 = 0.35 m beyond C. The direct
/// kinematics (Problem 2.11's answer): with v = a1'' u(q1'') - a1' u(q1'),
/// d2' = sqrt(|v|^2 - c^2), phi = Atan2(v_y, v_x) - Atan2(c, d2'), the end-effector is at
/// `a1'' u(q1'') + a4 n(phi)` with its x axis along n(phi) = u(phi + pi/2), where u(t) =
/// (cos t, sin t). The loop closes for every q since a1'' - a1' = 0.4 m > c.
pub fn slider_chain() -> Robot {
    use super::closure::SliderLoop;
    let (a1p, a1pp, c, a4) = (0.2, 0.6, 0.25, 0.35);
    let mechanism = SliderLoop {
        crank: 0,
        a_crank: a1p,
        arm: 1,
        a_arm: a1pp,
        offset: c,
    };
    let joints = slider_joints(mechanism);
    // Link 3': orthogonal to link 2' at the slider, through C to the end-effector.
    let ee = EndEffector {
        name: "tool".into(),
        parent: 3,
        tool: trans_x(c + a4),
    };
    let r = Robot::new("Slider closed chain", Pose::identity(), joints, vec![ee])
        .unwrap_or_else(|e| unreachable!("slider_chain: {e}"));
    r.with_description(
        "Four-link closed-chain planar arm with a prismatic joint (Problem 2.11, Fig. 2.34), opened at \
         the joint between link 3' and the arm 1''. The excerpt has no figure, so the geometry is \
         chosen: crank a1' = 0.2 m and arm a1'' = 0.6 m about the base axis (independent joints), \
         link 2' pinned at the crank's end, link 3' sliding along it (d2') and orthogonal to it, \
         pinned to the arm's end at c = 0.25 m from the slider, end-effector a4 = 0.35 m beyond. \
         q2' and d2' follow the loop: d2' = sqrt(|v|^2 - c^2), v = a1'' u(q1'') - a1' u(q1').",
    )
    .with_config("ready", vec![0.0, FRAC_PI_2])
    .with_config("figure", vec![FRAC_PI_3, 2.0 * FRAC_PI_3])
}

/// Spherical arm R-R-P (Table 2.3, Fig. 2.22), d2 = 0.5 m, 0.25 <= d3 <= 1 m.
pub fn spherical_arm() -> Robot {
    serial(
        "Spherical arm",
        Convention::Standard,
        &[
            row(R, 0.0, -FRAC_PI_2, 0.0, 0.0, FULL),
            row(R, 0.0, FRAC_PI_2, 0.5, 0.0, FULL),
            row(P, 0.0, 0.0, 0.0, 0.0, [0.25, 1.0]),
        ],
        Pose::identity(),
        "Spherical arm (Sect. 2.9.3, Table 2.3, Fig. 2.22): d2 = 0.5 m, prismatic d3 in [0.25, 1] m. \
         Direct kinematics (2.65).",
    )
    .with_config("ready", vec![0.0, FRAC_PI_4, 0.6])
    .with_config("figure", vec![FRAC_PI_6, FRAC_PI_3, 0.8])
}

/// Anthropomorphic arm 3R (Table 2.4, Fig. 2.23), a2 = a3 = 1 m.
pub fn anthropomorphic3r() -> Robot {
    serial(
        "Anthropomorphic arm",
        Convention::Standard,
        &[
            row(R, 0.0, FRAC_PI_2, 0.0, 0.0, FULL),
            row(R, 1.0, 0.0, 0.0, 0.0, FULL),
            row(R, 1.0, 0.0, 0.0, 0.0, FULL),
        ],
        Pose::identity(),
        "Anthropomorphic arm (Sect. 2.9.4, Table 2.4, Fig. 2.23): a2 = a3 = 1 m, limits [-pi, pi]. \
         Direct kinematics (2.66).",
    )
    .with_config("ready", vec![0.0, FRAC_PI_4, -FRAC_PI_2])
    .with_config("figure", vec![FRAC_PI_6, FRAC_PI_3, -FRAC_PI_3])
}

/// Spherical wrist (Table 2.5, Fig. 2.24), d6 = 0.1 m.
pub fn spherical_wrist() -> Robot {
    let mut r = serial(
        "Spherical wrist",
        Convention::Standard,
        &[
            row(R, 0.0, -FRAC_PI_2, 0.0, 0.0, FULL),
            row(R, 0.0, FRAC_PI_2, 0.0, 0.0, FULL),
            row(R, 0.0, 0.0, 0.1, 0.0, FULL),
        ],
        Pose::identity(),
        "Spherical wrist (Sect. 2.9.5, Table 2.5, Fig. 2.24): joints 4-6 alone, d6 = 0.1 m (chosen). \
         theta4, theta5, theta6 are ZYZ Euler angles of R_6^3, (2.67).",
    );
    rename(&mut r, &["q4", "q5", "q6"]);
    r.with_config("ready", vec![0.0, FRAC_PI_2, 0.0])
        .with_config("figure", vec![FRAC_PI_6, FRAC_PI_3, FRAC_PI_4])
}

/// Stanford manipulator (Table 2.6, Fig. 2.25): spherical arm + spherical wrist.
pub fn stanford() -> Robot {
    serial(
        "Stanford manipulator",
        Convention::Standard,
        &[
            row(R, 0.0, -FRAC_PI_2, 0.0, 0.0, [deg(-170.0), deg(170.0)]),
            row(R, 0.0, FRAC_PI_2, 0.154, 0.0, [deg(-170.0), deg(170.0)]),
            row(P, 0.0, 0.0, 0.0, 0.0, [0.3, 1.0]),
            row(R, 0.0, -FRAC_PI_2, 0.0, 0.0, [deg(-170.0), deg(170.0)]),
            row(R, 0.0, FRAC_PI_2, 0.0, 0.0, [deg(-90.0), deg(90.0)]),
            row(R, 0.0, 0.0, 0.263, 0.0, [deg(-170.0), deg(170.0)]),
        ],
        Pose::identity(),
        "Stanford manipulator (Sect. 2.9.6, Table 2.6, Fig. 2.25): spherical arm with spherical wrist. \
         Chosen numbers, those of the original Stanford arm: d2 = 0.154 m, d6 = 0.263 m, d3 in [0.3, 1] m. \
         Direct kinematics (2.68).",
    )
    .with_config("ready", vec![0.0, FRAC_PI_2, 0.5, 0.0, FRAC_PI_4, 0.0])
    .with_config("figure", vec![FRAC_PI_6, FRAC_PI_3, 0.6, 0.0, FRAC_PI_4, 0.0])
}

/// Anthropomorphic arm with spherical wrist (Table 2.7, Fig. 2.26): a2 = 0.5, d4 = 0.5,
/// d6 = 0.1 m. The default robot.
pub fn anthropomorphic_spherical_wrist() -> Robot {
    serial(
        "Anthropomorphic arm with spherical wrist",
        Convention::Standard,
        &[
            row(R, 0.0, FRAC_PI_2, 0.0, 0.0, FULL),
            row(R, 0.5, 0.0, 0.0, 0.0, FULL),
            row(R, 0.0, FRAC_PI_2, 0.0, 0.0, FULL),
            row(R, 0.0, -FRAC_PI_2, 0.5, 0.0, FULL),
            row(R, 0.0, FRAC_PI_2, 0.0, 0.0, FULL),
            row(R, 0.0, 0.0, 0.1, 0.0, FULL),
        ],
        Pose::identity(),
        "Anthropomorphic arm with spherical wrist (Sect. 2.9.7, Table 2.7, Fig. 2.26): a2 = 0.5 m, \
         d4 = 0.5 m, d6 = 0.1 m (chosen), limits [-pi, pi]. Direct kinematics (2.70).",
    )
    .with_config(
        "ready",
        vec![0.0, FRAC_PI_4, FRAC_PI_4, 0.0, FRAC_PI_4, 0.0],
    )
    .with_config(
        "figure",
        vec![FRAC_PI_6, FRAC_PI_3, FRAC_PI_6, 0.0, FRAC_PI_3, 0.0],
    )
}

const DLR_ROWS: [(f64, f64); 7] = [
    (FRAC_PI_2, 0.0),
    (FRAC_PI_2, 0.0),
    (FRAC_PI_2, 0.4),
    (FRAC_PI_2, 0.0),
    (FRAC_PI_2, 0.39),
    (FRAC_PI_2, 0.0),
    (0.0, 0.078),
];
const DLR_LIMITS: [f64; 7] = [170.0, 120.0, 170.0, 120.0, 170.0, 120.0, 170.0];

fn dlr_rows() -> Vec<Row> {
    DLR_ROWS
        .iter()
        .zip(DLR_LIMITS)
        .map(|(&(alpha, d), lim)| row(R, 0.0, alpha, d, 0.0, [deg(-lim), deg(lim)]))
        .collect()
}

/// DLR 7-DOF lightweight arm (Table 2.8, Fig. 2.27).
pub fn dlr() -> Robot {
    serial(
        "DLR manipulator",
        Convention::Standard,
        &dlr_rows(),
        Pose::identity(),
        "DLR 7-DOF lightweight arm (Sect. 2.9.8, Table 2.8, Fig. 2.27): all twists pi/2 but the last. \
         Chosen numbers (LWR-III class): d3 = 0.4 m, d5 = 0.39 m, d7 = 0.078 m; limits +-170 deg on \
         joints 1, 3, 5, 7 and +-120 deg on 2, 4, 6. Direct kinematics (2.71).",
    )
    .with_config("ready", vec![0.0, FRAC_PI_4, 0.0, FRAC_PI_2, 0.0, FRAC_PI_4, 0.0])
    .with_config("figure", vec![0.0, FRAC_PI_2, 0.0, FRAC_PI_2, 0.0, FRAC_PI_2, 0.0])
}

/// Humanoid (Figs 2.27–2.28, (2.78)–(2.79)): torso = anthropomorphic arm (2.66) with a fourth
/// joint coupled as theta4 = -theta2 - theta3 so the chest stays upright; two DLR arms on it.
///
/// Chosen numbers: torso a2 = a3 = 0.25 m; shoulders 0.2 m either side of the chest frame t and
/// 0.1 m above it, arm bases tilted down by beta = 30 deg; hands d7 = 0.1 m (the excerpt does not
/// give the modified seventh row of Problem 2.14, so the DLR row is kept with a longer hand).
pub fn humanoid() -> Robot {
    let mut joints = humanoid_torso();
    let ees = add_humanoid_arms(&mut joints);
    let r = Robot::new("Humanoid", Pose::identity(), joints, ees)
        .unwrap_or_else(|e| unreachable!("humanoid: {e}"));
    let mut ready = vec![0.0; 17];
    ready[1] = FRAC_PI_2;
    for arm in [3, 10] {
        ready[arm + 1] = FRAC_PI_4;
        ready[arm + 3] = FRAC_PI_2;
    }
    let mut figure = ready.clone();
    figure[1] = deg(80.0);
    figure[2] = deg(20.0);
    r.with_description(
        "Humanoid manipulator (Sect. 2.9.9, Figs 2.27-2.28, (2.78)-(2.79)): torso = anthropomorphic arm \
         with a2 = a3 = 0.25 m plus joint 4 coupled as theta4 = -theta2 - theta3 (chest kept upright), two \
         DLR arms (Table 2.8) on shoulders 0.2 m to each side and 0.1 m up, tilted down by beta = 30 deg, \
         hands d7 = 0.1 m. All numbers chosen. 17 DOF: torso 1-3, right arm 4-10, left arm 11-17.",
    )
    .with_config("ready", ready)
    .with_config("figure", figure)
}

/// A standard DH row's geometry with theta = 0 (the joint variable adds to it).
fn dh_geometry(a: f64, alpha: f64, d: f64) -> JointGeometry {
    JointGeometry::Dh {
        row: DhRow {
            a,
            alpha,
            d,
            theta: 0.0,
        },
        convention: Convention::Standard,
    }
}

/// The humanoid's torso: an anthropomorphic arm (2.66) and a fourth joint coupled as
/// theta4 = -theta2 - theta3 (T_t^3 of Sect. 2.9.9).
fn humanoid_torso() -> Vec<Joint> {
    let joint = |name: &str, parent, geometry, drive, limits| Joint {
        name: name.into(),
        kind: R,
        parent,
        pre: Pose::identity(),
        geometry,
        offset: 0.0,
        drive,
        limits,
    };
    vec![
        joint(
            "torso1",
            None,
            dh_geometry(0.0, FRAC_PI_2, 0.0),
            Drive::Actuated(0),
            [deg(-90.0), deg(90.0)],
        ),
        joint(
            "torso2",
            Some(0),
            dh_geometry(0.25, 0.0, 0.0),
            Drive::Actuated(1),
            [deg(45.0), deg(135.0)],
        ),
        joint(
            "torso3",
            Some(1),
            dh_geometry(0.25, 0.0, 0.0),
            Drive::Actuated(2),
            [deg(-45.0), deg(45.0)],
        ),
        // Joint 4: theta4 = -theta2 - theta3, T_t^3 of Sect. 2.9.9.
        joint(
            "torso4",
            Some(2),
            dh_geometry(0.0, 0.0, 0.0),
            Drive::Coupled(vec![(1, -1.0), (2, -1.0)]),
            FULL,
        ),
    ]
}

/// Two DLR arms (Table 2.8) on the torso's chest frame t, T_r^t and T_l^t of (2.78)-(2.79), with
/// hands d7 = 0.1 m; returns their end-effectors (right, left).
fn add_humanoid_arms(joints: &mut Vec<Joint>) -> Vec<EndEffector> {
    let beta = FRAC_PI_6;
    // Frame t: x forward, y up, z to the right. T_r^t and T_l^t of (2.78)-(2.79).
    let t_from_r = trans_y(0.1) * trans_z(0.2) * rot_x(beta);
    let t_from_l = trans_y(0.1) * trans_z(-0.2) * rot_x(PI - beta);
    let mut ees = Vec::new();
    for (side, pre) in [("r", t_from_r), ("l", t_from_l)] {
        for (k, (&(alpha, d), lim)) in DLR_ROWS.iter().zip(DLR_LIMITS).enumerate() {
            let d = if k == 6 { 0.1 } else { d };
            let dof = joints
                .iter()
                .filter(|j| matches!(j.drive, Drive::Actuated(_)))
                .count();
            let parent = if k == 0 { 3 } else { joints.len() - 1 };
            joints.push(Joint {
                name: format!("{side}{}", k + 1),
                kind: R,
                parent: Some(parent),
                pre: if k == 0 { pre } else { Pose::identity() },
                geometry: dh_geometry(0.0, alpha, d),
                offset: 0.0,
                drive: Drive::Actuated(dof),
                limits: [deg(-lim), deg(lim)],
            });
        }
        let name = if side == "r" {
            "right hand"
        } else {
            "left hand"
        };
        ees.push(EndEffector {
            name: name.into(),
            parent: joints.len() - 1,
            tool: Pose::identity(),
        });
    }
    ees
}

/// SCARA manipulator R-R-P-R (Problem 2.13, Fig. 2.36).
pub fn scara() -> Robot {
    serial(
        "SCARA manipulator",
        Convention::Standard,
        &[
            row(R, 0.4, 0.0, 0.4, 0.0, [deg(-130.0), deg(130.0)]),
            row(R, 0.3, PI, 0.0, 0.0, [deg(-145.0), deg(145.0)]),
            row(P, 0.0, 0.0, 0.0, 0.0, [0.0, 0.2]),
            row(R, 0.0, 0.0, 0.1, 0.0, [-2.0 * PI, 2.0 * PI]),
        ],
        Pose::identity(),
        "SCARA manipulator (Problem 2.13, Fig. 2.36): column d1 = 0.4 m, a1 = 0.4 m, a2 = 0.3 m, \
         alpha2 = pi so the prismatic joint moves down, stroke 0-0.2 m, tool d4 = 0.1 m. Numbers chosen \
         (a typical 0.7 m-reach SCARA).",
    )
    .with_config("ready", vec![0.0, FRAC_PI_2, 0.1, 0.0])
    .with_config("figure", vec![FRAC_PI_6, FRAC_PI_3, 0.1, 0.0])
}

/// Cylindrical arm R-P-P (Problem 2.12, Fig. 2.35).
pub fn cylindrical() -> Robot {
    serial(
        "Cylindrical arm",
        Convention::Standard,
        &[
            row(R, 0.0, 0.0, 0.5, 0.0, FULL),
            row(P, 0.0, FRAC_PI_2, 0.0, FRAC_PI_2, [0.0, 0.8]),
            row(P, 0.0, 0.0, 0.0, 0.0, [0.2, 0.6]),
        ],
        Pose::identity(),
        "Cylindrical arm (Problem 2.12, Fig. 2.35): a revolute column of height 0.5 m, a vertical \
         prismatic joint (0-0.8 m) and a horizontal one (0.2-0.6 m) pointing along x0 at q1 = 0. Numbers chosen.",
    )
    .with_config("ready", vec![0.0, 0.4, 0.4])
    .with_config("figure", vec![FRAC_PI_6, 0.5, 0.5])
}

/// Unimation Puma 560 with the Robotics Toolbox's parameters (pedestal d1 = 0.672 m).
pub fn puma560() -> Robot {
    let l = |a: f64, b: f64| [deg(a), deg(b)];
    serial(
        "Puma 560",
        Convention::Standard,
        &[
            row(R, 0.0, FRAC_PI_2, 0.67183, 0.0, l(-160.0, 160.0)),
            row(R, 0.4318, 0.0, 0.0, 0.0, l(-45.0, 225.0)),
            row(R, 0.0203, -FRAC_PI_2, 0.15005, 0.0, l(-225.0, 45.0)),
            row(R, 0.0, FRAC_PI_2, 0.4318, 0.0, l(-110.0, 170.0)),
            row(R, 0.0, -FRAC_PI_2, 0.0, 0.0, l(-100.0, 100.0)),
            row(R, 0.0, 0.0, 0.0, 0.0, l(-266.0, 266.0)),
        ],
        Pose::identity(),
        "Unimation Puma 560 (Robotics Toolbox rtb.models.DH.Puma560): anthropomorphic arm with shoulder \
         offset d3 = 0.15005 m, a3 = 0.0203 m, pedestal d1 = 0.67183 m, and a spherical wrist.",
    )
    .with_config("ready", vec![0.0, FRAC_PI_2, -FRAC_PI_2, 0.0, 0.0, 0.0])
    .with_config("stretch", vec![0.0, 0.0, -FRAC_PI_2, 0.0, 0.0, 0.0])
    .with_config("nominal", vec![0.0, FRAC_PI_4, -PI, 0.0, FRAC_PI_4, 0.0])
    .with_masses(&PUMA560_MASSES)
}

/// The Puma 560's link masses (kg) and centres of mass (m, in DH frame i), from the Robotics
/// Toolbox's `Puma560` dynamics (Armstrong, Khatib and Burdick 1986; Tarn et al.): link 1's
/// mass sits on its axis and pulls no torque, so it is left out.
const PUMA560_MASSES: [(usize, f64, [f64; 3]); 5] = [
    (1, 17.4, [-0.3638, 0.006, 0.2275]),
    (2, 4.8, [-0.0203, -0.0141, 0.070]),
    (3, 0.82, [0.0, 0.019, 0.0]),
    (4, 0.34, [0.0, 0.0, 0.0]),
    (5, 0.09, [0.0, 0.0, 0.032]),
];

fn gripper_tool() -> Pose {
    // Rz(-45 deg), then 0.103 m along z: the Robotics Toolbox's flange-to-gripper transform.
    rot_z(-FRAC_PI_4) * trans_z(0.103)
}

const LWR_LIMITS: [[f64; 2]; 7] = [
    [-2.8973, 2.8973],
    [-1.7628, 1.7628],
    [-2.8973, 2.8973],
    [-3.0718, -0.0698],
    [-2.8973, 2.8973],
    [-0.0175, 3.7525],
    [-2.8973, 2.8973],
];

/// KUKA LWR-IV (standard DH, Robotics Toolbox parameters, with the gripper tool).
pub fn lwr4() -> Robot {
    let t = [
        (FRAC_PI_2, 0.0),
        (-FRAC_PI_2, 0.0),
        (-FRAC_PI_2, 0.4),
        (FRAC_PI_2, 0.0),
        (FRAC_PI_2, 0.39),
        (-FRAC_PI_2, 0.0),
        (0.0, 0.0),
    ];
    let rows: Vec<Row> = t
        .iter()
        .zip(LWR_LIMITS)
        .map(|(&(al, d), lim)| row(R, 0.0, al, d, 0.0, lim))
        .collect();
    serial(
        "KUKA LWR-IV",
        Convention::Standard,
        &rows,
        gripper_tool(),
        "KUKA LWR-IV 7-DOF industrial arm (Robotics Toolbox rtb.models.DH.LWR4, standard DH) with the \
         toolbox's tool: Rz(-45 deg) then 0.103 m along z. The arm type of the DLR arm of Sect. 2.9.8.",
    )
    .with_config("ready", vec![0.0, FRAC_PI_4, 0.0, -FRAC_PI_2, 0.0, FRAC_PI_4, 0.0])
}

/// Franka Emika Panda (modified DH, Robotics Toolbox parameters, with the gripper tool).
pub fn panda() -> Robot {
    let t = [
        (0.0, 0.0, 0.333),
        (0.0, -FRAC_PI_2, 0.0),
        (0.0, FRAC_PI_2, 0.316),
        (0.0825, FRAC_PI_2, 0.0),
        (-0.0825, -FRAC_PI_2, 0.384),
        (0.0, FRAC_PI_2, 0.0),
        (0.088, FRAC_PI_2, 0.107),
    ];
    let rows: Vec<Row> = t
        .iter()
        .zip(LWR_LIMITS)
        .map(|(&(a, al, d), lim)| row(R, a, al, d, 0.0, lim))
        .collect();
    serial(
        "Franka Emika Panda",
        Convention::Modified,
        &rows,
        gripper_tool(),
        "Franka Emika Panda 7-DOF arm (Robotics Toolbox rtb.models.DH.Panda): modified (Craig) DH, row i \
         holds a_{i-1} and alpha_{i-1}; tool Rz(-45 deg) then 0.103 m along z.",
    )
    .with_config("ready", vec![0.0, -0.3, 0.0, -2.2, 0.0, 2.0, FRAC_PI_4])
}

fn rename(r: &mut Robot, names: &[&str]) {
    let joints: Vec<Joint> = r
        .joints()
        .iter()
        .zip(names)
        .map(|(j, n)| Joint {
            name: (*n).to_string(),
            ..j.clone()
        })
        .collect();
    let rebuilt = Robot::new(r.name.clone(), r.base, joints, r.end_effectors().to_vec())
        .unwrap_or_else(|e| unreachable!("rename: {e}"));
    let (desc, configs) = (
        std::mem::take(&mut r.description),
        std::mem::take(&mut r.configurations),
    );
    *r = rebuilt;
    r.description = desc;
    r.configurations = configs;
}
