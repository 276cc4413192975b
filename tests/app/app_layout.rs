//! The live window's layout, checked through the window's own layout code (`AppUi::show`, the
//! same panels, widths and styles as the window; egui_kittest reads the widgets' rectangles from
//! the accessibility tree): for every built-in model and every tab, at 1280x800, 1920x1080 and
//! 1200x800 (the guide's pictures; the pose matrix was cut there),
//! in normal and projector mode. The invariants a class relies on:
//! - the 3D view (the central area) keeps at least 55 % of the window's width;
//! - every panel lies inside the window, and the toolbar stays one row;
//! - no interactive widget is cut by its panel's side edges (wide tables scroll inside their
//!   panel: the DH table's cells are the one exception, inside a horizontal scroll area), and no
//!   two visible interactive widgets overlap;
//! - P twice restores every panel rectangle;
//! - the layout settles: no frame asks egui to discard and lay out again once it is steady.

use armlab::app::AppUi;
use armlab::app::layout::CENTRAL_SHARE;
use armlab::app::shell::PanelRects;
use armlab::app::state::AppState;
use armlab::app::tabs::Tabs;
use armlab::kinematics::models::BUILT_INS;
use egui::{Rect, vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};

const SIZES: [[f32; 2]; 3] = [[1280.0, 800.0], [1920.0, 1080.0], [1200.0, 800.0]];

fn harness(app: AppUi, size: [f32; 2]) -> Harness<'static, AppUi> {
    let mut h = Harness::builder()
        .with_size(vec2(size[0], size[1]))
        .build_ui_state(|ui, app: &mut AppUi| app.show(ui, None), app);
    settle(&mut h);
    h
}

/// A few frames: panel widths and text wrapping settle in the first two.
fn settle(h: &mut Harness<'static, AppUi>) {
    for _ in 0..4 {
        h.step();
    }
}

/// Interactive roles: what a click is meant for.
fn interactive(role: egui::accesskit::Role) -> bool {
    use egui::accesskit::Role::*;
    matches!(
        role,
        Button
            | CheckBox
            | RadioButton
            | Slider
            | SpinButton
            | TextInput
            | ComboBox
            | DisclosureTriangle
            | Tab
    )
}

/// The DH table's cells ("q3 alpha"): they scroll sideways inside their own area.
fn in_dh_table(label: &str) -> bool {
    label.rsplit_once(' ').is_some_and(|(joint, field)| {
        joint.starts_with('q')
            && ["a", "alpha", "d", "theta", "offset", "lower", "upper"].contains(&field)
    })
}

/// Every layout invariant for one window; `what` names it in failures.
fn check(h: &Harness<'static, AppUi>, size: [f32; 2], what: &str) -> Vec<String> {
    let mut bad = Vec::new();
    let app = h.state();
    let r = app.rects;
    let window = Rect::from_min_size(egui::Pos2::ZERO, vec2(size[0], size[1]));
    let share = r.central.width() / size[0];
    if share < CENTRAL_SHARE - 0.005 {
        bad.push(format!(
            "{what}: the central area is {:.0} px, {:.0} % of the window",
            r.central.width(),
            share * 100.0
        ));
    }
    let regions: Vec<(&str, Rect)> = [
        ("left panel", r.left),
        ("right panel", r.right),
        ("central area", Some(r.central)),
        ("toolbar", Some(r.top)),
        ("status bar", Some(r.bottom)),
    ]
    .into_iter()
    .filter_map(|(n, r)| r.map(|r| (n, r)))
    .collect();
    for (name, rect) in &regions {
        if !window.expand(0.5).contains_rect(*rect) {
            bad.push(format!("{what}: the {name} {rect:?} leaves the window"));
        }
    }
    let row = if app.layout.projector { 48.0 } else { 34.0 };
    if r.top.height() > row {
        bad.push(format!(
            "{what}: the toolbar is {:.0} px high: it reflowed",
            r.top.height()
        ));
    }
    bad.extend(cut_text(h, &regions, what));
    // Visible interactive widgets, each in the region holding its centre.
    let mut seen: Vec<(String, Rect)> = Vec::new();
    for n in h.query_all_by(|n| interactive(n.role())) {
        let Some(b) = n.accesskit_node().bounding_box() else {
            continue;
        };
        let rect = Rect::from_min_max(
            egui::pos2(b.x0 as f32, b.y0 as f32),
            egui::pos2(b.x1 as f32, b.y1 as f32),
        );
        let label = n.accesskit_node().label().unwrap_or_default();
        let Some((region, area)) = regions.iter().find(|(_, a)| a.contains(rect.center())) else {
            continue; // scrolled out of sight, or in a popup
        };
        let cut = rect.min.x < area.min.x - 0.5 || rect.max.x > area.max.x + 0.5;
        if cut && !in_dh_table(&label) {
            bad.push(format!(
                "{what}: \"{label}\" ({:?}) {rect:?} is cut by the {region}'s edge {area:?}",
                n.accesskit_node().role()
            ));
        }
        // Overlaps are checked among widgets wholly visible in their region.
        if area.expand(0.5).contains_rect(rect) && !in_dh_table(&label) {
            for (other, o) in &seen {
                let i = rect.intersect(*o);
                if i.is_positive() && i.area() > 4.0 {
                    bad.push(format!(
                        "{what}: \"{label}\" {rect:?} overlaps \"{other}\" {o:?}"
                    ));
                }
            }
            seen.push((label, rect));
        }
    }
    bad
}

