//! The kept backdrop of the window (vendor/egui-wgpu's lumlab patch,
//! `backdrop.rs`): egui's paint jobs under the first paint callback (the
//! panels under the viewport image) are copied from the last frame instead of
//! rastered again, for as long as nothing that decides their pixels changes.
//! What is kept; that every input of those pixels is seen as a change; which
//! changes redraw only their damage (`damage.rs`), and that a damaged redraw
//! gives the very pixels of a full one.

use std::sync::Arc;

use egui::epaint::{ClippedPrimitive, Primitive};
use egui::{Color32, Mesh, PaintCallback, Pos2, Rect, TextureId, pos2, vec2};
use egui_wgpu::ScreenDescriptor;
use egui_wgpu::backdrop::{BackdropCache, backdrop_len};
use egui_wgpu::damage::{Drawn, PixelRect, Redraw};

fn mesh(texture_id: TextureId, colour: Color32) -> ClippedPrimitive {
    let mut mesh = Mesh::with_texture(texture_id);
    mesh.add_rect_with_uv(
        Rect::from_min_max(pos2(1.0, 2.0), pos2(30.0, 40.0)),
        Rect::from_min_max(Pos2::ZERO, pos2(1.0, 1.0)),
        colour,
    );
    ClippedPrimitive {
        clip_rect: Rect::from_min_max(Pos2::ZERO, pos2(100.0, 100.0)),
        primitive: Primitive::Mesh(mesh),
    }
}

fn panel() -> ClippedPrimitive {
    mesh(TextureId::Managed(0), Color32::WHITE)
}

fn callback() -> ClippedPrimitive {
    ClippedPrimitive {
        clip_rect: Rect::from_min_max(Pos2::ZERO, pos2(100.0, 100.0)),
        primitive: Primitive::Callback(PaintCallback {
            rect: Rect::from_min_max(pos2(10.0, 10.0), pos2(90.0, 90.0)),
            callback: Arc::new(()),
        }),
    }
}

fn screen() -> ScreenDescriptor {
    ScreenDescriptor {
        size_in_pixels: [100, 100],
        pixels_per_point: 1.0,
    }
}

#[test]
fn the_backdrop_ends_at_the_first_callback() {
    assert_eq!(backdrop_len(&[]), 0);
    assert_eq!(backdrop_len(&[panel(), panel()]), 0, "no callback: nothing kept");
    assert_eq!(
        backdrop_len(&[panel(), panel(), callback(), panel(), callback()]),
        2
    );
    assert_eq!(backdrop_len(&[callback(), panel()]), 0);
}

#[test]
fn a_user_texture_under_the_callback_is_never_kept() {
    let user = mesh(TextureId::User(7), Color32::WHITE);
    assert_eq!(backdrop_len(&[panel(), user, callback()]), 0);
    let over = mesh(TextureId::User(7), Color32::WHITE);
    assert_eq!(backdrop_len(&[panel(), callback(), over]), 1);
}

