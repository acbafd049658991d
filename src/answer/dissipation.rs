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
//! 3. a rigorous enclosure ([`Provenance::Certified`]): without `--digits`, the 12 to 15
//!    digits ([`DEFAULT_LEAST_DIGITS`] to [`DEFAULT_DIGITS`]) that one enclosure in f64
//!    intervals proves, else 15 from Arb's balls; with `--digits N`, N digits from Arb's
//!    balls (from the intervals first where N ≤ 12 and they prove N); or only where none can be had
//!    ([`NoEnclosure`] says why) two precisions agreeing ([`Provenance::Agreement`],
//!    evidence, not proof). An f64 error estimate never decides a printed digit: it is
//!    not a bound (the accuracy report, `crate::accuracy`, still measures it).

use std::sync::Arc;
use std::time::{Duration, Instant};

use crate::admissibility::prove_admissible;
use crate::answer::agreed::{check_case, checked_exact_zero, verified_dissipation_of, MAX_DIGITS};
use crate::answer::DissipationAnswerError;
use crate::answer::{Answer, Provenance, Value};
use crate::case::{Case, CaseSpec, CaseText, InputError};
use crate::compliance::{ComplianceTable, TableInterpolant, TABLE_ORDER};
use crate::cycle::LoadCycle;
use crate::decimal::printing::F64_MOST_DIGITS;
use crate::dissipation::{dissipation, Dissipation, DissipationError, Options, Segment, Segments};
use crate::real::Precision;

