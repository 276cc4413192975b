//! The app driven through egui like a user: buttons clicked by their label (egui_kittest,
//! through the accessibility tree) and clicks at pixel positions in the 3D view. No GPU: the
//! layout and the interaction run without painting.

use armlab::app::AppUi;
use armlab::app::state::AppState;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};

fn harness(app: AppUi) -> Harness<'static, AppUi> {
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_ui_state(|ui, app: &mut AppUi| app.show(ui, None), app);
    h.run();
    h
}

#[test]
fn the_screenshot_button_asks_the_frame_loop_for_a_screenshot() {
    let mut h = harness(AppUi::new(AppState::from_spec("planar3").unwrap()));
    assert!(!h.state().screenshot_requested);
    h.get_by_label("Screenshot").click();
    h.run();
    assert!(h.state().screenshot_requested);
}

#[test]
fn the_help_button_and_the_h_key_toggle_the_shortcut_list() {
    let mut h = harness(AppUi::new(AppState::from_spec("planar3").unwrap()));
    h.get_by_label("Help (H)").click();
    h.run();
    assert!(h.state().show_help);
    assert!(h.query_by_label("Keyboard shortcuts").is_some());
    h.key_press(egui::Key::H);
    h.run();
    assert!(!h.state().show_help);
}

/// Clicking next to a ghost arm's joint in the 3D view makes that posture the arm's.
#[test]
fn clicking_a_ghost_arm_selects_its_posture() {
    let mut state = AppState::from_spec("puma560").unwrap();
    state.set_q(&[0.3, 0.5, -1.2, 0.4, 0.8, -0.6]).unwrap();
    let tool = state.robot().fk(state.q()).unwrap();
    state.set_target(0, tool).unwrap();
    let mut app = AppUi::new(state);
    app.state.display.ghosts = true;
    let mut h = harness(app);
    // Where each ghost's joints project in the view (window points).
    let app = h.state();
    let [w, hp] = app.tabs.view3d.viewport_px;
    let rect = app.tabs.view3d.viewport_rect;
    let robot = app.state.robot();
    let chain = robot.chain_to(robot.end_effectors()[0].parent).to_vec();
    let project = |q: &[f64]| -> Vec<egui::Pos2> {
        let frames = robot.fk_frames(q).unwrap();
        chain
            .iter()
            .filter_map(|&j| {
                let p = armlab::scene::point32(&frames[j].translation.vector);
                app.tabs.view3d.camera.project(&p, w, hp)
            })
            .map(|px| rect.min + egui::vec2(px[0], px[1]))
            .collect()
    };
    let ghosts = app.state.ghosts(0);
    let tool_px = *project(app.state.q()).last().unwrap();
    // A joint of an unselected ghost within the limits that no other such ghost's joint is
    // near, away from the target gizmo. Ghosts outside the limits may share the point (the
    // postures differing only at the wrist put their joints at the same places): the click
    // prefers the one that can be selected.
    let mut pick = None;
    for g in ghosts.iter().filter(|g| !g.selected && g.within_limits) {
        for p in project(&g.q) {
            let clear = ghosts
                .iter()
                .filter(|o| !o.selected && o.within_limits && o.posture != g.posture)
                .flat_map(|o| project(&o.q))
                .all(|x| (x - p).length() > 45.0);
            if clear && (p - tool_px).length() > 160.0 && rect.shrink(5.0).contains(p) {
                pick = Some((g.posture.clone(), p));
            }
        }
    }
    let (posture, at) = pick.expect("a ghost joint clear of the others and of the gizmo");
    let before = h.state().state.q().to_vec();
    h.event(egui::Event::PointerMoved(at));
    h.run();
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton {
            pos: at,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: egui::Modifiers::NONE,
        });
        h.run();
    }
    let app = h.state();
    let selected: Vec<_> = app
        .state
        .ghosts(0)
        .into_iter()
        .filter(|g| g.selected)
        .collect();
    assert_eq!(selected.len(), 1);
    assert_eq!(selected[0].posture, posture, "clicked at {at:?}");
    assert_ne!(
        app.state.q(),
        before.as_slice(),
        "the arm took the new posture"
    );
}

