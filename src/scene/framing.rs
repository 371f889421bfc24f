//! How a model a teacher brings is shown: the camera that frames it, the
//! ground that catches its shadow, and where the light goes. Everything
//! follows the model's bounds, so millimetres and kilometres behave alike.

use super::shapes::ground_grid;
use super::{Aabb, Camera, Material, Object, Scene};
use crate::settings::{GroundMode, GroundSettings, LightSettings, Settings};
use glam::{DVec3, Vec3, Vec4};

/// The name of the ground the lab adds under a model.
pub const GROUND_NAME: &str = "lumlab ground";
/// Azimuth of the framing view, from +Z towards −X (degrees): a
/// three-quarter view with the default light (at about +52°) to its side,
/// so that the shadow falls where the camera sees it.
const FRAMING_AZIMUTH_DEG: f64 = -40.0;
/// Elevation of the framing view (degrees).
const FRAMING_ELEVATION_DEG: f64 = 25.0;
/// The bounding sphere's share of the view's height.
const FRAMING_FILL: f64 = 0.85;
/// The light's azimuth from the framing view's (degrees): to the camera's
/// right, so that the shadow falls to the left and behind, in view.
const LIGHT_AZIMUTH_FROM_VIEW_DEG: f64 = 60.0;
/// The light's elevation above the model's centre (degrees).
const LIGHT_ELEVATION_DEG: f64 = 55.0;
/// The light's distance from the model's centre, in bounding radii.
const LIGHT_DISTANCE_RADII: f64 = 3.0;
/// Quads per side of the added ground (small triangles keep the
/// rasterizer's interpolation precise).
const GROUND_CELLS: u32 = 12;

/// The view a model opens with: its bounds' centre seen from an elevated
/// three-quarter direction, at the distance where the bounding sphere fills
/// the view's height; `fovy_deg` the vertical field of view.
pub fn framed_camera(bounds: &Aabb, fovy_deg: f32) -> Camera {
    if bounds.is_empty() {
        return Camera::default();
    }
    looking_at(
        bounds,
        direction(FRAMING_AZIMUTH_DEG, FRAMING_ELEVATION_DEG),
        fovy_deg,
    )
}

/// The unit direction at `azimuth_deg` from +Z towards +X and `elevation_deg`
/// above the horizon.
fn direction(azimuth_deg: f64, elevation_deg: f64) -> DVec3 {
    let (az, el) = (azimuth_deg.to_radians(), elevation_deg.to_radians());
    DVec3::new(el.cos() * az.sin(), el.sin(), el.cos() * az.cos())
}

/// Where the light goes for a model bounded by `bounds`, and its power (W):
/// above and in front of the model on the camera's side, at three bounding
/// radii from its centre, with the power that gives the model the
/// irradiance the built-in scene's objects get from its default light.
pub fn scene_light(bounds: &Aabb) -> Option<(Vec3, f32)> {
    if bounds.is_empty() {
        return None;
    }
    let (centre, radius) = bounds.bounding_sphere();
    let radius = radius.max(1e-9);
    let distance = LIGHT_DISTANCE_RADII * radius;
    let azimuth = FRAMING_AZIMUTH_DEG + LIGHT_AZIMUTH_FROM_VIEW_DEG;
    let position = centre + direction(azimuth, LIGHT_ELEVATION_DEG) * distance;
    // E = Φ / 4πd²: the built-in light at its distance from the objects.
    let built_in = LightSettings::default();
    let built_in_distance = (built_in.position - Camera::DEFAULT_TARGET).length() as f64;
    let power = built_in.power_w as f64 * (distance / built_in_distance).powi(2);
    Some((position.as_vec3(), power as f32))
}

/// `camera` moved along its own view direction so that `bounds` fill the
/// view (F, "frame all"): the direction and field of view are kept.
pub fn frame_all(camera: &Camera, bounds: &Aabb) -> Camera {
    if bounds.is_empty() {
        return *camera;
    }
    let back = -camera.frame().forward;
    looking_at(bounds, back, camera.fovy_deg)
}

/// The camera on the ray from the bounds' centre along unit `direction`.
fn looking_at(bounds: &Aabb, direction: DVec3, fovy_deg: f32) -> Camera {
    let (centre, radius) = bounds.bounding_sphere();
    let radius = radius.max(1e-9);
    let half = (0.5 * fovy_deg as f64).to_radians();
    let distance = radius / (FRAMING_FILL * half.sin());
    Camera {
        eye: (centre + direction * distance).as_vec3(),
        target: centre.as_vec3(),
        fovy_deg,
    }
}

