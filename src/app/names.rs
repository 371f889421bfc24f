//! The names and descriptions of the library's experiments in the
//! current language. The library keeps its English text (the command line
//! prints it); the app shows these instead.

use crate::colour::ColourModel;
use crate::presets::{Comparison, ComparisonAxis, Half, Preset, SplitPreset};
use crate::settings::Visibility;
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

/// A half's label in the split view ("norm none", "ray traced"): the
/// library's `Comparison::label` in the app's language; setting names shared
/// with the command line (none, pcss, auto) stay as they are.
pub fn comparison_label(comparison: &Comparison, half: Half) -> String {
    let i = half as usize;
    match comparison.axis {
        ComparisonAxis::Normalization => {
            tr!("compare-norm", value = comparison.norm[i].to_string())
        }
        ComparisonAxis::Filter => tr!("compare-filter", value = comparison.filter[i].to_string()),
        ComparisonAxis::Resolution => tr!(
            "compare-resolution",
            texels = comparison.resolution[i].to_string()
        ),
        ComparisonAxis::Bias => tr!("compare-bias", value = comparison.bias[i].to_string()),
        ComparisonAxis::Visibility => match comparison.visibility[i] {
            Visibility::ShadowMap => tr!("compare-shadow-map"),
            Visibility::RayTraced => tr!("compare-ray-traced"),
        },
        ComparisonAxis::Colour => match comparison.colour[i] {
            ColourModel::RgbApprox => tr!("compare-rgb-approx"),
            ColourModel::Spectral => tr!("compare-spectral"),
        },
    }
}

/// A split choice's name, for the View panel's buttons: the library's
/// `SplitPreset::title` in the app's language.
pub fn split_choice_name(choice: SplitPreset) -> String {
    match choice {
        SplitPreset::Normalization => tr!("split-choice-norm"),
        SplitPreset::Filter => tr!("split-choice-filter"),
        SplitPreset::Pcss => tr!("split-choice-pcss"),
        SplitPreset::Resolution => tr!("split-choice-resolution"),
        SplitPreset::Visibility => tr!("split-choice-visibility"),
        SplitPreset::Colour => tr!("split-choice-colour"),
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
        for choice in SplitPreset::ALL {
            assert_eq!(split_choice_name(choice), choice.title());
            let comparison = choice.comparison();
            for half in [Half::A, Half::B] {
                assert_eq!(comparison_label(&comparison, half), comparison.label(half));
            }
        }
    }
}
