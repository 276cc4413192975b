//! URDF files into robots, through `urdf-rs`.
//!
//! Every URDF joint becomes a [`Joint`] with [`JointGeometry::Origin`]: `parent_from_joint` is the
//! joint's `<origin>` (`xyz` in metres, `rpy` in radians with URDF's `R = Rz(yaw) Ry(pitch)
//! Rx(roll)`), and the joint moves about/along its unit `<axis>` in the joint frame. So the
//! robot's joint frames are the URDF *child link* frames.
//!
//! - `revolute` -> revolute with the `<limit>` bounds (an infinite bound, as URDF 1.2 writes an
//!   omitted one, becomes ±2 pi, and so does a missing `<limit>`, with a warning);
//! - `continuous` -> revolute with [`CONTINUOUS_LIMITS`] = [-2 pi, 2 pi], wide enough that a
//!   full turn either way from zero is inside the box;
//! - `prismatic` -> prismatic (finite `<limit>` bounds required, metres);
//! - `fixed` -> fixed;
//! - `floating`, `planar` and `spherical` are rejected with an error naming the joint.
//!
//! `<mimic joint="j" multiplier="m" offset="o"/>` gives `Drive::Coupled(vec![(j, m)])` and
//! `offset = o`, i.e. value = m * q_j + o; `j` must be actuated.
//!
//! Joints are ordered depth-first from the root link, children in file order, except that a
//! mimic joint is moved after the joint it mimics when needed; actuated joints take `q`
//! components in that order. Every leaf link (a link that is no joint's parent) and every
//! tool-like link with children (a gripper's base) gets an end-effector named after the link,
//! with an identity tool; they are sorted as [`crate::kinematics::end_effectors::catalog`] groups
//! them, so end-effector 0 is the tool of the longest arm.

mod visuals;
mod write;

pub use visuals::{MAX_MESH_BYTES, MAX_TRIANGLES, parse_mesh, set_package_paths};
pub use write::{UrdfExportError, to_urdf};

use crate::kinematics::pose::{Pose, rot_x, rot_y, rot_z};
use crate::kinematics::{Drive, EndEffector, Joint, JointGeometry, JointKind, ModelError, Robot};
use nalgebra::{Unit, Vector3};
use std::collections::{HashMap, HashSet};
use std::f64::consts::TAU;
use std::fmt;
use std::path::{Path, PathBuf};
use thiserror::Error;
use urdf_rs::JointType;

/// Limits given to a `continuous` joint (rad): one full turn either way.
pub const CONTINUOUS_LIMITS: [f64; 2] = [-TAU, TAU];

/// Why a `<mimic>` element is rejected.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MimicProblem {
    /// No joint has the mimicked name.
    NoSuchJoint,
    /// The mimicked joint is fixed or itself a mimic joint.
    NotActuated,
    /// The mimicked joint lies below the mimicking one in the tree, so no order has it first.
    Descendant,
}

impl fmt::Display for MimicProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            MimicProblem::NoSuchJoint => "there is no joint by that name",
            MimicProblem::NotActuated => {
                "the mimicked joint must be actuated (not fixed, not a mimic joint)"
            }
            MimicProblem::Descendant => "the mimicked joint must not lie below the mimic joint",
        })
    }
}

