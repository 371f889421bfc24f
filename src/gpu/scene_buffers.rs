//! A scene uploaded to the GPU: one vertex and one index buffer for every
//! object, the materials as a storage buffer and the base-colour textures as
//! one texture array; once they are built, the simplified meshes that drag
//! frames of a large scene draw ([`crate::scene::simplify`]), as a second
//! index buffer over the same vertices.

use super::bvh::{FlatBvh, GpuBvh, caster_triangles};
use super::bvh_build::BvhBuild;
use super::specialise::SceneAttributes;
use super::uniforms::{
    DYNAMIC_STRIDE, MATERIAL_DOUBLE_SIDED, MATERIAL_NO_SHADOWS_RECEIVED, MATERIAL_OWN_K, MATERIAL_OWN_M,
    MaterialRaw, MaterialWordsRaw,
};
use crate::physics::brdf::Normalization;
use crate::scene::simplify::SimplifiedMeshes;
use crate::scene::{Aabb, Material, Scene};
use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt;

/// A vertex as the shaders read it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct Vertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub uv: [f32; 2],
    /// The vertex colour multiplying the base colour (1 without one).
    pub colour: [f32; 3],
}

impl Vertex {
    pub const ATTRIBUTES: [wgpu::VertexAttribute; 4] = wgpu::vertex_attr_array![
        0 => Float32x3, 1 => Float32x3, 2 => Float32x2, 3 => Float32x3
    ];

    /// The full layout (camera pass).
    pub fn layout() -> wgpu::VertexBufferLayout<'static> {
        wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<Vertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &Self::ATTRIBUTES,
        }
    }

    /// Positions only (shadow pass).
    pub fn position_layout() -> wgpu::VertexBufferLayout<'static> {
        wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<Vertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &Self::ATTRIBUTES[..1],
        }
    }
}

/// One object's range in the shared buffers, and its material's slot.
#[derive(Clone, Copy, Debug)]
pub struct Draw {
    pub first_index: u32,
    pub index_count: u32,
    pub base_vertex: i32,
    /// The object's slot in the materials buffer: 2 i for material i, 2 i + 1
    /// where the object receives no shadows ([`Meshes::material_offset`]).
    pub slot: u32,
}

/// The materials buffer's bytes: two slots a material, [`DYNAMIC_STRIDE`]
/// bytes apart: 2 i for an object that receives shadows, 2 i + 1, with
/// [`MATERIAL_NO_SHADOWS_RECEIVED`] set, for one that does not. The camera
/// pass binds an object's slot for its draw, so its vertex stage reads the
/// material as a uniform: a software rasterizer loads a storage buffer at a
/// per-vertex index lane by lane, a uniform once (the engine's vertex stage
/// 24.8 → 13.0 M instructions).
fn material_slots(materials: &[MaterialRaw]) -> Vec<u8> {
    let slot = DYNAMIC_STRIDE as usize;
    let mut bytes = vec![0; 2 * slot * materials.len()];
    for (raw, pair) in materials.iter().zip(bytes.chunks_exact_mut(2 * slot)) {
        let mut unshadowed = *raw;
        unshadowed.words.flags |= MATERIAL_NO_SHADOWS_RECEIVED;
        for (m, out) in [*raw, unshadowed].iter().zip(pair.chunks_exact_mut(slot)) {
            out[..std::mem::size_of::<MaterialRaw>()].copy_from_slice(bytemuck::bytes_of(m));
        }
    }
    bytes
}

/// What a pass draws: the scene's vertices through one index buffer, an
/// object a range of it (the full meshes, or the simplified ones).
#[derive(Clone, Copy)]
pub struct Meshes<'a> {
    vertices: &'a wgpu::Buffer,
    indices: &'a wgpu::Buffer,
    draws: &'a [Draw],
}

