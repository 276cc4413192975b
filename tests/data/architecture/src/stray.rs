//! A module that is in no layer (fixture).
