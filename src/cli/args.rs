//! Value parsers and the shared options of the commands that render.

use crate::colour::Illuminant;
use crate::input::compact_range;
use crate::physics::Normalization;
use crate::settings::{
    BiasSettings, ColourSettings, DebugView, Filter, GroundMode, Settings, ShadowSettings, Visibility,
};
use glam::Vec3;
use std::path::PathBuf;

/// A comma-separated list given as one argument (a `Vec` field would make
/// clap expect the flag repeated).
#[derive(Clone, Debug, PartialEq)]
pub struct List<T>(pub Vec<T>);

/// Parses a comma-separated list of numbers, each checked by `check`.
pub fn number_list(
    text: &str,
    what: &str,
    check: impl Fn(f64) -> bool,
    allowed: &str,
) -> Result<Vec<f64>, String> {
    let values: Vec<f64> = text
        .split(',')
        .map(|item| {
            let item = item.trim();
            match item.parse::<f64>() {
                Ok(v) if v.is_finite() && check(v) => Ok(v),
                _ => Err(format!("{what} '{item}' is not allowed ({allowed})")),
            }
        })
        .collect::<Result<_, _>>()?;
    if values.is_empty() {
        return Err(format!("empty list ({allowed})"));
    }
    Ok(values)
}

/// A number in [min, max].
pub fn number_in(text: &str, min: f64, max: f64) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && (min..=max).contains(&v) => Ok(v),
        _ => Err(format!(
            "'{text}' is not a number in {}",
            compact_range(min as f32, max as f32)
        )),
    }
}

/// Three comma-separated numbers.
pub fn vec3(text: &str) -> Result<Vec3, String> {
    let v = number_list(text, "coordinate", |_| true, "three numbers x,y,z")?;
    match v.as_slice() {
        [x, y, z] => Ok(Vec3::new(*x as f32, *y as f32, *z as f32)),
        _ => Err(format!("'{text}' needs exactly three numbers x,y,z")),
    }
}

/// `WxH`, each side in 1 … 16384 pixels.
pub fn size(text: &str) -> Result<(u32, u32), String> {
    let parse = |s: &str| s.trim().parse::<u32>().ok().filter(|v| (1..=16384).contains(v));
    match text.split_once(['x', 'X']) {
        Some((w, h)) => match (parse(w), parse(h)) {
            (Some(w), Some(h)) => Ok((w, h)),
            _ => Err(format!(
                "'{text}': width and height must be whole numbers in 1 … 16384"
            )),
        },
        None => Err(format!("'{text}' is not a size WxH (e.g. 1280x720)")),
    }
}

/// Where the camera comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CameraChoice {
    /// `EYE:TARGET:FOVY_DEG`.
    Explicit { eye: Vec3, target: Vec3, fovy_deg: f32 },
    /// `gltf:N`: camera N of the scene file.
    Gltf(usize),
}

/// `EYE:TARGET:FOVY_DEG` (e.g. `0,2,5:0,0,0:45`) or `gltf:N`.
pub fn camera(text: &str) -> Result<CameraChoice, String> {
    if let Some(n) = text.strip_prefix("gltf:") {
        return n
            .trim()
            .parse::<usize>()
            .map(CameraChoice::Gltf)
            .map_err(|_| format!("'{text}': gltf:N needs a camera index N ≥ 0"));
    }
    let parts: Vec<&str> = text.split(':').collect();
    let [eye, target, fovy] = parts.as_slice() else {
        return Err(format!(
            "'{text}' is not EYE:TARGET:FOVY_DEG (e.g. 0,2,5:0,0,0:45) or gltf:N"
        ));
    };
    let (eye, target) = (vec3(eye)?, vec3(target)?);
    if eye.distance(target) < 1e-6 {
        return Err(format!("'{text}': the target must differ from the eye"));
    }
    Ok(CameraChoice::Explicit {
        eye,
        target,
        fovy_deg: number_in(fovy, 1.0, 179.0).map_err(|e| format!("field of view {e}"))? as f32,
    })
}

