//! The scene naming the GPU (fixture).
use wgpu::Buffer;
use crate::kinematics::Robot;
