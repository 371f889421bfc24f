//! The file's cameras, reduced to the lab's camera model: eye, target (where the orbit
//! turns) and vertical field of view.

use super::nodes::CameraInstance;
use super::{Loader, lab_extras};
use crate::scene::{Aabb, Camera, SceneCamera};
use crate::settings::Settings;
use glam::DVec3;
use gltf::json::camera::Type as CameraType;
use gltf::json::validation::Checked;

/// Field of view given to an orthographic camera when the scene gives no
/// distance to match its magnification with (degrees).
const FALLBACK_FOVY_DEG: f64 = 45.0;
/// The lab's field-of-view range (degrees), as the command line accepts it.
const FOVY_RANGE_DEG: (f64, f64) = (1.0, 179.0);

impl Loader<'_, '_, '_> {
    /// The placed cameras in file order, reduced to eye, target (along the
    /// node's −Z, at the depth of the bounds' centre unless the node's
    /// extras say `{"lumlab": {"target_distance": 8.6}}`) and vertical field
    /// of view.
    pub(super) fn cameras(&mut self, placed: &[CameraInstance], bounds: &Aabb) -> Vec<SceneCamera> {
        let root = self.root;
        let mut order: Vec<&CameraInstance> = placed.iter().collect();
        order.sort_by_key(|c| (c.camera, c.node));
        let mut cameras = Vec::new();
        for instance in order {
            let json = &root.cameras[instance.camera];
            let name = json
                .name
                .clone()
                .or_else(|| root.nodes[instance.node].name.clone())
                .unwrap_or_else(|| format!("camera {}", instance.camera));
            let eye = instance.world.transform_point3(DVec3::ZERO);
            let Some(forward) = instance.world.transform_vector3(DVec3::NEG_Z).try_normalize() else {
                self.warn(format!(
                    "camera '{name}': its node's transform has no direction; skipped"
                ));
                continue;
            };
            let fovy_deg = match (json.type_, &json.perspective, &json.orthographic) {
                (Checked::Valid(CameraType::Perspective), Some(p), _) => {
                    let deg = (p.yfov as f64).to_degrees();
                    if deg.is_finite() && deg > 0.0 && deg < 180.0 {
                        deg
                    } else {
                        self.warn(format!(
                            "camera '{name}': yfov {} is not an angle in (0, π); 45° used",
                            p.yfov
                        ));
                        FALLBACK_FOVY_DEG
                    }
                }
                (Checked::Valid(CameraType::Orthographic), _, Some(o)) => {
                    // The perspective view that shows the orthographic height
                    // 2·ymag at the distance of the scene's centre.
                    let distance = (bounds.center().as_dvec3() - eye).dot(forward);
                    let ymag = (o.ymag as f64).abs();
                    let deg = if !bounds.is_empty() && distance > 1e-6 && ymag > 0.0 && ymag.is_finite() {
                        2.0 * (ymag / distance).atan().to_degrees()
                    } else {
                        FALLBACK_FOVY_DEG
                    };
                    self.warn(format!(
                        "camera '{name}' is orthographic: shown in perspective with a {deg:.1}° field of view"
                    ));
                    deg
                }
                _ => {
                    self.warn(format!("camera '{name}' has no usable projection; skipped"));
                    continue;
                }
            };
            let clamped = fovy_deg.clamp(FOVY_RANGE_DEG.0, FOVY_RANGE_DEG.1);
            if clamped != fovy_deg {
                self.warn(format!(
                    "camera '{name}': a {fovy_deg:.3}° field of view is outside 1° … 179°; {clamped}° used"
                ));
            }
            let distance_m = target_distance(&root.nodes[instance.node].extras)
                .unwrap_or_else(|| orbit_distance(eye, forward, bounds));
            let camera = Camera {
                eye: eye.as_vec3(),
                target: (eye + forward * distance_m).as_vec3(),
                fovy_deg: clamped as f32,
            };
            // Past the lab's range, or so far out that f32 cannot tell its
            // target from its eye.
            if let Err(e) = Settings::validate_camera(&camera) {
                self.warn(format!("camera '{name}' is not usable ({e}); skipped"));
                continue;
            }
            cameras.push(SceneCamera { name, camera });
        }
        cameras
    }
}

/// How far ahead of a file's camera its orbit target goes (m): the depth of
/// the scene's centre along the view, so that orbiting turns around the
/// model; a tenth of the scene's size when the centre is behind or too near
/// (1 m for an empty scene).
fn orbit_distance(eye: DVec3, forward: DVec3, bounds: &Aabb) -> f64 {
    if bounds.is_empty() {
        return 1.0;
    }
    let size = bounds.extent().as_dvec3().length().max(1e-9);
    let depth = (bounds.center().as_dvec3() - eye).dot(forward);
    depth.max(0.1 * size)
}

/// A camera node's `{"lumlab": {"target_distance": D}}` (m), when positive.
fn target_distance(extras: &gltf::json::Extras) -> Option<f64> {
    lab_extras(extras)?
        .get("target_distance")?
        .as_f64()
        .filter(|d| d.is_finite() && *d > 0.0)
}
