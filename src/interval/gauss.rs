//! Gauss–Legendre rules in f64 intervals at the fewest points their Bernstein-ellipse
//! bound allows: the interval counterpart of `ball_gauss`, with its ellipses and its grid
//! of degrees.
//!
//! For f analytic in the Bernstein ellipse E_ρ about [−1, 1] (foci ±1, half axes sum ρ)
//! with |f| ≤ M there, the n-point rule errs by at most (64/15)·M/((ρ − 1)·ρ^(2n−1))
//! (Trefethen, Approximation Theory and Approximation Practice, Thm 19.3; Arb's bound).
//! Mapped onto [a, b] = mid ± δ, the ellipse lies in the rectangle mid + δ·([−X, X] +
//! i[−Y, Y]) with ρ = X + √(X² − 1) and Y = √(X² − 1); the integrand, evaluated once on
//! that rectangle in analytic mode, gives M (times |δ| for the change of variable). Every
//! step of the bound rounds upward (ρ downward). The rule's value is Σ wᵢ f(xᵢ)·δ in
//! intervals, with nodes and weights enclosed by doubles from Arb's balls, plus [−E, E].

use std::sync::Arc;

use super::elementary;
use super::span::Span;
use super::Interval;
use crate::ball::Ball;
use crate::ball_gauss::{degree_at_least, legendre, ELLIPSES, LEAST_DEGREE_TO_WIDEN, NARROW_ELLIPSE, OWN_DEPTH};
use crate::quad::cache::{cached, Table};
use crate::real::{Precision, Real};

/// The precision of the Arb tables the doubles are rounded from: far beyond 53 bits, so
/// that each node's and weight's ball lies between two adjacent doubles or on one.
const TABLE_BITS: u32 = 128;

/// The nodes x_k ≥ 0 (decreasing) of an n-point rule on [−1, 1] and their weights, as
/// intervals that contain them; the rule's other nodes are −x_k.
struct IntervalRule {
    nodes: Vec<(Interval, Interval)>,
}

impl Table for IntervalRule {
    fn precision(&self) -> Precision {
        Precision::DOUBLE
    }

    fn rounded(&self, _: Precision) -> Self {
        IntervalRule {
            nodes: self.nodes.clone(),
        }
    }

    fn bytes(&self) -> usize {
        self.nodes.len() * std::mem::size_of::<(Interval, Interval)>()
    }
}

/// The n-point rule, from the shared node cache.
fn rule(n: u64) -> Option<Arc<IntervalRule>> {
    cached(n as usize, Precision::DOUBLE, || {
        let balls = legendre::nodes(n, TABLE_BITS)?;
        let outward = |ball: &Ball| ball.real_span().map(|(lo, hi)| Interval::new(lo, hi));
        let nodes = balls
            .nodes
            .iter()
            .map(|(x, w)| Some((outward(x)?, outward(w)?)))
            .collect::<Option<Vec<_>>>()?;
        Some(IntervalRule { nodes })
    })
}

/// One Bernstein ellipse, held by the rectangle [−X, X] × [−Y, Y].
struct Ellipse {
    /// A lower bound of ρ = X + √(X² − 1).
    rho: f64,
    x: f64,
    /// An upper bound of Y = √(X² − 1).
    y: f64,
}

impl Ellipse {
    fn new(half_axis: f64) -> Ellipse {
        let root = Span::point(half_axis).square().sub(Span::point(1.0)).sqrt();
        Ellipse {
            rho: Span::point(half_axis).add(root).lo,
            x: half_axis,
            y: root.hi,
        }
    }

    /// The rectangle mid + δ·([±X] + [±Y]i).
    fn around(&self, mid: &Interval, delta: &Interval) -> Interval {
        Interval::rectangle((-self.x, self.x), (-self.y, self.y)) * delta + mid
    }

    /// An upper bound of (64/15)·M/((ρ − 1)·ρ^(2n−1)).
    fn error(&self, bound: f64, n: u64) -> f64 {
        let rho = Span::point(self.rho);
        let denominator = rho
            .sub(Span::point(1.0))
            .mul(elementary::powi(rho, (2 * n - 1) as f64))
            .mul(Span::point(15.0));
        Span::point(64.0).mul(Span::point(bound)).div(denominator).hi
    }

    /// The least degree of the grid, up to `limit`, whose error bound is below
    /// `tolerance`, with that bound.
    fn degree(&self, bound: f64, tolerance: f64, limit: u64) -> Option<(u64, f64)> {
        // Solve (64/15)·M/((ρ − 1)ρ^(2n−1)) = tolerance for n: a start, checked below.
        let estimate = ((64.0f64 / 15.0).log2() + bound.log2() - (self.rho - 1.0).log2() - tolerance.log2())
            / (2.0 * self.rho.log2())
            + 0.5;
        let mut n = degree_at_least(if estimate.is_finite() {
            estimate.max(1.0).ceil() as u64
        } else {
            1
        });
        while n <= limit {
            let error = self.error(bound, n);
            if error < tolerance {
                return Some((n, error));
            }
            n = degree_at_least(n + 1);
        }
        None
    }
}

/// How an interval's integral is enclosed.
struct Rule<'a> {
    integrand: &'a dyn Fn(&Interval, bool) -> Option<Interval>,
    tolerance: f64,
    degree_limit: u64,
}

