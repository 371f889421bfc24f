//! The hard cases: built in f64, their inputs rounded to f32.

use super::{Case, Defined, Input, Quantity};
use crate::physics::Normalization;
use crate::physics::brdf::BrdfParams;
use crate::physics::radiometry::{MIN_LIGHT_DISTANCE_M, sphere_irradiance};
use glam::{DVec3, Vec3};
use std::f64::consts::PI;

/// Blinn-Phong exponents, from the Lambertian lobe to a mirror.
const EXPONENTS: [f64; 6] = [0.0, 1.0, 8.0, 1e3, 1e4, 1e6];
/// Light powers (W): none, a firefly, a stadium.
const POWERS_W: [f64; 3] = [0.0, 1e-6, 1e9];
/// Diffuse/specular mixes: the lobe alone, half and half, Lambert alone.
const MIXES: [f64; 3] = [0.0, 0.5, 1.0];
/// The most grazing angle the lab shows (degrees).
const GRAZING_DEG: f64 = 89.99;
/// Shadow-map depth ranges (near, far) in metres: ratios 1e4, 1e6 and 1e8.
const DEPTH_RANGES_M: [(f64, f64); 4] = [(0.1, 1e3), (1e-3, 1e3), (1e-3, 1e5), (1e-2, 1e6)];
/// How far a receiver lies behind its caster (m).
const RECEIVER_GAP_M: f64 = 1e-3;
/// The farthest caster tested with that gap: beyond it 1 mm is below
/// DEPTH_TOLERANCE × z, and below f32's spacing of z itself from 8 km.
const FARTHEST_CASTER_M: f64 = 1e3;

/// Every hard case, grouped by quantity in `Quantity::ALL` order.
pub fn grid() -> Vec<Case> {
    let mut cases = Vec::new();
    normalizations(&mut cases);
    lobes(&mut cases);
    brdfs(&mut cases);
    irradiances(&mut cases);
    spheres(&mut cases);
    depths(&mut cases);
    shadows(&mut cases);
    cases
}

