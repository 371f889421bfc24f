//! The glTF loader against a corpus of small files built here: every way a
//! file may carry its data, every primitive mode and index type, node
//! hierarchies, cameras, materials, and every kind of broken input, with
//! exact triangle counts and bounds.

mod scene_support;

use glam::Vec3;
use lumlab::scene::{self, LoadProblem, NormalsPresence, Scene, SceneError};
use scene_support::builder::*;
use serde_json::json;
use std::path::Path;

const NAME: &str = "case.gltf";

fn load_bytes(bytes: &[u8]) -> Result<Scene, SceneError> {
    scene::gltf::load_slice(bytes, Path::new(NAME), None)
}

fn load_ok(bytes: &[u8]) -> Scene {
    load_bytes(bytes).unwrap_or_else(|e| panic!("{e}"))
}

/// The problem a file has; its message is one line naming the file.
fn problem(bytes: &[u8]) -> LoadProblem {
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
fn load_every_form(doc: &Doc) -> Scene {
    let dir = tempfile::tempdir().unwrap();
    let external = scene::load(&doc.write_external(dir.path(), "case")).unwrap_or_else(|e| panic!("{e}"));
    let glb = load_ok(&doc.glb());
    let embedded = load_ok(&doc.gltf_embedded());
    assert_eq!(glb.facts(), embedded.facts());
    assert_eq!(glb.facts(), external.facts());
    glb
}

fn assert_bounds(scene: &Scene, min: [f32; 3], max: [f32; 3]) {
    let facts = scene.facts();
    let (got_min, got_max) = (facts.bounds_min.unwrap(), facts.bounds_max.unwrap());
    for c in 0..3 {
        assert!((got_min[c] - min[c]).abs() < 1e-5, "min {got_min:?} vs {min:?}");
        assert!((got_max[c] - max[c]).abs() < 1e-5, "max {got_max:?} vs {max:?}");
    }
}

fn has_warning(scene: &Scene, text: &str) -> bool {
    scene.warnings.iter().any(|w| w.contains(text))
}

/// Every vertex normal of every object is `expected`.
fn assert_normals_are(scene: &Scene, expected: Vec3) {
    for object in &scene.objects {
        for n in &object.mesh.normals {
            assert!((*n - expected).length() < 1e-6, "{}: {n}", object.name);
        }
    }
}

/// Every triangle's winding agrees with its vertex normals (front faces CCW).
fn assert_front_faces_follow_normals(scene: &Scene) {
    for object in &scene.objects {
        let mesh = &object.mesh;
        for t in 0..mesh.triangle_count() {
            let [a, b, c] = mesh.triangle(t);
            let face = (b - a).cross(c - a);
            for k in 0..3 {
                let n = mesh.normals[mesh.indices[3 * t + k] as usize];
                assert!(
                    face.dot(n) > 0.0,
                    "{}: triangle {t} winds against its normal",
                    object.name
                );
            }
        }
    }
}

// --- Good files ---------------------------------------------------------

#[test]
fn a_square_loads_the_same_from_glb_data_uri_and_external_bin() {
    let scene = load_every_form(&Doc::square());
    let facts = scene.facts();
    assert_eq!((facts.meshes, facts.primitives, facts.triangles), (1, 1, 2));
    assert_eq!(facts.cameras, 0);
    assert!(facts.warnings.is_empty(), "{:?}", facts.warnings);
    assert_bounds(&scene, [0.0; 3], [1.0, 1.0, 0.0]);
}

#[test]
fn missing_normals_are_generated_facing_the_winding() {
    let scene = load_ok(&Doc::square().glb());
    assert_eq!(scene.facts().has_normals, NormalsPresence::Missing);
    assert_normals_are(&scene, Vec3::Z);
    assert_front_faces_follow_normals(&scene);
}

#[test]
fn triangle_strips_become_n_minus_2_triangles_with_the_winding_kept() {
    // 6 vertices zig-zag along x: 4 triangles, all facing +Z.
    let zigzag = [
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 1.0, 0.0],
    ];
    let (doc, _) = Doc::simple(
        &zigzag,
        Some((&[1, 0, 3, 2, 5, 4], UNSIGNED_BYTE)),
        TRIANGLE_STRIP,
    );
    let scene = load_every_form(&doc);
    assert_eq!(scene.triangle_count(), 4);
    assert_bounds(&scene, [0.0; 3], [2.0, 1.0, 0.0]);
    assert_front_faces_follow_normals(&scene);
    assert_normals_are(&scene, Vec3::Z);
    // Without indices the vertices are taken in order.
    let (doc, _) = Doc::simple(
        &[zigzag[1], zigzag[0], zigzag[3], zigzag[2]],
        None,
        TRIANGLE_STRIP,
    );
    assert_eq!(load_ok(&doc.glb()).triangle_count(), 2);
}

