//! The view panel: what the image shows, its exposure, and the split
//! comparison A | B.

use super::View;
use super::state::{SplitLayout, SplitState};
use crate::physics::Normalization;
use crate::presets::{Comparison, ComparisonAxis, Half};
use crate::settings::{BiasMode, DebugView, Filter, ViewSettings, Visibility};

pub struct ViewPanel<'a> {
    pub view: &'a mut ViewSettings,
    pub split: &'a mut SplitState,
    /// The adapter's largest texture side, for the resolution comparison.
    pub max_texture_side: u32,
}

/// What each debug view shows, with its unit.
pub fn view_help(view: DebugView) -> &'static str {
    match view {
        DebugView::Shaded => "Reflected radiance L = f_r · E · V (W/m²/sr), exposed and sRGB encoded",
        DebugView::Depth => "The light's depth map (normalized distance from the light)",
        DebugView::Visibility => "V ∈ [0, 1] from the shadow map: black = shadowed, white = lit",
        DebugView::Ndotl => "cos θ = max(0, n·l): black at the horizon, white facing the light",
        DebugView::Irradiance => "E · V = I cos θ / r² · V (W/m²), false colour",
        DebugView::Brdf => "f_r / c (1/sr), false colour, log scale over two decades",
        DebugView::Diffuse => "The diffuse part c · k/π · E · V (W/m²/sr)",
        DebugView::Specular => "The specular part c · (1 − k) N(m) cos^m θ_h · E · V (W/m²/sr)",
        DebugView::TexelDensity => "Shadow-map texels per screen pixel (log₂), red: magnified and aliased",
        DebugView::Frustum => "The light's frustum (or cube faces) drawn over the shaded image",
        DebugView::RefVisibility => {
            "The CPU reference's visibility V_ref (compute it in the Reference panel)"
        }
        DebugView::Error => "Signed error of luminance L − L_ref against the CPU reference (W/m²/sr)",
    }
}

impl View for ViewPanel<'_> {
    fn ui(&mut self, ui: &mut egui::Ui) {
        let ViewSettings { mode, exposure_ev } = self.view;
        ui.horizontal(|ui| {
            ui.label("Show")
                .on_hover_text("What the image shows (V: next view)");
            egui::ComboBox::from_id_salt("debug view")
                .selected_text(mode.name())
                .width(180.0)
                .show_ui(ui, |ui| {
                    for &choice in DebugView::ALL {
                        ui.selectable_value(mode, choice, choice.name())
                            .on_hover_text(view_help(choice));
                    }
                })
                .response
                .on_hover_text(view_help(*mode));
        });
        ui.add(
            egui::Slider::new(exposure_ev, -10.0..=10.0)
                .text("exposure")
                .suffix(" EV"),
        )
        .on_hover_text("Displayed value = L · 2^EV, then the sRGB transfer (shaded, diffuse, specular)");

        ui.separator();
        split_ui(ui, self.split, self.max_texture_side);
    }
}

fn split_ui(ui: &mut egui::Ui, split: &mut SplitState, max_texture_side: u32) {
    let SplitState {
        enabled,
        comparison,
        wipe,
        layout,
    } = split;
    ui.checkbox(enabled, "Split view A | B  (S)").on_hover_text(
        "Both halves show the current settings; B differs from A in one setting. \
         Drag the divider to wipe between them.",
    );
    if !*enabled {
        return;
    }
    ui.horizontal_wrapped(|ui| {
        for (name, preset) in Comparison::presets() {
            if ui
                .selectable_label(*comparison == preset, name)
                .on_hover_text(format!(
                    "A: {} | B: {}",
                    preset.label(Half::A),
                    preset.label(Half::B)
                ))
                .clicked()
            {
                *comparison = preset;
            }
        }
    });
    ui.horizontal(|ui| {
        ui.label("Compare")
            .on_hover_text("The setting that differs between A and B");
        egui::ComboBox::from_id_salt("comparison axis")
            .selected_text(comparison.axis.name())
            .show_ui(ui, |ui| {
                for &axis in ComparisonAxis::ALL {
                    ui.selectable_value(&mut comparison.axis, axis, axis.name());
                }
            })
            .response
            .on_hover_text("The setting that differs between A and B");
    });
    for (half, name) in [(Half::A, "A"), (Half::B, "B")] {
        let i = half as usize;
        ui.horizontal(|ui| {
            let label = ui.label(format!("{name}:")).id;
            let id = format!("comparison {name}");
            match comparison.axis {
                ComparisonAxis::Normalization => choose(
                    ui,
                    (&id, label),
                    &mut comparison.norm[i],
                    Normalization::ALL,
                    |n| n.name().into(),
                ),
                ComparisonAxis::Filter => {
                    choose(ui, (&id, label), &mut comparison.filter[i], Filter::ALL, |f| {
                        f.name().into()
                    })
                }
                ComparisonAxis::Bias => {
                    choose(ui, (&id, label), &mut comparison.bias[i], BiasMode::ALL, |b| {
                        b.name().into()
                    })
                }
                ComparisonAxis::Visibility => choose(
                    ui,
                    (&id, label),
                    &mut comparison.visibility[i],
                    Visibility::ALL,
                    |v| v.name().into(),
                ),
                ComparisonAxis::Resolution => {
                    let choices = super::shadow::resolution_choices(max_texture_side);
                    choose(ui, (&id, label), &mut comparison.resolution[i], &choices, |r| {
                        format!("{r}²")
                    })
                }
            }
        });
    }
    ui.horizontal(|ui| {
        ui.label("Layout");
        ui.selectable_value(layout, SplitLayout::Wipe, "wipe")
            .on_hover_text("One image: A left of the divider, B right of it");
        ui.selectable_value(layout, SplitLayout::SideBySide, "side by side")
            .on_hover_text("Two whole images of the same view, cameras linked: A left, B right");
    });
    if *layout == SplitLayout::Wipe {
        ui.add(egui::Slider::new(wipe, 0.0..=1.0).text("divider"))
            .on_hover_text(
                "Where A ends and B begins (fraction of the width); or drag the line in the image",
            );
    }
}

/// A combo box of `all`, named by the label `id.1`.
fn choose<T: Copy + PartialEq>(
    ui: &mut egui::Ui,
    (id, label): (&str, egui::Id),
    value: &mut T,
    all: &[T],
    name: impl Fn(T) -> String,
) {
    egui::ComboBox::from_id_salt(id)
        .selected_text(name(*value))
        .show_ui(ui, |ui| {
            for &choice in all {
                ui.selectable_value(value, choice, name(choice));
            }
        })
        .response
        .labelled_by(label);
}
