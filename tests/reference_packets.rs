//! Packets of rays walk the BVH together and still give every ray exactly
//! what it gets on its own and what testing every triangle gives: the same
//! closest hit (distance and barycentrics bit for bit, the lowest index among
//! equal distances) and the same shadow-ray answer. The scene is a bumpy
//! height field (every edge and vertex shared), a few floating triangles and
//! a box; the rays include rays aimed exactly at vertices and edges, rays
//! that miss, narrow packets (a pixel's samples) and packets whose rays
//! diverge across the whole scene.

use glam::DVec3;
use lumlab::reference::bvh::{
    BvhTriangle, Cone, PrimaryPacket, ShadowPacket, TriangleBvh, closest_hit_brute_force,
    occluded_brute_force,
};
use lumlab::reference::sampling::Rng;

/// Vertices per side of the height field.
const SIDE: usize = 24;

/// The height field's vertex (i, j): 8 m across, heights up to 0.6 m.
fn vertex(i: usize, j: usize, heights: &[f64]) -> DVec3 {
    let step = 8.0 / (SIDE - 1) as f64;
    DVec3::new(
        -4.0 + i as f64 * step,
        heights[j * SIDE + i],
        -4.0 + j as f64 * step,
    )
}

fn scene(rng: &mut Rng) -> Vec<BvhTriangle> {
    let heights: Vec<f64> = (0..SIDE * SIDE).map(|_| 0.6 * rng.next_f64()).collect();
    let mut corners = Vec::new();
    for j in 0..SIDE - 1 {
        for i in 0..SIDE - 1 {
            let [a, b, c, d] =
                [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)].map(|(x, z)| vertex(x, z, &heights));
            corners.push([a, d, c]);
            corners.push([a, c, b]);
        }
    }
    let mut random = |lo: f64, hi: f64| lo + (hi - lo) * rng.next_f64();
    for _ in 0..40 {
        let a = DVec3::new(random(-4.0, 4.0), random(0.8, 2.5), random(-4.0, 4.0));
        let spread = random(0.05, 1.0);
        let mut near = || a + DVec3::new(random(-1.0, 1.0), random(-0.3, 0.3), random(-1.0, 1.0)) * spread;
        corners.push([a, near(), near()]);
    }
    // A unit box standing on the field (its faces share edges and corners).
    let b = |x: f64, y: f64, z: f64| DVec3::new(0.5 + x, 0.6 + y, -1.0 + z);
    let c = [
        b(0., 0., 0.),
        b(1., 0., 0.),
        b(1., 1., 0.),
        b(0., 1., 0.),
        b(0., 0., 1.),
        b(1., 0., 1.),
        b(1., 1., 1.),
        b(0., 1., 1.),
    ];
    for [p, q, r, s] in [
        [0, 1, 2, 3],
        [5, 4, 7, 6],
        [4, 0, 3, 7],
        [1, 5, 6, 2],
        [3, 2, 6, 7],
        [4, 5, 1, 0],
    ] {
        corners.push([c[p], c[q], c[r]]);
        corners.push([c[p], c[r], c[s]]);
    }
    corners
        .into_iter()
        .enumerate()
        .map(|(i, corners)| BvhTriangle {
            corners: corners.map(|p| p.as_vec3()),
            occludes: i % 3 != 0,
        })
        .collect()
}

/// A point of a random triangle: a corner, a point of an edge, or inside.
fn point_on(triangles: &[BvhTriangle], rng: &mut Rng) -> DVec3 {
    let [a, b, c] =
        triangles[(rng.next_f64() * triangles.len() as f64) as usize % triangles.len()].corners_f64();
    match (rng.next_f64() * 3.0) as u32 {
        0 => a,
        1 => a.lerp(b, rng.next_f64()),
        _ => a.lerp(b, rng.next_f64()).lerp(c, rng.next_f64()),
    }
}

/// Points on triangles near a random one (within `reach` m), some far off
/// it when `reach` is large: what a narrow or a diverging packet aims at.
fn targets(triangles: &[BvhTriangle], rng: &mut Rng, reach: f64, count: usize) -> Vec<DVec3> {
    let first = point_on(triangles, rng);
    let mut out = vec![first];
    while out.len() < count {
        let p = point_on(triangles, rng);
        if (p - first).length() <= reach {
            out.push(p);
        } else {
            // Somewhere near the first one, on no triangle in particular.
            let jitter = DVec3::new(rng.next_f64() - 0.5, rng.next_f64() - 0.5, rng.next_f64() - 0.5);
            out.push(first + jitter * reach);
        }
    }
    out
}

