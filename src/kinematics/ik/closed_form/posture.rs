//! Posture labels of the closed-form solutions (Sect. 2.12): shoulder right/left, elbow up/down,
//! wrist flip/no flip, and the degenerate members of each pair.

use crate::kinematics::ik::FreeJoint;

/// Which of the two solutions for theta1, (2.109)-(2.110), generalised to a lateral shoulder offset
/// (Puma 560, Stanford arm). Serialised in snake case ("right", "on_axis").
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Shoulder {
    /// theta1 of (2.109): the wrist point lies ahead of the shoulder along x1 (Paul's right arm).
    Right,
    /// theta1 of (2.110): the arm reaches over its back (Paul's left arm).
    Left,
    /// The wrist point is on the axis of joint 1 (p_Wx = p_Wy = 0): theta1 is free.
    OnAxis,
    /// The wrist point is on the cylinder of radius equal to the lateral shoulder offset: the two
    /// theta1 solutions coincide.
    Boundary,
}

/// Elbow posture.
///
/// Planar arms follow Siciliano's naming (Sect. 2.12.1): "elbow down" is s2 > 0, "elbow up" is
/// s2 < 0 (the reference data `ik_planar2_closed_form.json` says "s2>0 (elbow-down in Siciliano's
/// naming)"). For spatial arms (anthropomorphic arm, Puma) "up" means the elbow lies on the +z0
/// side of the shoulder-wrist line for the shoulder-right solution (and the mirrored posture for
/// shoulder left), which is the Robotics Toolbox's `u`/`d` convention for the Puma 560.
/// Serialised in snake case ("up", "stretched").
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Elbow {
    /// Elbow up.
    Up,
    /// Elbow down.
    Down,
    /// Arm fully stretched (s3 = 0, c3 = 1): the up/down pair merges.
    Stretched,
    /// Arm fully folded (s3 = 0, c3 = -1): the up/down pair merges.
    Folded,
}

/// Sign of the extension of a prismatic joint that positions the wrist (spherical and
/// cylindrical arms). Serialised in snake case ("forward").
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Extension {
    /// The textbook's choice (d3 >= 0 in Sect. 2.12.3).
    Forward,
    /// The mirror solution with the opposite extension (returned by `solve` only when it lies
    /// inside the prismatic joint's limits).
    Reversed,
    /// Zero extension: the two solutions coincide.
    Zero,
}

/// Wrist posture: which of the two ZYZ-like solutions (2.111)-(2.112). Serialised in snake case
/// ("no_flip", "up").
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum WristFlip {
    /// The solution of (2.111), the middle ZYZ angle in (0, pi). For the textbook wrist
    /// (alpha4 = -pi/2) this is theta5 in (0, pi); with alpha4 = +pi/2 (Puma 560) theta5 < 0 (the
    /// Robotics Toolbox's `n`).
    NoFlip,
    /// The solution of (2.112) (theta4 + pi, -theta5, theta6 + pi).
    Flip,
    /// sin(theta5) = 0: only theta4 + theta6 (or theta4 - theta6) is determined.
    Singular,
    /// Three parallel axes (the UR family): theta5 in (0, pi), as UR and MoveIt users say "wrist
    /// up".
    Up,
    /// Three parallel axes: theta5 in (-pi, 0), "wrist down".
    Down,
}

/// Why a joint is free (infinitely many solutions). Serialised in snake case ("wrist_aligned").
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FreeReason {
    /// Wrist point on the axis of joint 1.
    ShoulderAxis,
    /// Wrist point at the shoulder of an arm with equal links, elbow folded.
    ElbowAtShoulder,
    /// Target at the base of a planar two-link arm with a1 = a2.
    PlanarOrigin,
    /// Spherical arm with zero extension: the wrist point is on the axis of joint 2.
    ExtensionZero,
    /// Wrist singularity, sin(theta5) = 0.
    WristAligned,
    /// Axis 6 parallel to the parallel axes 2-4 (general three-parallel arm).
    AxesAligned,
}

impl FreeReason {
    /// A sentence for [`FreeJoint::reason`].
    pub fn text(self) -> &'static str {
        match self {
            FreeReason::ShoulderAxis => {
                "wrist point on the axis of joint 1 (p_Wx = p_Wy = 0): theta1 is free (the value \
                 shown is one representative)"
            }
            FreeReason::ElbowAtShoulder => {
                "wrist point at the shoulder with a2 = a3 (elbow folded): theta2 is free"
            }
            FreeReason::PlanarOrigin => {
                "target at the base of a two-link arm with a1 = a2 (elbow folded): theta1 is free"
            }
            FreeReason::ExtensionZero => {
                "zero extension d3: the wrist point is on the axis of joint 2, theta2 is free"
            }
            FreeReason::WristAligned => {
                "wrist singularity (sin theta5 = 0): only theta4 + theta6 (or theta4 - theta6) is \
                 determined; theta4 (with its offset) is set to 0"
            }
            FreeReason::AxesAligned => {
                "axis 6 parallel to axes 2-4: only theta6 with theta2 + theta3 + theta4 is \
                 determined; theta6 is set to 0"
            }
        }
    }
}

