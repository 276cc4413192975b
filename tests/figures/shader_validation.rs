//! Every WGSL shader parses and validates with naga (no GPU needed). All failures are collected
//! before asserting, so one run reports every broken shader.

use armlab::render::SHADERS;

#[test]
fn every_shader_parses_and_validates() {
    assert!(!SHADERS.is_empty());
    let ui = [(
        "ui.wgsl",
        armlab::ui_render::painter::UI_WGSL,
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

/// Every entry point translates to GLSL ES 3.00 for WebGL2 (what the web build runs on):
/// naga refuses what WebGL2 lacks, e.g. `@interpolate(linear)` (no `noperspective` there), which
/// once stopped the web app at its first line pipeline.
#[test]
fn every_shader_translates_to_webgl2_glsl() {
    use naga::back::glsl;
    let ui = [(
        "ui.wgsl",
        armlab::ui_render::painter::UI_WGSL,
        &[
            "vs_main",
            "fs_gamma",
            "fs_linear",
            "fs_copy",
            "fs_copy_linear",
        ][..],
    )];
    let render = SHADERS
        .iter()
        .map(|&(name, source)| (name, source, &["vs_main", "fs_main"][..]));
    let mut failures = Vec::new();
    for (name, source, entries) in render.chain(ui) {
        let module = naga::front::wgsl::parse_str(source).expect("parses (checked above)");
        let info = naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::default(),
        )
        .validate(&module)
        .expect("validates (checked above)");
        let options = glsl::Options {
            version: glsl::Version::Embedded {
                version: 300,
                is_webgl: true,
            },
            ..Default::default()
        };
        for &entry in entries {
            let shader_stage = if entry.starts_with("vs_") {
                naga::ShaderStage::Vertex
            } else {
                naga::ShaderStage::Fragment
            };
            let pipeline = glsl::PipelineOptions {
                shader_stage,
                entry_point: entry.to_string(),
                multiview: None,
            };
            let mut out = String::new();
            let written = glsl::Writer::new(
                &mut out,
                &module,
                &info,
                &options,
                &pipeline,
                naga::proc::BoundsCheckPolicies::default(),
            )
            .and_then(|mut w| w.write());
            match written {
                Ok(_) if out.contains("#version 300 es") => {}
                Ok(_) => failures.push(format!("{name} {entry}: no `#version 300 es`:\n{out}")),
                Err(e) => failures.push(format!("{name} {entry}: {e}")),
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} entry point(s) do not run on WebGL2:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
