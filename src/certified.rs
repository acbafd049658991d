//! Certified W: the four segment integrals as rigorous enclosures of the exact input's
//! value (proofs/certified-digits.md).
//!
//! The cycle's geometry, the break points and the peaks of the integrands come from the
//! same generic code that runs in f64 and MPFR, here on Arb balls ([`Ball`]); every
//! comparison that code makes must be decided, or the attempt is refused. Each piece
//! (a segment split at its lowest loads and knots, narrow peaks mapped by s = c + w·sinh u)
//! is integrated by Gauss–Legendre rules whose error is bounded by the integrand's size
//! on a complex ball around the piece (Arb's bound: `ball_gauss` at the fewest
//! points it allows, Arb's `acb_calc_integrate` where that needs bisection); the
//! integrand is the generic one, evaluated on that ball with every function required to
//! be analytic there. W is λ times the sum of the piece enclosures.

use std::cell::Cell;
use std::ffi::{c_int, c_void};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::Instant;

use flint_sys::acb::{acb_get_mag, acb_indeterminate, acb_init};
use flint_sys::acb_calc::{acb_calc_integrate, acb_calc_integrate_opt_init, acb_calc_integrate_opt_struct};
use flint_sys::acb_types::acb_struct;
use flint_sys::arb_types::mag_struct;
use flint_sys::mag::{mag_clear, mag_init, mag_is_zero, mag_mul_2exp_si};

use crate::answer::{Decimal, Value};
use crate::ball::{watch, with_analytic, Ball, Doubts};
use crate::ball_gauss;
use std::rc::Rc;

use crate::compliance::{Compliance, SlopeChange};
use crate::cycle::{CycleError, CycleKind, EllipseGeometry, LoadCycle, ValidCycle};
use crate::dissipation::closed_forms::{
    constant_normal_load_segments, constant_normal_load_term, in_phase_segments, in_phase_terms, weighted_pieces,
};
use crate::dissipation::slope::knot_offsets;
use crate::dissipation::{Segment, SegmentIntegrands, Segments, NEAR_SEPARATION};
use crate::ladder::{doubled, Ladder, Rung, Stop};
use crate::phase::ReducedPhase;
use crate::quad::Piece;
use crate::real::{Precision, Real};
use rug::{Float, Rational};

/// W and its segments as balls that contain the exact values.
#[derive(Clone, Debug)]
pub struct Enclosure {
    /// W.
    pub total: Ball,
    /// ∫ (Q − Q0) du per segment, with u from v' − v'(P0), times λ.
    pub segments: Segments<Ball>,
    /// The working precision of the attempt that gave it.
    pub precision: Precision,
    /// How many pieces were integrated.
    pub pieces: usize,
    /// The kind of cycle, which chose the formula enclosed.
    pub kind: CycleKind,
}

/// W to a number of certified digits.
#[derive(Clone, Debug)]
pub struct Certified {
    /// The enclosure the digits come from.
    pub enclosure: Enclosure,
    /// W rounded to the digits every number in the enclosure rounds to.
    pub text: String,
    /// How many significant digits `text` has.
    pub digits: u32,
}

/// Why no enclosure (or none narrow enough) could be given.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CertifiedError {
    /// The cycle is not one the theory covers.
    #[error(transparent)]
    Cycle(#[from] CycleError),
    /// The case could not be built at a precision.
    #[error("the case could not be read at {bits} bits: {reason}")]
    Case {
        /// The working precision.
        bits: u32,
        /// Why the case could not be built.
        reason: String,
    },
    /// A comparison of the generic code was undecided on the input balls.
    #[error("at {bits} bits the cycle's geometry compares two numbers that overlap ({undecided} undecided comparisons); the input sits on a boundary between cases that no precision can resolve")]
    Undecided {
        /// The working precision.
        bits: u32,
        /// How many comparisons overlapped.
        undecided: u64,
    },
    /// A piece's enclosure is not finite (the integrand is singular on the piece, or
    /// Arb's subdivision gave up: an exponential at 10¹² decay loads whose bound on the
    /// boxes near its slip peak outgrows the evaluations allowed).
    #[error("at {bits} bits the {integral} integral has no finite enclosure: its integrand is not analytic on the piece [{start:.6e}, {end:.6e}], or grows there on the complex boxes around it faster than Arb's bisection resolves within its evaluations")]
    NotFinite {
        /// The working precision.
        bits: u32,
        /// The integral's name: a segment, or a closed form's term.
        integral: &'static str,
        /// The piece's first angle (or offset).
        start: f64,
        /// The piece's last angle.
        end: f64,
    },
    /// The enclosure stayed wider than asked at the largest precision tried.
    #[error("the enclosure of W reached only {reached} of the {asked} digits asked (relative radius {relative_radius:.2e} at {bits} bits)")]
    TooWide {
        /// The significant digits asked for.
        asked: u32,
        /// The significant digits the enclosure determines.
        reached: u32,
        /// The enclosure's radius relative to its midpoint (beyond f64's range at
        /// hundreds of digits).
        relative_radius: rug::Float,
        /// The largest working precision tried.
        bits: u32,
    },
    /// W lies beyond the decimal exponents printed ([`crate::ball::MOST_DECIMAL_BINARY_EXPONENT`]):
    /// e^(−P/c) at loads of 10¹⁸ decay loads c.
    #[error("W is enclosed but its size lies beyond 2^(±2^61) (10^(±6.9e17)), past the decimal exponents microslip prints: the case's loads are beyond 10^18 times the compliance's own load scale")]
    BeyondDecimalExponents,
    /// v' falls by more than e^[`MOST_DECAY_FOLDS`] across the cycle's loads: their span
    /// over the compliance's decay load (the exponential's c) is beyond what the bounds
    /// on complex boxes resolve at any precision.
    #[error("the compliance's v' falls by a factor of up to e^({folds:.1e}) across the cycle's loads (their span, at most 2·P1 + Q1/f, over its decay load); the enclosure resolves at most e^(1e13), so no digit of W can be vouched for: bring the loads within 10^13 decay loads of each other")]
    TooSteep {
        /// The span of the loads over the decay load.
        folds: f64,
    },
    /// The deadline passed, or would pass during the next attempt, before the enclosure
    /// was narrow enough.
    #[error("the time budget does not suffice: {reached} of the {asked} digits of W asked reached in {seconds:.1} s (working precision {bits} bits), and the next attempt would not end within the budget")]
    OutOfTime {
        /// The seconds spent.
        seconds: f64,
        /// The significant digits asked for.
        asked: u32,
        /// The significant digits the last enclosure determined.
        reached: u32,
        /// The working precision of the last attempt (the first, where none was run).
        bits: u32,
    },
}

