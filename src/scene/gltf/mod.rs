//! glTF 2.0 loading (`.gltf` with external files or data URIs, and `.glb`):
//! the file's default scene (or scene 0) flattened into world-space
//! [`Object`]s, one per primitive instance.
//!
//! The JSON is deserialized by the `gltf` crate's `json` types; everything
//! after that (indices, offsets, lengths, node links) is checked here, so a
//! malformed file gives a one-line [`LoadProblem`] and what can be repaired
//! (degenerate triangles, bad normals, NaN positions) is, with a warning.
//! As a last line of defence a panic anywhere in the parse is caught and
//! turned into an error.

mod accessor;
mod cameras;
mod container;
mod lights;
mod materials;
mod nodes;
mod primitive;
mod resources;
pub mod write;

pub use lights::LUMINOUS_EFFICACY_LM_PER_W;
pub use primitive::MAX_MODEL_COORDINATE_M;
pub use resources::MAX_IMAGE_SIDE;
pub use write::to_glb;

use super::{Aabb, LoadProblem, Material, Object, Scene, SceneError, SourceInfo};
use accessor::Data;
use gltf::json::Root;
use gltf::json::mesh::Semantic;
use gltf::json::validation::Checked;
use nodes::Placements;
use primitive::{LocalPrimitive, Topology};
use rayon::prelude::*;
use std::collections::{HashMap, HashSet};
use std::path::Path;

/// Extensions a file may require. Quantized attributes are read like any
/// other accessor; emission is not part of the lab's BRDF, so its strength
/// changes nothing that is drawn.
pub const SUPPORTED_REQUIRED_EXTENSIONS: &[&str] =
    &["KHR_mesh_quantization", "KHR_materials_emissive_strength"];

/// The lights' extension: read where a file uses it (its point light
/// becomes the lab's), though not among [`SUPPORTED_REQUIRED_EXTENSIONS`].
/// With those, the extensions a file may use without a warning.
const LIGHTS_EXTENSION: &str = "KHR_lights_punctual";

/// Most triangles a scene may place, all instances counted: beyond this the
/// flattened scene would not fit in memory (about 100 bytes a triangle).
pub const MAX_TRIANGLES: usize = 1 << 25;

/// Loads a `.gltf` or `.glb` file; relative URIs resolve beside it.
pub fn load(path: &Path) -> Result<Scene, SceneError> {
    let bytes =
        crate::input::read_bounded(path, crate::input::SCENE_LIMIT_BYTES, "a scene").map_err(|source| {
            SceneError::Read {
                path: path.to_owned(),
                source,
            }
        })?;
    load_slice(&bytes, path, path.parent())
}

/// Loads glTF or GLB bytes. `name` names the scene in messages; relative
/// URIs resolve in `base_dir` (none: only embedded data may be used).
pub fn load_slice(bytes: &[u8], name: &Path, base_dir: Option<&Path>) -> Result<Scene, SceneError> {
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| read_scene(bytes, base_dir)));
    let problem = match outcome {
        Ok(Ok(scene)) => return Ok(scene),
        Ok(Err(problem)) => problem,
        Err(payload) => LoadProblem::Internal(panic_message(payload.as_ref())),
    };
    Err(SceneError::Load {
        path: name.to_owned(),
        problem,
    })
}

fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    let text = payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "panic".into());
    text.replace('\n', " ")
}

fn read_scene(bytes: &[u8], base_dir: Option<&Path>) -> Result<Scene, LoadProblem> {
    let container::Container { root, bin } = container::parse(bytes)?;
    if let Some(ext) = root
        .extensions_required
        .iter()
        .find(|e| !SUPPORTED_REQUIRED_EXTENSIONS.contains(&e.as_str()))
    {
        return Err(LoadProblem::UnsupportedExtension(ext.clone()));
    }
    let buffers = resources::load_buffers(&root, bin, base_dir)?;
    let data = Data {
        root: &root,
        buffers: &buffers,
    };
    Loader {
        data: &data,
        root: &root,
        base_dir,
        warnings: Vec::new(),
    }
    .run()
}

