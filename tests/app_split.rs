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

#[test]
fn colour_comparison_shows_the_rgb_product_beside_the_spectral_result_under_a() {
    let mut harness = harness();
    {
        let app = harness.state_mut();
        let state = app.state_mut();
        state.split.enabled = true;
        state.split.layout = lumlab::app::SplitLayout::SideBySide;
        state.split.comparison = lumlab::presets::Comparison {
            axis: ComparisonAxis::Colour,
            ..Default::default()
        };
        app.settings_mut().colour.illuminant = Some(lumlab::colour::Illuminant::A);
    }
    harness.run();
    step_until(&mut harness, "both halves", |app| app.viewport_size().0 > 0);
    for _ in 0..10 {
        harness.step();
    }
    harness.get_by_label("A: RGB approximation");
    harness.get_by_label("B: spectral");
    let image = harness.render().expect("the harness renders through wgpu");
    let dir = std::env::var_os("LUMLAB_SCREENSHOTS")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("app-screenshots"));
    std::fs::create_dir_all(&dir).unwrap();
    image.save(dir.join("app-spectral.png")).unwrap();
    // The same pixel of both images: the chart's saturated patches differ
    // visibly (ΔE2000 up to 12 under A), neutral surfaces hardly.
    let a = harness.state().viewport_rect();
    let ppp = image.width() as f32 / app_support::SIZE.x;
    let (mut differing, mut total) = (0, 0);
    for j in (a.top() as u32..a.bottom() as u32).step_by(2) {
        for i in (a.left() as u32..a.right() as u32).step_by(2) {
            let (x, y) = ((i as f32 * ppp) as u32, (j as f32 * ppp) as u32);
            let dx = ((a.width() + 6.0) * ppp) as u32;
            if x + dx >= image.width() || y >= image.height() {
                continue;
            }
            let (pa, pb) = (image.get_pixel(x, y).0, image.get_pixel(x + dx, y).0);
            let diff = (0..3).map(|c| pa[c].abs_diff(pb[c])).max().unwrap_or(0);
            total += 1;
            differing += (diff > 12) as usize;
        }
    }
    assert!(total > 1000, "{total} pixels compared");
    assert!(
        differing > total / 200,
        "only {differing} of {total} pixels differ between RGB and spectral"
    );
}
