//! The names and descriptions of the library's experiments in the
//! current language. The library keeps its English text (the command line
//! prints it); the app shows these instead.

use crate::presets::Preset;
use crate::tr;

/// A preset's title, for its button.
pub fn preset_title(preset: Preset) -> String {
    match preset {
        Preset::ShadowAcne => tr!("preset-shadow-acne"),
        Preset::PeterPanning => tr!("preset-peter-panning"),
        Preset::Aliasing => tr!("preset-aliasing"),
        Preset::PcfSmoothing => tr!("preset-pcf-smoothing"),
        Preset::Penumbra => tr!("preset-penumbra"),
        Preset::EnergyGain => tr!("preset-energy-gain"),
        Preset::Grazing => tr!("preset-grazing"),
    }
}

/// What a preset shows and which values it sets, for its tooltip.
pub fn preset_description(preset: Preset) -> String {
    match preset {
        Preset::ShadowAcne => tr!("preset-shadow-acne-tip"),
        Preset::PeterPanning => tr!("preset-peter-panning-tip"),
        Preset::Aliasing => tr!("preset-aliasing-tip"),
        Preset::PcfSmoothing => tr!("preset-pcf-smoothing-tip"),
        Preset::Penumbra => tr!("preset-penumbra-tip"),
        Preset::EnergyGain => tr!("preset-energy-gain-tip"),
        Preset::Grazing => tr!("preset-grazing-tip"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn english_titles_and_descriptions_are_the_library_s() {
        // The tests run in English unless one switches (the default).
        for &preset in Preset::ALL {
            assert_eq!(preset_title(preset), preset.title());
            assert_eq!(
                preset_description(preset).replace('\n', " "),
                preset.description()
            );
        }
    }
}
