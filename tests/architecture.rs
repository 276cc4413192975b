//! The layer rules of `src/`, kept by a test (DESIGN.md section 1). It scans every source file,
//! comments and string literals removed, and fails naming the file and line of each breach:
//!
//! - a compute module (`kinematics`, `workspace`, `calibration`, `redundancy`, `model_file`,
//!   `urdf`, `construction`, `mesh`, `offload`, `animation`) names egui, eframe, wgpu, winit, image or
//!   `std::fs`, or a layer above it (`scene`, `render`, `ui_render`, `figure`, `headless`, `app`,
//!   `cli`, `camera`);
//! - `render` names egui or `kinematics`;
//! - a figure module calls an IK solver, a sampler or another computation (it paints what it is
//!   handed);
//! - `mesh`, the leaf module of triangle meshes, names anything of the crate;
//! - a file of `app` other than `app/shell.rs` implements `AppUi` (the app's parts return actions
//!   and read the state; only the shell changes the window model), or `app/shell.rs` grows past
//!   [`SHELL_LINES`] lines.
//!
//! The rules are first shown to catch each kind of breach on a small fixture tree
//! (`tests/data/architecture/src`), then applied to the real `src/`.

use std::path::{Path, PathBuf};

/// Compute modules: pure math and parsing of text they are handed.
const COMPUTE: &[&str] = &[
    "kinematics",
    "workspace",
    "calibration",
    "redundancy",
    "model_file",
    "urdf",
    "construction",
    "mesh",
    "offload",
    "animation",
];

/// Crates and paths a compute module must not name.
const NOT_IN_COMPUTE: &[&str] = &[
    "egui::",
    "eframe::",
    "egui_wgpu::",
    "egui_plot::",
    "wgpu::",
    "winit::",
    "image::",
    "std::fs",
    "crate::scene",
    "crate::render",
    "crate::ui_render",
    "crate::figure",
    "crate::headless",
    "crate::app",
    "crate::cli",
    "crate::camera",
];

/// What `render` must not name.
const NOT_IN_RENDER: &[&str] = &[
    "egui::",
    "egui_wgpu::",
    "eframe::",
    "crate::kinematics",
    "crate::app",
    "crate::figure",
];

/// Calls a figure must not make: solvers, samplers and the other computations.
const NOT_CALLED_IN_FIGURES: &[&str] = &[
    "solve",
    "solve_into",
    "solve_raw",
    "solve_prepared",
    "solve_position_raw",
    "sample",
    "sample_self_motion",
    "compute_map",
    "compute_map_forming",
    "map_statistics",
    "compute_figure_data",
    "compute_figure_data_forming",
    "statistics",
    "joint_rectangle",
    "planar_boundary",
    "parse_model",
    "parse_model_text",
    "load_model",
    "calibrate",
    "simulate",
    "accuracy_map",
];

/// The most lines `src/app/shell.rs` may have: the window's layout and the one place where the
/// actions are applied; what grows beyond goes to a file of its own under `src/app`.
const SHELL_LINES: usize = 500;

/// The source with comments and the contents of string and character literals blanked out
/// (line breaks kept, so that line numbers stay).
fn code_only(text: &str) -> String {
    let c: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    let keep_newlines = |s: &[char], out: &mut String| {
        for ch in s {
            out.push(if *ch == '\n' { '\n' } else { ' ' });
        }
    };
    while i < c.len() {
        let rest = &c[i..];
        if rest.starts_with(&['/', '/']) {
            let end = rest.iter().position(|&x| x == '\n').unwrap_or(rest.len());
            keep_newlines(&rest[..end], &mut out);
            i += end;
        } else if rest.starts_with(&['/', '*']) {
            let mut depth = 0;
            let mut k = 0;
            while k < rest.len() {
                if rest[k..].starts_with(&['/', '*']) {
                    depth += 1;
                    k += 2;
                } else if rest[k..].starts_with(&['*', '/']) {
                    depth -= 1;
                    k += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    k += 1;
                }
            }
            keep_newlines(&rest[..k.min(rest.len())], &mut out);
            i += k;
        } else if rest[0] == 'r' && (rest.get(1) == Some(&'"') || rest.get(1) == Some(&'#')) {
            // A raw string r#"..."#: find its closing quote and as many hashes.
            let hashes = rest[1..].iter().take_while(|&&x| x == '#').count();
            if rest.get(1 + hashes) != Some(&'"') {
                out.push(rest[0]);
                i += 1;
                continue;
            }
            let mut k = 2 + hashes;
            while k < rest.len() {
                if rest[k] == '"'
                    && rest[k + 1..]
                        .iter()
                        .take(hashes)
                        .filter(|&&x| x == '#')
                        .count()
                        == hashes
                {
                    k += 1 + hashes;
                    break;
                }
                k += 1;
            }
            out.push('"');
            keep_newlines(&rest[1..k.saturating_sub(1).max(1)], &mut out);
            out.push('"');
            i += k;
        } else if rest[0] == '"' {
            let mut k = 1;
            while k < rest.len() && rest[k] != '"' {
                k += if rest[k] == '\\' { 2 } else { 1 };
            }
            out.push('"');
            keep_newlines(&rest[1..k.min(rest.len())], &mut out);
            out.push('"');
            i += k + 1;
        } else if rest[0] == '\'' && (rest.get(2) == Some(&'\'') || rest.get(1) == Some(&'\\')) {
            // A character literal ('x' or '\n'); a lifetime ('a) is left as it is.
            let end = rest[1..]
                .iter()
                .position(|&x| x == '\'')
                .map_or(1, |p| p + 2);
            out.push_str("' '");
            i += end;
        } else {
            out.push(rest[0]);
            i += 1;
        }
    }
    out
}

