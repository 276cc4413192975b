//! Posture classes of a configuration, named as the closed-form IK labels its solutions
//! (Sect. 2.12): "elbow down" / "elbow up" for planar arms (s2 > 0 is elbow down in Siciliano's
//! naming, Sect. 2.12.1), "shoulder right/left, elbow up/down" for anthropomorphic arms
//! (Sect. 2.12.4, (2.109)-(2.110) and the elbow pair of (2.98)-(2.108)), "shoulder right/left" for
//! spherical arms (Sect. 2.12.3), and the single class "all" for arms without a closed form.

use super::rng;
use crate::kinematics::Pose;
use crate::kinematics::ik::SolutionPosture;
use crate::kinematics::ik::closed_form::{
    ArmKind, ClosedForm, Elbow, Family, MAX_DOF, Posture, RawSolutions, Shoulder,
};
use crate::kinematics::orientation::wrap_angle;
use crate::kinematics::robot::{JointKind, Robot};

/// Class index of a configuration whose posture is degenerate (elbow stretched or folded,
/// wrist point on the shoulder axis): it lies between classes.
pub const UNCLASSIFIED: u8 = u8::MAX;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Elbow,
    ShoulderElbow,
    Shoulder,
}

#[derive(Debug, Clone)]
enum Rule {
    /// One class, "all".
    Single,
    /// Planar arm: elbow down (class 0) iff sin(q[joint]) > 0, elbow up (class 1) iff < 0.
    SinQ2 { joint: usize },
    /// The posture of the closed-form solution equal to q (compared on the first `compare`
    /// joints, modulo 2 pi for revolute ones).
    ClosedForm {
        cf: Box<ClosedForm>,
        kind: Kind,
        compare: usize,
        revolute: [bool; MAX_DOF],
    },
}

/// Classifies configurations by posture. Built once per robot; cheap to query for planar arms
/// (a sign test), one allocation-free closed-form solve ([`ClosedForm::solve_raw`]) per query for
/// spatial arms.
#[derive(Debug, Clone)]
pub struct PostureClassifier {
    names: Vec<String>,
    rule: Rule,
}

impl PostureClassifier {
    /// The classifier of end-effector 0 (see [`PostureClassifier::for_end_effector`]).
    pub fn new(robot: &Robot) -> Self {
        Self::for_end_effector(robot, 0)
    }

    /// The classifier of end-effector `ee`, from the structure detected by
    /// [`ClosedForm::detect`]:
    ///
    /// | family | classes (index order) |
    /// |---|---|
    /// | two-/three-link planar, SCARA | "elbow down", "elbow up" |
    /// | anthropomorphic arm, with or without spherical wrist | "shoulder right, elbow up", "shoulder right, elbow down", "shoulder left, elbow up", "shoulder left, elbow down" |
    /// | spherical arm, with or without spherical wrist | "shoulder right", "shoulder left" |
    /// | anything else, or `ee` > 0 of a multi-end-effector robot | "all" |
    ///
    /// For the planar families the class is the sign of sin(q2) (s2 > 0: elbow down, Sect.
    /// 2.12.1) when that rule agrees with the closed form's labels on 64 test configurations (it
    /// does for the textbook arms), otherwise the closed-form rule is used.
    pub fn for_end_effector(robot: &Robot, ee: usize) -> Self {
        let single = Self {
            names: vec!["all".into()],
            rule: Rule::Single,
        };
        if ee != 0 || robot.end_effectors().len() != 1 {
            return single;
        }
        let Ok(cf) = ClosedForm::detect(robot) else {
            return single;
        };
        let kind = match cf.family() {
            Family::Planar2 | Family::Planar3 | Family::Scara => Kind::Elbow,
            Family::Anthropomorphic
            | Family::Decoupled6 {
                arm: ArmKind::Anthropomorphic,
            } => Kind::ShoulderElbow,
            Family::SphericalArm
            | Family::Decoupled6 {
                arm: ArmKind::Spherical,
            } => Kind::Shoulder,
            _ => return single,
        };
        let names: Vec<String> = match kind {
            Kind::Elbow => vec!["elbow down".into(), "elbow up".into()],
            Kind::ShoulderElbow => [
                "shoulder right, elbow up",
                "shoulder right, elbow down",
                "shoulder left, elbow up",
                "shoulder left, elbow down",
            ]
            .map(String::from)
            .to_vec(),
            Kind::Shoulder => vec!["shoulder right".into(), "shoulder left".into()],
        };
        let planar = matches!(cf.family(), Family::Planar2 | Family::Planar3);
        let mut revolute = [false; MAX_DOF];
        for (k, r) in revolute.iter_mut().enumerate().take(robot.dof()) {
            *r = robot.dof_joint(k).kind == JointKind::Revolute;
        }
        let exact = Self {
            names,
            rule: Rule::ClosedForm {
                cf: Box::new(cf),
                kind,
                compare: robot.dof().min(3),
                revolute,
            },
        };
        if planar {
            let fast = Self {
                names: exact.names.clone(),
                rule: Rule::SinQ2 { joint: 1 },
            };
            if fast.agrees_with(&exact, robot) {
                return fast;
            }
        }
        exact
    }

    /// Whether two classifiers agree on 64 pseudo-random non-degenerate configurations.
    fn agrees_with(&self, other: &Self, robot: &Robot) -> bool {
        let limits = robot.sampling_ranges();
        let mut g = rng::Xoshiro256pp::stream(0xC1A55, 0);
        let mut q = vec![0.0; robot.dof()];
        let mut checked = 0;
        for _ in 0..512 {
            rng::uniform_q(&mut g, &limits, &mut q);
            let Ok(t) = robot.fk(&q) else { return false };
            let b = other.classify(&q, &t);
            if b == UNCLASSIFIED || q[1].sin().abs() < 1e-3 {
                continue;
            }
            if self.classify(&q, &t) != b {
                return false;
            }
            checked += 1;
            if checked == 64 {
                break;
            }
        }
        checked > 0
    }

