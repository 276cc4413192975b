//! A compute module that names a layer above it (fixture).
use crate::scene::Scene;
