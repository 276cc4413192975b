//! A soak test: the real app (its UI and state, through egui_kittest) driven with a seeded
//! random sequence of events on every built-in model: clicks and drags anywhere, clicks on
//! every kind of widget (buttons, toggles, the posture list, the tabs, workspace start and
//! cancel), keys and shortcuts, random text typed into the DH cells, the target fields and the
//! model path, scrolling. After every event: no panic, q, the end-effector poses and the IK
//! targets finite, q inside the joint limits (the state's invariant), no text on screen showing
//! NaN (readouts, DH table, status; found through the accessibility tree); every few hundred events
//! and at the end the window is rendered (lavapipe) and must show more than the background.
//!
//! The normal suite runs `ARMLAB_SOAK_EVENTS` events per model (default 300); the long run
//! (10,000 per model) is `ARMLAB_SOAK_EVENTS=10000 cargo test --release --test soak`.
//! `ARMLAB_SOAK_SEED` changes the sequence (default 1); a failure names the model, the seed
//! and the event number, so it replays.

use armlab::app::AppUi;
use armlab::app::screenshot::{ScreenshotOptions, screenshot_with};
use armlab::app::state::AppState;
use armlab::kinematics::models::BUILT_INS;
use egui::{Event, Key, Modifiers, PointerButton, Pos2, accesskit::Role, pos2, vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const WINDOW: [f32; 2] = [1280.0, 800.0];
const RENDER_EVERY: usize = 250;

/// What a user might type anywhere.
const TEXTS: &[&str] = &[
    "nan",
    "inf",
    "-inf",
    "1e400",
    "-1e308",
    "0",
    "90",
    "-90deg",
    "pi/2",
    "-3*pi/4",
    "1.5rad",
    "abc",
    "",
    "   ",
    "1,2,3",
    "ääö",
    "99999999999999999999999",
    "-0",
    "1e-320",
    "0x10",
    "puma560",
    "dlr",
    "/dev/zero",
    "/nonexistent/robot.toml",
    "panda.toml",
    "nan_parameter.toml",
    "saved.urdf",
    "\u{1F916}",
    "12.5",
    "-1000",
    "1e6",
];

/// Runs the test in a folder of its own: typed texts become file names when the Save row or
/// the calibration's save is clicked, and must not land in (or overwrite files of) the
/// repository. Copies of a model and of a bad model are there to be opened (and overwritten).
fn private_working_dir() -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("armlab-soak-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let repo = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    for (from, to) in [
        ("assets/robots/panda.toml", "panda.toml"),
        (
            "tests/data/bad_models/nan_parameter.toml",
            "nan_parameter.toml",
        ),
    ] {
        std::fs::copy(repo.join(from), dir.join(to)).unwrap();
    }
    // The only test of this binary (tests/soak): changing the process's folder affects nothing else.
    std::env::set_current_dir(&dir).unwrap();
    dir
}

const KEYS: &[Key] = &[
    Key::W,
    Key::T,
    Key::Space,
    Key::R,
    Key::P,
    Key::O,
    Key::Num1,
    Key::Num2,
    Key::Num3,
    Key::Num4,
    Key::N,
    Key::L,
    Key::H,
    Key::G,
    Key::F1,
    Key::F,
    Key::Escape,
    Key::D,
    Key::C,
    Key::B,
    Key::ArrowRight,
    Key::ArrowLeft,
    Key::ArrowUp,
    Key::ArrowDown,
    Key::Tab,
    Key::Enter,
    Key::Backspace,
    Key::Delete,
    Key::Home,
    Key::End,
    Key::A,
    Key::Z,
];

/// Widget roles clicked on purpose (random clicks alone rarely hit a small toggle).
const ROLES: &[Role] = &[
    Role::Button,
    Role::CheckBox,
    Role::ComboBox,
    Role::RadioButton,
    Role::Tab,
    Role::TextInput,
    Role::Slider,
    Role::Switch,
];

