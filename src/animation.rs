//! The motions of `armlab animate`: one joint vector (and what to draw with it) per frame,
//! computed here by the kinematics and redundancy layers; the figure layer only paints them
//! ([`crate::figure::animation`]).
//!
//! - [`Motion::SelfMotion`]: the hand held still at the "ready" pose while the parameter of the
//!   exact self-motion (arm angle, q7, a locked joint) sweeps the feasible interval of the ready
//!   configuration's branch, there and back.
//! - [`Motion::Postures`]: every closed-form posture of the ready pose in turn, morphing from
//!   one to the next in joint space (shortest way round for revolute joints), the others shown
//!   as ghosts.
//! - [`Motion::DhFrames`]: the Denavit-Hartenberg build (Sect. 2.8.2): each `A_i` as its four
//!   elementary motions, `Rot(z, theta_i) Trans(z, d_i) Trans(x, a_i) Rot(x, alpha_i)` (2.52)
//!   (Craig's order for a modified table), frame `i-1` carried onto frame `i`.
//! - [`Motion::Path`]: a straight tool path at constant speed, solved by the closed form
//!   (the posture nearest the previous sample) or the numerical solver, with the joint rates.

pub mod rotation;

use crate::kinematics::dh::Convention;
use crate::kinematics::ik::Target;
use crate::kinematics::ik::solver::{self, SolverChoice};
use crate::kinematics::{JointKind, Pose, Robot};
use crate::redundancy::motion::ExactSelfMotion;
use nalgebra::{Translation3, UnitQuaternion, Vector3};
use std::f64::consts::PI;
use thiserror::Error;

/// What an animation shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Motion {
    /// The self-motion with the hand held still.
    SelfMotion,
    /// A morph through the closed-form postures.
    Postures,
    /// The DH build, four elementary motions per joint.
    DhFrames,
    /// A straight tool path with the joint rates.
    Path,
}

/// One frame of an animation.
#[derive(Debug, Clone, PartialEq)]
pub struct Shot {
    /// The arm's joint vector (rad, m).
    pub q: Vec<f64>,
    /// One line saying what the frame shows.
    pub caption: String,
    /// Other configurations shown as ghosts (the postures).
    pub ghosts: Vec<Vec<f64>>,
    /// DH frames already built, `world_from_frame_k` (DH build).
    pub frames: Vec<(String, Pose)>,
    /// The frame being carried by the current elementary motion (DH build).
    pub moving: Option<(String, Pose)>,
    /// Time of the frame from the start (s).
    pub time: f64,
}

/// The joint rates along a tool path.
#[derive(Debug, Clone, PartialEq)]
pub struct Rates {
    /// Sample times (s).
    pub t: Vec<f64>,
    /// Joint rates at each sample (rad/s or m/s), one vector per sample.
    pub qdot: Vec<Vec<f64>>,
    /// Tool speed along the path (m/s).
    pub speed: f64,
}

/// An animation's frames and what stays the same through them.
#[derive(Debug, Clone, PartialEq)]
pub struct Animation {
    /// Title of every frame.
    pub title: String,
    /// The frames, in order, evenly spaced in time.
    pub shots: Vec<Shot>,
    /// A polyline drawn in every frame (world, m): the elbow's circle of a self-motion, the
    /// tool path.
    pub trace: Vec<Vector3<f64>>,
    /// The joint rates of a tool path.
    pub rates: Option<Rates>,
}

/// Why an animation cannot be made.
#[derive(Debug, Error)]
pub enum AnimationError {
    /// The arm has no exact self-motion (it is not redundant, or not of a solved family).
    #[error("{robot}: no exact self-motion to animate ({reason})")]
    NoSelfMotion {
        /// The arm.
        robot: String,
        /// Why.
        reason: String,
    },
    /// The arm has no closed form, so no postures to morph through.
    #[error("{robot}: no closed-form postures to animate ({reason})")]
    NoPostures {
        /// The arm.
        robot: String,
        /// Why.
        reason: String,
    },
    /// The DH build needs a serial DH table.
    #[error(
        "{robot}: the DH build needs a serial chain described by DH rows (a built-in arm or a \
         model file with a DH table)"
    )]
    NoDhTable {
        /// The arm.
        robot: String,
    },
    /// The tool path leaves the workspace.
    #[error("{robot}: the tool path is not reachable at {fraction:.0} % of its length")]
    PathUnreachable {
        /// The arm.
        robot: String,
        /// Where (percent of the length).
        fraction: f64,
    },
    /// Bad frame count or duration.
    #[error("an animation needs 2 to 10000 frames and a positive duration (got {frames} frames)")]
    Frames {
        /// Frames asked for.
        frames: usize,
    },
    /// A kinematics failure (wrong joint count, NaN).
    #[error(transparent)]
    Kinematics(#[from] crate::kinematics::KinematicsError),
}

