//! The live classroom's server (issue 50; `armlab class serve`, or the desktop app's "Start
//! class"): class sessions over WebSockets on `/ws` (the messages of
//! [`crate::class::protocol`]), the web build's static files, a session's answers as CSV on
//! `/export.csv?token=T`, everything kept in SQLite.
//!
//! [`start`] runs the server on a thread of its own with its own tokio runtime and returns once
//! it listens, with the links to print ([`ServerHandle`]); stopping it (or dropping the
//! handle) closes the connections and writes the latest state to the data file.
//!
//! The parts: the hub (sessions found by token or code, joining), the session and the
//! teacher's and students' operations on it, one task per connection, the data file (a writer
//! thread), the limits (messages a second per connection, failed joins per address), the QR
//! code ([`qr`]) and the CSV export.

mod export;
mod http;
mod hub;
mod limits;
mod links;
mod load;
pub mod qr;
mod secret;
mod session;
mod store;
mod student;
mod teacher;
mod ws;

use hub::Hub;
use session::Session;
use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::Duration;
use thiserror::Error;
use tokio::sync::{oneshot, watch};

/// The port the server listens on unless told otherwise.
pub const DEFAULT_PORT: u16 = 8737;
/// The data file unless told otherwise (in the current folder).
pub const DEFAULT_DATA: &str = "armlab-class.sqlite";
/// The web build's folder looked for when none is given (relative to the current folder).
pub const DEFAULT_WEB: &str = "web/dist";
/// How often the latest state is written to the data file, at most.
const STATE_FLUSH: Duration = Duration::from_millis(250);

/// How to run a class server.
#[derive(Debug, Clone, PartialEq)]
pub struct ServerOptions {
    /// The address to listen on: 127.0.0.1 (this computer only) unless a classroom network
    /// must reach it (0.0.0.0: every interface).
    pub bind: IpAddr,
    /// The port (0: any free one; the links name the port taken).
    pub port: u16,
    /// The SQLite data file (made if missing): sessions, questions, answers.
    pub data: PathBuf,
    /// The web build's folder (holding `index.html`); `None`: [`DEFAULT_WEB`] if it exists.
    pub web: Option<PathBuf>,
    /// The teacher sees the students' nicknames (a new session's setting; given to an existing
    /// session, it turns names on for it).
    pub show_names: bool,
    /// Start a new session even if the data file holds some.
    pub new_session: bool,
}

impl Default for ServerOptions {
    fn default() -> Self {
        Self {
            bind: IpAddr::V4(Ipv4Addr::LOCALHOST),
            port: DEFAULT_PORT,
            data: PathBuf::from(DEFAULT_DATA),
            web: None,
            show_names: false,
            new_session: false,
        }
    }
}

/// What goes wrong starting or running the server.
#[derive(Debug, Error)]
pub enum ServerError {
    /// The address cannot be listened on (taken, or not this computer's).
    #[error("cannot listen on {addr}: {source}")]
    Bind {
        /// The address and port.
        addr: SocketAddr,
        /// Why.
        source: std::io::Error,
    },
    /// The data file cannot be opened.
    #[error("cannot open the class data file: {source} ({})", path.display())]
    Open {
        /// The file.
        path: PathBuf,
        /// Why.
        source: rusqlite::Error,
    },
    /// A query of the data file failed.
    #[error("the class data file: {what}: {source}")]
    Sql {
        /// What was being done.
        what: &'static str,
        /// Why it failed.
        source: rusqlite::Error,
    },
    /// A stored value that cannot be read (the file was changed by hand, or is damaged).
    #[error("the class data file: {what} {row} cannot be read: {reason}")]
    Corrupt {
        /// What the value is (`state`, `question`, `answer`).
        what: &'static str,
        /// Its row (`session/question/student`).
        row: String,
        /// Why.
        reason: String,
    },
    /// The server's threads or runtime could not start, or serving failed.
    #[error("the class server: {source}")]
    Runtime {
        /// Why.
        source: std::io::Error,
    },
    /// The operating system gave no randomness for the secrets.
    #[error("no randomness from the operating system for the secrets: {reason}")]
    Random {
        /// Why.
        reason: String,
    },
    /// The server's thread ended before it listened.
    #[error("the class server stopped before it listened")]
    Stopped,
}

