//! The lanes' filter against the scalar test, and their rounding.

use super::bound::UNBOUNDED;
use super::*;
use crate::reference::intersect::ShearedRay;
use crate::reference::sampling::Rng;

/// `up` and `down` give what stepping with `next_up` and `next_down`
/// gives, on special values, on values just past f32's and on random
/// values of every magnitude and sign.
#[test]
fn rounding_up_and_down_steps_as_next_up_and_next_down() {
    let stepped_up = |x: f64| {
        let y = x as f32;
        if (y as f64) < x { y.next_up() } else { y }
    };
    let stepped_down = |x: f64| {
        let y = x as f32;
        if (y as f64) > x { y.next_down() } else { y }
    };
    let tiny = f64::from(f32::from_bits(1));
    let mut values = vec![
        0.0,
        -0.0,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        f64::MAX,
        -f64::MAX,
        f64::from(f32::MAX),
        tiny,
        tiny / 3.0,
        1e-300,
        -1e-300,
        1e300,
        -1e300,
    ];
    let mut rng = Rng::new(11, 0, 0);
    for _ in 0..100_000 {
        let magnitude = 10f64.powf(90.0 * rng.next_f64() - 50.0);
        let x = if rng.next_f64() < 0.5 {
            -magnitude
        } else {
            magnitude
        };
        values.extend([
            x,
            f64::from(x as f32),
            f64::from(x as f32).next_up(),
            f64::from(x as f32).next_down(),
        ]);
    }
    for x in values {
        assert_eq!(up(x).to_bits(), stepped_up(x).to_bits(), "up({x:e})");
        assert_eq!(down(x).to_bits(), stepped_down(x).to_bits(), "down({x:e})");
        assert!(
            x.is_nan() || (f64::from(up(x)) >= x && f64::from(down(x)) <= x),
            "{x:e}"
        );
    }
}

/// Rays towards the points `aims`: from the apex (primary rays), or
/// (shadow rays) from beyond each point to the apex; and their spread
/// (the farthest origin from the apex, |·|∞).
fn packet(apex: DVec3, aims: &[DVec3], shadow: bool) -> (Vec<ShearedRay>, f64) {
    let rays: Vec<ShearedRay> = aims
        .iter()
        .map(|&p| {
            if shadow {
                let o = apex + (p - apex) * 1.5;
                ShearedRay::new(o, apex - o)
            } else {
                ShearedRay::new(apex, p - apex)
            }
        })
        .collect();
    let spread = rays
        .iter()
        .fold(0.0_f64, |m, r| m.max((r.origin - apex).abs().max_element()));
    (rays, spread)
}

/// Rays through corners, along edges and near them, from random points
/// on lines through an apex (behind it for shadow rays, at it for
/// primary rays): whenever the scalar test finds the triangle (at any
/// distance), the lanes must not have ruled it out; and they do rule
/// out most misses of rays aimed at random points (near-edge rays are
/// left to the scalar test by design). Rays whose limit lies before the
/// depth asked about are dropped, and only they.
#[test]
fn a_lane_called_a_miss_is_a_miss_of_the_scalar_test() {
    let mut rng = Rng::new(31, 0, 0);
    let mut point = |scale: f64| DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) * scale;
    let (mut found, mut ruled_out, mut misses) = (0, 0, 0);
    let mut lines = Lines::default();
    for case in 0..4000 {
        let apex = point(8.0) - DVec3::splat(4.0);
        let tri = [point(2.0), point(2.0), point(2.0)];
        let jitter = [0.0, 1e-15, 1e-9, 1e-3][case % 4];
        let aims: Vec<DVec3> = (0..LANES + 3)
            .map(|l| match l % 4 {
                0 => tri[l % 3],
                1 => tri[l % 3].lerp(tri[(l + 1) % 3], 0.3 + 0.01 * l as f64),
                2 => tri[0].lerp(tri[1], 0.5).lerp(tri[2], 0.5),
                _ => point(2.0),
            } + point(jitter))
            .collect();
        let (rays, spread) = packet(apex, &aims, case % 2 == 1);
        // Depths: the last ray is done, the others stop short of the
        // depth asked, reach just to it (not an f32) or reach far.
        let nearest = 1.0 + 1e-9;
        let limits: Vec<f64> = (0..rays.len())
            .map(|k| match (k + case) % 5 {
                _ if k + 1 == rays.len() => f64::NEG_INFINITY,
                0 => 0.5,
                1 => nearest,
                _ => f64::INFINITY,
            })
            .collect();
        lines.fill(
            rays.iter().map(|r| r.direction).zip(limits.iter().copied()),
            spread,
        );
        let planes = lines.planes(&tri.map(|p| p - apex));
        #[cfg(target_arch = "x86_64")]
        for block in lines.blocks.iter().filter(|_| lines.avx) {
            let at = down(nearest).max(f32::MIN);
            // SAFETY: the CPU has AVX.
            let avx = unsafe { kept_avx(block, &planes, at) };
            assert_eq!(avx, kept_by_lane(block, &planes, at), "case {case}: AVX");
        }
        for (k, ray) in rays.iter().enumerate() {
            let kept = lines.may_hit(k / LANES, &planes, nearest) & (1 << (k % LANES)) != 0;
            if limits[k] < nearest {
                assert!(!kept, "case {case}, ray {k}: beyond its limit");
                continue;
            }
            let hit = ray.intersect(&tri, f64::NEG_INFINITY, f64::INFINITY).is_some();
            assert!(kept || !hit, "case {case}, ray {k}: a hit ruled out");
            found += usize::from(hit);
            if k % 4 == 3 && !hit {
                misses += 1;
                ruled_out += usize::from(!kept);
            }
        }
    }
    assert!(found > 4000, "too few hits to tell: {found}");
    assert!(
        ruled_out * 10 > misses * 9,
        "{ruled_out} of {misses} misses ruled out"
    );
}

