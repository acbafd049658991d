//! [`Real`] for intervals: real spans on real values, the analytic continuations on
//! rectangles (and on every value while an integrand is bounded on one), as
//! [`crate::ball::Ball`] does.

use rug::{Float, Rational};

use super::span::Span;
use super::{complex, elementary, Interval};
use crate::doubts::{analytic_required, not_analytic, undecided};
use crate::real::{ParseRealError, Precision, Real};

impl Interval {
    /// Where the value is real and `real_domain` holds of its span (the real function is
    /// analytic there, so its real form is its continuation): `real` of the span;
    /// otherwise `continued` of the rectangle, refused where it touches the principal
    /// branch cut while analytic continuations are required.
    fn branch_cut(
        &self,
        real_domain: impl Fn(Span) -> bool,
        real: impl Fn(Span) -> Span,
        continued: impl Fn(&Interval) -> Interval,
    ) -> Interval {
        if !self.complex_context() {
            return Interval::real(real(self.re));
        }
        if self.is_real() && real_domain(self.re) {
            return Interval::real(real(self.re));
        }
        if analytic_required() && complex::touches_cut(self) {
            not_analytic();
            return self.indeterminate();
        }
        continued(self)
    }

    /// An entire function: its real form on real values, `continued` on rectangles.
    fn entire(&self, real: impl Fn(Span) -> Span, continued: impl Fn(&Interval) -> Interval) -> Interval {
        if self.is_real() {
            Interval::real(real(self.re))
        } else {
            continued(self)
        }
    }

    /// The larger (or smaller) of two values: `real` on real spans (no decision needed);
    /// on rectangles the one `first` picks, which must decide.
    fn extreme(
        &self,
        other: &Interval,
        real: fn(Span, Span) -> Span,
        first: impl Fn(&Interval, &Interval) -> bool,
    ) -> Interval {
        if self.complex_context() || other.complex_context() {
            return if first(self, other) { *self } else { *other };
        }
        Interval::real(real(self.re, other.re))
    }
}

fn positive(x: Span) -> bool {
    x.lo > 0.0
}

impl Real for Interval {
    fn precision(&self) -> Precision {
        Precision::DOUBLE
    }
    fn from_f64(x: f64, _: Precision) -> Self {
        Interval::real(Span::point(x))
    }
    fn from_i64(n: i64, _: Precision) -> Self {
        Interval::enclosing_integer(n)
    }
    fn from_float(x: &Float, _: Precision) -> Self {
        Interval::enclosing_float(x)
    }
    fn parse_decimal(text: &str, _: Precision) -> Result<Self, ParseRealError> {
        crate::decimal::decimal(text)
            .map(|exact| Interval::enclosing_rational(&exact))
            .ok_or_else(|| ParseRealError { text: text.to_string() })
    }
    fn from_rational(x: &Rational, _: Precision) -> Self {
        Interval::enclosing_rational(x)
    }
    fn enclose_pi_multiple(multiple: &Rational, offset: &Rational, _: Precision) -> Option<Self> {
        Some(Interval::enclosing_pi_multiple(multiple, offset))
    }
    fn pi(_: Precision) -> Self {
        Interval::real(Span::pi())
    }
    fn epsilon(_: Precision) -> Self {
        Interval::real(Span::point(f64::EPSILON))
    }
    /// As for f64, whose doubles these are: below it, products lose digits to subnormals.
    fn smallest_full_precision(_: Precision) -> Self {
        Interval::real(Span::point(f64::MIN_POSITIVE / f64::EPSILON))
    }