/// The rectangle of an accessibility node (points).
fn rect_of(n: &egui_kittest::Node<'_>) -> Option<Rect> {
    let b = n.accesskit_node().bounding_box()?;
    Some(Rect::from_min_max(
        egui::pos2(b.x0 as f32, b.y0 as f32),
        egui::pos2(b.x1 as f32, b.y1 as f32),
    ))
}

/// Text cut by a panel's edge (a matrix too wide for its panel once was, and the Calibration
/// tab's sentences at 1280 px): every text run whose centre is in a side panel or the central
/// area lies inside its width, except in the DH table, which
/// scrolls sideways (the rows between its header and its horizontal scroll bar).
fn cut_text(h: &Harness<'static, AppUi>, regions: &[(&str, Rect)], what: &str) -> Vec<String> {
    let dh_top = h
        .query_all_by_role(egui::accesskit::Role::DisclosureTriangle)
        .find(|n| {
            n.accesskit_node()
                .label()
                .is_some_and(|l| l.starts_with("DH table"))
        })
        .and_then(|n| rect_of(&n))
        .map(|r| r.max.y);
    let dh_band = dh_top.and_then(|top| {
        h.query_all_by_role(egui::accesskit::Role::ScrollBar)
            .filter_map(|n| rect_of(&n))
            .filter(|r| r.width() > 3.0 * r.height() && r.min.y > top)
            .map(|r| top..=r.max.y)
            .min_by(|a, b| a.end().total_cmp(b.end()))
    });
    let mut bad = Vec::new();
    for n in h.query_all_by(|n| {
        matches!(
            n.role(),
            egui::accesskit::Role::TextRun | egui::accesskit::Role::Label
        )
    }) {
        let Some(rect) = rect_of(&n) else { continue };
        // A text field's text scrolls inside the field.
        let in_field = n
            .accesskit_node()
            .parent()
            .is_some_and(|p| p.role() == egui::accesskit::Role::TextInput);
        if in_field
            || rect.width() <= 0.0
            || dh_band
                .as_ref()
                .is_some_and(|b| b.contains(&rect.center().y))
        {
            continue;
        }
        let Some((region, area)) = regions
            .iter()
            .filter(|(name, _)| name.ends_with("panel") || *name == "central area")
            .find(|(_, a)| a.contains(rect.center()))
        else {
            continue;
        };
        if rect.min.x < area.min.x - 0.5 || rect.max.x > area.max.x + 0.5 {
            let text = n.accesskit_node().value().unwrap_or_default();
            bad.push(format!(
                "{what}: text \"{text}\" {rect:?} is cut by the {region}'s edge {area:?}"
            ));
        }
    }
    bad
}

fn tab_names() -> Vec<&'static str> {
    Tabs::default().all().iter().map(|t| t.title()).collect()
}

/// Every built-in and every tab, at both sizes, normal and in projector mode.
#[test]
fn every_model_and_tab_keeps_the_3d_view_and_clips_nothing() {
    let mut bad = Vec::new();
    for size in SIZES {
        for projector in [false, true] {
            for b in BUILT_INS {
                let mut app = AppUi::new(AppState::from_spec(b.name).unwrap());
                app.layout.projector = projector;
                let mut h = harness(app, size);
                for (tab, title) in tab_names().iter().enumerate() {
                    if tab == armlab::app::tabs::WORKSPACE && b.name != "planar2" {
                        // Every model's workspace figure is a minute of CPU in the background;
                        // the tab's layout does not depend on the model (checked on one).
                        continue;
                    }
                    h.state_mut().tab = tab;
                    settle(&mut h);
                    let what = format!(
                        "{} in {title} at {}x{}{}",
                        b.name,
                        size[0],
                        size[1],
                        if projector { " (projector)" } else { "" }
                    );
                    bad.extend(check(&h, size, &what));
                }
            }
        }
    }
    assert!(
        bad.is_empty(),
        "{} problems:\n{}",
        bad.len(),
        bad.join("\n")
    );
}