/// A shadow-map side the settings allow (the device may clamp it further).
fn shadow_res(text: &str) -> Result<u32, String> {
    let (min, max) = (ShadowSettings::MIN_RESOLUTION, ShadowSettings::MAX_RESOLUTION);
    match text.trim().parse::<u32>() {
        Ok(v) if (min..=max).contains(&v) => Ok(v),
        _ => Err(format!("'{text}' is not a whole number in {min} … {max}")),
    }
}

fn pcf_size(text: &str) -> Result<u32, String> {
    match text.trim().parse::<u32>() {
        Ok(v) if ShadowSettings::PCF_SIZES.contains(&v) => Ok(v),
        _ => Err(format!("'{text}' is not one of 3, 5, 7, 9")),
    }
}

/// The bias text, checked now and applied onto the settings' bias later.
fn bias(text: &str) -> Result<String, String> {
    BiasSettings::default().parse_onto(text)?;
    Ok(text.to_owned())
}

fn normalization(text: &str) -> Result<Normalization, String> {
    text.parse()
}

fn filter(text: &str) -> Result<Filter, String> {
    text.parse()
}

fn visibility(text: &str) -> Result<Visibility, String> {
    text.parse()
}

/// `--illuminant`: `rgb` (none) or a spectrum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IlluminantArg(pub Option<Illuminant>);

fn illuminant(text: &str) -> Result<IlluminantArg, String> {
    ColourSettings::parse_illuminant(text).map(IlluminantArg)
}

fn ground(text: &str) -> Result<GroundMode, String> {
    text.parse()
}

fn view(text: &str) -> Result<DebugView, String> {
    text.parse()
}

fn unit_interval(text: &str) -> Result<f32, String> {
    number_in(text, 0.0, 1.0).map(|v| v as f32)
}

fn exponent(text: &str) -> Result<f32, String> {
    number_in(text, 0.0, 1e6).map(|v| v as f32)
}

fn non_negative(text: &str) -> Result<f32, String> {
    number_in(text, 0.0, Settings::MAX_POWER_W as f64).map(|v| v as f32)
}

fn exposure(text: &str) -> Result<f32, String> {
    number_in(text, -30.0, 30.0).map(|v| v as f32)
}

