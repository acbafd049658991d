//! The enclosure of W from its pieces, one copy for every rung's number type
//! ([`Enclosing`]): the cycle's geometry and the pieces come from the generic code of
//! the f64 path; every comparison it makes must be decided, or the attempt is refused;
//! each piece's integral is enclosed by the rung's own rule to an absolute tolerance
//! scaled by a rough W; W is λ times the sum of the pieces.

use std::cell::Cell;
use std::rc::Rc;

use super::enclosing::{CertifiedPiece, Enclosing};
use super::{CertifiedError, Enclosure};
use crate::compliance::{Compliance, SlopeChange};
use crate::cycle::{CycleKind, EllipseGeometry, LoadCycle, ValidCycle};
use crate::dissipation::closed_forms::{
    constant_normal_load_segments, constant_normal_load_term, in_phase_segments, in_phase_terms, weighted_pieces,
};
use crate::dissipation::slope::knot_offsets;
use crate::dissipation::{Segment, SegmentIntegrands, Segments, SlopeBetween, SlopesAtLoads, NEAR_SEPARATION};
use crate::doubts::{watch, Doubts};
use crate::quad::Piece;
use crate::real::Precision;

/// W for `cycle` and `compliance`, enclosed at the precision of the inputs' balls, with
/// Arb aiming at `goal_bits` relative accuracy per piece.
pub fn enclose_dissipation<R: Enclosing>(
    cycle: &LoadCycle<R>,
    compliance: &dyn Compliance<R>,
    goal_bits: u32,
) -> Result<Enclosure<R>, CertifiedError> {
    enclose_dissipation_with_lowest_load(cycle, None, compliance, goal_bits)
}

