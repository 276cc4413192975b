//! The `armlab` binary: parses the command line and reports errors. Bad input exits with code 2
//! and one line on stderr.

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    quiet_graphics_environment();
    let cli = armlab::cli::Cli::parse();
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    let result: anyhow::Result<()> = armlab::cli::run(cli, &mut out).map_err(anyhow::Error::from);
    match result.and_then(|()| std::io::Write::flush(&mut out).map_err(anyhow::Error::from)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if is_broken_pipe(&e) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("armlab: error: {}", one_line(&e));
            ExitCode::from(2)
        }
    }
}

/// The error and its causes on one line, each cause only where the text so far does not
/// already say it (typed errors often print their source themselves).
fn one_line(e: &anyhow::Error) -> String {
    let mut line = String::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if line.is_empty() {
            line = text;
        } else if !line.contains(&text) {
            line.push_str(": ");
            line.push_str(&text);
        }
    }
    line
}

/// Output piped into a program that stopped reading (`armlab info big.toml | head`): not an
/// error of armlab's, so it ends quietly as other command-line tools do.
fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.chain().any(|c| {
        c.downcast_ref::<std::io::Error>()
            .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
    })
}

/// Gives the graphics stack a private runtime directory when `XDG_RUNTIME_DIR` is unset or not
/// a directory. Mesa's Vulkan device-select layer asks libwayland for a display whenever an
/// instance enables the Wayland surface extension (wgpu always does), and libwayland prints
/// `error: XDG_RUNTIME_DIR is invalid or not set in the environment.` on stderr although
/// nothing failed. With a private, empty directory it finds no socket and stays quiet.
#[cfg(unix)]
#[allow(unsafe_code)]
fn quiet_graphics_environment() {
    let valid = std::env::var_os("XDG_RUNTIME_DIR")
        .filter(|d| !d.is_empty())
        .is_some_and(|d| std::path::Path::new(&d).is_dir());
    if valid {
        return;
    }
    let Some(dir) = private_runtime_dir() else {
        return;
    };
    // SAFETY: called first thing in `main`, before any other thread exists, so nothing reads the
    // environment concurrently.
    unsafe { std::env::set_var("XDG_RUNTIME_DIR", dir) };
}

#[cfg(not(unix))]
fn quiet_graphics_environment() {}

/// `$TMPDIR/armlab-runtime-<uid>`, created with mode 0700 if missing; `None` if it cannot be
/// made or belongs to another user.
#[cfg(unix)]
fn private_runtime_dir() -> Option<std::path::PathBuf> {
    use std::os::unix::fs::{DirBuilderExt, MetadataExt};
    let uid = std::fs::metadata("/proc/self").ok()?.uid();
    let dir = std::env::temp_dir().join(format!("armlab-runtime-{uid}"));
    if !dir.is_dir() {
        std::fs::DirBuilder::new().mode(0o700).create(&dir).ok()?;
    }
    let meta = std::fs::symlink_metadata(&dir).ok()?;
    (meta.is_dir() && meta.uid() == uid && meta.mode() & 0o077 == 0).then_some(dir)
}
