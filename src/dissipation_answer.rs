//! W as one [`Answer`]: the one policy that decides how W is computed for printing, and
//! says why wherever its first choice gave way.
//!
//! In order:
//! 1. a compliance with a table: f64 from the table's interpolant, with the table's error
//!    beside the quadrature's ([`Provenance::Table`]); with `--digits N`, N digits of W
//!    for the interpolant by steps 2 and 3, the table's error stated beside them (the
//!    estimated error of interpolating the given points, not of the solver or the surface
//!    that produced them);
//! 2. W exactly 0 for a reason read from the exact input ([`CaseSpec::exact_zero`]): at
//!    once, at any `--digits` ([`Provenance::Exact`]);
//! 3. with `--digits N`: a rigorous enclosure in ball arithmetic ([`Provenance::Certified`]),
//!    or only where none can be had ([`NoEnclosure`] says why) two precisions agreeing
//!    ([`Provenance::Agreement`], evidence, not proof);
//! 4. without: f64 with the digits its error estimate determines ([`Provenance::Estimate`]),
//!    or where f64 does not suffice ([`Fallback`] says why) [`F64_MOST_DIGITS`] digits by
//!    step 3.

use std::sync::Arc;
use std::time::{Duration, Instant};

use rug::Float;

use crate::admissibility::prove_admissible;
use crate::answer::{Answer, ExactReason, Provenance, Value};
use crate::case::{Case, CaseSpec, CaseText, InputError};
use crate::compliance::{Compliance, ComplianceTable, TableInterpolant, TABLE_ORDER};
use crate::cycle::{CycleError, LoadCycle};
use crate::dissipation::{dissipation, Dissipation, DissipationError, ExactZero, Method, Options, Segment, Segments};
use crate::real::{Precision, Real};
use crate::reference::{check_case, checked_exact_zero, verified_dissipation_of, ReferenceError, MAX_DIGITS};
use crate::verified::{resolved_digits, F64_DIGITS_FLOOR, F64_MOST_DIGITS};

/// W as printed, with why the policy took the path it took.
#[derive(Clone, Debug, PartialEq)]
pub struct DissipationAnswer {
    /// W and its segments, and what vouches for them.
    pub answer: Answer,
    /// Why a run without `--digits` did not print f64.
    pub fallback: Option<Fallback>,
    /// Why the digits rest on agreement of two precisions rather than an enclosure.
    pub no_enclosure: Option<NoEnclosure>,
    /// For a compliance with a table: the table's error and the quadrature's.
    pub table: Option<TableEstimate>,
}

impl DissipationAnswer {
    /// W as printed: empty where not one digit is determined (a table too coarse for it).
    pub fn total(&self) -> String {
        match self.answer.value.digits() {
            0 => String::new(),
            _ => self.answer.value.decimal.to_string(),
        }
    }
}

/// Why a run without `--digits` gave up f64 for [`F64_MOST_DIGITS`] digits at higher
/// precision.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Fallback {
    /// f64 cannot hold a number of the case (1e-400, c=1e400).
    CannotRead(InputError),
    /// Rounded to f64, the inputs cross a boundary of the theory that the exact cycle keeps
    /// off (P1 = 0.99999999999999999 rounds to P0 = 1).
    RoundedAcrossBoundary(CycleError),
    /// An intermediate of the compliance's formula leaves f64's range: its change of v'
    /// about P0 differs from MPFR's at `load`.
    ComplianceOverflow {
        /// The load at which the two differ.
        load: f64,
        /// v'(P) − v'(P0) there in f64.
        in_f64: f64,
        /// The same in MPFR, to four digits.
        in_mpfr: String,
    },
    /// A magnitude of the case lies outside what f64 carries through the integrals.
    OutsideRange {
        /// The quantity's name.
        quantity: String,
        /// Its value.
        value: f64,
        /// The least magnitude f64 carries.
        low: f64,
        /// The largest.
        high: f64,
    },
    /// f64 fails: the result is out of its range or not finite, or the compliance looks
    /// non-physical there.
    F64Fails(DissipationError),
    /// Rounding alone would move W by `expected` (relative).
    IllConditioned {
        /// What amplifies the rounding.
        cause: String,
        /// The relative change of W that rounding alone can cause.
        expected: f64,
    },
    /// The f64 integrals did not converge.
    NotConverged,
    /// W ± its error estimate straddles rounding boundaries of more than its last digits.
    Straddles {
        /// The digits f64 determines.
        resolved: u32,
        /// Its error estimate.
        error_estimate: f64,
    },
    /// f64 gives W = 0 with an error estimate of 0, as for an exact zero, which no reason
    /// read from the input makes it (those are answered before f64 runs): every change of
    /// v' over the cycle's loads, or every integrand value, has rounded to zero in f64
    /// (v' = a·exp(−P/c) + d at loads of thousands of c).
    ZeroInF64,
    /// The segments cancel to a W much smaller than themselves.
    Cancellation {
        /// The digits f64 determines.
        resolved: u32,
        /// The largest |segment|.
        largest_segment: f64,
    },
}