#[test]
fn every_input_of_the_pixels_is_a_change() {
    let clear = [0.1, 0.1, 0.1, 1.0];
    let drawn = Drawn::new(&[panel(), panel()], &screen(), clear);
    let redraw =
        |jobs: &[ClippedPrimitive], screen: &ScreenDescriptor, clear| drawn.redraw(jobs, screen, clear);
    assert_eq!(
        redraw(&[panel(), panel()], &screen(), clear),
        Redraw::Nothing,
        "the same jobs"
    );
    // Within a mesh: its damage, the rectangle of its quad (1, 2)–(30, 40).
    let quad = Redraw::Damage(vec![PixelRect {
        min: [1, 2],
        max: [30, 40],
    }]);
    let recoloured = mesh(TextureId::Managed(0), Color32::RED);
    assert_eq!(redraw(&[panel(), recoloured], &screen(), clear), quad, "a vertex");
    let mut moved = panel();
    if let Primitive::Mesh(mesh) = &mut moved.primitive {
        mesh.vertices[3].pos.x += 0.5;
    }
    assert_eq!(
        redraw(&[panel(), moved], &screen(), clear),
        Redraw::Damage(vec![PixelRect {
            min: [1, 2],
            max: [31, 40]
        }]),
        "a position: the old and the new second triangle"
    );
    let mut reindexed = panel();
    if let Primitive::Mesh(mesh) = &mut reindexed.primitive {
        mesh.indices.swap(0, 1);
    }
    assert_eq!(
        redraw(&[panel(), reindexed], &screen(), clear),
        quad,
        "the indices"
    );
    // Anything else: a full redraw.
    let other_texture = mesh(TextureId::Managed(1), Color32::WHITE);
    assert_eq!(
        redraw(&[panel(), other_texture], &screen(), clear),
        Redraw::Full,
        "the texture"
    );
    let mut clipped = panel();
    clipped.clip_rect.max.y = 50.0;
    assert_eq!(
        redraw(&[panel(), clipped], &screen(), clear),
        Redraw::Full,
        "the clip rectangle"
    );
    assert_eq!(redraw(&[panel()], &screen(), clear), Redraw::Full, "a job less");
    let larger = ScreenDescriptor {
        size_in_pixels: [100, 120],
        ..screen()
    };
    assert_eq!(
        redraw(&[panel(), panel()], &larger, clear),
        Redraw::Full,
        "the window's size"
    );
    let zoomed = ScreenDescriptor {
        pixels_per_point: 1.25,
        ..screen()
    };
    assert_eq!(
        redraw(&[panel(), panel()], &zoomed, clear),
        Redraw::Full,
        "the scale"
    );
    assert_eq!(
        redraw(&[panel(), panel()], &screen(), [0.2, 0.1, 0.1, 1.0]),
        Redraw::Full,
        "the clear colour"
    );
}

/// A mesh of `n` small quads in a row (like a line of glyphs), the `k`-th
/// of them coloured `colour` and the others white.
fn row_of_quads(n: usize, k: usize, colour: Color32) -> ClippedPrimitive {
    let mut mesh = Mesh::with_texture(TextureId::Managed(0));
    for i in 0..n {
        let min = pos2(2.0 + 6.0 * i as f32, 10.0);
        let colour = if i == k { colour } else { Color32::WHITE };
        mesh.add_rect_with_uv(
            Rect::from_min_size(min, vec2(5.0, 8.0)),
            Rect::from_min_max(Pos2::ZERO, pos2(1.0, 1.0)),
            colour,
        );
    }
    ClippedPrimitive {
        clip_rect: Rect::from_min_max(Pos2::ZERO, pos2(100.0, 100.0)),
        primitive: Primitive::Mesh(mesh),
    }
}

#[test]
fn a_change_in_one_small_region_damages_that_region_only() {
    let clear = [0.1, 0.1, 0.1, 1.0];
    let zoomed = ScreenDescriptor {
        size_in_pixels: [150, 150],
        pixels_per_point: 1.5,
    };
    let drawn = Drawn::new(&[panel(), row_of_quads(12, 99, Color32::RED)], &zoomed, clear);
    // The fifth quad, (26, 10)–(31, 18) points: in pixels ×1.5, outwards.
    assert_eq!(
        drawn.redraw(&[panel(), row_of_quads(12, 4, Color32::RED)], &zoomed, clear),
        Redraw::Damage(vec![PixelRect {
            min: [39, 15],
            max: [47, 27]
        }])
    );
    // One quad more at the end (text grew by a glyph): that quad only.
    assert_eq!(
        drawn.redraw(&[panel(), row_of_quads(13, 99, Color32::RED)], &zoomed, clear),
        Redraw::Damage(vec![PixelRect {
            min: [111, 15],
            max: [119, 27]
        }])
    );
    // Damages that overlap merge, so that no pixel is drawn twice.
    let first = Drawn::new(&[row_of_quads(12, 99, Color32::RED), panel()], &screen(), clear);
    let Redraw::Damage(rects) = first.redraw(
        &[
            row_of_quads(12, 0, Color32::RED),
            mesh(TextureId::Managed(0), Color32::RED),
        ],
        &screen(),
        clear,
    ) else {
        panic!("a damage");
    };
    assert_eq!(
        rects,
        vec![PixelRect {
            min: [1, 2],
            max: [30, 40]
        }]
    );
}

