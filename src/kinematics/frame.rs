//! The FK inner loop: a rigid transform as plain column arrays, updated in place joint by joint.
//! Revolute DH rows take a specialised product (30 multiplications instead of ~50); every other
//! joint goes through the general `pre * M(value) * post`.

use super::fk::local;
use super::pose::{Pose, compose};
use super::robot::{FastDh, Lowered};
use super::trig::sin_cos;
use nalgebra::{Matrix3, Rotation3, Translation3};

/// Rotation columns `r[0..3]` and translation `t` of a pose.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Frame {
    r: [[f64; 3]; 3],
    t: [f64; 3],
}

#[inline(always)]
fn lin(a: f64, x: &[f64; 3], b: f64, y: &[f64; 3]) -> [f64; 3] {
    [
        a * x[0] + b * y[0],
        a * x[1] + b * y[1],
        a * x[2] + b * y[2],
    ]
}

impl Frame {
    /// From a pose.
    #[inline(always)]
    pub(crate) fn from_pose(p: &Pose) -> Self {
        let m = p.rotation.matrix();
        let col = |c: usize| [m[(0, c)], m[(1, c)], m[(2, c)]];
        let v = &p.translation.vector;
        Self {
            r: [col(0), col(1), col(2)],
            t: [v.x, v.y, v.z],
        }
    }

    /// The origin of `self * tool` (world, m) without forming the rotation product.
    #[inline(always)]
    pub(crate) fn point_of(&self, tool: &Pose) -> [f64; 3] {
        let v = &tool.translation.vector;
        let [c0, c1, c2] = self.r;
        std::array::from_fn(|k| self.t[k] + c0[k] * v.x + c1[k] * v.y + c2[k] * v.z)
    }

    /// `R^T g` for this frame's rotation R: the rotation from this frame to `g`'s.
    #[inline(always)]
    pub(crate) fn rotation_to(&self, g: &Matrix3<f64>) -> Matrix3<f64> {
        let dot = |c: &[f64; 3], j: usize| c[0] * g[(0, j)] + c[1] * g[(1, j)] + c[2] * g[(2, j)];
        let [c0, c1, c2] = &self.r;
        Matrix3::new(
            dot(c0, 0),
            dot(c0, 1),
            dot(c0, 2),
            dot(c1, 0),
            dot(c1, 1),
            dot(c1, 2),
            dot(c2, 0),
            dot(c2, 1),
            dot(c2, 2),
        )
    }

    /// Back to a pose.
    #[inline(always)]
    pub(crate) fn to_pose(self) -> Pose {
        let [c0, c1, c2] = self.r;
        let m = Matrix3::new(
            c0[0], c1[0], c2[0], c0[1], c1[1], c2[1], c0[2], c1[2], c2[2],
        );
        Pose::from_parts(
            Translation3::new(self.t[0], self.t[1], self.t[2]),
            Rotation3::from_matrix_unchecked(m),
        )
    }

    /// `self = self * pre * M(var + offset) * post` for one lowered joint.
    #[inline(always)]
    pub(crate) fn apply(&mut self, l: &Lowered, var: f64) {
        let theta = var + l.offset;
        match l.fast {
            // (2.52): R Rz(theta) then Rx(alpha); t += a x_i + d z_{i-1}.
            Some(FastDh::Standard([ca, sa, a, d])) => {
                let (s, c) = sin_cos(theta);
                let [r0, r1, r2] = self.r;
                let m0 = lin(c, &r0, s, &r1);
                let m1 = lin(-s, &r0, c, &r1);
                for k in 0..3 {
                    self.t[k] += a * m0[k] + d * r2[k];
                }
                self.r = [m0, lin(ca, &m1, sa, &r2), lin(-sa, &m1, ca, &r2)];
            }
            // Craig: R Rx(alpha), t += a x; then Rz(theta); then t += d z.
            Some(FastDh::Modified([ca, sa, a, d])) => {
                let (s, c) = sin_cos(theta);
                let [r0, r1, r2] = self.r;
                let n1 = lin(ca, &r1, sa, &r2);
                let n2 = lin(-sa, &r1, ca, &r2);
                for k in 0..3 {
                    self.t[k] += a * r0[k] + d * n2[k];
                }
                self.r = [lin(c, &r0, s, &n1), lin(-s, &r0, c, &n1), n2];
            }
            None => *self = Frame::from_pose(&compose(&self.to_pose(), &local(l, var))),
        }
    }
}
