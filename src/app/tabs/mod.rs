//! The central area's tabs. Each tab is a module that owns its state, lays itself out when it
//! is shown, adds what it draws over the 3D view, and returns what it wants done as actions.
//! Adding a tab is one file here and one line in the `tabs!` list below.

pub mod calibration;
pub mod exercise;
pub mod orientation;
pub mod self_motion;
pub mod view3d;
pub mod workspace;

use super::action::Actions;
use super::file_picker::FilePicker;
use super::layout::Layout;
use super::state::{AppState, SelfMotionView};
use super::viewport::ViewportImage;
use crate::scene::Scene;

/// What a tab reads while it lays itself out.
pub struct TabContext<'a> {
    /// The shared model (read only: a tab changes it through actions).
    pub state: &'a AppState,
    /// The window's layout (projector mode).
    pub layout: &'a Layout,
    /// The end-effector the readouts refer to.
    pub ee: usize,
    /// The self-motion of `ee` (or why there is none) for the Self-motion tab, which plots it;
    /// `None` for the other tabs (it is sampled anew after every move).
    pub self_motion: Option<Result<SelfMotionView, String>>,
    /// File dialogs, downloads.
    pub picker: &'a mut dyn FilePicker,
    /// The rendered 3D view, for the 3D tab.
    pub image: Option<ViewportImage>,
}

/// A central tab.
pub trait Tab {
    /// Its name in the toolbar.
    fn title(&self) -> &'static str;
    /// Lays the tab out in the central area.
    fn ui(&mut self, cx: &mut TabContext<'_>, ui: &mut egui::Ui, out: &mut Actions);
    /// Adds what the tab shows over the 3D view (overlays) to the scene.
    fn decorate(&self, _state: &AppState, _scene: &mut Scene) {}
    /// The model changed: what belonged to the old one goes.
    fn model_changed(&mut self) {}
}

/// Declares the tabs, in the toolbar's order: `field: Type` (the type implements [`Tab`] and
/// `Default`).
macro_rules! tabs {
    ($($field:ident: $ty:ty),* $(,)?) => {
        /// Every central tab.
        #[derive(Default)]
        pub struct Tabs {
            $(
                #[doc = concat!("The ", stringify!($field), " tab.")]
                pub $field: $ty,
            )*
        }

        impl Tabs {
            /// The number of tabs.
            pub const COUNT: usize = [$(stringify!($field)),*].len();

            /// Tab `index` (in the toolbar's order).
            pub fn get_mut(&mut self, index: usize) -> Option<&mut dyn Tab> {
                let mut k = 0;
                $(
                    if k == index {
                        return Some(&mut self.$field);
                    }
                    k += 1;
                )*
                let _ = k;
                None
            }

            /// Every tab, in the toolbar's order.
            pub fn all(&self) -> Vec<&dyn Tab> {
                vec![$(&self.$field),*]
            }

            /// Every tab, to change.
            pub fn all_mut(&mut self) -> Vec<&mut dyn Tab> {
                vec![$(&mut self.$field),*]
            }
        }
    };
}

tabs! {
    view3d: view3d::View3d,
    workspace: workspace::WorkspaceTab,
    calibration: calibration::CalibrationTab,
    self_motion: self_motion::SelfMotionTab,
    exercise: exercise::ExerciseTab,
    orientation: orientation::OrientationTab,
}

impl Tabs {
    /// Adds what every tab shows over the 3D view to the scene.
    pub fn decorate(&self, state: &AppState, scene: &mut Scene) {
        for t in self.all() {
            t.decorate(state, scene);
        }
    }

    /// The model changed: every tab drops what belonged to the old one.
    pub fn model_changed(&mut self) {
        for t in self.all_mut() {
            t.model_changed();
        }
    }
}

/// The index of the 3D view among the tabs.
pub const VIEW3D: usize = 0;
/// The index of the workspace tab.
pub const WORKSPACE: usize = 1;
/// The index of the calibration tab.
pub const CALIBRATION: usize = 2;
/// The index of the self-motion tab.
pub const SELF_MOTION: usize = 3;
/// The index of the exercise tab.
pub const EXERCISE: usize = 4;
/// The index of the orientation tab.
pub const ORIENTATION: usize = 5;
