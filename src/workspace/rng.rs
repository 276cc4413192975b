//! Small seeded generators for the parallel samplers: SplitMix64 (seeding) and xoshiro256++
//! (the streams). Each chunk of samples gets its own stream from `(seed, chunk index)`, so the
//! result does not depend on how rayon schedules the chunks.

/// SplitMix64 (Steele, Lea, Flood 2014): used to expand seeds.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SplitMix64(u64);

/// The SplitMix64 output function: a bijective 64-bit mixer.
#[inline]
pub(crate) fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

impl SplitMix64 {
    /// A generator whose state is `seed`.
    pub(crate) fn new(seed: u64) -> Self {
        Self(seed)
    }

    /// Next 64 random bits.
    #[inline]
    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        mix64(self.0)
    }
}

/// xoshiro256++ 1.0 (Blackman, Vigna 2019).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Xoshiro256pp([u64; 4]);

impl Xoshiro256pp {
    /// Stream number `index` of `seed`: the state is four SplitMix64 outputs seeded by a hash of
    /// both numbers (never all zero).
    pub(crate) fn stream(seed: u64, index: u64) -> Self {
        let h = SplitMix64::new(seed).next_u64() ^ mix64(index.wrapping_add(0x6A09_E667_F3BC_C909));
        let mut sm = SplitMix64::new(h);
        let s = [sm.next_u64(), sm.next_u64(), sm.next_u64(), sm.next_u64()];
        if s == [0; 4] {
            Self([1, 2, 3, 4])
        } else {
            Self(s)
        }
    }

    /// Next 64 random bits.
    #[inline]
    pub(crate) fn next_u64(&mut self) -> u64 {
        let s = &mut self.0;
        let result = s[0].wrapping_add(s[3]).rotate_left(23).wrapping_add(s[0]);
        let t = s[1] << 17;
        s[2] ^= s[0];
        s[3] ^= s[1];
        s[1] ^= s[2];
        s[0] ^= s[3];
        s[2] ^= t;
        s[3] = s[3].rotate_left(45);
        result
    }

    /// Uniform in [0, 1) with 53 random bits.
    #[inline]
    pub(crate) fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// Fills `q` with a joint vector drawn uniformly in the box `limits` (rad or m).
#[inline]
pub(crate) fn uniform_q(rng: &mut Xoshiro256pp, limits: &[[f64; 2]], q: &mut [f64]) {
    for (v, [lo, hi]) in q.iter_mut().zip(limits) {
        *v = lo + rng.next_f64() * (hi - lo);
    }
}
