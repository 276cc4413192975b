//! Which of a robot's end-effector frames a user would pick, grouped by arm.
//!
//! A robot description names many frames; only some are tools. The frames are grouped by the
//! last moving joint on their chain (the tip of a moving chain): frames on the same tip are one
//! arm's. A group whose chain extends another group's past a tool-like frame (a gripper's
//! fingers past `panda_hand_tcp`) joins that arm as its fingers. Frames with no moving joint on
//! their chain (fixed to the base), and collision, visual, sensor and head frames are "other
//! frames". Each arm's tool is its most tool-like frame (`tool0`, `*_tcp`, `flange`, `ee_link`,
//! `end_effector`, then `hand`, `gripper`; the farthest out among equals), and the default
//! end-effector is the tool of the longest arm (most moving joints; the first in the file
//! among equals).

use super::robot::{Drive, JointKind, Robot};

/// One arm: its tool (the IK target) and its other frames (fingers included).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ArmGroup {
    /// The tool's end-effector index.
    pub tool: usize,
    /// The arm's other end-effector frames (indices), in file order.
    pub frames: Vec<usize>,
    /// Moving joints on the chain to the tool (mimic joints included).
    pub dof: usize,
}

/// A robot's end-effector frames sorted for a user.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct EndEffectorCatalog {
    /// The arms, longest first (the first one's tool is the default end-effector).
    pub arms: Vec<ArmGroup>,
    /// Frames that are not an arm's: fixed to the base, collision, visual, sensor, head.
    pub other: Vec<usize>,
}

impl EndEffectorCatalog {
    /// The default end-effector: the tool of the longest arm (0 when there is no arm).
    pub fn default_ee(&self) -> usize {
        self.arms.first().map_or(0, |a| a.tool)
    }

    /// The IK targets: one per arm, its tool.
    pub fn tools(&self) -> Vec<usize> {
        self.arms.iter().map(|a| a.tool).collect()
    }

    /// The arm (index in `arms`) that end-effector `ee` belongs to, if any.
    pub fn arm_of(&self, ee: usize) -> Option<usize> {
        self.arms
            .iter()
            .position(|a| a.tool == ee || a.frames.contains(&ee))
    }

    /// Every end-effector index in display order: each arm's tool then its frames, then the
    /// other frames.
    pub fn order(&self) -> Vec<usize> {
        let mut out = Vec::new();
        for a in &self.arms {
            out.push(a.tool);
            out.extend(&a.frames);
        }
        out.extend(&self.other);
        out
    }
}

/// How tool-like a frame's name is, best first: 0 `tool0`, 1 `*_tcp`, 2 `flange`, 3 `ee_link`
/// (or an `ee`/`eef` word), 4 `end_effector`, 5 another `tool`, 6 `hand` or `gripper` (where the
/// farthest frame out is taken), 7 anything else.
pub fn tool_rank(name: &str) -> u8 {
    let n = name.to_ascii_lowercase();
    let words: Vec<&str> = n.split(|c: char| !c.is_ascii_alphanumeric()).collect();
    let has = |w: &str| words.contains(&w);
    if has("tool0") {
        0
    } else if n.contains("tcp") {
        1
    } else if n.contains("flange") {
        2
    } else if has("ee") || has("eef") {
        3
    } else if n.contains("end_effector") || n.contains("endeffector") {
        4
    } else if n.contains("tool") {
        5
    } else if n.contains("hand") || n.contains("gripper") || n.contains("grasp") {
        6
    } else {
        7
    }
}

/// Whether a frame's name is tool-like at all ([`tool_rank`] below 7).
pub fn is_tool_like(name: &str) -> bool {
    tool_rank(name) < 7
}

/// Whether a frame's name says it is not a tool: collision, visual, sensor, camera or head.
pub fn is_auxiliary_frame(name: &str) -> bool {
    let n = name.to_ascii_lowercase();
    [
        "collision",
        "visual",
        "camera",
        "sensor",
        "laser",
        "lidar",
        "imu",
        "optical",
        "kinect",
        "sonar",
        "head",
        "gaze",
        "neck",
        "screen",
        "display",
        "mount",
        "_range",
        "accelerometer",
    ]
    .iter()
    .any(|w| n.contains(w))
}

