//! Arithmetic modulo a word-sized prime, shared by the gcd (62-bit primes)
//! and the factorization (primes below 2^16): products, sums, powers and
//! inverses of residues, rationals reduced mod p and lifted back, and the
//! gcd's stream of pseudo-random numbers.

use crate::num::Q;
use crate::rng::SplitMix64;
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::ToPrimitive;
use std::cell::RefCell;

/// 62-bit primes `2^62 - c` (small `c`, see [`mulmod`]) for the images of
/// the gcd.
pub(super) const PRIMES: [u64; 6] = [
    4611686018427387847,
    4611686018427387817,
    4611686018427387787,
    4611686018427387761,
    4611686018427387751,
    4611686018427387737,
];

thread_local! {
    /// [`next_rand`]'s stream (one per thread).
    static RNG: RefCell<SplitMix64> = const { RefCell::new(SplitMix64::new(0x9E37_79B9_7F4A_7C15)) };
}

/// The next number of this thread's stream: the random primes and
/// evaluation points of the gcd (a stream shared by every gcd on the thread,
/// so results never depend on it, only the work done).
pub(super) fn next_rand() -> u64 {
    RNG.with(|rng| rng.borrow_mut().next_u64())
}

/// `a * b mod p` for `a, b < p`. The primes used are `2^62 - c` with small
/// `c`, which allows a division-free reduction; other moduli fall back to
/// `u128` remainder.
#[inline]
pub(super) fn mulmod(a: u64, b: u64, p: u64) -> u64 {
    const MASK: u64 = (1 << 62) - 1;
    let x = a as u128 * b as u128;
    if p > (1 << 62) - (1 << 16) && p < (1 << 62) {
        let c = (1u64 << 62) - p;
        // x = hi * 2^62 + lo ≡ hi * c + lo
        let x1 = (x >> 62) * c as u128 + (x as u64 & MASK) as u128;
        let mut r = ((x1 >> 62) as u64) * c + (x1 as u64 & MASK);
        while r >= p {
            r -= p;
        }
        r
    } else {
        (x % p as u128) as u64
    }
}

#[inline]
pub(super) fn addmod(a: u64, b: u64, p: u64) -> u64 {
    let s = a + b; // p < 2^62: no overflow
    if s >= p {
        s - p
    } else {
        s
    }
}

#[inline]
pub(super) fn submod(a: u64, b: u64, p: u64) -> u64 {
    if a >= b {
        a - b
    } else {
        a + p - b
    }
}

pub(super) fn powmod(mut b: u64, mut e: u64, p: u64) -> u64 {
    let mut r = 1u64;
    b %= p;
    while e > 0 {
        if e & 1 == 1 {
            r = mulmod(r, b, p);
        }
        b = mulmod(b, b, p);
        e >>= 1;
    }
    r
}

/// Inverse modulo the prime `p` by the extended Euclidean algorithm
/// (`0` for `a ≡ 0`).
pub(super) fn invmod(a: u64, p: u64) -> u64 {
    // p < 2^63, so remainders and Bezout coefficients (|s| <= p) fit i64
    let (mut r0, mut r1) = (p as i64, (a % p) as i64);
    let (mut s0, mut s1) = (0i64, 1i64);
    while r1 != 0 {
        let q = r0 / r1;
        (r0, r1) = (r1, r0 - q * r1);
        (s0, s1) = (s1, s0 - q * s1);
    }
    if r0 != 1 {
        return 0;
    }
    s0.rem_euclid(p as i64) as u64
}

/// `c mod p`, `None` if the denominator vanishes mod `p`.
pub(super) fn q_mod(c: &Q, p: u64) -> Option<u64> {
    match c.small() {
        Some((n, d)) => {
            let nm = n.rem_euclid(p as i64) as u64;
            if d == 1 {
                return Some(nm);
            }
            let dm = (d as u64) % p;
            if dm == 0 {
                return None;
            }
            Some(mulmod(nm, invmod(dm, p), p))
        }
        None => {
            let pb = BigInt::from(p);
            let nm = c.numer().mod_floor(&pb).to_u64()?;
            let dm = c.denom().mod_floor(&pb).to_u64()?;
            if dm == 0 {
                return None;
            }
            Some(mulmod(nm, invmod(dm, p), p))
        }
    }
}

/// Drops the zero coefficients at the top of a dense polynomial mod p.
pub(super) fn trim(v: &mut Vec<u64>) {
    while v.last() == Some(&0) {
        v.pop();
    }
}

/// Symmetric lift of a residue mod p to an integer.
pub(super) fn lift_sym(c: u64, p: u64) -> Q {
    if c > p / 2 {
        Q::from_i64(-((p - c) as i64))
    } else {
        Q::from_i64(c as i64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The gcd's stream is SplitMix64 from 0x9E3779B97F4A7C15, the state
    /// after seed 0's first step: it continues seed 0's reference outputs
    /// (see crate::rng).
    #[test]
    fn the_gcd_stream_is_splitmix64_seed_0_after_its_first_output() {
        let fresh = std::thread::spawn(|| [next_rand(), next_rand(), next_rand()]);
        assert_eq!(
            fresh.join().expect("thread"),
            [
                0x6E78_9E6A_A1B9_65F4,
                0x06C4_5D18_8009_454F,
                0xF88B_B8A8_724C_81EC
            ]
        );
    }

    #[test]
    fn modular_helpers() {
        for &p in PRIMES.iter() {
            let mut rng = SplitMix64::new(p);
            for _ in 0..200 {
                let a = rng.below(p);
                let b = rng.below(p);
                let expect = ((a as u128 * b as u128) % p as u128) as u64;
                assert_eq!(mulmod(a, b, p), expect);
                assert_eq!(mulmod(p - 1, p - 1, p), 1);
                if a != 0 {
                    assert_eq!(mulmod(a, invmod(a, p), p), 1);
                }
            }
            // Fermat: the moduli are prime (for these witnesses)
            for w in [2u64, 3, 5, 7, 11, 13] {
                assert_eq!(powmod(w, p - 1, p), 1);
            }
        }
        assert_eq!(mulmod(10, 10, 7), 2);
    }
}