/// W as printed, with why the policy took the path it took.
#[derive(Clone, Debug, PartialEq)]
pub struct DissipationAnswer {
    /// W and its segments, and what vouches for them.
    pub answer: Answer,
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
    Refused(crate::digits::enclosure::CertifiedError),
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
pub fn dissipation_answer(
    case: &CaseText,
    digits: Option<u32>,
    budget: Duration,
) -> Result<Answer, DissipationAnswerError> {
    dissipation_report(case, digits, budget).map(|report| report.answer)
}

/// The most significant digits printed without `--digits`: as many as binary64 carries
/// through a decimal round trip, each one proven.
pub const DEFAULT_DIGITS: u32 = F64_MOST_DIGITS;

/// The fewest significant digits printed without `--digits`: W is printed to the digits
/// its f64 interval enclosure proves (its width from rounding in doubles is about 1e−15
/// to 1e−14 of W, so 12 to 15), and only where that proves fewer than these is the Arb
/// ladder climbed, for [`DEFAULT_DIGITS`]. `--digits N` with N up to these is served by
/// the intervals where they prove N.
pub const DEFAULT_LEAST_DIGITS: u32 = 12;

/// W for printing by the policy of this module, within `budget`: `digits` = Some(N) digits,
/// or without [`DEFAULT_DIGITS`], proven by an enclosure (by agreement only where no
/// enclosure can be had, saying why).
pub fn dissipation_report(
    case: &CaseText,
    digits: Option<u32>,
    budget: Duration,
) -> Result<DissipationAnswer, DissipationAnswerError> {
    // The case is read once; every precision below is computed from it.
    dissipation_of(&case.spec()?, digits, budget)
}

/// [`dissipation_report`] of a case already read (as [`CaseText::builder`] gives it).
///
/// ```
/// use std::time::Duration;
///
/// use microslip::case::CaseText;
/// use microslip::answer::dissipation::dissipation_of;
///
/// let case = CaseText::builder()
///     .p0(1).p1(0.4).q1(0.5).phi("0.4pi").friction(1).lambda(1)
///     .compliance("persson:gamma=1,sigma=1")
///     .build()
///     .unwrap();
/// let report = dissipation_of(&case, None, Duration::from_secs(60)).unwrap();
/// let w = &report.answer.value;
/// // The digits an enclosure in f64 intervals proves (12 to 15).
/// assert_eq!(w.decimal.to_string(), "4.062475792458e-1");
/// assert!(report.answer.provenance.is_proven());
/// // The exact W lies in the enclosure, every number of which rounds to the digits printed.
/// let (lower, upper) = w.enclosure_f64().unwrap();
/// assert!(lower <= upper && upper - lower < 1e-13);
/// ```
pub fn dissipation_of(
    case: &CaseSpec,
    digits: Option<u32>,
    budget: Duration,
) -> Result<DissipationAnswer, DissipationAnswerError> {
    let started = Instant::now();
    let deadline = started + budget;
    if let Some(digits) = digits.filter(|&d| d == 0 || d > MAX_DIGITS) {
        return Err(DissipationAnswerError::DigitsOutOfRange(digits));
    }
    prove_admissible(case).map_err(DissipationError::from)?;
    let tables = case.compliance().tables();
    if !tables.is_empty() {
        let estimate = table_answer(case, &tables, deadline)?;
        return match digits {
            // A table of equal slopes dissipates nothing, exactly, as any constant slope.
            None => match checked_exact_zero(case)? {
                Some(reason) => Ok(DissipationAnswer {
                    answer: Answer::exact_zero(reason, None),
                    ..estimate
                }),
                None => Ok(estimate),
            },
            Some(digits) => table_to_digits(case, estimate, digits, (started, deadline)),
        };
    }
    let plain = |answer| DissipationAnswer {
        answer,
        no_enclosure: None,
        table: None,
    };
    if let Some(reason) = checked_exact_zero(case)? {
        return Ok(plain(Answer::exact_zero(reason, digits)));
    }
    let range = digits.map_or((DEFAULT_LEAST_DIGITS, DEFAULT_DIGITS), |digits| (digits, digits));
    let (mut answer, no_enclosure) = to_digits(case, range, (started, deadline))?;
    answer.digits_requested = digits;
    Ok(DissipationAnswer {
        no_enclosure,
        ..plain(answer)
    })
}

/// At least `least` and at most `digits` digits: certified where an enclosure can be had
/// (f64 intervals where they prove `least`, Arb balls to `digits` otherwise), else
/// `digits` by agreement.
fn to_digits(
    case: &CaseSpec,
    (least, digits): (u32, u32),
    (started, deadline): (Instant, Instant),
) -> Result<(Answer, Option<NoEnclosure>), DissipationAnswerError> {
    // The enclosure needs a case inside the theory, which it does not check itself.
    check_case(case)?;
    let no_enclosure = match certified::answer(case, (least, digits), deadline) {
        Ok(answer) => return Ok((answer, None)),
        Err(refusal) => refusal?,
    };
    let budget = deadline.saturating_duration_since(Instant::now());
    match verified_dissipation_of(case, digits, budget) {
        Ok(verified) => Ok((verified.answer, Some(no_enclosure))),
        Err(DissipationAnswerError::Budget(mut spent)) => {
            // The time the request took, not agreement's share of it.
            spent.seconds = started.elapsed().as_secs_f64();
            Err(further_in_time(no_enclosure, spent))
        }
        Err(error) => Err(error),
    }
}

/// Where both the enclosure and agreement ran out of time, the one that got further (the
/// enclosure on a tie: its digits are proven).
fn further_in_time(no_enclosure: NoEnclosure, spent: crate::digits::agreement::OutOfBudget) -> DissipationAnswerError {
    match no_enclosure {
        #[cfg(feature = "certified")]
        NoEnclosure::Refused(error @ crate::digits::enclosure::CertifiedError::OutOfTime { reached, .. })
            if reached >= spent.digits_reached() =>
        {
            DissipationAnswerError::Certified(error)
        }
        _ => DissipationAnswerError::Budget(spent),
    }
}

#[cfg(feature = "certified")]
mod certified {
    use std::time::Instant;

