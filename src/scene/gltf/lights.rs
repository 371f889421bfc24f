//! The file's KHR_lights_punctual lights, reduced to the lab's point light:
//! a point light as it is, a spot light as a point light (its cone is not
//! modelled, said in a warning), a directional light skipped with a warning.

use super::Loader;
use super::nodes::LightInstance;
use crate::scene::SceneLight;
use glam::{DVec3, Vec3};
use gltf::json::extensions::scene::khr_lights_punctual::Type;
use gltf::json::validation::Checked;

/// Lumens per watt used to turn the file's photometric intensity (candela)
/// into radiant intensity (W/sr): 683 lm/W, the efficacy of 555 nm light,
/// the definition of the candela. A real white source has less efficacy
/// (it emits more watts for the same candela): the lab's light is then a
/// lower bound of its radiant power.
pub const LUMINOUS_EFFICACY_LM_PER_W: f32 = 683.0;

impl Loader<'_, '_, '_> {
    /// The placed lights in node order.
    pub(super) fn lights(&mut self, placed: &[LightInstance]) -> Vec<SceneLight> {
        let root = self.root;
        let defined: &[gltf::json::extensions::scene::khr_lights_punctual::Light] = root.as_ref();
        let mut lights = Vec::new();
        for instance in placed {
            let Some(light) = defined.get(instance.light) else {
                self.warn(format!(
                    "a node places light {} but the file defines {}; skipped",
                    instance.light,
                    defined.len()
                ));
                continue;
            };
            let name = light
                .name
                .clone()
                .unwrap_or_else(|| format!("light {}", instance.light));
            match light.type_ {
                Checked::Valid(Type::Point) => {}
                Checked::Valid(Type::Spot) => self.warn(format!(
                    "light '{name}' is a spot light: used as a point light (its cone is not modelled)"
                )),
                _ => {
                    self.warn(format!(
                        "light '{name}' is directional: not modelled (the lab has a point or sphere light)"
                    ));
                    continue;
                }
            }
            let position = instance.world.transform_point3(DVec3::ZERO);
            let intensity = light.intensity / LUMINOUS_EFFICACY_LM_PER_W;
            if !position.is_finite() || !intensity.is_finite() || intensity < 0.0 {
                self.warn(format!(
                    "light '{name}' has no usable position or intensity; skipped"
                ));
                continue;
            }
            lights.push(SceneLight {
                name,
                position: position.as_vec3(),
                intensity_w_sr: intensity,
                color: Vec3::from(light.color).max(Vec3::ZERO),
            });
        }
        lights
    }
}