/// The window's widgets run in an inner context on the outer (eframe's) input: a click reaches
/// them, and what they ask of the platform (cursor, clipboard, repaint) reaches the outer one.
#[test]
fn the_inner_context_gets_the_input_and_hands_back_the_platform_output() {
    use armlab::app::inner::InnerUi;
    let outer = egui::Context::default();
    let mut inner = InnerUi::default();
    let screen = egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(400.0, 300.0));
    let at = egui::pos2(32.0, 30.0);
    let mut clicks = 0;
    let mut frame = |events: Vec<egui::Event>, clicks: &mut i32| {
        let raw = egui::RawInput {
            screen_rect: Some(screen),
            events,
            ..Default::default()
        };
        let mut painted = None;
        let mut out = outer.run_ui(raw, |ui| {
            painted = Some(inner.run(ui.ctx(), |ui| {
                egui::Area::new(egui::Id::unique("probe"))
                    .fixed_pos(egui::pos2(20.0, 20.0))
                    .show(ui.ctx(), |ui| {
                        let r = ui.button("Copy");
                        if r.hovered() {
                            ui.ctx().set_cursor_icon(egui::CursorIcon::PointingHand);
                        }
                        if r.clicked() {
                            *clicks += 1;
                            ui.ctx().copy_text("q = [0, 1]".into());
                            ui.ctx().request_repaint();
                        }
                    });
            }));
        });
        // The outer context's own textures (its font atlas) are not painted here.
        out.textures_delta.clear();
        (out, painted.expect("inner frame"))
    };
    let (_, first) = frame(vec![egui::Event::PointerMoved(at)], &mut clicks);
    assert_eq!(first.size_px, [400, 300]);
    let press = |pressed| egui::Event::PointerButton {
        pos: at,
        button: egui::PointerButton::Primary,
        pressed,
        modifiers: egui::Modifiers::NONE,
    };
    // An area is laid out invisibly in its first frame, and hovering is found against the
    // widgets of the frame before: two more frames.
    frame(vec![], &mut clicks);
    let (out, second) = frame(vec![], &mut clicks);
    assert!(
        !second.prims.is_empty(),
        "the inner frame has the button to paint"
    );
    assert_eq!(
        out.platform_output.cursor_icon,
        egui::CursorIcon::PointingHand
    );
    frame(vec![press(true)], &mut clicks);
    let (out, _) = frame(vec![press(false)], &mut clicks);
    assert_eq!(clicks, 1, "the click reached the inner widget");
    assert!(
        out.platform_output
            .commands
            .iter()
            .any(|c| matches!(c, egui::OutputCommand::CopyText(t) if t == "q = [0, 1]")),
        "{:?}",
        out.platform_output.commands
    );
    assert!(
        out.viewport_output[&egui::ViewportId::ROOT]
            .repaint_delay
            .is_zero()
    );
    // Each outer frame is one pass: the inner context's passes are not counted into it (they
    // once were, and egui showed "request_discard has been called N frames in a row" over the
    // toolbar of every live window).
    for _ in 0..3 {
        let (out, _) = frame(vec![], &mut clicks);
        assert_eq!(out.platform_output.num_completed_passes, 1);
        assert!(out.platform_output.request_discard_reasons.is_empty());
    }
}

/// Every cell of the DH table is wide enough for its whole entry (the grid once squeezed the
/// Puma's "671.83" to "671." and "-160" to "-16"); the table scrolls sideways inside its panel
/// instead of widening it, so the panel ends where the 3D view starts.
#[test]
fn dh_cells_show_their_whole_entry() {
    let mut h = harness(AppUi::new(AppState::from_spec("puma560").unwrap()));
    h.run();
    let ctx = h.ctx.clone();
    let font = egui::TextStyle::Body.resolve(&ctx.global_style());
    let panel = h.state().tabs.view3d.viewport_rect.min.x;
    let mut checked = 0;
    for j in 1..=6 {
        for field in ["a", "alpha", "d", "lower", "upper"] {
            let label = format!("q{j} {field}");
            let node = h.get_by_label(&label);
            let text = node.value().unwrap_or_default();
            let width = ctx.fonts_mut(|f| {
                f.layout_no_wrap(text.clone(), font.clone(), egui::Color32::WHITE)
                    .size()
                    .x
            });
            let rect = node.rect();
            // The text plus the field's inner margins.
            assert!(
                rect.width() >= width + 8.0,
                "q{j} {field} = {text:?}: {:.1} pt wide for {width:.1} pt of text",
                rect.width()
            );
            checked += 1;
        }
    }
    assert_eq!(checked, 30);
    let left = h.state().rects.left.expect("the left panel is open");
    assert!(
        left.max.x <= panel + 0.5,
        "the left panel ends at {} past the 3D view's start {panel}",
        left.max.x
    );
}

/// The live window renders its first 3D frame before the panels are laid out, so the arm is
/// framed for a guessed viewport; once the real size is known (and the camera untouched) it is
/// framed again and fits. A camera the user moved is kept when the size changes.
#[test]
fn the_arm_is_framed_for_the_viewport_it_is_shown_in() {
    let mut app = AppUi::new(AppState::from_spec("anthropomorphic_spherical_wrist").unwrap());
    app.tabs.view3d.frame_if_needed(&app.state); // as the first live frame does, at the initial guess
    let guessed = app.tabs.view3d.camera;
    let mut h = harness(app);
    let app = h.state_mut();
    let [w, hp] = app.tabs.view3d.viewport_px;
    assert!(w < hp, "the view is taller than wide at 1280x800: {w}x{hp}");
    app.tabs.view3d.frame_if_needed(&app.state);
    assert_ne!(
        app.tabs.view3d.camera, guessed,
        "framed again for the real size"
    );
    let pts = armlab::scene::arm_points(app.state.robot(), app.state.q()).unwrap();
    for p in &pts {
        let [x, y] = app
            .tabs
            .view3d
            .camera
            .project(p, w, hp)
            .expect("in front of the camera");
        assert!(
            (0.0..w as f32).contains(&x) && (0.0..hp as f32).contains(&y),
            "{p:?} at ({x}, {y}) outside the {w}x{hp} view"
        );
    }
    // Moved by the user: a new size does not reframe.
    app.tabs.view3d.camera.orbit(0.3, 0.1);
    let moved = app.tabs.view3d.camera;
    app.tabs.view3d.viewport_px = [w + 100, hp];
    app.tabs.view3d.frame_if_needed(&app.state);
    assert_eq!(app.tabs.view3d.camera, moved);
}

