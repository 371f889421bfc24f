//! The BVH finds exactly what testing every triangle finds: the same closest
//! hit (same distance, bit for bit) and the same shadow-ray answer, on
//! thousands of random rays through a generated scene of spheres and boxes,
//! including rays aimed at vertices and edges, rays from far away and rays
//! whose direction is a micrometre long. The direction grids (rays from or to
//! a common point) agree with brute force too.

use glam::{DVec3, Vec3};
use lumlab::reference::bvh::{BvhTriangle, TriangleBvh, closest_hit_brute_force, occluded_brute_force};
use lumlab::reference::grid::{Answer, DirectionGrid};
use lumlab::reference::sampling::Rng;
use lumlab::reference::{SHADOW_OFFSET_REL, STOP_SHORT_REL};
use lumlab::scene::{Aabb, Camera, Mesh, shapes};

/// A ground, 12 boxes and 12 spheres at random places; every other object
/// casts no shadow so that the shadow-ray filter is exercised too.
fn generated_scene(rng: &mut Rng) -> Vec<BvhTriangle> {
    let mut meshes: Vec<Mesh> = vec![shapes::ground(Vec3::ZERO, 10.0)];
    let mut random = |lo: f64, hi: f64| (lo + (hi - lo) * rng.next_f64()) as f32;
    for _ in 0..12 {
        let min = Vec3::new(random(-4.0, 4.0), random(0.0, 1.0), random(-4.0, 4.0));
        let size = Vec3::new(random(0.1, 1.5), random(0.1, 1.5), random(0.1, 1.5));
        meshes.push(shapes::cuboid(Aabb { min, max: min + size }));
        let centre = Vec3::new(random(-4.0, 4.0), random(0.2, 2.0), random(-4.0, 4.0));
        meshes.push(shapes::sphere(centre, random(0.1, 0.8), 24, 12));
    }
    let mut triangles = Vec::new();
    for (i, mesh) in meshes.iter().enumerate() {
        for t in 0..mesh.triangle_count() {
            triangles.push(BvhTriangle {
                corners: mesh.triangle(t),
                occludes: i % 2 == 0,
            });
        }
    }
    triangles
}

fn random_direction(rng: &mut Rng) -> DVec3 {
    // Uniform on the sphere: z uniform in [−1, 1], φ uniform.
    let z = 2.0 * rng.next_f64() - 1.0;
    let phi = std::f64::consts::TAU * rng.next_f64();
    let s = (1.0 - z * z).sqrt();
    DVec3::new(s * phi.cos(), z, s * phi.sin())
}

fn random_point(rng: &mut Rng, half: f64) -> DVec3 {
    DVec3::new(
        (2.0 * rng.next_f64() - 1.0) * half,
        (2.0 * rng.next_f64() - 1.0) * half + half * 0.5,
        (2.0 * rng.next_f64() - 1.0) * half,
    )
}

/// A random triangle's index.
fn random_triangle(triangles: &[BvhTriangle], rng: &mut Rng) -> usize {
    (rng.next_f64() * triangles.len() as f64) as usize % triangles.len()
}

/// A point on a random triangle: a corner, a point on an edge, or inside.
fn point_on(triangles: &[BvhTriangle], rng: &mut Rng) -> DVec3 {
    let tri = &triangles[random_triangle(triangles, rng)];
    point_on_triangle(tri, rng)
}

/// A point on the triangle: a corner, a point on an edge, or inside.
fn point_on_triangle(tri: &BvhTriangle, rng: &mut Rng) -> DVec3 {
    let [a, b, c] = tri.corners_f64();
    match (rng.next_f64() * 3.0) as u32 {
        0 => a,
        1 => a.lerp(b, rng.next_f64()),
        _ => {
            let (u, v) = (rng.next_f64(), rng.next_f64());
            let (u, v) = if u + v > 1.0 { (1.0 - u, 1.0 - v) } else { (u, v) };
            a + (b - a) * u + (c - a) * v
        }
    }
}

