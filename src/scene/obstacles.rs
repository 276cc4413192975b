//! A cell's obstacles as draw lists: boxes, cylinders and spheres as the renderer's unit
//! shapes, a plane as a large thin square whose top face is the plane, a mesh as its own
//! triangles, each with its name as a label. It paints what it is handed: the obstacles' world
//! poses come from the caller ([`crate::collision::CollisionWorld::obstacle_poses`]).

use super::{CustomMesh, Label, MeshInstance, Rgba, Scene, Shape, col_major, v32};
use crate::collision::{CellScene, Obstacle, ObstacleShape};
use crate::kinematics::Pose;
use nalgebra::{Matrix4, Vector3};

/// How obstacles are drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObstacleStyle {
    /// Fill colour (linear RGBA); alpha < 1 draws it translucent, so that the arm behind a
    /// wall stays visible.
    pub color: Rgba,
    /// Half the side of the square a plane is drawn as (m): large enough to read as a floor or
    /// a wall, small enough to keep the camera's framing (e.g. the robot's reach).
    pub plane_half_size: f64,
    /// Thickness of that square (m), below the plane.
    pub plane_thickness: f64,
    /// Write each obstacle's name at its origin.
    pub labels: bool,
}

impl Default for ObstacleStyle {
    /// Grey, slightly translucent, planes 1.5 m across each way, labelled.
    fn default() -> Self {
        ObstacleStyle {
            color: [0.45, 0.46, 0.52, 0.85],
            plane_half_size: 1.5,
            plane_thickness: 0.01,
            labels: true,
        }
    }
}

/// Every obstacle of `cell` at its `world_from_obstacle` (one pose per obstacle, in order, as
/// [`crate::collision::CollisionWorld::obstacle_poses`] gives them), as a scene to
/// [`Scene::extend`] an arm's scene with. Obstacles without a pose are left out.
///
/// ```
/// use armlab::collision::{CellScene, Obstacle};
/// use armlab::kinematics::Pose;
/// use armlab::scene::obstacles::{ObstacleStyle, obstacle_scene};
///
/// let cell = CellScene {
///     obstacles: vec![
///         Obstacle::floor("floor", 0.0),
///         Obstacle::cuboid("table", [1.2, 0.8, 0.05], [0.6, 0.0, 0.375]),
///     ],
///     ..CellScene::default()
/// };
/// let poses: Vec<Pose> = cell.obstacles.iter().map(|o| o.frame_from_obstacle()).collect();
/// let scene = obstacle_scene(&cell, &poses, &ObstacleStyle::default());
/// assert_eq!(scene.meshes.len(), 2); // the floor's square and the table's box
/// // The table's box is centred where the scene file puts it.
/// let t = scene.meshes[1].world_from_unit[3];
/// assert!((t[0] - 0.6).abs() < 1e-6 && (t[2] - 0.375).abs() < 1e-6);
/// assert_eq!(scene.labels[1].text, "table");
/// ```
pub fn obstacle_scene(
    cell: &CellScene,
    world_from_obstacle: &[Pose],
    style: &ObstacleStyle,
) -> Scene {
    let mut scene = Scene::default();
    for (o, pose) in cell.obstacles.iter().zip(world_from_obstacle) {
        add_obstacle(&mut scene, o, pose, style);
    }
    scene
}

/// Adds one obstacle at `world_from_obstacle` to `scene` in `style` (a caller that colours
/// obstacles one by one, e.g. the one an arm hits in red).
pub fn add_obstacle(
    scene: &mut Scene,
    obstacle: &Obstacle,
    world_from_obstacle: &Pose,
    style: &ObstacleStyle,
) {
    let world = world_from_obstacle.to_homogeneous();
    let unit = |shape: Shape, scale: Vector3<f64>, centre: Vector3<f64>| MeshInstance {
        shape,
        world_from_unit: col_major(
            &(world * Matrix4::new_translation(&centre) * Matrix4::new_nonuniform_scaling(&scale)),
        ),
        color: style.color,
    };
    let mut label_at = Vector3::zeros();
    match &obstacle.shape {
        ObstacleShape::Box { size } => {
            scene
                .meshes
                .push(unit(Shape::Cube, Vector3::from(*size), Vector3::zeros()))
        }
        ObstacleShape::Cylinder { radius, length } => scene.meshes.push(unit(
            Shape::Cylinder,
            Vector3::new(*radius, *radius, *length),
            Vector3::zeros(),
        )),
        ObstacleShape::Sphere { radius } => scene.meshes.push(unit(
            Shape::Sphere,
            Vector3::repeat(*radius),
            Vector3::zeros(),
        )),
        ObstacleShape::Plane => {
            let (s, t) = (style.plane_half_size, style.plane_thickness);
            scene.meshes.push(unit(
                Shape::Cube,
                Vector3::new(2.0 * s, 2.0 * s, t),
                Vector3::new(0.0, 0.0, -0.5 * t),
            ));
            // The name near a corner of the square, not under the robot's base.
            label_at = Vector3::new(0.8 * s, -0.8 * s, 0.0);
        }
        ObstacleShape::Mesh { mesh, .. } => scene.custom_meshes.push(CustomMesh {
            mesh: mesh.clone(),
            coarse: None,
            world_from_mesh: col_major(&world),
            color: style.color,
        }),
    }
    if style.labels {
        scene.labels.push(Label {
            p: v32(&(world_from_obstacle * nalgebra::Point3::from(label_at)).coords),
            text: obstacle.name.clone(),
            color: [0.15, 0.15, 0.17, 1.0],
            movable: true,
        });
    }
}
