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
//! and locking them kept 26 k of its 110 k triangles (16.8 k unlocked). The result is an index list per object
//! into the object's own vertices: the GPU keeps one vertex buffer and draws
//! these indices instead of the full ones.
//!
//! Still frames, the probe, the error statistics, the CPU reference and
//! every exported image keep the full meshes: the simplified ones are an
//! approximation shown only while the user drags.

use super::Scene;
use std::sync::Arc;
use std::sync::mpsc::{Receiver, channel};

/// Scenes with more triangles than this get simplified meshes for drags.
/// The default scene (a few thousand) never does; the 110 k-triangle engine
/// model does.
pub const THRESHOLD_TRIANGLES: usize = 50_000;
/// The triangles the simplified meshes aim at, all objects together.
pub const TARGET_TRIANGLES: usize = 10_000;
/// The largest error a collapse may introduce, as a fraction of the model's
/// bounding diagonal: the simplifier stops there even above the target.
pub const MAX_ERROR: f32 = 2e-2;
/// Objects with at most this many triangles are kept whole: there is
/// little to gain, and a small part would lose its shape.
const KEPT_WHOLE_TRIANGLES: usize = 64;

/// A scene's simplified meshes: per object, three indices a triangle into
/// that object's vertices (`Scene::objects[i].mesh.positions`).
#[derive(Clone, Debug, PartialEq)]
pub struct SimplifiedMeshes {
    pub indices: Vec<Vec<u32>>,
    /// Triangles in `indices`, all objects together.
    pub triangles: usize,
    /// Triangles of the full meshes.
    pub full_triangles: usize,
}

/// The simplified meshes of `scene`, or None when it has at most
/// [`THRESHOLD_TRIANGLES`] (its drags draw the full meshes).
pub fn simplify(scene: &Scene) -> Option<SimplifiedMeshes> {
    let full_triangles = scene.triangle_count();
    (full_triangles > THRESHOLD_TRIANGLES).then(|| simplify_to(scene, TARGET_TRIANGLES))
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

/// Each object simplified towards its share of `target` triangles (its
/// share of the scene's), within [`MAX_ERROR`].
pub fn simplify_to(scene: &Scene, target: usize) -> SimplifiedMeshes {
    let full_triangles = scene.triangle_count();
    let ratio = target as f64 / full_triangles.max(1) as f64;
    let model = scene.model_bounds();
    let diagonal = if model.is_empty() {
        scene.bounds().extent().length()
    } else {
        model.extent().length()
    };
    let max_error = MAX_ERROR * diagonal;
    let indices: Vec<Vec<u32>> = scene
        .objects
        .iter()
        .map(|object| {
            let mesh = &object.mesh;
            let triangles = mesh.triangle_count();
            let in_range = mesh.indices.iter().all(|&i| (i as usize) < mesh.positions.len());
            if ratio >= 1.0 || triangles <= KEPT_WHOLE_TRIANGLES || !in_range {
                return mesh.indices.clone();
            }
            let wanted = ((triangles as f64 * ratio).ceil() as usize).max(KEPT_WHOLE_TRIANGLES);
            let positions: &[f32] = bytemuck::cast_slice(&mesh.positions);
            let vertices = meshopt::VertexDataAdapter::new(bytemuck::cast_slice(positions), 12, 0)
                .expect("three floats a vertex");
            meshopt::simplify(
                &mesh.indices,
                &vertices,
                3 * wanted,
                max_error,
                meshopt::SimplifyOptions::ErrorAbsolute,
                None,
            )
        })
        .collect();
    SimplifiedMeshes {
        triangles: indices.iter().map(|i| i.len() / 3).sum(),
        indices,
        full_triangles,
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

    #[test]
    fn a_large_scene_is_simplified_towards_the_target_within_its_vertices() {
        let scene = sphere_field(2 * THRESHOLD_TRIANGLES);
        let simplified = simplify(&scene).expect("above the threshold");
        assert_eq!(simplified.full_triangles, scene.triangle_count());
        assert_eq!(simplified.indices.len(), scene.objects.len());
        assert!(
            simplified.triangles <= TARGET_TRIANGLES + TARGET_TRIANGLES / 10,
            "{} triangles",
            simplified.triangles
        );
        for (object, indices) in scene.objects.iter().zip(&simplified.indices) {
            assert_eq!(indices.len() % 3, 0);
            assert!(
                indices
                    .iter()
                    .all(|&i| (i as usize) < object.mesh.positions.len())
            );
        }
    }

    #[test]
    fn a_simplified_sphere_keeps_its_silhouette() {
        let scene = sphere_field(2 * THRESHOLD_TRIANGLES);
        let simplified = simplify(&scene).expect("above the threshold");
        let sphere = &scene.objects[1];
        let centre = sphere.bounds.center();
        let radius = 0.5 * sphere.bounds.extent().x;
        let indices = &simplified.indices[1];
        assert!(indices.len() < sphere.mesh.indices.len() / 4);
        // Every kept corner lies on the sphere, and the triangles' centroids
        // stay within the error bound of it (a coarser tessellation cuts
        // the chords inwards).
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
}
