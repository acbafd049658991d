//! Admissibility proven: v' > 0 and v'' ≤ 0 on every load the cycle reaches, from the
//! lowest slip load P_T (or P0 − P1 if lower) to P0 + P1 ([`prove_admissible`]), or on the
//! loads a path reaches ([`prove_admissible_on`]).
//!
//! The theory needs both; without them W may come out negative, and a "proven" negative W
//! would prove nothing. A compliance whose form decides it (a power law with C > 0 and
//! β ≤ 0, Persson's, Hertz's, an exponential with a, c > 0 and d ≥ 0, their positive sums and
//! multiples: [`Compliance::admissible_by_form`]) is admissible at once, since the signs of
//! its parameters are those of the decimals written. Any other (a sum with a negative term,
//! a polynomial, a rational, a table) is checked with Arb balls: v'' is enclosed over
//! subintervals of the range, each bounded both directly and by its mean-value form
//! v''(m) + v'''(I)·(I − m), and an interval whose enclosure is not ≤ 0 is halved; a load
//! whose own enclosure of v'' is > 0 (or of v' is ≤ 0) is named in the refusal. Once v'' ≤ 0
//! is proven throughout, v' > 0 there follows from v'(P0 + P1) > 0 (v' is non-increasing).
//! A range that [`MAX_INTERVALS`] subintervals do not settle is refused as undecidable.
//! Built without ball arithmetic (no feature `certified`), the check samples the range in
//! MPFR ([`check_admissible`]).

use rug::Float;

use crate::case::{Case, CaseSpec};
use crate::compliance::{check_admissible, AdmissibilityError, Compliance, ComplianceSpec};
use crate::real::{Precision, Real};

/// The most subintervals the ball check may cut the range into.
pub const MAX_INTERVALS: usize = 4096;

/// Checks that the case's compliance is admissible on every load its cycle reaches
/// (the cycle is inside the theory: [`CaseSpec`] decided that when it was read).
pub fn prove_admissible(case: &CaseSpec) -> Result<(), AdmissibilityError> {
    if by_form_in_f64(case) {
        return Ok(());
    }
    let Some((low, high)) = load_range(case) else {
        return Ok(());
    };
    prove_admissible_on(case.compliance(), &low, &high)
}

/// Checks that the compliance `spec` is admissible on [low, high] (0 < low ≤ high), the
/// loads a cycle or a path reaches: by its form, else on Arb balls (in MPFR samples where
/// built without them). A spec that cannot be read in MPFR was refused when it was read.
///
/// ```
/// use microslip::admissibility::prove_admissible_on;
/// use microslip::compliance::ComplianceSpec;
/// use rug::Float;
///
/// let (low, high) = (Float::with_val(64, 0.5), Float::with_val(64, 1.5));
/// let persson = ComplianceSpec::parse("persson:gamma=1,sigma=1")?;
/// assert!(prove_admissible_on(&persson, &low, &high).is_ok());
/// // Convex by 1e-40: refused, naming a load where v'' > 0.
/// let convex = ComplianceSpec::parse("poly:p0=1,coeffs=2;1e-40")?;
/// assert!(prove_admissible_on(&convex, &low, &high).is_err());
/// # Ok::<(), microslip::compliance::SpecError>(())
/// ```
pub fn prove_admissible_on(spec: &ComplianceSpec, low: &Float, high: &Float) -> Result<(), AdmissibilityError> {
    let Ok(compliance) = spec.build::<Float>(Precision::bits(low.prec().max(high.prec()))) else {
        return Ok(());
    };
    if compliance.admissible_by_form(low, high) {
        return Ok(());
    }
    // v'' ≤ 0 from the exact form, after like terms cancel (v'' ≡ 0 for a constant v'):
    // then v' > 0 throughout wherever v'(high) > 0.
    if spec.is_constant_slope() || spec.is_concave_by_form() {
        return slope_positive_at_top(spec, compliance.as_ref(), low, high);
    }
    by_balls(spec, low, high).unwrap_or_else(|| check_admissible(compliance.as_ref(), low, high))
}

