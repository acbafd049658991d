//! Rigorous enclosures of the small-amplitude coefficient I(ρ, φ), the series
//! coefficients Iₙ and a case's partial sums W_N, up the one ladder of Arb precisions (proofs/series.md,
//! proofs/small-amplitude.md).
//!
//! The closed form and the exact trigonometric integrals are generic over [`Real`]; run on
//! Arb balls ([`Ball`]) whose inputs contain the exact decimals and the exact phase, every
//! operation returns a ball that contains the exact result. What can break that is a
//! branch: a comparison of overlapping balls answers `false` and is counted by
//! [`watch`]. The closed form's comparisons only choose between algebraically equal
//! expressions (proofs/small-amplitude.md), so its balls are enclosures whatever they
//! answer; the series' geometry branches on the cycle's shape, so there a doubt raises
//! the precision and, where it persists, no enclosure is given.

use std::time::Instant;

use rug::Float;

use super::{phase_offset, MAX_BITS};
use crate::ball::{watch, Ball};
use crate::case::{Case, CaseSpec, InputError};
use crate::decimal::printing::decimal_interval;
use crate::digits::{doubled, Ladder, Rung, Stop};
use crate::exact::{closed_form_coefficient, series_coefficients, SeriesError};
use crate::phase::ReducedPhase;
use crate::real::{Precision, Real};

/// Why no enclosure narrow enough could be given.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EnclosureError<E> {
    /// The computation itself refused the input.
    #[error(transparent)]
    Input(E),
    /// A comparison of the generic code stayed undecided as the precision rose.
    #[error("at {bits} bits a comparison of the cycle's geometry stays undecided")]
    Undecided {
        /// The last working precision tried.
        bits: u32,
    },
    /// The deadline passed before the enclosures were narrow enough.
    #[error("the enclosure reached only {reached} of the {asked} digits asked within the time budget")]
    OutOfTime {
        /// The digits asked for.
        asked: u32,
        /// The fewest digits any value reached.
        reached: u32,
    },
    /// A value lies beyond MPFR's exponents ([`Ball::is_beyond_mpfr`]), where its digits
    /// are not printed.
    #[error("a value lies beyond 2^(±2^29), outside the exponents printed here")]
    BeyondRange,
    /// The enclosures stayed wider than asked up to [`MAX_BITS`].
    #[error("the enclosure reached only {reached} of the {asked} digits asked at {bits} bits")]
    TooWide {
        /// The digits asked for.
        asked: u32,
        /// The fewest digits any value reached.
        reached: u32,
        /// The last working precision tried.
        bits: u32,
    },
}

/// Values enclosed to the digits asked, and the working precision that gave them.
#[derive(Clone, Debug)]
pub struct Enclosed {
    /// Balls that contain the exact values.
    pub values: Vec<Ball>,
    /// The working precision, in bits.
    pub bits: u32,
}

impl Enclosed {
    /// The `index`th value's real interval, rounded outwards to enough bits for `digits`.
    pub fn bounds(&self, index: usize, digits: u32) -> (Float, Float) {
        interval(&self.values[index], digits)
    }
}

/// The ball's real interval, rounded outwards to enough bits for `digits` and the ball.
fn interval(ball: &Ball, digits: u32) -> (Float, Float) {
    let bits = Precision::decimal_digits(digits)
        .in_bits()
        .max(ball.precision().in_bits())
        + 64;
    ball.bounds(bits)
}

/// The significant digits (at most `digits`) to which every point of the ball rounds,
/// by the one printing rule ([`decimal_interval`]); 0 where not one is determined.
fn digits_of(ball: &Ball, digits: u32) -> u32 {
    if !(ball.is_real() && ball.is_finite()) {
        return 0;
    }
    let (lower, upper) = interval(ball, digits);
    decimal_interval(&lower, &upper, digits).digits()
}

/// `compute` at rising working precisions until every value's ball rounds to `digits`
/// significant digits (the one printing rule). `decided` tells whether a computation's
/// undecided comparisons make its balls untrustworthy (`false` for code whose every
/// branch is an identity); a doubt that persists at two successive precisions is a tie
/// no precision resolves. The deadline is looked at before every attempt.
pub fn enclose<E>(
    digits: u32,
    must_decide: bool,
    deadline: Instant,
    compute: impl Fn(Precision) -> Result<Vec<Ball>, E>,
) -> Result<Enclosed, EnclosureError<E>> {
    let digits = digits.max(1);
    let start = Precision::bits(Precision::decimal_digits(digits).in_bits() + 24);
    let ladder = Ladder::new(start, Precision::bits(MAX_BITS)).until(Some(deadline));
    // Whether the last attempt met a doubt: a second in a row is a tie no precision resolves.
    let mut doubted = false;
    let rung = |precision: Precision| {
        let bits = precision.in_bits();
        let (values, doubts) = watch(|| compute(precision));
        let values = match values {
            Ok(values) => values,
            Err(error) => return Rung::Final(EnclosureError::Input(error)),
        };
        if must_decide && !doubts.none() {
            let undecided = EnclosureError::Undecided { bits };
            return match std::mem::replace(&mut doubted, true) {
                true => Rung::Final(undecided),
                false => Rung::Short(undecided),
            };
        }
        doubted = false;
        if values.iter().any(Ball::is_beyond_mpfr) {
            return Rung::Final(EnclosureError::BeyondRange);
        }
        let reached = values.iter().map(|v| digits_of(v, digits)).min().unwrap_or(digits);
        match reached >= digits {
            true => Rung::Reached(values),
            false => Rung::Short(EnclosureError::TooWide {
                asked: digits,
                reached,
                bits,
            }),
        }
    };
    match ladder.climb(rung, doubled) {
        Ok((values, precision)) => Ok(Enclosed {
            values,
            bits: precision.in_bits(),
        }),
        Err(Stop::Final(error) | Stop::Exhausted(error)) => Err(error),
        Err(Stop::OutOfTime { last, .. }) => Err(EnclosureError::OutOfTime {
            asked: digits,
            reached: match last {
                Some(EnclosureError::TooWide { reached, .. }) => reached,
                _ => 0,
            },
        }),
    }
}

