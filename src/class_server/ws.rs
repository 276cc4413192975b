//! One WebSocket connection: its frames read, rate-limited and parsed ([`parse_client`]), the
//! join first, then the teacher's or the student's messages dispatched; the session's
//! broadcasts written to it as they come (a slow connection falls behind on its own and is
//! brought up to date from the snapshot). Every bad message gets an error reply and the
//! connection goes on.
//!
//! Reading and writing are two tasks: a peer that sends a large message while a large one waits
//! for it is still read (they once took turns, and such a peer stalled its own connection).

use super::hub::{Hub, Joined, Joiner};
use super::limits::{
    STUDENT_BURST, STUDENT_RATE, TEACHER_BURST, TEACHER_RATE, Throttle, TokenBucket,
};
use super::session::{error_frame, frame};
use crate::class::protocol::{
    ClientMessage, MAX_MESSAGE_BYTES, ProtocolError, ServerMessage, parse_client,
};
use axum::extract::ws::{Message, Utf8Bytes, WebSocket};
use futures_util::{SinkExt, StreamExt};
use std::net::IpAddr;
use std::sync::Arc;
use std::time::{Duration, Instant};
use tokio::sync::broadcast::{self, error::RecvError, error::TryRecvError};

/// The most queued broadcasts written before one flush.
const BATCH: usize = 64;

/// The most batches waiting for the writer: past them the reader waits too, the session's
/// broadcasts queue up behind, and a connection that falls that far behind gets the snapshot.
const WRITES_WAITING: usize = 16;

/// How long the writer may take to say goodbye (a Close frame) to a peer that stopped reading.
const CLOSE_WAIT: Duration = Duration::from_secs(5);

/// What the reader hands the writer.
enum Write {
    /// Frames to write, flushed once.
    Frames(Vec<Utf8Bytes>),
    /// A Close frame, then the end.
    Close,
}

/// A connection's own state.
struct Conn {
    /// The server's sessions.
    hub: Arc<Hub>,
    /// The peer's address (failed joins are counted per address).
    ip: IpAddr,
    /// Who joined, once someone has.
    joiner: Option<Joiner>,
    /// The session's messages for them.
    subscription: Option<broadcast::Receiver<Utf8Bytes>>,
    /// Messages a second.
    bucket: TokenBucket,
    /// The "rate limit" error, at most once a second.
    throttle: Throttle,
    /// The connection ends after this round.
    closing: bool,
}

/// What woke the connection.
enum Event {
    /// A frame from the peer (or its end).
    Frame(Option<Result<Message, axum::Error>>),
    /// A broadcast of the session.
    Broadcast(Result<Utf8Bytes, RecvError>),
    /// The server stops.
    Shutdown,
}

/// Serves one WebSocket connection from `ip` until it closes or the server stops: this task
/// reads, a second one ([`writer`]) writes.
pub(crate) async fn connection(socket: WebSocket, ip: IpAddr, hub: Arc<Hub>) {
    let _alive = hub.connections.clone();
    let mut shutdown = hub.shutdown.clone();
    let (sink, mut stream) = socket.split();
    let (to_writer, writes) = tokio::sync::mpsc::channel(WRITES_WAITING);
    let mut writing = tokio::spawn(writer(sink, writes));
    let mut conn = Conn {
        hub,
        ip,
        joiner: None,
        subscription: None,
        bucket: TokenBucket::new(STUDENT_RATE, STUDENT_BURST, Instant::now()),
        throttle: Throttle::new(Duration::from_secs(1)),
        closing: false,
    };
    loop {
        let event = tokio::select! {
            f = stream.next() => Event::Frame(f),
            b = next_broadcast(&mut conn.subscription) => Event::Broadcast(b),
            _ = shutdown.wait_for(|stop| *stop) => Event::Shutdown,
        };
        let out = match event {
            Event::Frame(None | Some(Err(_))) => break,
            Event::Frame(Some(Ok(m))) => conn.on_frame(m).await,
            Event::Broadcast(b) => conn.on_broadcast(b),
            Event::Shutdown => {
                conn.closing = true;
                Vec::new()
            }
        };
        // the writer gone means the peer is: its socket failed
        if !out.is_empty() && to_writer.send(Write::Frames(out)).await.is_err() {
            break;
        }
        if conn.closing {
            let _ = to_writer.send(Write::Close).await;
            break;
        }
    }
    if let Some(Joiner::Student(session, number)) = &conn.joiner {
        session.student_left(*number);
    }
    drop(to_writer);
    if tokio::time::timeout(CLOSE_WAIT, &mut writing)
        .await
        .is_err()
    {
        writing.abort();
    }
}

