//! One mesh primitive in its mesh's own space: the triangle list drawn
//! (strips and fans converted, broken triangles dropped), normals read and
//! repaired (none when the file gives none: shaded flat), and what was
//! repaired, counted.

use super::accessor::Data;
use crate::scene::{LoadProblem, Mesh};
use crate::settings::Settings;
use glam::{Vec2, Vec3};
use gltf::json::accessor::Type;
use gltf::json::mesh::{Mode, Primitive, Semantic};
use gltf::json::validation::Checked;

/// What a primitive draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Topology {
    Triangles,
    /// Points and lines: not drawn, but their positions count in the bounds.
    PointsOrLines,
}

/// A primitive ready to be placed by each node that uses it.
#[derive(Debug)]
pub(super) struct LocalPrimitive {
    pub topology: Topology,
    /// Finite positions only; for triangles, also normals, uvs and the
    /// surviving triangles.
    pub mesh: Mesh,
    /// Triangles the primitive's mode defines, before any is dropped.
    pub triangles_defined: usize,
    /// Triangles with two equal corners or zero area.
    pub degenerate: usize,
    /// Triangles with a NaN or infinite corner in the file (placing the
    /// mesh drops those with a distant corner: [`repair_placed`]).
    pub out_of_range: usize,
    /// Vertices whose position in the file is NaN, infinite or past
    /// [`MAX_MODEL_COORDINATE_M`] (before their node's transform).
    pub distant_vertices: usize,
    /// Normals that were zero, NaN or infinite and were replaced.
    pub normals_repaired: usize,
    /// The NORMAL, TEXCOORD or COLOR_0 accessor had the wrong count and
    /// was ignored.
    pub attributes_ignored: Vec<String>,
}

/// The vertex triples of the triangles `mode` makes of `indices`, in the
/// order glTF defines so that every triangle keeps the primitive's winding.
pub(super) fn triangle_list(mode: Mode, indices: &[u32]) -> Vec<[u32; 3]> {
    let n = indices.len();
    match mode {
        Mode::Triangles => indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
        // Odd triangles swap their first two corners to keep the winding.
        Mode::TriangleStrip => (0..n.saturating_sub(2))
            .map(|i| {
                let (a, b, c) = (indices[i], indices[i + 1], indices[i + 2]);
                if i % 2 == 0 { [a, b, c] } else { [b, a, c] }
            })
            .collect(),
        Mode::TriangleFan => (1..n.saturating_sub(1))
            .map(|i| [indices[i], indices[i + 1], indices[0]])
            .collect(),
        Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip => Vec::new(),
    }
}

