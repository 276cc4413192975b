//! The closed-form families of Sect. 2.12.

/// The positioning arm of a six-DOF arm with spherical wrist.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ArmKind {
    /// Anthropomorphic arm R-R-R (Sect. 2.12.4), with the shoulder offsets of a Puma 560.
    Anthropomorphic,
    /// Spherical arm R-R-P (Sect. 2.12.3), e.g. the Stanford manipulator.
    Spherical,
    /// Cylindrical arm R-P-P (Problem 2.19).
    Cylindrical,
    /// Cartesian (gantry) arm P-P-P, three prismatic axes not in one plane (Sect. 1.1's
    /// Cartesian geometry).
    Cartesian,
    /// Any other three revolute joints (Pieper's general case: a quartic in tan(theta3 / 2)),
    /// solved only as the positioning arm of a six-revolute arm with a spherical wrist.
    General3R,
}

/// The family a six-revolute arm has when its chain is read from the tool back to the base
/// ([`Family::Reversed6`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReversedOf {
    /// A positioning arm and a spherical wrist: the arm's axes 1-3 meet (a wrist at the base).
    Decoupled(ArmKind),
    /// Three parallel axes and the Universal Robots structure: the arm's axes 3-5 are parallel.
    ThreeParallel,
    /// Three parallel axes, any other geometry: the arm's axes 3-5 are parallel.
    ThreeParallelGeneral,
}

impl ReversedOf {
    /// The family of the reversed chain.
    pub fn family(&self) -> Family {
        match *self {
            ReversedOf::Decoupled(arm) => Family::Decoupled6 { arm },
            ReversedOf::ThreeParallel => Family::ThreeParallel,
            ReversedOf::ThreeParallelGeneral => Family::ThreeParallelGeneral,
        }
    }
}

/// Which closed-form family an arm belongs to, detected from its DH table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// Two-link planar arm (Sect. 2.12.1 without the third link).
    Planar2,
    /// Three-link planar arm (Sect. 2.12.1), target (px, py, phi).
    Planar3,
    /// SCARA R-R-P-R (Problem 2.20), target position and rotation about the vertical.
    Scara,
    /// Anthropomorphic arm (Sect. 2.12.4), position target.
    Anthropomorphic,
    /// Spherical arm (Sect. 2.12.3), position target.
    SphericalArm,
    /// Cylindrical arm (Problem 2.19), position target.
    Cylindrical,
    /// Cartesian arm P-P-P, position target.
    Cartesian,
    /// Spherical wrist alone (Sect. 2.12.5), orientation target.
    SphericalWrist,
    /// Six-DOF arm with a spherical wrist, solved by kinematic decoupling (Sect. 2.12.2).
    Decoupled6 {
        /// The positioning arm.
        arm: ArmKind,
    },
    /// Six revolute joints, axes 2, 3, 4 parallel, no spherical wrist (Universal Robots).
    ThreeParallel,
    /// Six revolute joints, axes 2, 3, 4 parallel, any other lengths and twists (IK-Geo's
    /// `three_parallel`): theta1 from a quartic, up to 8 solutions labelled "elbow up, branch k".
    ThreeParallelGeneral,
    /// Six revolute joints that are one of the six-joint families above when read from the tool
    /// back to the base (a spherical wrist at the base; three parallel axes at 3-5): solved as the
    /// inverse pose of the reversed chain, with that chain's posture labels.
    Reversed6 {
        /// The family of the reversed chain.
        of: ReversedOf,
    },
    /// Any other six revolute joints: every real solution (at most 16) by Raghavan and Roth's
    /// elimination, labelled "branch k".
    General6,
}

