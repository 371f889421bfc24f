//! The packets' first filter: which rays surely miss a triangle, eight at a
//! time in f32, with a proven margin, so that only rays near its edges and
//! those that hit it go on to the exact f64 test.
//!
//! Every ray of a packet lies on a line through the cone's apex L (primary
//! rays start there; shadow rays end there). For a ray along d from o with
//! o − L ∥ d, the watertight test's edge function opposite corner A is
//! U = ±det(d, C − o, B − o) / d_kz = ±d · n_A / d_kz, n_A = (C − L) × (B − L),
//! with one sign for the three edges of a ray. The ray misses when two edge
//! functions take opposite signs. Here E = d · n runs in f32, and a sign
//! counts only where |E| > T = |d|∞ · τ + floor, with
//! τ = 8 ε₃₂ |n|₁ + 128 ε₆₄ (|C − L|∞ + R)(|B − L|∞ + R), R the farthest
//! origin from L:
//! - f32: rounding d and n and the three products and two sums move E by
//!   at most 5 ε₃₂ Σ|d_i n_i| ≤ 5 ε₃₂ |d|∞ |n|₁ (the floor covers underflow);
//! - f64: the scalar test's U (shear, products, difference, corners taken
//!   relative to o), n's own rounding and d ∦ o − L by d's rounding move
//!   d_kz U by less than 80 ε₆₄ |d|∞ |C − o|∞ |B − o|∞, and
//!   |C − o|∞ ≤ |C − L|∞ + R.
//!
//! So a sign found here is the sign of the scalar test's edge function, and
//! a ray called a miss is one the scalar test misses. NaN and infinities
//! fail both comparisons: such a ray goes on to the scalar test.
//!
//! The same pass drops the rays that cannot reach the triangle's least
//! depth: each ray's deepest useful depth is kept here as an f32 rounded
//! up and the triangle's least depth comes rounded down, so a ray dropped
//! for depth is one whose f64 limit the triangle lies beyond.
//!
//! Most blocks keep no ray of a triangle (nine in ten on a 110 k-triangle
//! model): a first pass decides [`GROUP`] blocks at once from a bound of
//! each block's rays, a centre c and a spread s with
//! |E(lane) − (c · n)| ≤ s |n|₁ for every lane of the block, E as the lane
//! test computes it (rounding included, see [`Lines::fill`]). A block is
//! passed over when one edge value is surely positive and another surely
//! negative for all its lanes (each against the largest margin of the
//! block), or when the triangle lies beyond every lane's limit: exactly
//! what the lane test would find for each of its rays.

use bound::block_bound;
#[cfg(target_arch = "x86_64")]
use bound::block_bound_avx;
use glam::DVec3;

/// Rays per block.
pub const LANES: usize = 8;

/// For each set of kept lanes (bit l: lane l), their indices in order,
/// first: what a loop over the set bits gives.
pub const LEFT_PACKED: [[u8; LANES]; 1 << LANES] = {
    let mut table = [[0_u8; LANES]; 1 << LANES];
    let mut set = 0;
    while set < 1 << LANES {
        let (mut lane, mut count) = (0, 0);
        while lane < LANES {
            if set & (1 << lane) != 0 {
                table[set][count] = lane as u8;
                count += 1;
            }
            lane += 1;
        }
        set += 1;
    }
    table
};

/// Added to every margin: the rounding of f32 products that underflow.
const FLOOR: f32 = 1e-30;

/// Blocks the first pass bounds side by side.
pub const GROUP: usize = 16;

/// Relative allowance for the first pass's own f32 rounding (a few
/// operations of 6·10⁻⁸ each), applied to its spreads and margins.
const BOUND_ROUNDING: f64 = 1e-5;

/// The bounds of [`GROUP`] blocks, block by block in each array (unused
/// blocks: limit −∞).
#[derive(Clone, Copy, Debug)]
struct Bounds {
    /// The centre c of each block's directions.
    c: [[f32; GROUP]; 3],
    /// s: |E(lane) − (c · n)| ≤ s |n|₁ for every lane, rounded up.
    spread: [f32; GROUP],
    /// The largest |d|∞ of each block, with the first pass's allowance.
    reach: [f32; GROUP],
    /// The deepest limit of each block's lanes.
    limit: [f32; GROUP],
}