    use crate::answer::DissipationAnswerError;
    use crate::answer::{Answer, Arithmetic, Provenance};
    use crate::ball::Ball;
    use crate::case::{Case, CaseSpec};
    use crate::digits::enclosure::{
        certified_dissipation_by, enclose_dissipation_with_lowest_load, CertifiedError, Enclosing, Enclosure,
        INTERVAL_GOAL_BITS,
    };
    use crate::dissipation::{DissipationError, Method, Segments, NEAR_SEPARATION};
    use crate::interval::Interval;
    use crate::real::{Precision, Real};

    use super::{NoEnclosure, DEFAULT_LEAST_DIGITS};

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

    /// W proven to at least `least` and at most `most` digits: first by one enclosure in
    /// f64 intervals where `least` is at most [`DEFAULT_LEAST_DIGITS`], then, where that
    /// proves fewer than `least` or refuses, by the Arb ladder to `most` digits;
    /// `Err(Ok(why))` where no enclosure can be had and agreement may serve,
    /// `Err(Err(error))` where nothing will (a cycle outside the theory, the budget spent).
    pub(super) fn answer(
        case: &CaseSpec,
        (least, most): (u32, u32),
        deadline: Instant,
    ) -> Result<Answer, Result<NoEnclosure, DissipationAnswerError>> {
        if least <= DEFAULT_LEAST_DIGITS {
            if let Some(answer) = in_intervals(case, least, most) {
                return Ok(answer);
            }
        }
        in_balls(case, most, deadline)
    }

    /// W from one enclosure in f64 intervals (each decimal read as the two doubles
    /// around it), where it proves at least `least` digits; `None` where it proves fewer,
    /// or cannot be had in doubles (an undecided comparison, a piece the rule cannot
    /// bound, a number beyond the range of f64).
    fn in_intervals(case: &CaseSpec, least: u32, most: u32) -> Option<Answer> {
        let Case { cycle, compliance } = case.at::<Interval>(Precision::DOUBLE).ok()?;
        // P0 − P1 read exactly: near separation the loads at the bottom of the cycle are
        // formed from it, where the difference of P0 and P1 each rounded would carry
        // their rounding amplified P1/(P0 − P1)-fold.
        let lowest = case.lowest_normal_load::<Interval>(Precision::DOUBLE).ok()?;
        // Near separation what doubles prove is set by how far the stick segments cancel:
        // away from φ ≡ π/2 the attempt is not made (proofs/printing.md, "Near separation in
        // f64 intervals").
        let near_separation = lowest.to_f64_lossy() * NEAR_SEPARATION as f64 <= cycle.normal_amplitude.to_f64_lossy();
        if near_separation && cycle.phase_trig().sin.square().to_f64_lossy() < LEAST_SQUARED_PHASE_SINE {
            return None;
        }
        let enclosure =
            enclose_dissipation_with_lowest_load(&cycle, Some(&lowest), compliance.as_ref(), INTERVAL_GOAL_BITS)
                .ok()?;
        let answer = enclosure_answer(&enclosure, most, Arithmetic::F64Intervals);
        (answer.value.digits() >= least).then_some(answer)
    }

    /// The least sin²φ at which a cycle near separation is tried in f64 intervals (φ within
    /// about 24° of π/2). BC and CH, each larger than W by up to about 1/sin²φ, cancel in
    /// W, and the width of their enclosures does not: of 700 cycles within 1e-3 to 1e-9 of
    /// separation (benches/default_rows.py, seeds 2026 and 2027), those the intervals prove
    /// lie mostly here, and beyond it the attempts that fail cost more than those that
    /// succeed save the Arb ladder.
    const LEAST_SQUARED_PHASE_SINE: f64 = 5.0 / 6.0;

