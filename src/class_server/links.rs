//! The links the server gives out: the teacher's (`http://HOST:PORT/?token=T`, on this
//! computer) and the students' (`http://HOST:PORT/?code=C`), and how a classroom network
//! reaches the server, in words.

use super::session::Session;
use std::net::{IpAddr, Ipv4Addr, Ipv6Addr, SocketAddr, UdpSocket};

/// The links of a listening server and its newest session.
#[derive(Debug, Clone)]
pub(crate) struct Links {
    /// The address listened on.
    pub(crate) addr: SocketAddr,
    /// The host the teacher's link names (this computer).
    teacher_host: String,
    /// The host the students' link names: the address listened on; for every interface
    /// (0.0.0.0), this computer's address on its network where it can be found, else
    /// 127.0.0.1.
    student_host: String,
    /// The newest session's teacher link.
    pub(crate) teacher_url: String,
    /// Its students' link.
    pub(crate) student_url: String,
    /// Its token.
    pub(crate) token: String,
    /// Its join code.
    pub(crate) code: String,
    /// Its students' link as QR rows.
    pub(crate) qr: Vec<String>,
}

/// `ip` as the host of a URL (IPv6 in brackets).
fn host(ip: IpAddr) -> String {
    match ip {
        IpAddr::V4(v4) => v4.to_string(),
        IpAddr::V6(v6) => format!("[{v6}]"),
    }
}

/// This computer's address on its network, as the operating system would route to another
/// machine: a UDP socket "connected" to a documentation address (TEST-NET-1) tells its local
/// address; a UDP connect sends nothing. `None` without a network.
fn network_address() -> Option<IpAddr> {
    let socket = UdpSocket::bind((Ipv4Addr::UNSPECIFIED, 0)).ok()?;
    socket.connect((Ipv4Addr::new(192, 0, 2, 1), 9)).ok()?;
    let ip = socket.local_addr().ok()?.ip();
    (!ip.is_loopback() && !ip.is_unspecified()).then_some(ip)
}

impl Links {
    /// The links of a server listening on `addr` (the session's parts filled in by
    /// [`Self::set_newest`]).
    pub(crate) fn new(addr: SocketAddr) -> Self {
        let (teacher_ip, student_ip) = match addr.ip() {
            IpAddr::V4(v4) if v4.is_unspecified() => {
                let local = IpAddr::V4(Ipv4Addr::LOCALHOST);
                (local, network_address().unwrap_or(local))
            }
            IpAddr::V6(v6) if v6.is_unspecified() => {
                let local = IpAddr::V6(Ipv6Addr::LOCALHOST);
                (local, network_address().unwrap_or(local))
            }
            ip => (ip, ip),
        };
        Self {
            addr,
            teacher_host: host(teacher_ip),
            student_host: host(student_ip),
            teacher_url: String::new(),
            student_url: String::new(),
            token: String::new(),
            code: String::new(),
            qr: Vec::new(),
        }
    }

    /// The students' link of join code `code`.
    pub(crate) fn student_url(&self, code: &str) -> String {
        format!(
            "http://{}:{}/?code={code}",
            self.student_host,
            self.addr.port()
        )
    }

    /// Takes the newest session's links.
    pub(crate) fn set_newest(&mut self, s: &Session) {
        self.teacher_url = format!(
            "http://{}:{}/?token={}",
            self.teacher_host,
            self.addr.port(),
            s.token
        );
        self.student_url = s.student_url.clone();
        self.token = s.token.clone();
        self.code = s.code.clone();
        self.qr = s.qr.clone();
    }

    /// How students on a classroom network reach the server, in words.
    pub(crate) fn network_hint(&self) -> String {
        let port = self.addr.port();
        let ip = self.addr.ip();
        if ip.is_loopback() {
            format!(
                "This server answers on this computer only. For a classroom network, start it \
                 with --bind 0.0.0.0 and give students http://<this computer's address>:{port}/?code={}",
                self.code
            )
        } else if ip.is_unspecified() {
            format!(
                "Students on the classroom network open http://<this computer's address>:{port}/?code={} \
                 (the students' link above uses {}: if it is not the address the classroom \
                 network sees, give them the right one).",
                self.code, self.student_host
            )
        } else {
            format!("Students on the network open {}", self.student_url)
        }
    }
}