/// The largest working precision [`certified_dissipation`] tries, in bits.
pub const MAX_BITS: u32 = 4096;

/// The working precision of the probe by which [`certified_dissipation_by`] foretells
/// the cost of a long first attempt, in bits.
const PROBE_BITS: u32 = 64;

/// Integrand evaluations Arb may spend on one piece, besides 16 per bit of precision
/// (an ordinary piece needs a few hundred).
const EVALUATION_LIMIT: i64 = 20_000;

/// W for `cycle` and `compliance`, enclosed at the precision of the inputs' balls, with
/// Arb aiming at `goal_bits` relative accuracy per piece.
pub fn enclose_dissipation(
    cycle: &LoadCycle<Ball>,
    compliance: &dyn Compliance<Ball>,
    goal_bits: u32,
) -> Result<Enclosure, CertifiedError> {
    let precision = cycle.mean_normal_load.precision();
    let bits = precision.in_bits();
    let (valid, doubts) = watch(|| ValidCycle::new(cycle.clone()));
    if !doubts.none() {
        return Err(undecided(bits, doubts));
    }
    let valid = valid?;
    if let Some(folds) = decay_folds(cycle, compliance).filter(|folds| folds.is_nan() || *folds > MOST_DECAY_FOLDS) {
        return Err(CertifiedError::TooSteep { folds });
    }
    let zero = cycle.mean_normal_load.int(0);
    let exact_zero = || Enclosure {
        total: zero.clone(),
        segments: Segments::from_fn(|_| zero.clone()),
        precision,
        pieces: 0,
        kind: valid.kind(),
    };
    let (sums, pieces) = match valid.kind() {
        // Q1 = 0 exactly: nothing slips back and forth, W = 0 exactly.
        CycleKind::NoTangentialOscillation => return Ok(exact_zero()),
        CycleKind::ConstantNormalLoad => {
            let term = constant_normal_load_term(cycle);
            let ([loop_integral], pieces) = enclose_terms(cycle, compliance, [term], goal_bits)?;
            (constant_normal_load_segments(cycle, loop_integral), pieces)
        }
        CycleKind::InPhase => {
            // Exactly in phase, Q1 ≤ fP1: the contact never slips, W = 0 exactly.
            let (terms, doubts) = watch(|| in_phase_terms(cycle));
            if !doubts.none() {
                return Err(undecided(bits, doubts));
            }
            let Some(terms) = terms else {
                return Ok(exact_zero());
            };
            let (integrals, pieces) = enclose_terms(cycle, compliance, terms, goal_bits)?;
            (in_phase_segments(cycle, integrals), pieces)
        }
        CycleKind::Elliptic => enclose_segments(&valid, compliance, goal_bits)?,
    };
    let lambda = &cycle.compliance_ratio;
    let segments = Segments::from_fn(|segment| sums.get(segment).clone() * lambda);
    let total = segments.total();
    Ok(Enclosure {
        total,
        segments,
        precision,
        pieces,
        kind: valid.kind(),
    })
}

/// The most e-folds of v' across a cycle's loads that [`enclose_dissipation`] takes on:
/// the bound of an integrand e^(−P/c) on a complex box grows as e^(width/c), and beyond
/// this the boxes it needs are too many to integrate (proofs/certified-digits.md, "Loads
/// of many decay loads").
pub const MOST_DECAY_FOLDS: f64 = 1e13;

/// How many times the compliance's decay load fits in the span of the loads v' is taken
/// at: from the lowest slip load P_T ≥ P0 − P1 − Q1/f up to P0 + P1, so at most
/// 2·P1 + Q1/f; `None` for a compliance without a decay load of its own.
fn decay_folds(cycle: &LoadCycle<Ball>, compliance: &dyn Compliance<Ball>) -> Option<f64> {
    let decay_load = compliance.decay_load()?;
    let span = cycle.normal_amplitude.clone() * &cycle.normal_amplitude.int(2)
        + &(cycle.tangential_amplitude.clone() / &cycle.friction);
    Some((span / &decay_load).to_f64_lossy())
}

/// The undecided comparisons of a computation, as the refusal at `bits`.
fn undecided(bits: u32, doubts: Doubts) -> CertifiedError {
    CertifiedError::Undecided {
        bits,
        undecided: doubts.undecided_comparisons + doubts.not_analytic,
    }
}

/// The slopes x ↦ v'(P0 + x) − v'(P0) to try, in turn: the compliance's own, free of
/// cancellation, where preparing it decides all it asks (a power law asks whether β is
/// a small rational, which a ball around −1/3 cannot answer); then the plain difference,
/// which is the same function and only loses the bits of v'(P0) that cancel.
fn slopes<'a>(
    compliance: &'a dyn Compliance<Ball>,
    mean_load: &Ball,
    bits: u32,
) -> Result<Vec<SlopeChange<'a, Ball>>, CertifiedError> {
    let (prepared, doubts) = watch(|| compliance.slope_change_about(mean_load));
    let mut attempts = vec![];
    if doubts.none() {
        attempts.push(prepared);
    }
    let (difference, doubts) = watch(|| difference_of_slopes(compliance, mean_load));
    if !doubts.none() {
        return Err(undecided(bits, doubts));
    }
    attempts.push(difference);
    Ok(attempts)
}

/// How far (in bits) above the rounding of v'(P0) a plain difference of slopes must lie
/// to bound the slope change on its own.
const ROUNDING_MARGIN_BITS: i64 = 32;

