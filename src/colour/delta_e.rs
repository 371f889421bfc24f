//! CIEDE2000 colour difference (CIE 142-2001; ISO/CIE 11664-6:2014), as
//! written out step by step by Sharma, Wu & Dalal, "The CIEDE2000
//! color-difference formula: implementation notes, supplementary test data,
//! and mathematical observations", Color Res. Appl. 30(1), 2005.
//!
//! ΔE2000 ≈ 1 is about the smallest difference an observer notices between
//! two patches side by side; above 2–3 it is plain to see.

use glam::DVec3;

/// Hue differences within this many degrees of 180° count as exactly 180°.
/// Sharma's pair 14 sits on that boundary in exact arithmetic; without the
/// tolerance, atan2's last-bit rounding picks the mean hue on the wrong side.
const HUE_TIE_DEG: f64 = 1e-9;

/// ΔE2000 between two CIE Lab colours, with the parametric factors
/// k_L = k_C = k_H = 1 (reference conditions). Symmetric in its arguments.
pub fn delta_e2000(lab1: DVec3, lab2: DVec3) -> f64 {
    let (l1, a1, b1) = (lab1.x, lab1.y, lab1.z);
    let (l2, a2, b2) = (lab2.x, lab2.y, lab2.z);

    // Sharma eqs. 2–7: a' stretched near the neutral axis by G.
    let c_bar = 0.5 * (a1.hypot(b1) + a2.hypot(b2));
    let c_bar7 = c_bar.powi(7);
    let g = 0.5 * (1.0 - (c_bar7 / (c_bar7 + 25f64.powi(7))).sqrt());
    let (a1p, a2p) = ((1.0 + g) * a1, (1.0 + g) * a2);
    let (c1p, c2p) = (a1p.hypot(b1), a2p.hypot(b2));
    let hue = |b: f64, ap: f64| {
        if b == 0.0 && ap == 0.0 {
            0.0
        } else {
            b.atan2(ap).to_degrees().rem_euclid(360.0)
        }
    };
    let (h1p, h2p) = (hue(b1, a1p), hue(b2, a2p));

    // Eqs. 8–11: differences; the hue difference is 0 when either chroma is 0.
    let dlp = l2 - l1;
    let dcp = c2p - c1p;
    let dh = h2p - h1p;
    let dhp = if c1p * c2p == 0.0 {
        0.0
    } else if dh.abs() <= 180.0 + HUE_TIE_DEG {
        dh
    } else if dh > 0.0 {
        dh - 360.0
    } else {
        dh + 360.0
    };
    let d_hp = 2.0 * (c1p * c2p).sqrt() * (dhp.to_radians() / 2.0).sin();

    // Eqs. 12–22: weights.
    let lp_bar = 0.5 * (l1 + l2);
    let cp_bar = 0.5 * (c1p + c2p);
    let hp_sum = h1p + h2p;
    let hp_bar = if c1p * c2p == 0.0 {
        hp_sum
    } else if (h1p - h2p).abs() <= 180.0 + HUE_TIE_DEG {
        0.5 * hp_sum
    } else if hp_sum < 360.0 {
        0.5 * (hp_sum + 360.0)
    } else {
        0.5 * (hp_sum - 360.0)
    };
    let t = 1.0 - 0.17 * (hp_bar - 30.0).to_radians().cos()
        + 0.24 * (2.0 * hp_bar).to_radians().cos()
        + 0.32 * (3.0 * hp_bar + 6.0).to_radians().cos()
        - 0.20 * (4.0 * hp_bar - 63.0).to_radians().cos();
    let d_theta = 30.0 * (-((hp_bar - 275.0) / 25.0).powi(2)).exp();
    let cp_bar7 = cp_bar.powi(7);
    let r_c = 2.0 * (cp_bar7 / (cp_bar7 + 25f64.powi(7))).sqrt();
    let l50 = (lp_bar - 50.0).powi(2);
    let s_l = 1.0 + 0.015 * l50 / (20.0 + l50).sqrt();
    let s_c = 1.0 + 0.045 * cp_bar;
    let s_h = 1.0 + 0.015 * cp_bar * t;
    let r_t = -(2.0 * d_theta).to_radians().sin() * r_c;

    let (l_term, c_term, h_term) = (dlp / s_l, dcp / s_c, d_hp / s_h);
    (l_term * l_term + c_term * c_term + h_term * h_term + r_t * c_term * h_term).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Sharma, Wu & Dalal (2005), Table 1: all 34 pairs (L*, a*, b*) and ΔE00.
    const SHARMA_2005: [([f64; 3], [f64; 3], f64); 34] = [
        ([50.0000, 2.6772, -79.7751], [50.0000, 0.0000, -82.7485], 2.0425),
        ([50.0000, 3.1571, -77.2803], [50.0000, 0.0000, -82.7485], 2.8615),
        ([50.0000, 2.8361, -74.0200], [50.0000, 0.0000, -82.7485], 3.4412),
        ([50.0000, -1.3802, -84.2814], [50.0000, 0.0000, -82.7485], 1.0000),
        ([50.0000, -1.1848, -84.8006], [50.0000, 0.0000, -82.7485], 1.0000),
        ([50.0000, -0.9009, -85.5211], [50.0000, 0.0000, -82.7485], 1.0000),
        ([50.0000, 0.0000, 0.0000], [50.0000, -1.0000, 2.0000], 2.3669),
        ([50.0000, -1.0000, 2.0000], [50.0000, 0.0000, 0.0000], 2.3669),
        ([50.0000, 2.4900, -0.0010], [50.0000, -2.4900, 0.0009], 7.1792),
        ([50.0000, 2.4900, -0.0010], [50.0000, -2.4900, 0.0010], 7.1792),
        ([50.0000, 2.4900, -0.0010], [50.0000, -2.4900, 0.0011], 7.2195),
        ([50.0000, 2.4900, -0.0010], [50.0000, -2.4900, 0.0012], 7.2195),
        ([50.0000, -0.0010, 2.4900], [50.0000, 0.0009, -2.4900], 4.8045),
        ([50.0000, -0.0010, 2.4900], [50.0000, 0.0010, -2.4900], 4.8045),
        ([50.0000, -0.0010, 2.4900], [50.0000, 0.0011, -2.4900], 4.7461),
        ([50.0000, 2.5000, 0.0000], [50.0000, 0.0000, -2.5000], 4.3065),
        ([50.0000, 2.5000, 0.0000], [73.0000, 25.0000, -18.0000], 27.1492),
        ([50.0000, 2.5000, 0.0000], [61.0000, -5.0000, 29.0000], 22.8977),
        ([50.0000, 2.5000, 0.0000], [56.0000, -27.0000, -3.0000], 31.9030),
        ([50.0000, 2.5000, 0.0000], [58.0000, 24.0000, 15.0000], 19.4535),
        ([50.0000, 2.5000, 0.0000], [50.0000, 3.1736, 0.5854], 1.0000),
        ([50.0000, 2.5000, 0.0000], [50.0000, 3.2972, 0.0000], 1.0000),
        ([50.0000, 2.5000, 0.0000], [50.0000, 1.8634, 0.5757], 1.0000),
        ([50.0000, 2.5000, 0.0000], [50.0000, 3.2592, 0.3350], 1.0000),
        ([60.2574, -34.0099, 36.2677], [60.4626, -34.1751, 39.4387], 1.2644),
        ([63.0109, -31.0961, -5.8663], [62.8187, -29.7946, -4.0864], 1.2630),
        ([61.2901, 3.7196, -5.3901], [61.4292, 2.2480, -4.9620], 1.8731),
        ([35.0831, -44.1164, 3.7933], [35.0232, -40.0716, 1.5901], 1.8645),
        ([22.7233, 20.0904, -46.6940], [23.0331, 14.9730, -42.5619], 2.0373),
        ([36.4612, 47.8580, 18.3852], [36.2715, 50.5065, 21.2231], 1.4146),
        ([90.8027, -2.0831, 1.4410], [91.1528, -1.6435, 0.0447], 1.4441),
        ([90.9257, -0.5406, -0.9208], [88.6381, -0.8985, -0.7239], 1.5381),
        ([6.7747, -0.2908, -2.4247], [5.8714, -0.0985, -2.2286], 0.6377),
        ([2.0776, 0.0795, -1.1350], [0.9033, -0.0636, -0.5514], 0.9082),
    ];

    #[test]
    fn sharma_wu_dalal_2005_pairs_to_1e_4() {
        for (i, (a, b, expected)) in SHARMA_2005.iter().enumerate() {
            let (a, b) = (DVec3::from_array(*a), DVec3::from_array(*b));
            for got in [delta_e2000(a, b), delta_e2000(b, a)] {
                assert!(
                    (got - expected).abs() <= 1e-4,
                    "pair {}: {got} ≠ {expected}",
                    i + 1
                );
            }
        }
    }

    #[test]
    fn identical_colours_differ_by_zero() {
        let c = DVec3::new(52.0, 10.0, -30.0);
        assert_eq!(delta_e2000(c, c), 0.0);
    }
}
