//! Orientation figures for slides and animations (Sects. 2.2-2.4): a frame turned over the
//! reference frame with its representations listed (`armlab rotation --figure`), and the
//! frames of a composition played step by step (`armlab animate --what rotation`). They paint
//! what they are handed: rotations from `kinematics::orientation`, shots from
//! [`crate::animation::rotation`].

use super::figures::{Figures, Scene3d};
use super::{FigureError, Theme};
use crate::animation::rotation::RotationShot;
use crate::camera::Camera;
use crate::kinematics::orientation::Representations;
use crate::scene::orientation::{FrameMark, OrientationPicture, orientation_scene};
use nalgebra::{Point3, Rotation3};

/// The camera of every orientation figure: the unit ball from an oblique view, filling the
/// frame of `size` pixels.
pub fn camera(size: [u32; 2]) -> Camera {
    let mut camera = Camera {
        yaw: 0.6,
        pitch: 0.35,
        ..Camera::default()
    };
    // the unit ball's box, and the axis tips (the highlighted axes reach 1.35)
    let pts: Vec<Point3<f32>> = (0..8)
        .map(|c| {
            let s = |bit: i32| if c & bit == 0 { -1.0 } else { 1.0 };
            Point3::new(s(1), s(2), s(4))
        })
        .chain((0..6).map(|k| {
            let mut p = Point3::origin();
            p[k % 3] = if k < 3 { 1.35 } else { -1.35 };
            p
        }))
        .collect();
    camera.target = Point3::origin();
    camera.fit_points(&pts, size[0], size[1], 0.85);
    camera
}

/// A frame turned by `rotation` over the reference frame, titled `title`, with the matrix and
/// every representation (both Euler solutions, the singular cases in words) listed under it.
pub fn frame_figure(
    figs: &mut Figures,
    rotation: &Rotation3<f64>,
    title: &str,
    size: [u32; 2],
    theme: Theme,
) -> Result<image::RgbaImage, FigureError> {
    let scene = orientation_scene(&OrientationPicture {
        rotation: *rotation,
        suffix: "'".into(),
        marks: Vec::new(),
        axes: Vec::new(),
        body: true,
        projector: false,
    });
    let all = Representations::of(rotation);
    let m = rotation.matrix();
    let rows: Vec<String> = (0..3)
        .map(|i| format!("{:.4}  {:.4}  {:.4}", m[(i, 0)], m[(i, 1)], m[(i, 2)]))
        .collect();
    let q = all.quaternion;
    let caption = [
        format!("R = [{}]", rows.join(";  ")),
        format!("ZYZ: {}", all.zyz),
        format!("ZXZ: {}", all.zxz),
        format!("RPY: {}", all.rpy),
        format!("angle-axis: {}", all.axis_angle),
        format!(
            "quaternion: eta = {:.4}, epsilon = ({:.4}, {:.4}, {:.4})",
            q.w, q.i, q.j, q.k
        ),
    ]
    .join("\n");
    figs.scene(
        size,
        theme,
        &Scene3d {
            title: title.to_string(),
            subtitle: "reference frame x y z (grey), turned frame x' y' z'".into(),
            caption,
            scene: &scene,
            camera: camera(size),
            legend: Vec::new(),
        },
    )
}

/// Every frame of a composition's animation at `size` pixels, titled `title`, each shot's
/// finished steps as fainter frames numbered 1, 2, ...
pub fn rotation_frames(
    figs: &mut Figures,
    shots: &[RotationShot],
    title: &str,
    size: [u32; 2],
    theme: Theme,
) -> Result<Vec<image::RgbaImage>, FigureError> {
    let camera = camera(size);
    shots
        .iter()
        .map(|shot| {
            let marks = shot
                .done
                .iter()
                .enumerate()
                // the step just finished is the frame itself
                .filter(|(_, r)| r.angle_to(&shot.rotation) > 1e-9)
                .map(|(k, r)| FrameMark {
                    rotation: *r,
                    suffix: (k + 1).to_string(),
                    weight: 0.35,
                })
                .collect();
            let scene = orientation_scene(&OrientationPicture {
                rotation: shot.rotation,
                suffix: "'".into(),
                marks,
                axes: Vec::new(),
                body: true,
                projector: false,
            });
            figs.scene(
                size,
                theme,
                &Scene3d {
                    title: title.to_string(),
                    subtitle: shot.caption.clone(),
                    caption: String::new(),
                    scene: &scene,
                    camera,
                    legend: Vec::new(),
                },
            )
        })
        .collect()
}
