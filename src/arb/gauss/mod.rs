//! Gauss–Legendre rules on Arb balls at the fewest points their Bernstein-ellipse bound
//! allows, one per piece or per half (proofs/certified-digits.md, "The rule per piece").
//!
//! Arb's `acb_calc_integrate` takes its degrees from steps of about √2 (…, 16, 22, 32,
//! 46, 64, 90, 128, …) and its ellipses from X = 2, 4, 8, 32, …, and bisects where X = 2
//! does not fit a subinterval. Here the degree is the least of a grid of eight steps an
//! octave (…, 16, 18, 20, …, 30, 32, 36, …) that the bound allows, and from 32 points up
//! the ellipses X = 9/4, 5/2, 3, 4, 6, 8, 16 are tried too. Where one box over the X = 2
//! rectangle does not bound the integrand, the narrower ellipse X = 3/2 is tried, or from
//! 256 bits the X = 2 rectangle cut into cells; where that fails too, the interval is
//! halved (so that the degrees of a case, and their node tables, stay few), and after
//! [`OWN_DEPTH`] halvings what is left goes to Arb's bisection. The parts of one piece at
//! one depth start from the bound that served the last of them. Where a node table is
//! costly (hundreds of digits), rules share tables: a rule takes a held table of up to a
//! quarter more points, or a degree of a coarser grid ([`shared_degree`]).

use flint_sys::acb::acb_init;
use flint_sys::acb_types::acb_struct;
use flint_sys::arb::{arb_add_error_mag, arb_mul_2exp_si, arb_mul_si, arb_set_d};
use flint_sys::arb_types::mag_struct;
use flint_sys::mag::{
    mag_add_lower, mag_cmp, mag_div, mag_get_d_log2_approx, mag_is_finite, mag_mul, mag_mul_2exp_si, mag_mul_lower,
    mag_mul_ui_lower, mag_one, mag_pow_ui_lower, mag_set, mag_sqrt, mag_sqrt_lower, mag_sub, mag_sub_lower,
};

pub(crate) mod legendre;

use legendre::nodes;

use crate::ball::{Ball, Mag};
use crate::real::Real;

/// The half axes X along the interval (in units of its half length) of the rectangles
/// that hold the Bernstein ellipses tried, in turn while they fit and lower the degree:
/// ρ = X + √(X² − 1), from 3.7 to 32. The first is Arb's first; the steps below 3 are
/// fine because the nearest singularity of an ordinary piece (where the load vanishes,
/// off the real axis) usually lies between the X = 2 and X = 3 rectangles, and ρ, which
/// sets the degree, grows by a sixth from X = 2 to 9/4 and again to 5/2.
pub(crate) const ELLIPSES: [f64; 8] = [2.0, 2.25, 2.5, 3.0, 4.0, 6.0, 8.0, 16.0];

/// The least degree at which a larger ellipse is tried: an evaluation on a complex ball
/// costs about four on real points, and the next ellipse saves a quarter of the points
/// where it fits, so below 32 points a probe that fails (the usual case on a piece whose
/// ends are the integrand's nearest singularities' neighbours) costs more than one that
/// fits saves.
pub(crate) const LEAST_DEGREE_TO_WIDEN: u64 = 32;

/// Cells per side of the grid on which the integrand is bounded where one box over the
/// whole first ellipse bounds it too loosely (see [`Ellipse::cells`]).
const GRID: u32 = 4;
// The cells' centres and radii are exact only for a power of two (`Ellipse::cells`).
const _: () = assert!(GRID.is_power_of_two());

/// The half axis X of the ellipse tried below [`GRID_FROM_BITS`] where X = 2 gives no
/// degree: its rectangle reaches 1.12 half lengths off the axis (X = 2: 1.73), so a box
/// arithmetic that widens with the box often bounds it (ρ = 2.6 against 3.7).
pub(crate) const NARROW_ELLIPSE: f64 = 1.5;

/// The least working precision at which the grid is tried: below it, the halves' rules
/// cost less than the grid's cells (proofs/certified-digits.md, "Cells on the ellipse").
const GRID_FROM_BITS: u32 = 256;

/// How many times an interval is halved here before Arb's bisection takes what is left.
pub(crate) const OWN_DEPTH: u32 = 6;

