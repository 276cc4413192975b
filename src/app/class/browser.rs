//! The browser's class link: the page's `WebSocket` (web-sys), its events collected for the
//! frame loop to poll; a closed connection is opened again after a pause that doubles from
//! [`FIRST_PAUSE_MS`] up to [`LONGEST_PAUSE_MS`] (the browser's timer), until the link is
//! dropped.

use super::link::{ClassLink, LinkEvent};
use std::cell::RefCell;
use std::rc::{Rc, Weak};
use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

/// The pause before the first reconnection (ms).
pub const FIRST_PAUSE_MS: i32 = 250;
/// The longest pause between two reconnections (ms).
pub const LONGEST_PAUSE_MS: i32 = 5000;

/// The socket's handlers, kept alive as long as the socket.
struct Handlers {
    _open: Closure<dyn FnMut(web_sys::Event)>,
    _message: Closure<dyn FnMut(web_sys::MessageEvent)>,
    _close: Closure<dyn FnMut(web_sys::CloseEvent)>,
}

/// What the socket's handlers and the link share.
struct Inner {
    url: String,
    socket: Option<web_sys::WebSocket>,
    handlers: Option<Handlers>,
    events: Vec<LinkEvent>,
    pause_ms: i32,
    dropped: bool,
    ctx: Option<egui::Context>,
}

impl Inner {
    fn push(&mut self, e: LinkEvent) {
        self.events.push(e);
        if let Some(ctx) = &self.ctx {
            ctx.request_repaint();
        }
    }
}

/// A WebSocket connection to the class server from a page.
pub struct BrowserLink {
    inner: Rc<RefCell<Inner>>,
}

impl BrowserLink {
    /// Opens a WebSocket to `ws` (`ws://HOST/ws`, `wss://` on an https page).
    pub fn connect(ws: &str) -> Result<Self, String> {
        let inner = Rc::new(RefCell::new(Inner {
            url: ws.to_string(),
            socket: None,
            handlers: None,
            events: Vec::new(),
            pause_ms: FIRST_PAUSE_MS,
            dropped: false,
            ctx: None,
        }));
        open(&inner).map_err(|e| format!("{ws}: {e:?}"))?;
        Ok(Self { inner })
    }
}

/// Opens the socket of `inner` with its handlers (each holds the link weakly).
fn open(inner: &Rc<RefCell<Inner>>) -> Result<(), JsValue> {
    let url = inner.borrow().url.clone();
    let socket = web_sys::WebSocket::new(&url)?;
    let weak = Rc::downgrade(inner);
    let on_open = Closure::<dyn FnMut(web_sys::Event)>::new({
        let weak = weak.clone();
        move |_e: web_sys::Event| {
            if let Some(i) = weak.upgrade() {
                let mut i = i.borrow_mut();
                i.pause_ms = FIRST_PAUSE_MS;
                i.push(LinkEvent::Opened);
            }
        }
    });
    let on_message = Closure::<dyn FnMut(web_sys::MessageEvent)>::new({
        let weak = weak.clone();
        move |e: web_sys::MessageEvent| {
            if let (Some(i), Some(text)) = (weak.upgrade(), e.data().as_string()) {
                i.borrow_mut().push(LinkEvent::Message(text));
            }
        }
    });
    let on_close = Closure::<dyn FnMut(web_sys::CloseEvent)>::new(move |e: web_sys::CloseEvent| {
        closed(&weak, e.code(), e.reason());
    });
    socket.set_onopen(Some(on_open.as_ref().unchecked_ref()));
    socket.set_onmessage(Some(on_message.as_ref().unchecked_ref()));
    socket.set_onclose(Some(on_close.as_ref().unchecked_ref()));
    let mut i = inner.borrow_mut();
    i.socket = Some(socket);
    i.handlers = Some(Handlers {
        _open: on_open,
        _message: on_message,
        _close: on_close,
    });
    Ok(())
}

/// The socket closed: said once, then opened again after the pause (doubled for the next).
fn closed(weak: &Weak<RefCell<Inner>>, code: u16, reason: String) {
    let Some(inner) = weak.upgrade() else {
        return;
    };
    let pause = {
        let mut i = inner.borrow_mut();
        if i.dropped {
            return;
        }
        let why = if reason.is_empty() {
            format!("the connection closed (code {code})")
        } else {
            format!("the connection closed: {reason}")
        };
        i.push(LinkEvent::Closed(why));
        let pause = i.pause_ms;
        i.pause_ms = (pause * 2).min(LONGEST_PAUSE_MS);
        pause
    };
    let weak = weak.clone();
    let again = Closure::once_into_js(move || {
        if let Some(inner) = weak.upgrade()
            && !inner.borrow().dropped
            && let Err(e) = open(&inner)
        {
            inner
                .borrow_mut()
                .push(LinkEvent::Closed(format!("cannot reconnect: {e:?}")));
        }
    });
    if let Some(w) = web_sys::window() {
        let _ =
            w.set_timeout_with_callback_and_timeout_and_arguments_0(again.unchecked_ref(), pause);
    }
}

impl ClassLink for BrowserLink {
    fn send(&mut self, text: String) {
        let i = self.inner.borrow();
        if let Some(s) = i
            .socket
            .as_ref()
            .filter(|s| s.ready_state() == web_sys::WebSocket::OPEN)
        {
            let _ = s.send_with_str(&text);
        }
    }

    fn poll(&mut self) -> Vec<LinkEvent> {
        std::mem::take(&mut self.inner.borrow_mut().events)
    }

    fn wake_with(&mut self, ctx: &egui::Context) {
        let mut i = self.inner.borrow_mut();
        if i.ctx.is_none() {
            i.ctx = Some(ctx.clone());
        }
    }
}

impl Drop for BrowserLink {
    fn drop(&mut self) {
        let mut i = self.inner.borrow_mut();
        i.dropped = true;
        if let Some(s) = i.socket.take() {
            s.set_onopen(None);
            s.set_onmessage(None);
            s.set_onclose(None);
            let _ = s.close();
        }
        i.handlers = None;
    }
}