/// The integral of `integrand` over [start, end]: one Gauss–Legendre rule per part, at
/// the fewest points whose Bernstein-ellipse bound (X = 2 and wider, else X = 3/2) is
/// below `tolerance`, the interval halved where no ellipse gives a degree up to
/// `degree_limit`; `None` where some part still has none after six halvings, or the
/// integrand has no enclosure.
///
/// `integrand(x, analytic)` encloses f on x; with `analytic` true, x is a complex
/// rectangle on which f must be shown holomorphic (the caller evaluates it under
/// [`crate::doubts::with_analytic`]), `None` where it cannot. `tolerance` is the absolute
/// error each rule may have.
pub fn integrate(
    integrand: &dyn Fn(&Interval, bool) -> Option<Interval>,
    start: &Interval,
    end: &Interval,
    tolerance: f64,
    degree_limit: u64,
) -> Option<Interval> {
    let rule = Rule {
        integrand,
        tolerance,
        degree_limit,
    };
    rule.parts(start, end, OWN_DEPTH)
}

impl Rule<'_> {
    /// One rule over [start, end], or the sum over its halves down to `depth` halvings.
    fn parts(&self, start: &Interval, end: &Interval, depth: u32) -> Option<Interval> {
        if let Some(value) = self.one_rule(start, end) {
            return Some(value);
        }
        if depth == 0 {
            return None;
        }
        // Any point between the ends splits the integral exactly: a double.
        let middle = Interval::from_f64(start.midpoint() * 0.5 + end.midpoint() * 0.5, Precision::DOUBLE);
        let first = self.parts(start, &middle, depth - 1)?;
        Some(first + self.parts(&middle, end, depth - 1)?)
    }

    /// A bound of |f| on the rectangle about the piece, times |δ|.
    fn bound_on(&self, rectangle: &Interval, delta: &Interval) -> Option<f64> {
        let value = (self.integrand)(rectangle, true)?;
        let bound = Span::point(value.magnitude_bound())
            .mul(Span::point(delta.re.magnitude()))
            .hi;
        bound.is_finite().then_some(bound)
    }

    /// The degree and error bound on the ellipse of half axis X.
    fn rule_on(&self, half_axis: f64, mid: &Interval, delta: &Interval) -> Option<(u64, f64)> {
        let ellipse = Ellipse::new(half_axis);
        let bound = self.bound_on(&ellipse.around(mid, delta), delta)?;
        ellipse.degree(bound, self.tolerance, self.degree_limit)
    }

    /// One rule over [start, end] at the fewest points the bound allows, or `None`.
    fn one_rule(&self, start: &Interval, end: &Interval) -> Option<Interval> {
        let delta = (*end - start).times_power_of_two(-1);
        let mid = (*end + start).times_power_of_two(-1);
        let (n, error) = match self.rule_on(ELLIPSES[0], &mid, &delta) {
            Some(mut best) => {
                // Wider ellipses from 32 points up, while they fit and lower the degree.
                for half_axis in &ELLIPSES[1..] {
                    if best.0 < LEAST_DEGREE_TO_WIDEN {
                        break;
                    }
                    match self.rule_on(*half_axis, &mid, &delta) {
                        Some(found) if found.0 < best.0 => best = found,
                        _ => break,
                    }
                }
                best
            }
            None => self.rule_on(NARROW_ELLIPSE, &mid, &delta)?,
        };
        let table = rule(n)?;
        let sum = rule_sum(&table, n, &|t: &Interval| (self.integrand)(&(mid + delta * t), false))?;
        let value = sum * delta;
        // The integrand is real on the real interval, so the integral is real, and the
        // rule's error is at most `error` in absolute value.
        value
            .is_real()
            .then(|| value + Interval::new(-error, error))
            .filter(Real::is_finite)
    }
}

/// Σ wₖ g(xₖ) over the n-point rule on [−1, 1] (the table's nodes and their negatives; of
/// an odd rule the last node is the middle one, 0, taken once).
fn rule_sum(table: &IntervalRule, n: u64, g: &dyn Fn(&Interval) -> Option<Interval>) -> Option<Interval> {
    let mut sum = Interval::new(0.0, 0.0);
    for (k, (node, weight)) in table.nodes.iter().enumerate() {
        let middle = n % 2 == 1 && k + 1 == table.nodes.len();
        let value = if middle { g(node)? } else { g(node)? + g(&-*node)? };
        sum += value * weight;
    }
    Some(sum)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules_of_every_parity_integrate_polynomials_of_their_degree() {
        // ∫₋₁¹ 1 = 2 and ∫₋₁¹ t² = 2/3, the middle node of odd rules counted once.
        for n in 1..=19u64 {
            let table = rule(n).expect("a rule");
            assert_eq!(table.nodes.len() as u64, n.div_ceil(2));
            let ones = rule_sum(&table, n, &|_| Some(Interval::new(1.0, 1.0))).unwrap();
            assert!(ones.contains(2.0) && ones.width() < 1e-14, "n = {n}: {ones:?}");
            if n >= 2 {
                let squares = rule_sum(&table, n, &|t| Some(t.square())).unwrap();
                let (lo, hi) = squares.real_bounds();
                assert!(
                    lo <= 2.0 / 3.0 && hi >= 2.0 / 3.0 && hi - lo < 1e-14,
                    "n = {n}: {squares:?}"
                );
            }
        }
    }
}
