//! Facts about a loaded scene: what `lumlab info` prints and what tests
//! check a loader against (counts, bounds, who casts and receives shadows).

use super::{Aabb, Scene};
use serde::Serialize;

/// What the source file defines beyond the flattened objects.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SourceInfo {
    /// Meshes the file defines (in every scene, drawn or not).
    pub meshes: usize,
    /// Primitives of those meshes, of every mode (points and lines too).
    pub primitives: usize,
    /// Of those primitives, the ones with a NORMAL attribute.
    pub primitives_with_normals: usize,
    pub nodes: usize,
    pub scenes: usize,
    /// The scene drawn (the file's default scene, else scene 0); `None` when
    /// the file defines no scene and its root nodes were drawn instead.
    pub scene: Option<usize>,
    /// World bounds (m) of the positions that draw no triangle: points and
    /// lines, and primitive instances whose every triangle was dropped.
    pub undrawn_bounds: Aabb,
}

named_enum! {
    /// Whether the primitives carry their own normals.
    pub enum NormalsPresence {
        /// Every primitive has a NORMAL attribute.
        Every = "all",
        /// No primitive has one: the loader generated them all.
        Missing = "none",
        /// Some have, some do not.
        Partial = "some",
    }
}

impl NormalsPresence {
    /// The presence for `with` primitives having normals out of `total`.
    pub fn of(with: usize, total: usize) -> Self {
        if with == 0 {
            Self::Missing
        } else if with >= total {
            Self::Every
        } else {
            Self::Partial
        }
    }
}

/// Everything `lumlab info` reports; serialized as its JSON output.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SceneFacts {
    /// Meshes the file defines (objects, for a scene built in code).
    pub meshes: usize,
    /// Primitives the file defines, of every mode.
    pub primitives: usize,
    /// Triangles the renderer draws: every instance counted, strips and fans
    /// converted, points, lines and dropped triangles not counted.
    pub triangles: usize,
    pub has_normals: NormalsPresence,
    /// World bounds (m), including the positions of points and lines; `None`
    /// when the scene has no position at all.
    pub bounds_min: Option<[f32; 3]>,
    pub bounds_max: Option<[f32; 3]>,
    /// Cameras found in the drawn scene.
    pub cameras: usize,
    /// What was repaired or skipped while loading.
    pub warnings: Vec<String>,
    pub nodes: usize,
    pub scenes: usize,
    /// The scene drawn, when the file names scenes.
    pub scene: Option<usize>,
    pub materials: usize,
    pub textures: usize,
    /// The drawn objects, one per primitive instance.
    pub objects: Vec<ObjectFacts>,
    /// The cameras, reduced to the lab's model.
    pub camera_list: Vec<CameraFacts>,
}

/// One drawn object.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ObjectFacts {
    pub name: String,
    pub material: String,
    pub triangles: usize,
    pub vertices: usize,
    pub bounds_min: Option<[f32; 3]>,
    pub bounds_max: Option<[f32; 3]>,
    pub casts_shadows: bool,
    pub receives_shadows: bool,
}

/// One camera of the scene.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CameraFacts {
    pub name: String,
    pub eye: [f32; 3],
    pub target: [f32; 3],
    pub fovy_deg: f32,
}

/// The corners of a box, or `None` for an empty one.
fn corners(b: &Aabb) -> (Option<[f32; 3]>, Option<[f32; 3]>) {
    if b.is_empty() {
        (None, None)
    } else {
        (Some(b.min.to_array()), Some(b.max.to_array()))
    }
}

impl Scene {
    /// Bounds, counts and per-object facts of the scene.
    pub fn facts(&self) -> SceneFacts {
        let with_normals = self.objects.iter().filter(|o| !o.mesh.normals.is_empty()).count();
        let in_code = SourceInfo {
            meshes: self.objects.len(),
            primitives: self.objects.len(),
            primitives_with_normals: with_normals,
            nodes: self.objects.len(),
            ..SourceInfo::default()
        };
        let source = self.source.as_ref().unwrap_or(&in_code);
        let (bounds_min, bounds_max) = corners(&self.bounds().union(&source.undrawn_bounds));
        let objects = self
            .objects
            .iter()
            .map(|o| {
                let (bounds_min, bounds_max) = corners(&o.bounds);
                ObjectFacts {
                    name: o.name.clone(),
                    material: self.material_of(o).name.clone(),
                    triangles: o.mesh.triangle_count(),
                    vertices: o.mesh.positions.len(),
                    bounds_min,
                    bounds_max,
                    casts_shadows: o.casts_shadows,
                    receives_shadows: o.receives_shadows,
                }
            })
            .collect();
        let camera_list = self
            .cameras
            .iter()
            .map(|c| CameraFacts {
                name: c.name.clone(),
                eye: c.camera.eye.to_array(),
                target: c.camera.target.to_array(),
                fovy_deg: c.camera.fovy_deg,
            })
            .collect();
        SceneFacts {
            meshes: source.meshes,
            primitives: source.primitives,
            triangles: self.triangle_count(),
            has_normals: NormalsPresence::of(source.primitives_with_normals, source.primitives),
            bounds_min,
            bounds_max,
            cameras: self.cameras.len(),
            warnings: self.warnings.clone(),
            nodes: source.nodes,
            scenes: source.scenes,
            scene: source.scene,
            materials: self.materials.len(),
            textures: self.textures.len(),
            objects,
            camera_list,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::shapes::{cuboid, ground};
    use crate::scene::{Material, Object};
    use glam::Vec3;

    #[test]
    fn a_scene_built_in_code_reports_its_objects() {
        let scene = Scene {
            objects: vec![
                Object::new("ground", ground(Vec3::ZERO, 4.0), 0),
                Object::new(
                    "box",
                    cuboid(Aabb {
                        min: Vec3::ZERO,
                        max: Vec3::ONE,
                    }),
                    0,
                ),
            ],
            materials: vec![Material::default()],
            ..Scene::default()
        };
        let facts = scene.facts();
        assert_eq!((facts.meshes, facts.primitives, facts.triangles), (2, 2, 14));
        assert_eq!(facts.has_normals, NormalsPresence::Every);
        assert_eq!(facts.bounds_min, Some([-2.0, 0.0, -2.0]));
        assert_eq!(facts.bounds_max, Some([2.0, 1.0, 2.0]));
        assert!(
            facts
                .objects
                .iter()
                .all(|o| o.casts_shadows && o.receives_shadows)
        );
    }

    #[test]
    fn undrawn_positions_widen_the_bounds() {
        let scene = Scene {
            source: Some(SourceInfo {
                meshes: 1,
                primitives: 1,
                undrawn_bounds: Aabb {
                    min: Vec3::splat(-1.0),
                    max: Vec3::splat(2.0),
                },
                ..SourceInfo::default()
            }),
            ..Scene::default()
        };
        let facts = scene.facts();
        assert_eq!(facts.triangles, 0);
        assert_eq!(facts.has_normals, NormalsPresence::Missing);
        assert_eq!(facts.bounds_max, Some([2.0; 3]));
    }

    #[test]
    fn normals_presence_names() {
        assert_eq!(NormalsPresence::of(0, 3).name(), "none");
        assert_eq!(NormalsPresence::of(1, 3).name(), "some");
        assert_eq!(NormalsPresence::of(3, 3).name(), "all");
    }
}