/// The motion's frames: `frames` of them over `seconds`, starting from the arm's "ready"
/// configuration (or zero).
pub fn plan(
    robot: &Robot,
    motion: Motion,
    frames: usize,
    seconds: f64,
) -> Result<Animation, AnimationError> {
    if !((2..=10_000).contains(&frames) && seconds > 0.0 && seconds.is_finite()) {
        return Err(AnimationError::Frames { frames });
    }
    let q0 = robot
        .config("ready")
        .map(<[f64]>::to_vec)
        .unwrap_or_else(|| vec![0.0; robot.dof()]);
    let dt = seconds / frames as f64;
    let mut anim = match motion {
        Motion::SelfMotion => self_motion(robot, &q0, frames)?,
        Motion::Postures => postures(robot, &nudged(robot, &q0, &vec![0.3; robot.dof()]), frames)?,
        Motion::DhFrames => dh_build(robot, &q0, frames)?,
        Motion::Path => path(robot, &q0, frames, dt)?,
    };
    for (k, s) in anim.shots.iter_mut().enumerate() {
        s.time = k as f64 * dt;
    }
    Ok(anim)
}

/// A shot of `q` with a caption and nothing else.
fn shot(q: Vec<f64>, caption: String) -> Shot {
    Shot {
        q,
        caption,
        ghosts: Vec::new(),
        frames: Vec::new(),
        moving: None,
        time: 0.0,
    }
}

/// The self-motion through `q0`'s hand pose: its branch's feasible interval swept there and
/// back (a cosine ramp, so the ends are slow).
fn self_motion(robot: &Robot, q0: &[f64], n: usize) -> Result<Animation, AnimationError> {
    let pose = robot.fk(q0)?;
    let m = ExactSelfMotion::new(robot, &pose).map_err(|e| AnimationError::NoSelfMotion {
        robot: robot.name.clone(),
        reason: e.to_string(),
    })?;
    let (branch, v0) = m.locate(robot, q0).unwrap_or((0, 0.0));
    let ivs = &m.feasible()[branch];
    let [lo, hi] = ivs
        .iter()
        .find(|iv| iv[0] <= v0 && v0 <= iv[1])
        .or_else(|| {
            ivs.iter()
                .max_by(|a, b| (a[1] - a[0]).total_cmp(&(b[1] - b[0])))
        })
        .copied()
        .unwrap_or([-PI, PI]);
    let name = m.names()[branch].clone();
    let parameter = m.parameter();
    let mut shots = Vec::with_capacity(n);
    let mut last = q0.to_vec();
    let elbow = elbow_joint(robot);
    let mut trace = Vec::new();
    for k in 0..n {
        let s = k as f64 / n as f64;
        let v = lo + (hi - lo) * 0.5 * (1.0 - (2.0 * PI * s).cos());
        if let Some(sol) = m.solutions(robot, v).into_iter().find(|b| b.name == name) {
            last = sol.q;
        }
        trace.push(robot.fk_frames(&last)?[elbow].translation.vector);
        shots.push(shot(
            last.clone(),
            format!(
                "{parameter} = {:.1} deg of the feasible {:.1} .. {:.1} deg ({name}); the hand \
                 does not move",
                v.to_degrees(),
                lo.to_degrees(),
                hi.to_degrees()
            ),
        ));
    }
    Ok(Animation {
        title: format!("Self-motion of the {}", robot.name.to_lowercase()),
        shots,
        trace,
        rates: None,
    })
}

