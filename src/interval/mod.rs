//! f64 intervals with outward rounding: a [`Real`](crate::real::Real) whose every value
//! encloses the exact value of what it computes, at the cost of a few double operations
//! per operation (Arb's balls cost about a hundred nanoseconds each).
//!
//! An [`Interval`] is a complex rectangle [a, b] + i[c, d] of doubles. Its semantics are
//! those of Arb balls (`crate::ball::Ball`): values built through `Real` are real (the imaginary
//! part exactly [0, 0]) and every function takes its real form (the square root of an
//! interval reaching below zero is indeterminate, as f64 gives NaN). Complex values
//! appear where an integrand is bounded on a rectangle around a piece of the real axis
//! ([`crate::doubts::with_analytic`]); there each function is the analytic continuation
//! of its real form, and a function that is not analytic on the rectangle (a branch cut
//! is touched, `abs` or a comparison cannot decide the sign of the real part) yields an
//! indeterminate value and counts a doubt. Comparisons of overlapping intervals answer
//! `false` and count an undecided comparison ([`crate::doubts::watch`]); they compare
//! real parts.
//!
//! Arithmetic and square roots round to nearest and widen by one ulp each way unless an
//! exactness test shows nothing was rounded; exp, ln, powers, sin, cos, atan2, hypot and
//! cbrt come from CORE-MATH, correctly rounded, widened likewise (module `elementary`).
//! Precision is always 53 bits.

mod complex;
mod elementary;
#[cfg(feature = "certified")]
pub mod gauss;
mod inputs;
mod operators;
mod real;
mod span;

use std::cmp::Ordering;
use std::fmt;

use num_traits::ToPrimitive;

use crate::doubts::{analytic_required, undecided};
use span::Span;

/// A complex rectangle of doubles, real wherever [`Real`](crate::real::Real) built it.
#[derive(Clone, Copy)]
pub struct Interval {
    re: Span,
    im: Span,
}

impl Interval {
    /// The real interval [lo, hi] (indeterminate where the ends are NaN or out of order).
    pub fn new(lo: f64, hi: f64) -> Interval {
        Interval::real(Span::new(lo, hi))
    }

    /// The rectangle [re.0, re.1] + i[im.0, im.1].
    pub fn rectangle(re: (f64, f64), im: (f64, f64)) -> Interval {
        Interval::from_parts(Span::new(re.0, re.1), Span::new(im.0, im.1))
    }

    /// The real part's ends (NaN for an indeterminate value).
    pub fn real_bounds(&self) -> (f64, f64) {
        (self.re.lo, self.re.hi)
    }

    /// The imaginary part's ends.
    pub fn imaginary_bounds(&self) -> (f64, f64) {
        (self.im.lo, self.im.hi)
    }

    /// Whether the imaginary part is exactly zero.
    #[inline]
    pub fn is_real(&self) -> bool {
        self.im.is_zero()
    }

    /// Whether the value is one exact number.
    pub fn is_exact(&self) -> bool {
        self.re.is_point() && self.im.is_point()
    }

    /// Whether the real interval holds the double `x`.
    pub fn contains(&self, x: f64) -> bool {
        self.is_real() && self.re.lo <= x && x <= self.re.hi
    }

    /// The width of the real part.
    pub fn width(&self) -> f64 {
        self.re.hi - self.re.lo
    }

    /// An upper bound of |z| over the rectangle (infinite where it is not finite).
    pub fn magnitude_bound(&self) -> f64 {
        if !crate::real::Real::is_finite(self) {
            return f64::INFINITY;
        }
        elementary::hypot(Span::point(self.re.magnitude()), Span::point(self.im.magnitude())).hi
    }

    #[inline]
    fn real(re: Span) -> Interval {
        Interval { re, im: Span::ZERO }
    }

    #[inline]
    fn from_parts(re: Span, im: Span) -> Interval {
        if re.is_indeterminate() || im.is_indeterminate() {
            return Interval {
                re: Span::INDETERMINATE,
                im: Span::INDETERMINATE,
            };
        }
        Interval { re, im }
    }

    /// A value that holds every complex number (not finite).
    fn indeterminate(&self) -> Interval {
        Interval::from_parts(Span::INDETERMINATE, Span::INDETERMINATE)
    }

    /// Whether functions must take their complex, analytic-checked form: on a complex
    /// rectangle, and on any value while an integrand is bounded on one.
    fn complex_context(&self) -> bool {
        !self.is_real() || analytic_required()
    }

    /// The sign of the real part where it is decided: `Some(true)` for > 0.
    fn real_sign(&self) -> Option<bool> {
        if self.re.lo > 0.0 {
            Some(true)
        } else if self.re.hi < 0.0 {
            Some(false)
        } else {
            None
        }
    }

    /// The real part's midpoint.
    fn midpoint(&self) -> f64 {
        self.re.lo * 0.5 + self.re.hi * 0.5
    }
}

impl PartialEq for Interval {
    /// Equal when both are the same exact number; unequal when the real or imaginary
    /// parts are disjoint; otherwise undecided (counted, and `false`).
    fn eq(&self, other: &Interval) -> bool {
        let disjoint = |a: Span, b: Span| a.hi < b.lo || b.hi < a.lo;
        if self.is_exact() && other.is_exact() && self.re == other.re && self.im == other.im {
            true
        } else if disjoint(self.re, other.re) || disjoint(self.im, other.im) {
            false
        } else {
            undecided();
            false
        }
    }
}

/// One order relation on the real parts, `certain` deciding it true and `refuted` false.
fn decide(certain: bool, refuted: bool) -> bool {
    if certain {
        true
    } else if !refuted {
        undecided();
        false
    } else {
        false
    }
}

impl PartialOrd for Interval {
    fn partial_cmp(&self, other: &Interval) -> Option<Ordering> {
        let (a, b) = (self.re, other.re);
        if a.hi < b.lo {
            Some(Ordering::Less)
        } else if a.lo > b.hi {
            Some(Ordering::Greater)
        } else if self.is_exact() && other.is_exact() && a == b && self.im == other.im {
            Some(Ordering::Equal)
        } else {
            undecided();
            None
        }
    }
    fn lt(&self, other: &Interval) -> bool {
        decide(self.re.hi < other.re.lo, self.re.lo >= other.re.hi)
    }
    fn le(&self, other: &Interval) -> bool {
        decide(self.re.hi <= other.re.lo, self.re.lo > other.re.hi)
    }
    fn gt(&self, other: &Interval) -> bool {
        decide(self.re.lo > other.re.hi, self.re.hi <= other.re.lo)
    }
    fn ge(&self, other: &Interval) -> bool {
        decide(self.re.lo >= other.re.hi, self.re.hi < other.re.lo)
    }
}

impl fmt::Debug for Interval {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "[{:e}, {:e}]", self.re.lo, self.re.hi)?;
        if !self.is_real() {
            write!(f, " + [{:e}, {:e}]i", self.im.lo, self.im.hi)?;
        }
        Ok(())
    }
}

impl ToPrimitive for Interval {
    fn to_i64(&self) -> Option<i64> {
        let x = self.midpoint();
        (x.is_finite() && x.abs() < 9.2e18).then_some(x as i64)
    }
    fn to_u64(&self) -> Option<u64> {
        let x = self.midpoint();
        (x.is_finite() && (0.0..1.8e19).contains(&x)).then_some(x as u64)
    }
    fn to_f64(&self) -> Option<f64> {
        Some(self.midpoint())
    }
}