fn env_number(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn harness(spec: &str) -> Harness<'static, AppUi> {
    let app = AppUi::new(AppState::from_spec(spec).unwrap());
    let mut h = Harness::builder()
        .with_size(vec2(WINDOW[0], WINDOW[1]))
        // Typed characters no font has (an emoji) are drawn as a box, as in the window (egui's
        // default); kittest's own default is to panic.
        .allow_missing_glyphs()
        .build_ui_state(|ui, app: &mut AppUi| app.show(ui, None), app);
    h.run_steps(2);
    h
}

fn random_pos(rng: &mut ChaCha8Rng) -> Pos2 {
    pos2(
        rng.random_range(0.0..WINDOW[0]),
        rng.random_range(0.0..WINDOW[1]),
    )
}

fn modifiers(rng: &mut ChaCha8Rng) -> Modifiers {
    match rng.random_range(0..8) {
        0 => Modifiers::SHIFT,
        1 => Modifiers::CTRL,
        2 => Modifiers::ALT,
        _ => Modifiers::NONE,
    }
}

fn press(h: &Harness<'_, AppUi>, pos: Pos2, pressed: bool, modifiers: Modifiers) {
    h.event(Event::PointerButton {
        pos,
        button: PointerButton::Primary,
        pressed,
        modifiers,
    });
}

/// A click (or drag, when `to` differs) at window points, stepping frames in between.
fn pointer(h: &mut Harness<'_, AppUi>, from: Pos2, to: Pos2, m: Modifiers) {
    h.event(Event::PointerMoved(from));
    h.step();
    press(h, from, true, m);
    h.step();
    for k in 1..=4 {
        let t = k as f32 / 4.0;
        h.event(Event::PointerMoved(from + (to - from) * t));
        h.step();
    }
    press(h, to, false, m);
    h.step();
}

/// Centres of the widgets of a random role now on screen.
fn widget_centres(h: &Harness<'_, AppUi>, role: Role) -> Vec<Pos2> {
    h.query_all_by_role(role)
        .map(|n| n.rect().center())
        .filter(|p| p.x >= 0.0 && p.y >= 0.0 && p.x < WINDOW[0] && p.y < WINDOW[1])
        .collect()
}

/// One random event, described for the failure message.
fn event(h: &mut Harness<'_, AppUi>, rng: &mut ChaCha8Rng) -> String {
    match rng.random_range(0..100) {
        0..20 => {
            let p = random_pos(rng);
            pointer(h, p, p, modifiers(rng));
            format!("click at {p:?}")
        }
        20..40 => {
            let (a, b) = (random_pos(rng), random_pos(rng));
            pointer(h, a, b, modifiers(rng));
            format!("drag {a:?} -> {b:?}")
        }
        40..65 => {
            let role = ROLES[rng.random_range(0..ROLES.len())];
            let centres = widget_centres(h, role);
            if centres.is_empty() {
                return format!("no {role:?} on screen");
            }
            let p = centres[rng.random_range(0..centres.len())];
            pointer(h, p, p, Modifiers::NONE);
            format!("click a {role:?} at {p:?}")
        }
        65..80 => {
            let centres = widget_centres(h, Role::TextInput);
            if centres.is_empty() {
                return "no text field".into();
            }
            let p = centres[rng.random_range(0..centres.len())];
            pointer(h, p, p, Modifiers::NONE);
            let text = TEXTS[rng.random_range(0..TEXTS.len())];
            h.key_press_modifiers(Modifiers::COMMAND, Key::A);
            h.event(Event::Text(text.into()));
            h.step();
            h.key_press(if rng.random_bool(0.7) {
                Key::Enter
            } else {
                Key::Tab
            });
            h.step();
            format!("type {text:?} at {p:?}")
        }
        80..95 => {
            let key = KEYS[rng.random_range(0..KEYS.len())];
            let m = modifiers(rng);
            h.key_press_modifiers(m, key);
            h.step();
            format!("key {key:?} {m:?}")
        }
        _ => {
            let p = random_pos(rng);
            h.event(Event::PointerMoved(p));
            h.event(Event::MouseWheel {
                unit: egui::MouseWheelUnit::Line,
                delta: vec2(0.0, rng.random_range(-5.0..5.0)),
                modifiers: modifiers(rng),
                phase: egui::TouchPhase::Move,
                source: egui::MouseWheelSource::Wheel,
            });
            h.step();
            format!("scroll at {p:?}")
        }
    }
}

