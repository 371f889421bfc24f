//! Where a primary ray lands, and the surface there: what the triangle
//! gives every point of it (material, colour, BRDF parameters, normals),
//! worked out once in [`TriangleShading`], and what each point adds
//! (position, direction to the eye, interpolated normal, uv, texture).

use super::bvh::Hit;
use super::grid::{Answer, Cell};
use super::light_packet::LightPacket;
use super::shading::Setup;
use super::{ObjectInfo, Reference, flat_normal, own_unreached, shadow_offset_m};
use crate::physics::BrdfParams;
use crate::physics::colour::tint;
use crate::scene::Material;
use glam::{DVec2, DVec3, Vec2};

/// Where a primary ray lands, and the surface there as the light sees it.
pub(super) struct Surface {
    /// Index into `Reference::triangles`.
    pub(super) triangle: usize,
    pub(super) p: DVec3,
    /// The shading normal (towards the viewer on double-sided materials).
    pub(super) n: DVec3,
    /// The face's normal on the viewer's side.
    pub(super) geometric_normal: DVec3,
    /// Unit direction to the eye.
    pub(super) o: DVec3,
    /// c · light colour: L = tint · LightEstimate::scaled_radiance.
    pub tint: DVec3,
    pub(super) brdf: BrdfParams<f64>,
    /// p lifted off the surface for shadow rays, by `shadow_offset_m`.
    pub(super) shadow_origin: DVec3,
    pub(super) shadow_offset_m: f64,
    /// Shadow rays are cast (shadows on and the object receives them).
    pub(super) shadowed: bool,
}

impl Surface {
    /// Where its shadow ray to a point light at `light` starts, the face's
    /// normal on the light's side, and its triangle where the ray cannot
    /// reach it (`usize::MAX` where it may: see
    /// `own_unreached`); None when it casts none (nearly
    /// certainly: a light on its horizon may go either way).
    pub(super) fn shadow_ray(&self, light: DVec3) -> Option<(DVec3, DVec3, usize)> {
        shadow_ray(
            light,
            (self.triangle, self.shadowed),
            (self.p, self.n, self.geometric_normal),
            (self.shadow_origin, self.shadow_offset_m),
        )
    }
}

/// [`Surface::shadow_ray`] of the point p of `triangle` (`shadowed`: it
/// casts shadow rays) of shading normal n and face normal g on the eye's
/// side, lifted to `origin` by `offset_m`.
#[inline(always)]
pub(super) fn shadow_ray(
    light: DVec3,
    (triangle, shadowed): (usize, bool),
    (p, n, g): (DVec3, DVec3, DVec3),
    (origin, offset_m): (DVec3, f64),
) -> Option<(DVec3, DVec3, usize)> {
    let to_light = light - p;
    (shadowed && n.dot(to_light) > 0.0).then(|| {
        let own = own_unreached(triangle, offset_m, g, to_light).unwrap_or(usize::MAX);
        (origin, if g.dot(to_light) < 0.0 { -g } else { g }, own)
    })
}

/// A triangle's corners, normals and BRDF in f64: what a point of it needs
/// for its position, its normal and its light (`TriangleShading::point`,
/// and `render::lanes` for many points at once).
#[derive(Clone, Copy, Debug)]
pub(super) struct Facet {
    pub(super) corners: [DVec3; 3],
    /// The vertex normals, None on a flat facet.
    pub(super) normals: Option<[DVec3; 3]>,
    /// The flat facet's normal, or the face's where the interpolated one
    /// vanishes.
    pub(super) normal: DVec3,
    pub(super) double_sided: bool,
    pub(super) brdf: BrdfParams<f64>,
}

impl Facet {
    /// The point at barycentrics b.
    #[inline(always)]
    pub(super) fn point_at(&self, [b0, b1, b2]: [f64; 3]) -> DVec3 {
        let [a, b, c] = self.corners;
        a * b0 + b * b1 + c * b2
    }

    /// The shading normal at barycentrics b, before it turns towards the
    /// viewer. Missing vertex normals are zero: where the interpolated
    /// normal vanishes, the face's own (winding) normal is used, as on the
    /// GPU (shade.wgsl's surface_at); tests/wgsl_parity.rs holds both to it.
    #[inline(always)]
    pub(super) fn normal_at(&self, [b0, b1, b2]: [f64; 3]) -> DVec3 {
        match self.normals {
            Some([n0, n1, n2]) => (n0 * b0 + n1 * b1 + n2 * b2).normalize_or(self.normal),
            None => self.normal,
        }
    }
}