    /// W to `digits` certified digits by the Arb ladder.
    fn in_balls(
        case: &CaseSpec,
        digits: u32,
        deadline: Instant,
    ) -> Result<Answer, Result<NoEnclosure, DissipationAnswerError>> {
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
            ) => return Err(Err(DissipationAnswerError::Certified(error))),
            Err(error) if beyond_mpfr(case) => return Err(Err(DissipationAnswerError::Certified(error))),
            Err(error) => return Err(Ok(NoEnclosure::Refused(error))),
        };
        let enclosure = &certified.enclosure;
        let answer = enclosure_answer(enclosure, digits, Arithmetic::ArbBalls);
        if answer.value.digits() < digits {
            // The driver settles its digits by the same rule at the same precision.
            return Err(Ok(NoEnclosure::Refused(CertifiedError::TooWide {
                asked: digits,
                reached: answer.value.digits(),
                relative_radius: enclosure.total.relative_radius(),
                bits: enclosure.precision.in_bits(),
            })));
        }
        Ok(answer)
    }

    /// W and each segment printed by the one rule from `enclosure`, to at most `most`
    /// digits, vouched for by the enclosure in `arithmetic`.
    fn enclosure_answer<R: Enclosing>(enclosure: &Enclosure<R>, most: u32, arithmetic: Arithmetic) -> Answer {
        Answer {
            value: enclosure.total.decimal_value(most),
            segments: Some(Segments::from_fn(|segment| {
                enclosure.segments.get(segment).decimal_value(most)
            })),
            digits_requested: Some(most),
            provenance: Provenance::Certified {
                bits: enclosure.precision.in_bits(),
                arithmetic,
            },
            method: Some(Method::from(enclosure.kind)),
        }
    }
}

#[cfg(not(feature = "certified"))]
mod certified {
    use std::time::Instant;

    use crate::answer::Answer;
    use crate::answer::DissipationAnswerError;
    use crate::case::CaseSpec;

    use super::NoEnclosure;

    /// Without ball arithmetic there is no enclosure.
    pub(super) fn answer(
        _: &CaseSpec,
        _: (u32, u32),
        _: Instant,
    ) -> Result<Answer, Result<NoEnclosure, DissipationAnswerError>> {
        Err(Ok(NoEnclosure::NotBuilt))
    }
}

/// An f64 result as an answer vouched for by `provenance`: W for the absolute `bound` on its
/// error, each segment for its own in `segment_errors`.
fn estimated(
    result: &Dissipation<f64>,
    (bound, segment_errors): (f64, &Segments<f64>),
    provenance: Provenance,
) -> Answer {
    let segments = &result.segments;
    Answer {
        value: Value::from_f64(result.total, bound),
        segments: Some(Segments::from_fn(|segment| {
            Value::from_f64(*segments.get(segment), *segment_errors.get(segment))
        })),
        digits_requested: None,
        provenance,
        method: Some(result.method),
    }
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
fn table_in_f64(error: DissipationError) -> DissipationAnswerError {
    match error {
        DissipationError::IllConditioned { .. }
        | DissipationError::NotConverged { .. }
        | DissipationError::OutOfRange { .. }
        | DissipationError::OutsideRange { .. } => DissipationAnswerError::TableInF64 { source: error },
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
) -> Result<(f64, Segments<f64>), DissipationAnswerError> {
    let other = case
        .compliance()
        .build_with::<f64>(Precision::DOUBLE, interpolant)
        .map_err(|e| DissipationAnswerError::Input(InputError::from(e)))?;
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
) -> Result<DissipationAnswer, DissipationAnswerError> {
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
    let answer = estimated(
        &result,
        (result.error_estimate + table_error, &segment_errors),
        Provenance::Table {
            table_error,
            smoothing_residual,
        },
    );
    Ok(DissipationAnswer {
        answer,
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
) -> Result<DissipationAnswer, DissipationAnswerError> {
    let (answer, no_enclosure) = match checked_exact_zero(case)? {
        Some(reason) => (Answer::exact_zero(reason, Some(digits)), None),
        None => to_digits(case, (digits, digits), clock)?,
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
