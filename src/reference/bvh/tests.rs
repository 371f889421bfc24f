//! The BVH against brute force, ray by ray and in packets.

use super::*;

fn quad(y: f32, half: f32, occludes: bool) -> [BvhTriangle; 2] {
    let c = [
        Vec3::new(-half, y, half),
        Vec3::new(half, y, half),
        Vec3::new(half, y, -half),
        Vec3::new(-half, y, -half),
    ];
    [
        BvhTriangle {
            corners: [c[0], c[1], c[2]],
            occludes,
        },
        BvhTriangle {
            corners: [c[0], c[2], c[3]],
            occludes,
        },
    ]
}

#[test]
fn closest_of_two_planes_is_found() {
    let mut tris = quad(0.0, 5.0, true).to_vec();
    tris.extend(quad(1.0, 0.5, true));
    let bvh = TriangleBvh::new(&tris);
    let down = DVec3::NEG_Y;
    let hit = bvh
        .closest_hit(DVec3::new(0.1, 3.0, 0.2), down, 0.0, f64::INFINITY)
        .unwrap();
    assert_eq!(hit.at.t, 2.0);
    assert!(hit.triangle >= 2);
    let hit = bvh
        .closest_hit(DVec3::new(2.0, 3.0, 0.2), down, 0.0, f64::INFINITY)
        .unwrap();
    assert_eq!(hit.at.t, 3.0);
    assert!(
        bvh.closest_hit(DVec3::new(9.0, 3.0, 0.0), down, 0.0, f64::INFINITY)
            .is_none()
    );
}

#[test]
fn only_occluders_block_and_only_inside_the_segment() {
    let mut tris = quad(0.0, 5.0, true).to_vec();
    tris.extend(quad(1.0, 0.5, false));
    let bvh = TriangleBvh::new(&tris);
    let o = DVec3::new(0.0, 3.0, 0.0);
    assert!(bvh.occluded(o, DVec3::NEG_Y, 0.0, 3.5));
    assert!(
        !bvh.occluded(o, DVec3::NEG_Y, 0.0, 2.5),
        "the upper quad casts no shadow"
    );
    assert!(
        !bvh.occluded(o, DVec3::NEG_Y, 0.0, 3.0),
        "the segment ends at the plane"
    );
}

#[test]
fn a_far_away_camera_keeps_exact_hits() {
    let tris = quad(0.0, 1.0, true);
    let bvh = TriangleBvh::new(&tris);
    let o = DVec3::new(0.3e6, 1.0e6, -0.2e6);
    let target = DVec3::new(0.999_999, 0.0, 0.5);
    let d = (target - o).normalize();
    let hit = bvh.closest_hit(o, d, 0.0, f64::INFINITY).unwrap();
    assert!((o + d * hit.at.t - target).length() < 1e-9);
}

#[test]
fn nothing_to_hit_is_fine() {
    let degenerate = [BvhTriangle {
        corners: [Vec3::ZERO, Vec3::X, Vec3::X * 2.0],
        occludes: true,
    }];
    for tris in [&degenerate[..], &[]] {
        let bvh = TriangleBvh::new(tris);
        assert!(bvh.is_empty());
        assert!(
            bvh.closest_hit(DVec3::Y, DVec3::NEG_Y, 0.0, f64::INFINITY)
                .is_none()
        );
        assert!(!bvh.occluded(DVec3::Y, DVec3::NEG_Y, 0.0, 2.0));
    }
}

/// A triangle with a corner not finite and a far one of zero area:
/// left out of the hits and of the scene's box, the others kept under
/// their own indices.
#[test]
fn unusable_triangles_are_left_out() {
    let mut tris = quad(0.0, 1.0, true).to_vec();
    tris.insert(
        1,
        BvhTriangle {
            corners: [Vec3::ZERO, Vec3::NAN, Vec3::X],
            occludes: true,
        },
    );
    tris.push(BvhTriangle {
        corners: [1e30, 2e30, 3e30].map(Vec3::splat),
        occludes: true,
    });
    let bvh = TriangleBvh::new(&tris);
    assert_eq!(bvh.len(), 2);
    assert!(bvh.min.cmpgt(DVec3::splat(-1.1)).all() && bvh.max.cmplt(DVec3::splat(1.1)).all());
    let mut found = Vec::new();
    for x in [-0.9, -0.5, 0.0, 0.5, 0.9] {
        for z in [-0.9, -0.5, 0.0, 0.5, 0.9] {
            let o = DVec3::new(x, 1.0, z + 0.013);
            let hit = bvh.closest_hit(o, DVec3::NEG_Y, 0.0, f64::INFINITY).unwrap();
            assert!((hit.at.t - 1.0).abs() < 1e-12);
            found.push(hit.triangle);
        }
    }
    found.sort_unstable();
    found.dedup();
    assert_eq!(found, [0, 2]);
}