/// Which bound served the last part of a piece at one halving depth. The parts at one
/// depth have the same length and, along a piece, often the same distance to the
/// integrand's nearest singularity (near separation every part of a bottom-map piece
/// fails alike), so the next part there starts from what served the last: the fallback
/// alone where it served; after a failure only the X = 2 box (the cells cost sixteen);
/// after two failures in a row none, the part halved at once. One failure is not enough
/// to skip a part: next to a pole at one end only the parts nearest to it fail, and the
/// parts after them must be tried. At the last depth, which hands a part to Arb's
/// bisection, every part gets the full attempt. Which rules are tried changes the points
/// spent, never the rigour.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
enum Served {
    /// The X = 2 ellipse (and any wider one), tried first.
    #[default]
    FirstEllipse,
    /// The narrower ellipse, or the cells from 256 bits.
    Fallback,
    /// Neither: the part was halved.
    Neither,
    /// Neither, on the last two parts.
    NeitherTwice,
}

/// One Bernstein ellipse E_ρ about [−1, 1], held by the rectangle [−X, X] × [−Y, Y].
pub(crate) struct Ellipse {
    /// A lower bound of ρ = X + √(X² − 1).
    rho: Mag,
    /// X (exact).
    x: Mag,
    /// An upper bound of Y = √(X² − 1).
    y: Mag,
}

impl Ellipse {
    pub(crate) fn new(half_axis: f64) -> Ellipse {
        let x = Mag::of(half_axis);
        let (mut rho, mut y, mut one) = (Mag::new(), Mag::new(), Mag::new());
        // SAFETY: all initialised; the lower and upper roundings keep ρ below and Y above
        // their exact values.
        unsafe {
            mag_one(&mut one.0);
            mag_mul_lower(&mut rho.0, &x.0, &x.0);
            mag_sub_lower(&mut rho.0, &rho.0, &one.0);
            mag_sqrt_lower(&mut rho.0, &rho.0);
            mag_add_lower(&mut rho.0, &rho.0, &x.0);
            mag_mul(&mut y.0, &x.0, &x.0);
            mag_sub(&mut y.0, &y.0, &one.0);
            mag_sqrt(&mut y.0, &y.0);
        }
        Ellipse { rho, x, y }
    }

    /// The rectangle mid + delta·([±X] + [±Y]i), which holds the ellipse mapped onto the piece.
    pub(crate) fn around(&self, mid: &Ball, delta: &Ball) -> Ball {
        let mut raw = acb_struct::default();
        // SAFETY: initialised, then only its radii set; `wrap` takes it over.
        unsafe {
            acb_init(&mut raw);
            mag_set(&mut raw.real.rad, &self.x.0);
            mag_set(&mut raw.imag.rad, &self.y.0);
        }
        let unit = Ball::wrap(raw, mid.precision().in_bits());
        unit * delta + mid
    }

