//! Modelling only what the scene needs: the light's frusta fitted to the
//! scene's bounds, and the casters that can shadow what the camera sees.
//! Pure geometry in f64, no GPU objects.
//!
//! A light outside the scene's bounds gets one perspective frustum, fitted
//! tightly (off-centre field of view, near and far) around the bounds. A light
//! inside them, or too close to fit them in a reasonable field of view, gets
//! the six faces of a cube; only faces whose frustum contains geometry are drawn.

use crate::scene::Aabb;
use crate::scene::camera::{Frame, look_frame, reversed_z_projection, rotation_to_view};
use glam::{DMat4, DVec3};

/// The widest single frustum (per axis, as a full angle): beyond it the cube
/// is used, whose faces waste fewer texels at the edges.
pub const MAX_SINGLE_FOV_DEG: f64 = 140.0;

/// A perspective frustum with its apex at `apex`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frustum {
    pub apex: DVec3,
    pub frame: Frame,
    /// left, right, bottom, top: extents as tangents (x/z, y/z).
    pub tan: [f64; 4],
    pub near: f64,
    pub far: f64,
}

/// A plane `normal · (p − apex) ≥ offset` bounding the inside of a frustum.
#[derive(Clone, Copy, Debug)]
struct Plane {
    normal: DVec3,
    offset: f64,
}

impl Frustum {
    /// World → view rotation (view looks down −Z).
    pub fn rotation(&self) -> DMat4 {
        rotation_to_view(&self.frame)
    }

    /// View → clip with reversed Z.
    pub fn projection(&self) -> DMat4 {
        let [l, r, b, t] = self.tan;
        reversed_z_projection(l, r, b, t, self.near, self.far)
    }

    fn planes(&self) -> [Plane; 6] {
        let Frame { right, up, forward } = self.frame;
        let [l, r, b, t] = self.tan;
        let side = |normal: DVec3| Plane { normal, offset: 0.0 };
        [
            side(right - forward * l),
            side(forward * r - right),
            side(up - forward * b),
            side(forward * t - up),
            Plane {
                normal: forward,
                offset: self.near,
            },
            Plane {
                normal: -forward,
                offset: -self.far,
            },
        ]
    }

    /// Conservative: false only when the box is entirely outside one plane.
    pub fn intersects(&self, aabb: &Aabb) -> bool {
        if aabb.is_empty() {
            return false;
        }
        let (min, max) = (aabb.min.as_dvec3(), aabb.max.as_dvec3());
        self.planes().iter().all(|plane| {
            // The corner furthest along the plane's normal.
            let corner = DVec3::select(plane.normal.cmpge(DVec3::ZERO), max, min);
            plane.normal.dot(corner - self.apex) >= plane.offset
        })
    }

    /// The eight corners: near plane then far plane, each (l,b) (r,b) (r,t) (l,t).
    pub fn corners(&self) -> [DVec3; 8] {
        let Frame { right, up, forward } = self.frame;
        let [l, r, b, t] = self.tan;
        let at = |x: f64, y: f64, z: f64| self.apex + (right * x + up * y + forward) * z;
        let (n, f) = (self.near, self.far);
        [
            at(l, b, n),
            at(r, b, n),
            at(r, t, n),
            at(l, t, n),
            at(l, b, f),
            at(r, b, f),
            at(r, t, f),
            at(l, t, f),
        ]
    }
}

/// Tight frustum from `apex` around `bounds`, or None when the bounds do not
/// fit in front of the apex within [`MAX_SINGLE_FOV_DEG`].
pub fn fit_around(apex: DVec3, bounds: &Aabb) -> Option<Frustum> {
    if bounds.is_empty() || bounds.contains(apex.as_vec3()) {
        return None;
    }
    let frame = look_frame(apex, bounds.center().as_dvec3());
    let mut tan = [f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY];
    let (mut near, mut far) = (f64::INFINITY, 0.0_f64);
    for corner in bounds.corners() {
        let d = corner.as_dvec3() - apex;
        let z = d.dot(frame.forward);
        if z <= 1e-9 * d.length().max(1e-30) {
            return None;
        }
        let (x, y) = (d.dot(frame.right) / z, d.dot(frame.up) / z);
        tan = [tan[0].min(x), tan[1].max(x), tan[2].min(y), tan[3].max(y)];
        near = near.min(z);
        far = far.max(z);
    }
    let max_extent = 2.0 * (0.5 * MAX_SINGLE_FOV_DEG).to_radians().tan();
    let too_wide =
        |lo: f64, hi: f64| (hi.atan() - lo.atan()).to_degrees() > MAX_SINGLE_FOV_DEG || hi - lo > max_extent;
    if too_wide(tan[0], tan[1]) || too_wide(tan[2], tan[3]) {
        return None;
    }
    Some(Frustum {
        apex,
        frame,
        tan,
        // A little slack so the bounds' own faces are not clipped.
        near: near * 0.99,
        far: far * 1.01,
    })
}

