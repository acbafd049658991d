//! The numerical pieces of a shape-preserving table interpolant: the concave fit of
//! the data, derivatives from local polynomials, and node derivatives limited so that
//! every cubic piece stays monotone.

use std::ops::Range;

use super::read::RawTable;
use super::{TableColumn, TableError, ROUNDING_TOLERANCE};

/// The data made concave: the slopes (or the approach) whose slopes (or secants) are the
/// least-squares non-increasing fit of the data's, and the largest relative change that
/// made beyond the data's rounding. A change beyond `smoothing` is refused, naming the
/// row where the data rise.
pub(super) fn concave_data(raw: &RawTable, smoothing: f64, path: &str) -> Result<(Vec<f64>, f64), TableError> {
    let n = raw.loads.len();
    let h: Vec<f64> = raw.loads.windows(2).map(|w| w[1] - w[0]).collect();
    // The slopes the shape is checked on: v' itself, or the secants of v; and the
    // relative size of their rounding errors.
    let (checked, weights, rounding, name) = match raw.column {
        TableColumn::Slope => (raw.values.clone(), vec![1.0; n], vec![0.0; n], "slope"),
        TableColumn::Approach => {
            let secants: Vec<f64> = (0..n - 1).map(|k| (raw.values[k + 1] - raw.values[k]) / h[k]).collect();
            // A difference of two values carries their rounding relative to the difference.
            let relative = |a: f64, b: f64| (a.abs() + b.abs()) / (b - a);
            let rounding: Vec<f64> = (0..n - 1)
                .map(|k| {
                    8.0 * f64::EPSILON
                        * (relative(raw.values[k], raw.values[k + 1]) + relative(raw.loads[k], raw.loads[k + 1]))
                })
                .collect();
            (secants, h.clone(), rounding, "secant slope of the approach")
        }
    };
    let fitted = non_increasing_fit(&checked, &weights);
    let tolerance = smoothing.max(ROUNDING_TOLERANCE);
    let mut residual: f64 = 0.0;
    for (k, (&data, &fit)) in checked.iter().zip(&fitted).enumerate() {
        let relative = (data - fit).abs() / data.abs();
        if relative > tolerance.max(rounding[k]) {
            // The rise nearest the value the fit moved most: where the fit had to pool.
            let rise = (1..checked.len())
                .filter(|&j| checked[j] > checked[j - 1])
                .min_by_key(|&j| j.abs_diff(k))
                .unwrap_or(k.max(1));
            // A rise of the slopes at row j; of the secants, at the row between secants j − 1 and j.
            let problem = format!(
                "the {name} rises from {:.4e} to {:.4e}: the data are not concave (v'' ≤ 0) here; the nearest concave fit moves them by {relative:.1e} relative, beyond the smoothing tolerance {tolerance:.0e} (raise smoothing= to fit noisy data)",
                checked[rise - 1],
                checked[rise]
            );
            return Err(raw.row_error(path, rise, problem));
        }
        if relative > rounding[k] {
            residual = residual.max(relative);
        }
    }
    let values = match raw.column {
        TableColumn::Slope => fitted,
        // The approach whose secants are the fitted ones, from the first row on.
        TableColumn::Approach => std::iter::once(raw.values[0])
            .chain((0..n - 1).scan(raw.values[0], |v, k| {
                *v += fitted[k] * h[k];
                Some(*v)
            }))
            .collect(),
    };
    Ok((values, residual))
}

/// Weighted least-squares fit of a non-increasing sequence (pool adjacent violators).
fn non_increasing_fit(values: &[f64], weights: &[f64]) -> Vec<f64> {
    // Blocks of (mean, weight, count), merged while a later block rises above an earlier one.
    let mut blocks: Vec<(f64, f64, usize)> = Vec::new();
    for (&value, &weight) in values.iter().zip(weights) {
        blocks.push((value, weight, 1));
        while blocks.len() > 1 {
            let (last, before) = (blocks[blocks.len() - 1], blocks[blocks.len() - 2]);
            if last.0 <= before.0 {
                break;
            }
            let weight = last.1 + before.1;
            let merged = (
                (last.0 * last.1 + before.0 * before.1) / weight,
                weight,
                last.2 + before.2,
            );
            blocks.pop();
            *blocks.last_mut().expect("two blocks") = merged;
        }
    }
    blocks
        .iter()
        .flat_map(|&(mean, _, count)| std::iter::repeat_n(mean, count))
        .collect()
}

/// The derivative at `x[i]` of the polynomial through the points of `stencil` (which holds i).
pub(super) fn stencil_derivative(x: &[f64], y: &[f64], i: usize, stencil: Range<usize>) -> f64 {
    let mut derivative = 0.0;
    for j in stencil.clone() {
        let weight = if j == i {
            stencil.clone().filter(|&k| k != i).map(|k| 1.0 / (x[i] - x[k])).sum()
        } else {
            let numerator: f64 = stencil
                .clone()
                .filter(|&k| k != i && k != j)
                .map(|k| x[i] - x[k])
                .product();
            let denominator: f64 = stencil.clone().filter(|&k| k != j).map(|k| x[j] - x[k]).product();
            numerator / denominator
        };
        derivative += weight * y[j];
    }
    derivative
}