/// Reads primitive `what` (e.g. "mesh 0 primitive 1"); `uv_set` is the
/// texture coordinate set its material samples. `Ok(None)` when it has no
/// POSITION attribute (nothing to place).
pub(super) fn build(
    data: &Data,
    primitive: &Primitive,
    what: &str,
    uv_set: u32,
) -> Result<Option<LocalPrimitive>, LoadProblem> {
    let attribute = |s: Semantic| primitive.attributes.get(&Checked::Valid(s)).map(|i| i.value());
    let Some(position_accessor) = attribute(Semantic::Positions) else {
        return Ok(None);
    };
    let positions = data.vec3s(position_accessor)?;
    let Checked::Valid(mode) = primitive.mode else {
        return Err(LoadProblem::InvalidValue {
            what: what.into(),
            detail: "unknown mode".into(),
        });
    };
    let topology = match mode {
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan => Topology::Triangles,
        Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip => Topology::PointsOrLines,
    };
    let distant_vertices = positions
        .iter()
        .filter(|&&p| !within(p, MAX_MODEL_COORDINATE_M))
        .count();
    let mut local = LocalPrimitive {
        topology,
        mesh: Mesh::default(),
        triangles_defined: 0,
        degenerate: 0,
        out_of_range: 0,
        distant_vertices,
        normals_repaired: 0,
        attributes_ignored: Vec::new(),
    };
    if topology == Topology::PointsOrLines {
        local.mesh.positions = positions.into_iter().filter(|p| p.is_finite()).collect();
        return Ok(Some(local));
    }

    let vertex_count = positions.len();
    let indices = match primitive.indices {
        Some(accessor) => {
            let indices = data.indices(accessor.value())?;
            if let Some(&bad) = indices.iter().find(|&&i| i as usize >= vertex_count) {
                return Err(LoadProblem::OutOfRange {
                    what: format!("accessor {}", accessor.value()),
                    detail: format!("index {bad} is past the {vertex_count} vertices of {what}"),
                });
            }
            indices
        }
        None => (0..u32::try_from(vertex_count)
            .map_err(|_| LoadProblem::TooLarge(format!("{what} has {vertex_count} vertices")))?)
            .collect(),
    };
    let triangles = triangle_list(mode, &indices);
    drop(indices);
    local.triangles_defined = triangles.len();

    let drawable = drawable(&positions, triangles.iter().copied(), f32::MAX);
    let kept = drawable.indices;
    local.out_of_range = drawable.out_of_range;
    local.degenerate = drawable.degenerate;
    drop(triangles);

    let mut normals = match attribute(Semantic::Normals) {
        Some(accessor) => {
            let normals = data.vec3s(accessor)?;
            if normals.len() == vertex_count {
                Some(normals)
            } else {
                local.attributes_ignored.push(format!(
                    "{what}: NORMAL has {} entries for {vertex_count} vertices",
                    normals.len()
                ));
                None
            }
        }
        None => None,
    };
    let uvs = match attribute(Semantic::TexCoords(uv_set)) {
        Some(accessor) => {
            let uvs = data.vec2s(accessor)?;
            if uvs.len() == vertex_count {
                uvs
            } else {
                local.attributes_ignored.push(format!(
                    "{what}: TEXCOORD_{uv_set} has {} entries for {vertex_count} vertices",
                    uvs.len()
                ));
                vec![Vec2::ZERO; vertex_count]
            }
        }
        None => vec![Vec2::ZERO; vertex_count],
    };
    // COLOR_0 multiplies the base colour: linear RGB, floats or normalized
    // integers, its alpha (like the material's) not modelled. A NaN or
    // infinite component counts as 1, a negative one as 0.
    let colours = match attribute(Semantic::Colors(0)) {
        Some(accessor) => {
            let (values, components) = data.floats(accessor, &[Type::Vec3, Type::Vec4])?;
            if values.len() == components * vertex_count {
                values
                    .chunks_exact(components)
                    .map(|c| Vec3::from_slice(c).map(|v| if v.is_finite() { v.max(0.0) } else { 1.0 }))
                    .collect()
            } else {
                local.attributes_ignored.push(format!(
                    "{what}: COLOR_0 has {} entries for {vertex_count} vertices",
                    values.len() / components.max(1)
                ));
                Vec::new()
            }
        }
        None => Vec::new(),
    };

    // Without NORMAL the primitive keeps no normals: glTF 2.0 (§3.7.2.1)
    // has it shaded flat, and both renderers then shade each triangle with
    // its face's normal (a missing vertex normal counts as zero there).
    // Given normals that are zero, NaN or infinite are repaired from the
    // triangles around their vertex.
    if let Some(given) = normals.as_mut()
        && given.iter().any(|v| !usable(*v))
    {
        let generated = vertex_normals(&positions, &kept);
        for (n, g) in given.iter_mut().zip(&generated) {
            if !usable(*n) {
                *n = *g;
                local.normals_repaired += 1;
            }
        }
    }
    let normals = normals
        .unwrap_or_default()
        .into_iter()
        .map(|n| n.normalize_or(Vec3::Y))
        .collect();

    local.mesh = Mesh {
        positions,
        normals,
        uvs,
        colours,
        indices: kept,
    };
    drop_vertices_past(&mut local.mesh, f32::MAX);
    Ok(Some(local))
}

/// The triangles worth drawing, as an index list, and what was dropped.
pub(super) struct Drawable {
    pub indices: Vec<u32>,
    /// Triangles with a corner past the bound (NaN included).
    pub out_of_range: usize,
    /// Triangles with two equal corners or zero area.
    pub degenerate: usize,
}

/// The farthest a placed vertex may lie from the origin along any axis
/// (m): a tenth of the lab's coordinate range, so that the camera and the
/// light framed around the largest model stay inside that range. A corner
/// past it is treated as a NaN one: its triangle is dropped.
pub const MAX_MODEL_COORDINATE_M: f32 = Settings::MAX_COORDINATE_M / 10.0;

/// Whether every coordinate of `p` lies within ±`bound` (never for NaN;
/// a bound of `f32::MAX` asks whether `p` is finite).
pub(super) fn within(p: Vec3, bound: f32) -> bool {
    p.abs().cmple(Vec3::splat(bound)).all()
}

/// Sorts `triangles` (indices into `positions`) into kept and dropped: a
/// corner past ±`bound`, or no area.
pub(super) fn drawable(
    positions: &[Vec3],
    triangles: impl ExactSizeIterator<Item = [u32; 3]>,
    bound: f32,
) -> Drawable {
    let mut out = Drawable {
        indices: Vec::with_capacity(3 * triangles.len()),
        out_of_range: 0,
        degenerate: 0,
    };
    for t in triangles {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        if !(within(a, bound) && within(b, bound) && within(c, bound)) {
            out.out_of_range += 1;
        } else if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || (b - a).cross(c - a) == Vec3::ZERO {
            out.degenerate += 1;
        } else {
            out.indices.extend_from_slice(&t);
        }
    }
    out
}

/// Repairs a mesh just placed in the world: a large transform can move
/// finite positions past [`MAX_MODEL_COORDINATE_M`] or overflow them to
/// infinity, a nearly flat one can collapse triangles (both are dropped),
/// an extreme normal matrix can lose normals (they are generated again).
/// Returns the out-of-range and degenerate triangles dropped.
pub(super) fn repair_placed(mesh: &mut Mesh) -> (usize, usize) {
    let triangles = mesh.indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]);
    let Drawable {
        indices,
        out_of_range,
        degenerate,
    } = drawable(&mesh.positions, triangles, MAX_MODEL_COORDINATE_M);
    mesh.indices = indices;
    drop_vertices_past(mesh, MAX_MODEL_COORDINATE_M);
    if mesh.normals.iter().any(|n| !usable(*n)) {
        let generated = vertex_normals(&mesh.positions, &mesh.indices);
        for (n, g) in mesh.normals.iter_mut().zip(generated) {
            if !usable(*n) {
                *n = g;
            }
        }
    }
    (out_of_range, degenerate)
}

