//! `lumlab info` end to end through the binary: JSON facts for the sample
//! models and the built-in scene, text for people, and a one-line error
//! with exit code 1 on a broken file.

mod cli_support;
mod scene_support;

use cli_support::{lumlab, stderr};
use scene_support::builder::Doc;
use scene_support::samples;

use serde_json::Value;
use std::path::Path;

fn info_json(scene: &Path) -> Value {
    let out = lumlab(&["info", "--scene", scene.to_str().unwrap(), "--format", "json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    serde_json::from_slice(&out.stdout).expect("JSON on stdout")
}

#[test]
fn info_reports_the_expected_facts_of_every_sample() {
    let Some(dir) = samples::samples_dir() else {
        eprintln!("no ../shared/gltf-samples: skipped");
        return;
    };
    for (model, facts) in samples::expected_models(&dir) {
        let got = info_json(&dir.join(&model));
        samples::check(&model, &got, &facts).unwrap();
        assert!(got["warnings"].is_array());
    }
}

#[test]
fn info_json_has_the_documented_keys() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("square.glb");
    std::fs::write(&path, Doc::square().glb()).unwrap();
    let facts = info_json(&path);
    for key in [
        "meshes",
        "primitives",
        "triangles",
        "has_normals",
        "bounds_min",
        "bounds_max",
        "cameras",
        "warnings",
        "objects",
    ] {
        assert!(facts.get(key).is_some(), "no {key} in {facts}");
    }
    assert_eq!(facts["triangles"], 2);
    assert_eq!(facts["has_normals"], "none");
    assert_eq!(facts["bounds_max"], serde_json::json!([1.0, 1.0, 0.0]));
    assert_eq!(facts["objects"][0]["casts_shadows"], true);
}

#[test]
fn info_without_a_scene_describes_the_built_in_one() {
    let out = lumlab(&["info", "--format", "json"]);
    assert!(out.status.success());
    let facts: Value = serde_json::from_slice(&out.stdout).unwrap();
    // 8 props, the ColorChecker chart's board and its 24 patches.
    assert_eq!(facts["meshes"], 8 + 1 + 24);
    assert_eq!(facts["warnings"], serde_json::json!([]));
    let out = lumlab(&["info"]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains("triangles") && text.contains("gold sphere"),
        "{text}"
    );
    let loaded = text.lines().last().unwrap_or_default();
    assert!(
        loaded.starts_with("loaded     in ") && loaded.contains(" s"),
        "{text}"
    );
    #[cfg(target_os = "linux")]
    assert!(
        loaded.contains(", peak memory ") && loaded.ends_with(" MiB"),
        "{text}"
    );
}

#[test]
fn info_on_a_broken_file_exits_1_with_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let glb = Doc::square().glb();
    let path = dir.path().join("cut.glb");
    std::fs::write(&path, &glb[..glb.len() - 10]).unwrap();
    for args in [
        vec!["info", "--scene", path.to_str().unwrap()],
        vec!["info", "--scene", path.to_str().unwrap(), "--format", "json"],
        vec!["info", "--scene", "/nonexistent/scene.gltf"],
    ] {
        let out = lumlab(&args);
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        assert!(out.stdout.is_empty());
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(
            stderr.contains(".glb") || stderr.contains("scene.gltf"),
            "{stderr}"
        );
    }
    let out = lumlab(&["info", "--format", "yaml"]);
    assert_eq!(out.status.code(), Some(2));
}
