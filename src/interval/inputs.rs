//! Exact inputs read into intervals: each value enclosed by the two doubles nearest it
//! (one double where it is one).

use rug::float::{Constant, Round};
use rug::{Float, Rational};

use super::span::Span;
use super::Interval;

/// The most bits with which a multiple of π is formed before its enclosure is taken as
/// it stands.
const MOST_PHASE_BITS: u32 = 1 << 16;

impl Interval {
    /// The MPFR number `x` between the doubles either side of it.
    pub(super) fn enclosing_float(x: &Float) -> Interval {
        if x.is_nan() {
            return Interval::real(Span::INDETERMINATE);
        }
        Interval::new(x.to_f64_round(Round::Down), x.to_f64_round(Round::Up))
    }

    /// The exact integer `n`.
    pub(super) fn enclosing_integer(n: i64) -> Interval {
        let nearest = n as f64;
        if nearest.abs() < 9.0e18 && nearest as i64 == n {
            Interval::real(Span::point(nearest))
        } else {
            Interval::enclosing_float(&Float::with_val(64, n))
        }
    }

    /// The exact rational `x`: an integer that is a double as it is; otherwise MPFR
    /// rounded down and up (to 53 bits and then to the double, in the same direction: the
    /// doubles, subnormals included, are 53-bit numbers, so the double below the 53-bit
    /// number below x is the double below x).
    pub(super) fn enclosing_rational(x: &Rational) -> Interval {
        if *x.denom() == 1 && x.numer().significant_bits() <= f64::MANTISSA_DIGITS {
            return Interval::real(Span::point(x.numer().to_f64()));
        }
        let at = |round: Round| {
            Float::with_val_round(f64::MANTISSA_DIGITS, x, round)
                .0
                .to_f64_round(round)
        };
        Interval::new(at(Round::Down), at(Round::Up))
    }

    /// mπ + x (m, x rational), formed in MPFR with every rounding outward, at enough bits
    /// that the sum is enclosed by adjacent doubles or, where it cancels, at doubling
    /// precisions up to [`MOST_PHASE_BITS`].
    pub(super) fn enclosing_pi_multiple(multiple: &Rational, offset: &Rational) -> Interval {
        if *multiple == 0 {
            return Interval::enclosing_rational(offset);
        }
        let size = (multiple.to_f64().abs() * std::f64::consts::PI + offset.to_f64().abs()).max(1.0);
        let mut bits = size.log2().ceil() as u32 + 128;
        loop {
            let end = |round: Round| {
                // The product's direction is that of the end asked for, flipped for m < 0.
                let pi_round = match (round, *multiple < 0) {
                    (Round::Down, false) | (Round::Up, true) => Round::Down,
                    _ => Round::Up,
                };
                let pi = Float::with_val_round(bits, Constant::Pi, pi_round).0;
                let product = Float::with_val_round(bits, &pi * multiple, round).0;
                Float::with_val_round(bits, &product + offset, round).0
            };
            let enclosure = Interval::new(
                end(Round::Down).to_f64_round(Round::Down),
                end(Round::Up).to_f64_round(Round::Up),
            );
            let (lo, hi) = enclosure.real_bounds();
            if lo.next_up().next_up() >= hi || bits >= MOST_PHASE_BITS {
                return enclosure;
            }
            bits *= 2;
        }
    }
}
