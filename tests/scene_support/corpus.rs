//! Loading the corpus's files, and what the scene tests assert of them.

use super::builder::Doc;
use glam::Vec3;
use lumlab::scene::{self, LoadProblem, Mesh, Scene, SceneError};
use std::path::Path;

pub const NAME: &str = "case.gltf";

pub fn load_bytes(bytes: &[u8]) -> Result<Scene, SceneError> {
    scene::gltf::load_slice(bytes, Path::new(NAME), None)
}

pub fn load_ok(bytes: &[u8]) -> Scene {
    load_bytes(bytes).unwrap_or_else(|e| panic!("{e}"))
}

/// The problem a file has; its message is one line naming the file.
pub fn problem(bytes: &[u8]) -> LoadProblem {
    match load_bytes(bytes) {
        Err(e @ SceneError::Load { .. }) => {
            let message = e.to_string();
            assert!(!message.contains('\n') && message.contains(NAME), "{message}");
            e.problem().cloned().expect("a load problem")
        }
        Err(e) => panic!("unexpected error kind: {e}"),
        Ok(_) => panic!("the file loaded"),
    }
}

/// The document loaded as GLB, as .gltf with a data URI and as .gltf with an
/// external .bin: the three must give the same facts.
pub fn load_every_form(doc: &Doc) -> Scene {
    let dir = tempfile::tempdir().unwrap();
    let external = scene::load(&doc.write_external(dir.path(), "case")).unwrap_or_else(|e| panic!("{e}"));
    let glb = load_ok(&doc.glb());
    let embedded = load_ok(&doc.gltf_embedded());
    assert_eq!(glb.facts(), embedded.facts());
    assert_eq!(glb.facts(), external.facts());
    glb
}

pub fn assert_bounds(scene: &Scene, min: [f32; 3], max: [f32; 3]) {
    let facts = scene.facts();
    let (got_min, got_max) = (facts.bounds_min.unwrap(), facts.bounds_max.unwrap());
    for c in 0..3 {
        assert!((got_min[c] - min[c]).abs() < 1e-5, "min {got_min:?} vs {min:?}");
        assert!((got_max[c] - max[c]).abs() < 1e-5, "max {got_max:?} vs {max:?}");
    }
}

/// Some warning of `scene` contains `text` (the failure lists them all).
pub fn assert_warns(scene: &Scene, text: &str) {
    assert!(
        scene.warnings.iter().any(|w| w.contains(text)),
        "no warning contains {text:?}: {:?}",
        scene.warnings
    );
}

/// Every vertex normal of every object is `expected`.
pub fn assert_normals_are(scene: &Scene, expected: Vec3) {
    for object in &scene.objects {
        for t in 0..object.mesh.triangle_count() {
            for n in shading_normals(&object.mesh, t) {
                assert!((n - expected).length() < 1e-6, "{}: {n}", object.name);
            }
        }
    }
}

/// The normals triangle t is shaded with at its corners: its vertex
/// normals, or its face's own (the winding's) where the mesh has none (a
/// glTF primitive without NORMAL is shaded flat).
pub fn shading_normals(mesh: &Mesh, t: usize) -> [Vec3; 3] {
    let [a, b, c] = mesh.triangle(t);
    let face = (b - a).cross(c - a).normalize();
    [0, 1, 2].map(|k| {
        mesh.normals
            .get(mesh.indices[3 * t + k] as usize)
            .copied()
            .unwrap_or(face)
    })
}

/// Every triangle's winding agrees with its vertex normals (front faces CCW).
pub fn assert_front_faces_follow_normals(scene: &Scene) {
    for object in &scene.objects {
        let mesh = &object.mesh;
        for t in 0..mesh.triangle_count() {
            let [a, b, c] = mesh.triangle(t);
            let face = (b - a).cross(c - a);
            for n in shading_normals(mesh, t) {
                assert!(
                    face.dot(n) > 0.0,
                    "{}: triangle {t} winds against its normal",
                    object.name
                );
            }
        }
    }
}