/// The slope change x ↦ v'(P0 + x) − v'(P0) on complex balls, for Arb's bounds: the
/// plain difference of slopes (the last of `slopes`), whose width does not grow with
/// the algebra of a compliance's own form; but for a compliance with a decay load (whose
/// v'(P0) is `at_mean`), where that difference is lost in the rounding of v'(P0) — a
/// slope change far below v' itself, as for a·e^(−P/c) + d at loads of thousands of c —
/// the tighter of it and the compliance's own form (the first), both enclosures of the
/// same value.
fn bounding_slope<'s>(
    slopes: &'s [SlopeChange<'_, Ball>],
    at_mean: Option<Ball>,
    bits: u32,
) -> impl Fn(&Ball) -> Ball + Send + Sync + 's {
    let plain = slopes.last().expect("the plain difference is always tried");
    let own = at_mean
        .filter(|_| slopes.len() > 1)
        .map(|at_mean| (&slopes[0], at_mean));
    let floor = ROUNDING_MARGIN_BITS - i64::from(bits);
    move |offset: &Ball| {
        let bound = plain(offset);
        match &own {
            Some((own, at_mean)) if bound.is_below_scaled(at_mean, floor) => bound.tighter(own(offset)),
            _ => bound,
        }
    }
}

/// A size that no segment integrand exceeds by much: the largest |v'(P) − v'(P0)| over
/// the cycle's loads (at P_T or at P0 + P1, v' being monotone) times Q1 and the largest
/// rates of slip, fP1 + Q1 + σ₊.
fn integrand_ceiling(geometry: &EllipseGeometry<Ball>, slope: &(dyn Fn(&Ball) -> Ball + Send + Sync)) -> Ball {
    let largest_change = slope(&geometry.permanent_stick_offset)
        .abs()
        .max_of(&slope(&geometry.normal_amplitude).abs());
    let rates = geometry.friction.clone() * &geometry.normal_amplitude
        + &geometry.tangential_amplitude
        + &geometry.sum_amplitude;
    largest_change * &geometry.tangential_amplitude * &rates
}

/// The four segments of an elliptic cycle per unit λ, and how many pieces they took.
fn enclose_segments(
    valid: &ValidCycle<Ball>,
    compliance: &dyn Compliance<Ball>,
    goal_bits: u32,
) -> Result<(Segments<Ball>, usize), CertifiedError> {
    let bits = valid.mean_normal_load.precision().in_bits();
    let (geometry, doubts) = watch(|| valid.geometry());
    if !doubts.none() {
        return Err(undecided(bits, doubts));
    }
    let integrands = SegmentIntegrands {
        geometry: &geometry,
        compliance,
        remove_constant_slope: true,
    };
    let mut outcome = None;
    let slopes = slopes(compliance, &geometry.mean_normal_load, bits)?;
    // Only a compliance with a decay load of its own has slope changes far below the
    // rounding of v'(P0), and peaks the rough W can miss; the others keep the plain bound.
    let at_mean = match compliance.decay_load() {
        Some(_) => {
            let (at_mean, doubts) = watch(|| compliance.slope(&geometry.mean_normal_load));
            if !doubts.none() {
                return Err(undecided(bits, doubts));
            }
            Some(at_mean)
        }
        None => None,
    };
    let ceiling = at_mean
        .is_some()
        .then(|| watch(|| integrand_ceiling(&geometry, slopes[0].as_ref())))
        .and_then(|(ceiling, doubts)| doubts.none().then_some(ceiling));
    let bound_slope = bounding_slope(&slopes, at_mean, bits);
    // Near separation, the same difference at the lowest load's bottom as a product.
    let (at_bottom, doubts) = watch(|| bottom_slope_change(compliance, &geometry));
    if !doubts.none() {
        return Err(undecided(bits, doubts));
    }
    for slope in &slopes {
        let (pieces, doubts) = watch(|| certified_pieces(&integrands, slope.as_ref(), &bound_slope, &at_bottom));
        if !doubts.none() {
            return Err(undecided(bits, doubts));
        }
        outcome = Some(integrate_pieces(
            &pieces,
            Segment::ALL.len(),
            goal_bits,
            bits,
            ceiling.as_ref(),
        ));
        if matches!(outcome, Some(Ok(_))) {
            break;
        }
    }
    let (sums, pieces) = outcome.expect("one slope at least")?;
    Ok((
        Segments::from_fn(|segment| sums[segment_index(segment)].clone()),
        pieces,
    ))
}

/// A closed form's weighted integrals ∫ w(x) v'(P0 + x) dx (each split at the
/// compliance's knots), enclosed; and how many pieces they took.
fn enclose_terms<const N: usize>(
    cycle: &LoadCycle<Ball>,
    compliance: &dyn Compliance<Ball>,
    terms: [Piece<'static, Ball>; N],
    goal_bits: u32,
) -> Result<([Ball; N], usize), CertifiedError> {
    let bits = cycle.mean_normal_load.precision().in_bits();
    let mean_load = &cycle.mean_normal_load;
    let (knots, doubts) = watch(|| knot_offsets(compliance, mean_load));
    if !doubts.none() {
        return Err(undecided(bits, doubts));
    }
    // The weights are kept apart from the slope so that each slope can be tried.
    let weights: Vec<_> = terms.into_iter().map(Rc::new).collect();
    let mut outcome = None;
    for slope in slopes(compliance, mean_load, bits)? {
        let slope = Rc::new(slope);
        let terms: [Piece<'_, Ball>; N] = std::array::from_fn(|term| {
            let weight = Rc::clone(&weights[term]);
            Piece::new(
                weight.label,
                weight.start.clone(),
                weight.end.clone(),
                move |x: &Ball| (weight.integrand)(x),
            )
        });
        let ((pieces, term_of_piece), doubts) = watch(|| weighted_pieces(terms, Rc::clone(&slope), &knots));
        if !doubts.none() {
            return Err(undecided(bits, doubts));
        }
        let decay_load = compliance.decay_load();
        let pieces: Vec<CertifiedPiece<'_>> = pieces
            .into_iter()
            .zip(term_of_piece)
            .flat_map(|(piece, term)| {
                let parts = match &decay_load {
                    Some(decay_load) => cut_from_low_end(&piece.start, &piece.end, decay_load),
                    None => vec![(piece.start.clone(), piece.end.clone())],
                };
                let integrand = Rc::new(piece.integrand);
                parts.into_iter().map(move |(start, end)| {
                    let integrand = Rc::clone(&integrand);
                    CertifiedPiece {
                        group: term,
                        label: piece.label,
                        start,
                        end,
                        integrand: Box::new(move |x: &Ball| integrand(x)),
                        bound: None,
                        evaluations: Cell::new(0),
                    }
                })
            })
            .collect();
        outcome = Some(integrate_pieces(&pieces, N, goal_bits, bits, None));
        if matches!(outcome, Some(Ok(_))) {
            break;
        }
    }
    let (sums, pieces) = outcome.expect("one slope at least")?;
    let mut sums = sums.into_iter();
    Ok((std::array::from_fn(|_| sums.next().expect("one sum per term")), pieces))
}