#[test]
fn bvh_hits_equal_brute_force_on_random_rays() {
    let mut rng = Rng::new(7, 0, 0);
    let triangles = generated_scene(&mut rng);
    assert!(triangles.len() > 5000, "{} triangles", triangles.len());
    let bvh = TriangleBvh::new(&triangles);
    let (mut hits, mut blocked) = (0, 0);
    for ray in 0..8000 {
        let (origin, direction) = match ray % 4 {
            // From anywhere, anywhere.
            0 => (random_point(&mut rng, 7.0), random_direction(&mut rng)),
            // Aimed at a vertex, an edge or a face.
            1 => {
                let origin = random_point(&mut rng, 7.0);
                (origin, point_on(&triangles, &mut rng) - origin)
            }
            // From just off a surface to another, with a direction a
            // micrometre long (shadow rays are not normalized).
            3 => {
                let origin = point_on(&triangles, &mut rng) + random_direction(&mut rng) * 1e-6;
                (origin, (point_on(&triangles, &mut rng) - origin) * 1e-6)
            }
            // From far away (a camera a kilometre off), at the scene.
            _ => {
                let origin = random_direction(&mut rng) * 1000.0;
                (origin, point_on(&triangles, &mut rng) - origin)
            }
        };
        if direction.length_squared() == 0.0 {
            continue;
        }
        let expected = closest_hit_brute_force(&triangles, origin, direction, 0.0, f64::INFINITY);
        let got = bvh.closest_hit(origin, direction, 0.0, f64::INFINITY);
        match (expected, got) {
            (None, None) => {}
            (Some(e), Some(g)) => {
                // Two triangles can share the hit (an edge): then either is right.
                assert_eq!(e.at.t, g.at.t, "ray {ray}: {origin} → {direction}");
                if e.triangle != g.triangle {
                    let again = closest_hit_brute_force(
                        &triangles[g.triangle..=g.triangle],
                        origin,
                        direction,
                        0.0,
                        f64::INFINITY,
                    );
                    assert_eq!(again.map(|h| h.at.t), Some(g.at.t), "ray {ray}");
                }
                hits += 1;
            }
            _ => panic!("ray {ray}: {origin} → {direction}: brute force {expected:?}, BVH {got:?}"),
        }
        // A shadow-ray segment along the same ray, ending at a random length.
        let t_max = rng.next_f64() * if ray % 4 == 3 { 2e6 } else { 2.0 };
        let expected = occluded_brute_force(&triangles, origin, direction, 0.0, t_max);
        assert_eq!(
            bvh.occluded(origin, direction, 0.0, t_max),
            expected,
            "segment {ray}"
        );
        blocked += expected as u32;
    }
    // The rays really exercised both answers.
    assert!(
        hits > 2000 && blocked > 300,
        "{hits} hits, {blocked} blocked segments"
    );
}

