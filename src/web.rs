//! The app in a browser (wasm32, `gui` feature; built by `web/build.sh`): eframe's web runner on
//! a canvas, with the web's ways of doing what the desktop does with files and flags.
//!
//! * The model comes from the page's URL (`?model=puma560`; a built-in name, optionally with a
//!   joint vector `&q=0.3,0.8,-1,0.4,0.6,0.2` in rad or m), else the remembered one (local
//!   storage), else the default robot.
//! * Files: "Open file..." and "Browse..." show the browser's file picker, a file dropped onto the
//!   page is opened, and saving (models, calibrated models, screenshots) is a download.
//! * The live class (issue 50): `?token=T` joins the class server the page came from as the
//!   teacher, `?code=C&name=N` as a student (`?code=C` alone asks for a nickname first).
//! * [`WebHandle::status`] reports the app's state as JSON, for the page and its tests.

use crate::app::AppUi;
use crate::app::class::{ClassAction, NamePrompt, link};
use crate::app::file_picker::{FileKind, FilePicker};
use crate::app::state::{AppState, Level};
use crate::app::workspace_job::WorkspaceJob;
use crate::app::{APP_ID, ArmlabApp};
use std::cell::RefCell;
use std::path::PathBuf;
use std::rc::Rc;
use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

/// The running app on one canvas, as the page's script holds it.
#[wasm_bindgen]
pub struct WebHandle {
    runner: eframe::WebRunner,
}

impl Default for WebHandle {
    fn default() -> Self {
        Self::new()
    }
}

#[wasm_bindgen]
impl WebHandle {
    /// A handle with nothing running yet; panics are reported on the browser's console.
    #[wasm_bindgen(constructor)]
    pub fn new() -> Self {
        Self {
            runner: eframe::WebRunner::new(),
        }
    }

    /// Starts the app on `canvas` with the model named in the page's URL (`?model=NAME`), at
    /// the joint vector it gives (`&q=...`, rad or m).
    pub async fn start(&self, canvas: web_sys::HtmlCanvasElement) -> Result<(), JsValue> {
        let requested = url_parameter("model");
        let q = url_parameter("q");
        let (state, mut model_given) = initial_state(requested.as_deref(), q.as_deref());
        // ?lesson=URL: the lesson file fetched before the app starts, opened on its first step
        let lesson = match url_parameter("lesson") {
            Some(url) => Some(fetch_text(&url).await.map(|text| (url.clone(), text))),
            None => None,
        };
        model_given |= lesson.is_some();
        let options = eframe::WebOptions {
            // The window has flat colours only: nothing to dither.
            dithering: false,
            ..Default::default()
        };
        self.runner
            .start(
                canvas,
                options,
                Box::new(move |cc| {
                    let mut ui = AppUi::new(state);
                    ui.file_picker = Box::new(BrowserFiles::default());
                    match lesson {
                        Some(Ok((url, text))) => {
                            let opened = crate::lesson::Lesson::parse(&text, &url)
                                .map_err(|e| e.to_string())
                                .and_then(|l| ui.open_lesson(l, &url));
                            if let Err(e) = opened {
                                ui.state
                                    .push_message(Level::Error, format!("?lesson=: {e}"));
                            }
                        }
                        Some(Err(e)) => ui
                            .state
                            .push_message(Level::Error, format!("?lesson=: {e}")),
                        None => {}
                    }
                    ui.clock = Some(|| js_sys::Date::now() / 1000.0);
                    join_class(&mut ui);
                    for _ in 0..pool_size() {
                        match WorkerOffload::new() {
                            Ok(w) => ui.offload.push(Box::new(w)),
                            Err(e) => web_sys::console::warn_1(&e),
                        }
                    }
                    Ok(Box::new(ArmlabApp::new(cc, ui, None, true, model_given)))
                }),
            )
            .await
    }

