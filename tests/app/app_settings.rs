//! What the app remembers across runs (issue 16): the last model, the view toggles, projector
//! mode and the angle unit, written and read back as eframe's storage does; an unreadable
//! value or settings file is ignored with a message. And the file dialogs' paths (a scripted
//! dialog stands in for the desktop's).

use armlab::app::AppUi;
use armlab::app::file_picker::{FileKind, FilePicker};
use armlab::app::settings::{Settings, restore};
use armlab::app::state::{AngleUnit, AppState, Level};
use std::path::PathBuf;

fn app(spec: &str) -> AppUi {
    AppUi::new(AppState::from_spec(spec).unwrap())
}

fn last_message(app: &AppUi) -> (Level, String) {
    let m = app.state.messages().back().expect("a message");
    (m.level, m.text.clone())
}

#[test]
fn settings_survive_a_restart() {
    let mut a = app("puma560");
    a.state.display.grid = false;
    a.state.display.workspace = true;
    a.layout.projector = true;
    a.state.set_angle_unit(AngleUnit::Radians);
    let text = Settings::capture(&a).to_text();
    // A new run on the default model restores all of it.
    let mut b = app("planar2");
    restore(&mut b, Some(text.clone()), None, false);
    assert_eq!(b.state.spec(), "puma560");
    assert_eq!(b.state.display, a.state.display);
    assert!(b.layout.projector);
    assert_eq!(b.state.angle_unit(), AngleUnit::Radians);
    // A model named on the command line wins; the rest still applies.
    let mut c = app("planar3");
    restore(&mut c, Some(text), None, true);
    assert_eq!(c.state.spec(), "planar3");
    assert!(c.layout.projector && !c.state.display.grid);
}

