//! Copying a texture back to the CPU (tests, the command line, the report),
//! blocking, or without blocking for the app ([`PendingRead`]).

use std::sync::Arc;
use std::sync::atomic::{AtomicU8, Ordering};

/// Reads mip 0, layer `layer` of `texture` into tightly packed rows of
/// `bytes_per_texel` bytes, row 0 at the top. Blocks until the GPU is done.
pub fn read_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    layer: u32,
    bytes_per_texel: u32,
) -> Vec<u8> {
    let origin = wgpu::Origin3d { x: 0, y: 0, z: layer };
    let size = (texture.width(), texture.height());
    let (buffer, padded, unpadded) = copy_to_buffer(device, queue, texture, origin, size, bytes_per_texel);
    map_and_read(device, &buffer, padded, unpadded)
}

/// Copies `size` texels at `origin` into a new mappable buffer (rows padded
/// to the copy alignment) and submits; returns it with the padded and
/// unpadded row lengths in bytes.
fn copy_to_buffer(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    origin: wgpu::Origin3d,
    (width, height): (u32, u32),
    bytes_per_texel: u32,
) -> (wgpu::Buffer, usize, usize) {
    let unpadded = width * bytes_per_texel;
    let padded = unpadded.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: (padded * height) as u64,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("readback"),
    });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin,
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
    queue.submit([encoder.finish()]);
    (buffer, padded as usize, unpadded as usize)
}

/// Maps a buffer of `rows × padded` bytes and keeps the first `unpadded` bytes of each row.
pub fn map_and_read(device: &wgpu::Device, buffer: &wgpu::Buffer, padded: usize, unpadded: usize) -> Vec<u8> {
    let slice = buffer.slice(..);
    let (sender, receiver) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = sender.send(r);
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .expect("the GPU device was lost while reading back");
    receiver
        .recv()
        .expect("map callback ran")
        .expect("buffer mapping failed");
    let data = slice.get_mapped_range().expect("buffer is mapped");
    let mut out = Vec::with_capacity(data.len() / padded.max(1) * unpadded);
    for row in data.chunks(padded) {
        out.extend_from_slice(&row[..unpadded]);
    }
    drop(data);
    buffer.unmap();
    out
}

/// A copy on its way back to the CPU, collected without blocking: the app
/// asks for it after a frame and picks it up on a later one.
pub struct PendingRead {
    device: wgpu::Device,
    buffer: wgpu::Buffer,
    state: Arc<AtomicU8>,
    padded: usize,
    unpadded: usize,
}

/// Where a [`PendingRead`] stands.
#[derive(Debug, PartialEq)]
pub enum ReadState<T> {
    Waiting,
    Ready(T),
    /// The mapping failed (device lost); the data will not come.
    Failed,
}

const WAITING: u8 = 0;
const MAPPED: u8 = 1;
const FAILED: u8 = 2;
/// The bytes were handed out; a later poll gives `Failed`.
const TAKEN: u8 = 3;

impl PendingRead {
    /// Starts copying the `size` texels at `origin` of mip 0, layer 0.
    pub fn texture_region(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        texture: &wgpu::Texture,
        origin: (u32, u32),
        size: (u32, u32),
        bytes_per_texel: u32,
    ) -> Self {
        let origin = wgpu::Origin3d {
            x: origin.0,
            y: origin.1,
            z: 0,
        };
        let (buffer, padded, unpadded) =
            copy_to_buffer(device, queue, texture, origin, size, bytes_per_texel);
        Self::map(device, buffer, padded, unpadded)
    }

    /// Starts copying the first `size` bytes of `source`.
    pub fn buffer(device: &wgpu::Device, queue: &wgpu::Queue, source: &wgpu::Buffer, size: u64) -> Self {
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("async readback"),
            size,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("async readback"),
        });
        encoder.copy_buffer_to_buffer(source, 0, &buffer, 0, size);
        queue.submit([encoder.finish()]);
        Self::map(device, buffer, size as usize, size as usize)
    }

    fn map(device: &wgpu::Device, buffer: wgpu::Buffer, padded: usize, unpadded: usize) -> Self {
        let state = Arc::new(AtomicU8::new(WAITING));
        let done = Arc::clone(&state);
        buffer.slice(..).map_async(wgpu::MapMode::Read, move |result| {
            let value = if result.is_ok() { MAPPED } else { FAILED };
            done.store(value, Ordering::Release);
        });
        Self {
            device: device.clone(),
            buffer,
            state,
            padded,
            unpadded,
        }
    }

    /// Polls the device without waiting; the bytes (rows unpadded) once they
    /// are here. `Ready` comes once.
    pub fn poll(&self) -> ReadState<Vec<u8>> {
        let _ = self.device.poll(wgpu::PollType::Poll);
        match self.state.load(Ordering::Acquire) {
            WAITING => ReadState::Waiting,
            MAPPED => {
                let Ok(data) = self.buffer.slice(..).get_mapped_range() else {
                    return ReadState::Failed;
                };
                let mut out = Vec::with_capacity(data.len() / self.padded.max(1) * self.unpadded);
                for row in data.chunks(self.padded.max(1)) {
                    out.extend_from_slice(&row[..self.unpadded.min(row.len())]);
                }
                drop(data);
                self.buffer.unmap();
                self.state.store(TAKEN, Ordering::Release);
                ReadState::Ready(out)
            }
            _ => ReadState::Failed,
        }
    }
}