    /// The app's state as JSON: `{"started", "model", "dof", "q" (rad, m), "position" (m),
    /// "rpy_deg", "solutions", "within_limits", "gizmo" ([x, y] in CSS pixels of a translation
    /// handle), "backend" ("BrowserWebGpu" or "Gl" for WebGL2), "workspace_progress" (0..1), "workspace_figure" ([w, h] px), "workspace_dots", "workspace_previews" (pictures of the figure as it formed), "workers" (the pool of web workers),
    /// "workspace_error", "messages", "frames", "panicked", "class" (the live class: role,
    /// connected, following, question, answered, joined, counts, correct_percent, mistakes; see
    /// [`crate::app::class::ClassClient::status`])}`.
    pub fn status(&self) -> String {
        let panicked = self.runner.has_panicked();
        let Some(app) = self.runner.app_mut::<ArmlabApp>() else {
            return serde_json::json!({ "started": false, "panicked": panicked }).to_string();
        };
        let mut v = status_json(app.app_ui());
        v["panicked"] = panicked.into();
        v["frames"] = app.frames().into();
        v["backend"] = app.graphics_backend().into();
        v.to_string()
    }

    /// The live class, for the page's tests: answers question `id` with `answer_json` (a
    /// poll's choice index, an exercise's text as a JSON string) through the same action as
    /// the question window's buttons and the Exercise tab's "Send answer". An error where the
    /// app has not started or the JSON cannot be read.
    pub fn class_answer(&self, id: u64, answer_json: &str) -> Result<(), JsValue> {
        let answer: serde_json::Value = serde_json::from_str(answer_json)
            .map_err(|e| JsValue::from_str(&format!("the answer's JSON: {e}")))?;
        self.class_action(ClassAction::Answer { id, answer })
    }

    /// The live class, for the page's tests: the teacher asks "Which posture is this?" about
    /// the current target, through the same action as the Class window's button.
    pub fn class_ask_poll(&self) -> Result<(), JsValue> {
        let mut app = self
            .runner
            .app_mut::<ArmlabApp>()
            .ok_or_else(|| JsValue::from_str("the app has not started"))?;
        let q = crate::app::class::poll_request(app.app_ui()).map_err(|e| JsValue::from_str(&e))?;
        app.apply(crate::app::action::Action::Class(ClassAction::Ask(q)));
        Ok(())
    }

    fn class_action(&self, action: ClassAction) -> Result<(), JsValue> {
        let mut app = self
            .runner
            .app_mut::<ArmlabApp>()
            .ok_or_else(|| JsValue::from_str("the app has not started"))?;
        app.apply(crate::app::action::Action::Class(action));
        Ok(())
    }

    /// Whether the app has panicked (then the page shows the panic).
    pub fn has_panicked(&self) -> bool {
        self.runner.has_panicked()
    }

    /// The panic's message, if any.
    pub fn panic_message(&self) -> Option<String> {
        self.runner.panic_summary().map(|s| s.message())
    }

    /// Stops the app and removes its event handlers.
    pub fn destroy(&self) {
        self.runner.destroy();
    }
}

/// What the web worker (`worker.js`) runs: one [`crate::offload::Request`] as JSON in, its
/// answer as JSON out; on the way, the map as it forms ([`crate::offload::Answer::Partial`] in
/// JSON) handed to `partial`: the coarse first look, then at most one every
/// [`PARTIAL_EVERY_MS`].
#[wasm_bindgen]
pub fn worker_compute(request: &str, partial: &js_sys::Function) -> String {
    let mut last: Option<f64> = None;
    crate::offload::answer_forming(
        request,
        &mut || {
            let now = js_sys::Date::now();
            let wanted = last.is_none_or(|t| now - t >= PARTIAL_EVERY_MS);
            if wanted {
                last = Some(now);
            }
            wanted
        },
        &mut |json| {
            let _ = partial.call1(&JsValue::NULL, &JsValue::from_str(&json));
        },
    )
}

/// Milliseconds between two partial maps a worker sends.
pub const PARTIAL_EVERY_MS: f64 = 400.0;

/// Web workers in the pool: one per logical core the browser reports
/// (`navigator.hardwareConcurrency`) but one, which the page keeps (it draws the overlay and,
/// without a GPU, rasterizes), at least 1, at most [`MAX_WORKERS`]; `?workers=N` in the URL
/// sets it.
fn pool_size() -> usize {
    let cores = web_sys::window().map_or(1.0, |w| w.navigator().hardware_concurrency());
    url_parameter("workers")
        .and_then(|n| n.trim().parse::<usize>().ok())
        .unwrap_or((cores as usize).saturating_sub(1))
        .clamp(1, MAX_WORKERS)
}

