//! No branch or loop exit of a pipeline the renderer builds is decided by
//! uniforms alone.
//!
//! lavapipe (Mesa 22.3, the software adapter of Debian 12 and of CI)
//! specializes a shader on the uniforms that alone decide an `if`, a
//! `switch` or a loop's exit (lvp_inline_uniforms): each time the pipeline
//! is bound it reads their current values, folds them in and compiles the
//! result anew, LLVM and all, unless its disk cache holds that very shader.
//! A drag that moves the camera or the light then compiled a shader every
//! frame: with an empty cache (any path the user has not dragged before),
//! orbiting the default scene showed 8.7–8.8 images a second and dragging
//! the light 4.5–4.8 (2.7 under PCSS), against 35.0–36.5, 25.8–29.9 and
//! 34.8 once no pipeline branched on uniforms alone. Replaying one drag
//! from a warm cache, as the benchmarks did, hid most of it.
//!
//! Each pipeline's module is read as naga parses it, its override
//! constants applied as the renderer sets them (`shader_flow` traces each
//! value to what it depends on). WGSL's `&&` and `||` short-circuit, so
//! naga turns them into `if`s: a uniform on their left counts too.

mod shader_flow;

use lumlab::gpu::ShadeOptions;
use lumlab::gpu::light_frustum::LayoutKind;
use lumlab::gpu::shaders::Shader;
use lumlab::gpu::specialise::{SceneAttributes, Specialisation};
use lumlab::settings::{BiasMode, DebugView, Filter, Settings, Visibility};
use shader_flow::{Source, Walk};
use std::collections::BTreeSet;

/// A shader's module as naga parses it, validated, with its name.
struct Parsed {
    name: &'static str,
    module: naga::Module,
    info: naga::valid::ModuleInfo,
}

impl Parsed {
    fn of(shader: Shader) -> Self {
        let module = naga::front::wgsl::parse_str(&shader.source()).expect("parses");
        let info = naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::all(),
        )
        .validate(&module)
        .expect("validates");
        Self {
            name: shader.name(),
            module,
            info,
        }
    }

    /// The findings of `entry` with `constants` applied, each named by
    /// the module and the entry point.
    fn findings(&self, entry: &str, constants: &[(&str, f64)]) -> BTreeSet<String> {
        let mut values = naga::back::PipelineConstants::default();
        for &(name, value) in constants {
            values.insert(name.to_owned(), value);
        }
        let stage = |module: &naga::Module| {
            module
                .entry_points
                .iter()
                .position(|e| e.name == entry)
                .unwrap_or_else(|| panic!("{}: no entry point {entry}", self.name))
        };
        let ep = &self.module.entry_points[stage(&self.module)];
        let (module, _) = naga::back::pipeline_constants::process_overrides(
            &self.module,
            &self.info,
            Some((ep.stage, entry)),
            &values,
        )
        .unwrap_or_else(|e| panic!("{} {entry}: {e}", self.name));
        let ep = &module.entry_points[stage(&module)];
        let mut walk = Walk::new(&module);
        let inputs = vec![Source::Varying; ep.function.arguments.len()];
        let top = walk.function(&ep.function, entry, inputs);
        walk.reachable(&top)
            .into_iter()
            .map(|f| format!("{} {entry}: {f}", self.name))
            .collect()
    }
}

/// The camera pass's specialisations over the settings that select them.
fn camera_passes() -> BTreeSet<Vec<(&'static str, u64)>> {
    let mut all = BTreeSet::new();
    let mut add =
        |settings: &Settings, layout: LayoutKind, accumulating: bool, attributes: SceneAttributes| {
            let s = Specialisation::for_frame(
                settings,
                Some(layout),
                ShadeOptions::default(),
                accumulating,
                false,
                attributes,
            );
            all.insert(
                s.constants()
                    .into_iter()
                    .map(|(n, v)| (n, v as u64))
                    .collect::<Vec<_>>(),
            );
        };
    let none = SceneAttributes::default();
    for &filter in Filter::ALL {
        for &bias in BiasMode::ALL {
            for layout in [LayoutKind::Single, LayoutKind::Cube] {
                let mut s = Settings::default();
                s.shadow.filter = filter;
                s.shadow.bias.mode = bias;
                add(&s, layout, false, none);
            }
        }
    }
    for &view in DebugView::ALL {
        for &visibility in Visibility::ALL {
            for sphere in [false, true] {
                for accumulating in [false, true] {
                    let mut s = Settings::default();
                    s.view.mode = view;
                    s.shadow.visibility = visibility;
                    s.light.radius_m = if sphere { 0.2 } else { 0.0 };
                    add(&s, LayoutKind::Single, accumulating, none);
                }
            }
        }
    }
    let mut off = Settings::default();
    off.shadow.enabled = false;
    for (vertex_colours, textures) in [(true, false), (false, true), (true, true)] {
        let attributes = SceneAttributes {
            vertex_colours,
            textures,
        };
        for s in [&Settings::default(), &off] {
            add(s, LayoutKind::Single, false, attributes);
        }
    }
    all
}

#[test]
fn no_pipeline_branches_on_uniforms_alone() {
    let mut found = BTreeSet::new();
    let shade = Parsed::of(Shader::Shade);
    for constants in camera_passes() {
        let constants: Vec<(&str, f64)> = constants.iter().map(|&(n, v)| (n, v as f64)).collect();
        for entry in ["vs", "vs_depth", "fs", "fs_quantity"] {
            found.extend(shade.findings(entry, &constants));
        }
    }
    let display = Parsed::of(Shader::Display);
    for (i, _) in DebugView::ALL.iter().enumerate() {
        found.extend(display.findings("fs", &[("SPECIALISED_VIEW", i as f64)]));
    }
    let others: [(Shader, &[&str]); 8] = [
        (Shader::Shadow, &["vs", "fs_moments"]),
        (Shader::DepthRanges, &["vs", "fs_blocks", "fs_windows"]),
        (Shader::Blur, &["vs", "fs"]),
        (Shader::Display, &["vs"]),
        (Shader::Lines, &["vs", "fs_visible", "fs_hidden"]),
        (Shader::ViewportImage, &["vs", "fs", "fs_srgb_target"]),
        (Shader::Reduce, &["main"]),
        (Shader::Accumulate, &["fold_frame"]),
    ];
    for (shader, entries) in others {
        let parsed = Parsed::of(shader);
        for entry in entries {
            found.extend(parsed.findings(entry, &[]));
        }
    }
    assert!(
        found.is_empty(),
        "{}",
        found.into_iter().collect::<Vec<_>>().join("\n")
    );
}
