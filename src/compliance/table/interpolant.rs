//! The piecewise-cubic v' of a table, in log–log coordinates (ln v' against ln P, where
//! a power law is a straight line) when every load is positive, else in the load itself.

use super::shape::monotone_tangents;
use crate::quad::gauss_legendre::node_table;
use crate::real::Real;

/// The coordinates a table's cubic pieces are built in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coordinates {
    /// ln v' as a cubic in ln P: power laws exactly, smooth compliances to fourth order
    /// in the logarithmic spacing. Needs loads > 0.
    LogLog,
    /// v' as a cubic in P: for tables that reach loads ≤ 0 (quadratics exactly).
    Linear,
}

impl Coordinates {
    /// Log–log where every load is positive.
    pub fn for_loads(loads: &[f64]) -> Self {
        if loads.iter().all(|&load| load > 0.0) {
            Coordinates::LogLog
        } else {
            Coordinates::Linear
        }
    }

    /// The abscissa of a load.
    pub(super) fn abscissa<R: Real>(self, load: &R) -> R {
        match self {
            Coordinates::LogLog => load.ln(),
            Coordinates::Linear => load.clone(),
        }
    }
}

/// Gauss–Legendre points per stretch of a log–log piece's integral.
const INTEGRAL_POINTS: usize = 16;

/// The width (in ln P plus ln v') of one stretch of that integral: e^x over a stretch
/// this wide is integrated by 16 points far below f64 rounding.
const INTEGRAL_STRETCH: f64 = 0.5;

/// Piece k's node values and tangents, a = m0 − δ, b = m1 − δ (δ the secant), and y at a
/// fraction of the piece ([`Piecewise::cubic_at`]).
struct CubicAt<R> {
    y0: R,
    y1: R,
    m0: R,
    m1: R,
    a: R,
    b: R,
    value: R,
}

/// A monotone cubic Hermite y(x) through the node values (x_i, y_i) with node
/// derivatives m_i ≤ 0, y = ln v' or v', x = ln P or P: v' > 0, non-increasing (v'' ≤ 0)
/// with a continuous v'' between the first and the last load, and nothing outside.
#[derive(Debug)]
pub(super) struct Piecewise {
    pub coordinates: Coordinates,
    /// The loads, strictly increasing.
    pub loads: Vec<f64>,
    x: Vec<f64>,
    y: Vec<f64>,
    m: Vec<f64>,
    /// ∫ v' from the first load to each load.
    cumulative: Vec<f64>,
}

impl Piecewise {
    /// The interpolant of positive, non-increasing node slopes v'(P_i).
    pub fn new(coordinates: Coordinates, loads: Vec<f64>, slopes: &[f64]) -> Self {
        let (x, y): (Vec<f64>, Vec<f64>) = match coordinates {
            Coordinates::LogLog => (
                loads.iter().map(|p| p.ln()).collect(),
                slopes.iter().map(|s| s.ln()).collect(),
            ),
            Coordinates::Linear => (loads.clone(), slopes.to_vec()),
        };
        let m = monotone_tangents(&x, &y);
        let mut piecewise = Piecewise {
            coordinates,
            loads,
            x,
            y,
            m,
            cumulative: Vec::new(),
        };
        piecewise.cumulative = std::iter::once(0.0)
            .chain((0..piecewise.loads.len() - 1).scan(0.0, |sum, k| {
                *sum += piecewise.piece_integral(k, &piecewise.loads[k + 1]);
                Some(*sum)
            }))
            .collect();
        piecewise
    }

    /// [first load, last load].
    pub fn range(&self) -> (f64, f64) {
        (self.loads[0], self.loads[self.loads.len() - 1])
    }

    /// The piece holding `load`, or None outside the table. A load within 4 ulps of an
    /// end (relative to itself) counts as the end: the cycle's loads are computed in
    /// floating point, and v' moves by rounding only over such a step.
    pub fn piece(&self, load: f64) -> Option<usize> {
        let (first, last) = self.range();
        if !(within_end(load, first, -1.0) && within_end(load, last, 1.0)) {
            return None;
        }
        let upper = self.loads.partition_point(|&x| x <= load);
        Some(upper.clamp(1, self.loads.len() - 1) - 1)
    }

