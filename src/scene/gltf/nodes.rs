//! The node hierarchy: the scene's root nodes, and the meshes, cameras and
//! lights the nodes place with their composed transforms.

use super::{Loader, out_of_range};
use crate::scene::LoadProblem;
use glam::{DMat4, DQuat, DVec3};

/// A mesh placed by a node.
pub(super) struct MeshInstance {
    pub(super) node: usize,
    pub(super) mesh: usize,
    pub(super) world: DMat4,
}

/// A camera placed by a node.
pub(super) struct CameraInstance {
    pub(super) node: usize,
    pub(super) camera: usize,
    pub(super) world: DMat4,
}

/// A KHR_lights_punctual light placed by a node.
pub(super) struct LightInstance {
    pub(super) light: usize,
    pub(super) world: DMat4,
}

/// What the node hierarchy places.
#[derive(Default)]
pub(super) struct Placements {
    pub(super) meshes: Vec<MeshInstance>,
    pub(super) cameras: Vec<CameraInstance>,
    pub(super) lights: Vec<LightInstance>,
}

impl Loader<'_, '_, '_> {
    /// The scene drawn and its root nodes: the file's default scene, else
    /// scene 0, else (a file without scenes) every node that is no child.
    pub(super) fn roots(&mut self) -> Result<(Option<usize>, Vec<usize>), LoadProblem> {
        let root = self.root;
        let chosen = root
            .scene
            .map(|s| s.value())
            .or((!root.scenes.is_empty()).then_some(0));
        if let Some(i) = chosen {
            let scene = root.scenes.get(i).ok_or_else(|| LoadProblem::OutOfRange {
                what: "scene".into(),
                detail: format!(
                    "the default scene {i} does not exist (the file has {})",
                    root.scenes.len()
                ),
            })?;
            return Ok((Some(i), scene.nodes.iter().map(|n| n.value()).collect()));
        }
        if root.nodes.is_empty() {
            return Ok((None, Vec::new()));
        }
        let mut is_child = vec![false; root.nodes.len()];
        for child in root.nodes.iter().flat_map(|n| n.children.iter().flatten()) {
            if let Some(flag) = is_child.get_mut(child.value()) {
                *flag = true;
            }
        }
        let roots: Vec<usize> = (0..root.nodes.len()).filter(|&i| !is_child[i]).collect();
        self.warn(format!(
            "the file defines no scene: its {} root nodes are drawn",
            roots.len()
        ));
        Ok((None, roots))
    }

    /// Walks the node hierarchy from `roots`, composing transforms. A node
    /// is placed once: a second reference (a cycle, or a node with two
    /// parents, both invalid glTF) is skipped, so the walk always ends.
    pub(super) fn walk(&mut self, roots: &[usize]) -> Result<Placements, LoadProblem> {
        let root = self.root;
        let mut placed = Placements::default();
        let mut visited = vec![false; root.nodes.len()];
        let (mut repeated, mut bad_transforms, mut skinned, mut morphed) = (0, 0, 0, 0);
        let mut stack: Vec<(usize, DMat4, Option<usize>)> =
            roots.iter().rev().map(|&n| (n, DMat4::IDENTITY, None)).collect();
        while let Some((index, parent_world, parent)) = stack.pop() {
            let node = root.nodes.get(index).ok_or_else(|| LoadProblem::OutOfRange {
                what: match parent {
                    Some(p) => format!("node {p}"),
                    None => "scene".into(),
                },
                detail: format!(
                    "names node {index}, which does not exist (the file has {})",
                    root.nodes.len()
                ),
            })?;
            if std::mem::replace(&mut visited[index], true) {
                repeated += 1;
                continue;
            }
            let Some(world) = local_matrix(node)
                .map(|m| parent_world * m)
                .filter(|m| m.is_finite())
            else {
                bad_transforms += 1;
                continue;
            };
            if let Some(mesh) = node.mesh {
                let mesh = mesh.value();
                let json = root
                    .meshes
                    .get(mesh)
                    .ok_or_else(|| out_of_range("node", index, "mesh", mesh, root.meshes.len()))?;
                skinned += usize::from(node.skin.is_some());
                morphed += usize::from(json.primitives.iter().any(|p| p.targets.is_some()));
                placed.meshes.push(MeshInstance {
                    node: index,
                    mesh,
                    world,
                });
            }
            if let Some(camera) = node.camera {
                let camera = camera.value();
                if camera >= root.cameras.len() {
                    return Err(out_of_range("node", index, "camera", camera, root.cameras.len()));
                }
                placed.cameras.push(CameraInstance {
                    node: index,
                    camera,
                    world,
                });
            }
            if let Some(light) = node
                .extensions
                .as_ref()
                .and_then(|e| e.khr_lights_punctual.as_ref())
            {
                placed.lights.push(LightInstance {
                    light: light.light.value(),
                    world,
                });
            }
            for child in node.children.iter().flatten().rev() {
                stack.push((child.value(), world, Some(index)));
            }
        }
        if repeated > 0 {
            self.warn(format!(
                "{repeated} node references repeat a node already placed (a cycle or a second parent): skipped"
            ));
        }
        if bad_transforms > 0 {
            self.warn(format!(
                "{bad_transforms} nodes have a NaN or infinite transform: skipped with their children"
            ));
        }
        if skinned > 0 {
            self.warn(format!(
                "{skinned} skinned meshes are drawn unskinned (skins are ignored)"
            ));
        }
        if morphed > 0 {
            self.warn(format!("{morphed} meshes have morph targets, which are ignored"));
        }
        Ok(placed)
    }
}

/// The node's own transform: its matrix, or translation × rotation × scale
/// with the rotation normalized (files often store it to a few digits).
/// `None` when it is not finite.
fn local_matrix(node: &gltf::json::Node) -> Option<DMat4> {
    let matrix = match node.matrix {
        Some(m) => DMat4::from_cols_array(&m.map(f64::from)),
        None => {
            let t = DVec3::from_array(node.translation.unwrap_or([0.0; 3]).map(f64::from));
            let s = DVec3::from_array(node.scale.unwrap_or([1.0; 3]).map(f64::from));
            let q = DQuat::from_array(node.rotation.map_or([0.0, 0.0, 0.0, 1.0], |r| r.0).map(f64::from));
            let length = q.length();
            if !(length.is_finite() && length > 0.0) {
                return None;
            }
            DMat4::from_scale_rotation_translation(s, q / length, t)
        }
    };
    matrix.is_finite().then_some(matrix)
}
