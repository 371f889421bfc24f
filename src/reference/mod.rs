//! The CPU reference: a ray tracer that renders the same scene, camera, light
//! and BRDF as the GPU path, in f64 through `physics`, exactly where it can be
//! (point light: one shadow ray gives V ∈ {0, 1}) and by stratified Monte Carlo
//! with a noise estimate where it cannot (the sphere light's penumbra).
//!
//! It shares no code with `gpu`: it judges the renderer. Per pixel, the primary
//! ray is the camera's ray ([`PixelRays`](crate::scene::camera::PixelRays),
//! cast along a direction that is not normalized)
//! through the pixel centre (one sample per pixel) or through jittered strata
//! of the pixel square (more samples, box filter). See `shading` for the
//! radiance and the shadow-ray epsilon, `bvh` for exact ray casting (an f32
//! BVH that never misses, an f64 watertight triangle test that decides),
//! `grid` for the faster exact path of rays from the eye and to a point
//! light, `sampling` for strata and the noise estimate.
//!
//! ```no_run
//! # use lumlab::{reference::*, scene, settings::Settings};
//! let settings = Settings::default();
//! let reference = Reference::new(&scene::default_scene());
//! let image = reference.render(&settings, &ReferenceOptions::default(), &RenderControl::default())?;
//! let png = image.to_display_rgba8(settings.view.exposure_ev as f64);
//! # Ok::<(), ReferenceError>(())
//! ```

pub mod bvh;
pub mod grid;
mod image;
pub mod intersect;
mod light_packet;
mod render;
pub mod sampling;
mod shading;
mod simd;
mod spectral;
mod sphere;
mod surface;
mod texture;

pub use image::{NoiseSummary, ReferenceImage, RenderStats, luminance};
pub use shading::{SHADOW_OFFSET_REL, STOP_SHORT_REL, ShadingSample};

use crate::scene::{Material, Mesh, Scene};
use crate::settings::{Settings, SettingsError};
use bvh::{BvhTriangle, TriangleBvh, TriangleSource};
use glam::{DVec3, Vec2, Vec3};
use rayon::prelude::*;
use sampling::Rng;
use shading::Setup;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use texture::LinearTexture;

/// How much work the reference does per pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ReferenceOptions {
    /// Primary samples per pixel: 1 is the pixel centre; more are jittered
    /// over a grid of strata of the pixel square (box filter).
    pub spp: u32,
    /// Strata N of the sphere light's cone per primary sample (ignored for a
    /// point light). Squares (16, 64, 256) stratify best.
    pub light_samples: u32,
    /// Seed of every random number: same seed, same image.
    pub seed: u64,
    /// Sample the sphere light even where no shadow ray can be blocked
    /// (plain Monte Carlo everywhere, to show its noise). Off: there the
    /// diffuse part is the closed form, exact and without noise.
    pub sample_everywhere: bool,
}

impl ReferenceOptions {
    /// The pixel centre, 64 light samples (8 × 8 strata), seed 0, the
    /// closed form where nothing blocks the light.
    pub const DEFAULT: Self = Self {
        spp: 1,
        light_samples: 64,
        seed: 0,
        sample_everywhere: false,
    };
}

impl Default for ReferenceOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Progress and cancellation, shared with the thread that watches a render.
#[derive(Debug, Default)]
pub struct RenderControl {
    /// Pixels finished so far (of width × height).
    pub pixels_done: AtomicUsize,
    /// Set to stop the render; it then returns [`ReferenceError::Cancelled`].
    pub cancel: AtomicBool,
}

impl RenderControl {
    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }

    fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }
}

#[derive(Debug, thiserror::Error)]
pub enum ReferenceError {
    #[error("the reference render was cancelled")]
    Cancelled,
    #[error(transparent)]
    Settings(#[from] SettingsError),
}

/// One triangle's place in the scene, in the scene's order: its object
/// and its index in the object's mesh, whose vertices ([`ObjectInfo`])
/// hold its corners, normals and uvs. Its face normal, flat normal and
/// shadow offset are worked out when a ray meets it
/// (`TriangleShading::new`), not stored: 8 bytes a triangle, where copies
/// of what the mesh stores took 112 (on the generated 1 M-triangle scene,
/// 104 MB less to write, fault in and hold, for 22 MB of copied meshes).
#[derive(Clone, Copy, Debug)]
struct TriangleInfo {
    object: u32,
    /// Index within the object's mesh.
    index: u32,
}

impl TriangleInfo {
    fn object(&self) -> usize {
        self.object as usize
    }