/// [`enclose_dissipation`], with the lowest normal load P0 − P1 enclosed by the caller
/// (read exactly from the decimals) where given: near separation the loads at the bottom
/// of the cycle are formed from it ([`EllipseGeometry::with_lowest_normal_load`]), which
/// the difference of the rounded P0 and P1 would widen P0/(P0 − P1)-fold. Given, it also
/// asks for the forms that keep the digits of a precision that cannot be raised (f64
/// intervals): the slip loads apart and the low loads from the lowest load, near
/// separation or where the slip terms cancel (`SlopesAtLoads`); the Arb ladder, which
/// raises its precision instead, keeps the cheaper segment formulas.
pub fn enclose_dissipation_with_lowest_load<R: Enclosing>(
    cycle: &LoadCycle<R>,
    lowest_normal_load: Option<&R>,
    compliance: &dyn Compliance<R>,
    goal_bits: u32,
) -> Result<Enclosure<R>, CertifiedError> {
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
        CycleKind::Elliptic => enclose_segments(&valid, lowest_normal_load, compliance, goal_bits)?,
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
fn decay_folds<R: Enclosing>(cycle: &LoadCycle<R>, compliance: &dyn Compliance<R>) -> Option<f64> {
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
fn slopes<'a, R: Enclosing>(
    compliance: &'a dyn Compliance<R>,
    mean_load: &R,
    bits: u32,
) -> Result<Vec<SlopeChange<'a, R>>, CertifiedError> {
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
fn bounding_slope<'s, R: Enclosing>(
    slopes: &'s [SlopeChange<'_, R>],
    at_mean: Option<R>,
    bits: u32,
) -> impl Fn(&R) -> R + Send + Sync + 's {
    let plain = slopes.last().expect("the plain difference is always tried");
    let own = at_mean
        .filter(|_| slopes.len() > 1)
        .map(|at_mean| (&slopes[0], at_mean));
    let floor = ROUNDING_MARGIN_BITS - i64::from(bits);
    move |offset: &R| {
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
fn integrand_ceiling<R: Enclosing>(geometry: &EllipseGeometry<R>, slope: &(dyn Fn(&R) -> R + Send + Sync)) -> R {
    let largest_change = slope(&geometry.permanent_stick_offset)
        .abs()
        .max_of(&slope(&geometry.normal_amplitude).abs());
    let rates = geometry.friction.clone() * &geometry.normal_amplitude
        + &geometry.tangential_amplitude
        + &geometry.sum_amplitude;
    largest_change * &geometry.tangential_amplitude * &rates
}

/// The four segments of an elliptic cycle per unit λ, and how many pieces they took.
fn enclose_segments<R: Enclosing>(
    valid: &ValidCycle<R>,
    lowest_normal_load: Option<&R>,
    compliance: &dyn Compliance<R>,
    goal_bits: u32,
) -> Result<(Segments<R>, usize), CertifiedError> {
    let bits = valid.mean_normal_load.precision().in_bits();
    let (geometry, doubts) = watch(|| match lowest_normal_load {
        Some(lowest) => valid.geometry().with_lowest_normal_load(lowest.clone()),
        None => valid.geometry(),
    });
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
    let at_loads = if lowest_normal_load.is_some() && loads_apart(valid, &geometry) {
        Some(slopes_at_loads(
            compliance,
            &geometry.mean_normal_load,
            slopes.len() > 1,
            bits,
        )?)
    } else {
        None
    };
    for slope in &slopes {
        let (pieces, doubts) =
            watch(|| certified_pieces(&integrands, slope.as_ref(), &bound_slope, &at_bottom, at_loads.as_ref()));
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
fn enclose_terms<R: Enclosing, const N: usize>(
    cycle: &LoadCycle<R>,
    compliance: &dyn Compliance<R>,
    terms: [Piece<'static, R>; N],
    goal_bits: u32,
) -> Result<([R; N], usize), CertifiedError> {
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
        let terms: [Piece<'_, R>; N] = std::array::from_fn(|term| {
            let weight = Rc::clone(&weights[term]);
            Piece::new(weight.label, weight.start.clone(), weight.end.clone(), move |x: &R| {
                (weight.integrand)(x)
            })
        });
        let ((pieces, term_of_piece), doubts) = watch(|| weighted_pieces(terms, Rc::clone(&slope), &knots));
        if !doubts.none() {
            return Err(undecided(bits, doubts));
        }
        let decay_load = compliance.decay_load();
        let pieces: Vec<CertifiedPiece<'_, R>> = pieces
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
                        integrand: Box::new(move |x: &R| integrand(x)),
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
fn cut_from_low_end<R: Enclosing>(start: &R, end: &R, decay_load: &R) -> Vec<(R, R)> {
    let (from, to) = (start.to_f64_lossy(), end.to_f64_lossy());
    // The last cut lies at most a quarter of the length from ℓ: decided by doubles, no
    // comparison of balls is needed to keep the cuts inside and in order.
    let cuts = ((to - from).abs() / decay_load.to_f64_lossy()).log2().floor() - 2.0;
    if cuts.is_nan() || cuts < 1.0 {
        return vec![(start.clone(), end.clone())];
    }
    let low = if from < to { start } else { end };
    let mut points: Vec<R> = (0..cuts.min(f64::from(i32::MAX)) as i32)
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
pub(super) fn bottom_slope_change<'a, R: Enclosing>(
    compliance: &'a dyn Compliance<R>,
    geometry: &EllipseGeometry<R>,
) -> Box<dyn Fn(&R) -> R + Send + Sync + 'a> {
    let lowest = geometry.lowest_normal_load.clone();
    let at_mean = compliance.slope(&geometry.mean_normal_load);
    Box::new(move |root: &R| compliance.slope_at_scaled_square(&lowest, root) - &at_mean)
}

/// x ↦ v'(P0 + x) − v'(P0) as the difference of two slopes.
pub(super) fn difference_of_slopes<'a, R: Enclosing>(
    compliance: &'a dyn Compliance<R>,
    mean_load: &R,
) -> SlopeChange<'a, R> {
    let (mean_load, at_load) = (mean_load.clone(), change_at_load(compliance, mean_load));
    Box::new(move |offset: &R| at_load(&(mean_load.clone() + offset)))
}

/// Whether the integrands take the slip loads apart and the low loads from the lowest
/// load ([`SlopesAtLoads`]): near separation (P0 − P1 below P1/[`NEAR_SEPARATION`]), where
/// the loads at the bottom of the cycle need it, and where the slip terms cancel by more
/// than [`SLIP_CANCELLATION`]. Elsewhere the segment formulas lose no digit that matters
/// and are cheaper to evaluate. Decided by doubles: both forms are the same function.
fn loads_apart<R: Enclosing>(valid: &ValidCycle<R>, geometry: &EllipseGeometry<R>) -> bool {
    let lowest = geometry.lowest_normal_load.to_f64_lossy();
    let near_separation = lowest * NEAR_SEPARATION as f64 <= geometry.normal_amplitude.to_f64_lossy();
    near_separation || valid.cancellation_amplification().to_f64_lossy() > SLIP_CANCELLATION
}

/// The cancellation of the slip terms ([`crate::cycle::LoadCycle::cancellation_amplification`])
/// beyond which the integrands take the slip loads apart away from separation: it costs
/// three of a double's sixteen digits there (proofs/printing.md, "Near separation in f64
/// intervals").
const SLIP_CANCELLATION: f64 = 1e3;

/// The slope change at loads given themselves ([`SlopesAtLoads`]): v'(L + x) − v'(L) by
/// the compliance's own form where `own_form` (its form about P0 decided all it asks, see
/// [`slopes`]), else as a plain difference.
fn slopes_at_loads<'a, R: Enclosing>(
    compliance: &'a dyn Compliance<R>,
    mean_load: &R,
    own_form: bool,
    bits: u32,
) -> Result<SlopesAtLoads<'a, R>, CertifiedError> {
    let (at_load, doubts) = watch(|| change_at_load(compliance, mean_load));
    if !doubts.none() {
        return Err(undecided(bits, doubts));
    }
    let between: SlopeBetween<'a, R> = if own_form {
        Box::new(move |load: &R, gap: &R| compliance.slope_change(load, gap))
    } else {
        Box::new(move |load: &R, gap: &R| compliance.slope(&(load.clone() + gap)) - &compliance.slope(load))
    };
    Ok(SlopesAtLoads { at_load, between })
}

