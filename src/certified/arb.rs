//! The Arb rung: balls at 64 bits and more, each piece integrated by Gauss–Legendre rules
//! whose error is bounded by the integrand's size on a complex ball around the piece
//! (Arb's bound: `ball_gauss` at the fewest points it allows, Arb's `acb_calc_integrate`
//! where that needs bisection).

use std::ffi::{c_int, c_void};

use flint_sys::acb::{acb_get_mag, acb_indeterminate, acb_init};
use flint_sys::acb_calc::{acb_calc_integrate, acb_calc_integrate_opt_init, acb_calc_integrate_opt_struct};
use flint_sys::acb_types::acb_struct;
use flint_sys::arb_types::mag_struct;
use flint_sys::mag::{mag_clear, mag_init, mag_is_zero, mag_mul_2exp_si};
use rug::Float;

use super::enclosing::Enclosing;
use super::pieces::CertifiedPiece;
use crate::answer::Value;
use crate::ball::Ball;
use crate::ball_gauss;
use crate::real::Real;

impl Enclosing for Ball {
    type Tolerance = Tolerance;

    fn tolerance(scale: Option<&Ball>, goal_bits: u32) -> Tolerance {
        Tolerance::of(scale, goal_bits)
    }

    fn integrate_piece(piece: &CertifiedPiece<'_, Ball>, goal_bits: u32, tolerance: &Tolerance, bits: u32) -> Ball {
        integrate_piece(piece, goal_bits, tolerance, bits)
    }

    fn is_below_scaled(&self, scale: &Ball, log2_factor: i64) -> bool {
        Ball::is_below_scaled(self, scale, log2_factor)
    }

    fn tighter(self, other: Ball) -> Ball {
        Ball::tighter(self, other)
    }

    fn decimal_exponent_fits(&self) -> bool {
        Ball::decimal_exponent_fits(self)
    }

    fn relative_radius(&self) -> Float {
        Ball::relative_radius(self)
    }

    fn decimal_value(&self, most: u32) -> Value {
        Value::of_ball(self, self.precision().in_bits(), most)
    }
}

/// Integrand evaluations Arb may spend on one piece, besides 16 per bit of precision
/// (an ordinary piece needs a few hundred).
const EVALUATION_LIMIT: i64 = 20_000;

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
    let piece = unsafe { &*(param as *const CertifiedPiece<'_, Ball>) };
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

/// An Arb magnitude (an upper bound of |x| times 2^−goal, or zero).
pub struct Tolerance(mag_struct);

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
fn integrate_piece(piece: &CertifiedPiece<'_, Ball>, goal_bits: u32, tolerance: &Tolerance, bits: u32) -> Ball {
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
    piece: &CertifiedPiece<'_, Ball>,
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
            piece as *const CertifiedPiece<'_, Ball> as *mut c_void,
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
