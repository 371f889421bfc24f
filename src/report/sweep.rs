//! Which shadow settings the report measures: the default sweep, or a TOML
//! file that lists configurations and/or asks for a cross-product of values
//! (like Filament's automation specs). Every key is a field of the settings
//! file's `[shadow]` table; `bias` also takes the command-line form.
//!
//! ```toml
//! # one configuration per table
//! [[config]]
//! filter = "pcf"
//! pcf_size = 5
//! resolution = 1024
//!
//! # every combination of these values (in addition to the list)
//! [cross]
//! resolution = [512, 2048]
//! filter = ["hw2x2", "evsm"]
//! bias = ["auto", "slope:0.002,1.5"]
//! ```

use crate::settings::{BiasMode, Filter, Settings, ShadowSettings, Visibility};
use std::path::Path;

/// One configuration of the sweep: the base settings' shadow section with
/// some keys replaced.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepPoint {
    /// A short name made of the values that matter (e.g. `pcf5 1024² auto`).
    pub label: String,
    pub shadow: ShadowSettings,
}

/// The default sweep: 2 resolutions × 7 filters × 2 biases = 28 shadow
/// maps, and 6 ray-traced points (shadow rays per frame × frames
/// accumulated) from 1 ray to 256 rays per pixel: 34 points under a sphere
/// light. Under a point light one ray is exact and the six are one point:
/// 29.
pub const DEFAULT_SWEEP: &str = r#"
[cross]
resolution = [512, 2048]
filter = ["none", "hw2x2", "pcf", "poisson", "vsm", "evsm", "msm"]
bias = ["auto", "constant:0.02"]

[[config]]
visibility = "ray-traced"
rt_light_samples = 1
rt_max_frames = 1

[[config]]
visibility = "ray-traced"
rt_light_samples = 4
rt_max_frames = 1

[[config]]
visibility = "ray-traced"
rt_light_samples = 16
rt_max_frames = 1

[[config]]
visibility = "ray-traced"
rt_light_samples = 4
rt_max_frames = 4

[[config]]
visibility = "ray-traced"
rt_light_samples = 4
rt_max_frames = 16

[[config]]
visibility = "ray-traced"
rt_light_samples = 16
rt_max_frames = 16
"#;

#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    #[error("cannot read the sweep file {path}: {source}")]
    Read {
        path: std::path::PathBuf,
        source: std::io::Error,
    },
    #[error("{0}")]
    Invalid(String),
}

/// Most configurations a sweep may ask for (each is rendered and timed):
/// a cross-product's size is computed and checked before it is expanded.
pub const MAX_POINTS: u64 = 1000;

/// The sweep in `text` applied to `base` (whose other sections stay).
pub fn parse(text: &str, base: &Settings) -> Result<Vec<SweepPoint>, SweepError> {
    let invalid = |message: String| SweepError::Invalid(message);
    let document: toml::Table = toml::from_str(text).map_err(|e| invalid(one_line_toml(&e)))?;
    let mut tables = Vec::new();
    for (key, value) in &document {
        match (key.as_str(), value) {
            ("config", toml::Value::Array(list)) => {
                if (tables.len() + list.len()) as u64 > MAX_POINTS {
                    return Err(too_many((tables.len() + list.len()) as u64));
                }
                for (i, item) in list.iter().enumerate() {
                    let table = item
                        .as_table()
                        .ok_or_else(|| invalid(format!("config[{i}] must be a table of shadow settings")))?;
                    tables.push(table.clone());
                }
            }
            ("cross", toml::Value::Table(axes)) => {
                let size = cross_size(axes)?;
                if tables.len() as u64 + size > MAX_POINTS {
                    return Err(too_many(tables.len() as u64 + size));
                }
                tables.extend(cross_product(axes)?);
            }
            ("config" | "cross", _) => {
                return Err(invalid(format!(
                    "'{key}' must be {}",
                    if key == "config" {
                        "an array of tables ([[config]])"
                    } else {
                        "a table of arrays ([cross])"
                    }
                )));
            }
            _ => {
                return Err(invalid(format!(
                    "unknown section '{}' (expected [[config]] or [cross])",
                    crate::input::escape_controls(key)
                )));
            }
        }
    }
    if tables.is_empty() {
        return Err(invalid("the sweep has no configuration".into()));
    }
    let mut points: Vec<SweepPoint> = Vec::with_capacity(tables.len());
    for table in &tables {
        // A cross-product can ask for values the filter never reads (a PCF
        // size with VSM): such points render alike, and are measured once.
        let point = point(table, base)?;
        if !points.iter().any(|p| p.shadow == point.shadow) {
            points.push(point);
        }
    }
    for point in &points {
        let mut settings = base.clone();
        settings.shadow = point.shadow;
        settings
            .validate()
            .map_err(|e| invalid(format!("configuration '{}': {e}", point.label)))?;
    }
    Ok(points)
}

