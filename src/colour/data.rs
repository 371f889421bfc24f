//! The published spectral tables, compiled into the binary.
//!
//! The CSV files under `assets/colour/` name their sources in their headers;
//! `scripts/export_colour_tables.py` regenerates them. All share the grid of
//! [`Spectrum`] (380–780 nm every 5 nm), which parsing checks row by row.

use super::spectrum::{BLACKBODY_MAX_K, BLACKBODY_MIN_K, SAMPLES, Spectrum, blackbody};
use std::sync::LazyLock;

/// Patches on the ColorChecker Classic.
pub const PATCH_COUNT: usize = 24;

/// A table: its column names (after `nm`) and one spectrum per column.
struct Table {
    names: Vec<&'static str>,
    columns: Vec<Spectrum>,
}

impl Table {
    fn column(&self, name: &str) -> Spectrum {
        let i = self.names.iter().position(|n| *n == name);
        self.columns[i.unwrap_or_else(|| panic!("embedded colour table has no column '{name}'"))]
    }
}

/// Parses a table compiled into the binary. Its text is fixed at build time
/// and every table is loaded by the tests, so a malformed one cannot ship:
/// a panic here is a build defect, never a user's input.
fn parse(text: &'static str) -> Table {
    let mut lines = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty());
    let header = lines.next().expect("embedded colour table has a header");
    let names: Vec<&'static str> = header.split(',').skip(1).collect();
    let mut columns = vec![Spectrum::constant(0.0); names.len()];
    let mut rows = 0;
    for (i, line) in lines.enumerate() {
        let mut fields = line.split(',').map(|f| {
            f.trim()
                .parse::<f64>()
                .unwrap_or_else(|_| panic!("embedded colour table: bad number '{f}'"))
        });
        assert!(
            i < SAMPLES && fields.next() == Some(Spectrum::wavelength_nm(i)),
            "embedded colour table: row {i} is off the 380–780 nm, 5 nm grid"
        );
        for column in &mut columns {
            column.0[i] = fields.next().expect("embedded colour table: short row");
        }
        rows += 1;
    }
    assert_eq!(rows, SAMPLES, "embedded colour table: wrong number of rows");
    Table { names, columns }
}

static CMFS: LazyLock<[Spectrum; 3]> = LazyLock::new(|| {
    let t = parse(include_str!("../../assets/colour/cie1931_2deg.csv"));
    [t.column("x_bar"), t.column("y_bar"), t.column("z_bar")]
});

static ILLUMINANTS: LazyLock<Table> =
    LazyLock::new(|| parse(include_str!("../../assets/colour/illuminants.csv")));

static COLORCHECKER: LazyLock<Table> = LazyLock::new(|| {
    let t = parse(include_str!("../../assets/colour/colorchecker_ohta.csv"));
    assert_eq!(
        t.names.len(),
        PATCH_COUNT,
        "embedded ColorChecker table: 24 patches"
    );
    t
});

/// The CIE 1931 2° colour-matching functions x̄, ȳ, z̄ (CIE 015:2018).
pub fn cmfs() -> &'static [Spectrum; 3] {
    &CMFS
}

/// The 24 patch names of the ColorChecker Classic, in chart order (row by
/// row from "dark skin" to "black 2").
pub fn patch_names() -> &'static [&'static str] {
    &COLORCHECKER.names
}

/// The measured reflectance (0..1) of patch `index` (0..24), N. Ohta (1997).
pub fn patch_reflectance(index: usize) -> Spectrum {
    COLORCHECKER.columns[index]
}

/// A light source whose spectral power the lab knows. Settings files hold
/// it by name (`"A"`, `"blackbody:3000"`).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "String", into = "String")]
pub enum Illuminant {
    /// CIE D65: average daylight, about 6504 K.
    D65,
    /// CIE A: a tungsten filament lamp, a 2856 K blackbody.
    A,
    /// CIE FL2: a cool-white fluorescent tube (broad-band halophosphate).
    Fl2,
    /// CIE FL11: a three-band fluorescent tube (narrow peaks).
    Fl11,
    /// CIE LED-B3: a phosphor-converted white LED (blue die + phosphor).
    LedB3,
    /// A Planckian radiator at `kelvin` (1000–25000 K).
    Blackbody { kelvin: f64 },
}

impl Illuminant {
    /// The five tabulated illuminants, in the order the lab lists them.
    pub const NAMED: [Illuminant; 5] = [Self::D65, Self::A, Self::Fl2, Self::Fl11, Self::LedB3];

