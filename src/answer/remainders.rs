//! A case's proven remainders, as `microslip series` and Python's `series` give them: the
//! bound on |W − W_N| beside each partial sum, where W ≥ W_N is proven, the W the series
//! alone proves, and the largest P1 at which the cubic law is proven within a ratio of W
//! (proofs/cubic-law-remainder.md).

use super::series_error::ExactAnswerError;
use super::{Answer, Arithmetic, Provenance, Value};
use crate::case::{Case, CaseText};
use crate::digits::enclosure::series::case_balls;
use crate::exact::remainder::{largest_amplitude, sums_and_remainders_with, Within};
use crate::exact::{Remainder, SeriesShape};
use crate::real::{Precision, Real};

/// The working precision of the remainders: they are bounds, read to a few digits.
pub const REMAINDER_BITS: u32 = 128;
/// Significant digits of W from the series at most.
const SERIES_DIGITS: u32 = 15;
/// The orders of the series `--within` reads the lower bound on |W| from.
const WITHIN_ORDER: usize = 3;

/// The remainders of a case's partial sums and what they prove.
#[derive(Clone, Debug)]
pub struct CaseRemainders {
    /// Index N − 1: a double at or above the proven bound on |W − W_N|.
    pub bounds: Vec<f64>,
    /// Index N − 1: whether W ≥ W_N is proven (as for a completely monotone v' at even N),
    /// so that W lies in [W_N, W_N + bound].
    pub from_below: Vec<bool>,
    /// W enclosed by the narrowest W_N + [least, greatest] of its remainder: the series
    /// alone proves it.
    pub series_w: Answer,
    /// With a ratio R: the largest P1 found at which |W − W₁| ≤ R·|W| is proven.
    pub within: Option<Within>,
}

/// The remainders of the case's partial sums to `order`, and with `within` = R the largest
/// P1 (ρ, φ, P0, Q0, f, λ and the compliance kept) at which |W − W₁| ≤ R·|W| is proven.
pub fn case_remainders(case: &CaseText, order: usize, within: Option<f64>) -> Result<CaseRemainders, ExactAnswerError> {
    let Case { cycle, compliance } = case_balls(&case.spec()?, Precision::bits(REMAINDER_BITS))?;
    // One shape serves the sums, their remainders and `within`'s search.
    let needed = if within.is_some() {
        order.max(WITHIN_ORDER)
    } else {
        order
    };
    let shape = SeriesShape::of_cycle(&cycle, needed)?;
    let (sums, enclosures) = sums_and_remainders_with(shape.as_ref(), &cycle, compliance.as_ref(), order)?;
    // W lies in every W_N + [least, greatest]: the narrowest.
    let mut narrowest = f64::INFINITY;
    let (mut lower, mut upper) = (sums[0].clone(), sums[0].clone());
    for (sum, remainder) in sums.iter().zip(&enclosures) {
        let (low, high) = (sum.clone() + &remainder.least, sum.clone() + &remainder.greatest);
        let width = high.to_f64_lossy() - low.to_f64_lossy();
        if width < narrowest {
            narrowest = width;
            (lower, upper) = (low, high);
        }
    }
    let bits = REMAINDER_BITS + 64;
    let (low, _) = lower.bounds(bits);
    let (_, high) = upper.bounds(bits);
    let series_w = Answer {
        value: Value::within(&low, &high, SERIES_DIGITS),
        segments: None,
        digits_requested: None,
        provenance: Provenance::Certified {
            bits: REMAINDER_BITS,
            arithmetic: Arithmetic::ArbBalls,
        },
        method: None,
    };
    // With Q1 = 0, W is 0 exactly and `within` has nothing to bound.
    let within = within
        .zip(shape.as_ref())
        .map(|(ratio, shape)| largest_amplitude(shape, &cycle, compliance.as_ref(), ratio));
    Ok(CaseRemainders {
        bounds: enclosures
            .iter()
            .map(|remainder| remainder.bound().real_span().map_or(f64::INFINITY, |span| span.1))
            .collect(),
        from_below: enclosures
            .iter()
            .map(|remainder: &Remainder<_>| remainder.least.real_span().is_some_and(|span| span.0 >= 0.0))
            .collect(),
        series_w,
        within,
    })
}