/// Reads and parses a sweep file.
pub fn load(path: &Path, base: &Settings) -> Result<Vec<SweepPoint>, SweepError> {
    let limit = crate::input::SWEEP_LIMIT_BYTES;
    let text =
        crate::input::read_text_bounded(path, limit, "a sweep file").map_err(|source| SweepError::Read {
            path: path.to_owned(),
            source,
        })?;
    parse(&text, base).map_err(|e| match e {
        SweepError::Invalid(message) => SweepError::Invalid(format!("{}: {message}", path.display())),
        other => other,
    })
}

/// How many combinations the axes make (saturating: an absurd product is
/// still "too many", never an overflow).
fn cross_size(axes: &toml::Table) -> Result<u64, SweepError> {
    axes.iter().try_fold(1u64, |product, (key, values)| match values {
        toml::Value::Array(values) if values.is_empty() => {
            Err(SweepError::Invalid(format!("cross.{key} has no values")))
        }
        toml::Value::Array(values) => Ok(product.saturating_mul(values.len() as u64)),
        _ => Ok(product),
    })
}

fn too_many(count: u64) -> SweepError {
    SweepError::Invalid(format!(
        "the sweep asks for {count} configurations; at most {MAX_POINTS} are allowed"
    ))
}

/// Every combination of the axes' values: keys in alphabetical order, the
/// first varying slowest.
fn cross_product(axes: &toml::Table) -> Result<Vec<toml::Table>, SweepError> {
    let mut tables = vec![toml::Table::new()];
    for (key, values) in axes {
        let values = match values {
            toml::Value::Array(values) if !values.is_empty() => values.clone(),
            toml::Value::Array(_) => {
                return Err(SweepError::Invalid(format!("cross.{key} has no values")));
            }
            single => vec![single.clone()],
        };
        tables = tables
            .into_iter()
            .flat_map(|table| {
                values.iter().map(move |value| {
                    let mut table = table.clone();
                    table.insert(key.clone(), value.clone());
                    table
                })
            })
            .collect();
    }
    Ok(tables)
}

/// The base shadow settings with the table's keys replaced.
fn point(table: &toml::Table, base: &Settings) -> Result<SweepPoint, SweepError> {
    let mut merged = toml::Table::try_from(base.shadow).map_err(|e| SweepError::Invalid(e.to_string()))?;
    let mut bias_text = None;
    for (key, value) in table {
        match (key.as_str(), value) {
            ("bias", toml::Value::String(text)) => bias_text = Some(text.clone()),
            _ => {
                merged.insert(key.clone(), value.clone());
            }
        }
    }
    let mut shadow: ShadowSettings = merged.try_into().map_err(|e: toml::de::Error| {
        SweepError::Invalid(format!("shadow settings: {}", one_line_toml(&e)))
    })?;
    if let Some(text) = bias_text {
        shadow.bias = shadow
            .bias
            .parse_onto(&text)
            .map_err(|e| SweepError::Invalid(format!("bias: {e}")))?;
    }
    let shadow = effective(shadow, base);
    Ok(SweepPoint {
        label: label(&shadow),
        shadow,
    })
}

