// The hard-case grid of `lumlab stability` (src/stability/): one invocation
// per case, each evaluated by the functions of common.wgsl the renderer uses.

// Case kinds, in stability::Quantity order.
const CASE_NORM: u32 = 0u;
const CASE_LOBE: u32 = 1u;
const CASE_BRDF: u32 = 2u;
const CASE_IRRADIANCE: u32 = 3u;
const CASE_SPHERE: u32 = 4u;
const CASE_DEPTH: u32 = 5u;
const CASE_SHADOW: u32 = 6u;

// One case's inputs (stability::CaseRaw).
struct Case {
    // x: kind, y: normalization, z, w: unused.
    kind: vec4<u32>,
    // norm: x = m. lobe: (cos θh, 1 − cos θh, m). brdf: (n, k).
    // irradiance: (p, Φ). sphere: (Φ, R, cos θ, r). depth, shadow: the
    // projection's (z row · v_z, z row · 1, w row · v_z, w row · 1).
    a: vec4<f32>,
    // brdf: (l, m). irradiance: (n, 0). depth: (a, b, z caster, 0).
    // shadow: (a, b, z caster, z receiver).
    b: vec4<f32>,
    // brdf: (o, 0). irradiance: (q, 0).
    c: vec4<f32>,
}

@group(0) @binding(0) var<storage, read> cases: array<Case>;
@group(0) @binding(1) var<storage, read_write> values: array<f32>;

// E at p (normal n) from a point light of power Φ at q, as shade.wgsl's fs
// computes it: light_incidence, then sphere_irradiance.
fn point_light_irradiance(p: vec3<f32>, n: vec3<f32>, q: vec3<f32>, power_w: f32) -> f32 {
    let incidence = light_incidence(q - p, n);
    return sphere_irradiance(power_w, 0.0, incidence.cos_theta, incidence.r);
}

// The caster's depth as the shadow pass stores it (clip.z / clip.w on the
// light's axis), read back in metres as shade.wgsl's stored_depth does.
fn stored_caster_depth(proj: vec4<f32>, coefficients: vec2<f32>, z: f32) -> f32 {
    let v_z = -z;
    let d = (proj.x * v_z + proj.y) / (proj.z * v_z + proj.w);
    return linear_depth(d, coefficients.x, coefficients.y);
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&cases) {
        return;
    }
    let c = cases[i];
    var value = 0.0;
    switch c.kind.x {
        case CASE_NORM: {
            value = norm_factor(c.kind.y, c.a.x);
        }
        case CASE_LOBE: {
            value = lobe(c.a.x, c.a.y, c.a.z);
        }
        case CASE_BRDF: {
            let f = blinn_phong(c.a.xyz, c.b.xyz, c.c.xyz, c.a.w, c.b.w, c.kind.y);
            value = f.x + f.y;
        }
        case CASE_IRRADIANCE: {
            value = point_light_irradiance(c.a.xyz, c.b.xyz, c.c.xyz, c.a.w);
        }
        case CASE_SPHERE: {
            value = sphere_irradiance(c.a.x, c.a.y, c.a.z, c.a.w);
        }
        case CASE_DEPTH: {
            value = stored_caster_depth(c.a, c.b.xy, c.b.z);
        }
        case CASE_SHADOW: {
            // depth_test without bias: lit when the receiver is no further
            // from the light than the stored caster.
            value = select(0.0, 1.0, c.b.w <= stored_caster_depth(c.a, c.b.xy, c.b.z));
        }
        default: {
            value = -1.0;
        }
    }
    values[i] = value;
}