/// The joint whose frame is the elbow (the middle of the chain to the first end-effector).
fn elbow_joint(robot: &Robot) -> usize {
    let chain = robot.chain_to(robot.end_effectors()[0].parent);
    chain[chain.len() / 2]
}

/// The closed-form postures of `q0`'s hand pose (moved off the ready configuration, often
/// singular), each held, then morphed into the next.
fn postures(robot: &Robot, q0: &[f64], n: usize) -> Result<Animation, AnimationError> {
    let pose = robot.fk(q0)?;
    let no = |reason: String| AnimationError::NoPostures {
        robot: robot.name.clone(),
        reason,
    };
    let (result, _) = solver::solve(
        robot,
        0,
        &Target::Pose(pose),
        None,
        SolverChoice::ClosedForm,
        &Default::default(),
    )
    .map_err(|e| no(e.to_string()))?;
    let sols = result.solutions;
    if sols.len() < 2 {
        return Err(no(format!("{} posture at the ready pose", sols.len())));
    }
    let ghosts: Vec<Vec<f64>> = sols.iter().map(|s| s.q.clone()).collect();
    let m = sols.len();
    let mut shots = Vec::with_capacity(n);
    for k in 0..n {
        // Segment j: hold posture j for 40 % of it, then morph into j + 1 (smooth step).
        let x = k as f64 / n as f64 * m as f64;
        let j = (x.floor() as usize).min(m - 1);
        let f = x - j as f64;
        let (a, b) = (&sols[j], &sols[(j + 1) % m]);
        let (q, caption) = if f < 0.4 {
            (
                a.q.clone(),
                format!("posture {} of {m}: {}", j + 1, a.posture),
            )
        } else {
            let t = (f - 0.4) / 0.6;
            let t = t * t * (3.0 - 2.0 * t);
            let q = robot
                .joints()
                .iter()
                .filter(|jt| jt.kind != JointKind::Fixed)
                .zip(a.q.iter().zip(&b.q))
                .map(|(jt, (x, y))| {
                    let d = if jt.kind == JointKind::Revolute {
                        (y - x + PI).rem_euclid(2.0 * PI) - PI
                    } else {
                        y - x
                    };
                    x + t * d
                })
                .collect::<Vec<_>>();
            let q = if q.len() == a.q.len() { q } else { a.q.clone() };
            (q, format!("{}  ->  {}", a.posture, b.posture))
        };
        let mut s = shot(q, caption);
        s.ghosts = ghosts.clone();
        shots.push(s);
    }
    Ok(Animation {
        title: format!(
            "The {m} postures of the {} for one hand pose",
            robot.name.to_lowercase()
        ),
        shots,
        trace: Vec::new(),
        rates: None,
    })
}

/// An elementary motion of the DH build: rotation about or translation along z or x.
#[derive(Debug, Clone, Copy)]
enum Step {
    RotZ(f64),
    TransZ(f64),
    TransX(f64),
    RotX(f64),
}

impl Step {
    /// The motion carried out to fraction `s` (0..1).
    fn pose(self, s: f64) -> Pose {
        match self {
            Step::RotZ(t) => Pose::from_parts(
                Translation3::identity(),
                UnitQuaternion::from_axis_angle(&Vector3::z_axis(), s * t).to_rotation_matrix(),
            ),
            Step::RotX(t) => Pose::from_parts(
                Translation3::identity(),
                UnitQuaternion::from_axis_angle(&Vector3::x_axis(), s * t).to_rotation_matrix(),
            ),
            Step::TransZ(d) => Pose::from_parts(
                Translation3::new(0.0, 0.0, s * d),
                nalgebra::Rotation3::identity(),
            ),
            Step::TransX(d) => Pose::from_parts(
                Translation3::new(s * d, 0.0, 0.0),
                nalgebra::Rotation3::identity(),
            ),
        }
    }

    /// The step's name in the book's notation for joint `i` (1-based).
    fn name(self, i: usize) -> String {
        match self {
            Step::RotZ(t) => format!("Rot(z, theta{i} = {:.1} deg)", t.to_degrees()),
            Step::TransZ(d) => format!("Trans(z, d{i} = {d:.3} m)"),
            Step::TransX(a) => format!("Trans(x, a{i} = {a:.3} m)"),
            Step::RotX(t) => format!("Rot(x, alpha{i} = {:.1} deg)", t.to_degrees()),
        }
    }
}

