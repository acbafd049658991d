//! Certified W: the four segment integrals as rigorous enclosures of the exact input's
//! value (proofs/certified-digits.md, proofs/printing.md).
//!
//! The cycle's geometry, the break points and the peaks of the integrands come from the
//! same generic code that runs in f64 and MPFR, here on enclosures: f64 intervals
//! ([`crate::interval::Interval`]) on the first rung, Arb balls ([`Ball`]) at rising
//! precisions above it. Every comparison that code makes must be decided, or the attempt
//! is refused. Each piece (a segment split at its lowest loads and knots, narrow peaks
//! mapped by s = c + w·sinh u) is integrated by Gauss–Legendre rules whose error is
//! bounded by the integrand's size on a complex box around the piece (each rung's own
//! rule, [`Enclosing`]); the integrand is the generic one, evaluated on that box with
//! every function required to be analytic there. W is λ times the sum of the piece
//! enclosures.

mod arb;
mod enclosing;
mod intervals;
mod path;
mod pieces;
pub mod series;

use std::time::Instant;

use rug::Rational;

use crate::arb::enclose_pi_multiple;
use crate::ball::{watch, Ball};
use crate::compliance::Compliance;
use crate::cycle::{CycleError, CycleKind, LoadCycle};
use crate::decimal::{printing::Decimal, value::Value};
use crate::digits::{doubled, Ladder, Rung, Stop};
use crate::dissipation::{Segments, NEAR_SEPARATION};
use crate::phase::ReducedPhase;
use crate::real::{Precision, Real};

pub use enclosing::Enclosing;
pub use path::enclose_path_dissipation;
pub use pieces::{enclose_dissipation, enclose_dissipation_with_lowest_load, MOST_DECAY_FOLDS};

/// W and its segments as enclosures (Arb balls, f64 intervals) that contain the exact
/// values.
#[derive(Clone, Debug)]
pub struct Enclosure<R = Ball> {
    /// W.
    pub total: R,
    /// ∫ (Q − Q0) du per segment, with u from v' − v'(P0), times λ.
    pub segments: Segments<R>,
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
    /// W by the one printing rule: the digits every number in the enclosure rounds to.
    pub value: Value,
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
    /// A path's steady cycle (varying P) left something open on the enclosures: a slip
    /// front's angle, the order of two angles, or where a front meets the top of the
    /// contact, which its sampling found but the proof after it did not bound.
    #[error("at {bits} bits the slip fronts of the path's steady cycle are not enclosed: {what}")]
    PathFronts {
        /// The working precision.
        bits: u32,
        /// What stayed open.
        what: &'static str,
    },
    /// A path's segments took more integrand evaluations than its enclosure is given
    /// (fronts racing near folds, where Krawczyk's boxes must be small).
    #[error("at {bits} bits the path's segments took more than the {evaluations} integrand evaluations its enclosure is given (slip fronts racing near a fold need small boxes)")]
    PathEffort {
        /// The working precision.
        bits: u32,
        /// The evaluations given.
        evaluations: i64,
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

/// The bits the f64 interval rung aims each piece's rule at below a rough W: its
/// quadrature error then lies about a hundred times below the rounding of W's
/// arithmetic in doubles (a relative width of about 1e−15 to 1e−14).
pub const INTERVAL_GOAL_BITS: u32 = 56;

/// The working precision of the probe by which [`certified_dissipation_by`] foretells
/// the cost of a long first attempt, in bits.
const PROBE_BITS: u32 = 64;

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
/// One function because its rung shares with the ladder's stop what the attempts learn:
/// the case read for the first precision, the digits reached, whether Arb gave up.
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
    let ladder = Ladder::new(Precision::bits(first), Precision::bits(MAX_BITS))
        .until(deadline)
        .foreseeing(4, foreseen_first_cost(&case, first, deadline));
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
                let (settled, value) = settled_digits(&enclosure.total, bits, digits);
                // Digits that arrive after the deadline are out of time all the same.
                if settled >= digits && !out_of_time() {
                    return Rung::Reached(Certified { enclosure, value });
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

/// The cost of a first attempt at `first` bits, foretold by a probe at [`PROBE_BITS`]
/// (quadratic in the bits) where the deadline is near enough for it to matter; zero
/// otherwise.
fn foreseen_first_cost<F>(case: &F, first: u32, deadline: Option<Instant>) -> std::time::Duration
where
    F: Fn(Precision) -> Result<(LoadCycle<Ball>, Box<dyn Compliance<Ball>>), String>,
{
    if !deadline.is_some_and(|deadline| needs_probe(first, deadline)) {
        return std::time::Duration::ZERO;
    }
    let started = Instant::now();
    if let Ok((cycle, compliance)) = case(Precision::bits(PROBE_BITS)) {
        let _ = enclose_dissipation(&cycle, compliance.as_ref(), PROBE_BITS);
    }
    started.elapsed() * (first / PROBE_BITS).pow(2)
}

/// The digits of `digits` asked that the one printing rule settles for W's enclosure at
/// `bits` (all of them for an exact zero), and W as printed with them.
fn settled_digits(total: &Ball, bits: u32, digits: u32) -> (u32, Value) {
    let value = Value::of_ball(total, bits, digits);
    let settled = match value.decimal {
        Decimal::Zero => digits,
        _ => value.digits(),
    };
    (settled, value)
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

#[cfg(test)]
mod tests {
    use super::pieces::{bottom_slope_change, difference_of_slopes};
    use super::*;
    use crate::ball_gauss;
    use crate::compliance::parse_spec;
    use crate::doubts::with_analytic;

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