    /// Piece k's cubic at its fraction t, h its width in x: the node values and tangents,
    /// a = m0 − δ and b = m1 − δ (δ the secant), and y = y0 + t·(y1 − y0) +
    /// h·t(1 − t)·[(1 − t)a − tb], which its derivatives are formed beside.
    fn cubic_at<R: Real>(&self, k: usize, t: &R, h: &R) -> CubicAt<R> {
        let at = |value: f64| R::from_f64(value, t.precision());
        let (y0, y1, m0, m1) = (at(self.y[k]), at(self.y[k + 1]), at(self.m[k]), at(self.m[k + 1]));
        let delta = (y1.clone() - &y0) / h;
        let (a, b) = (m0.clone() - &delta, m1.clone() - &delta);
        let one_minus = t.int(1) - t;
        let bump = (one_minus.clone() * &a - &(t.clone() * &b)) * t * &one_minus * h;
        let value = y0.clone() + &((y1.clone() - &y0) * t) + &bump;
        CubicAt {
            y0,
            y1,
            m0,
            m1,
            a,
            b,
            value,
        }
    }

    /// y and dy/dx of piece k at its fraction t, h its width in x.
    fn hermite<R: Real>(&self, k: usize, t: &R, h: &R) -> (R, R) {
        let CubicAt {
            y0, y1, m0, m1, value, ..
        } = self.cubic_at(k, t, h);
        // The derivatives of the Hermite basis, the value terms over h.
        let t2 = t.square();
        let d00 = (t2.clone() - t) * &t.int(6);
        let d10 = t2.clone() * &t.int(3) - &(t.clone() * &t.int(4)) + &t.int(1);
        let d11 = t2 * &t.int(3) - &(t.clone() * &t.int(2));
        let derivative = (d00 * &(y0 - &y1)) / h + &(d10 * &m0) + &(d11 * &m1);
        (value, derivative)
    }

    /// The pieces whose formulas `load` needs, first and last: for a number, the piece
    /// holding it; for a ball, every piece whose closed interval its real part meets
    /// (the end pieces continued past the ends). None outside the table.
    ///
    /// A ball's value is the union of those pieces' values. Where the ball stands for
    /// the real loads of an integration piece that ends at a knot, the loads lie in one
    /// knot interval and that interval's formula is among the ones taken: the union
    /// contains the interpolant at every real load of the ball and the analytic
    /// continuation of that one formula at its complex points, which is what a rigorous
    /// quadrature bound on a complex ball needs. A ball's midpoint would pick the formula
    /// by rounding where the ball reaches across the knot.
    fn pieces_at<R: Real>(&self, load: &R) -> Option<(usize, usize)> {
        let Some((lower, upper)) = load.real_span() else {
            let k = self.piece(load.to_f64_lossy())?;
            return Some((k, k));
        };
        let (first, last) = self.range();
        if lower.is_nan() || upper.is_nan() || !within_end(upper, first, -1.0) || !within_end(lower, last, 1.0) {
            return None;
        }
        let pieces = self.loads.len() - 1;
        let lowest = self.loads.partition_point(|&x| x < lower).clamp(1, pieces) - 1;
        let highest = self.loads.partition_point(|&x| x <= upper).clamp(1, pieces) - 1;
        Some((lowest, highest))
    }

    /// `formula(k, h, t)` of every piece k that `load` needs ([`Self::pieces_at`]), h the
    /// piece's width and t the fraction of it at `load`, as one value; NaN outside the
    /// table.
    fn on_pieces<R: Real>(&self, load: &R, formula: impl Fn(usize, &R, &R) -> R) -> R {
        let Some((lowest, highest)) = self.pieces_at(load) else {
            return not_a_number(load);
        };
        let at = |value: f64| R::from_f64(value, load.precision());
        let abscissa = self.coordinates.abscissa(load);
        (lowest..=highest)
            .map(|k| {
                let start = at(self.x[k]);
                let h = at(self.x[k + 1]) - &start;
                let t = (abscissa.clone() - &start) / &h;
                formula(k, &h, &t)
            })
            .reduce(|union, value| union.union(&value))
            .expect("at least one piece")
    }

    /// v' at `load` (NaN outside the table).
    pub fn slope<R: Real>(&self, load: &R) -> R {
        self.on_pieces(load, |k, h, t| {
            let (y, _) = self.hermite(k, t, h);
            match self.coordinates {
                Coordinates::LogLog => y.exp(),
                Coordinates::Linear => y,
            }
        })
    }

    /// v'' at `load` (NaN outside the table). Mathematically ≤ 0 (each piece is
    /// monotone); a rounding-level positive value is returned as 0.
    pub fn curvature<R: Real>(&self, load: &R) -> R {
        let curvature = self.on_pieces(load, |k, h, t| {
            let (y, derivative) = self.hermite(k, t, h);
            match self.coordinates {
                Coordinates::LogLog => derivative * &y.exp() / load,
                Coordinates::Linear => derivative,
            }
        });
        curvature.min_of(&load.int(0))
    }

