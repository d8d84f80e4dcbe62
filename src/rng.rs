//! The crate's one small seeded random number generator: SplitMix64 (Steele, Lea and Flood,
//! "Fast splittable pseudorandom number generators", OOPSLA 2014), the generator Java's
//! `SplittableRandom` uses and the usual seeder of xoshiro. The tolerance study draws each
//! sample from its own stream, seeded by the study's seed and the sample's index, so a
//! sample's draws do not depend on threads or shards; the random-chain estimate of the
//! counting search starts each chunk's stream at a hashed point ([`mix64`]).

/// SplitMix64.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SplitMix64 {
    state: u64,
}

/// The 64-bit golden-ratio increment of SplitMix64.
const GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;

impl SplitMix64 {
    /// A generator seeded with `seed`.
    pub(crate) fn new(seed: u64) -> SplitMix64 {
        SplitMix64 { state: seed }
    }

    /// The stream of sample `index` of a study seeded with `seed`.
    pub(crate) fn for_sample(seed: u64, index: u64) -> SplitMix64 {
        // mix the index once so neighbouring samples start far apart in the sequence
        let mut g = SplitMix64::new(index ^ 0xD1B5_4A32_D192_ED03);
        SplitMix64::new(seed ^ g.next_u64())
    }

    /// The next 64 random bits.
    pub(crate) fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(GAMMA);
        mix64(self.state)
    }

    /// A uniform whole number below `n` (from 53 random bits).
    pub(crate) fn below(&mut self, n: u64) -> u64 {
        (self.next_f64() * n as f64) as u64
    }

    /// A uniform number in `[0, 1)` (53 random bits).
    pub(crate) fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// A uniform number in `[-1, 1)`.
    pub(crate) fn symmetric(&mut self) -> f64 {
        2.0 * self.next_f64() - 1.0
    }
}

/// The SplitMix64 finaliser: a bijective hash of 64 bits.
pub(crate) fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_sequence_and_range() {
        // reference values of SplitMix64 seeded with 0 (as in the published C code)
        let mut g = SplitMix64::new(0);
        assert_eq!(g.next_u64(), 0xE220_A839_7B1D_CDAF);
        assert_eq!(g.next_u64(), 0x6E78_9E6A_A1B9_65F4);
        let mut g = SplitMix64::for_sample(7, 3);
        let mut sum = 0.0;
        for _ in 0..10_000 {
            let x = g.symmetric();
            assert!((-1.0..1.0).contains(&x));
            sum += x;
        }
        assert!(sum.abs() / 10_000.0 < 0.03, "{sum}");
    }
}
