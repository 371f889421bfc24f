//! Accessor data read with every index, offset, stride and length checked
//! against the buffer it lives in, so a corrupt file is an error, never an
//! out-of-bounds read or a huge allocation.

use crate::scene::LoadProblem;
use glam::{Vec2, Vec3};
use gltf::json::Root;
use gltf::json::accessor::{ComponentType, GenericComponentType, Type};
use gltf::json::validation::Checked;
use std::borrow::Cow;

/// Elements an accessor without a buffer view may claim (it is all zeros
/// plus its sparse values, so its count is not bounded by any data).
const MAX_UNBACKED_ELEMENTS: u64 = 1 << 24;

/// The JSON and the loaded buffers, to read accessors and buffer views from.
pub(super) struct Data<'r, 'b> {
    pub root: &'r Root,
    pub buffers: &'r [Cow<'b, [u8]>],
}

fn out_of_range(what: String, detail: String) -> LoadProblem {
    LoadProblem::OutOfRange { what, detail }
}

fn invalid(what: String, detail: impl Into<String>) -> LoadProblem {
    LoadProblem::InvalidValue {
        what,
        detail: detail.into(),
    }
}

/// Item `index` of a list of the JSON, or an error naming `what`.
fn lookup<'a, T>(items: &'a [T], index: usize, what: &str) -> Result<&'a T, LoadProblem> {
    items.get(index).ok_or_else(|| {
        out_of_range(
            what.into(),
            format!("does not exist (the file has {})", items.len()),
        )
    })
}

fn bytes_of(ty: ComponentType) -> usize {
    match ty {
        ComponentType::I8 | ComponentType::U8 => 1,
        ComponentType::I16 | ComponentType::U16 => 2,
        ComponentType::U32 | ComponentType::F32 => 4,
    }
}

fn components_of(ty: Type) -> usize {
    match ty {
        Type::Scalar => 1,
        Type::Vec2 => 2,
        Type::Vec3 => 3,
        Type::Vec4 | Type::Mat2 => 4,
        Type::Mat3 => 9,
        Type::Mat4 => 16,
    }
}

/// Reads one component as a float: normalized integers map to [0, 1] or
/// [−1, 1] as glTF (and KHR_mesh_quantization) define; others keep their value.
fn float_decoder(ty: ComponentType, normalized: bool) -> fn(&[u8]) -> f32 {
    match (ty, normalized) {
        (ComponentType::F32, _) => f32_le,
        (ComponentType::U8, true) => |b| b[0] as f32 / 255.0,
        (ComponentType::U8, false) => |b| b[0] as f32,
        (ComponentType::I8, true) => |b| (b[0] as i8 as f32 / 127.0).max(-1.0),
        (ComponentType::I8, false) => |b| b[0] as i8 as f32,
        (ComponentType::U16, true) => |b| u16::from_le_bytes([b[0], b[1]]) as f32 / 65535.0,
        (ComponentType::U16, false) => |b| u16::from_le_bytes([b[0], b[1]]) as f32,
        (ComponentType::I16, true) => |b| (i16::from_le_bytes([b[0], b[1]]) as f32 / 32767.0).max(-1.0),
        (ComponentType::I16, false) => |b| i16::from_le_bytes([b[0], b[1]]) as f32,
        (ComponentType::U32, true) => {
            |b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f32 / u32::MAX as f32
        }
        (ComponentType::U32, false) => |b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f32,
    }
}

/// A little-endian f32, the common case of float attributes.
fn f32_le(b: &[u8]) -> f32 {
    f32::from_le_bytes([b[0], b[1], b[2], b[3]])
}

/// A little-endian u32, the common case of indices.
fn u32_le(b: &[u8]) -> u32 {
    u32::from_le_bytes([b[0], b[1], b[2], b[3]])
}

/// Reads one unsigned index; `None` for the types indices may not have.
fn index_decoder(ty: ComponentType) -> Option<fn(&[u8]) -> u32> {
    match ty {
        ComponentType::U8 => Some(|b| b[0] as u32),
        ComponentType::U16 => Some(|b| u16::from_le_bytes([b[0], b[1]]) as u32),
        ComponentType::U32 => Some(u32_le),
        _ => None,
    }
}

/// Where an accessor's elements lie: `count` elements of `element_bytes`,
/// the first at `data[0]`, one every `stride` bytes.
struct Strided<'a> {
    data: &'a [u8],
    stride: usize,
}