/// A number as short as it reads: 0, 0.5, 89.99, 1e3, 1e-6.
pub(super) fn short(x: f64) -> String {
    if x == 0.0 || (1e-2..1e3).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// The shading normal of the BRDF and irradiance cases, tilted off the axes
/// so that no dot product is trivially exact.
fn normal() -> DVec3 {
    DVec3::new(0.3, 1.0, -0.2).normalize()
}

/// The unit direction at θ from the normal and azimuth φ around it (radians).
fn direction(theta: f64, phi: f64) -> DVec3 {
    let n = normal();
    let (t, b) = n.any_orthonormal_pair();
    (t * phi.cos() + b * phi.sin()) * theta.sin() + n * theta.cos()
}

fn deg(d: f64) -> f64 {
    d.to_radians()
}

fn exact(value: f64, rule: &'static str) -> Option<Defined> {
    Some(Defined {
        value,
        rule,
        exact: true,
    })
}

fn normalizations(cases: &mut Vec<Case>) {
    for &m in &EXPONENTS {
        for &norm in Normalization::ALL {
            let m32 = m as f32;
            cases.push(Case {
                quantity: Quantity::Norm,
                label: format!("{norm:<6} m = {}", short(m)),
                input: Input::Norm { m: m32, norm },
                scale: norm.factor(f64::from(m32)),
                defined: (norm == Normalization::None).then_some(Defined {
                    value: 1.0,
                    rule: "none: N = 1",
                    exact: true,
                }),
            });
        }
    }
}

fn lobes(cases: &mut Vec<Case>) {
    // Half-vector angles (radians) from the peak to grazing.
    let angles = [1e-4, 1e-3, 3e-3, 1e-2, 0.05, 0.1, 1.0, deg(GRAZING_DEG)];
    for &m in &EXPONENTS {
        let m32 = m as f32;
        let mut push = |label: String, gap: f64, defined: Option<Defined>| {
            // cos θh is the rounded gap's complement, rounded as a dot product
            // would be: the naive pow sees what the lobe sees, without the gap.
            let gap32 = gap as f32;
            let cos32 = (1.0 - f64::from(gap32)) as f32;
            cases.push(Case {
                quantity: Quantity::Lobe,
                label: format!("{label:<18} m = {}", short(m)),
                input: Input::Lobe {
                    cos_theta: cos32,
                    gap: gap32,
                    m: m32,
                },
                scale: 1.0,
                defined: if m == 0.0 {
                    exact(1.0, "m = 0 → 1 (0^0 = 1)")
                } else {
                    defined
                },
            });
        };
        push("θh = 0 (peak)".into(), 0.0, exact(1.0, "peak → 1"));
        for &theta in &angles {
            let half = (0.5 * theta).sin();
            let label = if theta > 1.5 {
                format!("θh = {GRAZING_DEG}°")
            } else {
                format!("θh = {} rad", short(theta))
            };
            push(label, 2.0 * half * half, None);
        }
        push("θh = 90°".into(), 1.0, exact(0.0, "cos θh = 0 → 0"));
    }
}

/// A pair of directions for the BRDF, named for the table.
struct Geometry {
    name: String,
    l: Vec3,
    o: Vec3,
    defined_zero: Option<&'static str>,
}

fn geometries() -> Vec<Geometry> {
    let g = |name: &str, (tl, pl): (f64, f64), (to, po): (f64, f64), zero: Option<&'static str>| Geometry {
        name: name.to_string(),
        l: direction(tl, pl).as_vec3(),
        o: direction(to, po).as_vec3(),
        defined_zero: zero,
    };
    let mirror = |theta_h: f64| {
        // l and o in one plane through n, 30° each side: h lies θh from n.
        g(
            &format!("θh = {} rad (30°)", short(theta_h)),
            (deg(30.0) + theta_h, 0.0),
            (deg(30.0) - theta_h, PI),
            None,
        )
    };
    let grazing = deg(GRAZING_DEG);
    let tangent = direction(deg(90.0), 0.0).as_vec3();
    vec![
        g("l = o = n", (0.0, 0.0), (0.0, 0.0), None),
        mirror(1e-3),
        mirror(3e-3),
        mirror(3e-2),
        g(
            "45° and 45° 90° apart",
            (deg(45.0), 0.0),
            (deg(45.0), deg(90.0)),
            None,
        ),
        g("89.99° mirror (h = n)", (grazing, 0.0), (grazing, PI), None),
        g(
            "89.99° 179.99° apart",
            (grazing, 0.0),
            (grazing, deg(179.99)),
            None,
        ),
        g("l at 89.99° o = n", (grazing, 0.0), (0.0, 0.0), None),
        Geometry {
            name: "l = −o (l + o = 0)".into(),
            l: tangent,
            o: -tangent,
            defined_zero: Some("l + o = 0 → 0"),
        },
        g(
            "l below (90.01°)",
            (deg(90.01), 0.0),
            (deg(30.0), PI),
            Some("n·l ≤ 0 → 0"),
        ),
        g(
            "o below (90.01°)",
            (deg(30.0), 0.0),
            (deg(90.01), PI),
            Some("n·o ≤ 0 → 0"),
        ),
    ]
}

fn brdf_case(geometry: &Geometry, k: f64, m: f64, norm: Normalization, label: String) -> Case {
    let (k32, m32) = (k as f32, m as f32);
    let params = BrdfParams {
        k: f64::from(k32),
        m: f64::from(m32),
        norm,
    };
    let peak = params.k / PI + (1.0 - params.k) * norm.factor(params.m);
    let defined = match geometry.defined_zero {
        Some(rule) => exact(0.0, rule),
        None if k == 1.0 => Some(Defined {
            value: 1.0 / PI,
            rule: "k = 1: Lambert 1/π",
            exact: false,
        }),
        None => None,
    };
    Case {
        quantity: Quantity::Brdf,
        label,
        input: Input::Brdf {
            n: normal().as_vec3(),
            l: geometry.l,
            o: geometry.o,
            k: k32,
            m: m32,
            norm,
        },
        scale: peak,
        defined,
    }
}