/// Everything that can go wrong reading a URDF file; every message ends with `(file)`.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum UrdfError {
    /// The file could not be read.
    #[error("cannot read the URDF file: {source} ({})", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        #[source]
        source: std::io::Error,
    },
    /// Not well-formed XML (a truncated file, an unclosed tag), located where the XML parser
    /// stopped.
    #[error("{}:{line}:{column}: not well-formed XML: {problem}", path.display())]
    Xml {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: u32,
        /// 1-based column.
        column: u32,
        /// What the XML parser found.
        problem: String,
    },
    /// Well-formed XML that is not valid URDF as far as `urdf-rs` is concerned.
    #[error("invalid URDF: {source} ({})", path.display())]
    Parse {
        /// The file.
        path: PathBuf,
        /// The parser's error.
        #[source]
        source: urdf_rs::UrdfError,
    },
    /// A `floating`, `planar` or `spherical` joint.
    #[error(
        "joint \"{joint}\": type {kind} is not supported (only revolute, continuous, prismatic and fixed) ({})",
        path.display()
    )]
    UnsupportedJoint {
        /// The file.
        path: PathBuf,
        /// The joint's name.
        joint: String,
        /// Its URDF type.
        kind: &'static str,
    },
    /// A joint's parent or child link that no `<link>` declares.
    #[error("joint \"{joint}\": link \"{link}\" is not declared ({})", path.display())]
    UnknownLink {
        /// The file.
        path: PathBuf,
        /// The joint's name.
        joint: String,
        /// The undeclared link.
        link: String,
    },
    /// Two joints, or two links, of the same name (URDF names each once).
    #[error("two {kind}s are named \"{name}\" (URDF names each {kind} once) ({})", path.display())]
    DuplicateName {
        /// The file.
        path: PathBuf,
        /// "joint" or "link".
        kind: &'static str,
        /// The repeated name.
        name: String,
    },
    /// A link that is the child of two joints.
    #[error(
        "link \"{link}\" is the child of both joint \"{first}\" and joint \"{second}\" ({})",
        path.display()
    )]
    TwoParents {
        /// The file.
        path: PathBuf,
        /// The link.
        link: String,
        /// The first joint.
        first: String,
        /// The second joint.
        second: String,
    },
    /// Not exactly one root link (a link that is no joint's child).
    #[error(
        "expected exactly one root link (a link that is no joint's child), found [{}] ({})",
        roots.join(", "), path.display()
    )]
    Roots {
        /// The file.
        path: PathBuf,
        /// The root links found.
        roots: Vec<String>,
    },
    /// A joint that cannot be reached from the root link (the links form a cycle).
    #[error("joint \"{joint}\" is not connected to the root link (a cycle?) ({})", path.display())]
    Unreachable {
        /// The file.
        path: PathBuf,
        /// The joint's name.
        joint: String,
    },
    /// The URDF has no joints.
    #[error("the URDF has no joints, so there is nothing to move ({})", path.display())]
    NoJoints {
        /// The file.
        path: PathBuf,
    },
    /// A `<mimic>` that cannot be honoured.
    #[error("joint \"{joint}\" mimics \"{mimicked}\": {problem} ({})", path.display())]
    Mimic {
        /// The file.
        path: PathBuf,
        /// The mimicking joint.
        joint: String,
        /// The joint it names.
        mimicked: String,
        /// Why it is rejected.
        problem: MimicProblem,
    },
    /// Limits that are not a finite interval.
    #[error(
        "joint \"{joint}\": limits [{lower}, {upper}] are not an interval (need finite lower <= upper) ({})",
        path.display()
    )]
    BadLimits {
        /// The file.
        path: PathBuf,
        /// The joint's name.
        joint: String,
        /// Lower limit (rad or m).
        lower: f64,
        /// Upper limit (rad or m).
        upper: f64,
    },
    /// NaN or an infinity in an origin, axis or mimic factor.
    #[error("joint \"{joint}\": {field} is not finite ({})", path.display())]
    NonFinite {
        /// The file.
        path: PathBuf,
        /// The joint's name.
        joint: String,
        /// Which element (`origin xyz`, `origin rpy`, `axis`, `mimic`).
        field: &'static str,
    },
    /// xacro markup in a `.urdf` file: it must be expanded first.
    #[error(
        "{}: the file holds xacro markup (<xacro:...>): expand it into URDF first, e.g. `xacro \
         {} > robot.urdf` (ROS 2: `ros2 run xacro xacro`; without ROS: `pip install xacro`)",
        path.display(),
        path.display()
    )]
    Xacro {
        /// The file.
        path: PathBuf,
    },
    /// A moving joint whose axis is the zero vector.
    #[error("joint \"{joint}\": axis has zero length ({})", path.display())]
    ZeroAxis {
        /// The file.
        path: PathBuf,
        /// The joint's name.
        joint: String,
    },
    /// The kinematics layer rejected the assembled robot.
    #[error("{source} ({})", path.display())]
    Model {
        /// The file.
        path: PathBuf,
        /// The kinematics layer's error.
        #[source]
        source: ModelError,
    },
}