#[test]
fn triangle_fans_become_n_minus_2_triangles() {
    // A hexagon fan around its first vertex: 5 vertices on the rim + centre.
    let mut fan = vec![[0.0f32, 0.0, 0.0]];
    for i in 0..6 {
        let a = i as f32 * std::f32::consts::TAU / 6.0;
        fan.push([a.cos(), a.sin(), 0.0]);
    }
    fan.push(fan[1]);
    let (doc, _) = Doc::simple(&fan, None, TRIANGLE_FAN);
    let scene = load_every_form(&doc);
    assert_eq!(scene.triangle_count(), fan.len() - 2);
    assert_front_faces_follow_normals(&scene);
    let (doc, _) = Doc::simple(&SQUARE, Some((&[0, 1, 2, 3], UNSIGNED_INT)), TRIANGLE_FAN);
    assert_eq!(load_ok(&doc.glb()).triangle_count(), 2);
}

#[test]
fn points_and_lines_draw_nothing_but_count_in_the_bounds() {
    for mode in [POINTS, LINES, LINE_LOOP, LINE_STRIP] {
        let (doc, _) = Doc::simple(&SQUARE, None, mode);
        let scene = load_every_form(&doc);
        let facts = scene.facts();
        assert_eq!(
            (facts.meshes, facts.primitives, facts.triangles),
            (1, 1, 0),
            "mode {mode}"
        );
        assert!(scene.objects.is_empty());
        assert_bounds(&scene, [0.0; 3], [1.0, 1.0, 0.0]);
        assert!(
            has_warning(&scene, "skipped 1 point or line"),
            "{:?}",
            scene.warnings
        );
    }
}

#[test]
fn points_beside_triangles_widen_the_bounds() {
    let mut doc = Doc::square();
    let far = doc.vec3s(&[[5.0, -2.0, 3.0]]);
    doc.json["meshes"][0]["primitives"]
        .as_array_mut()
        .unwrap()
        .push(json!({"attributes": {"POSITION": far}, "mode": POINTS}));
    let scene = load_ok(&doc.glb());
    let facts = scene.facts();
    assert_eq!((facts.primitives, facts.triangles), (2, 2));
    assert_bounds(&scene, [0.0, -2.0, 0.0], [5.0, 1.0, 3.0]);
    assert_eq!(scene.objects[0].bounds.max, Vec3::new(1.0, 1.0, 0.0));
}

#[test]
fn non_indexed_triangles_take_the_vertices_in_threes() {
    let soup = [
        SQUARE[0], SQUARE[1], SQUARE[2], SQUARE[0], SQUARE[2], SQUARE[3], SQUARE[0],
    ];
    let (doc, _) = Doc::simple(&soup, None, TRIANGLES);
    // The seventh vertex makes no triangle.
    assert_eq!(load_every_form(&doc).triangle_count(), 2);
}

