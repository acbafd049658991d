//! Where digits are decided: the one precision ladder, which every quantity whose digits
//! are proven or checked (W and its segments, I(ρ, φ), the coefficients Iₙ, a partial sum
//! W_N) climbs, and its rungs — `enclosure` (feature `certified`: W as rigorous
//! enclosures in f64 intervals and Arb balls) and [`agreement`] (two working precisions
//! agreeing, where no enclosure reaches).
//!
//! As an optimizer's executor owns its loop and a solver does one step, [`Ladder::climb`]
//! owns the loop over working precisions and the deadline, and a rung computes the quantity
//! at one precision and says how that went ([`Rung`]): reached, short of the digits (a
//! higher precision may settle them), or failed for good. The ladder stops for one reason
//! ([`Stop`]); each caller turns it into its own error with what it knows of the digits.

pub mod agreement;
#[cfg(feature = "certified")]
pub mod enclosure;

use std::time::{Duration, Instant};

use crate::real::Precision;

/// What one attempt at one working precision gave.
#[derive(Debug)]
pub enum Rung<T, E> {
    /// The digits asked for are settled: the ladder stops here.
    Reached(T),
    /// Not yet settled, for the reason `E`; a higher precision may settle them.
    Short(E),
    /// Failed in a way no precision changes: the ladder stops.
    Final(E),
}

/// Why the ladder stopped without a result.
#[derive(Debug, PartialEq)]
pub enum Stop<E> {
    /// The deadline came (or the next attempt was foreseen to end past it) before the digits
    /// were settled.
    OutOfTime {
        /// The time since the climb began.
        seconds: f64,
        /// The working precision of the last attempt made (`None`: none was).
        last_attempt: Option<Precision>,
        /// Why that attempt fell short.
        last: Option<E>,
    },
    /// A rung failed for good.
    Final(E),
    /// The highest precision allowed fell short too, for this reason.
    Exhausted(E),
}

/// The precisions tried and the time allowed.
#[derive(Clone, Copy, Debug)]
pub struct Ladder {
    /// The first working precision.
    pub start: Precision,
    /// No attempt starts at or past it.
    pub deadline: Option<Instant>,
    /// The highest working precision tried: the ladder stops where the next would exceed it.
    pub most: Precision,
    /// How much longer than the last the next attempt is expected to take; an attempt
    /// foreseen to end past the deadline is not started (`None`: every attempt before the
    /// deadline is started).
    pub cost_growth: Option<u32>,
    /// The expected cost of the first attempt, where a probe foretold it.
    pub first_cost: Duration,
}

impl Ladder {
    /// A ladder from `start` to `most`, with no deadline and no forecast.
    pub fn new(start: Precision, most: Precision) -> Ladder {
        Ladder {
            start,
            deadline: None,
            most,
            cost_growth: None,
            first_cost: Duration::ZERO,
        }
    }

    /// The same ladder with a deadline.
    pub fn until(self, deadline: Option<Instant>) -> Ladder {
        Ladder { deadline, ..self }
    }

    /// The same ladder, foreseeing each attempt to cost `growth` times the last and the
    /// first `first_cost`.
    pub fn foreseeing(self, growth: u32, first_cost: Duration) -> Ladder {
        Ladder {
            cost_growth: Some(growth),
            first_cost,
            ..self
        }
    }

    /// Runs `rung` at the start precision, then at `next(precision, &short)` after each
    /// attempt that fell short, until one reaches the digits, one fails for good, the
    /// deadline comes, or the next precision would exceed the highest or not rise.
    pub fn climb<T, E>(
        &self,
        mut rung: impl FnMut(Precision) -> Rung<T, E>,
        mut next: impl FnMut(Precision, &E) -> Precision,
    ) -> Result<(T, Precision), Stop<E>> {
        let started = Instant::now();
        let mut precision = self.start;
        let mut last: Option<(Precision, E)> = None;
        let mut next_cost = self.first_cost;
        loop {
            if self
                .deadline
                .is_some_and(|deadline| Instant::now() + next_cost >= deadline)
            {
                let (last_attempt, last) = match last {
                    Some((precision, short)) => (Some(precision), Some(short)),
                    None => (None, None),
                };
                return Err(Stop::OutOfTime {
                    seconds: started.elapsed().as_secs_f64(),
                    last_attempt,
                    last,
                });
            }
            let attempt_started = Instant::now();
            let short = match rung(precision) {
                Rung::Reached(value) => return Ok((value, precision)),
                Rung::Final(error) => return Err(Stop::Final(error)),
                Rung::Short(short) => short,
            };
            if let Some(growth) = self.cost_growth {
                next_cost = attempt_started.elapsed() * growth;
            }
            let raised = next(precision, &short);
            if raised.in_bits() > self.most.in_bits() || raised.in_bits() <= precision.in_bits() {
                return Err(Stop::Exhausted(short));
            }
            last = Some((precision, short));
            precision = raised;
        }
    }
}

/// Twice the bits: the schedule of the enclosures, whose cost is about quadratic in them.
pub fn doubled<E>(precision: Precision, _: &E) -> Precision {
    Precision::bits(precision.in_bits().saturating_mul(2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ladder_climbs_until_a_rung_reaches_and_says_at_which_precision() {
        let ladder = Ladder::new(Precision::bits(64), Precision::bits(1024));
        let mut tried = vec![];
        let reached = ladder.climb(
            |p| {
                tried.push(p.in_bits());
                match p.in_bits() {
                    256 => Rung::Reached("settled"),
                    _ => Rung::Short(p.in_bits()),
                }
            },
            doubled,
        );
        assert_eq!(reached, Ok(("settled", Precision::bits(256))));
        assert_eq!(tried, [64, 128, 256]);
    }

    #[test]
    fn the_ladder_stops_for_one_reason() {
        let ladder = Ladder::new(Precision::bits(64), Precision::bits(256));
        // Short at every precision: the last one's reason, after the highest.
        let exhausted = ladder.climb(|p| Rung::<(), u32>::Short(p.in_bits()), doubled);
        assert_eq!(exhausted, Err(Stop::Exhausted(256)));
        // A final failure stops at once.
        let mut attempts = 0;
        let failed = ladder.climb(
            |_| {
                attempts += 1;
                Rung::<(), &str>::Final("outside the theory")
            },
            doubled,
        );
        assert_eq!((failed, attempts), (Err(Stop::Final("outside the theory")), 1));
        // A deadline already past: no attempt, and no last reason.
        let past = Instant::now();
        let out = ladder.until(Some(past)).climb(|_| Rung::<(), u32>::Short(0), doubled);
        assert!(matches!(
            out,
            Err(Stop::OutOfTime {
                last_attempt: None,
                last: None,
                ..
            })
        ));
        // A first attempt foreseen to end past the deadline is not started either.
        let soon = Some(Instant::now() + Duration::from_secs(60));
        let foreseen = ladder
            .until(soon)
            .foreseeing(4, Duration::from_secs(3600))
            .climb(|_| Rung::<(), u32>::Short(0), doubled);
        assert!(matches!(foreseen, Err(Stop::OutOfTime { last_attempt: None, .. })));
    }
}