    /// [`GRID`]² cells whose union holds the rectangle of [`Ellipse::around`], each mapped
    /// onto the piece: a box arithmetic that widens with the box (a product of two loads
    /// that each vary over the rectangle) is the tighter the smaller the box.
    fn cells(&self, mid: &Ball, delta: &Ball) -> impl Iterator<Item = Ball> + '_ {
        // The cells cover [−X, X] × [−Y', Y'] with Y' = `mag_get_d(Y)` ≥ Y, each centred at
        // (2i + 1 − GRID)/GRID of a half axis with a radius of 1/GRID of it added to the
        // centre's own. X and Y' are doubles and GRID a power of two, so the radii are exact
        // doubles, which `mag_set_d` does not round down.
        let (x, y) = (self.x.to_f64(), self.y.to_f64());
        let (mid, delta) = (mid.clone(), delta.clone());
        let steps = GRID as i64;
        // From the outside in, the cells farthest from the real axis first: where the
        // integrand has a singularity in the rectangle, they are the likeliest to meet it,
        // and the first cell without an enclosure ends the bound.
        let outside_in = move |k: i64| if k % 2 == 0 { k / 2 } else { steps - 1 - k / 2 };
        (0..steps)
            .flat_map(move |j| (0..steps).map(move |i| (outside_in(i), outside_in(j))))
            .map(move |(i, j)| {
                let mut raw = acb_struct::default();
                // SAFETY: initialised, then set; `wrap` takes it over.
                unsafe {
                    acb_init(&mut raw);
                    for (part, half_axis, k) in [(&mut raw.real, x, i), (&mut raw.imag, y, j)] {
                        arb_set_d(part, half_axis);
                        arb_mul_si(part, part, 2 * k + 1 - steps, 128);
                        arb_mul_2exp_si(part, part, -(GRID.trailing_zeros() as i64));
                        arb_add_error_mag(part, &Mag::of(half_axis / GRID as f64).0);
                    }
                }
                Ball::wrap(raw, mid.precision().in_bits()) * &delta + &mid
            })
    }

    /// An upper bound of the error of the n-point rule for an integrand bounded by
    /// `bound` / delta on the ellipse: (64/15)·bound/((ρ − 1)·ρ^(2n−1)) (Arb's bound, from
    /// Trefethen, Approximation Theory and Approximation Practice, Thm 19.3).
    fn error(&self, bound: &Mag, n: u64) -> Mag {
        let (mut t, mut less) = (Mag::new(), Mag::new());
        let mut error = Mag::new();
        // SAFETY: all initialised; the denominator is rounded down, the quotient up.
        unsafe {
            mag_pow_ui_lower(&mut t.0, &self.rho.0, 2 * n - 1);
            mag_one(&mut less.0);
            mag_sub_lower(&mut less.0, &self.rho.0, &less.0);
            mag_mul_lower(&mut t.0, &t.0, &less.0);
            mag_mul_ui_lower(&mut t.0, &t.0, 15);
            mag_div(&mut error.0, &bound.0, &t.0);
            mag_mul_2exp_si(&mut error.0, &error.0, 6);
        }
        error
    }

    /// The least degree of [`degree_at_least`]'s grid, up to `limit`, whose error bound is
    /// below `tolerance`, with that bound.
    fn degree(&self, bound: &Mag, tolerance: &Mag, limit: u64) -> Option<(u64, Mag)> {
        // SAFETY: initialised magnitudes.
        let log2 = |m: &Mag| unsafe { mag_get_d_log2_approx(&m.0) };
        let rho = log2(&self.rho);
        let less = (self.x.to_f64() + (self.x.to_f64().powi(2) - 1.0).sqrt() - 1.0).log2();
        // Solve (64/15)·bound/((ρ − 1)ρ^(2n−1)) = tolerance for n: a start, checked below.
        let estimate = ((64.0f64 / 15.0).log2() + log2(bound) - less - log2(tolerance)) / (2.0 * rho) + 0.5;
        let mut n = degree_at_least(if estimate.is_finite() {
            estimate.max(1.0).ceil() as u64
        } else {
            1
        });
        while n <= limit {
            let error = self.error(bound, n);
            // SAFETY: initialised magnitudes.
            if unsafe { mag_cmp(&error.0, &tolerance.0) } < 0 {
                return Some((n, error));
            }
            n = degree_at_least(n + 1);
        }
        None
    }
}

impl Mag {
    fn to_f64(&self) -> f64 {
        // SAFETY: initialised.
        unsafe { flint_sys::mag::mag_get_d(&self.0) }
    }
}

/// The least degree ≥ n on the grid: every n up to 16, then m·2^k with 8 ≤ m ≤ 15 (steps
/// of 1/15 to 1/8), so that a thread keeps few node tables.
pub(crate) fn degree_at_least(n: u64) -> u64 {
    if n <= 16 {
        return n.max(1);
    }
    let shift = 64 - n.leading_zeros() - 4;
    n.div_ceil(1 << shift) << shift
}

/// The least n² × bits of a node table that is shared between rules where it can be:
/// about 4 ms of Arb's roots (proofs/certified-digits.md, "Shared node tables").
const SHARED_WORK: u64 = 1 << 22;

/// The degree of the table that serves a rule of `n` points at `bits`, at most `limit`:
/// `n` where its table is cheap. Where it is not, a table already held of at most a
/// quarter more points, else the least degree ≥ n on a grid of four steps an octave
/// (m·2^k, 4 ≤ m ≤ 7), so that the rules of one computation share fewer tables: one
/// costs about as many evaluations of P_n as it has points squared, and a rule with more
/// points than it needs costs only the integrand at those points.
pub(crate) fn shared_degree(n: u64, bits: u32, limit: u64) -> u64 {
    if n <= 16 || n * n * u64::from(bits) < SHARED_WORK {
        return n;
    }
    if let Some(held) = legendre::held_degree(n..=(n + n / 4).min(limit), bits) {
        return held;
    }
    let shift = 64 - n.leading_zeros() - 3;
    let coarse = n.div_ceil(1 << shift) << shift;
    if coarse <= limit {
        coarse
    } else {
        n
    }
}

