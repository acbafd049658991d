//! I(ρ, φ), the series coefficients Iₙ and a case's partial sums W_N beside W, as
//! [`Answer`]s: exact by reason where the input decides the value (I₀ ≡ 0, nothing slips,
//! the series ends, W's zeros), otherwise rigorous enclosures of the exact input's value
//! (`digits::enclosure::series`, feature `certified`) printed by the one rule, and — only where no enclosure can be
//! had (feature `certified` off, or a comparison no precision decides) — two precisions'
//! agreement, labelled as such.

use std::time::{Duration, Instant};

use rug::{Float, Rational};

pub use super::series_error::{ExactAnswerError, MAX_ORDER};
use super::{Answer, Arithmetic, ExactReason, Provenance, Value};
use crate::case::{parse_phase, Case, CaseText};
use crate::decimal::printing::{Decimal, F64_MOST_DIGITS};
use crate::digits::agreement::{agreement_radius, verified_values, OutOfBudget, MAX_DIGITS};
use crate::exact::{closed_form_coefficient, partial_sums, series_coefficients, SeriesError};
use crate::phase::{decimal, ExactPhase, ReducedPhase};
use crate::real::{ParseRealError, Precision, Real};

/// Significant digits of W_N − W (a difference, read for its size).
const DIFFERENCE_DIGITS: u32 = 3;

/// Why the Iₙ are exactly 0 in phase with ρ ≤ 1, decided from the text.
pub fn vanishes_in_phase(rho: &str, phase: &str) -> bool {
    let rho = decimal(rho);
    ExactPhase::parse(phase).is_ok_and(|phase| phase.is_in_phase()) && rho.is_some_and(|rho| rho > 0 && rho <= 1)
}

/// ρ and φ checked: ρ a positive decimal, φ a phase within range.
fn checked_shape(rho: &str, phase: &str) -> Result<(Rational, ReducedPhase), ExactAnswerError> {
    let exact_rho = decimal(rho).ok_or_else(|| ExactAnswerError::Number {
        quantity: "ρ",
        source: ParseRealError { text: rho.to_string() },
    })?;
    Ok((exact_rho, ExactPhase::parse(phase)?.reduce()?))
}

/// The digits asked for (without, [`F64_MOST_DIGITS`]), checked in range.
fn digits_asked(digits: Option<u32>) -> Result<u32, ExactAnswerError> {
    let asked = digits.unwrap_or(F64_MOST_DIGITS);
    if asked == 0 || asked > MAX_DIGITS {
        return Err(ExactAnswerError::DigitsOutOfRange(asked));
    }
    Ok(asked)
}

/// An exact answer.
fn exact(reason: ExactReason, digits: Option<u32>) -> Answer {
    Answer {
        value: Value::zero(),
        segments: None,
        digits_requested: digits,
        provenance: Provenance::Exact(reason),
        method: None,
    }
}

/// An answer for `value` with `provenance`.
fn answer(value: Value, digits: Option<u32>, provenance: Provenance) -> Answer {
    Answer {
        value,
        segments: None,
        digits_requested: digits,
        provenance,
        method: None,
    }
}

/// Values by rigorous enclosure to `asked` digits where one can be had (`None` where it
/// cannot: feature `certified` off, or a comparison no precision decides).
type Enclosures = Option<(Vec<Interval>, u32)>;

/// The lower and upper end of an interval that contains a value.
type Interval = (Float, Float);

#[cfg(feature = "certified")]
fn enclosures<E: Into<ExactAnswerError>>(
    quantity: &'static str,
    asked: u32,
    must_decide: bool,
    started: Instant,
    budget: Duration,
    compute: impl Fn(Precision) -> Result<Vec<crate::ball::Ball>, E>,
) -> Result<Enclosures, ExactAnswerError> {
    use crate::digits::enclosure::series::{enclose, EnclosureError};
    match enclose(asked, must_decide, started + budget, compute) {
        Ok(enclosed) => Ok(Some((
            (0..enclosed.values.len()).map(|i| enclosed.bounds(i, asked)).collect(),
            enclosed.bits,
        ))),
        Err(EnclosureError::Input(error)) => Err(error.into()),
        Err(EnclosureError::BeyondRange) => Err(ExactAnswerError::BeyondRange { quantity }),
        Err(EnclosureError::OutOfTime { asked, reached }) => Err(ExactAnswerError::Unreached {
            quantity,
            asked,
            reached,
            seconds: started.elapsed().as_secs_f64(),
        }),
        Err(EnclosureError::Undecided { .. } | EnclosureError::TooWide { .. }) => Ok(None),
    }
}