fn random_apex(rng: &mut Rng) -> DVec3 {
    DVec3::new(
        12.0 * rng.next_f64() - 6.0,
        1.0 + 5.0 * rng.next_f64(),
        12.0 * rng.next_f64() - 6.0,
    )
}

#[test]
fn primary_packets_find_what_each_ray_and_brute_force_find() {
    let mut rng = Rng::new(21, 0, 0);
    let triangles = scene(&mut rng);
    let bvh = TriangleBvh::new(&triangles);
    let mut packet = PrimaryPacket::default();
    let mut hits = 0;
    for case in 0..300 {
        let apex = random_apex(&mut rng);
        let reach = [0.01, 0.2, 3.0, 20.0][case % 4];
        let points = targets(&triangles, &mut rng, reach, 24);
        let Some(cone) = Cone::around(apex, points.iter().copied()) else {
            continue;
        };
        // Rays at the targets (vertices, edges), not normalized, and a few
        // between them.
        let mut directions: Vec<DVec3> = points
            .iter()
            .map(|&p| (p - apex) * (0.5 + rng.next_f64()))
            .collect();
        for k in 0..8 {
            let (a, b) = (directions[k], directions[k + 8]);
            directions.push(a.normalize().lerp(b.normalize(), rng.next_f64()));
        }
        bvh.closest_hits_in_cone(&cone, &directions, &mut packet);
        for (d, found) in directions.iter().zip(&packet.hits) {
            let alone = bvh.closest_hit(apex, *d, 0.0, f64::INFINITY);
            let brute = closest_hit_brute_force(&triangles, apex, *d, 0.0, f64::INFINITY);
            assert_eq!(
                *found, alone,
                "case {case}: packet against the ray alone, {apex} along {d}"
            );
            assert_eq!(alone, brute, "case {case}: the ray alone against brute force");
            hits += usize::from(found.is_some());
        }
    }
    assert!(hits > 3000, "too few hits to tell: {hits}");
}

#[test]
fn pixel_cones_hold_their_samples_and_find_what_brute_force_finds() {
    // As the reference casts a pixel: four corner rays span the cone, the
    // samples are bilinear mixes of them, at the packet's edges too.
    let mut rng = Rng::new(22, 0, 0);
    let triangles = scene(&mut rng);
    let bvh = TriangleBvh::new(&triangles);
    let mut packet = PrimaryPacket::default();
    for case in 0..300 {
        let apex = random_apex(&mut rng);
        let centre = point_on(&triangles, &mut rng) - apex;
        let (u, v) = centre.normalize().any_orthonormal_pair();
        let size = [1e-4, 1e-3, 0.05, 0.5][case % 4] * centre.length();
        let corner = |x: f64, y: f64| centre + u * (x * size) + v * (y * size);
        let corners = [
            corner(-1.0, -1.0),
            corner(1.0, -1.0),
            corner(1.0, 1.0),
            corner(-1.0, 1.0),
        ];
        let cone = Cone::spanned(apex, corners);
        let mut directions: Vec<DVec3> = corners.to_vec();
        directions.push(centre);
        for _ in 0..27 {
            let (x, y) = (2.0 * rng.next_f64() - 1.0, 2.0 * rng.next_f64() - 1.0);
            directions.push(corner(x, y));
        }
        bvh.closest_hits_in_cone(&cone, &directions, &mut packet);
        for (d, found) in directions.iter().zip(&packet.hits) {
            let brute = closest_hit_brute_force(&triangles, apex, *d, 0.0, f64::INFINITY);
            assert_eq!(*found, brute, "case {case}: {apex} along {d}");
        }
    }
}

