//! The file's KHR_lights_punctual lights, reduced to the lab's point light:
//! a point light as it is, a spot light as a point light (its cone is not
//! modelled, said in a warning), a directional light skipped with a warning.

use super::Loader;
use super::nodes::LightInstance;
use crate::scene::SceneLight;
use crate::settings::{LightSettings, Settings};
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
            let placed = SceneLight {
                name,
                position: instance.world.transform_point3(DVec3::ZERO).as_vec3(),
                intensity_w_sr: light.intensity / LUMINOUS_EFFICACY_LM_PER_W,
                color: Vec3::from(light.color).max(Vec3::ZERO),
            };
            // The point light the settings would make of it.
            let as_set = LightSettings {
                position: placed.position,
                power_w: placed.power_w(),
                radius_m: 0.0,
                color: placed.color,
            };
            match Settings::validate_light(&as_set) {
                Ok(()) => lights.push(placed),
                Err(e) => self.warn(format!("light '{}' is not usable ({e}); skipped", placed.name)),
            }
        }
        lights
    }
}