impl std::fmt::Display for Fallback {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Fallback::CannotRead(error) => write!(f, "f64 cannot read the case: {error}"),
            Fallback::RoundedAcrossBoundary(error) => write!(
                f,
                "rounded to f64 the inputs cross a boundary that the exact cycle keeps off (in f64: {error})"
            ),
            Fallback::ComplianceOverflow { load, in_f64, in_mpfr } => write!(
                f,
                "in f64 the compliance gives v'(P) − v'(P0) = {in_f64:.3e} at P = {load:.3e}, in MPFR {in_mpfr}: an intermediate of its formula leaves the range of f64"
            ),
            Fallback::OutsideRange {
                quantity,
                value,
                low,
                high,
            } => write!(
                f,
                "{quantity} = {value:.1e} is outside the magnitudes f64 carries through the integrals without overflow or underflow ({low:.0e} to {high:.0e})"
            ),
            Fallback::F64Fails(error) => write!(f, "f64 fails here: {error}"),
            Fallback::IllConditioned { cause, expected } => write!(
                f,
                "f64 is ill-conditioned here ({cause}): rounding alone would move W by ~{expected:.0e}"
            ),
            Fallback::NotConverged => f.write_str("the f64 integrals did not converge here"),
            Fallback::Straddles {
                resolved,
                error_estimate,
            } => write!(
                f,
                "f64 resolves {resolved} digits here: W ± its error estimate {error_estimate:.1e} straddles a rounding boundary of digit {}",
                resolved + 1
            ),
            Fallback::ZeroInF64 => f.write_str(
                "f64 gives W = 0, which no reason read from the input makes exact (in f64 the changes of v' over the cycle's loads, or the integrands, round to 0)",
            ),
            Fallback::Cancellation {
                resolved,
                largest_segment,
            } => write!(
                f,
                "f64 resolves {resolved} digits here: its segments, up to {largest_segment:.1e}, cancel to W"
            ),
        }
    }
}

/// Why digits rest on agreement of two precisions instead of a rigorous enclosure.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum NoEnclosure {
    /// The library was built without the `certified` feature (no Arb).
    NotBuilt,
    /// The certified driver refused the case: undecided geometry, an integrand not
    /// analytic on a piece, an enclosure too wide at the largest precision, or not narrow
    /// enough within its share of the budget.
    #[cfg(feature = "certified")]
    Refused(crate::certified::CertifiedError),
}

impl std::fmt::Display for NoEnclosure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            NoEnclosure::NotBuilt => f.write_str("built without ball arithmetic (feature `certified`)"),
            #[cfg(feature = "certified")]
            NoEnclosure::Refused(error) => write!(f, "{error}"),
        }
    }
}