/// A cell (a table and a box, the box selected: its size, position and angles in the Cell
/// section) and the solution list with what each posture hits: nothing clipped or overlapping,
/// at every size, normal and in projector mode with the side panels shown.
#[test]
fn the_cell_section_clips_nothing() {
    use armlab::app::cell::ObstacleKind;
    let mut bad = Vec::new();
    for size in SIZES {
        for projector in [false, true] {
            let mut state = AppState::from_spec("puma560").unwrap();
            for kind in [ObstacleKind::Table, ObstacleKind::Box] {
                let o = kind.obstacle(state.robot());
                state.add_obstacle(o).unwrap();
            }
            let mut app = AppUi::new(state);
            app.layout.projector = projector;
            let mut h = harness(app, size);
            if projector && h.state().rects.right.is_none() {
                h.key_press(egui::Key::V);
                settle(&mut h);
            }
            assert!(h.state().rects.right.is_some(), "the right panel is shown");
            let what = format!(
                "puma560 with a cell at {}x{}{}",
                size[0],
                size[1],
                if projector { " (projector)" } else { "" }
            );
            bad.extend(check(&h, size, &what));
        }
    }
    assert!(
        bad.is_empty(),
        "{} problems:\n{}",
        bad.len(),
        bad.join("\n")
    );
}

/// The Reachability section, with a map, a voxel's directions, the postures at the target and
/// a placement shown, clips nothing and keeps the 3D view's share, in every size and mode.
#[test]
fn the_reachability_section_clips_nothing() {
    use armlab::app::action::Action;
    use armlab::app::reachability::ReachabilityAction;
    use armlab::app::state::placement::PlaceSettings;
    use armlab::app::state::reachability::MapSettings;
    let mut bad = Vec::new();
    for size in SIZES {
        for projector in [false, true] {
            let mut app = AppUi::new(AppState::from_spec("puma560").unwrap());
            app.layout.projector = projector;
            app.ik.reach.map.settings = MapSettings {
                voxel_m: 0.2,
                directions: 16,
                rolls: 2,
            };
            app.apply(Action::Reachability(ReachabilityAction::Show(true)));
            app.ik.reach.map.wait(&app.state, 0);
            let m = &app.ik.reach.map.result().unwrap().map;
            let s = m.reachable.iter().position(|&b| b).unwrap();
            let (voxel, direction, roll) = (s / 32, s / 2 % 16, s % 2);
            app.apply(Action::Reachability(ReachabilityAction::Aim {
                voxel,
                direction,
                roll,
            }));
            app.apply(Action::Reachability(ReachabilityAction::AddTargetAsTask));
            let area = [-0.2, 0.2, -0.2, 0.2];
            let grid = PlaceSettings {
                area,
                step: 0.1,
                yaws: 4,
            };
            app.apply(Action::Reachability(ReachabilityAction::Place(grid)));
            app.ik.reach.placement.wait();
            let mut h = harness(app, size);
            if projector && h.state().rects.right.is_none() {
                h.key_press(egui::Key::V);
                settle(&mut h);
            }
            assert!(h.state().rects.right.is_some(), "the right panel is shown");
            let what = format!(
                "puma560 with the reachability overlay at {}x{}{}",
                size[0],
                size[1],
                if projector { " (projector)" } else { "" }
            );
            bad.extend(check(&h, size, &what));
        }
    }
    assert!(
        bad.is_empty(),
        "{} problems:\n{}",
        bad.len(),
        bad.join("\n")
    );
}

