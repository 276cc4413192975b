//! The class client's transport: a [`ClassLink`] carries the protocol's JSON text frames to the
//! class server's `/ws` and back, and says when the connection opens and closes. The desktop's
//! runs a WebSocket client on its own thread (`desktop`), the browser's the page's `WebSocket`
//! (`browser`); both reconnect on their own with a growing pause, so that the client only has
//! to join again after each [`LinkEvent::Opened`].

/// What happened on a link since it was last polled, in order.
#[derive(Debug, Clone, PartialEq)]
pub enum LinkEvent {
    /// The connection is open (again): the client joins.
    Opened,
    /// A text frame from the server.
    Message(String),
    /// The connection closed or could not be opened (why, in words); the link tries again.
    Closed(String),
}

/// A connection to the class server, polled once a frame.
pub trait ClassLink {
    /// Sends a text frame (dropped while the connection is down: the client sends its state
    /// again after joining).
    fn send(&mut self, text: String);
    /// What happened since the last poll.
    fn poll(&mut self) -> Vec<LinkEvent>;
    /// Asks `ctx` for a new frame whenever something arrives (the window sleeps otherwise).
    fn wake_with(&mut self, _ctx: &egui::Context) {}
}

/// Where to connect, read from a page link (`http://HOST:PORT/?token=T` or `?code=C&name=N`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PageLink {
    /// The WebSocket URL: `ws://HOST:PORT/ws` (`wss://` for an `https://` link).
    pub ws: String,
    /// The teacher's token (`token=`).
    pub token: Option<String>,
    /// The join code (`code=`).
    pub code: Option<String>,
    /// The nickname (`name=`).
    pub name: Option<String>,
}

impl PageLink {
    /// Reads a page link as the server prints it. A link without a scheme is taken as
    /// `http://`.
    ///
    /// # Examples
    ///
    /// ```
    /// use armlab::app::class::link::PageLink;
    ///
    /// let l = PageLink::parse("http://127.0.0.1:8737/?token=3f9c").unwrap();
    /// assert_eq!(l.ws, "ws://127.0.0.1:8737/ws");
    /// assert_eq!(l.token.as_deref(), Some("3f9c"));
    /// assert!(PageLink::parse("ftp://x/").is_err());
    /// ```
    pub fn parse(link: &str) -> Result<Self, String> {
        let link = link.trim();
        let (scheme, rest) = match link.split_once("://") {
            Some(("http", r)) => ("ws", r),
            Some(("https", r)) => ("wss", r),
            Some((s, _)) => return Err(format!("{s}:// links are not class links (http://...)")),
            None => ("ws", link),
        };
        let (host, query) = match rest.split_once('?') {
            Some((h, q)) => (h, q),
            None => (rest, ""),
        };
        let host = host.split('/').next().unwrap_or_default();
        if host.is_empty() {
            return Err(format!("{link:?}: no server address in the link"));
        }
        let value = |key: &str| {
            query
                .split('&')
                .filter_map(|kv| kv.split_once('='))
                .find(|(k, _)| *k == key)
                .map(|(_, v)| percent_decoded(v))
                .filter(|v| !v.trim().is_empty())
        };
        Ok(Self {
            ws: format!("{scheme}://{host}/ws"),
            token: value("token"),
            code: value("code"),
            name: value("name"),
        })
    }
}

/// A query value with `%XX` and `+` decoded (an invalid escape is kept as written).
fn percent_decoded(v: &str) -> String {
    let bytes = v.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = |b: u8| (b as char).to_digit(16);
        match bytes[i] {
            b'+' => out.push(b' '),
            b'%' if i + 2 < bytes.len() => match (hex(bytes[i + 1]), hex(bytes[i + 2])) {
                (Some(h), Some(l)) => {
                    out.push((h * 16 + l) as u8);
                    i += 2;
                }
                _ => out.push(b'%'),
            },
            b => out.push(b),
        }
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// A link to `ws` (a WebSocket URL) for this build: the desktop's thread, the browser's
/// WebSocket; an error where this build has neither.
pub fn open(ws: &str) -> Result<Box<dyn ClassLink>, String> {
    #[cfg(all(feature = "app", not(target_arch = "wasm32")))]
    {
        Ok(Box::new(super::desktop::DesktopLink::connect(ws)))
    }
    #[cfg(target_arch = "wasm32")]
    {
        super::browser::BrowserLink::connect(ws).map(|l| Box::new(l) as Box<dyn ClassLink>)
    }
    #[cfg(not(any(feature = "app", target_arch = "wasm32")))]
    {
        Err(format!("{ws}: this build has no network connection"))
    }
}