/// Without ball arithmetic there are no enclosures.
#[cfg(not(feature = "certified"))]
fn no_enclosure<T>(_inputs: &T) -> Enclosures {
    None
}

/// The values of `compute` to `asked` digits by two precisions' agreement (not proof).
fn agreed(
    asked: u32,
    deadline: Instant,
    compute: impl FnMut(Precision) -> Result<Vec<Float>, ExactAnswerError>,
) -> Result<(Vec<Interval>, u32), ExactAnswerError> {
    let verified = verified_values(asked, deadline, compute)?;
    let intervals = verified
        .output
        .iter()
        .zip(&verified.first)
        .map(|(second, first)| {
            let radius = agreement_radius(first, second);
            (
                Float::with_val(second.prec() + 64, second - &radius),
                Float::with_val(second.prec() + 64, second + &radius),
            )
        })
        .collect();
    Ok((intervals, verified.precision.in_bits()))
}

/// Answers from intervals: certified (`proven`) or agreed, at `bits`.
fn interval_answers(
    intervals: &[(Float, Float)],
    bits: u32,
    proven: bool,
    digits: Option<u32>,
    asked: u32,
) -> Vec<Answer> {
    let provenance = if proven {
        Provenance::Certified {
            bits,
            arithmetic: Arithmetic::ArbBalls,
        }
    } else {
        Provenance::Agreement { bits }
    };
    intervals
        .iter()
        .map(|(lower, upper)| answer(Value::within(lower, upper, asked), digits, provenance.clone()))
        .collect()
}

/// Certified answers where an enclosure was had, else agreed ones.
fn certified_or_agreed(
    asked: u32,
    digits: Option<u32>,
    deadline: Instant,
    enclosed: Enclosures,
    agree: impl FnMut(Precision) -> Result<Vec<Float>, ExactAnswerError>,
) -> Result<(Vec<Answer>, Vec<Interval>), ExactAnswerError> {
    let (intervals, bits, proven) = match enclosed {
        Some((intervals, bits)) => (intervals, bits, true),
        None => {
            let (intervals, bits) = agreed(asked, deadline, agree)?;
            (intervals, bits, false)
        }
    };
    Ok((interval_answers(&intervals, bits, proven, digits, asked), intervals))
}

/// Keeps the binary64 value computed beside an answer (the digits printed stay those of
/// the enclosure: f64 is only reported).
fn with_binary64(mut answer: Answer, value: Option<f64>) -> Answer {
    answer.value.binary64 = value.filter(|v| v.is_finite() && (*v == 0.0 || v.abs() >= f64::MIN_POSITIVE));
    answer
}

/// I(ρ, φ), what `microslip small-amplitude` prints: exact 0 in phase with ρ ≤ 1;
/// otherwise the closed form enclosed to `digits` (15 without) certified digits, with
/// I's binary64 value beside them where the run is without `digits`.
pub fn coefficient_answer(
    rho: &str,
    phase: &str,
    digits: Option<u32>,
    budget: Duration,
) -> Result<Answer, ExactAnswerError> {
    let started = Instant::now();
    let asked = digits_asked(digits)?;
    let (exact_rho, exact_phase) = checked_shape(rho, phase)?;
    if exact_rho <= 0 {
        return Err(ExactAnswerError::NonPositiveRatio(rho.to_string()));
    }
    // In phase with ρ ≤ 1 nothing slips; at ρ = 1 this is also the closed form's limit.
    if vanishes_in_phase(rho, phase) {
        return Ok(exact(ExactReason::NothingSlips, digits));
    }
    #[cfg(feature = "certified")]
    let enclosed = enclosures("I", asked, false, started, budget, |precision| {
        Ok::<_, ExactAnswerError>(vec![crate::digits::enclosure::series::coefficient_ball(
            rho,
            &exact_phase,
            precision,
        )])
    })?;
    #[cfg(not(feature = "certified"))]
    let enclosed = no_enclosure(&exact_phase);
    let (answers, _) = certified_or_agreed(asked, digits, started + budget, enclosed, |precision| {
        let (rho, phase) = read_shape::<Float>(rho, phase, precision)?;
        Ok(vec![closed_form_coefficient(&rho, &phase)])
    })?;
    let binary64 = digits
        .is_none()
        .then(|| read_shape::<f64>(rho, phase, Precision::DOUBLE).ok())
        .flatten()
        // + 0.0 turns a −0 from the formula into 0.
        .map(|(rho, phase)| closed_form_coefficient(&rho, &phase) + 0.0);
    Ok(with_binary64(answers.into_iter().next().expect("one value"), binary64))
}