/// Reads a URDF file into a [`Robot`] (see the module documentation for the mapping).
pub fn load_urdf(path: &Path) -> Result<Robot, UrdfError> {
    let text = crate::input::read_text(path, crate::input::MAX_MODEL_BYTES, "a model file")
        .map_err(|source| UrdfError::Read {
            path: path.to_path_buf(),
            source,
        })?;
    parse_urdf(&text, path)
}

/// Every link and every joint named once, as URDF requires.
fn unique_names(urdf: &urdf_rs::Robot, path: &Path) -> Result<(), UrdfError> {
    for (kind, names) in [
        (
            "link",
            urdf.links.iter().map(|l| &l.name).collect::<Vec<_>>(),
        ),
        ("joint", urdf.joints.iter().map(|j| &j.name).collect()),
    ] {
        let mut seen = HashSet::new();
        if let Some(name) = names.into_iter().find(|n| !seen.insert(n.as_str())) {
            return Err(UrdfError::DuplicateName {
                path: path.to_path_buf(),
                kind,
                name: name.clone(),
            });
        }
    }
    Ok(())
}

/// Why urdf-rs refused `text`: where it stops being well-formed XML (urdf-rs says "No elements
/// found" with no place; roxmltree finds it), else urdf-rs's own message.
fn read_error(text: &str, path: &Path, source: urdf_rs::UrdfError) -> UrdfError {
    let p = || path.to_path_buf();
    match roxmltree::Document::parse(text) {
        // A file cut short: the place is its end (the parser reports 1:1).
        Err(roxmltree::Error::UnclosedRootNode | roxmltree::Error::UnexpectedEndOfStream) => {
            let line = text.lines().count().max(1);
            let last = text.lines().last().unwrap_or("");
            let ends_in_line = !text.ends_with('\n');
            UrdfError::Xml {
                path: p(),
                line: (line + usize::from(!ends_in_line)) as u32,
                column: if ends_in_line {
                    last.chars().count() as u32 + 1
                } else {
                    1
                },
                problem: "the file ends before its elements are closed (cut short?)".into(),
            }
        }
        Err(xml) => UrdfError::Xml {
            path: p(),
            line: xml.pos().row,
            column: xml.pos().col,
            problem: xml.to_string(),
        },
        Ok(_) => UrdfError::Parse { path: p(), source },
    }
}

/// Reads URDF text into a [`Robot`]; `path` is only used in messages and the description.
pub fn parse_urdf(text: &str, path: &Path) -> Result<Robot, UrdfError> {
    let p = || path.to_path_buf();
    if has_xacro_markup(text) {
        return Err(UrdfError::Xacro { path: p() });
    }
    let urdf = urdf_rs::read_from_string(text).map_err(|source| read_error(text, path, source))?;
    let uj = &urdf.joints;
    if uj.is_empty() {
        return Err(UrdfError::NoJoints { path: p() });
    }
    unique_names(&urdf, path)?;
    let (child_of, children) = joint_tree(&urdf, path)?;
    let roots: Vec<String> = (urdf.links.iter())
        .filter(|l| !child_of.contains_key(l.name.as_str()))
        .map(|l| l.name.clone())
        .collect();
    if roots.len() != 1 {
        return Err(UrdfError::Roots { path: p(), roots });
    }
    let order = joint_order(uj, &roots[0], &children, &child_of, path)?;
    let mut new_id = vec![usize::MAX; uj.len()];
    for (k, &i) in order.iter().enumerate() {
        new_id[i] = k;
    }
    let (joints, ees) = assemble(uj, &order, &new_id, &child_of, &children, path)?;
    let name = robot_name(&urdf, path);
    let robot = Robot::new(name.clone(), Pose::identity(), joints.clone(), ees.clone())
        .map_err(|source| UrdfError::Model { path: p(), source })?;
    // The end-effectors in the catalog's order: the longest arm's tool first (the default).
    let sorted = crate::kinematics::end_effectors::catalog(&robot)
        .order()
        .into_iter()
        .map(|e| ees[e].clone())
        .collect();
    let mut robot = Robot::new(name, Pose::identity(), joints, sorted)
        .map_err(|source| UrdfError::Model { path: p(), source })?;
    // Every link keeps its frame: `--ee` takes any of them by name.
    robot.link_frames = uj
        .iter()
        .enumerate()
        .map(|(i, j)| (j.child.link.clone(), new_id[i]))
        .collect();
    let (visuals, warnings) =
        visuals::read(&urdf, path, |link| child_of.get(link).map(|&s| new_id[s]));
    (robot.collisions, robot.collision_warnings) = visuals::collisions(
        &urdf,
        path,
        |link| child_of.get(link).map(|&s| new_id[s]),
        &visuals,
    );
    robot.visuals = visuals;
    robot.root_link = Some(roots[0].clone());
    // The links' masses at their centres of mass (the inertia tensors are not needed for
    // gravity).
    robot.masses = urdf
        .links
        .iter()
        .filter(|l| l.inertial.mass.value > 0.0 && l.inertial.mass.value.is_finite())
        .map(|l| crate::kinematics::PointMass {
            joint: child_of.get(l.name.as_str()).map(|&s| new_id[s]),
            com: Vector3::from(l.inertial.origin.xyz.0),
            mass: l.inertial.mass.value,
        })
        .filter(|m| m.com.iter().all(|v| v.is_finite()))
        .collect();
    robot.load_warnings = quirks(uj);
    robot.load_warnings.extend(warnings);
    let description = format!(
        "Read from the URDF file {}: {} joints, {} degrees of freedom; joint frames are the \
         URDF child-link frames.",
        path.display(),
        robot.joints().len(),
        robot.dof()
    );
    Ok(robot.with_description(description))
}

