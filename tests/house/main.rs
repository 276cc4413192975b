//! The house's own tests: the layer table, the graphics-free library boundary, the examples
//! and the README's commands.

mod architecture;
mod examples;
mod library_boundary;
mod readme;