    /// The name on the command line and in files: `D65`, `A`, `FL2`, `FL11`,
    /// `LED-B3` or `blackbody:K`.
    pub fn name(self) -> String {
        match self {
            Self::D65 => "D65".into(),
            Self::A => "A".into(),
            Self::Fl2 => "FL2".into(),
            Self::Fl11 => "FL11".into(),
            Self::LedB3 => "LED-B3".into(),
            Self::Blackbody { kelvin } => format!("blackbody:{kelvin}"),
        }
    }

    /// What the source is, in a few words (figure titles).
    pub fn description(self) -> String {
        match self {
            Self::D65 => "CIE D65, average daylight".into(),
            Self::A => "CIE A, tungsten lamp (2856 K)".into(),
            Self::Fl2 => "CIE FL2, cool-white fluorescent".into(),
            Self::Fl11 => "CIE FL11, three-band fluorescent".into(),
            Self::LedB3 => "CIE LED-B3, phosphor white LED".into(),
            Self::Blackbody { kelvin } => format!("Planckian radiator at {kelvin} K"),
        }
    }

    /// The relative spectral power (CIE tables, or Planck's law normalized
    /// to 100 at 560 nm).
    pub fn spectrum(self) -> Spectrum {
        match self {
            Self::Blackbody { kelvin } => blackbody(kelvin),
            named => ILLUMINANTS.column(&named.name()),
        }
    }

    /// The accepted forms, for error messages and help.
    pub fn choices() -> String {
        format!("D65|A|FL2|FL11|LED-B3|blackbody:K with K in {BLACKBODY_MIN_K} … {BLACKBODY_MAX_K}")
    }
}

impl std::fmt::Display for Illuminant {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.name())
    }
}

impl From<Illuminant> for String {
    fn from(i: Illuminant) -> String {
        i.name()
    }
}

impl TryFrom<String> for Illuminant {
    type Error = String;
    fn try_from(text: String) -> Result<Self, String> {
        text.parse()
    }
}

/// Parses a name as [`Illuminant::name`] writes it (letter case ignored).
impl std::str::FromStr for Illuminant {
    type Err = String;
    fn from_str(text: &str) -> Result<Self, String> {
        let text = text.trim();
        if let Some(value) = text
            .get(..10)
            .filter(|p| p.eq_ignore_ascii_case("blackbody:"))
            .map(|_| &text[10..])
        {
            return match value.trim().parse::<f64>() {
                Ok(k) if (BLACKBODY_MIN_K..=BLACKBODY_MAX_K).contains(&k) => {
                    Ok(Self::Blackbody { kelvin: k })
                }
                _ => Err(format!(
                    "blackbody temperature '{value}' must be a number of kelvins in \
                     {BLACKBODY_MIN_K} … {BLACKBODY_MAX_K}"
                )),
            };
        }
        Self::NAMED
            .into_iter()
            .find(|i| i.name().eq_ignore_ascii_case(text))
            .ok_or_else(|| {
                format!(
                    "unknown illuminant '{}' (allowed: {})",
                    crate::input::escape_controls(text),
                    Self::choices()
                )
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_table_loads_on_the_grid() {
        assert!(cmfs().iter().all(|s| s.0.iter().all(|v| *v >= 0.0)));
        for i in Illuminant::NAMED {
            let s = i.spectrum();
            assert!(s.max() > 0.0 && s.0.iter().all(|v| *v >= 0.0), "{i}");
        }
        assert_eq!(patch_names().len(), PATCH_COUNT);
        for p in 0..PATCH_COUNT {
            let r = patch_reflectance(p);
            assert!(
                r.0.iter().all(|v| (0.0..=1.0).contains(v)),
                "{}",
                patch_names()[p]
            );
        }
    }

    #[test]
    fn published_sample_values() {
        // CIE 015:2018: ȳ(555 nm) = 1.0 (exactly at 555 in the 1931 table),
        // D65 and A are 100 at 560 nm.
        assert_eq!(cmfs()[1].0[35], 1.0);
        assert_eq!(Illuminant::D65.spectrum().0[36], 100.0);
        assert_eq!(Illuminant::A.spectrum().0[36], 100.0);
        assert_eq!(patch_names()[0], "dark skin");
        assert_eq!(patch_names()[23], "black 2");
    }

    #[test]
    fn names_parse_back() {
        for i in Illuminant::NAMED {
            assert_eq!(i.name().parse::<Illuminant>(), Ok(i));
        }
        assert_eq!("led-b3".parse::<Illuminant>(), Ok(Illuminant::LedB3));
        assert_eq!(
            "blackbody:6504".parse::<Illuminant>(),
            Ok(Illuminant::Blackbody { kelvin: 6504.0 })
        );
        for bad in [
            "D50",
            "",
            "blackbody:",
            "blackbody:999",
            "blackbody:30000",
            "blackbody:NaN",
        ] {
            assert!(bad.parse::<Illuminant>().is_err(), "{bad}");
        }
    }
}