#[test]
fn direction_grids_equal_brute_force_for_rays_through_their_centre() {
    let mut rng = Rng::new(11, 0, 0);
    let triangles = generated_scene(&mut rng);
    let centres = [
        // A camera outside, a light above, a point on the ground (a light
        // lying on a surface) and a box corner.
        DVec3::new(6.0, 4.0, 9.0),
        DVec3::new(0.5, 5.0, -0.3),
        DVec3::new(1.25, 0.0, -2.5),
        triangles[2].corners_f64()[0],
    ];
    let (mut answered, mut deferred) = (0, 0);
    for centre in centres {
        let grid = DirectionGrid::new(centre, &triangles, |_| true);
        let occluders = DirectionGrid::new(centre, &triangles, |t| t.occludes);
        for ray in 0..3000 {
            let target = match ray % 3 {
                0 => point_on(&triangles, &mut rng),
                1 => centre + random_direction(&mut rng),
                // On the edges between cube faces: |x| = |y|.
                _ => {
                    let d = random_direction(&mut rng);
                    centre
                        + DVec3::new(
                            d.x.abs().max(d.y.abs()) * d.x.signum(),
                            d.x.abs().max(d.y.abs()) * d.y.signum(),
                            d.z,
                        )
                }
            };
            let direction = target - centre;
            if direction.length_squared() == 0.0 {
                continue;
            }
            match grid.closest_from_centre(direction) {
                Answer::Known(hit) => {
                    let expected = closest_hit_brute_force(&triangles, centre, direction, 0.0, f64::INFINITY);
                    assert_eq!(hit, expected, "ray {ray} from {centre} along {direction}");
                    answered += 1;
                }
                Answer::AskBvh => deferred += 1,
            }
            // A shadow ray from somewhere along the line towards the centre.
            let origin = centre + direction * (0.2 + 2.0 * rng.next_f64());
            let t_max = 1.0 - 1e-9;
            if let Answer::Known(blocked) = occluders.blocked_towards_centre(&triangles, origin, t_max, None)
            {
                let expected = occluded_brute_force(&triangles, origin, centre - origin, 0.0, t_max);
                assert_eq!(blocked, expected, "shadow ray {ray} from {origin} to {centre}");
            }
        }
    }
    assert!(
        answered > 5000,
        "{answered} answered, {deferred} deferred to the BVH"
    );
}

/// A grid built for the rays towards a region (a camera's image rectangle,
/// as the render's eye grid is) answers those rays as the whole grid does,
/// and answers none wrongly elsewhere: beyond the region its cells defer to
/// the BVH (where no triangle is seen, such as the sky, they stay empty).
#[test]
fn a_grid_built_towards_a_region_answers_its_rays_as_the_whole_grid_does() {
    let mut rng = Rng::new(12, 0, 0);
    let triangles = generated_scene(&mut rng);
    let eye = DVec3::new(6.0, 4.0, 9.0);
    let forward = (DVec3::new(0.0, 0.5, 0.0) - eye).normalize();
    let right = forward.cross(DVec3::Y).normalize();
    let up = right.cross(forward);
    let (half_w, half_h) = (0.3, 0.2);
    let at = |x: f64, y: f64| eye + forward + right * (x * half_w) + up * (y * half_h);
    let [a, b, c, d] = [at(-1.0, -1.0), at(1.0, -1.0), at(1.0, 1.0), at(-1.0, 1.0)];
    let whole = DirectionGrid::new(eye, &triangles, |_| true);
    let seen = DirectionGrid::towards(eye, &triangles, |_| true, &[[a, b, c], [a, c, d]]);
    let (mut inside, mut cut, mut beyond) = (0, 0, 0);
    for ray in 0..6000 {
        // Half through the rectangle, half through one three times as wide.
        let scale = if ray % 2 == 0 { 1.0 } else { 3.0 };
        let (x, y) = (
            scale * (2.0 * rng.next_f64() - 1.0),
            scale * (2.0 * rng.next_f64() - 1.0),
        );
        let direction = at(x, y) - eye;
        let answer = seen.closest_from_centre(direction);
        if let Answer::Known(hit) = answer {
            let expected = closest_hit_brute_force(&triangles, eye, direction, 0.0, f64::INFINITY);
            assert_eq!(hit, expected, "ray {ray} along {direction}");
        }
        if x.abs() <= 1.0 && y.abs() <= 1.0 {
            assert_eq!(
                answer,
                whole.closest_from_centre(direction),
                "ray {ray} through the region"
            );
            inside += 1;
        } else if x.abs() > 1.5 || y.abs() > 1.5 {
            // Well beyond it: the cells the whole grid answers from are
            // mostly not built.
            beyond += 1;
            cut += usize::from(
                answer == Answer::AskBvh && whole.closest_from_centre(direction) != Answer::AskBvh,
            );
        }
    }
    assert!(
        inside > 3000 && cut > beyond / 10,
        "{inside} rays through the region; of {beyond} well beyond it, {cut} deferred by this grid alone"
    );
}