    /// v'' (`order` 2) or v''' (`order` 3) at `load` (NaN outside the table), with y and its
    /// derivatives in the fraction t in Horner form, so that a ball over part of a piece
    /// gets a range as narrow as the variation there (the node values' cancellations are
    /// done on numbers, not on the ball). v''' jumps at the knots (the interpolant is C¹ in
    /// its coordinates): a ball across a knot gets the union of both sides' values.
    pub fn higher_derivative<R: Real>(&self, order: usize, load: &R) -> R {
        self.on_pieces(load, |k, h, t| {
            let (y, first, second) = self.hermite_in_horner_form(k, t, h);
            match (self.coordinates, order) {
                // v' = e^y with y(ln P): v'' = e^y y'/P, v''' = e^y (y'² + y'' − y')/P².
                (Coordinates::LogLog, 2) => y.exp() * &first / load,
                (Coordinates::LogLog, _) => y.exp() * &(first.square() + &second - &first) / &load.square(),
                (Coordinates::Linear, 2) => first,
                (Coordinates::Linear, _) => second,
            }
        })
    }

    /// y, dy/dx and d²y/dx² of piece k at its fraction t, h its width in x, the derivatives
    /// as polynomials in t whose coefficients are formed from a and b first.
    fn hermite_in_horner_form<R: Real>(&self, k: usize, t: &R, h: &R) -> (R, R, R) {
        let CubicAt { m0, a, b, value, .. } = self.cubic_at(k, t, h);
        // dy/dx = m0 + t·c1 + t²·c2 and d²y/dx² = (c1 + 2t·c2)/h, with c1 = −4a − 2b and
        // c2 = 3(a + b).
        let linear = -(a.clone() * &t.int(4)) - &(b.clone() * &t.int(2));
        let quadratic = (a + &b) * &t.int(3);
        let first = m0 + &(t.clone() * &(linear.clone() + &(t.clone() * &quadratic)));
        let second = (linear + &(t.clone() * &(quadratic * &t.int(2)))) / h;
        (value, first, second)
    }

    /// The knots strictly between `low` and `high`.
    pub fn knots_between(&self, low: f64, high: f64) -> impl Iterator<Item = f64> + '_ {
        self.loads
            .iter()
            .copied()
            .filter(move |&load| low < load && load < high)
    }

    /// ∫ v' from the first load to `load` (NaN outside the table).
    pub fn integral<R: Real>(&self, load: &R) -> R {
        let Some(k) = self.piece(load.to_f64_lossy()) else {
            return not_a_number(load);
        };
        R::from_f64(self.cumulative[k], load.precision()) + &self.piece_integral(k, load)
    }

    /// ∫ v' over piece k from its start to `load`.
    fn piece_integral<R: Real>(&self, k: usize, load: &R) -> R {
        let at = |value: f64| R::from_f64(value, load.precision());
        let start = at(self.x[k]);
        let h = at(self.x[k + 1]) - &start;
        let x = self.coordinates.abscissa(load);
        match self.coordinates {
            Coordinates::Linear => {
                // The Hermite basis integrated from 0 to t, times h.
                let t = (x - &start) / &h;
                let (y0, y1, m0, m1) = (at(self.y[k]), at(self.y[k + 1]), at(self.m[k]), at(self.m[k + 1]));
                let (t2, t3) = (t.square(), t.square() * &t);
                let t4 = t2.square();
                let half = t.ratio(1, 2);
                let part = y0 * &(t.clone() - &t3 + &(t4.clone() * &half))
                    + &(y1 * &(t3.clone() - &(t4.clone() * &half)))
                    + &(h.clone()
                        * &(m0 * &(t2 * &half - &(t3.clone() * &t.ratio(2, 3)) + &(t4.clone() * &t.ratio(1, 4)))
                            + &(m1 * &(t4 * &t.ratio(1, 4) - &(t3 * &t.ratio(1, 3))))));
                part * &h
            }
            Coordinates::LogLog => {
                // ∫ e^{y(x) + x} dx; y is monotone on the piece, so the exponent varies by at
                // most the width plus |y1 − y0|, split into stretches of INTEGRAL_STRETCH.
                let span = (x.to_f64_lossy() - self.x[k]).abs() + (self.y[k + 1] - self.y[k]).abs();
                let stretches = (span / INTEGRAL_STRETCH).ceil().max(1.0) as i64;
                let rule = node_table::<R>(INTEGRAL_POINTS, load.precision());
                let step = (x - &start) / &load.int(stretches);
                (0..stretches)
                    .map(|j| {
                        let a = start.clone() + &(step.clone() * &load.int(j));
                        let b = a.clone() + &step;
                        rule.integrate(
                            |point| {
                                let (y, _) = self.hermite(k, &((point.clone() - &start) / &h), &h);
                                (y + point).exp()
                            },
                            &a,
                            &b,
                        )
                    })
                    .fold(load.int(0), |sum, part| sum + &part)
            }
        }
    }
}

