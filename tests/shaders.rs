//! Every WGSL module is valid (naga), the CPU mirrors of its structs have
//! the same sizes and field offsets, the shaders' constants follow the
//! settings' enums, and the numeric constants WGSL shares with Rust are the
//! Rust ones.

use lumlab::gpu::accumulate::FoldRaw;
use lumlab::gpu::shaders::{Shader, luminance_weights, shared_f32_constants, shared_u32_constants};
use lumlab::gpu::uniforms::{
    BlurParamsRaw, DisplayParamsRaw, GlobalsRaw, MaterialRaw, ShadowLayerRaw, ShadowRaw,
};
use lumlab::physics::Normalization;
use lumlab::settings::{BiasMode, DebugView, Filter, Visibility};
use std::mem::offset_of;

fn parse(shader: Shader) -> naga::Module {
    naga::front::wgsl::parse_str(&shader.source())
        .unwrap_or_else(|e| panic!("{}: {}", shader.name(), e.emit_to_string(&shader.source())))
}

#[test]
fn every_shader_validates() {
    for shader in Shader::ALL {
        let module = parse(shader);
        naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::all(),
        )
        .validate(&module)
        .unwrap_or_else(|e| panic!("{}: {:?}", shader.name(), e));
    }
}

/// No function takes an array through a pointer: naga's GLSL makes such a
/// parameter an `inout` array, which Mesa's GL copies in and out at every
/// call (the BVH walk's stack ran ~3.7× slower on llvmpipe's GL that way).
#[test]
fn no_function_takes_an_array_by_pointer() {
    for shader in Shader::ALL {
        let module = parse(shader);
        for (_, function) in module.functions.iter() {
            for argument in &function.arguments {
                if let naga::TypeInner::Pointer { base, .. } = module.types[argument.ty].inner {
                    assert!(
                        !matches!(module.types[base].inner, naga::TypeInner::Array { .. }),
                        "{}: {}'s argument {} is a pointer to an array",
                        shader.name(),
                        function.name.as_deref().unwrap_or("?"),
                        argument.name.as_deref().unwrap_or("?"),
                    );
                }
            }
        }
    }
}

fn struct_size(module: &naga::Module, name: &str) -> u32 {
    let (_, ty) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("struct {name} not in the shader"));
    match ty.inner {
        naga::TypeInner::Struct { span, .. } => span,
        _ => panic!("{name} is not a struct"),
    }
}

#[test]
fn uniform_structs_match_their_wgsl_size() {
    let shade = parse(Shader::Shade);
    let sizes = [
        ("Globals", std::mem::size_of::<GlobalsRaw>()),
        ("ShadowLayer", std::mem::size_of::<ShadowLayerRaw>()),
        ("Shadow", std::mem::size_of::<ShadowRaw>()),
        ("Material", std::mem::size_of::<MaterialRaw>()),
        ("DisplayParams", std::mem::size_of::<DisplayParamsRaw>()),
    ];
    for (name, size) in sizes {
        assert_eq!(struct_size(&shade, name) as usize, size, "{name}");
    }
    let blur = parse(Shader::Blur);
    assert_eq!(
        struct_size(&blur, "BlurParams") as usize,
        std::mem::size_of::<BlurParamsRaw>()
    );
    let accumulate = parse(Shader::Accumulate);
    assert_eq!(
        struct_size(&accumulate, "Fold") as usize,
        std::mem::size_of::<FoldRaw>()
    );
}

/// Each member of the WGSL struct `name`, by name, with its byte offset.
fn struct_members(module: &naga::Module, name: &str) -> Vec<(String, u32)> {
    let (_, ty) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("struct {name} not in the shader"));
    match &ty.inner {
        naga::TypeInner::Struct { members, .. } => members
            .iter()
            .map(|m| (m.name.clone().unwrap_or_default(), m.offset))
            .collect(),
        _ => panic!("{name} is not a struct"),
    }
}

