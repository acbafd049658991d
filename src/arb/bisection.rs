//! Arb's own adaptive integration (`acb_calc_integrate`): bisection with Gauss–Legendre
//! rules whose error is bounded on complex balls, for the pieces the rules of `gauss`
//! leave over. The integrand is a Rust closure, called back through FFI.

use std::ffi::{c_int, c_void};

use flint_sys::acb::{acb_indeterminate, acb_init};
use flint_sys::acb_calc::{acb_calc_integrate, acb_calc_integrate_opt_init, acb_calc_integrate_opt_struct};
use flint_sys::acb_types::acb_struct;

use super::ball::{Ball, Mag};

/// What Arb calls back: `integrand(x, analytic)` encloses f on x (`analytic`: a complex
/// ball on which f must be shown holomorphic), `None` where it cannot.
type Integrand<'a> = &'a dyn Fn(&Ball, bool) -> Option<Ball>;

/// The integrand as Arb calls it: at `order` 0 an enclosure of f on the (real) ball, at
/// `order` 1 an enclosure on a complex ball where f must be holomorphic. An evaluation
/// that gives `None` answers an indeterminate ball, which makes Arb subdivide or give a
/// non-finite result.
unsafe extern "C" fn evaluate(
    out: *mut acb_struct,
    input: *const acb_struct,
    param: *mut c_void,
    order: i64,
    prec: i64,
) -> c_int {
    // SAFETY: `param` is the `&Integrand` passed by `integrate`, alive for the call.
    let integrand = unsafe { *(param as *const Integrand<'_>) };
    let precision = prec.clamp(2, i64::from(u32::MAX)) as u32;
    // SAFETY: Arb passes an initialised ball it leaves alone during the call, and an
    // initialised ball `out` it owns.
    unsafe {
        match Ball::read_in_place(input, precision, |x| integrand(x, order != 0)) {
            Some(value) => value.move_into(out),
            None => acb_indeterminate(out),
        }
    }
    0
}

/// Arb's enclosure of ∫ from `start` to `end` of `integrand` at `bits` of working
/// precision, aiming at `goal_bits` relative accuracy or the absolute `tolerance`, within
/// `evaluations` integrand evaluations (not finite where they do not suffice).
pub(crate) fn integrate(
    integrand: Integrand<'_>,
    (start, end): (&Ball, &Ball),
    goal_bits: u32,
    tolerance: &Mag,
    bits: u32,
    evaluations: i64,
) -> Ball {
    let mut raw = acb_struct::default();
    let mut options = acb_calc_integrate_opt_struct::default();
    // SAFETY: `raw` is initialised before use and passes to the returned ball; `param`
    // points at `integrand`, which outlives the call.
    unsafe {
        acb_init(&mut raw);
        acb_calc_integrate_opt_init(&mut options);
        options.eval_limit = evaluations;
        acb_calc_integrate(
            &mut raw,
            Some(evaluate),
            &integrand as *const Integrand<'_> as *mut c_void,
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
