//! Copying a texture back to the CPU (tests, the command line, the report).

/// Reads mip 0, layer `layer` of `texture` into tightly packed rows of
/// `bytes_per_texel` bytes, row 0 at the top. Blocks until the GPU is done.
pub fn read_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    layer: u32,
    bytes_per_texel: u32,
) -> Vec<u8> {
    let (width, height) = (texture.width(), texture.height());
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
            origin: wgpu::Origin3d { x: 0, y: 0, z: layer },
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
    map_and_read(device, &buffer, padded as usize, unpadded as usize)
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
