//! The toolbar: the tabs, the view presets, what to show, projector mode and the side panels,
//! screenshot and help, in one row that never reflows; the model's name is last, right-aligned
//! and cut to the room left, so its length moves nothing.

use super::action::{Action, Actions};
use super::layout::Layout;
use super::state::DisplayToggles;
use crate::camera::{Preset, Projection};
use egui::RichText;

/// What the toolbar shows and changes; the shell hands it over (the toolbar knows nothing of
/// the window's other parts).
pub struct ToolbarContext<'a> {
    /// Projector mode and the side panels.
    pub layout: &'a Layout,
    /// The tabs' titles, in order, and the one shown.
    pub tabs: (Vec<&'static str>, usize),
    /// The model's name and degrees of freedom.
    pub model: (&'a str, usize),
    /// The 3D view's projection.
    pub projection: Projection,
    /// What the 3D view draws.
    pub display: &'a mut DisplayToggles,
    /// The 3D view's camera follows the IK target.
    pub follow: &'a mut bool,
    /// Frames recorded so far while the 3D view is being recorded.
    #[cfg(feature = "app")]
    pub recording: Option<usize>,
    /// An exam sheet is open: no screenshot, no recording.
    pub exam: bool,
    /// Whether there is a cell, and whether its collisions are checked.
    pub cell: (bool, bool),
}

/// The toolbar as a top panel of the window: what it shows is read from `layout`, the tabs
/// (`tabs`, the one shown) and `state`; it changes only the display toggles and the 3D view's
/// "follow" directly, the rest through `out`. Returns its rectangle.
pub fn bar(
    ui: &mut egui::Ui,
    layout: &Layout,
    (tabs, tab): (&mut super::tabs::Tabs, usize),
    state: &mut super::state::AppState,
    recording: Option<usize>,
    out: &mut Actions,
) -> egui::Rect {
    let _ = recording; // without the app feature there is no recorder
    let top = egui::Panel::top("top").show(ui, |ui| {
        let robot = state.robot();
        let (name, dof) = (robot.name.clone(), robot.dof());
        let cell = (state.cell_scene().is_some(), state.collisions_on());
        let mut cx = ToolbarContext {
            layout,
            tabs: (tabs.all().iter().map(|t| t.title()).collect(), tab),
            model: (&name, dof),
            projection: tabs.view3d.camera.projection,
            display: &mut state.display,
            follow: &mut tabs.view3d.follow,
            #[cfg(feature = "app")]
            recording,
            exam: state.hidden.exam,
            cell,
        };
        show(&mut cx, ui, out);
    });
    top.response.rect
}

/// Lays the toolbar out.
pub fn show(app: &mut ToolbarContext<'_>, ui: &mut egui::Ui, out: &mut Actions) {
    let projector = app.layout.projector;
    ui.horizontal(|ui| {
        // In projector mode on a narrow window the name gives its room to the tabs.
        if !projector || ui.available_width() > 1300.0 {
            ui.strong(RichText::new("armlab").size(if projector { 22.0 } else { 16.0 }));
            ui.separator();
        }
        let shown = app.tabs.1;
        for (k, title) in app.tabs.0.iter().enumerate() {
            if ui.selectable_label(shown == k, *title).clicked() {
                out.push(Action::ShowTab(k));
            }
        }
        ui.separator();
        // Large text or a narrow window: the presets fold into a menu, so the row still fits
        // (the buttons take about 280 points, and about 470 follow them, the model name
        // shrinking, and 85 more for Start class); narrower still (1200 px with six tabs), the
        // Cell menu goes there too. Start class goes there below 700 points of room (1280 px
        // with six tabs: the row is then as it was before the class came) and in projector
        // mode.
        let room = ui.available_width();
        let folded = Folded {
            presets: projector || room < 845.0,
            cell: projector || room < 610.0,
            screenshot: projector,
            class: projector || room < 700.0,
        };
        if folded.presets {
            ui.menu_button("View", |ui| view_menu(app, folded, ui, out));
        } else {
            view_buttons(app, ui, out);
        }
        ui.separator();
        show_menu(app, ui, out);
        if !folded.cell {
            ui.menu_button("Cell", |ui| cell_items(app.cell, ui, out))
                .response
                .on_hover_text("Obstacles around the robot, and collisions");
        }
        let sides = app.layout.sides();
        if ui
            .selectable_label(
                !(sides.left || sides.right),
                key_hint("Panels", "V", projector),
            )
            .on_hover_text("Hide or show both side panels (V)")
            .clicked()
        {
            out.push(Action::ToggleSidePanels);
        }
        if ui
            .selectable_label(projector, key_hint("Projector", "P", projector))
            .on_hover_text("Large fonts and lines, the 3D view large; P again restores the layout")
            .clicked()
        {
            out.push(Action::ToggleProjector);
        }
        // In projector mode Screenshot is under View (the row's large text has no room for it
        // at 1200 px with six tabs).
        if !projector {
            screenshot_button(app.exam, ui, out);
        }
        #[cfg(feature = "app")]
        record_button(app, projector, ui, out);
        if !folded.class {
            class_button(ui, out);
        }
        if ui.button("Help (H)").clicked() {
            out.push(Action::ToggleHelp);
        }
        // The model's name, in the room that is left: cut, never pushing anything.
        let name = format!("{} ({} DOF)", app.model.0, app.model.1);
        ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
            ui.add(egui::Label::new(RichText::new(name).weak()).truncate());
        });
    });
}

