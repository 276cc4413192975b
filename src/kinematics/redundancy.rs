//! Kinematic redundancy named (Sect. 2.10.2): for a robot and a task, the number of joints n, the
//! dimension m of the operational space of the task's kind, and the number r of components the
//! task constrains.
//!
//! "A manipulator is intrinsically redundant when the dimension of the operational space is
//! smaller than the dimension of the joint space (m < n)"; it "can be functionally redundant when
//! only a number of r components of operational space are of concern for the specific task, with
//! r < m". The degree of redundancy is n - r. Tasks are expressed in the **tool frame**, so "free
//! about the approach axis" (laser cutting, r = 5) is a task of its own.

use super::Robot;

/// A task: which components of the end-effector pose are prescribed, in the tool frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Task {
    /// Position and orientation (r = 6 of m = 6).
    #[default]
    Pose,
    /// Position only (r = 3 of m = 6).
    Position,
    /// Position and the approach axis z_e; the rotation about it is free (laser cutting: r = 5 of
    /// m = 6).
    PositionAxis,
    /// Position in the plane of a planar arm (r = 2 of m = 3).
    Planar,
    /// Position in the plane and the orientation phi (r = 3 of m = 3).
    PlanarPhi,
}

impl Task {
    /// Every task, in the order of the CLI's `--task` values.
    pub const ALL: [Task; 5] = [
        Task::Pose,
        Task::Position,
        Task::PositionAxis,
        Task::Planar,
        Task::PlanarPhi,
    ];

    /// The CLI name: `pose`, `position`, `position+axis`, `planar`, `planar+phi`.
    pub fn name(self) -> &'static str {
        match self {
            Task::Pose => "pose",
            Task::Position => "position",
            Task::PositionAxis => "position+axis",
            Task::Planar => "planar",
            Task::PlanarPhi => "planar+phi",
        }
    }

    /// The task of a CLI name.
    pub fn from_name(name: &str) -> Option<Task> {
        Task::ALL.into_iter().find(|t| t.name() == name)
    }

    /// A description in words.
    pub fn description(self) -> &'static str {
        match self {
            Task::Pose => "full pose: position and orientation",
            Task::Position => "position only, orientation free",
            Task::PositionAxis => "position and approach axis, free about the tool axis",
            Task::Planar => "position in the plane, orientation phi free",
            Task::PlanarPhi => "position in the plane and orientation phi",
        }
    }

    /// Whether the task belongs to the plane (m = 3) rather than to space (m = 6).
    pub fn is_planar(self) -> bool {
        matches!(self, Task::Planar | Task::PlanarPhi)
    }

    /// Dimension m of the operational space of the task's kind: 3 in the plane, 6 in space.
    pub fn operational_dimension(self) -> usize {
        if self.is_planar() { 3 } else { 6 }
    }

    /// Number r of components the task constrains.
    pub fn constrained(self) -> usize {
        match self {
            Task::Pose => 6,
            Task::Position => 3,
            Task::PositionAxis => 5,
            Task::Planar => 2,
            Task::PlanarPhi => 3,
        }
    }

    /// The constrained components of the 6-vector error `[p; o]` expressed in the **tool frame**
    /// (x, y, z of the position error; rotations about the tool's x, y, z), as
    /// [`super::ik::numerical::TaskMask`] uses them with [`super::ik::numerical::MaskFrame::Tool`].
    /// Planar tasks constrain the plane's x, y (and the rotation about its normal, the tool z of
    /// a planar arm with its tool z along the axes).
    pub fn tool_components(self) -> [bool; 6] {
        match self {
            Task::Pose => [true; 6],
            Task::Position => [true, true, true, false, false, false],
            Task::PositionAxis => [true, true, true, true, true, false],
            Task::Planar => [true, true, false, false, false, false],
            Task::PlanarPhi => [true, true, false, false, false, true],
        }
    }
}

/// The redundancy of a robot for a task (Sect. 2.10.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Redundancy {
    /// Joints (dimension of the joint space).
    pub n: usize,
    /// Dimension of the operational space of the task's kind (3 planar, 6 spatial).
    pub m: usize,
    /// Components the task constrains.
    pub r: usize,
}

impl Redundancy {
    /// n, m, r of `robot` for `task`.
    pub fn of(robot: &Robot, task: Task) -> Self {
        Self {
            n: robot.dof(),
            m: task.operational_dimension(),
            r: task.constrained(),
        }
    }

    /// Intrinsically redundant: m < n.
    pub fn intrinsic(&self) -> bool {
        self.m < self.n
    }

    /// Functionally redundant: r < m and r < n (the task leaves joint motions free).
    pub fn functional(&self) -> bool {
        self.r < self.m && self.r < self.n
    }

    /// Degree of redundancy n - r (0 or less: not redundant for the task).
    pub fn degree(&self) -> isize {
        self.n as isize - self.r as isize
    }

    /// "intrinsically redundant", "functionally redundant", "intrinsically and functionally
    /// redundant" or "not redundant".
    pub fn words(&self) -> &'static str {
        match (self.intrinsic(), self.functional()) {
            (true, true) => "intrinsically and functionally redundant",
            (true, false) => "intrinsically redundant",
            (false, true) => "functionally redundant",
            (false, false) => "not redundant",
        }
    }
}

impl std::fmt::Display for Redundancy {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "n = {}, m = {}, r = {}: {} (degree {})",
            self.n,
            self.m,
            self.r,
            self.words(),
            self.degree().max(0)
        )
    }
}
