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

/// A light the lab's settings could not take (past ±10¹² m, a power past
/// 10³² W, a colour past 10⁶) is skipped with a warning naming the field,
/// and the model's own light takes its place.
#[test]
fn lights_past_the_labs_range_are_skipped() {
    for (light, field) in [
        (
            json!({"type": "point", "intensity": 683.0, "color": [1.0, 1.0, 1.0]}),
            "light.position = [0, 0, 2e12] is out of range (allowed: three numbers in -1e12 … 1e12)",
        ),
        (
            json!({"type": "point", "intensity": 1e36, "color": [1.0, 1.0, 1.0]}),
            "light.power_w = 1.8398786e34 is out of range (allowed: 0 … 1e32)",
        ),
        (
            json!({"type": "point", "intensity": 683.0, "color": [1e7, 1.0, 1.0]}),
            "light.color = [1e7, 1, 1] is out of range (allowed: three numbers in 0 … 1000000)",
        ),
    ] {
        let far = light["intensity"] == 683.0 && light["color"][0] == 1.0;
        let mut doc = Doc::square();
        doc.json["extensionsUsed"] = json!(["KHR_lights_punctual"]);
        doc.json["extensions"] = json!({"KHR_lights_punctual": {"lights": [light]}});
        let z = if far { 2e12 } else { 3.0 };
        let bulb = doc.node(json!({"translation": [0.0, 0.0, z],
            "extensions": {"KHR_lights_punctual": {"light": 0}}}));
        doc.add_root(bulb);
        let dir = tempfile::tempdir().unwrap();
        let path = doc.write_external(dir.path(), "far");
        let scene = lumlab::scene::load(&path).unwrap();
        assert!(scene.lights.is_empty(), "{light}");
        assert!(
            scene
                .warnings
                .iter()
                .any(|w| w == &format!("light 'light 0' is not usable ({field}); skipped")),
            "{:?}",
            scene.warnings
        );
        let options = SceneOptions {
            scene: Some(path),
            ..SceneOptions::default()
        };
        let (settings, _) = load_scene(&options).unwrap();
        assert!(settings.light.position.z.abs() < 10.0, "{light}");
    }
}