/// The options every rendering command shares (DESIGN.md's contract).
#[derive(Clone, Debug, Default, clap::Args)]
pub struct SceneOptions {
    /// Settings file (TOML, as the app saves it); the flags below override it.
    #[arg(long, value_name = "FILE")]
    pub settings: Option<PathBuf>,
    /// glTF or GLB scene (default: the built-in scene).
    #[arg(long, value_name = "FILE.gltf|FILE.glb")]
    pub scene: Option<PathBuf>,
    /// Camera as EYE:TARGET:FOVY_DEG (e.g. 0,2,5:0,0,0:45) or gltf:N.
    #[arg(long, value_name = "EYE:TARGET:FOVY|gltf:N", value_parser = camera, allow_hyphen_values = true)]
    pub camera: Option<CameraChoice>,
    /// Image size in pixels.
    #[arg(long, value_name = "WxH", value_parser = size, allow_hyphen_values = true)]
    pub size: Option<(u32, u32)>,
    /// Light position (m).
    #[arg(long, value_name = "X,Y,Z", value_parser = vec3, allow_hyphen_values = true)]
    pub light: Option<Vec3>,
    /// Light power Φ (W).
    #[arg(long, value_name = "W", value_parser = non_negative, allow_negative_numbers = true)]
    pub power: Option<f32>,
    /// Sphere light radius R (m); 0 = point light.
    #[arg(long, value_name = "R", value_parser = non_negative, allow_negative_numbers = true)]
    pub light_radius: Option<f32>,
    /// Light colour (linear RGB).
    #[arg(long, value_name = "R,G,B", value_parser = vec3, allow_hyphen_values = true)]
    pub color: Option<Vec3>,
    /// Diffuse/specular mix k ∈ [0, 1] (applies to every object).
    #[arg(long, value_name = "K", value_parser = unit_interval, allow_negative_numbers = true)]
    pub k: Option<f32>,
    /// Blinn-Phong exponent m ∈ [0, 1e6] (applies to every object).
    #[arg(long, value_name = "M", value_parser = exponent, allow_negative_numbers = true)]
    pub m: Option<f32>,
    /// Lobe normalization: none|ndf|approx|exact.
    #[arg(long, value_name = "NAME", value_parser = normalization)]
    pub norm: Option<Normalization>,
    /// Shadow-map resolution (texels, 256 … 65536), clamped to the device limit and memory budget.
    #[arg(long, value_name = "N", value_parser = shadow_res, allow_negative_numbers = true)]
    pub shadow_res: Option<u32>,
    /// Shadow filter: none|hw2x2|pcf|poisson|pcss|vsm|evsm|msm.
    #[arg(long, value_name = "NAME", value_parser = filter)]
    pub filter: Option<Filter>,
    /// Where V comes from: shadow-map (default) | ray-traced (GPU shadow rays through a BVH).
    #[arg(long, value_name = "NAME", value_parser = visibility)]
    pub visibility: Option<Visibility>,
    /// Ray-traced shadow rays per pixel and frame towards a sphere light (1 … 256).
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    pub rt_samples: Option<u32>,
    /// PCF kernel size: 3|5|7|9.
    #[arg(long, value_name = "N", value_parser = pcf_size, allow_negative_numbers = true)]
    pub pcf_size: Option<u32>,
    /// Depth bias: auto | constant:D | slope:D,S | normal:N (D in m, N in texels).
    #[arg(long, value_name = "MODE", value_parser = bias)]
    pub bias: Option<String>,
    /// What to show: shaded|depth|visibility|ndotl|irradiance|brdf|diffuse|specular|texel-density|frustum|ref-visibility|error.
    #[arg(long, value_name = "NAME", value_parser = view)]
    pub view: Option<DebugView>,
    /// Exposure (EV): displayed = L · 2^EV.
    #[arg(long, value_name = "EV", value_parser = exposure, allow_hyphen_values = true)]
    pub exposure: Option<f32>,
    /// Turn shadows off (V = 1).
    #[arg(long)]
    pub no_shadows: bool,
    /// A shadow-receiving ground under a loaded model: auto (when it has
    /// none) | on | off.
    #[arg(long, value_name = "auto|on|off", value_parser = ground)]
    pub ground: Option<GroundMode>,
    /// The light's spectrum: rgb (the light's RGB colour × base colour, the
    /// lecture's product) | D65 | A | FL2 | FL11 | LED-B3 | blackbody:K
    /// (K in 1000 … 25000). A spectrum keeps the luminance of --color.
    #[arg(long, value_name = "NAME", value_parser = illuminant)]
    pub illuminant: Option<IlluminantArg>,
    /// Go ahead with CPU work estimated above the confirmation threshold (minutes or gigabytes).
    #[arg(long)]
    pub yes: bool,
    /// Draw a physically impossible set-up anyway (a light inside an object, a sphere light cutting a
    /// surface or holding the camera), where the GPU and the reference disagree.
    #[arg(long)]
    pub allow_impossible: bool,
}

impl SceneOptions {
    /// The settings file (or the defaults) naming the scene to draw, and
    /// whether they were saved for that very scene (they then carry its
    /// view and light; otherwise the scene's own are used). A bad file is
    /// a run-time error.
    pub fn base(&self) -> anyhow::Result<(Settings, bool)> {
        let mut s = match &self.settings {
            Some(path) => Settings::load(path)?,
            None => Settings::default(),
        };
        let saved =
            self.settings.is_some() && self.scene.as_ref().is_none_or(|p| s.scene.as_ref() == Some(p));
        if let Some(scene) = &self.scene {
            s.scene = Some(scene.clone());
        }
        Ok((s, saved))
    }

