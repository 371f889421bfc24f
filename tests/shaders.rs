//! Every WGSL module is valid (naga), the CPU mirrors of its structs have
//! the same sizes, and the shaders' constants follow the settings' enums.

use lumlab::gpu::shaders::Shader;
use lumlab::gpu::uniforms::{
    BlurParamsRaw, DisplayParamsRaw, GlobalsRaw, MaterialRaw, ShadowLayerRaw, ShadowRaw,
};
use lumlab::physics::Normalization;
use lumlab::settings::{BiasMode, DebugView, Filter};

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