/// The WGSL struct has exactly these members, at these offsets.
fn assert_members(module: &naga::Module, name: &str, rust: &[(&str, usize)]) {
    let wgsl = struct_members(module, name);
    let rust: Vec<(String, u32)> = rust.iter().map(|(n, o)| (n.to_string(), *o as u32)).collect();
    assert_eq!(
        wgsl, rust,
        "{name}: WGSL members (left) against the Rust fields (right)"
    );
}

#[test]
fn uniform_fields_match_their_wgsl_offsets() {
    let shade = parse(Shader::Shade);
    macro_rules! fields {
        ($t:ty: $($f:ident),+) => { [$((stringify!($f), offset_of!($t, $f))),+] };
    }
    assert_members(
        &shade,
        "Globals",
        &fields!(GlobalsRaw: view_proj, light_rel, light_radius_m, eye, light_power_w, light_color, k,
            color_override, m, view, visibility, use_scene_materials, use_color_override, norm_factor, shadow_apex_rel,
            exposure_ev, other_light_color, delta_e_defined, other_color_override, lab_white_relative),
    );
    assert_members(
        &shade,
        "ShadowLayer",
        &fields!(ShadowLayerRaw: rotation, proj, tan_left, tan_right, tan_bottom, tan_top, near_m, far_m,
            depth_a, depth_b),
    );
    assert_members(
        &shade,
        "Shadow",
        &fields!(ShadowRaw: layers, light_position, enabled, cube, layer_mask, filter_mode, bias_mode, pcf_size,
            poisson_samples, pcss_blocker_samples, resolution_texels, poisson_radius_texels, bias_depth_m,
            bias_slope, normal_offset_texels, vsm_bleed_reduction, evsm_exponent, light_radius_m, msm_bias, range_block),
    );
    assert_members(
        &shade,
        "Material",
        &fields!(MaterialRaw: base_color, words, other_model_color),
    );
    assert_members(
        &shade,
        "DisplayParams",
        &fields!(DisplayParamsRaw: size_px, view, has_comparison, exposure_ev),
    );
    assert_members(
        &parse(Shader::Blur),
        "BlurParams",
        &fields!(BlurParamsRaw: step, radius_texels, layer),
    );
}

/// The expression a module-scope `const` of the composed source holds.
fn constant_init<'a>(module: &'a naga::Module, name: &str) -> &'a naga::Expression {
    let (_, constant) = module
        .constants
        .iter()
        .find(|(_, c)| c.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("no const {name}"));
    &module.global_expressions[constant.init]
}

/// The value of a module-scope `const` of the composed source, as naga reads it.
fn constant_value(module: &naga::Module, name: &str) -> Vec<f32> {
    let scalar = |e: &naga::Expression| match e {
        naga::Expression::Literal(naga::Literal::F32(v)) => *v,
        other => panic!("{name}: not an f32 literal: {other:?}"),
    };
    match constant_init(module, name) {
        naga::Expression::Compose { components, .. } => components
            .iter()
            .map(|&c| scalar(&module.global_expressions[c]))
            .collect(),
        e => vec![scalar(e)],
    }
}

/// The value of a module-scope u32 `const`, as naga reads it.
fn constant_u32(module: &naga::Module, name: &str) -> u32 {
    match constant_init(module, name) {
        naga::Expression::Literal(naga::Literal::U32(v)) => *v,
        other => panic!("{name}: not a u32 literal: {other:?}"),
    }
}

