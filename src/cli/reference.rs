//! The command-line reference in Markdown, generated from the parser's own definitions (clap),
//! so that the guide's chapter cannot drift from the flags: `tests/cli/cli_reference.rs` checks that
//! `docs/src/cli.md` holds exactly this below its marker line.

use super::Cli;
use clap::{Arg, Command, CommandFactory};
use std::fmt::Write as _;

/// The marker line in `docs/src/cli.md` under which the generated reference stands.
pub const MARKER: &str = "<!-- generated from the parser by tests/cli/cli_reference.rs: UPDATE_DOCS=1 cargo test --test cli cli_reference rewrites it; do not edit below -->";

/// The whole reference: one section per subcommand (in the parser's order), each with its
/// description, its usage line and its arguments.
pub fn markdown() -> String {
    let root = Cli::command();
    let mut out = String::new();
    let _ = writeln!(out, "## Synopsis\n\n```text");
    for sub in visible_subcommands(&root) {
        let _ = writeln!(out, "armlab {:<12} {}", sub.get_name(), first_line(sub));
    }
    let _ = writeln!(out, "```\n");
    write_arguments(&mut out, "Options of every subcommand", &root);
    for sub in visible_subcommands(&root) {
        let mut sub = sub.clone().bin_name(format!("armlab {}", sub.get_name()));
        let usage = sub.render_usage().to_string();
        let usage = usage.trim_start_matches("Usage: ");
        let _ = writeln!(out, "## armlab {}\n", sub.get_name());
        let about = sub
            .get_long_about()
            .or(sub.get_about())
            .map(ToString::to_string)
            .unwrap_or_default();
        if !about.is_empty() {
            let _ = writeln!(out, "{}\n", about.trim());
        }
        let _ = writeln!(out, "```text\n{usage}\n```\n");
        write_arguments(&mut out, "", &sub);
    }
    out
}

/// The subcommands a user sees (not `help`, not hidden ones).
fn visible_subcommands(cmd: &Command) -> impl Iterator<Item = &Command> {
    cmd.get_subcommands()
        .filter(|s| !s.is_hide_set() && s.get_name() != "help")
}

/// The first line of a command's description.
fn first_line(cmd: &Command) -> String {
    cmd.get_about()
        .map(|a| a.to_string().lines().next().unwrap_or("").to_string())
        .unwrap_or_default()
}

/// A list of `cmd`'s own arguments (not the global ones inherited from the root), under
/// `heading` if it is not empty.
fn write_arguments(out: &mut String, heading: &str, cmd: &Command) {
    let args: Vec<&Arg> = cmd
        .get_arguments()
        .filter(|a| !a.is_hide_set() && !matches!(a.get_id().as_str(), "help" | "version"))
        .filter(|a| heading.is_empty() != a.is_global_set())
        .collect();
    if args.is_empty() {
        return;
    }
    if !heading.is_empty() {
        let _ = writeln!(out, "## {heading}\n");
    }
    for a in args {
        let _ = write!(out, "- `{}`", spelling(a));
        if a.is_required_set() {
            let _ = write!(out, " (required)");
        }
        let help = a
            .get_long_help()
            .or(a.get_help())
            .map(|h| h.to_string().replace('\n', " "))
            .unwrap_or_default();
        let help = help.trim();
        if !help.is_empty() {
            let stop = if help.ends_with(['.', ')', '?']) {
                ""
            } else {
                "."
            };
            let _ = write!(out, ": {help}{stop}");
        }
        let values: Vec<String> = a
            .get_possible_values()
            .iter()
            .filter(|v| !v.is_hide_set())
            .map(|v| format!("`{}`", v.get_name()))
            .collect();
        if !values.is_empty() {
            let _ = write!(out, " One of {}.", values.join(", "));
        }
        let defaults: Vec<String> = a
            .get_default_values()
            .iter()
            .map(|v| v.to_string_lossy().into_owned())
            .collect();
        if !defaults.is_empty() && a.get_action().takes_values() {
            let _ = write!(out, " Default: `{}`.", defaults.join(","));
        }
        let _ = writeln!(out);
    }
    let _ = writeln!(out);
}

/// How an argument is written: `--name <VALUE>`, `-s, --name`, or `<NAME>` for a positional.
fn spelling(a: &Arg) -> String {
    let value = || {
        a.get_value_names()
            .map(|v| {
                v.iter()
                    .map(|n| format!("<{n}>"))
                    .collect::<Vec<_>>()
                    .join(" ")
            })
            .unwrap_or_else(|| format!("<{}>", a.get_id().as_str().to_uppercase()))
    };
    if a.is_positional() {
        return value();
    }
    let takes_value = a.get_action().takes_values();
    let mut names = Vec::new();
    if let Some(s) = a.get_short() {
        names.push(format!("-{s}"));
    }
    if let Some(l) = a.get_long() {
        names.push(format!("--{l}"));
    }
    let mut s = names.join(", ");
    if takes_value {
        s.push(' ');
        s.push_str(&value());
    }
    s
}
