//! The built-in scene: a small stage for the lecture's experiments, built
//! here from [`shapes`](super::shapes), stored in `assets/default_scene.glb`,
//! embedded in the binary and loaded through the glTF loader like any file.
//! A test holds the committed asset to what [`build`] makes now, so the two
//! cannot drift; `LUMLAB_RENEW_ASSETS=1 cargo test --lib generated_asset`
//! writes it anew after a change here (then commit it).
//!
//! Seen from the default camera (eye (0, 3.4, 8.2), target (0, 0.7, 0),
//! 45° vertical, 16:9) and lit by the default point light at (2.5, 6, 2):
//! - a thin square occluder floating high on the left, whose shadow lands
//!   on the open ground: a wide penumbra under a sphere light;
//! - a vertical panel on the right that the light grazes at 80–85° from its
//!   normal: shadow acne without bias;
//! - a small cube resting on the ground in front: peter-panning with too
//!   much bias;
//! - three spheres (Lambert red, glossy blue, shiny gold) and a cylinder,
//!   each with its own k and m in the material extras;
//! - a ColorChecker chart standing at the back, facing the camera and the
//!   light: 24 patches whose materials carry the chart's measured spectra
//!   (named `ColorChecker NN …`, see `colour::shading`), their base colour
//!   being their linear sRGB under D65.
//!
//! Every mesh is closed, so no back face is ever seen. Every number is a
//! named constant below.

use super::shapes::{cuboid, cylinder, ground_slab, sphere};
use super::{Aabb, Camera, Material, Object, Scene, SceneCamera};
use crate::colour::PATCH_COUNT;
use crate::colour::chart::patch_linear_srgb;
use crate::colour::shading::chart_material_name;
use glam::{DVec3, Vec3};
use std::path::Path;

/// The committed asset, relative to the crate root.
pub const ASSET_PATH: &str = "assets/default_scene.glb";
/// The committed asset, embedded in the binary.
pub const ASSET: &[u8] = include_bytes!("../../assets/default_scene.glb");

/// Ground: a closed slab whose top is the plane y = 0 (m).
pub const GROUND_SIZE_M: f32 = 12.0;
pub const GROUND_THICKNESS_M: f32 = 0.1;
/// Quads per side of the ground's top: 1 m cells keep the rasterizer's
/// interpolation precise under sharp lobes.
pub const GROUND_CELLS: u32 = 12;

/// Occluder: a thin square plate high above the ground (m).
pub const OCCLUDER_CENTER: Vec3 = Vec3::new(-1.2, 2.4, 0.8);
pub const OCCLUDER_SIZE_M: Vec3 = Vec3::new(1.0, 0.02, 1.0);

/// Grazing panel: a thin vertical panel whose −X face the light reaches at
/// 80–85° from its normal (m).
pub const PANEL_FACE_X_M: f32 = 3.2;
pub const PANEL_THICKNESS_M: f32 = 0.06;
pub const PANEL_HEIGHT_M: f32 = 1.5;
pub const PANEL_WIDTH_M: f32 = 3.0;
pub const PANEL_CENTER_Z_M: f32 = 0.0;

/// Small cube resting on the ground, for peter-panning (m).
pub const SMALL_CUBE_CENTER_XZ: (f32, f32) = (0.6, 1.8);
pub const SMALL_CUBE_SIDE_M: f32 = 0.3;

/// Spheres resting on the ground: centre x, z and radius (m).
pub const RED_SPHERE: (f32, f32, f32) = (-0.9, -0.4, 0.5);
pub const BLUE_SPHERE: (f32, f32, f32) = (0.4, -0.9, 0.45);
pub const GOLD_SPHERE: (f32, f32, f32) = (1.7, -0.1, 0.4);
/// Segments around and rings from pole to pole.
pub const SPHERE_SEGMENTS: u32 = 48;
pub const SPHERE_RINGS: u32 = 24;

/// Cylinder standing on the ground: base x, z, radius, height (m).
pub const CYLINDER: (f32, f32, f32, f32) = (-2.3, -1.8, 0.3, 1.2);
pub const CYLINDER_SEGMENTS: u32 = 48;