/// The four elementary motions of `A_i`, taken from the relative pose of frames i-1 and i (so
/// that offsets and the joint variable are in theta or d as the arm has them).
fn elementary_steps(convention: Convention, a: f64, alpha: f64, rel: &Pose) -> [Step; 4] {
    let r = rel.rotation.matrix();
    let p = rel.translation.vector;
    match convention {
        // A = Rz(theta) Tz(d) Tx(a) Rx(alpha): first column (c, s, 0), p_z = d.  (2.52)
        Convention::Standard => [
            Step::RotZ(r[(1, 0)].atan2(r[(0, 0)])),
            Step::TransZ(p.z),
            Step::TransX(a),
            Step::RotX(alpha),
        ],
        // A = Rx(alpha) Tx(a) Rz(theta) Tz(d): Rx(-alpha) R = Rz(theta);
        // p = (a, 0, 0) + Rx(alpha) (0, 0, d).
        Convention::Modified => {
            let rx = nalgebra::Rotation3::from_axis_angle(&Vector3::x_axis(), -alpha);
            let m = rx * rel.rotation;
            let local = rx * (p - Vector3::new(a, 0.0, 0.0));
            [
                Step::RotX(alpha),
                Step::TransX(a),
                Step::RotZ(m.matrix()[(1, 0)].atan2(m.matrix()[(0, 0)])),
                Step::TransZ(local.z),
            ]
        }
    }
}

/// The DH build of `q0`: frame 0 at the base, then each `A_i` as four elementary motions.
fn dh_build(robot: &Robot, q0: &[f64], n: usize) -> Result<Animation, AnimationError> {
    let (convention, rows) = robot.dh_table().ok_or_else(|| AnimationError::NoDhTable {
        robot: robot.name.clone(),
    })?;
    let world = robot.fk_frames(q0)?;
    let base: (String, Pose) = ("0".into(), robot.base);
    let mut steps: Vec<(usize, usize, Step)> = Vec::new();
    let mut prev = robot.base;
    for (i, (_, row, _)) in rows.iter().enumerate() {
        let rel = prev.inverse() * world[i];
        for (k, s) in elementary_steps(convention, row.a, row.alpha, &rel)
            .into_iter()
            .enumerate()
        {
            steps.push((i, k, s));
        }
        prev = world[i];
    }
    let total = steps.len();
    let mut shots = Vec::with_capacity(n);
    for f in 0..n {
        // Step index and progress; the last 10 % of the frames show the finished build.
        let x = (f as f64 / (0.9 * n as f64)).min(1.0) * total as f64;
        let idx = (x.floor() as usize).min(total - 1);
        let progress = if x >= total as f64 {
            1.0
        } else {
            x - idx as f64
        };
        let (i, k, step) = steps[idx];
        // Frames 0..i built; frame i-1 carried through steps 0..k of A_{i+1}.
        let mut frames: Vec<(String, Pose)> = vec![base.clone()];
        frames.extend((0..i).map(|j| (format!("{}", j + 1), world[j])));
        let from = if i == 0 { robot.base } else { world[i - 1] };
        let mut carried = from;
        for (_, _, s) in steps[idx - k..idx].iter() {
            carried *= s.pose(1.0);
        }
        carried *= step.pose(progress.clamp(0.0, 1.0));
        let names: Vec<String> = steps[idx - k..idx + 4 - k]
            .iter()
            .map(|(_, _, s)| s.name(i + 1))
            .collect();
        let caption = if x >= total as f64 {
            format!(
                "T_{}^0 = A_1 ... A_{}: every frame built",
                rows.len(),
                rows.len()
            )
        } else {
            format!(
                "A_{} = {}  |  step {} of 4: {}",
                i + 1,
                names.join(" "),
                k + 1,
                names[k]
            )
        };
        let mut s = shot(q0.to_vec(), caption);
        s.frames = frames;
        s.moving = Some((format!("{}", i + 1), carried));
        if x >= total as f64 {
            s.frames
                .push((format!("{}", rows.len()), world[rows.len() - 1]));
            s.moving = None;
        }
        shots.push(s);
    }
    Ok(Animation {
        title: format!(
            "Denavit-Hartenberg frames of the {}, one elementary motion at a time",
            robot.name.to_lowercase()
        ),
        shots,
        trace: Vec::new(),
        rates: None,
    })
}

