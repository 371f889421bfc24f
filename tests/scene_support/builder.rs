//! Small glTF documents built in code for the loader's tests: a JSON value
//! plus one binary buffer, written as GLB, as .gltf with a data URI, or as
//! .gltf beside an external .bin.

use serde_json::{Value, json};
use std::path::{Path, PathBuf};

pub const POINTS: u32 = 0;
pub const LINES: u32 = 1;
pub const LINE_LOOP: u32 = 2;
pub const LINE_STRIP: u32 = 3;
pub const TRIANGLES: u32 = 4;
pub const TRIANGLE_STRIP: u32 = 5;
pub const TRIANGLE_FAN: u32 = 6;

pub const BYTE: u32 = 5120;
pub const UNSIGNED_BYTE: u32 = 5121;
pub const SHORT: u32 = 5122;
pub const UNSIGNED_SHORT: u32 = 5123;
pub const UNSIGNED_INT: u32 = 5125;
pub const FLOAT: u32 = 5126;

/// The unit square in z = 0, counter-clockwise seen from +Z.
pub const SQUARE: [[f32; 3]; 4] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];

pub struct Doc {
    pub json: Value,
    pub bin: Vec<u8>,
}

impl Default for Doc {
    fn default() -> Self {
        Self::new()
    }
}

fn push(list: &mut Value, item: Value) -> usize {
    let items = list.as_array_mut().expect("an array");
    items.push(item);
    items.len() - 1
}

impl Doc {
    pub fn new() -> Self {
        Self {
            json: json!({
                "asset": {"version": "2.0"},
                "buffers": [], "bufferViews": [], "accessors": [],
                "meshes": [], "nodes": [], "scenes": [], "materials": [],
            }),
            bin: Vec::new(),
        }
    }

    /// Appends bytes as a buffer view (4-byte aligned) of buffer 0.
    pub fn view(&mut self, bytes: &[u8], stride: Option<usize>) -> usize {
        self.bin.resize(self.bin.len().next_multiple_of(4), 0);
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        let mut view = json!({"buffer": 0, "byteOffset": offset, "byteLength": bytes.len()});
        if let Some(stride) = stride {
            view["byteStride"] = json!(stride);
        }
        push(&mut self.json["bufferViews"], view)
    }

    pub fn accessor(&mut self, accessor: Value) -> usize {
        push(&mut self.json["accessors"], accessor)
    }

    /// A float VEC3 accessor on its own view, with min and max of the finite values.
    pub fn vec3s(&mut self, values: &[[f32; 3]]) -> usize {
        let bytes: Vec<u8> = values.iter().flatten().flat_map(|v| v.to_le_bytes()).collect();
        let view = self.view(&bytes, None);
        let finite = || values.iter().filter(|v| v.iter().all(|c| c.is_finite()));
        let min: Vec<f32> = (0..3)
            .map(|c| finite().map(|v| v[c]).fold(f32::INFINITY, f32::min))
            .collect();
        let max: Vec<f32> = (0..3)
            .map(|c| finite().map(|v| v[c]).fold(f32::NEG_INFINITY, f32::max))
            .collect();
        self.accessor(json!({
            "bufferView": view, "componentType": FLOAT, "count": values.len(),
            "type": "VEC3", "min": min, "max": max,
        }))
    }

    pub fn vec2s(&mut self, values: &[[f32; 2]]) -> usize {
        let bytes: Vec<u8> = values.iter().flatten().flat_map(|v| v.to_le_bytes()).collect();
        let view = self.view(&bytes, None);
        self.accessor(
            json!({"bufferView": view, "componentType": FLOAT, "count": values.len(), "type": "VEC2"}),
        )
    }

    /// Indices stored as `component_type` (unsigned byte, short or int).
    pub fn indices(&mut self, indices: &[u32], component_type: u32) -> usize {
        let bytes: Vec<u8> = match component_type {
            UNSIGNED_BYTE => indices.iter().map(|&i| i as u8).collect(),
            UNSIGNED_SHORT => indices.iter().flat_map(|&i| (i as u16).to_le_bytes()).collect(),
            _ => indices.iter().flat_map(|&i| i.to_le_bytes()).collect(),
        };
        let view = self.view(&bytes, None);
        self.accessor(json!({
            "bufferView": view, "componentType": component_type, "count": indices.len(), "type": "SCALAR",
        }))
    }

