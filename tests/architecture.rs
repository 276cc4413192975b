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
//! - `mesh`, the leaf module of triangle meshes, names anything of the crate.
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
