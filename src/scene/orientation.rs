//! The orientation lab's 3D picture (Sect. 2.2-2.4): a rigid body's frame turned by a rotation
//! matrix, over the reference frame, with the intermediate frames of a composition as ghosts,
//! the axes about which a singular representation's first and last angles act alike, and the
//! arm's tool frame if asked for. It paints what it is handed: the rotations are computed by
//! the caller (`kinematics::orientation`).

use super::{AXIS_COLORS, Label, Line, MeshInstance, Rgba, Scene, Shape, col_major, v32};
use nalgebra::{Matrix4, Rotation3, Vector3};

/// Length of the turned frame's axes (m): the picture is in the unit ball.
pub const AXIS_LENGTH: f64 = 1.0;

/// One frame besides the turned one: a ghost of a composition step, the tool, a comparison.
#[derive(Debug, Clone, PartialEq)]
pub struct FrameMark {
    /// `reference_from_frame`.
    pub rotation: Rotation3<f64>,
    /// What its axis labels carry after x, y, z (`"1"` gives x1, y1, z1).
    pub suffix: String,
    /// How strongly it is drawn, 0 (faint) to 1 (as the turned frame).
    pub weight: f32,
}

/// A highlighted axis through the origin (unit direction in the reference frame) with a label.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisMark {
    /// The direction (unit, reference frame).
    pub direction: Vector3<f64>,
    /// The label at its tip.
    pub label: String,
}

/// What the orientation lab draws.
#[derive(Debug, Clone, PartialEq)]
pub struct OrientationPicture {
    /// `reference_from_body`: the frame turned.
    pub rotation: Rotation3<f64>,
    /// Its label suffix (`'` gives x', y', z', the textbook's O-x'y'z').
    pub suffix: String,
    /// The other frames (composition ghosts, the arm's tool, the frame before a change).
    pub marks: Vec<FrameMark>,
    /// Highlighted axes (a singular case: the axes of the first and last rotation).
    pub axes: Vec<AxisMark>,
    /// Draw the body (a flat box) with the frame.
    pub body: bool,
    /// Thicker lines for a projector.
    pub projector: bool,
}

/// The highlighted axes' colour (amber).
const AXIS_MARK: Rgba = [0.95, 0.6, 0.05, 1.0];
/// The reference frame's colour.
const REFERENCE: Rgba = [0.45, 0.45, 0.5, 1.0];

/// The scene of `picture`: the reference frame (grey, x y z), the turned frame (coloured,
/// x' y' z') with its body, the marks fainter, and the highlighted axes in amber.
pub fn orientation_scene(picture: &OrientationPicture) -> Scene {
    let mut scene = Scene::default();
    let w = if picture.projector { 1.6 } else { 1.0 };
    let origin = [0.0f32; 3];
    for k in 0..3 {
        let tip = v32(&Vector3::ith(k, AXIS_LENGTH * 1.15));
        scene.lines.push(Line {
            a: origin,
            b: tip,
            color: REFERENCE,
            width_px: 1.5 * w,
        });
        scene.labels.push(label(tip, ["x", "y", "z"][k], REFERENCE));
    }
    for m in &picture.marks {
        let faded = AXIS_COLORS.map(|c| fade(c, m.weight));
        triad(
            &mut scene,
            &m.rotation,
            &m.suffix,
            (faded, 1.0 + 1.5 * m.weight),
            w,
        );
    }
    triad(
        &mut scene,
        &picture.rotation,
        &picture.suffix,
        (AXIS_COLORS, 3.5),
        w,
    );
    for a in &picture.axes {
        let d = a.direction.normalize() * AXIS_LENGTH * 1.35;
        scene.lines.push(Line {
            a: v32(&-d),
            b: v32(&d),
            color: AXIS_MARK,
            width_px: 2.5 * w,
        });
        scene.labels.push(label(v32(&d), &a.label, AXIS_MARK));
    }
    if picture.body {
        let m = picture.rotation.to_homogeneous()
            * Matrix4::new_nonuniform_scaling(&Vector3::new(0.7, 0.45, 0.12));
        scene.meshes.push(MeshInstance {
            shape: Shape::Cube,
            world_from_unit: col_major(&m),
            color: [0.85, 0.7, 0.45, 0.55],
        });
    }
    scene.meshes.push(MeshInstance {
        shape: Shape::Sphere,
        world_from_unit: col_major(&Matrix4::new_scaling(0.04)),
        color: [0.3, 0.3, 0.3, 1.0],
    });
    scene
}

/// The axes of `rotation` from the origin, coloured `colors`, `width` px (times `w`), labelled
/// x, y, z with `suffix`.
fn triad(
    scene: &mut Scene,
    rotation: &Rotation3<f64>,
    suffix: &str,
    style: ([Rgba; 3], f32),
    w: f32,
) {
    let (colors, width) = style;
    for (k, color) in colors.iter().enumerate() {
        let tip = v32(&(rotation * Vector3::ith(k, AXIS_LENGTH)));
        scene.lines.push(Line {
            a: [0.0; 3],
            b: tip,
            color: *color,
            width_px: width * w,
        });
        let name = format!("{}{suffix}", ["x", "y", "z"][k]);
        scene.labels.push(label(tip, &name, *color));
    }
}

fn label(p: [f32; 3], text: &str, color: Rgba) -> Label {
    Label {
        p,
        text: text.to_string(),
        color,
        movable: false,
    }
}

/// `c` mixed toward white: `weight` 1 keeps it, 0 leaves a faint tint.
fn fade(c: Rgba, weight: f32) -> Rgba {
    let k = 0.25 + 0.75 * weight.clamp(0.0, 1.0);
    [
        1.0 - k * (1.0 - c[0]),
        1.0 - k * (1.0 - c[1]),
        1.0 - k * (1.0 - c[2]),
        1.0,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_turned_frame_points_where_the_rotation_says() {
        let r = Rotation3::from_axis_angle(&Vector3::z_axis(), std::f64::consts::FRAC_PI_2);
        let s = orientation_scene(&OrientationPicture {
            rotation: r,
            suffix: "'".into(),
            marks: vec![],
            axes: vec![],
            body: true,
            projector: false,
        });
        // x' along the reference y
        let x = s.labels.iter().find(|l| l.text == "x'").unwrap();
        assert!(
            (x.p[1] - 1.0).abs() < 1e-6 && x.p[0].abs() < 1e-6,
            "{:?}",
            x.p
        );
        assert_eq!(s.meshes.len(), 2);
    }
}