/// Makes `settings` show `scene` as it opens: its home view; the built-in
/// scene's light as designed, the file's first point light
/// (KHR_lights_punctual: Φ = 4π I, its colour), else a light from the
/// model's bounds ([`scene_light`]); the sphere light's radius and the bias
/// carried to its scale.
pub fn adopt(settings: &mut Settings, scene: &Scene) {
    let defaults = Settings::for_scale(scene.scale);
    settings.camera = scene.home_camera();
    settings.light.color = defaults.light.color;
    let light = match (scene.designed_view, scene.lights.first()) {
        (Some(_), _) => None,
        (None, Some(file)) => {
            settings.light.color = file.color;
            Some((file.position, file.power_w()))
        }
        (None, None) => scene_light(&scene.model_bounds()),
    };
    let (position, power_w) = light.unwrap_or((defaults.light.position, defaults.light.power_w));
    settings.light.position = position;
    settings.light.power_w = power_w;
    settings.light.radius_m = defaults.light.radius_m;
    settings.shadow.bias.depth_m = defaults.shadow.bias.depth_m;
}

/// Whether the scene already has something that catches shadows below it:
/// triangles lying flat at the bounds' lowest height, facing up, that
/// together cover most of their horizontal extent. Triangles, not objects:
/// a model exported as one mesh often holds its floor (a separate ground
/// would then lie in the same plane and fight it for every pixel), and a
/// closed model's own underside faces down.
pub fn has_ground(scene: &Scene) -> bool {
    let bounds = scene.model_bounds();
    if bounds.is_empty() {
        return false;
    }
    let extent = bounds.extent();
    let top = bounds.min.y + 0.02 * extent.length();
    let mut floor = Aabb::EMPTY;
    for o in scene.objects.iter().filter(|o| o.bounds.min.y <= top) {
        for t in o.mesh.indices.chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|k| o.mesh.positions[t[k] as usize]);
            let low = a.y.max(b.y).max(c.y) <= top;
            if low && (b - a).cross(c - a).y > 0.0 {
                floor = floor.including(a).including(b).including(c);
            }
        }
    }
    let covered = floor.extent();
    !floor.is_empty() && covered.x >= 0.8 * extent.x && covered.z >= 0.8 * extent.z
}

