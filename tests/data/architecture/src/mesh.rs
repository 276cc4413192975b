use crate::kinematics::Pose;