/// The posture of one closed-form solution: allocation-free, turned into a label by its
/// `Display` ([`Posture::label`]); serialised as its fields (the enums in snake case, `free` as six
/// reasons or nulls).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub struct Posture {
    /// Shoulder solution, for arms with a shoulder.
    pub shoulder: Option<Shoulder>,
    /// Elbow solution, for arms with an elbow.
    pub elbow: Option<Elbow>,
    /// Sign of the positioning prismatic joint's extension (spherical and cylindrical arms).
    pub extension: Option<Extension>,
    /// Wrist solution, for arms with a spherical wrist.
    pub wrist: Option<WristFlip>,
    /// `free[i]` says why `q[i]` is free, if it is.
    pub free: [Option<FreeReason>; 6],
    /// Branch number (1-based) of a general six-revolute arm, whose postures have no names.
    pub branch: Option<u8>,
    /// A posture of the chain read from the tool back to the base ([`super::Family::Reversed6`]):
    /// its shoulder is at the tool ("tool shoulder right") and its wrist at the base ("base wrist
    /// flip").
    pub reversed: bool,
}

impl Posture {
    /// Human-readable label, e.g. "shoulder right, elbow up, wrist no flip" (the `Display`
    /// text).
    pub fn label(&self) -> String {
        self.to_string()
    }

