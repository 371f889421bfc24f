//! The public sample models beside the crate and their expected facts.

use serde_json::Value;
use std::path::{Path, PathBuf};

/// The samples folder, if this checkout has one beside it.
pub fn samples_dir() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/gltf-samples");
    dir.join("expected.json").is_file().then_some(dir)
}

/// Compares facts (as JSON, the way `lumlab info` prints them) with one
/// model's expected facts; bounds within 1e-5 of the extent.
pub fn check(model: &str, facts: &Value, expected: &Value) -> Result<(), String> {
    for key in ["meshes", "primitives", "triangles", "has_normals", "cameras"] {
        if facts[key] != expected[key] {
            return Err(format!(
                "{model}: {key} is {} instead of {}",
                facts[key], expected[key]
            ));
        }
    }
    let corner = |v: &Value, key: &str| -> Vec<f64> {
        v[key]
            .as_array()
            .map(|a| a.iter().filter_map(Value::as_f64).collect())
            .unwrap_or_default()
    };
    let (min, max) = (corner(expected, "bounds_min"), corner(expected, "bounds_max"));
    let extent = (0..3).map(|c| max[c] - min[c]).fold(0.0, f64::max).max(1e-12);
    for key in ["bounds_min", "bounds_max"] {
        let (got, want) = (corner(facts, key), corner(expected, key));
        if got.len() != 3 || (0..3).any(|c| (got[c] - want[c]).abs() > 1e-5 * extent) {
            return Err(format!("{model}: {key} is {got:?} instead of {want:?}"));
        }
    }
    Ok(())
}

/// Every model of `expected.json` with its expected facts.
pub fn expected_models(dir: &Path) -> Vec<(String, Value)> {
    let text = std::fs::read_to_string(dir.join("expected.json")).unwrap();
    let expected: Value = serde_json::from_str(&text).unwrap();
    expected["models"]
        .as_object()
        .unwrap()
        .iter()
        .map(|(k, v)| (k.clone(), v.clone()))
        .collect()
}