/// What the toolbar's row has no room for, in the View menu instead.
#[derive(Debug, Clone, Copy)]
struct Folded {
    /// The camera presets, Fit and Ortho (the View menu is there when these are folded).
    presets: bool,
    /// The Cell menu.
    cell: bool,
    /// Screenshot.
    screenshot: bool,
    /// Start class.
    class: bool,
}

/// The View menu: the presets, the model list, and what else the row has no room for.
fn view_menu(app: &ToolbarContext<'_>, folded: Folded, ui: &mut egui::Ui, out: &mut Actions) {
    view_buttons(app, ui, out);
    // In projector mode the left panel is usually closed: the model list is here.
    ui.separator();
    ui.menu_button("Model", |ui| model_menu(ui, out));
    if folded.cell {
        ui.menu_button("Cell", |ui| cell_items(app.cell, ui, out));
    }
    if folded.screenshot {
        screenshot_button(app.exam, ui, out);
    }
    if folded.class {
        class_button(ui, out);
    }
}

/// Record, except in projector mode where the row has no room for it (1200 px); a recording
/// in progress always shows its Stop.
#[cfg(feature = "app")]
fn record_button(app: &ToolbarContext<'_>, projector: bool, ui: &mut egui::Ui, out: &mut Actions) {
    if app.recording.is_none() && (app.exam || (projector && ui.available_width() <= 260.0)) {
        return;
    }
    let (label, hint) = match app.recording {
        None => (
            "Record".to_string(),
            "Record what the 3D view shows; Stop saves it as armlab-<model>-<n>.gif",
        ),
        Some(n) => (
            format!("Stop ({n})"),
            "Stop recording and save the GIF (frames recorded so far)",
        ),
    };
    if ui.button(label).on_hover_text(hint).clicked() {
        out.push(Action::Record);
    }
}

/// "Start class": the Class window (start a class server here, or join one as the teacher).
fn class_button(ui: &mut egui::Ui, out: &mut Actions) {
    if ui
        .button("Start class")
        .on_hover_text(
            "A live class: start a class server here or join one as the teacher; the students \
             follow your view on their laptops and answer your questions",
        )
        .clicked()
    {
        out.push(Action::Class(super::class::ClassAction::ToggleWindow));
        ui.close();
    }
}

/// Screenshot, off during an exam.
fn screenshot_button(exam: bool, ui: &mut egui::Ui, out: &mut Actions) {
    if ui
        .add_enabled(!exam, egui::Button::new("Screenshot"))
        .on_hover_text("Save the window as armlab-<model>-<n>.png in the current folder")
        .on_disabled_hover_text("Off during an exam")
        .clicked()
    {
        out.push(Action::Screenshot);
        ui.close();
    }
}

/// The camera presets, Fit and the projection.
fn view_buttons(app: &ToolbarContext<'_>, ui: &mut egui::Ui, out: &mut Actions) {
    for (label, p) in [
        ("Top", Preset::Top),
        ("Front", Preset::Front),
        ("Side", Preset::Side),
        ("Iso", Preset::Iso),
    ] {
        if ui.button(label).clicked() {
            out.push(Action::CameraPreset(p));
        }
    }
    if ui.button("Fit").clicked() {
        out.push(Action::Fit);
    }
    let ortho = matches!(app.projection, Projection::Orthographic { .. });
    if ui.selectable_label(ortho, "Ortho").clicked() {
        out.push(Action::ToggleProjection);
    }
}

