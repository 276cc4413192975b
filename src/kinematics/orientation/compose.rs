//! Composition of elementary rotations, Sect. 2.3: about the current frame's axes
//! (post-multiplication, (2.14)) and about the fixed frame's axes (pre-multiplication, (2.16)).

use super::{Step, StepFrame};
use nalgebra::Rotation3;

/// The rotation after one more step: `R Ri` about the current frame (2.14), `Ri R` about the
/// fixed frame (2.16).
fn apply(r: &Rotation3<f64>, step: &Step) -> Rotation3<f64> {
    let ri = step.rotation();
    match step.frame {
        StepFrame::Current => r * ri, // (2.14)
        StepFrame::Fixed => ri * r,   // (2.16)
    }
}

/// The rotation of a sequence of elementary rotations, each about the current frame's axis
/// (post-multiplied, (2.14)) or the fixed frame's axis (pre-multiplied, (2.16)), starting from
/// the identity. No allocation.
///
/// # Examples
///
/// "Rz(phi), then Ry(theta) about the current y, then Rz(psi) about the current z" is the ZYZ
/// matrix (2.18); the same three turns about the fixed axes give the product in reverse order:
///
/// ```
/// use armlab::kinematics::orientation::{Axis, Step, StepFrame, compose, rotation_from_zyz};
/// use armlab::nalgebra::Vector3;
///
/// let steps = |frame| {
///     [(Axis::Z, 0.3), (Axis::Y, 1.1), (Axis::Z, -0.7)]
///         .map(|(axis, angle)| Step { frame, axis, angle })
/// };
/// let current = compose(&steps(StepFrame::Current));
/// assert!((current.matrix() - rotation_from_zyz(&Vector3::new(0.3, 1.1, -0.7)).matrix()).amax() < 1e-15);
/// let fixed = compose(&steps(StepFrame::Fixed));
/// assert!((fixed.matrix() - rotation_from_zyz(&Vector3::new(-0.7, 1.1, 0.3)).matrix()).amax() < 1e-15);
/// ```
pub fn compose(steps: &[Step]) -> Rotation3<f64> {
    steps
        .iter()
        .fold(Rotation3::identity(), |r, s| apply(&r, s))
}

/// The rotation after each step of [`compose`], in order: element `i` is the composition of
/// steps `0..=i`, the last is the whole product. Empty for no steps.
///
/// # Examples
///
/// ```
/// use armlab::kinematics::orientation::{Axis, Step, StepFrame, compose, elementary, partial_products};
///
/// let steps = [
///     Step { frame: StepFrame::Current, axis: Axis::Z, angle: 0.5 },
///     Step { frame: StepFrame::Fixed, axis: Axis::X, angle: 0.2 },
/// ];
/// let partial = partial_products(&steps);
/// assert_eq!(partial.len(), 2);
/// assert_eq!(partial[0], elementary(Axis::Z, 0.5));
/// // About the fixed x: pre-multiplied.
/// let expected = elementary(Axis::X, 0.2) * elementary(Axis::Z, 0.5);
/// assert!((partial[1].matrix() - expected.matrix()).amax() < 1e-15);
/// assert_eq!(partial[1], compose(&steps));
/// ```
pub fn partial_products(steps: &[Step]) -> Vec<Rotation3<f64>> {
    let mut out = Vec::with_capacity(steps.len());
    let mut r = Rotation3::identity();
    for s in steps {
        r = apply(&r, s);
        out.push(r);
    }
    out
}
