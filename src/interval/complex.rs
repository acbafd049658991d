//! Complex rectangles: the analytic continuations of the elementary functions, in
//! rectangular interval arithmetic. The rectangles enclose the functions' values (each
//! part computed by the real spans' rigorous operations), not tightly: they serve the
//! bound of an integrand over an ellipse, where a tenfold overestimate costs about one
//! node pair.

use super::elementary;
use super::span::Span;
use super::Interval;

pub(super) fn mul(a: &Interval, b: &Interval) -> Interval {
    Interval::from_parts(a.re.mul(b.re).sub(a.im.mul(b.im)), a.re.mul(b.im).add(a.im.mul(b.re)))
}

/// a/b = a·conj(b)/|b|²; indeterminate where |b|² may be zero.
pub(super) fn div(a: &Interval, b: &Interval) -> Interval {
    let norm = b.re.square().add(b.im.square());
    if norm.contains_zero() {
        return Interval::from_parts(Span::INDETERMINATE, Span::INDETERMINATE);
    }
    Interval::from_parts(
        a.re.mul(b.re).add(a.im.mul(b.im)).div(norm),
        a.im.mul(b.re).sub(a.re.mul(b.im)).div(norm),
    )
}

pub(super) fn square(z: &Interval) -> Interval {
    Interval::from_parts(z.re.square().sub(z.im.square()), z.re.mul(z.im).times_power_of_two(1))
}

/// e^(a+ib) = e^a (cos b + i sin b).
pub(super) fn exp(z: &Interval) -> Interval {
    let scale = elementary::exp(z.re);
    let (sin, cos) = elementary::sin_cos(z.im);
    Interval::from_parts(scale.mul(cos), scale.mul(sin))
}

/// Whether the rectangle meets the principal logarithm's branch cut (the real axis from
/// 0 down, 0 included), where no power or logarithm is analytic.
pub(super) fn touches_cut(z: &Interval) -> bool {
    (z.re.lo <= 0.0 && z.im.contains_zero()) || z.re.is_indeterminate()
}

/// The principal logarithm ln|z| + i·arg z (arg over the rectangle as
/// [`elementary::atan2`] bounds it: [−π, π] where the rectangle crosses the cut).
pub(super) fn ln(z: &Interval) -> Interval {
    let modulus = elementary::hypot(z.re, z.im);
    Interval::from_parts(elementary::ln(modulus), elementary::atan2(z.im, z.re))
}

/// z^w = e^(w ln z) on the principal branch.
pub(super) fn pow(z: &Interval, w: &Interval) -> Interval {
    exp(&mul(w, &ln(z)))
}

/// sin(a+ib) = sin a cosh b + i cos a sinh b.
pub(super) fn sin(z: &Interval) -> Interval {
    let (sinh, cosh) = (elementary::sinh(z.im), elementary::cosh(z.im));
    let (sin, cos) = elementary::sin_cos(z.re);
    Interval::from_parts(sin.mul(cosh), cos.mul(sinh))
}

/// cos(a+ib) = cos a cosh b − i sin a sinh b.
pub(super) fn cos(z: &Interval) -> Interval {
    let (sinh, cosh) = (elementary::sinh(z.im), elementary::cosh(z.im));
    let (sin, cos) = elementary::sin_cos(z.re);
    Interval::from_parts(cos.mul(cosh), sin.mul(sinh).neg())
}

/// sinh(a+ib) = sinh a cos b + i cosh a sin b and cosh(a+ib) = cosh a cos b + i sinh a sin b.
pub(super) fn sinh_cosh(z: &Interval) -> (Interval, Interval) {
    let (sinh, cosh) = (elementary::sinh(z.re), elementary::cosh(z.re));
    let (sin, cos) = elementary::sin_cos(z.im);
    (
        Interval::from_parts(sinh.mul(cos), cosh.mul(sin)),
        Interval::from_parts(cosh.mul(cos), sinh.mul(sin)),
    )
}

/// zⁿ by repeated squaring (a negative n: the reciprocal).
pub(super) fn powi(z: &Interval, n: i32) -> Interval {
    let mut result = Interval::from_parts(Span::point(1.0), Span::ZERO);
    let mut base = *z;
    let mut remaining = n.unsigned_abs();
    while remaining > 0 {
        if remaining % 2 == 1 {
            result = mul(&result, &base);
        }
        remaining /= 2;
        if remaining > 0 {
            base = square(&base);
        }
    }
    if n < 0 {
        div(&Interval::from_parts(Span::point(1.0), Span::ZERO), &result)
    } else {
        result
    }
}
