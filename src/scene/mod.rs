//! Scenes: what is drawn, in world space (metres, +Y up).
//!
//! A glTF file is flattened into [`Object`]s, one per mesh primitive instance,
//! with positions and normals already transformed to world space. The GPU
//! renderer, the CPU reference and the app all read this one structure.

pub mod bounds;
pub mod camera;
pub mod shapes;

pub use bounds::Aabb;
pub use camera::Camera;

use crate::settings::Settings;
use glam::{Vec2, Vec3, Vec4};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// A scene file could not be used. Each message is one line naming the
/// file and the problem.
#[derive(Debug, Error)]
pub enum SceneError {
    #[error("cannot load scene '{path}': {message}")]
    Invalid { path: PathBuf, message: String },
}

/// The scene the settings name: their glTF/GLB file, or the built-in scene.
pub fn for_settings(settings: &Settings) -> Result<Scene, SceneError> {
    match &settings.scene {
        Some(path) => load(path),
        None => Ok(default_scene()),
    }
}

/// Loads a glTF or GLB file.
pub fn load(path: &Path) -> Result<Scene, SceneError> {
    Err(SceneError::Invalid {
        path: path.to_owned(),
        message: "glTF loading is not implemented yet".into(),
    })
}

/// The built-in scene (a stand-in until the generated asset lands).
pub fn default_scene() -> Scene {
    use shapes::{cuboid, ground, sphere};
    let materials = vec![
        Material {
            name: "ground".into(),
            base_color: Vec4::new(0.75, 0.75, 0.75, 1.0),
            ..Material::default()
        },
        Material {
            name: "red".into(),
            base_color: Vec4::new(0.8, 0.15, 0.1, 1.0),
            ..Material::default()
        },
    ];
    let objects = vec![
        Object::new("ground", ground(Vec3::ZERO, 12.0), 0),
        Object::new(
            "box",
            cuboid(Aabb {
                min: Vec3::new(-0.5, 0.0, -0.5),
                max: Vec3::new(0.5, 1.0, 0.5),
            }),
            1,
        ),
        Object::new("sphere", sphere(Vec3::new(1.8, 0.5, 0.6), 0.5, 48, 24), 1),
    ];
    Scene {
        objects,
        materials,
        ..Scene::default()
    }
}

/// A flattened scene.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    pub objects: Vec<Object>,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    /// Cameras defined in the file, in file order.
    pub cameras: Vec<SceneCamera>,
    /// What was repaired or skipped while loading, one line each.
    pub warnings: Vec<String>,
}

/// One mesh primitive instance, in world space.
#[derive(Clone, Debug, Default)]
pub struct Object {
    pub name: String,
    pub mesh: Mesh,
    /// Index into [`Scene::materials`].
    pub material: usize,
    /// World-space bounds of the mesh.
    pub bounds: Aabb,
    /// Drawn into the shadow map.
    pub casts_shadows: bool,
    /// Shaded with shadows (V from the shadow map); otherwise V = 1.
    pub receives_shadows: bool,
}

/// An indexed triangle list in world space; front faces are counter-clockwise.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    pub positions: Vec<Vec3>,
    /// Unit normals, one per position.
    pub normals: Vec<Vec3>,
    /// Texture coordinates (set 0), one per position; zeros when the file has none.
    pub uvs: Vec<Vec2>,
    /// Three indices per triangle.
    pub indices: Vec<u32>,
}

impl Mesh {
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// The three corners of triangle `t`.
    pub fn triangle(&self, t: usize) -> [Vec3; 3] {
        let i = &self.indices[3 * t..3 * t + 3];
        [
            self.positions[i[0] as usize],
            self.positions[i[1] as usize],
            self.positions[i[2] as usize],
        ]
    }
}

/// A material: the colour c of the BRDF, and optionally its own k and m.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    pub name: String,
    /// Linear RGBA (glTF baseColorFactor).
    pub base_color: Vec4,
    /// Index into [`Scene::textures`], multiplied with `base_color`, sampled by uv set 0.
    pub base_color_texture: Option<usize>,
    /// The material's own diffuse/specular mix, if it gives one.
    pub k: Option<f32>,
    /// The material's own Blinn-Phong exponent, if it gives one.
    pub m: Option<f32>,
    /// Both faces are shaded (the normal is turned towards the viewer).
    pub double_sided: bool,
}

impl Default for Material {
    fn default() -> Self {
        Self {
            name: "default".into(),
            base_color: Vec4::new(0.8, 0.8, 0.8, 1.0),
            base_color_texture: None,
            k: None,
            m: None,
            double_sided: false,
        }
    }
}

/// An RGBA8 texture whose colour channels are sRGB encoded (glTF base colour).
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    pub width: u32,
    pub height: u32,
    /// Row-major, row 0 at the top (v = 0), four bytes per texel.
    pub rgba8: Vec<u8>,
}

/// A camera found in the file, already reduced to the lab's camera model
/// (eye, target, vertical field of view; up is +Y).
#[derive(Clone, Debug, PartialEq)]
pub struct SceneCamera {
    pub name: String,
    pub camera: Camera,
}

impl Scene {
    /// World bounds of every object.
    pub fn bounds(&self) -> Aabb {
        self.objects.iter().fold(Aabb::EMPTY, |b, o| b.union(&o.bounds))
    }

    pub fn triangle_count(&self) -> usize {
        self.objects.iter().map(|o| o.mesh.triangle_count()).sum()
    }

    /// The material of object `i`.
    pub fn material_of(&self, object: &Object) -> &Material {
        static FALLBACK: std::sync::OnceLock<Material> = std::sync::OnceLock::new();
        self.materials
            .get(object.material)
            .unwrap_or_else(|| FALLBACK.get_or_init(Material::default))
    }
}