/// Link name -> index of the URDF joint whose child it is.
type ChildOf<'u> = HashMap<&'u str, usize>;
/// Link name -> indices of the URDF joints whose parent it is, in file order.
type Children<'u> = HashMap<&'u str, Vec<usize>>;

/// Which URDF joint (index) has each link as its child, and which joints each link is the parent
/// of (file order). Rejects joint types without a [`JointKind`], links that do not exist and
/// links with two parents.
fn joint_tree<'u>(
    urdf: &'u urdf_rs::Robot,
    path: &Path,
) -> Result<(ChildOf<'u>, Children<'u>), UrdfError> {
    let p = || path.to_path_buf();
    let uj = &urdf.joints;
    let links: HashSet<&str> = urdf.links.iter().map(|l| l.name.as_str()).collect();
    let mut child_of: HashMap<&str, usize> = HashMap::new();
    let mut children: HashMap<&str, Vec<usize>> = HashMap::new();
    for (i, j) in uj.iter().enumerate() {
        let kind = match j.joint_type {
            JointType::Floating => Some("floating"),
            JointType::Planar => Some("planar"),
            JointType::Spherical => Some("spherical"),
            _ => None,
        };
        if let Some(kind) = kind {
            let joint = j.name.clone();
            return Err(UrdfError::UnsupportedJoint {
                path: p(),
                joint,
                kind,
            });
        }
        for link in [&j.parent.link, &j.child.link] {
            if !links.contains(link.as_str()) {
                let (joint, link) = (j.name.clone(), link.clone());
                return Err(UrdfError::UnknownLink {
                    path: p(),
                    joint,
                    link,
                });
            }
        }
        if let Some(&first) = child_of.get(j.child.link.as_str()) {
            return Err(UrdfError::TwoParents {
                path: p(),
                link: j.child.link.clone(),
                first: uj[first].name.clone(),
                second: j.name.clone(),
            });
        }
        child_of.insert(&j.child.link, i);
        children.entry(&j.parent.link).or_default().push(i);
    }
    Ok((child_of, children))
}