/// What a table compliance adds to a result.
#[derive(Clone, Debug, PartialEq)]
pub struct TableEstimate {
    /// Estimated absolute error of W due to the table: the larger |W\[half table\] − W\[table\]|
    /// of the two half tables (plus the quadrature errors of the difference), scaled by
    /// the order of the construction and by how much coarser each half is on the table's
    /// actual spacing, plus how far rounding of the data moves W.
    pub error: f64,
    /// The largest relative change the smoothing fit made to the data (0 when none).
    pub smoothing_residual: f64,
    /// W before rounding to the printed digits.
    pub unrounded: f64,
    /// The quadrature's absolute error estimate of W.
    pub quadrature_error: f64,
}

/// W as printed: [`dissipation_report`] without the reasons.
pub fn dissipation_answer(case: &CaseText, digits: Option<u32>, budget: Duration) -> Result<Answer, ReferenceError> {
    dissipation_report(case, digits, budget).map(|report| report.answer)
}

/// W for printing by the policy of this module, within `budget`: with `digits` = Some(N),
/// N certified digits (or by agreement where no enclosure can be had); without, f64
/// where it suffices.
pub fn dissipation_report(
    case: &CaseText,
    digits: Option<u32>,
    budget: Duration,
) -> Result<DissipationAnswer, ReferenceError> {
    let started = Instant::now();
    let deadline = started + budget;
    if let Some(digits) = digits.filter(|&d| d == 0 || d > MAX_DIGITS) {
        return Err(ReferenceError::DigitsOutOfRange(digits));
    }
    // The case is read once; every precision below is computed from it.
    let case = &case.spec()?;
    prove_admissible(case).map_err(DissipationError::from)?;
    let tables = case.compliance().tables();
    if !tables.is_empty() {
        let estimate = table_answer(case, &tables, deadline)?;
        return match digits {
            None => Ok(estimate),
            Some(digits) => table_to_digits(case, estimate, digits, (started, deadline)),
        };
    }
    let plain = |answer| DissipationAnswer {
        answer,
        fallback: None,
        no_enclosure: None,
        table: None,
    };
    if let Some(reason) = checked_exact_zero(case)? {
        return Ok(plain(exact_zero_answer(reason, digits)));
    }
    let fallback = match digits {
        Some(_) => None,
        None => match in_f64(case, deadline)? {
            Ok(answer) => return Ok(plain(answer)),
            Err(fallback) => Some(fallback),
        },
    };
    let (answer, no_enclosure) = to_digits(case, digits.unwrap_or(F64_MOST_DIGITS), (started, deadline))?;
    Ok(DissipationAnswer {
        fallback,
        no_enclosure,
        ..plain(answer)
    })
}

/// W = 0 exactly, and every segment, for `reason`.
pub fn exact_zero_answer(reason: ExactZero, digits: Option<u32>) -> Answer {
    Answer {
        value: Value::zero(),
        segments: Some(Segments::from_fn(|_| Value::zero())),
        digits_requested: digits,
        provenance: Provenance::Exact(ExactReason::Zero(reason)),
        method: Some(Method::Exact(reason)),
    }
}

/// `digits` digits: certified where an enclosure can be had, else by agreement.
fn to_digits(
    case: &CaseSpec,
    digits: u32,
    (started, deadline): (Instant, Instant),
) -> Result<(Answer, Option<NoEnclosure>), ReferenceError> {
    // The enclosure needs a case inside the theory, which it does not check itself.
    check_case(case)?;
    let no_enclosure = match certified::answer(case, digits, deadline) {
        Ok(answer) => return Ok((answer, None)),
        Err(refusal) => refusal?,
    };
    let budget = deadline.saturating_duration_since(Instant::now());
    match verified_dissipation_of(case, digits, budget) {
        Ok(verified) => Ok((verified.answer, Some(no_enclosure))),
        Err(ReferenceError::Budget(mut spent)) => {
            // The time the request took, not agreement's share of it.
            spent.seconds = started.elapsed().as_secs_f64();
            Err(further_in_time(no_enclosure, spent))
        }
        Err(error) => Err(error),
    }
}