    fn index(&self) -> usize {
        self.index as usize
    }
}

/// The normalized vertex normal when all three are equal (a flat facet:
/// interpolating and normalizing would give it again), `face` where it
/// vanishes.
fn flat_normal([n0, n1, n2]: [Vec3; 3], face: DVec3) -> Option<DVec3> {
    (n0 == n1 && n0 == n2).then(|| n0.as_dvec3().normalize_or(face))
}

/// How far shadow rays start off a triangle of these corners (m):
/// [`SHADOW_OFFSET_REL`] × its largest |coordinate|.
fn shadow_offset_m(corners: &[DVec3; 3]) -> f64 {
    SHADOW_OFFSET_REL * intersect::extent(corners)
}

/// How far the light must lie on the lifted side of a triangle's plane
/// (along its unit normal, `to_light` from a point of it) for a shadow ray
/// lifted `offset_m` off it never to reach that plane: the lift, and the
/// rounding of the dot product.
#[inline(always)]
fn lift_clearance(offset_m: f64, to_light: DVec3) -> f64 {
    offset_m + 1e-12 * to_light.abs().element_sum()
}

/// Whether a shadow ray lifted by `offset_m` along g (its face's unit
/// normal on the lifted side) never reaches its own triangle's plane: the
/// light (`to_light` from the point) lies on that side by more than the
/// lift and the rounding of the dot product.
#[inline(always)]
fn lift_clears(offset_m: f64, g: DVec3, to_light: DVec3) -> bool {
    g.dot(to_light) > lift_clearance(offset_m, to_light)
}

/// `triangle` when a shadow ray lifted by `offset_m` along g off a point
/// of it, `to_light` from that point, cannot reach it ([`lift_clears`]):
/// the ray may then pass over it.
#[inline(always)]
fn own_unreached(triangle: usize, offset_m: f64, g: DVec3, to_light: DVec3) -> Option<usize> {
    lift_clears(offset_m, g, to_light).then_some(triangle)
}

#[derive(Clone, Debug)]
struct ObjectInfo {
    /// Index into `Reference::materials` (always valid).
    material: usize,
    /// The scene's material index, None when it was out of range.
    material_index: Option<usize>,
    receives_shadows: bool,
    /// Its triangles block shadow rays.
    casts_shadows: bool,
    /// The mesh: its vertices and indices, which its triangles' shading
    /// reads (per vertex, not copied per triangle).
    mesh: Mesh,
}

impl ObjectInfo {
    /// The vertex indices of the mesh's triangle `index`: inside the mesh
    /// for every triangle the reference keeps (see [`kept_triangles`]).
    fn ids(&self, index: usize) -> [usize; 3] {
        let ids = &self.mesh.indices[3 * index..3 * index + 3];
        [ids[0] as usize, ids[1] as usize, ids[2] as usize]
    }

    /// The corners of the mesh's triangle `index`, in f32 as the mesh
    /// holds them.
    fn positions(&self, index: usize) -> [Vec3; 3] {
        self.ids(index).map(|i| self.mesh.positions[i])
    }

    /// The corners of the mesh's triangle `index`, in f64 (exact).
    fn corners(&self, index: usize) -> [DVec3; 3] {
        bvh::widened(&self.positions(index))
    }

    /// Its vertex normals; a missing one counts as zero: where the
    /// interpolated normal vanishes, `surface` uses the face's own (so does
    /// the GPU, shade.wgsl's surface_at).
    fn normals(&self, index: usize) -> [Vec3; 3] {
        self.ids(index)
            .map(|i| self.mesh.normals.get(i).copied().unwrap_or(Vec3::ZERO))
    }

    /// Its uvs (all zero where one is missing).
    fn uvs(&self, index: usize) -> [Vec2; 3] {
        corner_values(&self.mesh.uvs, self.ids(index)).unwrap_or([Vec2::ZERO; 3])
    }

    /// Whether its vertex colours vary the base colour.
    fn has_colours(&self) -> bool {
        !self.mesh.colours.is_empty()
    }

    /// The vertex colours at the corners of the mesh's triangle `index`,
    /// None without colours (1, as the GPU uploads).
    fn corner_colours(&self, index: usize) -> Option<[Vec3; 3]> {
        corner_values(&self.mesh.colours, self.ids(index))
    }
}

/// A scene prepared for ray tracing: build once, render many settings.
pub struct Reference {
    bvh: TriangleBvh,
    /// The BVH's triangles, in the order of `triangles`: what the direction
    /// grids are built from, so kept only where they are (see
    /// `render::GRID_MAX_TRIANGLES`; 79 MB on 1 M triangles).
    grid_triangles: Vec<BvhTriangle>,
    triangles: Vec<TriangleInfo>,
    objects: Vec<ObjectInfo>,
    /// The scene's materials, then the default one for invalid indices.
    materials: Vec<Material>,
    textures: Vec<Option<LinearTexture>>,
    /// Triangles left out: indices out of range.
    skipped_triangles: usize,
}

impl Reference {
    /// Flattens the scene's triangles and builds the BVH. Triangles whose
    /// indices point outside their mesh are skipped (counted).
    pub fn new(scene: &Scene) -> Self {
        let mut materials = scene.materials.clone();
        let fallback = materials.len();
        materials.push(Material::default());
        let objects: Vec<ObjectInfo> = scene
            .objects
            .iter()
            .map(|object| {
                let material_index = (object.material < fallback).then_some(object.material);
                ObjectInfo {
                    material: material_index.unwrap_or(fallback),
                    material_index,
                    receives_shadows: object.receives_shadows,
                    casts_shadows: object.casts_shadows,
                    mesh: object.mesh.clone(),
                }
            })
            .collect();
        let triangles = kept_triangles(scene);
        // The BVH reads the corners from the meshes in place. Gathered
        // first (40 bytes a triangle), they took 26 ms of one thread on
        // 1 M triangles while the other waited: in place, that scene's
        // BVH line is 3 % shorter and its peak some 35 MB lower, the same
        // bytes. Only the direction grids take a list, and only small
        // scenes build them.
        let source = MeshSource {
            objects: &objects,
            triangles: &triangles,
        };
        let (grid_triangles, bvh) = rayon::join(
            || {
                if render::builds_grids(triangles.len()) {
                    source.listed()
                } else {
                    Vec::new()
                }
            },
            || TriangleBvh::of(&source),
        );
        Self {
            bvh,
            skipped_triangles: scene.triangle_count() - triangles.len(),
            grid_triangles,
            triangles,
            objects,
            materials,
            textures: scene.textures.iter().map(LinearTexture::new).collect(),
        }
    }

