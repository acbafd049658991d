//! Real intervals [lo, hi] of doubles with outward rounding: the one place where a
//! rounded double becomes a bound.
//!
//! Each operation rounds to nearest and then moves the result one ulp outward, unless an
//! exactness test proves that no rounding happened (sums by Knuth's two-sum; products and
//! quotients of two points whose significands fit 53 bits together), so that exact
//! constants stay exact. A correctly rounded result lies
//! within half an ulp of the exact value, so the ulp either side of it encloses the value
//! (at a power of two the ulp below is half the one above, still more than half of
//! either). A span is either ordered (lo ≤ hi, the ends possibly infinite) or
//! indeterminate (both ends NaN): what f64 answers with NaN, and what no operation turns
//! back into a number.

/// A real interval [lo, hi], or indeterminate (both ends NaN).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Span {
    pub(crate) lo: f64,
    pub(crate) hi: f64,
}

/// Magnitudes below which Knuth's two-sum cannot overflow in its intermediate steps.
const TWO_SUM_SAFE: f64 = 1.0e307;

impl Span {
    pub(crate) const ZERO: Span = Span { lo: 0.0, hi: 0.0 };
    pub(crate) const INDETERMINATE: Span = Span {
        lo: f64::NAN,
        hi: f64::NAN,
    };
    /// [−1, 1], the range of sine and cosine.
    pub(crate) const UNIT: Span = Span { lo: -1.0, hi: 1.0 };

    /// [lo, hi]; indeterminate where either end is NaN or they are out of order.
    #[inline]
    pub(crate) fn new(lo: f64, hi: f64) -> Span {
        if lo <= hi {
            Span { lo, hi }
        } else {
            Span::INDETERMINATE
        }
    }

    /// The double `x` exactly.
    #[inline]
    pub(crate) fn point(x: f64) -> Span {
        Span::new(x, x)
    }

    /// The enclosure of a value whose double rounded to nearest is `x`: the ulp either side.
    #[inline]
    pub(crate) fn around(x: f64) -> Span {
        Span::new(x.next_down(), x.next_up())
    }

    /// π: the double nearest it lies below it, the next one above.
    pub(crate) fn pi() -> Span {
        Span {
            lo: std::f64::consts::PI,
            hi: std::f64::consts::PI.next_up(),
        }
    }

    #[inline]
    pub(crate) fn is_indeterminate(self) -> bool {
        self.lo.is_nan()
    }

    #[inline]
    pub(crate) fn is_point(self) -> bool {
        self.lo == self.hi
    }

    #[inline]
    pub(crate) fn is_zero(self) -> bool {
        self.lo == 0.0 && self.hi == 0.0
    }

    #[inline]
    pub(crate) fn is_finite(self) -> bool {
        self.lo.is_finite() && self.hi.is_finite()
    }

    /// Whether zero lies in the span (an indeterminate span holds everything).
    #[inline]
    pub(crate) fn contains_zero(self) -> bool {
        self.is_indeterminate() || (self.lo <= 0.0 && self.hi >= 0.0)
    }

    /// The least |x| over the span.
    #[inline]
    pub(crate) fn mignitude(self) -> f64 {
        if self.lo > 0.0 {
            self.lo
        } else if self.hi < 0.0 {
            -self.hi
        } else if self.is_indeterminate() {
            f64::NAN
        } else {
            0.0
        }
    }

    /// The greatest |x| over the span.
    #[inline]
    pub(crate) fn magnitude(self) -> f64 {
        if self.is_indeterminate() {
            f64::NAN
        } else {
            self.hi.abs().max(self.lo.abs())
        }
    }

    /// The smallest span that holds both.
    pub(crate) fn hull(self, other: Span) -> Span {
        if self.is_indeterminate() || other.is_indeterminate() {
            return Span::INDETERMINATE;
        }
        Span::new(self.lo.min(other.lo), self.hi.max(other.hi))
    }

    /// The larger of the two at each point (no decision needed: max is monotone).
    pub(crate) fn max(self, other: Span) -> Span {
        if self.is_indeterminate() || other.is_indeterminate() {
            return Span::INDETERMINATE;
        }
        Span::new(self.lo.max(other.lo), self.hi.max(other.hi))
    }

