//! The `armlab` binary: parses the command line and reports errors. Bad input exits with code 2
//! and one line on stderr.

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = armlab::cli::Cli::parse();
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    let result: anyhow::Result<()> = armlab::cli::run(cli, &mut out).map_err(anyhow::Error::from);
    match result.and_then(|()| std::io::Write::flush(&mut out).map_err(anyhow::Error::from)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("armlab: error: {e:#}");
            ExitCode::from(2)
        }
    }
}
