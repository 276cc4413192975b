//! A DH table derived from the joint axes of any serial chain (a URDF's origins and axes, or a
//! table with `pre` transforms), with the base and tool transforms that make its forward
//! kinematics equal to the chain's (Sect. 2.8.2's rules applied to the axes at q = 0).
//!
//! Frame i - 1's z axis is joint i's axis (its sense, so a positive joint value turns or slides
//! positively). Frame i's x axis is the common normal from axis i to axis i + 1, its origin where
//! that normal meets axis i + 1; where the two axes intersect the origin is the intersection and
//! x = z_{i-1} x z_i; where they are parallel the normal through the previous origin is taken
//! (as the textbook does); of the two senses of an x axis left free the one nearer the previous
//! x is taken, so that theta offsets stay within +-90 degrees. Then `d_i` and `a_i` are the components of `o_i - o_{i-1}` along
//! `z_{i-1}` and `x_i`, `theta_i` the angle from `x_{i-1}` to `x_i` about `z_{i-1}` and `alpha_i`
//! the angle from `z_{i-1}` to `z_i` about `x_i` ((2.51)-(2.52)). Frame 0 has its origin on axis 1
//! nearest the robot's base origin and its x axis along the base's x projected normal to axis 1;
//! frame n keeps axis n as z, its origin nearest the flange, its x along the flange's projected x.
//! Fixed joints between the moving ones disappear into the geometry. A prismatic joint fixes only
//! a direction; its line is taken through the joint frame's origin at q = 0.
//!
//! Every derived table is checked: its forward kinematics must equal the chain's at q = 0 and at
//! eight further joint vectors to 1e-9 of the arm's size, or the derivation is refused.

use super::dh::{Convention, DhRow, standard_to_modified};
use super::robot::{DhJoint, Drive, JointKind, Robot};
use super::{KinematicsError, Pose};
use nalgebra::{Matrix3, Rotation3, Translation3, Vector3};
use std::f64::consts::FRAC_PI_2;
use thiserror::Error;

/// A DH table equivalent to a serial chain.
#[derive(Debug, Clone, PartialEq)]
pub struct DerivedDh {
    /// The table's convention.
    pub convention: Convention,
    /// The rows in chain order, one per moving joint, with the chain's offsets (rad or m, the DH
    /// value at q = 0), limits and names.
    pub joints: Vec<DhJoint>,
    /// `world_from_base`: where frame 0 sits in the world (m).
    pub world_from_base: Pose,
    /// `flange_from_tool`: the end-effector in frame n (m).
    pub flange_from_tool: Pose,
}

/// Why a chain has no DH table.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum NoDhTable {
    /// A moving joint off the end-effector's chain (the robot is a tree).
    #[error(
        "no DH table: joint \"{joint}\" is not on the chain to end-effector \"{ee}\" (the robot \
         is a tree, and a DH table describes one serial chain)"
    )]
    Tree {
        /// The joint off the chain.
        joint: String,
        /// The end-effector.
        ee: String,
    },
    /// A joint that follows others (a mimic joint, a closed chain).
    #[error(
        "no DH table: joint \"{joint}\" follows other joints (mimic or closed chain), and a DH \
         table has one variable per row"
    )]
    Coupled {
        /// The coupled joint's name.
        joint: String,
    },
    /// The chain has no moving joint.
    #[error("no DH table: the chain has no moving joint")]
    NoJoints,
    /// The derived table's forward kinematics did not reproduce the chain's.
    #[error("no DH table: the derived table misses the chain's pose by {error:.3e} m at some q")]
    Mismatch {
        /// The largest position error found (m).
        error: f64,
    },
    /// The derived table is not a valid robot (nearly parallel axes give huge lengths).
    #[error(
        "no DH table: the derived table is not a valid robot ({reason}); nearly parallel axes \
         put the common normal far away"
    )]
    Invalid {
        /// The kinematics layer's reason.
        reason: String,
    },
    /// Bad robot input.
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
}

/// One joint's axis at q = 0 (world): a point on it and its unit direction.
#[derive(Debug, Clone, Copy)]
struct Axis {
    p: Vector3<f64>,
    z: Vector3<f64>,
}

/// A frame under construction (world).
#[derive(Debug, Clone, Copy)]
struct Frame {
    o: Vector3<f64>,
    x: Vector3<f64>,
    z: Vector3<f64>,
}

