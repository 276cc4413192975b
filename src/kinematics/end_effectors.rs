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
/// farthest frame out is taken), 7 anything else, the parts of a gripper's mechanism included
/// (fingers, knuckles, motors: `gripper_left_fingertip_1_link`, `l_gripper_l_finger_tip`).
pub fn tool_rank(name: &str) -> u8 {
    let n = name.to_ascii_lowercase();
    let words: Vec<&str> = n.split(|c: char| !c.is_ascii_alphanumeric()).collect();
    let has = |w: &str| words.contains(&w);
    // The parts of a gripper's mechanism are not its tool.
    let part = ["finger", "knuckle", "thumb", "motor", "inner", "outer"];
    if part.iter().any(|w| n.contains(w)) {
        7
    } else if has("tool0") {
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

/// Whether a frame's name says it is not a tool: collision, visual, a sensor (camera, lidar,
/// force-torque, LED, IMU, depth), or the head.
pub fn is_auxiliary_frame(name: &str) -> bool {
    let n = name.to_ascii_lowercase();
    // Short names only as whole words ("led_link", "wrist_ft_frame", "cam0"), not inside others
    // ("handled", "left"); a frame that also names itself a tool (`wrist_ft_tool_link`, the
    // tool on a force-torque sensor) stays a tool.
    let words = n.split(|c: char| !c.is_ascii_alphabetic());
    let sensor_words = [
        "led", "leds", "ft", "fts", "cam", "tof", "gps", "rgbd", "ir",
    ];
    if words.into_iter().any(|w| sensor_words.contains(&w)) && tool_rank(name) > 5 {
        return true;
    }
    [
        "force_torque",
        "forcetorque",
        "wrench",
        "rgb",
        "depth",
        "realsense",
        "stereo",
        "webcam",
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

/// Frames whose chains end at one moving joint.
struct Group {
    /// The moving joints of the chain, root to tip.
    chain: Vec<usize>,
    /// The end-effector indices, in file order.
    members: Vec<usize>,
    /// Whether one of them has a tool-like name.
    tool_like: bool,
}

/// The catalog of `robot`'s end-effectors (see the module docs).
pub fn catalog(robot: &Robot) -> EndEffectorCatalog {
    let (groups, mut other) = group_by_tip(robot);
    let host = hosts(&groups);
    let root = |mut i: usize| {
        while let Some(p) = host[i] {
            i = p;
        }
        i
    };
    // Each arm: its root group and every group that joined it.
    let mut members: Vec<(usize, Vec<usize>)> = Vec::new();
    for (i, g) in groups.iter().enumerate() {
        let r = root(i);
        match members.iter_mut().find(|m| m.0 == r) {
            Some(m) => m.1.extend(&g.members),
            None => members.push((r, g.members.clone())),
        }
    }
    let mut arms: Vec<ArmGroup> = members
        .into_iter()
        .map(|(r, mut all)| {
            let tool = pick_tool(robot, &groups[r].members);
            all.sort_unstable();
            all.retain(|&e| e != tool);
            ArmGroup {
                tool,
                frames: all,
                dof: groups[r].chain.len(),
            }
        })
        .collect();
    arms.sort_by_key(|a| (usize::MAX - a.dof, a.tool));
    other.sort_unstable();
    EndEffectorCatalog { arms, other }
}

/// The frames grouped by the last moving joint of their chain, and the other frames (no moving
/// joint, or an auxiliary name).
fn group_by_tip(robot: &Robot) -> (Vec<Group>, Vec<usize>) {
    let joints = robot.joints();
    let mut other = Vec::new();
    let mut groups: Vec<Group> = Vec::new();
    for (ee, frame) in robot.end_effectors().iter().enumerate() {
        let chain: Vec<usize> = robot
            .chain_to(frame.parent)
            .iter()
            .copied()
            .filter(|&j| {
                joints[j].kind != JointKind::Fixed && !matches!(joints[j].drive, Drive::None)
            })
            .collect();
        if chain.is_empty() || is_auxiliary_frame(&frame.name) {
            other.push(ee);
            continue;
        }
        let tool_like = is_tool_like(&frame.name);
        match groups.iter_mut().find(|g| g.chain.last() == chain.last()) {
            Some(g) => {
                g.members.push(ee);
                g.tool_like |= tool_like;
            }
            None => groups.push(Group {
                chain,
                members: vec![ee],
                tool_like,
            }),
        }
    }
    (groups, other)
}

/// The group each group joins, if any: fingers (a chain running past a group with a tool-like
/// frame) join the nearest such group; frames part way along an arm (no tool-like name, the
/// chain a prefix of a longer one's) join the nearest longer group.
fn hosts(groups: &[Group]) -> Vec<Option<usize>> {
    let extends = |long: &Group, short: &Group| {
        long.chain.len() > short.chain.len() && long.chain.starts_with(&short.chain)
    };
    groups
        .iter()
        .enumerate()
        .map(|(i, g)| {
            let others = || groups.iter().enumerate().filter(move |(k, _)| *k != i);
            let finger_of = others()
                .filter(|(_, h)| h.tool_like && extends(g, h))
                .max_by_key(|(_, h)| h.chain.len());
            let along = || {
                others()
                    .filter(|(_, h)| !g.tool_like && extends(h, g))
                    .min_by_key(|(_, h)| h.chain.len())
            };
            finger_of.or_else(along).map(|(k, _)| k)
        })
        .collect()
}

/// The most tool-like of `own` (end-effector indices): by [`tool_rank`], among hands, grippers
/// and unnamed tips the farthest out, among equal names the plainest (`iiwa_link_ee` before
/// `iiwa_link_ee_kuka`).
fn pick_tool(robot: &Robot, own: &[usize]) -> usize {
    let ees = robot.end_effectors();
    let depth = |ee: usize| robot.chain_to(ees[ee].parent).len();
    own.iter()
        .copied()
        .min_by_key(|&e| {
            let rank = tool_rank(&ees[e].name);
            let out = if rank >= 6 { usize::MAX - depth(e) } else { 0 };
            (rank, out, ees[e].name.len(), e)
        })
        .unwrap_or(own[0])
}
