//! The glTF loader against broken files: each gives a one-line error that
//! names the file and the problem, or opens empty with a banner.

mod scene_support;

use lumlab::scene::{self, LoadProblem, Scene, SceneError};
use scene_support::builder::*;
use scene_support::corpus::*;
use serde_json::json;

// --- Broken files -------------------------------------------------------

#[test]
fn a_file_that_is_not_gltf_is_named_as_such() {
    for bytes in [&b""[..], b"\x89PNG\r\n", b"[1, 2]", b"{\"asset\": 3}", b"{"] {
        assert!(matches!(problem(bytes), LoadProblem::NotGltf(_)), "{bytes:?}");
    }
}

#[test]
fn a_truncated_glb_is_an_error_at_every_length() {
    let bytes = Doc::square().glb();
    for len in 0..bytes.len() {
        let p = problem(&bytes[..len]);
        assert!(
            matches!(p, LoadProblem::BadGlb(_) | LoadProblem::NotGltf(_)),
            "{len}: {p}"
        );
    }
}

#[test]
fn a_glb_whose_binary_chunk_is_short_is_out_of_range() {
    let doc = Doc::square();
    let json = serde_json::to_vec(&json!(null)).unwrap();
    assert!(matches!(problem(&glb(&json, None)), LoadProblem::NotGltf(_)));
    let mut short = doc.json.clone();
    short["buffers"] = json!([{"byteLength": doc.bin.len() + 64}]);
    let bytes = glb(&serde_json::to_vec(&short).unwrap(), Some(&doc.bin));
    assert!(matches!(problem(&bytes), LoadProblem::OutOfRange { what, .. } if what == "buffer 0"));
    // No binary chunk at all.
    let bytes = glb(&serde_json::to_vec(&short).unwrap(), None);
    assert!(matches!(problem(&bytes), LoadProblem::MissingData { .. }));
}

#[test]
fn a_missing_buffer_file_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let path = Doc::square().write_external(dir.path(), "lost");
    std::fs::remove_file(dir.path().join("lost.bin")).unwrap();
    let e = scene::load(&path).unwrap_err();
    let message = e.to_string();
    assert!(
        message.contains("lost.gltf") && message.contains("buffer 0 'lost.bin'"),
        "{message}"
    );
    assert!(!message.contains('\n'));
    assert!(matches!(e.problem(), Some(LoadProblem::MissingData { .. })));
    // And a scene file that is not there at all.
    let e = scene::load(&dir.path().join("nowhere.glb")).unwrap_err();
    assert!(matches!(e, SceneError::Read { .. }) && e.to_string().contains("nowhere.glb"));
}

#[test]
fn unusable_uris_are_refused() {
    let mut doc = Doc::square();
    for uri in [
        "https://example.com/a.bin",
        "data:application/octet-stream;base64,@@@@",
        "data:,abc",
    ] {
        let mut json = doc.json.clone();
        json["buffers"] = json!([{"byteLength": doc.bin.len(), "uri": uri}]);
        let p = problem(&serde_json::to_vec(&json).unwrap());
        assert!(matches!(p, LoadProblem::MissingData { .. }), "{uri}: {p}");
    }
    // A relative file from memory: nowhere to look for it.
    doc.json["buffers"] = json!([{"byteLength": 4, "uri": "a.bin"}]);
    assert!(matches!(
        problem(&serde_json::to_vec(&doc.json).unwrap()),
        LoadProblem::MissingData { .. }
    ));
}

#[test]
fn an_accessor_past_its_view_is_out_of_range() {
    let mut doc = Doc::square();
    doc.json["accessors"][0]["count"] = json!(5);
    assert!(matches!(problem(&doc.glb()), LoadProblem::OutOfRange { what, .. } if what == "accessor 0"));
    let mut doc = Doc::square();
    doc.json["accessors"][1]["byteOffset"] = json!(4);
    assert!(matches!(problem(&doc.glb()), LoadProblem::OutOfRange { what, .. } if what == "accessor 1"));
    let mut doc = Doc::square();
    doc.json["accessors"][0]["count"] = json!(u64::MAX / 2);
    assert!(matches!(problem(&doc.glb()), LoadProblem::OutOfRange { .. }));
    let mut doc = Doc::square();
    doc.json["bufferViews"][0]["byteStride"] = json!(4);
    assert!(matches!(problem(&doc.glb()), LoadProblem::InvalidValue { .. }));
}

#[test]
fn a_buffer_view_past_its_buffer_is_out_of_range() {
    let mut doc = Doc::square();
    doc.json["bufferViews"][0]["byteLength"] = json!(1_000_000);
    assert!(matches!(problem(&doc.glb()), LoadProblem::OutOfRange { what, .. } if what == "buffer view 0"));
    let mut doc = Doc::square();
    doc.json["bufferViews"][1]["buffer"] = json!(3);
    assert!(matches!(problem(&doc.glb()), LoadProblem::OutOfRange { .. }));
}