/// The status bar and the IK panel say the same thing about an unreachable target, however far
/// it is dragged (they once showed "387.3 mm outside" and "10.4 mm outside" at the same time: the
/// status kept the first message of the drag).
#[test]
fn the_status_bar_and_the_ik_panel_never_disagree() {
    let state = AppState::from_spec("anthropomorphic_spherical_wrist").unwrap();
    let mut t = state.robot().fk(state.q()).unwrap();
    let reach = state.robot().characteristic_length();
    let mut h = harness(AppUi::new(state));
    for step in [1.02, 1.1, 1.3, 1.6] {
        t.translation.vector = nalgebra::Vector3::new(reach * step, 0.0, 0.4);
        let _ = h.state_mut().state.set_target(0, t);
        h.run();
        let app = h.state();
        let panel = app.state.targets()[0].reach.message().expect("unreachable");
        assert!(panel.contains("mm outside"), "{panel}");
        let status = app.state.status_line(0).unwrap().text;
        assert!(
            status.contains(&panel),
            "status {status:?} vs panel {panel:?}"
        );
        // On screen: every text that names a distance names the same one.
        let mm: Vec<String> = h
            .root()
            .children_recursive()
            .flat_map(|n| {
                let a = n.accesskit_node();
                [a.label(), a.value()]
            })
            .flatten()
            .filter(|t| t.contains("mm outside"))
            .collect();
        assert!(mm.len() >= 2, "{mm:?}");
        let number = |s: &str| {
            s.split(" mm outside")
                .next()
                .unwrap()
                .rsplit(' ')
                .next()
                .unwrap()
                .to_string()
        };
        assert!(mm.iter().all(|s| number(s) == number(&panel)), "{mm:?}");
    }
}

/// A 2D figure whose bounds have no extent (a workspace shrunk to a point when every length is
/// edited to zero) or are not finite is drawn, not a panic in egui_plot (found by the long soak
/// run, tests/soak/app_soak.rs, in the Workspace tab).
#[test]
fn a_plot_without_extent_is_drawn() {
    use armlab::figure::plot2d::{Plot2d, drawable_bounds, show};
    for bounds in [
        [1.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 0.0, 0.0],
        [f64::NAN, 1.0, 0.0, 1.0],
        [2.0, -2.0, 1e300, f64::INFINITY],
    ] {
        let [x0, x1, y0, y1] = drawable_bounds(bounds);
        assert!(x1 - x0 >= 1e-3 && y1 - y0 >= 1e-3, "{bounds:?}");
        for equal_aspect in [false, true] {
            let plot = Plot2d {
                bounds,
                equal_aspect,
                ..Default::default()
            };
            let mut h = Harness::new_ui(|ui| {
                show(ui, &plot, None);
            });
            h.run();
        }
    }
}

/// A press on a popup over the 3D view (a menu, a combo box's list, a window) belongs to the
/// popup: the gizmo under it does not start dragging (clicks once fell through). Without the
/// popup, the same press and drag moves the target.
#[test]
fn presses_on_a_popup_do_not_reach_the_gizmo_under_it() {
    for with_popup in [false, true] {
        let app = AppUi::new(AppState::from_spec("anthropomorphic_spherical_wrist").unwrap());
        let grip = std::rc::Rc::new(std::cell::Cell::new(None::<egui::Pos2>));
        let g = grip.clone();
        let mut h = Harness::builder()
            .with_size(egui::vec2(1280.0, 800.0))
            .build_ui_state(
                move |ui, app: &mut AppUi| {
                    app.show(ui, None);
                    if let (true, Some(p)) = (with_popup, g.get()) {
                        egui::Area::new(egui::Id::unique("popup over the view"))
                            .order(egui::Order::Foreground)
                            .fixed_pos(p - egui::vec2(60.0, 40.0))
                            .show(ui.ctx(), |ui| {
                                ui.set_min_size(egui::vec2(120.0, 80.0));
                                let _ = ui.button("a menu entry");
                            });
                    }
                },
                app,
            );
        h.run();
        let p = h.state().gizmo_grip().expect("the gizmo is shown");
        grip.set(Some(p));
        h.run();
        let before = h.state().state.target(0).unwrap().world_from_tool;
        h.drag_at(p);
        h.step();
        for k in 1..=5 {
            h.hover_at(p + egui::vec2(8.0 * k as f32, 5.0 * k as f32));
            h.step();
        }
        h.drop_at(p + egui::vec2(40.0, 25.0));
        h.run();
        let after = h.state().state.target(0).unwrap().world_from_tool;
        let moved = (after.translation.vector - before.translation.vector).norm()
            + (after.rotation.angle_to(&before.rotation));
        if with_popup {
            assert!(
                moved < 1e-12,
                "the press on the popup moved the target by {moved}"
            );
        } else {
            assert!(
                moved > 1e-4,
                "the drag on the gizmo did not move the target"
            );
        }
    }
}