    /// Triangles that rays can hit (degenerate ones left out).
    pub fn triangle_count(&self) -> usize {
        self.bvh.len()
    }

    /// Triangles left out because their indices point outside their mesh.
    pub fn skipped_triangles(&self) -> usize {
        self.skipped_triangles
    }

    /// Everything about the primary sample through image point (x, y) of
    /// the settings' image (pixels; the centre of pixel (i, j) is
    /// (i + 0.5, j + 0.5)); None on background. At a pixel centre with one
    /// sample per pixel this is exactly the sample `render` took there.
    pub fn trace_pixel(
        &self,
        settings: &Settings,
        options: &ReferenceOptions,
        x: f64,
        y: f64,
    ) -> Option<ShadingSample> {
        let setup = Setup::new(settings, options, &self.materials);
        let pixel = pixel_index(&setup, x.floor(), y.floor());
        let mut rng = Rng::new(options.seed, pixel, 0);
        self.probe(&setup, x, y, &mut rng)
    }
}

/// Every triangle of the scene whose indices lie inside its mesh, in
/// order: an object's all at once on the pool where all of them do (the
/// loaders leave no other), else one by one.
fn kept_triangles(scene: &Scene) -> Vec<TriangleInfo> {
    let mut kept = Vec::with_capacity(scene.triangle_count());
    for (object, o) in scene.objects.iter().enumerate() {
        let mesh = &o.mesh;
        let (triangles, _) = mesh.indices.as_chunks::<3>();
        let inside = |t: &[u32; 3]| t.iter().all(|&i| (i as usize) < mesh.positions.len());
        // A glTF mesh's indices and the scene's objects number fewer than
        // 2³² (its accessors count in u32).
        let info = |index: usize| TriangleInfo {
            object: object as u32,
            index: index as u32,
        };
        if triangles.par_iter().all(inside) {
            kept.par_extend((0..triangles.len()).into_par_iter().map(info));
        } else {
            kept.extend((0..triangles.len()).filter(|&t| inside(&triangles[t])).map(info));
        }
    }
    kept
}

/// The kept triangles as the BVH reads them: from the meshes, in place.
struct MeshSource<'a> {
    objects: &'a [ObjectInfo],
    triangles: &'a [TriangleInfo],
}

impl MeshSource<'_> {
    /// Every triangle, listed.
    fn listed(&self) -> Vec<BvhTriangle> {
        (0..self.count())
            .map(|i| BvhTriangle {
                corners: self.corners(i),
                occludes: self.occludes(i),
            })
            .collect()
    }
}

impl TriangleSource for MeshSource<'_> {
    fn count(&self) -> usize {
        self.triangles.len()
    }

    fn corners(&self, i: usize) -> [Vec3; 3] {
        let t = self.triangles[i];
        self.objects[t.object()].positions(t.index())
    }

    fn occludes(&self, i: usize) -> bool {
        self.objects[self.triangles[i].object()].casts_shadows
    }
}

/// The values of `values` at the three indices, None when one is out of range.
fn corner_values<T: Copy>(values: &[T], ids: [usize; 3]) -> Option<[T; 3]> {
    Some([*values.get(ids[0])?, *values.get(ids[1])?, *values.get(ids[2])?])
}

/// The pixel's number for seeding its random streams (clamped into the image).
fn pixel_index(setup: &Setup, i: f64, j: f64) -> u64 {
    let i = i.clamp(0.0, setup.width.saturating_sub(1) as f64) as u64;
    let j = j.clamp(0.0, setup.height.saturating_sub(1) as f64) as u64;
    j * setup.width as u64 + i
}

#[cfg(test)]
mod tests;
