//! The glTF loader against a corpus of small files built here: every way a
//! file may carry its data, every primitive mode and index type, node
//! hierarchies, with exact triangle counts and bounds. Cameras, materials
//! and textures: `scene_corpus_materials.rs`; broken files:
//! `scene_corpus_broken.rs`.

mod scene_support;

use glam::Vec3;
use lumlab::scene::{LoadProblem, NormalsPresence};
use scene_support::builder::*;
use scene_support::corpus::*;
use serde_json::json;

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
fn missing_normals_shade_flat_facing_the_winding() {
    let scene = load_ok(&Doc::square().glb());
    assert_eq!(scene.facts().has_normals, NormalsPresence::Missing);
    assert_normals_are(&scene, Vec3::Z);
    assert_front_faces_follow_normals(&scene);
    // glTF 2.0 §3.7.2.1: a primitive without NORMAL is shaded flat. A
    // bent strip keeps no normals, so each of its faces is shaded with its
    // own normal, not one smoothed across the bend.
    let bent = [
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [2.0, 0.0, 1.0],
        [2.0, 1.0, 1.0],
    ];
    let (doc, _) = Doc::simple(&bent, Some((&[1, 0, 3, 2, 5, 4], UNSIGNED_BYTE)), TRIANGLE_STRIP);
    let scene = load_ok(&doc.glb());
    let mesh = &scene.objects[0].mesh;
    assert!(mesh.normals.is_empty(), "{:?}", mesh.normals);
    assert_front_faces_follow_normals(&scene);
    // Two faces in z = 0, two rising to z = 1, meeting along x = 1.
    let slanted = Vec3::new(-1.0, 0.0, 1.0).normalize();
    for (t, expected) in [Vec3::Z, Vec3::Z, slanted, slanted].into_iter().enumerate() {
        for n in shading_normals(mesh, t) {
            assert!((n - expected).length() < 1e-6, "triangle {t}: {n}");
        }
    }
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
        assert_warns(&scene, "skipped 1 point or line");
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
fn vertex_colours_are_read_as_floats_or_normalized_bytes() {
    // VEC3 floats.
    let mut doc = Doc::square();
    let colours = doc.vec3s(&[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 1.0, 1.0]]);
    doc.json["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = json!(colours);
    let scene = load_every_form(&doc);
    assert_eq!(scene.objects[0].mesh.colours[2], Vec3::Z);
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    // VEC4 normalized unsigned bytes: the alpha is not modelled.
    let mut doc = Doc::square();
    let bytes = [
        [255u8, 0, 0, 255],
        [0, 255, 0, 255],
        [0, 0, 255, 0],
        [255, 255, 255, 255],
    ]
    .concat();
    let view = doc.view(&bytes, None);
    let colours = doc.accessor(
        json!({"bufferView": view, "componentType": UNSIGNED_BYTE, "normalized": true, "count": 4, "type": "VEC4"}),
    );
    doc.json["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = json!(colours);
    let scene = load_every_form(&doc);
    assert_eq!(scene.objects[0].mesh.colours[1], Vec3::Y);
    assert_eq!(scene.objects[0].mesh.colours[2], Vec3::Z);
    // The wrong count: ignored, and said.
    let mut doc = Doc::square();
    let colours = doc.vec3s(&[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    doc.json["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = json!(colours);
    let scene = load_ok(&doc.glb());
    assert!(scene.objects[0].mesh.colours.is_empty());
    assert_warns(&scene, "COLOR_0 has 3 entries for 4 vertices");
}

#[test]
fn extensions_the_lab_does_not_read_are_named() {
    let mut doc = Doc::square();
    doc.json["extensionsUsed"] = json!([
        "KHR_texture_transform",
        "KHR_lights_punctual",
        "KHR_materials_sheen"
    ]);
    let scene = load_ok(&doc.glb());
    assert_warns(
        &scene,
        "uses extensions the lab does not read: KHR_texture_transform, KHR_materials_sheen",
    );
    doc.json["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    assert!(load_ok(&doc.glb()).warnings.is_empty());
}

#[test]
fn see_through_materials_are_said_to_be_drawn_opaque() {
    let mut doc = Doc::square();
    doc.json["materials"] = json!([{"name": "leaf", "alphaMode": "MASK"}, {"name": "wall"}]);
    doc.json["meshes"][0]["primitives"][0]["material"] = json!(0);
    let scene = load_ok(&doc.glb());
    assert_warns(
        &scene,
        "1 materials are alpha-masked or blended (alphaMode, first: 'leaf')",
    );
    doc.json["materials"][0]["alphaMode"] = json!("OPAQUE");
    assert!(load_ok(&doc.glb()).warnings.is_empty());
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
    assert_warns(&scene, "repaired 2 zero, NaN or infinite normals");
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

/// The unit square's four corners and `extra` ones, drawn as the
/// triangles `indices` (16-bit).
fn square_and(extra: &[[f32; 3]], indices: &[u32]) -> Doc {
    let positions = [&SQUARE[..], extra].concat();
    Doc::simple(&positions, Some((indices, UNSIGNED_SHORT)), TRIANGLES).0
}

#[test]
fn nan_and_infinite_positions_drop_the_triangles_that_use_them() {
    let doc = square_and(
        &[[f32::NAN, 0.0, 0.0], [f32::INFINITY, 1.0, 0.0]],
        &[0, 1, 2, 0, 2, 3, 0, 1, 4, 4, 5, 2],
    );
    let scene = load_every_form(&doc);
    assert_eq!(scene.triangle_count(), 2);
    assert_bounds(&scene, [0.0; 3], [1.0, 1.0, 0.0]);
    assert!(scene.objects[0].mesh.positions.iter().all(|p| p.is_finite()));
    assert_warns(
        &scene,
        "dropped 2 triangles with NaN, infinite or distant corners (past ±1e11 m; 2 such vertices in the file",
    );
}

/// Found by the fuzzer: finite positions that a node's scale overflows to
/// infinity are dropped like NaN ones, and never reach the renderer.
#[test]
fn positions_a_transform_overflows_are_dropped() {
    let mut doc = square_and(&[[3.0e38, 1.0, 0.5]], &[0, 1, 2, 0, 2, 3, 0, 1, 4]);
    doc.json["nodes"][0]["scale"] = json!([10.0, 1.0, 1.0]);
    let scene = load_ok(&doc.glb());
    assert_eq!(scene.triangle_count(), 2);
    assert!(scene.objects[0].mesh.positions.iter().all(|p| p.is_finite()));
    assert_bounds(&scene, [0.0; 3], [10.0, 1.0, 0.0]);
    assert_warns(
        &scene,
        "dropped 1 triangles with NaN, infinite or distant corners",
    );
}

/// Found by the fuzzer (a float's exponent byte overwritten): a finite
/// vertex at 1.7·10³⁸ m gave bounds whose size overflowed f32, and the
/// file's camera an infinite orbit target. The lab takes models within
/// ±10¹¹ m (its camera and light, framed around them, within ±10¹² m): a
/// triangle with a corner past it is dropped like a NaN one, at the limit
/// it is kept, and a model wholly past it is a one-line error.
#[test]
fn corners_past_the_labs_range_are_dropped_like_nan_ones() {
    let limit = lumlab::scene::gltf::MAX_MODEL_COORDINATE_M;
    assert_eq!(limit, lumlab::settings::Settings::MAX_COORDINATE_M / 10.0);
    let doc = square_and(
        &[[1.7e38, 1.0, 0.0], [0.5, limit, 0.0]],
        &[0, 1, 2, 0, 2, 3, 0, 1, 4, 1, 5, 2],
    );
    let scene = load_every_form(&doc);
    assert_eq!(scene.triangle_count(), 3);
    assert_bounds(&scene, [0.0; 3], [1.0, limit, 0.0]);
    assert_warns(
        &scene,
        "dropped 1 triangles with NaN, infinite or distant corners (past ±1e11 m; 1 such vertices",
    );

    // Placed past it by the node's transform, the same.
    let (mut doc, _) = Doc::simple(&SQUARE, Some((&[0, 1, 2, 0, 2, 3], UNSIGNED_SHORT)), TRIANGLES);
    doc.json["nodes"][0]["translation"] = json!([0.0, 2.0 * limit, 0.0]);
    let problem = problem(&doc.glb());
    assert!(
        matches!(&problem, LoadProblem::NothingToDraw(d) if d.contains("all 2 triangles are degenerate or have NaN, infinite or distant corners")),
        "{problem}"
    );
}

/// A file's camera the settings would refuse (its eye or orbit target past
/// the lab's coordinate range, or its target on its eye) is skipped with a
/// warning.
#[test]
fn cameras_past_the_labs_range_are_skipped() {
    let mut doc = Doc::square();
    doc.json["cameras"] = json!([{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}}]);
    let near = doc.node(json!({"camera": 0, "translation": [0.5, 0.5, 3.0]}));
    let far = doc.node(json!({"camera": 0, "translation": [0.5, 0.5, 3e12]}));
    // Found by the fuzzer: 4.3·10⁹ m out along +X and looking further out,
    // its target 0.14 m ahead rounds to its eye in f32.
    let half = std::f32::consts::FRAC_1_SQRT_2;
    let away = doc.node(json!({"camera": 0, "translation": [4294967295.0, 0.0, 5.0],
        "rotation": [0.0, -half, 0.0, half]}));
    doc.json["scenes"][0]["nodes"] = json!([0, near, far, away]);
    let scene = load_every_form(&doc);
    assert_eq!(scene.cameras.len(), 1);
    assert_eq!(scene.cameras[0].camera.eye.z, 3.0);
    assert_warns(
        &scene,
        "camera 'camera 0' is not usable (camera.eye = [0.5, 0.5, 3e12] is out of range",
    );
    assert_warns(
        &scene,
        "is out of range (allowed: any point at least 1 µm from camera.eye)); skipped",
    );
}

#[test]
fn degenerate_triangles_are_dropped_and_counted() {
    // A repeated corner, and three collinear corners (zero area).
    let doc = square_and(&[[2.0, 0.0, 0.0]], &[0, 1, 2, 0, 2, 3, 0, 0, 1, 0, 1, 4]);
    let scene = load_every_form(&doc);
    assert_eq!(scene.facts().triangles, 2);
    assert_warns(&scene, "dropped 2 degenerate triangles");
    // Every instance counts its own.
    let mut doc = doc;
    let node = doc.node(json!({"mesh": 0, "translation": [3.0, 0.0, 0.0]}));
    doc.add_root(node);
    let scene = load_ok(&doc.glb());
    assert_eq!(scene.facts().triangles, 4);
    assert_warns(&scene, "dropped 4 degenerate triangles");
}

#[test]
fn a_node_that_flattens_its_mesh_drops_its_triangles() {
    let mut doc = Doc::square();
    let flat = doc.node(json!({"mesh": 0, "translation": [5.0, 0.0, 0.0], "scale": [0.0, 1.0, 1.0]}));
    doc.add_root(flat);
    let scene = load_ok(&doc.glb());
    assert_eq!((scene.objects.len(), scene.triangle_count()), (1, 2));
    assert_warns(&scene, "flattens");
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
    assert_warns(&scene, "dropped 2 degenerate triangles");
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