/// The first pass passes over a block only when the lane test keeps
/// none of its rays: packets of coherent rays (a pixel's primary rays,
/// shadow rays from nearby points) against triangles around them,
/// some crossing the packet, with limits before, at and beyond the
/// depth asked; and it does pass over many of the blocks that keep nothing.
#[test]
fn a_block_passed_over_keeps_no_lane() {
    let rng = std::cell::RefCell::new(Rng::new(37, 0, 0));
    let unit = || rng.borrow_mut().next_f64();
    let (mut passed, mut empty, mut kept) = (0, 0, 0);
    let mut lines = Lines::default();
    for case in 0..3000 {
        let apex = DVec3::new(unit(), unit(), unit()) * 4.0 - 2.0;
        let axis = DVec3::new(unit() - 0.5, unit() - 0.5, unit() - 0.5).normalize_or(DVec3::X);
        let (u, v) = axis.any_orthonormal_pair();
        let width = [1e-4, 1e-2, 0.3][case % 3];
        let shadow = case % 2 == 1;
        let count = 1 + case % (3 * LANES * GROUP / 2);
        let point = |distance: f64, spread: f64| {
            apex + (axis + (u * (unit() - 0.5) + v * (unit() - 0.5)) * spread) * distance
        };
        let aims: Vec<DVec3> = (0..count).map(|_| point(2.0, width)).collect();
        // Triangles the size of the packet or smaller, near it or across it.
        let size = width * [0.1, 1.0, 3.0][case / 3 % 3];
        let centre = point(1.0 + unit(), width * 3.0);
        let tri = [0, 1, 2].map(|_| centre + DVec3::new(unit(), unit(), unit()) * size - size / 2.0);
        let (rays, spread) = packet(apex, &aims, shadow);
        let nearest = 0.5 + unit();
        let limits: Vec<f64> = (0..count)
            .map(|k| match (k + case) % 7 {
                0 => f64::NEG_INFINITY,
                1 => 0.5,
                2 => nearest,
                _ => f64::INFINITY,
            })
            .collect();
        lines.fill(
            rays.iter().map(|r| r.direction).zip(limits.iter().copied()),
            spread,
        );
        let planes = lines.planes(&tri.map(|p| p - apex));
        #[cfg(target_arch = "x86_64")]
        for bounds in lines.bounds.iter().filter(|_| lines.avx) {
            let at = down(nearest).max(f32::MIN);
            // SAFETY: the CPU has AVX.
            let avx = unsafe { group_kept_avx(bounds, &planes, at, GROUP / LANES) };
            assert_eq!(avx, group_kept_by_block(bounds, &planes, at), "case {case}: AVX");
        }
        for b in 0..lines.blocks.len() {
            let first = lines.group_may_hit(b / GROUP, &planes, nearest) & (1 << (b % GROUP)) != 0;
            let lanes = lines.may_hit(b, &planes, nearest);
            assert!(
                first || lanes == 0,
                "case {case}, block {b}: lanes {lanes:#b} passed over"
            );
            passed += usize::from(!first);
            empty += usize::from(lanes == 0);
            kept += usize::from(lanes != 0);
        }
    }
    assert!(kept > 1000, "too few blocks keep a lane to tell: {kept}");
    // Wide packets and triangles across them leave many to the lanes.
    assert!(passed * 3 > empty, "{passed} of {empty} empty blocks passed over");
}

