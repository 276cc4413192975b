//! The layer table of `src/`, kept by a test (DESIGN.md section 1). Every top-level module of
//! `src/` sits in exactly one layer of [`LAYERS`], lowest first; a module may name (`crate::m`)
//! only modules of its own layer and of the layers below it. The test scans every source file,
//! comments and string literals removed, and fails naming the file and line of each breach:
//!
//! - a module that is in no layer (the message says where to add it);
//! - a module naming a module of a higher layer (`use crate::workspace` in `kinematics`);
//! - graphics crates below the renderer (egui, eframe, wgpu, winit, image), and egui or winit in
//!   `render`;
//! - file access (`std::fs`, `std::io`, also as `use std::{fs, io}`) outside the layers that read
//!   and write files: input, the headless figures and the front ends (`std::io::Error` and
//!   `std::io::Result`, which carry an error the input layer made, are allowed everywhere);
//! - a figure that calls an IK solver, the closed-form detection, a sampler or another
//!   computation (it paints what it is handed);
//! - `render` naming the kinematics, and `mesh`, the leaf module of triangle meshes, naming
//!   anything of the crate;
//! - a file of `app` other than `app/shell.rs` implements `AppUi` (the app's parts return actions
//!   and read the state; only the shell changes the window model), or `app/shell.rs` grows past
//!   [`SHELL_LINES`] lines.
//!
//! The rules are first shown to catch each kind of breach on a small fixture tree
//! (`tests/data/architecture/src`), then applied to the real `src/`.

use std::path::{Path, PathBuf};

/// What graphics crates a layer may name.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Graphics {
    /// None: the layer runs without the `app` feature's graphics stack.
    No,
    /// wgpu and image (the renderer draws and reads pixels back, and knows no egui).
    Renderer,
    /// Any (egui, eframe, wgpu, winit, image).
    Any,
}

/// One layer of `src/`.
struct Layer {
    /// The layer's name, for messages.
    name: &'static str,
    /// Its top-level modules (`src/<m>.rs` or `src/<m>/`).
    modules: &'static [&'static str],
    /// The graphics crates it may name.
    graphics: Graphics,
    /// Whether it may read and write files (`std::fs`, `std::io`).
    files: bool,
}

/// The layers of `src/`, lowest first. A module may name only its own layer and those below it.
/// A new top-level module goes into the lowest layer whose modules it names.
const LAYERS: &[Layer] = &[
    Layer {
        name: "input",
        modules: &["input", "npz"],
        graphics: Graphics::No,
        files: true,
    },
    Layer {
        name: "meshes",
        modules: &["mesh"],
        graphics: Graphics::No,
        files: false,
    },
    Layer {
        name: "kinematics",
        modules: &["kinematics"],
        graphics: Graphics::No,
        files: false,
    },
    Layer {
        name: "model files",
        modules: &["model_file", "urdf"],
        graphics: Graphics::No,
        files: false,
    },
    Layer {
        name: "compute",
        modules: &[
            "workspace",
            "collision",
            "reachability",
            "calibration",
            "redundancy",
            "construction",
            "exercise",
            "lesson",
            "class",
            "offload",
            "animation",
        ],
        graphics: Graphics::No,
        files: false,
    },
    Layer {
        name: "scene",
        modules: &["scene", "camera"],
        graphics: Graphics::No,
        files: false,
    },
    Layer {
        name: "render",
        modules: &["render"],
        graphics: Graphics::Renderer,
        files: false,
    },
    Layer {
        name: "headless figures",
        modules: &["ui_render", "figure", "headless"],
        graphics: Graphics::Any,
        files: true,
    },
    Layer {
        name: "front ends",
        modules: &["app", "cli", "web", "class_server"],
        graphics: Graphics::Any,
        files: true,
    },
];

/// Graphics crates, as they are named in paths.
const GRAPHICS: &[&str] = &[
    "egui",
    "eframe",
    "egui_wgpu",
    "egui_plot",
    "egui_kittest",
    "wgpu",
    "winit",
    "image",
];