/// Where both the enclosure and agreement ran out of time, the one that got further (the
/// enclosure on a tie: its digits are proven).
fn further_in_time(no_enclosure: NoEnclosure, spent: crate::verified::OutOfBudget) -> ReferenceError {
    match no_enclosure {
        #[cfg(feature = "certified")]
        NoEnclosure::Refused(error @ crate::certified::CertifiedError::OutOfTime { reached, .. })
            if reached >= spent.digits_reached() =>
        {
            ReferenceError::Certified(error)
        }
        _ => ReferenceError::Budget(spent),
    }
}

#[cfg(feature = "certified")]
mod certified {
    use std::time::Instant;

    use crate::answer::{Answer, Provenance, Value};
    use crate::ball::Ball;
    use crate::case::{Case, CaseSpec};
    use crate::certified::{certified_dissipation_by, CertifiedError};
    use crate::dissipation::{DissipationError, Method, Segments};
    use crate::reference::ReferenceError;

    use super::NoEnclosure;

    /// Whether the compliance has a decay load c and every load the cycle reads (all above
    /// P0 − P1 − Q1/f) is more than 2^29·ln 2 decay loads: then each e^(−P/c), and W with
    /// them, lies below 2^(−2^29), which no MPFR precision holds, and agreement of two
    /// precisions cannot answer where the enclosure did not.
    fn beyond_mpfr(case: &CaseSpec) -> bool {
        let Ok(Case { cycle, compliance }) = case.at::<f64>(crate::real::Precision::DOUBLE) else {
            return false;
        };
        let Some(decay_load) = compliance.decay_load() else {
            return false;
        };
        let lowest = cycle.mean_normal_load - cycle.normal_amplitude - cycle.tangential_amplitude / cycle.friction;
        lowest / decay_load > (1u64 << 29) as f64 * std::f64::consts::LN_2
    }

    /// W to `digits` certified digits; `Err(Ok(why))` where no enclosure can be had and
    /// agreement may serve, `Err(Err(error))` where nothing will (a cycle outside the
    /// theory, the budget spent).
    pub(super) fn answer(
        case: &CaseSpec,
        digits: u32,
        deadline: Instant,
    ) -> Result<Answer, Result<NoEnclosure, ReferenceError>> {
        let read = |precision| {
            let Case { cycle, compliance } = case.at::<Ball>(precision).map_err(|e| e.to_string())?;
            Ok((cycle, compliance))
        };
        // The enclosure gets the whole budget: running out of time is a failure with the
        // digits reached, never a reason to print digits that are not proven.
        let certified = match certified_dissipation_by(read, digits, Some(deadline)) {
            Ok(certified) => certified,
            Err(CertifiedError::Cycle(error)) => return Err(Err(DissipationError::from(error).into())),
            // No precision of MPFR holds such a W either, nor resolves such a compliance.
            Err(
                error @ (CertifiedError::BeyondDecimalExponents
                | CertifiedError::TooSteep { .. }
                | CertifiedError::OutOfTime { .. }),
            ) => return Err(Err(ReferenceError::Certified(error))),
            Err(error) if beyond_mpfr(case) => return Err(Err(ReferenceError::Certified(error))),
            Err(error) => return Err(Ok(NoEnclosure::Refused(error))),
        };
        let enclosure = &certified.enclosure;
        let bits = enclosure.precision.in_bits();
        let value = |ball: &Ball| Value::of_ball(ball, bits, digits);
        let total = value(&enclosure.total);
        if total.digits() < digits {
            // The one printing rule is stricter than the driver's where an end is a tie.
            return Err(Ok(NoEnclosure::Refused(CertifiedError::TooWide {
                asked: digits,
                reached: total.digits(),
                relative_radius: enclosure.total.relative_radius(),
                bits,
            })));
        }
        Ok(Answer {
            value: total,
            segments: Some(Segments::from_fn(|segment| value(enclosure.segments.get(segment)))),
            digits_requested: Some(digits),
            provenance: Provenance::Certified { bits },
            method: Some(Method::from(enclosure.kind)),
        })
    }
}

