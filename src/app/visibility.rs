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
    noise_target_percent: &mut f32,
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
        ui.add(
            egui::Slider::new(
                noise_target_percent,
                0.0..=ShadowSettings::MAX_RT_NOISE_TARGET_PERCENT,
            )
            .logarithmic(true)
            .smallest_positive(0.01)
            .suffix(" %")
            .text(tr!("visibility-noise-target")),
        )
        .on_hover_text(tr!("visibility-noise-target-tip"));
    }
}

/// "37 / 256 frames × 4 rays, noise ≈ 0.21 % of the mean": the ray-traced
/// accumulation so far, at the bottom left of a half, with the noise
/// measured on the image (gpu::noise); before the first measure (four
/// frames), σ(V) ≤ 0.5 / √(N·S) bounds the noise left in V. A mean that
/// holds before its last frame, its noise at most `noise_target_percent`,
/// says so; `elapsed`, the time its frames took so far, is given from the
/// second frame on.
pub fn accumulation_text(
    a: &Accumulation,
    noise_target_percent: f32,
    elapsed: Option<std::time::Duration>,
) -> String {
    let noise = match a.estimate {
        _ if a.noise_bound == 0.0 => tr!("visibility-exact"),
        Some(e) => tr!(
            "visibility-noise-estimate",
            percent = two_significant(100.0 * e.relative)
        ),
        None => format!("σ(V) ≤ {:.3}", a.noise_bound),
    };
    let noise = match elapsed.filter(|_| a.frames > 1) {
        Some(t) => format!(
            "{noise} {}",
            tr!("visibility-elapsed", seconds = format!("{:.1}", t.as_secs_f64()))
        ),
        None => noise,
    };
    let noise = if !a.is_complete() && a.meets(noise_target_percent) {
        // 0.1, not 0.10: the target as the slider set it, to two digits.
        let target = two_significant(f64::from(noise_target_percent));
        let target = target.trim_end_matches('0').trim_end_matches('.');
        format!("{noise}, {}", tr!("visibility-held", target = target))
    } else {
        noise
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
pub fn paint_accumulation(
    painter: &egui::Painter,
    area: egui::Rect,
    a: &Accumulation,
    noise_target_percent: f32,
    elapsed: Option<std::time::Duration>,
) {
    let at = area.left_bottom() + egui::vec2(10.0, -10.0);
    let text = accumulation_text(a, noise_target_percent, elapsed);
    let font = egui::FontId::proportional(14.0);
    let wrap = (area.width() - 28.0).max(80.0);
    let galley = painter.layout(text, font, egui::Color32::WHITE, wrap);
    let rect = egui::Align2::LEFT_BOTTOM
        .anchor_size(at, galley.size())
        .expand(4.0);
    painter.rect_filled(rect, 3.0, egui::Color32::from_black_alpha(160));
    painter.galley(rect.min + egui::vec2(4.0, 4.0), galley, egui::Color32::WHITE);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu::noise::NoiseEstimate;

    #[test]
    fn a_mean_held_below_its_target_says_so() {
        let a = Accumulation {
            frames: 70,
            max_frames: 256,
            rays_per_frame: 4,
            noise_bound: 0.003,
            run: 0,
            estimate: Some(NoiseEstimate {
                frames: 64,
                earlier_frames: 32,
                relative: 0.00095,
            }),
        };
        // The label keeps a number with its unit (no-break spaces).
        let held =
            accumulation_text(&a, 0.1, Some(std::time::Duration::from_millis(5_840))).replace('\u{a0}', " ");
        assert!(
            held.contains("0.095 %") && held.contains("0.1 %") && held.contains("5.8 s"),
            "{held}"
        );
        for (a, target) in [(a, 0.05), (a, 0.0), (Accumulation { frames: 256, ..a }, 0.1)] {
            let text = accumulation_text(&a, target, None).replace('\u{a0}', " ");
            assert!(!text.contains("0.1 %") && !text.contains("0.05 %"), "{text}");
        }
    }
}