/// The joints converted in `order` (`new_id` maps a URDF joint index to its place in it), with
/// their parents, and an end-effector at every leaf link and at every tool-like link whose
/// children all move (`xarm_gripper_base_link`: a tool carrying fingers).
fn assemble(
    uj: &[urdf_rs::Joint],
    order: &[usize],
    new_id: &[usize],
    child_of: &HashMap<&str, usize>,
    children: &HashMap<&str, Vec<usize>>,
    path: &Path,
) -> Result<(Vec<Joint>, Vec<EndEffector>), UrdfError> {
    let mut joints = Vec::with_capacity(uj.len());
    let mut ees = Vec::new();
    for &i in order {
        let j = convert(&uj[i], &joints, path, |name| {
            uj.iter().position(|x| x.name == name).map(|s| new_id[s])
        })?;
        let parent = child_of.get(uj[i].parent.link.as_str()).map(|&s| new_id[s]);
        joints.push(Joint { parent, ..j });
        let child = uj[i].child.link.as_str();
        let leaf = !children.contains_key(child);
        // A tool-like link with children is a tool carrying moving fingers only when no
        // tool-like leaf hangs from it by fixed joints alone (else that leaf, `panda_hand_tcp`,
        // is the tool).
        let tool_like = crate::kinematics::end_effectors::is_tool_like(child)
            && !crate::kinematics::end_effectors::is_auxiliary_frame(child)
            && !fixed_leaf_below(uj, children, child);
        if leaf || tool_like {
            ees.push(EndEffector {
                name: uj[i].child.link.clone(),
                parent: joints.len() - 1,
                tool: Pose::identity(),
            });
        }
    }
    Ok((joints, ees))
}

/// Whether the text has a `<xacro:...>` element outside comments (an expanded URDF often keeps
/// commented-out xacro calls, as TALOS's does).
fn has_xacro_markup(text: &str) -> bool {
    let mut rest = text;
    while let Some(i) = rest.find('<') {
        rest = &rest[i..];
        if let Some(after) = rest.strip_prefix("<!--") {
            match after.find("-->") {
                Some(end) => rest = &after[end + 3..],
                None => return false,
            }
        } else if rest.starts_with("<xacro:") {
            return true;
        } else {
            rest = &rest[1..];
        }
    }
    false
}

/// Whether a tool-like leaf link hangs from `link` through fixed joints only.
fn fixed_leaf_below(
    uj: &[urdf_rs::Joint],
    children: &HashMap<&str, Vec<usize>>,
    link: &str,
) -> bool {
    children.get(link).is_some_and(|kids| {
        kids.iter().any(|&k| {
            let c = uj[k].child.link.as_str();
            let tool_leaf =
                !children.contains_key(c) && crate::kinematics::end_effectors::is_tool_like(c);
            uj[k].joint_type == JointType::Fixed && (tool_leaf || fixed_leaf_below(uj, children, c))
        })
    })
}

/// The robot's name, or the file's stem when the URDF gives none.
fn robot_name(urdf: &urdf_rs::Robot, path: &Path) -> String {
    if urdf.name.is_empty() {
        path.file_stem()
            .map_or("URDF robot".into(), |s| s.to_string_lossy().into_owned())
    } else {
        urdf.name.clone()
    }
}

/// What the file does that armlab reads liberally, one warning naming the element each: a
/// `<mimic>` on a fixed joint (RViz and urdf-viz ignore it; so does armlab: the joint stays
/// fixed), a revolute or prismatic joint without a `<limit>` range, a continuous joint with
/// one, an axis that is not a unit vector (a zero axis stays an error).
fn quirks(uj: &[urdf_rs::Joint]) -> Vec<String> {
    let mut out = Vec::new();
    for j in uj {
        let name = &j.name;
        let (lo, hi) = (j.limit.lower, j.limit.upper);
        match j.joint_type {
            JointType::Fixed => {
                if let Some(m) = &j.mimic {
                    out.push(format!(
                        "joint \"{name}\": a fixed joint with <mimic joint=\"{}\">: the mimic \
                         is ignored, the joint stays fixed",
                        m.joint
                    ));
                }
            }
            JointType::Revolute if lo == 0.0 && hi == 0.0 => out.push(format!(
                "joint \"{name}\": revolute without a <limit> range (lower = upper = 0): it turns \
                 freely, [-360, 360] deg"
            )),
            JointType::Prismatic if lo == hi => out.push(format!(
                "joint \"{name}\": prismatic with lower = upper = {lo} m (no <limit> range?): it \
                 cannot move"
            )),
            JointType::Continuous if lo != 0.0 || hi != 0.0 => out.push(format!(
                "joint \"{name}\": continuous with <limit lower=\"{lo}\" upper=\"{hi}\">: the \
                 limits are ignored, it turns freely, [-360, 360] deg"
            )),
            _ => {}
        }
        let a = &j.axis.xyz;
        let norm = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        if j.joint_type != JointType::Fixed && norm > 0.0 && (norm - 1.0).abs() > 1e-9 {
            out.push(format!(
                "joint \"{name}\": axis ({}, {}, {}) is not a unit vector (length {norm}): \
                 normalised",
                a[0], a[1], a[2]
            ));
        }
    }
    out
}

