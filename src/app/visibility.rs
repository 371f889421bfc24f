//! The visibility method: shadow map or ray traced, and the ray tracer's
//! sampling (a part of the shadow panel).

use crate::gpu::raytrace::Accumulation;
use crate::settings::{ShadowSettings, Visibility};
use crate::tr;

/// Tooltip of each visibility method.
pub fn visibility_help(visibility: Visibility) -> String {
    match visibility {
        Visibility::ShadowMap => tr!("visibility-shadow-map-tip"),
        Visibility::RayTraced => tr!("visibility-ray-traced-tip"),
    }
}

/// The method's menu, and the ray tracer's samples and frames when chosen.
pub fn visibility_ui(
    ui: &mut egui::Ui,
    visibility: &mut Visibility,
    samples: &mut u32,
    max_frames: &mut u32,
) {
    ui.horizontal(|ui| {
        ui.label(tr!("visibility-label"))
            .on_hover_text(tr!("visibility-label-tip"));
        egui::ComboBox::from_id_salt("visibility method")
            .selected_text(visibility.name())
            .show_ui(ui, |ui| {
                for &choice in Visibility::ALL {
                    ui.selectable_value(visibility, choice, choice.name())
                        .on_hover_text(visibility_help(choice));
                }
            })
            .response
            .on_hover_text(visibility_help(*visibility));
    });
    if *visibility == Visibility::RayTraced {
        ui.add(
            egui::Slider::new(samples, 1..=ShadowSettings::MAX_RT_LIGHT_SAMPLES)
                .logarithmic(true)
                .text(tr!("visibility-rays")),
        )
        .on_hover_text(tr!("visibility-rays-tip"));
        ui.add(
            egui::Slider::new(max_frames, 1..=ShadowSettings::MAX_RT_FRAMES)
                .logarithmic(true)
                .text(tr!("visibility-frames")),
        )
        .on_hover_text(tr!("visibility-frames-tip"));
    }
}

/// "37 / 256 frames × 4 rays, noise ≈ 0.21 % of the mean": the ray-traced
/// accumulation so far, at the bottom left of a half, with the noise
/// measured on the image (gpu::noise); before the first measure (four
/// frames), σ(V) ≤ 0.5 / √(N·S) bounds the noise left in V.
pub fn accumulation_text(a: &Accumulation) -> String {
    let noise = match a.estimate {
        _ if a.noise_bound == 0.0 => tr!("visibility-exact"),
        Some(e) => tr!(
            "visibility-noise-estimate",
            percent = two_significant(100.0 * e.relative)
        ),
        None => format!("σ(V) ≤ {:.3}", a.noise_bound),
    };
    tr!(
        "visibility-accumulation",
        frames = a.frames,
        max = a.max_frames,
        rays = a.rays_per_frame,
        noise = noise
    )
}

/// `x` to two significant digits, at least one decimal: 2.1, 0.21, 0.043.
fn two_significant(x: f64) -> String {
    let decimals = if x > 0.0 && x.is_finite() {
        (1 - x.log10().floor() as i32).max(1) as usize
    } else {
        1
    };
    format!("{x:.decimals$}")
}

/// The accumulation's text at the bottom left of `area`, wrapped to its
/// width (a half of a side-by-side split is narrow).
pub fn paint_accumulation(painter: &egui::Painter, area: egui::Rect, a: &Accumulation) {
    let at = area.left_bottom() + egui::vec2(10.0, -10.0);
    let text = accumulation_text(a);
    let font = egui::FontId::proportional(14.0);
    let wrap = (area.width() - 28.0).max(80.0);
    let galley = painter.layout(text, font, egui::Color32::WHITE, wrap);
    let rect = egui::Align2::LEFT_BOTTOM
        .anchor_size(at, galley.size())
        .expand(4.0);
    painter.rect_filled(rect, 3.0, egui::Color32::from_black_alpha(160));
    painter.galley(rect.min + egui::vec2(4.0, 4.0), galley, egui::Color32::WHITE);
}