impl Default for Bounds {
    fn default() -> Self {
        Self {
            c: [[0.0; GROUP]; 3],
            spread: [0.0; GROUP],
            reach: [0.0; GROUP],
            limit: [f32::NEG_INFINITY; GROUP],
        }
    }
}

/// Eight rays' directions (d, any nonzero multiple), |d|∞ and deepest
/// useful depths (rounded up; −∞: done or unused), lane by lane.
#[derive(Clone, Copy, Debug)]
struct Block {
    d: [[f32; LANES]; 3],
    reach: [f32; LANES],
    limit: [f32; LANES],
}

impl Default for Block {
    fn default() -> Self {
        Self {
            d: [[0.0; LANES]; 3],
            reach: [0.0; LANES],
            limit: [f32::NEG_INFINITY; LANES],
        }
    }
}

/// The rays of a packet as lines through the apex, in blocks of [`LANES`].
#[derive(Debug, Default)]
pub struct Lines {
    blocks: Vec<Block>,
    /// The first pass's bounds, one [`Bounds`] per [`GROUP`] blocks.
    bounds: Vec<Bounds>,
    /// R: the farthest ray origin from the apex (|·|∞, 0 for primary rays).
    spread: f64,
    /// Whether the CPU runs AVX: eight lanes in one register.
    #[cfg(target_arch = "x86_64")]
    avx: bool,
}

/// A triangle's three edge planes through the apex, as [`Lines::may_hit`]
/// takes them: normals n (f32) and margins τ per unit of |d|∞.
#[derive(Clone, Copy, Debug)]
pub struct EdgePlanes {
    n: [[f32; 3]; 3],
    tau: [f32; 3],
    /// |n|₁ of each, rounded up.
    l1: [f32; 3],
}

impl Lines {
    /// The `rays`, each a direction and its deepest useful depth, in order,
    /// each on a line through the apex from an origin within `spread` (|·|∞)
    /// of it. Inlined into the walks, so compiled for AVX2 where they are.
    #[inline(always)]
    pub fn fill(&mut self, rays: impl ExactSizeIterator<Item = (DVec3, f64)>, spread: f64) {
        self.blocks.clear();
        self.spread = spread;
        #[cfg(target_arch = "x86_64")]
        {
            self.avx = std::arch::is_x86_feature_detected!("avx");
        }
        // Unused lanes stay zero: E = 0 is never a sure sign. (The blocks
        // made first: a new one every eighth ray was a branch the loop
        // mispredicted.)
        self.blocks.resize(rays.len().div_ceil(LANES), Block::default());
        // Counted in the loop, though `rays.len()` knows it: taken from
        // there, the engine's process ran 34 M instructions more.
        let mut count = 0_usize;
        for (k, (d, limit)) in rays.enumerate() {
            count += 1;
            let (block, l) = (&mut self.blocks[k / LANES], k % LANES);
            let d = d.as_vec3();
            for i in 0..3 {
                block.d[i][l] = d[i];
            }
            block.limit[l] = up(limit);
        }
        self.blocks.truncate(count.div_ceil(LANES));
        self.bounds.clear();
        self.bounds
            .resize(self.blocks.len().div_ceil(GROUP), Bounds::default());
        for (b, block) in self.blocks.iter_mut().enumerate() {
            let lanes = (count - b * LANES).min(LANES);
            #[cfg(target_arch = "x86_64")]
            let bound = if self.avx {
                // SAFETY: the CPU has AVX.
                unsafe { block_bound_avx(block, lanes) }
            } else {
                block_bound(block, lanes)
            };
            #[cfg(not(target_arch = "x86_64"))]
            let bound = block_bound(block, lanes);
            let bounds = &mut self.bounds[b / GROUP];
            let at = b % GROUP;
            for (i, ci) in bound.c.into_iter().enumerate() {
                bounds.c[i][at] = ci;
            }
            bounds.spread[at] = bound.spread;
            bounds.reach[at] = bound.reach;
            bounds.limit[at] = block.deepest();
        }
    }