#[cfg(not(feature = "certified"))]
mod certified {
    use std::time::Instant;

    use crate::answer::Answer;
    use crate::case::CaseSpec;
    use crate::reference::ReferenceError;

    use super::NoEnclosure;

    /// Without ball arithmetic there is no enclosure.
    pub(super) fn answer(_: &CaseSpec, _: u32, _: Instant) -> Result<Answer, Result<NoEnclosure, ReferenceError>> {
        Err(Ok(NoEnclosure::NotBuilt))
    }
}

/// W in f64 with the digits its error estimate determines, or why f64 does not suffice.
fn in_f64(case: &CaseSpec, deadline: Instant) -> Result<Result<Answer, Fallback>, ReferenceError> {
    let Case { cycle, compliance } = match case.at::<f64>(Precision::DOUBLE) {
        Ok(case) => case,
        // A number f64 cannot hold (1e-400, c=1e400): MPFR reads the text exactly.
        Err(error) if case.at::<Float>(Precision::bits(64)).is_ok() => return Ok(Err(Fallback::CannotRead(error))),
        Err(error) => return Err(error.into()),
    };
    if let Err(error) = cycle.validate() {
        return Ok(Err(Fallback::RoundedAcrossBoundary(error)));
    }
    let compliance_rounding = match compliance_rounding(case, &cycle, compliance.as_ref()) {
        Ok(rounding) => rounding,
        Err(fallback) => return Ok(Err(fallback)),
    };
    let within_budget = Options {
        deadline: Some(deadline),
        ..Options::default()
    };
    let result = match dissipation(&cycle, compliance.as_ref(), &within_budget) {
        Ok(result) => result,
        Err(DissipationError::OutsideRange {
            quantity,
            value,
            low,
            high,
            ..
        }) => {
            return Ok(Err(Fallback::OutsideRange {
                quantity,
                value,
                low,
                high,
            }))
        }
        // Out of f64's range in the result, not finite, or a compliance f64 sees as
        // non-physical (v' underflowing to 0, say): MPFR either computes it or says why not.
        Err(
            error @ (DissipationError::OutOfRange { .. }
            | DissipationError::NotFinite { .. }
            | DissipationError::Compliance(_)),
        ) => return Ok(Err(Fallback::F64Fails(error))),
        Err(DissipationError::IllConditioned { cause, expected, .. }) => {
            return Ok(Err(Fallback::IllConditioned { cause, expected }))
        }
        Err(DissipationError::NotConverged { .. }) => return Ok(Err(Fallback::NotConverged)),
        Err(other) => return Err(other.into()),
    };
    // The quadrature's estimate covers the rounding of the loads, not the compliance's own: where
    // the terms of v' cancel (a sum of power laws of opposite signs), the change of v' carries
    // the rounding of its terms, measured above against MPFR; beyond ordinary rounding it is
    // carried into W through the segments, with a factor of ten for the kernels' spread.
    let mut result = result;
    if compliance_rounding > 64.0 * f64::EPSILON {
        let spread: f64 = result.segments.named().iter().map(|(_, v)| v.abs()).sum();
        result.error_estimate += 10.0 * compliance_rounding * spread;
    }
    let segment_errors = Segments::from_fn(|_| result.error_estimate);
    Ok(f64_suffices(&result).map(|()| estimated(&result, result.error_estimate, &segment_errors)))
}