/// How an interval's integral is enclosed.
pub(crate) struct Rule<'a> {
    /// `integrand(x, analytic)` encloses f on x (`analytic`: a complex ball on which f
    /// must be shown holomorphic), `None` where it cannot.
    pub integrand: &'a dyn Fn(&Ball, bool) -> Option<Ball>,
    /// The absolute error each rule may have.
    pub tolerance: &'a mag_struct,
    /// The most points a rule may take.
    pub degree_limit: u64,
    /// Arb's adaptive bisection on an interval left over.
    pub otherwise: &'a dyn Fn(&Ball, &Ball) -> Ball,
}

impl Rule<'_> {
    /// The integral over [start, end]: one Gauss–Legendre rule where its error bound on an
    /// ellipse (X = 2 and wider; else X = 3/2, or from 256 bits the cells) meets the
    /// tolerance; else the sum over the two halves, down to `depth` halvings; else Arb's
    /// bisection.
    pub(crate) fn integrate(&self, start: &Ball, end: &Ball, depth: u32) -> Ball {
        let mut served = [Served::default(); OWN_DEPTH as usize + 1];
        self.integrate_parts(start, end, depth.min(OWN_DEPTH), &mut served)
    }

    /// [`Self::integrate`] with `served[depth]` the bound that served the last part at
    /// each depth.
    fn integrate_parts(&self, start: &Ball, end: &Ball, depth: u32, served: &mut [Served]) -> Ball {
        let last = &mut served[depth as usize];
        let from = match *last {
            Served::Neither | Served::NeitherTwice if depth == 0 => Served::FirstEllipse,
            from => from,
        };
        if from != Served::NeitherTwice {
            let (value, now) = self.one_rule(start, end, from);
            *last = match (now, *last) {
                (Served::Neither, Served::Neither | Served::NeitherTwice) => Served::NeitherTwice,
                (now, _) => now,
            };
            if let Some(value) = value {
                return value;
            }
        }
        if depth == 0 {
            return (self.otherwise)(start, end);
        }
        let middle = (start.clone() + end).times_power_of_two(-1);
        let first = self.integrate_parts(start, &middle, depth - 1, served);
        if !first.is_finite() {
            // The piece has no finite enclosure; the other half cannot change that.
            return first;
        }
        first + self.integrate_parts(&middle, end, depth - 1, served)
    }

    /// One rule over [start, end] at the fewest points the bound allows, trying the
    /// bounds `from` names ([`Served`]), or `None`; and which bound served (`Neither`
    /// where none did).
    fn one_rule(&self, start: &Ball, end: &Ball, from: Served) -> (Option<Ball>, Served) {
        let mut served = Served::FirstEllipse;
        let value = self.one_rule_from(start, end, from, &mut served);
        (value, served)
    }

    /// [`Self::one_rule`], noting in `served` which bound served. One function because its
    /// steps share the piece's centre, half length and tolerance and decide in turn: the
    /// degree the X = 2 box allows, wider ellipses while they lower it, the fallback bounds
    /// where it gives none, then the rule's sum with the bound's error added.
    fn one_rule_from(&self, start: &Ball, end: &Ball, from: Served, served: &mut Served) -> Option<Ball> {
        let bits = start.precision().in_bits();
        let delta = (end.clone() - start).times_power_of_two(-1);
        let mid = (end.clone() + start).times_power_of_two(-1);
        let mut tolerance = Mag::new();
        // SAFETY: initialised.
        unsafe { mag_set(&mut tolerance.0, self.tolerance) };
        // A bound of |f| over `boxes` (which hold the ellipse), times the half length.
        let bound_over = |boxes: &mut dyn Iterator<Item = Ball>| -> Option<Mag> {
            let (mut bound, mut part, mut half) = (Mag::new(), Mag::new(), Mag::new());
            for cell in boxes {
                let value = (self.integrand)(&cell, true)?;
                // SAFETY: initialised.
                unsafe {
                    flint_sys::acb::acb_get_mag(&mut part.0, value.as_raw());
                    flint_sys::mag::mag_max(&mut bound.0, &bound.0, &part.0);
                }
            }
            // SAFETY: initialised.
            unsafe {
                flint_sys::acb::acb_get_mag(&mut half.0, delta.as_raw());
                mag_mul(&mut bound.0, &bound.0, &half.0);
                (mag_is_finite(&bound.0) != 0).then_some(bound)
            }
        };
        // The degree the bound on one box over the ellipse allows.
        let rule_on = |half_axis: f64| -> Option<(u64, Mag)> {
            let ellipse = Ellipse::new(half_axis);
            let bound = bound_over(&mut std::iter::once(ellipse.around(&mid, &delta)))?;
            ellipse.degree(&bound, &tolerance, self.degree_limit)
        };
        // Where one box is too loose, the first ellipse bounded on a grid of cells.
        let on_cells = || -> Option<(u64, Mag)> {
            let ellipse = Ellipse::new(ELLIPSES[0]);
            let bound = bound_over(&mut ellipse.cells(&mid, &delta))?;
            ellipse.degree(&bound, &tolerance, self.degree_limit)
        };
        // Where one box over the X = 2 rectangle gives no degree: the cells from 256 bits,
        // below them the narrower ellipse (neither is widened: a wider ellipse's box holds
        // the X = 2 one).
        let mut fallback = || {
            *served = Served::Neither;
            let found = if bits >= GRID_FROM_BITS {
                on_cells()
            } else {
                rule_on(NARROW_ELLIPSE)
            }?;
            *served = Served::Fallback;
            Some(found)
        };
        let first = match from {
            Served::Fallback => None,
            Served::FirstEllipse | Served::Neither | Served::NeitherTwice => rule_on(ELLIPSES[0]),
        };
        let (n, error) = match first {
            Some(mut best) => {
                // Wider ellipses from 32 points up, while they fit and lower the degree.
                for half_axis in &ELLIPSES[1..] {
                    if best.0 < LEAST_DEGREE_TO_WIDEN {
                        break;
                    }
                    match rule_on(*half_axis) {
                        Some(found) if found.0 < best.0 => best = found,
                        _ => break,
                    }
                }
                best
            }
            // After a failure at this depth, only the X = 2 box is tried.
            None if from == Served::Neither => {
                *served = Served::Neither;
                return None;
            }
            None => fallback()?,
        };
        // A degree above the least keeps its error bound below `error` (the bound falls
        // with n), so a table shared with other pieces serves as well.
        let n = shared_degree(n, bits, self.degree_limit);
        let table = nodes(n, bits)?;
        let mut sum = start.int(0);
        for k in 0..n as usize {
            let (node, weight) = &table.nodes[k.min(n as usize - 1 - k)];
            let offset = delta.clone() * node;
            let x = if 2 * k < n as usize {
                mid.clone() + &offset
            } else {
                mid.clone() - &offset
            };
            sum += (self.integrand)(&x, false)? * weight;
        }
        let mut value = sum * &delta;
        if !value.is_real() {
            return None;
        }
        // The integrand is real on the real interval, so the integral is real, and the
        // rule's error is at most `error` in absolute value.
        // SAFETY: `value` is an initialised real ball; only its radius grows.
        unsafe { arb_add_error_mag(value.real_mut(), &error.0) };
        Some(value)
    }
}