#[test]
fn a_change_of_structure_redraws_everything() {
    let clear = [0.1, 0.1, 0.1, 1.0];
    let drawn = Drawn::new(&[panel(), panel()], &screen(), clear);
    assert_eq!(
        drawn.redraw(&[panel(), panel(), panel()], &screen(), clear),
        Redraw::Full,
        "a job more"
    );
    assert_eq!(
        drawn.redraw(&[panel(), callback()], &screen(), clear),
        Redraw::Full,
        "a callback in place of a mesh"
    );
}

/// A side panel as egui lays it out: labels, a slider at `value`, its
/// derived value; the paint jobs and the texture changes of one pass.
fn panel_frame(ctx: &egui::Context, mut value: f32) -> (Vec<ClippedPrimitive>, egui::TexturesDelta) {
    let input = egui::RawInput {
        screen_rect: Some(Rect::from_min_size(Pos2::ZERO, vec2(240.0, 160.0))),
        ..Default::default()
    };
    let output = ctx.run_ui(input, |ui| {
        ui.heading("Light");
        ui.add(egui::Slider::new(&mut value, 0.0..=10.0).text("radius"));
        ui.label(format!("L_e = {:.4} W/m²/sr", 1.0 / (1.0 + value)));
        ui.label("A line that stays");
    });
    (
        ctx.tessellate(output.shapes, output.pixels_per_point),
        output.textures_delta,
    )
}

#[test]
fn a_damaged_redraw_gives_the_pixels_of_a_full_one() {
    let gpu = lumlab::gpu::context::GpuContext::headless().expect("a GPU adapter");
    let (device, queue) = (&gpu.device, &gpu.queue);
    let format = wgpu::TextureFormat::Rgba8Unorm;
    let mut renderer = egui_wgpu::Renderer::new(device, format, egui_wgpu::RendererOptions::PREDICTABLE);
    let screen = ScreenDescriptor {
        size_in_pixels: [360, 240],
        pixels_per_point: 1.5,
    };
    let clear = [0.15, 0.15, 0.17, 1.0];
    let ctx = egui::Context::default();
    // egui settles its layout over a first pass.
    let (_, delta_first) = panel_frame(&ctx, 2.0);
    let (before, delta_before) = panel_frame(&ctx, 2.0);
    let (after, delta_after) = panel_frame(&ctx, 3.5);
    for mut textures in [delta_first, delta_before, delta_after] {
        for (id, deltas) in &textures.set {
            for delta in deltas {
                renderer.update_texture(device, queue, *id, delta);
            }
        }
        // Applied (nothing is freed here): debug builds check that no delta is dropped unseen.
        textures.clear();
    }
    let Redraw::Damage(rects) = Drawn::new(&before, &screen, clear).redraw(&after, &screen, clear) else {
        panic!("the slider's move is a damage");
    };
    let damaged: u32 = rects
        .iter()
        .map(|r| (r.max[0] - r.min[0]) * (r.max[1] - r.min[1]))
        .sum();
    assert!(damaged < 360 * 240 / 3, "a small part of the panel: {rects:?}");

    let target = || {
        device.create_texture(&wgpu::TextureDescriptor {
            label: Some("frame"),
            size: wgpu::Extent3d {
                width: 360,
                height: 240,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::COPY_DST
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        })
    };
    let mut draw = |cache: &mut BackdropCache, jobs: &[ClippedPrimitive], target: &wgpu::Texture| {
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        let extra = renderer.update_buffers(device, queue, &mut encoder, jobs, &screen);
        cache.copy_to(
            device,
            &mut encoder,
            &renderer,
            jobs,
            jobs.len(),
            &screen,
            clear,
            false,
            target,
        );
        queue.submit(extra.into_iter().chain([encoder.finish()]));
        lumlab::gpu::readback::read_texture(device, queue, target, 0, 4)
    };
    let (damaged_frame, full_frame) = (target(), target());
    let mut kept = BackdropCache::default();
    let first = draw(&mut kept, &before, &damaged_frame);
    let damaged_redraw = draw(&mut kept, &after, &damaged_frame);
    let full_redraw = draw(&mut BackdropCache::default(), &after, &full_frame);
    assert_ne!(first, full_redraw, "the slider moved");
    let differing = damaged_redraw
        .chunks(4)
        .zip(full_redraw.chunks(4))
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(
        differing, 0,
        "pixels differing between a damaged and a full redraw"
    );
}
