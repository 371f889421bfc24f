//! The glTF loader against the corpus: cameras, materials, textures, node
//! extras and the file structures that are not plain meshes.

mod scene_support;

use glam::Vec3;
use lumlab::scene;
use scene_support::builder::*;
use scene_support::corpus::*;
use serde_json::json;

#[test]
fn cameras_are_reduced_to_eye_target_and_vertical_fov() {
    let mut doc = Doc::square();
    let half = std::f32::consts::FRAC_1_SQRT_2;
    doc.json["cameras"] = json!([
        {"name": "side", "type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}},
        {"type": "orthographic", "orthographic": {"xmag": 1.0, "ymag": 1.0, "znear": 0.1, "zfar": 100.0}},
    ]);
    // Turned 90° about +Y, the camera looks down −X.
    let side =
        doc.node(json!({"camera": 0, "translation": [1.0, 2.0, 3.0], "rotation": [0.0, half, 0.0, half]}));
    let front = doc.node(json!({"camera": 1, "translation": [0.5, 0.5, 3.0]}));
    let rig = doc.node(json!({"children": [front], "extras": {"note": "a rig"}}));
    doc.json["scenes"][0]["nodes"] = json!([0, side, rig]);
    let scene = load_every_form(&doc);
    assert_eq!(scene.facts().cameras, 2);
    let side = &scene.cameras[0];
    assert_eq!(side.name, "side");
    assert!((side.camera.eye - Vec3::new(1.0, 2.0, 3.0)).length() < 1e-6);
    // The orbit target lies ahead at the depth of the scene's centre (not a
    // fixed metre): the square's centre x = 0.5 is 0.5 m ahead along −X.
    let centre = scene.bounds().center();
    assert!((side.camera.target - Vec3::new(centre.x, 2.0, 3.0)).length() < 1e-6);
    assert!((side.camera.fovy_deg - 0.5f32.to_degrees()).abs() < 1e-4);
    // Orthographic: the perspective view that shows its height 2·ymag at
    // the distance of the scene's centre (3 m away).
    let front = &scene.cameras[1].camera;
    assert!((front.target - Vec3::new(0.5, 0.5, centre.z)).length() < 1e-6);
    assert!((front.fovy_deg - 2.0 * (1.0f32 / 3.0).atan().to_degrees()).abs() < 1e-3);
    assert_warns(&scene, "orthographic");
}

#[test]
fn material_base_colour_double_sidedness_and_lab_extras() {
    let mut doc = Doc::square();
    doc.material(json!({
        "name": "glossy",
        "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.6, 1.0]},
        "doubleSided": true,
        "extras": {"lumlab": {"k": 0.3, "m": 64}},
    }));
    doc.material(json!({"extras": {"lumlab": {"k": 1.5, "m": "shiny"}}}));
    doc.json["meshes"][0]["primitives"][0]["material"] = json!(0);
    let scene = load_every_form(&doc);
    let m = scene.material_of(&scene.objects[0]);
    assert_eq!(m.name, "glossy");
    assert_eq!(m.base_color.to_array(), [0.2, 0.4, 0.6, 1.0]);
    assert!(m.double_sided);
    assert_eq!((m.k, m.m), (Some(0.3), Some(64.0)));
    let other = &scene.materials[1];
    assert_eq!((other.k, other.m), (Some(1.0), None));
    assert_warns(&scene, "clamped");
    assert_warns(&scene, "not a number");
    // A primitive without material gets the default one.
    let plain = load_ok(&Doc::square().glb());
    assert_eq!(plain.material_of(&plain.objects[0]).name, "default");
}

fn encoded(format: image::ImageFormat) -> Vec<u8> {
    let pixels = image::RgbImage::from_fn(4, 2, |x, _| image::Rgb([x as u8 * 60, 128, 255]));
    let mut bytes = std::io::Cursor::new(Vec::new());
    image::DynamicImage::ImageRgb8(pixels)
        .write_to(&mut bytes, format)
        .unwrap();
    bytes.into_inner()
}

#[test]
fn base_colour_textures_decode_from_png_and_jpeg() {
    let mut doc = Doc::square();
    let uvs = doc.vec2s(&[[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]]);
    doc.json["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = json!(uvs);
    let png = doc.view(&encoded(image::ImageFormat::Png), None);
    let jpeg = format!(
        "data:image/jpeg;base64,{}",
        base64::encode(encoded(image::ImageFormat::Jpeg))
    );
    doc.json["images"] = json!([{"bufferView": png, "mimeType": "image/png"}, {"uri": jpeg}]);
    doc.json["textures"] = json!([{"source": 0}, {"source": 1}]);
    for t in 0..2 {
        doc.material(json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": t}}}));
    }
    doc.json["meshes"][0]["primitives"][0]["material"] = json!(1);
    let scene = load_every_form(&doc);
    assert_eq!(scene.textures.len(), 2);
    let png = &scene.textures[scene.materials[0].base_color_texture.unwrap()];
    assert_eq!((png.width, png.height), (4, 2));
    assert_eq!(&png.rgba8[4..8], &[60, 128, 255, 255]);
    let jpeg = &scene.textures[scene.materials[1].base_color_texture.unwrap()];
    assert_eq!((jpeg.width, jpeg.height, jpeg.rgba8.len()), (4, 2, 32));
    assert_eq!(scene.objects[0].mesh.uvs[2].to_array(), [1.0, 0.0]);
}

#[test]
fn an_image_file_beside_the_scene_is_read() {
    let mut doc = Doc::square();
    doc.json["images"] = json!([{"uri": "wood%20grain.png"}]);
    doc.json["textures"] = json!([{"source": 0}]);
    doc.material(json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}));
    doc.json["meshes"][0]["primitives"][0]["material"] = json!(0);
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("wood grain.png"),
        encoded(image::ImageFormat::Png),
    )
    .unwrap();
    let scene = scene::load(&doc.write_external(dir.path(), "textured")).unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert_eq!(scene.materials[0].base_color_texture, Some(0));
    assert_eq!((scene.textures[0].width, scene.textures[0].height), (4, 2));
}