/// A running server: its address and the links to give out. Stopping it ([`Self::stop`], or
/// dropping it) closes the connections and writes the latest state to the data file.
#[derive(Debug)]
pub struct ServerHandle {
    /// The address listened on (its port the one taken, where the options asked for 0).
    pub addr: SocketAddr,
    /// The teacher's link (`http://HOST:PORT/?token=T`): keep it secret, it drives the session.
    pub teacher_url: String,
    /// The students' link (`http://HOST:PORT/?code=C`).
    pub student_url: String,
    /// The teacher token of the newest session (128 random bits, hex).
    pub token: String,
    /// The join code of the newest session.
    pub code: String,
    /// The students' link as a QR code: rows of `#` (dark) and ` ` (light), no quiet zone.
    pub qr: Vec<String>,
    /// How students on a classroom network reach the server, in words.
    pub network_hint: String,
    /// What the server could not do but went on without (no web build found), in words.
    pub warnings: Vec<String>,
    /// Tells the server's thread to stop.
    stop: Option<oneshot::Sender<()>>,
    /// The server's thread.
    thread: Option<JoinHandle<Result<(), ServerError>>>,
}

impl ServerHandle {
    /// Stops the server: closes every connection, writes the latest state, waits for the
    /// data file's writes. What went wrong while it served, if anything.
    pub fn stop(mut self) -> Result<(), ServerError> {
        self.shut_down()
    }

    /// Whether the server still runs (false after it stopped on an error).
    pub fn is_running(&self) -> bool {
        self.thread.as_ref().is_some_and(|t| !t.is_finished())
    }

    /// Stops the thread and waits for it.
    fn shut_down(&mut self) -> Result<(), ServerError> {
        if let Some(stop) = self.stop.take() {
            let _ = stop.send(());
        }
        match self.thread.take().map(JoinHandle::join) {
            Some(Ok(result)) => result,
            Some(Err(_)) => Err(ServerError::Stopped),
            None => Ok(()),
        }
    }
}

impl Drop for ServerHandle {
    fn drop(&mut self) {
        if let Err(e) = self.shut_down() {
            eprintln!("armlab class: {e}");
        }
    }
}

/// What the server's thread tells [`start`] once it listens.
struct Ready {
    /// See [`ServerHandle`].
    addr: SocketAddr,
    teacher_url: String,
    student_url: String,
    token: String,
    code: String,
    qr: Vec<String>,
    network_hint: String,
    warnings: Vec<String>,
}

/// Starts a class server on a thread of its own (with its own tokio runtime) and returns once
/// it listens. The data file's sessions are kept; a new one is made if it holds none or
/// [`ServerOptions::new_session`] asks; the handle's links are the newest session's.
///
/// # Examples
///
/// ```
/// use armlab::class_server::{ServerOptions, start};
///
/// let dir = std::env::temp_dir().join(format!("armlab-doc-class-{}", std::process::id()));
/// std::fs::create_dir_all(&dir)?;
/// let server = start(ServerOptions {
///     port: 0, // any free port
///     data: dir.join("class.sqlite"),
///     ..ServerOptions::default()
/// })?;
/// assert!(server.teacher_url.starts_with("http://127.0.0.1:"));
/// assert!(server.teacher_url.ends_with(&format!("/?token={}", server.token)));
/// assert!(server.student_url.ends_with(&format!("/?code={}", server.code)));
/// assert!(server.token.len() >= 32 && server.code.len() == 6);
/// server.stop()?;
/// # std::fs::remove_dir_all(&dir)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn start(options: ServerOptions) -> Result<ServerHandle, ServerError> {
    let (ready_tx, ready_rx) = std::sync::mpsc::channel();
    let (stop_tx, stop_rx) = oneshot::channel();
    let thread = std::thread::Builder::new()
        .name("armlab-class".into())
        .spawn(move || run(options, ready_tx, stop_rx))
        .map_err(|source| ServerError::Runtime { source })?;
    match ready_rx.recv() {
        Ok(Ok(r)) => Ok(ServerHandle {
            addr: r.addr,
            teacher_url: r.teacher_url,
            student_url: r.student_url,
            token: r.token,
            code: r.code,
            qr: r.qr,
            network_hint: r.network_hint,
            warnings: r.warnings,
            stop: Some(stop_tx),
            thread: Some(thread),
        }),
        Ok(Err(e)) => {
            let _ = thread.join();
            Err(e)
        }
        Err(_) => match thread.join() {
            Ok(Err(e)) => Err(e),
            _ => Err(ServerError::Stopped),
        },
    }
}

/// The server's thread: a runtime, the server until `stop`, then a short wait for tasks.
fn run(
    options: ServerOptions,
    ready: std::sync::mpsc::Sender<Result<Ready, ServerError>>,
    stop: oneshot::Receiver<()>,
) -> Result<(), ServerError> {
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .thread_name("armlab-class-worker")
        .build()
        .map_err(|source| ServerError::Runtime { source })?;
    let result = runtime.block_on(async move {
        let prepared = match prepare(&options).await {
            Ok(p) => p,
            Err(e) => {
                let _ = ready.send(Err(e));
                return Ok(());
            }
        };
        let _ = ready.send(Ok(prepared.ready()));
        prepared.serve(stop).await
    });
    runtime.shutdown_timeout(Duration::from_secs(2));
    result
}

