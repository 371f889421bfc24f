//! The split view side by side: two whole images of the same view, cameras
//! linked, A left and B right; a click on the right image probes B; each
//! preset picks the comparison that shows its remedy.

use egui::Modifiers;
use egui_kittest::kittest::Queryable;
use lumlab::app::Command;
use lumlab::presets::{ComparisonAxis, Half, Preset};

mod app_support;
use app_support::{harness, step_until};

#[test]
fn side_by_side_shows_two_whole_images_and_probes_b_on_the_right() {
    let mut harness = harness();
    let wide = harness.state().viewport_size();
    {
        let state = harness.state_mut().state_mut();
        state.split.enabled = true;
        state.split.layout = lumlab::app::SplitLayout::SideBySide;
    }
    harness.run();
    let half = harness.state().viewport_size();
    // Each image about half as wide as the single one, as tall.
    assert!(
        (half.0 as f64 / wide.0 as f64 - 0.5).abs() < 0.02,
        "{wide:?} → {half:?}"
    );
    assert_eq!(half.1, wide.1);
    harness.get_by_label("A: norm none");
    harness.get_by_label("B: norm approx");
    // A click at the same place in the right image probes B's same pixel.
    let a_rect = harness.state().viewport_rect();
    let right = a_rect.center() + egui::vec2(a_rect.width() + 6.0, 0.0);
    harness.event(egui::Event::PointerMoved(right));
    for pressed in [true, false] {
        harness.event(egui::Event::PointerButton {
            pos: right,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: Modifiers::NONE,
        });
        harness.step();
    }
    step_until(&mut harness, "the probe", |app| app.probe_pixel().is_some());
    let probe = harness.state().probe_pixel().unwrap();
    assert_eq!(probe.half, Half::B);
    let centre = (half.0 / 2, half.1 / 2);
    assert!(
        probe.pixel.0.abs_diff(centre.0) <= 2 && probe.pixel.1.abs_diff(centre.1) <= 2,
        "{probe:?}"
    );
}

#[test]
fn each_preset_picks_the_comparison_of_its_remedy() {
    let mut harness = harness();
    for (preset, axis) in [
        (Preset::ShadowAcne, ComparisonAxis::Bias),
        (Preset::Aliasing, ComparisonAxis::Resolution),
        (Preset::Penumbra, ComparisonAxis::Filter),
        (Preset::EnergyGain, ComparisonAxis::Normalization),
    ] {
        harness.state_mut().emit(Command::ApplyPreset(preset));
        harness.run();
        assert_eq!(
            harness.state_mut().state_mut().split.comparison.axis,
            axis,
            "{preset}"
        );
    }
}
