//! Set-ups that cannot exist physically, found before anything is drawn: a
//! light inside a closed object, a sphere light that cuts through a surface,
//! a sphere light that holds the camera. The GPU and the CPU reference
//! treat such a light differently (the reference intersects the emitter and
//! clips its cone, the shading formulas assume it is outside), so their
//! images disagree; the command line refuses them unless told otherwise
//! and the app shows the lines in its status bar.

use super::{Object, Scene};
use crate::settings::Settings;
use glam::DVec3;

/// Directions probed from the light: the axes and the cube's diagonals,
/// tilted a little so that none runs exactly along an edge of a box.
const PROBES: [[f64; 3]; 14] = [
    [1.0, 0.013, 0.021],
    [-1.0, 0.017, -0.011],
    [0.019, 1.0, 0.012],
    [-0.014, -1.0, 0.016],
    [0.011, -0.018, 1.0],
    [0.015, 0.012, -1.0],
    [1.0, 1.03, 0.97],
    [1.02, 0.98, -1.0],
    [1.0, -0.97, 1.03],
    [0.99, -1.0, -1.02],
    [-1.0, 1.01, 0.98],
    [-0.97, 1.0, -1.03],
    [-1.02, -0.99, 1.0],
    [-1.0, -1.02, -0.98],
];

/// Lines shown at most for one kind of problem, the rest counted.
const MAX_NAMED: usize = 3;

/// One warning line per physically impossible part of the set-up, empty
/// when there is none.
pub fn impossible_setups(scene: &Scene, settings: &Settings) -> Vec<String> {
    let light = settings.light.position.as_dvec3();
    let radius = settings.light.radius_m as f64;
    let kind = if radius > 0.0 {
        "sphere light"
    } else {
        "point light"
    };
    let mut warnings = Vec::new();

    let enclosing: Vec<&str> = scene
        .objects
        .iter()
        .filter(|o| encloses(o, light))
        .map(|o| o.name.as_str())
        .collect();
    warnings.extend(named(&enclosing, |name| {
        format!(
            "the {kind} at {} is inside the closed object '{name}': no light can leave it",
            xyz(light)
        )
    }));

    if radius > 0.0 {
        let cut: Vec<(&str, f64)> = scene
            .objects
            .iter()
            .filter(|o| o.bounds.distance_to(settings.light.position) as f64 <= radius)
            .filter_map(|o| {
                nearest_distance(o, light)
                    .filter(|&d| d < radius)
                    .map(|d| (o.name.as_str(), d))
            })
            .collect();
        let names: Vec<&str> = cut.iter().map(|(name, _)| *name).collect();
        warnings.extend(named(&names, |name| {
            let d = cut.iter().find(|(n, _)| *n == name).map_or(0.0, |(_, d)| *d);
            format!(
                "the sphere light (R = {radius} m at {}) cuts through '{name}', whose surface is {d:.3} m from its centre",
                xyz(light)
            )
        }));
        let eye = settings.camera.eye.as_dvec3();
        if eye.distance(light) < radius {
            warnings.push(format!(
                "the sphere light (R = {radius} m at {}) holds the camera at {}: the camera would see only the light",
                xyz(light),
                xyz(eye)
            ));
        }
    }
    warnings
}

/// One line per name, up to [`MAX_NAMED`], then "and N more".
fn named(names: &[&str], line: impl Fn(&str) -> String) -> Vec<String> {
    let mut lines: Vec<String> = names
        .iter()
        .take(MAX_NAMED)
        .map(|n| crate::input::escape_controls(&line(n)))
        .collect();
    if names.len() > MAX_NAMED {
        lines.push(format!(
            "… and {} more object(s) like it",
            names.len() - MAX_NAMED
        ));
    }
    lines
}

fn xyz(p: DVec3) -> String {
    format!("({}, {}, {})", p.x as f32, p.y as f32, p.z as f32)
}

/// The point is inside the object's closed surface: every probe from it
/// hits the object, and the nearest hit is always a back face (the inside
/// of a solid; a room modelled with its faces turned inward is not a solid
/// around the point).
fn encloses(object: &Object, point: DVec3) -> bool {
    if !object.bounds.contains(point.as_vec3()) || object.mesh.triangle_count() == 0 {
        return false;
    }
    PROBES.iter().all(|d| {
        let direction = DVec3::from_array(*d).normalize();
        nearest_hit(object, point, direction).is_some_and(|(_, back_face)| back_face)
    })
}