#[test]
fn shadow_packets_block_what_each_ray_and_brute_force_block() {
    let mut rng = Rng::new(23, 0, 0);
    let triangles = scene(&mut rng);
    let bvh = TriangleBvh::new(&triangles);
    let mut packet = ShadowPacket::default();
    let (mut blocked, mut total) = (0, 0);
    for case in 0..300 {
        let light = random_apex(&mut rng);
        let reach = [0.01, 0.2, 3.0, 20.0][case % 4];
        // Origins on triangles (segments from vertices and edges), and
        // the light's side of them; segments that end exactly on a triangle
        // (t_max = 1) and that stop short of the light.
        let origins = targets(&triangles, &mut rng, reach, 24);
        let Some(cone) = Cone::around(light, origins.iter().copied()) else {
            continue;
        };
        // The floor's normal changes no answer: none, a random one, the
        // light's direction from the origins (a floor just below the lowest
        // of them) and its opposite.
        let towards = (light - origins.iter().sum::<DVec3>() / origins.len() as f64).normalize();
        let random = DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) - 0.5;
        let up = [DVec3::ZERO, random.normalize(), towards, -towards][case / 4 % 4];
        for t_max in [1.0, 1.0 - 1e-9] {
            bvh.occluded_in_cone(&cone, (&origins, up, &[]), t_max, &mut packet);
            for (i, &o) in origins.iter().enumerate() {
                let alone = bvh.occluded(o, light - o, 0.0, t_max);
                let brute = occluded_brute_force(&triangles, o, light - o, 0.0, t_max);
                assert_eq!(packet.blocked(i), alone, "case {case}: from {o} to {light}");
                assert_eq!(alone, brute, "case {case}: the ray alone against brute force");
                blocked += usize::from(alone);
                total += 1;
            }
        }
    }
    assert!(
        blocked > total / 10 && blocked < total * 9 / 10,
        "{blocked} of {total} blocked"
    );
}

/// Shadow rays lifted off height-field triangles, as the reference lifts
/// them (10⁻⁹ of the triangle's largest coordinate along its normal on the
/// light's side), each passing over its own triangle where the light lies
/// on that side by more than the lift: the same answers as brute force over
/// every triangle, own ones included, which the packet never tests.
#[test]
fn a_ray_passing_over_its_own_triangle_blocks_as_brute_force_does() {
    let mut rng = Rng::new(29, 0, 0);
    let triangles = scene(&mut rng);
    let field = 2 * (SIDE - 1) * (SIDE - 1);
    let bvh = TriangleBvh::new(&triangles);
    let mut packet = ShadowPacket::default();
    let (mut blocked, mut passed, mut total) = (0, 0, 0);
    for case in 0..300 {
        let light = random_apex(&mut rng);
        let first = (rng.next_f64() * field as f64) as usize % field;
        let (mut origins, mut passes) = (Vec::new(), Vec::new());
        for _ in 0..32 {
            // Triangles within about a row of cells of the first one (by index).
            let near = first as f64 + (rng.next_f64() - 0.5) * 4.0 * (SIDE - 1) as f64;
            let index = (near.max(0.0) as usize).min(field - 1);
            let [a, b, c] = triangles[index].corners_f64();
            let p = a.lerp(b, rng.next_f64()).lerp(c, rng.next_f64());
            let face = (b - a).cross(c - a).normalize();
            let to_light = light - p;
            let n = if face.dot(to_light) < 0.0 { -face } else { face };
            let lift = 1e-9
                * [a, b, c]
                    .iter()
                    .fold(0.0_f64, |m, q| m.max(q.abs().max_element()));
            let clear = n.dot(to_light) > lift + 1e-12 * to_light.abs().element_sum();
            origins.push(p + n * lift);
            passes.push(if clear { index } else { usize::MAX });
            passed += usize::from(clear);
        }
        let Some(cone) = Cone::around(light, origins.iter().copied()) else {
            continue;
        };
        let up = [DVec3::ZERO, DVec3::Y][case % 2];
        bvh.occluded_in_cone(&cone, (&origins, up, &passes), 1.0 - 1e-9, &mut packet);
        for (i, &o) in origins.iter().enumerate() {
            let brute = occluded_brute_force(&triangles, o, light - o, 0.0, 1.0 - 1e-9);
            assert_eq!(packet.blocked(i), brute, "case {case}: from {o} to {light}");
            blocked += usize::from(brute);
            total += 1;
        }
    }
    assert!(
        passed * 2 > total,
        "{passed} of {total} rays passed over their triangle"
    );
    assert!(
        blocked > total / 10 && blocked < total * 9 / 10,
        "{blocked} of {total} blocked"
    );
}

#[test]
fn a_packet_looking_away_or_at_nothing_finds_nothing() {
    let mut rng = Rng::new(24, 0, 0);
    let triangles = scene(&mut rng);
    let bvh = TriangleBvh::new(&triangles);
    let apex = DVec3::new(0.0, 3.0, 0.0);
    let up = [
        DVec3::new(-0.1, 1.0, -0.1),
        DVec3::new(0.1, 1.0, -0.1),
        DVec3::new(0.1, 1.0, 0.1),
        DVec3::new(-0.1, 1.0, 0.1),
    ];
    let mut packet = PrimaryPacket::default();
    bvh.closest_hits_in_cone(&Cone::spanned(apex, up), &up, &mut packet);
    assert!(packet.hits.iter().all(Option::is_none));
    let empty = TriangleBvh::new(&[]);
    let down = up.map(|d| -d);
    empty.closest_hits_in_cone(&Cone::spanned(apex, down), &down, &mut packet);
    assert!(packet.hits.iter().all(Option::is_none));
    assert!(Cone::around(apex, [apex + DVec3::X, apex - DVec3::X].into_iter()).is_none());
}

