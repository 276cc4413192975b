//! The README's test command is exactly what CI runs (`.ci/run`), and the README's two commands
//! are where a new user looks first.

fn read(rel: &str) -> String {
    std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/").to_string() + rel)
        .unwrap_or_else(|e| panic!("{rel}: {e}"))
}

#[test]
fn ci_runs_the_readme_test_command() {
    let readme = read("README.md");
    let section = readme
        .split("## Two commands")
        .nth(1)
        .expect("README has a 'Two commands' section");
    let blocks: Vec<&str> = section
        .split("```sh\n")
        .skip(1)
        .map(|b| b.split("```").next().unwrap_or("").trim())
        .collect();
    assert!(blocks.len() >= 2, "two sh blocks: {blocks:?}");
    assert_eq!(blocks[0], "cargo run --release", "the main command");
    let test_command = blocks[1];
    assert!(
        test_command.starts_with("cargo fmt --check"),
        "{test_command}"
    );
    let ci = read(".ci/run");
    assert!(
        ci.lines().any(|l| l.trim() == test_command),
        ".ci/run does not run the README's test command:\n{test_command}"
    );
}