/// A normal that can be normalized: finite and not zero.
fn usable(n: Vec3) -> bool {
    n.is_finite() && n.length_squared() > 0.0
}

/// Per-vertex normals from the triangles: each face normal weighted by the
/// triangle's area (the cross product's length is twice the area) and by
/// the angle at the corner, so that a vertex's normal does not depend on
/// how a flat region around it was split into triangles. A vertex no
/// triangle uses gets +Y.
pub(super) fn vertex_normals(positions: &[Vec3], indices: &[u32]) -> Vec<Vec3> {
    let mut sum = vec![Vec3::ZERO; positions.len()];
    for t in indices.chunks_exact(3) {
        let p = [0, 1, 2].map(|k| positions[t[k] as usize]);
        let face = (p[1] - p[0]).cross(p[2] - p[0]);
        for k in 0..3 {
            let e1 = p[(k + 1) % 3] - p[k];
            let e2 = p[(k + 2) % 3] - p[k];
            // atan2 of |e1 × e2| and e1 · e2 stays accurate for thin corners.
            let angle = e1.cross(e2).length().atan2(e1.dot(e2));
            sum[t[k] as usize] += face * angle;
        }
    }
    // Where opposite faces cancel (a vertex shared by both sides of a
    // sheet), the first face that uses the vertex decides.
    let mut fallback = vec![Vec3::ZERO; positions.len()];
    for t in indices.chunks_exact(3) {
        let p = [0, 1, 2].map(|k| positions[t[k] as usize]);
        let face = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
        for &v in t {
            if fallback[v as usize] == Vec3::ZERO {
                fallback[v as usize] = face;
            }
        }
    }
    sum.iter()
        .zip(&fallback)
        .map(|(s, f)| s.try_normalize().or_else(|| f.try_normalize()).unwrap_or(Vec3::Y))
        .collect()
}

/// Drops the mesh's vertices past ±`bound`, if any (no kept triangle
/// uses them).
fn drop_vertices_past(mesh: &mut Mesh, bound: f32) {
    if mesh.positions.iter().all(|&p| within(p, bound)) {
        return;
    }
    let mut remap = vec![u32::MAX; mesh.positions.len()];
    let mut out = Mesh::default();
    for (i, &p) in mesh.positions.iter().enumerate() {
        if within(p, bound) {
            remap[i] = out.positions.len() as u32;
            out.positions.push(p);
            out.normals.extend(mesh.normals.get(i));
            out.uvs.push(mesh.uvs[i]);
            out.colours.extend(mesh.colours.get(i));
        }
    }
    out.indices = mesh.indices.iter().map(|&i| remap[i as usize]).collect();
    *mesh = out;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_and_fans_keep_the_winding() {
        // A quad 0-1-2-3 counter-clockwise, as a strip 0,1,3,2 and a fan 0,1,2,3.
        assert_eq!(
            triangle_list(Mode::TriangleStrip, &[0, 1, 3, 2]),
            vec![[0, 1, 3], [3, 1, 2]]
        );
        assert_eq!(
            triangle_list(Mode::TriangleFan, &[0, 1, 2, 3]),
            vec![[1, 2, 0], [2, 3, 0]]
        );
        assert!(triangle_list(Mode::TriangleStrip, &[0, 1]).is_empty());
        assert!(triangle_list(Mode::TriangleFan, &[]).is_empty());
        assert_eq!(triangle_list(Mode::Triangles, &[0, 1, 2, 3]).len(), 1);
    }

    #[test]
    fn generated_normals_of_a_flat_fan_point_up() {
        let positions = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 0.0, -1.0), Vec3::NEG_Z];
        let normals = vertex_normals(&positions, &[0, 1, 2, 0, 2, 3]);
        for n in normals {
            assert!((n - Vec3::Y).length() < 1e-6, "{n}");
        }
    }

    #[test]
    fn a_cube_corner_gets_the_diagonal_whatever_the_split() {
        // Three unit faces meeting at the origin; two are split through
        // the corner, the third (y = 0) is not: the corner normal is still
        // the symmetric diagonal, as the faces are symmetric.
        let p = [
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::Y,
            Vec3::new(0.0, 1.0, 1.0),
            Vec3::Z,
            Vec3::new(1.0, 0.0, 1.0),
        ];
        // Faces z = 0 (normal −Z), x = 0 (−X), y = 0 (−Y), outward from the cube.
        let indices = [0, 3, 2, 0, 2, 1, 0, 5, 4, 0, 4, 3, 0, 1, 5, 1, 6, 5];
        let n = vertex_normals(&p, &indices)[0];
        assert!((n - Vec3::splat(-1.0).normalize()).length() < 1e-6, "{n}");
    }
}