impl Meshes<'_> {
    pub fn bind(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        pass.set_index_buffer(self.indices.slice(..), wgpu::IndexFormat::Uint32);
    }

    /// The dynamic offset that binds object `i`'s material slot.
    pub fn material_offset(&self, i: usize) -> wgpu::DynamicOffset {
        self.draws[i].slot * DYNAMIC_STRIDE as u32
    }

    /// Draws object `i` (the pass has the buffers bound).
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>, i: usize) {
        let d = self.draws[i];
        if d.index_count > 0 {
            pass.draw_indexed(d.first_index..d.first_index + d.index_count, d.base_vertex, 0..1);
        }
    }
}

/// One simplified copy on the GPU: its indices into the scene's vertices
/// and each object's range.
struct SimplifiedBuffers {
    indices: wgpu::Buffer,
    draws: Vec<Draw>,
}

/// The simplified meshes on the GPU: the camera pass's copy, the
/// shadow pass's coarser one, and the BVH of the camera's copy.
struct Simplified {
    camera: SimplifiedBuffers,
    casters: SimplifiedBuffers,
    bvh: GpuBvh,
    triangles: usize,
}

/// What decides the materials' colours: the illuminant (None: RGB) and,
/// under one, the colour model.
pub type ColourKey = (Option<crate::colour::Illuminant>, crate::colour::ColourModel);

/// Side of the texture array's layers (texels).
const MAX_TEXTURE_SIDE: u32 = 2048;

pub struct GpuScene {
    pub vertices: wgpu::Buffer,
    /// Vertex colours (the objects without are uploaded as 1) and
    /// textures the camera pass must read.
    pub attributes: SceneAttributes,
    pub indices: wgpu::Buffer,
    pub draws: Vec<Draw>,
    /// Per object: its bounds when it casts shadows.
    pub caster_bounds: Vec<Option<Aabb>>,
    /// Per object: its bounds.
    pub bounds: Vec<Aabb>,
    pub materials: wgpu::Buffer,
    /// What `materials` holds, and each material's name and RGB base colour:
    /// under a spectral light the colours are replaced (see [`Self::write_colours`]).
    materials_raw: Vec<MaterialRaw>,
    pub material_colours: Vec<(String, glam::DVec3)>,
    /// The colours last written, for the colour settings of this key.
    colours_written: Option<ColourKey>,
    /// The normalization whose N(own m) the materials buffer holds (see
    /// [`Self::write_norm_factors`]).
    norm_written: Option<Normalization>,
    pub textures: wgpu::Texture,
    pub texture_view: wgpu::TextureView,
    pub triangle_count: usize,
    /// The shadow casters' BVH, for the ray-traced visibility: uploaded by
    /// [`Self::bvh`] once `bvh_build` hands it over (see [`BvhBuild`]).
    bvh: std::sync::OnceLock<GpuBvh>,
    bvh_build: BvhBuild,
    /// Bound in its place until then.
    no_bvh: GpuBvh,
    /// Set by [`Self::set_simplified`] (large scenes only).
    simplified: Option<Simplified>,
}