    fn sqrt(&self) -> Self {
        self.branch_cut(positive, Span::sqrt, |z| {
            complex::exp(&complex::mul(&complex::ln(z), &Interval::real(Span::point(0.5))))
        })
    }
    fn cbrt(&self) -> Self {
        let root = |z: &Interval| {
            if z.is_real() {
                Interval::real(elementary::cbrt(z.re))
            } else {
                complex::pow(z, &Interval::real(Span::point(1.0).div(Span::point(3.0))))
            }
        };
        if !self.complex_context() {
            return root(self);
        }
        // The real cube root is odd: continue it from whichever side of zero the value is on.
        match self.real_sign() {
            Some(true) => root(self),
            Some(false) => -root(&-*self),
            None => {
                not_analytic();
                self.indeterminate()
            }
        }
    }
    fn ln(&self) -> Self {
        self.branch_cut(positive, elementary::ln, complex::ln)
    }
    fn ln_1p(&self) -> Self {
        if !self.complex_context() {
            return Interval::real(elementary::ln_1p(self.re));
        }
        let shifted = *self + Interval::real(Span::point(1.0));
        if analytic_required() && shifted.real_sign() != Some(true) {
            // ln(1 + z) is analytic where Re z > −1.
            not_analytic();
            return self.indeterminate();
        }
        self.branch_cut(|x| x.lo > -1.0, elementary::ln_1p, |_| complex::ln(&shifted))
    }
    fn exp(&self) -> Self {
        self.entire(elementary::exp, complex::exp)
    }
    fn exp_m1(&self) -> Self {
        self.entire(elementary::exp_m1, |z| {
            complex::exp(z) - Interval::real(Span::point(1.0))
        })
    }
    fn powr(&self, exponent: &Self) -> Self {
        let both_real = self.is_real() && exponent.is_real();
        if !(self.complex_context() || exponent.complex_context()) || (both_real && positive(self.re)) {
            return Interval::real(elementary::powr(self.re, exponent.re));
        }
        if analytic_required() && complex::touches_cut(self) {
            not_analytic();
            return self.indeterminate();
        }
        complex::pow(self, exponent)
    }
    fn powi(&self, exponent: i32) -> Self {
        self.entire(
            |x| elementary::powi(x, f64::from(exponent)),
            |z| complex::powi(z, exponent),
        )
    }
    fn square(&self) -> Self {
        self.entire(Span::square, complex::square)
    }
    /// Exact unless it leaves the normal range.
    fn times_power_of_two(self, exponent: i32) -> Self {
        Interval::from_parts(
            self.re.times_power_of_two(exponent),
            self.im.times_power_of_two(exponent),
        )
    }
    fn sin(&self) -> Self {
        self.entire(elementary::sin, complex::sin)
    }
    fn cos(&self) -> Self {
        self.entire(elementary::cos, complex::cos)
    }
    fn sin_cos(&self) -> (Self, Self) {
        if self.is_real() {
            let (sin, cos) = elementary::sin_cos(self.re);
            return (Interval::real(sin), Interval::real(cos));
        }
        (complex::sin(self), complex::cos(self))
    }
    fn sinh_cosh(&self) -> (Self, Self) {
        if self.is_real() {
            return (
                Interval::real(elementary::sinh(self.re)),
                Interval::real(elementary::cosh(self.re)),
            );
        }
        complex::sinh_cosh(self)
    }
    fn hypot(&self, other: &Self) -> Self {
        if !(self.complex_context() || other.complex_context()) {
            return Interval::real(elementary::hypot(self.re, other.re));
        }
        (self.square() + other.square()).sqrt()
    }
    fn atan2(&self, x: &Self) -> Self {
        if self.complex_context() || x.complex_context() {
            not_analytic();
            return self.indeterminate();
        }
        Interval::real(elementary::atan2(self.re, x.re))
    }
    fn abs(&self) -> Self {
        if !self.complex_context() {
            return Interval::real(self.re.abs());
        }
        match self.real_sign() {
            Some(true) => *self,
            Some(false) => -*self,
            None => {
                undecided();
                self.indeterminate()
            }
        }
    }
    fn floor(&self) -> Self {
        let floor = self.re.floor();
        // On a rectangle floor is analytic (constant) only where it is one integer.
        if self.complex_context() && !floor.is_point() {
            not_analytic();
            return self.indeterminate();
        }
        Interval::real(floor)
    }
    fn is_finite(&self) -> bool {
        self.re.is_finite() && self.im.is_finite()
    }
    fn max_of(&self, other: &Self) -> Self {
        self.extreme(other, Span::max, |a, b| a >= b)
    }
    fn min_of(&self, other: &Self) -> Self {
        self.extreme(other, Span::min, |a, b| a <= b)
    }
    fn to_scientific(&self, digits: usize) -> String {
        Real::to_scientific(&self.midpoint(), digits)
    }
    /// The real part; an indeterminate value stands for the whole line.
    fn real_span(&self) -> Option<(f64, f64)> {
        if self.re.is_indeterminate() {
            return Some((f64::NEG_INFINITY, f64::INFINITY));
        }
        Some((self.re.lo, self.re.hi))
    }
    fn lies_inside(&self, outer: &Self) -> bool {
        let strictly = |inner: Span, outer: Span| outer.lo < inner.lo && inner.hi < outer.hi;
        strictly(self.re, outer.re) && (strictly(self.im, outer.im) || (self.im.is_zero() && outer.im.is_zero()))
    }
    fn real_ends(&self) -> (Self, Self) {
        (
            Interval::real(Span::point(self.re.lo)),
            Interval::real(Span::point(self.re.hi)),
        )
    }
    fn centred_square(&self) -> Self {
        let reach = self.re.magnitude().max(self.im.magnitude());
        let around = Span::new(-reach, reach);
        if self.im.is_zero() {
            Interval::real(around)
        } else {
            Interval::from_parts(around, around)
        }
    }
    fn midpoint_value(&self) -> Self {
        Interval::real(Span::point(self.midpoint()))
    }
    fn union(&self, other: &Self) -> Self {
        Interval::from_parts(self.re.hull(other.re), self.im.hull(other.im))
    }
}