/// ρ and φ's offset from the nearest multiple of π (the series has period π in φ), read
/// at a precision, for the agreement path and the binary64 values.
fn read_shape<R: Real>(rho: &str, phase: &str, precision: Precision) -> Result<(R, R), ExactAnswerError> {
    let rho_value =
        R::parse_decimal(rho, precision).map_err(|source| ExactAnswerError::Number { quantity: "ρ", source })?;
    if !(rho_value.is_finite() && rho_value > rho_value.int(0)) {
        return Err(ExactAnswerError::NonPositiveRatio(rho.to_string()));
    }
    let (offset, _) = parse_phase(phase, precision)?;
    Ok((rho_value, offset))
}

/// I₁ … I_N at a precision (I₀ ≡ 0 is not computed).
fn coefficients_at<R: Real>(rho: &R, phase: &R, order: usize) -> Result<Vec<R>, ExactAnswerError> {
    let values = series_coefficients(rho, phase, order)?;
    Ok(values.into_iter().skip(1).map(|(value, _)| value).collect())
}

/// I₀ … I_`order` at (ρ, φ) given as text: I₀ exact (the constant-term theorem), every
/// Iₙ exact in phase with ρ ≤ 1, the others enclosed to `digits` (15 without) certified
/// digits, with their binary64 values beside them where the run is without `digits`.
pub fn coefficient_answers(
    rho: &str,
    phase: &str,
    order: usize,
    digits: Option<u32>,
    budget: Duration,
) -> Result<Vec<Answer>, ExactAnswerError> {
    if order == 0 || order > MAX_ORDER {
        return Err(ExactAnswerError::OrderOutOfRange(order));
    }
    let started = Instant::now();
    let asked = digits_asked(digits)?;
    let (exact_rho, exact_phase) = checked_shape(rho, phase)?;
    if exact_rho <= 0 {
        return Err(SeriesError::NonPositiveRatio {
            rho: f64::from_rational(&exact_rho, Precision::DOUBLE),
        }
        .into());
    }
    if vanishes_in_phase(rho, phase) {
        return Ok(vec![exact(ExactReason::NothingSlips, digits); order + 1]);
    }
    #[cfg(feature = "certified")]
    let enclosed = enclosures("Iₙ", asked, true, started, budget, |precision| {
        crate::digits::enclosure::series::coefficient_balls(rho, &exact_phase, order, precision)
    })?;
    #[cfg(not(feature = "certified"))]
    let enclosed = no_enclosure(&exact_phase);
    let (computed, _) = certified_or_agreed(asked, digits, started + budget, enclosed, |precision| {
        let (rho, phase) = read_shape::<Float>(rho, phase, precision)?;
        coefficients_at(&rho, &phase, order)
    })?;
    let in_f64 = digits
        .is_none()
        .then(|| read_shape::<f64>(rho, phase, Precision::DOUBLE).ok())
        .flatten()
        .and_then(|(rho, phase)| coefficients_at(&rho, &phase, order).ok());
    let mut answers = vec![exact(ExactReason::ConstantTerm, digits)];
    for (n, computed) in computed.into_iter().enumerate() {
        answers.push(with_binary64(computed, in_f64.as_ref().map(|values| values[n])));
    }
    Ok(answers)
}

/// The partial sums W_N (N = 1 … order) of a case beside its W.
#[derive(Clone, Debug, PartialEq)]
pub struct PartialSums {
    /// W, from the four-segment path (or exact by reason).
    pub dissipation: Answer,
    /// W_N at index N − 1.
    pub sums: Vec<Answer>,
    /// W_N − W at index N − 1.
    pub differences: Vec<Answer>,
}

