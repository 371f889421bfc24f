//! Frames stay fluid while the user drags: the viewport renders at a reduced
//! scale during the drag and at full resolution as soon as it ends (with a
//! repaint asked for, so the sharp image comes without another event).

mod app_support;
use app_support::{harness, primary_button};
use egui::Event;

/// The size (pixels) of half A's last rendered image.
fn rendered_size(harness: &egui_kittest::Harness<'_, lumlab::app::LabApp>) -> (u32, u32) {
    let texture = harness
        .state()
        .renderer()
        .and_then(|r| r.display_texture())
        .expect("a frame was rendered");
    (texture.width(), texture.height())
}

#[test]
fn dragging_renders_at_a_reduced_scale_and_releasing_returns_to_full_resolution() {
    let mut harness = harness();
    // The first frames' GPU times size the interaction scale.
    for _ in 0..20 {
        harness.step();
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let full = harness.state().viewport_size();
    assert_eq!(rendered_size(&harness), full, "idle: full resolution");
    let rect = harness.state().viewport_rect();
    let from = rect.center();
    harness.event(Event::PointerMoved(from));
    harness.step();
    primary_button(&mut harness, from, true);
    harness.step();
    let mut to = from;
    for _ in 0..5 {
        let renders = harness.state().renders();
        to += egui::vec2(20.0, 0.0);
        harness.event(Event::PointerMoved(to));
        harness.step();
        assert_eq!(harness.state().renders(), renders + 1, "each drag step renders");
        let size = rendered_size(&harness);
        // The software adapter needs well over the renderer's share of a
        // 30 frames/s budget at full size: the scale drops, keeping the shape.
        assert!(
            size.0 < full.0 && size.1 < full.1,
            "dragging renders {size:?} of {full:?}"
        );
        let aspect = |s: (u32, u32)| s.0 as f64 / s.1 as f64;
        assert!((aspect(size) / aspect(full) - 1.0).abs() < 0.02);
    }
    let orbited = harness.state().settings().camera;
    let renders = harness.state().renders();
    primary_button(&mut harness, to, false);
    harness.step();
    if rendered_size(&harness) != full {
        // The release frame was still an interaction frame: it must ask for
        // the next one, which is full size.
        assert!(
            harness.ctx.has_requested_repaint(),
            "a reduced image left without a repaint"
        );
        harness.step();
    }
    assert_eq!(rendered_size(&harness), full, "released: full resolution");
    assert!(
        harness.state().renders() > renders,
        "the full-resolution frame was rendered"
    );
    assert_eq!(
        harness.state().settings().camera,
        orbited,
        "the same view, only sharper"
    );
    let settled = harness.state().renders();
    harness.run_steps(5);
    assert_eq!(
        harness.state().renders(),
        settled,
        "idle again: nothing re-rendered"
    );
}
