//! The server's routes (axum): `/ws` (the class's WebSocket, [`super::ws`]), `/export.csv`
//! (a session's answers for the teacher's token), and the web build's static files (or, where
//! there is no build, a plain-text page saying how to make one).

use super::hub::Hub;
use super::limits;
use super::ws;
use axum::Router;
use axum::extract::ws::WebSocketUpgrade;
use axum::extract::{ConnectInfo, Query, State};
use axum::http::{StatusCode, header};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use serde::Deserialize;
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

/// The largest WebSocket message or frame taken at all: above what [`parse_client`] accepts
/// for a model file, so that the parser (not the WebSocket layer, which would close the
/// connection) answers an oversized message with an error.
///
/// [`parse_client`]: crate::class::protocol::parse_client
pub(crate) const WS_MAX_BYTES: usize = 10 * 1024 * 1024;

/// The page `/` answers where the web build is missing (plain text: nothing of it is markup).
const NO_WEB_PAGE: &str = "armlab class server\n\n\
The web build is missing, so there is no page to show here. Build it with web/build.sh \
(it writes web/dist), or start the server with --web DIR naming a folder that holds the \
build's index.html.\n\n\
The class's WebSocket still answers at /ws, for the desktop app and other clients.\n";

/// The routes, with the web build of `web` (a folder holding `index.html`) or, if `None`, the
/// plain page that says how to build it.
pub(crate) fn router(hub: Arc<Hub>, web: Option<PathBuf>) -> Router {
    let router = Router::new()
        .route("/ws", get(websocket))
        .route("/export.csv", get(export));
    let router = match web {
        Some(dir) => router.fallback_service(tower_http::services::ServeDir::new(dir)),
        None => router
            .route("/", get(no_web_build))
            .fallback(|| async { (StatusCode::NOT_FOUND, "not found\n") }),
    };
    router.with_state(hub)
}

/// `/ws`: the class's WebSocket, messages up to [`WS_MAX_BYTES`].
async fn websocket(
    upgrade: WebSocketUpgrade,
    ConnectInfo(peer): ConnectInfo<SocketAddr>,
    State(hub): State<Arc<Hub>>,
) -> Response {
    upgrade
        .max_message_size(WS_MAX_BYTES)
        .max_frame_size(WS_MAX_BYTES)
        .on_upgrade(move |socket| ws::connection(socket, peer.ip(), hub))
}

/// The query of `/export.csv`.
#[derive(Debug, Deserialize)]
struct ExportQuery {
    /// The teacher's token.
    #[serde(default)]
    token: Option<String>,
}

/// `/export.csv?token=T`: the session's answers as CSV; 403 without the right token (a failed
/// attempt of the address, as a wrong token on `/ws`).
async fn export(
    Query(query): Query<ExportQuery>,
    ConnectInfo(peer): ConnectInfo<SocketAddr>,
    State(hub): State<Arc<Hub>>,
) -> Response {
    let ip = peer.ip();
    if hub.blocked(ip) {
        return (StatusCode::TOO_MANY_REQUESTS, limits_message()).into_response();
    }
    let Some(session) = query.token.as_deref().and_then(|t| hub.by_token(t)) else {
        hub.failed(ip, Instant::now());
        return (StatusCode::FORBIDDEN, "wrong teacher token\n").into_response();
    };
    let csv = session.export();
    let disposition = format!("attachment; filename=\"armlab-class-{}.csv\"", session.id);
    (
        [
            (header::CONTENT_TYPE, "text/csv; charset=utf-8".to_string()),
            (header::CONTENT_DISPOSITION, disposition),
        ],
        csv,
    )
        .into_response()
}

/// The words of a refused join.
pub(crate) fn limits_message() -> String {
    format!(
        "too many join attempts from this address; wait a minute (at most {} failed attempts \
         a minute)",
        limits::MAX_FAILED_ATTEMPTS
    )
}

/// `/` without a web build: how to make one.
async fn no_web_build() -> Response {
    (
        [(header::CONTENT_TYPE, "text/plain; charset=utf-8")],
        NO_WEB_PAGE,
    )
        .into_response()
}