/// Repairs counted over the whole scene, reported as one warning each.
#[derive(Default)]
struct Tally {
    degenerate: usize,
    out_of_range: usize,
    distant_vertices: usize,
    normals_repaired: usize,
    points_or_lines: usize,
    without_positions: usize,
    singular: usize,
    attributes_ignored: Vec<String>,
}

struct Loader<'d, 'r, 'b> {
    data: &'d Data<'r, 'b>,
    root: &'r Root,
    base_dir: Option<&'d Path>,
    warnings: Vec<String>,
}

impl Loader<'_, '_, '_> {
    /// A warning, kept to one line whatever names from the file it quotes.
    fn warn(&mut self, message: String) {
        self.warnings.push(crate::input::escape_controls(&message));
    }

    fn run(mut self) -> Result<Scene, LoadProblem> {
        let root = self.root;
        let ignored: Vec<&str> = root
            .extensions_used
            .iter()
            .map(String::as_str)
            // What any other changes (a texture's placement, a PBR lobe) is not drawn.
            .filter(|&e| e != LIGHTS_EXTENSION && !SUPPORTED_REQUIRED_EXTENSIONS.contains(&e))
            .collect();
        if !ignored.is_empty() {
            self.warn(format!(
                "the file uses extensions the lab does not read: {} (it draws the base colour, its texture and \
                 the vertex colours, with the lab's own BRDF)",
                ignored.join(", ")
            ));
        }
        let (scene_index, roots) = self.roots()?;
        if root.meshes.is_empty() {
            return Ok(self.empty(scene_index, "it defines no mesh".into()));
        }
        let placed = self.walk(&roots)?;
        if placed.meshes.is_empty() {
            let why = match scene_index {
                Some(i) => format!("scene {i} places no mesh"),
                None => "no node places a mesh".into(),
            };
            return Ok(self.empty(scene_index, why));
        }
        let (mut materials, textures) = self.materials();
        let locals = self.primitives(&placed)?;
        let planned: usize = placed
            .meshes
            .iter()
            .flat_map(|m| locals[&m.mesh].iter().flatten())
            .map(|p| p.mesh.triangle_count())
            .sum();
        if planned > MAX_TRIANGLES {
            return Err(LoadProblem::TooLarge(format!(
                "the scene places {planned} triangles; the lab draws at most {MAX_TRIANGLES}"
            )));
        }
        let default_material = materials.len();
        let mut tally = Tally::default();
        let mut undrawn_bounds = Aabb::EMPTY;
        let mut objects = Vec::new();
        let mut triangles_defined = 0;
        // Each placed triangle mesh in world space, repaired, on the thread
        // pool: whether its placement is singular, and per primitive (mesh,
        // triangles out of range, degenerate ones).
        let repaired: Vec<(bool, Vec<_>)> = placed
            .meshes
            .par_iter()
            .map(|instance| {
                let world = instance.world.as_mat4();
                let singular = !world.determinant().is_normal();
                let locals = &locals[&instance.mesh];
                let meshes = locals
                    .iter()
                    .map(|local| {
                        let local = local
                            .as_ref()
                            .filter(|l| l.topology == Topology::Triangles && !singular)?;
                        let mut placed = local.mesh.transformed(world);
                        let (out_of_range, degenerate) = primitive::repair_placed(&mut placed);
                        Some((placed, out_of_range, degenerate))
                    })
                    .collect();
                (singular, meshes)
            })
            .collect();
        for (instance, (singular, repaired)) in placed.meshes.iter().zip(repaired) {
            let mesh_json = &root.meshes[instance.mesh];
            let node_json = &root.nodes[instance.node];
            let world = instance.world.as_mat4();
            let (casts, receives) = shadow_flags(&node_json.extras);
            for (p, (local, repaired)) in locals[&instance.mesh].iter().zip(repaired).enumerate() {
                let Some(local) = local else {
                    tally.without_positions += 1;
                    continue;
                };
                if local.topology == Topology::PointsOrLines {
                    tally.points_or_lines += 1;
                } else {
                    triangles_defined += local.triangles_defined;
                    tally.degenerate += local.degenerate;
                    tally.out_of_range += local.out_of_range;
                    if singular {
                        tally.singular += 1;
                        tally.degenerate += local.mesh.triangle_count();
                    }
                }
                let mut mesh = None;
                if let Some((placed, out_of_range, degenerate)) = repaired {
                    tally.out_of_range += out_of_range;
                    tally.degenerate += degenerate;
                    mesh = Some(placed).filter(|m| !m.indices.is_empty());
                }
                let Some(mesh) = mesh else {
                    let points = local
                        .mesh
                        .positions
                        .iter()
                        .map(|&q| world.transform_point3(q))
                        .filter(|&q| primitive::within(q, MAX_MODEL_COORDINATE_M));
                    undrawn_bounds = undrawn_bounds.union(&Aabb::from_points(points));
                    continue;
                };
                let material = match mesh_json.primitives[p].material {
                    Some(m) => m.value(),
                    None => default_material,
                };
                let mut object =
                    Object::new(object_name(root, instance.node, instance.mesh, p), mesh, material);
                object.casts_shadows = casts;
                object.receives_shadows = receives;
                objects.push(object);
            }
        }
        for local in locals.values().flatten().flatten() {
            tally.normals_repaired += local.normals_repaired;
            tally.distant_vertices += local.distant_vertices;
            tally
                .attributes_ignored
                .extend(local.attributes_ignored.iter().cloned());
        }
        if objects.is_empty() && triangles_defined > 0 {
            return Err(LoadProblem::NothingToDraw(format!(
                "all {triangles_defined} triangles are degenerate or have NaN, infinite or distant \
                 corners (past ±{MAX_MODEL_COORDINATE_M:.0e} m)"
            )));
        }
        if objects.is_empty() && tally.points_or_lines == 0 {
            return Err(LoadProblem::NothingToDraw("no primitive has positions".into()));
        }
        if objects.iter().any(|o| o.material == default_material) {
            materials.push(Material::default());
        }
        self.report(&tally);
        let bounds = objects
            .iter()
            .fold(undrawn_bounds, |b, o: &Object| b.union(&o.bounds));
        let cameras = self.cameras(&placed.cameras, &bounds);
        let lights = self.lights(&placed.lights);
        let source = SourceInfo {
            meshes: root.meshes.len(),
            primitives: root.meshes.iter().map(|m| m.primitives.len()).sum(),
            primitives_with_normals: root
                .meshes
                .iter()
                .flat_map(|m| &m.primitives)
                .filter(|p| p.attributes.contains_key(&Checked::Valid(Semantic::Normals)))
                .count(),
            nodes: root.nodes.len(),
            scenes: root.scenes.len(),
            scene: scene_index,
            undrawn_bounds,
        };
        Ok(Scene {
            objects,
            materials,
            textures,
            cameras,
            lights,
            warnings: self.warnings,
            source: Some(source),
            scale: super::SceneScale::of_bounds(&bounds),
            designed_view: None,
        })
    }

    /// A valid file with nothing to draw: an empty scene whose warning says
    /// why (the lab shows it in the viewport; `info` reports 0 triangles).
    fn empty(mut self, scene: Option<usize>, why: String) -> Scene {
        let root = self.root;
        self.warn(format!("nothing to draw: {why}"));
        Scene {
            warnings: self.warnings,
            source: Some(SourceInfo {
                meshes: root.meshes.len(),
                primitives: root.meshes.iter().map(|m| m.primitives.len()).sum(),
                primitives_with_normals: 0,
                nodes: root.nodes.len(),
                scenes: root.scenes.len(),
                scene,
                undrawn_bounds: Aabb::EMPTY,
            }),
            ..Scene::default()
        }
    }

    /// Every primitive of every placed mesh, read once however many nodes
    /// place it; `None` for a primitive without positions.
    fn primitives(
        &self,
        placed: &Placements,
    ) -> Result<HashMap<usize, Vec<Option<LocalPrimitive>>>, LoadProblem> {
        let mut seen = HashSet::new();
        let meshes: Vec<usize> = placed
            .meshes
            .iter()
            .map(|instance| instance.mesh)
            .filter(|&mesh| seen.insert(mesh))
            .collect();
        // Each mesh on the thread pool; the first problem in the placements'
        // order is the one reported.
        let built: Vec<_> = meshes
            .par_iter()
            .map(|&mesh| self.mesh_primitives(mesh))
            .collect();
        let mut locals = HashMap::new();
        for (mesh, built) in meshes.into_iter().zip(built) {
            locals.insert(mesh, built?);
        }
        Ok(locals)
    }

    /// Mesh `mesh`'s primitives in its own frame.
    fn mesh_primitives(&self, mesh: usize) -> Result<Vec<Option<LocalPrimitive>>, LoadProblem> {
        let root = self.root;
        let mut built = Vec::new();
        for (p, json) in root.meshes[mesh].primitives.iter().enumerate() {
            let uv_set = match json.material {
                Some(m) => {
                    let material = root.materials.get(m.value()).ok_or_else(|| {
                        out_of_range(
                            &format!("mesh {mesh} primitive"),
                            p,
                            "material",
                            m.value(),
                            root.materials.len(),
                        )
                    })?;
                    material
                        .pbr_metallic_roughness
                        .base_color_texture
                        .as_ref()
                        .map_or(0, |t| t.tex_coord)
                }
                None => 0,
            };
            let what = format!("mesh {mesh} primitive {p}");
            built.push(primitive::build(self.data, json, &what, uv_set)?);
        }
        Ok(built)
    }

    /// One warning per kind of repair, with its count.
    fn report(&mut self, t: &Tally) {
        let lines = [
            (
                t.degenerate,
                format!(
                    "dropped {} degenerate triangles (repeated corners or zero area)",
                    t.degenerate
                ),
            ),
            (
                t.out_of_range,
                format!(
                    "dropped {} triangles with NaN, infinite or distant corners (past ±{:.0e} m; \
                     {} such vertices in the file, others placed there by their node's transform)",
                    t.out_of_range, MAX_MODEL_COORDINATE_M, t.distant_vertices
                ),
            ),
            (
                t.normals_repaired,
                format!(
                    "repaired {} zero, NaN or infinite normals with generated ones",
                    t.normals_repaired
                ),
            ),
            (
                t.points_or_lines,
                format!(
                    "skipped {} point or line primitive instances (only triangles are drawn)",
                    t.points_or_lines
                ),
            ),
            (
                t.without_positions,
                format!(
                    "skipped {} primitive instances without POSITION",
                    t.without_positions
                ),
            ),
            (
                t.singular,
                format!(
                    "{} mesh instances have a transform that flattens them (scale 0): their triangles are dropped",
                    t.singular
                ),
            ),
        ];
        for (count, line) in lines {
            if count > 0 {
                self.warn(line);
            }
        }
        if let Some(first) = t.attributes_ignored.first() {
            self.warn(format!(
                "ignored {} attributes with the wrong count (first: {first})",
                t.attributes_ignored.len()
            ));
        }
    }
}