/// One layer of the shadow map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightLayer {
    pub frustum: Frustum,
    /// Drawn (a cube face with no geometry in it is skipped).
    pub active: bool,
}

/// How the light's view of the scene is split into layers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LayoutKind {
    /// One frustum fitted around the scene.
    Single,
    /// Six cube faces (+X, −X, +Y, −Y, +Z, −Z), the light inside or among the geometry.
    Cube,
}

#[derive(Clone, Debug, PartialEq)]
pub struct ShadowLayout {
    pub kind: LayoutKind,
    /// One layer (single) or six (cube), in the shader's face order.
    pub layers: Vec<LightLayer>,
}

/// Cube face directions in the shader's order.
pub const CUBE_AXES: [DVec3; 6] = [
    DVec3::X,
    DVec3::NEG_X,
    DVec3::Y,
    DVec3::NEG_Y,
    DVec3::Z,
    DVec3::NEG_Z,
];

/// Beyond this many bounding radii from the scene, a light's shadow map is
/// drawn from a stand-in apex on the same line at this distance: f32 cannot
/// hold a point of a 1 m scene relative to a sun 1.5·10¹¹ m away (its ulp
/// there is 16 km), while the directions from the stand-in differ from the
/// true ones by less than 1/1000 rad. The irradiance keeps the true light.
pub const FAR_LIGHT_RADII: f64 = 1000.0;

/// Where the shadow map of a light at `light` is drawn from, for a scene
/// bounded by `bounds`: the light itself, or its stand-in when it is far.
pub fn shadow_apex(light: DVec3, bounds: &Aabb) -> DVec3 {
    if bounds.is_empty() {
        return light;
    }
    let (centre, radius) = bounds.bounding_sphere();
    let radius = radius.max(1e-9);
    let offset = light - centre;
    let limit = FAR_LIGHT_RADII * radius;
    if offset.length() > limit {
        centre + offset.normalize() * limit
    } else {
        light
    }
}

impl ShadowLayout {
    /// Fits the layers around `objects` (their bounds) for a light at `light`.
    /// `margin` widens each frustum by that fraction of its extent so filter
    /// kernels near its edges stay inside the map.
    pub fn fit(light: DVec3, objects: &[Aabb], margin: f64) -> Self {
        let bounds = objects.iter().fold(Aabb::EMPTY, |b, o| b.union(o));
        if let Some(mut frustum) = fit_around(light, &bounds) {
            let [l, r, b, t] = frustum.tan;
            let (mx, my) = (margin * (r - l), margin * (t - b));
            frustum.tan = [l - mx, r + mx, b - my, t + my];
            return Self {
                kind: LayoutKind::Single,
                layers: vec![LightLayer {
                    frustum,
                    active: true,
                }],
            };
        }
        let extent = bounds.extent().length().max(1e-6) as f64;
        let half = 1.0 + 2.0 * margin;
        // A face's depth is along its axis: at tangents (t1, t2) a point at
        // distance d lies at depth d / √(1 + t1² + t2²), down to d / √(1 + 2·half²)
        // in the face's corners. The nearest geometry must stay beyond near there
        // too, or it is clipped off the map and light leaks through it.
        let corner = (1.0 + 2.0 * half * half).sqrt();
        let near = (bounds.distance_to(light.as_vec3()) as f64 * 0.99 / corner).max(extent * 1e-6);
        let far_corner = bounds
            .corners()
            .iter()
            .map(|c| (c.as_dvec3() - light).length())
            .fold(0.0, f64::max);
        // Every face alike but for its axis: shadow_map.wgsl reads the
        // tangents, near and far planes of layer 0 for all of them.
        let layers = CUBE_AXES
            .iter()
            .map(|&axis| {
                let frustum = Frustum {
                    apex: light,
                    frame: look_frame(light, light + axis),
                    tan: [-half, half, -half, half],
                    near,
                    far: (far_corner * 1.01).max(near * 2.0),
                };
                let active = objects.iter().any(|o| frustum.intersects(o));
                LightLayer { frustum, active }
            })
            .collect();
        Self {
            kind: LayoutKind::Cube,
            layers,
        }
    }

