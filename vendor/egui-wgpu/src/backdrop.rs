//! lumlab patch (see `LUMLAB-PATCH.md`): the paint jobs before the first
//! paint callback, the *backdrop* (panels, menus and whatever else lies under
//! an application's own drawing), are kept in a texture and copied to the
//! frame for as long as they stay the same. Only the callback and what is
//! painted after it are drawn again; when a few of the backdrop's triangles
//! change, only the pixels they touch are (`damage.rs`).
//!
//! Why: on a software rasterizer (Mesa's llvmpipe/lavapipe) every painted
//! pixel and every small triangle costs CPU time, and an application that
//! redraws its own view every frame (a drag) made egui raster unchanged side
//! panels each time. A texture copy is a `memcpy` there.

use epaint::{ClippedPrimitive, Primitive, TextureId};

use crate::damage::{Drawn, PixelRect, Redraw};
use crate::{Renderer, ScreenDescriptor};

/// The backdrop of one viewport, as last drawn.
#[derive(Default)]
pub struct BackdropCache {
    texture: Option<wgpu::Texture>,
    /// A texture of the same size holding only the clear colour: damaged
    /// rectangles are cleared by copies from it (a render pass clears a
    /// whole texture or nothing).
    blank: Option<wgpu::Texture>,
    /// The colour `blank` holds (None: not cleared yet).
    blank_colour: Option<[f32; 4]>,
    /// What was drawn into `texture`.
    drawn: Option<Drawn>,
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

impl BackdropCache {
    /// Puts the first `len` jobs (see [`backdrop_len`]) into `target`: drawn
    /// into the cache where they changed (everywhere when egui's textures
    /// did), then copied. `target` must allow copies into it; the caller
    /// then draws the other jobs over it with [`wgpu::LoadOp::Load`]. The
    /// renderer's buffers must hold `jobs` ([`Renderer::update_buffers`]).
    #[expect(clippy::too_many_arguments)]
    pub fn copy_to(
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
        let fits = |texture: &Option<wgpu::Texture>| {
            texture
                .as_ref()
                .is_some_and(|t| t.size() == target.size() && t.format() == target.format())
        };
        if !fits(&self.texture) || !fits(&self.blank) {
            self.drawn = None;
            self.blank_colour = None;
            let texture = |label| {
                device.create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size: target.size(),
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format: target.format(),
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                        | wgpu::TextureUsages::COPY_SRC
                        | wgpu::TextureUsages::COPY_DST,
                    view_formats: &[],
                })
            };
            self.texture = Some(texture("egui_backdrop"));
            self.blank = Some(texture("egui_backdrop_blank"));
        }
        let (Some(texture), Some(blank)) = (&self.texture, &self.blank) else {
            return;
        };
        let backdrop = &jobs[..len];
        let redraw = match &self.drawn {
            Some(drawn) if !textures_changed => drawn.redraw(backdrop, screen, clear),
            _ => Redraw::Full,
        };
        let within = match &redraw {
            Redraw::Nothing => None,
            Redraw::Full => {
                // The blank texture takes the clear colour when new or when it changed.
                if self.blank_colour != Some(clear) {
                    drop(begin_pass(encoder, blank, wgpu::LoadOp::Clear(color(clear))));
                    self.blank_colour = Some(clear);
                }
                let pass = begin_pass(encoder, texture, wgpu::LoadOp::Clear(color(clear)));
                Some((pass.forget_lifetime(), None))
            }
            Redraw::Damage(rects) => {
                for rect in rects {
                    copy_rect(encoder, blank, texture, rect);
                }
                let pass = begin_pass(encoder, texture, wgpu::LoadOp::Load);
                Some((pass.forget_lifetime(), Some(rects.as_slice())))
            }
        };
        if let Some((mut pass, within)) = within {
            renderer.render_range(&mut pass, jobs, screen, 0..len, within);
            drop(pass);
            self.drawn = Some(Drawn::new(backdrop, screen, clear));
        }
        encoder.copy_texture_to_texture(texture.as_image_copy(), target.as_image_copy(), target.size());
    }
}

/// The clear colour as a render pass takes it.
pub(crate) fn color(clear: [f32; 4]) -> wgpu::Color {
    let [r, g, b, a] = clear.map(f64::from);
    wgpu::Color { r, g, b, a }
}

fn begin_pass<'a>(
    encoder: &'a mut wgpu::CommandEncoder,
    texture: &wgpu::Texture,
    load: wgpu::LoadOp<wgpu::Color>,
) -> wgpu::RenderPass<'a> {
    let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("egui_backdrop"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: &view,
            resolve_target: None,
            ops: wgpu::Operations {
                load,
                store: wgpu::StoreOp::Store,
            },
            depth_slice: None,
        })],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}

/// Copies the pixels of `rect` from `from` to the same place in `to`.
fn copy_rect(encoder: &mut wgpu::CommandEncoder, from: &wgpu::Texture, to: &wgpu::Texture, rect: &PixelRect) {
    let origin = wgpu::Origin3d {
        x: rect.min[0],
        y: rect.min[1],
        z: 0,
    };
    let [width, height] = rect.size();
    let size = wgpu::Extent3d {
        width,
        height,
        depth_or_array_layers: 1,
    };
    encoder.copy_texture_to_texture(
        wgpu::TexelCopyTextureInfo {
            origin,
            ..from.as_image_copy()
        },
        wgpu::TexelCopyTextureInfo {
            origin,
            ..to.as_image_copy()
        },
        size,
    );
}
