//! Scenes: what is drawn, in world space (metres, +Y up).
//!
//! A glTF file is flattened into [`Object`]s, one per mesh primitive instance,
//! with positions and normals already transformed to world space. The GPU
//! renderer, the CPU reference and the app all read this one structure.

pub mod bounds;
pub mod camera;
pub mod default_scene;
pub mod facts;
pub mod framing;
pub mod gltf;
pub mod lecture_scene;
pub mod plausibility;
pub mod scale;
pub mod shapes;
pub mod simplify;
pub mod stress;

pub use bounds::Aabb;
pub use camera::Camera;
pub use facts::{NormalsPresence, ObjectFacts, SceneFacts, SourceInfo};
pub use scale::SceneScale;

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
    #[error("cannot read scene '{path}': {source}")]
    Read { path: PathBuf, source: std::io::Error },
    #[error("cannot load scene '{path}': {problem}")]
    Load { path: PathBuf, problem: LoadProblem },
}

impl SceneError {
    /// What went wrong, for callers that react to the kind of problem.
    pub fn problem(&self) -> Option<&LoadProblem> {
        match self {
            SceneError::Load { problem, .. } => Some(problem),
            _ => None,
        }
    }
}

/// Why a file could not be turned into a scene (one line each).
#[derive(Clone, Debug, Error, PartialEq)]
pub enum LoadProblem {
    /// Neither glTF JSON nor a binary glTF container.
    #[error("not a glTF file: {0}")]
    NotGltf(String),
    /// A GLB container whose chunks do not fit its bytes.
    #[error("truncated or corrupt GLB: {0}")]
    BadGlb(String),
    /// A buffer or image the file names cannot be read.
    #[error("{what} cannot be read: {reason}")]
    MissingData { what: String, reason: String },
    /// An index, offset or length points outside what it refers to.
    #[error("{what}: {detail}")]
    OutOfRange { what: String, detail: String },
    /// A value the format does not allow.
    #[error("{what}: {detail}")]
    InvalidValue { what: String, detail: String },
    #[error("it requires the extension {0}, which the lab does not support")]
    UnsupportedExtension(String),
    /// Every triangle was degenerate or had a non-finite corner.
    #[error("nothing to draw: {0}")]
    NothingToDraw(String),
    #[error("too large: {0}")]
    TooLarge(String),
    /// The glTF library or the loader panicked; caught so the lab stays up.
    #[error("internal error while reading it ({0})")]
    Internal(String),
}

/// The scene the settings name: their glTF/GLB file, or the built-in scene.
pub fn for_settings(settings: &Settings) -> Result<Scene, SceneError> {
    match &settings.scene {
        Some(path) => load(path),
        None => Ok(default_scene()),
    }
}

/// Loads a glTF (`.gltf` with external or embedded data) or GLB file.
pub fn load(path: &Path) -> Result<Scene, SceneError> {
    gltf::load(path)
}

/// The built-in scene: `assets/default_scene.glb`, built by
/// [`default_scene::build`] and embedded in the binary.
pub fn default_scene() -> Scene {
    default_scene::load_embedded()
}

/// A flattened scene.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    pub objects: Vec<Object>,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    /// Cameras defined in the file, in file order.
    pub cameras: Vec<SceneCamera>,
    /// Point lights placed by the file (KHR_lights_punctual), in node order.
    pub lights: Vec<SceneLight>,
    /// What was repaired or skipped while loading, one line each.
    pub warnings: Vec<String>,
    /// What the file defines beyond the flattened objects (counts, the
    /// bounds of points and lines); `None` for scenes built in code.
    pub source: Option<SourceInfo>,
    /// How the lab's lengths map onto this scene: the built-in scale for the
    /// built-in scene and scenes built in code, the bounds' for a file.
    pub scale: SceneScale,
    /// A view designed with the scene (the built-in scene's); none: the
    /// model is framed from its bounds.
    pub designed_view: Option<Camera>,
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
    /// Shaded with shadows (V from the visibility source); otherwise V = 1.
    pub receives_shadows: bool,
}

/// An indexed triangle list in world space; front faces are counter-clockwise.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    pub positions: Vec<Vec3>,
    /// Unit normals, one per position, or none: a glTF primitive without
    /// NORMAL is shaded flat, each triangle with its face's normal.
    pub normals: Vec<Vec3>,
    /// Texture coordinates, one per position: the set the material's base
    /// colour texture samples (set 0 but for rare files); zeros when the
    /// file has none.
    pub uvs: Vec<Vec2>,
    /// Linear RGB factors, one per position, multiplying the material's
    /// base colour (glTF COLOR_0), or none.
    pub colours: Vec<Vec3>,
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
    /// Index into [`Scene::textures`], multiplied with `base_color`, sampled at the mesh's uvs.
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

/// A light the file places (KHR_lights_punctual), reduced to the lab's
/// point light.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneLight {
    pub name: String,
    /// World position (m).
    pub position: Vec3,
    /// Radiant intensity I (W/sr), from the file's candela at
    /// [`gltf::LUMINOUS_EFFICACY_LM_PER_W`]; the lab's power is Φ = 4π I.
    pub intensity_w_sr: f32,
    /// Linear RGB colour.
    pub color: Vec3,
}

impl SceneLight {
    /// The lab's radiant power Φ = 4π I (W).
    pub fn power_w(&self) -> f32 {
        4.0 * std::f32::consts::PI * self.intensity_w_sr
    }
}

impl Scene {
    /// World bounds of every object.
    pub fn bounds(&self) -> Aabb {
        self.objects.iter().fold(Aabb::EMPTY, |b, o| b.union(&o.bounds))
    }

    /// World bounds of the model: every object but the ground the lab adds.
    pub fn model_bounds(&self) -> Aabb {
        self.objects
            .iter()
            .filter(|o| o.name != framing::GROUND_NAME)
            .fold(Aabb::EMPTY, |b, o| b.union(&o.bounds))
    }

    /// The view the scene opens with and Reset view returns to: the
    /// built-in scene's designed view, else the model framed.
    pub fn home_camera(&self) -> Camera {
        self.designed_view
            .unwrap_or_else(|| framing::framed_camera(&self.model_bounds(), Camera::DEFAULT_FOVY_DEG))
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
