//! The view panel: what the image shows, its exposure, and the split
//! comparison A | B.

use super::View;
use super::state::{SplitLayout, SplitState};
use crate::colour::ColourModel;
use crate::physics::Normalization;
use crate::presets::{ComparisonAxis, Half, SplitPreset};
use crate::settings::{BiasMode, DebugView, Filter, ViewSettings, Visibility};
use crate::tr;

pub struct ViewPanel<'a> {
    pub view: &'a mut ViewSettings,
    pub split: &'a mut SplitState,
    /// The adapter's largest texture side, for the resolution comparison.
    pub max_texture_side: u32,
}

/// What each debug view shows, with its unit.
pub fn view_help(view: DebugView) -> String {
    match view {
        DebugView::Shaded => tr!("view-shaded-tip"),
        DebugView::Depth => tr!("view-depth-tip"),
        DebugView::Visibility => tr!("view-visibility-tip"),
        DebugView::Ndotl => tr!("view-ndotl-tip"),
        DebugView::Irradiance => tr!("view-irradiance-tip"),
        DebugView::Brdf => tr!("view-brdf-tip"),
        DebugView::Diffuse => tr!("view-diffuse-tip"),
        DebugView::Specular => tr!("view-specular-tip"),
        DebugView::TexelDensity => tr!("view-texel-density-tip"),
        DebugView::Frustum => tr!("view-frustum-tip"),
        DebugView::RefVisibility => tr!("view-ref-visibility-tip"),
        DebugView::Error => tr!("view-error-tip"),
        DebugView::DeltaE => tr!("view-delta-e-tip"),
    }
}

impl View for ViewPanel<'_> {
    fn ui(&mut self, ui: &mut egui::Ui) {
        let ViewSettings { mode, exposure_ev } = self.view;
        ui.horizontal(|ui| {
            ui.label(tr!("view-show")).on_hover_text(tr!("view-show-tip"));
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
                .text(tr!("view-exposure"))
                .suffix(" EV"),
        )
        .on_hover_text(tr!("view-exposure-tip"));

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
    ui.checkbox(enabled, tr!("split-enabled"))
        .on_hover_text(tr!("split-enabled-tip"));
    if !*enabled {
        return;
    }
    ui.horizontal_wrapped(|ui| {
        for choice in SplitPreset::ALL {
            let preset = choice.comparison();
            if ui
                .selectable_label(*comparison == preset, super::names::split_choice_name(choice))
                .on_hover_text(format!(
                    "A: {} | B: {}",
                    super::names::comparison_label(&preset, Half::A),
                    super::names::comparison_label(&preset, Half::B)
                ))
                .clicked()
            {
                *comparison = preset;
            }
        }
    });
    ui.horizontal(|ui| {
        ui.label(tr!("split-compare"))
            .on_hover_text(tr!("split-compare-tip"));
        egui::ComboBox::from_id_salt("comparison axis")
            .selected_text(comparison.axis.name())
            .show_ui(ui, |ui| {
                for &axis in ComparisonAxis::ALL {
                    ui.selectable_value(&mut comparison.axis, axis, axis.name());
                }
            })
            .response
            .on_hover_text(tr!("split-compare-tip"));
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
                ComparisonAxis::Colour => choose(
                    ui,
                    (&id, label),
                    &mut comparison.colour[i],
                    ColourModel::ALL,
                    |c| c.name().into(),
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
        ui.label(tr!("split-layout"));
        ui.selectable_value(layout, SplitLayout::Wipe, tr!("split-wipe"))
            .on_hover_text(tr!("split-wipe-tip"));
        ui.selectable_value(layout, SplitLayout::SideBySide, tr!("split-side-by-side"))
            .on_hover_text(tr!("split-side-by-side-tip"));
    });
    if *layout == SplitLayout::Wipe {
        ui.add(egui::Slider::new(wipe, 0.0..=1.0).text(tr!("split-divider")))
            .on_hover_text(tr!("split-divider-tip"));
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