/// Built in groups (a new root over eight BVHs), by obvhs's fast or
/// very fast build, the BVH still finds what brute force finds, ray by
/// ray and in packets, on rays aimed at corners and edges too.
#[test]
fn a_bvh_built_in_groups_equals_brute_force() {
    for very_fast_from in [usize::MAX, 0] {
        bvh_in_groups_equals_brute_force(very_fast_from);
    }
}

fn bvh_in_groups_equals_brute_force(very_fast_from: usize) {
    use crate::reference::sampling::Rng;
    let rng = &mut Rng::new(11, 0, 0);
    let mut tris = quad(0.0, 6.0, true).to_vec();
    for s in 0..12 {
        let (x, y, z) = (rng.next_f64(), rng.next_f64(), rng.next_f64());
        let centre = DVec3::new(4.0 * x - 2.0, y, 4.0 * z - 2.0).as_vec3();
        let sphere = crate::scene::shapes::sphere(centre, 0.2 + rng.next_f64() as f32, 24, 12);
        tris.extend((0..sphere.triangle_count()).map(|t| BvhTriangle {
            corners: sphere.triangle(t),
            occludes: s % 3 != 0,
        }));
    }
    let bvh = TriangleBvh::in_groups(tris.as_slice(), (300, very_fast_from));
    let root = &bvh.bvh.as_ref().unwrap().nodes[0];
    assert_eq!(root.imask.count_ones(), 8, "eight groups");
    // A corner, a point on an edge or inside a random triangle.
    let aim = |rng: &mut Rng| {
        let [a, b, c] = tris[(rng.next_f64() * tris.len() as f64) as usize].corners_f64();
        match (rng.next_f64() * 3.0) as u32 {
            0 => a,
            1 => a.lerp(b, rng.next_f64()),
            _ => a.lerp(b, rng.next_f64()).lerp(c, rng.next_f64()),
        }
    };
    let mut packet = PrimaryPacket::default();
    let (mut hits, mut blocked) = (0, 0);
    for case in 0..300 {
        let (x, y, z) = (rng.next_f64(), rng.next_f64(), rng.next_f64());
        let apex = DVec3::new(12.0 * x - 6.0, 4.0 * y, 12.0 * z - 6.0);
        let centre = aim(rng);
        // Rays from one apex around a point on a triangle: a packet.
        let directions: Vec<DVec3> = (0..12)
            .map(|k| {
                let target = if k % 2 == 0 {
                    aim(rng)
                } else {
                    centre + DVec3::splat(0.1 * rng.next_f64() - 0.05)
                };
                target - apex
            })
            .collect();
        let Some(cone) = Cone::around(apex, directions.iter().map(|&d| apex + d)) else {
            continue;
        };
        bvh.closest_hits_in_cone(&cone, &directions, &mut packet);
        for (k, &d) in directions.iter().enumerate() {
            let expected = closest_hit_brute_force(&tris, apex, d, 0.0, f64::INFINITY);
            let t = |h: Option<Hit>| h.map(|h| h.at.t);
            assert_eq!(
                t(bvh.closest_hit(apex, d, 0.0, f64::INFINITY)),
                t(expected),
                "{case}/{k}"
            );
            assert_eq!(t(packet.hits[k]), t(expected), "{case}/{k}: packet");
            let expected = occluded_brute_force(&tris, apex, d, 0.0, 1.0);
            assert_eq!(bvh.occluded(apex, d, 0.0, 1.0), expected, "{case}/{k}: segment");
            hits += usize::from(t(packet.hits[k]).is_some());
            blocked += usize::from(expected);
        }
    }
    assert!(hits > 1000 && blocked > 300, "{hits} hits, {blocked} blocked");
}
