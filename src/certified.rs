//! Certified W: the four segment integrals as rigorous enclosures of the exact input's
//! value (proofs/certified-digits.md).
//!
//! The cycle's geometry, the break points and the peaks of the integrands come from the
//! same generic code that runs in f64 and MPFR, here on Arb balls ([`Ball`]); every
//! comparison that code makes must be decided, or the attempt is refused. Each piece
//! (a segment split at its lowest loads and knots, narrow peaks mapped by s = c + w·sinh u)
//! is integrated by Arb's `acb_calc_integrate`, which bounds the error of its
//! Gauss–Legendre rules by the integrand's size on a complex ball around the piece; the
//! integrand is the generic one, evaluated on that ball with every function required to
//! be analytic there. W is λ times the sum of the piece enclosures.

use std::ffi::{c_int, c_void};
use std::panic::{catch_unwind, AssertUnwindSafe};

use flint_sys::acb::{acb_indeterminate, acb_init, acb_set};
use flint_sys::acb_calc::{acb_calc_integrate, acb_calc_integrate_opt_init, acb_calc_integrate_opt_struct};
use flint_sys::acb_types::acb_struct;
use flint_sys::arb_types::mag_struct;
use flint_sys::mag::{mag_clear, mag_init};

use crate::ball::{certain_digits, watch, with_analytic, Ball, Doubts};
use crate::compliance::{Compliance, SlopeChange};
use crate::cycle::{CycleError, CycleKind, LoadCycle, ValidCycle};
use crate::dissipation::{Segment, SegmentIntegrands, Segments};
use crate::quad::sinh_map::resolve_peaks;
use crate::real::{Precision, Real};

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
    /// Arb's subdivision gave up).
    #[error("at {bits} bits the {segment} integral has no finite enclosure: its integrand is not analytic on the piece [{start:.6e}, {end:.6e}]")]
    NotFinite {
        /// The working precision.
        bits: u32,
        /// The segment whose integral it is.
        segment: Segment,
        /// The piece's first angle.
        start: f64,
        /// The piece's last angle.
        end: f64,
    },
    /// The enclosure stayed wider than asked at the largest precision tried.
    #[error("the enclosure of W reached only {reached} of the {asked} digits asked (relative radius {relative_radius:.1e} at {bits} bits)")]
    TooWide {
        /// The significant digits asked for.
        asked: u32,
        /// The significant digits the enclosure determines.
        reached: u32,
        /// The enclosure's radius relative to its midpoint.
        relative_radius: f64,
        /// The largest working precision tried.
        bits: u32,
    },
}

/// The largest working precision [`certified_dissipation`] tries, in bits.
pub const MAX_BITS: u32 = 4096;

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
    let refuse = |doubts: Doubts| CertifiedError::Undecided {
        bits,
        undecided: doubts.undecided_comparisons + doubts.not_analytic,
    };
    let (valid, doubts) = watch(|| ValidCycle::new(cycle.clone()));
    if !doubts.none() {
        return Err(refuse(doubts));
    }
    let valid = valid?;
    let zero = cycle.mean_normal_load.int(0);
    if valid.kind() == CycleKind::NoTangentialOscillation {
        // Q1 = 0 exactly: nothing slips back and forth, W = 0 exactly.
        return Ok(Enclosure {
            total: zero.clone(),
            segments: Segments::from_fn(|_| zero.clone()),
            precision,
            pieces: 0,
        });
    }
    let (geometry, doubts) = watch(|| valid.geometry());
    if !doubts.none() {
        return Err(refuse(doubts));
    }
    let integrands = SegmentIntegrands {
        geometry: &geometry,
        compliance,
        remove_constant_slope: true,
    };
    // The compliance's own v'(P0 + x) − v'(P0), free of cancellation, where preparing it
    // decides all it asks (a power law asks whether β is a small rational, which a ball
    // around −1/3 cannot answer); otherwise the plain difference, which is the same
    // function and only loses the bits of v'(P0) that cancel.
    let (prepared, doubts) = watch(|| integrands.prepared_slope());
    let mut attempts = vec![];
    if doubts.none() {
        attempts.push(prepared);
    }
    let (difference, doubts) = watch(|| difference_of_slopes(compliance, &geometry.mean_normal_load));
    if !doubts.none() {
        return Err(refuse(doubts));
    }
    attempts.push(difference);
    let mut outcome = None;
    for slope in &attempts {
        let (pieces, doubts) = watch(|| certified_pieces(&integrands, slope.as_ref()));
        if !doubts.none() {
            return Err(refuse(doubts));
        }
        outcome = Some(integrate_pieces(&pieces, goal_bits, bits, &zero));
        if matches!(outcome, Some(Ok(_))) {
            break;
        }
    }
    let (sums, pieces) = outcome.expect("one slope at least")?;
    let lambda = &cycle.compliance_ratio;
    let segments = Segments::from_fn(|segment| sums.get(segment).clone() * lambda);
    let total = segments.total();
    Ok(Enclosure {
        total,
        segments,
        precision,
        pieces,
    })
}

/// x ↦ v'(P0 + x) − v'(P0) as the difference of two slopes.
fn difference_of_slopes<'a>(compliance: &'a dyn Compliance<Ball>, mean_load: &Ball) -> SlopeChange<'a, Ball> {
    let (mean_load, at_mean) = (mean_load.clone(), compliance.slope(mean_load));
    Box::new(move |offset: &Ball| compliance.slope(&(mean_load.clone() + offset)) - &at_mean)
}

