//! qdot's one pseudo-random generator, SplitMix64 (Steele, Lea & Flood,
//! "Fast splittable pseudorandom number generators", OOPSLA 2014; the
//! constants of Vigna's reference `splitmix64.c`, prng.di.unimi.it).
//!
//! Every random choice in qdot is deterministic: the gcd's primes and
//! evaluation points, the factorization's splits and points, the numeric
//! root search's starting points, a sweep's random design, and the tests'
//! random inputs. The same seed gives the same stream on every machine, so
//! results and failures reproduce. Not for cryptography.

/// SplitMix64: a 64-bit state advanced by a fixed odd increment, each
/// output a bijective mix of the state (so any seed, 0 included, is good).
#[derive(Clone, Debug)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// The stream of `seed`.
    pub const fn new(seed: u64) -> Self {
        SplitMix64 { state: seed }
    }

    /// The stream of `seed` for `key`: each key its own reproducible
    /// stream (a random state gives every atom its value this way).
    pub fn keyed(seed: u64, key: &impl std::hash::Hash) -> Self {
        use std::hash::Hasher;
        let mut h = rustc_hash::FxHasher::default();
        key.hash(&mut h);
        SplitMix64::new(seed ^ h.finish())
    }

    /// The next 64 bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A number in `0..n` (`n > 0`): the next 64 bits modulo `n`, whose
    /// bias (at most n/2⁶⁴) no use here can see.
    pub fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }

    /// A double uniform in [0, 1): the top 53 bits over 2⁵³, exactly.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A double uniform in [lo, hi): `lo + (hi − lo)·u` for the next
    /// [`unit`](Self::unit) `u`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

#[cfg(test)]
mod tests {
    use super::SplitMix64;

    fn first_five(seed: u64) -> [u64; 5] {
        let mut rng = SplitMix64::new(seed);
        [(); 5].map(|_| rng.next_u64())
    }

    /// The reference outputs of `splitmix64.c` (the ones Rosetta Code's
    /// "Pseudo-random numbers/Splitmix64" publishes for seed 1234567;
    /// recomputed here from the reference C for seeds 0 and 1234567).
    #[test]
    fn matches_the_reference_outputs() {
        assert_eq!(
            first_five(0),
            [
                0xE220_A839_7B1D_CDAF,
                0x6E78_9E6A_A1B9_65F4,
                0x06C4_5D18_8009_454F,
                0xF88B_B8A8_724C_81EC,
                0x1B39_896A_51A8_749B,
            ]
        );
        assert_eq!(
            first_five(1234567),
            [
                6457827717110365317,
                3203168211198807973,
                9817491932198370423,
                4593380528125082431,
                16408922859458223821,
            ]
        );
    }

    /// unit, uniform and below are the documented functions of next_u64.
    #[test]
    fn derived_draws_are_functions_of_the_next_bits() {
        let mut bits = SplitMix64::new(1234567);
        let mut rng = SplitMix64::new(1234567);
        let top53 = |b: u64| (b >> 11) as f64 / 9007199254740992.0;
        assert_eq!(rng.unit(), top53(bits.next_u64()));
        assert_eq!(rng.uniform(-2.0, 2.0), -2.0 + 4.0 * top53(bits.next_u64()));
        assert_eq!(rng.below(97), bits.next_u64() % 97);
        // 6457827717110365317 >> 11 = 3153236189995295, over 2^53
        assert_eq!(
            SplitMix64::new(1234567).unit(),
            3153236189995295.0 / 9007199254740992.0
        );
        assert!((0..10_000).all(|_| (0.0..1.0).contains(&rng.unit())));
    }

    /// A clone continues the same stream; another seed gives another one.
    #[test]
    fn a_seed_fixes_the_stream() {
        let mut a = SplitMix64::new(7);
        a.next_u64();
        let mut b = a.clone();
        assert_eq!([(); 4].map(|_| a.next_u64()), [(); 4].map(|_| b.next_u64()));
        assert_ne!(first_five(7), first_five(8));
    }
}