/// Projector mode twice (the P key) gives back every panel rectangle, in every tab; and in
/// projector mode the 3D view is the largest thing on screen.
#[test]
fn projector_mode_twice_restores_every_panel() {
    for name in ["puma560", "dlr", "planar2_fig2_30"] {
        for size in SIZES {
            let mut h = harness(AppUi::new(AppState::from_spec(name).unwrap()), size);
            for tab in 0..tab_names().len() {
                h.state_mut().tab = tab;
                settle(&mut h);
                let before: PanelRects = h.state().rects;
                h.key_press(egui::Key::P);
                settle(&mut h);
                assert!(h.state().layout.projector);
                let r = h.state().rects;
                for side in [r.left, r.right].into_iter().flatten() {
                    assert!(
                        r.central.width() > side.width(),
                        "{name}: projector mode: the 3D view {:?} is not the largest, {side:?}",
                        r.central
                    );
                }
                // Moving the mouse over the window changes nothing (it once grew a panel).
                for x in [100.0, 400.0, 900.0, 1200.0] {
                    h.hover_at(egui::pos2(x, 300.0));
                    h.step();
                }
                settle(&mut h);
                assert_eq!(
                    r,
                    h.state().rects,
                    "{name}: projector layout moved with the mouse"
                );
                h.key_press(egui::Key::P);
                for _ in 0..4 {
                    h.step();
                }
                assert!(!h.state().layout.projector);
                assert_eq!(
                    before,
                    h.state().rects,
                    "{name} tab {tab} at {size:?}: P twice changed the panels"
                );
            }
        }
    }
}

/// The toolbar's buttons stay where they are whatever the model's name: a click meant for
/// "Top" never hits another button after a model change.
#[test]
fn the_toolbar_does_not_move_when_the_model_changes() {
    let positions = |name: &str| -> Vec<(String, Rect)> {
        let h = harness(AppUi::new(AppState::from_spec(name).unwrap()), SIZES[0]);
        h.query_all_by_role(egui::accesskit::Role::Button)
            .filter(|n| n.rect().max.y < h.state().rects.top.max.y)
            .map(|n| (n.accesskit_node().label().unwrap_or_default(), n.rect()))
            .collect()
    };
    let short = positions("planar2");
    assert!(short.len() >= 10, "toolbar buttons: {short:?}");
    for name in ["stanford", "anthropomorphic_spherical_wrist", "humanoid"] {
        assert_eq!(short, positions(name), "{name}");
    }
}