/// Whether the digits f64 determines are enough to print: [`F64_DIGITS_FLOOR`] or more,
/// or one fewer where only the rounding boundary of the next digit is straddled (every
/// digit printed is still right, and MPFR would cost a thousand times more); never for a
/// W of 0 ± 0 (an exact zero is answered by its reason before f64 runs).
fn f64_suffices(result: &Dissipation<f64>) -> Result<(), Fallback> {
    if result.total == 0.0 && result.error_estimate == 0.0 {
        return Err(Fallback::ZeroInF64);
    }
    let resolved = resolved_digits(result.total, result.error_estimate);
    if resolved >= F64_DIGITS_FLOOR {
        return Ok(());
    }
    // The digits the estimate's width alone would leave.
    let width = (result.total.abs() / result.error_estimate).log10();
    if width >= f64::from(F64_DIGITS_FLOOR) {
        if resolved + 1 >= F64_DIGITS_FLOOR {
            return Ok(());
        }
        return Err(Fallback::Straddles {
            resolved,
            error_estimate: result.error_estimate,
        });
    }
    let largest_segment = result.segments.named().iter().map(|(_, v)| v.abs()).fold(0.0, f64::max);
    Err(Fallback::Cancellation {
        resolved,
        largest_segment,
    })
}

/// An f64 result as an estimated answer: W for the absolute `bound` on its error, each
/// segment for its own in `segment_errors`.
fn estimated(result: &Dissipation<f64>, bound: f64, segment_errors: &Segments<f64>) -> Answer {
    let segments = &result.segments;
    Answer {
        value: Value::from_f64(result.total, bound),
        segments: Some(Segments::from_fn(|segment| {
            Value::from_f64(*segments.get(segment), *segment_errors.get(segment))
        })),
        digits_requested: None,
        provenance: Provenance::Estimate {
            error_estimate: result.error_estimate,
        },
        method: Some(result.method),
    }
}

/// Interior loads of the cycle at which [`compliance_rounding`] compares.
const COMPARED_LOADS: i64 = 16;

/// The rounding of the f64 compliance: the largest difference of its change of v' about P0
/// (the only function of it the integrals see) from the same change in MPFR, at loads across
/// the cycle, relative to the largest change (0 where the comparison cannot be made). Beyond
/// 1e-6 the f64 compliance is not to be trusted at all: that is what an overflow or underflow
/// inside a compliance formula does (v' = a + b/(P + c) with c = 1e300 makes every change 0 in
/// f64), and within f64 it may look like a legitimate linear v.
fn compliance_rounding(
    case: &CaseSpec,
    cycle: &LoadCycle<f64>,
    compliance: &dyn Compliance<f64>,
) -> Result<f64, Fallback> {
    let Ok(precise) = case.at::<Float>(Precision::bits(64)) else {
        return Ok(0.0);
    };
    let p0 = cycle.mean_normal_load;
    let low = (p0 - cycle.normal_amplitude).min(cycle.permanent_stick_load());
    let high = p0 + cycle.normal_amplitude;
    if !(low.is_finite() && high.is_finite() && low < high) {
        return Ok(0.0);
    }
    let change = compliance.slope_change_about(&p0);
    let precise_change = precise.compliance.slope_change_about(&precise.cycle.mean_normal_load);
    // Compared in MPFR: an exact change below f64's range must not round to the f64 zero.
    let pairs: Vec<(f64, f64, Float)> = (1..COMPARED_LOADS)
        .map(|k| {
            let offset = (low - p0) + (high - low) * (k as f64 / COMPARED_LOADS as f64);
            let exact = precise_change(&Float::with_val(64, offset));
            (p0 + offset, change(&offset), exact)
        })
        .collect();
    let zero = Float::with_val(64, 0);
    let largest = pairs
        .iter()
        .fold(zero, |acc, (_, _, exact)| acc.max(&exact.clone().abs()));
    let tolerance = Float::with_val(64, &largest / 1_000_000u32);
    let mut worst = Float::with_val(64, 0);
    for (load, in_f64, exact) in pairs {
        let difference = (Float::with_val(64, in_f64) - &exact).abs();
        // NaN on either side counts as a difference.
        if difference.is_nan() || difference > tolerance {
            return Err(Fallback::ComplianceOverflow {
                load,
                in_f64,
                in_mpfr: exact.to_scientific(4),
            });
        }
        worst.max_mut(&difference);
    }
    Ok(if largest > 0 { (worst / largest).to_f64() } else { 0.0 })
}