#[test]
fn a_model_file_is_remembered_by_its_absolute_path() {
    let dir = std::env::temp_dir().join(format!("armlab-settings-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("arm.toml");
    std::fs::copy(
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/assets/robots/example_2_6.toml"
        ),
        &file,
    )
    .unwrap();
    let a = app(file.to_str().unwrap());
    let s = Settings::capture(&a);
    let remembered = PathBuf::from(s.model.clone().unwrap());
    assert!(remembered.is_absolute(), "{remembered:?}");
    assert_eq!(remembered, std::fs::canonicalize(&file).unwrap());
    // The file is gone at the next start: the default model stays, and the status says why.
    std::fs::remove_dir_all(&dir).unwrap();
    let mut b = app("planar2");
    restore(&mut b, Some(s.to_text()), None, false);
    assert_eq!(b.state.spec(), "planar2");
    let (level, text) = last_message(&b);
    assert_eq!(level, Level::Error);
    assert!(text.contains("arm.toml"), "{text}");
}

#[test]
fn unreadable_settings_are_ignored_with_a_message() {
    for bad in ["{", "[1, 2]", "{\"projector\": \"yes\"}", "\u{0}\u{1}", ""] {
        let mut a = app("planar2");
        let before = a.state.display;
        restore(&mut a, Some(bad.to_string()), None, false);
        assert_eq!(a.state.spec(), "planar2");
        assert_eq!(a.state.display, before);
        assert!(!a.layout.projector);
        let (level, text) = last_message(&a);
        assert_eq!(level, Level::Warning);
        assert!(text.contains("unreadable settings"), "{text}");
    }
    // Fields missing or unknown (an older or newer armlab) are fine.
    let mut a = app("planar2");
    restore(
        &mut a,
        Some("{\"projector\": true, \"colour\": 3}".into()),
        None,
        false,
    );
    assert!(a.layout.projector && a.state.display.grid);
    assert!(a.state.messages().is_empty());
    // eframe's settings file exists but gave nothing back (it could not be parsed).
    let dir = std::env::temp_dir().join(format!("armlab-ron-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let ron = dir.join("app.ron");
    std::fs::write(&ron, "(((( not ron").unwrap();
    let mut a = app("planar2");
    restore(&mut a, None, Some(&ron), false);
    let (level, text) = last_message(&a);
    assert_eq!(level, Level::Warning);
    assert!(
        text.contains("app.ron") && text.contains("defaults"),
        "{text}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Answers each dialog with the next path of a list.
struct Scripted(Vec<PathBuf>, Vec<FileKind>);

impl FilePicker for Scripted {
    fn available(&self) -> bool {
        true
    }
    fn open(&mut self, kind: FileKind) -> Option<PathBuf> {
        self.1.push(kind);
        self.0.pop()
    }
    fn save(&mut self, kind: FileKind, suggested: &str) -> Option<PathBuf> {
        assert!(suggested.ends_with(".toml"), "{suggested}");
        self.1.push(kind);
        self.0.pop()
    }
}

#[test]
fn the_file_dialogs_open_and_save_models() {
    let dir = std::env::temp_dir().join(format!("armlab-dialogs-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut a = app("puma560");
    // Save as "edited" (no extension: .toml), then open what was saved.
    a.file_picker = Box::new(Scripted(vec![dir.join("edited")], vec![]));
    a.save_with_dialog();
    let saved = dir.join("edited.toml");
    assert!(saved.is_file(), "{:?}", a.state.messages());
    assert_eq!(a.model.save_path, saved.to_string_lossy());
    let mut b = app("planar2");
    b.file_picker = Box::new(Scripted(vec![saved.clone()], vec![]));
    b.open_with_dialog();
    assert_eq!(b.state.spec(), saved.to_string_lossy());
    assert_eq!(b.state.robot().dof(), 6);
    // Cancelling changes nothing (a dialog that answers at once was never shown: the in-app
    // file browser is offered instead, as where no desktop portal answers).
    b.file_picker = Box::new(Scripted(vec![], vec![]));
    b.open_with_dialog();
    assert_eq!(b.state.spec(), saved.to_string_lossy());
    // Without a dialog (no desktop portal) the in-app file browser opens.
    let mut c = app("planar2");
    c.open_with_dialog();
    assert!(c.browser.open, "the in-app file browser opens");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Files the browser's way (the web build's picker): opening hands over a name and bytes later,
/// saving is a download. Shared state so the test can feed and read it.
#[derive(Default, Clone)]
struct Browser {
    files: Shared<(FileKind, String, Vec<u8>)>,
    downloads: Shared<(String, String, Vec<u8>)>,
    asked: Shared<FileKind>,
}

type Shared<T> = std::rc::Rc<std::cell::RefCell<Vec<T>>>;

impl FilePicker for Browser {
    fn available(&self) -> bool {
        true
    }
    fn open(&mut self, kind: FileKind) -> Option<PathBuf> {
        self.asked.borrow_mut().push(kind);
        None
    }
    fn save(&mut self, _kind: FileKind, _suggested: &str) -> Option<PathBuf> {
        panic!("the browser saves by downloading, never through a path")
    }
    fn poll_opened(&mut self) -> Option<(FileKind, String, Vec<u8>)> {
        let mut f = self.files.borrow_mut();
        (!f.is_empty()).then(|| f.remove(0))
    }
    fn download(&mut self, name: &str, mime: &str, bytes: &[u8]) -> bool {
        let d = (name.to_string(), mime.to_string(), bytes.to_vec());
        self.downloads.borrow_mut().push(d);
        true
    }
    fn downloads(&self) -> bool {
        true
    }
}

/// The web build opens models from a name and bytes (picked or dropped) and saves by download:
/// a Puma edited in one app, downloaded as TOML and as URDF, opens in another with the same FK
/// (computed by each robot, compared here); a bad file keeps the model with a message naming
/// the file and line; a non-text or unknown file is refused.
#[test]
fn the_browser_opens_bytes_and_saves_downloads() {
    let browser = Browser::default();
    let mut a = app("puma560");
    a.file_picker = Box::new(browser.clone());
    a.save_with_dialog();
    a.model.save_path = "puma.urdf".into();
    a.save_with_dialog();
    let downloads = browser.downloads.borrow().clone();
    assert_eq!(downloads.len(), 2, "{:?}", a.state.messages());
    assert_eq!(downloads[0].0, "puma_560.toml");
    assert_eq!(downloads[0].1, "application/toml");
    assert_eq!(
        (downloads[1].0.as_str(), downloads[1].1.as_str()),
        ("puma.urdf", "application/xml")
    );
    let q = [0.3, 0.8, -1.0, 0.4, 0.6, 0.2];
    let want = a.state.robot().fk(&q).unwrap();
    for (name, _, bytes) in &downloads {
        let mut b = app("planar2");
        b.file_picker = Box::new(browser.clone());
        b.open_with_dialog();
        assert_eq!(browser.asked.borrow().last(), Some(&FileKind::Model));
        assert_eq!(
            b.state.robot().dof(),
            2,
            "nothing opens before the file arrives"
        );
        b.opened_file(FileKind::Model, name, bytes);
        assert_eq!(b.state.spec(), name);
        let got = b.state.robot().fk(&q).unwrap();
        assert!(
            (got.to_homogeneous() - want.to_homogeneous()).abs().max() < 1e-12,
            "{name}"
        );
    }
    // A TOML file with a bad line: the model stays, the message names the file and the line.
    let mut c = app("planar2");
    let bad = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/bad_models/bad_angle_string.toml"
    ))
    .unwrap();
    c.open_bytes("bad.toml", &bad);
    assert_eq!(c.state.robot().dof(), 2);
    let (level, text) = last_message(&c);
    assert_eq!(level, Level::Error);
    assert!(
        text.contains("bad.toml:9") && text.contains("pi/two"),
        "{text}"
    );
    c.open_bytes("robot.stl", b"solid x");
    assert!(
        last_message(&c).1.contains("not a model file"),
        "{:?}",
        last_message(&c)
    );
    c.open_bytes("robot.toml", &[0xff, 0xfe, 0x00]);
    assert!(
        last_message(&c).1.contains("not a text file"),
        "{:?}",
        last_message(&c)
    );
    assert_eq!(c.state.robot().dof(), 2);
}
