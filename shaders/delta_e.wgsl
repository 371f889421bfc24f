// CIE Lab and the CIEDE2000 colour difference, for the `delta-e` view: the
// WGSL mirror of src/colour/tristimulus.rs (`lab`) and src/colour/delta_e.rs
// (Sharma, Wu & Dalal 2005, k_L = k_C = k_H = 1), step for step, in f32.
// tests/delta_e_view.rs runs them on the GPU against the Rust.

// Hue differences within this many degrees of 180° count as exactly 180°
// (the Rust's HUE_TIE_DEG, widened to f32: hues carry about 1e-5° of error).
const DELTA_E_HUE_TIE_DEG: f32 = 1e-4;
// 25^7, the chroma at which G and R_C are halfway.
const DELTA_E_25_POW_7: f32 = 6103515625.0;

// x^7 by products (pow(0, y) is undefined in WGSL).
fn pow7(x: f32) -> f32 {
    let x2 = x * x;
    return x2 * x2 * x2 * x;
}

// CIE 1976 L*a*b* of a colour given relative to the reference white,
// t = (X/Xn, Y/Yn, Z/Zn); CIE 015:2018 §8.2.1 with ε = 216/24389, κ = 24389/27.
fn lab_of_white_relative(t: vec3<f32>) -> vec3<f32> {
    let epsilon = 216.0 / 24389.0;
    let kappa = 24389.0 / 27.0;
    let cube_root = pow(max(t, vec3<f32>(epsilon)), vec3<f32>(1.0 / 3.0));
    let f = select((kappa * t + 16.0) / 116.0, cube_root, t > vec3<f32>(epsilon));
    return vec3<f32>(116.0 * f.y - 16.0, 500.0 * (f.x - f.y), 200.0 * (f.y - f.z));
}

// Hue angle h' (degrees, 0 … 360) of (a', b'); 0 when both are 0.
fn delta_e_hue_deg(b: f32, a_prime: f32) -> f32 {
    if b == 0.0 && a_prime == 0.0 {
        return 0.0;
    }
    let h = degrees(atan2(b, a_prime));
    return select(h, h + 360.0, h < 0.0);
}

fn cos_deg(x: f32) -> f32 {
    return cos(radians(x));
}

// ΔE2000 between two CIE Lab colours (colour::delta_e2000).
fn delta_e2000(lab1: vec3<f32>, lab2: vec3<f32>) -> f32 {
    // Sharma eqs. 2–7: a' stretched near the neutral axis by G.
    let c_bar7 = pow7(0.5 * (length(lab1.yz) + length(lab2.yz)));
    let g = 0.5 * (1.0 - sqrt(c_bar7 / (c_bar7 + DELTA_E_25_POW_7)));
    let a1p = (1.0 + g) * lab1.y;
    let a2p = (1.0 + g) * lab2.y;
    let c1p = length(vec2<f32>(a1p, lab1.z));
    let c2p = length(vec2<f32>(a2p, lab2.z));
    let h1p = delta_e_hue_deg(lab1.z, a1p);
    let h2p = delta_e_hue_deg(lab2.z, a2p);

    // Eqs. 8–11: differences; the hue difference is 0 when either chroma is 0.
    let dlp = lab2.x - lab1.x;
    let dcp = c2p - c1p;
    let dh = h2p - h1p;
    var dhp = dh;
    if c1p * c2p == 0.0 {
        dhp = 0.0;
    } else if abs(dh) > 180.0 + DELTA_E_HUE_TIE_DEG {
        dhp = select(dh + 360.0, dh - 360.0, dh > 0.0);
    }
    let d_hp = 2.0 * sqrt(c1p * c2p) * sin(radians(dhp) / 2.0);

    // Eqs. 12–22: weights.
    let lp_bar = 0.5 * (lab1.x + lab2.x);
    let cp_bar = 0.5 * (c1p + c2p);
    let hp_sum = h1p + h2p;
    var hp_bar = hp_sum;
    if c1p * c2p != 0.0 {
        if abs(h1p - h2p) <= 180.0 + DELTA_E_HUE_TIE_DEG {
            hp_bar = 0.5 * hp_sum;
        } else if hp_sum < 360.0 {
            hp_bar = 0.5 * (hp_sum + 360.0);
        } else {
            hp_bar = 0.5 * (hp_sum - 360.0);
        }
    }
    let t = 1.0 - 0.17 * cos_deg(hp_bar - 30.0) + 0.24 * cos_deg(2.0 * hp_bar)
        + 0.32 * cos_deg(3.0 * hp_bar + 6.0) - 0.20 * cos_deg(4.0 * hp_bar - 63.0);
    let d_theta_arg = (hp_bar - 275.0) / 25.0;
    let d_theta = 30.0 * exp(-d_theta_arg * d_theta_arg);
    let cp_bar7 = pow7(cp_bar);
    let r_c = 2.0 * sqrt(cp_bar7 / (cp_bar7 + DELTA_E_25_POW_7));
    let l50 = (lp_bar - 50.0) * (lp_bar - 50.0);
    let s_l = 1.0 + 0.015 * l50 / sqrt(20.0 + l50);
    let s_c = 1.0 + 0.045 * cp_bar;
    let s_h = 1.0 + 0.015 * cp_bar * t;
    let r_t = -sin(radians(2.0 * d_theta)) * r_c;

    let l_term = dlp / s_l;
    let c_term = dcp / s_c;
    let h_term = d_hp / s_h;
    // max: f32 rounding must not make a zero difference NaN.
    return sqrt(max(l_term * l_term + c_term * c_term + h_term * h_term + r_t * c_term * h_term, 0.0));
}

// ΔE2000 between two displayed linear sRGB colours (radiance × 2^EV):
// `to_white_relative` takes linear sRGB to XYZ over the reference white's
// XYZ (colour::shading::pixel_delta_e).
fn pixel_delta_e(a: vec3<f32>, b: vec3<f32>, to_white_relative: mat3x3<f32>) -> f32 {
    return delta_e2000(
        lab_of_white_relative(to_white_relative * a),
        lab_of_white_relative(to_white_relative * b),
    );
}
