//! Simplified copies of a large scene's meshes, for the app's drag frames
//! only.
//!
//! On a software adapter a drag frame of a large model is bound by the
//! rasterizer's triangle setup, which runs on one thread whatever the image
//! size: lavapipe spends 50–67 ms on the 110 k triangles of the engine
//! model even at a quarter of the viewport's side, so the render scale
//! cannot bring such a drag to 30 frames/s. Fewer triangles can. Each mesh is
//! simplified by meshoptimizer's edge collapses under a quadric error
//! (`meshopt::simplify`): attribute seams (a hard edge's split normals, a
//! texture seam) are kept by the simplifier itself, and the error is
//! bounded in scene units, so a silhouette or an open border moves by at
//! most [`MAX_ERROR`] of the model's size. Open borders are not locked in
//! place: the engine model's CAD parts are open along most of their edges,
//! and locking them kept 26 k of its 110 k triangles (17 k unlocked). The
//! result is an index list per object into the object's own vertices: the
//! GPU keeps one vertex buffer and draws these indices instead of the full
//! ones.
//!
//! The shadow map gets a coarser copy of its own ([`SimplifiedMeshes::casters`]):
//! depth from the light needs positions only, so each mesh is first welded
//! (every corner replaced by the first vertex at the same position). A hard
//! edge's split normals are then no seam, and the simplifier collapses
//! across them: the engine model's casters fall to 5.2 k triangles within
//! the same error bound, where the camera's copy, which must keep those
//! normals, stops at 17 k. A light drag redraws the map every frame, and on
//! lavapipe its cost is that of its triangles (9 ms → 3.6 ms). Where the
//! two copies differ, a surface may shadow itself a little differently
//! while the light moves; the still frame after the drag draws the full
//! meshes in both passes.
//!
//! Under ray-traced visibility a drag frame's shadow rays meet the camera's
//! copy, the very triangles the frame shades, through a BVH of its own
//! ([`SimplifiedMeshes::bvh`], built on the same thread): against the full
//! meshes a simplified surface would shadow itself wherever it sank below
//! them.
//!
//! Still frames, the probe, the error statistics, the CPU reference and
//! every exported image keep the full meshes: the simplified ones are an
//! approximation shown only while the user drags.

use super::Scene;
use crate::gpu::bvh::FlatBvh;
use std::sync::Arc;
use std::sync::mpsc::{Receiver, channel};

/// Scenes with more triangles than this get simplified meshes for drags.
/// The default scene (a few thousand) never does; the 110 k-triangle engine
/// model does.
pub const THRESHOLD_TRIANGLES: usize = 50_000;
/// The triangles the simplified meshes aim at, all objects together.
pub const TARGET_TRIANGLES: usize = 10_000;
/// The triangles the shadow casters' copy aims at, all objects together.
pub const CASTER_TARGET_TRIANGLES: usize = 3_000;
/// The largest error a collapse may introduce, as a fraction of the model's
/// bounding diagonal: the simplifier stops there even above the target.
pub const MAX_ERROR: f32 = 2e-2;

/// How one copy is made.
struct Recipe {
    /// Triangles aimed at, all objects together.
    target: usize,
    /// Objects with at most this many triangles are kept whole, and no
    /// object goes below it.
    kept_whole: usize,
    /// Welded by position first (see [`Welded`]): for a copy whose normals
    /// and texture coordinates are never read.
    weld: bool,
}

/// The camera's copy: small parts (64 triangles or fewer) are kept whole,
/// there is little to gain and they would lose their shape in shading.
const CAMERA: Recipe = Recipe {
    target: TARGET_TRIANGLES,
    kept_whole: 64,
    weld: false,
};

/// The shadow casters' copy: only its silhouettes from the light show, and
/// the error bound keeps them. The engine model's 74 parts held at 64
/// triangles each kept 8.9 k casters (5.0 ms of lavapipe's shadow pass in a
/// light drag), held at 8 they keep 5.2 k (3.6 ms).
const CASTERS: Recipe = Recipe {
    target: CASTER_TARGET_TRIANGLES,
    kept_whole: 8,
    weld: true,
};

/// A scene's simplified meshes: per object, three indices a triangle into
/// that object's vertices (`Scene::objects[i].mesh.positions`).
#[derive(Clone, Debug, PartialEq)]
pub struct SimplifiedMeshes {
    /// What the camera pass draws: seams and split normals kept.
    pub indices: Vec<Vec<u32>>,
    /// What the shadow pass draws: welded by position, then simplified
    /// towards [`CASTER_TARGET_TRIANGLES`] within the same error bound.
    pub casters: Vec<Vec<u32>>,
    /// The shadow casters of the camera's copy as the GPU ray tracer's BVH:
    /// drag frames under ray-traced visibility send their rays against the
    /// very triangles they shade (against the full meshes, a simplified
    /// surface would shadow itself wherever it sank below them).
    pub bvh: FlatBvh,
    pub counts: TriangleCounts,
}

