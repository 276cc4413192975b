//! The desktop's class link: a tokio-tungstenite WebSocket client on its own thread, with a
//! small single-threaded tokio runtime; frames go out through a tokio channel and come back
//! through a std one, polled by the window's frame loop. A dropped connection is opened again
//! after a pause that doubles from [`FIRST_PAUSE`] up to [`LONGEST_PAUSE`]; dropping the link
//! ends the thread.

use super::link::{ClassLink, LinkEvent};
use futures_util::{SinkExt, StreamExt};
use std::sync::{Arc, Mutex, mpsc};
use std::time::Duration;
use tokio::sync::mpsc as tokio_mpsc;
use tokio_tungstenite::tungstenite::Message;

/// The pause before the first reconnection.
pub const FIRST_PAUSE: Duration = Duration::from_millis(250);
/// The longest pause between two reconnections.
pub const LONGEST_PAUSE: Duration = Duration::from_secs(5);

/// Who to wake when a frame arrives (the window's context, once the client has one).
type Waker = Arc<Mutex<Option<egui::Context>>>;

/// A WebSocket connection to the class server, run on its own thread.
pub struct DesktopLink {
    outgoing: tokio_mpsc::UnboundedSender<String>,
    events: mpsc::Receiver<LinkEvent>,
    waker: Waker,
}

impl DesktopLink {
    /// Starts connecting to `ws` (`ws://HOST:PORT/ws`) on a new thread; what happens comes back
    /// through [`ClassLink::poll`] (a thread that cannot start is a [`LinkEvent::Closed`]).
    pub fn connect(ws: &str) -> Self {
        let (outgoing, rx) = tokio_mpsc::unbounded_channel();
        let (tx, events) = mpsc::channel();
        let waker: Waker = Arc::default();
        let (url, wake) = (ws.to_string(), waker.clone());
        let started = std::thread::Builder::new()
            .name("armlab class link".into())
            .spawn(move || {
                let runtime = tokio::runtime::Builder::new_current_thread()
                    .enable_all()
                    .build();
                match runtime {
                    Ok(rt) => rt.block_on(run(url, rx, Events { tx, wake })),
                    Err(e) => _ = Events { tx, wake }.emit(LinkEvent::Closed(e.to_string())),
                }
            });
        let link = Self {
            outgoing,
            events,
            waker,
        };
        if let Err(e) = started {
            // No thread: the receiver's sender is gone, and poll says so once.
            return Self::failed(link, e.to_string());
        }
        link
    }

    fn failed(link: Self, why: String) -> Self {
        let (tx, events) = mpsc::channel();
        let _ = tx.send(LinkEvent::Closed(why));
        Self { events, ..link }
    }
}

impl ClassLink for DesktopLink {
    fn send(&mut self, text: String) {
        let _ = self.outgoing.send(text);
    }

    fn poll(&mut self) -> Vec<LinkEvent> {
        self.events.try_iter().collect()
    }

    fn wake_with(&mut self, ctx: &egui::Context) {
        if let Ok(mut w) = self.waker.lock()
            && w.is_none()
        {
            *w = Some(ctx.clone());
        }
    }
}

/// The way back to the window: the events, and a new frame asked for each.
struct Events {
    tx: mpsc::Sender<LinkEvent>,
    wake: Waker,
}

impl Events {
    /// Hands `e` over; `false` when the link is gone.
    fn emit(&self, e: LinkEvent) -> bool {
        let sent = self.tx.send(e).is_ok();
        if let Ok(w) = self.wake.lock()
            && let Some(ctx) = w.as_ref()
        {
            ctx.request_repaint();
        }
        sent
    }
}

/// How a connection ended.
enum Ended {
    /// The link was dropped: the thread ends.
    Dropped,
    /// The connection closed (why): open it again.
    Closed(String),
}

/// Connects, relays, and reconnects after a growing pause until the link is dropped.
async fn run(url: String, mut outgoing: tokio_mpsc::UnboundedReceiver<String>, events: Events) {
    let mut pause = FIRST_PAUSE;
    loop {
        let why = match tokio_tungstenite::connect_async(url.as_str()).await {
            Ok((ws, _)) => {
                pause = FIRST_PAUSE;
                if !events.emit(LinkEvent::Opened) {
                    return;
                }
                match relay(ws, &mut outgoing, &events).await {
                    Ended::Dropped => return,
                    Ended::Closed(why) => why,
                }
            }
            Err(e) => format!("cannot connect to {url}: {e}"),
        };
        if !events.emit(LinkEvent::Closed(why)) || !wait(pause, &mut outgoing).await {
            return;
        }
        pause = (pause * 2).min(LONGEST_PAUSE);
    }
}

/// Waits `pause`, dropping what is sent meanwhile; `false` when the link was dropped.
async fn wait(pause: Duration, outgoing: &mut tokio_mpsc::UnboundedReceiver<String>) -> bool {
    let until = tokio::time::Instant::now() + pause;
    loop {
        tokio::select! {
            _ = tokio::time::sleep_until(until) => return true,
            m = outgoing.recv() => if m.is_none() {
                return false;
            },
        }
    }
}

type Socket =
    tokio_tungstenite::WebSocketStream<tokio_tungstenite::MaybeTlsStream<tokio::net::TcpStream>>;

/// Relays frames both ways on one open connection until it closes or the link is dropped.
async fn relay(
    mut ws: Socket,
    outgoing: &mut tokio_mpsc::UnboundedReceiver<String>,
    events: &Events,
) -> Ended {
    loop {
        tokio::select! {
            m = outgoing.recv() => match m {
                Some(text) => {
                    if let Err(e) = ws.send(Message::text(text)).await {
                        return Ended::Closed(e.to_string());
                    }
                }
                None => {
                    let _ = ws.close(None).await;
                    return Ended::Dropped;
                }
            },
            m = ws.next() => match m {
                Some(Ok(Message::Text(t))) => {
                    if !events.emit(LinkEvent::Message(t.to_string())) {
                        return Ended::Dropped;
                    }
                }
                Some(Ok(Message::Close(frame))) => {
                    let why = frame.map_or_else(String::new, |f| f.reason.to_string());
                    return Ended::Closed(format!("the server closed the connection {why}"));
                }
                Some(Ok(_)) => {}
                Some(Err(e)) => return Ended::Closed(e.to_string()),
                None => return Ended::Closed("the connection ended".into()),
            },
        }
    }
}