impl Frame {
    fn pose(&self) -> Pose {
        let y = self.z.cross(&self.x);
        let m = Matrix3::from_columns(&[self.x, y, self.z]);
        Pose::from_parts(
            Translation3::from(self.o),
            Rotation3::from_matrix_unchecked(m),
        )
    }
}

/// `v` made unit and normal to `z`, or `None` when it is (nearly) along `z`.
fn normal_part(v: &Vector3<f64>, z: &Vector3<f64>) -> Option<Vector3<f64>> {
    let w = v - z * z.dot(v);
    let n = w.norm();
    (n > 1e-9 * v.norm().max(1e-300)).then(|| w / n)
}

/// The signed angle from `u` to `v` about `n` (rad).
fn signed(u: &Vector3<f64>, v: &Vector3<f64>, n: &Vector3<f64>) -> f64 {
    n.dot(&u.cross(v)).atan2(u.dot(v))
}

/// The moving joints of end-effector `ee`'s chain and their axes at q = 0, after checking that
/// the chain is serial and every joint has its own variable.
fn chain_axes(robot: &Robot, ee: usize) -> Result<(Vec<usize>, Vec<Axis>), NoDhTable> {
    let e = robot.end_effector(ee)?;
    let chain: Vec<usize> = robot
        .chain_to(e.parent)
        .iter()
        .copied()
        .filter(|&j| robot.joints()[j].kind != JointKind::Fixed)
        .collect();
    // A joint that follows others is said first: a mimic's leader off the chain is no tree.
    for joint in robot.joints() {
        if joint.kind != JointKind::Fixed && !matches!(joint.drive, Drive::Actuated(_)) {
            return Err(NoDhTable::Coupled {
                joint: joint.name.clone(),
            });
        }
    }
    for (j, joint) in robot.joints().iter().enumerate() {
        if joint.kind != JointKind::Fixed && !chain.contains(&j) {
            return Err(NoDhTable::Tree {
                joint: joint.name.clone(),
                ee: e.name.clone(),
            });
        }
    }
    if chain.is_empty() {
        return Err(NoDhTable::NoJoints);
    }
    let q0 = vec![0.0; robot.dof()];
    let frames = robot.fk_frames(&q0)?;
    let jac = robot.jacobian(&q0, ee)?;
    let pe = robot.fk_ee(&q0, ee)?.translation.vector;
    let axes = chain
        .iter()
        .map(|&j| {
            let Drive::Actuated(k) = robot.joints()[j].drive else {
                unreachable!("checked above")
            };
            let c = jac.column(k);
            let (v, w) = (
                Vector3::new(c[0], c[1], c[2]),
                Vector3::new(c[3], c[4], c[5]),
            );
            match robot.joints()[j].kind {
                // A point on a revolute axis: p_e - (p_e - p)_perp = p_e + w x v for unit w.
                JointKind::Revolute => Axis {
                    p: pe + w.cross(&v) / w.norm_squared(),
                    z: w.normalize(),
                },
                _ => Axis {
                    p: frames[j].translation.vector,
                    z: v.normalize(),
                },
            }
        })
        .collect();
    Ok((chain, axes))
}

/// Frame i from frame i - 1 (whose z is axis i) and axis i + 1: common normal, intersection or
/// the parallel case.
fn next_frame(prev: &Frame, next: &Axis, tol: f64, parallel: f64) -> Frame {
    let (z0, z1) = (prev.z, next.z);
    let n = z0.cross(&z1);
    let w = next.p - prev.o;
    if n.norm() <= parallel {
        // Parallel: the normal through the previous origin.
        let foot = next.p + z1 * z1.dot(&(prev.o - next.p));
        let x = normal_part(&(foot - prev.o), &z0)
            .filter(|_| (foot - prev.o).norm() > tol)
            .unwrap_or(prev.x);
        return Frame { o: foot, x, z: z1 };
    }
    let nu = n / n.norm();
    let gap = nu.dot(&w);
    // Parameters along each line of the closest points: prev.o + s z0, next.p + t z1.
    let (b, d, e) = (z0.dot(&z1), z0.dot(&w), z1.dot(&w));
    let den = 1.0 - b * b;
    let t = (b * d - e) / den;
    let o = next.p + z1 * t;
    if gap.abs() <= tol {
        // Intersecting: x = +-(z_{i-1} x z_i), the sign that keeps theta_i within +-90 degrees.
        let x = if nu.dot(&prev.x) < 0.0 { -nu } else { nu };
        return Frame { o, x, z: z1 };
    }
    Frame {
        o,
        x: nu * gap.signum(),
        z: z1,
    }
}