/// The state's invariants: finite q inside the limits, finite poses and targets.
fn check(app: &AppUi) -> Result<(), String> {
    let s = &app.state;
    let robot = s.robot();
    let q = s.q();
    if q.len() != robot.dof() || q.iter().any(|v| !v.is_finite()) {
        return Err(format!("q not {} finite values: {q:?}", robot.dof()));
    }
    if !robot.within_limits(q, 1e-9) {
        return Err(format!("q outside the limits: {q:?}"));
    }
    for ee in 0..robot.end_effectors().len() {
        let pose = robot.fk_ee(q, ee).map_err(|e| e.to_string())?;
        if pose.to_homogeneous().iter().any(|v| !v.is_finite()) {
            return Err(format!("end-effector {ee} pose not finite"));
        }
    }
    for t in s.targets() {
        if t.world_from_tool
            .to_homogeneous()
            .iter()
            .any(|v| !v.is_finite())
        {
            return Err("an IK target is not finite".into());
        }
    }
    if !app.tabs.view3d.camera.eye().iter().all(|v| v.is_finite()) {
        return Err("the camera is not finite".into());
    }
    Ok(())
}

/// What the user reads: no text on screen shows a NaN (the readouts, the DH table, the status).
fn check_readouts(h: &Harness<'_, AppUi>) -> Result<(), String> {
    let by = egui_kittest::kittest::By::new().label_contains("NaN");
    match h.query_all(by).next() {
        Some(node) => Err(format!("a readout shows NaN: {node:?}")),
        None => Ok(()),
    }
}

/// Renders the window offscreen: it must work and show more than one colour.
fn check_render(app: &AppUi) -> Result<(), String> {
    let img = screenshot_with(app, [640, 400], &ScreenshotOptions::default())
        .map_err(|e| format!("render failed: {e}"))?;
    let first = *img.get_pixel(0, 0);
    let other = img.pixels().filter(|p| **p != first).count();
    if other < 1000 {
        return Err(format!("the render is blank ({other} pixels differ)"));
    }
    Ok(())
}

fn soak(spec: &str, events: usize, seed: u64) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ (spec.len() as u64 * 0x9E37_79B9));
    let mut h = harness(spec);
    // The NaN check reads the labels of the accessibility tree: the readouts must be there.
    let readout = egui_kittest::kittest::By::new().label_contains("manipulability");
    assert!(
        h.query_all(readout).next().is_some(),
        "{spec}: no readout label seen"
    );
    let mut last = Vec::new();
    for n in 0..events {
        let what = event(&mut h, &mut rng);
        last.push(what);
        if last.len() > 8 {
            last.remove(0);
        }
        let mut result = check(h.state()).and_then(|()| check_readouts(&h));
        if result.is_ok() && (n + 1) % RENDER_EVERY == 0 {
            result = check_render(h.state());
        }
        if let Err(e) = result {
            panic!(
                "{spec}, seed {seed}, event {n}: {e}\nmodel now {}; last events:\n{}",
                h.state().state.spec(),
                last.join("\n")
            );
        }
    }
    if let Err(e) = check_render(h.state()) {
        panic!("{spec}, seed {seed}, after {events} events: {e}");
    }
}

#[test]
fn random_events_on_every_built_in_keep_the_app_sound() {
    let dir = private_working_dir();
    let events = env_number("ARMLAB_SOAK_EVENTS", 300) as usize;
    let seed = env_number("ARMLAB_SOAK_SEED", 1);
    let start = std::time::Instant::now();
    for b in BUILT_INS {
        let t = std::time::Instant::now();
        soak(b.name, events, seed);
        eprintln!(
            "soak: {} {events} events in {:.1} s",
            b.name,
            t.elapsed().as_secs_f64()
        );
    }
    std::fs::remove_dir_all(&dir).ok();
    eprintln!(
        "soak: {} models x {events} events in {:.1} s",
        BUILT_INS.len(),
        start.elapsed().as_secs_f64()
    );
}