/// Most web workers in the pool (each holds an instance of the module).
pub const MAX_WORKERS: usize = 8;

/// One of the page's web workers, for the workspace's heavy computations.
struct WorkerOffload {
    worker: web_sys::Worker,
    answer: Rc<RefCell<Option<String>>>,
    _on_message: Closure<dyn FnMut(web_sys::MessageEvent)>,
    _on_error: Closure<dyn FnMut(web_sys::ErrorEvent)>,
}

impl WorkerOffload {
    fn new() -> Result<Self, JsValue> {
        let options = web_sys::WorkerOptions::new();
        options.set_type(web_sys::WorkerType::Module);
        let worker = web_sys::Worker::new_with_options("./worker.js", &options)?;
        let answer: Rc<RefCell<Option<String>>> = Rc::default();
        let slot = answer.clone();
        let on_message =
            Closure::<dyn FnMut(web_sys::MessageEvent)>::new(move |e: web_sys::MessageEvent| {
                *slot.borrow_mut() = e.data().as_string();
            });
        worker.set_onmessage(Some(on_message.as_ref().unchecked_ref()));
        let slot = answer.clone();
        let on_error = Closure::<dyn FnMut(web_sys::ErrorEvent)>::new(
            move |e: web_sys::ErrorEvent| {
                let text = serde_json::json!({ "Error": format!("the web worker failed: {}", e.message()) });
                *slot.borrow_mut() = Some(text.to_string());
            },
        );
        worker.set_onerror(Some(on_error.as_ref().unchecked_ref()));
        Ok(Self {
            worker,
            answer,
            _on_message: on_message,
            _on_error: on_error,
        })
    }
}

impl crate::offload::Offload for WorkerOffload {
    fn submit(&mut self, request: String) -> bool {
        self.answer.borrow_mut().take();
        self.worker
            .post_message(&JsValue::from_str(&request))
            .is_ok()
    }

    fn poll(&mut self) -> Option<String> {
        self.answer.borrow_mut().take()
    }
}

/// The state for the model `requested` by the URL (a built-in name), else the default robot;
/// whether the model was asked for (it then wins over the remembered one). A joint vector in
/// the URL (`q=0.3,0.8,-1,0.4,0.6,0.2`: rad or m, or angles such as `pi/2` and `-90deg`) is
/// opened with the IK target on the tool, as `armlab view --q` does.
fn initial_state(requested: Option<&str>, q: Option<&str>) -> (AppState, bool) {
    let default = || AppState::from_spec(crate::kinematics::models::DEFAULT_MODEL);
    let (mut state, given) = match requested.map(AppState::from_spec) {
        Some(Ok(s)) => (s, true),
        Some(Err(e)) => {
            let mut s = default().expect("the default model is built in");
            s.push_message(Level::Error, format!("?model=: {e}"));
            (s, false)
        }
        None => (default().expect("the default model is built in"), false),
    };
    if let Some(text) = q
        && let Err(e) = open_at(&mut state, text)
    {
        state.push_message(Level::Error, format!("?q={text}: {e}"));
    }
    (state, given)
}

/// Puts the arm at the joint vector `text` (comma-separated) and the IK target on its tool.
fn open_at(state: &mut AppState, text: &str) -> Result<(), String> {
    let q: Vec<f64> = text
        .split(',')
        .map(|v| {
            let v = v.trim();
            v.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .or_else(|| crate::model_file::parse_angle(v))
                .ok_or_else(|| format!("\"{v}\" is not a number or an angle"))
        })
        .collect::<Result<_, _>>()?;
    state.set_q(&q).map_err(|e| e.to_string())?;
    let tool = state
        .robot()
        .fk_ee(state.q(), 0)
        .map_err(|e| e.to_string())?;
    state.set_target(0, tool).map_err(|e| e.to_string())?;
    state.clear_trails();
    Ok(())
}