/// The standard DH rows between consecutive frames, with each joint's kind, name and limits;
/// rounding residues (below 1e-12 of the arm's size, or 1e-12 rad) are written as zero.
fn rows_between(robot: &Robot, chain: &[usize], frames: &[Frame]) -> Vec<DhJoint> {
    let scale = robot.characteristic_length();
    let length = |v: f64| if v.abs() <= 1e-12 * scale { 0.0 } else { v };
    let angle = |v: f64| if v.abs() <= 1e-12 { 0.0 } else { v };
    chain
        .iter()
        .enumerate()
        .map(|(i, &j)| {
            let (f0, f1) = (frames[i], frames[i + 1]);
            let delta = f1.o - f0.o;
            let (d, a) = (length(delta.dot(&f0.z)), length(delta.dot(&f1.x)));
            let theta = angle(signed(&f0.x, &f1.x, &f0.z));
            let alpha = angle(signed(&f0.z, &f1.z, &f1.x));
            let joint = &robot.joints()[j];
            let (row, offset) = match joint.kind {
                // (2.52): theta is the variable of a revolute joint, d of a prismatic one.
                JointKind::Revolute => (
                    DhRow {
                        a,
                        alpha,
                        d,
                        theta: 0.0,
                    },
                    theta,
                ),
                _ => (
                    DhRow {
                        a,
                        alpha,
                        d: 0.0,
                        theta,
                    },
                    d,
                ),
            };
            let mut dj = DhJoint::new(joint.kind, row).offset(offset);
            dj.limits = joint.limits;
            dj.name = Some(joint.name.clone());
            dj
        })
        .collect()
}

/// Derives a DH table of `convention` for end-effector `ee`'s chain (see the module docs), or
/// says why none exists.
pub fn derive_dh(robot: &Robot, ee: usize, convention: Convention) -> Result<DerivedDh, NoDhTable> {
    let scale = robot.characteristic_length();
    let derived = derive_frames(robot, ee, convention, 1e-10 * scale, 1e-12)?;
    check(robot, ee, &derived, scale, 1e-9 * scale)?;
    Ok(derived)
}

/// How far a chain is from its ideal structure: the largest length (m) and angle (rad) of the
/// derived table that were rounded to 0, or to a multiple of 90 degrees, and the largest
/// pose difference between the ideal table and the chain (m; rotations times the arm's size).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Deviation {
    /// Largest length rounded to zero (m).
    pub length: f64,
    /// Largest angle rounded to a multiple of 90 degrees (rad).
    pub angle: f64,
    /// Largest forward-kinematics difference between the ideal table and the chain (m).
    pub pose: f64,
}

/// The DH table of the chain's *ideal* structure: axes within `angle_tol` (rad) of parallel
/// are taken as parallel, axes whose common normal is shorter than `length_tol` (m) as meeting,
/// and then twists within `angle_tol` of a multiple of 90 degrees and lengths below
/// `length_tol` are rounded to it. CAD-rounded URDFs (`rpy = "1.5708"`) and calibrated models
/// have such near-misses. The ideal table must still follow the chain to
/// `1000 * length_tol` (or the rounding was not a near miss); the deviation is returned.
pub fn derive_ideal_dh(
    robot: &Robot,
    ee: usize,
    angle_tol: f64,
    length_tol: f64,
) -> Result<(DerivedDh, Deviation), NoDhTable> {
    let scale = robot.characteristic_length();
    let mut d = derive_frames(robot, ee, Convention::Standard, length_tol, angle_tol)?;
    let mut dev = Deviation::default();
    for j in &mut d.joints {
        for v in [&mut j.row.a, &mut j.row.d] {
            if v.abs() <= length_tol {
                dev.length = dev.length.max(v.abs());
                *v = 0.0;
            }
        }
        // A revolute joint's theta is its variable (0 here, the offset holds the rest).
        let mut angles = vec![&mut j.row.alpha];
        if j.kind == JointKind::Prismatic {
            angles.push(&mut j.row.theta);
        }
        for v in angles {
            let right = (*v / FRAC_PI_2).round() * FRAC_PI_2;
            if (*v - right).abs() <= angle_tol {
                dev.angle = dev.angle.max((*v - right).abs());
                *v = right;
            }
        }
    }
    dev.pose = check(robot, ee, &d, scale, 1000.0 * length_tol)?;
    d.convention = Convention::Standard;
    Ok((d, dev))
}

