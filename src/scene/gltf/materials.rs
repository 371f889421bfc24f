//! The file's materials and the base-colour images they use, with the
//! lab's own k and m from their extras.

use super::{Loader, lab_extras, resources};
use crate::scene::{Material, Texture};
use glam::Vec4;
use gltf::json::material::AlphaMode;
use gltf::json::validation::Checked;
use std::collections::HashMap;

impl Loader<'_, '_, '_> {
    /// Every material of the file, with the base-colour images they use.
    pub(super) fn materials(&mut self) -> (Vec<Material>, Vec<Texture>) {
        let root = self.root;
        let mut textures = Vec::new();
        let mut by_image: HashMap<usize, Option<usize>> = HashMap::new();
        let mut unreadable: Vec<String> = Vec::new();
        let mut materials = Vec::with_capacity(root.materials.len());
        let mut see_through = Vec::new();
        for (i, json) in root.materials.iter().enumerate() {
            let name = json.name.clone().unwrap_or_else(|| format!("material {i}"));
            let pbr = &json.pbr_metallic_roughness;
            let factor = Vec4::from_array(pbr.base_color_factor.0);
            let base_color = if factor.is_finite() {
                factor.clamp(Vec4::ZERO, Vec4::ONE)
            } else {
                self.warn(format!(
                    "material '{name}': baseColorFactor is not finite; grey used"
                ));
                Material::default().base_color
            };
            let base_color_texture = pbr.base_color_texture.as_ref().and_then(|info| {
                let texture = info.index.value();
                let Some(image) = root.textures.get(texture).map(|t| t.source.value()) else {
                    unreadable.push(format!("texture {texture} does not exist"));
                    return None;
                };
                *by_image.entry(image).or_insert_with(|| match self.image(image) {
                    Ok(t) => {
                        textures.push(t);
                        Some(textures.len() - 1)
                    }
                    Err(reason) => {
                        unreadable.push(reason);
                        None
                    }
                })
            });
            if json.alpha_mode != Checked::Valid(AlphaMode::Opaque) {
                see_through.push(name.clone());
            }
            let (k, m) = self.lab_parameters(&name, &json.extras);
            materials.push(Material {
                name,
                base_color,
                base_color_texture,
                k,
                m,
                double_sided: json.double_sided,
            });
        }
        if let Some(first) = see_through.first() {
            // The lab models opaque surfaces only: a cut-out or a glass
            // would need its alpha in the shadow rays and maps alike.
            self.warn(format!(
                "{} materials are alpha-masked or blended (alphaMode, first: '{first}'); the lab draws them opaque",
                see_through.len()
            ));
        }
        if let Some(first) = unreadable.first() {
            self.warn(format!(
                "{} base-colour textures cannot be used (first: {first}); their base colour factor alone is drawn",
                unreadable.len()
            ));
        }
        (materials, textures)
    }

    /// Decodes image `index` (from a URI or a buffer view).
    fn image(&self, index: usize) -> Result<Texture, String> {
        let Some(image) = self.root.images.get(index) else {
            return Err(format!("image {index} does not exist"));
        };
        let what = resources::describe("image", index, image.uri.as_deref());
        let bytes = match (&image.uri, image.buffer_view) {
            (Some(uri), _) => {
                std::borrow::Cow::Owned(resources::read_uri(uri, self.base_dir, resources::Kind::Image)?)
            }
            (None, Some(view)) => {
                std::borrow::Cow::Borrowed(self.data.view(view.value()).map_err(|e| e.to_string())?.0)
            }
            (None, None) => return Err(format!("{what} has neither uri nor bufferView")),
        };
        resources::decode_image(&bytes).map_err(|e| format!("{what}: {e}"))
    }

    /// The lab's own k and m from a material's extras,
    /// `{"lumlab": {"k": 0.3, "m": 64}}`, clamped to their ranges.
    fn lab_parameters(&mut self, name: &str, extras: &gltf::json::Extras) -> (Option<f32>, Option<f32>) {
        let Some(lab) = lab_extras(extras) else {
            return (None, None);
        };
        let mut read = |key: &str, (lo, hi): (f64, f64)| -> Option<f32> {
            let value = lab.get(key)?;
            match value.as_f64().filter(|v| v.is_finite()) {
                Some(v) if (lo..=hi).contains(&v) => Some(v as f32),
                Some(v) => {
                    self.warn(format!(
                        "material '{name}': lumlab {key} = {v} is outside {lo} … {hi}; clamped"
                    ));
                    Some(v.clamp(lo, hi) as f32)
                }
                None => {
                    self.warn(format!(
                        "material '{name}': lumlab {key} = {value} is not a number; ignored"
                    ));
                    None
                }
            }
        };
        (read("k", (0.0, 1.0)), read("m", (0.0, 1e6)))
    }
}