/// Every `.rs` file under `dir`, sorted.
fn sources(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap_or_else(|e| panic!("{}: {e}", d.display())) {
            let p = e.expect("a directory entry").path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "rs") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// The top-level module a file belongs to: `src/kinematics/ik/solver.rs` -> "kinematics",
/// `src/urdf.rs` -> "urdf".
fn module_of(src: &Path, file: &Path) -> String {
    let rel = file.strip_prefix(src).expect("a file under src");
    let first = rel.components().next().expect("a path component");
    let name = first.as_os_str().to_string_lossy();
    name.strip_suffix(".rs").unwrap_or(&name).to_string()
}

/// Whether `code` contains `name` as a path (not inside a longer identifier).
fn names(code: &str, name: &str) -> bool {
    code.match_indices(name).any(|(i, _)| {
        let before = code[..i].chars().next_back();
        let starts_word = name.starts_with("crate::") || name.starts_with("std::");
        starts_word || !before.is_some_and(|b| b.is_alphanumeric() || b == '_' || b == ':')
    })
}

/// Whether `code` calls `function` (as `function(`, `x.function(` or `path::function(`).
fn calls(code: &str, function: &str) -> bool {
    code.match_indices(function).any(|(i, _)| {
        let before = code[..i].chars().next_back();
        let after = code[i + function.len()..].trim_start();
        let word_start = !before.is_some_and(|b| b.is_alphanumeric() || b == '_');
        let is_definition = code[..i].trim_end().ends_with("fn");
        word_start && !is_definition && (after.starts_with('(') || after.starts_with("::<"))
    })
}

/// Every breach of the layer rules under `src`, as "file:line: what".
fn violations(src: &Path) -> Vec<String> {
    let mut out = Vec::new();
    for file in sources(src) {
        let module = module_of(src, &file);
        let text =
            std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        let code = code_only(&text);
        let rel = file
            .strip_prefix(src.parent().unwrap_or(src))
            .unwrap_or(&file);
        for (n, line) in code.lines().enumerate() {
            let mut breach =
                |what: String| out.push(format!("{}:{}: {what}", rel.display(), n + 1));
            if COMPUTE.contains(&module.as_str()) {
                for name in NOT_IN_COMPUTE {
                    if names(line, name) {
                        breach(format!("the compute module `{module}` names `{name}`"));
                    }
                }
            }
            if module == "mesh" && (line.contains("crate::") || line.contains("super::")) {
                breach("the leaf module `mesh` names another module of the crate".into());
            }
            if module == "render" {
                for name in NOT_IN_RENDER {
                    if names(line, name) {
                        breach(format!("`render` names `{name}`"));
                    }
                }
            }
            if module == "figure" {
                for f in NOT_CALLED_IN_FIGURES {
                    if calls(line, f) {
                        breach(format!(
                            "a figure calls `{f}`: figures paint what they are handed; compute \
                             it in the caller (see headless::workspace_figure)"
                        ));
                    }
                }
            }
        }
    }
    out
}

/// The type a line's `impl` block is for (`impl<T> Trait for path::Type<T> {` -> "Type"), or
/// `None` where the line opens no impl block.
fn implemented_type(line: &str) -> Option<&str> {
    let rest = line.trim_start().strip_prefix("impl")?;
    let mut head = rest.split('{').next()?;
    if head.starts_with('<') {
        // The impl's own generics: up to the matching '>'.
        let mut depth = 0;
        let end = head.char_indices().find_map(|(i, ch)| {
            depth += match ch {
                '<' => 1,
                '>' => -1,
                _ => 0,
            };
            (depth == 0).then_some(i + 1)
        })?;
        head = &head[end..];
    } else if !head.starts_with(char::is_whitespace) {
        return None; // `implies`, say
    }
    let ty = head.rsplit(" for ").next()?.split('<').next()?.trim();
    ty.rsplit("::").next().filter(|t| !t.is_empty())
}

/// Every breach of the app's rule under `app` (a `src/app` folder), as "app/file:line: what": an
/// impl block for `AppUi` in a file other than `shell.rs`, and a `shell.rs` of more than
/// `max_shell_lines` lines.
fn app_breaches(app: &Path, max_shell_lines: usize) -> Vec<String> {
    let mut out = Vec::new();
    for file in sources(app) {
        let rel = file.strip_prefix(app).expect("a file under app");
        let text =
            std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        if rel == Path::new("shell.rs") {
            let n = text.lines().count();
            if n > max_shell_lines {
                out.push(format!(
                    "app/shell.rs: {n} lines (at most {max_shell_lines})"
                ));
            }
            continue;
        }
        for (n, line) in code_only(&text).lines().enumerate() {
            if implemented_type(line) == Some("AppUi") {
                out.push(format!(
                    "app/{}:{}: an impl block for `AppUi` outside app/shell.rs",
                    rel.display(),
                    n + 1
                ));
            }
        }
    }
    out
}

#[test]
fn comments_and_strings_are_not_code() {
    let code = code_only(
        "let a = \"egui::Ui\"; // egui::Ui\n/* wgpu::\n */ let c = '\"'; let r = r#\"std::fs\"#;\nfn f<'a>(x: &'a str) {}",
    );
    assert!(!code.contains("egui"), "{code}");
    assert!(!code.contains("wgpu"), "{code}");
    assert!(!code.contains("std::fs"), "{code}");
    assert_eq!(code.lines().count(), 4, "{code}");
    assert!(code.contains("fn f<'a>(x: &'a str)"), "{code}");
}

#[test]
fn the_rules_catch_each_kind_of_breach_on_a_fixture() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/architecture/src");
    let found = violations(&src);
    let expect = [
        "src/kinematics/bad.rs:3: the compute module `kinematics` names `egui::`",
        "src/kinematics/bad.rs:7: the compute module `kinematics` names `std::fs`",
        "src/workspace.rs:2: the compute module `workspace` names `crate::scene`",
        "src/render/bad.rs:2: `render` names `crate::kinematics`",
        "src/render/bad.rs:3: `render` names `egui::`",
        "src/figure/bad.rs:5: a figure calls `solve_into`",
        "src/figure/bad.rs:6: a figure calls `sample`",
        "src/mesh.rs:1: the leaf module `mesh` names another module of the crate",
    ];
    for e in expect {
        assert!(
            found.iter().any(|f| f.starts_with(e)),
            "the fixture's breach {e:?} was not reported; reported:\n{}",
            found.join("\n")
        );
    }
    assert_eq!(
        found.len(),
        expect.len(),
        "the fixture's clean lines (comments, strings, definitions) were reported:\n{}",
        found.join("\n")
    );
}