/// The pieces' enclosures summed per segment (per unit λ), and how many pieces there were.
fn integrate_pieces(
    pieces: &[CertifiedPiece<'_>],
    goal_bits: u32,
    bits: u32,
    zero: &Ball,
) -> Result<(Segments<Ball>, usize), CertifiedError> {
    let mut sums = Segments::from_fn(|_| zero.clone());
    for piece in pieces {
        let value = integrate_piece(piece, goal_bits, bits);
        if !value.is_finite() {
            return Err(CertifiedError::NotFinite {
                bits,
                segment: piece.segment,
                start: piece.start.to_f64_lossy(),
                end: piece.end.to_f64_lossy(),
            });
        }
        *sums.get_mut(piece.segment) += &value;
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
    let digits = digits.max(1);
    // Guard bits for the rounding of the integrand and the sum of the pieces.
    let mut bits = Precision::decimal_digits(digits).in_bits() + 24;
    let mut last_error = None;
    while bits <= MAX_BITS {
        let (cycle, compliance) =
            case(Precision::bits(bits)).map_err(|reason| CertifiedError::Case { bits, reason })?;
        match enclose_dissipation(&cycle, compliance.as_ref(), bits) {
            Ok(enclosure) => {
                if let Some((text, reached)) = certain_digits(&enclosure.total, digits) {
                    if reached >= digits {
                        return Ok(Certified {
                            enclosure,
                            text,
                            digits: reached,
                        });
                    }
                }
                let reached = certain_digits(&enclosure.total, digits).map_or(0, |(_, n)| n);
                last_error = Some(CertifiedError::TooWide {
                    asked: digits,
                    reached,
                    relative_radius: enclosure.total.relative_radius(),
                    bits,
                });
            }
            // A cycle outside the theory stays outside at any precision.
            Err(error @ CertifiedError::Cycle(_)) => return Err(error),
            Err(error) => last_error = Some(error),
        }
        bits *= 2;
    }
    Err(last_error.expect("at least one precision is tried"))
}

/// One integral of W: ∫ from `start` to `end` of `integrand`, in `segment`.
struct CertifiedPiece<'a> {
    segment: Segment,
    start: Ball,
    end: Ball,
    integrand: Box<dyn Fn(&Ball) -> Ball + 'a>,
}

/// The pieces of the four segments, as [`SegmentIntegrands::pieces`] splits them, with
/// the sinh map written through sinh and cosh so that it stays analytic on complex
/// balls (the generic map branches on the sign of u).
fn certified_pieces<'a>(
    integrands: &SegmentIntegrands<'a, Ball>,
    slope: &'a (dyn Fn(&Ball) -> Ball + Send + Sync + 'a),
) -> Vec<CertifiedPiece<'a>> {
    let mut pieces = Vec::new();
    for segment in Segment::ALL {
        let peaks = integrands.low_load_peaks(segment);
        for (start, end) in integrands.windows(segment) {
            for part in resolve_peaks(&start, &end, &peaks) {
                let integrands = *integrands;
                let integrand: Box<dyn Fn(&Ball) -> Ball + 'a> = match part.map {
                    None => Box::new(move |s: &Ball| integrands.integrand_with(segment, s, slope)),
                    Some(map) => {
                        // The map's centre and width are its point and rate at u = 0.
                        let (center, width) = map.point_and_rate(&part.start.int(0));
                        Box::new(move |u: &Ball| {
                            let (sinh, cosh) = u.sinh_cosh();
                            let s = center.clone() + &(width.clone() * &sinh);
                            integrands.integrand_with(segment, &s, slope) * &(width.clone() * &cosh)
                        })
                    }
                };
                pieces.push(CertifiedPiece {
                    segment,
                    start: part.start,
                    end: part.end,
                    integrand,
                });
            }
        }
    }
    pieces
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
    // SAFETY: Arb passes an initialised ball.
    let x = unsafe { Ball::from_raw(input, prec.clamp(2, i64::from(u32::MAX)) as u32) };
    let outcome = catch_unwind(AssertUnwindSafe(|| {
        watch(|| with_analytic(order != 0, || (piece.integrand)(&x)))
    }));
    // SAFETY: `out` is an initialised ball Arb owns.
    unsafe {
        match outcome {
            Ok((value, doubts)) if doubts.none() => acb_set(out, value.as_raw()),
            _ => acb_indeterminate(out),
        }
    }
    0
}

/// Arb's enclosure of one piece's integral at `bits` of working precision.
fn integrate_piece(piece: &CertifiedPiece<'_>, goal_bits: u32, bits: u32) -> Ball {
    let mut raw = acb_struct::default();
    let mut tolerance = mag_struct::default();
    let mut options = acb_calc_integrate_opt_struct::default();
    // SAFETY: `raw` and `tolerance` are initialised before use and `tolerance` cleared
    // after; `raw` passes to the returned ball. A zero tolerance makes Arb aim at the
    // relative goal only; `param` outlives the call.
    unsafe {
        acb_init(&mut raw);
        mag_init(&mut tolerance);
        acb_calc_integrate_opt_init(&mut options);
        // Arb's default, 1000·prec + prec², lets a piece that cannot be enclosed (an
        // integrand undecided near a point) run for minutes at high precision.
        options.eval_limit = EVALUATION_LIMIT + 16 * i64::from(bits);
        acb_calc_integrate(
            &mut raw,
            Some(evaluate),
            piece as *const CertifiedPiece<'_> as *mut c_void,
            piece.start.as_raw(),
            piece.end.as_raw(),
            i64::from(goal_bits),
            &tolerance,
            &options,
            i64::from(bits),
        );
        mag_clear(&mut tolerance);
    }
    Ball::wrap(raw, bits)
}
