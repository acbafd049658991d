//! The elementary functions of real spans, from CORE-MATH's correctly rounded doubles
//! (the `core-math` crate): the exact value of each function at a double lies within
//! half an ulp of the double returned, so the ulp either side encloses it. A monotone
//! function takes its range from the span's ends; sine and cosine also from the extrema
//! that the span may hold, found against an enclosure of π.

use core_math as cm;

use super::span::Span;

/// An increasing function over the span, from its correctly rounded values at the ends.
fn increasing(x: Span, f: impl Fn(f64) -> f64) -> Span {
    if x.is_point() {
        return Span::around(f(x.lo));
    }
    Span::new(f(x.lo).next_down(), f(x.hi).next_up())
}

/// A function of |x| that increases with it, over the span.
fn increasing_in_magnitude(x: Span, f: impl Fn(f64) -> f64) -> Span {
    if x.is_point() {
        return Span::around(f(x.lo));
    }
    Span::new(f(x.mignitude()).next_down(), f(x.magnitude()).next_up())
}

/// The half line [0, ∞], which holds every exponential.
const POSITIVE: Span = Span {
    lo: 0.0,
    hi: f64::INFINITY,
};

pub(crate) fn exp(x: Span) -> Span {
    if x.is_zero() {
        return Span::point(1.0);
    }
    increasing(x, cm::exp).within(POSITIVE)
}

pub(crate) fn exp_m1(x: Span) -> Span {
    if x.is_zero() {
        return Span::ZERO;
    }
    increasing(x, cm::expm1).within(Span::new(-1.0, f64::INFINITY))
}

/// The natural logarithm; indeterminate where the span reaches zero or below.
pub(crate) fn ln(x: Span) -> Span {
    if x.is_indeterminate() || x.lo <= 0.0 {
        return Span::INDETERMINATE;
    }
    if x == Span::point(1.0) {
        return Span::ZERO;
    }
    increasing(x, cm::log)
}

/// ln(1 + x); indeterminate where the span reaches −1 or below.
pub(crate) fn ln_1p(x: Span) -> Span {
    if x.is_indeterminate() || x.lo <= -1.0 {
        return Span::INDETERMINATE;
    }
    if x.is_zero() {
        return Span::ZERO;
    }
    increasing(x, cm::log1p)
}

/// The real cube root, exact where the double's cube is the argument.
pub(crate) fn cbrt(x: Span) -> Span {
    let root = |v: f64| {
        let r = cm::cbrt(v);
        let square = r * r;
        let exact = super::span::is_exact_product(r, r, square)
            && super::span::is_exact_product(square, r, square * r)
            && square * r == v;
        if exact || v == 0.0 {
            Span::point(r)
        } else {
            Span::around(r)
        }
    };
    Span::new(root(x.lo).lo, root(x.hi).hi)
}

pub(crate) fn sinh(x: Span) -> Span {
    if x.is_zero() {
        return Span::ZERO;
    }
    increasing(x, cm::sinh)
}

pub(crate) fn cosh(x: Span) -> Span {
    if x.is_zero() {
        return Span::point(1.0);
    }
    increasing_in_magnitude(x, cm::cosh).within(Span::new(1.0, f64::INFINITY))
}

pub(crate) fn sin(x: Span) -> Span {
    if x.is_zero() {
        return Span::ZERO;
    }
    match narrow_sin_cos(x) {
        Some((sin, _)) => sin,
        None => periodic(x, cm::sin, 0.5),
    }
}

pub(crate) fn cos(x: Span) -> Span {
    if x.is_zero() {
        return Span::point(1.0);
    }
    match narrow_sin_cos(x) {
        Some((_, cos)) => cos,
        None => periodic(x, cm::cos, 0.0),
    }
}

/// (sin x, cos x) for one evaluation of both where the span is narrow.
pub(crate) fn sin_cos(x: Span) -> (Span, Span) {
    match narrow_sin_cos(x) {
        Some(pair) if !x.is_zero() => pair,
        _ => (sin(x), cos(x)),
    }
}

/// The largest half width of a span whose sine and cosine are taken by Taylor's theorem
/// about its midpoint: the remainder's r²/2 is then below r/32 of the first term's r.
const TAYLOR_RADIUS: f64 = 1.0 / 16.0;

/// Sine and cosine of a point, or of a span of half width r ≤ [`TAYLOR_RADIUS`] about a
/// midpoint m: sin(m + h) = sin m + h cos m − (h²/2) sin ξ and cos(m + h) = cos m −
/// h sin m − (h²/2) cos ξ with |h| ≤ r, from one correctly rounded sincos of m. `None`
/// for a wider span.
fn narrow_sin_cos(x: Span) -> Option<(Span, Span)> {
    if x.is_point() && x.is_finite() {
        let (sin, cos) = cm::sincos(x.lo);
        return Some((
            Span::around(sin).within(Span::UNIT),
            Span::around(cos).within(Span::UNIT),
        ));
    }
    let middle = x.lo * 0.5 + x.hi * 0.5;
    let m = Span::point(middle);
    let radius = Span::point(x.hi).sub(m).hi.max(m.sub(Span::point(x.lo)).hi);
    if radius.is_nan() || radius > TAYLOR_RADIUS {
        return None;
    }
    let (sin, cos) = cm::sincos(middle);
    let (sin, cos) = (Span::around(sin), Span::around(cos));
    let step = Span::new(-radius, radius);
    let remainder = Span::point(radius).square().times_power_of_two(-1).hi;
    let remainder = Span::new(-remainder, remainder);
    Some((
        sin.add(cos.mul(step)).add(remainder).within(Span::UNIT),
        cos.sub(sin.mul(step)).add(remainder).within(Span::UNIT),
    ))
}