/// Joint vector `q` moved by `delta` (rad or m per joint), each joint kept inside its limits
/// with a margin of a tenth of its range.
fn nudged(robot: &Robot, q: &[f64], delta: &[f64]) -> Vec<f64> {
    let limits = robot.limits();
    q.iter()
        .zip(delta)
        .zip(&limits)
        .map(|((v, d), [lo, hi])| {
            let (lo, hi) = if lo.is_finite() && hi.is_finite() {
                let m = 0.1 * (hi - lo);
                (lo + m, hi - m)
            } else {
                (*lo, *hi)
            };
            (v + d).clamp(lo, hi.max(lo))
        })
        .collect()
}

/// A straight tool path at constant speed and fixed orientation, between the tool poses of
/// two configurations near the ready one (moved off it, since ready configurations often sit
/// on a singularity: the Puma's wrist); IK at every frame, the closed-form posture nearest the
/// previous frame (or the numerical solver seeded there).
fn path(robot: &Robot, ready: &[f64], n: usize, dt: f64) -> Result<Animation, AnimationError> {
    let dof = robot.dof();
    let q0 = nudged(robot, ready, &vec![0.3; dof]);
    let mut delta = vec![0.0; dof];
    for (k, d) in [0.5, 0.35, -0.35].iter().enumerate().take(dof) {
        delta[k] = *d;
    }
    let start = robot.fk(&q0)?;
    let p0 = start.translation.vector;
    let p1 = robot.fk(&nudged(robot, &q0, &delta))?.translation.vector;
    let length = (p1 - p0).norm();
    let q0 = q0.as_slice();
    let mut qs: Vec<Vec<f64>> = Vec::with_capacity(n);
    let mut last = q0.to_vec();
    let mut trace = Vec::with_capacity(n);
    for k in 0..n {
        let s = k as f64 / (n - 1) as f64;
        let p = p0 + (p1 - p0) * s;
        trace.push(p);
        let target = Pose::from_parts(Translation3::from(p), start.rotation);
        let (result, _) = solver::solve(
            robot,
            0,
            &Target::Pose(target),
            Some(&last),
            SolverChoice::Auto,
            &Default::default(),
        )
        .map_err(|_| AnimationError::PathUnreachable {
            robot: robot.name.clone(),
            fraction: 100.0 * s,
        })?;
        let best = solver::closest(robot, &result.solutions, &last).ok_or(
            AnimationError::PathUnreachable {
                robot: robot.name.clone(),
                fraction: 100.0 * s,
            },
        )?;
        if best.position_error > 1e-6 {
            return Err(AnimationError::PathUnreachable {
                robot: robot.name.clone(),
                fraction: 100.0 * s,
            });
        }
        last = best.q.clone();
        qs.push(last.clone());
    }
    let qdot = rates_of(&qs, dt);
    let speed = length / ((n - 1) as f64 * dt);
    let shots = qs
        .iter()
        .enumerate()
        .map(|(k, q)| {
            shot(
                q.clone(),
                format!(
                    "straight tool path, {:.3} m at {speed:.3} m/s: {:.0} %",
                    length,
                    100.0 * k as f64 / (n - 1) as f64
                ),
            )
        })
        .collect();
    Ok(Animation {
        title: format!("A straight tool path of the {}", robot.name.to_lowercase()),
        shots,
        trace,
        rates: Some(Rates {
            t: (0..n).map(|k| k as f64 * dt).collect(),
            qdot,
            speed,
        }),
    })
}

/// Joint rates of samples `dt` apart, by central differences (one-sided at the ends).
fn rates_of(qs: &[Vec<f64>], dt: f64) -> Vec<Vec<f64>> {
    let n = qs.len();
    (0..n)
        .map(|k| {
            let (a, b) = (k.saturating_sub(1), (k + 1).min(n - 1));
            qs[a]
                .iter()
                .zip(&qs[b])
                .map(|(x, y)| (y - x) / ((b - a) as f64 * dt))
                .collect()
        })
        .collect()
}