/// The nearest hit along the ray: its distance, and whether the ray meets
/// the triangle's back (counter-clockwise triangles face front).
fn nearest_hit(object: &Object, origin: DVec3, direction: DVec3) -> Option<(f64, bool)> {
    let mut best: Option<(f64, bool)> = None;
    for t in 0..object.mesh.triangle_count() {
        let [a, b, c] = object.mesh.triangle(t).map(|p| p.as_dvec3());
        let (e1, e2) = (b - a, c - a);
        // Möller–Trumbore.
        let p = direction.cross(e2);
        let det = e1.dot(p);
        if det.abs() < 1e-300 {
            continue;
        }
        let s = origin - a;
        let u = s.dot(p) / det;
        let q = s.cross(e1);
        let v = direction.dot(q) / det;
        let distance = e2.dot(q) / det;
        if u < 0.0 || v < 0.0 || u + v > 1.0 || distance <= 0.0 || !distance.is_finite() {
            continue;
        }
        if best.is_none_or(|(d, _)| distance < d) {
            best = Some((distance, e1.cross(e2).dot(direction) > 0.0));
        }
    }
    best
}

/// The shortest distance from the point to the object's triangles.
fn nearest_distance(object: &Object, point: DVec3) -> Option<f64> {
    (0..object.mesh.triangle_count())
        .map(|t| {
            let [a, b, c] = object.mesh.triangle(t).map(|p| p.as_dvec3());
            closest_on_triangle(point, a, b, c).distance(point)
        })
        .filter(|d| d.is_finite())
        .min_by(f64::total_cmp)
}

/// The point of triangle abc closest to p (Ericson, Real-Time Collision
/// Detection, 5.1.5: which Voronoi region of the triangle p falls in).
fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(settings: &mut Settings, position: [f32; 3], radius: f32) {
        settings.light.position = glam::Vec3::from_array(position);
        settings.light.radius_m = radius;
    }

    #[test]
    fn the_default_set_up_is_possible() {
        let scene = super::super::default_scene();
        assert_eq!(
            impossible_setups(&scene, &Settings::default()),
            Vec::<String>::new()
        );
    }

    #[test]
    fn lights_inside_solids_or_cutting_surfaces_are_named() {
        let scene = super::super::default_scene();
        let mut settings = Settings::default();
        let solid = scene
            .objects
            .iter()
            .find(|o| {
                let c = o.bounds.center();
                o.mesh.triangle_count() > 0 && encloses(o, c.as_dvec3())
            })
            .expect("the default scene has a closed object");
        at(&mut settings, solid.bounds.center().to_array(), 0.0);
        let lines = impossible_setups(&scene, &settings);
        assert!(
            lines.iter().any(|l| l.contains("inside the closed object")),
            "{lines:?}"
        );

        // Just above the ground, a sphere light 1 m wide reaches into it.
        let ground_top = scene.bounds().min.y;
        at(&mut settings, [4.0, ground_top + 0.2, 4.0], 0.5);
        let lines = impossible_setups(&scene, &settings);
        assert!(lines.iter().any(|l| l.contains("cuts through")), "{lines:?}");

        let eye = settings.camera.eye.to_array();
        at(&mut settings, eye, 0.5);
        let lines = impossible_setups(&scene, &settings);
        assert!(lines.iter().any(|l| l.contains("holds the camera")), "{lines:?}");
    }

    #[test]
    fn closest_point_of_a_triangle_is_in_its_right_region() {
        let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::Y);
        for (p, expected) in [
            ([0.2, 0.2, 1.0], [0.2, 0.2, 0.0]),
            ([-1.0, -1.0, 0.0], [0.0, 0.0, 0.0]),
            ([0.5, -2.0, 0.0], [0.5, 0.0, 0.0]),
            ([2.0, 2.0, 0.0], [0.5, 0.5, 0.0]),
        ] {
            let got = closest_on_triangle(DVec3::from_array(p), a, b, c);
            assert!(got.distance(DVec3::from_array(expected)) < 1e-12, "{p:?}: {got}");
        }
    }
}
