//! The lab's ray-traced visibility accumulates frames while nothing changes
//! and starts anew on every change of a setting.

use lumlab::app::{Command, LabApp};
use lumlab::settings::{DebugView, Filter, Settings, Visibility};

mod app_support;
use app_support::{click_viewport, harness, step_until, wait_for_probe};
use egui_kittest::Harness;

/// A setting's name and how to change it.
type Change = (&'static str, fn(&mut Settings));

fn frames(app: &LabApp) -> u32 {
    app.renderer()
        .and_then(|r| r.accumulation())
        .map_or(0, |a| a.frames)
}

/// Has the lab show settings `s`.
fn show(harness: &mut Harness<'static, LabApp>, s: &Settings) {
    harness
        .state_mut()
        .emit(Command::SetSettings(Box::new(s.clone())));
}

/// The lab under a ray-traced sphere light of R = 0.3 m, its mean `frames`
/// deep; the settings it shows.
fn accumulating(frames_at_least: u32) -> (Harness<'static, LabApp>, Settings) {
    let mut harness = harness();
    let mut s = harness.state().settings().clone();
    s.shadow.visibility = Visibility::RayTraced;
    s.light.radius_m = 0.3;
    show(&mut harness, &s);
    step_until(&mut harness, "frames to accumulate", |app| {
        frames(app) >= frames_at_least
    });
    (harness, s)
}

#[test]
fn accumulation_restarts_on_every_setting_change() {
    let (mut harness, mut s) = accumulating(2);
    let changes: [Change; 9] = [
        ("light position", |s| s.light.position.x += 0.1),
        ("light radius", |s| s.light.radius_m = 0.2),
        ("power", |s| s.light.power_w *= 2.0),
        ("k", |s| s.material.k = 0.3),
        ("m", |s| s.material.m = 8.0),
        ("rays per frame", |s| s.shadow.rt_light_samples = 16),
        ("camera", |s| s.camera.eye.y += 0.1),
        ("view", |s| s.view.mode = DebugView::Visibility),
        ("filter", |s| s.shadow.filter = Filter::Poisson),
    ];
    for (what, change) in changes {
        change(&mut s);
        show(&mut harness, &s);
        harness.step();
        assert_eq!(
            frames(harness.state()),
            1,
            "{what} did not restart the accumulation"
        );
        step_until(&mut harness, what, |app| frames(app) >= 2);
    }
    // Done accumulating: the image holds.
    s.shadow.rt_max_frames = 3;
    show(&mut harness, &s);
    step_until(&mut harness, "the last frame", |app| frames(app) == 3);
    for _ in 0..3 {
        harness.step();
    }
    assert_eq!(frames(harness.state()), 3);
}

#[test]
fn the_mean_holds_once_its_measured_noise_meets_the_target() {
    use lumlab::presets::Half;
    // 2 % of the mean: met within a few frames of 8 rays, long before 256
    // (set on the mean's first frame, which it goes on with).
    let (mut harness, mut s) = accumulating(1);
    s.shadow.rt_noise_target_percent = 2.0;
    show(&mut harness, &s);
    step_until(&mut harness, "the noise to meet the target", |app| {
        app.shown_accumulation(Half::A).is_some_and(|a| a.meets(2.0))
    });
    // The frame or two already on their way when the estimate came back.
    harness.run_steps(3);
    let held = frames(harness.state());
    harness.run_steps(5);
    assert_eq!(frames(harness.state()), held, "the mean went on");
    let shown = harness.state().shown_accumulation(Half::A).expect("ray traced");
    assert!(held < s.shadow.rt_max_frames && !shown.is_complete());
    // Another target goes on with the same mean, not a new one.
    s.shadow.rt_noise_target_percent = 0.0;
    show(&mut harness, &s);
    step_until(&mut harness, "the mean to go on", |app| frames(app) > held + 1);
}

#[test]
fn a_click_on_the_probe_does_not_restart_the_accumulation() {
    // The probe reads the aux target, which the app's still frames write
    // only where it is read; a ray-traced half writes it throughout, since
    // turning it on would start the mean anew.
    let (mut harness, _) = accumulating(3);
    let before = frames(harness.state());
    click_viewport(&mut harness, 0.93);
    // The click's own frame went on with the mean.
    let after = frames(harness.state());
    assert!(
        after > before,
        "the mean restarted: {after} frames after {before}"
    );
    wait_for_probe(&mut harness);
}

#[test]
fn split_shows_shadow_map_against_ray_traced_under_a_sphere_light() {
    use egui_kittest::kittest::Queryable;
    use lumlab::presets::{Comparison, ComparisonAxis};
    let mut harness = harness();
    let app = harness.state_mut();
    let split = &mut app.state_mut().split;
    split.enabled = true;
    split.layout = lumlab::app::SplitLayout::SideBySide;
    split.comparison = Comparison {
        axis: ComparisonAxis::Visibility,
        ..Comparison::default()
    };
    let s = app.settings_mut();
    s.light.radius_m = 0.3;
    s.shadow.filter = Filter::Pcss;
    s.shadow.rt_light_samples = 16;
    s.shadow.rt_max_frames = 16;
    let target = s.shadow.rt_noise_target_percent;
    // Accumulating frames ask for the next: step, never run to rest.
    harness.run_steps(2);
    harness.get_by_label("A: shadow map");
    harness.get_by_label("B: ray traced");
    step_until(&mut harness, "the accumulation", |app| {
        app.renderer_of(lumlab::presets::Half::B)
            .and_then(|r| r.accumulation())
            .is_some_and(|a| a.holds(target))
    });
    // Half A keeps its shadow map: no accumulation there.
    assert!(
        harness
            .state()
            .renderer()
            .and_then(|r| r.accumulation())
            .is_none()
    );
    let image = harness.render().expect("the harness renders");
    if let Some(dir) = std::env::var_os("LUMLAB_SCREENSHOTS") {
        image
            .save(std::path::Path::new(&dir).join("app-raytraced.png"))
            .expect("the screenshot is written");
    }
}