/// W as an [`Answer`], by the one policy for W ([`crate::answer::dissipation`]).
fn dissipation_answer(case: &CaseText, digits: Option<u32>, budget: Duration) -> Result<Answer, ExactAnswerError> {
    Ok(crate::answer::dissipation::dissipation_answer(case, digits, budget)?)
}

/// W_N − W from their intervals, with the weaker provenance of the two.
fn difference(sum: &Answer, sum_interval: &Interval, w: &Answer, digits: Option<u32>) -> Answer {
    let bound = |text: &str| Float::parse(text).map(|parsed| Float::with_val(sum_interval.0.prec(), parsed));
    let interval = w
        .value
        .enclosure
        .as_ref()
        .and_then(|(lower, upper)| Some((bound(lower).ok()?, bound(upper).ok()?)));
    let Some((w_lower, w_upper)) = interval else {
        let unknown = Value {
            decimal: Decimal::Undetermined {
                lower: "-inf".to_string(),
                upper: "inf".to_string(),
            },
            enclosure: None,
            binary64: None,
        };
        return answer(unknown, digits, w.provenance.clone());
    };
    let lower = Float::with_val_round(
        sum_interval.0.prec(),
        &sum_interval.0 - &w_upper,
        rug::float::Round::Down,
    )
    .0;
    let upper = Float::with_val_round(sum_interval.1.prec(), &sum_interval.1 - &w_lower, rug::float::Round::Up).0;
    let provenance = if w.provenance.is_proven() {
        sum.provenance.clone()
    } else {
        w.provenance.clone()
    };
    answer(Value::within(&lower, &upper, DIFFERENCE_DIGITS), digits, provenance)
}

/// The series of a case summed to orders 1 … `order`, each partial sum to `digits`
/// certified digits (15 without), beside W. Where W is exactly 0 (v'' ≡ 0, Q1 = 0, in
/// phase with nothing slipping) every W_N and difference is too, and where v' is a
/// polynomial of degree d, W_N − W = 0 exactly from N = d on.
pub fn partial_sum_answers(
    case: &CaseText,
    order: usize,
    digits: Option<u32>,
    budget: Duration,
) -> Result<PartialSums, ExactAnswerError> {
    if order == 0 || order > MAX_ORDER {
        return Err(ExactAnswerError::OrderOutOfRange(order));
    }
    let asked = digits_asked(digits)?;
    let started = Instant::now();
    let w = dissipation_answer(case, Some(asked), budget)?;
    let spec = case.spec()?;
    if let Provenance::Exact(reason) = w.provenance {
        return Ok(PartialSums {
            sums: vec![exact(reason, digits); order],
            differences: vec![exact(reason, digits); order],
            dissipation: w,
        });
    }
    #[cfg(feature = "certified")]
    let enclosed = enclosures("W_N", asked, true, started, budget, |precision| {
        let Case { cycle, compliance } = crate::digits::enclosure::series::case_balls(&spec, precision)?;
        Ok::<_, ExactAnswerError>(partial_sums(&cycle, compliance.as_ref(), order)?)
    })?;
    #[cfg(not(feature = "certified"))]
    let enclosed = no_enclosure(&spec);
    let (sums, intervals) = certified_or_agreed(asked, digits, started + budget, enclosed, |precision| {
        let Case { cycle, compliance } = spec.at::<Float>(precision)?;
        Ok(partial_sums(&cycle, compliance.as_ref(), order)?)
    })
    .map_err(|error| match error {
        // Running out, the sums report the whole run's time.
        ExactAnswerError::OutOfTime(out) => ExactAnswerError::OutOfTime(OutOfBudget {
            seconds: started.elapsed().as_secs_f64(),
            ..out
        }),
        other => other,
    })?;
    let degree = spec.compliance().slope_polynomial_degree();
    let differences = sums
        .iter()
        .zip(&intervals)
        .enumerate()
        .map(|(index, (sum, interval))| {
            if degree.is_some_and(|degree| degree <= index + 1) {
                exact(ExactReason::SeriesEnds, digits)
            } else {
                difference(sum, interval, &w, digits)
            }
        })
        .collect();
    Ok(PartialSums {
        dissipation: w,
        sums,
        differences,
    })
}