fn status_json(app: &AppUi) -> serde_json::Value {
    let s = &app.state;
    let tool = s.robot().fk_ee(s.q(), app.ee()).ok();
    let position = tool.map(|t| t.translation.vector.iter().copied().collect::<Vec<_>>());
    let rpy_deg = tool.map(|t| {
        let (r, p, y) = t.rotation.euler_angles();
        [r, p, y].map(f64::to_degrees)
    });
    let ghosts = s.ghosts(app.ee());
    serde_json::json!({
        "started": true,
        "app": APP_ID,
        "model": s.robot().name,
        "dof": s.robot().dof(),
        "q": s.q(),
        "position": position,
        "rpy_deg": rpy_deg,
        "solutions": ghosts.len(),
        "within_limits": ghosts.iter().filter(|g| g.within_limits).count(),
        "gizmo": app.gizmo_grip().map(|p| [p.x, p.y]),
        "tab": app.tab,
        "workspace_progress": app.tabs.workspace.job.as_ref().map(|w| w.progress().unwrap_or(1.0)),
        "workspace_figure": app.tabs.workspace.job.as_ref().and_then(|w| w.figure()).map(|f| [f.width(), f.height()]),
        "workspace_dots": app.tabs.workspace.job.as_ref().and_then(|w| w.dots()).map(<[_]>::len),
        "workspace_previews": app.tabs.workspace.job.as_ref().map(WorkspaceJob::previews),
        "workers": app.offload.len(),
        "workspace_error": app.tabs.workspace.job.as_ref().and_then(|w| w.error()),
        "messages": s.messages().iter().map(|m| m.text.clone()).collect::<Vec<_>>(),
        "class": app.class.status(),
        "lesson": app.lesson.as_ref().map(|p| serde_json::json!({
            "title": p.lesson.title,
            "step": p.step,
            "steps": p.lesson.steps.len(),
        })),
    })
}

/// Joins the live class the page's URL names: `?token=T` as the teacher (the Class window
/// open), `?code=C&name=N` as the student `N`, `?code=C` alone after the nickname prompt; over
/// `ws(s)://HOST/ws` of the page's own server. A student's resume secret is kept in local
/// storage per code, so that a reload is the same student.
fn join_class(ui: &mut AppUi) {
    let (token, code) = (url_parameter("token"), url_parameter("code"));
    if token.is_none() && code.is_none() {
        return;
    }
    let Some(ws) = page_ws_url() else {
        return ui
            .state
            .push_message(Level::Error, "class: the page has no address");
    };
    if let Some(token) = token {
        match link::open(&ws) {
            Ok(l) => ui.class.connect_teacher(l, &token),
            Err(e) => ui.state.push_message(Level::Error, format!("class: {e}")),
        }
        ui.class.window = true;
        return;
    }
    let code = code.unwrap_or_default();
    let key = format!("armlab-class-resume-{code}");
    let resume = local_storage().and_then(|s| s.get_item(&key).ok().flatten());
    ui.class.on_resume = Some(Box::new(move |secret| {
        if let Some(s) = local_storage() {
            let _ = s.set_item(&key, secret);
        }
    }));
    match url_parameter("name") {
        Some(name) => match link::open(&ws) {
            Ok(l) => ui.class.connect_student(l, &code, &name, resume),
            Err(e) => ui.state.push_message(Level::Error, format!("class: {e}")),
        },
        None => ui.class.prompt = Some(NamePrompt { ws, code, resume }),
    }
}

/// The class server's WebSocket URL on the page's own host: `ws://HOST/ws` (`wss://` on https).
fn page_ws_url() -> Option<String> {
    let location = web_sys::window()?.location();
    let scheme = match location.protocol().ok()?.as_str() {
        "https:" => "wss",
        _ => "ws",
    };
    Some(format!("{scheme}://{}/ws", location.host().ok()?))
}

/// The page's local storage, where the browser allows it.
fn local_storage() -> Option<web_sys::Storage> {
    web_sys::window()?.local_storage().ok().flatten()
}

/// The text at `url` (relative to the page), fetched.
async fn fetch_text(url: &str) -> Result<String, String> {
    let window = web_sys::window().ok_or("no window")?;
    let response = wasm_bindgen_futures::JsFuture::from(window.fetch_with_str(url))
        .await
        .map_err(|e| format!("{url}: {e:?}"))?;
    let response: web_sys::Response = response
        .dyn_into()
        .map_err(|_| format!("{url}: no response"))?;
    if !response.ok() {
        return Err(format!("{url}: HTTP {}", response.status()));
    }
    let text = response.text().map_err(|e| format!("{url}: {e:?}"))?;
    let text = wasm_bindgen_futures::JsFuture::from(text)
        .await
        .map_err(|e| format!("{url}: {e:?}"))?;
    text.as_string().ok_or_else(|| format!("{url}: not text"))
}

