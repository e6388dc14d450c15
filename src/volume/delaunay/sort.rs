//! Insertion order: BRIO rounds, each sorted along a Hilbert curve.
//!
//! Why: a purely random order gives the expected-linear conflict work of randomised
//! incremental construction but terrible memory locality and long walks; a pure space-filling
//! curve order gives short walks but can build long, skinny intermediate triangulations.
//! BRIO (Amenta–Choi–Rote) keeps enough randomness (rounds of geometrically growing size, each
//! a random sample) while the Hilbert sort inside each round makes consecutive points close,
//! so the walk from the last created tet is a few steps.

/// A small, fast deterministic generator (xorshift64*), good enough for shuffles and for the
/// walk's random face choice.
#[derive(Clone, Debug)]
pub(crate) struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    #[inline(always)]
    pub fn next(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    #[inline]
    pub fn below(&mut self, n: usize) -> usize {
        ((self.next() >> 32) as usize * n) >> 32
    }
}

const BITS: u32 = 21;

/// Hilbert index of a point with integer coordinates in `0..2^BITS` (Skilling's transpose
/// method: undo the excess rotations, Gray-encode, then interleave the bits).
///
/// Written without data-dependent branches: each level's choice depends on a random bit of
/// the input, so the branchy form mispredicts about once per level and axis, which made the
/// keys a tenth of the whole serial triangulation time at 10⁶ points.
#[inline]
fn hilbert_key(x: [u32; 3]) -> u64 {
    let [mut x0, mut x1, mut x2] = x;
    let mut q = 1u32 << (BITS - 1);
    while q > 1 {
        let p = q - 1;
        let bit = |v: u32| 0u32.wrapping_sub((v & q != 0) as u32);
        // i = 0: invert the low bits of x0 when its bit is set (the exchange is a no-op).
        x0 ^= p & bit(x0);
        // i = 1, 2: invert x0's low bits if x_i's bit is set, else exchange them with x_i's.
        let m1 = bit(x1);
        let t1 = (x0 ^ x1) & p & !m1;
        x0 ^= (p & m1) | t1;
        x1 ^= t1;
        let m2 = bit(x2);
        let t2 = (x0 ^ x2) & p & !m2;
        x0 ^= (p & m2) | t2;
        x2 ^= t2;
        q >>= 1;
    }
    x1 ^= x0;
    x2 ^= x1;
    let mut t = 0;
    q = 1u32 << (BITS - 1);
    while q > 1 {
        t ^= (q - 1) & 0u32.wrapping_sub((x2 & q != 0) as u32);
        q >>= 1;
    }
    (spread(x0 ^ t) << 2) | (spread(x1 ^ t) << 1) | spread(x2 ^ t)
}

/// The low 21 bits of `v` moved to bits 0, 3, 6, … (bit interleaving for three axes).
#[inline(always)]
fn spread(v: u32) -> u64 {
    let mut x = v as u64 & 0x1f_ffff;
    x = (x | x << 32) & 0x001f_0000_0000_ffff;
    x = (x | x << 16) & 0x001f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    x = (x | x << 2) & 0x1249_2492_4924_9249;
    x
}

/// Hilbert keys of all points (in parallel on the current rayon pool), quantised over their common bounding box (one scale for all
/// three axes, so the curve is not distorted).
pub(crate) fn hilbert_keys(points: &[[f64; 3]]) -> Vec<u64> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let ext = (0..3).map(|k| hi[k] - lo[k]).fold(0.0f64, f64::max);
    let scale = if ext > 0.0 {
        ((1u64 << BITS) - 1) as f64 / ext
    } else {
        0.0
    };
    use rayon::prelude::*;
    points
        .par_iter()
        .with_min_len(4096)
        .map(|p| {
            let q =
                |k: usize| ((p[k] - lo[k]) * scale).clamp(0.0, ((1u64 << BITS) - 1) as f64) as u32;
            hilbert_key([q(0), q(1), q(2)])
        })
        .collect()
}

/// Rounds smaller than this are not split further.
const MIN_ROUND: usize = 64;
/// Fraction of a range that goes into the earlier rounds (the rest is the last round).
const ROUND_RATIO: f64 = 0.125;

/// BRIO order of `points`: shuffle, then split into rounds `[.., n·r³), [n·r³, n·r²), …,
/// [n·r, n)` (the last round is the large one) and Hilbert-sort each round.
pub(crate) fn brio_order(points: &[[f64; 3]], seed: u64) -> Vec<u32> {
    brio_order_keys(points, seed).0
}

