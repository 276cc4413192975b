//! Load benchmark of the class server (issue 50): 200 students and a teacher on loopback, the
//! teacher sending 30 states a second for 60 s. Reports the delay from the teacher's send to
//! each student's receipt (p50, p95, max), the messages each student expected and got (every
//! seq 1..N, none lost), and the server's CPU and peak memory.
//!
//! The server is `target/release/armlab class serve --port 0` as a process of its own (build it
//! first: `cargo build --release`), so that its CPU and memory are its own; without that binary
//! the server runs in this process (and the CPU and memory include the clients').
//!
//! ```text
//! cargo bench --bench class_load
//! ARMLAB_LOAD_SECONDS=20 ARMLAB_LOAD_STUDENTS=200 cargo bench --bench class_load
//! ```
//!
//! Not a timed test: the numbers go into the README by hand.

use armlab::class::protocol::{
    ClassState, ClientMessage, Join, RobotRef, Role, ServerMessage, parse_server,
};
use futures_util::{SinkExt, StreamExt};
use std::io::BufRead;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};
use tokio_tungstenite::connect_async;
use tokio_tungstenite::tungstenite::Message;

/// States a second.
const RATE: u64 = 30;

/// What the benchmark runs against.
struct Target {
    /// host:port.
    hostport: String,
    /// The teacher token.
    token: String,
    /// The join code.
    code: String,
    /// The server's process id (this process for the in-process server).
    pid: u32,
    /// What it is, in words.
    what: String,
    /// The child process, if one.
    child: Option<std::process::Child>,
    /// The in-process server, if that.
    _in_process: Option<armlab::class_server::ServerHandle>,
}

/// The release binary, if it is there (`ARMLAB_BIN` names another).
fn binary() -> Option<PathBuf> {
    let path = std::env::var_os("ARMLAB_BIN")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/release/armlab"));
    path.is_file().then_some(path)
}

/// The value after `key=` in a link.
fn query_value(url: &str, key: &str) -> String {
    url.split_once(&format!("?{key}="))
        .map(|(_, v)| v.trim().to_string())
        .unwrap_or_default()
}

/// Starts the server: the release binary as a process, else in this process.
fn start_server(data: PathBuf) -> Target {
    if let Some(bin) = binary() {
        let mut child = std::process::Command::new(&bin)
            .args(["class", "serve", "--port", "0", "--data"])
            .arg(&data)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::null())
            .spawn()
            .expect("the server binary runs");
        let mut out = std::io::BufReader::new(child.stdout.take().expect("stdout"));
        let (mut teacher, mut students) = (String::new(), String::new());
        out.read_line(&mut teacher).expect("the teacher line");
        out.read_line(&mut students).expect("the students line");
        std::thread::spawn(move || {
            let mut line = String::new();
            while out.read_line(&mut line).is_ok_and(|n| n > 0) {
                line.clear();
            }
        });
        let hostport = teacher
            .trim()
            .trim_start_matches("teacher: http://")
            .split('/')
            .next()
            .unwrap_or_default()
            .to_string();
        return Target {
            hostport,
            token: query_value(&teacher, "token"),
            code: query_value(&students, "code"),
            pid: child.id(),
            what: format!("{} (process {})", bin.display(), child.id()),
            child: Some(child),
            _in_process: None,
        };
    }
    let server = armlab::class_server::start(armlab::class_server::ServerOptions {
        port: 0,
        data,
        ..Default::default()
    })
    .expect("the in-process server starts");
    Target {
        hostport: server.addr.to_string(),
        token: server.token.clone(),
        code: server.code.clone(),
        pid: std::process::id(),
        what: "in this process (no target/release/armlab: CPU and memory include the clients)"
            .into(),
        child: None,
        _in_process: Some(server),
    }
}

/// A process's CPU time (user + system, s) from /proc.
fn cpu_seconds(pid: u32) -> Option<f64> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // The fields after the command's closing parenthesis; utime and stime are the 14th and
    // 15th of the whole line, the 12th and 13th after it.
    let rest = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let ticks: f64 = fields.get(11)?.parse::<f64>().ok()? + fields.get(12)?.parse::<f64>().ok()?;
    Some(ticks / clock_ticks())
}