#[cfg(test)]
mod tests {
    use std::cell::Cell;

    use rug::float::Constant;
    use rug::Float;

    use super::*;
    use crate::real::Precision;

    const BITS: u32 = 128;

    fn int(n: i64) -> Ball {
        Ball::from_i64(n, Precision::bits(BITS))
    }

    /// 2^−bits, as an Arb magnitude.
    fn tolerance(bits: i64) -> Mag {
        let mut m = Mag::new();
        // SAFETY: initialised.
        unsafe {
            mag_one(&mut m.0);
            mag_mul_2exp_si(&mut m.0, &m.0, -bits);
        }
        m
    }

    /// The integral of `f` over [a, b] at a tolerance of 2^−100, with how often the rule
    /// handed an interval to `otherwise` (which answers a ball that holds everything).
    fn integral(f: &dyn Fn(&Ball) -> Ball, a: i64, b: i64) -> (Ball, u32) {
        integral_handing(f, a, b, &Ball::indeterminate)
    }

    /// [`integral`] with `otherwise` answering `stand_in(start)` for an interval.
    fn integral_handing(f: &dyn Fn(&Ball) -> Ball, a: i64, b: i64, stand_in: &dyn Fn(&Ball) -> Ball) -> (Ball, u32) {
        let handed = Cell::new(0);
        let otherwise = |start: &Ball, _: &Ball| {
            handed.set(handed.get() + 1);
            stand_in(start)
        };
        let tolerance = tolerance(100);
        let rule = Rule {
            integrand: &|x: &Ball, _| Some(f(x)),
            tolerance: &tolerance.0,
            degree_limit: 124,
            otherwise: &otherwise,
        };
        let value = rule.integrate(&int(a), &int(b), OWN_DEPTH);
        (value, handed.get())
    }