/// Start of each BRIO round of `n` points, ascending (the first is 0); round `k` ends where
/// round `k + 1` starts, the last at `n`.
pub(crate) fn brio_round_starts(n: usize) -> Vec<usize> {
    let mut starts = Vec::new();
    let mut end = n;
    loop {
        let start = if end > MIN_ROUND {
            (end as f64 * ROUND_RATIO) as usize
        } else {
            0
        };
        starts.push(start);
        if start == 0 {
            break;
        }
        end = start;
    }
    starts.reverse();
    starts
}

/// [`brio_order`] and the Hilbert key of every point in that order (keys ascend within each
/// round); parallel insertion partitions space by key ranges.
pub(crate) fn brio_order_keys(points: &[[f64; 3]], seed: u64) -> (Vec<u32>, Vec<u64>) {
    let n = points.len();
    let mut order: Vec<u32> = (0..n as u32).collect();
    let mut rng = Rng::new(seed);
    for i in (1..n).rev() {
        let j = rng.below(i + 1);
        order.swap(i, j);
    }
    let keys = hilbert_keys(points);
    let starts = brio_round_starts(n);
    let mut sorted_keys = vec![0u64; n];
    let mut buf: Vec<(u64, u32)> = Vec::new();
    for (k, &start) in starts.iter().enumerate() {
        let end = starts.get(k + 1).copied().unwrap_or(n);
        buf.clear();
        buf.extend(order[start..end].iter().map(|&i| (keys[i as usize], i)));
        {
            use rayon::slice::ParallelSliceMut;
            buf.par_sort_unstable();
        }
        for ((dst, key), &(h, i)) in order[start..end]
            .iter_mut()
            .zip(&mut sorted_keys[start..end])
            .zip(&buf)
        {
            *dst = i;
            *key = h;
        }
    }
    (order, sorted_keys)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The straightforward (branchy) form of `hilbert_key`, as reference.
    fn hilbert_key_reference(mut x: [u32; 3]) -> u64 {
        let m = 1u32 << (BITS - 1);
        let mut q = m;
        while q > 1 {
            let p = q - 1;
            for i in 0..3 {
                if x[i] & q != 0 {
                    x[0] ^= p;
                } else {
                    let t = (x[0] ^ x[i]) & p;
                    x[0] ^= t;
                    x[i] ^= t;
                }
            }
            q >>= 1;
        }
        x[1] ^= x[0];
        x[2] ^= x[1];
        let mut t = 0;
        q = m;
        while q > 1 {
            if x[2] & q != 0 {
                t ^= q - 1;
            }
            q >>= 1;
        }
        for xi in &mut x {
            *xi ^= t;
        }
        let mut key = 0u64;
        for b in (0..BITS).rev() {
            for xi in &x {
                key = (key << 1) | ((xi >> b) & 1) as u64;
            }
        }
        key
    }

    #[test]
    fn branchless_hilbert_matches_reference() {
        let mut r = Rng::new(3);
        for k in 0..200_000 {
            let lim = if k % 2 == 0 { 1u64 << BITS } else { 16 };
            let x = [0; 3].map(|_: u32| (r.next() % lim) as u32);
            assert_eq!(hilbert_key(x), hilbert_key_reference(x), "{x:?}");
        }
    }

    #[test]
    fn hilbert_is_a_bijection_on_a_small_grid() {
        // With BITS bits per axis, keys of distinct cells must differ; check a coarse grid
        // scaled to the top bits and that consecutive keys are face-adjacent cells.
        let s = 1u32 << (BITS - 3);
        let mut cells = Vec::new();
        for x in 0..8u32 {
            for y in 0..8u32 {
                for z in 0..8u32 {
                    cells.push((hilbert_key([x * s, y * s, z * s]), [x, y, z]));
                }
            }
        }
        cells.sort();
        for w in cells.windows(2) {
            assert_ne!(w[0].0, w[1].0);
            let d: u32 = (0..3).map(|k| w[0].1[k].abs_diff(w[1].1[k])).sum();
            assert_eq!(d, 1, "{:?} -> {:?}", w[0].1, w[1].1);
        }
    }

    #[test]
    fn brio_rounds_cover_all_points() {
        for n in [0usize, 1, 64, 65, 1000, 123_457] {
            let s = brio_round_starts(n);
            assert_eq!(s[0], 0);
            assert!(s.windows(2).all(|w| w[0] < w[1] && w[1] <= n));
        }
    }

    #[test]
    fn brio_is_a_permutation() {
        let pts: Vec<[f64; 3]> = (0..1000)
            .map(|i| [i as f64, (i * 7 % 13) as f64, 0.5])
            .collect();
        let mut o = brio_order(&pts, 1);
        o.sort();
        assert!(o.iter().enumerate().all(|(i, &v)| i as u32 == v));
    }
}