/// Depth-first order from `root`, children in file order, with each mimic joint moved after
/// the joint it mimics.
fn joint_order(
    uj: &[urdf_rs::Joint],
    root: &str,
    children: &HashMap<&str, Vec<usize>>,
    child_of: &HashMap<&str, usize>,
    path: &Path,
) -> Result<Vec<usize>, UrdfError> {
    let mut dfs = Vec::with_capacity(uj.len());
    let mut stack: Vec<usize> = children.get(root).map_or(Vec::new(), |c| c.clone());
    stack.reverse();
    while let Some(i) = stack.pop() {
        dfs.push(i);
        if let Some(c) = children.get(uj[i].child.link.as_str()) {
            stack.extend(c.iter().rev());
        }
    }
    if let Some(j) = uj.iter().enumerate().find(|(i, _)| !dfs.contains(i)) {
        let joint = j.1.name.clone();
        return Err(UrdfError::Unreachable {
            path: path.to_path_buf(),
            joint,
        });
    }
    let mimicked = |i: usize| -> Result<Option<usize>, UrdfError> {
        let Some(m) = &uj[i].mimic else {
            return Ok(None);
        };
        let err = |problem| UrdfError::Mimic {
            path: path.to_path_buf(),
            joint: uj[i].name.clone(),
            mimicked: m.joint.clone(),
            problem,
        };
        if uj[i].joint_type == JointType::Fixed {
            // Nothing moves it: the mimic is ignored (a warning, see `quirks`).
            return Ok(None);
        }
        let src = uj.iter().position(|x| x.name == m.joint);
        match src {
            None => Err(err(MimicProblem::NoSuchJoint)),
            Some(s) if uj[s].joint_type == JointType::Fixed || uj[s].mimic.is_some() => {
                Err(err(MimicProblem::NotActuated))
            }
            Some(s) => Ok(Some(s)),
        }
    };
    let deps: Vec<Option<usize>> = (0..uj.len()).map(mimicked).collect::<Result<_, _>>()?;
    let mut done = vec![false; uj.len()];
    let mut order = Vec::with_capacity(uj.len());
    while order.len() < uj.len() {
        let ready = dfs.iter().copied().find(|&i| {
            let parent_done = child_of
                .get(uj[i].parent.link.as_str())
                .is_none_or(|&p| done[p]);
            !done[i] && parent_done && deps[i].is_none_or(|s| done[s])
        });
        let Some(i) = ready else {
            // Only a mimic joint waiting for one of its own descendants can block.
            let i = dfs.iter().copied().find(|&i| !done[i] && deps[i].is_some());
            let i = i.unwrap_or(dfs[0]);
            return Err(UrdfError::Mimic {
                path: path.to_path_buf(),
                joint: uj[i].name.clone(),
                mimicked: uj[i]
                    .mimic
                    .as_ref()
                    .map_or(String::new(), |m| m.joint.clone()),
                problem: MimicProblem::Descendant,
            });
        };
        done[i] = true;
        order.push(i);
    }
    Ok(order)
}