/// Writes what the reader hands over, in order, until a Close, the reader's end or a failed
/// write.
async fn writer<S>(mut sink: S, mut writes: tokio::sync::mpsc::Receiver<Write>)
where
    S: futures_util::Sink<Message, Error = axum::Error> + Unpin,
{
    while let Some(w) = writes.recv().await {
        match w {
            Write::Frames(frames) => {
                if write_all(&mut sink, frames).await.is_err() {
                    return;
                }
            }
            Write::Close => {
                let _ = sink.send(Message::Close(None)).await;
                return;
            }
        }
    }
}

/// The next broadcast, or never before the join.
async fn next_broadcast(
    sub: &mut Option<broadcast::Receiver<Utf8Bytes>>,
) -> Result<Utf8Bytes, RecvError> {
    match sub {
        Some(rx) => rx.recv().await,
        None => std::future::pending().await,
    }
}

/// Writes `frames` and flushes once.
async fn write_all<S>(sink: &mut S, frames: Vec<Utf8Bytes>) -> Result<(), axum::Error>
where
    S: futures_util::Sink<Message, Error = axum::Error> + Unpin,
{
    if frames.is_empty() {
        return Ok(());
    }
    for f in frames {
        sink.feed(Message::Text(f)).await?;
    }
    sink.flush().await
}

impl Conn {
    /// A broadcast, with whatever else is queued behind it; a connection that fell behind
    /// gets the snapshot instead of what it missed.
    fn on_broadcast(&mut self, first: Result<Utf8Bytes, RecvError>) -> Vec<Utf8Bytes> {
        match first {
            Ok(f) => {
                let mut out = vec![f];
                if let Some(rx) = &mut self.subscription {
                    while out.len() < BATCH {
                        match rx.try_recv() {
                            Ok(f) => out.push(f),
                            Err(TryRecvError::Lagged(_)) => return self.snapshot(),
                            Err(_) => break,
                        }
                    }
                }
                out
            }
            Err(RecvError::Lagged(_)) => self.snapshot(),
            Err(RecvError::Closed) => {
                self.closing = true;
                Vec::new()
            }
        }
    }

    /// What the joiner must see now (after falling behind).
    fn snapshot(&self) -> Vec<Utf8Bytes> {
        match &self.joiner {
            Some(Joiner::Teacher(s)) => s.teacher_snapshot(&s.lock()),
            Some(Joiner::Student(s, _)) => s.student_snapshot(&s.lock()),
            None => Vec::new(),
        }
    }

    /// One frame from the peer: rate-limited, then read.
    async fn on_frame(&mut self, m: Message) -> Vec<Utf8Bytes> {
        match m {
            Message::Text(t) => {
                if !self.bucket.take(Instant::now()) {
                    return self.limited();
                }
                self.on_text(t.as_str()).await
            }
            Message::Binary(_) => {
                if !self.bucket.take(Instant::now()) {
                    return self.limited();
                }
                vec![error_frame(
                    "binary frames are not part of the protocol: send JSON text frames",
                )]
            }
            Message::Close(_) => {
                self.closing = true;
                Vec::new()
            }
            Message::Ping(_) | Message::Pong(_) => Vec::new(),
        }
    }