/// The range [min(P_T, P0 − P1), P0 + P1] of the loads the cycle
/// reaches. P_T > 0 for every cycle inside the theory (no gross slip means σ₊ + σ₋ < 2fP0), but
/// near separation its formula cancels: the bits rise until its lower end is positive, and past
/// [`MAX_RANGE_BITS`] the end is taken as 2^(−2^20) P0, below the true one. None where MPFR cannot
/// read the case.
fn load_range(case: &CaseSpec) -> Option<(Float, Float)> {
    let mut bits = 128;
    loop {
        let Case { cycle, .. } = case.at::<Float>(Precision::bits(bits)).ok()?;
        let low = (cycle.mean_normal_load.clone() - &cycle.normal_amplitude).min_of(&cycle.permanent_stick_load());
        let high = cycle.mean_normal_load.clone() + &cycle.normal_amplitude;
        if low > 0 {
            return Some((low, high));
        }
        if bits >= MAX_RANGE_BITS {
            let floor = cycle.mean_normal_load.clone() >> (1 << 20);
            return Some((floor, high));
        }
        bits *= 8;
    }
}

/// The most bits the load range is computed with.
const MAX_RANGE_BITS: u32 = 8192;

/// v'(high) > 0, the least v' on a range where v'' ≤ 0: proven in balls where built with
/// them, else in MPFR.
#[cfg(feature = "certified")]
fn slope_positive_at_top(
    spec: &ComplianceSpec,
    _: &dyn Compliance<Float>,
    low: &Float,
    high: &Float,
) -> Result<(), AdmissibilityError> {
    balls::slope_positive_at_top(spec, low, high)
}

#[cfg(not(feature = "certified"))]
fn slope_positive_at_top(
    _: &ComplianceSpec,
    compliance: &dyn Compliance<Float>,
    low: &Float,
    high: &Float,
) -> Result<(), AdmissibilityError> {
    let slope = compliance.slope(high);
    if slope > 0 {
        return Ok(());
    }
    Err(AdmissibilityError::NonPositiveSlope {
        load: high.to_f64(),
        slope: slope.to_f64(),
        low: low.to_f64(),
        high: high.to_f64(),
    })
}

/// Whether the form decides it in f64 (the cheap path for the usual families); false where
/// f64 cannot read the case or the form does not decide.
fn by_form_in_f64(case: &CaseSpec) -> bool {
    let Ok(Case { cycle, compliance }) = case.at::<f64>(Precision::DOUBLE) else {
        return false;
    };
    let low = (cycle.mean_normal_load - cycle.normal_amplitude).min(cycle.permanent_stick_load());
    let high = cycle.mean_normal_load + cycle.normal_amplitude;
    low.is_finite() && high.is_finite() && low > 0.0 && compliance.admissible_by_form(&low, &high)
}

#[cfg(feature = "certified")]
fn by_balls(spec: &ComplianceSpec, low: &Float, high: &Float) -> Option<Result<(), AdmissibilityError>> {
    Some(balls::prove(spec, low, high))
}

#[cfg(not(feature = "certified"))]
fn by_balls(_: &ComplianceSpec, _: &Float, _: &Float) -> Option<Result<(), AdmissibilityError>> {
    None
}

#[cfg(feature = "certified")]
mod balls {
    use rug::Float;

    use crate::ball::{watch, Ball};
    use crate::compliance::{AdmissibilityError, Compliance, ComplianceSpec};
    use crate::real::{Precision, Real};

    use super::MAX_INTERVALS;

    /// The working precision of the check.
    const BITS: u32 = 128;
    /// The most bits v' at the top of the range is computed with.
    const MAX_SLOPE_BITS: u32 = 8192;

    /// The sign of an enclosure: settled one way, or not.
    #[derive(PartialEq)]
    enum Sign {
        AtMostZero,
        Positive,
        Unsettled,
    }

    fn sign(ball: &Ball) -> Sign {
        if !ball.is_real() {
            return Sign::Unsettled;
        }
        let (lower, upper) = ball.bounds(BITS);
        if upper <= 0 {
            Sign::AtMostZero
        } else if lower > 0 {
            Sign::Positive
        } else {
            Sign::Unsettled
        }
    }

    /// An enclosure computed without an undecided comparison, or none.
    fn decided(computation: impl FnOnce() -> Option<Ball>) -> Option<Ball> {
        let (value, doubts) = watch(computation);
        value.filter(|v| doubts.none() && v.is_real())
    }

    /// The ball of all loads in [a, b].
    fn interval(a: &Float, b: &Float) -> Ball {
        let precision = Precision::bits(BITS);
        Ball::from_float(a, precision).union(&Ball::from_float(b, precision))
    }