#[test]
fn constants_shared_with_rust_are_defined_once_from_the_rust_values() {
    for shader in Shader::ALL {
        let module = parse(shader);
        for (name, value) in shared_f32_constants() {
            assert_eq!(
                constant_value(&module, name),
                vec![value],
                "{}: {name}",
                shader.name()
            );
        }
        for (name, value) in shared_u32_constants() {
            assert_eq!(constant_u32(&module, name), value, "{}: {name}", shader.name());
        }
        assert_eq!(
            constant_value(&module, "LUMINANCE_WEIGHTS"),
            luminance_weights().to_vec(),
            "{}",
            shader.name()
        );
    }
    // The values themselves, from where they are defined.
    assert_eq!(
        luminance_weights(),
        lumlab::physics::colour::LUMINANCE_WEIGHTS.map(|w| w as f32)
    );
    let named: std::collections::HashMap<_, _> = shared_f32_constants().into_iter().collect();
    assert_eq!(named["PI"], std::f32::consts::PI);
    assert_eq!(
        named["MIN_LIGHT_DISTANCE_M"],
        lumlab::physics::radiometry::MIN_LIGHT_DISTANCE_M as f32
    );
    assert_eq!(
        named["MAX_FILTER_RADIUS_TEXELS"],
        lumlab::gpu::shadow::MAX_FILTER_RADIUS_TEXELS
    );
    assert_eq!(
        named["AUTO_BIAS_SLACK_TEXELS"],
        lumlab::gpu::shadow::AUTO_BIAS_SLACK_TEXELS
    );
    assert_eq!(
        named["AUTO_BIAS_SLACK_REL"],
        lumlab::gpu::shadow::AUTO_BIAS_SLACK_REL
    );
    assert_eq!(named["MAX_SLOPE"], lumlab::gpu::shadow::MAX_SLOPE);
    // No WGSL file writes its own copy (naga would also reject a second definition).
    let files = [
        include_str!("../shaders/common.wgsl"),
        include_str!("../shaders/shade.wgsl"),
        include_str!("../shaders/shadow_map.wgsl"),
        include_str!("../shaders/display.wgsl"),
        include_str!("../shaders/reduce.wgsl"),
        include_str!("../shaders/shadow.wgsl"),
        include_str!("../shaders/blur.wgsl"),
        include_str!("../shaders/lines.wgsl"),
        include_str!("../shaders/stability.wgsl"),
        include_str!("../shaders/raytrace.wgsl"),
        include_str!("../shaders/bvh.wgsl"),
    ];
    let flags = shared_u32_constants().map(|(name, _)| name);
    for name in named.keys().copied().chain(flags).chain(["LUMINANCE_WEIGHTS"]) {
        let declaration = format!("const {name}:");
        assert!(
            files.iter().all(|f| !f.contains(&declaration)),
            "{name} written by hand"
        );
    }
    for literal in ["0.2126", "0.7152", "0.0722", "48.0"] {
        assert!(
            files.iter().all(|f| !f.contains(literal)),
            "{literal} written by hand"
        );
    }
}

/// The value of `const PREFIX_NAME: u32 = Nu;` in common.wgsl for each variant name.
fn constant(prefix: &str, variant: &str) -> u32 {
    let wanted = format!(
        "const {prefix}_{}: u32 =",
        variant.to_uppercase().replace('-', "_")
    );
    let source = include_str!("../shaders/common.wgsl");
    let line = source
        .lines()
        .find(|l| l.starts_with(&wanted))
        .unwrap_or_else(|| panic!("no `{wanted}` in common.wgsl"));
    line[wanted.len()..]
        .trim()
        .trim_end_matches("u;")
        .parse()
        .expect("a u32 literal")
}

#[test]
fn shader_constants_follow_the_enums() {
    for (i, v) in DebugView::ALL.iter().enumerate() {
        assert_eq!(constant("VIEW", v.name()), i as u32, "{v}");
    }
    for (i, f) in Filter::ALL.iter().enumerate() {
        assert_eq!(constant("FILTER", f.name()), i as u32, "{f}");
    }
    for (i, b) in BiasMode::ALL.iter().enumerate() {
        assert_eq!(constant("BIAS", b.name()), i as u32, "{b}");
    }
    for (i, n) in Normalization::ALL.iter().enumerate() {
        assert_eq!(constant("NORM", n.name()), i as u32, "{n}");
    }
    for (i, v) in Visibility::ALL.iter().enumerate() {
        assert_eq!(constant("VISIBILITY", v.name()), i as u32, "{v}");
    }
    // norm_factor's switch cases are in Normalization order.
    assert_eq!(
        Normalization::ALL,
        [
            Normalization::None,
            Normalization::Ndf,
            Normalization::Approx,
            Normalization::Exact
        ]
    );
}