    /// The smaller of the two at each point.
    pub(crate) fn min(self, other: Span) -> Span {
        if self.is_indeterminate() || other.is_indeterminate() {
            return Span::INDETERMINATE;
        }
        Span::new(self.lo.min(other.lo), self.hi.min(other.hi))
    }

    /// Clipped to `range`, which is known to hold every value (as [−1, 1] holds a sine).
    pub(crate) fn within(self, range: Span) -> Span {
        if self.is_indeterminate() {
            return self;
        }
        Span::new(self.lo.max(range.lo), self.hi.min(range.hi))
    }

    #[inline]
    pub(crate) fn neg(self) -> Span {
        Span {
            lo: -self.hi,
            hi: -self.lo,
        }
    }

    #[inline]
    pub(crate) fn add(self, other: Span) -> Span {
        Span::new(add_down(self.lo, other.lo), add_up(self.hi, other.hi))
    }

    #[inline]
    pub(crate) fn sub(self, other: Span) -> Span {
        self.add(other.neg())
    }

    /// The product, from the two end products that the signs of the factors select (of
    /// two points, exact where the product is).
    #[inline]
    pub(crate) fn mul(self, other: Span) -> Span {
        let (a, b) = (self, other);
        if a.is_point() && b.is_point() {
            if a.lo == 0.0 || b.lo == 0.0 {
                return Span::point(0.0);
            }
            return Span::new(mul_down(a.lo, b.lo), mul_up(a.lo, b.lo));
        }
        if a.is_indeterminate() || b.is_indeterminate() {
            return Span::INDETERMINATE;
        }
        let (lo, hi) = if a.lo >= 0.0 {
            if b.lo >= 0.0 {
                (mul_down(a.lo, b.lo), mul_up(a.hi, b.hi))
            } else if b.hi <= 0.0 {
                (mul_down(a.hi, b.lo), mul_up(a.lo, b.hi))
            } else {
                (mul_down(a.hi, b.lo), mul_up(a.hi, b.hi))
            }
        } else if a.hi <= 0.0 {
            if b.lo >= 0.0 {
                (mul_down(a.lo, b.hi), mul_up(a.hi, b.lo))
            } else if b.hi <= 0.0 {
                (mul_down(a.hi, b.hi), mul_up(a.lo, b.lo))
            } else {
                (mul_down(a.lo, b.hi), mul_up(a.lo, b.lo))
            }
        } else if b.lo >= 0.0 {
            (mul_down(a.lo, b.hi), mul_up(a.hi, b.hi))
        } else if b.hi <= 0.0 {
            (mul_down(a.hi, b.lo), mul_up(a.lo, b.lo))
        } else {
            (
                mul_down(a.lo, b.hi).min(mul_down(a.hi, b.lo)),
                mul_up(a.lo, b.lo).max(mul_up(a.hi, b.hi)),
            )
        };
        Span::new(lo, hi)
    }

    /// The quotient, from the two end quotients that the signs select (of two points,
    /// exact where the quotient is); indeterminate where the divisor may be zero.
    #[inline]
    pub(crate) fn div(self, other: Span) -> Span {
        let (a, b) = (self, other);
        if b.contains_zero() {
            return Span::INDETERMINATE;
        }
        if a.is_point() && b.is_point() {
            return Span::new(div_down(a.lo, b.lo), div_up(a.lo, b.lo));
        }
        let (lo, hi) = if b.lo > 0.0 {
            if a.lo >= 0.0 {
                (div_down(a.lo, b.hi), div_up(a.hi, b.lo))
            } else if a.hi <= 0.0 {
                (div_down(a.lo, b.lo), div_up(a.hi, b.hi))
            } else {
                (div_down(a.lo, b.lo), div_up(a.hi, b.lo))
            }
        } else if a.lo >= 0.0 {
            (div_down(a.hi, b.hi), div_up(a.lo, b.lo))
        } else if a.hi <= 0.0 {
            (div_down(a.hi, b.lo), div_up(a.lo, b.hi))
        } else {
            (div_down(a.hi, b.hi), div_up(a.lo, b.hi))
        };
        Span::new(lo, hi)
    }

