//! Colour legends drawn over the image: the false-colour ramps of
//! `gpu::colormap` with their numbers and units, and the grey views.

use crate::gpu::colormap::{self, Legend, STOPS};
use crate::settings::DebugView;
use crate::tr;
use egui::{Align2, Color32, FontId, Pos2, Rect, Stroke, Vec2, epaint::Mesh};

/// Grey views: the display writes the value itself as the sRGB-encoded grey.
static GREY: [[f32; 3]; STOPS] = [
    [0.0, 0.0, 0.0],
    [0.25, 0.25, 0.25],
    [0.5, 0.5, 0.5],
    [0.75, 0.75, 0.75],
    [1.0, 1.0, 1.0],
];
/// The depth view: near is white, far is dark (1 − 0.9 t).
static DEPTH: [[f32; 3]; STOPS] = [
    [1.0, 1.0, 1.0],
    [0.775, 0.775, 0.775],
    [0.55, 0.55, 0.55],
    [0.325, 0.325, 0.325],
    [0.1, 0.1, 0.1],
];

/// The legend of `view` with the false-colour scale `scale` (None while it
/// is being read back); None for views in radiance.
pub fn for_view(view: DebugView, scale: Option<f32>) -> Option<Legend> {
    let quarters = |labels: [&str; 5]| {
        [0.0, 0.25, 0.5, 0.75, 1.0]
            .into_iter()
            .zip(labels)
            .map(|(t, l)| (t, l.to_string()))
            .collect()
    };
    let grey = |title: &str| Legend {
        title: title.into(),
        ramp: &GREY,
        ticks: quarters(["0", "0.25", "0.5", "0.75", "1"]),
    };
    match view {
        DebugView::Visibility => Some(grey(&tr!("legend-visibility"))),
        DebugView::RefVisibility => Some(grey(&tr!("legend-ref-visibility"))),
        DebugView::Ndotl => Some(grey("cos θ = max(0, n·l)")),
        DebugView::Depth => Some(Legend {
            title: tr!("legend-depth"),
            ramp: &DEPTH,
            ticks: quarters([&tr!("legend-near"), "", "", "", &tr!("legend-far")]),
        }),
        DebugView::TexelDensity => colormap::legend(view, 1.0),
        DebugView::DeltaE => Some(colormap::delta_e_legend(tr!("legend-delta-e"))),
        _ => colormap::legend(view, scale?),
    }
}

/// The width of a legend's card in `area`.
fn card_width(area: Rect) -> f32 {
    (area.width() - 24.0).clamp(120.0, 420.0)
}

/// Paints a dark card of `height` at the bottom of `area` and returns it;
/// None when `area` is too short for it.
fn card(painter: &egui::Painter, area: Rect, height: f32) -> Option<Rect> {
    if area.height() < height + 24.0 {
        return None;
    }
    let width = card_width(area);
    let card = Rect::from_min_size(
        Pos2::new(area.center().x - width / 2.0, area.max.y - height - 12.0),
        Vec2::new(width, height),
    );
    painter.rect_filled(card, 6.0, Color32::from_black_alpha(190));
    Some(card)
}

/// Paints `note` where a legend would be: what a view needs before it can
/// show anything (the `delta-e` view without a spectral illuminant).
pub fn paint_note(painter: &egui::Painter, area: Rect, note: &str) {
    let font = FontId::proportional(15.0);
    let galley = painter.layout(note.to_string(), font, Color32::WHITE, card_width(area) - 20.0);
    if let Some(card) = card(painter, area, galley.size().y + 12.0) {
        painter.galley(card.min + Vec2::new(10.0, 6.0), galley, Color32::WHITE);
    }
}

fn color(c: [f32; 3]) -> Color32 {
    let byte = |x: f32| (x.clamp(0.0, 1.0) * 255.0).round() as u8;
    Color32::from_rgb(byte(c[0]), byte(c[1]), byte(c[2]))
}

/// Paints `legend` at the bottom of `area`: a dark card with the title, the
/// ramp and its labelled ticks, large enough to read from the back of a room.
pub fn paint(painter: &egui::Painter, area: Rect, legend: &Legend) {
    let Some(card) = card(painter, area, 78.0) else {
        return;
    };
    let font = FontId::proportional(15.0);
    painter.text(
        card.min + Vec2::new(10.0, 6.0),
        Align2::LEFT_TOP,
        &legend.title,
        font.clone(),
        Color32::WHITE,
    );
    let bar = Rect::from_min_max(
        Pos2::new(card.min.x + 16.0, card.min.y + 30.0),
        Pos2::new(card.max.x - 16.0, card.min.y + 46.0),
    );
    // Many thin segments sampled like the shader samples the ramp, so the
    // mesh's own interpolation cannot bend the gradient.
    const SEGMENTS: usize = 64;
    let mut mesh = Mesh::default();
    for i in 0..=SEGMENTS {
        let t = i as f32 / SEGMENTS as f32;
        let x = bar.min.x + bar.width() * t;
        let c = color(colormap::sample(legend.ramp, t));
        mesh.colored_vertex(Pos2::new(x, bar.min.y), c);
        mesh.colored_vertex(Pos2::new(x, bar.max.y), c);
        if i > 0 {
            let v = 2 * i as u32;
            mesh.add_triangle(v - 2, v - 1, v);
            mesh.add_triangle(v - 1, v + 1, v);
        }
    }
    painter.add(mesh);
    painter.rect_stroke(
        bar,
        0.0,
        Stroke::new(1.0, Color32::GRAY),
        egui::StrokeKind::Outside,
    );
    for (t, label) in &legend.ticks {
        let x = bar.min.x + bar.width() * t;
        painter.line_segment(
            [Pos2::new(x, bar.max.y), Pos2::new(x, bar.max.y + 4.0)],
            Stroke::new(1.0, Color32::WHITE),
        );
        let align = if *t <= 0.0 {
            Align2::LEFT_TOP
        } else if *t >= 1.0 {
            Align2::RIGHT_TOP
        } else {
            Align2::CENTER_TOP
        };
        painter.text(
            Pos2::new(x, bar.max.y + 5.0),
            align,
            label,
            font.clone(),
            Color32::WHITE,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn false_colour_views_have_units_and_grey_views_a_range() {
        let irradiance = for_view(DebugView::Irradiance, Some(40.0)).unwrap();
        assert!(irradiance.title.contains("W/m²"));
        assert_eq!(irradiance.ticks.last().unwrap().1, "40");
        assert!(for_view(DebugView::Irradiance, None).is_none());
        assert!(for_view(DebugView::Visibility, None).is_some());
        assert!(for_view(DebugView::Shaded, Some(1.0)).is_none());
        // A fixed scale: shown before (and whatever) the read-back scale.
        let delta_e = for_view(DebugView::DeltaE, None).unwrap();
        assert_eq!(delta_e.ticks.last().unwrap().1, "≥ 10");
        assert!(
            delta_e
                .ticks
                .iter()
                .any(|(t, l)| (*t - 0.23).abs() < 1e-6 && l == "2.3")
        );
        assert!(
            for_view(DebugView::Error, Some(0.5))
                .unwrap()
                .title
                .contains("W/m²/sr")
        );
    }
}