/// The frames and rows of [`derive_dh`] with the given tolerances (m for meeting axes, the sine
/// of the angle for parallel ones), unchecked.
fn derive_frames(
    robot: &Robot,
    ee: usize,
    convention: Convention,
    tol: f64,
    parallel: f64,
) -> Result<DerivedDh, NoDhTable> {
    let (chain, axes) = chain_axes(robot, ee)?;
    let bx = robot.base.rotation * Vector3::x();
    let by = robot.base.rotation * Vector3::y();
    let a1 = axes[0];
    let base_o = robot.base.translation.vector;
    let mut frames = vec![Frame {
        o: a1.p + a1.z * a1.z.dot(&(base_o - a1.p)),
        x: normal_part(&bx, &a1.z)
            .or_else(|| normal_part(&by, &a1.z))
            .unwrap_or(bx),
        z: a1.z,
    }];
    for axis in &axes[1..] {
        let f = next_frame(
            frames.last().unwrap_or_else(|| unreachable!()),
            axis,
            tol,
            parallel,
        );
        frames.push(f);
    }
    // Frame n: axis n as z, the origin nearest the flange, x along the flange's projected x.
    let q0 = vec![0.0; robot.dof()];
    let e = robot.end_effector(ee)?;
    let flange = robot.fk_frames(&q0)?[e.parent];
    let last = *frames.last().unwrap_or_else(|| unreachable!());
    let fo = flange.translation.vector;
    let fx = flange.rotation * Vector3::x();
    frames.push(Frame {
        o: last.o + last.z * last.z.dot(&(fo - last.o)),
        x: normal_part(&fx, &last.z)
            .or_else(|| normal_part(&(flange.rotation * Vector3::y()), &last.z))
            .unwrap_or(last.x),
        z: last.z,
    });
    let rows = rows_between(robot, &chain, &frames);
    let world_from_base = frames[0].pose();
    let world_from_n = frames.last().unwrap_or_else(|| unreachable!()).pose();
    let tool = world_from_n.inverse() * robot.fk_ee(&q0, ee)?;
    Ok(in_convention(rows, world_from_base, tool, convention))
}

/// The standard table as is, or regrouped into the modified convention (exact).
fn in_convention(rows: Vec<DhJoint>, base: Pose, tool: Pose, convention: Convention) -> DerivedDh {
    if convention == Convention::Standard {
        return DerivedDh {
            convention,
            joints: rows,
            world_from_base: base,
            flange_from_tool: tool,
        };
    }
    let plain: Vec<DhRow> = rows.iter().map(|r| r.row).collect();
    let (modified, extra) = standard_to_modified(&plain);
    let joints = rows
        .into_iter()
        .zip(modified)
        .map(|(mut j, row)| {
            j.row = row;
            j
        })
        .collect();
    DerivedDh {
        convention,
        joints,
        world_from_base: base,
        flange_from_tool: extra * tool,
    }
}

impl DerivedDh {
    /// The robot this table describes (same joint names, limits and q).
    pub fn robot(&self, name: &str) -> Result<Robot, super::ModelError> {
        Robot::from_dh(
            name,
            self.convention,
            &self.joints,
            self.world_from_base,
            self.flange_from_tool,
        )
    }
}

/// The derived table's FK against the chain's at q = 0 and eight spread joint vectors: the
/// largest difference (m; rotation differences times `scale`), an error above `limit`.
fn check(
    robot: &Robot,
    ee: usize,
    d: &DerivedDh,
    scale: f64,
    limit: f64,
) -> Result<f64, NoDhTable> {
    let dh = d.robot(&robot.name).map_err(|e| NoDhTable::Invalid {
        reason: e.to_string(),
    })?;
    let ranges = robot.sampling_ranges();
    let mut worst: f64 = 0.0;
    for k in 0..9 {
        let q: Vec<f64> = ranges
            .iter()
            .enumerate()
            .map(|(i, r)| {
                let t = ((k * 7 + i * 3) % 11) as f64 / 10.0;
                if k == 0 {
                    0.0
                } else {
                    r[0] + (r[1] - r[0]) * t
                }
            })
            .collect();
        let (a, b) = (robot.fk_ee(&q, ee)?, dh.fk(&q)?);
        let dp = (a.translation.vector - b.translation.vector).norm();
        let dr = (a.rotation.matrix() - b.rotation.matrix()).amax() * scale;
        worst = worst.max(dp).max(dr);
    }
    if worst.is_finite() && worst <= limit {
        Ok(worst)
    } else {
        Err(NoDhTable::Mismatch { error: worst })
    }
}