    fn assert_encloses(value: &Ball, exact: &Float, radius_below: f64) {
        assert!(value.contains(exact), "{value:?} does not hold {exact}");
        assert!(value.relative_radius() < radius_below, "{value:?} is too wide");
    }

    #[test]
    fn the_cells_cover_the_rectangle_of_the_ellipse() {
        // Points of [−X, X] × [−Y, Y] (Y rounded up as a double), the edges and corners
        // included, mapped onto [1, 4]: each lies in one of the cells.
        let (mid, delta) = (int(5).times_power_of_two(-1), int(3).times_power_of_two(-1));
        for half_axis in ELLIPSES {
            let ellipse = Ellipse::new(half_axis);
            let cells: Vec<Ball> = ellipse.cells(&mid, &delta).collect();
            assert_eq!(cells.len(), (GRID * GRID) as usize);
            let (x, y) = (ellipse.x.to_f64(), ellipse.y.to_f64());
            for i in 0..=20 {
                for j in 0..=20 {
                    let mut raw = acb_struct::default();
                    // SAFETY: initialised, then set exactly; `wrap` takes it over.
                    unsafe {
                        acb_init(&mut raw);
                        arb_set_d(&mut raw.real, x * (f64::from(i) / 10.0 - 1.0));
                        arb_set_d(&mut raw.imag, y * (f64::from(j) / 10.0 - 1.0));
                    }
                    let point = Ball::wrap(raw, BITS) * &delta + &mid;
                    // SAFETY: initialised balls.
                    let inside =
                        |cell: &Ball| unsafe { flint_sys::acb::acb_contains(cell.as_raw(), point.as_raw()) != 0 };
                    assert!(cells.iter().any(inside), "X = {half_axis}: ({i}, {j}) in no cell");
                }
            }
        }
    }

    #[test]
    fn the_narrow_ellipse_and_the_cells_bound_what_one_box_cannot() {
        // f = 1/((x − 1)² + 9/4) on [−½, ½]: its poles 1 ± 3i/2 lie outside the ellipse
        // X = 2, but box arithmetic over its whole rectangle holds a zero of the
        // denominator; over the narrower rectangle (X = 3/2), and over each cell, it does not.
        let boxes = Cell::new(0);
        let f = |x: &Ball| {
            let shifted = x.clone() - &x.int(1);
            x.int(1) / &(shifted.square() + &x.ratio(9, 4))
        };
        let integrand = |x: &Ball, analytic: bool| {
            boxes.set(boxes.get() + u32::from(analytic));
            Some(f(x))
        };
        let otherwise = |start: &Ball, _: &Ball| start.indeterminate();
        let half = |n: i64, bits: u32| Ball::from_i64(n, Precision::bits(bits)).times_power_of_two(-1);
        let rule_at = |bits: u32| {
            let tolerance = tolerance(i64::from(bits) - 20);
            let rule = Rule {
                integrand: &integrand,
                tolerance: &tolerance.0,
                degree_limit: 512,
                otherwise: &otherwise,
            };
            boxes.set(0);
            let (value, served) = rule.one_rule(&half(-1, bits), &half(1, bits), Served::FirstEllipse);
            assert_eq!(served, Served::Fallback);
            (value, boxes.get())
        };
        let whole = Ellipse::new(ELLIPSES[0]).around(&half(0, BITS), &half(1, BITS));
        assert!(!f(&whole).is_finite(), "one box bounds it: the test shows nothing");
        // (2/3)(atan(1) − atan(1/3)) = (2/3)·atan(1/2).
        let exact = Float::with_val(400, 0.5).atan() * 2u32 / 3u32;
        let (narrow, narrow_boxes) = rule_at(128);
        assert_eq!(narrow_boxes, 2, "X = 2, then X = 3/2");
        assert_encloses(&narrow.expect("the narrow ellipse bounds it"), &exact, 1e-30);
        let (cells, cell_boxes) = rule_at(GRID_FROM_BITS);
        assert_eq!(cell_boxes, 1 + GRID * GRID, "X = 2, then the cells");
        assert_encloses(&cells.expect("the cells bound it"), &exact, 1e-70);
    }

