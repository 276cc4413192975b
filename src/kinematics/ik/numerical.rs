//! Numerical IK.
