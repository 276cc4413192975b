//! The composition of elementary rotations played as an animation (`armlab animate --what
//! rotation`, Sect. 2.3): each step turns the frame from where the previous one left it, about
//! the current frame's axis (post-multiplied, (2.14)) or the fixed frame's (pre-multiplied,
//! (2.16)), the frames already reached left as ghosts.

use crate::kinematics::orientation::{Step, StepFrame, elementary};
use nalgebra::Rotation3;

/// One frame of the animation.
#[derive(Debug, Clone, PartialEq)]
pub struct RotationShot {
    /// The turning frame, `reference_from_frame`.
    pub rotation: Rotation3<f64>,
    /// The frames reached after each finished step (ghosts).
    pub done: Vec<Rotation3<f64>>,
    /// What the frame shows: the step and the product so far, written out.
    pub caption: String,
}

/// The product of `steps` written out, `R = Rz(30°) Ry(45°)`: a step about the current frame
/// multiplies on the right (2.14), one about the fixed frame on the left (2.16).
///
/// # Examples
///
/// ```
/// use armlab::animation::rotation::product_text;
/// use armlab::kinematics::orientation::{Axis, Step, StepFrame};
/// let s = |frame, axis, deg: f64| Step { frame, axis, angle: deg.to_radians() };
/// let steps = [s(StepFrame::Current, Axis::Z, 30.0), s(StepFrame::Fixed, Axis::X, 10.0)];
/// assert_eq!(product_text(&steps), "R = Rx(10°) Rz(30°)");
/// assert_eq!(product_text(&[]), "R = I");
/// ```
pub fn product_text(steps: &[Step]) -> String {
    let mut factors = std::collections::VecDeque::new();
    for s in steps {
        let f = format!("R{}({:.0}°)", s.axis, s.angle.to_degrees());
        match s.frame {
            StepFrame::Current => factors.push_back(f),
            StepFrame::Fixed => factors.push_front(f),
        }
    }
    if factors.is_empty() {
        return "R = I".into();
    }
    format!("R = {}", Vec::from(factors).join(" "))
}

/// `frames` frames (at least 2) of `steps` played one after the other, each step eased in and
/// out over an equal share of the time, the last frame holding the whole product.
///
/// # Examples
///
/// ```
/// use armlab::animation::rotation::rotation_shots;
/// use armlab::kinematics::orientation::{Axis, Step, StepFrame, compose};
/// let steps = [
///     Step { frame: StepFrame::Current, axis: Axis::Z, angle: 0.5 },
///     Step { frame: StepFrame::Fixed, axis: Axis::X, angle: 0.2 },
/// ];
/// let shots = rotation_shots(&steps, 40);
/// assert_eq!(shots.len(), 40);
/// assert!(shots[0].rotation.angle() < 1e-12);
/// let end = compose(&steps);
/// assert!((shots[39].rotation.matrix() - end.matrix()).amax() < 1e-12);
/// assert_eq!(shots[39].done.len(), 2);
/// ```
pub fn rotation_shots(steps: &[Step], frames: usize) -> Vec<RotationShot> {
    let frames = frames.max(2);
    let n = steps.len().max(1);
    (0..frames)
        .map(|f| {
            // progress through the whole sequence, 0 to n steps
            let t = f as f64 / (frames - 1) as f64 * n as f64;
            let k = (t.floor() as usize).min(steps.len());
            let mut done = Vec::with_capacity(k);
            let mut r = Rotation3::identity();
            for s in &steps[..k] {
                r = apply(&r, s, s.angle);
                done.push(r);
            }
            let (rotation, caption) = match steps.get(k) {
                Some(s) => {
                    let x = t - k as f64;
                    let eased = x * x * (3.0 - 2.0 * x);
                    let turned = apply(&r, s, s.angle * eased);
                    let partial = Step {
                        angle: s.angle * eased,
                        ..*s
                    };
                    let mut shown = steps[..k].to_vec();
                    shown.push(partial);
                    let about = format!("{} about the {} {} axis", k + 1, s.frame, s.axis);
                    (turned, format!("step {about}: {}", product_text(&shown)))
                }
                None => (
                    r,
                    format!("all {} steps: {}", steps.len(), product_text(steps)),
                ),
            };
            RotationShot {
                rotation,
                done,
                caption,
            }
        })
        .collect()
}

/// `r` turned by `s` through `angle`: post-multiplied about the current frame (2.14),
/// pre-multiplied about the fixed one (2.16).
fn apply(r: &Rotation3<f64>, s: &Step, angle: f64) -> Rotation3<f64> {
    let e = elementary(s.axis, angle);
    match s.frame {
        StepFrame::Current => r * e,
        StepFrame::Fixed => e * r,
    }
}
