//! [`Iv`]: microslip's [`Real`] on inari's f64 intervals with outward rounding, so that the
//! library's generic integrands run unchanged on intervals.
//!
//! Every arithmetic result and every elementary function encloses the exact image of its
//! arguments (inari conforms to IEEE 1788.1; its elementary functions round outward
//! through MPFR). The functions inari lacks are composed from ones it has (cbrt as a
//! power with an enclosed 1/3, ln_1p as ln(1 + x), exp_m1 as exp(x) − 1, hypot as
//! √(x² + y²)): still enclosures, only wider near zero. A comparison of overlapping
//! intervals cannot be decided; it is answered by the midpoints, as f64 would, and
//! counted ([`doubts`]), since a rigorous route would have to settle every one.

use std::cell::Cell;
use std::cmp::Ordering;
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Rem, RemAssign, Sub, SubAssign};

use inari::Interval;
use microslip::real::{ParseRealError, Precision, Real};
use num_traits::ToPrimitive;
use rug::float::Round;
use rug::{Float, Rational};

/// An f64 interval [inf, sup] that contains the exact value.
#[derive(Clone, Copy, Debug)]
pub struct Iv(pub Interval);

thread_local! {
    static DOUBTS: Cell<u64> = const { Cell::new(0) };
}

/// Comparisons of overlapping intervals on this thread so far (decided by midpoints).
pub fn doubts() -> u64 {
    DOUBTS.with(Cell::get)
}

fn doubt() {
    DOUBTS.with(|count| count.set(count.get() + 1));
}

impl Iv {
    /// The interval [lower, upper].
    pub fn new(lower: f64, upper: f64) -> Iv {
        Iv(Interval::try_from((lower, upper)).expect("lower ≤ upper, both not NaN"))
    }

    fn point(x: f64) -> Iv {
        Iv::new(x, x)
    }

    /// The lower and upper end.
    pub fn bounds(&self) -> (f64, f64) {
        (self.0.inf(), self.0.sup())
    }

    /// The smallest f64 interval containing `x`.
    fn around_float(x: &Float) -> Iv {
        Iv::new(x.to_f64_round(Round::Down), x.to_f64_round(Round::Up))
    }

    fn around_rational(x: &Rational) -> Iv {
        let (lower, _) = Float::with_val_round(53, x, Round::Down);
        let (upper, _) = Float::with_val_round(53, x, Round::Up);
        Iv::new(lower.to_f64(), upper.to_f64())
    }

    fn map(self, f: impl Fn(Interval) -> Interval) -> Iv {
        Iv(f(self.0))
    }
}

macro_rules! arithmetic {
    ($($trait:ident $method:ident $assign_trait:ident $assign:ident $op:tt),*) => {$(
        impl $trait<Iv> for Iv {
            type Output = Iv;
            fn $method(self, other: Iv) -> Iv {
                Iv(self.0 $op other.0)
            }
        }
        impl $trait<&Iv> for Iv {
            type Output = Iv;
            fn $method(self, other: &Iv) -> Iv {
                Iv(self.0 $op other.0)
            }
        }
        impl $assign_trait<Iv> for Iv {
            fn $assign(&mut self, other: Iv) {
                self.0 = self.0 $op other.0;
            }
        }
        impl $assign_trait<&Iv> for Iv {
            fn $assign(&mut self, other: &Iv) {
                self.0 = self.0 $op other.0;
            }
        }
    )*};
}

arithmetic!(Add add AddAssign add_assign +, Sub sub SubAssign sub_assign -,
    Mul mul MulAssign mul_assign *, Div div DivAssign div_assign /);

/// x − y⌊x/y⌋, enclosed (the integrands never take a remainder; the trait asks for one).
fn remainder(x: Interval, y: Interval) -> Interval {
    x - y * (x / y).floor()
}

impl Rem<Iv> for Iv {
    type Output = Iv;
    fn rem(self, other: Iv) -> Iv {
        Iv(remainder(self.0, other.0))
    }
}

impl Rem<&Iv> for Iv {
    type Output = Iv;
    fn rem(self, other: &Iv) -> Iv {
        Iv(remainder(self.0, other.0))
    }
}

impl RemAssign<Iv> for Iv {
    fn rem_assign(&mut self, other: Iv) {
        self.0 = remainder(self.0, other.0);
    }
}

impl RemAssign<&Iv> for Iv {
    fn rem_assign(&mut self, other: &Iv) {
        self.0 = remainder(self.0, other.0);
    }
}

impl Neg for Iv {
    type Output = Iv;
    fn neg(self) -> Iv {
        Iv(-self.0)
    }
}

impl PartialEq for Iv {
    fn eq(&self, other: &Iv) -> bool {
        if self.0.is_singleton() && self.0 == other.0 {
            true
        } else if self.0.disjoint(other.0) {
            false
        } else {
            doubt();
            self.0.mid() == other.0.mid()
        }
    }
}

impl PartialOrd for Iv {
    fn partial_cmp(&self, other: &Iv) -> Option<Ordering> {
        if self.0.sup() < other.0.inf() {
            Some(Ordering::Less)
        } else if self.0.inf() > other.0.sup() {
            Some(Ordering::Greater)
        } else if self.0.is_singleton() && self.0 == other.0 {
            Some(Ordering::Equal)
        } else {
            doubt();
            self.0.mid().partial_cmp(&other.0.mid())
        }
    }
}