/// The figure computed by W (1200x900 px) stays on screen when the Workspace tab opens and
/// recomputes it at the tab's size: the tab was blank for that time (a minute in a browser).
#[test]
fn the_workspace_tab_shows_the_finished_figure_while_it_resizes_it() {
    let mut app = AppUi::new(AppState::from_spec("planar2").unwrap());
    app.tabs.workspace.start(&app.state);
    app.tabs.workspace.job.as_ref().unwrap().wait();
    assert!(app.tabs.workspace.job.as_ref().unwrap().figure().is_some());
    app.tab = armlab::app::tabs::WORKSPACE;
    let mut h = harness(app);
    h.step();
    let tab = &h.state().tabs.workspace;
    assert!(
        tab.job.as_ref().unwrap().progress().is_some(),
        "the tab recomputes at its own size"
    );
    assert!(
        tab.showing_figure(),
        "the finished figure stays on screen meanwhile"
    );
    h.state().tabs.workspace.job.as_ref().unwrap().wait();
    h.step();
    h.step();
    let tab = &h.state().tabs.workspace;
    assert!(tab.showing_figure());
    let f = tab.job.as_ref().unwrap().figure().unwrap();
    assert_ne!([f.width(), f.height()], [1200, 900], "the tab's own size");
}

/// The Symbols section shows the kinematics in the textbook's notation, steps through the
/// product, and highlights the partial product's frame in the 3D view.
#[test]
fn the_symbols_section_steps_through_the_product() {
    // a tall window: at 1280x800 the section is below the fold of the right panel
    let app = AppUi::new(AppState::from_spec("anthropomorphic_spherical_wrist").unwrap());
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 2400.0))
        .build_ui_state(|ui, app: &mut AppUi| app.show(ui, None), app);
    h.run();
    h.get_by_label("Show the kinematics in symbols").click();
    h.run();
    assert!(h.state().ik.symbols.shown);
    // the wrist point of (2.95), in a layout whose subscripts are smaller (text without '_')
    assert!(h.query_by_label("pWx = c1(a2c2 + d4s23)").is_some());
    for _ in 0..5 {
        h.get_by_label("Next >").click();
        h.run();
    }
    assert_eq!(h.state().ik.symbols.step, 5);
    assert!(h.query_by_label("step 6 of 6").is_some());
    let mut scene = armlab::scene::Scene::default();
    let state = AppState::from_spec("anthropomorphic_spherical_wrist").unwrap();
    h.state_mut().ik.symbols.decorate(&state, 0, &mut scene);
    assert!(scene.labels.iter().any(|l| l.text == "frame 6"));
}

/// Types `table` (a, alpha, d per row) into the open sheet's grid, with z1 chosen the other
/// way round (alpha1 = -90 deg): a right answer written with other frames.
fn type_table_z1_flipped(
    app: &mut AppUi,
    table: &[(
        armlab::kinematics::JointKind,
        armlab::kinematics::DhRow,
        f64,
    )],
) {
    let open = app.tabs.exercise.sheet.as_mut().unwrap();
    for (row, (_, r, _)) in open.rows.iter_mut().zip(table) {
        row.a = r.a.to_string();
        row.alpha_deg = r.alpha.to_degrees().to_string();
        row.d = r.d.to_string();
    }
    open.rows[0].alpha_deg = "-90".into();
}

/// The Exercise tab: a sheet's key opens its arm with the DH table and frames hidden, the
/// answer typed in the grid is graded by equivalence, with feedback per row.
#[test]
fn the_exercise_tab_grades_a_typed_dh_table() {
    use armlab::exercise::{Kind, generate};
    let puma = armlab::kinematics::models::built_in("puma560").unwrap();
    let sheet = generate(Kind::DhTable, Some(&puma), 5, 1).unwrap();
    let key = serde_json::to_string(&sheet.key).unwrap();
    let mut app = AppUi::new(AppState::from_spec("planar3").unwrap());
    app.open_exercise_text("key.json", &key).unwrap();
    assert!(app.state.hidden.dh_table && !app.state.display.frames);
    assert_eq!(app.tab, armlab::app::tabs::EXERCISE);
    // the answer: the Puma's table with z1 chosen the other way (alpha1 = -90 deg)
    let (_, table) = puma.dh_table().unwrap();
    type_table_z1_flipped(&mut app, &table);
    let app = {
        let mut h = Harness::builder()
            .with_size(egui::vec2(1280.0, 1600.0))
            .build_ui_state(|ui, app: &mut AppUi| app.show(ui, None), app);
        h.run();
        h.get_by_label("Check").click();
        h.run();
        assert!(h.query_by_label("score 6 of 6").is_some());
        // a real slip: d4 the other way
        let open = h.state_mut().tabs.exercise.sheet.as_mut().unwrap();
        open.rows[3].d = format!("-{}", table[3].1.d);
        h.run();
        h.get_by_label("Check").click();
        h.run();
        assert!(h.query_by_label("score 5 of 6").is_some());
        h.get_by_label("Close sheet").click();
        h.run();
        h.into_state()
    };
    assert!(!app.state.hidden.dh_table && app.tabs.exercise.sheet.is_none());
}