/// The catalog of `robot`'s end-effectors (see the module docs).
///
/// Long (about 100 lines) because its four passes (group by tip, attach fingers and frames
/// along an arm, pick each arm's tool, sort) share the groups' indices; split, they would pass
/// the same three vectors around.
pub fn catalog(robot: &Robot) -> EndEffectorCatalog {
    let ees = robot.end_effectors();
    let joints = robot.joints();
    let moving = |ee: usize| -> Vec<usize> {
        robot
            .chain_to(ees[ee].parent)
            .iter()
            .copied()
            .filter(|&j| {
                joints[j].kind != JointKind::Fixed && !matches!(joints[j].drive, Drive::None)
            })
            .collect()
    };
    let mut other = Vec::new();
    // Groups by tip joint: (tip, chain of moving joints, members).
    let mut groups: Vec<(usize, Vec<usize>, Vec<usize>)> = Vec::new();
    for (ee, frame) in ees.iter().enumerate() {
        let m = moving(ee);
        let Some(&tip) = m.last() else {
            other.push(ee);
            continue;
        };
        if is_auxiliary_frame(&frame.name) {
            other.push(ee);
            continue;
        }
        match groups.iter_mut().find(|g| g.0 == tip) {
            Some(g) => g.2.push(ee),
            None => groups.push((tip, m, vec![ee])),
        }
    }
    // Fingers: a group whose chain runs through another group's tip, when that group has a
    // tool-like frame, joins it.
    let mut parent_of: Vec<Option<usize>> = vec![None; groups.len()];
    for (i, g) in groups.iter().enumerate() {
        let host = groups
            .iter()
            .enumerate()
            .filter(|(k, h)| {
                *k != i
                    && g.1.len() > h.1.len()
                    && g.1.starts_with(&h.1)
                    && h.2.iter().any(|&e| is_tool_like(&ees[e].name))
            })
            .max_by_key(|(_, h)| h.1.len());
        // Frames part way along an arm (no tool-like name, the chain a prefix of a longer
        // one's) belong to that arm.
        let along = || {
            groups
                .iter()
                .enumerate()
                .filter(|(k, h)| {
                    *k != i
                        && h.1.len() > g.1.len()
                        && h.1.starts_with(&g.1)
                        && !g.2.iter().any(|&e| is_tool_like(&ees[e].name))
                })
                .min_by_key(|(_, h)| h.1.len())
        };
        parent_of[i] = host.or_else(along).map(|(k, _)| k);
    }
    let root = |mut i: usize| {
        while let Some(p) = parent_of[i] {
            i = p;
        }
        i
    };
    let depth = |ee: usize| robot.chain_to(ees[ee].parent).len();
    let mut arms: Vec<ArmGroup> = Vec::new();
    let mut members: Vec<(usize, Vec<usize>)> = Vec::new();
    for (i, g) in groups.iter().enumerate() {
        let r = root(i);
        match members.iter_mut().find(|m| m.0 == r) {
            Some(m) => m.1.extend(&g.2),
            None => members.push((r, g.2.clone())),
        }
    }
    for (r, mut all) in members {
        let own = &groups[r].2;
        let tool = *own
            .iter()
            .min_by_key(|&&e| {
                let rank = tool_rank(&ees[e].name);
                // Among hands and grippers (and unnamed tips) the farthest out.
                let out = if rank >= 6 { usize::MAX - depth(e) } else { 0 };
                // Among equal tool names the plainest (`iiwa_link_ee` before `iiwa_link_ee_kuka`).
                (rank, out, ees[e].name.len(), e)
            })
            .unwrap_or(&own[0]);
        all.sort_unstable();
        all.retain(|&e| e != tool);
        arms.push(ArmGroup {
            tool,
            frames: all,
            dof: groups[r].1.len(),
        });
    }
    arms.sort_by_key(|a| (usize::MAX - a.dof, a.tool));
    other.sort_unstable();
    EndEffectorCatalog { arms, other }
}