/// [`start`, `end`] (in either order) cut at ℓ + c·2^k, k = 0, 1, …, strictly inside,
/// with ℓ its lower end and c the decay load: an integrand e^(−(x − ℓ)/c) varies over each
/// part's Bernstein ellipse (X = 2) by no more than over the part itself, where over one
/// piece of many decay loads its bound grows as e^(length/c).
fn cut_from_low_end(start: &Ball, end: &Ball, decay_load: &Ball) -> Vec<(Ball, Ball)> {
    let (from, to) = (start.to_f64_lossy(), end.to_f64_lossy());
    // The last cut lies at most a quarter of the length from ℓ: decided by doubles, no
    // comparison of balls is needed to keep the cuts inside and in order.
    let cuts = ((to - from).abs() / decay_load.to_f64_lossy()).log2().floor() - 2.0;
    if cuts.is_nan() || cuts < 1.0 {
        return vec![(start.clone(), end.clone())];
    }
    let low = if from < to { start } else { end };
    let mut points: Vec<Ball> = (0..cuts.min(f64::from(i32::MAX)) as i32)
        .map(|k| low.clone() + &decay_load.clone().times_power_of_two(k))
        .collect();
    if from > to {
        points.reverse();
    }
    points.insert(0, start.clone());
    points.push(end.clone());
    points
        .windows(2)
        .map(|pair| (pair[0].clone(), pair[1].clone()))
        .collect()
}

/// The position of a segment in [`Segment::ALL`].
fn segment_index(segment: Segment) -> usize {
    Segment::ALL
        .iter()
        .position(|s| *s == segment)
        .expect("every segment is listed")
}

/// cosh u ↦ v'(δ cosh²u) − v'(P0), with δ = P0 − P1 the lowest load: the difference of
/// slopes at the bottom of a cycle near separation (u the bottom map's variable), with the
/// load as a product ([`Compliance::slope_at_scaled_square`]), whose factor cosh u keeps
/// away from 0 on boxes where the sum P0 + x does not.
fn bottom_slope_change<'a>(
    compliance: &'a dyn Compliance<Ball>,
    geometry: &EllipseGeometry<Ball>,
) -> Box<dyn Fn(&Ball) -> Ball + Send + Sync + 'a> {
    let lowest = geometry.mean_normal_load.clone() - &geometry.normal_amplitude;
    let at_mean = compliance.slope(&geometry.mean_normal_load);
    Box::new(move |root: &Ball| compliance.slope_at_scaled_square(&lowest, root) - &at_mean)
}

/// x ↦ v'(P0 + x) − v'(P0) as the difference of two slopes.
fn difference_of_slopes<'a>(compliance: &'a dyn Compliance<Ball>, mean_load: &Ball) -> SlopeChange<'a, Ball> {
    let (mean_load, at_mean) = (mean_load.clone(), compliance.slope(mean_load));
    Box::new(move |offset: &Ball| compliance.slope(&(mean_load.clone() + offset)) - &at_mean)
}