/// Clock ticks a second (`getconf CLK_TCK`, else 100).
fn clock_ticks() -> f64 {
    std::process::Command::new("getconf")
        .arg("CLK_TCK")
        .output()
        .ok()
        .and_then(|o| String::from_utf8_lossy(&o.stdout).trim().parse().ok())
        .unwrap_or(100.0)
}

/// A process's peak resident memory (VmHWM, MB).
fn peak_memory_mb(pid: u32) -> Option<f64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}

/// What one student saw: each state's seq and its delay (µs).
#[derive(Default)]
struct Seen {
    /// Seqs received, in order.
    seqs: Vec<u64>,
    /// Delays (µs).
    delays: Vec<u64>,
}

/// A join message.
fn join(role: Role, token: Option<String>, code: Option<String>, name: Option<String>) -> String {
    ClientMessage::Join(Join {
        role,
        token,
        code,
        name,
        resume: None,
    })
    .to_text()
}

/// One student: joins, then records every state until seq `n` (or `deadline`).
async fn student(
    hostport: String,
    code: String,
    k: usize,
    n: u64,
    epoch: Instant,
    sent: Arc<Vec<std::sync::atomic::AtomicU64>>,
    deadline: tokio::time::Instant,
) -> Seen {
    let (mut ws, _) = connect_async(format!("ws://{hostport}/ws"))
        .await
        .expect("connects");
    let name = Some(format!("student {k}"));
    ws.send(Message::text(join(Role::Student, None, Some(code), name)))
        .await
        .expect("joins");
    let mut seen = Seen::default();
    while let Ok(Some(Ok(m))) = tokio::time::timeout_at(deadline, ws.next()).await {
        let Message::Text(t) = m else { continue };
        let at = epoch.elapsed().as_micros() as u64;
        if let Ok(ServerMessage::State { seq, .. }) = parse_server(t.as_str()) {
            let Some(s) = sent.get(seq as usize) else {
                continue;
            };
            let s = s.load(std::sync::atomic::Ordering::Acquire);
            seen.seqs.push(seq);
            seen.delays.push(at.saturating_sub(s));
            if seq >= n {
                break;
            }
        }
    }
    seen
}

/// The teacher: joins, waits for the students, sends `n` states at [`RATE`] a second, each
/// state's send time (µs since `epoch`) noted under its seq.
async fn teacher(
    hostport: String,
    token: String,
    n: u64,
    epoch: Instant,
    sent: Arc<Vec<std::sync::atomic::AtomicU64>>,
    joined: usize,
) {
    let (mut ws, _) = connect_async(format!("ws://{hostport}/ws"))
        .await
        .expect("connects");
    ws.send(Message::text(join(Role::Teacher, Some(token), None, None)))
        .await
        .expect("joins");
    // Wait for the roster to count every student (at most 60 s).
    let until = tokio::time::Instant::now() + Duration::from_secs(60);
    while let Ok(Some(Ok(Message::Text(t)))) = tokio::time::timeout_at(until, ws.next()).await {
        if let Ok(ServerMessage::Roster { joined: j, .. }) = parse_server(t.as_str())
            && j >= joined
        {
            break;
        }
    }
    let (mut tx, mut rx) = ws.split();
    // Drain the teacher's own messages (rosters) so the server never waits on this socket.
    tokio::spawn(async move { while let Some(Ok(_)) = rx.next().await {} });
    let mut tick = tokio::time::interval(Duration::from_micros(1_000_000 / RATE));
    for seq in 1..=n {
        tick.tick().await;
        let q = vec![seq as f64 * 1e-3, 0.1, -0.2, 0.3, 0.4, -0.5];
        let state = ClassState {
            robot: RobotRef::Builtin("puma560".into()),
            q,
            view: Default::default(),
            lesson: None,
        };
        let text = ClientMessage::State { state }.to_text();
        sent[seq as usize].store(
            epoch.elapsed().as_micros() as u64,
            std::sync::atomic::Ordering::Release,
        );
        tx.send(Message::text(text)).await.expect("sends");
    }
    // Keep the connection until the students are done.
    tokio::time::sleep(Duration::from_secs(3)).await;
}

/// The p-th percentile (0..=100) of sorted values.
fn percentile(sorted: &[u64], p: f64) -> u64 {
    if sorted.is_empty() {
        return 0;
    }
    let i = ((p / 100.0) * (sorted.len() - 1) as f64).round() as usize;
    sorted[i.min(sorted.len() - 1)]
}

