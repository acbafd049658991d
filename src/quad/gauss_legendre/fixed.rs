//! The Legendre recurrence in fixed point, for node tables above f64 precision.
//!
//! Every quantity of the recurrence on [−1, 1] is at most 2 in magnitude (|P_j| ≤ 1,
//! |x| < 1, 0 ≤ j/(j+1) < 1), so a fixed binary point loses nothing a floating one
//! would keep. Numbers are pure fractions in sign-magnitude limbs; the P's are held
//! divided by 4, and each product has one unscaled factor (x or j/(j+1)), so no product
//! needs a shift. No normalisation, rounding modes or allocation in the loop: cheaper
//! than MPFR at the precisions of verified digits. Each operation truncates, so the absolute error of
//! P_n grows at most linearly in n (the recurrence is stable on [−1, 1]); callers size
//! the fraction with guard bits for that and for the cancellation near ±1.

use crate::real::{Precision, Real};

/// A fixed-point fraction: sign and magnitude, the magnitude's little-endian 64-bit limbs
/// read as an integer scaled by 2^(−64·limbs).
#[derive(Clone, Debug)]
pub(super) struct Fixed {
    negative: bool,
    limbs: Vec<u64>,
}

impl Fixed {
    fn zero(length: usize) -> Fixed {
        Fixed {
            negative: false,
            limbs: vec![0; length],
        }
    }

    /// 1/4, the scaled P_0.
    fn quarter(length: usize) -> Fixed {
        let mut fixed = Fixed::zero(length);
        fixed.limbs[length - 1] = 1 << 62;
        fixed
    }

    /// A quarter of self (exact but for the bits shifted out at the bottom).
    fn quartered(&self) -> Fixed {
        let mut limbs = self.limbs.clone();
        for i in 0..limbs.len() {
            let above = limbs.get(i + 1).copied().unwrap_or(0);
            limbs[i] = (limbs[i] >> 2) | (above << 62);
        }
        Fixed {
            negative: self.negative,
            limbs,
        }
    }

    /// numerator/denominator (both small, numerator < denominator), truncated.
    pub(super) fn ratio(numerator: u64, denominator: u64, length: usize) -> Fixed {
        let mut fixed = Fixed::zero(length);
        let mut remainder = u128::from(numerator);
        for limb in fixed.limbs.iter_mut().rev() {
            let shifted = remainder << 64;
            *limb = (shifted / u128::from(denominator)) as u64;
            remainder = shifted % u128::from(denominator);
        }
        fixed
    }

    /// The `length` most significant limbs (the same number, truncated or extended).
    pub(super) fn resized(&self, length: usize) -> Fixed {
        let current = self.limbs.len();
        let limbs = if length <= current {
            self.limbs[current - length..].to_vec()
        } else {
            let mut limbs = vec![0; length - current];
            limbs.extend_from_slice(&self.limbs);
            limbs
        };
        Fixed {
            negative: self.negative,
            limbs,
        }
    }

    /// `x` (|x| < 1), truncated.
    pub(super) fn from_real<R: Real>(x: &R, length: usize) -> Fixed {
        let mut fixed = Fixed::zero(length);
        fixed.negative = *x < x.int(0);
        let mut rest = x.abs();
        let chunk_scale = x.int(1 << 32);
        for limb in fixed.limbs.iter_mut().rev() {
            let mut value = 0u64;
            for _ in 0..2 {
                rest *= &chunk_scale;
                let chunk = rest.floor();
                rest -= &chunk;
                value = (value << 32) | chunk.to_f64_lossy() as u64;
            }
            *limb = value;
        }
        fixed
    }

    /// The value, rounded to `precision`.
    pub(super) fn to_real<R: Real>(&self, precision: Precision) -> R {
        let inverse_scale = R::from_f64(2f64.powi(-32), precision);
        let mut value = R::from_i64(0, precision);
        for &limb in &self.limbs {
            for chunk in [limb & 0xffff_ffff, limb >> 32] {
                value += &R::from_i64(chunk as i64, precision);
                value *= &inverse_scale;
            }
        }
        if self.negative {
            -value
        } else {
            value
        }
    }

