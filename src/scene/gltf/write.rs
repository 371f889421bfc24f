//! Writing a [`Scene`] as binary glTF, so that scenes built in code (the
//! built-in scene, the large scenes of tests and benchmarks) reach the lab
//! through the same loader as any file.
//!
//! One mesh and one node per object, already in world space (no node
//! transform); the base colour factor, double-sidedness and the lab's k and m
//! (material extras); shadow flags that are off (node extras); the cameras as
//! perspective cameras, with the distance to their target (node extras). Textures are not written. The output depends only
//! on the scene, byte for byte, so a committed asset can be checked against
//! its generator.

use crate::scene::{Object, Scene};
use serde_json::{Value, json};

const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;
/// Near plane written for cameras (m); the lab fits its own planes.
const CAMERA_ZNEAR_M: f32 = 0.05;

/// The binary chunk and the views and accessors into it.
#[derive(Default)]
struct Binary {
    bytes: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Binary {
    /// Appends `data` as a new buffer view and an accessor on it; returns
    /// the accessor's index.
    fn add(&mut self, data: &[u8], target: u32, mut accessor: Value) -> usize {
        // Every component written is 4 bytes, so views stay 4-byte aligned.
        let offset = self.bytes.len();
        self.bytes.extend_from_slice(data);
        self.views.push(json!({
            "buffer": 0,
            "byteOffset": offset,
            "byteLength": data.len(),
            "target": target,
        }));
        accessor["bufferView"] = json!(self.views.len() - 1);
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }

    fn floats<const N: usize>(
        &mut self,
        values: impl Iterator<Item = [f32; N]>,
        count: usize,
        kind: &str,
    ) -> usize {
        let mut data = Vec::with_capacity(count * N * 4);
        for v in values {
            for c in v {
                data.extend_from_slice(&c.to_le_bytes());
            }
        }
        self.add(
            &data,
            ARRAY_BUFFER,
            json!({"componentType": FLOAT, "count": count, "type": kind}),
        )
    }

    /// The object's mesh as a primitive's attributes and indices.
    fn primitive(&mut self, object: &Object) -> Value {
        let mesh = &object.mesh;
        let n = mesh.positions.len();
        let position = self.floats(mesh.positions.iter().map(|p| p.to_array()), n, "VEC3");
        // POSITION must carry its bounds.
        self.accessors[position]["min"] = json!(object.bounds.min.to_array());
        self.accessors[position]["max"] = json!(object.bounds.max.to_array());
        let mut attributes = json!({ "POSITION": position });
        if mesh.normals.len() == n {
            attributes["NORMAL"] = json!(self.floats(mesh.normals.iter().map(|v| v.to_array()), n, "VEC3"));
        }
        if mesh.uvs.len() == n {
            attributes["TEXCOORD_0"] = json!(self.floats(mesh.uvs.iter().map(|v| v.to_array()), n, "VEC2"));
        }
        if mesh.colours.len() == n {
            attributes["COLOR_0"] = json!(self.floats(mesh.colours.iter().map(|v| v.to_array()), n, "VEC3"));
        }
        let indices: Vec<u8> = mesh.indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        let indices = self.add(
            &indices,
            ELEMENT_ARRAY_BUFFER,
            json!({"componentType": UNSIGNED_INT, "count": mesh.indices.len(), "type": "SCALAR"}),
        );
        json!({
            "attributes": attributes,
            "indices": indices,
            "material": object.material,
        })
    }
}

/// The scene as a GLB file.
pub fn to_glb(scene: &Scene) -> Vec<u8> {
    let mut binary = Binary::default();
    let (mut meshes, mut nodes) = (Vec::new(), Vec::new());
    for object in scene.objects.iter().filter(|o| o.mesh.triangle_count() > 0) {
        let primitive = binary.primitive(object);
        meshes.push(json!({"name": object.name, "primitives": [primitive]}));
        let mut node = json!({"name": object.name, "mesh": meshes.len() - 1});
        let mut flags = serde_json::Map::new();
        if !object.casts_shadows {
            flags.insert("casts_shadows".into(), json!(false));
        }
        if !object.receives_shadows {
            flags.insert("receives_shadows".into(), json!(false));
        }
        if !flags.is_empty() {
            node["extras"] = json!({ "lumlab": flags });
        }
        nodes.push(node);
    }
    let mut cameras = Vec::new();
    for c in &scene.cameras {
        let f = c.camera.frame();
        let e = c.camera.eye.as_dvec3();
        // The camera looks down its node's −Z with +Y up.
        let matrix = [
            f.right.x,
            f.right.y,
            f.right.z,
            0.0, //
            f.up.x,
            f.up.y,
            f.up.z,
            0.0, //
            -f.forward.x,
            -f.forward.y,
            -f.forward.z,
            0.0, //
            e.x,
            e.y,
            e.z,
            1.0,
        ]
        .map(|v| v as f32);
        cameras.push(json!({
            "name": c.name,
            "type": "perspective",
            "perspective": {"yfov": c.camera.fovy_deg.to_radians(), "znear": CAMERA_ZNEAR_M},
        }));
        // glTF cameras have no target; the lab's extras keep its distance.
        let target_distance = c.camera.eye.distance(c.camera.target);
        nodes.push(json!({
            "name": c.name,
            "camera": cameras.len() - 1,
            "matrix": matrix,
            "extras": {"lumlab": {"target_distance": target_distance}},
        }));
    }
    let materials: Vec<Value> = scene
        .materials
        .iter()
        .map(|m| {
            let mut material = json!({
                "name": m.name,
                "pbrMetallicRoughness": {
                    "baseColorFactor": m.base_color.to_array(),
                    "metallicFactor": 0.0,
                    "roughnessFactor": 1.0,
                },
            });
            if m.double_sided {
                material["doubleSided"] = json!(true);
            }
            let mut lab = serde_json::Map::new();
            if let Some(k) = m.k {
                lab.insert("k".into(), json!(k));
            }
            if let Some(exponent) = m.m {
                lab.insert("m".into(), json!(exponent));
            }
            if !lab.is_empty() {
                material["extras"] = json!({ "lumlab": lab });
            }
            material
        })
        .collect();
    let mut document = json!({
        "asset": {"version": "2.0", "generator": "lumlab"},
        "scene": 0,
        "scenes": [{"nodes": (0..nodes.len()).collect::<Vec<_>>()}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": materials,
        "accessors": binary.accessors,
        "bufferViews": binary.views,
        "buffers": [{"byteLength": binary.bytes.len()}],
    });
    if !cameras.is_empty() {
        document["cameras"] = json!(cameras);
    }
    let json_text = document.to_string().into_bytes();
    glb(&json_text, &binary.bytes)
}

/// The GLB container: header, JSON chunk padded with spaces, binary chunk
/// padded with zeros (chunks start on 4-byte boundaries).
fn glb(json_text: &[u8], bin: &[u8]) -> Vec<u8> {
    let padded = |len: usize| len.next_multiple_of(4);
    let total = 12 + 8 + padded(json_text.len()) + 8 + padded(bin.len());
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    for (kind, data, pad) in [(b"JSON", json_text, b' '), (b"BIN\0", bin, 0u8)] {
        out.extend_from_slice(&(padded(data.len()) as u32).to_le_bytes());
        out.extend_from_slice(kind);
        out.extend_from_slice(data);
        out.resize(out.len() + padded(data.len()) - data.len(), pad);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::shapes::{cuboid, sphere};
    use crate::scene::{Aabb, Camera, Material, SceneCamera};
    use glam::{Vec3, Vec4};
    use std::path::Path;

    fn scene() -> Scene {
        let mut hidden = Object::new("hidden", sphere(Vec3::new(2.0, 1.0, 0.0), 0.5, 12, 6), 1);
        hidden.casts_shadows = false;
        Scene {
            objects: vec![
                Object::new(
                    "box",
                    cuboid(Aabb {
                        min: Vec3::ZERO,
                        max: Vec3::ONE,
                    }),
                    0,
                ),
                hidden,
            ],
            materials: vec![
                Material {
                    name: "red".into(),
                    base_color: Vec4::new(0.8, 0.1, 0.1, 1.0),
                    k: Some(1.0),
                    ..Material::default()
                },
                Material {
                    name: "gold".into(),
                    k: Some(0.15),
                    m: Some(512.0),
                    double_sided: true,
                    ..Material::default()
                },
            ],
            cameras: vec![SceneCamera {
                name: "view".into(),
                camera: Camera {
                    eye: Vec3::new(0.0, 2.0, 5.0),
                    target: Vec3::ZERO,
                    fovy_deg: 40.0,
                },
            }],
            ..Scene::default()
        }
    }

    #[test]
    fn a_written_scene_loads_back_the_same() {
        let original = scene();
        let bytes = to_glb(&original);
        assert_eq!(bytes.len() % 4, 0);
        let loaded = super::super::load_slice(&bytes, Path::new("memory.glb"), None).unwrap();
        assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
        assert_eq!(loaded.objects.len(), 2);
        for (a, b) in original.objects.iter().zip(&loaded.objects) {
            assert_eq!(a.name, b.name);
            assert_eq!(a.mesh.positions, b.mesh.positions);
            assert_eq!(a.mesh.indices, b.mesh.indices);
            assert_eq!(a.bounds, b.bounds);
            assert_eq!(a.material, b.material);
            assert_eq!(a.casts_shadows, b.casts_shadows);
            for (n, m) in a.mesh.normals.iter().zip(&b.mesh.normals) {
                assert!((*n - *m).length() < 1e-6);
            }
        }
        assert_eq!(loaded.materials, original.materials);
        let camera = &loaded.cameras[0].camera;
        let expected = &original.cameras[0].camera;
        assert!((camera.eye - expected.eye).length() < 1e-6);
        assert!((camera.fovy_deg - 40.0).abs() < 1e-4);
        assert!((camera.target - expected.target).length() < 1e-5);
    }

    #[test]
    fn writing_is_deterministic() {
        assert_eq!(to_glb(&scene()), to_glb(&scene()));
    }
}