/// Calls a figure must not make: solvers, the closed-form detection, samplers and the other
/// computations.
const NOT_CALLED_IN_FIGURES: &[&str] = &[
    "solve",
    "solve_into",
    "solve_raw",
    "solve_prepared",
    "solve_position_raw",
    "detect",
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

/// Items of `std::io` that any layer may name: they carry an error the input layer made.
const IO_ERROR_TYPES: &[&str] = &["Error", "Result", "ErrorKind"];

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

/// The layer index of a top-level module, if it is in [`LAYERS`].
fn layer_of(module: &str) -> Option<usize> {
    LAYERS.iter().position(|l| l.modules.contains(&module))
}

/// The identifiers a path names right after `prefix` (`crate::`, `std::`): one for
/// `crate::scene::Scene`, each top-level member for `crate::{scene::Scene, render}`, each with
/// what follows it up to the next `,` or `}` (`io::Error`). Offsets are into `code`.
fn named_after(code: &str, prefix: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    for (i, _) in code.match_indices(prefix) {
        let before = code[..i].chars().next_back();
        if before.is_some_and(|b| b.is_alphanumeric() || b == '_' || b == ':') {
            continue;
        }
        let rest = &code[i + prefix.len()..];
        let path_end = |s: &str| {
            s.find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
                .unwrap_or(s.len())
        };
        if let Some(group) = rest.strip_prefix('{') {
            // A group: its top-level members, separated by commas at depth 0.
            let mut depth = 0;
            let mut member_start = 0;
            for (k, ch) in group.char_indices() {
                let end_member = match ch {
                    '{' => {
                        depth += 1;
                        false
                    }
                    '}' if depth == 0 => true,
                    '}' => {
                        depth -= 1;
                        false
                    }
                    ',' => depth == 0,
                    _ => false,
                };
                if end_member {
                    let member = group[member_start..k].trim();
                    if !member.is_empty() {
                        let m = &member[..path_end(member)];
                        out.push((i, m.to_string()));
                    }
                    member_start = k + 1;
                    if ch == '}' {
                        break;
                    }
                }
            }
        } else {
            out.push((i, rest[..path_end(rest)].to_string()));
        }
    }
    out
}

/// The 1-based line of byte offset `at` in `code`.
fn line_at(code: &str, at: usize) -> usize {
    code[..at].matches('\n').count() + 1
}

/// Every top-level module of `src`: `src/<m>.rs` and `src/<m>/`, but `lib.rs` and `main.rs`.
fn top_level_modules(src: &Path) -> Vec<(String, PathBuf)> {
    let mut out: Vec<(String, PathBuf)> = std::fs::read_dir(src)
        .unwrap_or_else(|e| panic!("{}: {e}", src.display()))
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter_map(|p| {
            let name = p.file_name()?.to_string_lossy().into_owned();
            let module = if p.is_dir() {
                name
            } else {
                name.strip_suffix(".rs")?.to_string()
            };
            (module != "lib" && module != "main").then_some((module, p))
        })
        .collect();
    out.sort();
    out.dedup_by(|a, b| a.0 == b.0);
    out
}

/// Every breach of the layer rules under `src`, as "file:line: what".
fn violations(src: &Path) -> Vec<String> {
    let mut out = Vec::new();
    let shown = |p: &Path| {
        p.strip_prefix(src.parent().unwrap_or(src))
            .unwrap_or(p)
            .display()
            .to_string()
    };
    for (module, path) in top_level_modules(src) {
        if layer_of(&module).is_none() {
            out.push(format!(
                "{}: the module `{module}` is in no layer: add it to LAYERS in \
                 tests/house/architecture.rs, in the lowest layer whose modules it names",
                shown(&path)
            ));
        }
    }
    for file in sources(src) {
        let module = module_of(src, &file);
        // The crate roots (`lib.rs`, `main.rs`) are in no layer: they name every module.
        let Some(layer) = layer_of(&module) else {
            continue;
        };
        let text =
            std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        let code = code_only(&text);
        let rel = shown(&file);
        let mut breach = |at: usize, what: String| {
            out.push(format!("{rel}:{}: {what}", line_at(&code, at)));
        };
        let here = &LAYERS[layer];
        for (at, named) in named_after(&code, "crate::") {
            let top = named.split("::").next().unwrap_or("");
            if let Some(l) = layer_of(top).filter(|&l| l > layer) {
                breach(
                    at,
                    format!(
                        "`{module}` ({}) names `crate::{top}` of the higher layer {}",
                        here.name, LAYERS[l].name
                    ),
                );
            }
            if module == "render" && top == "kinematics" {
                breach(at, "`render` names `crate::kinematics`".into());
            }
        }
        if module == "mesh" {
            for (at, _) in code
                .match_indices("crate::")
                .chain(code.match_indices("super::"))
            {
                breach(
                    at,
                    "the leaf module `mesh` names another module of the crate".into(),
                );
            }
        }
        for g in GRAPHICS {
            let allowed = match here.graphics {
                Graphics::Any => true,
                Graphics::Renderer => *g == "wgpu" || *g == "image",
                Graphics::No => false,
            };
            let path = format!("{g}::");
            if !allowed {
                for (at, _) in code
                    .match_indices(&path)
                    .filter(|(i, _)| starts_word(&code, *i))
                {
                    breach(at, format!("`{module}` ({}) names `{path}`", here.name));
                }
            }
        }
        if !here.files {
            for (at, named) in named_after(&code, "std::") {
                let mut parts = named.split("::");
                let first = parts.next().unwrap_or("");
                let item = parts.next();
                let file_access = first == "fs"
                    || (first == "io" && !item.is_some_and(|i| IO_ERROR_TYPES.contains(&i)));
                if file_access {
                    breach(
                        at,
                        format!(
                            "`{module}` ({}) names `std::{first}`: file access belongs to the \
                             input, headless and front-end layers",
                            here.name
                        ),
                    );
                }
            }
        }
        if module == "figure" {
            for (n, line) in code.lines().enumerate() {
                for f in NOT_CALLED_IN_FIGURES {
                    if calls(line, f) {
                        out.push(format!(
                            "{rel}:{}: a figure calls `{f}`: figures paint what they are handed; \
                             compute it in the caller (see headless::workspace_figure)",
                            n + 1
                        ));
                    }
                }
            }
        }
    }
    out
}

/// Whether the match at `i` starts a path (not inside a longer identifier or path).
fn starts_word(code: &str, i: usize) -> bool {
    !code[..i]
        .chars()
        .next_back()
        .is_some_and(|b| b.is_alphanumeric() || b == '_' || b == ':')
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
fn grouped_imports_are_read_member_by_member() {
    let code = "use crate::{scene::Scene, render};\nuse std::{fs, io::{self, Read}, io::Error};";
    let crate_names: Vec<String> = named_after(code, "crate::")
        .into_iter()
        .map(|n| n.1)
        .collect();
    assert_eq!(crate_names, ["scene::Scene", "render"]);
    let std_names: Vec<String> = named_after(code, "std::")
        .into_iter()
        .map(|n| n.1)
        .collect();
    assert_eq!(std_names, ["fs", "io::", "io::Error"]);
}

#[test]
fn every_layer_is_above_the_ones_it_may_name() {
    // Each module in exactly one layer.
    let mut seen = std::collections::BTreeSet::new();
    for l in LAYERS {
        for m in l.modules {
            assert!(seen.insert(*m), "`{m}` is in two layers");
        }
    }
    assert!(layer_of("kinematics") < layer_of("workspace"));
    assert!(layer_of("workspace") < layer_of("scene"));
    assert!(layer_of("scene") < layer_of("render"));
    assert!(layer_of("render") < layer_of("figure"));
    assert!(layer_of("figure") < layer_of("app"));
}

#[test]
fn the_rules_catch_each_kind_of_breach_on_a_fixture() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/architecture/src");
    let found = violations(&src);
    let expect = [
        "src/stray.rs: the module `stray` is in no layer: add it to LAYERS",
        "src/kinematics/bad.rs:3: `kinematics` (kinematics) names `egui::`",
        "src/kinematics/bad.rs:7: `kinematics` (kinematics) names `std::fs`",
        "src/kinematics/bad.rs:9: `kinematics` (kinematics) names `crate::workspace` of the higher layer compute",
        "src/kinematics/bad.rs:10: `kinematics` (kinematics) names `std::fs`",
        "src/kinematics/bad.rs:10: `kinematics` (kinematics) names `std::io`",
        "src/workspace.rs:2: `workspace` (compute) names `crate::scene` of the higher layer scene",
        "src/render/bad.rs:2: `render` names `crate::kinematics`",
        "src/render/bad.rs:3: `render` (render) names `egui::`",
        "src/scene.rs:2: `scene` (scene) names `wgpu::`",
        "src/figure/bad.rs:5: a figure calls `solve_into`",
        "src/figure/bad.rs:6: a figure calls `sample`",
        "src/figure/bad.rs:8: a figure calls `detect`",
        "src/figure/bad.rs:10: `figure` (headless figures) names `crate::app` of the higher layer front ends",
        "src/mesh.rs:1: `mesh` (meshes) names `crate::kinematics` of the higher layer kinematics",
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
        "the fixture's clean lines (comments, strings, definitions, allowed layers) were \
         reported:\n{}",
        found.join("\n")
    );
}

#[test]
fn every_module_of_src_is_in_a_layer_and_every_layer_module_exists() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let modules: Vec<String> = top_level_modules(&src).into_iter().map(|m| m.0).collect();
    for l in LAYERS {
        for m in l.modules {
            assert!(
                modules.iter().any(|x| x == m),
                "LAYERS names `{m}`, which src/ does not have: remove it"
            );
        }
    }
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