/// The model name in the page's URL query, e.g. `?model=puma560`.
fn url_parameter(key: &str) -> Option<String> {
    let search = web_sys::window()?.location().search().ok()?;
    web_sys::UrlSearchParams::new_with_str(&search)
        .ok()?
        .get(key)
        .filter(|v| !v.trim().is_empty())
}

/// Files the browser's way: a hidden file input for opening, downloads for saving.
#[derive(Default)]
struct BrowserFiles {
    /// Files read since the last poll (filled by the input's change handler).
    arrived: Arrived,
}

/// Files read by the browser (kind, name, bytes), waiting to be opened.
type Arrived = Rc<RefCell<Vec<(FileKind, String, Vec<u8>)>>>;

impl FilePicker for BrowserFiles {
    fn available(&self) -> bool {
        true
    }

    fn open(&mut self, kind: FileKind) -> Option<PathBuf> {
        if let Err(e) = pick_file(kind, self.arrived.clone()) {
            web_sys::console::error_1(&e);
        }
        None
    }

    fn save(&mut self, _kind: FileKind, _suggested: &str) -> Option<PathBuf> {
        None
    }

    fn poll_opened(&mut self) -> Option<(FileKind, String, Vec<u8>)> {
        let mut a = self.arrived.borrow_mut();
        (!a.is_empty()).then(|| a.remove(0))
    }

    fn take_dropped(&mut self, file: &egui::DroppedFileHandle) -> bool {
        let (file, arrived) = (file.clone(), self.arrived.clone());
        wasm_bindgen_futures::spawn_local(async move {
            let name = file.path().to_string_lossy().into_owned();
            match file.bytes_async().await {
                Ok(bytes) => arrived.borrow_mut().push((FileKind::Model, name, bytes)),
                Err(e) => web_sys::console::error_1(&format!("{name}: {e}").into()),
            }
        });
        true
    }

    fn download(&mut self, name: &str, mime: &str, bytes: &[u8]) -> bool {
        download(name, mime, bytes).is_ok()
    }

    fn downloads(&self) -> bool {
        true
    }
}

/// Opens the browser's file picker; the chosen file's bytes are pushed onto `arrived`.
fn pick_file(kind: FileKind, arrived: Arrived) -> Result<(), JsValue> {
    let document = web_sys::window()
        .and_then(|w| w.document())
        .ok_or("no document")?;
    let input: web_sys::HtmlInputElement = document.create_element("input")?.dyn_into()?;
    input.set_type("file");
    input.set_accept(match kind {
        FileKind::Measurements => ".csv,.txt",
        _ => ".toml,.urdf",
    });
    let picked = input.clone();
    let on_change = Closure::once(move || {
        let Some(file) = picked.files().and_then(|f| f.get(0)) else {
            return;
        };
        wasm_bindgen_futures::spawn_local(async move {
            let name = file.name();
            let buffer = wasm_bindgen_futures::JsFuture::from(file.array_buffer()).await;
            if let Ok(buffer) = buffer {
                let bytes = js_sys::Uint8Array::new(&buffer).to_vec();
                arrived.borrow_mut().push((kind, name, bytes));
            }
        });
    });
    input.set_onchange(Some(on_change.as_ref().unchecked_ref()));
    on_change.forget();
    input.click();
    Ok(())
}

/// Offers `bytes` as a download named `name` (a blob URL on a clicked link).
fn download(name: &str, mime: &str, bytes: &[u8]) -> Result<(), JsValue> {
    let document = web_sys::window()
        .and_then(|w| w.document())
        .ok_or("no document")?;
    let parts = js_sys::Array::of1(&js_sys::Uint8Array::from(bytes));
    let props = web_sys::BlobPropertyBag::new();
    props.set_type(mime);
    let blob = web_sys::Blob::new_with_u8_array_sequence_and_options(&parts, &props)?;
    let url = web_sys::Url::create_object_url_with_blob(&blob)?;
    let a: web_sys::HtmlAnchorElement = document.create_element("a")?.dyn_into()?;
    a.set_href(&url);
    a.set_download(name);
    a.click();
    web_sys::Url::revoke_object_url(&url)?;
    Ok(())
}