    pub fn mesh(&mut self, primitives: Vec<Value>) -> usize {
        push(&mut self.json["meshes"], json!({ "primitives": primitives }))
    }

    pub fn node(&mut self, node: Value) -> usize {
        push(&mut self.json["nodes"], node)
    }

    pub fn material(&mut self, material: Value) -> usize {
        push(&mut self.json["materials"], material)
    }

    /// A scene of these root nodes, made the default scene.
    pub fn scene(&mut self, nodes: &[usize]) -> usize {
        let index = push(&mut self.json["scenes"], json!({ "nodes": nodes }));
        self.json["scene"] = json!(index);
        index
    }

    /// Adds a root node to the default scene.
    pub fn add_root(&mut self, node: usize) {
        let scene = self.json["scene"].as_u64().unwrap_or(0) as usize;
        push(&mut self.json["scenes"][scene]["nodes"], json!(node));
    }

    /// A mesh of one primitive over `positions`, placed by one root node
    /// in a default scene; returns the mesh index.
    pub fn simple(positions: &[[f32; 3]], indices: Option<(&[u32], u32)>, mode: u32) -> (Doc, usize) {
        let mut doc = Doc::new();
        let position = doc.vec3s(positions);
        let mut primitive = json!({"attributes": {"POSITION": position}, "mode": mode});
        if let Some((indices, ty)) = indices {
            primitive["indices"] = json!(doc.indices(indices, ty));
        }
        let mesh = doc.mesh(vec![primitive]);
        let node = doc.node(json!({ "mesh": mesh }));
        doc.scene(&[node]);
        (doc, mesh)
    }

    /// The square as two indexed triangles.
    pub fn square() -> Doc {
        Self::simple(&SQUARE, Some((&[0, 1, 2, 0, 2, 3], UNSIGNED_SHORT)), TRIANGLES).0
    }

    /// The JSON with buffer 0 pointing at `uri` (or at the GLB chunk).
    fn with_buffer(&self, uri: Option<String>) -> Value {
        let mut json = self.json.clone();
        if !self.bin.is_empty() {
            let mut buffer = json!({ "byteLength": self.bin.len() });
            if let Some(uri) = uri {
                buffer["uri"] = json!(uri);
            }
            json["buffers"] = json!([buffer]);
        }
        json
    }

    /// As a .gltf whose buffer is a base64 data URI.
    pub fn gltf_embedded(&self) -> Vec<u8> {
        let uri = format!(
            "data:application/octet-stream;base64,{}",
            base64::encode(&self.bin)
        );
        serde_json::to_vec_pretty(&self.with_buffer(Some(uri))).expect("JSON")
    }

    /// As `dir/name.gltf` beside `dir/name.bin`; returns the .gltf path.
    pub fn write_external(&self, dir: &Path, name: &str) -> PathBuf {
        let bin_name = format!("{name}.bin");
        std::fs::write(dir.join(&bin_name), &self.bin).expect("writing .bin");
        let path = dir.join(format!("{name}.gltf"));
        let json = serde_json::to_vec_pretty(&self.with_buffer(Some(bin_name))).expect("JSON");
        std::fs::write(&path, json).expect("writing .gltf");
        path
    }

    /// As a GLB with the buffer in its binary chunk.
    pub fn glb(&self) -> Vec<u8> {
        let json = serde_json::to_vec(&self.with_buffer(None)).expect("JSON");
        glb(&json, (!self.bin.is_empty()).then_some(&self.bin[..]))
    }
}

/// A GLB container around these chunks (padded to 4 bytes).
pub fn glb(json: &[u8], bin: Option<&[u8]>) -> Vec<u8> {
    let mut chunks = Vec::new();
    for (kind, data, pad) in [(b"JSON", Some(json), b' '), (b"BIN\0", bin, 0u8)] {
        if let Some(data) = data {
            let padded = data.len().next_multiple_of(4);
            chunks.extend((padded as u32).to_le_bytes());
            chunks.extend(kind);
            chunks.extend(data);
            chunks.resize(chunks.len() + padded - data.len(), pad);
        }
    }
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend(((12 + chunks.len()) as u32).to_le_bytes());
    out.extend(chunks);
    out
}