    /// Applies every given flag to `s` and validates it (a flag that makes
    /// the whole invalid is a usage error); returns the `gltf:N` camera
    /// asked for, which needs the loaded scene.
    pub fn apply_flags(&self, s: &mut Settings) -> anyhow::Result<Option<usize>> {
        let mut gltf_camera = None;
        match self.camera {
            Some(CameraChoice::Explicit {
                eye,
                target,
                fovy_deg,
            }) => {
                s.camera.eye = eye;
                s.camera.target = target;
                s.camera.fovy_deg = fovy_deg;
            }
            Some(CameraChoice::Gltf(n)) => gltf_camera = Some(n),
            None => {}
        }
        if let Some((w, h)) = self.size {
            s.image.width = w;
            s.image.height = h;
        }
        let light = &mut s.light;
        light.position = self.light.unwrap_or(light.position);
        light.power_w = self.power.unwrap_or(light.power_w);
        light.radius_m = self.light_radius.unwrap_or(light.radius_m);
        light.color = self.color.unwrap_or(light.color);
        let material = &mut s.material;
        if self.k.is_some() || self.m.is_some() {
            // k and m from the command line apply to every object.
            material.use_scene_materials = false;
        }
        material.k = self.k.unwrap_or(material.k);
        material.m = self.m.unwrap_or(material.m);
        material.norm = self.norm.unwrap_or(material.norm);
        let shadow = &mut s.shadow;
        shadow.resolution = self.shadow_res.unwrap_or(shadow.resolution);
        shadow.filter = self.filter.unwrap_or(shadow.filter);
        shadow.pcf_size = self.pcf_size.unwrap_or(shadow.pcf_size);
        shadow.visibility = self.visibility.unwrap_or(shadow.visibility);
        shadow.rt_light_samples = self.rt_samples.unwrap_or(shadow.rt_light_samples);
        if let Some(bias) = &self.bias {
            shadow.bias = shadow
                .bias
                .parse_onto(bias)
                .map_err(|e| super::usage(format!("--bias {e}")))?;
        }
        if self.no_shadows {
            shadow.enabled = false;
        }
        s.view.mode = self.view.unwrap_or(s.view.mode);
        s.view.exposure_ev = self.exposure.unwrap_or(s.view.exposure_ev);
        s.ground.mode = self.ground.unwrap_or(s.ground.mode);
        if let Some(IlluminantArg(illuminant)) = self.illuminant {
            s.colour.illuminant = illuminant;
        }
        s.validate()
            .map_err(|e| super::usage(format!("invalid settings: {e}")))?;
        Ok(gltf_camera)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn camera_parses_both_forms() {
        assert_eq!(
            camera("0,2,5:0,0,0:45").unwrap(),
            CameraChoice::Explicit {
                eye: Vec3::new(0.0, 2.0, 5.0),
                target: Vec3::ZERO,
                fovy_deg: 45.0
            }
        );
        assert_eq!(camera("gltf:1").unwrap(), CameraChoice::Gltf(1));
        for bad in [
            "0,2,5:0,0,0",
            "0,2:0,0,0:45",
            "0,2,5:0,0,0:200",
            "gltf:x",
            "1,1,1:1,1,1:45",
        ] {
            assert!(camera(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn size_parses() {
        assert_eq!(size("1280x720").unwrap(), (1280, 720));
        assert!(size("0x10").is_err() && size("12").is_err() && size("20000x10").is_err());
    }

    #[test]
    fn lists_reject_bad_items() {
        assert!(number_list("1,abc", "m", |_| true, "").is_err());
        assert!(number_list("1,-3", "m", |v| v >= 0.0, "").is_err());
        assert_eq!(
            number_list("1, 2,4", "m", |_| true, "").unwrap(),
            vec![1.0, 2.0, 4.0]
        );
    }
}