/// One URDF joint as a [`Joint`] (parent filled in by the caller). `earlier` are the joints
/// already converted; `id_of` maps a URDF joint name to its new index.
fn convert(
    j: &urdf_rs::Joint,
    earlier: &[Joint],
    path: &Path,
    id_of: impl Fn(&str) -> Option<usize>,
) -> Result<Joint, UrdfError> {
    let (xyz, rpy) = (j.origin.xyz.0, j.origin.rpy.0);
    finite(j, path, &xyz, "origin xyz")?;
    finite(j, path, &rpy, "origin rpy")?;
    finite(j, path, &j.axis.xyz.0, "axis")?;
    let parent_from_joint =
        Pose::translation(xyz[0], xyz[1], xyz[2]) * rot_z(rpy[2]) * rot_y(rpy[1]) * rot_x(rpy[0]);
    let kind = match j.joint_type {
        JointType::Prismatic => JointKind::Prismatic,
        JointType::Fixed => JointKind::Fixed,
        _ => JointKind::Revolute,
    };
    let axis = match Unit::try_new(Vector3::from(j.axis.xyz.0), 1e-12) {
        Some(a) => a,
        None if kind == JointKind::Fixed => Vector3::z_axis(),
        None => {
            return Err(UrdfError::ZeroAxis {
                path: path.to_path_buf(),
                joint: j.name.clone(),
            });
        }
    };
    let limits = joint_limits(j, path)?;
    let (drive, offset) = drive_of(j, kind, earlier, path, id_of)?;
    Ok(Joint {
        name: j.name.clone(),
        kind,
        parent: None,
        pre: Pose::identity(),
        geometry: JointGeometry::Origin {
            parent_from_joint,
            axis,
        },
        offset,
        drive,
        limits,
    })
}

/// Rejects a non-finite number in `field` of joint `j`.
fn finite(
    j: &urdf_rs::Joint,
    path: &Path,
    v: &[f64],
    field: &'static str,
) -> Result<(), UrdfError> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(UrdfError::NonFinite {
            path: path.to_path_buf(),
            joint: j.name.clone(),
            field,
        })
    }
}

/// The joint's limits: [`CONTINUOUS_LIMITS`] for a continuous joint, zero for a fixed one, an
/// unbounded side of a revolute joint at one turn; finite and ordered, or an error.
fn joint_limits(j: &urdf_rs::Joint, path: &Path) -> Result<[f64; 2], UrdfError> {
    let (lo, hi) = (j.limit.lower, j.limit.upper);
    let limits = match j.joint_type {
        JointType::Continuous => CONTINUOUS_LIMITS,
        JointType::Fixed => [0.0, 0.0],
        // No `<limit>` (read as lower = upper = 0) leaves a revolute joint free, as an omitted
        // bound does; `quirks` warns.
        JointType::Revolute if lo == 0.0 && hi == 0.0 => CONTINUOUS_LIMITS,
        JointType::Revolute => [
            if lo == f64::NEG_INFINITY { -TAU } else { lo },
            if hi == f64::INFINITY { TAU } else { hi },
        ],
        _ => [lo, hi],
    };
    if !(limits[0].is_finite() && limits[1].is_finite() && limits[0] <= limits[1]) {
        let (lower, upper) = (lo, hi);
        return Err(UrdfError::BadLimits {
            path: path.to_path_buf(),
            joint: j.name.clone(),
            lower,
            upper,
        });
    }
    Ok(limits)
}

/// How the joint is driven, and its offset: none (fixed), coupled to the joint it mimics
/// (`multiplier`, `offset`), or actuated as the next actuated joint after `earlier`.
fn drive_of(
    j: &urdf_rs::Joint,
    kind: JointKind,
    earlier: &[Joint],
    path: &Path,
    id_of: impl Fn(&str) -> Option<usize>,
) -> Result<(Drive, f64), UrdfError> {
    Ok(match (&j.mimic, kind) {
        (_, JointKind::Fixed) => (Drive::None, 0.0),
        (Some(m), _) => {
            let (factor, offset) = (m.multiplier.unwrap_or(1.0), m.offset.unwrap_or(0.0));
            finite(j, path, &[factor, offset], "mimic")?;
            let src = id_of(&m.joint).ok_or_else(|| UrdfError::Mimic {
                path: path.to_path_buf(),
                joint: j.name.clone(),
                mimicked: m.joint.clone(),
                problem: MimicProblem::NoSuchJoint,
            })?;
            (Drive::Coupled(vec![(src, factor)]), offset)
        }
        (None, _) => {
            let dof = earlier
                .iter()
                .filter(|e| matches!(e.drive, Drive::Actuated(_)))
                .count();
            (Drive::Actuated(dof), 0.0)
        }
    })
}