impl Family {
    /// Human-readable name.
    pub fn name(&self) -> &'static str {
        match self {
            Family::Planar2 => "two-link planar arm",
            Family::Planar3 => "three-link planar arm",
            Family::Scara => "SCARA manipulator",
            Family::Anthropomorphic => "anthropomorphic arm",
            Family::SphericalArm => "spherical arm",
            Family::Cylindrical => "cylindrical arm",
            Family::Cartesian => "Cartesian arm",
            Family::SphericalWrist => "spherical wrist",
            Family::Decoupled6 {
                arm: ArmKind::Anthropomorphic,
            } => "anthropomorphic arm with spherical wrist",
            Family::Decoupled6 {
                arm: ArmKind::Spherical,
            } => "spherical arm with spherical wrist (Stanford type)",
            Family::Decoupled6 {
                arm: ArmKind::Cylindrical,
            } => "cylindrical arm with spherical wrist",
            Family::Decoupled6 {
                arm: ArmKind::Cartesian,
            } => "Cartesian arm with spherical wrist (gantry type)",
            Family::Decoupled6 {
                arm: ArmKind::General3R,
            } => "three-revolute arm with spherical wrist (Pieper's general case)",
            Family::ThreeParallel => "three parallel axes (Universal Robots type)",
            Family::ThreeParallelGeneral => "three parallel axes 2-4, any other geometry",
            Family::Reversed6 { of } => match of {
                ReversedOf::Decoupled(ArmKind::Anthropomorphic) => {
                    "spherical wrist at the base: the anthropomorphic arm with spherical wrist \
                     read from the tool"
                }
                ReversedOf::Decoupled(ArmKind::General3R) => {
                    "spherical wrist at the base: Pieper's general case read from the tool"
                }
                ReversedOf::Decoupled(ArmKind::Spherical) => {
                    "spherical wrist at the base: the Stanford type read from the tool"
                }
                ReversedOf::Decoupled(ArmKind::Cylindrical) => {
                    "spherical wrist at the base: the cylindrical arm read from the tool"
                }
                ReversedOf::Decoupled(ArmKind::Cartesian) => {
                    "spherical wrist at the base: the gantry read from the tool"
                }
                ReversedOf::ThreeParallel => {
                    "three parallel axes 3-5: the Universal Robots type read from the tool"
                }
                ReversedOf::ThreeParallelGeneral => {
                    "three parallel axes 3-5: the general three-parallel arm read from the tool"
                }
            },
            Family::General6 => "general six-revolute arm (all real solutions, by elimination)",
        }
    }

    /// Number of distinct solutions [`super::ClosedForm::solve`] returns for a generic reachable target
    /// (no singularity, mirror extensions outside the limits): the theory implemented here.
    pub fn generic_solution_count(&self) -> usize {
        match self {
            Family::Planar2 | Family::Planar3 | Family::Scara => 2,
            Family::Anthropomorphic => 4,
            Family::SphericalArm => 2,
            Family::Cylindrical | Family::Cartesian => 1,
            Family::SphericalWrist => 2,
            Family::Decoupled6 { arm } => match arm {
                ArmKind::Anthropomorphic => 8,
                ArmKind::Spherical => 4,
                ArmKind::Cylindrical | ArmKind::Cartesian => 2,
                // At most (the quartic's real roots, 2 wrist postures each).
                ArmKind::General3R => 8,
            },
            Family::ThreeParallel | Family::ThreeParallelGeneral => 8,
            Family::Reversed6 { of } => of.family().generic_solution_count(),
            // At most; how many are real depends on the arm and the target.
            Family::General6 => 16,
        }
    }

    /// Whether the family's solutions are numbered "branch k" (alone, or with the wrist's
    /// posture) rather than named by their geometry: the general six-revolute arm and Pieper's
    /// general case.
    pub fn numbered_branches(&self) -> bool {
        matches!(
            self,
            Family::General6
                | Family::Decoupled6 {
                    arm: ArmKind::General3R
                }
                | Family::ThreeParallelGeneral
                | Family::Reversed6 {
                    of: ReversedOf::Decoupled(ArmKind::General3R)
                        | ReversedOf::ThreeParallelGeneral
                }
        )
    }

    /// Whether the family solves a full pose of frame n (otherwise the position of the tool
    /// point).
    pub fn uses_frame(&self) -> bool {
        matches!(
            self,
            Family::Planar3
                | Family::Scara
                | Family::SphericalWrist
                | Family::Decoupled6 { .. }
                | Family::ThreeParallel
                | Family::ThreeParallelGeneral
                | Family::Reversed6 { .. }
                | Family::General6
        )
    }
}

impl std::fmt::Display for Family {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