    /// x², which is not below zero even where the span straddles it.
    #[inline]
    pub(crate) fn square(self) -> Span {
        if self.is_point() {
            return self.mul(self);
        }
        let (least, most) = (self.mignitude(), self.magnitude());
        Span::new(mul_down(least, least), mul_up(most, most))
    }

    /// The square root; indeterminate where the span reaches below zero.
    pub(crate) fn sqrt(self) -> Span {
        if self.is_indeterminate() || self.lo < 0.0 {
            return Span::INDETERMINATE;
        }
        // √x − r has the sign of x − r² (a remainder found exactly): each end is rounded in
        // its own direction.
        let root = |x: f64| {
            let r = x.sqrt();
            match remainder(x, r, r).filter(|_| x >= PRODUCT_ERROR_SAFE) {
                Some(0.0) => Span::point(r),
                Some(remainder) if remainder > 0.0 => Span::new(r, r.next_up()),
                Some(_) => Span::new(r.next_down(), r),
                None if x == 0.0 => Span::point(0.0),
                None => Span::around(r),
            }
        };
        Span::new(root(self.lo).lo, root(self.hi).hi)
    }

    /// |x|.
    pub(crate) fn abs(self) -> Span {
        if self.lo >= 0.0 {
            self
        } else if self.hi <= 0.0 {
            self.neg()
        } else {
            Span::new(0.0, self.magnitude())
        }
    }

    /// The largest integer not above x (exact).
    pub(crate) fn floor(self) -> Span {
        Span::new(self.lo.floor(), self.hi.floor())
    }

    /// 2^`exponent`·x, exact unless it leaves the normal range.
    #[inline]
    pub(crate) fn times_power_of_two(self, exponent: i32) -> Span {
        if !(-1022..=1023).contains(&exponent) {
            // 2^exponent itself is not a normal double: scale in two steps.
            let half = exponent / 2;
            return self.times_power_of_two(half).times_power_of_two(exponent - half);
        }
        let factor = f64::from_bits(((exponent + 1023) as u64) << 52);
        let scale = |x: f64, outward: fn(f64) -> f64| {
            let p = x * factor;
            if x == 0.0 || is_exact_product(x, factor, p) {
                p
            } else {
                outward(p)
            }
        };
        Span::new(scale(self.lo, f64::next_down), scale(self.hi, f64::next_up))
    }
}

/// a + b rounded down: exact where Knuth's two-sum finds no rounding error, else the
/// double below the sum where the error is negative.
#[inline]
fn add_down(a: f64, b: f64) -> f64 {
    match sum_error(a, b) {
        (s, Some(error)) if error >= 0.0 => s,
        (s, _) => s.next_down(),
    }
}

/// a + b rounded up.
#[inline]
fn add_up(a: f64, b: f64) -> f64 {
    match sum_error(a, b) {
        (s, Some(error)) if error <= 0.0 => s,
        (s, _) => s.next_up(),
    }
}

/// The double nearest a + b and the exact error of that rounding (Knuth's two-sum), where
/// the magnitudes are safe from overflow in its steps.
#[inline]
fn sum_error(a: f64, b: f64) -> (f64, Option<f64>) {
    let s = a + b;
    if !(a.abs() < TWO_SUM_SAFE && b.abs() < TWO_SUM_SAFE) {
        return (s, None);
    }
    let b_virtual = s - a;
    let a_virtual = s - b_virtual;
    (s, Some((a - a_virtual) + (b - b_virtual)))
}

/// The least magnitude of a product or quotient whose rounding error [`product_error`]
/// returns exactly: the error's parts, 2^−108 of it and more, stay above the subnormals.
const PRODUCT_ERROR_SAFE: f64 = 1e-270;

/// The largest magnitude of a factor that Veltkamp's split takes without overflow (the
/// split multiplies it by 2^27 + 1).
const SPLIT_SAFE: f64 = 1e300;

/// The least magnitude of a factor taken by Veltkamp's split: normal, with its halves
/// (down to 2^−53 of it) normal too.
const SPLIT_LEAST: f64 = 1e-290;

