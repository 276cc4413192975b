//! The guide's command-line reference (`docs/src/cli.md`, below its marker line) is exactly what
//! the parser generates (`armlab::cli::reference::markdown`), so it cannot drift from the flags.
//! `UPDATE_DOCS=1 cargo test --test cli cli_reference` rewrites it.

use armlab::cli::reference::{MARKER, markdown};

#[test]
fn the_guide_holds_the_generated_reference() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/src/cli.md");
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let Some((head, body)) = text.split_once(&format!("{MARKER}\n")) else {
        panic!("{path} has no marker line {MARKER:?}");
    };
    let generated = markdown();
    if std::env::var_os("UPDATE_DOCS").is_some() {
        std::fs::write(path, format!("{head}{MARKER}\n\n{generated}"))
            .unwrap_or_else(|e| panic!("{path}: {e}"));
        return;
    }
    assert_eq!(
        body.trim(),
        generated.trim(),
        "{path} is not the reference the parser generates: run \
         `UPDATE_DOCS=1 cargo test --test cli cli_reference` and commit the chapter"
    );
}

#[test]
fn every_subcommand_and_flag_is_in_the_reference() {
    let md = markdown();
    for section in [
        "## armlab robots",
        "## armlab info",
        "## armlab fk",
        "## armlab ik",
        "## armlab workspace",
        "## armlab figure",
        "## armlab calibrate",
        "## armlab self-motion",
        "## armlab view",
    ] {
        assert!(md.contains(section), "no section {section:?}");
    }
    for flag in [
        "`--q <Q>`",
        "--package-path",
        "--format",
        "--all",
        "--hayati",
        "--rotation <REPRESENTATION>",
    ] {
        assert!(md.contains(flag), "no flag {flag:?}");
    }
}