/// A remembered layout with a panel dragged far too wide (or a stored panel state from a
/// larger screen) opens with the central area's share: the stored width is clamped.
#[test]
fn a_remembered_oversized_panel_is_clamped() {
    let app = AppUi::new(AppState::from_spec("puma560").unwrap());
    let mut h = Harness::builder()
        .with_size(vec2(1280.0, 800.0))
        .build_ui_state(|ui, app: &mut AppUi| app.show(ui, None), app);
    h.step();
    // Drag the left panel's edge to the far right.
    let edge = h.state().rects.left.unwrap().right();
    h.drag_at(egui::pos2(edge, 400.0));
    h.step();
    for x in [600.0, 900.0, 1250.0] {
        h.hover_at(egui::pos2(x, 400.0));
        h.step();
    }
    h.drop_at(egui::pos2(1250.0, 400.0));
    settle(&mut h);
    let bad = check(
        &h,
        SIZES[0],
        "after dragging the left panel to the right edge",
    );
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// Once steady, a frame asks for no second layout pass (egui warns when every frame does, and
/// the window then lays itself out twice a frame).
#[test]
fn a_steady_window_lays_out_once_a_frame() {
    for name in ["puma560", "dlr", "stanford"] {
        for projector in [false, true] {
            let mut app = AppUi::new(AppState::from_spec(name).unwrap());
            app.layout.projector = projector;
            let mut h = harness(app, SIZES[0]);
            for tab in 0..tab_names().len() {
                h.state_mut().tab = tab;
                settle(&mut h);
                settle(&mut h);
                h.step();
                let reasons = &h.output().platform_output.request_discard_reasons;
                assert!(
                    reasons.is_empty(),
                    "{name} tab {tab} projector {projector}: discard requested every frame: {reasons:?}"
                );
            }
        }
    }
}

/// The Calibration tab after each lesson, with its report and the accuracy maps, at 1280x800:
/// nothing cut (its buttons and the identifiability sentence once were), and the lesson says in
/// one sentence what to look at.
#[test]
fn the_calibration_tab_after_its_lessons_fits_at_1280() {
    for projector in [false, true] {
        let mut app = AppUi::new(AppState::from_spec("puma560").unwrap());
        app.layout.projector = projector;
        app.tab = armlab::app::tabs::CALIBRATION;
        let mut h = harness(app, SIZES[0]);
        for lesson in [
            "Lesson: converged is not accurate",
            "Lesson: parallel axes",
            "... with Hayati's beta",
        ] {
            h.get_by_label(lesson).click();
            settle(&mut h);
            let lab = &h.state().tabs.calibration.lab;
            let sentence = lab.lesson.expect("the lesson says what to look at");
            assert!(sentence.starts_with("Look at"), "{sentence}");
            assert!(h.query_by_label_contains("Look at").is_some());
            let what = format!("calibration after \"{lesson}\" (projector {projector})");
            let bad = check(&h, SIZES[0], &what);
            assert!(bad.is_empty(), "{}", bad.join("\n"));
        }
        h.state_mut().tabs.calibration.lab.compute_maps(40, 4_000);
        settle(&mut h);
        assert!(
            h.query_by_label_contains("share one colour scale")
                .is_some()
        );
        let bad = check(&h, SIZES[0], "calibration with its maps");
        assert!(bad.is_empty(), "{}", bad.join("\n"));
    }
}

/// C shows the construction and scrolls the right panel to it at 1280x800: the step buttons and
/// the current step are in sight without touching the scroll bar (they were below the fold).
#[test]
fn the_construction_steps_come_into_view_when_shown() {
    for name in ["puma560", "stanford", "planar2_fig2_30"] {
        let mut h = harness(AppUi::new(AppState::from_spec(name).unwrap()), SIZES[0]);
        h.key_press(egui::Key::C);
        settle(&mut h);
        settle(&mut h);
        let right = h.state().rects.right.unwrap();
        let next = h.get_by_label("Next (N) >").rect();
        assert!(
            right.contains_rect(next),
            "{name}: the Next button {next:?} is out of sight in {right:?}"
        );
        let step = h
            .query_all_by(|n| {
                n.role() == egui::accesskit::Role::Button
                    && n.label().is_some_and(|l| l.starts_with("1. "))
            })
            .next()
            .expect("the first step")
            .rect();
        assert!(
            right.contains_rect(step),
            "{name}: step 1 {step:?} is out of sight"
        );
    }
}

/// Issue 46, item 8: V in projector mode showed both panels, the left one so narrow that it
/// wrapped "Open" as "Ope n". Now it shows one panel at a time, the left one at least as wide
/// as in normal mode, every layout invariant kept; the model list is in the toolbar too.
#[test]
fn v_in_projector_mode_gives_a_readable_panel_and_the_model_list_is_in_the_toolbar() {
    let size = [1280.0, 800.0];
    let normal = harness(AppUi::new(AppState::from_spec("puma560").unwrap()), size);
    let normal_left = normal.state().rects.left.unwrap().width();
    let mut app = AppUi::new(AppState::from_spec("puma560").unwrap());
    app.layout.projector = true;
    let mut h = harness(app, size);
    assert!(h.state().rects.left.is_none() && h.state().rects.right.is_some());
    h.key_press(egui::Key::V);
    settle(&mut h);
    let r = h.state().rects;
    let left = r.left.expect("V shows the left panel");
    assert!(r.right.is_none(), "one panel at a time in projector mode");
    assert!(
        left.width() >= normal_left,
        "left panel {} px, {normal_left} px in normal mode",
        left.width()
    );
    let bad = check(&h, size, "projector, V");
    assert!(bad.is_empty(), "{bad:#?}");
    // the Open button is one line: as high as the Help button
    let height = |h: &Harness<'static, AppUi>, label: &str| {
        rect_of(&h.get_by_label(label)).unwrap().height()
    };
    let (open, help) = (height(&h, "Open"), height(&h, "Help (H)"));
    assert!(open <= help + 0.5, "Open {open} px high, Help {help} px");
    h.key_press(egui::Key::V);
    settle(&mut h);
    assert!(h.state().rects.left.is_none() && h.state().rects.right.is_none());
    h.key_press(egui::Key::V);
    settle(&mut h);
    assert!(h.state().rects.left.is_none() && h.state().rects.right.is_some());
    // the model list without any panel
    h.get_by_label("View").click();
    settle(&mut h);
    h.get_by_label("Model").click();
    settle(&mut h);
    h.get_by_label("stanford").click();
    settle(&mut h);
    assert_eq!(h.state().state.spec(), "stanford");
}

