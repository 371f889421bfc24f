//! The light and material colours a view shades with under its colour
//! settings (see `colour::shading`): computed once per change on the CPU,
//! then uploaded as ordinary colours, so the shaders are the RGB ones. The
//! other colour model's colours go up beside them for the `delta-e` view.

use super::scene_buffers::{ColourKey, GpuScene};
use crate::colour::{ColourModel, ShadingColours, shading_colours};
use crate::settings::Settings;
use glam::Vec3;

/// Everything the colours depend on.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Inputs {
    key: ColourKey,
    light: Vec3,
    color_override: Option<Vec3>,
    scene_generation: u64,
}

/// The colours of the model shown and of the other one (spectral ↔ RGB
/// approximation), which the `delta-e` view compares with; in RGB mode
/// both are the RGB colours.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelColours {
    pub shown: ShadingColours,
    pub other: ShadingColours,
}

/// One view's colours, recomputed only when their inputs change (an uplift
/// per material is a few hundred spectrum integrations).
#[derive(Default)]
pub struct ColourCache {
    last: Option<(Inputs, ModelColours)>,
}

impl ColourCache {
    /// The colours for `settings`, written into the scene's materials buffer
    /// when it holds another view's; returns them for the uniforms.
    pub fn apply(
        &mut self,
        settings: &Settings,
        scene: &mut GpuScene,
        scene_generation: u64,
        queue: &wgpu::Queue,
    ) -> &ModelColours {
        let c = settings.colour;
        let inputs = Inputs {
            // Without an illuminant the model changes nothing.
            key: (
                c.illuminant,
                c.illuminant.map_or(ColourModel::default(), |_| c.model),
            ),
            light: settings.light.color,
            color_override: settings.material.color_override,
            scene_generation,
        };
        if self.last.as_ref().is_some_and(|(i, _)| *i != inputs) {
            self.last = None;
        }
        let (inputs, colours) = self.last.get_or_insert_with(|| {
            let run = |model| {
                shading_colours(
                    c.illuminant,
                    model,
                    inputs.light.as_dvec3(),
                    scene.material_colours.iter().map(|(n, c)| (n.as_str(), *c)),
                    inputs.color_override.map(|c| c.as_dvec3()),
                )
            };
            let colours = ModelColours {
                shown: run(c.model),
                other: run(c.model.other()),
            };
            (inputs, colours)
        });
        scene.write_colours(
            queue,
            inputs.key,
            &colours.shown.materials,
            &colours.other.materials,
        );
        colours
    }
}
