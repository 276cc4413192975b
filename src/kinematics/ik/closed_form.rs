//! Closed-form IK.
