//! The window's layout as data: which side panels are open, projector mode, and the rules that
//! keep the 3D view the largest thing on screen. Normal and projector mode each keep their own
//! panels (and egui keeps each one's width under its own id), so leaving projector mode restores
//! the exact previous layout. A remembered layout is validated when it is loaded.

use serde::{Deserialize, Serialize};

/// The smallest share of the window's width the central area (the 3D view) keeps, however the
/// side panels are dragged.
pub const CENTRAL_SHARE: f32 = 0.55;
/// The narrowest a side panel can be dragged (points).
pub const MIN_PANEL: f32 = 180.0;

/// Which side panels are open in one mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Sides {
    /// The model and joints panel (left).
    pub left: bool,
    /// The readouts and inverse kinematics panel (right).
    pub right: bool,
}

/// The layout of the window.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Layout {
    /// Large fonts, thick lines, large 3D labels.
    pub projector: bool,
    /// The panels open in normal mode.
    pub normal: Sides,
    /// The panels open in projector mode (by default only the right one: the lesson's
    /// readouts, with the 3D view as large as it can be).
    pub presenting: Sides,
    /// "Present this figure": the tab's figure (the 3D view, the workspace plot) fills the
    /// window, with no toolbar, side panel, status bar or tab controls; F5 or Escape leaves.
    /// Not remembered: a window never opens without its toolbar.
    #[serde(skip)]
    pub present: bool,
}

impl Default for Layout {
    fn default() -> Self {
        Self {
            projector: false,
            normal: Sides {
                left: true,
                right: true,
            },
            presenting: Sides {
                left: false,
                right: true,
            },
            present: false,
        }
    }
}

impl Layout {
    /// The panels open in the current mode.
    pub fn sides(&self) -> Sides {
        if self.projector {
            self.presenting
        } else {
            self.normal
        }
    }

    /// The panels of the current mode, to change.
    pub fn sides_mut(&mut self) -> &mut Sides {
        if self.projector {
            &mut self.presenting
        } else {
            &mut self.normal
        }
    }

    /// Applies a layout action (projector mode, the side panels, presenting); others are
    /// ignored.
    pub fn apply(&mut self, action: &super::action::Action) {
        use super::action::Action;
        match action {
            Action::ToggleProjector => self.projector ^= true,
            Action::ToggleSidePanels => self.toggle_side_panels(),
            Action::TogglePresent => self.present ^= true,
            Action::EndPresent => self.present = false,
            _ => {}
        }
    }

    /// One key hides both side panels, or shows both again. In projector mode, where two
    /// panels leave each too narrow to read (the left one wrapped "Open" as "Ope n"), it shows
    /// one at a time, each as wide as in normal mode or wider: the right one (the readouts),
    /// then the left one (the model and joints), then none.
    pub fn toggle_side_panels(&mut self) {
        let projector = self.projector;
        let s = self.sides_mut();
        let (left, right) = match (projector, s.left, s.right) {
            (false, l, r) => (!(l || r), !(l || r)),
            (true, false, true) => (true, false),
            (true, true, false) => (false, false),
            (true, _, _) => (false, true),
        };
        *s = Sides { left, right };
    }

    /// The egui ids of the left and right panels in the current mode: each mode's panels keep
    /// their own widths.
    pub fn panel_ids(&self) -> (&'static str, &'static str) {
        if self.projector {
            ("left panel (projector)", "right panel (projector)")
        } else {
            ("left panel", "right panel")
        }
    }

    /// The width (points) the side panels may share: what the central area's share of a
    /// window `window` points wide leaves of the `avail` points inside the window's margins.
    pub fn side_room(avail: f32, window: f32) -> f32 {
        avail - CENTRAL_SHARE * window
    }

    /// The default widths (points) of the left and right panels in the current mode, with
    /// `avail` points inside the margins of a window `window` points wide: together they leave
    /// the central area its share.
    pub fn default_widths(&self, avail: f32, window: f32) -> (f32, f32) {
        let (left, right): (f32, f32) = if self.projector {
            (320.0, 400.0)
        } else {
            (270.0, 300.0)
        };
        // Only the open panels share the room. Where it is short, the right panel keeps its
        // width (its pose matrix needs it; at 1200 px it was cut) and the left one gives way,
        // down to its minimum.
        let sides = self.sides();
        let room = Self::side_room(avail, window);
        let right = if sides.left {
            right.min(room - MIN_PANEL)
        } else {
            right.min(room)
        };
        let left = if sides.right {
            left.min(room - right)
        } else {
            left.min(room)
        };
        (left.max(MIN_PANEL), right.max(MIN_PANEL))
    }

