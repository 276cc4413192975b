//! Every WGSL shader parses and validates with naga (no GPU needed). All failures are collected
//! before asserting, so one run reports every broken shader.

use armlab::render::SHADERS;

#[test]
fn every_shader_parses_and_validates() {
    assert!(!SHADERS.is_empty());
    let ui = [(
        "ui.wgsl",
        armlab::figure::ui_painter::UI_WGSL,
        &["vs_main", "fs_gamma", "fs_linear"][..],
    )];
    let render = SHADERS
        .iter()
        .map(|&(name, source)| (name, source, &["vs_main", "fs_main"][..]));
    let mut failures = Vec::new();
    for (name, source, entries) in render.chain(ui) {
        let module = match naga::front::wgsl::parse_str(source) {
            Ok(m) => m,
            Err(e) => {
                failures.push(format!(
                    "{name}: parse error\n{}",
                    e.emit_to_string_with_path(source, name)
                ));
                continue;
            }
        };
        let mut validator = naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::default(),
        );
        if let Err(e) = validator.validate(&module) {
            failures.push(format!(
                "{name}: validation error\n{}",
                e.emit_to_string_with_path(source, name)
            ));
            continue;
        }
        for &entry in entries {
            let stage = if entry.starts_with("vs_") {
                naga::ShaderStage::Vertex
            } else {
                naga::ShaderStage::Fragment
            };
            if !module
                .entry_points
                .iter()
                .any(|ep| ep.name == entry && ep.stage == stage)
            {
                failures.push(format!("{name}: no {stage:?} entry point `{entry}`"));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} shader failure(s):\n\n{}",
        failures.len(),
        failures.join("\n\n")
    );
}
