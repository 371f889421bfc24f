//! The lab's ray-traced visibility accumulates frames while nothing changes
//! and starts anew on every change of a setting.

use lumlab::app::{Command, LabApp};
use lumlab::settings::{DebugView, Filter, Settings, Visibility};

mod app_support;
use app_support::{harness, step_until};

fn frames(app: &LabApp) -> u32 {
    app.renderer()
        .and_then(|r| r.accumulation())
        .map_or(0, |a| a.frames)
}

#[test]
fn accumulation_restarts_on_every_setting_change() {
    let mut harness = harness();
    let mut s = harness.state().settings().clone();
    s.shadow.visibility = Visibility::RayTraced;
    s.light.radius_m = 0.3;
    harness
        .state_mut()
        .emit(Command::SetSettings(Box::new(s.clone())));
    step_until(&mut harness, "frames to accumulate", |app| frames(app) >= 2);
    let changes: [(&str, fn(&mut Settings)); 9] = [
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
        harness
            .state_mut()
            .emit(Command::SetSettings(Box::new(s.clone())));
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
    harness
        .state_mut()
        .emit(Command::SetSettings(Box::new(s.clone())));
    step_until(&mut harness, "the last frame", |app| frames(app) == 3);
    for _ in 0..3 {
        harness.step();
    }
    assert_eq!(frames(harness.state()), 3);
}