    /// `output` = self × other, truncated; `product` is scratch of twice the limbs.
    /// Only the partial products of the kept limbs and the one below are formed: the
    /// columns left out add less than `limbs` units of the last kept limb.
    fn multiply_into(&self, other: &Fixed, output: &mut Fixed, product: &mut [u64]) {
        let length = self.limbs.len();
        product.fill(0);
        for (i, &a) in self.limbs.iter().enumerate() {
            if a == 0 {
                continue;
            }
            let mut carry = 0u128;
            let first = (length - 1).saturating_sub(i);
            for (j, &b) in other.limbs.iter().enumerate().skip(first) {
                let sum = u128::from(a) * u128::from(b) + u128::from(product[i + j]) + carry;
                product[i + j] = sum as u64;
                carry = sum >> 64;
            }
            product[i + length] = carry as u64;
        }
        output.limbs.copy_from_slice(&product[length..]);
        output.negative = self.negative != other.negative;
    }

    /// Whether |self| ≥ |other|.
    fn magnitude_at_least(&self, other: &Fixed) -> bool {
        for (a, b) in self.limbs.iter().rev().zip(other.limbs.iter().rev()) {
            if a != b {
                return a > b;
            }
        }
        true
    }

    /// self −= other.
    fn subtract(&mut self, other: &Fixed) {
        if self.negative != other.negative {
            let mut carry = false;
            for (a, &b) in self.limbs.iter_mut().zip(&other.limbs) {
                let (sum, first) = a.overflowing_add(b);
                let (sum, second) = sum.overflowing_add(u64::from(carry));
                *a = sum;
                carry = first || second;
            }
        } else if self.magnitude_at_least(other) {
            let mut borrow = false;
            for (a, &b) in self.limbs.iter_mut().zip(&other.limbs) {
                let (difference, first) = a.overflowing_sub(b);
                let (difference, second) = difference.overflowing_sub(u64::from(borrow));
                *a = difference;
                borrow = first || second;
            }
        } else {
            let mut borrow = false;
            for (a, &b) in self.limbs.iter_mut().zip(&other.limbs) {
                let (difference, first) = b.overflowing_sub(*a);
                let (difference, second) = difference.overflowing_sub(u64::from(borrow));
                *a = difference;
                borrow = first || second;
            }
            self.negative = !self.negative;
        }
    }
}

/// P_n(x)/4 and P_{n−1}(x)/4 for n = `ratios.len()`, where `ratios[j]` = j/(j+1), all at
/// the limbs of `x`: P_{j+1} = t − (P_{j−1} − t)·j/(j+1) with t = x P_j, on P/4.
pub(super) fn legendre_quarters(ratios: &[Fixed], x: &Fixed) -> (Fixed, Fixed) {
    let length = x.limbs.len();
    let mut previous = Fixed::quarter(length);
    let mut current = x.quartered();
    let mut scratch = Fixed::zero(length);
    let mut scaled = Fixed::zero(length);
    let mut product = vec![0u64; 2 * length];
    for ratio in ratios.iter().skip(1) {
        x.multiply_into(&current, &mut scratch, &mut product);
        previous.subtract(&scratch);
        ratio.multiply_into(&previous, &mut scaled, &mut product);
        scratch.subtract(&scaled);
        std::mem::swap(&mut previous, &mut current);
        std::mem::swap(&mut current, &mut scratch);
    }
    (current, previous)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rug::Float;

    #[test]
    fn round_trip_and_recurrence_match_mpfr() {
        let precision = Precision::bits(300);
        let x = Float::with_val(300, -0.3) / 7u32;
        let fixed = Fixed::from_real(&x, 5);
        let back: Float = fixed.to_real(precision);
        assert!((back - &x).abs() < Float::with_val(300, 1) >> 310u32);
        let ratios: Vec<Fixed> = (0..40u64).map(|j| Fixed::ratio(j, j + 1, 5)).collect();
        let (p, below) = legendre_quarters(&ratios, &fixed);
        // P_40 and P_39 by the textbook recurrence in MPFR at 400 bits.
        let x = Float::with_val(400, &x);
        let (mut previous, mut current) = (Float::with_val(400, 1), x.clone());
        for j in 1..40u32 {
            let next = (Float::with_val(400, &x * &current) * (2 * j + 1) - previous * j) / (j + 1);
            previous = current;
            current = next;
        }
        let tolerance = Float::with_val(300, 1) >> 300u32;
        assert!((p.to_real::<Float>(precision) * 4u32 - &current).abs() < tolerance);
        assert!((below.to_real::<Float>(precision) * 4u32 - &previous).abs() < tolerance);
    }
}
