//! lumlab patch (see `LUMLAB-PATCH.md`): the paint jobs before the first
//! paint callback, the *backdrop* (panels, menus and whatever else lies under
//! an application's own drawing), are kept in a texture and copied to the
//! frame for as long as they stay the same. Only the callback and what is
//! painted after it are drawn again.
//!
//! Why: on a software rasterizer (Mesa's llvmpipe/lavapipe) every painted
//! pixel and every small triangle costs CPU time, and an application that
//! redraws its own view every frame (a drag) made egui raster unchanged side
//! panels each time. A texture copy is a `memcpy` there.

use std::hash::{Hash as _, Hasher as _};

use epaint::{ClippedPrimitive, Primitive, TextureId};

use crate::{Renderer, ScreenDescriptor};

/// The backdrop of one viewport, as last drawn.
#[derive(Default)]
pub(crate) struct BackdropCache {
    texture: Option<wgpu::Texture>,
    /// What was drawn into `texture` (see [`backdrop_key`]).
    key: Option<u64>,
}

/// The number of leading paint jobs that form a cacheable backdrop: those
/// before the first paint callback, or 0 where there is no callback or one of
/// them samples a user texture (whose content can change without egui
/// knowing; egui's own textures change only through its texture deltas).
pub fn backdrop_len(jobs: &[ClippedPrimitive]) -> usize {
    let Some(first_callback) = jobs
        .iter()
        .position(|job| matches!(job.primitive, Primitive::Callback(_)))
    else {
        return 0;
    };
    let samples_user_texture = jobs[..first_callback].iter().any(|job| {
        matches!(&job.primitive, Primitive::Mesh(mesh) if matches!(mesh.texture_id, TextureId::User(_)))
    });
    if samples_user_texture { 0 } else { first_callback }
}

/// A hash of everything that decides the backdrop's pixels: the jobs' clip
/// rectangles, textures, vertices and indices (with their counts, so that no
/// two splits of the same bytes collide), the target's size and scale and
/// the clear colour.
pub fn backdrop_key(jobs: &[ClippedPrimitive], screen: &ScreenDescriptor, clear: [f32; 4]) -> u64 {
    let mut hasher = ahash::AHasher::default();
    screen.size_in_pixels.hash(&mut hasher);
    screen.pixels_per_point.to_bits().hash(&mut hasher);
    clear.map(f32::to_bits).hash(&mut hasher);
    for ClippedPrimitive { clip_rect, primitive } in jobs {
        [clip_rect.min, clip_rect.max]
            .map(|p| [p.x.to_bits(), p.y.to_bits()])
            .hash(&mut hasher);
        if let Primitive::Mesh(mesh) = primitive {
            mesh.texture_id.hash(&mut hasher);
            [mesh.indices.len(), mesh.vertices.len()].hash(&mut hasher);
            hasher.write(bytemuck::cast_slice(&mesh.indices));
            hasher.write(bytemuck::cast_slice(&mesh.vertices));
        }
    }
    hasher.finish()
}

impl BackdropCache {
    /// Puts the first `len` jobs (see [`backdrop_len`]) into `target`: drawn
    /// into the cache when they changed (or egui's textures did), then copied.
    /// `target` must allow copies into it; the caller then draws the other
    /// jobs over it with [`wgpu::LoadOp::Load`].
    #[expect(clippy::too_many_arguments)]
    pub(crate) fn copy_to(
        &mut self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        renderer: &Renderer,
        jobs: &[ClippedPrimitive],
        len: usize,
        screen: &ScreenDescriptor,
        clear: [f32; 4],
        textures_changed: bool,
        target: &wgpu::Texture,
    ) {
        let fits =
            |texture: &wgpu::Texture| texture.size() == target.size() && texture.format() == target.format();
        if !self.texture.as_ref().is_some_and(fits) {
            self.key = None;
            self.texture = Some(device.create_texture(&wgpu::TextureDescriptor {
                label: Some("egui_backdrop"),
                size: target.size(),
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: target.format(),
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            }));
        }
        let Some(texture) = &self.texture else {
            return;
        };
        let key = backdrop_key(&jobs[..len], screen, clear);
        if textures_changed || self.key != Some(key) {
            let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
            let [r, g, b, a] = clear.map(f64::from);
            let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("egui_backdrop"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &view,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a }),
                        store: wgpu::StoreOp::Store,
                    },
                    depth_slice: None,
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            renderer.render_range(&mut pass.forget_lifetime(), jobs, screen, 0..len);
            self.key = Some(key);
        }
        encoder.copy_texture_to_texture(texture.as_image_copy(), target.as_image_copy(), target.size());
    }
}