fn out_of_range(owner: &str, owner_index: usize, kind: &str, index: usize, available: usize) -> LoadProblem {
    LoadProblem::OutOfRange {
        what: format!("{owner} {owner_index}"),
        detail: format!("names {kind} {index}, which does not exist (the file has {available})"),
    }
}

/// "node name", else "mesh name", else "node 3"; with "#p" when the mesh
/// has several primitives.
fn object_name(root: &Root, node: usize, mesh: usize, primitive: usize) -> String {
    let base = root.nodes[node]
        .name
        .clone()
        .or_else(|| root.meshes[mesh].name.clone())
        .unwrap_or_else(|| format!("node {node}"));
    if root.meshes[mesh].primitives.len() > 1 {
        format!("{base}#{primitive}")
    } else {
        base
    }
}

/// The `"lumlab"` object of some extras, if any.
fn lab_extras(extras: &gltf::json::Extras) -> Option<serde_json::Map<String, serde_json::Value>> {
    let raw = extras.as_ref()?;
    let value: serde_json::Value = serde_json::from_str(raw.get()).ok()?;
    value.get("lumlab")?.as_object().cloned()
}

/// A node's `{"lumlab": {"casts_shadows": false, "receives_shadows": false}}`;
/// both default to true.
fn shadow_flags(extras: &gltf::json::Extras) -> (bool, bool) {
    let lab = lab_extras(extras).unwrap_or_default();
    let flag = |key: &str| lab.get(key).and_then(serde_json::Value::as_bool).unwrap_or(true);
    (flag("casts_shadows"), flag("receives_shadows"))
}
