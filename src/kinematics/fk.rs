//! Direct kinematics, eq. (2.50): the pose of every joint frame and of each end-effector.

use super::error::KinematicsError;
pub(crate) use super::frame::Frame;
use super::pose::Pose;
use super::robot::{Drive, Lowered, Motion, Robot};
use nalgebra::{Matrix3, Rotation3, Translation3, Vector3};

impl Robot {
    /// Checks that `q` has `dof()` finite entries.
    ///
    /// # Examples
    ///
    /// Every function that takes a joint vector reports a wrong one as a typed
    /// [`KinematicsError`] instead of panicking:
    ///
    /// ```
    /// use armlab::kinematics::KinematicsError;
    /// use armlab::kinematics::models::built_in;
    ///
    /// let planar2 = built_in("planar2").expect("a built-in model");
    /// assert_eq!(planar2.check_q(&[0.1, 0.2]), Ok(()));
    /// assert_eq!(
    ///     planar2.fk(&[0.1, 0.2, 0.3]).unwrap_err(),
    ///     KinematicsError::DofMismatch { expected: 2, got: 3 }
    /// );
    /// let err = planar2.fk(&[0.1, f64::NAN]).unwrap_err();
    /// assert!(matches!(err, KinematicsError::NonFinite { index: 1, .. }));
    /// assert_eq!(err.to_string(), "joint value 1 (q2) is not a finite number: NaN");
    /// ```
    pub fn check_q(&self, q: &[f64]) -> Result<(), KinematicsError> {
        if q.len() != self.dof() {
            return Err(KinematicsError::DofMismatch {
                expected: self.dof(),
                got: q.len(),
            });
        }
        if let Some((index, &value)) = q.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(KinematicsError::NonFinite {
                index,
                name: self.dof_joint(index).name.clone(),
                value,
            });
        }
        Ok(())
    }

    /// End-effector `ee`, or the error naming how many there are.
    pub fn end_effector(
        &self,
        ee: usize,
    ) -> Result<&crate::kinematics::EndEffector, KinematicsError> {
        self.end_effectors()
            .get(ee)
            .ok_or(KinematicsError::NoSuchEndEffector {
                index: ee,
                count: self.end_effectors().len(),
            })
    }

    /// The variable of joint `j` (before its offset) for the joint vector `q`: `q[k]` for an
    /// actuated joint, the linear combination for a coupled one, the loop's closed-form value
    /// for a closure-driven one, 0 for a fixed one.
    /// `q` must already be checked.
    #[inline]
    pub fn joint_variable(&self, j: usize, q: &[f64]) -> f64 {
        match &self.joints()[j].drive {
            Drive::Actuated(k) => q[*k],
            Drive::Coupled(terms) => terms
                .iter()
                .map(|&(src, c)| match self.joints()[src].drive {
                    Drive::Actuated(k) => c * q[k],
                    _ => 0.0,
                })
                .sum(),
            Drive::Closure(c) => {
                let m = &c.mechanism;
                c.value(self.joint_angle(m.crank, q), self.joint_angle(m.arm, q))
                    .0
            }
            Drive::None => 0.0,
        }
    }

    /// The angle of the actuated revolute joint `j` (variable plus offset, rad).
    #[inline]
    pub(crate) fn joint_angle(&self, j: usize, q: &[f64]) -> f64 {
        let joint = &self.joints()[j];
        match joint.drive {
            Drive::Actuated(k) => q[k] + joint.offset,
            _ => joint.offset,
        }
    }

    #[inline(always)]
    fn variable_of(&self, j: usize, l: &Lowered, q: &[f64]) -> f64 {
        match l.dof {
            Some(k) => q[k],
            None => self.joint_variable(j, q),
        }
    }

    /// `world_from_frame_j` for every joint j into `frames` (length `joints().len()`), with no
    /// allocation. Frame j is the joint's output frame (DH frame j for a DH chain).
    pub fn fk_frames_into(&self, q: &[f64], frames: &mut [Pose]) -> Result<(), KinematicsError> {
        self.check_q(q)?;
        assert_eq!(
            frames.len(),
            self.lowered.len(),
            "frames buffer has the wrong length"
        );
        for (j, l) in self.lowered.iter().enumerate() {
            let mut f = Frame::from_pose(&match l.parent {
                Some(p) => frames[p],
                None => self.base,
            });
            f.apply(l, self.variable_of(j, l, q));
            frames[j] = f.to_pose();
        }
        Ok(())
    }

    /// `world_from_frame_j` for every joint j.
    ///
    /// # Examples
    ///
    /// The frames of the three-link planar arm (a = 0.5, 0.3, 0.2 m): the origin of frame 1 is
    /// the elbow at `(a1 c1, a1 s1)`, that of frame 2 the wrist.
    ///
    /// ```
    /// use armlab::kinematics::models::built_in;
    ///
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// let arm = built_in("planar3").expect("a built-in model");
    /// let q = [0.4, -0.3, 0.2];
    /// let frames = arm.fk_frames(&q)?;
    /// assert_eq!(frames.len(), 3);
    /// let elbow = frames[0].translation.vector;
    /// assert!((elbow.x - 0.5 * q[0].cos()).abs() < 1e-15);
    /// assert!((elbow.y - 0.5 * q[0].sin()).abs() < 1e-15);
    /// // The last frame is the flange: the tool of this model is the identity.
    /// let tool = arm.fk(&q)?;
    /// assert!((frames[2].to_homogeneous() - tool.to_homogeneous()).amax() < 1e-15);
    /// # Ok(())
    /// # }
    /// ```
    pub fn fk_frames(&self, q: &[f64]) -> Result<Vec<Pose>, KinematicsError> {
        let mut f = vec![Pose::identity(); self.lowered.len()];
        self.fk_frames_into(q, &mut f)?;
        Ok(f)
    }

    /// `world_from_tool` of end-effector `ee`, eq. (2.50) followed by the tool transform:
    /// `T = base * A_1(q_1) ... A_n(q_n) * tool`. Allocation-free; only the joints on the
    /// end-effector's chain are evaluated.
    pub fn fk_ee(&self, q: &[f64], ee: usize) -> Result<Pose, KinematicsError> {
        self.check_q(q)?;
        let e = self.end_effector(ee)?;
        let mut f = Frame::from_pose(&self.base);
        for &j in &self.chains[e.parent] {
            let l = &self.lowered[j];
            f.apply(l, self.variable_of(j, l, q));
        }
        let t = f.to_pose();
        Ok(t * e.tool)
    }

    /// Position of end-effector `ee` (world, m): the workspace-sampling hot path. Same checks as
    /// [`Self::fk_ee`], but the tool's rotation is never multiplied out.
    ///
    /// # Examples
    ///
    /// ```
    /// use armlab::kinematics::models::built_in;
    ///
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// let puma = built_in("puma560").expect("a built-in model");
    /// let q = [0.1, -0.4, 0.3, 0.5, -0.2, 0.9];
    /// let p = puma.fk_ee_position(&q, 0)?;
    /// let t = puma.fk(&q)?.translation.vector;
    /// assert!((p[0] - t.x).abs() < 1e-15 && (p[1] - t.y).abs() < 1e-15 && (p[2] - t.z).abs() < 1e-15);
    /// // An end-effector the robot does not have is an error, not a panic.
    /// assert!(puma.fk_ee_position(&q, 1).is_err());
    /// # Ok(())
    /// # }
    /// ```
    pub fn fk_ee_position(&self, q: &[f64], ee: usize) -> Result<[f64; 3], KinematicsError> {
        self.check_q(q)?;
        if ee >= self.end_effectors().len() {
            return Err(KinematicsError::NoSuchEndEffector {
                index: ee,
                count: self.end_effectors().len(),
            });
        }
        Ok(self.fk_ee_position_prechecked(q, ee))
    }

    /// [`Self::fk_ee_position`] for a `q` already known to have `dof()` finite entries and an
    /// existing `ee` (samplers that draw q inside the limits). Panics on a bad index.
    #[inline]
    pub fn fk_ee_position_prechecked(&self, q: &[f64], ee: usize) -> [f64; 3] {
        let e = &self.end_effectors()[ee];
        let mut f = Frame::from_pose(&self.base);
        for &j in &self.chains[e.parent] {
            let l = &self.lowered[j];
            f.apply(l, self.variable_of(j, l, q));
        }
        f.point_of(&e.tool)
    }

    /// The frame of end-effector `ee`'s parent joint (the flange: apply the end-effector's `tool`
    /// for the tool frame), as [`Self::fk_ee`] computes it, for joint vectors that often share their first `split` components (the
    /// closed-form solutions of one arm branch with the two wrist solutions): the frame after
    /// the chain's joints driven by `q[..split]` (and the fixed rows among them) is kept in
    /// `shared` and reused while those components are equal. Same result to the last bit as
    /// `fk_ee`, since the same products are taken in the same order.
    pub(crate) fn fk_ee_shared(
        &self,
        q: &[f64],
        ee: usize,
        shared: &mut SharedPrefix,
    ) -> Result<Frame, KinematicsError> {
        // The closed forms hand over q of length dof, every entry checked finite; a wrong length
        // is still an error, never a panic.
        if q.len() != self.dof() {
            return Err(KinematicsError::DofMismatch {
                expected: self.dof(),
                got: q.len(),
            });
        }
        debug_assert!(q.iter().all(|v| v.is_finite()));
        let e = self.end_effector(ee)?;
        let chain = &self.chains[e.parent];
        let split = shared.split.min(q.len());
        let (mut f, start) = match shared.frame {
            Some(f) if shared.ee == ee && shared.key[..split] == q[..split] => (f, shared.pos),
            _ => {
                let mut f = Frame::from_pose(&self.base);
                let mut pos = 0;
                for &j in chain {
                    let l = &self.lowered[j];
                    let in_prefix = match (l.dof, &self.joints()[j].drive) {
                        (Some(k), _) => k < split,
                        (None, Drive::None) => true,
                        _ => false,
                    };
                    if !in_prefix {
                        break;
                    }
                    f.apply(l, self.variable_of(j, l, q));
                    pos += 1;
                }
                shared.frame = Some(f);
                shared.pos = pos;
                shared.ee = ee;
                shared.key[..split].copy_from_slice(&q[..split]);
                (f, pos)
            }
        };
        for &j in &chain[start..] {
            let l = &self.lowered[j];
            f.apply(l, self.variable_of(j, l, q));
        }
        Ok(f)
    }

    /// `world_from_tool` of the first end-effector.
    ///
    /// # Examples
    ///
    /// The three-link planar arm's direct kinematics (2.63): `x = a1 c1 + a2 c12 + a3 c123`,
    /// `y = a1 s1 + a2 s12 + a3 s123`, and the tool's x axis at `phi = q1 + q2 + q3`.
    ///
    /// ```
    /// use armlab::kinematics::models::built_in;
    ///
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// let arm = built_in("planar3").expect("a built-in model");
    /// let (a1, a2, a3) = (0.5, 0.3, 0.2); // Problem 2.17
    /// let q = [0.3, 0.6, -0.4];
    /// let world_from_tool = arm.fk(&q)?;
    /// let (q12, q123) = (q[0] + q[1], q[0] + q[1] + q[2]);
    /// let x = a1 * q[0].cos() + a2 * q12.cos() + a3 * q123.cos();
    /// let y = a1 * q[0].sin() + a2 * q12.sin() + a3 * q123.sin();
    /// let p = world_from_tool.translation.vector;
    /// assert!((p.x - x).abs() < 1e-15 && (p.y - y).abs() < 1e-15 && p.z.abs() < 1e-15);
    /// let x_axis = world_from_tool.rotation * armlab::nalgebra::Vector3::x();
    /// assert!((x_axis.y.atan2(x_axis.x) - q123).abs() < 1e-15);
    /// # Ok(())
    /// # }
    /// ```
    pub fn fk(&self, q: &[f64]) -> Result<Pose, KinematicsError> {
        self.fk_ee(q, 0)
    }

    /// `world_from_tool` of every end-effector.
    ///
    /// # Examples
    ///
    /// The humanoid of Fig. 2.28 has two hands on one torso:
    ///
    /// ```
    /// use armlab::kinematics::models::built_in;
    ///
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// let humanoid = built_in("humanoid").expect("a built-in model");
    /// assert_eq!(humanoid.dof(), 17);
    /// let q = humanoid.ready_or_zero();
    /// let hands = humanoid.fk_all_ee(&q)?;
    /// assert_eq!(hands.len(), humanoid.end_effectors().len());
    /// for (k, hand) in hands.iter().enumerate() {
    ///     let alone = humanoid.fk_ee(&q, k)?;
    ///     assert!((hand.to_homogeneous() - alone.to_homogeneous()).amax() < 1e-12);
    /// }
    /// # Ok(())
    /// # }
    /// ```
    pub fn fk_all_ee(&self, q: &[f64]) -> Result<Vec<Pose>, KinematicsError> {
        let frames = self.fk_frames(q)?;
        Ok(self
            .end_effectors()
            .iter()
            .map(|e| frames[e.parent] * e.tool)
            .collect())
    }
}