/// a·b − p exactly, for p the double nearest a·b (Dekker's two-product: each factor split
/// into halves of 26 bits by Veltkamp's method, whose four products are exact), where the
/// factors and the product lie in the range that keeps every step exact; `None` outside
/// it. It takes about half the time of a call of libm's `fma`, which a binary built for any
/// x86-64 machine makes without the FMA instruction.
#[inline]
fn product_error(a: f64, b: f64, p: f64) -> Option<f64> {
    let safe = |x: f64| (SPLIT_LEAST..SPLIT_SAFE).contains(&x.abs());
    if !(safe(a) && safe(b) && p.is_finite() && p.abs() >= PRODUCT_ERROR_SAFE) {
        return None;
    }
    let split = |x: f64| {
        let scaled = 134_217_729.0 * x;
        let high = scaled - (scaled - x);
        (high, x - high)
    };
    let ((a_high, a_low), (b_high, b_low)) = (split(a), split(b));
    Some(((a_high * b_high - p) + a_high * b_low + a_low * b_high) + a_low * b_low)
}

/// A bound below a·b: the double nearest it where its exact error shows it is not above, else the
/// double below (0 where either is 0, as in interval arithmetic 0·∞ is).
#[inline]
fn mul_down(a: f64, b: f64) -> f64 {
    if a == 0.0 || b == 0.0 {
        return 0.0;
    }
    let p = a * b;
    match product_error(a, b, p) {
        Some(error) if error >= 0.0 => p,
        _ => p.next_down(),
    }
}

/// A bound above a·b.
#[inline]
fn mul_up(a: f64, b: f64) -> f64 {
    if a == 0.0 || b == 0.0 {
        return 0.0;
    }
    let p = a * b;
    match product_error(a, b, p) {
        Some(error) if error <= 0.0 => p,
        _ => p.next_up(),
    }
}

/// The sign of a/b − q for the double q nearest a/b, from the exact remainder a − q·b
/// (`None` where it may not be exact).
#[inline]
fn quotient_error(a: f64, b: f64, q: f64) -> Option<f64> {
    if a.abs() < PRODUCT_ERROR_SAFE {
        return None;
    }
    remainder(a, q, b).map(|remainder| if b > 0.0 { remainder } else { -remainder })
}

/// a − q·b exactly, where q is the double nearest a/b (or, with q = b, nearest √a): then
/// the double p nearest q·b lies within a few ulps of a, so a − p is exact (Sterbenz), and
/// the remainder a − p − (q·b − p) is itself a double, so the last subtraction is exact too.
/// `None` where [`product_error`] is.
#[inline]
fn remainder(a: f64, q: f64, b: f64) -> Option<f64> {
    let p = q * b;
    let error = product_error(q, b, p)?;
    a.is_finite().then_some((a - p) - error)
}

/// A bound below a/b (b ≠ 0).
#[inline]
fn div_down(a: f64, b: f64) -> f64 {
    if a == 0.0 && b.is_finite() {
        return 0.0;
    }
    let q = a / b;
    match quotient_error(a, b, q) {
        Some(error) if error >= 0.0 => q,
        _ => q.next_down(),
    }
}

/// A bound above a/b (b ≠ 0).
#[inline]
fn div_up(a: f64, b: f64) -> f64 {
    if a == 0.0 && b.is_finite() {
        return 0.0;
    }
    let q = a / b;
    match quotient_error(a, b, q) {
        Some(error) if error <= 0.0 => q,
        _ => q.next_up(),
    }
}

/// Whether `p`, the double nearest a·b, is a·b exactly: the two significands fit 53 bits
/// together (so the exact product has at most 53 significant bits), and `p` lies in the
/// normal range (so those bits are representable and nothing over- or underflowed).
#[inline]
pub(crate) fn is_exact_product(a: f64, b: f64, p: f64) -> bool {
    significant_bits(a) + significant_bits(b) <= 53 && p.is_finite() && p.abs() > f64::MIN_POSITIVE
}

