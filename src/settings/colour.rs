//! The light's spectrum and the colour model (DESIGN.md, `--illuminant`).

use crate::colour::{ColourModel, Illuminant};
use serde::{Deserialize, Serialize};

/// Whether light and materials are RGB triplets (the lecture's model) or
/// spectra; see `colour::shading` for how a spectrum is normalized.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ColourSettings {
    /// The light's spectrum; none (`rgb`, the default) = the light's RGB
    /// colour times the materials' base colours.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub illuminant: Option<Illuminant>,
    /// Under an illuminant: the spectral result, or the RGB product it approximates.
    pub model: ColourModel,
}

impl ColourSettings {
    /// `rgb`, or the illuminant's name: what `--illuminant` takes.
    pub fn illuminant_name(&self) -> String {
        self.illuminant.map_or_else(|| "rgb".into(), Illuminant::name)
    }

    /// Parses what `--illuminant` takes: `rgb` or an illuminant's name.
    pub fn parse_illuminant(text: &str) -> Result<Option<Illuminant>, String> {
        if text.trim().eq_ignore_ascii_case("rgb") {
            Ok(None)
        } else {
            text.parse()
                .map(Some)
                .map_err(|e: String| e.replace("(allowed: ", "(allowed: rgb|"))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::Settings;

    #[test]
    fn old_settings_files_load_in_rgb_mode() {
        let s = Settings::from_toml("[light]\npower_w = 10.0\n").unwrap();
        assert_eq!(s.colour, ColourSettings::default());
        assert_eq!(s.colour.illuminant, None);
    }

    #[test]
    fn illuminant_round_trips_through_toml() {
        let mut s = Settings::default();
        s.colour.illuminant = Some(Illuminant::Blackbody { kelvin: 3200.0 });
        s.colour.model = ColourModel::RgbApprox;
        let text = s.to_toml();
        assert!(text.contains("illuminant = \"blackbody:3200\""), "{text}");
        assert_eq!(Settings::from_toml(&text).unwrap(), s);
        assert!(Settings::from_toml("[colour]\nilluminant = \"D50\"\n").is_err());
    }

    #[test]
    fn rgb_names_no_illuminant() {
        assert_eq!(ColourSettings::parse_illuminant("RGB"), Ok(None));
        assert_eq!(ColourSettings::parse_illuminant("A"), Ok(Some(Illuminant::A)));
        let e = ColourSettings::parse_illuminant("D50").unwrap_err();
        assert!(e.contains("rgb|D65"), "{e}");
    }
}