#[test]
fn src_keeps_the_layer_rules() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let found = violations(&src);
    assert!(
        found.is_empty(),
        "{} breach(es) of the layer rules:\n{}",
        found.len(),
        found.join("\n")
    );
}

#[test]
fn impl_blocks_are_told_by_their_type() {
    for (line, ty) in [
        ("impl AppUi {", Some("AppUi")),
        ("    impl super::shell::AppUi {", Some("AppUi")),
        ("impl Default for AppUi {", Some("AppUi")),
        ("impl<'a> From<&'a AppUi> for Settings {", Some("Settings")),
        ("impl<T: Into<f64>> Wrapper<T> {", Some("Wrapper")),
        ("impl AppUiParts {", Some("AppUiParts")),
        ("let implied = AppUi::new();", None),
        ("fn f(x: impl AppUi) {}", None),
    ] {
        assert_eq!(implemented_type(line), ty, "{line}");
    }
}

#[test]
fn the_app_rule_catches_impl_blocks_and_a_long_shell_on_a_fixture() {
    let app = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/architecture/src/app");
    let shell_lines = std::fs::read_to_string(app.join("shell.rs"))
        .expect("the fixture's shell")
        .lines()
        .count();
    let found = app_breaches(&app, shell_lines - 1);
    let expect = [
        "app/player.rs:3: an impl block for `AppUi`",
        "app/player.rs:6: an impl block for `AppUi`",
        "app/shell.rs: 5 lines (at most 4)",
    ];
    for e in expect {
        assert!(
            found.iter().any(|f| f.starts_with(e)),
            "the fixture's breach {e:?} was not reported; reported:\n{}",
            found.join("\n")
        );
    }
    assert_eq!(found.len(), expect.len(), "{}", found.join("\n"));
    // At its length, the shell is no breach.
    assert_eq!(app_breaches(&app, shell_lines).len(), 2);
}

#[test]
fn only_the_shell_implements_the_app_window_model() {
    let app = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/app");
    let found = app_breaches(&app, SHELL_LINES);
    assert!(
        found.is_empty(),
        "{} breach(es) of the app's rule:\n{}",
        found.len(),
        found.join("\n")
    );
}