#[test]
fn occluders_gathered_near_a_ball_block_exactly_what_brute_force_does() {
    let mut rng = Rng::new(13, 0, 0);
    let triangles = generated_scene(&mut rng);
    let bvh = TriangleBvh::new(&triangles);
    let mut candidates = Vec::new();
    let (mut gathered, mut blocked) = (0, 0);
    for trial in 0..400 {
        // A shading point on the scene, a sphere light somewhere above.
        let from = point_on(&triangles, &mut rng) + DVec3::Y * 1e-6;
        let centre = random_point(&mut rng, 6.0) + DVec3::Y * 4.0;
        let radius = 0.05 + rng.next_f64();
        // Any plane through the point may be the walk's floor where the
        // ball lies above it: here the horizontal one, every other trial.
        let surface = if trial % 2 == 0 { DVec3::Y } else { DVec3::ZERO };
        if !bvh.gather_near_ball((from, surface), centre, radius, 4000, &mut candidates) {
            continue;
        }
        gathered += 1;
        for _ in 0..16 {
            // A point in the ball: the end of one shadow ray.
            let target = centre + random_direction(&mut rng) * radius * rng.next_f64().cbrt();
            let d = target - from;
            let expected = occluded_brute_force(&triangles, from, d, 0.0, 1.0 - 1e-9);
            assert_eq!(
                bvh.blocked_by(&candidates, from, d, 1.0 - 1e-9),
                expected,
                "trial {trial}: {from} → {target}"
            );
            blocked += expected as u32;
        }
    }
    assert!(
        gathered > 200 && blocked > 100,
        "{gathered} gathered, {blocked} blocked"
    );
}

/// The unit normal of the triangle on the light's side of point p, and
/// the shadow offset of its shadow rays (as the reference lifts them).
fn shadow_lift(tri: &BvhTriangle, p: DVec3, light: DVec3) -> (DVec3, f64) {
    let [a, b, c] = tri.corners_f64();
    let face = (b - a).cross(c - a).normalize();
    let normal = if face.dot(light - p) > 0.0 { face } else { -face };
    let largest = [a, b, c]
        .iter()
        .fold(0.0_f64, |m, q| m.max(q.abs().max_element()));
    (normal, SHADOW_OFFSET_REL * largest)
}

#[test]
fn a_shadow_ray_lifted_off_its_triangle_towards_the_light_never_meets_it() {
    // What lets the light's grid skip a shading point's own triangle: lifted
    // by the shadow offset along the normal on the light's side, its
    // segment to the light never meets that triangle, and the grid that
    // skips it answers what brute force over every triangle answers.
    let mut rng = Rng::new(17, 0, 0);
    let triangles = generated_scene(&mut rng);
    let light = DVec3::new(0.5, 5.0, -0.3);
    let grid = DirectionGrid::new(light, &triangles, |t| t.occludes);
    let t_max = 1.0 - STOP_SHORT_REL;
    let (mut tested, mut blocked) = (0, 0);
    for ray in 0..20_000 {
        let own = random_triangle(&triangles, &mut rng);
        let p = point_on_triangle(&triangles[own], &mut rng);
        let (normal, offset) = shadow_lift(&triangles[own], p, light);
        // The condition the shading checks before it skips the triangle.
        let to_light = light - p;
        if normal.dot(to_light) <= offset + 1e-12 * to_light.abs().element_sum() {
            continue;
        }
        let origin = p + normal * offset;
        let d = light - origin;
        assert!(
            !occluded_brute_force(&triangles[own..=own], origin, d, 0.0, t_max),
            "ray {ray}: triangle {own} blocks its own shadow ray"
        );
        let expected = occluded_brute_force(&triangles, origin, d, 0.0, t_max);
        if let Answer::Known(got) = grid.blocked_towards_centre(&triangles, origin, t_max, Some(own)) {
            assert_eq!(got, expected, "ray {ray} from triangle {own}");
            tested += 1;
            blocked += expected as u32;
        }
    }
    assert!(
        tested > 5000 && blocked > 500,
        "{tested} tested, {blocked} blocked"
    );
}