    #[test]
    fn parts_at_one_depth_start_from_the_bound_that_served_the_last() {
        // 1/(c² + sin²(8πx)) on [0, 1]: a pole asinh(c)/(8π) off the axis at every
        // multiple of 1/8, so that every part of one length meets the same nearest pole.
        let c = int(1);
        let f = |x: &Ball| x.int(1) / &(c.square() + &(x.pi_like() * x * &x.int(8)).sin().square());
        // Each box's real width, X times the part's length: which ellipse it held.
        let boxes = std::cell::RefCell::new(Vec::new());
        let integrand = |x: &Ball, analytic: bool| {
            if analytic {
                boxes.borrow_mut().push(x.real_span().map_or(f64::NAN, |(a, b)| b - a));
            }
            Some(f(x))
        };
        let otherwise = |start: &Ball, _: &Ball| start.indeterminate();
        let tolerance = tolerance(100);
        let rule = Rule {
            integrand: &integrand,
            tolerance: &tolerance.0,
            degree_limit: 256,
            otherwise: &otherwise,
        };
        let value = rule.integrate(&int(0), &int(1), OWN_DEPTH);
        // ∫ over a period of 1/(c² + sin²t) is π/(c·√(1 + c²)): here 1/√2.
        let exact = Float::with_val(400, 2).sqrt().recip();
        assert_encloses(&value, &exact, 1e-25);
        // At depths 1 to 4 the first part tries X = 2 and then X = 3/2, the second X = 2
        // alone, and both fail; the others there are halved at once. At depth 5 X = 3/2
        // fits: the first part tries X = 2 before it, the 31 after it X = 3/2 alone.
        // 47 boxes; trying every part afresh takes 126.
        let widths = boxes.into_inner();
        let count = |x: f64, depth: i32| {
            let width = x / f64::from(1 << depth);
            widths.iter().filter(|w| (*w / width - 1.0).abs() < 1e-6).count()
        };
        assert_eq!(widths.len(), 47, "{widths:?}");
        assert_eq!((count(2.0, 0), count(NARROW_ELLIPSE, 0)), (1, 1), "{widths:?}");
        for depth in 1..5 {
            assert_eq!((count(2.0, depth), count(NARROW_ELLIPSE, depth)), (2, 1), "{widths:?}");
        }
        assert_eq!((count(2.0, 5), count(NARROW_ELLIPSE, 5)), (1, 32), "{widths:?}");
    }

    #[test]
    fn a_pole_at_one_end_leaves_the_rest_to_the_rule() {
        // 1/(x² + ε²) on [0, 1], ε = 1e−4: the parts next to the pole fail at every depth;
        // the parts after them, farther from it, must still be tried, not halved unseen
        // down to the other rule (here a finite stand-in that counts its calls).
        let epsilon = int(1) / &int(10_000);
        let f = |x: &Ball| x.int(1) / &(x.square() + &epsilon.square());
        let (value, handed) = integral_handing(&f, 0, 1, &|start: &Ball| start.int(0));
        assert!(value.is_finite());
        assert!(handed <= 2, "{handed} parts went to the other rule");
    }

    #[test]
    fn one_rule_encloses_an_integral_with_distant_poles() {
        // ∫₀¹ dx/(1 + x²) = π/4; the poles ±i lie outside the ellipse X = 2 about [0, 1].
        let f = |x: &Ball| x.int(1) / &(x.square() + &x.int(1));
        let (value, handed) = integral(&f, 0, 1);
        let exact = Float::with_val(400, Constant::Pi) / 4u32;
        assert_encloses(&value, &exact, 1e-29);
        assert_eq!(handed, 0);
    }

    #[test]
    fn a_pole_near_the_piece_is_met_by_halving() {
        // ∫₀¹⁰ dx/(x + 3) = ln(13/3): the ellipse about [0, 10] holds the pole at −3, those
        // about its halves do not.
        let f = |x: &Ball| x.int(1) / &(x.clone() + &x.int(3));
        let (value, handed) = integral(&f, 0, 10);
        let exact = (Float::with_val(400, 13) / 3u32).ln();
        assert_encloses(&value, &exact, 1e-29);
        assert_eq!(handed, 0);
    }