/// Relative quadrature tolerance of W from a table: far below any table's own error,
/// and reachable on the interpolant's piecewise-cubic v' in f64.
pub const TABLE_QUADRATURE_TOLERANCE: f64 = 1e-12;

/// What |W[half table] − W[table]| is divided by to estimate the error of W[table], for
/// a table of `rows` evenly spaced rows. For a construction of order p = 4 the quotient
/// tends to 2^p − 1 = 15, but before the data are asymptotic it is smaller: over the scan
/// of proofs/table-compliance.md it fell to 6 at 16 to 24 rows, to 1 at 9 rows, and below
/// 1 for tables of up to 5 rows (halves of three rows, one parabola of node values, can be
/// as close to the full table as its own error). The divisor keeps a factor of about two
/// below the least quotient measured at each size; [`refinement_scale`] lowers it where
/// the rows are not evenly spaced.
fn half_table_divisor(rows: usize) -> f64 {
    match rows {
        0..=5 => 0.25,
        6..=12 => 0.5,
        _ => 3.0,
    }
}

/// Σ H^(p+1) / Σ h^(p+1) of a half table of evenly spaced rows: 2^p.
const EVEN_REFINEMENT: f64 = (1 << TABLE_ORDER) as f64;

/// The share of [`half_table_divisor`] that a half table keeps whose refinement
/// ([`ComplianceTable::half_refinements`], 2^p for even spacing) is `refinement`:
/// ((refinement − 1)/(2^p − 1))², 1 for even spacing. The first power is what an error
/// spread evenly over the pieces gives; on irregular spacing the pieces that carry the
/// error are the widest, which widen least when a row is dropped, so the measured
/// quotient falls further (proofs/table-compliance.md: the square keeps a factor of
/// about two on random spacing, the first power did not).
fn refinement_scale(refinement: f64) -> f64 {
    ((refinement - 1.0) / (EVEN_REFINEMENT - 1.0)).clamp(0.0, 1.0).powi(2)
}

/// How many times the move of W under [`TableInterpolant::DataRounding`] enters the table
/// error: rounding moves W in no fixed direction, and one move of the data samples it.
const ROUNDING_FACTOR: f64 = 2.0;

/// An f64 failure on a table, for which no more precision is offered.
fn table_in_f64(error: DissipationError) -> ReferenceError {
    match error {
        DissipationError::IllConditioned { .. }
        | DissipationError::NotConverged { .. }
        | DissipationError::OutOfRange { .. }
        | DissipationError::OutsideRange { .. } => ReferenceError::TableInF64 { source: error },
        other => other.into(),
    }
}

/// How far W and each segment move from `result` when the tables' interpolant gives way
/// to `interpolant`, each with the quadrature errors of both added.
fn table_shift(
    case: &CaseSpec,
    cycle: &LoadCycle<f64>,
    options: &Options<f64>,
    result: &Dissipation<f64>,
    interpolant: TableInterpolant,
) -> Result<(f64, Segments<f64>), ReferenceError> {
    let other = case
        .compliance()
        .build_with::<f64>(Precision::DOUBLE, interpolant)
        .map_err(|e| ReferenceError::Input(InputError::from(e)))?;
    let moved = dissipation(cycle, other.as_ref(), options).map_err(table_in_f64)?;
    let uncertainty = moved.error_estimate + result.error_estimate;
    let segments =
        Segments::from_fn(|segment| (moved.segments.get(segment) - result.segments.get(segment)).abs() + uncertainty);
    Ok(((moved.total - result.total).abs() + uncertainty, segments))
}

