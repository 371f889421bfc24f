//! PCF and Poisson decided from the depth ranges (gpu::depth_ranges: one
//! read settles a kernel whose texels all light, or all hide, the receiver)
//! give the V of the same taps tested one by one, for every PCF kernel
//! size, bias mode and map layout. Tests elsewhere hold the filters
//! themselves to the CPU reference.

mod common;

use common::*;
use lumlab::gpu::light_frustum::LayoutKind;
use lumlab::gpu::{Renderer, ShadeOptions};
use lumlab::settings::{BiasMode, Filter, Settings};

#[test]
fn filters_decided_from_depth_ranges_match_every_tap_tested() {
    let gpu = gpu();
    let scene = lumlab::scene::default_scene();
    let mut renderer = Renderer::new(&gpu.adapter, &gpu.device, &gpu.queue, &scene);
    // Lavapipe (the tests' adapter) renders their format; llvmpipe's GL
    // does not, and tests every tap (the held frame below reads none).
    let ranges = renderer.capabilities().depth_ranges;
    assert!(ranges || renderer.capabilities().gl, "only GL lacks the ranges");
    let size = (160, 120);
    let auto = Settings::default().shadow.bias.mode;
    let mut cases = Vec::new();
    // The light high above the scene: one fitted frustum; at its default
    // height: six cube faces; low: the ground steep in the light's view,
    // lit kernels decided by its plane (the bounds' gradient).
    for (light_y_m, layout) in [
        (40.0, LayoutKind::Single),
        (6.0, LayoutKind::Cube),
        (2.0, LayoutKind::Cube),
    ] {
        for n in lumlab::settings::ShadowSettings::PCF_SIZES {
            cases.push((light_y_m, layout, n, auto));
        }
        for &bias in BiasMode::ALL {
            cases.push((light_y_m, layout, 3, bias));
        }
        // n = 0: the Poisson disc (its default radius, 2 texels).
        cases.push((light_y_m, layout, 0, auto));
    }
    for (i, (light_y_m, layout, n, bias)) in cases.into_iter().enumerate() {
        let mut s = Settings::default();
        // A light that moved a little: each case draws its own map.
        s.light.position.x += 1e-3 * i as f32;
        s.light.position.y = light_y_m;
        if n == 0 {
            s.shadow.filter = Filter::Poisson;
        } else {
            s.shadow.filter = Filter::Pcf;
            s.shadow.pcf_size = n;
        }
        s.shadow.bias.mode = bias;
        let filter = match n {
            0 => "Poisson".to_owned(),
            _ => format!("PCF {n}×{n}"),
        };
        let what = format!("{filter}, bias {bias:?}, {layout:?} map");
        // The frame that draws the map tests every texel; the next one
        // builds the ranges and reads them.
        let drawn = renderer.render(&s, size);
        assert_eq!(drawn.layout.map(|l| l.kind), Some(layout), "{what}");
        assert!(drawn.shadow_redrawn, "{what}: the map is drawn");
        assert_eq!(drawn.depth_ranges, None, "{what}: no ranges with the map");
        let tested = renderer.read_aux();
        let held = renderer.render(&s, size);
        assert!(!held.shadow_redrawn, "{what}: the map holds");
        if !ranges {
            assert_eq!(held.depth_ranges, None, "{what}: the device has no ranges");
            continue;
        }
        let block = held.depth_ranges.unwrap_or_else(|| panic!("{what}: ranges read"));
        assert!(n <= block, "{what}: a kernel fits in a window of B = {block}");
        let decided = renderer.read_aux();
        // The baseline the benchmarks compare with: the map held, no ranges.
        renderer.set_shade_options(ShadeOptions {
            depth_ranges: false,
            ..ShadeOptions::default()
        });
        assert_eq!(renderer.render(&s, size).depth_ranges, None, "{what}: ranges off");
        renderer.set_shade_options(ShadeOptions::default());
        let lit = tested.iter().filter(|t| t[3] > 0.0 && t[0] > 0.999).count();
        let dark = tested.iter().filter(|t| t[3] > 0.0 && t[0] == 0.0).count();
        assert!(
            lit > 100 && dark > 100,
            "{what}: {lit} lit and {dark} shadowed pixels"
        );
        // V is a weighted sum of tests: deciding a kernel at once changes it
        // by at least one texel's weight where a decision was wrong, by the
        // sum's rounding (< 1e-6) where it was right.
        let worst = tested
            .iter()
            .zip(&decided)
            .map(|(a, b)| (a[0] - b[0]).abs())
            .fold(0.0, f32::max);
        assert!(worst <= 1e-6, "{what}: V differs by {worst}");
    }
}