    #[test]
    fn an_integrand_never_analytic_goes_to_the_other_rule_in_every_part() {
        // A callback that cannot show f holomorphic on any ellipse: each of the 2^depth
        // parts goes to the other rule, whose answer (not finite here) is returned as is.
        let handed = Cell::new(0);
        let otherwise = |start: &Ball, end: &Ball| {
            handed.set(handed.get() + 1);
            end.clone() - start
        };
        let tolerance = tolerance(100);
        let rule = Rule {
            integrand: &|x: &Ball, analytic: bool| (!analytic).then(|| x.int(1)),
            tolerance: &tolerance.0,
            degree_limit: 124,
            otherwise: &otherwise,
        };
        let value = rule.integrate(&int(0), &int(3), OWN_DEPTH);
        assert_eq!(handed.get(), 1 << OWN_DEPTH);
        assert!(value.contains(&Float::with_val(64, 3)));
    }

    #[test]
    fn a_part_without_enclosure_stops_the_halving() {
        // The first part handed over is not finite: the rest is not integrated.
        let (value, handed) = integral(&|x: &Ball| x.int(1) / x, -1, 1);
        assert!(!value.is_finite());
        assert_eq!(handed, 1);
    }

    #[test]
    fn the_error_bound_is_not_below_the_true_error() {
        // ∫₋₁¹ eˣ dx = e − 1/e at the fewest points the bound allows for 2^−40: the ball,
        // whose radius is that bound, must hold the exact value.
        let tolerance = tolerance(40);
        let otherwise = |start: &Ball, _: &Ball| start.indeterminate();
        let rule = Rule {
            integrand: &|x: &Ball, _| Some(x.exp()),
            tolerance: &tolerance.0,
            degree_limit: 124,
            otherwise: &otherwise,
        };
        let value = rule.integrate(&int(-1), &int(1), 0);
        let e = Float::with_val(400, 1).exp();
        let exact = e.clone() - Float::with_val(400, 1) / e;
        assert!(value.contains(&exact));
        assert!(value.relative_radius() < 1e-11 && value.relative_radius() > 1e-20);
    }

    #[test]
    fn degrees_lie_on_a_grid_of_eight_steps_an_octave() {
        let degrees: Vec<u64> = [1, 8, 9, 13, 16, 17, 20, 21, 33, 90, 97, 1000]
            .map(degree_at_least)
            .to_vec();
        assert_eq!(degrees, [1, 8, 9, 13, 16, 18, 20, 22, 36, 96, 104, 1024]);
        for n in 1..5000 {
            let d = degree_at_least(n);
            assert!(d >= n && (d as f64) <= 1.125 * n as f64 + 1.0);
            assert_eq!(degree_at_least(d), d);
        }
    }

    #[test]
    fn a_costly_table_is_shared_with_rules_of_up_to_a_quarter_fewer_points() {
        // Cheap tables are the degree asked for.
        assert_eq!(shared_degree(100, 64, 1000), 100);
        assert_eq!(shared_degree(16, 4000, 1000), 16);
        // A costly one (200² × 304 bits): the coarse grid's 224 = 7·32, or 200 where the
        // limit is below it. 304 bits and [200, 250] are used by no other test.
        assert_eq!(shared_degree(200, 304, 210), 200);
        assert_eq!(shared_degree(200, 304, 1000), 224);
        let table = nodes(224, 304).expect("the rule");
        // Held now: it serves every rule of 180 to 224 points, not 178 (224 > 178 + 44).
        assert_eq!(shared_degree(180, 304, 1000), 224);
        assert_eq!(shared_degree(178, 304, 1000), 192);
        // And where a lower precision is asked for, rounded from it.
        assert_eq!(shared_degree(190, 256, 1000), 224);
        // The shared rule integrates exactly what the rule of fewer points does: ∫₋₁¹ x^300 dx.
        let zero = table.nodes[0].0.int(0);
        let half = table.nodes.iter().fold(zero, |sum, (x, w)| sum + x.powi(300) * w);
        let sum = half.times_power_of_two(1);
        let exact = Float::with_val(400, 2) / 301u32;
        assert!(sum.contains(&exact) && sum.relative_radius() < 1e-80);
    }
}