    pub(super) fn prove(spec: &ComplianceSpec, low: &Float, high: &Float) -> Result<(), AdmissibilityError> {
        let Ok(compliance) = spec.build::<Ball>(Precision::bits(BITS)) else {
            return Err(undecidable(low, high, low));
        };
        let compliance = compliance.as_ref();
        let (low_f, high_f) = (low.to_f64(), high.to_f64());
        let named = |load: &Float| -> Option<AdmissibilityError> {
            let at = Ball::from_float(load, Precision::bits(BITS));
            let slope = decided(|| Some(compliance.slope(&at)))?;
            if sign(&slope) == Sign::AtMostZero {
                return Some(AdmissibilityError::NonPositiveSlope {
                    load: load.to_f64(),
                    slope: slope.bounds(53).1.to_f64(),
                    low: low_f,
                    high: high_f,
                });
            }
            let curvature = decided(|| Some(compliance.curvature(&at)))?;
            (sign(&curvature) == Sign::Positive).then(|| AdmissibilityError::PositiveCurvature {
                load: load.to_f64(),
                curvature: curvature.bounds(53).0.to_f64(),
                low: low_f,
                high: high_f,
            })
        };
        let mut pending = vec![(low.clone(), high.clone())];
        let mut intervals = 0;
        while let Some((a, b)) = pending.pop() {
            intervals += 1;
            let middle = Float::with_val(BITS + 8, &a + &b) / 2u32;
            if concave_on(compliance, &a, &b, &middle) {
                continue;
            }
            if let Some(refusal) = named(&middle).or_else(|| named(&a)).or_else(|| named(&b)) {
                return Err(refusal);
            }
            if intervals >= MAX_INTERVALS || middle <= a || middle >= b {
                return Err(undecidable(low, high, &middle));
            }
            pending.push((middle.clone(), b));
            pending.push((a, middle));
        }
        // v'' ≤ 0 throughout: v' is least at the top of the range.
        slope_positive_at_top(spec, low, high)
    }

    /// v'' ≤ 0 on [a, b], proven by its direct enclosure, or by its Taylor form about
    /// `middle` of first order (v''(m) + v'''(I)·(I − m)) or of second order
    /// (v''(m) + v'''(m)·(I − m) + v''''(I)·(I − m)²/2), whose overestimate shrinks with the
    /// square or the cube of the width where a sum of terms cancels.
    fn concave_on(compliance: &dyn Compliance<Ball>, a: &Float, b: &Float, middle: &Float) -> bool {
        let whole = interval(a, b);
        let at_most_zero = |c: Option<Ball>| c.is_some_and(|c| sign(&c) == Sign::AtMostZero);
        if at_most_zero(decided(|| Some(compliance.curvature(&whole)))) {
            return true;
        }
        let at_middle = Ball::from_float(middle, Precision::bits(BITS));
        let spread = whole.clone() - &at_middle;
        let first_order = decided(|| {
            let third = compliance.slope_derivative(2, &whole)?;
            Some(compliance.curvature(&at_middle) + &(third * &spread))
        });
        if at_most_zero(first_order) {
            return true;
        }
        at_most_zero(decided(|| {
            let third = compliance.slope_derivative(2, &at_middle)?;
            let fourth = compliance.slope_derivative(3, &whole)?;
            let square = spread.clone() * &spread;
            Some(compliance.curvature(&at_middle) + &(third * &spread) + &(fourth * &square / &at_middle.int(2)))
        }))
    }

    /// v'(high) > 0, proven (the least v' where v'' ≤ 0 on [low, high]) at a precision that
    /// rises while the terms of a sum cancel; a v' proven ≤ 0 is named, one not settled at
    /// [`MAX_SLOPE_BITS`] is undecidable.
    pub(super) fn slope_positive_at_top(
        spec: &ComplianceSpec,
        low: &Float,
        high: &Float,
    ) -> Result<(), AdmissibilityError> {
        let mut bits = BITS;
        loop {
            let precision = Precision::bits(bits);
            let Ok(compliance) = spec.build::<Ball>(precision) else {
                return Err(undecidable(low, high, high));
            };
            let top = Ball::from_float(high, precision);
            match decided(|| Some(compliance.slope(&top))) {
                Some(slope) if sign(&slope) == Sign::Positive => return Ok(()),
                Some(slope) if sign(&slope) == Sign::AtMostZero => {
                    return Err(AdmissibilityError::NonPositiveSlope {
                        load: high.to_f64(),
                        slope: slope.bounds(53).1.to_f64(),
                        low: low.to_f64(),
                        high: high.to_f64(),
                    })
                }
                _ if bits >= MAX_SLOPE_BITS => return Err(undecidable(low, high, high)),
                _ => bits *= 4,
            }
        }
    }

    fn undecidable(low: &Float, high: &Float, load: &Float) -> AdmissibilityError {
        AdmissibilityError::Undecidable {
            load: load.to_f64(),
            low: low.to_f64(),
            high: high.to_f64(),
            intervals: MAX_INTERVALS,
        }
    }
}