/// The pieces' enclosures summed per group (a segment, or a closed form's term), and
/// how many pieces there were.
fn integrate_pieces(
    pieces: &[CertifiedPiece<'_>],
    groups: usize,
    goal_bits: u32,
    bits: u32,
    ceiling: Option<&Ball>,
) -> Result<(Vec<Ball>, usize), CertifiedError> {
    let mut sums = vec![Ball::from_i64(0, Precision::bits(bits)); groups];
    let zero = Ball::from_i64(0, Precision::bits(bits));
    let tolerance = absolute_tolerance(pieces, goal_bits, &zero, ceiling);
    for piece in pieces {
        let value = integrate_piece(piece, goal_bits, &tolerance, bits);
        if !value.is_finite() {
            return Err(CertifiedError::NotFinite {
                bits,
                integral: piece.label,
                start: piece.start.to_f64_lossy(),
                end: piece.end.to_f64_lossy(),
            });
        }
        sums[piece.group] += &value;
    }
    Ok((sums, pieces.len()))
}

/// W to `digits` certified significant digits: the case is built by `case` at rising
/// precisions (its decimals read as balls that contain them) until the enclosure of W
/// rounds to one `digits`-digit decimal, up to [`MAX_BITS`].
pub fn certified_dissipation<F>(case: F, digits: u32) -> Result<Certified, CertifiedError>
where
    F: Fn(Precision) -> Result<(LoadCycle<Ball>, Box<dyn Compliance<Ball>>), String>,
{
    certified_dissipation_by(case, digits, None)
}

/// [`certified_dissipation`] that starts no attempt after `deadline` (an attempt itself
/// cannot be interrupted): [`CertifiedError::OutOfTime`] then names the digits reached.
pub fn certified_dissipation_by<F>(case: F, digits: u32, deadline: Option<Instant>) -> Result<Certified, CertifiedError>
where
    F: Fn(Precision) -> Result<(LoadCycle<Ball>, Box<dyn Compliance<Ball>>), String>,
{
    let started_at = Instant::now();
    let digits = digits.max(1);
    let read = |bits| case(Precision::bits(bits)).map_err(|reason| CertifiedError::Case { bits, reason });
    // The digits' bits with guard bits for the rounding of the integrand and the sum of
    // the pieces (more near separation), and the bits that a phase near a multiple of π
    // costs, known before the first attempt, rounded up once to whole limbs. The case
    // read for them serves the first attempt where they cost no limb more.
    let digit_bits = Precision::decimal_digits(digits).in_bits();
    let likely = whole_limbs(digit_bits + GUARD_BITS);
    let mut first_read = Some(read(likely)?);
    let (extra, guard) = first_read.as_ref().map_or((0, GUARD_BITS), |(cycle, _)| {
        (phase_bits(cycle), separation_guard_bits(cycle).max(GUARD_BITS))
    });
    let first = whole_limbs(digit_bits + guard + extra);
    let out_of_time = || deadline.is_some_and(|deadline| Instant::now() >= deadline);
    // An attempt at twice the bits costs about four times the last: one that would end
    // past the deadline is not started.
    let mut first_cost = std::time::Duration::ZERO;
    if deadline.is_some_and(|deadline| needs_probe(first, deadline)) {
        // A probe at a low precision foretells the first attempt's cost (quadratic in the bits).
        let started = Instant::now();
        if let Ok((cycle, compliance)) = case(Precision::bits(PROBE_BITS)) {
            let _ = enclose_dissipation(&cycle, compliance.as_ref(), PROBE_BITS);
        }
        first_cost = started.elapsed() * (first / PROBE_BITS).pow(2);
    }
    let ladder = Ladder::new(Precision::bits(first), Precision::bits(MAX_BITS))
        .until(deadline)
        .foreseeing(4, first_cost);
    // The digits the last enclosure settled, and whether Arb gave up on a piece there.
    let (mut reached, mut gave_up_before) = (0, false);
    let rung = |precision: Precision| {
        let bits = precision.in_bits();
        let case = match first_read.take() {
            Some(case) if bits == likely => Ok(case),
            _ => read(bits),
        };
        let (cycle, compliance) = match case {
            Ok(case) => case,
            Err(error) => return Rung::Final(error),
        };
        // The digits' bits and [`GOAL_GUARD_BITS`] more (and the phase's), not the limb's
        // spare bits; a retry adds what the precision gained.
        let goal = (digit_bits + GOAL_GUARD_BITS + extra).min(first) + (bits - first);
        let error = match enclose_dissipation(&cycle, compliance.as_ref(), goal) {
            Ok(enclosure) if !enclosure.total.decimal_exponent_fits() => {
                return Rung::Final(CertifiedError::BeyondDecimalExponents);
            }
            Ok(enclosure) => {
                // The one printing rule decides the digits settled.
                let value = Value::of_ball(&enclosure.total, bits, digits);
                let settled = match value.decimal {
                    Decimal::Zero => digits,
                    _ => value.digits(),
                };
                // Digits that arrive after the deadline are out of time all the same.
                if settled >= digits && !out_of_time() {
                    return Rung::Reached(Certified {
                        enclosure,
                        text: value.decimal.to_string(),
                        digits: settled,
                    });
                }
                reached = settled;
                CertifiedError::TooWide {
                    asked: digits,
                    reached,
                    relative_radius: enclosure.total.relative_radius(),
                    bits,
                }
            }
            // A cycle outside the theory stays outside at any precision, and so does one
            // too steep for the bounds.
            Err(error @ (CertifiedError::Cycle(_) | CertifiedError::TooSteep { .. })) => return Rung::Final(error),
            // Arb gave up on a piece at two precisions in a row: its integrand has a
            // singularity too near the piece for bisection, which more bits do not move.
            Err(error @ CertifiedError::NotFinite { .. }) if gave_up_before => return Rung::Final(error),
            Err(error) => error,
        };
        gave_up_before = matches!(error, CertifiedError::NotFinite { .. });
        Rung::Short(error)
    };
    match ladder.climb(rung, doubled) {
        Ok((certified, _)) => Ok(certified),
        Err(Stop::Final(error) | Stop::Exhausted(error)) => Err(error),
        Err(Stop::OutOfTime { last_attempt, .. }) => Err(CertifiedError::OutOfTime {
            seconds: started_at.elapsed().as_secs_f64(),
            asked: digits,
            reached,
            // Where no attempt was run in time, the first one's precision.
            bits: last_attempt.map_or(first, Precision::in_bits),
        }),
    }
}

/// The bits a phase φ near a multiple of π costs beyond the digits asked: the angles of
/// the ellipse are resolved to about |sin φ| of a turn (log2(1/|sin φ|) bits), or, with
/// Q1 < fP1, where the segments, each of order one, cancel to W ∝ sin²φ
/// ([`LoadCycle::in_phase_cancellation`]), the bits of that cancellation, which are more.
/// Zero exactly in phase, which has no angles.
fn phase_bits(cycle: &LoadCycle<Ball>) -> u32 {
    // Only an estimate of a starting precision: undecided comparisons here do no harm.
    let ((sin, cancellation), _) = watch(|| (cycle.phase_trig().sin.abs(), cycle.in_phase_cancellation()));
    let log2 = |x: &Ball| x.ln().to_f64_lossy() / std::f64::consts::LN_2;
    let bits = log2(&cancellation).max(-log2(&sin));
    if bits.is_finite() && bits > 0.0 {
        (bits.ceil() as u32).min(MAX_BITS)
    } else {
        0
    }
}

/// The guard bits a cycle near separation needs in place of [`GUARD_BITS`]: the
/// integrands about the lowest load δ = P0 − P1 amplify the working precision's rounding
/// by about P1/δ, so an enclosure there is about log2(P1/δ) + 2 bits wider than the
/// working precision (proofs/certified-digits.md, "The first precision and the
/// halvings"), and 3 bits more let it round to the digits. Zero above the δ at which the
/// bottom map takes over (δ < P1/[`NEAR_SEPARATION`]); a cycle with P1 = 0 or δ ≤ 0
/// (refused later) costs nothing here.
fn separation_guard_bits(cycle: &LoadCycle<Ball>) -> u32 {
    // Only an estimate of a starting precision: undecided comparisons here do no harm.
    let ((amplitude, lowest), _) = watch(|| {
        let p1 = cycle.normal_amplitude.to_f64_lossy();
        (
            p1,
            (cycle.mean_normal_load.clone() - &cycle.normal_amplitude).to_f64_lossy(),
        )
    });
    let ratio = amplitude / lowest;
    if ratio.is_finite() && lowest > 0.0 && ratio > NEAR_SEPARATION as f64 {
        (ratio.log2().ceil() as u32 + 5).min(MAX_BITS)
    } else {
        0
    }
}

/// Bits a phase offset is computed with beyond the working precision and its exponent.
const PHASE_GUARD_BITS: u32 = 64;
/// The most bits the offset of a phase from its nearest multiple of π may need.
const MAX_PHASE_BITS: u32 = 1 << 22;

/// ψ = φ − nπ for the integer n nearest φ/π, as a ball that contains the exact ψ with
/// the working precision's relative accuracy, and whether n is odd. ψ lies in
/// (−π/2, π/2]; the cancellation of φ − nπ (`3.141592653589793` − π ≈ −1.2e−16) is paid
/// for with bits, and an offset from an integer multiple (`pi-1e-100`) is the exact
/// rational itself.
pub fn phase_offset(phase: &ReducedPhase, precision: Precision) -> (Ball, bool) {
    let (mut reverses, rest, offset) = phase.offset_parts();
    let mut rest = rest.clone();
    // ψ = −π/2 exactly is taken as π/2 (n − 1 in place of n): the generic code reads a
    // negative offset as one below π, and at −π/2 exactly it could not decide that.
    if rest == Rational::from((-1, 2)) && *offset == 0 {
        rest = Rational::from((1, 2));
        reverses = !reverses;
    }
    (enclose_pi_multiple(&rest, offset, precision), reverses)
}

/// A ball that contains mπ + x with the relative accuracy of `precision` (the working
/// bits are raised while x cancels mπ; it is not zero unless m = x = 0, π being
/// irrational), or as close to it as the largest working precision allowed (2²² bits) gives.
pub fn enclose_pi_multiple(multiple: &Rational, offset: &Rational, precision: Precision) -> Ball {
    if *multiple == 0 {
        return Ball::from_rational(offset, precision);
    }
    let exponent = (multiple.to_f64().abs() * std::f64::consts::PI + offset.to_f64().abs())
        .max(1.0)
        .log2()
        .ceil() as u32;
    let mut working = precision.in_bits() + exponent + PHASE_GUARD_BITS;
    loop {
        let at = Precision::bits(working);
        let psi = Ball::from_rational(multiple, at) * &Ball::pi(at) + &Ball::from_rational(offset, at);
        if relatively_within(&psi, precision.in_bits()) || working.saturating_mul(2) > MAX_PHASE_BITS {
            // SAFETY: `psi` is an initialised ball; the copy keeps its midpoint and radius.
            return unsafe { Ball::from_raw(psi.as_raw(), precision.in_bits()) };
        }
        working = working.saturating_mul(2);
    }
}

/// Whether the ball's width is at most 2^−`bits` of its smallest magnitude (a ball
/// that contains zero is not).
pub(crate) fn relatively_within(ball: &Ball, bits: u32) -> bool {
    let (lower, upper) = ball.bounds(ball.precision().in_bits() + 64);
    if lower.is_zero() || upper.is_zero() || lower.is_sign_negative() != upper.is_sign_negative() {
        return false;
    }
    let width = Float::with_val(64, &upper - &lower);
    let smallest = lower.get_exp().min(upper.get_exp()).unwrap_or(i32::MIN);
    width.is_zero() || i64::from(width.get_exp().unwrap_or(i32::MAX)) + i64::from(bits) < i64::from(smallest)
}

/// `bits` rounded up to whole 64-bit limbs: Arb works limb by limb, so the bits up to
/// the next limb cost nothing (15 digits and their guard bits fit one limb).
fn whole_limbs(bits: u32) -> u32 {
    bits.next_multiple_of(64)
}

/// The fewest guard bits of the first attempt.
const GUARD_BITS: u32 = 12;

/// The bits Arb aims at beyond the digits' own: the enclosure's radius then lies about
/// 2^−12 of a unit of the last digit below it, so that an enclosure straddles a rounding
/// boundary (and the next precision is tried) about once in a few thousand cases.
const GOAL_GUARD_BITS: u32 = 12;

/// Whether the cost of a first attempt at `bits` must be foretold by a probe before it
/// starts: where the time left before `deadline` holds it even at [`PROBE_HORIZON`] per
/// probe, quadratic in the bits, the probe (about a seventh of an ordinary attempt at
/// 100 digits) would be wasted.
fn needs_probe(bits: u32, deadline: Instant) -> bool {
    bits >= 4 * PROBE_BITS
        && deadline.saturating_duration_since(Instant::now()) < PROBE_HORIZON * (bits / PROBE_BITS).pow(2)
}

/// A pessimistic cost of one attempt at [`PROBE_BITS`] (an ordinary case takes about a
/// millisecond, one 10⁻⁶ from separation 0.2 s).
const PROBE_HORIZON: std::time::Duration = std::time::Duration::from_millis(100);

/// One integral of W: ∫ from `start` to `end` of `integrand`, summed into `group`.
struct CertifiedPiece<'a> {
    /// The segment's (or the closed form's term's) position.
    group: usize,
    /// Its name, for messages.
    label: &'static str,
    start: Ball,
    end: Ball,
    /// The integrand at real points, with the slope change formed without cancellation.
    integrand: PieceIntegrand<'a>,
    /// The same analytic function with the slope change as a plain difference of slopes,
    /// for Arb's bound on complex balls: the precision of a bound does not matter, its
    /// width does, and the algebraic forms of the slope change (a root raised to powers
    /// and divided) widen far more on a complex ball than one `acb_pow` does.
    /// `None` where the integrand serves for both.
    bound: Option<PieceIntegrand<'a>>,
    /// Integrand evaluations so far, against the piece's budget ([`evaluation_limit`]).
    evaluations: Cell<i64>,
}