/// ColorChecker chart: a board standing on the ground at the back, its
/// front face at z = CHART_FRONT_Z_M, and 6 × 4 patches of CHART_PATCH_M
/// with CHART_GAP_M between them, their lower-left corner at
/// CHART_ORIGIN_XY; placed right of the occluder's and left of the panel's
/// silhouettes and above the spheres' from the default eye, inside the
/// props' bounds so that the scene's scale (`SceneScale`) is unchanged (m).
/// The origin was searched so that, at the 192 × 108 size the GPU is held
/// to the reference with, no patch or board edge passes within 0.002 px of
/// a pixel centre: closer, the rasterizer's sub-pixel snapping and the ray
/// tracer may take different sides of the edge.
pub const CHART_FRONT_Z_M: f32 = -2.04;
pub const CHART_BOARD_THICKNESS_M: f32 = 0.05;
pub const CHART_ORIGIN_XY: (f32, f32) = (-0.792, 0.5485);
pub const CHART_PATCH_M: f32 = 0.42;
pub const CHART_GAP_M: f32 = 0.04;
/// Patches stand this far in front of the board, as thick plates (m).
pub const CHART_PATCH_GAP_M: f32 = 0.002;
pub const CHART_PATCH_THICKNESS_M: f32 = 0.01;
pub const CHART_COLUMNS: usize = 6;
pub const CHART_BOARD: Finish = Finish::new("chart board", [0.03, 0.03, 0.03], 0.9, 8.0);
/// The patches' own k and m: a matte paint.
const CHART_PATCH_K_M: (f32, f32) = (0.95, 8.0);

/// A material of the scene: linear RGB colour c and the lab's k and m.
pub struct Finish {
    pub name: &'static str,
    pub color: [f32; 3],
    pub k: f32,
    pub m: f32,
}

pub const GROUND: Finish = Finish::new("ground", [0.62, 0.62, 0.6], 0.9, 16.0);
pub const OCCLUDER: Finish = Finish::new("occluder slate", [0.2, 0.24, 0.3], 0.8, 16.0);
pub const PANEL: Finish = Finish::new("panel off-white", [0.8, 0.76, 0.66], 0.9, 8.0);
pub const SMALL_CUBE: Finish = Finish::new("cube orange", [0.85, 0.35, 0.08], 0.6, 32.0);
pub const RED_LAMBERT: Finish = Finish::new("red lambert", [0.7, 0.06, 0.05], 1.0, 1.0);
pub const BLUE_GLOSSY: Finish = Finish::new("blue glossy", [0.06, 0.18, 0.65], 0.4, 64.0);
pub const GOLD_SHINY: Finish = Finish::new("gold shiny", [1.0, 0.71, 0.29], 0.15, 512.0);
pub const CYLINDER_GREEN: Finish = Finish::new("cylinder green", [0.18, 0.45, 0.22], 0.7, 24.0);

impl Finish {
    const fn new(name: &'static str, color: [f32; 3], k: f32, m: f32) -> Self {
        Self { name, color, k, m }
    }

    fn material(&self) -> Material {
        Material {
            name: self.name.into(),
            base_color: Vec3::from_array(self.color).extend(1.0),
            k: Some(self.k),
            m: Some(self.m),
            ..Material::default()
        }
    }
}

/// A box given by its centre and size.
fn centred_box(center: Vec3, size: Vec3) -> Aabb {
    Aabb {
        min: center - 0.5 * size,
        max: center + 0.5 * size,
    }
}