/// The `points` consecutive indices of `0..n` most nearly centred on `i` (points ≤ n).
pub(super) fn centred_stencil(i: usize, points: usize, n: usize) -> Range<usize> {
    let start = i.saturating_sub(points / 2).min(n - points);
    start..start + points
}

/// Node derivatives of a non-increasing cubic Hermite through (x, y): the derivative of
/// the five-point polynomial (fourth order; three points for four rows), limited to
/// [−3 min(|δ_{i−1}|, |δ_i|), 0] (δ the secants), which keeps each piece monotone
/// (Fritsch and Carlson) and changes nothing where the data are smooth and monotone.
pub(super) fn monotone_tangents(x: &[f64], y: &[f64]) -> Vec<f64> {
    let n = x.len();
    let delta: Vec<f64> = (0..n - 1).map(|k| (y[k + 1] - y[k]) / (x[k + 1] - x[k])).collect();
    let points = n.min(5);
    (0..n)
        .map(|i| {
            let raw = stencil_derivative(x, y, i, centred_stencil(i, points, n));
            let before = if i == 0 { f64::INFINITY } else { delta[i - 1].abs() };
            let after = if i == n - 1 { f64::INFINITY } else { delta[i].abs() };
            // v' does not increase: a node derivative is ≤ 0 and within the Hermite bound.
            let limit = 3.0 * before.min(after);
            if raw.is_finite() {
                raw.min(0.0).max(-limit)
            } else {
                0.0
            }
        })
        .collect()
}

/// The slopes v'(P_i) of concave approach data v at the loads P (in `x`, the coordinate
/// the data are smoothest in, with `to_slope` turning a derivative there into v'): the
/// derivative of the highest-order local polynomial (seven, five points) that lies
/// between the neighbouring secants of v — where a concave v puts v'(P_i), and which
/// keeps the node slopes non-increasing — else the three-point parabola's in the load
/// (second order, always between them, or at the last row no less than half the last
/// secant).
pub(super) fn approach_node_slopes(
    loads: &[f64],
    approach: &[f64],
    secants: &[f64],
    x: &[f64],
    y: &[f64],
    to_slope: impl Fn(usize, f64) -> f64,
) -> Vec<f64> {
    let n = loads.len();
    (0..n)
        .map(|i| {
            let above = if i == 0 { f64::INFINITY } else { secants[i - 1] };
            let below = if i == n - 1 { 0.0 } else { secants[i] };
            let high_order = [7, 5].into_iter().filter(|&points| points <= n).find_map(|points| {
                let slope = to_slope(i, stencil_derivative(x, y, i, centred_stencil(i, points, n)));
                (slope.is_finite() && slope > 0.0 && slope >= below && slope <= above).then_some(slope)
            });
            high_order.unwrap_or_else(|| {
                let parabola = stencil_derivative(loads, approach, i, centred_stencil(i, 3, n));
                parabola.max(secants[secants.len() - 1] / 2.0).min(above)
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn non_increasing_fit_pools_violators() {
        let fit = non_increasing_fit(&[3.0, 1.0, 2.0, 0.5], &[1.0; 4]);
        assert_eq!(fit, vec![3.0, 1.5, 1.5, 0.5]);
        let untouched = non_increasing_fit(&[4.0, 3.0, 2.0], &[1.0, 2.0, 3.0]);
        assert_eq!(untouched, vec![4.0, 3.0, 2.0]);
    }

    #[test]
    fn stencil_derivative_is_exact_for_quartics() {
        let x = [0.3, 0.7, 1.2, 1.4, 2.5];
        let y: Vec<f64> = x.iter().map(|&p: &f64| p.powi(4) - 2.0 * p * p + p).collect();
        for i in 0..5 {
            let expected = 4.0 * x[i].powi(3) - 4.0 * x[i] + 1.0;
            assert!((stencil_derivative(&x, &y, i, 0..5) - expected).abs() < 1e-11);
        }
    }

    #[test]
    fn monotone_tangents_reproduce_a_line() {
        let x = [1.0, 2.0, 4.0, 5.0, 7.0, 7.5];
        let y: Vec<f64> = x.iter().map(|p| 3.0 - 0.5 * p).collect();
        for m in monotone_tangents(&x, &y) {
            assert!((m + 0.5).abs() < 1e-14, "{m}");
        }
    }

    #[test]
    fn monotone_tangents_keep_each_piece_within_the_hermite_bound() {
        // A step: the raw derivatives overshoot, the limited ones stay within 3|δ| and are 0 on the flat.
        let x = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
        let y = [1.0, 1.0, 1.0, 0.0, 0.0, 0.0];
        let m = monotone_tangents(&x, &y);
        assert_eq!(m[0], 0.0);
        assert_eq!(m[1], 0.0);
        assert_eq!(m[2], 0.0);
        assert_eq!(m[3], 0.0);
        assert!(m.iter().all(|d| (-3.0..=0.0).contains(d)));
    }

    #[test]
    fn centred_stencils_stay_inside() {
        assert_eq!(centred_stencil(0, 5, 9), 0..5);
        assert_eq!(centred_stencil(4, 5, 9), 2..7);
        assert_eq!(centred_stencil(8, 5, 9), 4..9);
        assert_eq!(centred_stencil(1, 7, 7), 0..7);
    }
}