/// The settings with every value the filter and the bias mode do not read
/// set to its default, so that two points that render alike are equal;
/// `base` gives the light.
fn effective(mut s: ShadowSettings, base: &Settings) -> ShadowSettings {
    let d = ShadowSettings::default();
    if s.visibility == Visibility::RayTraced {
        // No shadow map: only the rays and frames the tracer uses matter
        // (under a point light one of each).
        let traced = Settings {
            shadow: s,
            ..base.clone()
        };
        return ShadowSettings {
            enabled: s.enabled,
            visibility: s.visibility,
            rt_light_samples: traced.ray_traced_rays_per_frame(),
            rt_max_frames: traced.ray_traced_frames(),
            ..d
        };
    }
    s.rt_light_samples = d.rt_light_samples;
    s.rt_max_frames = d.rt_max_frames;
    let uses = |filters: &[Filter]| filters.contains(&s.filter);
    if !uses(&[Filter::Pcf]) {
        s.pcf_size = d.pcf_size;
    }
    if !uses(&[Filter::Poisson, Filter::Pcss]) {
        s.poisson_samples = d.poisson_samples;
    }
    if !uses(&[Filter::Poisson]) {
        s.poisson_radius_texels = d.poisson_radius_texels;
    }
    if !uses(&[Filter::Pcss]) {
        s.pcss_blocker_samples = d.pcss_blocker_samples;
    }
    if !uses(&[Filter::Vsm, Filter::Evsm, Filter::Msm]) {
        s.vsm_blur_texels = d.vsm_blur_texels;
    }
    if !uses(&[Filter::Vsm, Filter::Evsm]) {
        s.vsm_bleed_reduction = d.vsm_bleed_reduction;
    }
    if !uses(&[Filter::Msm]) {
        s.msm_bias = d.msm_bias;
    }
    let (bias, db) = (&mut s.bias, d.bias);
    if !matches!(bias.mode, BiasMode::Constant | BiasMode::Slope) {
        bias.depth_m = db.depth_m;
    }
    if bias.mode != BiasMode::Slope {
        bias.slope = db.slope;
    }
    if bias.mode != BiasMode::Normal {
        bias.normal_texels = db.normal_texels;
    }
    s
}

/// `filter resolution² bias`: the filter with its size (pcf3, poisson16)
/// and any of its other parameters that differ from the defaults.
pub fn label(s: &ShadowSettings) -> String {
    let d = ShadowSettings::default();
    if s.visibility == Visibility::RayTraced {
        return format!("ray-traced {}×{}", s.rt_light_samples, s.rt_max_frames);
    }
    let mut filter = match s.filter {
        Filter::Pcf => format!("pcf{}", s.pcf_size),
        Filter::Poisson => format!("poisson{}", s.poisson_samples),
        other => other.name().to_string(),
    };
    // (parameter differs from the default, how the label names it)
    let extras = match s.filter {
        Filter::Poisson => vec![(
            s.poisson_radius_texels != d.poisson_radius_texels,
            format!("r{}", s.poisson_radius_texels),
        )],
        Filter::Pcss => vec![
            (
                s.pcss_blocker_samples != d.pcss_blocker_samples,
                format!("search{}", s.pcss_blocker_samples),
            ),
            (
                s.poisson_samples != d.poisson_samples,
                format!("filter{}", s.poisson_samples),
            ),
        ],
        Filter::Vsm | Filter::Evsm => vec![
            (
                s.vsm_blur_texels != d.vsm_blur_texels,
                format!("blur{}", s.vsm_blur_texels),
            ),
            (
                s.vsm_bleed_reduction != d.vsm_bleed_reduction,
                format!("bleed{}", s.vsm_bleed_reduction),
            ),
        ],
        Filter::Msm => vec![
            (
                s.vsm_blur_texels != d.vsm_blur_texels,
                format!("blur{}", s.vsm_blur_texels),
            ),
            (s.msm_bias != d.msm_bias, format!("alpha{}", s.msm_bias)),
        ],
        _ => Vec::new(),
    };
    for (_, text) in extras.iter().filter(|(differs, _)| *differs) {
        filter += &format!(" {text}");
    }
    format!("{filter} {}² {}", s.resolution, s.bias.describe())
}