    /// Ray k's deepest useful depth is now `limit` (−∞: done).
    #[inline(always)]
    pub fn set_limit(&mut self, k: usize, limit: f64) {
        let block = &mut self.blocks[k / LANES];
        block.limit[k % LANES] = up(limit);
        self.bounds[k / (LANES * GROUP)].limit[k / LANES % GROUP] = block.deepest();
    }

    /// The deepest of the rays' limits as the blocks hold them (rounded up
    /// to f32: no shallower than the deepest f64 limit; −∞ when every ray
    /// is done): one value a block instead of one a ray.
    pub fn deepest(&self) -> f64 {
        f64::from(deepest_of(self.bounds.iter().flat_map(|b| &b.limit)))
    }

    /// Groups of [`GROUP`] blocks, for [`Self::group_may_hit`].
    pub fn groups(&self) -> usize {
        self.bounds.len()
    }

    /// Bit i set unless block `GROUP · group + i` surely keeps no ray of
    /// the triangle of `planes` at depth `nearest` (the first pass: see
    /// the module's note); [`Self::may_hit`] then tells its lanes.
    #[inline(always)]
    pub fn group_may_hit(&self, group: usize, planes: &EdgePlanes, nearest: f64) -> u32 {
        let nearest = down(nearest).max(f32::MIN);
        let b = &self.bounds[group];
        #[cfg(target_arch = "x86_64")]
        if self.avx {
            // Only the halves that hold blocks (unused ones keep nothing).
            let halves = (self.blocks.len() - group * GROUP).min(GROUP).div_ceil(LANES);
            // SAFETY: the CPU has AVX.
            return unsafe { group_kept_avx(b, planes, nearest, halves) };
        }
        group_kept_by_block(b, planes, nearest)
    }

    /// The edge planes of the triangle with corners `relative` to the apex:
    /// n = c × b, a × c and b × a. The three edges side by side, one lane
    /// each (and a fourth unused), so that each step is one packed
    /// operation: the same operations in the same order as edge by edge.
    #[inline(always)]
    pub fn planes(&self, [a, b, c]: &[DVec3; 3]) -> EdgePlanes {
        let r = self.spread;
        // |corner|∞ + R, once a corner.
        let [ra, rb, rc] = [a, b, c].map(|p| p.abs().max_element() + r);
        let lanes = |u: f64, v: f64, w: f64| [u, v, w, 0.0];
        let (p, q) = ([c, a, b], [b, c, a]);
        let [px, py, pz] = [0, 1, 2].map(|i| lanes(p[0][i], p[1][i], p[2][i]));
        let [qx, qy, qz] = [0, 1, 2].map(|i| lanes(q[0][i], q[1][i], q[2][i]));
        let (rp, rq) = (lanes(rc, ra, rb), lanes(rb, rc, ra));
        let (mut nx, mut ny, mut nz) = ([0.0; 4], [0.0; 4], [0.0; 4]);
        let (mut sum, mut tau) = ([0.0; 4], [0.0; 4]);
        for e in 0..4 {
            nx[e] = py[e] * qz[e] - qy[e] * pz[e];
            ny[e] = pz[e] * qx[e] - qz[e] * px[e];
            nz[e] = px[e] * qy[e] - qx[e] * py[e];
            sum[e] = nx[e].abs() + ny[e].abs() + nz[e].abs();
            tau[e] = 8.0 * f32::EPSILON as f64 * sum[e] + 128.0 * f64::EPSILON * rp[e] * rq[e];
        }
        // τ rounded up to f32; and |n|₁ of n's f32 copy, rounded up from
        // the f64 sum: each of its terms is |n_i| moved by 2⁻²⁴ of it at
        // most, or by half the least subnormal.
        EdgePlanes {
            n: std::array::from_fn(|e| [nx[e] as f32, ny[e] as f32, nz[e] as f32]),
            tau: std::array::from_fn(|e| (tau[e] * (1.0 + 1e-6)) as f32),
            l1: std::array::from_fn(|e| up(sum[e] * (1.0 + 1e-6) + 3.0 * f64::from(f32::from_bits(1)))),
        }
    }

