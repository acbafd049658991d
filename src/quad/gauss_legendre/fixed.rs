//! The Legendre recurrence in fixed point, for node tables above f64 precision.
//!
//! Every quantity of the recurrence on [−1, 1] is at most 2 in magnitude (|P_j| ≤ 1,
//! |x| < 1, 0 ≤ j/(j+1) < 1), so a fixed binary point loses nothing a floating one
//! would keep. A number is an integer m standing for m·2^(−bits); a product is the
//! integer product shifted right by `bits`. No normalisation or rounding modes in the
//! loop: cheaper than MPFR at the precisions of verified digits. Each shift truncates, so
//! the absolute error of P_n grows at most linearly in n (the recurrence is stable on
//! [−1, 1]); callers size `bits` with guard bits for that and for the cancellation near ±1.

use rug::{Assign, Float, Integer};

use crate::real::{Precision, Real};

/// Numbers scaled by 2^`bits`.
#[derive(Clone, Copy, Debug)]
pub(super) struct FixedPoint {
    pub(super) bits: u32,
}

impl FixedPoint {
    /// j/(j + 1) for j = 0 … `points` − 1, truncated: the recurrence's coefficients.
    pub(super) fn ratios(self, points: usize) -> Vec<Integer> {
        (0..points as u64)
            .map(|j| (Integer::from(j) << self.bits) / (j + 1))
            .collect()
    }

    /// `value` (held at `from`'s scale) at this scale, truncated or extended.
    pub(super) fn rescaled(self, value: &Integer, from: FixedPoint) -> Integer {
        if from.bits >= self.bits {
            Integer::from(value >> (from.bits - self.bits))
        } else {
            Integer::from(value << (self.bits - from.bits))
        }
    }

    /// `x` (|x| < 1), truncated toward −∞.
    pub(super) fn scaled<R: Real>(self, x: &R) -> Integer {
        // 32 bits at a time: the chunks are exact in any `Real`, whatever its precision.
        let chunk_scale = x.int(1 << 32);
        let mut rest = x.clone();
        let mut value = Integer::new();
        let mut bits = 0;
        while bits < self.bits {
            let take = (self.bits - bits).min(32);
            rest *= &if take == 32 {
                chunk_scale.clone()
            } else {
                x.int(1 << take)
            };
            let chunk = rest.floor();
            rest -= &chunk;
            value <<= take;
            value += chunk.to_f64_lossy() as i64;
            bits += take;
        }
        value
    }

    /// The value `scaled`·2^(−bits), rounded once to `precision`.
    pub(super) fn to_real<R: Real>(self, scaled: &Integer, precision: Precision) -> R {
        let exact = Float::with_val(scaled.significant_bits().max(1), scaled) >> self.bits;
        R::from_float(&exact, precision)
    }

    /// P_n(x) and P_{n−1}(x) for n = `ratios.len()`, where `ratios[j]` = j/(j+1), all at
    /// this scale: P_{j+1} = t − (P_{j−1} − t)·j/(j+1) with t = x P_j.
    pub(super) fn legendre_pair(self, ratios: &[Integer], x: &Integer) -> (Integer, Integer) {
        let mut previous = Integer::from(1) << self.bits;
        let mut current = x.clone();
        let mut scratch = Integer::new();
        for ratio in ratios.iter().skip(1) {
            scratch.assign(x * &current);
            scratch >>= self.bits;
            previous -= &scratch;
            previous *= ratio;
            previous >>= self.bits;
            scratch -= &previous;
            std::mem::swap(&mut previous, &mut current);
            std::mem::swap(&mut current, &mut scratch);
        }
        (current, previous)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_and_recurrence_match_mpfr() {
        let precision = Precision::bits(300);
        let scale = FixedPoint { bits: 320 };
        let x = Float::with_val(300, -0.3) / 7u32;
        let fixed = scale.scaled(&x);
        let back: Float = scale.to_real(&fixed, precision);
        assert!((back - &x).abs() < Float::with_val(300, 1) >> 310u32);
        let ratios = scale.ratios(40);
        let (p, below) = scale.legendre_pair(&ratios, &fixed);
        // P_40 and P_39 by the textbook recurrence in MPFR at 400 bits.
        let x = Float::with_val(400, &x);
        let (mut previous, mut current) = (Float::with_val(400, 1), x.clone());
        for j in 1..40u32 {
            let next = (Float::with_val(400, &x * &current) * (2 * j + 1) - previous * j) / (j + 1);
            previous = current;
            current = next;
        }
        let tolerance = Float::with_val(300, 1) >> 300u32;
        assert!((scale.to_real::<Float>(&p, precision) - &current).abs() < tolerance);
        assert!((scale.to_real::<Float>(&below, precision) - &previous).abs() < tolerance);
        // Rescaling to fewer bits keeps the leading ones.
        let coarse = FixedPoint { bits: 100 };
        let rescaled = coarse.rescaled(&ratios[7], scale);
        assert_eq!(rescaled, (Integer::from(7) << 100u32) / 8u32);
    }
}