#[test]
fn an_unreadable_image_is_a_warning_and_the_factor_alone_is_drawn() {
    let mut doc = Doc::square();
    doc.json["images"] = json!([{"uri": "missing.png"}, {"uri": "data:image/png;base64,AAAA"}]);
    doc.json["textures"] = json!([{"source": 0}, {"source": 1}]);
    doc.material(json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}));
    doc.material(json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 1}}}));
    doc.json["meshes"][0]["primitives"][0]["material"] = json!(0);
    let dir = tempfile::tempdir().unwrap();
    let scene = scene::load(&doc.write_external(dir.path(), "textured")).unwrap();
    assert!(scene.textures.is_empty());
    assert!(scene.materials.iter().all(|m| m.base_color_texture.is_none()));
    assert_warns(&scene, "2 base-colour textures cannot be used");
    assert_warns(&scene, "missing.png");
}

#[test]
fn node_extras_can_turn_shadows_off() {
    let mut doc = Doc::square();
    doc.json["nodes"][0]["extras"] = json!({"lumlab": {"casts_shadows": false}});
    let scene = load_ok(&doc.glb());
    assert!(!scene.objects[0].casts_shadows && scene.objects[0].receives_shadows);
}

#[test]
fn a_file_without_scenes_draws_its_root_nodes() {
    let mut doc = Doc::square();
    let child = doc.node(json!({"mesh": 0, "translation": [0.0, 0.0, 1.0]}));
    doc.json["nodes"][0]["children"] = json!([child]);
    let obj = doc.json.as_object_mut().unwrap();
    obj.remove("scene");
    obj.remove("scenes");
    let scene = load_ok(&doc.glb());
    assert_eq!(scene.triangle_count(), 4);
    assert_eq!(scene.facts().scene, None);
    assert_warns(&scene, "no scene");
}

#[test]
fn node_cycles_and_shared_children_end() {
    let mut doc = Doc::square();
    let a = doc.node(json!({"mesh": 0, "children": [0]}));
    doc.json["nodes"][0]["children"] = json!([a, a]);
    doc.json["scenes"][0]["nodes"] = json!([0, a]);
    let scene = load_ok(&doc.glb());
    assert_eq!(scene.objects.len(), 2);
    assert_warns(&scene, "repeat a node");
}

#[test]
fn skins_and_morph_targets_are_named_as_ignored() {
    let mut doc = Doc::square();
    let offsets = doc.vec3s(&[[0.0; 3]; 4]);
    doc.json["meshes"][0]["primitives"][0]["targets"] = json!([{"POSITION": offsets}]);
    let scene = load_ok(&doc.glb());
    assert_warns(&scene, "morph targets");
}

/// Names from the file that a warning quotes keep it on one line: a line
/// break in a material's name is written `\n`.
#[test]
fn warnings_quote_names_on_one_line() {
    let mut doc = Doc::square();
    doc.material(json!({"name": "two\nlines", "extras": {"lumlab": {"k": 1.5}}}));
    doc.json["meshes"][0]["primitives"][0]["material"] = json!(0);
    let scene = load_every_form(&doc);
    assert_warns(
        &scene,
        "material 'two\\nlines': lumlab k = 1.5 is outside 0 … 1; clamped",
    );
    assert!(
        scene.warnings.iter().all(|w| !w.contains('\n')),
        "{:?}",
        scene.warnings
    );
}
