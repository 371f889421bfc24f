//! The window shows the renderer's frame as it is: the viewport image, drawn
//! by its own pipeline inside egui's render pass (app::viewport_image), has
//! at full scale the bytes of the renderer's display texture, pixel for pixel.

mod app_support;

use app_support::{harness, step_until};

#[test]
fn the_viewport_shows_the_rendered_frame_pixel_for_pixel() {
    let mut harness = harness();
    step_until(&mut harness, "a frame", |app| app.renders() >= 1);
    let window = harness.render().expect("the harness renders through wgpu");
    let app = harness.state();
    let rect = app.viewport_rect();
    let frame = app.renderer().expect("a renderer").read_display();
    let (w, h) = frame.dimensions();
    assert_eq!(
        (w as f32, h as f32),
        (rect.width(), rect.height()),
        "one pixel a texel"
    );
    let (x0, y0) = (rect.min.x as u32, rect.min.y as u32);
    // The lower half: no overlay (the light's marker, labels) is drawn there.
    let mut worst = 0;
    let mut distinct = std::collections::HashSet::new();
    for y in h / 2..h {
        for x in 0..w {
            let want = frame.get_pixel(x, y).0;
            let got = window.get_pixel(x0 + x, y0 + y).0;
            distinct.insert(want);
            for c in 0..3 {
                worst = worst.max(want[c].abs_diff(got[c]));
            }
        }
    }
    assert!(
        distinct.len() > 50,
        "the frame shows the scene ({} colours)",
        distinct.len()
    );
    // 0 where the window stores bytes as written; an sRGB window re-encodes
    // the decoded value, which may round to the next byte.
    assert!(worst <= 1, "a window pixel differs from the frame by {worst}/255");
}