/// Directions from `apex` to points of `triangles` near `aim`, some
/// through vertices and edges, some along the diagonals where two axes
/// weigh the same (so a packet may hold rays with different main axes).
fn packet_directions(triangles: &[BvhTriangle], rng: &mut Rng, apex: DVec3, count: usize) -> Vec<DVec3> {
    let mut out: Vec<DVec3> = targets(triangles, rng, 0.3, count)
        .into_iter()
        .map(|p| p - apex)
        .collect();
    for d in out.iter_mut().skip(1).step_by(3) {
        // |d_x| = |d_y| or |d_y| = |d_z| exactly: the tie between axes.
        if rng.next_f64() < 0.5 {
            d.x = d.y.abs().copysign(d.x);
        } else {
            d.z = d.y.abs().copysign(d.z);
        }
    }
    out
}

#[test]
fn packets_of_every_size_and_mixed_axes_agree_with_each_ray_and_brute_force() {
    // The packets test their rays four at a time when all share one main
    // axis: sizes that leave a group part-filled, and packets whose rays
    // straddle a tie between axes, must still give each ray its own answer.
    let mut rng = Rng::new(25, 0, 0);
    let triangles = scene(&mut rng);
    let bvh = TriangleBvh::new(&triangles);
    let (mut primary, mut shadow) = (PrimaryPacket::default(), ShadowPacket::default());
    let (mut hits, mut blocked) = (0, 0);
    for case in 0..600 {
        let count = 1 + case % 13;
        let apex = random_apex(&mut rng);
        let directions = packet_directions(&triangles, &mut rng, apex, count);
        let Some(cone) = Cone::around(apex, directions.iter().map(|&d| apex + d)) else {
            continue;
        };
        bvh.closest_hits_in_cone(&cone, &directions, &mut primary);
        for (d, found) in directions.iter().zip(&primary.hits) {
            let brute = closest_hit_brute_force(&triangles, apex, *d, 0.0, f64::INFINITY);
            assert_eq!(*found, brute, "case {case}: {apex} along {d}");
            hits += usize::from(found.is_some());
        }
        // The same points as shadow-ray origins towards a light at the apex.
        let origins: Vec<DVec3> = directions.iter().map(|&d| apex + d).collect();
        let up = DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) - 0.5;
        bvh.occluded_in_cone(&cone, (&origins, up.normalize(), &[]), 1.0, &mut shadow);
        for (i, &o) in origins.iter().enumerate() {
            let brute = occluded_brute_force(&triangles, o, apex - o, 0.0, 1.0);
            assert_eq!(shadow.blocked(i), brute, "case {case}: from {o} to {apex}");
            blocked += usize::from(brute);
        }
    }
    assert!(
        hits > 1000 && blocked > 300,
        "too few to tell: {hits} hits, {blocked} blocked"
    );
}