#[test]
fn indices_of_every_unsigned_type() {
    for ty in [UNSIGNED_BYTE, UNSIGNED_SHORT, UNSIGNED_INT] {
        let (doc, _) = Doc::simple(&SQUARE, Some((&[0, 1, 2, 0, 2, 3], ty)), TRIANGLES);
        let scene = load_every_form(&doc);
        assert_eq!(scene.triangle_count(), 2, "type {ty}");
        assert_eq!(scene.objects[0].mesh.indices, [0, 1, 2, 0, 2, 3]);
    }
}

#[test]
fn nested_node_transforms_compose() {
    let mut doc = Doc::square();
    // Parent: scale 2 then move 10 along x; child: turn 90° about +Y, lift 1.
    let half = std::f32::consts::FRAC_1_SQRT_2;
    doc.json["nodes"] = json!([
        {"translation": [10.0, 0.0, 0.0], "scale": [2.0, 2.0, 2.0], "children": [1]},
        {"mesh": 0, "rotation": [0.0, half, 0.0, half], "translation": [0.0, 1.0, 0.0]},
    ]);
    doc.json["scenes"] = json!([{"nodes": [0]}]);
    let scene = load_every_form(&doc);
    assert_eq!(scene.triangle_count(), 2);
    // (x, y, 0) → (0, y + 1, −x) → (10, 2y + 2, −2x).
    assert_bounds(&scene, [10.0, 2.0, -2.0], [10.0, 4.0, 0.0]);
    assert_front_faces_follow_normals(&scene);
    // The same with a matrix on the parent (column-major).
    doc.json["nodes"][0] = json!({
        "matrix": [2.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 10.0, 0.0, 0.0, 1.0],
        "children": [1],
    });
    assert_bounds(&load_ok(&doc.glb()), [10.0, 2.0, -2.0], [10.0, 4.0, 0.0]);
}