/// The bits from the leading one to the last one of a normal double's significand; 53
/// for anything else (the most it can be).
#[inline]
fn significant_bits(x: f64) -> u32 {
    const FRACTION: u64 = (1 << 52) - 1;
    let bits = x.to_bits();
    let exponent = (bits >> 52) & 0x7ff;
    if exponent == 0 || exponent == 0x7ff {
        return 53;
    }
    53 - ((bits & FRACTION) | (1 << 52)).trailing_zeros()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_operations_stay_points() {
        let (two, three) = (Span::point(2.0), Span::point(3.0));
        assert_eq!(two.add(three), Span::point(5.0));
        assert_eq!(two.mul(three), Span::point(6.0));
        assert_eq!(Span::point(6.0).div(three), two);
        assert_eq!(Span::point(9.0).sqrt(), three);
        assert_eq!(Span::point(0.1).times_power_of_two(3), Span::point(0.8));
        // Through the subnormals and back: no longer exact, still holding 0.1.
        let round_trip = Span::point(0.1).times_power_of_two(-1080).times_power_of_two(1080);
        assert!(round_trip.lo < 0.1 && round_trip.hi > 0.1);
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(50_000))]
        #[test]
        fn products_and_remainders_are_exact_as_fma_finds_them(
            a in proptest::num::f64::NORMAL,
            b in proptest::num::f64::NORMAL,
            scale in -300i32..300,
        ) {
            // Factors over the whole range, products kept mostly finite.
            let (a, b) = (a.abs().sqrt().copysign(a) * 10f64.powi(scale / 2), b.abs().sqrt().copysign(b));
            let p = a * b;
            if let Some(error) = product_error(a, b, p) {
                proptest::prop_assert_eq!(error, a.mul_add(b, -p));
            }
            let q = a / b;
            if let Some(rest) = remainder(a, q, b) {
                proptest::prop_assert_eq!(rest, (-q).mul_add(b, a));
            }
            let r = a.abs().sqrt();
            if let Some(rest) = remainder(a.abs(), r, r) {
                proptest::prop_assert_eq!(rest, (-r).mul_add(r, a.abs()));
            }
        }
    }

    #[test]
    fn inexact_operations_are_one_ulp_wide() {
        // Each end rounded in its own direction (the exact rounding error gives its sign):
        // the two doubles around the exact value.
        let exact = |x: f64| rug::Rational::from_f64(x).expect("finite");
        let third = Span::point(1.0).div(Span::point(3.0));
        assert!(third.hi.next_down() == third.lo, "{third:?}");
        assert!(exact(third.lo) * 3u32 < 1 && exact(third.hi) * 3u32 > 1, "{third:?}");
        let product = Span::point(0.1).mul(Span::point(-3.0));
        assert!(product.hi.next_down() == product.lo, "{product:?}");
        let truth = exact(0.1) * -3i32;
        assert!(exact(product.lo) < truth && truth < exact(product.hi), "{product:?}");
        let sum = Span::point(0.1).add(Span::point(0.2));
        assert!(sum.hi.next_down() == sum.lo && sum.lo <= 0.3 && sum.hi >= 0.3);
        assert_eq!(significant_bits(1.0), 1);
        assert_eq!(significant_bits(3.0), 2);
        assert_eq!(significant_bits(1.0 / 3.0), 53);
        assert_eq!(significant_bits(5e-324), 53);
    }

    #[test]
    fn nan_and_division_by_zero_are_indeterminate() {
        assert!(Span::point(1.0).div(Span::new(-1.0, 1.0)).is_indeterminate());
        assert!(Span::new(-1.0, 4.0).sqrt().is_indeterminate());
        assert!(Span::INDETERMINATE.mul(Span::ZERO).is_indeterminate());
        assert!(Span::point(f64::INFINITY)
            .sub(Span::point(f64::INFINITY))
            .is_indeterminate());
        assert_eq!(Span::new(0.0, 1.0).mul(Span::new(1.0, f64::INFINITY)).lo, 0.0);
        let big = Span::point(f64::MAX).add(Span::point(f64::MAX));
        assert_eq!((big.lo, big.hi), (f64::MAX, f64::INFINITY));
    }
}