/// A small surface a fraction of a millimetre in front of a large one
/// tilted towards the eye, whose box therefore comes nearer along the
/// cone's axis: the walk finds the large one first and must still reach the
/// small one, its depth filters allowing for rounding only, not for
/// millimetres.
#[test]
fn a_surface_a_hair_in_front_of_a_hit_is_still_found() {
    let mut rng = Rng::new(24, 0, 0);
    let eye = DVec3::new(0.0, 0.0, 5.0);
    // The large one: z = 0.2 y, 20 m across, 3 m from the eye at its nearest.
    let far = |x: f64, y: f64| DVec3::new(x, y, 0.2 * y);
    let mut corners = vec![
        [far(-10.0, -10.0), far(10.0, -10.0), far(10.0, 10.0)],
        [far(-10.0, -10.0), far(10.0, 10.0), far(-10.0, 10.0)],
    ];
    // The small one, flat at z = 5e-4 m around the axis, 0.3 to 0.7 mm in
    // front of the large one where the rays meet it.
    let near = |x: f64, y: f64| DVec3::new(x, y, 5e-4);
    corners.push([near(-0.001, -0.001), near(0.001, -0.001), near(0.0, 0.001)]);
    // Tiny triangles around it in its plane, off the rays, so that it
    // shares its leaves and nodes with them, not with the large one, and
    // their boxes come no nearer than it.
    corners.extend(ring(&mut rng, near, DVec3::Y));
    let triangles = occluders(corners);
    let bvh = TriangleBvh::new(&triangles);
    // Rays at points of the small one (barycentric mixes inside it).
    let directions: Vec<DVec3> = (0..16)
        .map(|_| {
            let (u, v) = (0.1 + 0.4 * rng.next_f64(), 0.1 + 0.4 * rng.next_f64());
            let [a, b, c] = triangles[2].corners_f64();
            a + (b - a) * u + (c - a) * v - eye
        })
        .collect();
    let cone = Cone::around(eye, directions.iter().map(|&d| eye + d)).expect("all in front");
    let mut packet = PrimaryPacket::default();
    bvh.closest_hits_in_cone(&cone, &directions, &mut packet);
    for (d, found) in directions.iter().zip(&packet.hits) {
        let brute = closest_hit_brute_force(&triangles, eye, *d, 0.0, f64::INFINITY);
        assert_eq!(
            brute.map(|h| h.triangle),
            Some(2),
            "the small one is in front along {d}"
        );
        assert_eq!(*found, brute, "packet against brute force along {d}");
    }
}

#[test]
fn a_blocker_a_hair_above_the_floor_still_blocks() {
    // Shadow origins on flat ground (y = 0) under a light 4 m up, the floor
    // across +y just below them; a small triangle 0.5 mm above the ground
    // over some origins, among tiny ones beside it (so that it shares its
    // leaves and nodes with them), blocks the rays through it. A floor
    // raised by 1 mm would pass over it.
    let mut rng = Rng::new(26, 0, 0);
    let light = DVec3::new(0.3, 4.0, -0.2);
    let flat = |x: f64, z: f64, y: f64| DVec3::new(x, y, z);
    let mut corners = vec![
        [flat(-5.0, -5.0, 0.0), flat(-5.0, 5.0, 0.0), flat(5.0, 5.0, 0.0)],
        [flat(-5.0, -5.0, 0.0), flat(5.0, 5.0, 0.0), flat(5.0, -5.0, 0.0)],
        [
            flat(-0.01, -0.01, 5e-4),
            flat(-0.01, 0.01, 5e-4),
            flat(0.01, 0.0, 5e-4),
        ],
    ];
    corners.extend(ring(&mut rng, |x, z| flat(x, z, 5e-4), DVec3::Z));
    let triangles = occluders(corners);
    let bvh = TriangleBvh::new(&triangles);
    let origins: Vec<DVec3> = (0..24)
        .map(|_| flat(0.03 * (rng.next_f64() - 0.5), 0.03 * (rng.next_f64() - 0.5), 0.0))
        .collect();
    let cone = Cone::around(light, origins.iter().copied()).expect("all below the light");
    let mut packet = ShadowPacket::default();
    bvh.occluded_in_cone(&cone, (&origins, DVec3::Y, &[]), 1.0 - 1e-9, &mut packet);
    let mut blocked = 0;
    for (i, &o) in origins.iter().enumerate() {
        let brute = occluded_brute_force(&triangles, o, light - o, 0.0, 1.0 - 1e-9);
        assert_eq!(packet.blocked(i), brute, "from {o}");
        blocked += usize::from(brute);
    }
    assert!(
        blocked > 2 && blocked < origins.len(),
        "{blocked} of {} blocked",
        origins.len()
    );
}

/// 64 triangles 1 cm across, 5 to 25 cm from the middle of the plane that
/// `at` maps (x, y) into, their second side along `side`.
fn ring(rng: &mut Rng, at: impl Fn(f64, f64) -> DVec3, side: DVec3) -> Vec<[DVec3; 3]> {
    (0..64)
        .map(|k| {
            let angle = k as f64 * std::f64::consts::TAU / 64.0;
            let radius = 0.05 + 0.2 * rng.next_f64();
            let a = at(radius * angle.cos(), radius * angle.sin());
            [a, a + DVec3::X * 0.01, a + side * 0.01]
        })
        .collect()
}

/// Triangles that all cast shadows.
fn occluders(corners: Vec<[DVec3; 3]>) -> Vec<BvhTriangle> {
    corners
        .into_iter()
        .map(|corners| BvhTriangle {
            corners: corners.map(|p| p.as_vec3()),
            occludes: true,
        })
        .collect()
}
