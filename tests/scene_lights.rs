//! KHR_lights_punctual: a point light in the file becomes the lab's light
//! (candela to W/sr at 683 lm/W), a spot light is used as a point light with
//! a note, a directional light is reported as not modelled.

mod scene_support;

use glam::Vec3;
use lumlab::cli::{SceneOptions, load_scene};
use scene_support::builder::Doc;
use serde_json::json;

/// A square with three lights: a point light of 683 cd (1 W/sr) at
/// (1, 2, 3) under a node turned and moved, a spot light, a directional one.
fn lit_square() -> Doc {
    let mut doc = Doc::square();
    doc.json["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    doc.json["extensions"] = json!({"KHR_lights_punctual": {"lights": [
        {"name": "bulb", "type": "point", "intensity": 683.0, "color": [1.0, 0.5, 0.25]},
        {"name": "torch", "type": "spot", "intensity": 10.0, "spot": {"outerConeAngle": 0.5}},
        {"name": "sun", "type": "directional", "intensity": 3.0},
    ]}});
    let bulb = doc.node(json!({"translation": [0.0, 2.0, 3.0],
        "extensions": {"KHR_lights_punctual": {"light": 0}}}));
    let parent = doc.node(json!({"translation": [1.0, 0.0, 0.0], "children": [bulb]}));
    let torch = doc.node(json!({"extensions": {"KHR_lights_punctual": {"light": 1}}}));
    let sun = doc.node(json!({"extensions": {"KHR_lights_punctual": {"light": 2}}}));
    for node in [parent, torch, sun] {
        doc.add_root(node);
    }
    doc
}

#[test]
fn a_point_light_in_the_file_becomes_the_labs_light() {
    let dir = tempfile::tempdir().unwrap();
    let path = lit_square().write_external(dir.path(), "lit");
    let scene = lumlab::scene::load(&path).unwrap();
    assert_eq!(scene.lights.len(), 2, "the directional light is skipped");
    let bulb = &scene.lights[0];
    assert!((bulb.position - Vec3::new(1.0, 2.0, 3.0)).length() < 1e-6);
    assert!(
        (bulb.intensity_w_sr - 1.0).abs() < 1e-6,
        "683 cd = 1 W/sr at 683 lm/W"
    );
    let said = |what: &str| scene.warnings.iter().any(|w| w.contains(what));
    assert!(
        said("'torch' is a spot light: used as a point light"),
        "{:?}",
        scene.warnings
    );
    assert!(said("'sun' is directional: not modelled"), "{:?}", scene.warnings);

    let options = SceneOptions {
        scene: Some(path),
        ..SceneOptions::default()
    };
    let (settings, _) = load_scene(&options).unwrap();
    assert_eq!(settings.light.position, bulb.position);
    let expected = 4.0 * std::f32::consts::PI;
    assert!((settings.light.power_w - expected).abs() < 1e-5, "Φ = 4π I");
    assert_eq!(settings.light.color, Vec3::new(1.0, 0.5, 0.25));
}
