//! What the app rule reports here (lines 3 and 6), and what it leaves.
use super::shell::AppUi;
impl AppUi {
    fn step(&mut self) {}
}
impl Default for super::shell::AppUi {
    fn default() -> Self { todo!() }
}
// impl AppUi { in a comment }
const S: &str = "impl AppUi {";
pub struct Settings;
impl<'a> From<&'a AppUi> for Settings {
    fn from(_: &'a AppUi) -> Self { Settings }
}
impl Settings {}
pub struct AppUiParts;
impl AppUiParts {}
