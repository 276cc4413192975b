//! Views of a sampled workspace as plain data for figures: 2D projections as in a data sheet
//! (Sect. 2.10.1: "a top view and a side view") and 3D point clouds. The joint-space rectangle of
//! Fig. 2.29 is [`super::joint_rectangle`]; grid regions are [`super::GridAnalysis`].

use super::sample::Samples;
use crate::kinematics::Robot;
use nalgebra::Point3;

/// Which 2D projection.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum View {
    /// The base frame's x-y plane (the arm plane of a planar arm): (x_b, y_b), m.
    Plane,
    /// Top view: world (x, y), m.
    Top,
    /// Side view: world (x, z), m.
    SideXZ,
    /// Side view of the radial section: (r, z) with r the horizontal distance from the vertical
    /// line through the base origin (>= 0) and z the world height, m. For arms whose first axis is
    /// vertical this is the cross-section swept by joint 1.
    SideRZ,
}

impl View {
    /// Names of the two axes, e.g. `["x", "y"]`.
    pub fn axes(self) -> [&'static str; 2] {
        match self {
            View::Plane => ["x_base", "y_base"],
            View::Top => ["x", "y"],
            View::SideXZ => ["x", "z"],
            View::SideRZ => ["r", "z"],
        }
    }
}

/// A 2D projection of samples (m).
#[derive(Debug, Clone, PartialEq)]
pub struct Projection {
    /// The view.
    pub view: View,
    /// Axis names.
    pub axes: [&'static str; 2],
    /// Projected points (m), in sample order.
    pub points: Vec<[f64; 2]>,
    /// Posture classes of the samples, if they were computed.
    pub classes: Option<Vec<u8>>,
    /// Class names.
    pub class_names: Vec<String>,
}

/// Projects the samples for `view` (`robot` gives the base frame).
pub fn project(robot: &Robot, samples: &Samples, view: View) -> Projection {
    let base = robot.base;
    let o = base.translation.vector;
    let points = samples
        .positions
        .iter()
        .map(|p| match view {
            View::Plane => {
                let l = base.inverse_transform_point(&Point3::new(p[0], p[1], p[2]));
                [l.x, l.y]
            }
            View::Top => [p[0], p[1]],
            View::SideXZ => [p[0], p[2]],
            View::SideRZ => [(p[0] - o.x).hypot(p[1] - o.y), p[2]],
        })
        .collect();
    Projection {
        view,
        axes: view.axes(),
        points,
        classes: samples.classes.clone(),
        class_names: samples.class_names.clone(),
    }
}

/// A 3D point cloud for rendering (world frame, m, single precision).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[must_use]
pub struct PointCloud {
    /// Positions (world frame, m).
    pub positions: Vec<[f32; 3]>,
    /// Class of each point (0 when the samples have no classes; [`super::UNCLASSIFIED`] for a
    /// degenerate posture).
    pub classes: Vec<u8>,
    /// Class names.
    pub class_names: Vec<String>,
    /// Manipulability of each point, if computed.
    pub manipulability: Option<Vec<f32>>,
}

/// The samples as a point cloud.
pub fn point_cloud(samples: &Samples) -> PointCloud {
    PointCloud {
        positions: samples
            .positions
            .iter()
            .map(|p| p.map(|v| v as f32))
            .collect(),
        classes: samples
            .classes
            .clone()
            .unwrap_or_else(|| vec![0; samples.len()]),
        class_names: samples.class_names.clone(),
        manipulability: samples.manipulability.clone(),
    }
}