/// W in f64 from the tables' interpolant, for the absolute error its quadrature error
/// plus the table's error leave (each segment likewise for its own).
fn table_answer(
    case: &CaseSpec,
    tables: &[Arc<ComplianceTable>],
    deadline: Instant,
) -> Result<DissipationAnswer, ReferenceError> {
    let Case { cycle, compliance } = case.at::<f64>(Precision::DOUBLE)?;
    cycle.validate().map_err(DissipationError::from)?;
    tables_cover(tables, &cycle)?;
    let options = Options {
        relative_tolerance: Some(TABLE_QUADRATURE_TOLERANCE),
        deadline: Some(deadline),
        ..Options::default()
    };
    let result = dissipation(&cycle, compliance.as_ref(), &options).map_err(table_in_f64)?;
    // The table error: how far W moves when the table loses its odd rows, or its even rows,
    // over how much coarser that half is where the cycle reads it; and how far rounding of
    // the data moves it.
    let divisor = half_table_divisor(tables.iter().map(|t| t.loads.len()).min().unwrap_or(0));
    let (low, high) = cycle_loads(&cycle);
    let (mut table_error, mut segment_shifts) = (0.0f64, Segments::from_fn(|_| 0.0f64));
    let halves = [TableInterpolant::HalfTable, TableInterpolant::OtherHalfTable];
    for (index, interpolant) in halves.into_iter().enumerate() {
        let (moved, segments_moved) = table_shift(case, &cycle, &options, &result, interpolant)?;
        let refinement = tables
            .iter()
            .filter_map(|table| table.half_refinements(low, high).get(index).copied())
            .fold(EVEN_REFINEMENT, f64::min);
        let divisor = divisor * refinement_scale(refinement);
        table_error = table_error.max(moved / divisor);
        for segment in Segment::ALL {
            let shift = segment_shifts.get_mut(segment);
            *shift = shift.max(segments_moved.get(segment) / divisor);
        }
    }
    let (rounding, segments_rounding) = table_shift(case, &cycle, &options, &result, TableInterpolant::DataRounding)?;
    table_error += ROUNDING_FACTOR * rounding;
    let segment_errors = Segments::from_fn(|segment| {
        result.error_estimate + segment_shifts.get(segment) + ROUNDING_FACTOR * segments_rounding.get(segment)
    });
    let smoothing_residual = tables.iter().map(|t| t.smoothing_residual).fold(0.0, f64::max);
    let answer = Answer {
        provenance: Provenance::Table {
            table_error,
            smoothing_residual,
        },
        ..estimated(&result, result.error_estimate + table_error, &segment_errors)
    };
    Ok(DissipationAnswer {
        answer,
        fallback: None,
        no_enclosure: None,
        table: Some(TableEstimate {
            error: table_error,
            smoothing_residual,
            unrounded: result.total,
            quadrature_error: result.error_estimate,
        }),
    })
}

/// W of the tables' interpolant to `digits` digits, as for any compliance (exact by
/// reason, certified, or by agreement), with the table's own error from `estimate`
/// beside it: the digits are those of the smooth function integrated, the table error
/// estimates how far interpolating the given points may have moved it (nothing of how
/// the points were produced).
fn table_to_digits(
    case: &CaseSpec,
    estimate: DissipationAnswer,
    digits: u32,
    clock: (Instant, Instant),
) -> Result<DissipationAnswer, ReferenceError> {
    let (answer, no_enclosure) = match checked_exact_zero(case)? {
        Some(reason) => (exact_zero_answer(reason, Some(digits)), None),
        None => to_digits(case, digits, clock)?,
    };
    Ok(DissipationAnswer {
        answer,
        no_enclosure,
        ..estimate
    })
}

/// Refuses a valid cycle whose loads, from min(P_T, P0 − P1) to P0 + P1, leave a table.
pub(crate) fn tables_cover(
    tables: &[Arc<ComplianceTable>],
    cycle: &LoadCycle<f64>,
) -> Result<(), crate::compliance::TableError> {
    let (low, high) = cycle_loads(cycle);
    tables.iter().try_for_each(|table| table.check_covers(low, high))
}

/// The loads W reads v' at: min(P_T, P0 − P1) to P0 + P1.
fn cycle_loads(cycle: &LoadCycle<f64>) -> (f64, f64) {
    let low = (cycle.mean_normal_load - cycle.normal_amplitude).min(cycle.permanent_stick_load());
    (low, cycle.mean_normal_load + cycle.normal_amplitude)
}