fn brdfs(cases: &mut Vec<Case>) {
    let geometries = geometries();
    // Every geometry and exponent for the pure lobe with the largest N(m).
    for geometry in &geometries {
        for &m in &EXPONENTS {
            let label = format!("{:<22} m = {}", geometry.name, short(m));
            cases.push(brdf_case(geometry, 0.0, m, Normalization::Exact, label));
        }
    }
    // Every mix and normalization near the peak and at l + o = 0.
    for geometry in [&geometries[1], &geometries[8]] {
        for &k in &MIXES {
            for &norm in Normalization::ALL {
                for m in [0.0, 8.0, 1e6] {
                    let label = format!("{:<19} k = {k:<3} {norm:<6} m = {}", geometry.name, short(m));
                    cases.push(brdf_case(geometry, k, m, norm, label));
                }
            }
        }
    }
}

fn irradiances(cases: &mut Vec<Case>) {
    // The receiver at the origin: an offset of 1e-7 m stays representable.
    let p = DVec3::ZERO;
    let n = normal();
    for &power in &POWERS_W {
        let mut push = |label: String, q: DVec3, clamp: bool| {
            let (p32, n32, q32) = (p.as_vec3(), n.as_vec3(), q.as_vec3());
            let power32 = power as f32;
            let (p64, n64, q64) = (p32.as_dvec3(), n32.as_dvec3(), q32.as_dvec3());
            let r = (q64 - p64).length();
            let scale = sphere_irradiance(f64::from(power32), 0.0, 1.0, r);
            let defined = if power == 0.0 {
                exact(0.0, "Φ = 0 → 0")
            } else if clamp {
                // E = I cos θ / (1 µm)², with l = n when r = 0.
                let l = if r > 0.0 { (q64 - p64) / r } else { n64 };
                Some(Defined {
                    value: sphere_irradiance(f64::from(power32), 0.0, n64.dot(l), 0.0),
                    rule: "r < 1 µm → I cos θ/(1 µm)²",
                    exact: false,
                })
            } else {
                None
            };
            cases.push(Case {
                quantity: Quantity::Irradiance,
                label: format!("{label:<26} Φ = {} W", short(power)),
                input: Input::Irradiance {
                    p: p32,
                    n: n32,
                    q: q32,
                    power_w: power32,
                },
                scale,
                defined,
            });
        };
        push("r = 0 (on the surface)".into(), p, true);
        push("r = 1e-7 m θ = 0°".into(), p + n * 1e-7, true);
        for r in [MIN_LIGHT_DISTANCE_M, 1e-3, 1.0, 1e3, 1e6] {
            for theta_deg in [0.0, GRAZING_DEG] {
                let q = p + direction(deg(theta_deg), 0.3) * r;
                push(format!("r = {} m θ = {theta_deg}°", short(r)), q, false);
            }
        }
    }
}

fn spheres(cases: &mut Vec<Case>) {
    let power = 100.0_f64;
    let mut push = |label: String, radius: f64, cos: f64, r: f64, defined: Option<Defined>| {
        let (radius32, cos32, r32) = (radius as f32, cos as f32, r as f32);
        let (radius64, r64) = (f64::from(radius32), f64::from(r32));
        cases.push(Case {
            quantity: Quantity::Sphere,
            label,
            input: Input::Sphere {
                power_w: power as f32,
                radius_m: radius32,
                cos_theta: cos32,
                r_m: r32,
            },
            scale: sphere_irradiance(power, radius64, 1.0, r64),
            defined,
        });
    };
    for (radius, r) in [(0.5, 1.0), (0.01, 1.0), (1e-4, 1.0), (1.0, 1e3), (1e-2, 1e3)] {
        let sin_alpha = radius / r;
        let name = format!("R = {} r = {} m", short(radius), short(r));
        push(format!("{name} θ = 0°"), radius, 1.0, r, None);
        // Straddling the horizon: the centre sin α/2 above, at, and below it.
        for (what, cos) in [
            ("half above", 0.5 * sin_alpha),
            ("centre on", 0.0),
            ("half below", -0.5 * sin_alpha),
        ] {
            push(format!("{name} {what} horizon"), radius, cos, r, None);
        }
        push(
            format!("{name} θ = 120°"),
            radius,
            -0.5,
            r,
            exact(0.0, "below the horizon → 0"),
        );
    }
    let inside = Some(Defined {
        value: sphere_irradiance(power, 0.5, 1.0, 0.0),
        rule: "inside: π L_e",
        exact: false,
    });
    push("R = 0.5 r = 0.3 m (inside)".into(), 0.5, 0.3, 0.3, inside);
    push("R = 0.5 r = 0 (centre)".into(), 0.5, 1.0, 0.0, inside);
    // Radius and distance both below the clamp: the point light's clamp.
    let clamped = Some(Defined {
        value: sphere_irradiance(power, 0.0, 1.0, 0.0),
        rule: "r < 1 µm → I/(1 µm)²",
        exact: false,
    });
    push("R = 1e-7 r = 0 m".into(), 1e-7, 1.0, 0.0, clamped);
    push("R = 0 r = 1 m θ = 60° (point)".into(), 0.0, 0.5, 1.0, None);
}

