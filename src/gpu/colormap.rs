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

/// The `delta-e` view's scale: ΔE2000 from 0 (black) to this (white), so
/// that images compare whatever they show; larger values saturate.
pub const DELTA_E_VIEW_MAX: f32 = 10.0;

/// Named differences on the ΔE2000 scale, marked on its legend: about 1 is
/// the smallest an observer notices side by side; 2.3 is the
/// just-noticeable difference (JND) Sharma (Digital Color Imaging Handbook,
/// 2003) gives for CIE Lab.
pub const DELTA_E_THRESHOLDS: [f32; 2] = [1.0, 2.3];

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
         var<private> DIVERGING: array<vec3<f32>, {STOPS}> = array<vec3<f32>, {STOPS}>({});\n\
         const DELTA_E_VIEW_MAX: f32 = {DELTA_E_VIEW_MAX:?};\n",
        list(&SEQUENTIAL),
        list(&DIVERGING)
    )
}

/// How a false-colour view maps values to its ramp, for a legend.
#[derive(Clone, Debug, PartialEq)]
pub struct Legend {
    pub title: String,
    pub ramp: &'static [[f32; 3]; STOPS],
    /// Positions along the ramp (0 … 1) and their labels.
    pub ticks: Vec<(f32, String)>,
}

/// The `delta-e` view's legend: its fixed scale 0 … [`DELTA_E_VIEW_MAX`]
/// with the named thresholds marked; `title` names them (the app translates).
pub fn delta_e_legend(title: String) -> Legend {
    let max = DELTA_E_VIEW_MAX as f64;
    let mut ticks = vec![(0.0, "0".to_string())];
    ticks.extend(DELTA_E_THRESHOLDS.map(|v| (v / DELTA_E_VIEW_MAX, short(v as f64))));
    ticks.push((0.5, short(0.5 * max)));
    ticks.push((1.0, format!("≥ {}", short(max))));
    Legend {
        title,
        ramp: &SEQUENTIAL,
        ticks,
    }
}

/// A short number for a tick label.
fn short(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if (1e-3..1e4).contains(&x.abs()) {
        format!("{}", (x * 1e3).round() / 1e3)
    } else {
        format!("{x:.2e}")
    }
}

/// The legend of a false-colour view whose largest value is `scale` (as the
/// display shader maps it), or None for views shown in grey or radiance.
pub fn legend(view: crate::settings::DebugView, scale: f32) -> Option<Legend> {
    use crate::settings::DebugView as V;
    let scale = scale.max(1e-30) as f64;
    let quarters = [0.0_f32, 0.25, 0.5, 0.75, 1.0];
    let ticks = |label: &dyn Fn(f32) -> String| quarters.iter().map(|&t| (t, label(t))).collect();
    let legend = match view {
        V::Irradiance => Legend {
            title: "irradiance E·V (W/m²)".into(),
            ramp: &SEQUENTIAL,
            ticks: ticks(&|t| short(t as f64 * scale)),
        },
        V::Brdf => Legend {
            title: "BRDF f_r / c (1/sr), log scale".into(),
            ramp: &SEQUENTIAL,
            ticks: ticks(&|t| short(scale * 10f64.powf(2.0 * (t as f64 - 1.0)))),
        },
        V::TexelDensity => Legend {
            title: "shadow-map texels per pixel (red: magnified, aliased)".into(),
            ramp: &DIVERGING,
            ticks: ticks(&|t| short(2f64.powf(8.0 * (0.5 - t as f64)))),
        },
        V::Error => Legend {
            title: "signed error of luminance L − L_ref (W/m²/sr)".into(),
            ramp: &DIVERGING,
            ticks: ticks(&|t| short((2.0 * t as f64 - 1.0) * scale)),
        },
        V::DeltaE => delta_e_legend("ΔE2000, RGB approximation vs spectral (1: visible, 2.3: JND)".into()),
        _ => return None,
    };
    Some(legend)
}