    /// A message over the rate limit: dropped, the error at most once a second.
    fn limited(&mut self) -> Vec<Utf8Bytes> {
        if !self.throttle.allow(Instant::now()) {
            return Vec::new();
        }
        let (rate, burst) = match self.joiner {
            Some(Joiner::Teacher(_)) => (TEACHER_RATE, TEACHER_BURST),
            _ => (STUDENT_RATE, STUDENT_BURST),
        };
        vec![error_frame(format!(
            "rate limit: at most {rate} messages a second (bursts of {burst}); messages over \
             it are dropped"
        ))]
    }

    /// A text frame: read, then dispatched by who sent it.
    async fn on_text(&mut self, text: &str) -> Vec<Utf8Bytes> {
        let teacher = matches!(self.joiner, Some(Joiner::Teacher(_)));
        if !teacher && text.len() > MAX_MESSAGE_BYTES {
            // Only the teacher may send a model file: anyone else's long message is refused
            // before it is read.
            let e = ProtocolError::Oversized {
                bytes: text.len(),
                limit: MAX_MESSAGE_BYTES,
            };
            return vec![error_frame(e.to_string())];
        }
        let message = match parse_client(text) {
            Ok(m) => m,
            Err(e) => return vec![error_frame(e.to_string())],
        };
        match (self.joiner.clone(), message) {
            (None, ClientMessage::Join(j)) => self.join(j).await,
            (None, m) => vec![error_frame(format!(
                "the first message must be a join ({{\"type\": \"join\", ...}}), not {:?}",
                m.type_name()
            ))],
            (Some(_), ClientMessage::Join(_)) => {
                vec![error_frame("already joined: one join per connection")]
            }
            (Some(Joiner::Student(s, number)), m) => match m {
                ClientMessage::Answer { id, answer } => s.answer(number, id, answer).await,
                ClientMessage::Leave => {
                    self.closing = true;
                    Vec::new()
                }
                _ => vec![error_frame("students may send only join, answer and leave")],
            },
            (Some(Joiner::Teacher(s)), m) => self.teacher(&s, m).await,
        }
    }

    /// The join: the welcome and the snapshot, or why not.
    async fn join(&mut self, join: crate::class::protocol::Join) -> Vec<Utf8Bytes> {
        match self.hub.join(join, self.ip).await {
            Ok(Joined {
                joiner,
                subscription,
                frames,
            }) => {
                if matches!(joiner, Joiner::Teacher(_)) {
                    self.bucket
                        .reset(TEACHER_RATE, TEACHER_BURST, Instant::now());
                }
                self.joiner = Some(joiner);
                self.subscription = Some(subscription);
                frames
            }
            Err(e) => vec![error_frame(e)],
        }
    }

    /// One of the teacher's messages.
    async fn teacher(&mut self, s: &super::session::Session, m: ClientMessage) -> Vec<Utf8Bytes> {
        let done = match m {
            ClientMessage::State { state } => s.set_state(state),
            ClientMessage::Model { name, text } => s.add_model(name, text).await,
            ClientMessage::Question(req) => s.ask(req).await,
            ClientMessage::Close { id } => s.close(id).await,
            ClientMessage::Show { id } => s.show(id),
            ClientMessage::Follow => {
                s.follow();
                Ok(())
            }
            ClientMessage::Export => {
                return vec![frame(&ServerMessage::Export { csv: s.export() })];
            }
            ClientMessage::Leave => {
                self.closing = true;
                Ok(())
            }
            ClientMessage::Answer { .. } => Err("the teacher does not answer questions".into()),
            ClientMessage::Join(_) => Err("already joined: one join per connection".into()),
        };
        match done {
            Ok(()) => Vec::new(),
            Err(e) => vec![error_frame(e)],
        }
    }
}