#[test]
fn references_to_missing_items_are_out_of_range() {
    let cases: [(&str, serde_json::Value); 6] = [
        ("/meshes/0/primitives/0/attributes/POSITION", json!(9)),
        ("/meshes/0/primitives/0/indices", json!(9)),
        ("/meshes/0/primitives/0/material", json!(9)),
        ("/nodes/0/mesh", json!(9)),
        ("/scenes/0/nodes/0", json!(9)),
        ("/scene", json!(9)),
    ];
    for (pointer, value) in cases {
        let mut doc = Doc::square();
        let (parent, key) = pointer.rsplit_once('/').unwrap();
        match doc.json.pointer_mut(parent).unwrap() {
            serde_json::Value::Array(items) => items[key.parse::<usize>().unwrap()] = value,
            parent => parent[key] = value,
        }
        let p = problem(&doc.glb());
        assert!(matches!(p, LoadProblem::OutOfRange { .. }), "{pointer}: {p}");
    }
}

#[test]
fn an_index_past_the_vertices_is_out_of_range() {
    let (doc, _) = Doc::simple(&SQUARE, Some((&[0, 1, 2, 0, 2, 4], UNSIGNED_SHORT)), TRIANGLES);
    let p = problem(&doc.glb());
    assert!(
        matches!(&p, LoadProblem::OutOfRange { detail, .. } if detail.contains("index 4")),
        "{p}"
    );
}

#[test]
fn indices_of_a_signed_or_float_type_are_invalid() {
    let mut doc = Doc::square();
    doc.json["accessors"][1]["componentType"] = json!(SHORT);
    assert!(matches!(problem(&doc.glb()), LoadProblem::InvalidValue { .. }));
    let mut doc = Doc::square();
    doc.json["accessors"][0]["type"] = json!("VEC2");
    assert!(matches!(problem(&doc.glb()), LoadProblem::InvalidValue { .. }));
    let mut doc = Doc::square();
    doc.json["meshes"][0]["primitives"][0]["mode"] = json!(9);
    assert!(matches!(problem(&doc.glb()), LoadProblem::InvalidValue { .. }));
}

#[test]
fn only_degenerate_triangles_is_nothing_to_draw() {
    let (doc, _) = Doc::simple(&SQUARE, Some((&[0, 0, 1, 1, 2, 2], UNSIGNED_BYTE)), TRIANGLES);
    assert!(matches!(problem(&doc.glb()), LoadProblem::NothingToDraw(_)));
    let (doc, _) = Doc::simple(&[[f32::NAN; 3]; 3], None, TRIANGLES);
    assert!(matches!(problem(&doc.glb()), LoadProblem::NothingToDraw(_)));
}

/// A valid file with nothing to draw opens as an empty scene whose warning
/// says why (the lab shows it; `info` reports 0 triangles).
fn assert_empty(scene: &Scene, why: &str) {
    assert_eq!(scene.triangle_count(), 0);
    assert!(
        scene
            .warnings
            .iter()
            .any(|w| w.contains("nothing to draw") && w.contains(why)),
        "{:?}",
        scene.warnings
    );
}

#[test]
fn a_file_without_scene_or_mesh_opens_empty() {
    let mut doc = Doc::new();
    assert_empty(&load_every_form(&doc), "no mesh");
    doc.node(json!({"name": "empty"}));
    doc.scene(&[0]);
    assert_empty(&load_every_form(&doc), "no mesh");
    let mut doc = Doc::square();
    let empty = doc.node(json!({}));
    doc.json["scenes"][0]["nodes"] = json!([empty]);
    assert_empty(&load_every_form(&doc), "scene 0 places no mesh");
    // `scenes[].nodes` may be absent: an empty scene, valid glTF.
    let mut doc = Doc::square();
    doc.json["scenes"][0].as_object_mut().unwrap().remove("nodes");
    assert_empty(&load_every_form(&doc), "scene 0 places no mesh");
}

#[test]
fn an_unsupported_required_extension_is_named() {
    let mut doc = Doc::square();
    doc.json["extensionsUsed"] = json!(["KHR_draco_mesh_compression", "KHR_texture_transform"]);
    doc.json["extensionsRequired"] = json!(["KHR_draco_mesh_compression"]);
    let e = load_bytes(&doc.glb()).unwrap_err();
    assert!(e.to_string().contains("KHR_draco_mesh_compression"), "{e}");
    assert_eq!(
        e.problem(),
        Some(&LoadProblem::UnsupportedExtension(
            "KHR_draco_mesh_compression".into()
        ))
    );
    // Used but not required: drawn without it.
    doc.json["extensionsRequired"] = json!([]);
    assert_eq!(load_ok(&doc.glb()).triangle_count(), 2);
}