/// The scene, built in code.
pub fn scene() -> Scene {
    let finishes = [
        &GROUND,
        &OCCLUDER,
        &PANEL,
        &SMALL_CUBE,
        &RED_LAMBERT,
        &BLUE_GLOSSY,
        &GOLD_SHINY,
        &CYLINDER_GREEN,
    ];
    let material = |f: &Finish| finishes.iter().position(|g| g.name == f.name).unwrap_or(0);
    let resting_sphere =
        |(x, z, r): (f32, f32, f32)| sphere(Vec3::new(x, r, z), r, SPHERE_SEGMENTS, SPHERE_RINGS);
    let (cube_x, cube_z) = SMALL_CUBE_CENTER_XZ;
    let (cyl_x, cyl_z, cyl_r, cyl_h) = CYLINDER;
    let objects = vec![
        Object::new(
            "ground",
            ground_slab(Vec3::ZERO, GROUND_SIZE_M, GROUND_THICKNESS_M, GROUND_CELLS),
            material(&GROUND),
        ),
        Object::new(
            "occluder",
            cuboid(centred_box(OCCLUDER_CENTER, OCCLUDER_SIZE_M)),
            material(&OCCLUDER),
        ),
        Object::new(
            "grazing panel",
            cuboid(Aabb {
                min: Vec3::new(PANEL_FACE_X_M, 0.0, PANEL_CENTER_Z_M - 0.5 * PANEL_WIDTH_M),
                max: Vec3::new(
                    PANEL_FACE_X_M + PANEL_THICKNESS_M,
                    PANEL_HEIGHT_M,
                    PANEL_CENTER_Z_M + 0.5 * PANEL_WIDTH_M,
                ),
            }),
            material(&PANEL),
        ),
        Object::new(
            "small cube",
            cuboid(centred_box(
                Vec3::new(cube_x, 0.5 * SMALL_CUBE_SIDE_M, cube_z),
                Vec3::splat(SMALL_CUBE_SIDE_M),
            )),
            material(&SMALL_CUBE),
        ),
        Object::new("red sphere", resting_sphere(RED_SPHERE), material(&RED_LAMBERT)),
        Object::new("blue sphere", resting_sphere(BLUE_SPHERE), material(&BLUE_GLOSSY)),
        Object::new("gold sphere", resting_sphere(GOLD_SPHERE), material(&GOLD_SHINY)),
        Object::new(
            "cylinder",
            cylinder(Vec3::new(cyl_x, 0.0, cyl_z), cyl_r, cyl_h, CYLINDER_SEGMENTS),
            material(&CYLINDER_GREEN),
        ),
    ];
    let mut objects = objects;
    let mut materials: Vec<Material> = finishes.iter().map(|f| f.material()).collect();
    chart(&mut objects, &mut materials);
    Scene {
        objects,
        materials,
        cameras: vec![SceneCamera {
            name: "default".into(),
            camera: Camera::default(),
        }],
        ..Scene::default()
    }
}

/// The chart's board (resting on the ground) and its 24 patches, in chart
/// order left to right, top to bottom.
fn chart(objects: &mut Vec<Object>, materials: &mut Vec<Material>) {
    let pitch = CHART_PATCH_M + CHART_GAP_M;
    let rows = PATCH_COUNT.div_ceil(CHART_COLUMNS);
    let (x0, y0) = CHART_ORIGIN_XY;
    let margin = CHART_GAP_M;
    let mut board = Object::new(
        "chart board",
        cuboid(Aabb {
            min: Vec3::new(x0 - margin, 0.0, CHART_FRONT_Z_M - CHART_BOARD_THICKNESS_M),
            max: Vec3::new(
                x0 + CHART_COLUMNS as f32 * pitch,
                y0 + rows as f32 * pitch,
                CHART_FRONT_Z_M,
            ),
        }),
        materials.len(),
    );
    // The chart is an instrument for colour: it casts no shadow, so the
    // shadow experiments (their edges, the moment maps' light bleeding)
    // stay those the scene was designed for.
    board.casts_shadows = false;
    objects.push(board);
    materials.push(CHART_BOARD.material());
    let (k, m) = CHART_PATCH_K_M;
    for patch in 0..PATCH_COUNT {
        let (column, row) = (patch % CHART_COLUMNS, patch / CHART_COLUMNS);
        let min = Vec3::new(
            x0 + column as f32 * pitch,
            y0 + (rows - 1 - row) as f32 * pitch,
            CHART_FRONT_Z_M + CHART_PATCH_GAP_M,
        );
        let size = Vec3::new(CHART_PATCH_M, CHART_PATCH_M, CHART_PATCH_THICKNESS_M);
        let mut plate = Object::new(
            format!("chart patch {:02}", patch + 1),
            cuboid(Aabb { min, max: min + size }),
            materials.len(),
        );
        // Printed on the board, a real chart's patches cast no shadow.
        plate.casts_shadows = false;
        objects.push(plate);
        // glTF base colours lie in 0..1: the cyan patch's red, slightly
        // outside sRGB, is clipped (its spectrum is not).
        let rgb = patch_linear_srgb(patch).clamp(DVec3::ZERO, DVec3::ONE).as_vec3();
        materials.push(Material {
            name: chart_material_name(patch),
            base_color: rgb.extend(1.0),
            k: Some(k),
            m: Some(m),
            ..Material::default()
        });
    }
}

