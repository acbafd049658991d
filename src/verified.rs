//! Verified digits: a computation run at two working precisions, its results
//! printed only as far as the two agree (with guard digits), the precision raised
//! until they do or the deadline passes.

use std::time::Instant;

use rug::Float;

use crate::real::Precision;
use crate::reference::{agreeing_digits, GUARD_DIGITS};

/// Values on which two precisions agreed.
#[derive(Clone, Debug)]
pub struct Verified {
    /// The values from the higher of the two precisions.
    pub values: Vec<Float>,
    /// The significant digits on which every value agreed (at least those asked for
    /// plus [`GUARD_DIGITS`]).
    pub agreed: u32,
    /// The higher working precision.
    pub precision: Precision,
}

/// Why verified digits were not obtained.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum VerifyError<E> {
    /// The computation itself failed.
    #[error(transparent)]
    Failed(E),
    /// The deadline passed before enough digits agreed.
    #[error("only {reached} of the {required} significant digits needed ({GUARD_DIGITS} of them guard digits) agreed between two precisions before the time budget ran out")]
    OutOfTime { required: u32, reached: u32 },
}

/// Runs `compute` at a precision p and at p' > p and accepts the results when every
/// value agrees to `digits` + [`GUARD_DIGITS`] significant digits; otherwise raises
/// the precision by the digits that were missing and tries again until `deadline`.
/// `compute` must re-read its inputs at the precision it is given. A value that is
/// exactly zero at both precisions does not count as agreeing (it is what complete
/// cancellation looks like); exact zeros are for the caller to recognise.
pub fn verified_values<E>(
    digits: u32,
    deadline: Instant,
    mut compute: impl FnMut(Precision) -> Result<Vec<Float>, E>,
) -> Result<Verified, VerifyError<E>> {
    let required = digits + GUARD_DIGITS;
    let mut precision = Precision::decimal_digits(required + 8);
    let mut reached = 0;
    loop {
        if Instant::now() >= deadline {
            return Err(VerifyError::OutOfTime { required, reached });
        }
        let higher = Precision::bits(precision.in_bits() * 5 / 4 + 32);
        let first = compute(precision).map_err(VerifyError::Failed)?;
        let second = compute(higher).map_err(VerifyError::Failed)?;
        let agreed = first
            .iter()
            .zip(&second)
            // Two zeros say nothing: a difference that cancelled completely at both precisions.
            .map(|(a, b)| {
                if a.is_zero() && b.is_zero() {
                    0
                } else {
                    agreeing_digits(&Float::with_val(higher.in_bits(), a), b)
                }
            })
            .min()
            .unwrap_or(u32::MAX);
        if agreed >= required {
            return Ok(Verified {
                values: second,
                agreed,
                precision: higher,
            });
        }
        reached = reached.max(agreed);
        let missing = Precision::decimal_digits(required - agreed + 8).in_bits();
        precision = Precision::bits((precision.in_bits() * 5 / 4).max(precision.in_bits() + missing));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::real::Real;
    use std::time::Duration;

    #[test]
    fn cancellation_raises_the_precision_until_the_digits_agree() {
        // (1 + 10⁻⁶⁰) − 1 needs more than 200 bits to keep any digit.
        let deadline = Instant::now() + Duration::from_secs(10);
        let tiny = |p: Precision| -> Result<Vec<Float>, ()> {
            let one = Float::with_val(p.in_bits(), 1);
            let small = Float::parse_decimal("1e-60", p).map_err(|_| ())?;
            Ok(vec![(one.clone() + &small) - &one])
        };
        let verified = verified_values(20, deadline, tiny).unwrap();
        assert!(verified.precision.in_bits() > 260, "{:?}", verified.precision);
        assert_eq!(verified.values[0].to_scientific(20), "1.0000000000000000000e-60");
        let never = |p: Precision| -> Result<Vec<Float>, ()> { Ok(vec![Float::with_val(p.in_bits(), p.in_bits())]) };
        let past = Instant::now();
        assert!(matches!(
            verified_values(5, past, never),
            Err(VerifyError::OutOfTime { .. })
        ));
    }
}