/// The environment variable `name` as a number, else `default`.
fn env_or(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn main() {
    // `cargo bench` passes `--bench`; nothing else is taken.
    let seconds = env_or("ARMLAB_LOAD_SECONDS", 60);
    let students = env_or("ARMLAB_LOAD_STUDENTS", 200) as usize;
    let n = seconds * RATE;
    let dir = std::env::temp_dir().join(format!("armlab-class-load-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let mut target = start_server(dir.join("load.sqlite"));
    println!(
        "class_load: {students} students, 1 teacher, {RATE} states/s for {seconds} s ({n} states)"
    );
    println!("server: {}", target.what);
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .expect("a runtime");
    let (seen, wall, cpu) = runtime.block_on(run(&target, students, n));
    report(&seen, n, wall, cpu, peak_memory_mb(target.pid));
    if let Some(child) = &mut target.child {
        let _ = child.kill();
        let _ = child.wait();
    }
    drop(target);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Connects everyone, runs the teacher, collects what each student saw; the wall time of the
/// sending and the server's CPU seconds over it.
async fn run(target: &Target, students: usize, n: u64) -> (Vec<Seen>, f64, Option<f64>) {
    let epoch = Instant::now();
    let sent: Arc<Vec<std::sync::atomic::AtomicU64>> = Arc::new(
        (0..=n)
            .map(|_| std::sync::atomic::AtomicU64::new(0))
            .collect(),
    );
    let deadline = tokio::time::Instant::now() + Duration::from_secs(n / RATE + 90);
    let mut tasks = Vec::new();
    for k in 1..=students {
        tasks.push(tokio::spawn(student(
            target.hostport.clone(),
            target.code.clone(),
            k,
            n,
            epoch,
            sent.clone(),
            deadline,
        )));
    }
    let cpu0 = cpu_seconds(target.pid);
    let start = Instant::now();
    let t = tokio::spawn(teacher(
        target.hostport.clone(),
        target.token.clone(),
        n,
        epoch,
        sent.clone(),
        students,
    ));
    let mut seen = Vec::new();
    for task in tasks {
        seen.push(task.await.expect("a student task"));
    }
    let wall = start.elapsed().as_secs_f64();
    let cpu = cpu0.zip(cpu_seconds(target.pid)).map(|(a, b)| b - a);
    let _ = t.await;
    (seen, wall, cpu)
}

/// The table.
fn report(seen: &[Seen], n: u64, wall: f64, cpu: Option<f64>, memory: Option<f64>) {
    let mut delays: Vec<u64> = seen.iter().flat_map(|s| s.delays.iter().copied()).collect();
    delays.sort_unstable();
    let complete = |s: &Seen| s.seqs.len() as u64 == n && s.seqs.iter().copied().eq(1..=n);
    let lost: u64 = seen
        .iter()
        .map(|s| n.saturating_sub(s.seqs.len() as u64))
        .sum();
    let incomplete = seen.iter().filter(|s| !complete(s)).count();
    let min = seen.iter().map(|s| s.seqs.len()).min().unwrap_or(0);
    let max = seen.iter().map(|s| s.seqs.len()).max().unwrap_or(0);
    let ms = |us: u64| format!("{:.2} ms", us as f64 / 1000.0);
    let rows = [
        ("states received (all students)", delays.len().to_string()),
        (
            "delay p50 (teacher send -> student)",
            ms(percentile(&delays, 50.0)),
        ),
        ("delay p95", ms(percentile(&delays, 95.0))),
        ("delay max", ms(delays.last().copied().unwrap_or(0))),
        ("expected per student", n.to_string()),
        ("received per student (min / max)", format!("{min} / {max}")),
        (
            "lost (all students) / students with a gap",
            format!("{lost} / {incomplete}"),
        ),
        (
            "server CPU (user + system, % of one core)",
            cpu.map_or("not measured".into(), |c| {
                format!("{:.1} % over {wall:.1} s", 100.0 * c / wall)
            }),
        ),
        (
            "server peak memory (VmHWM)",
            memory.map_or("not measured".into(), |m| format!("{m:.1} MB")),
        ),
    ];
    println!();
    println!("| {:<42} | value |", "measure");
    println!("|{}|-------|", "-".repeat(44));
    for (label, value) in rows {
        println!("| {label:<42} | {value} |");
    }
}
