//! Passive joints of a closed chain whose values follow from the actuated joints through the
//! loop-closure equation of their mechanism, solved in closed form (the closed chains of
//! Sect. 2.9.2 and Problem 2.11). A joint driven this way has [`super::Drive::Closure`]; its
//! value and its derivatives with respect to the joints the loop reads are exact.
//!
//! The one mechanism so far is the **slider loop** of the four-link closed-chain planar arm with
//! a prismatic joint (Problem 2.11, Fig. 2.34): a crank of length `a_crank` and an arm of length
//! `a_arm` turn about the same base axis (angles theta_c, theta_a from the base x axis); link 2'
//! is pinned at the crank's end A; link 3' slides along link 2' (the prismatic joint, slide d
//! from A) and stands orthogonal to it; link 3' is pinned to the arm's end C at the distance
//! `offset` (c) from the slider. With v = C - A the loop closes when `d u(phi) + c n(phi) = v`
//! (u(phi) the direction of link 2', n(phi) its normal), so
//!
//! - `d = sqrt(|v|^2 - c^2)` (the assembly with d > 0),
//! - `phi = Atan2(v_y, v_x) - Atan2(c, d)`, and the revolute joint at A turns by
//!   `theta_2' = phi - theta_c` relative to the crank.
//!
//! The loop closes for every crank and arm angle when `|a_arm - a_crank| > |c|` (then
//! `|v| >= |a_arm - a_crank| > |c|`), which [`super::Robot::new`] checks.

use super::JointId;

/// The slider loop of Problem 2.11 (see the module documentation): lengths in m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SliderLoop {
    /// The crank: an actuated revolute joint at the base.
    pub crank: JointId,
    /// Its length, base axis to A (m).
    pub a_crank: f64,
    /// The arm: an actuated revolute joint about the same base axis.
    pub arm: JointId,
    /// Its length, base axis to C (m).
    pub a_arm: f64,
    /// c: the distance along link 3' from the slider to C (m), positive to the left of link 2'.
    pub offset: f64,
}

/// Which value of its loop a closure-driven joint takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LoopOutput {
    /// The angle of link 2' relative to the crank, theta_2' (rad): the revolute joint at A.
    Angle,
    /// The slide d along link 2' (m): the prismatic joint.
    Slide,
}

/// How a passive joint follows its loop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Closure {
    /// The loop.
    pub mechanism: SliderLoop,
    /// Which of its values the joint takes.
    pub output: LoopOutput,
}

/// The loop's values at one crank and arm angle, with their derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoopState {
    /// theta_2' (rad).
    pub angle: f64,
    /// d (m).
    pub slide: f64,
    /// d theta_2' / d (theta_c, theta_a).
    pub d_angle: [f64; 2],
    /// d d / d (theta_c, theta_a) (m/rad).
    pub d_slide: [f64; 2],
}

impl SliderLoop {
    /// Whether the loop closes for every crank and arm angle: finite lengths with
    /// `|a_arm - a_crank| > |offset|`.
    pub fn always_closes(&self) -> bool {
        [self.a_crank, self.a_arm, self.offset]
            .iter()
            .all(|v| v.is_finite())
            && (self.a_arm - self.a_crank).abs() > self.offset.abs()
    }

    /// The loop at crank angle `theta_c` and arm angle `theta_a` (rad, from the base x axis).
    pub fn solve(&self, theta_c: f64, theta_a: f64) -> LoopState {
        let (sc, cc) = theta_c.sin_cos();
        let (sa, ca) = theta_a.sin_cos();
        let v = [
            self.a_arm * ca - self.a_crank * cc,
            self.a_arm * sa - self.a_crank * sc,
        ];
        let r2 = v[0] * v[0] + v[1] * v[1];
        let c = self.offset;
        // Never negative when the loop always closes; clamped against rounding.
        let d = (r2 - c * c).max(0.0).sqrt();
        let phi = v[1].atan2(v[0]) - c.atan2(d);
        // dv / d(theta_c, theta_a)
        let dv = [
            [self.a_crank * sc, -self.a_crank * cc],
            [-self.a_arm * sa, self.a_arm * ca],
        ];
        let mut d_angle = [0.0; 2];
        let mut d_slide = [0.0; 2];
        for k in 0..2 {
            let dd = (v[0] * dv[k][0] + v[1] * dv[k][1]) / d;
            let dphi = (v[0] * dv[k][1] - v[1] * dv[k][0] + c * dd) / r2;
            d_slide[k] = dd;
            d_angle[k] = dphi - if k == 0 { 1.0 } else { 0.0 };
        }
        LoopState {
            angle: phi - theta_c,
            slide: d,
            d_angle,
            d_slide,
        }
    }
}

impl Closure {
    /// The joint's value and its derivatives with respect to the crank and arm angles.
    pub fn value(&self, theta_c: f64, theta_a: f64) -> (f64, [f64; 2]) {
        let s = self.mechanism.solve(theta_c, theta_a);
        match self.output {
            LoopOutput::Angle => (s.angle, s.d_angle),
            LoopOutput::Slide => (s.slide, s.d_slide),
        }
    }
}