#[test]
fn the_record_button_starts_and_stops_a_recording() {
    let mut h = harness(AppUi::new(AppState::from_spec("planar3").unwrap()));
    h.get_by_label("Record").click();
    h.run();
    assert!(h.state().recorder.is_some());
    assert!(h.query_by_label("Stop (0)").is_some());
}

/// The workspace overlay remembered as on from the last session (or set by a lesson) computes
/// the workspace at once: it showed nothing, and W then turned it off (found by the web test,
/// whose second page remembered the first one's overlay).
#[test]
fn a_remembered_workspace_overlay_computes_the_workspace() {
    let mut app = AppUi::new(AppState::from_spec("planar2").unwrap());
    app.state.display.workspace = true;
    let h = harness(app);
    assert!(
        h.state().tabs.workspace.job.is_some(),
        "the overlay is on but no workspace is computed"
    );
}

/// Types `text` as a keyboard does: per character, its key down, its text, its key up, a frame
/// each (a shortcut reads the key; a text field takes the text).
fn type_like_a_keyboard(h: &mut Harness<'static, AppUi>, text: &str) {
    for c in text.chars() {
        let key = match c {
            ' ' => Some(egui::Key::Space),
            _ => egui::Key::from_name(&c.to_ascii_uppercase().to_string()),
        };
        if let Some(k) = key {
            h.key_down(k);
        }
        h.event(egui::Event::Text(c.to_string()));
        if let Some(k) = key {
            h.key_up(k);
        }
        h.run();
    }
}

/// What a stray shortcut would change: the display toggles, the layout (projector, side
/// panels), the camera (presets, projection), the help window, the joints (Space: next posture).
fn settings(app: &AppUi) -> String {
    format!(
        "{:?} {:?} {:?} {} {:?}",
        app.state.display,
        app.layout,
        app.tabs.view3d.camera,
        app.show_help,
        app.state.q()
    )
}

/// What a lesson step records of the app's view: its camera, the 3D view's tab.
fn seen_in(app: &AppUi) -> armlab::app::lesson::Seen {
    armlab::app::lesson::Seen {
        camera: app.tabs.view3d.camera,
        tab: 0,
        figure: "this-model".into(),
        construction: None,
        orientation: None,
    }
}

/// Issue 46, item 1: the caption editor took one character, then vanished, and every key after
/// it fired a shortcut (posture lock, ortho, workspace, projector, Space's next posture).
#[test]
fn a_lesson_caption_takes_a_whole_sentence_and_no_key_fires_a_shortcut() {
    use armlab::app::lesson::{LessonPlayer, current_step};
    const SENTENCE: &str = "Elbow down: theta1 = alpha - beta, with q2 and q3 (Fig. 2.23)";
    let mut app = AppUi::new(AppState::from_spec("puma560").unwrap());
    let mut player = LessonPlayer::on(&app.state);
    for _ in 0..2 {
        player.append(current_step(&app.state, 0, &seen_in(&app), ""));
    }
    player.step = 0;
    app.lesson = Some(player);
    let mut h = harness(app);
    let before = settings(h.state());
    h.get_by_role(egui::accesskit::Role::MultilineTextInput)
        .click();
    h.run();
    type_like_a_keyboard(&mut h, SENTENCE);
    let caption = |h: &Harness<'static, AppUi>, i: usize| {
        h.state().lesson.as_ref().unwrap().lesson.steps[i]
            .caption
            .clone()
    };
    assert_eq!(caption(&h, 0), SENTENCE);
    assert_eq!(
        settings(h.state()),
        before,
        "a key typed into the caption fired a shortcut"
    );
    // Done shows the caption large, with a button to edit it again.
    h.get_by_label("Done").click();
    h.run();
    assert!(h.query_by_label(SENTENCE).is_some());
    h.get_by_label("Edit caption").click();
    h.run();
    h.get_by_role(egui::accesskit::Role::MultilineTextInput)
        .click();
    h.run();
    h.key_press(egui::Key::End);
    h.run();
    type_like_a_keyboard(&mut h, " again");
    assert_eq!(caption(&h, 0), format!("{SENTENCE} again"));
    assert_eq!(settings(h.state()), before);
    // Outside the field, the keys are shortcuts again (Escape leaves it).
    h.key_press(egui::Key::Escape);
    h.run();
    h.key_press(egui::Key::G);
    h.run();
    assert_ne!(
        settings(h.state()),
        before,
        "G toggles the grid outside a text field"
    );
    // The steps reorder and delete.
    h.get_by_label("Move step later").click();
    h.run();
    let player = h.state().lesson.as_ref().unwrap();
    assert_eq!(player.step, 1);
    assert_eq!(player.lesson.steps[1].caption, format!("{SENTENCE} again"));
    assert!(player.lesson.steps[0].caption.is_empty());
    h.get_by_label("Delete step").click();
    h.run();
    let player = h.state().lesson.as_ref().unwrap();
    assert_eq!(player.lesson.steps.len(), 1);
    assert!(player.lesson.steps[0].caption.is_empty());
}

