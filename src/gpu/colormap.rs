//! The false-colour ramps of the debug views, as sRGB stops. The display
//! shader interpolates them (injected into WGSL); legends drawn on the CPU use
//! the same stops.

/// Stops of each ramp.
pub const STOPS: usize = 5;

/// Sequential (irradiance, BRDF): black, deep blue, teal, yellow, white.
pub const SEQUENTIAL: [[f32; 3]; STOPS] = [
    [0.02, 0.02, 0.04],
    [0.10, 0.16, 0.50],
    [0.00, 0.58, 0.62],
    [0.95, 0.85, 0.25],
    [1.00, 1.00, 0.96],
];

/// Diverging (signed error, texel density): blue, light blue, white, orange, red.
pub const DIVERGING: [[f32; 3]; STOPS] = [
    [0.15, 0.30, 0.75],
    [0.55, 0.68, 0.92],
    [0.96, 0.96, 0.96],
    [0.94, 0.60, 0.45],
    [0.75, 0.12, 0.12],
];

/// The sRGB colour of `t` ∈ [0, 1] on a ramp (what the shader computes).
pub fn sample(ramp: &[[f32; 3]; STOPS], t: f32) -> [f32; 3] {
    let x = t.clamp(0.0, 1.0) * (STOPS - 1) as f32;
    let i = (x.floor() as usize).min(STOPS - 2);
    let f = x - i as f32;
    std::array::from_fn(|c| ramp[i][c] + (ramp[i + 1][c] - ramp[i][c]) * f)
}

/// The WGSL declarations of the ramps.
pub fn wgsl() -> String {
    let list = |ramp: &[[f32; 3]; STOPS]| {
        ramp.iter()
            .map(|c| format!("vec3<f32>({:?}, {:?}, {:?})", c[0], c[1], c[2]))
            .collect::<Vec<_>>()
            .join(", ")
    };
    format!(
        "const RAMP_STOPS: u32 = {STOPS}u;\n\
         var<private> SEQUENTIAL: array<vec3<f32>, {STOPS}> = array<vec3<f32>, {STOPS}>({});\n\
         var<private> DIVERGING: array<vec3<f32>, {STOPS}> = array<vec3<f32>, {STOPS}>({});\n",
        list(&SEQUENTIAL),
        list(&DIVERGING)
    )
}