impl ToPrimitive for Iv {
    fn to_i64(&self) -> Option<i64> {
        self.0.mid().to_i64()
    }
    fn to_u64(&self) -> Option<u64> {
        self.0.mid().to_u64()
    }
    fn to_f64(&self) -> Option<f64> {
        Some(self.0.mid())
    }
}

impl Real for Iv {
    fn precision(&self) -> Precision {
        Precision::DOUBLE
    }
    fn from_f64(x: f64, _: Precision) -> Self {
        Iv::point(x)
    }
    fn from_i64(n: i64, _: Precision) -> Self {
        // Exact in f64 up to 2⁵³ in magnitude (the integrands ask for small integers).
        const EXACT: i64 = 1 << 53;
        if (-EXACT..=EXACT).contains(&n) {
            Iv::point(n as f64)
        } else {
            Iv::around_rational(&Rational::from(n))
        }
    }
    fn from_float(x: &Float, _: Precision) -> Self {
        Iv::around_float(x)
    }
    fn parse_decimal(text: &str, _: Precision) -> Result<Self, ParseRealError> {
        let error = || ParseRealError { text: text.to_string() };
        // The exact decimal, then its two neighbours in f64.
        let rounded = |round| {
            let exact = Float::parse(text.trim()).map_err(|_| error())?;
            Ok(Float::with_val_round(53, exact, round).0)
        };
        let (lower, upper) = (rounded(Round::Down)?, rounded(Round::Up)?);
        let value = Iv::new(lower.to_f64(), upper.to_f64());
        if value.0.is_common_interval() {
            Ok(value)
        } else {
            Err(error())
        }
    }
    fn from_rational(x: &Rational, _: Precision) -> Self {
        Iv::around_rational(x)
    }
    fn pi(_: Precision) -> Self {
        Iv(Interval::PI)
    }
    fn epsilon(_: Precision) -> Self {
        Iv::point(f64::EPSILON)
    }
    fn smallest_full_precision(_: Precision) -> Self {
        Iv::point(f64::MIN_POSITIVE)
    }
    fn sqrt(&self) -> Self {
        self.map(Interval::sqrt)
    }
    fn cbrt(&self) -> Self {
        // x^(1/3) for x ≥ 0 with 1/3 enclosed; odd continuation below zero.
        let third = Iv::around_rational(&Rational::from((1, 3))).0;
        if self.0.inf() >= 0.0 {
            self.map(|x| x.pow(third))
        } else if self.0.sup() <= 0.0 {
            self.map(|x| -(-x).pow(third))
        } else {
            let (low, high) = ((-self.0.inf()), self.0.sup());
            let bound = |x: f64| Iv::point(x).0.pow(third).sup();
            Iv::new(-bound(low), bound(high))
        }
    }
    fn ln(&self) -> Self {
        self.map(Interval::ln)
    }
    fn ln_1p(&self) -> Self {
        self.map(|x| (Iv::point(1.0).0 + x).ln())
    }
    fn exp(&self) -> Self {
        self.map(Interval::exp)
    }
    fn exp_m1(&self) -> Self {
        self.map(|x| x.exp() - Iv::point(1.0).0)
    }
    fn powr(&self, exponent: &Self) -> Self {
        self.map(|x| x.pow(exponent.0))
    }
    fn powi(&self, exponent: i32) -> Self {
        self.map(|x| x.powi(exponent))
    }
    fn sin(&self) -> Self {
        self.map(Interval::sin)
    }
    fn cos(&self) -> Self {
        self.map(Interval::cos)
    }
    fn sin_cos(&self) -> (Self, Self) {
        (self.sin(), self.cos())
    }
    fn hypot(&self, other: &Self) -> Self {
        Iv((self.0.sqr() + other.0.sqr()).sqrt())
    }
    fn atan2(&self, x: &Self) -> Self {
        self.map(|y| y.atan2(x.0))
    }
    fn abs(&self) -> Self {
        self.map(Interval::abs)
    }
    fn floor(&self) -> Self {
        self.map(Interval::floor)
    }
    fn is_finite(&self) -> bool {
        self.0.is_common_interval()
    }
    fn to_scientific(&self, digits: usize) -> String {
        Real::to_scientific(&self.0.mid(), digits)
    }
    fn square(&self) -> Self {
        self.map(Interval::sqr)
    }
    fn max_of(&self, other: &Self) -> Self {
        Iv(self.0.max(other.0))
    }
    fn min_of(&self, other: &Self) -> Self {
        Iv(self.0.min(other.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimals_are_enclosed() {
        let tenth = Iv::parse_decimal("0.1", Precision::DOUBLE).unwrap();
        let (lower, upper) = tenth.bounds();
        assert!(Float::with_val(200, lower) < Rational::from((1, 10)));
        assert!(Float::with_val(200, upper) > Rational::from((1, 10)));
    }

    #[test]
    fn sine_of_pi_encloses_zero() {
        let (lower, upper) = Iv::pi(Precision::DOUBLE).sin().bounds();
        assert!(lower <= 0.0 && 0.0 <= upper && upper - lower < 1e-15);
    }
}
