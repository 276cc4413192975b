//! The live classroom's data (issue 50): the protocol's messages ([`protocol`]) and the grading
//! and counting of the room's answers ([`grading`]). Graphics-free and without I/O: the server
//! (`class_server`, the desktop build) and the apps' clients (desktop and web) share it.

pub mod grading;
pub mod protocol;
