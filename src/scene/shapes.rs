//! Procedural meshes in world space: the building blocks of the built-in
//! scene's generator and of the tests' scenes.

use super::{Aabb, Mesh, Object};
use glam::{Mat4, Vec2, Vec3};
use std::f32::consts::{PI, TAU};

impl Mesh {
    /// Appends a quad (two triangles) with corners `a, b, c, d` in
    /// counter-clockwise order seen from the side the normal points to.
    fn push_quad(&mut self, [a, b, c, d]: [Vec3; 4], normal: Vec3) {
        let base = self.positions.len() as u32;
        self.positions.extend([a, b, c, d]);
        self.normals.extend([normal; 4]);
        self.uvs.extend([
            Vec2::new(0.0, 1.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(0.0, 0.0),
        ]);
        self.indices
            .extend([base, base + 1, base + 2, base, base + 2, base + 3]);
    }

    /// Adds `other`'s triangles to this mesh.
    pub fn append(&mut self, other: &Mesh) {
        let base = self.positions.len() as u32;
        self.positions.extend_from_slice(&other.positions);
        self.normals.extend_from_slice(&other.normals);
        self.uvs.extend_from_slice(&other.uvs);
        self.colours.extend_from_slice(&other.colours);
        self.indices.extend(other.indices.iter().map(|i| base + i));
    }

    /// The mesh with every position moved by `transform` (normals by its
    /// inverse transpose); a mirroring transform keeps the faces front-facing.
    pub fn transformed(&self, transform: Mat4) -> Mesh {
        let normal_matrix = transform.inverse().transpose();
        let mut indices = self.indices.clone();
        if transform.determinant() < 0.0 {
            for t in indices.chunks_exact_mut(3) {
                t.swap(1, 2);
            }
        }
        Mesh {
            positions: self
                .positions
                .iter()
                .map(|&p| transform.transform_point3(p))
                .collect(),
            normals: self
                .normals
                .iter()
                .map(|&n| normal_matrix.transform_vector3(n).normalize_or_zero())
                .collect(),
            uvs: self.uvs.clone(),
            colours: self.colours.clone(),
            indices,
        }
    }
}

/// A horizontal square of side `size` centred on `center`, facing +Y.
pub fn ground(center: Vec3, size: f32) -> Mesh {
    let h = 0.5 * size;
    let mut mesh = Mesh::default();
    mesh.push_quad(
        [
            center + Vec3::new(-h, 0.0, h),
            center + Vec3::new(h, 0.0, h),
            center + Vec3::new(h, 0.0, -h),
            center + Vec3::new(-h, 0.0, -h),
        ],
        Vec3::Y,
    );
    mesh
}

/// The same square split into `cells` × `cells` quads: small triangles keep
/// the rasterizer's f32 interpolation of positions precise.
pub fn ground_grid(center: Vec3, size: f32, cells: u32) -> Mesh {
    let mut mesh = Mesh::default();
    let step = size / cells as f32;
    let origin = center - Vec3::new(0.5 * size, 0.0, 0.5 * size);
    for i in 0..cells {
        for j in 0..cells {
            let a = origin + Vec3::new(i as f32 * step, 0.0, (j + 1) as f32 * step);
            mesh.push_quad(
                [
                    a,
                    a + Vec3::X * step,
                    a + Vec3::new(step, 0.0, -step),
                    a - Vec3::Z * step,
                ],
                Vec3::Y,
            );
        }
    }
    mesh
}

/// An axis-aligned box with flat faces.
pub fn cuboid(bounds: Aabb) -> Mesh {
    cuboid_faces(bounds, |_| true)
}

/// A horizontal slab of side `size` and `thickness` whose top, at
/// `top_center`, is split into `cells` × `cells` quads: a ground that is a
/// closed box, precise under the rasterizer.
pub fn ground_slab(top_center: Vec3, size: f32, thickness: f32, cells: u32) -> Mesh {
    let h = 0.5 * size;
    let mut mesh = ground_grid(top_center, size, cells);
    mesh.append(&cuboid_faces(
        Aabb {
            min: top_center + Vec3::new(-h, -thickness, -h),
            max: top_center + Vec3::new(h, 0.0, h),
        },
        |normal| normal != Vec3::Y,
    ));
    mesh
}

/// The faces of an axis-aligned box whose outward normal `keep` accepts.
fn cuboid_faces(bounds: Aabb, keep: impl Fn(Vec3) -> bool) -> Mesh {
    let c = bounds.corners();
    let mut mesh = Mesh::default();
    // Corner i has x from bit 0, y from bit 1, z from bit 2.
    let faces = [
        ([1, 3, 7, 5], Vec3::X),
        ([4, 6, 2, 0], Vec3::NEG_X),
        ([2, 6, 7, 3], Vec3::Y),
        ([0, 1, 5, 4], Vec3::NEG_Y),
        ([4, 5, 7, 6], Vec3::Z),
        ([1, 0, 2, 3], Vec3::NEG_Z),
    ];
    for (idx, normal) in faces.into_iter().filter(|&(_, n)| keep(n)) {
        mesh.push_quad(idx.map(|i| c[i]), normal);
    }
    mesh
}

/// A UV sphere with smooth normals.
pub fn sphere(center: Vec3, radius: f32, segments: u32, rings: u32) -> Mesh {
    let mut mesh = Mesh::default();
    for ring in 0..=rings {
        let v = ring as f32 / rings as f32;
        let theta = v * PI;
        for seg in 0..=segments {
            let u = seg as f32 / segments as f32;
            let phi = u * TAU;
            let n = Vec3::new(theta.sin() * phi.cos(), theta.cos(), -theta.sin() * phi.sin());
            mesh.positions.push(center + radius * n);
            mesh.normals.push(n);
            mesh.uvs.push(Vec2::new(u, v));
        }
    }
    let row = segments + 1;
    for ring in 0..rings {
        for seg in 0..segments {
            let a = ring * row + seg;
            let b = a + row;
            if ring != 0 {
                mesh.indices.extend([a, b, a + 1]);
            }
            if ring != rings - 1 {
                mesh.indices.extend([a + 1, b, b + 1]);
            }
        }
    }
    mesh
}

/// A closed vertical cylinder standing on `base` (smooth side, flat caps).
pub fn cylinder(base: Vec3, radius: f32, height: f32, segments: u32) -> Mesh {
    let mut mesh = Mesh::default();
    let top = base + Vec3::Y * height;
    for seg in 0..segments {
        let (a0, a1) = (
            seg as f32 / segments as f32 * TAU,
            (seg + 1) as f32 / segments as f32 * TAU,
        );
        let d0 = Vec3::new(a0.cos(), 0.0, -a0.sin());
        let d1 = Vec3::new(a1.cos(), 0.0, -a1.sin());
        let i = mesh.positions.len() as u32;
        mesh.positions.extend([
            base + d0 * radius,
            base + d1 * radius,
            top + d1 * radius,
            top + d0 * radius,
        ]);
        mesh.normals.extend([d0, d1, d1, d0]);
        mesh.uvs.extend([Vec2::ZERO; 4]);
        mesh.indices.extend([i, i + 1, i + 2, i, i + 2, i + 3]);
        for (centre, normal, ring) in [(top, Vec3::Y, [d0, d1]), (base, Vec3::NEG_Y, [d1, d0])] {
            let j = mesh.positions.len() as u32;
            mesh.positions
                .extend([centre, centre + ring[0] * radius, centre + ring[1] * radius]);
            mesh.normals.extend([normal; 3]);
            mesh.uvs.extend([Vec2::ZERO; 3]);
            mesh.indices.extend([j, j + 1, j + 2]);
        }
    }
    mesh
}

impl Object {
    /// An object that casts and receives shadows, with its bounds computed.
    pub fn new(name: impl Into<String>, mesh: Mesh, material: usize) -> Self {
        Self {
            name: name.into(),
            bounds: Aabb::from_points(mesh.positions.iter().copied()),
            mesh,
            material,
            casts_shadows: true,
            receives_shadows: true,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every triangle's winding agrees with its vertex normals (front faces CCW).
    fn assert_outward(mesh: &Mesh) {
        for t in 0..mesh.triangle_count() {
            let [a, b, c] = mesh.triangle(t);
            let face = (b - a).cross(c - a);
            if face.length() < 1e-9 {
                continue;
            }
            let n = mesh.normals[mesh.indices[3 * t] as usize];
            assert!(face.dot(n) > 0.0, "triangle {t} winds against its normal");
        }
    }

    #[test]
    fn shapes_wind_counter_clockwise_towards_their_normals() {
        assert_outward(&ground(Vec3::ZERO, 2.0));
        assert_outward(&ground_grid(Vec3::ZERO, 2.0, 3));
        assert_outward(&cuboid(Aabb {
            min: Vec3::ZERO,
            max: Vec3::ONE,
        }));
        assert_outward(&sphere(Vec3::ONE, 0.5, 16, 8));
        assert_outward(&cylinder(Vec3::ZERO, 0.3, 1.0, 12));
    }

    #[test]
    fn the_ground_slab_is_a_closed_box_with_a_fine_top() {
        let slab = ground_slab(Vec3::ZERO, 2.0, 0.1, 3);
        assert_outward(&slab);
        assert_eq!(slab.triangle_count(), 2 * 3 * 3 + 2 * 5);
        let bounds = Aabb::from_points(slab.positions.iter().copied());
        assert_eq!(bounds.max, Vec3::new(1.0, 0.0, 1.0));
        assert_eq!(bounds.min, Vec3::new(-1.0, -0.1, -1.0));
    }

    #[test]
    fn mirroring_keeps_front_faces() {
        let mirrored = cuboid(Aabb {
            min: Vec3::ZERO,
            max: Vec3::ONE,
        })
        .transformed(Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0)));
        assert_outward(&mirrored);
    }

    #[test]
    fn sphere_has_the_expected_triangle_count() {
        assert_eq!(sphere(Vec3::ZERO, 1.0, 16, 8).triangle_count(), 16 * (2 * 8 - 2));
    }
}
