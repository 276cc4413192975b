//! The shell may add methods to the window model.
pub struct AppUi;
impl AppUi {
    pub fn new() -> Self { AppUi }
}