/// Each set of lanes packs to its lanes in order, as a loop over its set
/// bits finds them.
#[test]
fn every_set_of_lanes_packs_to_its_lanes_in_order() {
    for set in 0..1_u32 << LANES {
        let mut bits = set;
        let mut lanes = Vec::new();
        while bits != 0 {
            lanes.push(bits.trailing_zeros() as u8);
            bits &= bits - 1;
        }
        assert_eq!(&LEFT_PACKED[set as usize][..lanes.len()], &lanes[..], "{set:08b}");
    }
}

/// A block's bound holds every used lane, in f64 from the f32 values
/// stored: |d − c|₂ and the allowance for the lane test's rounding within
/// the spread, |d|∞ within the reach, each lane's own |d|∞ exact; and it
/// stays tight (within 10⁻⁴ of that, or the floor); the AVX bound is the
/// lane-by-lane one; a lane that is not finite leaves the block unbounded.
#[test]
fn a_blocks_bound_holds_its_lanes() {
    let mut rng = Rng::new(41, 0, 0);
    let mut unit = || rng.next_f64();
    for case in 0..20_000 {
        let scale = 10f64.powf(12.0 * unit() - 6.0);
        let width = [0.0, 1e-7, 1e-3, 0.5, 3.0][case % 5];
        let lanes = 1 + case % LANES;
        let centre = DVec3::new(unit() - 0.5, unit() - 0.5, unit() - 0.5);
        let mut block = Block::default();
        for l in 0..lanes {
            let d = (centre + DVec3::new(unit() - 0.5, unit() - 0.5, unit() - 0.5) * width) * scale;
            for i in 0..3 {
                block.d[i][l] = d[i] as f32;
            }
        }
        if case % 97 == 0 {
            block.d[case % 3][case % lanes] = [f32::NAN, f32::INFINITY][case % 2];
        }
        let mut plain = block;
        let bound = block_bound(&mut plain, lanes);
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx") {
            let mut wide = block;
            // SAFETY: the CPU has AVX.
            let avx = unsafe { block_bound_avx(&mut wide, lanes) };
            assert_eq!(avx, bound, "case {case}: AVX");
            // (A lane that is not finite may take either reach: its tests
            // compare a NaN, which keeps it, either way.)
            if bound != UNBOUNDED {
                assert_eq!(wide.reach, plain.reach, "case {case}: AVX reach");
            }
        }
        let d: Vec<DVec3> = (0..lanes)
            .map(|l| DVec3::new(block.d[0][l] as f64, block.d[1][l] as f64, block.d[2][l] as f64))
            .collect();
        if !d.iter().all(|d| d.is_finite()) {
            assert_eq!(bound, UNBOUNDED, "case {case}");
            continue;
        }
        let c = DVec3::from(bound.c.map(f64::from));
        let r = d.iter().map(|&dl| (dl - c).length()).fold(0.0, f64::max);
        let needed = (r + 16.0 * f32::EPSILON as f64 * (c.abs().max_element() + r)) * (1.0 + BOUND_ROUNDING);
        let spread = f64::from(bound.spread);
        assert!(spread >= needed, "case {case}: spread {spread:e} < {needed:e}");
        assert!(
            spread <= needed * 1.0001 + 1e-17,
            "case {case}: spread {spread:e} ≫ {needed:e}"
        );
        let reach = d.iter().map(|d| d.abs().max_element()).fold(0.0, f64::max);
        assert!(
            f64::from(bound.reach) >= reach * (1.0 + BOUND_ROUNDING),
            "case {case}: reach"
        );
        for (l, dl) in d.iter().enumerate() {
            assert_eq!(
                f64::from(plain.reach[l]),
                dl.abs().max_element(),
                "case {case}, lane {l}"
            );
        }
    }
}