/// Whether `load` is on the table's side of `end` (`side` −1 for the first load, +1 for
/// the last), allowing 4 ulps of the load.
fn within_end(load: f64, end: f64, side: f64) -> bool {
    let excess = (load - end) * side;
    excess <= 4.0 * f64::EPSILON * load.abs()
}

fn not_a_number<R: Real>(like: &R) -> R {
    like.int(0) / &like.int(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_power_law_is_a_straight_line_in_log_log() {
        let loads: Vec<f64> = (0..6).map(|i| 0.1 * 3f64.powi(i)).collect();
        let slopes: Vec<f64> = loads.iter().map(|p| 2.0 * p.powf(-0.4)).collect();
        let piecewise = Piecewise::new(Coordinates::LogLog, loads.clone(), &slopes);
        for load in [0.1f64, 0.13, 0.77, 5.0, 24.3] {
            let exact_slope = 2.0 * load.powf(-0.4);
            let exact_curvature = -0.8 * load.powf(-1.4);
            let exact_integral = 2.0 / 0.6 * (load.powf(0.6) - 0.1f64.powf(0.6));
            assert!((piecewise.slope(&load) - exact_slope).abs() <= 1e-14 * exact_slope);
            assert!((piecewise.curvature(&load) - exact_curvature).abs() <= 1e-13 * exact_curvature.abs());
            assert!((piecewise.integral(&load) - exact_integral).abs() <= 1e-14 * exact_integral);
        }
    }

    #[cfg(feature = "certified")]
    #[test]
    fn a_ball_across_a_knot_takes_the_formulas_of_both_pieces() {
        use crate::ball::Ball;
        use crate::real::Precision;
        let loads = vec![1.0, 2.0, 3.0, 4.0, 5.0];
        let slopes: Vec<f64> = loads.iter().map(|p| 1.0 / p).collect();
        let piecewise = Piecewise::new(Coordinates::Linear, loads, &slopes);
        let ball = |x: f64| Ball::from_f64(x, Precision::bits(128));
        // A number at a knot is in the piece that starts there, as always.
        assert_eq!(piecewise.pieces_at(&2.0f64), Some((1, 1)));
        assert_eq!(piecewise.pieces_at(&ball(2.5)), Some((1, 1)));
        // A ball at the knot, or across it, needs both formulas; one past the last load
        // by its radius continues the last piece.
        assert_eq!(piecewise.pieces_at(&ball(2.0)), Some((0, 1)));
        let across = ball(1.999).union(&ball(2.001));
        assert_eq!(piecewise.pieces_at(&across), Some((0, 1)));
        assert_eq!(piecewise.pieces_at(&ball(4.999).union(&ball(5.001))), Some((3, 3)));
        assert_eq!(piecewise.pieces_at(&ball(5.5).union(&ball(6.0))), None);
        // The union holds the interpolant on both sides of the knot.
        let slope = piecewise.slope(&across);
        for x in [1.999, 1.9995, 2.0, 2.0005, 2.001] {
            assert!(slope.contains(&rug::Float::with_val(53, piecewise.slope(&x))), "{x}");
        }
    }

    #[test]
    fn loads_beyond_the_ends_are_not_interpolated() {
        let loads = vec![1e-2, 1.0, 1e4, 1e8, 1e12];
        let slopes: Vec<f64> = loads.iter().map(|p: &f64| p.powf(-0.5)).collect();
        let piecewise = Piecewise::new(Coordinates::LogLog, loads, &slopes);
        assert!(piecewise.slope(&5e-3).is_nan());
        assert!(piecewise.slope(&(1e-2 * (1.0 - 1e-13))).is_nan());
        assert!(piecewise.slope(&(1e12 * (1.0 + 1e-13))).is_nan());
        assert!(piecewise.slope(&(1e-2 * (1.0 - f64::EPSILON))).is_finite());
        assert!(piecewise.slope(&1e12).is_finite());
    }
}