#[test]
fn a_mirrored_node_keeps_its_faces_front_facing() {
    let mut doc = Doc::square();
    doc.json["nodes"][0]["scale"] = json!([-1.0, 1.0, 1.0]);
    let scene = load_every_form(&doc);
    assert_bounds(&scene, [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    assert_front_faces_follow_normals(&scene);
    assert_normals_are(&scene, Vec3::Z);
}

#[test]
fn every_instance_of_a_mesh_is_drawn_and_counted() {
    let mut doc = Doc::square();
    for x in [2.0, 4.0] {
        let node = doc.node(json!({"mesh": 0, "translation": [x, 0.0, 0.0]}));
        doc.add_root(node);
    }
    let scene = load_every_form(&doc);
    let facts = scene.facts();
    assert_eq!((facts.meshes, facts.primitives, facts.triangles), (1, 1, 6));
    assert_eq!(scene.objects.len(), 3);
    assert_bounds(&scene, [0.0; 3], [5.0, 1.0, 0.0]);
}

#[test]
fn the_default_scene_of_the_file_is_drawn() {
    let mut doc = Doc::square();
    let other = doc.node(json!({"mesh": 0, "translation": [0.0, 0.0, 7.0]}));
    doc.json["scenes"] = json!([{"nodes": [0]}, {"nodes": [other]}]);
    doc.json["scene"] = json!(1);
    let scene = load_ok(&doc.glb());
    assert_eq!(scene.facts().scene, Some(1));
    assert_bounds(&scene, [0.0, 0.0, 7.0], [1.0, 1.0, 7.0]);
    // Without "scene", scene 0.
    doc.json.as_object_mut().unwrap().remove("scene");
    assert_bounds(&load_ok(&doc.glb()), [0.0; 3], [1.0, 1.0, 0.0]);
}

#[test]
fn given_normals_are_kept_and_zero_or_nan_ones_repaired() {
    let mut doc = Doc::square();
    let normals = doc.vec3s(&[
        [0.0, 0.0, 2.0],
        [0.0, 0.0, 0.0],
        [f32::NAN, 0.0, 1.0],
        [0.0, 0.0, 1.0],
    ]);
    doc.json["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = json!(normals);
    let scene = load_every_form(&doc);
    assert_eq!(scene.facts().has_normals, NormalsPresence::Every);
    assert_normals_are(&scene, Vec3::Z);
    assert!(
        has_warning(&scene, "repaired 2 zero, NaN or infinite normals"),
        "{:?}",
        scene.warnings
    );
}

#[test]
fn some_primitives_with_normals_is_some() {
    let mut doc = Doc::square();
    let position = doc.vec3s(&SQUARE);
    let normal = doc.vec3s(&[[0.0, 0.0, 1.0]; 4]);
    let indices = doc.indices(&[0, 1, 2], UNSIGNED_SHORT);
    doc.json["meshes"][0]["primitives"]
        .as_array_mut()
        .unwrap()
        .push(json!({"attributes": {"POSITION": position, "NORMAL": normal}, "indices": indices}));
    let facts = load_ok(&doc.glb()).facts();
    assert_eq!((facts.primitives, facts.triangles), (2, 3));
    assert_eq!(facts.has_normals, NormalsPresence::Partial);
}

#[test]
fn nan_and_infinite_positions_drop_the_triangles_that_use_them() {
    let mut positions = SQUARE.to_vec();
    positions.push([f32::NAN, 0.0, 0.0]);
    positions.push([f32::INFINITY, 1.0, 0.0]);
    let (doc, _) = Doc::simple(
        &positions,
        Some((&[0, 1, 2, 0, 2, 3, 0, 1, 4, 4, 5, 2], UNSIGNED_SHORT)),
        TRIANGLES,
    );
    let scene = load_every_form(&doc);
    assert_eq!(scene.triangle_count(), 2);
    assert_bounds(&scene, [0.0; 3], [1.0, 1.0, 0.0]);
    assert!(scene.objects[0].mesh.positions.iter().all(|p| p.is_finite()));
    assert!(
        has_warning(
            &scene,
            "dropped 2 triangles with NaN or infinite corners (2 such vertices in the file"
        ),
        "{:?}",
        scene.warnings
    );
}

/// Found by the fuzzer: finite positions that a node's scale overflows to
/// infinity are dropped like NaN ones, and never reach the renderer.
#[test]
fn positions_a_transform_overflows_are_dropped() {
    let mut positions = SQUARE.to_vec();
    positions.push([3.0e38, 1.0, 0.5]);
    let (mut doc, _) = Doc::simple(
        &positions,
        Some((&[0, 1, 2, 0, 2, 3, 0, 1, 4], UNSIGNED_SHORT)),
        TRIANGLES,
    );
    doc.json["nodes"][0]["scale"] = json!([10.0, 1.0, 1.0]);
    let scene = load_ok(&doc.glb());
    assert_eq!(scene.triangle_count(), 2);
    assert!(scene.objects[0].mesh.positions.iter().all(|p| p.is_finite()));
    assert_bounds(&scene, [0.0; 3], [10.0, 1.0, 0.0]);
    assert!(
        has_warning(&scene, "dropped 1 triangles with NaN or infinite corners"),
        "{:?}",
        scene.warnings
    );
}

#[test]
fn degenerate_triangles_are_dropped_and_counted() {
    let mut positions = SQUARE.to_vec();
    positions.push([2.0, 0.0, 0.0]);
    // A repeated corner, and three collinear corners (zero area).
    let (doc, _) = Doc::simple(
        &positions,
        Some((&[0, 1, 2, 0, 2, 3, 0, 0, 1, 0, 1, 4], UNSIGNED_SHORT)),
        TRIANGLES,
    );
    let scene = load_every_form(&doc);
    assert_eq!(scene.facts().triangles, 2);
    assert!(
        has_warning(&scene, "dropped 2 degenerate triangles"),
        "{:?}",
        scene.warnings
    );
    // Every instance counts its own.
    let mut doc = doc;
    let node = doc.node(json!({"mesh": 0, "translation": [3.0, 0.0, 0.0]}));
    doc.add_root(node);
    let scene = load_ok(&doc.glb());
    assert_eq!(scene.facts().triangles, 4);
    assert!(
        has_warning(&scene, "dropped 4 degenerate triangles"),
        "{:?}",
        scene.warnings
    );
}

#[test]
fn a_node_that_flattens_its_mesh_drops_its_triangles() {
    let mut doc = Doc::square();
    let flat = doc.node(json!({"mesh": 0, "translation": [5.0, 0.0, 0.0], "scale": [0.0, 1.0, 1.0]}));
    doc.add_root(flat);
    let scene = load_ok(&doc.glb());
    assert_eq!((scene.objects.len(), scene.triangle_count()), (1, 2));
    assert!(has_warning(&scene, "flattens"), "{:?}", scene.warnings);
    assert_bounds(&scene, [0.0; 3], [5.0, 1.0, 0.0]);
}

#[test]
fn triangles_a_transform_collapses_are_dropped_as_degenerate() {
    // A 0.1 nm square, squeezed a further 1e-20 in its own plane (the node
    // stays invertible): in f32 its area underflows to zero.
    let tiny = SQUARE.map(|p| p.map(|c| c * 1e-10));
    let (mut doc, _) = Doc::simple(&tiny, Some((&[0, 1, 2, 0, 2, 3], UNSIGNED_BYTE)), TRIANGLES);
    doc.json["nodes"][0]["scale"] = json!([1e-20, 1e-20, 1e20]);
    let square = doc.vec3s(&SQUARE);
    let mesh = doc.mesh(vec![json!({"attributes": {"POSITION": square}})]);
    let node = doc.node(json!({ "mesh": mesh }));
    doc.add_root(node);
    let scene = load_ok(&doc.glb());
    // Only the second mesh (its first three vertices, not indexed) is drawn.
    assert_eq!((scene.objects.len(), scene.triangle_count()), (1, 1));
    assert!(
        has_warning(&scene, "dropped 2 degenerate triangles"),
        "{:?}",
        scene.warnings
    );
}

#[test]
fn sparse_accessors_replace_elements() {
    let mut doc = Doc::square();
    // Vertex 2 of the square moves to (2, 3, 0).
    let indices = doc.view(&[2], None);
    let values = doc.view(&[2.0f32, 3.0, 0.0].map(f32::to_le_bytes).concat(), None);
    doc.json["accessors"][0]["sparse"] = json!({
        "count": 1,
        "indices": {"bufferView": indices, "componentType": UNSIGNED_BYTE},
        "values": {"bufferView": values},
    });
    assert_bounds(&load_every_form(&doc), [0.0; 3], [2.0, 3.0, 0.0]);
    // Without a buffer view the accessor starts as zeros.
    let indices = doc.view(&[1u16, 2].map(u16::to_le_bytes).concat(), None);
    let values = doc.view(
        &[1.0f32, 0.0, 0.0, 0.0, 1.0, 0.0].map(f32::to_le_bytes).concat(),
        None,
    );
    let sparse = doc.accessor(json!({
        "componentType": FLOAT, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0],
        "sparse": {"count": 2, "indices": {"bufferView": indices, "componentType": UNSIGNED_SHORT},
                   "values": {"bufferView": values}},
    }));
    doc.json["meshes"][0]["primitives"] = json!([{"attributes": {"POSITION": sparse}}]);
    let scene = load_ok(&doc.glb());
    assert_eq!(scene.triangle_count(), 1);
    assert_bounds(&scene, [0.0; 3], [1.0, 1.0, 0.0]);
}

#[test]
fn interleaved_attributes_are_read_with_their_stride() {
    let mut doc = Doc::new();
    let interleaved: Vec<u8> = SQUARE
        .iter()
        .flat_map(|p| [p[0], p[1], p[2], 0.0, 0.0, 1.0])
        .flat_map(f32::to_le_bytes)
        .collect();
    let view = doc.view(&interleaved, Some(24));
    let position = doc.accessor(
        json!({"bufferView": view, "componentType": FLOAT, "count": 4, "type": "VEC3",
                                       "min": [0, 0, 0], "max": [1, 1, 0]}),
    );
    let normal = doc.accessor(
        json!({"bufferView": view, "byteOffset": 12, "componentType": FLOAT, "count": 4, "type": "VEC3"}),
    );
    let indices = doc.indices(&[0, 1, 2, 0, 2, 3], UNSIGNED_BYTE);
    let mesh = doc.mesh(vec![
        json!({"attributes": {"POSITION": position, "NORMAL": normal}, "indices": indices}),
    ]);
    let node = doc.node(json!({ "mesh": mesh }));
    doc.scene(&[node]);
    let scene = load_every_form(&doc);
    assert_eq!(scene.objects[0].mesh.positions[2], Vec3::new(1.0, 1.0, 0.0));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
}

#[test]
fn quantized_positions_load_when_the_extension_is_required() {
    let mut doc = Doc::new();
    let positions: Vec<u8> = [[0u16, 0, 0, 0], [2, 0, 0, 0], [2, 2, 0, 0], [0, 2, 0, 0]]
        .iter()
        .flatten()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let view = doc.view(&positions, Some(8));
    let position = doc.accessor(
        json!({"bufferView": view, "componentType": UNSIGNED_SHORT, "count": 4,
                                       "type": "VEC3", "min": [0, 0, 0], "max": [2, 2, 0]}),
    );
    let normals = doc.view(&[0u8, 0, 127, 0].repeat(4), Some(4));
    let normal = doc.accessor(json!({"bufferView": normals, "componentType": BYTE,
                                     "normalized": true, "count": 4, "type": "VEC3"}));
    let indices = doc.indices(&[0, 1, 2, 0, 2, 3], UNSIGNED_BYTE);
    let mesh = doc.mesh(vec![
        json!({"attributes": {"POSITION": position, "NORMAL": normal}, "indices": indices}),
    ]);
    let node = doc.node(json!({ "mesh": mesh }));
    doc.scene(&[node]);
    doc.json["extensionsUsed"] = json!(["KHR_mesh_quantization"]);
    doc.json["extensionsRequired"] = json!(["KHR_mesh_quantization"]);
    let scene = load_every_form(&doc);
    assert_bounds(&scene, [0.0; 3], [2.0, 2.0, 0.0]);
    assert_normals_are(&scene, Vec3::Z);
}

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
    assert!(has_warning(&scene, "orthographic"), "{:?}", scene.warnings);
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
    assert!(
        has_warning(&scene, "clamped") && has_warning(&scene, "not a number"),
        "{:?}",
        scene.warnings
    );
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
    assert!(
        has_warning(&scene, "2 base-colour textures cannot be used"),
        "{:?}",
        scene.warnings
    );
    assert!(has_warning(&scene, "missing.png"), "{:?}", scene.warnings);
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
    assert!(has_warning(&scene, "no scene"), "{:?}", scene.warnings);
}

#[test]
fn node_cycles_and_shared_children_end() {
    let mut doc = Doc::square();
    let a = doc.node(json!({"mesh": 0, "children": [0]}));
    doc.json["nodes"][0]["children"] = json!([a, a]);
    doc.json["scenes"][0]["nodes"] = json!([0, a]);
    let scene = load_ok(&doc.glb());
    assert_eq!(scene.objects.len(), 2);
    assert!(has_warning(&scene, "repeat a node"), "{:?}", scene.warnings);
}

#[test]
fn skins_and_morph_targets_are_named_as_ignored() {
    let mut doc = Doc::square();
    let offsets = doc.vec3s(&[[0.0; 3]; 4]);
    doc.json["meshes"][0]["primitives"][0]["targets"] = json!([{"POSITION": offsets}]);
    let scene = load_ok(&doc.glb());
    assert!(has_warning(&scene, "morph targets"), "{:?}", scene.warnings);
}

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