    /// Bit l set when ray `LANES · block + l` reaches depth `nearest` and
    /// does not surely miss the triangle of `planes` (see the module's note).
    #[inline(always)]
    pub fn may_hit(&self, block: usize, planes: &EdgePlanes, nearest: f64) -> u32 {
        // Rounded down; no lower than f32::MIN, which −∞ (done) stays below.
        let nearest = down(nearest).max(f32::MIN);
        let b = &self.blocks[block];
        #[cfg(target_arch = "x86_64")]
        if self.avx {
            // SAFETY: the CPU has AVX.
            return unsafe { kept_avx(b, planes, nearest) };
        }
        kept_by_lane(b, planes, nearest)
    }
}

impl Block {
    /// The deepest of its lanes' limits.
    fn deepest(&self) -> f32 {
        deepest_of(&self.limit)
    }
}

/// The largest of `limits` (−∞ for none), by comparisons: a NaN is passed
/// over as `f32::max` would, in one instruction a value instead of several
/// (engine's primary walk −0.7 %; over the packets' f64 limits `f64::max`
/// was faster).
fn deepest_of<'a>(limits: impl IntoIterator<Item = &'a f32>) -> f32 {
    limits
        .into_iter()
        .fold(f32::NEG_INFINITY, |m, &l| if l > m { l } else { m })
}

/// `x` rounded up to f32: the nearest f32, stepped up a unit in its bits
/// when below x (a positive one up, a negative one down: a rounded value
/// of −0 is never below x). Arithmetic, not a branch: whether to step is
/// a coin toss for the rays' depths.
fn up(x: f64) -> f32 {
    let y = x as f32;
    let (step, negative) = (((y as f64) < x) as u32, y.to_bits() >> 31);
    f32::from_bits(
        y.to_bits()
            .wrapping_add(step)
            .wrapping_sub((step & negative) << 1),
    )
}

/// `x` rounded down to f32, as [`up`] (a rounded value of +0 is never
/// above x).
fn down(x: f64) -> f32 {
    let y = x as f32;
    let (step, negative) = (((y as f64) > x) as u32, y.to_bits() >> 31);
    f32::from_bits(
        y.to_bits()
            .wrapping_sub(step)
            .wrapping_add((step & negative) << 1),
    )
}

/// Bit l: lane l reaches `nearest` and its edge values do not take both
/// signs beyond their margins, E = (d_x n_x + d_y n_y) + d_z n_z against
/// |d|∞ τ + floor. AVX: the eight lanes in one register.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
fn kept_avx(b: &Block, planes: &EdgePlanes, nearest: f32) -> u32 {
    use std::arch::x86_64::*;
    // SAFETY: each load reads eight in-bounds f32.
    let load = |a: &[f32; LANES]| unsafe { _mm256_loadu_ps(a.as_ptr()) };
    let (dx, dy, dz, reach) = (load(&b.d[0]), load(&b.d[1]), load(&b.d[2]), load(&b.reach));
    let (mut positive, mut negative) = (_mm256_setzero_ps(), _mm256_setzero_ps());
    for e in 0..3 {
        let value = dot_avx([dx, dy, dz], planes.n[e]);
        let margin = _mm256_add_ps(
            _mm256_mul_ps(reach, _mm256_set1_ps(planes.tau[e])),
            _mm256_set1_ps(FLOOR),
        );
        positive = _mm256_or_ps(positive, _mm256_cmp_ps::<_CMP_GT_OQ>(value, margin));
        negative = _mm256_or_ps(
            negative,
            _mm256_cmp_ps::<_CMP_LT_OQ>(value, _mm256_sub_ps(_mm256_setzero_ps(), margin)),
        );
    }
    let reaches = _mm256_cmp_ps::<_CMP_LE_OQ>(_mm256_set1_ps(nearest), load(&b.limit));
    let misses = _mm256_and_ps(positive, negative);
    _mm256_movemask_ps(_mm256_andnot_ps(misses, reaches)) as u32
}

/// (x n_x + y n_y) + z n_z in each of eight lanes, `xyz` = [x, y, z].
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
fn dot_avx(xyz: [std::arch::x86_64::__m256; 3], n: [f32; 3]) -> std::arch::x86_64::__m256 {
    use std::arch::x86_64::*;
    let [nx, ny, nz] = n.map(|x| _mm256_set1_ps(x));
    _mm256_add_ps(
        _mm256_add_ps(_mm256_mul_ps(xyz[0], nx), _mm256_mul_ps(xyz[1], ny)),
        _mm256_mul_ps(xyz[2], nz),
    )
}