impl<'r, 'b> Data<'r, 'b> {
    /// The bytes of buffer view `index`, checked against its buffer, and its stride.
    pub fn view(&self, index: usize) -> Result<(&'r [u8], Option<usize>), LoadProblem> {
        let what = format!("buffer view {index}");
        let view = lookup(&self.root.buffer_views, index, &what)?;
        let buffer_index = view.buffer.value();
        let buffer = self.buffers.get(buffer_index).ok_or_else(|| {
            out_of_range(
                what.clone(),
                format!("names buffer {buffer_index}, which does not exist"),
            )
        })?;
        let start = view.byte_offset.map_or(0, |o| o.0);
        let len = view.byte_length.0;
        let end = start
            .checked_add(len)
            .filter(|&e| e <= buffer.len() as u64)
            .ok_or_else(|| {
                out_of_range(
                    what.clone(),
                    format!(
                        "bytes {start}..{start}+{len} lie outside buffer {buffer_index} ({} bytes)",
                        buffer.len()
                    ),
                )
            })?;
        Ok((
            &buffer[start as usize..end as usize],
            view.byte_stride.map(|s| s.0),
        ))
    }

    /// The element layout of accessor `index`, which must have `want` components.
    fn layout(
        &self,
        index: usize,
        want: &[Type],
    ) -> Result<(&'r gltf::json::Accessor, ComponentType, usize), LoadProblem> {
        let what = format!("accessor {index}");
        let accessor = lookup(&self.root.accessors, index, &what)?;
        let Checked::Valid(GenericComponentType(ty)) = accessor.component_type else {
            return Err(invalid(what, "unknown componentType"));
        };
        let Checked::Valid(kind) = accessor.type_ else {
            return Err(invalid(what, "unknown type"));
        };
        if !want.contains(&kind) {
            return Err(invalid(what, format!("type {kind:?} where {want:?} is expected")));
        }
        Ok((accessor, ty, components_of(kind)))
    }