/// P ↦ v'(P) − v'(P0), the slope change at a load given itself: at loads far below P0,
/// formed from the cycle's lowest loads, where P0 + x would lose them to the rounding of
/// P0 ([`crate::dissipation::segments`]).
fn change_at_load<'a, R: Enclosing>(compliance: &'a dyn Compliance<R>, mean_load: &R) -> SlopeChange<'a, R> {
    let at_mean = compliance.slope(mean_load);
    Box::new(move |load: &R| compliance.slope(load) - &at_mean)
}

/// The pieces' enclosures summed per group (a segment, or a closed form's term), and
/// how many pieces there were.
pub(super) fn integrate_pieces<R: Enclosing>(
    pieces: &[CertifiedPiece<'_, R>],
    groups: usize,
    goal_bits: u32,
    bits: u32,
    ceiling: Option<&R>,
) -> Result<(Vec<R>, usize), CertifiedError> {
    let zero = R::from_i64(0, Precision::bits(bits));
    let mut sums = vec![zero.clone(); groups];
    let tolerance = absolute_tolerance(pieces, goal_bits, &zero, ceiling);
    for piece in pieces {
        let value = R::integrate_piece(piece, goal_bits, &tolerance, bits);
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

/// The pieces of the four segments, as [`SegmentIntegrands::pieces`] splits them (the
/// sinh map is analytic on complex balls: Arb's sinh and cosh).
fn certified_pieces<'a, R: Enclosing>(
    integrands: &SegmentIntegrands<'a, R>,
    slope: &'a (dyn Fn(&R) -> R + Send + Sync + 'a),
    bound_slope: &'a (dyn Fn(&R) -> R + Send + Sync + 'a),
    at_bottom: &'a (dyn Fn(&R) -> R + Send + Sync + 'a),
    at_loads: Option<&'a SlopesAtLoads<'a, R>>,
) -> Vec<CertifiedPiece<'a, R>> {
    integrands
        .plans()
        .into_iter()
        .map(|plan| CertifiedPiece {
            group: segment_index(plan.segment),
            label: plan.segment.name(),
            integrand: integrands.plan_integrand_at_bottom(
                plan.segment,
                plan.map.clone(),
                slope,
                None::<fn(&R) -> R>,
                at_loads,
            ),
            bound: Some(integrands.plan_integrand_at_bottom(
                plan.segment,
                plan.map,
                bound_slope,
                Some(at_bottom),
                None,
            )),
            evaluations: Cell::new(0),
            start: plan.start,
            end: plan.end,
        })
        .collect()
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
fn absolute_tolerance<R: Enclosing>(
    pieces: &[CertifiedPiece<'_, R>],
    goal_bits: u32,
    zero: &R,
    ceiling: Option<&R>,
) -> R::Tolerance {
    let rough = |estimate: &dyn Fn(&CertifiedPiece<'_, R>) -> Option<R>| {
        pieces
            .iter()
            .try_fold(zero.clone(), |sum, piece| Some(sum + &estimate(piece)?))
            .filter(R::is_finite)
    };
    let mut scale = rough(&|piece| piece.rough_integral());
    if let (Some(estimate), Some(ceiling)) = (&scale, ceiling) {
        if estimate.is_below_scaled(ceiling, -MISSED_PEAK_BITS) {
            scale = rough(&|piece| piece.rough_integral_with_ends()).or(scale);
        }
    }
    R::tolerance(scale.as_ref(), goal_bits)
}

/// How far below the integrands' ceiling a rough W must lie to be suspected of a missed
/// peak ([`absolute_tolerance`]).
const MISSED_PEAK_BITS: i64 = 30;
