//! A compute module that breaks the rules (a fixture of tests/architecture.rs; never compiled).
// egui::Ui in a comment is fine.
use egui::Ui;
const NAME: &str = "wgpu::Device in a string is fine";

fn read(path: &str) -> String {
    std::fs::read_to_string(path).unwrap_or_default()
}
use crate::workspace::Map;
use std::{fs, io::Read};
fn fine() -> std::io::Result<()> { Err(std::io::Error::other("an error is not file access")) }