/// Triangles of each copy, all objects together.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TriangleCounts {
    /// The camera's copy ([`SimplifiedMeshes::indices`]).
    pub camera: usize,
    /// The shadow casters' copy ([`SimplifiedMeshes::casters`]).
    pub casters: usize,
    /// The full meshes.
    pub full: usize,
}

/// The simplified meshes of `scene`, or None when it has at most
/// [`THRESHOLD_TRIANGLES`] (its drags draw the full meshes).
pub fn simplify(scene: &Scene) -> Option<SimplifiedMeshes> {
    (scene.triangle_count() > THRESHOLD_TRIANGLES).then(|| SimplifiedMeshes::new(scene))
}

/// Starts [`simplify`] on a thread of its own, so that loading a scene
/// does not wait for it (drags draw the full meshes until it is done); None
/// when the scene is not simplified. The receiver gets one message, or none
/// when the thread fails.
pub fn simplify_in_background(scene: &Arc<Scene>) -> Option<Receiver<SimplifiedMeshes>> {
    if scene.triangle_count() <= THRESHOLD_TRIANGLES {
        return None;
    }
    let (tx, rx) = channel();
    let scene = Arc::clone(scene);
    std::thread::Builder::new()
        .name("lumlab simplify".into())
        .spawn(move || {
            if let Some(meshes) = simplify(&scene) {
                let _ = tx.send(meshes);
            }
        })
        .ok()?;
    Some(rx)
}

impl SimplifiedMeshes {
    /// Both copies of `scene`'s meshes, aiming at [`TARGET_TRIANGLES`]
    /// and [`CASTER_TARGET_TRIANGLES`].
    fn new(scene: &Scene) -> Self {
        let indices = simplify_to(scene, &CAMERA);
        let casters = simplify_to(scene, &CASTERS);
        let count = |lists: &[Vec<u32>]| lists.iter().map(|i| i.len() / 3).sum();
        Self {
            bvh: FlatBvh::of_casters(scene, indices.iter().map(|i| &i[..])),
            counts: TriangleCounts {
                camera: count(&indices),
                casters: count(&casters),
                full: scene.triangle_count(),
            },
            indices,
            casters,
        }
    }
}

/// Each object simplified as `recipe` says, towards its share of the
/// target (its share of the scene's triangles), within [`MAX_ERROR`].
fn simplify_to(scene: &Scene, recipe: &Recipe) -> Vec<Vec<u32>> {
    let ratio = recipe.target as f64 / scene.triangle_count().max(1) as f64;
    let model = scene.model_bounds();
    let diagonal = if model.is_empty() {
        scene.bounds().extent().length()
    } else {
        model.extent().length()
    };
    let max_error = MAX_ERROR * diagonal;
    scene
        .objects
        .iter()
        .map(|object| {
            let mesh = &object.mesh;
            let triangles = mesh.triangle_count();
            let in_range = mesh.indices.iter().all(|&i| (i as usize) < mesh.positions.len());
            if ratio >= 1.0 || triangles <= recipe.kept_whole || !in_range {
                return mesh.indices.clone();
            }
            let wanted = ((triangles as f64 * ratio).ceil() as usize).max(recipe.kept_whole);
            if recipe.weld {
                let welded = Welded::new(&mesh.positions, &mesh.indices);
                let indices = collapse(&welded.positions, &welded.indices, wanted, max_error);
                indices.iter().map(|&i| welded.first[i as usize]).collect()
            } else {
                collapse(&mesh.positions, &mesh.indices, wanted, max_error)
            }
        })
        .collect()
}

/// meshoptimizer's edge collapses on one mesh, towards `wanted` triangles
/// within `max_error` (scene units).
fn collapse(positions: &[glam::Vec3], indices: &[u32], wanted: usize, max_error: f32) -> Vec<u32> {
    let floats: &[f32] = bytemuck::cast_slice(positions);
    let vertices =
        meshopt::VertexDataAdapter::new(bytemuck::cast_slice(floats), 12, 0).expect("three floats a vertex");
    meshopt::simplify(
        indices,
        &vertices,
        3 * wanted,
        max_error,
        meshopt::SimplifyOptions::ErrorAbsolute,
        None,
    )
}

/// A mesh welded by position: one vertex per distinct position (bit for
/// bit), so that triangles cut apart along seams (split normals or
/// texture coordinates) join again. The simplifier must see only these:
/// a vertex that shares its position with another is a seam to it, which
/// it keeps.
struct Welded {
    positions: Vec<glam::Vec3>,
    indices: Vec<u32>,
    /// Per welded vertex: the first of the mesh's vertices at its position.
    first: Vec<u32>,
}