#[test]
fn rays_through_a_pixel_that_shares_a_cell_find_what_brute_force_finds() {
    // The reference looks up a pixel's cell once when its four corners
    // share it: every ray through the pixel must then find its closest hit
    // in that cell's list. A camera near the scene, so that cells list many
    // triangles, and pixels half as wide as a cell (0.3°): 4000 random
    // pixels of a 320×240 image.
    let mut rng = Rng::new(19, 0, 0);
    let triangles = generated_scene(&mut rng);
    let camera = Camera {
        eye: Vec3::new(5.0, 2.5, 6.0),
        target: Vec3::new(0.0, 0.5, 0.0),
        fovy_deg: 70.0,
    };
    let (w, h) = (320, 240);
    let rays = camera.pixel_rays(w, h);
    let grid = DirectionGrid::new(rays.eye, &triangles, |_| true);
    let (mut shared, mut hits) = (0, 0);
    for _ in 0..4000 {
        let (i, j) = (
            (rng.next_f64() * w as f64).floor(),
            (rng.next_f64() * h as f64).floor(),
        );
        let Some(cell) = grid.pixel_cell(&rays, i, j) else {
            continue;
        };
        shared += 1;
        // Corners and edges of the pixel too, where rounding is closest to the cell's edge.
        for (dx, dy) in [
            (0.0, 0.0),
            (1.0, 1.0),
            (0.0, rng.next_f64()),
            (rng.next_f64(), rng.next_f64()),
        ] {
            let (x, y) = (i + dx, j + dy);
            let v = rays.towards(x, y);
            if let Answer::Known(hit) = grid.closest_in(cell, v) {
                let expected = closest_hit_brute_force(&triangles, rays.eye, v, 0.0, f64::INFINITY);
                assert_eq!(hit, expected, "pixel ({i}, {j}) at ({x}, {y})");
                hits += hit.is_some() as u32;
            }
        }
    }
    assert!(
        shared > 1000 && hits > 1000,
        "{shared} pixels shared a cell, {hits} hits"
    );
}

/// The four corner rays of pixel (i, j).
fn pixel_corners(rays: &lumlab::scene::camera::PixelRays, i: f64, j: f64) -> [DVec3; 4] {
    [(i, j), (i + 1.0, j), (i, j + 1.0), (i + 1.0, j + 1.0)].map(|(x, y)| rays.towards(x, y))
}