/// Sine or cosine over the span: `f` has its maxima (1) where x/π − `shift` is an even
/// integer and its minima (−1) where it is odd, and is monotone between them. The
/// integers n with x/π − `shift` = n possible in the span are found from an enclosure of
/// x/π; where none is, the range is the hull of the ends' values; where one is, its
/// extremum joins them; where two or more are, it is [−1, 1].
fn periodic(x: Span, f: fn(f64) -> f64, shift: f64) -> Span {
    if x.is_indeterminate() {
        return x;
    }
    if !x.is_finite() {
        return Span::UNIT;
    }
    if x.is_point() {
        return Span::around(f(x.lo)).within(Span::UNIT);
    }
    let turns = x.div(Span::pi()).sub(Span::point(shift));
    let (first, last) = (turns.lo.ceil(), turns.hi.floor());
    // Two candidates or more (or an enclosure too wide to count them): both extrema.
    let beyond_first = last - first;
    if beyond_first.is_nan() || beyond_first >= 1.0 {
        return Span::UNIT;
    }
    let mut range = Span::around(f(x.lo)).hull(Span::around(f(x.hi)));
    if first == last {
        if first % 2.0 == 0.0 {
            range.hi = 1.0;
        } else {
            range.lo = -1.0;
        }
    }
    range.within(Span::UNIT)
}

/// The angle of the points (x, y) of a box, in [−π, π]: the hull of the corners' angles
/// (the angle is monotone along each edge of a box that misses the origin, and continuous
/// off the negative x axis), or [−π, π] where the box holds the origin or crosses the
/// negative x axis (y = 0 with x < 0 has the angle π, and points just below it angles
/// near −π). At the origin itself, 0.
pub(crate) fn atan2(y: Span, x: Span) -> Span {
    if y.is_indeterminate() || x.is_indeterminate() {
        return Span::INDETERMINATE;
    }
    if y.is_zero() && x.is_zero() {
        // The origin's angle, by Arb's convention (f64 gives ±0 or ±π by the zeros' signs).
        return Span::ZERO;
    }
    let whole = Span::new(-Span::pi().hi, Span::pi().hi);
    let crosses_axis = y.lo < 0.0 && y.hi >= 0.0;
    if (crosses_axis && x.lo <= 0.0) || (x.contains_zero() && y.contains_zero()) {
        return whole;
    }
    // +0 for −0: the angle at y = 0 is that of the positive zero (π for x < 0).
    let (y_lo, y_hi) = (y.lo + 0.0, y.hi + 0.0);
    if y.is_point() && x.is_point() {
        return Span::around(cm::atan2(y_lo, x.lo)).within(whole);
    }
    let corners = [(y_lo, x.lo), (y_lo, x.hi), (y_hi, x.lo), (y_hi, x.hi)];
    corners
        .iter()
        .map(|&(b, a)| Span::around(cm::atan2(b, a)))
        .reduce(Span::hull)
        .unwrap_or(whole)
        .within(whole)
}

/// √(x² + y²) over a box: increasing in |x| and |y|.
pub(crate) fn hypot(x: Span, y: Span) -> Span {
    if x.is_indeterminate() || y.is_indeterminate() {
        return Span::INDETERMINATE;
    }
    let least = cm::hypot(x.mignitude(), y.mignitude());
    let most = cm::hypot(x.magnitude(), y.magnitude());
    if least == most && x.is_point() && y.is_point() {
        return Span::around(least).within(POSITIVE);
    }
    Span::new(least.next_down(), most.next_up()).within(POSITIVE)
}

/// x^e for x ≥ 0: e·ln x is bilinear in (e, ln x), so over a box its extremes, and those
/// of x^e, lie at the corners. Indeterminate where x reaches below zero.
pub(crate) fn powr(x: Span, e: Span) -> Span {
    if e.is_point() && e.lo.fract() == 0.0 {
        // An integer power is defined for every base, as f64 and Arb take it.
        return powi(x, e.lo);
    }
    if x.is_indeterminate() || x.lo < 0.0 || e.is_indeterminate() {
        return Span::INDETERMINATE;
    }
    if x.is_point() && e.is_point() {
        return Span::around(cm::pow(x.lo, e.lo)).within(POSITIVE);
    }
    let corners = [(x.lo, e.lo), (x.lo, e.hi), (x.hi, e.lo), (x.hi, e.hi)];
    corners
        .iter()
        .map(|&(base, exponent)| Span::around(cm::pow(base, exponent)))
        .reduce(Span::hull)
        .unwrap_or(Span::INDETERMINATE)
        .within(POSITIVE)
}

/// xⁿ for an integer n: monotone on either side of zero; across it, odd powers increase
/// and even ones take their least value 0 there (a negative power has none:
/// indeterminate).
pub(crate) fn powi(x: Span, n: f64) -> Span {
    if x.is_indeterminate() {
        return x;
    }
    let power = |v: f64| cm::pow(v, n);
    let even = n % 2.0 == 0.0;
    match n {
        0.0 => Span::point(1.0),
        1.0 => x,
        2.0 => x.square(),
        _ if x.contains_zero() && n < 0.0 => Span::INDETERMINATE,
        _ if x.contains_zero() && even => Span::new(0.0, power(x.magnitude()).next_up()),
        _ if x.contains_zero() => increasing(x, power),
        _ if x.is_point() => Span::around(power(x.lo)),
        _ => Span::around(power(x.lo)).hull(Span::around(power(x.hi))),
    }
}