/// A caption is Markdown (the lesson format says so), and the lesson bar shows it rendered: the
/// strong words and the equation's code span as text of their own, none of the markup.
#[test]
fn a_lesson_caption_shows_its_markdown_rendered() {
    use armlab::app::lesson::{LessonPlayer, current_step};
    const CAPTION: &str = "**Elbow down**: theta3 from `(2.101)`, then theta2.";
    let mut app = AppUi::new(AppState::from_spec("puma560").unwrap());
    let mut player = LessonPlayer::on(&app.state);
    player.append(current_step(&app.state, 0, &seen_in(&app), CAPTION));
    player.step = 0;
    player.editing = None;
    app.lesson = Some(player);
    let h = harness(app);
    for shown in ["Elbow down", "(2.101)"] {
        assert!(
            h.query_all_by_label(shown).next().is_some(),
            "{shown:?} is not a text of its own"
        );
    }
    for markup in ["**", "`"] {
        assert!(
            h.query_all_by_label_contains(markup).next().is_none(),
            "{markup:?} shown as text"
        );
    }
    assert!(h.query_by_label("Edit caption").is_some());
}

/// Issue 46, item 10: a long status message wraps inside the 1280 px window instead of being
/// cut at its edge, and its whole text is one label (readable in full, also on hover).
#[test]
fn a_long_status_message_wraps_inside_the_window() {
    use armlab::app::state::Level;
    let long = "the model file robots/very_long_folder_name/another_folder/arm.urdf: joint \
                \"shoulder_pan_joint\": the limit's lower bound is above its upper bound, so the \
                joint was given its whole turn instead, and the workspace and every figure \
                drawn from it use that turn; fix the file and open it again to use its own limits";
    let mut app = AppUi::new(AppState::from_spec("puma560").unwrap());
    app.state.push_message(Level::Warning, long.to_string());
    let h = harness(app);
    let label = h.get_by_label(long);
    let rect = label.accesskit_node().bounding_box().unwrap();
    assert!(
        rect.x1 <= 1280.0,
        "the message runs off the window: {rect:?}"
    );
    assert!(
        rect.y1 - rect.y0 > 20.0,
        "one line of {} px: not wrapped",
        rect.x1 - rect.x0
    );
}

/// Issue 46, item 2 (exam mode): the student's sheet file opens the arm and the question with
/// no key; Save, Save as, Save as lesson, the Symbols and the screenshot do nothing; the grid's
/// answer is saved beside the sheet as `student-01.toml`, and the teacher's class grading gives
/// it full marks from the key the student never had.
#[test]
fn an_exam_sheet_opens_without_its_key_and_nothing_can_be_copied_out() {
    use armlab::exercise::{Kind, SheetFile, generate};
    let dir = std::env::temp_dir().join(format!("armlab-exam-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let puma = armlab::kinematics::models::built_in("puma560").unwrap();
    let sheet = generate(Kind::DhTable, Some(&puma), 5, 1).unwrap();
    let student = dir.join("student-01");
    std::fs::create_dir_all(&student).unwrap();
    let sheet_path = student.join("sheet.json");
    let file = serde_json::to_string(&SheetFile::of(&sheet).unwrap()).unwrap();
    std::fs::write(&sheet_path, &file).unwrap();
    // the sheet holds no key (the arm's form is checked in the compute tests)
    for word in [
        "armlab exercise key",
        "\"answer\"",
        "\"model\"",
        "tolerance",
    ] {
        assert!(!file.contains(word), "the sheet file holds {word:?}");
    }
    let mut app = AppUi::new(AppState::from_spec("planar3").unwrap());
    app.load(sheet_path.to_str().unwrap());
    assert!(app.state.hidden.exam && app.state.hidden.dh_table);
    assert_eq!(app.state.robot().dof(), 6);
    let opened = app.tabs.exercise.sheet.as_ref().unwrap();
    assert!(opened.key.is_none());
    assert_eq!(
        std::path::Path::new(&opened.answer_path),
        student.join("student-01.toml")
    );
    // the arm drawn is the key's arm at the sheet's q (independently: the key's own model)
    let tool = app.state.robot().fk(app.state.q()).unwrap();
    let want = sheet.robot.as_ref().unwrap().fk(&sheet.q).unwrap();
    assert!((tool.to_homogeneous() - want.to_homogeneous()).amax() < 1e-12);
    // the student types the Puma's table (z1 the other way round)
    let (_, table) = puma.dh_table().unwrap();
    type_table_z1_flipped(&mut app, &table);
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 1600.0))
        .build_ui_state(|ui, app: &mut AppUi| app.show(ui, None), app);
    h.run();
    assert!(
        h.query_by_label("Check").is_none(),
        "an exam grades nothing"
    );
    assert!(
        h.query_by_label("Off while the exercise is answered")
            .is_some()
    );
    for button in ["Screenshot", "Save model as...", "Save as lesson", "Save"] {
        h.get_by_label(button).click();
        h.run();
    }
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::S);
    h.run();
    assert!(!h.state().screenshot_requested);
    let written: Vec<_> = std::fs::read_dir(&student).unwrap().collect();
    assert_eq!(
        written.len(),
        1,
        "only the sheet is in the student's folder"
    );
    h.get_by_label("Save answer").click();
    h.run();
    assert!(student.join("student-01.toml").is_file());
    // the teacher grades the folder with the key
    let keys = dir.join("keys");
    let answers = dir.join("answers");
    std::fs::create_dir_all(&keys).unwrap();
    std::fs::create_dir_all(&answers).unwrap();
    std::fs::write(
        keys.join("student-01.json"),
        serde_json::to_string(&sheet.key).unwrap(),
    )
    .unwrap();
    std::fs::copy(
        student.join("student-01.toml"),
        answers.join("student-01.toml"),
    )
    .unwrap();
    let key = serde_json::from_str(&std::fs::read_to_string(keys.join("student-01.json")).unwrap())
        .unwrap();
    let answer =
        armlab::model_file::load_model(answers.join("student-01.toml").to_str().unwrap()).unwrap();
    let g =
        armlab::exercise::grade(&key, &armlab::exercise::Answer::Model(Box::new(answer))).unwrap();
    assert_eq!((g.score, g.max), (6, 6), "{:?}", g.items);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A sheet's question is Markdown, and the student reads it rendered: the table of joint axes as