/// A server that listens, its sessions loaded, not yet serving.
struct Prepared {
    /// The socket.
    listener: tokio::net::TcpListener,
    /// The sessions.
    hub: Arc<Hub>,
    /// The data file's writer.
    writer: store::Writer,
    /// Turns the hub's shutdown signal on.
    shutdown: watch::Sender<bool>,
    /// The web build's folder, if there is one.
    web: Option<PathBuf>,
    /// The links and the rest [`start`] returns.
    links: links::Links,
    /// What the server goes on without.
    warnings: Vec<String>,
}

/// Listens, opens the data file, makes the sessions.
async fn prepare(options: &ServerOptions) -> Result<Prepared, ServerError> {
    let addr = SocketAddr::new(options.bind, options.port);
    let listener = tokio::net::TcpListener::bind(addr)
        .await
        .map_err(|source| ServerError::Bind { addr, source })?;
    let addr = listener
        .local_addr()
        .map_err(|source| ServerError::Bind { addr, source })?;
    let opening = store::Opening {
        new_session: options.new_session,
        show_names: options.show_names,
    };
    let path = options.data.clone();
    let (db, writer, stored) = tokio::task::spawn_blocking(move || store::open(&path, opening))
        .await
        .map_err(|e| ServerError::Runtime {
            source: std::io::Error::other(e.to_string()),
        })??;
    let mut links = links::Links::new(addr);
    let sessions: Vec<Arc<Session>> = stored
        .into_iter()
        .map(|s| {
            let url = links.student_url(&s.code);
            Arc::new(Session::new(s, url, db.clone()))
        })
        .collect();
    let newest = sessions.last().cloned().ok_or(ServerError::Stopped)?;
    links.set_newest(&newest);
    let (web, warnings) = web_folder(options.web.as_deref());
    let (shutdown, shutdown_rx) = watch::channel(false);
    Ok(Prepared {
        listener,
        hub: Arc::new(Hub::new(sessions, shutdown_rx)),
        writer,
        shutdown,
        web,
        links,
        warnings,
    })
}

/// The web build's folder: the one given, or [`DEFAULT_WEB`]; `None` (and a warning) where it
/// or its `index.html` is missing.
fn web_folder(given: Option<&Path>) -> (Option<PathBuf>, Vec<String>) {
    let dir = given.map_or_else(|| PathBuf::from(DEFAULT_WEB), Path::to_path_buf);
    if dir.join("index.html").is_file() {
        return (Some(dir), Vec::new());
    }
    let warning = format!(
        "no web build in {} (no index.html): students' browsers get a page saying how to \
         build it (web/build.sh); the WebSocket /ws still works",
        dir.display()
    );
    (None, vec![warning])
}

impl Prepared {
    /// What [`start`] returns.
    fn ready(&self) -> Ready {
        let l = &self.links;
        Ready {
            addr: l.addr,
            teacher_url: l.teacher_url.clone(),
            student_url: l.student_url.clone(),
            token: l.token.clone(),
            code: l.code.clone(),
            qr: l.qr.clone(),
            network_hint: l.network_hint(),
            warnings: self.warnings.clone(),
        }
    }

    /// Serves until `stop`; then closes the connections, writes the latest states and stops
    /// the data file's writer.
    async fn serve(self, stop: oneshot::Receiver<()>) -> Result<(), ServerError> {
        let Prepared {
            listener,
            hub,
            writer,
            shutdown,
            web,
            ..
        } = self;
        let flusher = tokio::spawn(flush_states(hub.clone()));
        let app = http::router(hub.clone(), web);
        let served = axum::serve(
            listener,
            app.into_make_service_with_connect_info::<SocketAddr>(),
        )
        .with_graceful_shutdown(async move {
            let _ = stop.await;
            let _ = shutdown.send(true);
        })
        .await;
        // The WebSocket tasks saw the signal: give them a moment to close.
        for _ in 0..200 {
            if Arc::strong_count(&hub.connections) == 1 {
                break;
            }
            tokio::time::sleep(Duration::from_millis(10)).await;
        }
        flusher.abort();
        for s in &hub.sessions {
            s.flush_state();
        }
        let _ = tokio::task::spawn_blocking(move || writer.stop()).await;
        served.map_err(|source| ServerError::Runtime { source })
    }
}

/// Writes each session's latest state to the data file, at most every [`STATE_FLUSH`].
async fn flush_states(hub: Arc<Hub>) {
    let mut tick = tokio::time::interval(STATE_FLUSH);
    tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
    loop {
        tick.tick().await;
        for s in &hub.sessions {
            s.flush_state();
        }
    }
}