type PieceIntegrand<'a> = Box<dyn Fn(&Ball) -> Ball + 'a>;

/// The pieces of the four segments, as [`SegmentIntegrands::pieces`] splits them (the
/// sinh map is analytic on complex balls: Arb's sinh and cosh).
fn certified_pieces<'a>(
    integrands: &SegmentIntegrands<'a, Ball>,
    slope: &'a (dyn Fn(&Ball) -> Ball + Send + Sync + 'a),
    bound_slope: &'a (dyn Fn(&Ball) -> Ball + Send + Sync + 'a),
    at_bottom: &'a (dyn Fn(&Ball) -> Ball + Send + Sync + 'a),
) -> Vec<CertifiedPiece<'a>> {
    integrands
        .plans()
        .into_iter()
        .map(|plan| CertifiedPiece {
            group: segment_index(plan.segment),
            label: plan.segment.name(),
            integrand: integrands.plan_integrand(plan.segment, plan.map.clone(), slope),
            bound: Some(integrands.plan_integrand_at_bottom(plan.segment, plan.map, bound_slope, Some(at_bottom))),
            evaluations: Cell::new(0),
            start: plan.start,
            end: plan.end,
        })
        .collect()
}

/// The integrand as Arb calls it: at `order` 0 an enclosure of f on the (real) ball,
/// at `order` 1 an enclosure on a complex ball where f must be holomorphic. An
/// evaluation that met an undecided comparison or a branch cut, or that panicked,
/// answers an indeterminate ball, which makes Arb subdivide or give a non-finite result.
unsafe extern "C" fn evaluate(
    out: *mut acb_struct,
    input: *const acb_struct,
    param: *mut c_void,
    order: i64,
    prec: i64,
) -> c_int {
    // SAFETY: `param` is the `&CertifiedPiece` passed by `integrate_piece`, alive for the call.
    let piece = unsafe { &*(param as *const CertifiedPiece<'_>) };
    let precision = prec.clamp(2, i64::from(u32::MAX)) as u32;
    // SAFETY: Arb passes an initialised ball it leaves alone during the call, and an
    // initialised ball `out` it owns.
    unsafe {
        match Ball::read_in_place(input, precision, |x| piece.value(x, order != 0)) {
            Some(value) => value.move_into(out),
            None => acb_indeterminate(out),
        }
    }
    0
}

impl CertifiedPiece<'_> {
    /// The integrand on `x` (required to be analytic there where `analytic`), or `None`
    /// where the evaluation met an undecided comparison or a branch cut, or panicked.
    fn value(&self, x: &Ball, analytic: bool) -> Option<Ball> {
        self.evaluations.set(self.evaluations.get() + 1);
        let integrand = match (&self.bound, analytic) {
            (Some(bound), true) => bound,
            _ => &self.integrand,
        };
        let outcome = catch_unwind(AssertUnwindSafe(|| watch(|| with_analytic(analytic, || integrand(x)))));
        match outcome {
            Ok((value, doubts)) if doubts.none() => Some(value),
            _ => None,
        }
    }

    /// A rough value of the integral (three-point Gauss–Legendre on the midpoints),
    /// only to scale the tolerance Arb aims at; `None` where an evaluation fails.
    fn rough_integral(&self) -> Option<Ball> {
        let half = (self.end.clone() - &self.start) / &self.start.int(2);
        let middle = self.start.clone() + &half;
        let offset = half.clone() * &(self.start.int(3) / &self.start.int(5)).sqrt();
        let mut sum = self.value(&middle, false)? * &self.start.int(8);
        for node in [middle.clone() - &offset, middle + &offset] {
            sum += self.value(&node, false)? * &self.start.int(5);
        }
        Some(sum * &half / &self.start.int(9))
    }

    /// A rough value of the integral that also sees the ends, where the pieces' narrow
    /// peaks lie (five-point Gauss–Lobatto); the three-point value where an end cannot
    /// be evaluated.
    fn rough_integral_with_ends(&self) -> Option<Ball> {
        let (Some(at_start), Some(at_end)) = (self.value(&self.start, false), self.value(&self.end, false)) else {
            return self.rough_integral();
        };
        let int = |n: i64| self.start.int(n);
        let half = (self.end.clone() - &self.start) / &int(2);
        let middle = self.start.clone() + &half;
        let offset = half.clone() * &(int(3) / &int(7)).sqrt();
        // Weights 1/10, 49/90, 32/45, 49/90, 1/10 on [−1, 1], over 90.
        let mut sum = (at_start + &at_end) * &int(9) + &(self.value(&middle, false)? * &int(64));
        for node in [middle.clone() - &offset, middle + &offset] {
            sum += self.value(&node, false)? * &int(49);
        }
        Some(sum * &half / &int(90))
    }
}

/// An absolute error Arb may stop at on a subinterval: 2^−goal of a rough W, so that a
/// piece whose integrand changes sign (its crude enclosure contains zero, and Arb's
/// relative goal alone would ask for every bit) stops where W needs no more. Any
/// tolerance keeps the enclosure rigorous; a rough W far too large only costs digits,
/// which the next precision recovers. Zero (the relative goal alone) where no rough W
/// is at hand. Where that W is below 2^−[`MISSED_PEAK_BITS`] of the integrands'
/// `ceiling`, a peak at a piece's end narrower than the three points' spacing may have
/// been missed (e^(−P/c) at loads of millions of c: the rough W is then smaller than W
/// by thousands of digits, and no precision could meet a tolerance scaled to it), and
/// a rough W that sees the ends replaces it.
fn absolute_tolerance(pieces: &[CertifiedPiece<'_>], goal_bits: u32, zero: &Ball, ceiling: Option<&Ball>) -> Tolerance {
    let rough = |estimate: &dyn Fn(&CertifiedPiece<'_>) -> Option<Ball>| {
        pieces
            .iter()
            .try_fold(zero.clone(), |sum, piece| Some(sum + &estimate(piece)?))
            .filter(Ball::is_finite)
    };
    let mut scale = rough(&|piece| piece.rough_integral());
    if let (Some(estimate), Some(ceiling)) = (&scale, ceiling) {
        if estimate.is_below_scaled(ceiling, -MISSED_PEAK_BITS) {
            scale = rough(&|piece| piece.rough_integral_with_ends()).or(scale);
        }
    }
    Tolerance::of(scale.as_ref(), goal_bits)
}

/// How far below the integrands' ceiling a rough W must lie to be suspected of a missed
/// peak ([`absolute_tolerance`]).
const MISSED_PEAK_BITS: i64 = 30;

/// An Arb magnitude (an upper bound of |x| times 2^−goal, or zero).
struct Tolerance(mag_struct);

impl Tolerance {
    fn of(scale: Option<&Ball>, goal_bits: u32) -> Tolerance {
        let mut magnitude = mag_struct::default();
        // SAFETY: initialised here, cleared on drop.
        unsafe {
            mag_init(&mut magnitude);
            if let Some(scale) = scale {
                acb_get_mag(&mut magnitude, scale.as_raw());
                mag_mul_2exp_si(&mut magnitude, &magnitude, -i64::from(goal_bits));
            }
        }
        Tolerance(magnitude)
    }
}

impl Drop for Tolerance {
    fn drop(&mut self) {
        // SAFETY: initialised in `of`.
        unsafe { mag_clear(&mut self.0) }
    }
}

/// The enclosure of one piece's integral at `bits` of working precision: Gauss–Legendre
/// rules at the fewest points their bounds allow (`ball_gauss`), Arb's adaptive
/// bisection on what they leave.
fn integrate_piece(piece: &CertifiedPiece<'_>, goal_bits: u32, tolerance: &Tolerance, bits: u32) -> Ball {
    let otherwise = |start: &Ball, end: &Ball| arb_bisection(piece, start, end, goal_bits, tolerance, bits);
    // SAFETY: an initialised magnitude.
    if unsafe { mag_is_zero(&tolerance.0) } != 0 {
        // Arb's relative goal alone: no rule of this module can meet a zero tolerance.
        return otherwise(&piece.start, &piece.end);
    }
    let rule = ball_gauss::Rule {
        integrand: &|x: &Ball, analytic: bool| piece.value(x, analytic),
        tolerance: &tolerance.0,
        // Arb's own limit on the degree.
        degree_limit: u64::from(goal_bits.min(bits) / 2 + 60),
        otherwise: &otherwise,
    };
    rule.integrate(&piece.start, &piece.end, ball_gauss::OWN_DEPTH)
}

/// The integrand evaluations a piece may spend at `bits`: Arb's default, 1000·prec +
/// prec², lets a piece that cannot be enclosed (an integrand undecided near a point) run
/// for minutes at high precision.
fn evaluation_limit(bits: u32) -> i64 {
    EVALUATION_LIMIT + 16 * i64::from(bits)
}

/// Arb's enclosure of the integral of a piece's integrand over [start, end] at `bits` of
/// working precision, within what is left of the piece's evaluations (not finite where
/// nothing is).
fn arb_bisection(
    piece: &CertifiedPiece<'_>,
    start: &Ball,
    end: &Ball,
    goal_bits: u32,
    tolerance: &Tolerance,
    bits: u32,
) -> Ball {
    let left = evaluation_limit(bits) - piece.evaluations.get();
    if left <= 0 {
        return start.indeterminate();
    }
    let mut raw = acb_struct::default();
    let mut options = acb_calc_integrate_opt_struct::default();
    // SAFETY: `raw` is initialised before use and passes to the returned ball; `param`
    // outlives the call.
    unsafe {
        acb_init(&mut raw);
        acb_calc_integrate_opt_init(&mut options);
        options.eval_limit = left;
        acb_calc_integrate(
            &mut raw,
            Some(evaluate),
            piece as *const CertifiedPiece<'_> as *mut c_void,
            start.as_raw(),
            end.as_raw(),
            i64::from(goal_bits),
            &tolerance.0,
            &options,
            i64::from(bits),
        );
    }
    Ball::wrap(raw, bits)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compliance::parse_spec;

    const BITS: u32 = 128;

    /// 1e−6 from separation, the bottom map's part u ∈ [2, 2.8] on the rectangle of the
    /// ellipse X = 2 as the rule bounds it (where δ cosh²u has no zero): the difference of
    /// slopes at P0 + x, x = P1(2t² sinh²u − 1) as the integrand forms it, has no finite
    /// bound (the box of 1 + sinh²u holds 0), while at δ·cosh²u it has; at real points the
    /// two forms enclose the same value.
    #[test]
    fn the_bottom_load_as_a_product_bounds_the_slope_change_where_its_offset_cannot() {
        let p = Precision::bits(BITS);
        let ball = |text: &str| Ball::parse_decimal(text, p).expect("a decimal");
        let (mean, amplitude) = (ball("1"), ball("0.999999"));
        let geometry = LoadCycle {
            mean_normal_load: mean.clone(),
            normal_amplitude: amplitude.clone(),
            mean_tangential_load: ball("0"),
            tangential_amplitude: ball("0.0005"),
            phase: mean.pi_like().times_power_of_two(-1),
            friction: ball("1"),
            compliance_ratio: ball("1"),
        }
        .geometry()
        .expect("a valid cycle");
        let scale = ((mean.clone() - &amplitude) / &amplitude).times_power_of_two(-1).sqrt();
        let offset_at = |u: &Ball| {
            let half_sin = scale.clone() * &u.sinh_cosh().0;
            amplitude.clone() * &(half_sin.square().times_power_of_two(1) - &u.int(1))
        };
        for spec in [
            "persson:gamma=1,sigma=1",
            "power:c=1,beta=-0.5",
            "hertz:r=1,estar=1",
            "2*persson:gamma=1,sigma=1+power:c=0.3,beta=-0.25",
        ] {
            let compliance = parse_spec::<Ball>(spec, p).expect("a SPEC");
            let by_offset = difference_of_slopes(compliance.as_ref(), &mean);
            let by_product = bottom_slope_change(compliance.as_ref(), &geometry);
            let rectangle = ball_gauss::Ellipse::new(2.0).around(&ball("2.4"), &ball("0.4"));
            let (offset_bound, product_bound) = with_analytic(true, || {
                (by_offset(&offset_at(&rectangle)), by_product(&rectangle.sinh_cosh().1))
            });
            assert!(!offset_bound.is_finite(), "{spec}: {offset_bound:?}");
            assert!(product_bound.is_finite(), "{spec}: {product_bound:?}");
            for u in ["0.2", "1.8", "3.4", "5.8"] {
                let u = ball(u);
                let difference = by_offset(&offset_at(&u)) - &by_product(&u.sinh_cosh().1);
                assert!(difference.contains_zero(), "{spec} at u = {u:?}: {difference:?}");
            }
        }
    }
}
