//! The side panels. Each panel group is a module that owns its state, reads the shared state
//! and returns actions: the model and its joints (left), the readouts and inverse kinematics
//! with the construction and redundancy sections (right).

pub mod construction;
pub mod ik;
pub mod model;
pub mod redundancy;
pub mod symbols;