/// a table (each header and each direction a cell of its own), the heading as a heading; none of
/// the markup (`| joint |`, `|---|`, `# `) is shown. It was shown raw, in class and out.
#[test]
fn an_exercise_sheets_question_shows_its_table_as_a_table() {
    use armlab::exercise::{Kind, SheetFile, generate};
    let dir = std::env::temp_dir().join(format!("armlab-sheet-md-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let puma = armlab::kinematics::models::built_in("puma560").unwrap();
    let sheet = generate(Kind::DhTable, Some(&puma), 5, 1).unwrap();
    let sheet_path = dir.join("sheet.json");
    let file = SheetFile::of(&sheet).unwrap();
    assert!(
        file.question.contains("|---|"),
        "the question is a Markdown table"
    );
    std::fs::write(&sheet_path, serde_json::to_string(&file).unwrap()).unwrap();
    let mut app = AppUi::new(AppState::from_spec("planar3").unwrap());
    app.load(sheet_path.to_str().unwrap());
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 1600.0))
        .build_ui_state(|ui, app: &mut AppUi| app.show(ui, None), app);
    h.run();
    for cell in ["joint", "type", "a point on the axis", "direction"] {
        assert!(
            h.query_all_by_label(cell).next().is_some(),
            "no header cell {cell:?}"
        );
    }
    assert!(h.query_by_label("The DH table of an arm").is_some());
    // every cell of the table's rows (split here at the bars) is a label of its own
    let rows: Vec<&str> = file
        .question
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| joint"))
        .collect();
    assert_eq!(rows.len(), 6, "six joints' rows");
    for row in rows {
        for cell in row.trim_matches('|').split('|').map(str::trim) {
            assert!(
                h.query_all_by_label(cell).next().is_some(),
                "no cell {cell:?} of {row}"
            );
        }
    }
    for markup in ["|---", "| joint", "# The DH"] {
        assert!(
            h.query_all_by_label_contains(markup).next().is_none(),
            "{markup:?} shown as text"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 46, item 10: the derived DH table follows the chosen end-effector (it showed Baxter's
/// right arm after the left was picked).
#[test]
fn the_derived_dh_table_follows_the_chosen_end_effector() {
    let mut app = AppUi::new(AppState::from_spec("tests/data/urdf_corpus/baxter.urdf").unwrap());
    let ees = app.state.robot().end_effectors();
    let left = ees.iter().position(|e| e.name == "left_gripper").unwrap();
    let right = ees.iter().position(|e| e.name == "right_gripper").unwrap();
    for (ee, side, other) in [(left, "left", "right"), (right, "right", "left")] {
        app.apply(armlab::app::action::Action::SelectEe(ee));
        let h = harness(app);
        let shown = h
            .query_by_label_contains("The arm of")
            .expect("the arm's line")
            .accesskit_node()
            .value()
            .unwrap_or_default();
        assert!(shown.contains(&format!("{side}_")), "{side}: {shown}");
        assert!(!shown.contains(&format!("{other}_")), "{side}: {shown}");
        app = h.into_state();
    }
}

/// Issue 46, item 5: "Save as lesson" writes what the class saw, and the lesson sets it again:
/// the camera's look-at point and distance, the open tab, the Workspace tab's figure, the
/// construction's step, and every overlay on or off (an app that remembered the workspace
/// overlay from another session does not show it on step 1).
#[test]
fn a_lesson_saves_and_replays_the_tab_the_figure_the_construction_and_the_camera() {
    use armlab::app::lesson::LessonPlayer;
    use armlab::app::tabs::{VIEW3D, WORKSPACE};
    let dir = std::env::temp_dir().join(format!("armlab-lesson-seen-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("seen.toml");
    let mut live = AppUi::new(AppState::from_spec("planar2_fig2_30").unwrap());
    live.tabs
        .workspace
        .choose_figure("2.30", &live.state)
        .unwrap();
    live.tab = WORKSPACE;
    live.ik.construction.shown = true;
    live.ik.construction.step = 1;
    live.state.display.frames = false;
    // the grid off and the trail on (found live: G before Save as lesson came back on replay)
    live.state.display.grid = false;
    live.state.display.trail = true;
    let mut cam = live.tabs.view3d.camera;
    cam.target = nalgebra::Point3::new(0.2, -0.1, 0.05);
    cam.distance = 2.5;
    live.tabs.view3d.set_camera(cam);
    let mut player = LessonPlayer::on(&live.state);
    player.file = file.to_string_lossy().into_owned();
    live.lesson = Some(player);
    live.save_as_lesson().unwrap();
    let text = std::fs::read_to_string(&file).unwrap();
    for line in [
        "tab = \"workspace\"",
        "figure = \"2.30\"",
        "construction_step = 2",
        "overlays_off = [",
    ] {
        assert!(text.contains(line), "{line} not in:\n{text}");
    }
    // another app, on another model, with the workspace overlay remembered and the 3D view
    let mut replay = AppUi::new(AppState::from_spec("puma560").unwrap());
    replay.state.display.workspace = true;
    replay.state.display.frames = true;
    replay.state.display.grid = true;
    replay.state.display.trail = false;
    assert_eq!(replay.tab, VIEW3D);
    replay.load(file.to_str().unwrap());
    assert_eq!(replay.state.spec(), "planar2_fig2_30");
    assert_eq!(replay.tab, WORKSPACE);
    assert_eq!(replay.tabs.workspace.figure_name(), "2.30");
    assert!(replay.ik.construction.shown && replay.ik.construction.step == 1);
    assert!(!replay.state.display.workspace && !replay.state.display.frames);
    assert_eq!(replay.state.display, live.state.display);
    let got = replay.tabs.view3d.camera;
    assert!((got.target - cam.target).norm() < 1e-6, "{got:?}");
    assert!((got.distance - cam.distance).abs() < 1e-6);
    assert!((got.yaw - cam.yaw).abs() < 1e-6 && (got.pitch - cam.pitch).abs() < 1e-6);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 46, item 9: a warning that appears while a pointer button is down (a drag) moves
/// nothing under the pointer: its space is frozen until the release, then fits the warning.
/// The Puma's wrist singularity (q5 = 0) brings the Jacobian's warning above the inverse
/// kinematics section; the section stays where it was until the button is released.
#[test]
fn a_warning_during_a_drag_moves_nothing_under_the_pointer() {
    let mut state = AppState::from_spec("puma560").unwrap();
    state.set_q(&[0.2, -0.5, 0.4, 0.3, 0.6, 0.1]).unwrap();
    let mut h = harness(AppUi::new(state));
    let y_of = |h: &Harness<'static, AppUi>, label: &str| {
        let b = h
            .get_by_label(label)
            .accesskit_node()
            .bounding_box()
            .unwrap();
        b.y0
    };
    let before = y_of(&h, "Inverse kinematics");
    let pose = h
        .get_by_label("Pose")
        .accesskit_node()
        .bounding_box()
        .unwrap();
    let at = egui::pos2(pose.x0 as f32 + 2.0, pose.y0 as f32 + 2.0);
    h.event(egui::Event::PointerMoved(at));
    h.event(egui::Event::PointerButton {
        pos: at,
        button: egui::PointerButton::Primary,
        pressed: true,
        modifiers: egui::Modifiers::NONE,
    });
    h.run();
    h.state_mut()
        .state
        .set_q(&[0.2, -0.5, 0.4, 0.3, 0.0, 0.1])
        .unwrap();
    h.run();
    assert!(
        (y_of(&h, "Inverse kinematics") - before).abs() < 0.5,
        "the IK heading moved from {before} to {} during the drag",
        y_of(&h, "Inverse kinematics")
    );
    h.event(egui::Event::PointerButton {
        pos: at,
        button: egui::PointerButton::Primary,
        pressed: false,
        modifiers: egui::Modifiers::NONE,
    });
    h.run();
    h.run();
    assert!(
        y_of(&h, "Inverse kinematics") > before + 10.0,
        "after the release the warning has its room"
    );
}
