//! The kinematics library's tests: forward kinematics against the reference data, every
//! closed-form IK family and the numerical solver, Jacobians, orientation, singularities, model
//! files and URDF, the textbook's arms and symbols. One test crate (one link of the crate).

#[path = "../common/mod.rs"]
mod common;

mod fk_reference;
mod fuzz_regressions;
mod hold;
mod ik_branches;
mod ik_cartesian;
mod ik_closed_form;
mod ik_closed_form_degenerate;
mod ik_closed_form_user_arms;
mod ik_general6;
mod ik_numerical;
mod ik_parallel3;
mod ik_parallel3_general;
mod ik_pieper;
mod ik_reversed;
mod jacobian;
mod model_files;
mod opening_pose;
mod orientation;
mod panda;
mod singularity;
mod srs;
mod symbolic;
mod textbook;
mod urdf;
mod urdf_arms;
mod urdf_corpus;
mod urdf_export;
