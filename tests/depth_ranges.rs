//! PCF, Poisson and PCSS's blocker search decided from the depth ranges
//! (gpu::depth_ranges: one read settles a kernel whose texels all light,
//! or all hide, the receiver) give the V of the same taps tested one by
//! one, for every PCF kernel size, bias mode and map layout. Tests elsewhere hold the filters
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
            cases.push((light_y_m, layout, Filter::Pcf, n, auto));
        }
        for &bias in BiasMode::ALL {
            cases.push((light_y_m, layout, Filter::Pcf, 3, bias));
        }
        // The Poisson disc (its default radius, 2 texels), and PCSS under a
        // sphere light (its blocker search's square, up to 99 texels).
        cases.push((light_y_m, layout, Filter::Poisson, 0, auto));
        for &bias in BiasMode::ALL {
            cases.push((light_y_m, layout, Filter::Pcss, 0, bias));
        }
    }
    for (i, (light_y_m, layout, filter, n, bias)) in cases.into_iter().enumerate() {
        let mut s = Settings::default();
        // A light that moved a little: each case draws its own map.
        s.light.position.x += 1e-3 * i as f32;
        s.light.position.y = light_y_m;
        s.light.radius_m = if filter == Filter::Pcss { 0.2 } else { 0.0 };
        s.shadow.filter = filter;
        s.shadow.pcf_size = n.max(3);
        s.shadow.bias.mode = bias;
        let filter = match filter {
            Filter::Pcf => format!("PCF {n}×{n}"),
            other => other.to_string(),
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

/// The bounds the ranges build from a map of known values: every stored
/// value within its window's bound, and a window that one plane fills
/// bounded by that plane to rounding (a flat range would be as wide as the
/// plane's rise over the window).
#[test]
fn window_bounds_hold_every_texel_and_find_a_plane() {
    use lumlab::gpu::Capabilities;
    use lumlab::gpu::depth_ranges::{RangePass, RangeTextures, block_texels};
    let gpu = gpu();
    let (device, queue) = (&gpu.device, &gpu.queue);
    let capabilities = Capabilities::of(&gpu.adapter, device);
    if !capabilities.depth_ranges {
        assert!(capabilities.gl, "only GL lacks the ranges");
        return;
    }
    // A sloped plane, a nearer occluder over 8×8 texels and a patch where
    // nothing was drawn (0, the far plane).
    let side = 64u32;
    let plane = |i: u32, j: u32| 0.5 + 0.003 * f64::from(i) - 0.002 * f64::from(j);
    let occluder = |i: u32, j: u32| (20..28).contains(&i) && (30..38).contains(&j);
    let undrawn = |i: u32, j: u32| (48..56).contains(&i) && (8..16).contains(&j);
    let stored = |i: u32, j: u32| match (occluder(i, j), undrawn(i, j)) {
        (true, _) => 0.9,
        (_, true) => 0.0,
        _ => plane(i, j) as f32,
    };
    let values: Vec<f32> = (0..side * side).map(|t| stored(t % side, t / side)).collect();
    let size = wgpu::Extent3d {
        width: side,
        height: side,
        depth_or_array_layers: 1,
    };
    // GL binds a texture of one layer as a plain 2D one, not an array.
    let layers = capabilities.array_layers(1);
    let depth = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("test depth values"),
        size: wgpu::Extent3d {
            depth_or_array_layers: layers,
            ..size
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::R32Float,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    queue.write_texture(
        depth.as_image_copy(),
        bytemuck::cast_slice(&values),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(4 * side),
            rows_per_image: Some(side),
        },
        size,
    );
    let view = depth.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        ..Default::default()
    });
    let level = 0;
    let b = block_texels(level);
    let mut ranges = RangeTextures::new(device, side, layers);
    let pass = RangePass::new(device, 1);
    let mut encoder = device.create_command_encoder(&Default::default());
    pass.encode(
        (device, queue),
        &mut encoder,
        (&view, &[0]),
        (&mut ranges, level),
        None,
    );
    queue.submit([encoder.finish()]);
    let windows = ranges.read_windows((device, queue), level, 0);
    let count = side / b;
    assert_eq!(windows.len(), (count * count) as usize);
    let mut planes = 0;
    for (e, bound) in windows.iter().enumerate() {
        let (ex, ey) = (e as u32 % count, e as u32 / count);
        let [c, gx, gy, w] = bound.map(f64::from);
        // The window's texels in the map (the last windows reach past it).
        let texels = (ey * b..(ey * b + 2 * b).min(side))
            .flat_map(|j| (ex * b..(ex * b + 2 * b).min(side)).map(move |i| (i, j)));
        let mut on_plane = true;
        for (i, j) in texels {
            let along = c + gx * f64::from(i - ex * b) + gy * f64::from(j - ey * b);
            let d = f64::from(stored(i, j));
            assert!(
                (d - along).abs() <= w,
                "window {ex}, {ey}: texel {i}, {j} holds {d}, bound {along} ± {w}"
            );
            on_plane &= !occluder(i, j) && !undrawn(i, j);
        }
        // Inside the map, a window that only the plane fills: the plane
        // itself, to rounding.
        if on_plane && ex + 1 < count && ey + 1 < count {
            planes += 1;
            assert!(w <= 4e-6, "window {ex}, {ey}: half-width {w} on one plane");
            assert!(
                (gx - 0.003).abs() < 1e-5 && (gy + 0.002).abs() < 1e-5,
                "window {ex}, {ey}: slope {gx}, {gy}"
            );
        }
    }
    assert!(planes > 150, "{planes} windows on the plane alone");
}
