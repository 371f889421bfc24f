//! The loader on mutated copies of small valid files (GLB and .gltf with a
//! data URI), for a bounded number of cases: whatever the bytes, it returns
//! a scene or a one-line error, never panics (not even one it would catch)
//! and never takes long; a scene it returns is sound (finite positions,
//! unit normals, indices in range) and opens in the lab (the settings
//! framed around it, and its cameras, are valid). Inputs that once broke
//! it live in `tests/data/fuzz/` and are replayed first.
//!
//! The settings file and the report's sweep file get the same treatment:
//! mutated values and bytes give a valid result or a one-line error, fast,
//! and a sweep never expands past its bound.
//!
//! More cases: `LUMLAB_FUZZ_CASES=100000 cargo test --release --test scene_fuzz`.

mod scene_support;

use lumlab::scene::{LoadProblem, Scene, framing, gltf::load_slice};
use lumlab::settings::Settings;
use proptest::prelude::*;
use proptest::sample::Index;
use scene_support::builder::*;
use serde_json::{Value, json};
use std::path::Path;
use std::time::{Duration, Instant};

/// Longest a small file may take to load (s), generous for debug builds.
const MAX_LOAD_S: f64 = 2.0;

fn cases() -> u32 {
    std::env::var("LUMLAB_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(600)
}

/// A small file that uses most of what the loader reads: indices of two
/// types, a strip, points, normals, uvs, a sparse accessor, a node
/// hierarchy with a mirror, a camera, a material with extras and a PNG.
fn rich_doc() -> Doc {
    let mut doc = Doc::new();
    let position = doc.vec3s(&SQUARE);
    let normal = doc.vec3s(&[[0.0, 0.0, 1.0]; 4]);
    let uv = doc.vec2s(&[[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]]);
    let quad = doc.indices(&[0, 1, 2, 0, 2, 3], UNSIGNED_SHORT);
    let strip = doc.indices(&[1, 0, 2, 3], UNSIGNED_BYTE);
    let sparse_indices = doc.view(&[2], None);
    let sparse_values = doc.view(&[2.0f32, 2.0, 0.0].map(f32::to_le_bytes).concat(), None);
    let moved = doc.accessor(json!({
        "bufferView": 0, "componentType": FLOAT, "count": 4, "type": "VEC3",
        "min": [0, 0, 0], "max": [2, 2, 0],
        "sparse": {"count": 1, "indices": {"bufferView": sparse_indices, "componentType": UNSIGNED_BYTE},
                   "values": {"bufferView": sparse_values}},
    }));
    let mut png = std::io::Cursor::new(Vec::new());
    image::DynamicImage::ImageRgba8(image::RgbaImage::new(2, 2))
        .write_to(&mut png, image::ImageFormat::Png)
        .unwrap();
    let image = doc.view(&png.into_inner(), None);
    doc.json["images"] = json!([{"bufferView": image, "mimeType": "image/png"}]);
    doc.json["textures"] = json!([{"source": 0}]);
    doc.material(json!({
        "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1.0], "baseColorTexture": {"index": 0}},
        "extras": {"lumlab": {"k": 0.5, "m": 32}},
    }));
    doc.mesh(vec![
        json!({"attributes": {"POSITION": position, "NORMAL": normal, "TEXCOORD_0": uv}, "indices": quad, "material": 0}),
        json!({"attributes": {"POSITION": moved}, "indices": strip, "mode": TRIANGLE_STRIP}),
        json!({"attributes": {"POSITION": position}, "mode": POINTS}),
    ]);
    doc.json["cameras"] = json!([{"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.1}}]);
    let child = doc.node(json!({"mesh": 0, "scale": [-1.0, 1.0, 1.0], "translation": [0.0, 0.0, 1.0]}));
    let camera = doc.node(json!({"camera": 0, "translation": [0.0, 0.0, 5.0]}));
    let parent =
        doc.node(json!({"mesh": 0, "children": [child, camera], "rotation": [0.0, 0.0, 0.38, 0.92]}));
    doc.scene(&[parent]);
    doc
}

/// Loads `bytes` and checks everything the loader promises. A failing
/// input is saved as `target/fuzz-failure.bin` (the last one written is
/// the shrunk one): copy it into `tests/data/fuzz/` to keep it.
fn check(bytes: &[u8]) -> Result<(), TestCaseError> {
    let result = check_load(bytes);
    if result.is_err() {
        let _ = std::fs::write(
            Path::new(env!("CARGO_MANIFEST_DIR")).join("target/fuzz-failure.bin"),
            bytes,
        );
    }
    result
}

fn check_load(bytes: &[u8]) -> Result<(), TestCaseError> {
    let start = Instant::now();
    let result = load_slice(bytes, Path::new("fuzz.glb"), None);
    let took = start.elapsed();
    prop_assert!(took < Duration::from_secs_f64(MAX_LOAD_S), "took {took:?}");
    match result {
        Err(e) => {
            let message = e.to_string();
            prop_assert!(
                !matches!(e.problem(), Some(LoadProblem::Internal(_))),
                "{message}"
            );
            prop_assert!(!message.contains('\n'), "{message}");
        }
        Ok(scene) => check_scene(&scene)?,
    }
    Ok(())
}

fn check_scene(scene: &Scene) -> Result<(), TestCaseError> {
    for o in &scene.objects {
        let m = &o.mesh;
        // Normals: one per position, or none (shaded flat).
        prop_assert!(m.normals.is_empty() || m.normals.len() == m.positions.len());
        prop_assert!(m.uvs.len() == m.positions.len());
        prop_assert!(m.indices.len() % 3 == 0 && !m.indices.is_empty());
        prop_assert!(m.indices.iter().all(|&i| (i as usize) < m.positions.len()));
        prop_assert!(m.positions.iter().all(|p| p.is_finite()));
        prop_assert!(
            m.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-3),
            "{}",
            o.name
        );
        prop_assert!(o.material < scene.materials.len());
        prop_assert!(!o.bounds.is_empty() && o.bounds.min.is_finite() && o.bounds.max.is_finite());
    }
    prop_assert!(
        scene.warnings.iter().all(|w| !w.contains('\n')),
        "{:?}",
        scene.warnings
    );
    for m in &scene.materials {
        prop_assert!(m.base_color.is_finite());
        prop_assert!(m.base_color_texture.is_none_or(|t| t < scene.textures.len()));
    }
    for t in &scene.textures {
        prop_assert_eq!(t.rgba8.len(), 4 * t.width as usize * t.height as usize);
    }
    // The lab can open it: the settings framed around it, and each of its
    // cameras, are within the settings' ranges.
    let mut settings = Settings::default();
    framing::adopt(&mut settings, scene);
    if let Err(e) = settings.validate() {
        prop_assert!(false, "framed: {e}");
    }
    for c in &scene.cameras {
        if let Err(e) = Settings::validate_camera(&c.camera) {
            prop_assert!(false, "camera '{}': {e}", c.name);
        }
    }
    let facts = scene.facts();
    prop_assert_eq!(facts.triangles, scene.triangle_count());
    Ok(())
}

/// JSON pointers to every value inside `value` (arrays and objects
/// included, the root not), in document order.
fn value_pointers(value: &Value, at: &str, out: &mut Vec<String>) {
    let children: Vec<(String, &Value)> = match value {
        Value::Array(items) => items
            .iter()
            .enumerate()
            .map(|(i, v)| (i.to_string(), v))
            .collect(),
        Value::Object(map) => map
            .iter()
            .map(|(k, v)| (k.replace('~', "~0").replace('/', "~1"), v))
            .collect(),
        _ => Vec::new(),
    };
    for (key, v) in children {
        let pointer = format!("{at}/{key}");
        out.push(pointer.clone());
        value_pointers(v, &pointer, out);
    }
}

/// JSON pointers to every number in a value.
fn number_pointers(value: &Value) -> Vec<String> {
    let mut all = Vec::new();
    value_pointers(value, "", &mut all);
    all.retain(|p| value.pointer(p).is_some_and(Value::is_number));
    all
}

/// Values of every JSON type put in place of any value of the file: the
/// loader must tell a wrong type, a wrong name or an odd string from a
/// right one.
fn edge_json_values() -> Vec<Value> {
    vec![
        Value::Null,
        json!(true),
        json!(""),
        json!("VEC3"),
        json!("MAT4"),
        json!("SCALAR"),
        json!("image/png"),
        json!("data:,"),
        json!("data:application/octet-stream;base64,AAAA"),
        json!("two\nlines"),
        json!("../../../etc/passwd"),
        json!("%ZZ"),
        json!([]),
        json!([0]),
        json!([1e300, -1e300, 0.0, 1.0]),
        json!({}),
        json!({"index": 0}),
        json!(-1),
        json!(0),
        json!(1),
        json!(0.5),
        json!(4294967296u64),
    ]
}

/// Numbers that sit on the edges of what the loader checks.
const EDGE_NUMBERS: &[f64] = &[
    0.0,
    1.0,
    2.0,
    3.0,
    -1.0,
    4.0,
    5.0,
    7.0,
    255.0,
    256.0,
    65535.0,
    4294967295.0,
    4294967296.0,
    9007199254740991.0,
    1e300,
    -1e300,
    0.5,
    5120.0,
    5121.0,
    5122.0,
    5123.0,
    5125.0,
    5126.0,
];

fn replayed_inputs() -> Vec<(String, Vec<u8>)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/fuzz");
    let Ok(entries) = std::fs::read_dir(&dir) else {
        return Vec::new();
    };
    let mut inputs: Vec<(String, Vec<u8>)> = entries
        .flatten()
        .filter(|e| e.path().is_file())
        .map(|e| {
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect();
    inputs.sort();
    inputs
}

#[test]
fn the_seeds_load_cleanly() {
    let doc = rich_doc();
    for bytes in [doc.glb(), doc.gltf_embedded()] {
        let scene = load_slice(&bytes, Path::new("seed"), None).unwrap();
        assert_eq!(scene.objects.len(), 4, "{:?}", scene.warnings);
        assert_eq!((scene.cameras.len(), scene.textures.len()), (1, 1));
        check(&bytes).unwrap();
    }
}

#[test]
fn inputs_that_once_broke_the_loader_load_or_fail_cleanly() {
    for (name, bytes) in replayed_inputs() {
        check(&bytes).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(), failure_persistence: None, ..ProptestConfig::default() })]

    /// Random bytes overwritten, and the file possibly cut short.
    #[test]
    fn byte_mutations(
        glb in any::<bool>(),
        edits in prop::collection::vec((any::<Index>(), any::<u8>()), 1..12),
        cut in prop::option::of(any::<Index>()),
    ) {
        let doc = rich_doc();
        let mut bytes = if glb { doc.glb() } else { doc.gltf_embedded() };
        for (at, value) in edits {
            let i = at.index(bytes.len());
            bytes[i] = value;
        }
        if let Some(cut) = cut {
            bytes.truncate(cut.index(bytes.len()));
        }
        check(&bytes)?;
    }

    /// The binary data mutated, the JSON intact: accessors read garbage,
    /// NaNs, huge or out-of-range indices.
    #[test]
    fn binary_mutations(edits in prop::collection::vec((any::<Index>(), any::<u8>()), 1..24)) {
        let mut doc = rich_doc();
        for (at, value) in edits {
            let i = at.index(doc.bin.len());
            doc.bin[i] = value;
        }
        check(&doc.glb())?;
    }

    /// Numbers of the JSON (indices, counts, offsets, strides, types,
    /// transforms) replaced by edge values, keys removed, and bytes of the
    /// binary data overwritten.
    #[test]
    fn json_number_mutations(
        glb in any::<bool>(),
        edits in prop::collection::vec((any::<Index>(), any::<Index>()), 1..6),
        removals in prop::collection::vec(any::<Index>(), 0..3),
        binary in prop::collection::vec((any::<Index>(), any::<u8>()), 0..4),
    ) {
        let mut doc = rich_doc();
        let pointers = number_pointers(&doc.json);
        for (at, value) in edits {
            let pointer = &pointers[at.index(pointers.len())];
            if let Some(slot) = doc.json.pointer_mut(pointer) {
                *slot = json!(EDGE_NUMBERS[value.index(EDGE_NUMBERS.len())]);
            }
        }
        for at in removals {
            let pointer = &pointers[at.index(pointers.len())];
            if let Some((parent, key)) = pointer.rsplit_once('/')
                && let Some(Value::Object(map)) = doc.json.pointer_mut(parent)
            {
                map.remove(key);
            }
        }
        for (at, value) in binary {
            let i = at.index(doc.bin.len());
            doc.bin[i] = value;
        }
        check(&if glb { doc.glb() } else { doc.gltf_embedded() })?;
    }

    /// Any value of the JSON (a number, a string, an array, an object)
    /// replaced by a value of any type.
    #[test]
    fn json_value_mutations(
        glb in any::<bool>(),
        edits in prop::collection::vec((any::<Index>(), any::<Index>()), 1..4),
    ) {
        let mut doc = rich_doc();
        let mut pointers = Vec::new();
        value_pointers(&doc.json, "", &mut pointers);
        let edges = edge_json_values();
        for (at, value) in edits {
            let pointer = &pointers[at.index(pointers.len())];
            if let Some(slot) = doc.json.pointer_mut(pointer) {
                *slot = edges[value.index(edges.len())].clone();
            }
        }
        check(&if glb { doc.glb() } else { doc.gltf_embedded() })?;
    }
}

/// Values put in place of a settings or sweep value: wrong types, edges,
/// NaN, huge arrays.
fn edge_toml_values() -> Vec<toml::Value> {
    use toml::Value as V;
    vec![
        V::Integer(0),
        V::Integer(-1),
        V::Integer(65537),
        V::Integer(i64::MAX),
        V::Float(f64::NAN),
        V::Float(f64::INFINITY),
        V::Float(-0.0),
        V::Float(1e30),
        V::String(String::new()),
        V::String("pcf".into()),
        V::String("slope:1e40,2".into()),
        V::Boolean(true),
        V::Array(Vec::new()),
        V::Array((0..64).map(|i| V::Integer(256 + i)).collect()),
        V::Table(toml::Table::new()),
    ]
}

/// Key paths to every value of a TOML tree (array elements by index).
fn toml_paths(value: &toml::Value, at: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    match value {
        toml::Value::Table(table) => {
            for (key, v) in table {
                at.push(key.clone());
                out.push(at.clone());
                toml_paths(v, at, out);
                at.pop();
            }
        }
        toml::Value::Array(items) => {
            for (i, v) in items.iter().enumerate() {
                at.push(i.to_string());
                out.push(at.clone());
                toml_paths(v, at, out);
                at.pop();
            }
        }
        _ => {}
    }
}

fn toml_slot<'a>(mut value: &'a mut toml::Value, path: &[String]) -> Option<&'a mut toml::Value> {
    for key in path {
        value = match value {
            toml::Value::Table(t) => t.get_mut(key)?,
            toml::Value::Array(a) => a.get_mut(key.parse::<usize>().ok()?)?,
            _ => return None,
        };
    }
    Some(value)
}