/// What every point of one triangle shares, under one setup.
pub(super) struct TriangleShading<'a> {
    setup: &'a Setup,
    triangle: usize,
    /// Its index within its object's mesh, its uvs and its shadow offset.
    index: usize,
    uvs: [Vec2; 3],
    shadow_offset_m: f64,
    object: &'a ObjectInfo,
    material: &'a Material,
    /// The face's unit normal (counter-clockwise winding).
    face: DVec3,
    /// The colour and tint where neither a texture nor vertex colours
    /// vary them over the triangle.
    plain: Option<(DVec3, DVec3)>,
    facet: Facet,
}

impl<'a> TriangleShading<'a> {
    pub(super) fn new(reference: &'a Reference, setup: &'a Setup, triangle: usize) -> Self {
        let tri = &reference.triangles[triangle];
        let object = &reference.objects[tri.object()];
        // An index out of range was mapped to the default material when the
        // reference was built; the GPU's materials buffer does the same.
        let material = &reference.materials[object.material];
        let own = |value: Option<f32>, default: f64| match value {
            Some(v) if setup.use_scene_materials => v as f64,
            _ => default,
        };
        let varies = material.base_color_texture.is_some() || object.has_colours();
        let index = tri.index();
        let corners = object.corners(index);
        // The face's unit normal (counter-clockwise winding); zero for a
        // degenerate one.
        let face = (corners[1] - corners[0])
            .cross(corners[2] - corners[0])
            .normalize_or_zero();
        let normals = object.normals(index);
        let flat = flat_normal(normals, face);
        let mut shading = Self {
            setup,
            triangle,
            index,
            uvs: object.uvs(index),
            shadow_offset_m: shadow_offset_m(&corners),
            object,
            material,
            face,
            plain: None,
            facet: Facet {
                corners,
                normals: flat.is_none().then(|| normals.map(|n| n.as_dvec3())),
                normal: flat.unwrap_or(face),
                double_sided: material.double_sided,
                brdf: BrdfParams {
                    k: own(material.k, setup.k),
                    m: own(material.m, setup.m),
                    norm: setup.norm,
                },
            },
        };
        shading.plain = (!varies).then(|| shading.colour_and_tint(DVec3::ONE));
        shading
    }

    /// The colour c and the tint, under a modulation of the base colour
    /// (texture × vertex colour) of `modulation`.
    fn colour_and_tint(&self, modulation: DVec3) -> (DVec3, DVec3) {
        let setup = self.setup;
        let color = match setup.color_override {
            Some(c) => c,
            None => self.material.base_color.truncate().as_dvec3() * modulation,
        };
        let surface_tint = match &setup.spectral {
            None => tint(color, setup.light_color),
            // They modulate the spectral colour as they do the RGB one.
            Some(light) if setup.color_override.is_none() => {
                light.reflected_rgb(self.object.material) * modulation
            }
            Some(light) => light.reflected_rgb(self.object.material),
        };
        (color, surface_tint)
    }

    /// The point where the primary ray along `towards` (not normalized)
    /// meets the triangle at `hit`, its shading normal (towards the viewer
    /// on double-sided materials) and the unit direction to the eye: what
    /// the light at a point needs of it.
    #[inline(always)]
    pub(super) fn point(&self, towards: DVec3, hit: Hit) -> (DVec3, DVec3, DVec3) {
        let length = towards.length();
        let b = hit.at.barycentric;
        let p = self.facet.point_at(b);
        let o = -towards / length;
        let mut n = self.facet.normal_at(b);
        if self.facet.double_sided && n.dot(o) < 0.0 {
            n = -n;
        }
        (p, n, o)
    }

    /// The tint of every point, where neither a texture nor vertex colours
    /// vary it.
    pub(super) fn plain_tint(&self) -> Option<DVec3> {
        self.plain.map(|(_, tint)| tint)
    }

    /// Its corners, normals and BRDF in f64.
    pub(super) fn facet(&self) -> &Facet {
        &self.facet
    }

    /// Whether its points cast shadow rays (shadows on and the object
    /// receives them).
    pub(super) fn shadowed(&self) -> bool {
        self.setup.shadows && self.object.receives_shadows
    }

    /// The face's normal on the eye's side, `to_eye` pointing there (any
    /// length).
    pub(super) fn geometric_normal(&self, to_eye: DVec3) -> DVec3 {
        let face = self.face;
        if face.dot(to_eye) < 0.0 { -face } else { face }
    }