    /// The shoulder's part of the label: "shoulder right", or "tool shoulder right" on the
    /// reversed chain.
    pub fn shoulder_label(&self) -> Option<&'static str> {
        self.shoulder.map(|s| match (s, self.reversed) {
            (Shoulder::Right, false) => "shoulder right",
            (Shoulder::Left, false) => "shoulder left",
            (Shoulder::OnAxis, false) => "shoulder on axis",
            (Shoulder::Boundary, false) => "shoulder boundary",
            (Shoulder::Right, true) => "tool shoulder right",
            (Shoulder::Left, true) => "tool shoulder left",
            (Shoulder::OnAxis, true) => "tool shoulder on axis",
            (Shoulder::Boundary, true) => "tool shoulder boundary",
        })
    }

    /// The elbow's part of the label: "elbow up".
    pub fn elbow_label(&self) -> Option<&'static str> {
        self.elbow.map(|e| match e {
            Elbow::Up => "elbow up",
            Elbow::Down => "elbow down",
            Elbow::Stretched => "elbow stretched",
            Elbow::Folded => "elbow folded",
        })
    }

    /// The extension's part of the label: "extension forward".
    pub fn extension_label(&self) -> Option<&'static str> {
        self.extension.map(|x| match x {
            Extension::Forward => "extension forward",
            Extension::Reversed => "extension reversed",
            Extension::Zero => "extension zero",
        })
    }

    /// The wrist's part of the label: "wrist no flip", or "base wrist no flip" on the reversed
    /// chain.
    pub fn wrist_label(&self) -> Option<&'static str> {
        self.wrist.map(|w| match (w, self.reversed) {
            (WristFlip::NoFlip, false) => "wrist no flip",
            (WristFlip::Flip, false) => "wrist flip",
            (WristFlip::Singular, false) => "wrist singular",
            (WristFlip::Up, false) => "wrist up",
            (WristFlip::Down, false) => "wrist down",
            (WristFlip::NoFlip, true) => "base wrist no flip",
            (WristFlip::Flip, true) => "base wrist flip",
            (WristFlip::Singular, true) => "base wrist singular",
            (WristFlip::Up, true) => "base wrist up",
            (WristFlip::Down, true) => "base wrist down",
        })
    }

    /// The named parts of the label, in order (shoulder, elbow, extension, wrist; the branch
    /// number, which is no name, is left out). No allocation.
    pub fn parts(&self) -> impl Iterator<Item = &'static str> {
        [
            self.shoulder_label(),
            self.elbow_label(),
            self.extension_label(),
            self.wrist_label(),
        ]
        .into_iter()
        .flatten()
    }

    /// True on a degenerate solution: a free joint or a merged pair of postures.
    pub fn is_degenerate(&self) -> bool {
        self.free.iter().any(Option::is_some) || self.is_merged()
    }

    /// True when the posture is the merged member of a pair (the label says so: "elbow
    /// stretched", "elbow folded", "wrist singular", "shoulder on axis", "shoulder boundary",
    /// "extension zero"), whatever the free joints.
    pub fn is_merged(&self) -> bool {
        matches!(self.shoulder, Some(Shoulder::OnAxis | Shoulder::Boundary))
            || matches!(self.elbow, Some(Elbow::Stretched | Elbow::Folded))
            || self.extension == Some(Extension::Zero)
            || self.wrist == Some(WristFlip::Singular)
    }

    /// The posture less its branch number and free joints: what the label says besides "branch
    /// k", the group in which branch numbers are unique
    /// ([`crate::kinematics::ik::branches::continue_numbers`]).
    pub fn without_branch(&self) -> Posture {
        Posture {
            branch: None,
            free: [None; 6],
            ..*self
        }
    }

    /// Whether two postures have the same label: equal but for the free joints, which the label
    /// does not show.
    pub fn same_label(&self, other: &Posture) -> bool {
        self.without_branch() == other.without_branch() && self.branch == other.branch
    }

    /// The short label, for places that must stay short (ghost arms): "shoulder right, elbow
    /// up, wrist no flip" is "R U N" ([`SHORT_LEGEND`] spells the letters out); "wrist
    /// singular" is "!", and the branch number stays "branch k".
    pub fn short(&self) -> String {
        let r = self.reversed;
        let shoulder = self.shoulder.map(|s| match (s, r) {
            (Shoulder::Right, false) => "R",
            (Shoulder::Left, false) => "L",
            (Shoulder::OnAxis, false) => "A",
            (Shoulder::Boundary, false) => "B",
            (Shoulder::Right, true) => "tR",
            (Shoulder::Left, true) => "tL",
            (Shoulder::OnAxis, true) => "tA",
            (Shoulder::Boundary, true) => "tB",
        });
        let elbow = self.elbow.map(|e| match e {
            Elbow::Up => "U",
            Elbow::Down => "D",
            Elbow::Stretched => "S",
            Elbow::Folded => "Fo",
        });
        let extension = self.extension.map(|x| match x {
            Extension::Forward => "+",
            Extension::Reversed => "-",
            Extension::Zero => "0",
        });
        let wrist = self.wrist.map(|w| match (w, r) {
            (WristFlip::Singular, _) => "!",
            (WristFlip::NoFlip, false) => "N",
            (WristFlip::Flip, false) => "F",
            (WristFlip::Up, false) => "W+",
            (WristFlip::Down, false) => "W-",
            (WristFlip::NoFlip, true) => "bN",
            (WristFlip::Flip, true) => "bF",
            (WristFlip::Up, true) => "bW+",
            (WristFlip::Down, true) => "bW-",
        });
        let mut words: Vec<String> = [shoulder, elbow, extension, wrist]
            .into_iter()
            .flatten()
            .map(str::to_string)
            .collect();
        words.extend(self.branch.map(|b| format!("branch {b}")));
        words.join(" ")
    }

    /// The free joints as [`FreeJoint`]s.
    pub fn free_joints(&self) -> Vec<FreeJoint> {
        self.free
            .iter()
            .enumerate()
            .filter_map(|(index, r)| {
                r.map(|r| FreeJoint {
                    index,
                    reason: r.text(),
                })
            })
            .collect()
    }
}

impl Posture {
    /// Writes the label (see `Display`) to `w`.
    fn write_label(&self, w: &mut impl std::fmt::Write) -> std::fmt::Result {
        let mut first = true;
        for p in self.parts() {
            if !first {
                w.write_str(", ")?;
            }
            w.write_str(p)?;
            first = false;
        }
        if let Some(b) = self.branch {
            if !first {
                w.write_str(", ")?;
            }
            write!(w, "branch {b}")?;
        }
        Ok(())
    }
}

impl std::fmt::Display for Posture {
    /// The label: the parts joined by ", " ("shoulder right, elbow up, wrist no flip"), the
    /// branch number last ("wrist flip, branch 3"). A width (`{:<42}`) pads it as it pads a
    /// string.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if f.width().is_some() {
            let mut s = String::new();
            self.write_label(&mut s)?;
            return f.pad(&s);
        }
        self.write_label(f)
    }
}

/// What the short labels mean.
pub const SHORT_LEGEND: &str = "R/L shoulder right/left, U/D elbow up/down, N/F wrist no flip/flip \
(A shoulder on axis, S/Fo elbow stretched/folded, +/- extension, ! wrist singular)";

/// What the short labels of the three-parallel-axes family (UR) mean.
pub const SHORT_LEGEND_UR: &str =
    "R/L shoulder right/left, U/D elbow up/down, W+/W- wrist up/down (! wrist singular)";