/// `text` with values replaced and bytes overwritten.
fn mutate_toml(text: &str, values: &[(Index, Index)], bytes: &[(Index, u8)]) -> String {
    let mut tree: toml::Value = toml::from_str(text).expect("the seed is valid TOML");
    let mut paths = Vec::new();
    toml_paths(&tree, &mut Vec::new(), &mut paths);
    let edges = edge_toml_values();
    for (at, value) in values {
        let path = &paths[at.index(paths.len())];
        if let Some(slot) = toml_slot(&mut tree, path) {
            *slot = edges[value.index(edges.len())].clone();
        }
    }
    let mut out = toml::to_string(&tree).unwrap_or_default().into_bytes();
    for (at, byte) in bytes {
        if !out.is_empty() {
            let i = at.index(out.len());
            out[i] = *byte;
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

fn check_one_line(message: &str) -> Result<(), TestCaseError> {
    prop_assert!(!message.is_empty() && !message.contains('\n'), "{message:?}");
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases() / 3, failure_persistence: None, ..ProptestConfig::default() })]

    /// The settings file: parsed and validated, or one line naming the problem.
    #[test]
    fn settings_mutations(
        values in prop::collection::vec((any::<Index>(), any::<Index>()), 0..4),
        bytes in prop::collection::vec((any::<Index>(), any::<u8>()), 0..3),
    ) {
        use lumlab::settings::Settings;
        let text = mutate_toml(&Settings::default().to_toml(), &values, &bytes);
        let start = Instant::now();
        match Settings::from_toml(&text) {
            Err(message) => check_one_line(&message)?,
            Ok(settings) => match settings.validate() {
                Err(e) => check_one_line(&e.to_string())?,
                // What validates survives a round trip through the file.
                Ok(()) => prop_assert_eq!(Settings::from_toml(&settings.to_toml()).ok(), Some(settings)),
            },
        }
        prop_assert!(start.elapsed() < Duration::from_secs_f64(MAX_LOAD_S));
    }

    /// The sweep file: a bounded list of valid configurations, or one line.
    #[test]
    fn sweep_mutations(
        values in prop::collection::vec((any::<Index>(), any::<Index>()), 0..5),
        bytes in prop::collection::vec((any::<Index>(), any::<u8>()), 0..3),
    ) {
        use lumlab::report::sweep;
        use lumlab::settings::Settings;
        let seed = format!("{}\n[[config]]\nfilter = \"pcf\"\npcf_size = 5\n", sweep::DEFAULT_SWEEP);
        let text = mutate_toml(&seed, &values, &bytes);
        let base = Settings::default();
        let start = Instant::now();
        match sweep::parse(&text, &base) {
            Err(e) => check_one_line(&e.to_string())?,
            Ok(points) => {
                prop_assert!(!points.is_empty() && points.len() as u64 <= sweep::MAX_POINTS);
                for point in points {
                    let mut settings = base.clone();
                    settings.shadow = point.shadow;
                    prop_assert!(settings.validate().is_ok(), "{}", point.label);
                }
            }
        }
        prop_assert!(start.elapsed() < Duration::from_secs_f64(MAX_LOAD_S));
    }
}