    /// The face's normal on the eye's side at the point p seen along o
    /// (towards the eye, any length), and p lifted along it for shadow rays.
    #[inline(always)]
    pub(super) fn lift(&self, p: DVec3, o: DVec3) -> (DVec3, DVec3) {
        let g = self.geometric_normal(o);
        (g, p + g * self.shadow_offset_m)
    }

    /// How far [`Self::lift`] lifts a point (m).
    pub(super) fn shadow_offset_m(&self) -> f64 {
        self.shadow_offset_m
    }

    /// Whether the shadow ray of the point p seen along o (unit, towards
    /// the eye) to the point light is blocked: `Surface`'s, for points
    /// that need no more of it.
    pub(super) fn blocked_from_light(
        &self,
        reference: &Reference,
        (p, o): (DVec3, DVec3),
        packet: &mut LightPacket,
    ) -> bool {
        let (g, origin) = self.lift(p, o);
        reference.blocked_from_point(
            self.setup,
            (self.triangle, p, g),
            (origin, self.shadow_offset_m),
            packet,
        )
    }

    /// The surface where the primary ray along `towards` (not normalized)
    /// meets the triangle at `hit` (barycentrics and distance).
    #[inline(always)]
    pub(super) fn surface(&self, reference: &Reference, towards: DVec3, hit: Hit) -> Surface {
        let (p, n, o) = self.point(towards, hit);
        let (geometric_normal, shadow_origin) = self.lift(p, o);
        let tint = self.tint_at(reference, hit.at.barycentric);
        Surface {
            triangle: self.triangle,
            p,
            n,
            geometric_normal,
            o,
            tint,
            brdf: self.facet.brdf,
            shadow_origin,
            shadow_offset_m: self.shadow_offset_m,
            shadowed: self.shadowed(),
        }
    }

    /// What the probe shows of the point at `hit` beside its [`Surface`]:
    /// its distance from the eye along `towards`, its uv and its colour c.
    pub(super) fn probe_values(
        &self,
        reference: &Reference,
        towards: DVec3,
        hit: Hit,
    ) -> (f64, DVec2, DVec3) {
        let (uv, colour, _) = self.uv_colour_and_tint(reference, hit.at.barycentric);
        (hit.at.t * towards.length(), uv, colour)
    }

    /// The tint at barycentrics b.
    #[inline(always)]
    pub(super) fn tint_at(&self, reference: &Reference, b: [f64; 3]) -> DVec3 {
        // The uv only where a texture needs it.
        self.plain_tint()
            .unwrap_or_else(|| self.uv_colour_and_tint(reference, b).2)
    }

    /// The uv at barycentrics b, and the colour c and tint there.
    #[inline(always)]
    fn uv_colour_and_tint(&self, reference: &Reference, [b0, b1, b2]: [f64; 3]) -> (DVec2, DVec3, DVec3) {
        let [t0, t1, t2] = self.uvs.map(|t| t.as_dvec2());
        let uv = t0 * b0 + t1 * b1 + t2 * b2;
        let (colour, tint) = self.plain.unwrap_or_else(|| {
            let texture = self
                .material
                .base_color_texture
                .and_then(|t| reference.textures.get(t)?.as_ref())
                .map(|texture| texture.sample(uv));
            // The texture and the vertex colours modulate the base colour.
            let vertex_colour = self
                .object
                .corner_colours(self.index)
                .map_or(DVec3::ONE, |[c0, c1, c2]| {
                    c0.as_dvec3() * b0 + c1.as_dvec3() * b1 + c2.as_dvec3() * b2
                });
            self.colour_and_tint(texture.unwrap_or(DVec3::ONE) * vertex_colour)
        });
        (uv, colour, tint)
    }
}

impl Reference {
    /// The surface seen along `towards` from the eye (`PixelRays::towards`
    /// of an image point) and what the probe shows beside it
    /// ([`TriangleShading::probe_values`]); None on background.
    pub(super) fn probed_surface(
        &self,
        setup: &Setup,
        towards: DVec3,
    ) -> Option<(Surface, (f64, DVec2, DVec3))> {
        let hit = self.primary_hit(setup, towards, None)?;
        let shading = TriangleShading::new(self, setup, hit.triangle);
        Some((
            shading.surface(self, towards, hit),
            shading.probe_values(self, towards, hit),
        ))
    }