/// Every text egui paints (its font size in pixels) and the text itself, visible in the window.
fn painted_text(h: &Harness<'static, AppUi>) -> Vec<(f32, String)> {
    fn walk(shape: &egui::Shape, clip: Rect, out: &mut Vec<(f32, String)>) {
        match shape {
            egui::Shape::Vec(v) => v.iter().for_each(|s| walk(s, clip, out)),
            egui::Shape::Text(t) => {
                let bounds = t.visual_bounding_rect();
                if !bounds.intersects(clip) || t.galley.job.text.trim().is_empty() {
                    return;
                }
                for s in &t.galley.job.sections {
                    let text = &t.galley.job.text[s.byte_range.start.0..s.byte_range.end.0];
                    if !text.trim().is_empty() {
                        out.push((s.format.font_id.size, text.to_string()));
                    }
                }
            }
            _ => {}
        }
    }
    let out = h.output();
    let ppp = out.pixels_per_point;
    let mut texts = Vec::new();
    for c in &out.shapes {
        walk(&c.shape, c.clip_rect, &mut texts);
    }
    texts.into_iter().map(|(s, t)| (s * ppp, t)).collect()
}

/// Issue 46, item 4: in projector mode at 1280x800, no text egui paints in any tab is under
/// 16 px (Fig. 2.30's marks were 7-10 px, the construction's formulas 13, the drag readout
/// about 10). The figures' own pictures are checked where they are drawn.
#[test]
fn projector_text_is_at_least_16_px_in_every_tab() {
    let mut bad = Vec::new();
    for model in ["puma560", "dlr", "planar2"] {
        for tab in 0..armlab::app::tabs::Tabs::COUNT {
            let mut app = AppUi::new(AppState::from_spec(model).unwrap());
            app.layout.projector = true;
            app.tab = tab;
            app.ik.construction.shown = true;
            app.ik.symbols.shown = true;
            app.state.display.ghosts = true;
            let mut h = harness(app, [1280.0, 800.0]);
            // the left panel too (V), then the right one again
            for _ in 0..2 {
                for (size, text) in painted_text(&h) {
                    if size < 16.0 - 0.01 {
                        bad.push(format!("{model}, tab {tab}: {size:.1} px: {text:?}"));
                    }
                }
                h.key_press(egui::Key::V);
                settle(&mut h);
            }
        }
    }
    bad.sort();
    bad.dedup();
    assert!(
        bad.is_empty(),
        "{} texts under 16 px:\n{}",
        bad.len(),
        bad.join("\n")
    );
}

/// Issue 46, item 4: "present this figure" fills the window with the tab's figure: F5 (or the
/// Show menu's button) hides the toolbar, the side panels, the status bar and the workspace
/// tab's controls; the central area is the whole window; Esc restores every rectangle. In
/// projector mode the way out is said in text of at least 16 px.
#[test]
fn present_this_figure_fills_the_window_and_esc_restores_the_layout() {
    let size = [1280.0, 800.0];
    for (tab, projector) in [(0, false), (1, false), (0, true)] {
        let mut app = AppUi::new(AppState::from_spec("planar2").unwrap());
        app.layout.projector = projector;
        app.tab = tab;
        let mut h = harness(app, size);
        let before = h.state().rects;
        assert!(before.central.width() < size[0] - 100.0 || projector);
        if tab == 0 {
            h.get_by_label("Show").click();
            settle(&mut h);
            h.get_by_label("Present this figure (F5)").click();
        } else {
            h.key_press(egui::Key::F5);
        }
        settle(&mut h);
        let r = h.state().rects;
        assert!(h.state().layout.present, "tab {tab}: presenting");
        assert!(r.left.is_none() && r.right.is_none(), "tab {tab}: {r:?}");
        // the central panel is the window, less egui's margin
        assert!(
            r.central.width() >= size[0] - 20.0 && r.central.height() >= size[1] - 20.0,
            "tab {tab}: central {:?}",
            r.central
        );
        for gone in ["Projector (P)", "Show", "Figure:"] {
            assert!(
                h.query_by_label(gone).is_none(),
                "tab {tab}: {gone} still shown while presenting"
            );
        }
        let hint = painted_text(&h)
            .into_iter()
            .find(|(_, t)| t.contains("Esc"))
            .expect("the way out is said");
        if projector {
            assert!(hint.0 >= 16.0, "hint {} px", hint.0);
        }
        h.key_press(egui::Key::Escape);
        settle(&mut h);
        assert!(!h.state().layout.present);
        assert_eq!(
            h.state().rects,
            before,
            "tab {tab}: Esc restores every rectangle"
        );
    }
}