impl GpuScene {
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &Scene,
        caps: &super::Capabilities,
    ) -> Self {
        let mut vertices = Vec::new();
        let mut indices: Vec<u32> = Vec::new();
        let mut draws = Vec::with_capacity(scene.objects.len());
        // The materials buffer holds the scene's materials, then the default
        // one: an object whose index is out of range gets the default, as in
        // the reference (and `Scene::material_of`).
        let default_material = Material::default();
        let fallback = scene.materials.len();
        for object in &scene.objects {
            let mesh = &object.mesh;
            let material = object.material.min(fallback) as u32;
            draws.push(Draw {
                first_index: indices.len() as u32,
                index_count: mesh.indices.len() as u32,
                base_vertex: vertices.len() as i32,
                slot: 2 * material + u32::from(!object.receives_shadows),
            });
            indices.extend_from_slice(&mesh.indices);
            vertices.extend(mesh.positions.iter().enumerate().map(|(i, p)| {
                Vertex {
                    position: p.to_array(),
                    // Missing: zero, which the camera pass replaces by the face
                    // normal, as the reference does.
                    normal: mesh
                        .normals
                        .get(i)
                        .copied()
                        .unwrap_or(glam::Vec3::ZERO)
                        .to_array(),
                    uv: mesh.uvs.get(i).copied().unwrap_or_default().to_array(),
                    colour: mesh.colours.get(i).copied().unwrap_or(glam::Vec3::ONE).to_array(),
                }
            }));
        }
        let buffer = |label: &str, contents: &[u8], usage: wgpu::BufferUsages| {
            buffer_init(device, label, contents, usage)
        };
        let (textures, layer_of) = upload_textures(device, queue, scene, caps);
        let materials: Vec<MaterialRaw> = scene
            .materials
            .iter()
            .chain([&default_material])
            .map(|m| MaterialRaw {
                base_color: m.base_color.to_array(),
                words: MaterialWordsRaw {
                    own_k: m.k.unwrap_or(0.0),
                    own_m: m.m.unwrap_or(0.0),
                    texture_layer_plus_one: m
                        .base_color_texture
                        .and_then(|t| layer_of.get(t).copied())
                        .map_or(0, |l| l + 1),
                    flags: [
                        (m.k.is_some(), MATERIAL_OWN_K),
                        (m.m.is_some(), MATERIAL_OWN_M),
                        (m.double_sided, MATERIAL_DOUBLE_SIDED),
                    ]
                    .into_iter()
                    .filter_map(|(set, flag)| set.then_some(flag))
                    .fold(0, |flags, flag| flags | flag),
                },
                other_model_color: m.base_color.to_array(),
            })
            .collect();
        let material_colours = scene
            .materials
            .iter()
            .chain([&default_material])
            .map(|m| (m.name.clone(), m.base_color.truncate().as_dvec3()))
            .collect();
        Self {
            attributes: SceneAttributes {
                vertex_colours: scene.objects.iter().any(|o| !o.mesh.colours.is_empty()),
                textures: materials.iter().any(|m| m.words.texture_layer_plus_one > 0),
            },
            vertices: buffer(
                "scene vertices",
                bytemuck::cast_slice(&vertices),
                // STORAGE: a compute pass (a ray-traced visibility) reads the triangles.
                wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::STORAGE,
            ),
            indices: buffer(
                "scene indices",
                bytemuck::cast_slice(&indices),
                wgpu::BufferUsages::INDEX | wgpu::BufferUsages::STORAGE,
            ),
            draws,
            caster_bounds: scene
                .objects
                .iter()
                .map(|o| o.casts_shadows.then_some(o.bounds))
                .collect(),
            bounds: scene.objects.iter().map(|o| o.bounds).collect(),
            materials: buffer(
                "materials",
                &material_slots(&materials),
                // COPY_DST: the colours change with the light's spectrum.
                wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            ),
            materials_raw: materials,
            norm_written: None,
            material_colours,
            colours_written: None,
            texture_view: textures.create_view(&wgpu::TextureViewDescriptor {
                label: Some("base colour textures"),
                dimension: Some(wgpu::TextureViewDimension::D2Array),
                ..Default::default()
            }),
            textures,
            triangle_count: scene.triangle_count(),
            bvh: std::sync::OnceLock::new(),
            bvh_build: BvhBuild::new(caster_triangles(
                scene,
                scene.objects.iter().map(|o| &o.mesh.indices[..]),
            )),
            no_bvh: GpuBvh::new(device, &FlatBvh::default()),
            simplified: None,
        }
    }

    /// Uploads the simplified meshes of this scene (built from the same
    /// `Scene`: one index list per object in each copy); ignored when they
    /// have another count of objects.
    pub fn set_simplified(&mut self, device: &wgpu::Device, meshes: &SimplifiedMeshes) {
        if meshes.indices.len() != self.draws.len() || meshes.casters.len() != self.draws.len() {
            return;
        }
        // As `new` lays out the full meshes: each object's indices after
        // the last, over that object's own vertices.
        let upload = |label: &str, lists: &[Vec<u32>]| {
            let mut indices: Vec<u32> = Vec::new();
            let draws = self
                .draws
                .iter()
                .zip(lists)
                .map(|(full, object)| {
                    let draw = Draw {
                        first_index: indices.len() as u32,
                        index_count: object.len() as u32,
                        base_vertex: full.base_vertex,
                        slot: full.slot,
                    };
                    indices.extend_from_slice(object);
                    draw
                })
                .collect();
            SimplifiedBuffers {
                indices: buffer_init(
                    device,
                    label,
                    bytemuck::cast_slice(&indices),
                    wgpu::BufferUsages::INDEX,
                ),
                draws,
            }
        };
        self.simplified = Some(Simplified {
            camera: upload("simplified scene indices", &meshes.indices),
            casters: upload("simplified caster indices", &meshes.casters),
            bvh: GpuBvh::new(device, &meshes.bvh),
            triangles: meshes.counts.camera,
        });
    }

    /// The triangles of the camera's simplified meshes, once uploaded.
    pub fn simplified_triangles(&self) -> Option<usize> {
        self.simplified.as_ref().map(|s| s.triangles)
    }

    /// What the camera pass draws: the simplified meshes when `simplified`
    /// and they are uploaded, else the full ones.
    pub fn meshes(&self, simplified: bool) -> Meshes<'_> {
        self.drawn(self.drag_copy(simplified).map(|s| &s.camera))
    }

    /// What the shadow pass draws: the casters' coarser copy when
    /// `simplified` and it is uploaded, else the full meshes.
    pub fn caster_meshes(&self, simplified: bool) -> Meshes<'_> {
        self.drawn(self.drag_copy(simplified).map(|s| &s.casters))
    }

    /// The shadow rays' BVH, and whether it is the scene's: that of the
    /// camera's simplified copy when `simplified` and it is uploaded (the
    /// triangles [`Self::meshes`] draws then), else the full meshes',
    /// built (or waited for) here when a frame first `traces` rays, and
    /// uploaded by any frame once a background build is done. Until then
    /// an empty BVH stands in (false).
    pub fn bvh(&self, device: &wgpu::Device, simplified: bool, traces: bool) -> (&GpuBvh, bool) {
        if let Some(copy) = self.drag_copy(simplified) {
            return (&copy.bvh, true);
        }
        if self.bvh.get().is_none()
            && let Some(bvh) = self.bvh_build.take(device, traces)
        {
            // Only the frame that takes it gets here: `bvh` is empty.
            let _ = self.bvh.set(bvh);
        }
        self.bvh.get().map_or((&self.no_bvh, false), |bvh| (bvh, true))
    }

    /// Starts building and uploading the full meshes' BVH on a thread of
    /// its own (the app's scenes): a first ray-traced frame then waits for
    /// what is left of it, not for all of it.
    pub fn build_bvh_in_background(&self, device: &wgpu::Device) {
        self.bvh_build.start_in_background(device);
    }

    /// The simplified meshes when `simplified` and they are uploaded.
    fn drag_copy(&self, simplified: bool) -> Option<&Simplified> {
        self.simplified.as_ref().filter(|_| simplified)
    }

    /// The scene's vertices through `copy`'s indices, or the full ones.
    fn drawn<'a>(&'a self, copy: Option<&'a SimplifiedBuffers>) -> Meshes<'a> {
        let (indices, draws) = copy.map_or((&self.indices, &self.draws[..]), |c| (&c.indices, &c.draws[..]));
        Meshes {
            vertices: &self.vertices,
            indices,
            draws,
        }
    }

    /// Makes the materials buffer hold `colours` (one per material, see
    /// [`crate::colour::shading_colours`]) and, for the `delta-e` view, the
    /// `other` colour model's, unless it already holds those of `key`.
    /// Views sharing the scene may differ (a split "RGB | spectral"): each
    /// writes its own before it submits, and a write lands before the next
    /// submission, so each frame reads its own.
    pub fn write_colours(
        &mut self,
        queue: &wgpu::Queue,
        key: ColourKey,
        colours: &[glam::DVec3],
        other: &[glam::DVec3],
    ) {
        if self.colours_written == Some(key) {
            return;
        }
        for ((raw, c), o) in self.materials_raw.iter_mut().zip(colours).zip(other) {
            let norm = raw.base_color[3];
            raw.base_color = c.as_vec3().extend(norm).to_array();
            raw.other_model_color = o.as_vec3().extend(raw.other_model_color[3]).to_array();
        }
        queue.write_buffer(&self.materials, 0, &material_slots(&self.materials_raw));
        self.colours_written = Some(key);
    }

    /// Makes the materials buffer hold each material's N(own m) under
    /// `norm` (in its base colour's w), unless it already does; views of
    /// other normalizations write theirs before they submit, as for
    /// [`Self::write_colours`]. One value a material, not one per
    /// normalization indexed in the shader.
    pub fn write_norm_factors(&mut self, queue: &wgpu::Queue, norm: Normalization) {
        if self.norm_written == Some(norm) {
            return;
        }
        for raw in &mut self.materials_raw {
            raw.base_color[3] = norm.factor(f64::from(raw.words.own_m)) as f32;
        }
        queue.write_buffer(&self.materials, 0, &material_slots(&self.materials_raw));
        self.norm_written = Some(norm);
    }

    /// Bounds of every object.
    pub fn scene_bounds(&self) -> Aabb {
        self.bounds.iter().fold(Aabb::EMPTY, |b, o| b.union(o))
    }
}