    /// The widths a side panel may be dragged to (points), with the other side panel `other`
    /// points wide: at most what leaves the central area its share of the window (`avail` and
    /// `window` as in [`Self::default_widths`]).
    pub fn width_range(avail: f32, window: f32, other: f32) -> egui::Rangef {
        let max = (Self::side_room(avail, window) - other).max(MIN_PANEL);
        egui::Rangef::new(MIN_PANEL.min(max), max)
    }

    /// The layout read back from stored text; anything unreadable gives the default (a
    /// remembered layout can never open a broken window).
    pub fn validated(stored: Option<Layout>) -> Layout {
        stored.unwrap_or_default()
    }

    /// The text scale of the current mode.
    pub fn text_scale(&self) -> f32 {
        if self.projector { 1.4 } else { 1.0 }
    }
}

/// The smallest text projector mode allows (px at one pixel per point): read from the back of
/// a room.
pub const PROJECTOR_MIN_TEXT: f32 = 16.0;

/// Where [`apply_style`] keeps the current mode's smallest text size.
const TEXT_FLOOR: &str = "armlab text floor";

/// The smallest text size the current mode allows (points): [`PROJECTOR_MIN_TEXT`] in projector
/// mode, 0 otherwise. Text sized by hand (a subscript, a label painted over the 3D view) takes
/// at least this.
pub fn text_floor(ctx: &egui::Context) -> f32 {
    ctx.data(|d| d.get_temp(egui::Id::unique(TEXT_FLOOR)))
        .unwrap_or(0.0)
}

/// Applies the fonts and visuals of the mode to `ctx`: larger text in projector mode, square
/// widgets (crisp on a projector, and cheap on a software rasterizer), panels painted over the
/// cleared window.
pub fn apply_style(ctx: &egui::Context, layout: &Layout) {
    let floor = if layout.projector {
        PROJECTOR_MIN_TEXT
    } else {
        0.0
    };
    ctx.data_mut(|d| d.insert_temp(egui::Id::unique(TEXT_FLOOR), floor));
    let scale = layout.text_scale();
    ctx.global_style_mut(|s| {
        use egui::{FontId, TextStyle};
        s.text_styles
            .insert(TextStyle::Heading, FontId::proportional(18.0 * scale));
        s.text_styles
            .insert(TextStyle::Body, FontId::proportional(13.5 * scale));
        s.text_styles
            .insert(TextStyle::Button, FontId::proportional(13.5 * scale));
        // In projector mode nothing is under 16 px, small text included (11 x 1.4 = 15.4).
        let small = if layout.projector {
            (11.0 * scale).max(PROJECTOR_MIN_TEXT)
        } else {
            11.0
        };
        s.text_styles
            .insert(TextStyle::Small, FontId::proportional(small));
        s.text_styles
            .insert(TextStyle::Monospace, FontId::monospace(12.5 * scale));
        // Visible handles on the panels' edges.
        s.interaction.resize_grab_radius_side = 6.0;
    });
    let mut v = egui::Visuals::light();
    if layout.projector {
        v.override_text_color = Some(egui::Color32::BLACK);
    }
    // Panels are painted transparent over a window cleared to the background colour: the same
    // pixels, but a clear costs almost nothing where a window-sized egui rectangle costs
    // milliseconds per frame on a software rasterizer.
    v.panel_fill = egui::Color32::TRANSPARENT;
    // Square widgets: crisp on a projector, and a rounded corner is tessellated into a fan of
    // long thin triangles, which is what a software rasterizer pays for (the window's ~14 000
    // triangles become ~6 500, 2-3 ms of lavapipe time a frame).
    let w = &mut v.widgets;
    for state in [
        &mut w.noninteractive,
        &mut w.inactive,
        &mut w.hovered,
        &mut w.active,
        &mut w.open,
    ] {
        state.corner_radius = egui::CornerRadius::ZERO;
    }
    // The panels' edges are drawn, so their resize handles can be found.
    w.noninteractive.bg_stroke = egui::Stroke::new(1.0, egui::Color32::from_gray(170));
    ctx.set_visuals(v);
}

/// The window's background colour (what the panels show); the frame is cleared to it.
pub fn background() -> egui::Color32 {
    egui::Visuals::light().panel_fill
}