/// The cached leading frame of [`Robot::fk_ee_shared`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct SharedPrefix {
    split: usize,
    key: [f64; 8],
    frame: Option<Frame>,
    pos: usize,
    ee: usize,
}

impl SharedPrefix {
    /// A cache of the frame after the joints driven by `q[..split]` (at most 8).
    pub(crate) fn new(split: usize) -> Self {
        Self {
            split: split.min(8),
            key: [0.0; 8],
            frame: None,
            pos: 0,
            ee: 0,
        }
    }
}

/// `pre * M(var + offset) * post` of one lowered joint.
#[inline]
pub(crate) fn local(l: &Lowered, var: f64) -> Pose {
    let v = var + l.offset;
    let moved = match l.motion {
        Motion::RotZ => {
            // Rz(theta) * post, written out: only the first two rows mix (2.8).
            let (s, c) = super::trig::sin_cos(v);
            let r = l.post.rotation.matrix();
            let t = &l.post.translation.vector;
            let m = Matrix3::new(
                c * r[(0, 0)] - s * r[(1, 0)],
                c * r[(0, 1)] - s * r[(1, 1)],
                c * r[(0, 2)] - s * r[(1, 2)],
                s * r[(0, 0)] + c * r[(1, 0)],
                s * r[(0, 1)] + c * r[(1, 1)],
                s * r[(0, 2)] + c * r[(1, 2)],
                r[(2, 0)],
                r[(2, 1)],
                r[(2, 2)],
            );
            let tv = Vector3::new(c * t.x - s * t.y, s * t.x + c * t.y, t.z);
            Pose::from_parts(Translation3::from(tv), Rotation3::from_matrix_unchecked(m))
        }
        Motion::TransZ => {
            let mut p = l.post;
            p.translation.vector.z += v;
            p
        }
        Motion::Rot(axis) => {
            Pose::from_parts(
                Translation3::identity(),
                Rotation3::from_axis_angle(&axis, v),
            ) * l.post
        }
        Motion::Trans(axis) => {
            Pose::from_parts(
                Translation3::from(axis.into_inner() * v),
                Rotation3::identity(),
            ) * l.post
        }
        Motion::Fixed => l.post,
    };
    if l.pre_is_identity {
        moved
    } else {
        l.pre * moved
    }
}
