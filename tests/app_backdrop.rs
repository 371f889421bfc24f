//! The kept backdrop of the window (vendor/egui-wgpu's lumlab patch,
//! `backdrop.rs`): egui's paint jobs under the first paint callback (the
//! panels under the viewport image) are copied from the last frame instead of
//! rastered again, for as long as nothing that decides their pixels changes.
//! What is kept, and that every input of those pixels changes the key that
//! decides whether the copy is still good.

use std::sync::Arc;

use egui::epaint::{ClippedPrimitive, Primitive};
use egui::{Color32, Mesh, PaintCallback, Pos2, Rect, TextureId, pos2};
use egui_wgpu::ScreenDescriptor;
use egui_wgpu::backdrop::{backdrop_key, backdrop_len};

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
fn every_input_of_the_pixels_changes_the_key() {
    let clear = [0.1, 0.1, 0.1, 1.0];
    let key = |jobs: &[ClippedPrimitive], screen: &ScreenDescriptor, clear| backdrop_key(jobs, screen, clear);
    let base = key(&[panel(), panel()], &screen(), clear);
    assert_eq!(base, key(&[panel(), panel()], &screen(), clear), "deterministic");

    let recoloured = mesh(TextureId::Managed(0), Color32::RED);
    assert_ne!(base, key(&[panel(), recoloured], &screen(), clear), "a vertex");
    let mut moved = panel();
    if let Primitive::Mesh(mesh) = &mut moved.primitive {
        mesh.vertices[2].pos.x += 0.5;
    }
    assert_ne!(base, key(&[panel(), moved], &screen(), clear), "a position");
    let mut reindexed = panel();
    if let Primitive::Mesh(mesh) = &mut reindexed.primitive {
        mesh.indices.swap(0, 1);
    }
    assert_ne!(base, key(&[panel(), reindexed], &screen(), clear), "the indices");
    let other_texture = mesh(TextureId::Managed(1), Color32::WHITE);
    assert_ne!(
        base,
        key(&[panel(), other_texture], &screen(), clear),
        "the texture"
    );
    let mut clipped = panel();
    clipped.clip_rect.max.y = 50.0;
    assert_ne!(
        base,
        key(&[panel(), clipped], &screen(), clear),
        "the clip rectangle"
    );
    assert_ne!(base, key(&[panel()], &screen(), clear), "a job less");
    let larger = ScreenDescriptor {
        size_in_pixels: [100, 120],
        ..screen()
    };
    assert_ne!(
        base,
        key(&[panel(), panel()], &larger, clear),
        "the window's size"
    );
    let zoomed = ScreenDescriptor {
        pixels_per_point: 1.25,
        ..screen()
    };
    assert_ne!(base, key(&[panel(), panel()], &zoomed, clear), "the scale");
    assert_ne!(
        base,
        key(&[panel(), panel()], &screen(), [0.2, 0.1, 0.1, 1.0]),
        "the clear colour"
    );
}