    /// Names of the classes; a class index is a position in this list.
    pub fn class_names(&self) -> &[String] {
        &self.names
    }

    /// Number of classes (1 to 4).
    pub fn class_count(&self) -> usize {
        self.names.len()
    }

    /// Whether the classes are postures (false for the single class "all").
    pub fn has_postures(&self) -> bool {
        !matches!(self.rule, Rule::Single)
    }

    /// The closed-form solver, when the robot has one and it names the postures.
    pub fn closed_form(&self) -> Option<&ClosedForm> {
        match &self.rule {
            Rule::ClosedForm { cf, .. } => Some(cf),
            _ => None,
        }
    }

    /// Index of the class an IK solution's posture belongs to, as the workspace figures colour
    /// it: [`Self::class_of_posture`] for a closed-form posture ("shoulder right, elbow up, wrist
    /// flip" is in "shoulder right, elbow up"). `None` for a degenerate posture, the numerical
    /// solver's, or a classifier without posture classes.
    pub fn class_of_solution(&self, posture: &SolutionPosture) -> Option<u8> {
        if !self.has_postures() {
            return None;
        }
        posture.closed_form().and_then(|p| self.class_of_posture(p))
    }

    /// Index of the class called `name`.
    pub fn class_index(&self, name: &str) -> Option<u8> {
        self.names.iter().position(|n| n == name).map(|i| i as u8)
    }

    /// Whether [`Self::classify`] uses the pose (closed-form rules) or only q.
    pub fn needs_pose(&self) -> bool {
        matches!(self.rule, Rule::ClosedForm { .. })
    }

    /// The class of configuration `q` (rad or m) whose end-effector pose is `world_from_tool`
    /// (world frame, from [`Robot::fk`]); [`UNCLASSIFIED`] for a degenerate posture. Allocation
    /// free.
    #[inline]
    pub fn classify(&self, q: &[f64], world_from_tool: &Pose) -> u8 {
        match &self.rule {
            Rule::Single => 0,
            Rule::SinQ2 { joint } => {
                let s = q[*joint].sin();
                if s > 0.0 {
                    0
                } else if s < 0.0 {
                    1
                } else {
                    UNCLASSIFIED
                }
            }
            Rule::ClosedForm {
                cf,
                kind,
                compare,
                revolute,
            } => {
                let mut raw = RawSolutions::default();
                if cf.solve_raw(world_from_tool, &mut raw).is_err() || raw.len == 0 {
                    return UNCLASSIFIED;
                }
                let dist = |s: &[f64]| -> f64 {
                    (0..*compare)
                        .map(|k| {
                            let d = s[k] - q[k];
                            if revolute[k] {
                                wrap_angle(d).abs()
                            } else {
                                d.abs()
                            }
                        })
                        .sum()
                };
                let best = (0..raw.len)
                    .min_by(|&a, &b| dist(&raw.q[a]).total_cmp(&dist(&raw.q[b])))
                    .unwrap_or(0);
                class_of(*kind, &raw.postures[best]).unwrap_or(UNCLASSIFIED)
            }
        }
    }

    /// The class of a closed-form posture, `None` when it is degenerate or has no label of
    /// this classifier.
    pub fn class_of_posture(&self, posture: &Posture) -> Option<u8> {
        match &self.rule {
            Rule::Single => Some(0),
            Rule::SinQ2 { .. } => class_of(Kind::Elbow, posture),
            Rule::ClosedForm { kind, .. } => class_of(*kind, posture),
        }
    }

    /// Bit k set when a closed-form posture belongs to class k; a degenerate posture (stretched
    /// or folded elbow, shoulder on the axis) sets the bits of every class it borders.
    pub fn posture_mask(&self, posture: &Posture) -> u8 {
        let kind = match &self.rule {
            Rule::Single => return 1,
            Rule::SinQ2 { .. } => Kind::Elbow,
            Rule::ClosedForm { kind, .. } => *kind,
        };
        let elbows: u8 = match posture.elbow {
            Some(Elbow::Up) => 0b01,
            Some(Elbow::Down) => 0b10,
            _ => 0b11,
        };
        let shoulders: u8 = match posture.shoulder {
            Some(Shoulder::Right) => 0b01,
            Some(Shoulder::Left) => 0b10,
            _ => 0b11,
        };
        match kind {
            // class 0 = down, 1 = up
            Kind::Elbow => ((elbows >> 1) & 1) | ((elbows & 1) << 1),
            Kind::Shoulder => shoulders,
            Kind::ShoulderElbow => {
                let mut m = 0;
                for s in 0..2 {
                    for e in 0..2 {
                        if shoulders >> s & 1 == 1 && elbows >> e & 1 == 1 {
                            m |= 1 << (2 * s + e);
                        }
                    }
                }
                m
            }
        }
    }
}

fn class_of(kind: Kind, p: &Posture) -> Option<u8> {
    let elbow = match p.elbow {
        Some(Elbow::Up) => Some(0),
        Some(Elbow::Down) => Some(1),
        _ => None,
    };
    let shoulder = match p.shoulder {
        Some(Shoulder::Right) => Some(0),
        Some(Shoulder::Left) => Some(1),
        _ => None,
    };
    match kind {
        Kind::Elbow => elbow.map(|e| 1 - e),
        Kind::Shoulder => shoulder,
        Kind::ShoulderElbow => Some(2 * shoulder? + elbow?),
    }
}