impl Welded {
    fn new(positions: &[glam::Vec3], indices: &[u32]) -> Self {
        let (count, remap) = meshopt::generate_vertex_remap(positions, None);
        let mut first = vec![u32::MAX; count];
        let mut welded = vec![glam::Vec3::ZERO; count];
        for (i, &r) in remap.iter().enumerate() {
            if first[r as usize] == u32::MAX {
                first[r as usize] = i as u32;
                welded[r as usize] = positions[i];
            }
        }
        Self {
            positions: welded,
            indices: indices.iter().map(|&i| remap[i as usize]).collect(),
            first,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::stress::sphere_field;

    #[test]
    fn small_scenes_are_not_simplified() {
        let scene = crate::scene::default_scene();
        assert!(scene.triangle_count() <= THRESHOLD_TRIANGLES);
        assert_eq!(simplify(&scene), None);
    }

    /// Every index list of both copies, as (object, copy's name, indices).
    fn copies(simplified: &SimplifiedMeshes) -> impl Iterator<Item = (usize, &'static str, &Vec<u32>)> {
        let camera = simplified
            .indices
            .iter()
            .enumerate()
            .map(|(i, l)| (i, "camera", l));
        camera.chain(
            simplified
                .casters
                .iter()
                .enumerate()
                .map(|(i, l)| (i, "casters", l)),
        )
    }

    #[test]
    fn a_large_scene_is_simplified_towards_the_targets_within_its_vertices() {
        let scene = sphere_field(2 * THRESHOLD_TRIANGLES);
        let simplified = simplify(&scene).expect("above the threshold");
        let counts = simplified.counts;
        assert_eq!(counts.full, scene.triangle_count());
        assert_eq!(simplified.indices.len(), scene.objects.len());
        assert_eq!(simplified.casters.len(), scene.objects.len());
        assert!(
            counts.camera <= TARGET_TRIANGLES + TARGET_TRIANGLES / 10,
            "{counts:?}"
        );
        assert!(
            counts.casters <= CASTER_TARGET_TRIANGLES + CASTER_TARGET_TRIANGLES / 10,
            "{counts:?}"
        );
        for (object, copy, indices) in copies(&simplified) {
            let vertices = scene.objects[object].mesh.positions.len();
            assert_eq!(indices.len() % 3, 0, "{copy}");
            assert!(indices.iter().all(|&i| (i as usize) < vertices), "{copy}");
        }
    }

    /// Every kept corner of `indices` lies on `scene`'s sphere `object`, and
    /// the triangles' centroids stay within the error bound of it (a
    /// coarser tessellation cuts the chords inwards).
    fn assert_on_sphere(scene: &Scene, object: usize, indices: &[u32]) {
        let sphere = &scene.objects[object];
        let centre = sphere.bounds.center();
        let radius = 0.5 * sphere.bounds.extent().x;
        let diagonal = scene.model_bounds().extent().length();
        for triangle in indices.chunks_exact(3) {
            let corners = [0, 1, 2].map(|k| sphere.mesh.positions[triangle[k] as usize]);
            for c in corners {
                assert!(((c - centre).length() - radius).abs() < 1e-4);
            }
            let centroid = (corners[0] + corners[1] + corners[2]) / 3.0;
            assert!(radius - (centroid - centre).length() < 2.0 * MAX_ERROR * diagonal);
        }
    }

    #[test]
    fn a_simplified_sphere_keeps_its_silhouette_in_both_copies() {
        let scene = sphere_field(2 * THRESHOLD_TRIANGLES);
        let simplified = simplify(&scene).expect("above the threshold");
        let full = scene.objects[1].mesh.indices.len();
        assert!(simplified.indices[1].len() < full / 4);
        assert!(simplified.casters[1].len() <= simplified.indices[1].len());
        assert_on_sphere(&scene, 1, &simplified.indices[1]);
        assert_on_sphere(&scene, 1, &simplified.casters[1]);
    }

    /// A CAD export's hard edges split every corner: here each triangle has
    /// corners of its own, so that every edge is a seam. The camera's copy
    /// must keep them; the casters' copy welds them and simplifies as if the
    /// mesh were smooth.
    #[test]
    fn the_casters_copy_simplifies_across_split_corners() {
        let mut scene = sphere_field(2 * THRESHOLD_TRIANGLES);
        for object in &mut scene.objects[1..] {
            let mesh = &mut object.mesh;
            let corners = |values: &[glam::Vec3]| -> Vec<glam::Vec3> {
                mesh.indices.iter().map(|&i| values[i as usize]).collect()
            };
            let (positions, normals) = (corners(&mesh.positions), corners(&mesh.normals));
            let uvs = mesh.indices.iter().map(|&i| mesh.uvs[i as usize]).collect();
            *mesh = crate::scene::Mesh {
                indices: (0..positions.len() as u32).collect(),
                positions,
                normals,
                uvs,
                colours: Vec::new(),
            };
        }
        let simplified = simplify(&scene).expect("above the threshold");
        let full = scene.objects[1].mesh.indices.len();
        assert!(simplified.indices[1].len() > full / 2, "{:?}", simplified.counts);
        assert!(simplified.casters[1].len() < full / 20, "{:?}", simplified.counts);
        assert_on_sphere(&scene, 1, &simplified.casters[1]);
    }
}