#[test]
fn pixels_one_triangle_covers_find_what_brute_force_finds() {
    // The reference takes a covered pixel's hits from the covering triangle
    // (`DirectionGrid::cover`): every ray through the pixel must find that
    // triangle first, at the distance testing every triangle gives (to
    // rounding). Near the scene (cells list many triangles, some stacked in
    // depth) with pixels from a fifth of a cell to several cells wide.
    let mut rng = Rng::new(23, 0, 0);
    let triangles = generated_scene(&mut rng);
    let (mut covered, mut tested) = (0, 0);
    for (eye, w, h) in [
        ((5.0, 2.5, 6.0), 640, 480),
        ((2.0, 1.2, 2.5), 160, 120),
        ((9.0, 6.0, -7.0), 48, 36),
    ] {
        let camera = Camera {
            eye: Vec3::new(eye.0, eye.1, eye.2),
            target: Vec3::new(0.0, 0.5, 0.0),
            fovy_deg: 60.0,
        };
        let rays = camera.pixel_rays(w, h);
        let grid = DirectionGrid::new(rays.eye, &triangles, |_| true);
        for _ in 0..3000 {
            let (i, j) = (
                (rng.next_f64() * w as f64).floor(),
                (rng.next_f64() * h as f64).floor(),
            );
            let Some(cover) = grid.cover(&pixel_corners(&rays, i, j)) else {
                continue;
            };
            covered += 1;
            for (dx, dy) in [
                (0.0, 0.0),
                (1.0, 1.0),
                (1.0, rng.next_f64()),
                (rng.next_f64(), rng.next_f64()),
            ] {
                let v = rays.towards(i + dx, j + dy);
                let expected = closest_hit_brute_force(&triangles, rays.eye, v, 0.0, f64::INFINITY)
                    .unwrap_or_else(|| panic!("pixel ({i}, {j}) at +({dx}, {dy}): a miss"));
                let got = cover.hit(v);
                assert_eq!(
                    got.triangle, expected.triangle,
                    "pixel ({i}, {j}) at +({dx}, {dy})"
                );
                assert!((got.at.t - expected.at.t).abs() <= 1e-12 * expected.at.t);
                for (g, e) in got.at.barycentric.iter().zip(expected.at.barycentric) {
                    assert!(
                        (g - e).abs() <= 1e-12,
                        "barycentrics {:?} vs {:?}",
                        got.at.barycentric,
                        expected.at.barycentric
                    );
                }
                tested += 1;
            }
        }
    }
    assert!(
        covered > 2000 && tested > 8000,
        "{covered} pixels covered, {tested} rays"
    );
}

#[test]
fn shadow_rays_from_a_clear_patch_are_blocked_by_nothing() {
    // The reference decides a covered pixel's shadow rays at once when the
    // light's grid shows that nothing but their own triangle can block any
    // ray from the lifted patch of plane the pixel sees
    // (`DirectionGrid::clear_towards_centre`): brute force over every
    // other triangle must then find every such ray unblocked. Patches from
    // a millimetre to 2 cm across, on random triangles, lifted by the
    // shadow offset towards the light; their own triangle skipped or not.
    let mut rng = Rng::new(29, 0, 0);
    let triangles = generated_scene(&mut rng);
    let light = DVec3::new(0.5, 5.0, -0.3);
    let grid = DirectionGrid::new(light, &triangles, |t| t.occludes);
    let t_max = 1.0 - STOP_SHORT_REL;
    let (mut clear, mut not_clear) = (0, 0);
    for patch in 0..20_000 {
        let own = random_triangle(&triangles, &mut rng);
        let p = point_on_triangle(&triangles[own], &mut rng);
        let (normal, offset) = shadow_lift(&triangles[own], p, light);
        let lift = normal * offset;
        let [a, b, c] = triangles[own].corners_f64();
        let size = 1e-3 * 20f64.powf(rng.next_f64());
        let (e1, e2) = ((b - a).normalize() * size, (c - a).normalize() * size);
        let origins = [p, p + e1, p + e2, p + e1 + e2].map(|q| q + lift);
        let skip = rng.next_f64() < 0.5;
        if !grid.clear_towards_centre(&origins, if skip { own } else { usize::MAX }) {
            not_clear += 1;
            continue;
        }
        clear += 1;
        for _ in 0..4 {
            let (s, t) = (rng.next_f64(), rng.next_f64());
            let origin = origins[0] + (origins[1] - origins[0]) * s + (origins[2] - origins[0]) * t;
            let (before, after) = if skip {
                (&triangles[..own], &triangles[own + 1..])
            } else {
                (&triangles[..], &triangles[..0])
            };
            let d = light - origin;
            assert!(
                !occluded_brute_force(before, origin, d, 0.0, t_max)
                    && !occluded_brute_force(after, origin, d, 0.0, t_max),
                "patch {patch} on triangle {own} (skipped: {skip}): a shadow ray is blocked"
            );
        }
    }
    assert!(clear > 400 && not_clear > 3000, "{clear} clear, {not_clear} not");
}
