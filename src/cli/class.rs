//! `armlab class serve`: the live classroom's server ([`crate::class_server`]). Prints the
//! teacher's and the students' links first (one line each, flushed at once, for scripts), then
//! the students' link as a QR code, how a classroom network reaches it, and serves until
//! Ctrl+C, which stops it cleanly (everything stays in the data file).

use super::CliError;
use crate::class_server::{
    self, DEFAULT_DATA, DEFAULT_PORT, ServerError, ServerHandle, ServerOptions,
};
use clap::Subcommand;
use std::io::Write;
use std::net::{IpAddr, Ipv4Addr};
use std::path::PathBuf;
use std::time::Duration;

/// `armlab class ...`.
#[derive(Debug, clap::Args)]
pub struct ClassArgs {
    /// What to do.
    #[command(subcommand)]
    pub action: ClassAction,
}

/// The class subcommands.
#[derive(Debug, Subcommand)]
pub enum ClassAction {
    /// Serve a live class: the web build, and class sessions over WebSockets (the teacher's
    /// view followed by every student, questions answered from the seats and graded on the
    /// server); everything kept in an SQLite file. Ctrl+C stops it.
    Serve(ServeArgs),
    /// Rehearse a class alone: a server on this computer, the teacher's app joined to it, and
    /// simulated students who follow and answer (right, or with the mistakes students make);
    /// with --screenshot / --student-screenshot, the windows rendered to PNG instead.
    Demo(super::class_demo::DemoArgs),
}

/// Arguments of `armlab class serve`.
#[derive(Debug, clap::Args)]
pub struct ServeArgs {
    /// The address to listen on: 127.0.0.1 is this computer only; 0.0.0.0 lets a classroom
    /// network reach it.
    #[arg(long, default_value_t = IpAddr::V4(Ipv4Addr::LOCALHOST), value_name = "ADDR")]
    pub bind: IpAddr,
    /// The port (0: any free one; the links name it).
    #[arg(long, default_value_t = DEFAULT_PORT, value_name = "N")]
    pub port: u16,
    /// The SQLite file of sessions, questions and answers (made if missing; kept across
    /// restarts).
    #[arg(long, default_value = DEFAULT_DATA, value_name = "FILE.sqlite")]
    pub data: PathBuf,
    /// The web build's folder (holding index.html; default: web/dist if it exists).
    #[arg(long, value_name = "DIR")]
    pub web: Option<PathBuf>,
    /// The teacher sees the students' nicknames (otherwise numbers only).
    #[arg(long)]
    pub show_names: bool,
    /// Start a new session even if the data file holds one (the others are kept, their links
    /// still work).
    #[arg(long)]
    pub new: bool,
}

/// Runs `armlab class ...`.
pub fn run(args: &ClassArgs, out: &mut dyn Write) -> Result<(), CliError> {
    match &args.action {
        ClassAction::Serve(a) => serve(a, out),
        ClassAction::Demo(a) => super::class_demo::run(a, out),
    }
}

/// `armlab class serve`: starts the server, prints the links, waits for Ctrl+C.
fn serve(args: &ServeArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let server = class_server::start(ServerOptions {
        bind: args.bind,
        port: args.port,
        data: args.data.clone(),
        web: args.web.clone(),
        show_names: args.show_names,
        new_session: args.new,
    })?;
    print_links(&server, &args.data, out)?;
    wait_for_ctrl_c(&server)?;
    server.stop()?;
    writeln!(
        out,
        "stopped; everything is kept in {}",
        args.data.display()
    )?;
    Ok(())
}

/// The links (flushed at once), the QR code, the network hint, how to stop.
fn print_links(
    server: &ServerHandle,
    data: &std::path::Path,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    writeln!(out, "teacher: {}", server.teacher_url)?;
    writeln!(out, "students: {}", server.student_url)?;
    out.flush()?;
    for w in &server.warnings {
        eprintln!("armlab: warning: {w}");
    }
    write!(out, "{}", class_server::qr::terminal(&server.qr))?;
    writeln!(out, "{}", server.network_hint)?;
    writeln!(
        out,
        "Ctrl+C stops the server (everything is kept in {})",
        data.display()
    )?;
    out.flush()?;
    Ok(())
}

/// Waits for Ctrl+C (or for the server to end on its own, after an error).
fn wait_for_ctrl_c(server: &ServerHandle) -> Result<(), CliError> {
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .map_err(|source| ServerError::Runtime { source })?;
    let waited = runtime.block_on(async {
        let ctrl_c = tokio::signal::ctrl_c();
        tokio::pin!(ctrl_c);
        loop {
            tokio::select! {
                r = &mut ctrl_c => return r,
                _ = tokio::time::sleep(Duration::from_millis(500)) => {
                    if !server.is_running() {
                        return Ok(());
                    }
                }
            }
        }
    });
    waited.map_err(|source| ServerError::Runtime { source })?;
    Ok(())
}