/// A buffer holding `contents`: wgpu refuses empty bindings, so an empty
/// list (an empty scene) still gets 4 bytes.
fn buffer_init(
    device: &wgpu::Device,
    label: &str,
    contents: &[u8],
    usage: wgpu::BufferUsages,
) -> wgpu::Buffer {
    let contents = if contents.is_empty() {
        &[0u8; 4][..]
    } else {
        contents
    };
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents,
        usage,
    })
}

/// Every base-colour texture resampled to one square size as a layer of an
/// sRGB texture array; returns the array and each texture's layer.
fn upload_textures(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    scene: &Scene,
    caps: &super::Capabilities,
) -> (wgpu::Texture, Vec<u32>) {
    let max_layers = device.limits().max_texture_array_layers as usize;
    let used = &scene.textures[..scene.textures.len().min(max_layers)];
    let side = used
        .iter()
        .map(|t| t.width.max(t.height))
        .max()
        .unwrap_or(1)
        .clamp(1, MAX_TEXTURE_SIDE);
    let layers = caps.array_layers(used.len().max(1) as u32);
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("base colour textures"),
        size: wgpu::Extent3d {
            width: side,
            height: side,
            depth_or_array_layers: layers,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8UnormSrgb,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    let white = vec![255u8; (side * side * 4) as usize];
    for layer in 0..layers {
        let pixels = used.get(layer as usize).and_then(|t| {
            let image = image::RgbaImage::from_raw(t.width, t.height, t.rgba8.clone())?;
            Some(if t.width == side && t.height == side {
                image.into_raw()
            } else {
                image::imageops::resize(&image, side, side, image::imageops::FilterType::Triangle).into_raw()
            })
        });
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: 0,
                origin: wgpu::Origin3d { x: 0, y: 0, z: layer },
                aspect: wgpu::TextureAspect::All,
            },
            pixels.as_deref().unwrap_or(&white),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(side * 4),
                rows_per_image: Some(side),
            },
            wgpu::Extent3d {
                width: side,
                height: side,
                depth_or_array_layers: 1,
            },
        );
    }
    (texture, (0..used.len() as u32).collect())
}