/// The scene as the GLB bytes of the committed asset.
pub fn build() -> Vec<u8> {
    super::gltf::to_glb(&scene())
}

/// The embedded asset through the loader; should it ever fail (the tests
/// say it does not), the same scene built in code, with a warning.
///
/// glTF stores a camera as a node's rotation, not as a target point, so the
/// loaded camera's target is the default one only to f32 rounding; the
/// generator's exact camera (the app's default view) replaces it.
pub fn load_embedded() -> Scene {
    match super::gltf::load_slice(ASSET, Path::new("built-in scene"), None) {
        Ok(mut scene) => {
            scene.cameras = self::scene().cameras;
            scene.scale = super::SceneScale::BUILT_IN;
            scene.designed_view = Some(Camera::default());
            scene
        }
        Err(e) => {
            let mut scene = scene();
            scene
                .warnings
                .push(format!("{e}; the scene was built in code instead"));
            scene
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::{ImageSettings, LightSettings};

    fn default_camera() -> Camera {
        Camera::default()
    }

    /// Normalized device coordinates of `p` seen by the default camera
    /// (x, y in [−1, 1] inside the 16:9 view), or `None` behind it.
    fn ndc(p: Vec3) -> Option<(f64, f64)> {
        let camera = default_camera();
        let image = ImageSettings::default();
        let aspect = image.width as f64 / image.height as f64;
        let clip = camera.projection(aspect, 0.1, 100.0)
            * camera.view_rotation()
            * (p.as_dvec3() - camera.eye.as_dvec3()).extend(1.0);
        (clip.w > 0.0).then(|| (clip.x / clip.w, clip.y / clip.w))
    }

    fn inside_view(p: Vec3, margin: f64) -> bool {
        ndc(p).is_some_and(|(x, y)| x.abs() <= 1.0 - margin && y.abs() <= 1.0 - margin)
    }

    #[test]
    fn the_generated_asset_is_what_build_makes() {
        let fresh = build();
        if ASSET != fresh.as_slice() {
            crate::output::renew_asset_or_fail(ASSET_PATH, &fresh);
        }
    }

    #[test]
    fn the_embedded_asset_loads_cleanly() {
        let scene = crate::scene::default_scene();
        assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
        // 8 props, the chart's board and its 24 patches.
        assert_eq!(scene.objects.len(), 8 + 1 + PATCH_COUNT);
        assert_eq!(scene.cameras.len(), 1);
        let built = super::scene();
        // The asset's own camera is the default one, to rounding.
        let stored = crate::scene::gltf::load_slice(ASSET, Path::new("asset"), None).unwrap();
        let (a, b) = (&stored.cameras[0].camera, &built.cameras[0].camera);
        let along = (a.target - a.eye).normalize().dot((b.target - b.eye).normalize());
        assert!(
            (a.eye - b.eye).length() < 1e-5 && along > 1.0 - 1e-9,
            "{a:?} vs {b:?}"
        );
        assert!((a.fovy_deg - b.fovy_deg).abs() < 1e-4);
        assert_eq!(scene.triangle_count(), built.triangle_count());
        for (loaded, made) in scene.objects.iter().zip(&built.objects) {
            assert_eq!(loaded.name, made.name);
            assert_eq!(loaded.bounds, made.bounds);
            assert_eq!(scene.material_of(loaded), built.material_of(made));
        }
        let red = scene
            .materials
            .iter()
            .find(|m| m.name == RED_LAMBERT.name)
            .unwrap();
        assert_eq!((red.k, red.m), (Some(1.0), Some(1.0)));
    }

    #[test]
    fn every_prop_is_inside_the_default_view() {
        for object in scene().objects.iter().filter(|o| o.name != "ground") {
            for corner in object.bounds.corners() {
                assert!(
                    inside_view(corner, 0.03),
                    "{} corner {corner} is outside the view: {:?}",
                    object.name,
                    ndc(corner)
                );
            }
        }
    }

    #[test]
    fn props_rest_on_the_ground_without_touching_each_other() {
        let scene = scene();
        let props: Vec<&Object> = scene.objects.iter().filter(|o| o.name != "ground").collect();
        for (i, a) in props.iter().enumerate() {
            assert!(a.bounds.min.y >= 0.0, "{} sinks into the ground", a.name);
            assert!(a.bounds.max.x.abs() < 0.5 * GROUND_SIZE_M && a.bounds.max.z.abs() < 0.5 * GROUND_SIZE_M);
            for b in &props[i + 1..] {
                assert!(!a.bounds.intersects(&b.bounds), "{} touches {}", a.name, b.name);
            }
        }
        let ground = &scene.objects[0];
        assert_eq!(ground.bounds.max.y, 0.0);
    }

    #[test]
    fn the_occluder_shadow_lands_on_open_ground_in_view() {
        let light = LightSettings::DEFAULT_POSITION;
        let scene = scene();
        let occluder = &scene.objects[1].bounds;
        // The shadow of each corner of the plate's underside on y = 0.
        let shadow: Vec<Vec3> = occluder
            .corners()
            .into_iter()
            .filter(|c| c.y == occluder.min.y)
            .map(|c| light + (c - light) * (light.y / (light.y - c.y)))
            .collect();
        let footprint = Aabb::from_points(shadow.iter().copied());
        for corner in &shadow {
            assert!(
                inside_view(*corner, 0.05),
                "shadow corner {corner} is outside the view"
            );
        }
        // Nothing else stands on the ground where the shadow and its
        // penumbra fall.
        let margin_m = 0.3;
        let overlaps_xz = |b: &Aabb| {
            b.min.x <= footprint.max.x + margin_m
                && footprint.min.x - margin_m <= b.max.x
                && b.min.z <= footprint.max.z + margin_m
                && footprint.min.z - margin_m <= b.max.z
        };
        for o in scene.objects.iter().skip(2) {
            assert!(!overlaps_xz(&o.bounds), "{} stands in the shadow", o.name);
        }
        // Wide: the penumbra of a 0.3 m sphere light is 0.4 m across.
        let gap = OCCLUDER_CENTER.y as f64;
        let to_light = (light.y - OCCLUDER_CENTER.y) as f64;
        assert!(2.0 * 0.3 * gap / to_light > 0.35);
    }

    #[test]
    fn light_grazes_the_panel_between_80_and_85_degrees() {
        let light = LightSettings::DEFAULT_POSITION.as_dvec3();
        let normal = DVec3::NEG_X;
        let z0 = (PANEL_CENTER_Z_M - 0.5 * PANEL_WIDTH_M) as f64;
        let z1 = (PANEL_CENTER_Z_M + 0.5 * PANEL_WIDTH_M) as f64;
        for y in [0.0, 0.5 * PANEL_HEIGHT_M as f64, PANEL_HEIGHT_M as f64] {
            for z in [z0, 0.5 * (z0 + z1), z1] {
                let p = DVec3::new(PANEL_FACE_X_M as f64, y, z);
                let angle = normal.angle_between(light - p).to_degrees();
                assert!((80.0..=85.0).contains(&angle), "{angle:.1}° at y {y}, z {z}");
            }
        }
        // The face the light grazes is the one the camera sees.
        const { assert!(Camera::DEFAULT_EYE.x < PANEL_FACE_X_M) };
    }

    #[test]
    fn the_small_cube_sits_in_front_on_the_ground() {
        let scene = scene();
        let cube = scene.objects.iter().find(|o| o.name == "small cube").unwrap();
        assert_eq!(cube.bounds.min.y, 0.0);
        assert!(
            scene
                .objects
                .iter()
                .filter(|o| o.name != "ground" && o.name != "small cube")
                .all(|o| o.bounds.max.z < cube.bounds.max.z)
        );
    }
}
