//! What a renderer's last frame holds, read back: its float targets (the
//! quantity and, where the frame wrote it, the aux target), its displayed
//! image and its false-colour scale, at once or without blocking; and the
//! reads a ray-traced mean's noise is measured on (`gpu::noise`).

use super::Renderer;
use crate::gpu::readback::{PendingRead, read_texture};
use crate::gpu::targets::{FloatTarget, PendingScale, PendingTexels, decode_float_texels};

impl Renderer {
    fn read_float_target(&self, texture: &wgpu::Texture) -> Vec<[f32; 4]> {
        let bytes_per_texel = texture.format().block_copy_size(None).unwrap_or(16);
        let bytes = read_texture(&self.device, &self.queue, texture, 0, bytes_per_texel);
        decode_float_texels(&bytes, bytes_per_texel)
    }

    /// Starts reading a rectangle of the last frame's quantity or aux target
    /// without blocking (the app's pixel probe and error statistics); None
    /// before the first frame, when the rectangle leaves the image or when
    /// the last frame did not write the aux target asked for.
    pub fn request_texels(
        &self,
        target: FloatTarget,
        origin: (u32, u32),
        size: (u32, u32),
    ) -> Option<PendingTexels> {
        let t = self.targets.as_ref()?;
        let fits = |o: u32, s: u32, side: u32| s > 0 && o.checked_add(s).is_some_and(|end| end <= side);
        if !(fits(origin.0, size.0, t.size.0) && fits(origin.1, size.1, t.size.1)) {
            return None;
        }
        let texture = match target {
            FloatTarget::Quantity => &t.quantity,
            FloatTarget::Aux if self.aux_written => &t.aux,
            FloatTarget::Aux => return None,
        };
        let bytes_per_texel = texture.format().block_copy_size(None).unwrap_or(16);
        Some(PendingTexels {
            read: PendingRead::texture_region(
                &self.device,
                &self.queue,
                texture,
                origin,
                size,
                bytes_per_texel,
            ),
            bytes_per_texel,
        })
    }

    /// Starts reading the last false-colour scale (see [`Self::read_scale`])
    /// without blocking.
    pub fn request_scale(&self) -> PendingScale {
        PendingScale(PendingRead::buffer(
            &self.device,
            &self.queue,
            self.display.scale_buffer(),
            16,
        ))
    }

    /// The last frame's view quantity, row-major from the top (W/m²/sr for `shaded`).
    pub fn read_quantity(&self) -> Vec<[f32; 4]> {
        self.targets
            .as_ref()
            .map_or_else(Vec::new, |t| self.read_float_target(&t.quantity))
    }

    /// The last frame's aux target: V, texel density, cos θ, coverage
    /// (empty when the frame did not write it, see [`crate::gpu::ShadeOptions::aux`]).
    pub fn read_aux(&self) -> Vec<[f32; 4]> {
        self.targets
            .as_ref()
            .filter(|_| self.aux_written)
            .map_or_else(Vec::new, |t| self.read_float_target(&t.aux))
    }

    /// The last frame's displayed image.
    pub fn read_display(&self) -> image::RgbaImage {
        let Some(t) = &self.targets else {
            return image::RgbaImage::new(0, 0);
        };
        let bytes = read_texture(&self.device, &self.queue, &t.display, 0, 4);
        image::RgbaImage::from_raw(t.size.0, t.size.1, bytes).unwrap_or_default()
    }

    /// The largest value of the last false-colour view (its scale).
    pub fn read_scale(&self) -> f32 {
        self.display.read_scale(&self.device, &self.queue)
    }

    /// After a frame: starts reading the quantity back where the noise
    /// probe measures the ray-traced mean (a sphere light's, at powers of
    /// two and at its last frame).
    pub(super) fn read_for_noise(&mut self) {
        let _ = self.noise.poll();
        let Some(a) = self.raytrace.accumulation().filter(|a| a.noise_bound > 0.0) else {
            return;
        };
        let Some(size) = self.targets.as_ref().map(|t| t.size) else {
            return;
        };
        if self.noise.wants(a.run, a.frames, a.is_complete())
            && let Some(texels) = self.request_texels(FloatTarget::Quantity, (0, 0), size)
        {
            self.noise.read(a.frames, texels);
        }
    }

    /// Picks up the noise probe's read once it is back, without blocking;
    /// true while one is on its way.
    pub fn poll_noise(&mut self) -> bool {
        self.noise.poll()
    }

    /// Waits for the noise probe's read (the command line, the tests).
    pub fn settle_noise(&mut self) {
        let _ = self.device.poll(wgpu::PollType::wait_indefinitely());
        self.noise.poll();
    }
}