/// Caster depths: the near plane, then decades to the far plane.
fn depths_in(near: f64, far: f64) -> Vec<f64> {
    let mut z = vec![near];
    z.extend([1.0, 100.0, 1e4].into_iter().filter(|&z| z > near && z < far));
    z.push(far);
    z
}

fn range_name(near: f64, far: f64) -> String {
    format!("near/far = {}/{}", short(near), short(far))
}

fn depths(cases: &mut Vec<Case>) {
    for &(near, far) in &DEPTH_RANGES_M {
        for z in depths_in(near, far) {
            let z32 = z as f32;
            cases.push(Case {
                quantity: Quantity::Depth,
                label: format!("{} z = {} m", range_name(near, far), short(z)),
                input: Input::Depth {
                    near_m: near,
                    far_m: far,
                    z_m: z32,
                },
                scale: f64::from(z32),
                defined: None,
            });
        }
    }
}

fn shadows(cases: &mut Vec<Case>) {
    for &(near, far) in &DEPTH_RANGES_M {
        let casters = depths_in(near, far)
            .into_iter()
            .filter(|&z| z < FARTHEST_CASTER_M)
            .chain([FARTHEST_CASTER_M])
            .filter(|&z| z + RECEIVER_GAP_M <= far);
        for z in casters {
            cases.push(Case {
                quantity: Quantity::Shadow,
                label: format!("{} caster {} m + 1 mm", range_name(near, far), short(z)),
                input: Input::Shadow {
                    near_m: near,
                    far_m: far,
                    caster_m: z as f32,
                    receiver_m: (z + RECEIVER_GAP_M) as f32,
                },
                scale: 1.0,
                defined: exact(0.0, "1 mm behind → hidden"),
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_grid_covers_every_quantity_exponent_power_and_norm() {
        let cases = grid();
        for &q in Quantity::ALL {
            assert!(cases.iter().any(|c| c.quantity == q), "{q}");
        }
        assert!(cases.iter().all(|c| !c.label.contains(',')));
        let brdf_ms: Vec<f32> = cases
            .iter()
            .filter_map(|c| match c.input {
                Input::Brdf { m, .. } => Some(m),
                _ => None,
            })
            .collect();
        assert!(EXPONENTS.iter().all(|&m| brdf_ms.contains(&(m as f32))));
        assert!(
            cases
                .iter()
                .any(|c| matches!(c.input, Input::Shadow { near_m, far_m, .. } if far_m / near_m >= 1e8))
        );
    }

    #[test]
    fn the_mirror_geometries_have_their_half_vector_angle() {
        let g = &geometries()[1];
        let h = (g.l.as_dvec3() + g.o.as_dvec3()).normalize();
        let theta_h = h.cross(normal()).length().asin();
        assert!((theta_h - 1e-3).abs() < 1e-5, "{theta_h}");
        assert_eq!(geometries()[8].l + geometries()[8].o, Vec3::ZERO);
    }
}