/// "Show": what the 3D view draws.
fn show_menu(app: &mut ToolbarContext<'_>, ui: &mut egui::Ui, out: &mut Actions) {
    ui.menu_button("Show", |ui| {
        let d = &mut *app.display;
        ui.checkbox(&mut d.frames, "Frames (D)");
        ui.checkbox(&mut d.labels, "Labels");
        ui.checkbox(&mut d.all_labels, "Labels of every frame")
            .on_hover_text("Big robots label only the driven chain's frames unless this is on");
        ui.checkbox(&mut d.grid, "Grid (G)");
        ui.checkbox(&mut d.trail, "Trail (T)");
        ui.checkbox(&mut d.ghosts, "All postures");
        let mut ws = d.workspace;
        if ui.checkbox(&mut ws, "Workspace (W)").changed() {
            out.push(Action::ToggleWorkspace);
        }
        let mut reach = d.reachability;
        if ui
            .checkbox(&mut reach, "Reachability")
            .on_hover_text(
                "Where the tool reaches, in which orientations and with which postures: a \
                 slice of voxels coloured by the share of orientations reached",
            )
            .changed()
        {
            use super::reachability::ReachabilityAction;
            out.push(Action::Reachability(ReachabilityAction::Show(reach)));
        }
        ui.checkbox(app.follow, "Camera follows the target");
        ui.separator();
        if ui
            .button("Present this figure (F5)")
            .on_hover_text(
                "The tab's figure fills the window, without bars or panels; F5 or Esc leaves",
            )
            .clicked()
        {
            out.push(Action::TogglePresent);
            ui.close();
        }
    });
}

/// The Cell menu: obstacles sized to the robot, the checks, the scene file. `cell` says
/// whether there is a cell and whether its collisions are checked.
fn cell_items((exists, on): (bool, bool), ui: &mut egui::Ui, out: &mut Actions) {
    use super::cell::{CellAction, ObstacleKind};
    for kind in ObstacleKind::ALL {
        if ui.button(format!("Add {}", kind.name())).clicked() {
            out.push(Action::Cell(CellAction::Add(kind)));
            ui.close();
        }
    }
    ui.separator();
    let mut check = on;
    if ui
        .checkbox(&mut check, "Check collisions")
        .on_hover_text("The arm and every posture against itself and the obstacles")
        .changed()
    {
        out.push(Action::Cell(CellAction::Check(check)));
    }
    if ui.button("Open scene...").clicked() {
        out.push(Action::Cell(CellAction::Open(None)));
        ui.close();
    }
    if ui
        .add_enabled(exists, egui::Button::new("Save scene..."))
        .clicked()
    {
        out.push(Action::Cell(CellAction::Save(None)));
        ui.close();
    }
    if ui
        .add_enabled(exists, egui::Button::new("Remove the cell"))
        .on_hover_text("Every obstacle goes; nothing is checked")
        .clicked()
    {
        out.push(Action::Cell(CellAction::Use(None)));
        ui.close();
    }
}

/// A button's name with its key, `Panels (V)`; in projector mode without the key (the row's
/// large text leaves no room for it at 1280 px; the keys are in the help and on hover).
fn key_hint(name: &str, key: &str, projector: bool) -> String {
    if projector {
        name.to_string()
    } else {
        format!("{name} ({key})")
    }
}

/// The projector's model menu: every built-in model, and a model file.
fn model_menu(ui: &mut egui::Ui, out: &mut Actions) {
    egui::ScrollArea::vertical()
        .max_height(ui.ctx().content_rect().height() * 0.7)
        .show(ui, |ui| {
            for b in crate::kinematics::models::BUILT_INS {
                if ui.button(b.name).on_hover_text(b.summary).clicked() {
                    out.push(Action::Load(b.name.to_string()));
                    ui.close();
                }
            }
        });
    ui.separator();
    if ui.button("Open file...").clicked() {
        out.push(Action::OpenDialog);
        ui.close();
    }
}