/// A ball that contains the decimal `text` (checked to be a number by the caller).
pub fn decimal_ball(text: &str, precision: Precision) -> Option<Ball> {
    Ball::parse_decimal(text, precision).ok()
}

/// I(ρ, φ) enclosed: the closed form on balls that contain ρ and ψ. (Its comparisons
/// choose between equal expressions; a σ₋ that may be 0 gives a non-finite ball.)
pub fn coefficient_ball(rho: &str, phase: &ReducedPhase, precision: Precision) -> Ball {
    let rho = decimal_ball(rho, precision).expect("ρ is checked to read before");
    let (psi, _) = phase_offset(phase, precision);
    closed_form_coefficient(&rho, &psi)
}

/// I₁ … I_`order` enclosed at a precision (I₀ ≡ 0 is not computed).
pub fn coefficient_balls(
    rho: &str,
    phase: &ReducedPhase,
    order: usize,
    precision: Precision,
) -> Result<Vec<Ball>, SeriesError> {
    let rho = decimal_ball(rho, precision).expect("ρ is checked to read before");
    let (psi, _) = phase_offset(phase, precision);
    let values = series_coefficients(&rho, &psi, order)?;
    Ok(values.into_iter().skip(1).map(|(value, _)| value).collect())
}

/// A case read as balls, its phase as the exact offset ψ from the nearest multiple nπ
/// (with Q0 reversed for odd n: the mirror image, which has the same W).
pub fn case_balls(case: &CaseSpec, precision: Precision) -> Result<Case<Ball>, InputError> {
    let Case { mut cycle, compliance } = case.at::<Ball>(precision)?;
    let (psi, reverses) = phase_offset(case.phase(), precision);
    // `at` reverses Q0 for the mirror image it reads near an odd multiple of π; here it
    // is reversed for every odd n (negating a ball is exact).
    if reverses != case.phase().is_mirror_image() {
        cycle.mean_tangential_load = -cycle.mean_tangential_load;
    }
    cycle.phase = psi;
    Ok(Case { cycle, compliance })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arb::relatively_within;
    use crate::phase::ExactPhase;
    use rug::float::Constant;

    /// ψ = φ − nπ in MPFR at 3000 bits, from the phase's value computed directly.
    fn reference(k: i64, offset: &str) -> (Float, bool) {
        let bits = 3000;
        let pi = Float::with_val(bits, Constant::Pi);
        let phi = pi.clone() * k + Float::with_val(bits, Float::parse(offset).unwrap());
        let n = Float::with_val(bits, &phi / &pi).round();
        let odd = n.to_integer().unwrap().is_odd();
        (phi - n * pi, odd)
    }

    #[test]
    fn the_phase_offset_ball_contains_the_exact_offset() {
        let precision = Precision::bits(200);
        for (text, k, offset) in [
            ("pi-1e-100", 1, "-1e-100"),
            ("3.141592653589793", 0, "3.141592653589793"),
            ("1e50", 0, "1e50"),
            ("-3pi+0.25", -3, "0.25"),
            ("0.3", 0, "0.3"),
        ] {
            let (psi, reverses) = phase_offset(&ExactPhase::parse(text).unwrap().reduce().unwrap(), precision);
            let (expected, odd) = reference(k, offset);
            assert!(psi.contains(&expected), "{text}: {psi:?} vs {expected}");
            assert_eq!(reverses, odd, "{text}");
            assert!(relatively_within(&psi, 190), "{text}: {psi:?}");
        }
        // −π/2 exactly is read as +π/2 from the next multiple: the same cycle, mirrored.
        let (psi, reverses) = phase_offset(&ExactPhase::parse("-pi/2").unwrap().reduce().unwrap(), precision);
        let half_pi = Float::with_val(3000, Constant::Pi) / 2u32;
        assert!(psi.contains(&half_pi) && reverses, "{psi:?}");
    }

    #[test]
    fn a_doubt_that_persists_gives_no_enclosure() {
        let deadline = Instant::now() + std::time::Duration::from_secs(60);
        // A comparison of two overlapping balls at every precision: 1/3·3 against 1.
        let tie = |precision: Precision| -> Result<Vec<Ball>, ()> {
            let one = Ball::from_i64(1, precision);
            let third = one.clone() / &one.int(3) * &one.int(3);
            let _ = third < one;
            Ok(vec![one])
        };
        assert!(matches!(
            enclose(10, true, deadline, tie),
            Err(EnclosureError::Undecided { .. })
        ));
        // Where the branches are identities the doubt does not matter.
        assert_eq!(enclose(10, false, deadline, tie).unwrap().values.len(), 1);
    }
}
