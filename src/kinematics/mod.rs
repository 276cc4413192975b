//! Pure kinematics in f64 (nalgebra): no graphics, no file system.
//!
//! Frames follow chapter 2 of Siciliano et al.: a robot is a tree of joints described by DH rows
//! (standard or modified) or URDF-style origins, the world frame is the base's reference, and
//! poses are named `world_from_x`. Units: metres and radians.

pub mod arm;
pub mod closure;
pub mod dh;
pub mod dh_derive;
pub mod end_effectors;
pub mod error;
pub mod fk;
mod frame;
pub mod hold;
pub mod ik;
pub mod jacobian;
pub mod models;
pub mod opening;
pub mod orientation;
pub mod pose;
pub mod redundancy;
pub mod robot;
pub mod singularity;
pub mod symbolic;
pub mod trig;
pub mod visual;

pub use dh::{Convention, DhRow};
pub use error::{KinematicsError, ModelError};
pub use jacobian::JacobianAnalysis;
pub use orientation::EulerKind;
pub use pose::Pose;
pub use robot::{
    DhJoint, DisabledPair, Drive, EndEffector, Joint, JointGeometry, JointId, JointKind,
    NamedConfig, PointMass, Robot, UNBOUNDED,
};