    /// The accessor's `count` elements of `element_bytes`, checked against its view.
    fn strided(
        &self,
        index: usize,
        accessor: &gltf::json::Accessor,
        element_bytes: usize,
    ) -> Result<Option<Strided<'r>>, LoadProblem> {
        let what = format!("accessor {index}");
        let count = accessor.count.0;
        let Some(view_index) = accessor.buffer_view else {
            if count > MAX_UNBACKED_ELEMENTS {
                return Err(LoadProblem::TooLarge(format!(
                    "{what} has no buffer view but claims {count} elements"
                )));
            }
            return Ok(None);
        };
        let (bytes, stride) = self.view(view_index.value())?;
        let stride = stride.unwrap_or(element_bytes);
        if stride < element_bytes {
            return Err(invalid(
                what,
                format!("byteStride {stride} is smaller than its {element_bytes}-byte elements"),
            ));
        }
        let offset = accessor.byte_offset.map_or(0, |o| o.0);
        let needed = match count {
            0 => Some(offset),
            n => (n - 1)
                .checked_mul(stride as u64)
                .and_then(|b| b.checked_add(offset))
                .and_then(|b| b.checked_add(element_bytes as u64)),
        };
        match needed {
            Some(end) if end <= bytes.len() as u64 => Ok(Some(Strided {
                data: &bytes[offset as usize..],
                stride,
            })),
            _ => Err(out_of_range(
                what,
                format!(
                    "{count} elements of {element_bytes} bytes every {stride} from byte {offset} do not fit in buffer view {} ({} bytes)",
                    view_index.value(),
                    bytes.len()
                ),
            )),
        }
    }

    /// Every component of accessor `index` (dense, then its sparse values),
    /// `components` per element, decoded by `decode`.
    fn read<T: Copy + Default>(
        &self,
        index: usize,
        accessor: &gltf::json::Accessor,
        ty: ComponentType,
        components: usize,
        (decode, packed): (fn(&[u8]) -> T, impl Fn(&[u8]) -> T),
    ) -> Result<Vec<T>, LoadProblem> {
        let size = bytes_of(ty);
        let element_bytes = size * components;
        let count = accessor.count.0 as usize;
        let dense = self.strided(index, accessor, element_bytes)?;
        let mut values = Vec::with_capacity(count * components);
        match dense {
            // Packed elements: one pass over the components, decoded by
            // `packed` (the same function, inlined where the caller could).
            Some(Strided { data, stride }) if stride == element_bytes => {
                values.extend(data.chunks_exact(size).take(count * components).map(packed));
            }
            Some(Strided { data, stride }) => {
                for element in 0..count {
                    let at = element * stride;
                    values.extend((0..components).map(|c| decode(&data[at + c * size..])));
                }
            }
            None => values.resize(count * components, T::default()),
        }
        if let Some(sparse) = &accessor.sparse {
            self.apply_sparse(index, sparse, count, size, components, decode, &mut values)?;
        }
        Ok(values)
    }

    /// Overwrites the elements a sparse accessor lists.
    #[allow(clippy::too_many_arguments)]
    fn apply_sparse<T: Copy>(
        &self,
        index: usize,
        sparse: &gltf::json::accessor::sparse::Sparse,
        count: usize,
        size: usize,
        components: usize,
        decode: fn(&[u8]) -> T,
        values: &mut [T],
    ) -> Result<(), LoadProblem> {
        let what = format!("accessor {index} (sparse)");
        let n = sparse.count.0;
        let Checked::Valid(index_type) = sparse.indices.component_type else {
            return Err(invalid(what, "unknown index componentType"));
        };
        let decode_index =
            index_decoder(index_type.0).ok_or_else(|| invalid(what.clone(), "indices must be unsigned"))?;
        let index_bytes = bytes_of(index_type.0);
        let packed = |view: usize, offset: u64, element: usize| -> Result<&'r [u8], LoadProblem> {
            let (bytes, _) = self.view(view)?;
            n.checked_mul(element as u64)
                .and_then(|len| len.checked_add(offset))
                .filter(|&end| end <= bytes.len() as u64)
                .map(|end| &bytes[offset as usize..end as usize])
                .ok_or_else(|| {
                    out_of_range(
                        what.clone(),
                        format!(
                            "{n} entries do not fit in buffer view {view} ({} bytes)",
                            bytes.len()
                        ),
                    )
                })
        };
        let indices = packed(
            sparse.indices.buffer_view.value(),
            sparse.indices.byte_offset.0,
            index_bytes,
        )?;
        let element_bytes = size * components;
        let replacements = packed(
            sparse.values.buffer_view.value(),
            sparse.values.byte_offset.0,
            element_bytes,
        )?;
        for (slot, (i, v)) in indices
            .chunks_exact(index_bytes)
            .zip(replacements.chunks_exact(element_bytes))
            .enumerate()
        {
            let target = decode_index(i) as usize;
            if target >= count {
                return Err(out_of_range(
                    what,
                    format!("entry {slot} replaces element {target} of {count}"),
                ));
            }
            for c in 0..components {
                values[target * components + c] = decode(&v[c * size..]);
            }
        }
        Ok(())
    }

    /// A float attribute of `components` per element (normalized integers allowed).
    pub fn floats(&self, index: usize, want: &[Type]) -> Result<(Vec<f32>, usize), LoadProblem> {
        let (accessor, ty, components) = self.layout(index, want)?;
        let decode = float_decoder(ty, accessor.normalized);
        // The common type's packed elements through a function the loop inlines.
        let values = match ty {
            ComponentType::F32 => self.read(index, accessor, ty, components, (decode, f32_le))?,
            _ => self.read(index, accessor, ty, components, (decode, decode))?,
        };
        Ok((values, components))
    }

    pub fn vec3s(&self, index: usize) -> Result<Vec<Vec3>, LoadProblem> {
        let (values, _) = self.floats(index, &[Type::Vec3])?;
        Ok(values.chunks_exact(3).map(Vec3::from_slice).collect())
    }

    pub fn vec2s(&self, index: usize) -> Result<Vec<Vec2>, LoadProblem> {
        let (values, _) = self.floats(index, &[Type::Vec2])?;
        Ok(values.chunks_exact(2).map(Vec2::from_slice).collect())
    }

    /// Vertex indices: scalars of unsigned bytes, shorts or ints.
    pub fn indices(&self, index: usize) -> Result<Vec<u32>, LoadProblem> {
        let (accessor, ty, components) = self.layout(index, &[Type::Scalar])?;
        let decode = index_decoder(ty).ok_or_else(|| {
            invalid(
                format!("accessor {index}"),
                format!("indices of type {ty:?}; only unsigned bytes, shorts and ints are allowed"),
            )
        })?;
        match ty {
            ComponentType::U32 => self.read(index, accessor, ty, components, (decode, u32_le)),
            _ => self.read(index, accessor, ty, components, (decode, decode)),
        }
    }
}