    /// The closest hit along `towards` from the eye, as [`Self::probed_surface`]
    /// finds it.
    #[inline(always)]
    pub(super) fn primary_hit(&self, setup: &Setup, towards: DVec3, cell: Option<Cell>) -> Option<Hit> {
        // The ray is cast along a direction that is not normalized: the
        // normalization (a square root and a division) then runs beside
        // the intersection instead of before it, which is 18 % faster.
        let answer = setup.eye_grid.as_ref().map(|g| match cell {
            Some(cell) => g.closest_in(cell, towards),
            None => g.closest_from_centre(towards),
        });
        match answer {
            Some(Answer::Known(hit)) => hit,
            _ => self.bvh.closest_hit(setup.rays.eye, towards, 0.0, f64::INFINITY),
        }
    }

    /// The surface where the primary ray along `towards` (not normalized)
    /// lands, its closest hit being `hit`, with the shading of its triangle
    /// from `cache` (kept, or made anew): neighbouring samples mostly meet
    /// the same few triangles.
    #[inline(always)]
    pub(super) fn surface_at<'a>(
        &'a self,
        setup: &'a Setup,
        towards: DVec3,
        hit: Hit,
        cache: &mut ShadingCache<'a>,
    ) -> Surface {
        cache.get(self, setup, hit.triangle).surface(self, towards, hit)
    }
}

/// How many triangles' shading a [`ShadingCache`] keeps.
const CACHED: usize = 8;

/// The shading of the triangles met last, by triangle index modulo
/// [`CACHED`] (a pixel's edge alternates between two or three).
pub(super) struct ShadingCache<'a> {
    slots: [Option<TriangleShading<'a>>; CACHED],
}

impl<'a> ShadingCache<'a> {
    /// The shading of `triangle`: kept, or made anew.
    #[inline(always)]
    pub(super) fn get(
        &mut self,
        reference: &'a Reference,
        setup: &'a Setup,
        triangle: usize,
    ) -> &TriangleShading<'a> {
        let slot = &mut self.slots[triangle % CACHED];
        if slot.as_ref().is_some_and(|kept| kept.triangle != triangle) {
            *slot = None;
        }
        slot.get_or_insert_with(|| TriangleShading::new(reference, setup, triangle))
    }
}

impl Default for ShadingCache<'_> {
    fn default() -> Self {
        Self {
            slots: std::array::from_fn(|_| None),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::ReferenceOptions;
    use crate::reference::intersect::TriangleHit;
    use crate::scene::{Object, Scene, shapes};
    use crate::settings::Settings;
    use glam::{Vec3, Vec4};

    /// Samples that hop between many triangles (more than the cache keeps,
    /// many of them in the same slot), of two materials and of every
    /// orientation, get the surface their own triangle's shading gives.
    #[test]
    fn the_shading_cache_gives_each_triangle_its_own_surface() {
        let material = |colour: Vec4| Material {
            base_color: colour,
            ..Material::default()
        };
        let scene = Scene {
            objects: vec![
                Object::new("red", shapes::sphere(Vec3::ZERO, 1.0, 12, 8), 0),
                Object::new("blue", shapes::sphere(Vec3::new(3.0, 0.0, 0.0), 1.0, 12, 8), 1),
            ],
            materials: vec![
                material(Vec4::new(0.8, 0.1, 0.1, 1.0)),
                material(Vec4::new(0.1, 0.2, 0.9, 1.0)),
            ],
            ..Scene::default()
        };
        let reference = Reference::new(&scene);
        let setup = Setup::new(
            &Settings::default(),
            &ReferenceOptions::default(),
            &reference.materials,
        );
        let count = reference.triangles.len();
        assert!(count > 8 * CACHED);
        let mut cache = ShadingCache::default();
        let towards = DVec3::new(0.1, -0.2, -1.0);
        for step in 0..2000 {
            // Strides that fill and evict every slot.
            let triangle = (step * 7 + (step / 5) * CACHED) % count;
            let hit = Hit {
                triangle,
                at: TriangleHit {
                    t: 2.0,
                    barycentric: [0.2, 0.3, 0.5],
                },
            };
            let got = reference.surface_at(&setup, towards, hit, &mut cache);
            let fresh = TriangleShading::new(&reference, &setup, triangle).surface(&reference, towards, hit);
            assert_eq!(got.triangle, triangle);
            assert_eq!(
                (got.p, got.n, got.geometric_normal, got.tint, got.shadow_origin),
                (
                    fresh.p,
                    fresh.n,
                    fresh.geometric_normal,
                    fresh.tint,
                    fresh.shadow_origin
                ),
                "step {step}, triangle {triangle}"
            );
        }
    }
}
