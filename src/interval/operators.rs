//! The arithmetic operators: real spans on real values, rectangles otherwise.

use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Rem, RemAssign, Sub, SubAssign};

use super::span::Span;
use super::{complex, Interval};
use crate::doubts::not_analytic;

impl Interval {
    #[inline]
    fn plus(&self, rhs: &Interval) -> Interval {
        if self.is_real() && rhs.is_real() {
            return Interval::real(self.re.add(rhs.re));
        }
        Interval::from_parts(self.re.add(rhs.re), self.im.add(rhs.im))
    }

    #[inline]
    fn minus(&self, rhs: &Interval) -> Interval {
        self.plus(&-*rhs)
    }

    #[inline]
    fn times(&self, rhs: &Interval) -> Interval {
        if self.is_real() && rhs.is_real() {
            return Interval::real(self.re.mul(rhs.re));
        }
        complex::mul(self, rhs)
    }

    #[inline]
    fn over(&self, rhs: &Interval) -> Interval {
        if self.is_real() && rhs.is_real() {
            return Interval::real(self.re.div(rhs.re));
        }
        complex::div(self, rhs)
    }

    /// x − y·trunc(x/y), the remainder f64's `%` gives; where trunc(x/y) is not one
    /// integer throughout, the interval covers every candidate.
    fn remainder(&self, rhs: &Interval) -> Interval {
        if self.complex_context() || rhs.complex_context() {
            not_analytic();
            return self.indeterminate();
        }
        let quotient = self.re.div(rhs.re);
        let floor = quotient.floor();
        let ceiling = Span::new(quotient.lo.ceil(), quotient.hi.ceil());
        let truncated = if quotient.lo >= 0.0 {
            floor
        } else if quotient.hi <= 0.0 {
            ceiling
        } else {
            floor.hull(ceiling)
        };
        Interval::real(self.re.sub(truncated.mul(rhs.re)))
    }
}

/// A binary operator and its assigning form, by value and by reference.
macro_rules! operator {
    ($trait:ident, $method:ident, $assign_trait:ident, $assign:ident, $inherent:ident) => {
        impl $trait<&Interval> for Interval {
            type Output = Interval;
            #[inline]
            fn $method(self, rhs: &Interval) -> Interval {
                self.$inherent(rhs)
            }
        }
        impl $trait<Interval> for Interval {
            type Output = Interval;
            #[inline]
            fn $method(self, rhs: Interval) -> Interval {
                self.$inherent(&rhs)
            }
        }
        impl $assign_trait<&Interval> for Interval {
            #[inline]
            fn $assign(&mut self, rhs: &Interval) {
                *self = self.$inherent(rhs);
            }
        }
        impl $assign_trait<Interval> for Interval {
            #[inline]
            fn $assign(&mut self, rhs: Interval) {
                *self = self.$inherent(&rhs);
            }
        }
    };
}

operator!(Add, add, AddAssign, add_assign, plus);
operator!(Sub, sub, SubAssign, sub_assign, minus);
operator!(Mul, mul, MulAssign, mul_assign, times);
operator!(Div, div, DivAssign, div_assign, over);
operator!(Rem, rem, RemAssign, rem_assign, remainder);

impl Neg for Interval {
    type Output = Interval;
    #[inline]
    fn neg(self) -> Interval {
        Interval {
            re: self.re.neg(),
            im: self.im.neg(),
        }
    }
}