/// `scene` with the ground `settings` ask for: under a model at its bounds'
/// lowest point, centred under it, as wide as the built-in scene's ground is
/// for its objects, neutral grey with the settings' k and m. `auto` adds it
/// to a scene that has none; the built-in scene has its own.
pub fn with_ground(mut scene: Scene, settings: &GroundSettings) -> Scene {
    let add = match settings.mode {
        GroundMode::Off => false,
        GroundMode::On => true,
        GroundMode::Auto => !has_ground(&scene),
    };
    let bounds = scene.model_bounds();
    if !add || bounds.is_empty() {
        return scene;
    }
    let centre = bounds.center();
    let size = scene
        .scale
        .length(super::default_scene::GROUND_SIZE_M)
        .max(2.5 * bounds.extent().length());
    let mesh = ground_grid(Vec3::new(centre.x, bounds.min.y, centre.z), size, GROUND_CELLS);
    scene.materials.push(Material {
        name: GROUND_NAME.into(),
        base_color: Vec4::new(0.5, 0.5, 0.5, 1.0),
        k: Some(settings.k),
        m: Some(settings.m),
        ..Material::default()
    });
    scene.objects.push(Object {
        name: GROUND_NAME.into(),
        bounds: Aabb::from_points(mesh.positions.iter().copied()),
        mesh,
        material: scene.materials.len() - 1,
        casts_shadows: false,
        receives_shadows: true,
    });
    scene
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::SceneScale;
    use crate::scene::shapes::cuboid;

    fn box_scene(size: f32) -> Scene {
        let mesh = cuboid(Aabb {
            min: Vec3::new(-0.5 * size, 0.0, -0.5 * size),
            max: Vec3::new(0.5 * size, size, 0.5 * size),
        });
        let bounds = Aabb::from_points(mesh.positions.iter().copied());
        Scene {
            objects: vec![Object {
                name: "box".into(),
                mesh,
                material: 0,
                bounds,
                casts_shadows: true,
                receives_shadows: true,
            }],
            materials: vec![Material::default()],
            scale: SceneScale::of_bounds(&bounds),
            ..Scene::default()
        }
    }

    #[test]
    fn the_framed_view_shows_the_whole_bounding_sphere() {
        for size in [1e-3, 1.0, 1e3] {
            let scene = box_scene(size);
            let b = scene.bounds();
            let c = framed_camera(&b, 45.0);
            let f = c.frame();
            for corner in b.corners() {
                let d = corner.as_dvec3() - c.eye.as_dvec3();
                let depth = d.dot(f.forward);
                assert!(depth > 0.0);
                let t = c.tan_half_fovy();
                assert!(d.dot(f.up).abs() / depth <= t * 1.0001, "size {size}");
                assert!(d.dot(f.right).abs() / depth <= t * 16.0 / 9.0);
            }
            assert!(c.eye.y > c.target.y, "elevated");
        }
    }

    #[test]
    fn the_light_gives_the_model_the_built_in_irradiance_at_every_scale() {
        let built_in = LightSettings::default();
        let d0 = (built_in.position - Camera::DEFAULT_TARGET).length();
        let e0 = built_in.power_w / (4.0 * std::f32::consts::PI * d0 * d0);
        for size in [1e-3, 1.0, 1e3] {
            let b = box_scene(size).bounds();
            let (q, power) = scene_light(&b).unwrap();
            let d = q.distance(b.center());
            let e = power / (4.0 * std::f32::consts::PI * d * d);
            assert!((e / e0 - 1.0).abs() < 1e-4, "size {size}: E {e} against {e0}");
            assert!(q.y > b.max.y, "above the model");
            let camera = framed_camera(&b, 45.0);
            let to_light = (q - b.center()).as_dvec3();
            let to_eye = (camera.eye - camera.target).as_dvec3();
            assert!(to_light.dot(to_eye) > 0.0, "on the camera's side");
        }
    }

    #[test]
    fn frame_all_keeps_the_direction() {
        let b = box_scene(2.0).bounds();
        let c = Camera {
            eye: Vec3::new(50.0, 3.0, 1.0),
            target: b.center(),
            fovy_deg: 30.0,
        };
        let framed = frame_all(&c, &b);
        assert!((framed.frame().forward - c.frame().forward).length() < 1e-6);
        assert!(framed.eye.distance(b.center()) < 10.0);
    }

    /// A model exported as one mesh with its floor: the floor's triangles
    /// count, and no second ground is laid in their plane.
    #[test]
    fn a_floor_inside_the_models_mesh_is_its_ground() {
        let mut scene = box_scene(1.0);
        let mesh = &mut scene.objects[0].mesh;
        let base = mesh.positions.len() as u32;
        // Wound counter-clockwise seen from above: facing up.
        mesh.positions.extend([
            Vec3::new(-2.0, 0.0, -2.0),
            Vec3::new(-2.0, 0.0, 2.0),
            Vec3::new(2.0, 0.0, 2.0),
            Vec3::new(2.0, 0.0, -2.0),
        ]);
        mesh.normals.extend([Vec3::Y; 4]);
        mesh.uvs.extend([glam::Vec2::ZERO; 4]);
        mesh.indices.extend([0, 1, 2, 0, 2, 3].map(|i| base + i));
        scene.objects[0].bounds = Aabb::from_points(mesh.positions.iter().copied());
        assert!(has_ground(&scene));
        let grounded = with_ground(scene.clone(), &GroundSettings::default());
        assert_eq!(grounded.objects.len(), 1);
        // Facing down, the same quad is an underside.
        let mesh = &mut scene.objects[0].mesh;
        let n = mesh.indices.len();
        mesh.indices[n - 6..].reverse();
        assert!(!has_ground(&scene));
    }

    #[test]
    fn a_ground_is_added_once_under_a_model_without_one() {
        let s = GroundSettings::default();
        let scene = with_ground(box_scene(1e3), &s);
        assert_eq!(scene.objects.len(), 2);
        let ground = &scene.objects[1];
        assert_eq!(ground.bounds.max.y, 0.0);
        assert!(ground.bounds.extent().x > 2.0 * 1e3);
        assert!(has_ground(&scene));
        assert_eq!(
            with_ground(scene, &s).objects.len(),
            2,
            "auto adds none to a grounded scene"
        );
        assert!(has_ground(&crate::scene::default_scene()));
        // A box's underside faces down: it is not a ground.
        assert!(!has_ground(&box_scene(1.0)));
        let off = GroundSettings {
            mode: GroundMode::Off,
            ..s
        };
        assert_eq!(with_ground(box_scene(1.0), &off).objects.len(), 1);
    }
}