/// A TOML error on one line.
fn one_line_toml(e: &toml::de::Error) -> String {
    e.message().replace('\n', " ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_sweep_has_34_distinct_points_of_both_methods() {
        let mut sphere = Settings::default();
        sphere.light.radius_m = 0.3;
        let points = parse(DEFAULT_SWEEP, &sphere).unwrap();
        assert_eq!(points.len(), 34);
        let mut labels: Vec<_> = points.iter().map(|p| p.label.clone()).collect();
        labels.sort();
        labels.dedup();
        assert_eq!(labels.len(), 34);
        let traced = points
            .iter()
            .filter(|p| p.shadow.visibility == Visibility::RayTraced)
            .count();
        assert_eq!(traced, 6);
        assert!(labels.contains(&"ray-traced 4×16".to_string()));
    }

    #[test]
    fn under_a_point_light_the_ray_traced_points_are_one() {
        let point_light = Settings::default();
        assert_eq!(point_light.light.radius_m, 0.0);
        let points = parse(DEFAULT_SWEEP, &point_light).unwrap();
        assert_eq!(points.len(), 29);
        let traced: Vec<_> = points
            .iter()
            .filter(|p| p.shadow.visibility == Visibility::RayTraced)
            .map(|p| p.label.as_str())
            .collect();
        assert_eq!(traced, ["ray-traced 1×1"]);
    }

    #[test]
    fn list_and_cross_product_add_up() {
        let text = r#"
            [[config]]
            filter = "pcf"
            pcf_size = 5
            [cross]
            resolution = [512, 1024, 2048]
            bias = ["auto", "slope:0.001,2"]
        "#;
        let points = parse(text, &Settings::default()).unwrap();
        assert_eq!(points.len(), 1 + 6);
        assert_eq!(points[0].shadow.pcf_size, 5);
        assert_eq!(points[0].label, "pcf5 2048² auto");
        assert!(points.iter().any(|p| p.label == "pcf3 512² slope:0.001,2"));
    }

    #[test]
    fn values_a_filter_does_not_read_make_no_new_point() {
        let text = r#"
            [cross]
            filter = ["hw2x2", "pcf", "vsm"]
            pcf_size = [3, 9]
            vsm_blur_texels = [2, 4]
        "#;
        let labels: Vec<String> = parse(text, &Settings::default())
            .unwrap()
            .into_iter()
            .map(|p| p.label)
            .collect();
        assert_eq!(
            labels,
            [
                "hw2x2 2048² auto",
                "pcf3 2048² auto",
                "pcf9 2048² auto",
                "vsm 2048² auto",
                "vsm blur4 2048² auto"
            ]
        );
    }

    #[test]
    fn bad_files_name_the_problem() {
        let base = Settings::default();
        let error = |text: &str| parse(text, &base).unwrap_err().to_string();
        assert!(error("[[config]]\nfilter = \"blur\"").contains("blur"));
        assert!(error("[[config]]\nsize = 3").contains("size"));
        assert!(error("[[config]]\nresolution = 3").contains("shadow.resolution"));
        assert!(error("[[config]]\nbias = \"tilt:3\"").contains("tilt"));
        assert!(error("[cross]\nresolution = []").contains("no values"));
        assert!(error("[extra]\na = 1").contains("extra"));
        assert!(error("").contains("no configuration"));
        assert!(!error("[[config").is_empty());
    }

    #[test]
    fn an_astronomical_cross_product_is_refused_before_it_is_expanded() {
        // 2^60 combinations in a few hundred bytes: expanding it would never end.
        let axis = "[512, 512]";
        let keys = [
            "resolution",
            "pcf_size",
            "poisson_samples",
            "vsm_blur_texels",
            "filter",
        ];
        let mut text = String::from("[cross]\n");
        for i in 0..60 {
            text += &format!("{}_{i} = {axis}\n", keys[i % keys.len()]);
        }
        let error = parse(&text, &Settings::default()).unwrap_err().to_string();
        assert!(error.contains("1152921504606846976 configurations"), "{error}");
        let list = "[[config]]\nfilter = \"pcf\"\n".repeat(MAX_POINTS as usize + 1);
        assert!(
            parse(&list, &Settings::default())
                .unwrap_err()
                .to_string()
                .contains("at most 1000")
        );
    }
}