/// [`kept_avx`] lane by lane, where there is no AVX (and in the tests,
/// against it).
#[inline(always)]
fn kept_by_lane(b: &Block, planes: &EdgePlanes, nearest: f32) -> u32 {
    let mut bits = 0;
    for l in 0..LANES {
        let (mut positive, mut negative) = (false, false);
        for e in 0..3 {
            let [nx, ny, nz] = planes.n[e];
            let value = (b.d[0][l] * nx + b.d[1][l] * ny) + b.d[2][l] * nz;
            let margin = b.reach[l] * planes.tau[e] + FLOOR;
            positive |= value > margin;
            negative |= value < -margin;
        }
        bits |= u32::from(!(positive && negative) && nearest <= b.limit[l]) << l;
    }
    bits
}

/// The margin's floor in the first pass, with its allowance.
const BOUND_FLOOR: f32 = FLOOR * (1.0 + BOUND_ROUNDING as f32);

/// Bit i: block i of the group may keep a lane (see
/// [`Lines::group_may_hit`]): its limit reaches `nearest` and its bounded
/// edge values do not take both signs beyond their margins. AVX: eight
/// blocks in one register, for the first `halves` of its eight-block halves.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
fn group_kept_avx(b: &Bounds, planes: &EdgePlanes, nearest: f32, halves: usize) -> u32 {
    use std::arch::x86_64::*;
    let mut bits = 0;
    for half in 0..halves {
        let at = half * LANES;
        // SAFETY: each load reads eight in-bounds f32.
        let load = |a: &[f32; GROUP]| unsafe { _mm256_loadu_ps(a[at..at + LANES].as_ptr()) };
        let (cx, cy, cz) = (load(&b.c[0]), load(&b.c[1]), load(&b.c[2]));
        let (spread, reach) = (load(&b.spread), load(&b.reach));
        let (mut positive, mut negative) = (_mm256_setzero_ps(), _mm256_setzero_ps());
        for e in 0..3 {
            let centre = dot_avx([cx, cy, cz], planes.n[e]);
            let spread = _mm256_mul_ps(spread, _mm256_set1_ps(planes.l1[e]));
            let margin = _mm256_add_ps(
                _mm256_mul_ps(reach, _mm256_set1_ps(planes.tau[e])),
                _mm256_set1_ps(BOUND_FLOOR),
            );
            let below = _mm256_sub_ps(_mm256_setzero_ps(), margin);
            positive = _mm256_or_ps(
                positive,
                _mm256_cmp_ps::<_CMP_GT_OQ>(_mm256_sub_ps(centre, spread), margin),
            );
            negative = _mm256_or_ps(
                negative,
                _mm256_cmp_ps::<_CMP_LT_OQ>(_mm256_add_ps(centre, spread), below),
            );
        }
        let reaches = _mm256_cmp_ps::<_CMP_LE_OQ>(_mm256_set1_ps(nearest), load(&b.limit));
        let misses = _mm256_and_ps(positive, negative);
        bits |= (_mm256_movemask_ps(_mm256_andnot_ps(misses, reaches)) as u32) << at;
    }
    bits
}

/// [`group_kept_avx`] block by block, where there is no AVX (and in the
/// tests, against it).
#[inline(always)]
fn group_kept_by_block(b: &Bounds, planes: &EdgePlanes, nearest: f32) -> u32 {
    let (mut positive, mut negative) = ([false; GROUP], [false; GROUP]);
    for e in 0..3 {
        let [nx, ny, nz] = planes.n[e];
        for i in 0..GROUP {
            let centre = (b.c[0][i] * nx + b.c[1][i] * ny) + b.c[2][i] * nz;
            let spread = b.spread[i] * planes.l1[e];
            let margin = b.reach[i] * planes.tau[e] + BOUND_FLOOR;
            positive[i] |= centre - spread > margin;
            negative[i] |= centre + spread < -margin;
        }
    }
    let mut bits = 0;
    for i in 0..GROUP {
        let misses = positive[i] && negative[i];
        bits |= u32::from(!misses && nearest <= b.limit[i]) << i;
    }
    bits
}

mod bound;
#[cfg(test)]
mod tests;