    /// The indices of the layers drawn.
    pub fn active_layers(&self) -> Vec<usize> {
        (0..self.layers.len())
            .filter(|&i| self.layers[i].active)
            .collect()
    }

    /// Bit i set when layer i is drawn.
    pub fn active_mask(&self) -> u32 {
        self.active_layers().into_iter().map(|i| 1 << i).sum()
    }
}

/// For each layer, the objects to draw into it: casters inside the layer's
/// frustum that can shadow a receiver the camera sees, i.e. that meet the
/// frustum from the light around the visible receivers' bounds.
pub fn select_casters(
    layout: &ShadowLayout,
    casters: &[Option<Aabb>],
    visible_receivers: &Aabb,
) -> Vec<Vec<usize>> {
    if visible_receivers.is_empty() {
        return vec![Vec::new(); layout.layers.len()];
    }
    let light = layout.layers[0].frustum.apex;
    // Casters beyond the receivers (seen from the light) cannot shadow them.
    let cone = fit_around(light, visible_receivers).map(|mut f| {
        f.near = 0.0;
        f
    });
    layout
        .layers
        .iter()
        .map(|layer| {
            if !layer.active {
                return Vec::new();
            }
            casters
                .iter()
                .enumerate()
                .filter_map(|(i, b)| b.as_ref().map(|b| (i, b)))
                .filter(|(_, b)| layer.frustum.intersects(b) && cone.as_ref().is_none_or(|c| c.intersects(b)))
                .map(|(i, _)| i)
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn aabb(min: [f32; 3], max: [f32; 3]) -> Aabb {
        Aabb {
            min: Vec3::from(min),
            max: Vec3::from(max),
        }
    }

    #[test]
    fn a_far_light_draws_its_map_from_a_stand_in_on_the_same_line() {
        let b = aabb([-1.0, 0.0, -1.0], [1.0, 1.0, 1.0]);
        let near = DVec3::new(2.0, 5.0, 1.0);
        assert_eq!(shadow_apex(near, &b), near);
        let sun = DVec3::new(6e10, 1.2e11, 5e10);
        let apex = shadow_apex(sun, &b);
        let (centre, radius) = b.bounding_sphere();
        assert!(((apex - centre).length() / radius - FAR_LIGHT_RADII).abs() < 1e-9);
        assert!((apex - centre).normalize().dot((sun - centre).normalize()) > 1.0 - 1e-12);
    }

    #[test]
    fn light_above_the_scene_gets_one_tight_frustum() {
        let ground = aabb([-5.0, 0.0, -5.0], [5.0, 0.1, 5.0]);
        let layout = ShadowLayout::fit(DVec3::new(0.0, 10.0, 0.0), &[ground], 0.0);
        assert_eq!(layout.kind, LayoutKind::Single);
        let f = layout.layers[0].frustum;
        // Every corner inside, and the frustum no wider than it must be.
        for c in ground.corners() {
            let d = c.as_dvec3() - f.apex;
            let z = d.dot(f.frame.forward);
            assert!(z >= f.near && z <= f.far);
        }
        assert!(
            (f.tan[1] - 5.0 / 9.9).abs() < 1e-6 && (f.near - 9.9 * 0.99).abs() < 1e-6,
            "{f:?}"
        );
    }

    #[test]
    fn light_inside_the_scene_gets_a_cube_drawing_only_faces_with_geometry() {
        // A floor below and one box on the +X side: +X, −Y and whatever sees them.
        let floor = aabb([-5.0, -2.0, -5.0], [5.0, -1.9, 5.0]);
        let boxx = aabb([3.0, -1.9, -0.5], [4.0, -0.5, 0.5]);
        let layout = ShadowLayout::fit(DVec3::ZERO, &[floor, boxx], 0.01);
        assert_eq!(layout.kind, LayoutKind::Cube);
        assert!(layout.layers[3].active, "−Y sees the floor");
        assert!(layout.layers[0].active, "+X sees the box");
        assert!(!layout.layers[2].active, "+Y sees nothing");
    }

    #[test]
    fn cube_faces_clip_no_geometry_off_their_axis() {
        // The default scene's case: the light above a wide ground, the
        // nearest geometry 45° off two face axes.
        let ground = aabb([-6.0, -0.5, -6.0], [6.0, 0.0, 6.0]);
        let slab = aabb([-1.7, 2.39, 0.3], [-0.7, 2.41, 1.3]);
        let light = DVec3::new(2.5, 6.0, 2.0);
        let margin = 50.0 / 1024.0;
        let layout = ShadowLayout::fit(light, &[ground, slab], margin);
        assert_eq!(layout.kind, LayoutKind::Cube);
        let half = 1.0 + 2.0 * margin;
        for layer in &layout.layers {
            let f = &layer.frustum;
            // Points all over the slab, not only its corners.
            let steps = 20;
            let points = (0..=steps).flat_map(|i| {
                (0..=steps).flat_map(move |k| {
                    [0.0, 1.0].map(|j| {
                        let t =
                            DVec3::new(i as f64, j, k as f64) / DVec3::new(steps as f64, 1.0, steps as f64);
                        slab.min.as_dvec3() + (slab.max - slab.min).as_dvec3() * t
                    })
                })
            });
            for point in points {
                let d = point - f.apex;
                let z = d.dot(f.frame.forward);
                let (tx, ty) = (d.dot(f.frame.right) / z, d.dot(f.frame.up) / z);
                if z > 0.0 && tx.abs() <= half && ty.abs() <= half {
                    assert!(z > f.near, "{point:?} at depth {z} before near {}", f.near);
                }
            }
        }
    }

    #[test]
    fn cube_faces_share_their_extent_and_only_permute_axes() {
        // shadow_map.wgsl reads every face's tangents, near and far planes
        // from layer 0 (`frustum`), and turns directions into a face's view
        // by the permutations of `to_view`: (1, 2, 3) in each face's view.
        let ground = aabb([-6.0, -0.5, -6.0], [6.0, 0.0, 6.0]);
        let layout = ShadowLayout::fit(DVec3::new(0.5, 1.0, -0.3), &[ground], 0.02);
        assert_eq!(layout.kind, LayoutKind::Cube);
        let first = &layout.layers[0].frustum;
        let permuted = [
            [3.0, 2.0, -1.0],
            [-3.0, 2.0, 1.0],
            [1.0, 3.0, -2.0],
            [-1.0, 3.0, 2.0],
            [-1.0, 2.0, -3.0],
            [1.0, 2.0, 3.0],
        ];
        for (layer, expected) in layout.layers.iter().zip(permuted) {
            let f = &layer.frustum;
            assert_eq!((f.tan, f.near, f.far), (first.tan, first.near, first.far));
            let view = f.rotation().transform_vector3(DVec3::new(1.0, 2.0, 3.0));
            assert_eq!(view.to_array(), expected);
        }
    }

    #[test]
    fn frustum_culling_is_conservative() {
        let f = fit_around(
            DVec3::new(0.0, 10.0, 0.0),
            &aabb([-1.0, 0.0, -1.0], [1.0, 1.0, 1.0]),
        )
        .unwrap();
        assert!(f.intersects(&aabb([0.5, 0.5, 0.5], [3.0, 3.0, 3.0])));
        assert!(!f.intersects(&aabb([5.0, 0.0, 5.0], [6.0, 1.0, 6.0])));
        assert!(
            !f.intersects(&aabb([-1.0, 20.0, -1.0], [1.0, 21.0, 1.0])),
            "behind the light"
        );
    }

    #[test]
    fn casters_outside_the_receivers_cone_are_dropped() {
        let ground = aabb([-10.0, -0.1, -10.0], [10.0, 0.0, 10.0]);
        let above = aabb([-0.5, 2.0, -0.5], [0.5, 2.5, 0.5]);
        let far_away = aabb([8.0, 0.0, 8.0], [9.0, 1.0, 9.0]);
        let light = DVec3::new(0.0, 10.0, 0.0);
        let layout = ShadowLayout::fit(light, &[ground, above, far_away], 0.0);
        // The camera sees only the ground right under the light.
        let visible = aabb([-1.0, -0.1, -1.0], [1.0, 0.0, 1.0]);
        let casters = [Some(ground), Some(above), Some(far_away)];
        let selected = select_casters(&layout, &casters, &visible);
        assert_eq!(selected[0], vec![0, 1]);
        assert!(select_casters(&layout, &casters, &Aabb::EMPTY)[0].is_empty());
    }
}
